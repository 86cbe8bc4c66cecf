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
    pub message: String,
}

impl FileDiagnostic {
    pub fn error(file: &str, line: usize, message: impl Into<String>) -> FileDiagnostic {
        FileDiagnostic {
            severity: Severity::Error,
            file: file.to_string(),
            line,
            message: message.into(),
        }
    }

    pub fn warning(file: &str, line: usize, message: impl Into<String>) -> FileDiagnostic {
        FileDiagnostic {
            severity: Severity::Warning,
            ..FileDiagnostic::error(file, line, message)
        }
    }
}

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
