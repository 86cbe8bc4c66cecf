//! Problems found in a source text, each with a place, a reason and a hint, rendered for people.

use crate::span::{line_column, Span};
use codespan_reporting::diagnostic::{Diagnostic as Rendered, Label};
use codespan_reporting::files::{Error as FilesError, Files, SimpleFile};
use codespan_reporting::term;
use std::ops::Range;

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
    let mut out = String::new();
    for diagnostic in diagnostics {
        let short = || diagnostic.short(file_name, source);
        if line_length_at(source, diagnostic.span.start as usize) > LONGEST_QUOTED {
            out.push_str(&short());
            out.push('\n');
            continue;
        }
        out.push_str(&emit(
            &file,
            to_codespan(diagnostic, source.len()),
            color,
            short,
        ));
    }
    out
}

/// Renders one diagnostic on line `line` (1-based) of a file, given that line's text alone
/// (its span within the line): a file of many problems needs no copy of itself for each.
pub fn render_line(
    diagnostic: &Diagnostic,
    file_name: &str,
    line: usize,
    text: &str,
    color: bool,
) -> String {
    let file = OneLine {
        name: file_name,
        text,
        index: line.saturating_sub(1),
    };
    let short = || {
        let column = text
            .get(..(diagnostic.span.start as usize).min(text.len()))
            .map_or(1, |before| before.chars().count() + 1);
        format!("{file_name}:{line}:{column}: {}", diagnostic.message)
    };
    emit(&file, to_codespan(diagnostic, text.len()), color, short)
}

/// One diagnostic through codespan, in colour when asked; `short` when it cannot render.
fn emit<'f, F: Files<'f, FileId = ()>>(
    files: &'f F,
    rendered: Rendered<()>,
    color: bool,
    short: impl Fn() -> String,
) -> String {
    let config = term::Config::default();
    if color {
        let mut buffer = term::termcolor::Buffer::ansi();
        if term::emit_to_write_style(&mut buffer, &config, files, &rendered).is_ok() {
            return String::from_utf8_lossy(buffer.as_slice()).into_owned();
        }
    }
    term::emit_into_string(&config, files, &rendered).unwrap_or_else(|_| short() + "\n")
}

/// One line of a file, numbered as in the file.
struct OneLine<'s> {
    name: &'s str,
    text: &'s str,
    /// 0-based.
    index: usize,
}

impl<'a> Files<'a> for OneLine<'a> {
    type FileId = ();
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, (): ()) -> Result<&'a str, FilesError> {
        Ok(self.name)
    }

    fn source(&'a self, (): ()) -> Result<&'a str, FilesError> {
        Ok(self.text)
    }

    fn line_index(&'a self, (): (), _byte_index: usize) -> Result<usize, FilesError> {
        Ok(self.index)
    }

    fn line_range(&'a self, (): (), line_index: usize) -> Result<Range<usize>, FilesError> {
        let end = self.text.len();
        Ok(if line_index == self.index {
            0..end
        } else {
            end..end
        })
    }
}

/// The longest source line a diagnostic quotes: past it, the diagnostic is its one line of
/// file, line, column and message, so a few hundred problems on one line of megabytes print
/// kilobytes, not gigabytes.
pub const LONGEST_QUOTED: usize = 1_000;

/// The length in bytes of the line holding byte `at` of `source`.
fn line_length_at(source: &str, at: usize) -> usize {
    let at = at.min(source.len());
    let bytes = source.as_bytes();
    let start = bytes[..at]
        .iter()
        .rposition(|b| *b == b'\n')
        .map_or(0, |i| i + 1);
    let end = bytes[at..]
        .iter()
        .position(|b| *b == b'\n')
        .map_or(bytes.len(), |i| at + i);
    end - start
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_too_long_to_quote_is_reported_in_one_line_each() {
        let long = format!("a.\n{}\n", "[[x]]".repeat(20_000));
        let problems: Vec<Diagnostic> = (0..200)
            .map(|i| Diagnostic::error(Span::new(3 + 5 * i, 4 + 5 * i), "unexpected `[`"))
            .collect();
        let out = render(&problems, "t.dl", &long, false);
        assert_eq!(out.lines().count(), 200, "{}", &out[..200]);
        assert!(
            out.starts_with("t.dl:2:1: error: unexpected `[`\nt.dl:2:6: error"),
            "{}",
            &out[..200]
        );
        let one = render_line(&problems[0], "t.dl", 12, "[[x]]", false);
        assert!(
            one.contains("t.dl:12:4") && one.contains("12 │ [[x]]"),
            "{one}"
        );
        // A line of ordinary length is quoted as ever.
        let quoted = render(&problems[..1], "t.dl", "a.\n[[x]]\n", false);
        assert!(quoted.contains("2 │ [[x]]"), "{quoted}");
    }
}
