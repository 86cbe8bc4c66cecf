//! The languages theories are written in: `.dl` (clausal defeasible logic with Rock's DPL
//! input/output statements) and SPINdle's `.dfl`, parsed to one syntax tree with diagnostics.
//!
//! Also the small line formats every crate reads: durations and the impersonator's script
//! (`script.rs`), which a compiled behaviour reads too, and the bounded reader of every source
//! file (`proclaim-runtime`'s `source.rs`), re-exported.
//!
//! Parsing never fails: it returns the statements that parsed and a diagnostic for each problem.
//! This crate knows nothing of meaning (labels, priorities, consistency): see `proclaim-cdl`.

pub mod ast;
mod dfl;
pub mod diagnostic;
mod fast_path;
pub mod lexer;
mod located;
mod nearest;
mod parse;
pub mod span;

lalrpop_util::lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused)]
    grammar
);

pub use ast::{Algorithm, Arrow, Item, OutputPart, Query, RuleItem, SourceLiteral};
pub use dfl::{parse_dfl, parse_dfl_each};
pub use diagnostic::{render, Diagnostic, Severity};
pub use located::FileDiagnostic;
pub use nearest::nearest;
pub use parse::{parse_dl, parse_dl_each, parse_query, NameTok, ParsedTheory, UserError};
pub use proclaim_runtime::{code_lines, parse_duration, LineError, LineErrors, LONGEST_DURATION};
pub use proclaim_runtime::{parse_script, Script, ScriptStep, ScriptValue, When};
pub use proclaim_runtime::{read_source, read_within, too_large, Unread, MAX_SOURCE_BYTES};
pub use span::{line_column, Span};

/// The two theory languages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Language {
    /// `.dl`, this project's language.
    Dl,
    /// `.dfl`, SPINdle's defeasible logic format.
    Dfl,
}

impl Language {
    /// `.dfl` files are SPINdle's; everything else is read as `.dl`.
    pub fn from_path(path: &std::path::Path) -> Language {
        match path.extension().and_then(|e| e.to_str()) {
            Some(ext) if ext.eq_ignore_ascii_case("dfl") => Language::Dfl,
            _ => Language::Dl,
        }
    }
}

/// Parses a text in the given language, handing each statement to `on_item` as soon as it is
/// parsed; the result holds the diagnostics and no items.
pub fn parse_each(source: &str, language: Language, on_item: impl FnMut(Item)) -> ParsedTheory {
    match language {
        Language::Dl => parse_dl_each(source, on_item),
        Language::Dfl => parse_dfl_each(source, on_item),
    }
}

/// Parses a text in the given language.
pub fn parse(source: &str, language: Language) -> ParsedTheory {
    match language {
        Language::Dl => parse_dl(source),
        Language::Dfl => parse_dfl(source),
    }
}
