//! A machine as a Graphviz diagram: states with their activities, transitions with their labels
//! and priority numbers (1 = tried first), the initial state marked, sub-machines a state starts
//! linked to it.

use crate::control::Command;
use crate::model::{Action, Argument, Machine};
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
        for action in &state.on_entry {
            if let Action::Post { ty, content } = action {
                // Spelled exactly: `Light: on` is a lamp's state, not a command.
                if [Command::On, Command::Restart]
                    .iter()
                    .any(|c| c.word() == content)
                {
                    started.push((id(state.id), ty.clone()));
                }
            }
        }
    }
    for state in &machine.states {
        for (priority, t) in machine.outgoing(state.id).enumerate() {
            let _ = writeln!(
                out,
                "{indent}{} -> {} [label=\"{}: {}\"];",
                id(t.source),
                id(t.target),
                priority + 1,
                escape(&t.label.to_string())
            );
        }
    }
    started
}

/// State ids may be negative; node names may not start with `-`.
fn node(id: i64) -> String {
    if id < 0 {
        format!("m{}", -id)
    } else {
        id.to_string()
    }
}

fn show(action: &Action) -> String {
    match action {
        Action::Post { ty, content } => format!("{ty}: {content}"),
        Action::Call {
            function,
            argument: None,
        } => format!("{function}()"),
        Action::Call {
            function,
            argument: Some(Argument::Int(i)),
        } => format!("{function}({i})"),
        Action::Call {
            function,
            argument: Some(Argument::Str(s)),
        } => format!("{function}(\"{s}\")"),
        Action::Call {
            function,
            argument: Some(Argument::Word(w)),
        } => format!("{function}({w})"),
        Action::Statement(statement) => statement.to_string(),
        Action::Code(code) => format!("code: {code}"),
    }
}

fn escape(text: &str) -> String {
    text.replace('\\', "\\\\")
        .replace('"', "\\\"")
        .replace('\n', " ")
}

/// A DOT string literal.
pub fn quote(text: &str) -> String {
    format!("\"{}\"", escape(text))
}
