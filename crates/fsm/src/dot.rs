//! A machine as a Graphviz diagram: states with their activities, transitions with their labels
//! and priority numbers (1 = tried first), the initial state marked, sub-machines a state starts
//! linked to it.

use crate::control::Command;
use crate::dot_text::{escape, node, show, stays_marks};
use crate::model::{Action, Machine, State};

pub use crate::dot_text::quote;
use std::fmt::Write;

/// DOT text for one machine. Deterministic, so it can be compared in tests and diffed.
pub fn to_dot(machine: &Machine) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "digraph {} {{", quote(&machine.name));
    header(&mut out);
    let started = body(&mut out, machine, "", "  ");
    let mut drawn: Vec<&str> = Vec::new();
    for (from, target) in &started {
        if !drawn.contains(&target.as_str()) {
            let _ = writeln!(out, "  {} [shape=component, style=dashed];", quote(target));
            drawn.push(target);
        }
        let _ = writeln!(
            out,
            "  {from} -> {} [style=dashed, arrowhead=odot, label=\"starts\"];",
            quote(target)
        );
    }
    out.push_str("}\n");
    out
}

/// The nodes [`to_dot`] draws each state of `machine` as, by its id: one, or for a state of a
/// parallel state's regions one a region, the first standing for the state (`docs/spec/behaviour.md`
/// §3.2). What lights a state on a page lights these.
pub fn drawn_nodes(machine: &Machine) -> Vec<(i64, Vec<String>)> {
    if machine.composites.is_empty() {
        return (machine.states.iter())
            .map(|s| (s.id, vec![format!("s{}", node(s.id))]))
            .collect();
    }
    crate::dot_chart::state_nodes(machine, "")
}

/// The graph attributes every diagram starts with (left to right, rounded boxes).
pub fn header(out: &mut String) {
    out.push_str(
        "  rankdir=LR;\n  node [shape=box, style=rounded, fontname=\"Helvetica\", fontsize=10];\n",
    );
    out.push_str("  edge [fontname=\"Helvetica\", fontsize=9];\n");
}

/// The states and transitions of one machine, node names prefixed; returns the (node, machine)
/// pairs of the sub-machines its states start. A behaviour's diagram draws each machine so.
pub fn body(
    out: &mut String,
    machine: &Machine,
    prefix: &str,
    indent: &str,
) -> Vec<(String, String)> {
    let id = |state: i64| format!("{prefix}s{}", node(state));
    if !machine.composites.is_empty() {
        crate::dot_chart::chart_body(out, machine, prefix, indent);
        return crate::dot_chart::start_nodes(machine, prefix, |s| starts(s).collect());
    }
    let _ = writeln!(out, "{indent}{prefix}start [shape=point, width=0.15];");
    let _ = writeln!(out, "{indent}{prefix}start -> {};", id(machine.initial));
    let mut started = Vec::new();
    for state in &machine.states {
        let mut label = format!("{} ({})\\n", escape(&state.name), state.id);
        for (section, actions) in [
            ("entry", &state.on_entry),
            ("exit", &state.on_exit),
            ("internal", &state.internal),
        ] {
            for action in actions {
                let _ = write!(label, "{section}: {}\\l", escape(&show(action)));
            }
        }
        let peripheries = if state.id == machine.initial {
            ", peripheries=2"
        } else {
            ""
        };
        let _ = writeln!(
            out,
            "{indent}{} [label=\"{label}\"{peripheries}];",
            id(state.id)
        );
        started.extend(starts(state).map(|(_, machine)| (id(state.id), machine)));
    }
    for state in &machine.states {
        for (priority, t) in machine.outgoing(state.id).enumerate() {
            let (said, style) = stays_marks(t);
            let _ = writeln!(
                out,
                "{indent}{} -> {} [label=\"{}: {}{said}\"{style}];",
                id(t.source),
                id(t.target),
                priority + 1,
                escape(&t.shown().to_string()),
            );
        }
    }
    started
}

/// The machines a state's arrival starts, each with the action that posts the start (a
/// `Type: word` line, or a statement however deep: `restart("Dive")`).
fn starts(state: &State) -> impl Iterator<Item = (&Action, String)> + '_ {
    state.on_entry.iter().flat_map(|action| {
        // Spelled exactly: `Light: on` is a lamp's state, not a command.
        let starting = |(_, word): &(String, String)| {
            [Command::On, Command::Restart]
                .iter()
                .any(|c| c.word() == word)
        };
        let postings = action.literal_postings().into_iter();
        postings.filter(starting).map(move |(ty, _)| (action, ty))
    })
}
