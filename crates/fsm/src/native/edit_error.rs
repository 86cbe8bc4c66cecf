//! Why an edit of a machine file was refused: each variant says what the person asked for and
//! what stands in the way.

use std::fmt;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EditError {
    /// The file does not read as a machine, so there are no places to patch.
    DoesNotParse {
        line: usize,
        message: String,
    },
    /// Only native `.machine` files are edited in place.
    NotNative {
        format: String,
    },
    /// A valid file that uses what the edits do not place yet: `what` it is.
    Unsupported {
        line: usize,
        what: &'static str,
    },
    NoSuchState {
        state: usize,
        count: usize,
    },
    NoSuchTransition {
        state: String,
        transition: usize,
        count: usize,
    },
    /// Another state already has the name.
    NameTaken {
        name: String,
    },
    BadName {
        name: String,
        why: &'static str,
    },
    /// Deleting the state would leave these transitions pointing nowhere: `(from, line)`.
    Targeted {
        state: String,
        by: Vec<(String, usize)>,
    },
    /// The initial state cannot go; another must be made initial first.
    Initial {
        state: String,
    },
    /// A state that announces an outcome is final: it cannot be given a transition.
    Announces {
        state: String,
        outcome: String,
    },
    /// A label or activity that cannot be written where it goes (a line break in a label).
    BadText {
        what: &'static str,
        why: String,
    },
}

impl fmt::Display for EditError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EditError::DoesNotParse { line, message } => write!(
                f,
                "the file does not read as a machine (line {line}: {message}); fix it in a text editor first"
            ),
            EditError::Unsupported { line, what } => write!(
                f,
                "the machine {what} (line {line}), which the editor does not edit yet: change the file in a text editor (`proclaim check` reads it)"
            ),
            EditError::NotNative { format } => write!(
                f,
                "{format} machines are not edited in place: `proclaim import` converts them to a native .machine file, which can be"
            ),
            EditError::NoSuchState { state, count } => {
                write!(f, "there is no state number {state} (the machine has {count})")
            }
            EditError::NoSuchTransition {
                state,
                transition,
                count,
            } => write!(
                f,
                "state {state} has no transition number {transition} (it has {count})"
            ),
            EditError::NameTaken { name } => write!(f, "a state is already named `{name}`"),
            EditError::BadName { name, why } => write!(f, "`{name}` cannot name a state: {why}"),
            EditError::Targeted { state, by } => {
                let from: Vec<String> = by
                    .iter()
                    .map(|(from, line)| format!("from {from} (line {line})"))
                    .collect();
                write!(
                    f,
                    "state {state} cannot be deleted while transitions lead to it: {}; delete or retarget them first",
                    from.join(", ")
                )
            }
            EditError::Initial { state } => write!(
                f,
                "state {state} is the initial state; make another state initial before deleting it"
            ),
            EditError::BadText { what, why } => write!(f, "the {what} cannot be written: {why}"),
            EditError::Announces { state, outcome } => write!(
                f,
                "state {state} announces outcome `{outcome}`, so it is final: take `outcome {outcome}` out of it before giving it a transition"
            ),
        }
    }
}

impl std::error::Error for EditError {}
