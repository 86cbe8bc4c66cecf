//! Reading a theory named on the command line (a path, or the name of an embedded theory) and
//! turning its diagnostics into text for people or JSON for programs.

use crate::embedded;
use crate::failure::Failure;
use proclaim_cdl::{check_source, Diagnostic, Language, Theory};
use proclaim_syntax::{line_column, render, Severity};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// A theory's text and where it came from.
pub struct Source {
    pub name: String,
    pub text: String,
    pub language: Language,
}

pub fn read(theory: &str) -> Result<Source, Failure> {
    let path = Path::new(theory);
    if !path.exists() {
        if let Some((file, text)) = embedded::find(theory) {
            return Ok(Source {
                name: format!("<embedded>/{file}"),
                text: text.to_string(),
                language: Language::Dl,
            });
        }
    }
    let bytes = std::fs::read(path).map_err(|error| Failure::Read {
        path: PathBuf::from(theory),
        error: if error.kind() == std::io::ErrorKind::NotFound {
            std::io::Error::new(
                error.kind(),
                format!(
                    "no such file (and no embedded theory of that name: {})",
                    embedded::names()
                ),
            )
        } else {
            error
        },
    })?;
    let text = String::from_utf8(bytes).map_err(|e| Failure::Read {
        path: PathBuf::from(theory),
        error: std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        ),
    })?;
    Ok(Source {
        name: theory.to_string(),
        language: Language::from_path(path),
        text,
    })
}

/// The checked theory and its warnings, or every error rendered.
pub fn checked(source: &Source) -> Result<(Theory, Vec<Diagnostic>), Failure> {
    let result = check_source(&source.text, source.language);
    let (errors, warnings): (Vec<_>, Vec<_>) = result
        .diagnostics
        .into_iter()
        .partition(Diagnostic::is_error);
    match result.theory {
        Some(theory) => Ok((theory, warnings)),
        None => Err(Failure::Invalid {
            what: "the theory",
            rendered: render(&errors, &source.name, &source.text, color()),
            errors: errors.len(),
        }),
    }
}

/// Loads a theory for a command that needs one, printing its warnings to stderr.
pub fn theory(name: &str) -> Result<(Source, Theory), Failure> {
    let source = read(name)?;
    let (theory, warnings) = checked(&source)?;
    if !warnings.is_empty() {
        eprint!("{}", render(&warnings, &source.name, &source.text, color()));
    }
    Ok((source, theory))
}

/// A file in one of the small line formats (scripts, game scripts, mappings), parsed; every bad
/// line is reported as `file:line: error: …`, all at once.
pub fn line_file<T>(
    path: &Path,
    what: &'static str,
    parse: impl FnOnce(&str) -> Result<T, proclaim_experts::LineErrors>,
) -> Result<T, Failure> {
    let text = std::fs::read_to_string(path).map_err(|error| Failure::Read {
        path: path.to_path_buf(),
        error,
    })?;
    parse(&text).map_err(|errors| Failure::Invalid {
        what,
        errors: errors.len(),
        rendered: errors
            .iter()
            .map(|e| format!("{}:{}: error: {}\n", path.display(), e.line, e.message))
            .collect(),
    })
}

/// Whether stderr wants colour.
pub fn color() -> bool {
    std::env::var_os("NO_COLOR").is_none() && std::io::stderr().is_terminal()
}

/// A diagnostic as a JSON object: file, line, column, severity, message, label, hint.
pub fn diagnostic_json(d: &Diagnostic, file: &str, text: &str) -> serde_json::Value {
    let (line, column) = line_column(text, d.span.start as usize);
    serde_json::json!({
        "file": file,
        "line": line,
        "column": column,
        "severity": if d.severity == Severity::Error { "error" } else { "warning" },
        "message": d.message,
        "label": d.label,
        "hint": d.hint,
    })
}
