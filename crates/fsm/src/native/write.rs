//! Writes a machine in the native format; reading the text back gives the same machine.

use crate::model::{Action, Argument, Machine, State, StateId};
use std::fmt::Write;

const KEYWORDS: [&str; 10] = [
    "machine",
    "description",
    "initial",
    "state",
    "entry",
    "exit",
    "internal",
    "when",
    "call",
    "code",
];

/// The machine as a native file. Ids are written only when they are not the ones the reader
/// would give (1, 2, 3… in order), so hand-written machines stay free of them and imported
/// ones keep their original ids.
pub fn to_native(machine: &Machine) -> String {
    let mut out = String::new();
    let implicit_ids = machine
        .states
        .iter()
        .enumerate()
        .all(|(i, s)| s.id == i as StateId + 1);
    let _ = writeln!(out, "machine {}", name(&machine.name));
    if !machine.description.is_empty() {
        let _ = writeln!(out, "description {}", quoted(&machine.description));
    }
    let _ = writeln!(out, "initial {}", reference(machine, machine.initial));
    for state in &machine.states {
        out.push('\n');
        write_state(&mut out, machine, state, implicit_ids);
    }
    out
}

fn write_state(out: &mut String, machine: &Machine, state: &State, implicit_ids: bool) {
    let _ = write!(out, "state {}", name(&state.name));
    if !implicit_ids {
        let _ = write!(out, " #{}", state.id);
    }
    out.push_str(" {\n");
    for (section, actions) in [
        ("entry", &state.on_entry),
        ("exit", &state.on_exit),
        ("internal", &state.internal),
    ] {
        if actions.is_empty() {
            continue;
        }
        let _ = writeln!(out, "    {section} {{");
        for action in actions {
            out.push_str("        ");
            write_action(out, action);
            out.push('\n');
        }
        out.push_str("    }\n");
    }
    for t in machine.outgoing(state.id) {
        let _ = writeln!(
            out,
            "    when {} -> {}",
            t.label,
            reference(machine, t.target)
        );
    }
    // Kept so nothing of the original is lost; a comment, so the file still reads.
    for u in machine.unread.iter().filter(|u| u.source == state.id) {
        let _ = writeln!(
            out,
            "    // not read (line {}: {}): when {} -> {}",
            u.line,
            one_line(&u.reason),
            one_line(&u.label),
            reference(machine, u.target)
        );
    }
    out.push_str("}\n");
}

fn write_action(out: &mut String, action: &Action) {
    match action {
        Action::Post { ty, content } => {
            let _ = write!(out, "{}: {}", name(ty), one_line(content));
        }
        Action::Call { function, argument } => {
            let _ = write!(out, "call {}", name(function));
            match argument {
                None => {}
                Some(Argument::Int(n)) => {
                    let _ = write!(out, "({n})");
                }
                Some(Argument::Str(s)) => {
                    let _ = write!(out, "({})", quoted(s));
                }
                Some(Argument::Word(w)) if is_word(w) => {
                    let _ = write!(out, "({w})");
                }
                Some(Argument::Word(w)) => {
                    let _ = write!(out, "({})", quoted(w));
                }
            }
        }
        Action::Statement(statement) => {
            let _ = write!(out, "{statement}");
        }
        Action::Code(code) => {
            let _ = write!(out, "code {}", one_line(code));
        }
    }
}

/// A state by name when the name is unique, else by id.
fn reference(machine: &Machine, id: StateId) -> String {
    match machine.state(id) {
        Some(s) if machine.states.iter().filter(|o| o.name == s.name).count() == 1 => name(&s.name),
        _ => format!("#{id}"),
    }
}

pub(super) fn is_word(text: &str) -> bool {
    let mut chars = text.chars();
    chars.next().is_some_and(|c| c.is_alphabetic() || c == '_')
        && chars.all(|c| c.is_alphanumeric() || c == '_' || c == '.')
        && !KEYWORDS.contains(&text)
}

pub(super) fn name(text: &str) -> String {
    if is_word(text) {
        text.to_string()
    } else {
        quoted(text)
    }
}

fn quoted(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Contents and code are the rest of a line, trimmed; a line break inside would end them early.
fn one_line(text: &str) -> String {
    text.trim().replace(['\n', '\r'], " ")
}
