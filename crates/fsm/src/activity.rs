//! Activities as written in the two imported formats: T/A items (`Type: content; C++: f(12)`)
//! and gufsm's blocks of activity-language statements (`OnEntry { post("Say", "hi"); x = x + 1; }
//! OnExit { } { }`).

use crate::code::{parse_statements, Expr, Statement};
use crate::control::Command;
use crate::model::{Action, Argument};
use crate::sections::{section, split_sections, Section};
use proclaim_syntax::Severity;

/// Parses `;`-separated T/A items, with a problem for each item that is not `C++: call`,
/// `Type: content` or a statement of the activity language (a bare `f(12)` is read as a call,
/// with a warning).
pub fn parse_ta_items(text: &str) -> (Vec<Action>, Vec<(Severity, String)>) {
    let mut actions = Vec::new();
    let mut errors: Vec<(Severity, String)> = Vec::new();
    for item in text.split(';').map(str::trim).filter(|i| !i.is_empty()) {
        if let Some(call) = item.strip_prefix("C++:") {
            match parse_call(call.trim()) {
                Some((function, argument)) => actions.push(Action::Call { function, argument }),
                None => errors.push((
                    Severity::Error,
                    format!(
                        "`{item}` is not a call such as `C++: f`, `C++: f(12)` or `C++: f(\"s\")`"
                    ),
                )),
            }
        } else if let Some((ty, content)) = item.split_once(':') {
            if ty.trim().is_empty() || ty.trim().contains(char::is_whitespace) {
                errors.push((
                    Severity::Error,
                    format!("`{item}` does not start with a message type"),
                ));
            } else {
                actions.push(Action::Post {
                    ty: ty.trim().to_string(),
                    content: content.trim().to_string(),
                });
            }
        } else if let Some((function, argument)) =
            parse_call(item).filter(|(f, _)| item.ends_with(')') && !is_builtin(f))
        {
            errors.push((
                Severity::Warning,
                format!("`{item}` has no `C++:`; it is read as a call"),
            ));
            actions.push(Action::Call { function, argument });
        } else if let Some(statements) = ta_statements(item) {
            actions.extend(statements.into_iter().map(action));
        } else {
            errors.push((Severity::Error, format!("`{item}` is not `Type: content`")));
        }
    }
    (actions, errors)
}

/// An item of the activity language in a T/A table (`count = count + 1`, `int n`): statements
/// that do something, not a lone name or number. (Items are cut at every `;`, so a `for` loop,
/// whose head holds `;`, cannot be written in a T/A table.)
fn ta_statements(item: &str) -> Option<Vec<Statement>> {
    let statements = parse_statements(item).ok()?;
    let does_something = |s: &Statement| match s {
        Statement::Expr(e) => matches!(e, Expr::Call { .. }),
        _ => true,
    };
    (!statements.is_empty() && statements.iter().all(does_something)).then_some(statements)
}

/// `f`, `f()`, `f(12)`, `f("s")`, `f(word)`.
fn parse_call(text: &str) -> Option<(String, Option<Argument>)> {
    let (name, rest) = match text.find('(') {
        Some(i) => (text[..i].trim(), Some(text[i + 1..].trim())),
        None => (text, None),
    };
    if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
        return None;
    }
    let argument = match rest {
        None => None,
        Some(rest) => {
            let inner = rest.strip_suffix(')')?.trim();
            argument(inner)
        }
    };
    Some((name.to_string(), argument))
}

fn argument(text: &str) -> Option<Argument> {
    if text.is_empty() {
        None
    } else if let Ok(i) = text.parse() {
        Some(Argument::Int(i))
    } else if let Some(s) = text.strip_prefix('"').and_then(|t| t.strip_suffix('"')) {
        Some(Argument::Str(s.to_string()))
    } else {
        Some(Argument::Word(text.to_string()))
    }
}

/// A Qfsm description read, in either form gufsm's editors saved: its three activities (OnEntry,
/// OnExit, Internal; the declarations of a `$variables$` section lead OnEntry, which gives the
/// machine those variables), what to keep as a note (`$includes$`), and the problems.
#[derive(Debug, Default)]
pub struct Description {
    pub activities: [Vec<Action>; 3],
    pub notes: Vec<String>,
    pub problems: Vec<(Severity, String)>,
}

pub fn parse_description(text: &str) -> Description {
    let Some(sections) = split_sections(text) else {
        let (activities, problems) = parse_gufsm_activities(text);
        return Description {
            activities,
            problems,
            ..Description::default()
        };
    };
    let mut d = Description::default();
    let mut declarations = Vec::new();
    for (name, body) in sections {
        match section(name) {
            Section::Activity(i) => {
                d.activities[i].extend(block_actions(unbraced(body), &mut d.problems));
            }
            Section::Variables => declarations.extend(variables(body, &mut d.problems)),
            Section::Includes if !body.trim().is_empty() => {
                d.notes.push(format!("includes: {}", body.trim()));
            }
            Section::SuspendResume if !body.trim().is_empty() => d.problems.push((
                Severity::Warning,
                format!("`${name}$` is not run: proclaim suspends a machine without running code"),
            )),
            Section::Unknown if !body.trim().is_empty() => d.problems.push((
                Severity::Warning,
                format!("section `${name}$` is not one proclaim reads; it is ignored"),
            )),
            _ => {}
        }
    }
    d.activities[0].splice(0..0, declarations);
    d
}

/// A section's statements without the braces the team's files put round them (`$OnExit$` then
/// `{ light=1; }`), so they read as the braced form's blocks do.
fn unbraced(body: &str) -> &str {
    let trimmed = body.trim();
    match matching_brace(trimmed) {
        Some(close) if trimmed.starts_with('{') && close == trimmed.len() - 1 => &trimmed[1..close],
        _ => body,
    }
}

/// The declarations of a `$variables$` section, one a line as the editors write them
/// (`int\tcount;\t///< how many`); a line that is no declaration of the activity language (a C++
/// type such as `const char *`) is a warning, and its variable is not declared.
fn variables(body: &str, problems: &mut Vec<(Severity, String)>) -> Vec<Action> {
    let mut out = Vec::new();
    for line in body.lines() {
        let code = line.split("//").next().unwrap_or("").trim();
        if code.is_empty() {
            continue;
        }
        match parse_statements(code) {
            Ok(statements)
                if statements
                    .iter()
                    .all(|s| matches!(s, Statement::Declare { .. })) =>
            {
                out.extend(statements.into_iter().map(action));
            }
            _ => problems.push((
                Severity::Warning,
                format!(
                    "`{code}` in `$variables$` is not a declaration proclaim knows (int, bool, char, float, double); the variable is not declared"
                ),
            )),
        }
    }
    out
}

/// The three activities of a gufsm description (OnEntry, OnExit, Internal), and a problem for
/// each statement that could not be read (kept as [`Action::Code`]) or block that is not one of
/// the three.
pub fn parse_gufsm_activities(text: &str) -> ([Vec<Action>; 3], Vec<(Severity, String)>) {
    let mut sections: [Vec<Action>; 3] = Default::default();
    let mut problems = Vec::new();
    let mut rest = text;
    let mut unnamed = 0;
    while let Some(open) = rest.find('{') {
        let keyword = rest[..open].replace('$', "");
        let keyword = keyword.trim();
        let Some(close) = matching_brace(&rest[open..]) else {
            problems.push((
                Severity::Error,
                "a `{` is never closed; the rest of the description is ignored".to_string(),
            ));
            break;
        };
        let body = &rest[open + 1..open + close];
        let section = match keyword {
            "OnEntry" => 0,
            "OnExit" => 1,
            "Internal" => 2,
            "" => {
                unnamed += 1;
                2
            }
            other => {
                problems.push((
                    Severity::Warning,
                    format!("`{other}` is not OnEntry, OnExit or Internal; its block is read as Internal"),
                ));
                2
            }
        };
        sections[section].extend(block_actions(body, &mut problems));
        rest = &rest[open + close + 1..];
    }
    if unnamed > 1 {
        problems.push((
            Severity::Warning,
            format!("{unnamed} unnamed blocks; all were read as Internal"),
        ));
    }
    (sections, problems)
}

/// The statements of one block as actions. When the block does not parse as a whole, each
/// `;`-separated piece is read alone, so one bad statement keeps only itself as code.
fn block_actions(body: &str, problems: &mut Vec<(Severity, String)>) -> Vec<Action> {
    if let Ok(statements) = parse_statements(body) {
        return statements.into_iter().map(action).collect();
    }
    let mut out = Vec::new();
    for piece in split_top_level(body, ';') {
        let piece = piece.trim();
        if piece.is_empty() {
            continue;
        }
        match parse_statements(piece) {
            Ok(statements) => out.extend(statements.into_iter().map(action)),
            Err(e) => {
                problems.push((
                    Severity::Error,
                    format!(
                        "`{piece}` is not a statement: {e}; it is kept as code and does nothing"
                    ),
                ));
                out.push(Action::Code(piece.to_string()));
            }
        }
    }
    out
}

/// The plainest action for a statement: a posting of a literal (`post("Say", "hi")` is
/// `Say: hi`), sub-machine control (`suspend("M")` is `M: suspend`), a host call with a literal
/// argument; anything else stays a statement.
fn action(statement: Statement) -> Action {
    let Statement::Expr(Expr::Call {
        function,
        arguments,
        ..
    }) = &statement
    else {
        return Action::Statement(statement);
    };
    let literal = |e: &Expr| match e {
        Expr::Str(s) => Some(s.trim().to_string()),
        Expr::Int(i) => Some(i.to_string()),
        _ => None,
    };
    match (function.as_str(), arguments.as_slice()) {
        ("post" | "post_int", [Expr::Str(ty), content]) => match literal(content) {
            // Spaces around a value are not part of it (and a native file could not keep them).
            Some(content) if !content.is_empty() => Action::Post {
                ty: ty.clone(),
                content,
            },
            _ => Action::Statement(statement),
        },
        (f, [Expr::Str(machine)]) if Command::from_function(f).is_some() => Action::Post {
            ty: machine.clone(),
            content: Command::from_function(f).map_or_else(String::new, |c| c.word().to_string()),
        },
        (f, []) if !is_builtin(f) => Action::Call {
            function: f.to_string(),
            argument: None,
        },
        (f, [Expr::Int(i)]) if !is_builtin(f) || f == "msleep" || f == "sleep" => Action::Call {
            function: f.to_string(),
            argument: Some(Argument::Int(*i)),
        },
        (f, [Expr::Str(s)]) if !is_builtin(f) => Action::Call {
            function: f.to_string(),
            argument: Some(Argument::Str(s.clone())),
        },
        _ => Action::Statement(statement),
    }
}

impl Action {
    /// The postings of literal type and content the action makes, however deep in a block or
    /// loop (`post("Say", "hi")`, `suspend("Dive")` is `Dive: suspend`): what `check` holds to
    /// the behaviour's machines and modules, whichever format the activity was written in.
    pub fn literal_postings(&self) -> Vec<(String, String)> {
        let mut found = Vec::new();
        match self {
            Action::Post { ty, content } => found.push((ty.clone(), content.clone())),
            Action::Statement(s) => statement_postings(s, &mut found),
            Action::Call { .. } | Action::Code(_) => {}
        }
        found
    }
}

fn statement_postings(statement: &Statement, found: &mut Vec<(String, String)>) {
    match statement {
        Statement::Block(body) => body.iter().for_each(|s| statement_postings(s, found)),
        Statement::For { body, .. } => statement_postings(body, found),
        Statement::Expr(Expr::Call { .. }) => {
            if let Action::Post { ty, content } = action(statement.clone()) {
                found.push((ty, content));
            }
        }
        _ => {}
    }
}

/// Functions the interpreter itself provides to activities (see the runner), beside the
/// sub-machine controls (`Command::from_function`); a call of any other name is a host
/// function.
pub const BUILTIN_FUNCTIONS: [&str; 21] = [
    "post",
    "post_int",
    "postv",
    "post_v",
    "say",
    "speech",
    "say_state_name",
    "speak_state_name",
    "print",
    "print_int",
    "print_fixed",
    "print_state_name",
    "msleep",
    "sleep",
    "abs",
    "sqrt",
    "sin",
    "cos",
    "tan",
    "atan",
    "atan2",
];

/// Built in: the functions above, and the sub-machine controls, whose one place is
/// `control.rs`.
fn is_builtin(function: &str) -> bool {
    BUILTIN_FUNCTIONS.contains(&function)
        || crate::control::Command::from_function(function).is_some()
}

/// Byte offset of the `}` matching the `{` that starts `text`, skipping strings.
fn matching_brace(text: &str) -> Option<usize> {
    let mut depth = 0;
    let mut in_string = false;
    let mut escaped = false;
    for (i, c) in text.char_indices() {
        match c {
            _ if escaped => escaped = false,
            '\\' if in_string => escaped = true,
            '"' => in_string = !in_string,
            '{' if !in_string => depth += 1,
            '}' if !in_string => {
                depth -= 1;
                if depth == 0 {
                    return Some(i);
                }
            }
            _ => {}
        }
    }
    None
}

fn split_top_level(text: &str, separator: char) -> Vec<&str> {
    let mut parts = Vec::new();
    let (mut depth, mut in_string, mut start) = (0i32, false, 0);
    for (i, c) in text.char_indices() {
        match c {
            '"' => in_string = !in_string,
            '(' | '{' | '[' if !in_string => depth += 1,
            ')' | '}' | ']' if !in_string => depth -= 1,
            c if c == separator && !in_string && depth == 0 => {
                parts.push(&text[start..i]);
                start = i + c.len_utf8();
            }
            _ => {}
        }
    }
    parts.push(&text[start..]);
    parts
}
