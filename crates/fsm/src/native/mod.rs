//! The native machine format: one machine a file, readable and diffable, comments allowed,
//! transitions listed in priority order (first = tried first).
//!
//! ```text
//! // The seed paper's Figure 1, cut down.
//! machine GameController
//! initial INITIAL
//!
//! state INITIAL {
//!     entry {
//!         LEDS: ChestBoard Off
//!         call sayTeam
//!     }
//!     when readyReceived -> READY
//! }
//!
//! state READY {
//!     entry {
//!         Placer: On
//!     }
//!     exit {
//!         Placer: Off
//!     }
//!     when setReceived && !penaltyReceived -> SET
//!     when timeout(5000000) -> INITIAL
//! }
//! ```
//!
//! A posting is `Type: content` (the content is the rest of the line), a host call is
//! `call f`, `call f(12)`, `call f("text")`; anything else in an activity is a statement of the
//! activity language ending in `;` (`count = count + 1;`, `post("Say", count);`, `int n;`), and
//! `code …` keeps text that an importer could not read, as written. States may carry their original id (`state GetUp #14`); where names repeat,
//! a transition names its target by id (`-> #14`).

mod ast;
mod lexer;
mod write;

use crate::code::parse_statements;
use crate::diagnostic::FileDiagnostic;
use crate::label::parse_label;
use crate::model::{Action, Machine, State, StateId, Transition};
use crate::Imported;
use ast::{ActionAst, FileAst, Member, Ref, Section, TopItem};
use lalrpop_util::ParseError;
use lexer::{LexError, Lexer, Tok};

pub use write::to_native;

lalrpop_util::lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused)]
    grammar,
    "/native/grammar.rs"
);

/// The file extension of native machine files.
pub const EXTENSION: &str = "machine";

/// Reads one machine in the native format. Never fails: a file that does not parse yields no
/// machine and a diagnostic naming the line; names that resolve to no state are reported too.
pub fn parse_machine(file: &str, text: &str) -> Imported {
    let lines = LineIndex::new(text);
    let parsed = grammar::FileParser::new().parse(Lexer::new(text));
    match parsed {
        Ok(ast) => lower(file, &lines, ast),
        Err(error) => {
            let (at, message) = describe(error, text.len());
            Imported {
                machines: Vec::new(),
                diagnostics: vec![lines.error(file, at, message)],
            }
        }
    }
}

fn describe(error: ParseError<usize, Tok<'_>, LexError>, end: usize) -> (usize, String) {
    let expected = |expected: &[String]| {
        let names: Vec<String> = expected.iter().map(|e| friendly(e)).collect();
        match names.as_slice() {
            [] => String::new(),
            [one] => format!("; expected {one}"),
            many => format!("; expected one of {}", many.join(", ")),
        }
    };
    match error {
        ParseError::InvalidToken { location } => (location, "unreadable text".into()),
        ParseError::UnrecognizedEof { expected: e, .. } => {
            (end, format!("the file ends too early{}", expected(&e)))
        }
        ParseError::UnrecognizedToken {
            token: (at, tok, _),
            expected: e,
        } => (at, format!("unexpected {tok}{}", expected(&e))),
        ParseError::ExtraToken {
            token: (at, tok, _),
        } => (at, format!("unexpected {tok}")),
        ParseError::User { error } => (error.at, error.message),
    }
}

/// lalrpop names terminals as they are written in the grammar; say what they are instead.
fn friendly(terminal: &str) -> String {
    match terminal {
        "Word" => "a name".into(),
        "Str" => "a quoted string".into(),
        "Int" => "a whole number".into(),
        "Text" => "`:` and the posting's content".into(),
        "LabelText" => "a label".into(),
        "Statement" => "a statement".into(),
        quoted => format!("`{}`", quoted.trim_matches('"')),
    }
}

struct LineIndex<'t> {
    text: &'t str,
    starts: Vec<usize>,
}

impl LineIndex<'_> {
    fn new(text: &str) -> LineIndex<'_> {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex { text, starts }
    }

    /// 1-based.
    fn line(&self, offset: usize) -> usize {
        self.starts.partition_point(|&s| s <= offset)
    }

    /// An error at a byte offset, with its line and column.
    fn error(&self, file: &str, offset: usize, message: String) -> FileDiagnostic {
        let line = self.line(offset);
        let start = self.starts[line - 1];
        let column = self
            .text
            .get(start..offset.min(self.text.len()))
            .map_or(1, |before| before.chars().count() + 1);
        FileDiagnostic::error(file, line, message).at_column(column)
    }
}

fn lower(file: &str, lines: &LineIndex<'_>, ast: FileAst) -> Imported {
    let mut diagnostics = Vec::new();
    let mut error = |at: usize, message: String| {
        diagnostics.push(lines.error(file, at, message));
    };
    let mut initial_ref = None;
    let mut description = String::new();
    let mut parsed = Vec::new();
    for item in ast.items {
        match item {
            TopItem::Description(text, at) => {
                if !description.is_empty() {
                    error(at, "the description is given twice".into());
                }
                description = text;
            }
            TopItem::Initial(target, at) => {
                if initial_ref.is_some() {
                    error(at, "the initial state is given twice".into());
                } else {
                    initial_ref = Some((target, at));
                }
            }
            TopItem::State(s) => parsed.push(s),
        }
    }
    // Ids as written; the others numbered from 1, skipping those taken.
    let mut taken: Vec<StateId> = Vec::new();
    for s in &parsed {
        if let Some(id) = s.id {
            if taken.contains(&id) {
                error(s.at, format!("state id #{id} is used twice"));
            }
            taken.push(id);
        }
    }
    let mut next = 1;
    let ids: Vec<StateId> = parsed
        .iter()
        .map(|s| {
            s.id.unwrap_or_else(|| {
                while taken.contains(&next) {
                    next += 1;
                }
                taken.push(next);
                next
            })
        })
        .collect();
    let names: Vec<(String, StateId)> = parsed
        .iter()
        .zip(&ids)
        .map(|(s, &id)| (s.name.clone(), id))
        .collect();
    let resolve = |target: &Ref| -> Result<StateId, String> {
        match target {
            Ref::Id(id) if ids.contains(id) => Ok(*id),
            Ref::Id(id) => Err(format!("there is no state #{id}")),
            Ref::Name(name) => {
                let found: Vec<StateId> = names
                    .iter()
                    .filter(|(n, _)| n == name)
                    .map(|(_, id)| *id)
                    .collect();
                match found.as_slice() {
                    [id] => Ok(*id),
                    [] => Err(match proclaim_syntax::nearest(names.iter().map(|(n, _)| n.as_str()), name) {
                        Some(near) => format!("there is no state named `{name}`; did you mean `{near}`?"),
                        None => format!("there is no state named `{name}`"),
                    }),
                    many => Err(format!(
                        "`{name}` names {} states ({}); name the one meant by its id, as in `-> #{}`",
                        many.len(),
                        many.iter()
                            .map(|id| format!("#{id}"))
                            .collect::<Vec<_>>()
                            .join(", "),
                        many[0]
                    )),
                }
            }
        }
    };
    let mut states = Vec::new();
    let mut transitions = Vec::new();
    for (s, &id) in parsed.into_iter().zip(&ids) {
        let mut state = State {
            id,
            name: s.name,
            on_entry: Vec::new(),
            on_exit: Vec::new(),
            internal: Vec::new(),
            line: lines.line(s.at),
        };
        let mut seen: Vec<Section> = Vec::new();
        for member in s.members {
            match member {
                Member::Activity {
                    section,
                    actions,
                    at,
                } => {
                    if seen.contains(&section) {
                        error(
                            at,
                            format!(
                                "state `{}` has two {} blocks; put their items in one",
                                state.name,
                                section_name(section)
                            ),
                        );
                    }
                    seen.push(section);
                    let list = match section {
                        Section::Entry => &mut state.on_entry,
                        Section::Exit => &mut state.on_exit,
                        Section::Internal => &mut state.internal,
                    };
                    for (action, at) in actions {
                        match action {
                            ActionAst::Done(action) => list.push(action),
                            ActionAst::Statement(text) => match parse_statements(&text) {
                                Ok(statements) => {
                                    list.extend(statements.into_iter().map(Action::Statement))
                                }
                                Err(e) => {
                                    error(at + e.offset, format!("bad statement: {}", e.message))
                                }
                            },
                        }
                    }
                }
                Member::When {
                    label,
                    label_at,
                    target,
                    target_at,
                    at,
                } => {
                    if label.is_empty() {
                        error(
                            at,
                            "a transition needs a label; write `when TRUE -> …` for one that always fires".into(),
                        );
                        continue;
                    }
                    let label = match parse_label(&label) {
                        Ok(l) => l,
                        Err(e) => {
                            error(label_at + e.offset, format!("bad label: {}", e.message));
                            continue;
                        }
                    };
                    match resolve(&target) {
                        Ok(to) => transitions.push(Transition {
                            source: id,
                            target: to,
                            label,
                            line: lines.line(at),
                        }),
                        Err(message) => error(target_at, message),
                    }
                }
            }
        }
        states.push(state);
    }
    let initial = match initial_ref {
        Some((target, at)) => match resolve(&target) {
            Ok(id) => Some(id),
            Err(message) => {
                error(at, message);
                None
            }
        },
        None => states.first().map(|s| s.id),
    };
    let machines = match initial {
        Some(initial) => vec![Machine {
            name: ast.name,
            description,
            states,
            transitions,
            initial,
            unread: Vec::new(),
        }],
        None if states.is_empty() => {
            error(ast.name_at, format!("machine `{}` has no states", ast.name));
            Vec::new()
        }
        None => Vec::new(),
    };
    Imported {
        machines,
        diagnostics,
    }
}

fn section_name(section: Section) -> &'static str {
    match section {
        Section::Entry => "entry",
        Section::Exit => "exit",
        Section::Internal => "internal",
    }
}

/// Whether a file name is a native machine file.
pub fn is_native(path: &str) -> bool {
    std::path::Path::new(path)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(EXTENSION))
}
