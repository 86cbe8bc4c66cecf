//! What the small line-based formats (mapping files, impersonator scripts, game scripts) share:
//! `#` comments, blank lines skipped, and errors that name their line.

use std::fmt;

/// A line of a line-based file that could not be read, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineError {
    pub line: usize,
    pub message: String,
}

impl fmt::Display for LineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for LineError {}

/// The non-blank lines with their comments removed, numbered from 1.
pub(crate) fn code_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().filter_map(|(i, raw)| {
        let code = raw.split('#').next().unwrap_or("").trim();
        (!code.is_empty()).then_some((i + 1, code))
    })
}
