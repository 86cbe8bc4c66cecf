//! Writes a flat machine in the native format; reading the text back gives the same machine
//! (a machine that nests states is written by its own file, or as SCXML by `to_scxml`).

use crate::code::{Expr, Statement};
use crate::interface::global_of;
use crate::model::{Action, Argument, Machine, State, StateId, Transition, UnreadTransition};
use std::collections::HashMap;
use std::fmt::Write;

/// The words the native format keeps for itself: a name that is one is written quoted.
pub const KEYWORDS: [&str; 12] = [
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
    "param",
    "outcome",
];

/// The machine as a native file. Ids are written only when they are not the ones the reader
/// would give (1, 2, 3… in order), so hand-written machines stay free of them and imported
/// ones keep their original ids.
pub fn to_native(machine: &Machine) -> String {
    let written;
    let machine = if machine.interface.is_empty() {
        machine
    } else {
        written = as_written(machine);
        &written
    };
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
    for p in &machine.interface.params {
        let _ = writeln!(out, "param {}: {}", p.name, p.ty.name());
    }
    if !machine.interface.outcomes.is_empty() {
        let _ = writeln!(
            out,
            "outcome {}",
            machine.interface.outcome_names().join(", ")
        );
    }
    let index = Index::of(machine);
    let _ = writeln!(out, "initial {}", index.reference(machine.initial));
    for state in &machine.states {
        out.push('\n');
        write_state(&mut out, &index, state, implicit_ids);
    }
    out
}

/// What writing a state looks up, found once for the machine so that a machine of many states
/// is written in time proportional to its size: each state's transitions (in the machine's
/// order) and unread ones, and how each state is named.
struct Index<'m> {
    outgoing: HashMap<StateId, Vec<&'m Transition>>,
    unread: HashMap<StateId, Vec<&'m UnreadTransition>>,
    /// Each state's reference: its name when no other state has it, else its id.
    references: HashMap<StateId, String>,
    /// The final states that announce an outcome: the last of their OnEntry sets its global.
    announced: HashMap<StateId, &'m str>,
}

impl<'m> Index<'m> {
    fn of(machine: &'m Machine) -> Index<'m> {
        let mut outgoing: HashMap<StateId, Vec<&Transition>> = HashMap::new();
        for t in &machine.transitions {
            outgoing.entry(t.source).or_default().push(t);
        }
        let mut unread: HashMap<StateId, Vec<&UnreadTransition>> = HashMap::new();
        for u in &machine.unread {
            unread.entry(u.source).or_default().push(u);
        }
        let mut names: HashMap<&str, usize> = HashMap::new();
        for s in &machine.states {
            *names.entry(s.name.as_str()).or_default() += 1;
        }
        let mut references = HashMap::new();
        // The first state of an id is the one `Machine::state` finds.
        for s in machine.states.iter().rev() {
            let reference = if names[s.name.as_str()] == 1 {
                name(&s.name)
            } else {
                format!("#{}", s.id)
            };
            references.insert(s.id, reference);
        }
        let announced = machine
            .states
            .iter()
            .filter(|s| !outgoing.contains_key(&s.id))
            .filter_map(|s| {
                let o = machine.interface.outcomes.iter().find(|o| {
                    s.on_entry.last()
                        == Some(&Action::Statement(Statement::Assign {
                            name: global_of(&machine.name, &o.name),
                            value: Expr::Int(1),
                        }))
                })?;
                Some((s.id, o.name.as_str()))
            })
            .collect();
        Index {
            outgoing,
            unread,
            references,
            announced,
        }
    }

    /// A state by name when the name is unique, else by id.
    fn reference(&self, id: StateId) -> String {
        self.references
            .get(&id)
            .cloned()
            .unwrap_or_else(|| format!("#{id}"))
    }
}

/// The machine with its parameters read by their names again, as its file says them.
fn as_written(machine: &Machine) -> Machine {
    let mut machine = machine.clone();
    let params: Vec<(String, String)> = machine
        .interface
        .params
        .iter()
        .map(|p| (global_of(&machine.name, &p.name), p.name.clone()))
        .collect();
    machine.rename(&mut |n| params.iter().find(|(g, _)| g == n).map(|(_, p)| p.clone()));
    machine
}

fn write_state(out: &mut String, index: &Index<'_>, state: &State, implicit_ids: bool) {
    let _ = write!(out, "state {}", name(&state.name));
    if !implicit_ids {
        let _ = write!(out, " #{}", state.id);
    }
    out.push_str(" {\n");
    let mut entry = state.on_entry.as_slice();
    let announced = index.announced.get(&state.id);
    if announced.is_some() {
        entry = &entry[..entry.len() - 1];
    }
    for (section, actions) in [
        ("entry", entry),
        ("exit", state.on_exit.as_slice()),
        ("internal", state.internal.as_slice()),
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
    for t in index.outgoing.get(&state.id).into_iter().flatten() {
        // One that stays runs its own actions alone, and always has its block.
        if t.stays {
            let _ = write!(out, "    when {} {{", t.label);
            match t.leaving.as_deref().unwrap_or_default() {
                [] => out.push_str(" }\n"),
                own => write_block_body(out, own),
            }
            continue;
        }
        let _ = write!(out, "    when {} -> {}", t.label, index.reference(t.target));
        // A transition's own actions follow its state's OnExit in what it runs leaving (a
        // chart's lowered transitions, which leave more, are written by their own file).
        let own = t
            .leaving
            .as_deref()
            .and_then(|leaving| leaving.strip_prefix(state.on_exit.as_slice()))
            .filter(|own| !own.is_empty());
        match own {
            Some(own) => {
                out.push_str(" {");
                write_block_body(out, own);
            }
            None => out.push('\n'),
        }
    }
    if let Some(outcome) = announced {
        let _ = writeln!(out, "    outcome {outcome}");
    }
    // Kept so nothing of the original is lost; a comment, so the file still reads.
    for u in index.unread.get(&state.id).into_iter().flatten() {
        let _ = writeln!(
            out,
            "    // not read (line {}: {}): when {} -> {}",
            u.line,
            one_line(&u.reason),
            one_line(&u.label),
            index.reference(u.target)
        );
    }
    out.push_str("}\n");
}

/// A transition's actions after its `{`, one a line, and the `}` that closes them.
fn write_block_body(out: &mut String, actions: &[Action]) {
    out.push('\n');
    for action in actions {
        out.push_str("        ");
        write_action(out, action);
        out.push('\n');
    }
    out.push_str("    }\n");
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

#[cfg(test)]
mod tests {
    use super::to_native;
    use crate::native::parse_machine;

    /// A name two states share is written as the ids; a unique one by name; each state's
    /// transitions in the machine's order.
    #[test]
    fn states_are_referred_to_by_name_where_unique_and_by_id_where_names_repeat() {
        let text = "machine M\ninitial #4\n\nstate A #4 {\n    when go -> #5\n    when TRUE -> B\n}\n\nstate A #5 {\n    when stop -> #4\n}\n\nstate B #6 {\n}\n";
        let read = parse_machine("m.machine", text);
        assert!(read.diagnostics.is_empty(), "{:?}", read.diagnostics);
        assert_eq!(to_native(&read.machines[0]), text);
    }
}
