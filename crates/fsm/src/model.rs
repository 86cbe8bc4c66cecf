//! The machine model: states with three activities, transitions in priority order, labels.

use crate::label::Label;

/// A state's identifier as written in its file (T/A ids, Qfsm codes). Names may repeat; ids do
/// not.
pub type StateId = i64;

#[derive(Clone, Debug, PartialEq)]
pub struct Machine {
    pub name: String,
    pub states: Vec<State>,
    /// Every transition; those of one source state are in priority order (first = tried first).
    pub transitions: Vec<Transition>,
    pub initial: StateId,
}

impl Machine {
    pub fn state(&self, id: StateId) -> Option<&State> {
        self.states.iter().find(|s| s.id == id)
    }

    /// The transitions leaving `id`, highest priority first.
    pub fn outgoing(&self, id: StateId) -> impl Iterator<Item = &Transition> + '_ {
        self.transitions.iter().filter(move |t| t.source == id)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct State {
    pub id: StateId,
    pub name: String,
    pub on_entry: Vec<Action>,
    pub on_exit: Vec<Action>,
    pub internal: Vec<Action>,
    /// Where it was written (1-based), for diagnostics.
    pub line: usize,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Transition {
    pub source: StateId,
    pub target: StateId,
    pub label: Label,
    pub line: usize,
}

/// One thing an activity does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Action {
    /// `Type: content`: a whiteboard posting. Sub-machine control is a posting to the machine's
    /// name (`SMPlayer: On`, and gufsm's `suspend("M")` becomes `M: suspend`).
    Post { ty: String, content: String },
    /// `C++: f`, `C++: f(12)`, `msleep(100)`: a host function registered by name.
    Call {
        function: String,
        argument: Option<Argument>,
    },
    /// A statement of gufsm's C-like code that is kept as written but not run (assignments with
    /// expressions, arithmetic); importers warn about each.
    Code(String),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Argument {
    Int(i64),
    Str(String),
    /// An identifier or anything else, as written.
    Word(String),
}
