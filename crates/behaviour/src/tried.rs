//! Why a machine did or did not move in a recorded round (`proclaim explain B MACHINE
//! --recording F --round N`): the state its ringlet ran in, the answers its labels read, and
//! its transitions in priority order: the one that fired, those before it (their labels did not
//! hold), those after it (never tried).

use crate::load::Behaviour;
use crate::recorded::Recording;
use proclaim_board::Value;
use proclaim_fsm::names::Resolved;
use proclaim_lower::arith::{text, zero};
use proclaim_runner::{Answerer, Event};
use std::fmt;

/// A machine's ringlet of one recorded round.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Tried {
    pub machine: String,
    pub round: u64,
    pub state: String,
    /// When the state was entered: round and microseconds since the start.
    pub entered: (u64, u64),
    /// Each answer its labels read, as the trace shows it: `atom = value (who)`.
    pub read: Vec<String>,
    /// Its state's transitions in priority order.
    pub transitions: Vec<TriedTransition>,
}

/// One transition of the state in the ringlet.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct TriedTransition {
    pub to: String,
    /// It has no target: it acts and stays (`to` is its own state).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub stays: bool,
    pub label: String,
    pub outcome: Outcome,
    /// What its label's propositions read in the ringlet (`atom = value`), those it asked.
    pub read: Vec<String>,
}

/// How one transition of the state came out in the ringlet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    Fired,
    /// Its label did not hold.
    DidNotHold,
    /// One before it fired.
    NotTried,
}

/// Why a machine's round cannot be shown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TriedError {
    NoMachine(String),
    /// It took no ringlet in that round (not running, or the run had ended).
    DidNotRing {
        machine: String,
        round: u64,
    },
}

impl fmt::Display for TriedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TriedError::NoMachine(name) => write!(f, "the behaviour has no machine `{name}`"),
            TriedError::DidNotRing { machine, round } => write!(
                f,
                "{machine} took no ringlet in round {round} (it was not running, or the run had ended)"
            ),
        }
    }
}

impl std::error::Error for TriedError {}

/// `machine`'s ringlet in `round` of the recorded run.
pub fn tried(
    behaviour: &Behaviour,
    recording: &Recording,
    machine: &str,
    round: u64,
) -> Result<Tried, TriedError> {
    let place = behaviour
        .machines
        .iter()
        .position(|m| m.machine.name == machine)
        .ok_or_else(|| TriedError::NoMachine(machine.to_string()))?;
    let rang = recording
        .ringlets
        .iter()
        .any(|r| r.round == round && r.machine == place);
    let did_not_ring = || TriedError::DidNotRing {
        machine: machine.to_string(),
        round,
    };
    let model = &behaviour.machines[place].machine;
    let ours = recording.events.iter().filter(|e| e.machine() == machine);
    let entered = ours
        .clone()
        .filter(|e| e.round() <= round)
        .filter_map(|e| match e {
            Event::Entered { id, round, at, .. } => Some((*id, *round, at.as_micros() as u64)),
            _ => None,
        })
        .next_back();
    let (Some((state, entered_round, entered_at)), true) = (entered, rang) else {
        return Err(did_not_ring());
    };
    let mut read = Vec::new();
    let mut values: Vec<(&str, bool)> = Vec::new();
    let mut fired = None;
    for e in ours.filter(|e| e.round() == round) {
        match e {
            Event::Answered {
                atom, value, by, ..
            } => {
                read.push(format!("{atom} = {value} ({})", answerer(by)));
                values.push((atom, *value));
            }
            Event::Fired { to, label, .. } => fired = Some((*to, label.clone())),
            _ => {}
        }
    }
    let held = held_by_names(behaviour, recording, place, round, state, &values);
    let transitions = outcomes(model, state, fired, &values, &held);
    Ok(Tried {
        machine: machine.to_string(),
        round,
        state: state_name(model, state),
        entered: (entered_round, entered_at),
        read,
        transitions,
    })
}

/// A state's name (`?` for a number the machine does not have).
fn state_name(model: &proclaim_fsm::Machine, id: i64) -> String {
    let state = model.states.iter().find(|s| s.id == id);
    state.map_or("?".to_string(), |s| s.name.clone())
}

/// The state's transitions in priority order: the one that `fired` (target, label), those
/// before it, whose labels did not hold, those after it, never tried; and what each label's
/// propositions read (`values`).
fn outcomes(
    model: &proclaim_fsm::Machine,
    state: i64,
    fired: Option<(i64, String)>,
    values: &[(&str, bool)],
    held: &[(String, String)],
) -> Vec<TriedTransition> {
    let mut outcome = Outcome::DidNotHold;
    let from = model.transitions.iter().filter(|t| t.source == state);
    from.map(|t| {
        let label = t.shown().to_string();
        let this = if outcome == Outcome::NotTried {
            Outcome::NotTried
        } else if fired.as_ref() == Some(&(t.target, label.clone())) {
            outcome = Outcome::NotTried;
            Outcome::Fired
        } else {
            Outcome::DidNotHold
        };
        let asked = label_names(&t.label).into_iter().filter_map(|n| {
            if let Some((_, value)) = values.iter().find(|(atom, _)| *atom == n) {
                return Some(format!("{n} = {value}"));
            }
            let (_, value) = held.iter().find(|(name, _)| name == n)?;
            Some(format!("{n} = {value}"))
        });
        TriedTransition {
            to: state_name(model, t.target),
            stays: t.stays,
            label,
            outcome: this,
            read: asked.collect(),
        }
    })
    .collect()
}

/// Every name a label reads, as a condition or in a comparison, left to right, once each.
fn label_names(label: &proclaim_fsm::Label) -> Vec<&str> {
    let mut names = Vec::new();
    label.visit_names(&mut |name, _| {
        if !names.contains(&name) {
            names.push(name);
        }
    });
    names
}

/// What the names the state's labels read, and no expert answered, held when the labels were
/// tried: a variable its last assignment (the machine's own, or any machine's for a global),
/// or its starting value; anything else the whiteboard's last posting of that type, as the
/// run's events say (text), or "never posted". The labels are tried after OnEntry and before Internal:
/// the ringlet's events count up to its first answer or firing (all of them when it has
/// neither).
fn held_by_names(
    behaviour: &Behaviour,
    recording: &Recording,
    place: usize,
    round: u64,
    state: i64,
    answered: &[(&str, bool)],
) -> Vec<(String, String)> {
    let machines = behaviour.machines.iter().map(|m| &m.machine);
    let names = proclaim_fsm::names::Names::of(machines);
    let model = &behaviour.machines[place].machine;
    let machine = model.name.as_str();
    let events = &recording.events;
    let ours = |e: &Event| e.machine() == machine && e.round() == round;
    let tried = |e: &Event| ours(e) && matches!(e, Event::Answered { .. } | Event::Fired { .. });
    let later = || events.iter().position(|e| e.round() > round);
    let cut = events.iter().position(tried).unwrap_or_else(|| {
        let last = events.iter().rposition(ours).map(|last| last + 1);
        last.or_else(later).unwrap_or(events.len())
    });
    let before = &events[..cut];
    let from = model.transitions.iter().filter(|t| t.source == state);
    let mut held: Vec<(String, String)> = Vec::new();
    for name in from.flat_map(|t| label_names(&t.label)) {
        if answered.iter().any(|(a, _)| *a == name) || held.iter().any(|(n, _)| n == name) {
            continue;
        }
        let value = match names.resolve(place, name) {
            resolved @ (Resolved::Own | Resolved::Global) => {
                let own = resolved == Resolved::Own;
                let set = before.iter().rev().find_map(|e| match e {
                    Event::Assigned {
                        machine: m,
                        variable,
                        value,
                        ..
                    } if variable == name && (!own || m == machine) => Some(value.clone()),
                    _ => None,
                });
                // Never assigned: as declared (a global starts at 0).
                let first = names.own[place].iter().find(|o| o.name == name);
                let zero = first.map_or(Value::Int(0), |o| zero(&o.first));
                set.unwrap_or_else(|| text(&zero))
            }
            Resolved::Extern | Resolved::Other => {
                let posted = before.iter().rev().find_map(|e| match e {
                    Event::Posted { ty, content, .. } if ty == name => Some(content.clone()),
                    _ => None,
                });
                posted.unwrap_or_else(|| "never posted".into())
            }
        };
        held.push((name.to_string(), value));
    }
    held
}

/// Who gave an answer, as the trace says it.
fn answerer(by: &Answerer) -> String {
    match by {
        Answerer::Expert(who) => who.clone(),
        Answerer::Posted(who) => format!("as posted by {who}"),
        Answerer::TimedOut => "no answer in time".into(),
        Answerer::NoExpert => "no expert answers it".into(),
    }
}

impl fmt::Display for Tried {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (round, at) = self.entered;
        writeln!(
            f,
            "round {}: {} rang in {} (entered in round {round}, at {:.3} s)",
            self.round,
            self.machine,
            self.state,
            at as f64 / 1e6
        )?;
        if self.read.is_empty() {
            writeln!(f, "  its labels read no answer")?;
        } else {
            writeln!(f, "  its labels read: {}", self.read.join(", "))?;
        }
        for (n, t) in self.transitions.iter().enumerate() {
            let how = match t.outcome {
                Outcome::Fired => "fired",
                Outcome::DidNotHold => "did not hold",
                Outcome::NotTried => "not tried (one before it fired)",
            };
            let read = match (t.outcome, t.read.is_empty()) {
                (Outcome::NotTried, _) | (_, true) => String::new(),
                _ => format!(" ({})", t.read.join(", ")),
            };
            let goes = match t.stays {
                true => "stays".to_string(),
                false => format!("-> {}", t.to),
            };
            writeln!(f, "  {}. {goes} when {}: {how}{read}", n + 1, t.label)?;
        }
        if !self.transitions.iter().any(|t| t.outcome == Outcome::Fired) {
            writeln!(f, "  none fired: its Internal ran")?;
        }
        Ok(())
    }
}
