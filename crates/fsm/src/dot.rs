//! A machine as a Graphviz diagram: states with their activities, transitions with their labels
//! and priority numbers (1 = tried first), the initial state marked, sub-machines a state starts
//! linked to it.

use crate::model::{Action, Argument, Machine};
use std::fmt::Write;

/// DOT text for one machine. Deterministic, so it can be compared in tests and diffed.
pub fn to_dot(machine: &Machine) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "digraph {} {{", quote(&machine.name));
    out.push_str(
        "  rankdir=LR;\n  node [shape=box, style=rounded, fontname=\"Helvetica\", fontsize=10];\n",
    );
    out.push_str("  edge [fontname=\"Helvetica\", fontsize=9];\n");
    out.push_str("  start [shape=point, width=0.15];\n");
    let _ = writeln!(out, "  start -> s{};", node(machine.initial));
    let mut started: Vec<String> = Vec::new();
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
            "  s{} [label=\"{label}\"{peripheries}];",
            node(state.id)
        );
        for action in &state.on_entry {
            if let Action::Post { ty, content } = action {
                if matches!(content.as_str(), "On" | "restart") {
                    if !started.contains(ty) {
                        let _ = writeln!(out, "  {} [shape=component, style=dashed];", quote(ty));
                        started.push(ty.clone());
                    }
                    let _ = writeln!(
                        out,
                        "  s{} -> {} [style=dashed, arrowhead=odot, label=\"starts\"];",
                        node(state.id),
                        quote(ty)
                    );
                }
            }
        }
    }
    for state in &machine.states {
        for (priority, t) in machine.outgoing(state.id).enumerate() {
            let _ = writeln!(
                out,
                "  s{} -> s{} [label=\"{}: {}\"];",
                node(t.source),
                node(t.target),
                priority + 1,
                escape(&t.label.to_string())
            );
        }
    }
    out.push_str("}\n");
    out
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
        Action::Code(code) => format!("code: {code}"),
    }
}

fn escape(text: &str) -> String {
    text.replace('\\', "\\\\")
        .replace('"', "\\\"")
        .replace('\n', " ")
}

fn quote(text: &str) -> String {
    format!("\"{}\"", escape(text))
}
