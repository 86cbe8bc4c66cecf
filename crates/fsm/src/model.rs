//! The machine model: states with three activities, transitions in priority order, labels.

use crate::code::Statement;
use crate::label::Label;

/// A state's identifier as written in its file (T/A ids, Qfsm codes). Names may repeat; ids do
/// not.
pub type StateId = i64;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Machine {
    pub name: String,
    /// What the file said of the machine beyond its name (a Qfsm `name` attribute that is not
    /// the file's name); empty when nothing.
    pub description: String,
    pub states: Vec<State>,
    /// Every transition; those of one source state are in priority order (first = tried first).
    pub transitions: Vec<Transition>,
    pub initial: StateId,
    /// Transitions of the original file whose label could not be read: not run, but kept so
    /// that an import can write them down (as comments) instead of losing them.
    pub unread: Vec<UnreadTransition>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnreadTransition {
    pub source: StateId,
    pub target: StateId,
    /// The label as written.
    pub label: String,
    /// Why it could not be read.
    pub reason: String,
    pub line: usize,
}

impl Machine {
    /// Every action of every state, in file order.
    pub fn actions(&self) -> impl Iterator<Item = &Action> + '_ {
        self.states
            .iter()
            .flat_map(|s| s.on_entry.iter().chain(&s.on_exit).chain(&s.internal))
    }

    /// Every statement of every activity, nested ones included, outermost first.
    pub fn statements(&self) -> Vec<&Statement> {
        let mut out = Vec::new();
        for action in self.actions() {
            if let Action::Statement(s) = action {
                s.visit(&mut |inner| out.push(inner));
            }
        }
        out
    }

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
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// `Type: content`: a whiteboard posting. Sub-machine control is a posting to the machine's
    /// name (`SMPlayer: On`, and gufsm's `suspend("M")` becomes `M: suspend`).
    Post { ty: String, content: String },
    /// `C++: f`, `C++: f(12)`, `msleep(100)`: a host function registered by name.
    Call {
        function: String,
        argument: Option<Argument>,
    },
    /// A statement of the activity language: a declaration, an assignment, a computed posting
    /// (`post("T", x + 1)`), a call, a block or a `for` loop.
    Statement(Statement),
    /// Text that could not be read as a statement, kept as written so nothing is lost; the
    /// reader reports it as an error and it does nothing when run.
    Code(String),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Argument {
    Int(i64),
    Str(String),
    /// An identifier or anything else, as written.
    Word(String),
}
