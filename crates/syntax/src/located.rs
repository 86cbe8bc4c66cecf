//! A problem located in a named file by line (and column, where the reader knows it): what every
//! reader and loader above the theory parser hands upward (machine files, manifests, scripts,
//! behaviours, and theories once their spans are turned into lines). Rendered to text or JSON
//! only in the binary.

use crate::diagnostic::{Diagnostic, Severity};
use crate::span::line_column;
use std::fmt;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileDiagnostic {
    pub severity: Severity,
    pub file: String,
    /// 1-based; `None` when the problem is the file as a whole (it cannot be read, it names no
    /// machine).
    pub line: Option<usize>,
    /// 1-based, in characters, where the reader knows it.
    pub column: Option<usize>,
    pub message: String,
    /// How to fix it, where there is something to say.
    pub hint: Option<String>,
}

impl FileDiagnostic {
    pub fn error(file: &str, line: usize, message: impl Into<String>) -> FileDiagnostic {
        FileDiagnostic {
            severity: Severity::Error,
            file: file.to_string(),
            line: Some(line),
            column: None,
            message: message.into(),
            hint: None,
        }
    }

    pub fn warning(file: &str, line: usize, message: impl Into<String>) -> FileDiagnostic {
        FileDiagnostic {
            severity: Severity::Warning,
            ..FileDiagnostic::error(file, line, message)
        }
    }

    /// An error about the file as a whole.
    pub fn in_file(file: &str, message: impl Into<String>) -> FileDiagnostic {
        FileDiagnostic {
            line: None,
            ..FileDiagnostic::error(file, 0, message)
        }
    }

    pub fn at_column(mut self, column: usize) -> FileDiagnostic {
        self.column = Some(column);
        self
    }

    pub fn with_hint(mut self, hint: impl Into<String>) -> FileDiagnostic {
        self.hint = Some(hint.into());
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl Diagnostic {
    /// This diagnostic of `source`, the text of `file`, placed by line and column.
    pub fn in_file(&self, file: &str, source: &str) -> FileDiagnostic {
        let (line, column) = line_column(source, self.span.start as usize);
        FileDiagnostic {
            severity: self.severity,
            file: file.to_string(),
            line: Some(line),
            column: Some(column),
            message: self.message.clone(),
            hint: self.hint.clone(),
        }
    }
}

/// `file:line: severity: message` (`file: severity: message` for the file as a whole; the hint
/// and the column are for renderers that show the line itself).
impl fmt::Display for FileDiagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        match self.line {
            Some(line) => write!(f, "{}:{line}: {severity}: {}", self.file, self.message),
            None => write!(f, "{}: {severity}: {}", self.file, self.message),
        }
    }
}
