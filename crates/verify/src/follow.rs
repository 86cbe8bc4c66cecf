//! Following a run of the runner in the model: whether a trace the runner wrote is a path of
//! the model, ringlet by ringlet. What the checker proves is only worth its agreement with
//! what runs; the conformance test runs random behaviours and follows every trace here, and a
//! tool can follow a recorded run the same way.
//!
//! The trace does not say what the environment did (free inputs, timers coming due) nor which
//! ringlets did nothing visible, so the follower keeps the *set* of model worlds consistent with
//! everything seen so far. Round by round (the trace's `round`), it steps every world through
//! one ringlet of each machine the model lets ring, in schedule order, keeping the successors
//! that did what the runner did in that ringlet: the same state entered (or none), the same
//! transition fired (or none), a final state reported finished, the same values left in every
//! variable and in every whiteboard type the machines write (what no event mentions kept its
//! value), and every machine in the mode the commands it obeyed left it. A machine with no
//! events in a round rang silently, or did not ring: the model decides which. The last round
//! may have been cut short by the end of the run, so its worlds may stop once every ringlet
//! seen has been matched. An empty set is a [`Mismatch`]: the round, what the runner did in
//! it, and why each candidate step of the model did not fit.

use crate::arith::text;
use crate::model::{Model, Name, SlotId};
use crate::ringlet::{initial_worlds, StepGenerator, Successor};
use crate::search::Search;
use crate::world::{Status, SystemState};
use proclaim_fsm::control::Command;
use proclaim_runtime::Event;
use rustc_hash::FxHashMap;
use std::collections::BTreeMap;
use std::fmt;
use std::hash::{Hash, Hasher};

/// How far a followed run went.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Followed {
    /// Rounds stepped through (the last round with an event of a machine).
    pub rounds: u64,
    /// Ringlets with events matched.
    pub ringlets: usize,
    /// The most model worlds consistent with the run at once, at a round's end.
    pub widest: usize,
}

/// A run that is no path of the model.
#[derive(Clone, Debug)]
pub struct Mismatch {
    pub round: u64,
    /// What the runner did in that round, one line an event.
    pub observed: Vec<String>,
    /// How many model worlds were consistent with the run before the round.
    pub worlds: usize,
    /// Why candidate steps of the model did not fit (distinct reasons, the first few).
    pub reasons: Vec<String>,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "round {}: no step of the model does what the runner did ({} worlds before it)",
            self.round, self.worlds
        )?;
        writeln!(f, "the runner's round:")?;
        if self.observed.is_empty() {
            writeln!(f, "  (nothing visible)")?;
        }
        for line in &self.observed {
            writeln!(f, "  {line}")?;
        }
        writeln!(f, "the model's candidates:")?;
        for reason in &self.reasons {
            writeln!(f, "  {reason}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Mismatch {}

/// What one ringlet of the runner showed.
#[derive(Clone, Debug)]
struct Observed {
    machine: usize,
    entered: Option<String>,
    /// Source id, target id, label as written.
    fired: Option<(i64, i64, String)>,
    finished: bool,
    /// Slot → its value as text when the ringlet ended (the last write).
    writes: FxHashMap<SlotId, String>,
    /// (machine, command) obeyed as the ringlet ended.
    commands: Vec<(usize, String)>,
    lines: Vec<String>,
}

impl Observed {
    fn new(machine: usize) -> Observed {
        Observed {
            machine,
            entered: None,
            fired: None,
            finished: false,
            writes: FxHashMap::default(),
            commands: Vec::new(),
            lines: Vec::new(),
        }
    }
}

/// Follows `events` (a run of the behaviour `model` was built from, as the runner reports it,
/// every event in the order it came) in the model.
pub fn follow(model: &Model, events: &[Event]) -> Result<Followed, Mismatch> {
    let model = &Search::new(model);
    let rounds = ringlets(model, events)?;
    let last = rounds.keys().next_back().copied().unwrap_or(0);
    let stepper = StepGenerator::new(model);
    let mut worlds: Vec<SystemState> = initial_worlds(model).collect();
    let mut statuses: Vec<Status> = model
        .machines
        .iter()
        .map(|m| {
            if m.start {
                Status::Running
            } else {
                Status::Dormant
            }
        })
        .collect();
    let mut followed = Followed {
        rounds: last,
        ..Followed::default()
    };
    let none = Vec::new();
    for round in 1..=last {
        let observed = rounds.get(&round).unwrap_or(&none);
        // The modes after each ringlet seen: before the first, after the first, ...
        let mut modes = vec![statuses.clone()];
        for o in observed {
            for (k, command) in &o.commands {
                statuses[*k] = obeyed(statuses[*k], command);
            }
            modes.push(statuses.clone());
        }
        let before = worlds.len();
        worlds = step_round(model, &stepper, worlds, observed, &modes, round == last).map_err(
            |reasons| Mismatch {
                round,
                observed: observed.iter().flat_map(|o| o.lines.clone()).collect(),
                worlds: before,
                reasons,
            },
        )?;
        followed.ringlets += observed.len();
        followed.widest = followed.widest.max(worlds.len());
    }
    Ok(followed)
}

/// A machine's mode after it obeyed `command`. The trace says which commands a machine obeyed,
/// not the mode they left it in; this is gufsm's `SuspensibleMachine` as §3 decides it.
fn obeyed(status: Status, command: &str) -> Status {
    match (Command::parse(command), status) {
        (Some(Command::Suspend), Status::Running) => Status::Suspended,
        (Some(Command::Suspend), other) => other,
        (Some(Command::On | Command::Resume | Command::Restart), _) => Status::Running,
        (Some(Command::Off), _) => Status::Dormant,
        (Some(Command::Reload | Command::Reread) | None, other) => other,
    }
}

/// The trace cut into rounds of ringlets, each round's in the order they rang.
fn ringlets(model: &Search, events: &[Event]) -> Result<BTreeMap<u64, Vec<Observed>>, Mismatch> {
    let mut rounds: BTreeMap<u64, Vec<Observed>> = BTreeMap::new();
    for event in events {
        // Events of other modules (the impersonator's postings) are the environment's.
        let Some(k) = model.machine_index(event.machine()) else {
            continue;
        };
        let round = event.round();
        let ringlets = rounds.entry(round).or_default();
        let bad = |message: String| Mismatch {
            round,
            observed: vec![describe(event)],
            worlds: 0,
            reasons: vec![message],
        };
        if let Event::Control { command, .. } = event {
            // Obeyed when the ringlet that posted it ended.
            let Some(current) = ringlets.last_mut() else {
                return Err(bad(
                    "a command obeyed before any ringlet of its round posted it".into(),
                ));
            };
            current.commands.push((k, command.clone()));
            current.lines.push(describe(event));
            continue;
        }
        if ringlets.last().is_none_or(|o| o.machine != k) {
            if ringlets.last().is_some_and(|o| o.machine > k) {
                return Err(bad(format!(
                    "{} rang after a machine later in the manifest",
                    model.machines[k].name
                )));
            }
            ringlets.push(Observed::new(k));
        }
        let current = ringlets.last_mut().expect("pushed above");
        current.lines.push(describe(event));
        match event {
            Event::Entered { state, .. } => current.entered = Some(state.clone()),
            Event::Fired {
                from, to, label, ..
            } => current.fired = Some((*from, *to, label.clone())),
            Event::Finished { .. } => current.finished = true,
            Event::Assigned {
                variable, value, ..
            } => {
                if let Some(Name::Slot(slot)) = model.resolve(Some(k), variable) {
                    current.writes.insert(slot, value.clone());
                }
            }
            // Postings to a machine's name are commands: their effect is the modes.
            Event::Posted { ty, content, .. } if model.machine_index(ty).is_none() => {
                if let Some(&Name::Slot(slot)) = model.names.get(ty) {
                    if model.slots[slot].free.is_none() {
                        current.writes.insert(slot, content.clone());
                    }
                }
            }
            _ => {}
        }
    }
    Ok(rounds)
}

fn describe(event: &Event) -> String {
    let m = event.machine();
    match event {
        Event::Entered { state, .. } => format!("{m} → {state}"),
        Event::Fired {
            from, to, label, ..
        } => format!("{m} fires #{from} → #{to} on {label}"),
        Event::Finished { state, .. } => format!("{m} finished in {state}"),
        Event::Assigned {
            variable, value, ..
        } => format!("{m} sets {variable} = {value}"),
        Event::Posted { ty, content, .. } => format!("{m} posts {ty}: {content}"),
        Event::Control { command, .. } => format!("{m} told {command}"),
        Event::Answered {
            atom, value, by, ..
        } => format!("{m} reads {atom} = {value} ({by:?})"),
        other => format!("{other:?}"),
    }
}

/// One round: every world stepped through the ringlets the model lets ring in it, keeping
/// those that match `observed` in order; the worlds at the round's end, or why none are.
/// `modes[j]`: every machine's mode once the first `j` ringlets seen have rung.
fn step_round(
    model: &Search,
    stepper: &StepGenerator<'_>,
    worlds: Vec<SystemState>,
    observed: &[Observed],
    modes: &[Vec<Status>],
    last: bool,
) -> Result<Vec<SystemState>, Vec<String>> {
    let mut ended = WorldSet::default();
    // Worlds within the round, by how many ringlets seen they have matched; whether they have
    // rung at all this round.
    let mut seen: Vec<WorldSet> = (0..=observed.len()).map(|_| WorldSet::default()).collect();
    let mut frontier: Vec<(SystemState, usize, bool)> =
        worlds.into_iter().map(|w| (w, 0, false)).collect();
    let mut reasons: Vec<String> = Vec::new();
    let mut reason = |r: String| {
        if reasons.len() < 8 && !reasons.contains(&r) {
            reasons.push(r);
        }
    };
    let mut successors = Vec::new();
    while let Some((world, matched, rang)) = frontier.pop() {
        if last && matched == observed.len() && rang {
            // The run may have ended within its last round.
            ended.insert(world);
            continue;
        }
        successors.clear();
        stepper.successors(&world, false, &mut successors);
        if successors.is_empty() || (rang && successors[0].wrapped) {
            match observed.get(matched) {
                None => {
                    ended.insert(world);
                }
                Some(o) => reason(format!(
                    "the model's round ends before {} rings",
                    model.machines[o.machine].name
                )),
            }
            continue;
        }
        for s in successors.drain(..) {
            let seen_now = match observed.get(matched) {
                Some(o) if o.machine == s.machine => Some(o),
                Some(o) if o.machine < s.machine => {
                    reason(format!(
                        "the model rings {} where the runner rang {}",
                        model.machines[s.machine].name, model.machines[o.machine].name
                    ));
                    continue;
                }
                _ => None,
            };
            let next = matched + usize::from(seen_now.is_some());
            match fits(model, &world, &s, seen_now, &modes[next]) {
                Ok(()) => {
                    if seen[next].insert(s.world.clone()) {
                        frontier.push((s.world, next, true));
                    }
                }
                Err(why) => reason(why),
            }
        }
    }
    if ended.is_empty() {
        Err(reasons)
    } else {
        Ok(ended.into_worlds())
    }
}

/// Whether the model's step `s` from `before` did what the runner's ringlet `seen` showed
/// (`None`: a ringlet with no events), leaving every machine in the mode `modes` says.
fn fits(
    model: &Search,
    before: &SystemState,
    s: &Successor,
    seen: Option<&Observed>,
    modes: &[Status],
) -> Result<(), String> {
    let machine = &model.machines[s.machine];
    let state = &machine.states[s.from];
    let at = format!("{} in {}", machine.name, state.name);
    let entered = before.machines[s.machine].just_entered;
    let seen_entered = seen.and_then(|o| o.entered.as_deref());
    match (entered, seen_entered) {
        (false, None) => {}
        (true, Some(name)) if name == state.name => {}
        (true, _) => {
            return Err(format!(
                "{at}: the model enters it, the runner entered {seen_entered:?}"
            ))
        }
        (false, Some(name)) => {
            return Err(format!(
                "{at}: the runner entered {name}, the model did not"
            ))
        }
    }
    let finished = entered && state.is_final();
    if finished != seen.is_some_and(|o| o.finished) {
        return Err(format!(
            "{at}: finished in the model {finished}, in the runner {}",
            !finished
        ));
    }
    fits_firing(model, s, seen, &at)?;
    fits_writes(model, before, s, seen, &at)?;
    for (k, mode) in modes.iter().enumerate() {
        let model_mode = s.world.machines[k].status;
        if model_mode != *mode {
            return Err(format!(
                "{at}: {} is {model_mode:?} in the model, {mode:?} in the runner",
                model.machines[k].name
            ));
        }
    }
    Ok(())
}

/// Whether the model fired what the runner fired, from machine `s.machine`'s current state.
fn fits_firing(
    model: &Search,
    s: &Successor,
    seen: Option<&Observed>,
    at: &str,
) -> Result<(), String> {
    let machine = &model.machines[s.machine];
    let state = &machine.states[s.from];
    let seen_fired = seen.and_then(|o| o.fired.as_ref());
    match (s.fired, seen_fired) {
        (None, None) => {}
        (Some(i), Some((from, to, label))) => {
            let t = &state.transitions[i];
            let id = |index: usize| machine.machine.states[index].id;
            let shown = machine.shown(t);
            if id(s.from) != *from || id(t.target) != *to || shown.to_string() != *label {
                return Err(format!(
                    "{at}: the model fires `{shown}` to {}, the runner #{from} → #{to} on `{label}`",
                    machine.states[t.target].name
                ));
            }
        }
        (Some(i), None) => {
            return Err(format!(
                "{at}: the model fires `{}`, the runner fired nothing",
                machine.shown(&state.transitions[i])
            ))
        }
        (None, Some((_, _, label))) => {
            return Err(format!(
                "{at}: the runner fires `{label}`, the model fires nothing"
            ))
        }
    }
    Ok(())
}

/// Whether the model's step wrote what the runner's ringlet wrote, and nothing else.
fn fits_writes(
    model: &Search,
    before: &SystemState,
    s: &Successor,
    seen: Option<&Observed>,
    at: &str,
) -> Result<(), String> {
    let values = model.values.borrow();
    let show = |id| values.get(id).map(text).unwrap_or_default();
    for (slot, info) in model.slots.iter().enumerate() {
        if info.free.is_some() {
            continue;
        }
        let now = s.world.values[slot];
        match seen.and_then(|o| o.writes.get(&slot)) {
            Some(written) if show(now) != *written => {
                return Err(format!(
                    "{at}: {} is {} in the model, {written} in the runner",
                    info.name,
                    show(now)
                ))
            }
            Some(_) => {}
            None if now != before.values[slot] => {
                return Err(format!(
                    "{at}: the model changes {} from {} to {}, the runner does not",
                    info.name,
                    show(before.values[slot]),
                    show(now)
                ))
            }
            None => {}
        }
    }
    Ok(())
}

/// Worlds without repeats. `SystemState` is the lead's to change, so it is hashed here by the parts
/// every world has (where each machine is and the values), and compared whole.
#[derive(Default)]
struct WorldSet {
    buckets: FxHashMap<u64, Vec<SystemState>>,
    len: usize,
}

impl WorldSet {
    /// Whether `world` was new.
    fn insert(&mut self, world: SystemState) -> bool {
        let mut h = rustc_hash::FxHasher::default();
        for c in &world.machines {
            (c.state, c.just_entered, c.status as u8).hash(&mut h);
        }
        world.values.hash(&mut h);
        let bucket = self.buckets.entry(h.finish()).or_default();
        if bucket.contains(&world) {
            return false;
        }
        bucket.push(world);
        self.len += 1;
        true
    }

    fn is_empty(&self) -> bool {
        self.len == 0
    }

    fn into_worlds(self) -> Vec<SystemState> {
        self.buckets.into_values().flatten().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_behaviour::{load, Embedded};
    use std::sync::Arc;
    use std::time::Duration;

    const MACHINE: &str = "machine A
state S0 {
    entry { g = 1; }
    when in0 -> S1
}
state S1 {
}
";

    fn model() -> Model {
        let files = Embedded {
            name: "follow",
            files: &[
                ("behaviour.toml", "[[machine]]\nfile = \"A.machine\"\n"),
                ("A.machine", MACHINE),
            ],
        };
        let behaviour = load("follow", Arc::new(files)).expect("loads");
        Model::build(&behaviour, &[])
    }

    /// The run in which `in0` turns true before the second round, with `g` set to `g`.
    fn run(model: &Model, g: &str, fire_in: u64) -> Vec<Event> {
        let ids: Vec<i64> = model.machines[0]
            .machine
            .states
            .iter()
            .map(|s| s.id)
            .collect();
        let at = Duration::ZERO;
        let machine = "A".to_string();
        vec![
            Event::Entered {
                machine: machine.clone(),
                state: "S0".into(),
                id: ids[0],
                round: 1,
                at,
            },
            Event::Assigned {
                machine: machine.clone(),
                variable: "g".into(),
                value: g.into(),
                round: 1,
                at,
            },
            Event::Fired {
                machine: machine.clone(),
                from: ids[0],
                to: ids[1],
                label: "in0".into(),
                round: fire_in,
                at,
            },
            Event::Entered {
                machine: machine.clone(),
                state: "S1".into(),
                id: ids[1],
                round: 3,
                at,
            },
            Event::Finished {
                machine,
                state: "S1".into(),
                round: 3,
                at,
            },
        ]
    }

    #[test]
    fn a_run_the_model_allows_is_followed_to_its_end() {
        let model = model();
        let followed = follow(&model, &run(&model, "1", 2)).expect("a path of the model");
        assert_eq!((followed.rounds, followed.ringlets), (3, 3));
    }

    #[test]
    fn a_wrong_value_or_a_move_out_of_turn_is_a_mismatch_at_its_round() {
        let model = model();
        let wrong_value = follow(&model, &run(&model, "2", 2)).expect_err("g is 1");
        assert_eq!(wrong_value.round, 1);
        assert!(
            wrong_value.to_string().contains("g is 1 in the model, 2"),
            "{wrong_value}"
        );
        // Entering S1 in the round after the firing, not two rounds after it.
        let too_late = follow(&model, &run(&model, "1", 1)).expect_err("S1 is entered in round 2");
        assert_eq!(too_late.round, 2, "{too_late}");
    }
}
