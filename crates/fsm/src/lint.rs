//! What can be seen wrong in one machine without running it: states never reached,
//! transitions never tried (below a `TRUE`) or never fired (below the same label), a cycle that
//! takes no time (each state's first transition `TRUE`), text kept as code that does nothing,
//! and transitions whose label was never read.

use crate::label::Label;
use crate::model::{Action, Machine, StateId, Transition};
use proclaim_syntax::FileDiagnostic;
use std::collections::{HashMap, HashSet};

/// Each state's transitions, highest priority first: looked up once, so a machine of many
/// states is linted in time linear in its size (`Machine::outgoing` scans every transition).
type Outgoing<'m> = HashMap<StateId, Vec<&'m Transition>>;

fn outgoing_of(machine: &Machine) -> Outgoing<'_> {
    let mut outgoing: Outgoing<'_> = HashMap::new();
    for t in &machine.transitions {
        outgoing.entry(t.source).or_default().push(t);
    }
    outgoing
}

/// Warnings about `machine`, read from `file`, in state order.
pub fn lint(machine: &Machine, file: &str) -> Vec<FileDiagnostic> {
    let mut out = Vec::new();
    let outgoing = outgoing_of(machine);
    let reached: HashSet<StateId> = reachable_by(machine, &outgoing).into_iter().collect();
    // A nested state lowers to a flat state for each way into it (`native/chart.rs`): it is
    // reached when one of them is, and what is wrong with it is said once.
    let reached_as_written: HashSet<(&str, usize)> = machine
        .states
        .iter()
        .filter(|s| reached.contains(&s.id))
        .map(|s| (s.name.as_str(), s.line))
        .collect();
    let initial = machine
        .state(machine.initial)
        .map_or("?", |s| s.name.as_str());
    for state in &machine.states {
        if !reached_as_written.contains(&(state.name.as_str(), state.line)) {
            out.push(FileDiagnostic::warning(
                file,
                state.line,
                format!(
                    "state {} is never reached from the initial state {initial}",
                    state.name,
                ),
            ));
        }
        for action in state
            .on_entry
            .iter()
            .chain(&state.on_exit)
            .chain(&state.internal)
        {
            if let Action::Code(code) = action {
                out.push(FileDiagnostic::warning(
                    file,
                    state.line,
                    format!(
                        "state {}: `{code}` is kept as code and does nothing",
                        state.name
                    ),
                ));
            }
        }
        for u in machine.unread.iter().filter(|u| u.source == state.id) {
            out.push(FileDiagnostic::warning(
                file,
                u.line,
                format!("the transition on `{}` is not run: {}", u.label, u.reason),
            ));
        }
        let leaving = outgoing.get(&state.id).map_or(&[][..], Vec::as_slice);
        out.extend(shadowed(leaving, file));
    }
    out.extend(timeless_cycles(machine, &outgoing, file));
    out.extend(endless_stays(machine, &outgoing, file));
    let mut said = HashSet::new();
    out.retain(|d| said.insert((d.line, d.message.clone())));
    out
}

/// The transitions of one state that a label above them always beats.
fn shadowed(leaving: &[&Transition], file: &str) -> Vec<FileDiagnostic> {
    let mut out = Vec::new();
    // What is above each transition, kept as it goes so a state of many transitions is linted
    // in linear time: the first `TRUE`, and the first of each label (by its text, then equal).
    let mut first_true: Option<&Transition> = None;
    let mut labels: HashMap<String, Vec<&Transition>> = HashMap::new();
    for t in leaving {
        let text = t.label.to_string();
        let same = (labels.get(&text).into_iter().flatten()).find(|a| a.label == t.label);
        let same = same.copied();
        if first_true.is_none() && t.label == Label::TRUE {
            first_true = Some(t);
        }
        if same.is_none() {
            labels.entry(text).or_default().push(t);
        }
        // A composite's transition is copied to each state inside it: shadowed in one of
        // them, it may still fire from the others.
        if t.composite.is_some() {
            continue;
        }
        if t.label == Label::Bool(false) && t.written.is_some() {
            // What lowering decided, as an `in(S)` of another state is in a flat machine.
            out.push(FileDiagnostic::warning(
                file,
                t.line,
                format!("`{}` never fires: it is false in this state", t.shown()),
            ));
        } else if let Some(always) = first_true.filter(|a| !std::ptr::eq(*a, *t)) {
            // Shown as written: `in(S)` of its own state is always true there too.
            out.push(FileDiagnostic::warning(
                file,
                t.line,
                format!(
                    "`{}` is never tried: `{}` above it (line {}) always fires first",
                    t.shown(),
                    always.shown(),
                    always.line
                ),
            ));
        } else if let Some(same) = same {
            out.push(FileDiagnostic::warning(
                file,
                t.line,
                format!(
                    "`{}` never fires: the same label above it (line {}) is tried first",
                    t.shown(),
                    same.line
                ),
            ));
        }
    }
    out
}

/// Each cycle of states whose first transition is `TRUE`: one always fires, the next round
/// the next, so the machine goes round at one moment for ever and time cannot pass (a run
/// halts such a machine: `docs/spec/behaviour.md` §3.1). Reported once, at the line of the
/// cycle's first transition from the lowest state.
fn timeless_cycles(machine: &Machine, outgoing: &Outgoing<'_>, file: &str) -> Vec<FileDiagnostic> {
    let always = |id: StateId| {
        outgoing
            .get(&id)
            .and_then(|ts| ts.first().copied())
            .filter(|t| t.label == Label::TRUE)
    };
    let names: HashMap<StateId, &str> = machine
        .states
        .iter()
        .map(|s| (s.id, s.name.as_str()))
        .collect();
    let name = |id: StateId| names.get(&id).copied().unwrap_or("?");
    let mut out = Vec::new();
    // States whose forced moves were followed to their end already: each is walked once.
    let mut done: HashSet<StateId> = HashSet::new();
    for start in machine.states.iter().map(|s| s.id) {
        // Follow the forced moves; a state seen twice on this walk closes a cycle.
        let mut path = vec![start];
        let mut on_path: HashMap<StateId, usize> = HashMap::from([(start, 0)]);
        let mut at = start;
        while let Some(t) = always(at).filter(|_| !done.contains(&at)) {
            if let Some(&from) = on_path.get(&t.target) {
                let cycle = &path[from..];
                let lowest = *cycle.iter().min().unwrap_or(&start);
                let names: Vec<&str> = cycle.iter().chain([&cycle[0]]).map(|s| name(*s)).collect();
                out.push(FileDiagnostic::warning(
                    file,
                    always(lowest).map_or(0, |t| t.line),
                    format!(
                        "{} goes round at one moment for ever: each state's first transition is `TRUE`, so time cannot pass (a run halts the machine)",
                        names.join(" -> ")
                    ),
                ));
                break;
            }
            on_path.insert(t.target, path.len());
            path.push(t.target);
            at = t.target;
        }
        done.extend(path);
    }
    out
}

/// Each transition that stays whose label reads nothing that can change while it stays (only
/// constants, time tests and `in`): once it fires, the round after follows at once and finds
/// it true again, at the same moment, for ever (§3.2). A first transition `TRUE` is
/// [`timeless_cycles`]'s to report.
fn endless_stays(machine: &Machine, outgoing: &Outgoing<'_>, file: &str) -> Vec<FileDiagnostic> {
    let mut out = Vec::new();
    for t in machine.transitions.iter().filter(|t| t.stays) {
        let mut reads = false;
        t.label.visit_names(&mut |_, _| reads = true);
        let first = outgoing
            .get(&t.source)
            .and_then(|ts| ts.first())
            .is_some_and(|f| std::ptr::eq(*f, t));
        if reads || (first && t.label == Label::TRUE) {
            continue;
        }
        out.push(FileDiagnostic::warning(
            file,
            t.line,
            format!(
                "`when {} {{ … }}` stays and reads nothing that changes while it stays: once it fires it fires in every round, at one moment, so time cannot pass (a run halts the machine); give it a target or a label that turns false",
                t.shown()
            ),
        ));
    }
    out
}

/// The states reachable from the initial state.
pub fn reachable(machine: &Machine) -> Vec<StateId> {
    reachable_by(machine, &outgoing_of(machine))
}

fn reachable_by(machine: &Machine, outgoing: &Outgoing<'_>) -> Vec<StateId> {
    let mut seen = vec![machine.initial];
    let mut known: HashSet<StateId> = seen.iter().copied().collect();
    let mut next = 0;
    while next < seen.len() {
        let at = seen[next];
        next += 1;
        for t in outgoing.get(&at).into_iter().flatten() {
            if known.insert(t.target) {
                seen.push(t.target);
            }
        }
    }
    seen
}
