//! A problem in an imported file: which file, which line, what and why.

use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileDiagnostic {
    pub severity: Severity,
    pub file: String,
    /// 1-based.
    pub line: usize,
    /// 1-based, in characters, where the reader knows it (the native format).
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
            line,
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
}

impl FileDiagnostic {
    pub fn at_column(mut self, column: usize) -> FileDiagnostic {
        self.column = Some(column);
        self
    }

    pub fn with_hint(mut self, hint: impl Into<String>) -> FileDiagnostic {
        self.hint = Some(hint.into());
        self
    }
}

/// `file:line: severity: message` (the hint and the column are for renderers that show the
/// line itself).
impl fmt::Display for FileDiagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(
            f,
            "{}:{}: {severity}: {}",
            self.file, self.line, self.message
        )
    }
}
