//! What the native grammar reads, before names are resolved to states.

use crate::model::Action;

pub struct FileAst {
    pub name: String,
    pub name_at: usize,
    pub items: Vec<TopItem>,
}

pub enum TopItem {
    /// `initial A`, or `initial P.A.X, P.B.Y` (a state in each of several regions): each state
    /// where it is written, the first at the keyword.
    Initial(Initials),
    Description(String, usize),
    /// `param side: int`: the text after `param`.
    Param(String, usize),
    /// `outcome saved, missed`: the text after `outcome`.
    Outcome(String, usize),
    State(StateAst),
}

/// A state named by its name, or by `#id` where names repeat.
#[derive(Clone, Debug)]
pub enum Ref {
    Name(String),
    Id(i64),
}

pub struct StateAst {
    pub name: String,
    pub id: Option<i64>,
    pub at: usize,
    pub members: Vec<Member>,
    /// `parallel NAME { … }`: the states it holds are regions, all active while it is.
    pub parallel: bool,
}

/// Which of a state's three activities.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Section {
    Entry,
    Exit,
    Internal,
}

pub enum Member {
    Activity {
        section: Section,
        actions: Vec<(ActionAst, usize)>,
        at: usize,
    },
    When {
        label: String,
        label_at: usize,
        /// `None` for one that stays (`when p { … }`, SCXML's transition without a target).
        target: Option<Ref>,
        target_at: usize,
        /// Further targets, each with where it is written (`-> P.A.X, P.B.Y`: a state in each
        /// of several regions, entered together).
        also: Vec<(Ref, usize)>,
        at: usize,
        /// What it runs as it fires, after what leaving runs (`when p -> B { … }`).
        actions: Vec<(ActionAst, usize)>,
    },
    /// A composite state's first sub-state, `initial NAME` inside its block: one of its own, a
    /// deeper one (`initial HEAD.TRACK`), or one in each of several regions (`initial
    /// PLAY.HEAD.TRACK, PLAY.BODY.KICK`); each where it is written, the first at the keyword.
    Initial(Initials),
    /// `outcome saved`: the state is final and announces this outcome of its machine.
    Outcome(String, usize),
    /// A sub-state: the state holding it is composite.
    State(StateAst),
}

/// An action as read: complete, or a statement still to be parsed.
pub enum ActionAst {
    Done(Action),
    Statement(String),
}

/// The states an `initial` names, each with where it is written.
pub type Initials = Vec<(Ref, usize)>;

/// An `initial`'s states as parsed (the first, and each further one after the position of
/// its comma), each with where it is written, the first at the keyword `at`.
pub fn initials(at: usize, (first, also): (Ref, Vec<(usize, Ref)>)) -> Initials {
    std::iter::once((first, at))
        .chain(also.into_iter().map(|(at, r)| (r, at)))
        .collect()
}
