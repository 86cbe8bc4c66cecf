//! Behaviour machines (`docs/spec/behaviour.md` §3–4): the model the interpreter will run,
//! the label expressions transitions wait on, and importers for the formats robot teams already
//! have: the original T/A tables and Qfsm `.fsm` XML, and the native format ([`parse_machine`],
//! [`to_native`]). Pure: texts in, machines and diagnostics
//! out. Importing never fails: a file yields what could be read and a diagnostic, with its line,
//! for everything that could not.
//!

mod activity;
pub mod code;
pub mod control;
pub mod dot;
mod dot_chart;
mod dot_text;
mod format;
mod interface;
mod label;
mod link;
mod lint;
mod model;
pub mod names;
mod native;
mod qfsm;
mod scxml;
mod sections;
mod start;
mod ta;
mod team;

pub use activity::{
    parse_description, parse_gufsm_activities, parse_ta_items, Description, BUILTIN_FUNCTIONS,
};
pub use code::{BinOp, Expr, ForLoop, Statement, StatementKind, UnOp, VarType};
pub use control::{machine_of_running_type, running_type, Command};
pub use dot::{drawn_nodes, to_dot};
pub use format::{machine_format, MachineFormat};
pub use interface::{fits, global_of, DeclaredOutcome, Interface, Param};
pub use label::{parse_label, Label, LabelError, TIME_TESTS};
pub use link::{link, Launch, LinkProblem};
pub use lint::{lint, reachable};
pub use model::{
    Action, Argument, Composite, Machine, State, StateId, Transition, UnreadTransition,
};
pub use native::{parse_machine, to_native, to_scxml, EXTENSION, KEYWORDS};
pub use start::{start_of, Start};

/// Editing native machine files in place: each edit a text patch at the reader's spans, so
/// what it does not touch stays byte for byte as written.
pub mod edit {
    pub use crate::native::{
        check_native, edit_native, editable, view_native, ActivityView, Edit, EditError, Edited,
        Section, StateView, TransitionView,
    };
}
pub use proclaim_syntax::{FileDiagnostic, Severity};
pub use qfsm::import_qfsm;
pub use scxml::{import_scxml, ImportedScxml};
pub use ta::{import_ta, partner_of};
pub use team::{team_words, Aggregate, TeamWord};

/// What an importer read from one file, with everything it could not read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Imported {
    pub machines: Vec<Machine>,
    pub diagnostics: Vec<FileDiagnostic>,
}

impl Imported {
    pub fn has_errors(&self) -> bool {
        self.diagnostics
            .iter()
            .any(|d| d.severity == Severity::Error)
    }
}
