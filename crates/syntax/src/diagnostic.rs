//! Problems found in a source text, each with a place, a reason and a hint, rendered for people.

use crate::span::{line_column, Span};
use codespan_reporting::diagnostic::{Diagnostic as Rendered, Label};
use codespan_reporting::files::SimpleFile;
use codespan_reporting::term;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

/// One problem in one source text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub severity: Severity,
    /// What went wrong, in one sentence.
    pub message: String,
    /// Where: the caret goes under this span.
    pub span: Span,
    /// Text shown beside the caret.
    pub label: String,
    /// How to fix it, when we can tell.
    pub hint: Option<String>,
    /// Other places that take part (the other half of a duplicate, the rules of a cycle).
    pub related: Vec<(Span, String)>,
}

impl Diagnostic {
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            message: message.into(),
            span,
            label: String::new(),
            hint: None,
            related: Vec::new(),
        }
    }

    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(span, message)
        }
    }

    pub fn with_label(mut self, label: impl Into<String>) -> Diagnostic {
        self.label = label.into();
        self
    }

    pub fn with_hint(mut self, hint: impl Into<String>) -> Diagnostic {
        self.hint = Some(hint.into());
        self
    }

    pub fn with_related(mut self, span: Span, label: impl Into<String>) -> Diagnostic {
        self.related.push((span, label.into()));
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// `file:line:column: error: message`, the one-line form for programs and editors.
    pub fn short(&self, file_name: &str, source: &str) -> String {
        let (line, column) = line_column(source, self.span.start as usize);
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        format!("{file_name}:{line}:{column}: {severity}: {}", self.message)
    }
}

/// The most diagnostics one file keeps; past it, one final diagnostic says how many were dropped.
/// A 100 MB file of garbage must not need gigabytes of error messages.
pub const MAX_DIAGNOSTICS: usize = 200;

/// Collects diagnostics up to [`MAX_DIAGNOSTICS`], counting the rest.
#[derive(Default, Debug)]
pub struct Sink {
    kept: Vec<Diagnostic>,
    dropped: usize,
}

impl Sink {
    pub fn push(&mut self, diagnostic: Diagnostic) {
        if self.kept.len() < MAX_DIAGNOSTICS {
            self.kept.push(diagnostic);
        } else {
            self.dropped += 1;
        }
    }

    pub fn has_errors(&self) -> bool {
        self.kept.iter().any(Diagnostic::is_error)
    }

    pub fn finish(mut self, end: usize) -> Vec<Diagnostic> {
        if self.dropped > 0 {
            self.kept.push(Diagnostic::error(
                Span::new(end, end),
                format!(
                    "{} more problems not shown (only the first {MAX_DIAGNOSTICS} are reported)",
                    self.dropped
                ),
            ));
        }
        self.kept
    }
}

/// Renders diagnostics as people read them: `file:line:column`, the source line, a caret under
/// the problem, and the hint.
pub fn render(diagnostics: &[Diagnostic], file_name: &str, source: &str, color: bool) -> String {
    let file = SimpleFile::new(file_name, source);
    let config = term::Config::default();
    let mut out = String::new();
    for diagnostic in diagnostics {
        let rendered = to_codespan(diagnostic, source.len());
        if color {
            let mut buffer = term::termcolor::Buffer::ansi();
            if term::emit_to_write_style(&mut buffer, &config, &file, &rendered).is_ok() {
                out.push_str(&String::from_utf8_lossy(buffer.as_slice()));
                continue;
            }
        }
        match term::emit_into_string(&config, &file, &rendered) {
            Ok(text) => out.push_str(&text),
            Err(_) => {
                out.push_str(&diagnostic.short(file_name, source));
                out.push('\n');
            }
        }
    }
    out
}

fn to_codespan(diagnostic: &Diagnostic, source_len: usize) -> Rendered<()> {
    let clamp = |span: Span| {
        let start = (span.start as usize).min(source_len);
        start..(span.end as usize).clamp(start, source_len)
    };
    let rendered = match diagnostic.severity {
        Severity::Error => Rendered::error(),
        Severity::Warning => Rendered::warning(),
    };
    let mut labels =
        vec![Label::primary((), clamp(diagnostic.span)).with_message(diagnostic.label.clone())];
    labels.extend(
        diagnostic
            .related
            .iter()
            .map(|(span, text)| Label::secondary((), clamp(*span)).with_message(text.clone())),
    );
    rendered
        .with_message(diagnostic.message.clone())
        .with_labels(labels)
        .with_notes(
            diagnostic
                .hint
                .iter()
                .map(|h| format!("hint: {h}"))
                .collect(),
        )
}
