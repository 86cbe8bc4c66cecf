//! Clausal defeasible logic (`docs/spec/cdl.md`): a syntax tree is checked into a
//! [`Theory`], compiled into an [`Engine`], and asked through a [`Session`] that holds input
//! values and re-proves only what an input change reaches. No I/O happens here.
//!
//! ```
//! use proclaim_cdl::{load, Algorithm, Language, Session};
//! let theory = load("bird. R2: bird => fly. R3: penguin => ~fly. R3 > R2.", Language::Dl).unwrap();
//! let fly = theory.lit("fly").unwrap();
//! let mut session = Session::new(proclaim_cdl::Engine::new(theory));
//! assert!(session.prove(Algorithm::Beta, fly));
//! ```

mod atoms;
mod check;
mod closure;
mod component;
mod cycle;
mod cycle_warnings;
mod dominators;
mod engine;
mod explain;
mod goal;
mod goal_number;
mod layers;
mod literal;
mod matching;
mod query;
mod reference;
mod relevance;
mod ring;
mod scc;
mod session;
mod slots;
mod table;
mod theory;

pub use check::{check, check_source, Checked};
pub use closure::MAX_CLOSURE;
pub use component::SearchLimits;
pub use cycle_warnings::attack_cycle_warnings;
pub use engine::Engine;
pub use explain::{About, Explanation};
pub use literal::{Atom, Lit, RuleId};
pub use proclaim_syntax::{render, Algorithm, Diagnostic, Language, Severity};
pub use query::Formula;
pub use reference::ReferenceProver;
pub use session::{InputConflict, ProofOutcome, Searched, Session, Undecided};
pub use table::{truth_table, Column, Row, Table, TableError, MAX_ROWS};
pub use theory::{Clause, InputGroup, Origin, Output, RowFilter, RuleKind, RuleRef, Theory};

/// Parses and checks a theory text: the theory, or every error (warnings are dropped here; use
/// [`check`] to see them). The error renders each problem with its line, a caret and a hint.
pub fn load(source: &str, language: Language) -> Result<Theory, LoadError> {
    load_named("theory", source, language)
}

/// [`load`], naming the text (a file name) in the errors.
pub fn load_named(name: &str, source: &str, language: Language) -> Result<Theory, LoadError> {
    let checked = check_source(source, language);
    match checked.theory {
        Some(theory) => Ok(theory),
        None => Err(LoadError {
            name: name.to_string(),
            rendered: render(&checked.diagnostics, name, source, false),
            diagnostics: checked
                .diagnostics
                .into_iter()
                .filter(Diagnostic::is_error)
                .collect(),
        }),
    }
}

/// Why a theory did not load: every error, with where it is.
#[derive(Clone, Debug)]
pub struct LoadError {
    name: String,
    rendered: String,
    diagnostics: Vec<Diagnostic>,
}

impl LoadError {
    /// The errors as data (spans into the text, messages, hints).
    pub fn diagnostics(&self) -> &[Diagnostic] {
        &self.diagnostics
    }
}

/// Every problem as `proclaim check` shows it: file, line, the line itself with a caret, hint.
impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} does not load ({} error{}):\n{}",
            self.name,
            self.diagnostics.len(),
            if self.diagnostics.len() == 1 { "" } else { "s" },
            self.rendered.trim_end()
        )
    }
}

impl std::error::Error for LoadError {}
