//! The words of a DOT diagram that `dot` and `dot_chart` both write: node names, quoted and
//! escaped text, an action as one line.

use crate::model::{Action, Argument};

/// State ids may be negative; node names may not start with `-`.
pub(crate) fn node(id: i64) -> String {
    if id < 0 {
        format!("m{}", -id)
    } else {
        id.to_string()
    }
}

pub(crate) fn show(action: &Action) -> String {
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

pub(crate) fn escape(text: &str) -> String {
    text.replace('\\', "\\\\")
        .replace('"', "\\\"")
        .replace('\n', " ")
}

/// A DOT string literal.
pub fn quote(text: &str) -> String {
    format!("\"{}\"", escape(text))
}
