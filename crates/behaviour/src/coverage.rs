//! What a set of recorded runs exercised of a behaviour (`proclaim test --coverage`): the states
//! its machines entered and the transitions they fired (the recordings' events), the rules of
//! its theories that applied and the priorities that decided an answer (each answer explained
//! from the inputs the theory held when a machine asked, as `why.rs` replays them), and what
//! they never did: a recording that passes says nothing about what it never exercised.

use crate::load::Behaviour;
use crate::recorded::{written_label, Recording};
use crate::why::replay;
use proclaim_cdl::{About, Explanation};
use proclaim_runner::Event;
use rustc_hash::{FxHashMap, FxHashSet};

/// How deep an answer's explanation is followed for the rules under it (each literal is
/// explained once, so a theory's chains end well before this).
const DEPTH: usize = 64;

/// One thing a behaviour can do, and whether the recordings did it.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Covered {
    /// `Machine.State`, `Machine: FROM -> TO (label)`, `theory: Rule`, `theory: Winner > Loser`.
    pub what: String,
    pub exercised: bool,
    /// A state's or a transition's place in its machine (what a diagram colours).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub place: Option<CoveredPlace>,
}

/// Where a state or a transition is in its machine: the state (a transition's source), and a
/// transition's target and label.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct CoveredPlace {
    pub machine: String,
    pub state: i64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<i64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
}

/// What the recordings exercised, by kind, each in the behaviour's order.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Coverage {
    pub states: Vec<Covered>,
    pub transitions: Vec<Covered>,
    pub rules: Vec<Covered>,
    pub priorities: Vec<Covered>,
}

/// What the recordings did: states entered (machine, state), transitions fired (machine,
/// from, to, label), rules applied (theory, rule), priorities that decided (theory, winner,
/// loser).
#[derive(Default)]
struct Exercised {
    entered: FxHashSet<(String, i64)>,
    fired: FxHashSet<(String, i64, i64, String)>,
    applied: FxHashSet<(String, String)>,
    decided: FxHashSet<(String, String, String)>,
}

/// The coverage of `recordings` (runs of `behaviour`).
pub fn coverage(behaviour: &Behaviour, recordings: &[Recording]) -> Coverage {
    let mut done = Exercised::default();
    for recording in recordings {
        machines_did(behaviour, recording, &mut done);
        theories_did(behaviour, recording, &mut done);
    }
    listed(behaviour, &done)
}

/// The states the recording's machines entered and the transitions they fired.
fn machines_did(behaviour: &Behaviour, recording: &Recording, done: &mut Exercised) {
    for event in &recording.events {
        match event {
            Event::Entered { machine, id, .. } => {
                done.entered.insert((machine.clone(), *id));
            }
            Event::Fired {
                machine,
                from,
                to,
                label,
                ..
            } => {
                // An older recording's lowered label counts as the label as written.
                let label = written_label(behaviour, event).unwrap_or_else(|| label.clone());
                done.fired.insert((machine.clone(), *from, *to, label));
            }
            _ => {}
        }
    }
}

/// The rules each answer's explanation shows applying, and the priorities between two rules
/// that both applied to one question (there the priority decided).
fn theories_did(behaviour: &Behaviour, recording: &Recording, done: &mut Exercised) {
    replay(behaviour, recording, &mut |asked, expert| {
        let Some(explanation) = expert.as_mut().and_then(|e| e.explain(&asked.label, DEPTH)) else {
            return false;
        };
        let mut here = FxHashSet::default();
        applied_in(&explanation, &mut here);
        if let Some(t) = behaviour.theories.iter().find(|t| t.name == asked.theory) {
            for &(winner, loser) in t.theory.priorities() {
                let (w, l) = (t.theory.rule_name(winner), t.theory.rule_name(loser));
                if here.contains(&w) && here.contains(&l) {
                    done.decided.insert((asked.theory.clone(), w, l));
                }
            }
        }
        let theory = &asked.theory;
        done.applied
            .extend(here.into_iter().map(|r| (theory.clone(), r)));
        false
    });
}

/// Everything the behaviour can do, each marked with whether it was done.
fn listed(behaviour: &Behaviour, done: &Exercised) -> Coverage {
    let mut coverage = Coverage::default();
    for m in &behaviour.machines {
        machine_listed(&m.machine, done, &mut coverage);
    }
    for t in &behaviour.theories {
        let theory = &t.theory;
        for id in 0..theory.written_rule_count() as u32 {
            let rule = theory.rule_name(id);
            coverage.rules.push(Covered {
                exercised: done.applied.contains(&(t.name.clone(), rule.clone())),
                what: format!("{}: {rule}", t.name),
                place: None,
            });
        }
        for &(winner, loser) in theory.priorities() {
            let pair = (
                t.name.clone(),
                theory.rule_name(winner),
                theory.rule_name(loser),
            );
            coverage.priorities.push(Covered {
                what: format!("{}: {} > {}", t.name, pair.1, pair.2),
                exercised: done.decided.contains(&pair),
                place: None,
            });
        }
    }
    coverage
}

/// A machine's states and transitions as written, each once: a nested state lowers to a flat
/// state for each way into it and a composite's transition to a copy for each state inside it
/// (`docs/spec/behaviour.md` §3.2), and what was written is exercised when any of them was.
fn machine_listed(machine: &proclaim_fsm::Machine, done: &Exercised, coverage: &mut Coverage) {
    let name = &machine.name;
    // Each as written, at its place in the list; the flat copies after it mark it.
    let mut state_at: FxHashMap<(&str, usize), usize> = FxHashMap::default();
    for s in &machine.states {
        let entered = done.entered.contains(&(name.clone(), s.id));
        let at = *state_at
            .entry((s.name.as_str(), s.line))
            .or_insert_with(|| {
                coverage.states.push(Covered {
                    what: format!("{name}.{}", s.name),
                    exercised: false,
                    place: Some(CoveredPlace {
                        machine: name.clone(),
                        state: s.id,
                        target: None,
                        label: None,
                    }),
                });
                coverage.states.len() - 1
            });
        coverage.states[at].exercised |= entered;
    }
    let state = |id| machine.state(id).map_or("?", |s| s.name.as_str());
    let mut transition_at: FxHashMap<(String, usize), usize> = FxHashMap::default();
    for t in &machine.transitions {
        let label = t.shown().to_string();
        let from = machine.written_on(t).unwrap_or("?");
        // One that stays goes back to where it was written, for each copy of it alike.
        let to = if t.stays { from } else { state(t.target) };
        let what = format!("{name}: {from} -> {to} ({label})");
        let fired = done
            .fired
            .contains(&(name.clone(), t.source, t.target, label.clone()));
        let at = *transition_at
            .entry((what.clone(), t.line))
            .or_insert_with(|| {
                coverage.transitions.push(Covered {
                    what,
                    exercised: false,
                    place: Some(CoveredPlace {
                        machine: name.clone(),
                        state: t.source,
                        target: Some(t.target),
                        label: Some(label),
                    }),
                });
                coverage.transitions.len() - 1
            });
        coverage.transitions[at].exercised |= fired;
    }
}

/// The rules an explanation shows applying: their bodies held (a supporter, a strict chain, an
/// attacker that stands or is beaten).
fn applied_in(e: &Explanation, applied: &mut FxHashSet<String>) {
    if let About::Rule { rule, role, .. } = &e.about {
        if matches!(*role, "supports" | "strict_chain" | "stands" | "beaten") {
            applied.insert(rule.clone());
        }
    }
    for child in &e.children {
        applied_in(child, applied);
    }
}

impl Coverage {
    /// Every kind with what of it was never exercised: `(kind, exercised, of, never)`.
    pub fn summary(&self) -> Vec<(&'static str, usize, usize, Vec<&str>)> {
        [
            ("states entered", &self.states),
            ("transitions fired", &self.transitions),
            ("rules applied", &self.rules),
            ("priorities deciding an answer", &self.priorities),
        ]
        .into_iter()
        .map(|(kind, all)| {
            let never = all.iter().filter(|c| !c.exercised).map(|c| c.what.as_str());
            let never: Vec<&str> = never.collect();
            (kind, all.len() - never.len(), all.len(), never)
        })
        .collect()
    }
}
