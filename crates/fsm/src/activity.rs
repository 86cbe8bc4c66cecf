//! Activities as written in the two imported formats: T/A items (`Type: content; C++: f(12)`)
//! and gufsm's C-like blocks (`OnEntry { post("Say", "hi"); msleep(100); } OnExit { } { }`).

use crate::diagnostic::Severity;
use crate::model::{Action, Argument};

/// Parses `;`-separated T/A items, with a problem for each item that is not `C++: call` or
/// `Type: content` (a bare `f(12)` is read as a call, with a warning).
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
        } else if let Some((function, argument)) = parse_call(item).filter(|_| item.ends_with(')'))
        {
            errors.push((
                Severity::Warning,
                format!("`{item}` has no `C++:`; it is read as a call"),
            ));
            actions.push(Action::Call { function, argument });
        } else {
            errors.push((Severity::Error, format!("`{item}` is not `Type: content`")));
        }
    }
    (actions, errors)
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

/// The three activities of a gufsm description, and a warning for each statement kept as code.
pub fn parse_gufsm_activities(text: &str) -> ([Vec<Action>; 3], Vec<String>) {
    let mut sections: [Vec<Action>; 3] = Default::default();
    let mut warnings = Vec::new();
    let mut rest = text;
    let mut unnamed = 0;
    while let Some(open) = rest.find('{') {
        let keyword = rest[..open].replace('$', "");
        let keyword = keyword.trim();
        let Some(close) = matching_brace(&rest[open..]) else {
            warnings
                .push("a `{` is never closed; the rest of the description is ignored".to_string());
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
                warnings.push(format!(
                    "`{other}` is not OnEntry, OnExit or Internal; its block is read as Internal"
                ));
                2
            }
        };
        for statement in split_top_level(body, ';') {
            let statement = statement.trim();
            if statement.is_empty() {
                continue;
            }
            let action = gufsm_statement(statement);
            if let Action::Code(code) = &action {
                warnings.push(format!("`{code}` is kept as code and will not run"));
            }
            sections[section].push(action);
        }
        rest = &rest[open + close + 1..];
    }
    if unnamed > 1 {
        warnings.push(format!(
            "{unnamed} unnamed blocks; all were read as Internal"
        ));
    }
    (sections, warnings)
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

/// A number or a string literal.
fn literal(text: &str) -> bool {
    text.parse::<f64>().is_ok() || (text.len() >= 2 && text.starts_with('"') && text.ends_with('"'))
}

fn gufsm_statement(statement: &str) -> Action {
    let code = || Action::Code(statement.to_string());
    let Some(open) = statement.find('(') else {
        return code();
    };
    let name = statement[..open].trim();
    if name.is_empty()
        || !name.chars().all(|c| c.is_alphanumeric() || c == '_')
        || !statement.ends_with(')')
    {
        return code();
    }
    let args: Vec<&str> = split_top_level(&statement[open + 1..statement.len() - 1], ',')
        .into_iter()
        .map(str::trim)
        .filter(|a| !a.is_empty())
        .collect();
    let string = |a: &str| {
        a.strip_prefix('"')
            .and_then(|s| s.strip_suffix('"'))
            .map(str::to_string)
    };
    match (name, args.as_slice()) {
        ("post" | "postv" | "post_v" | "post_int", [ty, content]) => {
            match (string(ty), string(content)) {
                // Spaces around a value are not part of it (and a native file could not keep them).
                (Some(ty), Some(content)) => Action::Post {
                    ty,
                    content: content.trim().to_string(),
                },
                (Some(ty), None) => Action::Post {
                    ty,
                    content: content.to_string(),
                },
                _ => code(),
            }
        }
        // `postv("T", 0, 0, 35, 100)`: several literal values, posted space-separated.
        ("postv" | "post_v", [ty, values @ ..])
            if values.len() > 1 && values.iter().all(|v| literal(v)) =>
        {
            match string(ty) {
                Some(ty) => Action::Post {
                    ty,
                    content: values
                        .iter()
                        .map(|v| string(v).unwrap_or_else(|| v.to_string()))
                        .collect::<Vec<_>>()
                        .join(" "),
                },
                None => code(),
            }
        }
        ("suspend" | "resume" | "restart", [machine]) => match string(machine) {
            Some(machine) => Action::Post {
                ty: machine,
                content: name.to_string(),
            },
            None => code(),
        },
        ("start" | "stop", [machine]) => match string(machine) {
            Some(machine) => Action::Post {
                ty: machine,
                content: if name == "start" { "On" } else { "Off" }.into(),
            },
            None => code(),
        },
        (_, []) => Action::Call {
            function: name.to_string(),
            argument: None,
        },
        (_, [one])
            if !one.contains(|c: char| "+-*/<>=".contains(c)) || one.parse::<i64>().is_ok() =>
        {
            Action::Call {
                function: name.to_string(),
                argument: argument(one),
            }
        }
        _ => code(),
    }
}
