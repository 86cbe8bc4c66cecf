//! Problems located by file and line (`FileDiagnostic`), as people read them: the line itself
//! with a caret under the place and the hint when the file is on disk and the column known,
//! else the one-line `file:line: severity: message`.

use crate::load::color;
use proclaim_syntax::{render, FileDiagnostic, Severity};

/// One problem, ending in a newline.
pub fn shown(d: &FileDiagnostic) -> String {
    shown_with_source(d).unwrap_or_else(|| format!("{d}\n"))
}

/// A machine file's problem as a `.dl` problem is shown: the line itself, a caret under the
/// place, the hint; `None` where the place or the file is not known.
fn shown_with_source(d: &FileDiagnostic) -> Option<String> {
    let column = d.column?;
    let text = std::fs::read_to_string(&d.file).ok()?;
    let line_start: usize = text
        .split_inclusive('\n')
        .take(d.line?.saturating_sub(1))
        .map(str::len)
        .sum();
    let line = text[line_start..].lines().next().unwrap_or("");
    let at = line_start
        + line
            .char_indices()
            .nth(column - 1)
            .map_or(line.len(), |(i, _)| i);
    // Under the word that starts there, or one character.
    let word = text[at..]
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(text.len() - at)
        .max(1);
    let span = proclaim_syntax::Span::new(at, (at + word).min(text.len()));
    let mut diagnostic = match d.severity {
        Severity::Error => proclaim_syntax::Diagnostic::error(span, d.message.clone()),
        Severity::Warning => proclaim_syntax::Diagnostic::warning(span, d.message.clone()),
    };
    if let Some(hint) = &d.hint {
        diagnostic = diagnostic.with_hint(hint.clone());
    }
    Some(render(&[diagnostic], &d.file, &text, color()))
}
