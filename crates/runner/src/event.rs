//! What a running machine reports: the trace of a behaviour, as data.

use std::time::Duration;

#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    Entered {
        machine: String,
        state: String,
        id: i64,
        at: Duration,
    },
    /// A label's atom was answered (or counted false after a timeout / for want of an expert).
    Answered {
        machine: String,
        atom: String,
        value: bool,
        by: Option<String>,
        at: Duration,
    },
    Fired {
        machine: String,
        from: i64,
        to: i64,
        label: String,
        at: Duration,
    },
    /// A host function the embedding program did not register; it is skipped.
    UnknownFunction { machine: String, function: String },
    Control {
        machine: String,
        command: String,
        at: Duration,
    },
}
