//! A problem located in a named file by line (and column, where the reader knows it): what every
//! reader and loader above the theory parser hands upward (machine files, manifests, scripts,
//! behaviours, and theories once their spans are turned into lines), carrying the text of its
//! line so that it renders with a caret without reading the file again.

use crate::diagnostic::{render_line, Diagnostic, Severity};
use crate::span::{line_column, Span};
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
    /// The text of the line, as the reader read it, where the column is known: what a renderer
    /// quotes with a caret under the place, without reading the file again (it may have changed
    /// or be gone by then).
    pub source_line: Option<Box<str>>,
    pub message: String,
    /// How to fix it, where there is something to say.
    pub hint: Option<Box<str>>,
}

impl FileDiagnostic {
    pub fn error(file: &str, line: usize, message: impl Into<String>) -> FileDiagnostic {
        FileDiagnostic {
            severity: Severity::Error,
            file: file.to_string(),
            line: Some(line),
            column: None,
            source_line: None,
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

    /// Placed at `column` of its line, `source`'s line `self.line`.
    pub fn at_column(self, column: usize, source: &str) -> FileDiagnostic {
        let text = self
            .line
            .and_then(|line| source.lines().nth(line.saturating_sub(1)));
        self.at_column_of(column, text.unwrap_or_default())
    }

    /// Placed at `column` of its line, whose text is `line` (no scan of the whole source: a
    /// file of many problems reports them in time linear in its size).
    pub fn at_column_of(mut self, column: usize, line: &str) -> FileDiagnostic {
        self.column = Some(column);
        self.source_line = self.line.map(|_| Box::from(line));
        self
    }

    pub fn with_hint(mut self, hint: impl Into<String>) -> FileDiagnostic {
        self.hint = Some(hint.into().into_boxed_str());
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// As people read it, ending in a newline: the line itself with a caret under the word at
    /// the place and the hint, as a theory's problems are shown; the one-line form where the
    /// place or the line's text is not known.
    pub fn render(&self, color: bool) -> String {
        self.quoted(color).unwrap_or_else(|| format!("{self}\n"))
    }

    fn quoted(&self, color: bool) -> Option<String> {
        let (line, column, text) = (self.line?, self.column?, self.source_line.as_deref()?);
        if text.len() > crate::diagnostic::LONGEST_QUOTED {
            return None;
        }
        let at = text
            .char_indices()
            .nth(column - 1)
            .map_or(text.len(), |(i, _)| i);
        let word = text[at..]
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(text.len() - at)
            .max(1);
        let span = Span::new(at, (at + word).min(text.len()));
        let mut diagnostic = match self.severity {
            Severity::Error => Diagnostic::error(span, self.message.clone()),
            Severity::Warning => Diagnostic::warning(span, self.message.clone()),
        };
        if let Some(hint) = &self.hint {
            diagnostic = diagnostic.with_hint(hint.to_string());
        }
        Some(render_line(&diagnostic, &self.file, line, text, color))
    }
}

impl Diagnostic {
    /// This diagnostic of `source`, the text of `file`, placed by line and column.
    pub fn in_file(&self, file: &str, source: &str) -> FileDiagnostic {
        let (line, column) = line_column(source, self.span.start as usize);
        let located = match self.severity {
            Severity::Error => FileDiagnostic::error(file, line, self.message.clone()),
            Severity::Warning => FileDiagnostic::warning(file, line, self.message.clone()),
        };
        FileDiagnostic {
            hint: self.hint.as_deref().map(Box::from),
            ..located.at_column(column, source)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_its_line_with_a_caret_from_what_it_carries() {
        let text = "machine M\n\nstate Idle\n  on ready -> Nowhere\n";
        let d = FileDiagnostic::error("gone/m.machine", 4, "unknown state `Nowhere`")
            .at_column(15, text)
            .with_hint("declare it");
        // The file does not exist: the line comes from the diagnostic.
        let shown = d.render(false);
        assert!(shown.contains("gone/m.machine:4:15"), "{shown}");
        assert!(shown.contains("4 │   on ready -> Nowhere"), "{shown}");
        assert!(shown.contains("^^^^^^^"), "{shown}");
        assert!(shown.contains("declare it"), "{shown}");
    }

    #[test]
    fn renders_one_line_where_the_place_is_not_known() {
        let d = FileDiagnostic::in_file("m.machine", "cannot read it");
        assert_eq!(d.render(false), "m.machine: error: cannot read it\n");
        let d = FileDiagnostic::warning("m.machine", 3, "unused");
        assert_eq!(d.render(false), "m.machine:3: warning: unused\n");
    }
}
