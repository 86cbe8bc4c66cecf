//! The original interpreter's T/A tables: machine `NAME` is `TNAME.txt` (transitions, one a line,
//! `source<TAB>label<TAB>target`, the **last** line of a state tried first) plus `ANAME.txt` (states,
//! `id<TAB>NAME|OnEntry …/ OnExit …/ internal`, the **last** line the initial state).

use crate::activity::parse_ta_items;
use crate::label::parse_label;
use crate::model::{Machine, State, StateId, Transition, UnreadTransition};
use crate::Imported;
use proclaim_syntax::{FileDiagnostic, Severity};
use std::path::{Path, PathBuf};

/// The other file of a T/A pair: `TFoo.txt` ↔ `AFoo.txt`, in the same folder.
pub fn partner_of(path: &Path) -> Option<PathBuf> {
    let name = path.file_name()?.to_str()?;
    let partner = match name.split_at_checked(1)? {
        ("T", rest) => format!("A{rest}"),
        ("A", rest) => format!("T{rest}"),
        _ => return None,
    };
    Some(path.with_file_name(partner))
}

/// Imports one machine from its T and A texts. `name` is the machine's name (`GameController`
/// for `TGameController.txt`).
pub fn import_ta(name: &str, t_file: &str, t_text: &str, a_file: &str, a_text: &str) -> Imported {
    let mut diagnostics = Vec::new();
    let mut states: Vec<State> = Vec::new();
    for (i, raw) in a_text.lines().enumerate() {
        if raw.trim().is_empty() {
            continue;
        }
        if let Some(state) = a_line(raw, i + 1, &states, a_file, &mut diagnostics) {
            states.push(state);
        }
    }
    let Some(initial) = states.last().map(|s| s.id) else {
        diagnostics.push(FileDiagnostic::error(
            a_file,
            1,
            "no states: the initial state is the last line of the A file",
        ));
        return Imported {
            machines: Vec::new(),
            diagnostics,
        };
    };
    let mut machine = Machine {
        name: name.to_string(),
        states,
        initial,
        ..Machine::default()
    };
    let files = (t_file, a_file);
    for (i, raw) in t_text
        .lines()
        .enumerate()
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
    {
        if !raw.trim().is_empty() {
            t_line(raw, i + 1, &mut machine, files, &mut diagnostics);
        }
    }
    // Reading T backwards put each state's transitions in priority order; keep it per state.
    machine.transitions.sort_by_key(|t| t.source);
    Imported {
        machines: vec![machine],
        diagnostics,
    }
}

/// One line of the A file (`ID NAME|OnEntry …/ OnExit …/ internal`): the state, or `None` with
/// a diagnostic saying why not.
fn a_line(
    raw: &str,
    line: usize,
    states: &[State],
    a_file: &str,
    diagnostics: &mut Vec<FileDiagnostic>,
) -> Option<State> {
    let (id_text, rest) = raw
        .trim_start()
        .split_once(|c: char| c.is_whitespace())
        .unwrap_or((raw.trim(), ""));
    let Ok(id) = id_text.parse::<StateId>() else {
        diagnostics.push(FileDiagnostic::error(
            a_file,
            line,
            format!("`{id_text}` is not a state id (a whole number)"),
        ));
        return None;
    };
    if states.iter().any(|s| s.id == id) {
        diagnostics.push(FileDiagnostic::error(
            a_file,
            line,
            format!("state id {id} is used twice"),
        ));
        return None;
    }
    let (state_name, activities) = rest.split_once('|').unwrap_or((rest, ""));
    let state_name = state_name.trim();
    if state_name.is_empty() {
        diagnostics.push(FileDiagnostic::error(
            a_file,
            line,
            format!("state {id} has no name"),
        ));
        return None;
    }
    if let Some(word) = misspelt_section(activities) {
        diagnostics.push(FileDiagnostic::error(
            a_file,
            line,
            format!("`{word}` is not a section keyword (OnEntry or OnExit); its items are read as Internal"),
        ));
    }
    let [entry, exit, internal] = sections(activities);
    let mut read = |text: &str| {
        // A lone `/` ends a section that has no keyword; it is not an item.
        let (actions, problems) = parse_ta_items(text.trim_end_matches('/'));
        for (severity, message) in problems {
            diagnostics.push(match severity {
                Severity::Error => FileDiagnostic::error(a_file, line, message),
                Severity::Warning => FileDiagnostic::warning(a_file, line, message),
            });
        }
        actions
    };
    Some(State {
        id,
        name: state_name.to_string(),
        on_entry: read(&entry),
        on_exit: read(&exit),
        // Internal text can hold more `/`-ended chunks (`…/ C++: f(1);/ C++: g;`): separators too.
        internal: read(&internal.replace('/', ";")),
        line,
        arrives_through: 0,
        arrival_clocks: Vec::new(),
    })
}

/// A word that looks like a section keyword but is not one (`OnEnrtry`), which would
/// silently move the items to Internal.
fn misspelt_section(activities: &str) -> Option<&str> {
    activities.split(|c: char| !c.is_alphanumeric()).find(|w| {
        w.starts_with("On")
            && w.len() > 3
            && *w != "OnEntry"
            && *w != "OnExit"
            && !activities.contains("OnEntry")
    })
}

/// One line of the T file (`SOURCE<TAB>LABEL<TAB>TARGET`): a transition of `machine`, kept
/// unread when its label does not parse.
fn t_line(
    raw: &str,
    line: usize,
    machine: &mut Machine,
    (t_file, a_file): (&str, &str),
    diagnostics: &mut Vec<FileDiagnostic>,
) {
    let states = &machine.states;
    let fields: Vec<&str> = if raw.matches('\t').count() == 2 {
        raw.split('\t').collect()
    } else {
        raw.split_whitespace().collect()
    };
    let [source, label, target] = fields[..] else {
        diagnostics.push(FileDiagnostic::error(
            t_file,
            line,
            "expected `source<TAB>label<TAB>target`",
        ));
        return;
    };
    let id = |text: &str| -> Result<StateId, String> {
        let id = text
            .trim()
            .parse::<StateId>()
            .map_err(|_| format!("`{}` is not a state id", text.trim()))?;
        if states.iter().any(|s| s.id == id) {
            Ok(id)
        } else {
            Err(format!("state {id} is not in {a_file}"))
        }
    };
    let (source, target) = match (id(source), id(target)) {
        (Ok(source), Ok(target)) => (source, target),
        (Err(e), _) | (_, Err(e)) => {
            diagnostics.push(FileDiagnostic::error(t_file, line, e));
            return;
        }
    };
    match parse_label(label) {
        Ok(label) => machine.transitions.push(Transition {
            source,
            target,
            label,
            line,
            leaving: None,
            composite: None,
            enters: Vec::new(),
            written: None,
            joined: Vec::new(),
            stays: false,
            targets: Vec::new(),
        }),
        Err(e) => {
            diagnostics.push(FileDiagnostic::error(
                t_file,
                line,
                format!("label `{}`: {e}", label.trim()),
            ));
            machine.unread.push(UnreadTransition {
                source,
                target,
                label: label.trim().to_string(),
                reason: e.to_string(),
                line,
            });
        }
    }
}

/// Splits `OnEntry …/ OnExit …/ internal` at the keywords, each section ended by the first `/`.
/// Text between sections (`…/ C++: f; OnExit …`) is read as Internal too, before the rest.
fn sections(text: &str) -> [String; 3] {
    fn take<'a>(rest: &mut &'a str, keyword: &str, stray: &mut String) -> &'a str {
        let Some(at) = rest.find(keyword) else {
            return "";
        };
        stray.push_str(&rest[..at]);
        stray.push(';');
        let after = &rest[at + keyword.len()..];
        let end = after.find('/').unwrap_or(after.len());
        *rest = after.get(end + 1..).unwrap_or("");
        &after[..end]
    }
    let mut rest = text;
    let mut internal = String::new();
    let entry = take(&mut rest, "OnEntry", &mut internal).to_string();
    let exit = take(&mut rest, "OnExit", &mut internal).to_string();
    internal.push_str(rest);
    [entry, exit, internal]
}
