//! Properties drawn for a random behaviour (issue 44), and what runs say of verify's verdicts
//! on them: a run may never make true a `never` verify said holds, nor reach a `reachable`
//! verify said fails; a counterexample or witness, written as a script and played by the
//! runner, must show what it claims; and a lasso verify found for an `always_eventually`, its
//! way in followed by its loop played again and again, never makes the property true in the
//! loop. A property is a conjunction of a machine's state and the globals' values, so a run can
//! read its truth between rounds.

use crate::common::random_behaviour::Rng;
use proclaim_behaviour::testing::RoundByRound;
use proclaim_behaviour::Behaviour;
use proclaim_board::Value;
use proclaim_fsm::BinOp;
use proclaim_runner::Event;
use proclaim_verify::{
    arith, to_script, unroll, PropertyKind, PropertyOutcome, PropertySource, SearchEngine, Trace,
    Verdict,
};
use std::time::Duration;

/// A property drawn, as written and as a run reads it.
pub(super) struct Claim {
    kind: PropertyKind,
    text: String,
    atoms: Vec<Atom>,
}

enum Atom {
    /// The machine is in the state (a top-level one: a flat machine's, or a chart's plain `Q`).
    In { machine: String, state: String },
    /// A global compared with a constant (an unset one is the number 0, as to the model).
    Compare {
        global: String,
        op: &'static str,
        value: Value,
    },
}

/// The engine a seed's properties are checked with: every engine in turn, so that the
/// symbolic engine's verdicts are held to runs as the explicit search's are.
pub(super) fn engine(seed: u64) -> SearchEngine {
    match seed % 3 {
        0 => SearchEngine::Auto,
        1 => SearchEngine::Explicit,
        _ => SearchEngine::Symbolic,
    }
}

/// Two properties over the behaviour's `files`: `never` or `reachable`, each a conjunction of
/// one or two of a machine's state and a global (set somewhere) compared with a constant; for
/// one seed in two, where `liveness` asks for it, an `always_eventually` of one such atom too
/// (drawn from a sequence of its own, so the first two are what they were before it).
pub(super) fn draw(seed: u64, files: &[(String, String)], liveness: bool) -> Vec<Claim> {
    let mut rng = Rng::new(seed ^ 0xc1a1_3000);
    let mut states = Vec::new();
    for (_, text) in files {
        let Some(machine) = text.lines().find_map(|l| l.strip_prefix("machine ")) else {
            continue;
        };
        for line in text.lines() {
            if let Some(state) = line
                .strip_prefix("state ")
                .and_then(|s| s.strip_suffix(" {"))
            {
                states.push((machine.to_string(), state.to_string()));
            }
        }
    }
    let all: String = files.iter().map(|(_, t)| t.as_str()).collect();
    let globals: Vec<&str> = ["v0", "v1", "t0"]
        .into_iter()
        .filter(|g| all.contains(&format!("{g} = ")))
        .collect();
    let mut live = Rng::new(seed ^ 0x11fe_5eed);
    let liveness = (liveness && live.chance(50)).then(|| {
        let atom = atom(&mut live, &states, &globals);
        let text = atom.text();
        Claim {
            kind: PropertyKind::AlwaysEventually,
            text,
            atoms: vec![atom],
        }
    });
    (0..2)
        .map(|_| {
            let kind = if rng.chance(65) {
                PropertyKind::Never
            } else {
                PropertyKind::Reachable
            };
            let atoms: Vec<Atom> = (0..rng.between(1, 2))
                .map(|_| atom(&mut rng, &states, &globals))
                .collect();
            let text = atoms
                .iter()
                .map(Atom::text)
                .collect::<Vec<_>>()
                .join(" && ");
            Claim { kind, text, atoms }
        })
        .chain(liveness)
        .collect()
}

fn atom(rng: &mut Rng, states: &[(String, String)], globals: &[&str]) -> Atom {
    if globals.is_empty() || rng.chance(50) {
        let (machine, state) = rng.pick(states).clone();
        return Atom::In { machine, state };
    }
    let global = rng.pick(globals).to_string();
    if global == "t0" {
        let value = Value::Str(rng.pick(&["go", "stop", ""]).to_string());
        let op = *rng.pick(&["==", "!="]);
        return Atom::Compare { global, op, value };
    }
    let value = Value::Int(*rng.pick(&[-3, 0, 2, 10]));
    let op = *rng.pick(&["<", "<=", ">", ">=", "==", "!="]);
    Atom::Compare { global, op, value }
}

impl Atom {
    fn text(&self) -> String {
        match self {
            Atom::In { machine, state } => format!("{machine}.{state}"),
            Atom::Compare {
                global,
                op,
                value: Value::Str(s),
            } => format!("{global} {op} \"{s}\""),
            Atom::Compare { global, op, value } => format!("{global} {op} {value}"),
        }
    }

    fn holds_in(&self, run: &RoundByRound, behaviour: &Behaviour) -> bool {
        match self {
            Atom::In { machine, state } => current_state(run, behaviour, machine)
                .is_some_and(|s| s.split(", ").any(|atomic| atomic == state)),
            Atom::Compare { global, op, value } => {
                let now = (behaviour.machines.first())
                    .and_then(|m| run.variable(&m.machine.name, global))
                    .unwrap_or(Value::Int(0));
                compare(&now, op, value)
            }
        }
    }
}

/// The state `machine` is in, as a property means it: the target of the transition that last
/// fired, from the moment it fired (the runner says it entered only when its OnEntry runs, at
/// the machine's next ringlet), else the state it last entered.
fn current_state(run: &RoundByRound, behaviour: &Behaviour, machine: &str) -> Option<String> {
    let m = behaviour
        .machines
        .iter()
        .find(|m| m.machine.name == machine)?;
    run.events.iter().rev().find_map(|e| match e {
        Event::Fired { machine: x, to, .. } if x == machine => {
            m.machine.state(*to).map(|s| s.name.clone())
        }
        Event::Entered {
            machine: x, state, ..
        } if x == machine => Some(state.clone()),
        _ => None,
    })
}

/// `a op b` as the runner's own operators take it (`arith`, which the model shares): numbers
/// by value, a truth as 0 or 1, text by text.
fn compare(a: &Value, op: &str, b: &Value) -> bool {
    let op = match op {
        "<" => BinOp::Lt,
        "<=" => BinOp::Le,
        ">" => BinOp::Gt,
        ">=" => BinOp::Ge,
        "==" => BinOp::Eq,
        _ => BinOp::Ne,
    };
    arith::binary(op, Some(a.clone()), Some(b.clone())) == Some(Value::Bool(true))
}

impl Claim {
    pub(super) fn source(&self, i: usize) -> PropertySource {
        PropertySource {
            name: format!("p{i}"),
            kind: self.kind,
            expression: self.text.clone(),
            fair: Vec::new(),
        }
    }

    pub(super) fn holds_in(&self, run: &RoundByRound, behaviour: &Behaviour) -> bool {
        self.atoms.iter().all(|a| a.holds_in(run, behaviour))
    }

    /// Whether verify said no run makes it true: a `never` that holds, a `reachable` that
    /// fails.
    pub(super) fn absent(&self, outcome: &PropertyOutcome) -> bool {
        matches!(
            (self.kind, outcome.verdict),
            (PropertyKind::Never, Verdict::Holds) | (PropertyKind::Reachable, Verdict::Fails)
        )
    }

    /// An `always_eventually`: its run found is a lasso.
    pub(super) fn is_liveness(&self) -> bool {
        self.kind == PropertyKind::AlwaysEventually
    }

    pub(super) fn describe(&self) -> String {
        let kind = match self.kind {
            PropertyKind::Never => "never",
            PropertyKind::AlwaysEventually => "always_eventually",
            _ => "reachable",
        };
        format!("{kind} {}", self.text)
    }

    /// Plays the run verify found for it (a `never`'s counterexample, a `reachable`'s
    /// witness) in the runner, one round every `PERIOD` as the script assumes: `None` where
    /// the script says it does not reproduce the run (its notes), or where the run ends between
    /// two machines' ringlets of a round (a run is read between rounds), else whether a round
    /// ended with it true.
    pub(super) fn replays(
        &self,
        outcome: &PropertyOutcome,
        dir: &std::path::Path,
        behaviour: &Behaviour,
    ) -> Option<Result<(), String>> {
        if self.kind == PropertyKind::AlwaysEventually {
            return self.replays_lasso(outcome, dir, behaviour);
        }
        let found = matches!(
            (self.kind, outcome.verdict),
            (PropertyKind::Never, Verdict::Fails) | (PropertyKind::Reachable, Verdict::Holds)
        );
        // A run of no step would be shown before the runner did anything.
        let trace = (outcome.trace.as_ref()).filter(|t| found && !t.steps.is_empty())?;
        // A round's end is where the run can read it: the run verify found must end with the
        // last machine's ringlet (every machine rang in its last round, in manifest order).
        let last = trace.steps.last().map(|s| s.machine.as_str());
        let final_machine = behaviour.machines.last().map(|m| m.machine.name.as_str());
        if last.is_some_and(|m| final_machine != Some(m)) {
            return None;
        }
        const PERIOD: Duration = Duration::from_millis(25);
        let (script, notes) = to_script(trace, PERIOD, "replay");
        if !notes.is_empty() {
            return None;
        }
        let mut run = match RoundByRound::start(dir, &script) {
            Ok(run) => run,
            Err(e) => return Some(Err(format!("the script does not start: {e}\n{script}"))),
        };
        let rounds = trace.steps.last().map_or(0, |s| s.round) + 2;
        let mut shown = false;
        for _ in 0..rounds {
            run.round();
            shown = self.holds_in(&run, behaviour);
            if shown {
                break;
            }
            run.wait(PERIOD);
        }
        Some(if shown {
            Ok(())
        } else {
            Err(format!(
                "the runner, played its script, never made it true\n--- script\n{script}"
            ))
        })
    }
}

impl Claim {
    /// Plays the lasso verify found for an `always_eventually` that fails: its way in, then its
    /// loop `LOOP_REPEATS` times. Every round that ends in the loop must end with the property
    /// false, as every state of the loop has it. `None` where the script says it does not
    /// reproduce the run, where the way in or the loop ends between two machines' ringlets,
    /// or where the run ends where no machine can ring.
    fn replays_lasso(
        &self,
        outcome: &PropertyOutcome,
        dir: &std::path::Path,
        behaviour: &Behaviour,
    ) -> Option<Result<(), String>> {
        if outcome.verdict != Verdict::Fails {
            return None;
        }
        let (prefix, cycle) = (outcome.trace.as_ref()?, outcome.cycle.as_ref()?);
        let final_machine = behaviour.machines.last().map(|m| m.machine.name.as_str());
        let at_a_rounds_end =
            |t: &Trace| (t.steps.last()).is_none_or(|s| Some(s.machine.as_str()) == final_machine);
        if cycle.steps.is_empty() || !at_a_rounds_end(prefix) || !at_a_rounds_end(cycle) {
            return None;
        }
        const PERIOD: Duration = Duration::from_millis(25);
        let unrolled = unroll(prefix, cycle);
        let (script, notes) = to_script(&unrolled, PERIOD, "replay");
        if !notes.is_empty() {
            return None;
        }
        let mut run = match RoundByRound::start(dir, &script) {
            Ok(run) => run,
            Err(e) => return Some(Err(format!("the script does not start: {e}\n{script}"))),
        };
        // The loop starts where the way in ends (the initial state, for none).
        let from = prefix.steps.last().map_or(0, |s| s.round);
        let last = unrolled.steps.last().map_or(0, |s| s.round);
        for round in 1..=last {
            run.round();
            if round >= from && self.holds_in(&run, behaviour) {
                return Some(Err(format!(
                    "the runner, played its lasso, made it true after round {round}, in the loop (from round {from}) where verify said it never is\n--- script\n{script}"
                )));
            }
            run.wait(PERIOD);
        }
        Some(Ok(()))
    }
}
