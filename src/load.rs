//! Reading a theory named on the command line (a path, or the name of an embedded theory) and
//! turning its diagnostics into text for people or JSON for programs.

use crate::embedded;
use crate::failure::Failure;
use proclaim_cdl::{check_source, Diagnostic, Language, Theory};
use proclaim_syntax::{line_column, render, FileDiagnostic, Severity};
use proclaim_syntax::{read_within, too_large, Unread, MAX_SOURCE_BYTES};
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
    let bytes = read_within(path, MAX_SOURCE_BYTES).map_err(|unread| Failure::Read {
        path: PathBuf::from(theory),
        error: match unread {
            Unread::Io(error) if error.kind() == std::io::ErrorKind::NotFound => {
                std::io::Error::new(
                    error.kind(),
                    format!(
                        "no such file (and no embedded theory of that name: {})",
                        embedded::names()
                    ),
                )
            }
            Unread::Io(error) => error,
            Unread::TooLarge(size) => {
                std::io::Error::new(std::io::ErrorKind::InvalidData, too_large(size))
            }
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
    let text = proclaim_syntax::read_source(path).map_err(|error| Failure::Read {
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

/// One problem as `check --json` reports it; every problem has this one shape,
/// whichever reader found it (the guide's tour of the commands).
#[derive(serde::Serialize)]
pub struct ProblemJson<'a> {
    pub file: &'a str,
    /// 1-based; `null` for a problem with the file as a whole.
    pub line: Option<usize>,
    /// 1-based, in characters; `null` where the reader does not know it.
    pub column: Option<usize>,
    /// `"error"` or `"warning"`.
    pub severity: &'static str,
    pub message: &'a str,
    /// What the place is, where the reader says (a theory's problems do).
    pub label: Option<&'a str>,
    pub hint: Option<&'a str>,
}

impl<'a> ProblemJson<'a> {
    /// A theory's problem, `text` being the theory `file`.
    pub fn of_theory(d: &'a Diagnostic, file: &'a str, text: &str) -> ProblemJson<'a> {
        let (line, column) = line_column(text, d.span.start as usize);
        ProblemJson {
            file,
            line: Some(line),
            column: Some(column),
            severity: severity(d.severity),
            message: &d.message,
            label: (!d.label.is_empty()).then_some(d.label.as_str()),
            hint: d.hint.as_deref(),
        }
    }

    /// A problem of a machine file, manifest, script or behaviour.
    pub fn of_file(d: &'a FileDiagnostic) -> ProblemJson<'a> {
        ProblemJson {
            file: &d.file,
            line: d.line,
            column: d.column,
            severity: severity(d.severity),
            message: &d.message,
            label: None,
            hint: d.hint.as_deref(),
        }
    }

    pub fn value(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or_default()
    }
}

fn severity(severity: Severity) -> &'static str {
    match severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
    }
}
