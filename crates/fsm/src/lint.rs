//! What can be seen wrong in one machine without running it: states never reached,
//! transitions never tried (below a `TRUE`) or never fired (below the same label), a cycle that
//! takes no time (each state's first transition `TRUE`), text kept as code that does nothing,
//! and transitions whose label was never read.

use crate::label::Label;
use crate::model::{Action, Machine, StateId};
use proclaim_syntax::FileDiagnostic;

/// Warnings about `machine`, read from `file`, in state order.
pub fn lint(machine: &Machine, file: &str) -> Vec<FileDiagnostic> {
    let mut out = Vec::new();
    let reached = reachable(machine);
    for state in &machine.states {
        if !reached.contains(&state.id) {
            out.push(FileDiagnostic::warning(
                file,
                state.line,
                format!(
                    "state {} is never reached from the initial state {}",
                    state.name,
                    machine
                        .state(machine.initial)
                        .map_or("?", |s| s.name.as_str())
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
        let outgoing: Vec<_> = machine.outgoing(state.id).collect();
        for (i, t) in outgoing.iter().enumerate() {
            let above = &outgoing[..i];
            if let Some(always) = above.iter().find(|a| a.label == Label::TRUE) {
                out.push(FileDiagnostic::warning(
                    file,
                    t.line,
                    format!(
                        "`{}` is never tried: `TRUE` above it (line {}) always fires first",
                        t.label, always.line
                    ),
                ));
            } else if let Some(same) = above.iter().find(|a| a.label == t.label) {
                out.push(FileDiagnostic::warning(
                    file,
                    t.line,
                    format!(
                        "`{}` never fires: the same label above it (line {}) is tried first",
                        t.label, same.line
                    ),
                ));
            }
        }
    }
    out.extend(timeless_cycles(machine, file));
    out
}

/// Each cycle of states whose first transition is `TRUE`: one always fires, the next round
/// the next, so the machine goes round at one moment for ever and time cannot pass (a run
/// halts such a machine: `docs/spec/behaviour.md` §3.1). Reported once, at the line of the
/// cycle's first transition from the lowest state.
fn timeless_cycles(machine: &Machine, file: &str) -> Vec<FileDiagnostic> {
    let always = |id: StateId| {
        machine
            .outgoing(id)
            .next()
            .filter(|t| t.label == Label::TRUE)
    };
    let name = |id: StateId| machine.state(id).map_or("?", |s| s.name.as_str());
    let mut reported: Vec<StateId> = Vec::new();
    let mut out = Vec::new();
    for start in machine.states.iter().map(|s| s.id) {
        // Follow the forced moves; a state seen twice closes a cycle.
        let mut path = vec![start];
        while let Some(t) = always(*path.last().unwrap_or(&start)) {
            if let Some(at) = path.iter().position(|s| *s == t.target) {
                let cycle = &path[at..];
                let lowest = *cycle.iter().min().unwrap_or(&start);
                if !reported.contains(&lowest) {
                    reported.push(lowest);
                    let names: Vec<&str> =
                        cycle.iter().chain([&cycle[0]]).map(|s| name(*s)).collect();
                    out.push(FileDiagnostic::warning(
                        file,
                        always(lowest).map_or(0, |t| t.line),
                        format!(
                            "{} goes round at one moment for ever: each state's first transition is `TRUE`, so time cannot pass (a run halts the machine)",
                            names.join(" -> ")
                        ),
                    ));
                }
                break;
            }
            path.push(t.target);
        }
    }
    out
}

/// The states reachable from the initial state.
pub fn reachable(machine: &Machine) -> Vec<StateId> {
    let mut seen = vec![machine.initial];
    let mut next = 0;
    while next < seen.len() {
        let at = seen[next];
        next += 1;
        for t in machine.outgoing(at) {
            if !seen.contains(&t.target) {
                seen.push(t.target);
            }
        }
    }
    seen
}
