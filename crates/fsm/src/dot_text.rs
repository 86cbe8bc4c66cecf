//! The words of a DOT diagram that `dot` and `dot_chart` both write: node names, quoted and
//! escaped text, an action as one line, how a transition that stays is marked.

use crate::model::{Action, Argument, Transition};

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

/// How a transition that stays is told from one that leaves its state and enters it again: a
/// dashed loop, said in its label too. What to add to its label, and to its attributes.
pub(crate) fn stays_marks(t: &Transition) -> (&'static str, &'static str) {
    if t.stays {
        (" (stays)", ", style=dashed")
    } else {
        ("", "")
    }
}
