//! The module's exceptions, and the reasoner's errors turned into them with their details as
//! attributes (a program reads `error.line`, not the message).

use proclaim_cdl::{InputConflict as Conflict, LoadError, Undecided as Stalled};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyUserWarning};
use pyo3::prelude::*;

create_exception!(
    proclaim,
    Error,
    PyException,
    "Every error the reasoner raises derives from this one."
);
create_exception!(
    proclaim,
    TheoryError,
    Error,
    "A theory did not load: `file`, `line` and `column` (1-based) of its first error, and \
     `message`, every error rendered with its line and a caret."
);
create_exception!(
    proclaim,
    Undecided,
    Error,
    "The search ran out of its step budget inside an attack cycle before deciding: neither \
     proved nor refuted. `goal` is the goal asked (`beta t0`), `stalled_at` the undecided goal \
     of the cycle it depends on."
);
create_exception!(
    proclaim,
    InputConflict,
    Error,
    "Setting an input would contradict the theory's axioms; the session is left as it was. \
     `input` is the refused literal, `clause` the axiom it contradicts."
);

/// The exception for a theory that did not load; `place` is where its first error is (line and
/// column, 1-based), `None` when it has none.
pub(crate) fn theory_error(
    py: Python<'_>,
    file: &str,
    place: Option<(usize, usize)>,
    message: String,
) -> PyErr {
    let error = TheoryError::new_err(message.clone());
    let (line, column) = place.unwrap_or((0, 0));
    let value = error.value(py);
    let attributes = [
        value.setattr("file", file),
        value.setattr("line", line),
        value.setattr("column", column),
        value.setattr("message", message),
    ];
    match attributes.into_iter().find_map(Result::err) {
        Some(failed) => failed,
        None => error,
    }
}

/// The OSError subclass Python raises for `error` (FileNotFoundError, PermissionError, …), made
/// as `open()` makes it: `errno`, `strerror` and `filename` set.
pub(crate) fn os_error(py: Python<'_>, error: std::io::Error, filename: &str) -> PyErr {
    let errno = error.raw_os_error().unwrap_or(0);
    // The message without the " (os error N)" Rust adds.
    let strerror = error.to_string();
    let strerror = strerror
        .split(" (os error")
        .next()
        .unwrap_or_default()
        .to_string();
    let kind = PyErr::from(error).get_type(py);
    match kind.call1((errno, strerror, filename)) {
        Ok(value) => PyErr::from_value(value),
        Err(failed) => failed,
    }
}

/// [`theory_error`] for the reasoner's [`LoadError`], placed at its first error in `source`.
pub(crate) fn load_error(py: Python<'_>, file: &str, source: &str, error: &LoadError) -> PyErr {
    let place = error
        .diagnostics()
        .first()
        .map(|d| proclaim_syntax::line_column(source, d.span.start as usize));
    theory_error(py, file, place, error.to_string())
}

pub(crate) fn undecided(py: Python<'_>, stalled: Stalled) -> PyErr {
    let error = Undecided::new_err(stalled.to_string());
    let value = error.value(py);
    match value
        .setattr("goal", stalled.goal)
        .and_then(|()| value.setattr("stalled_at", stalled.stalled_at))
    {
        Ok(()) => error,
        Err(failed) => failed,
    }
}

pub(crate) fn input_conflict(py: Python<'_>, conflict: Conflict) -> PyErr {
    let error = InputConflict::new_err(conflict.to_string());
    let value = error.value(py);
    match value
        .setattr("input", conflict.input)
        .and_then(|()| value.setattr("clause", conflict.clause))
    {
        Ok(()) => error,
        Err(failed) => failed,
    }
}

create_exception!(
    proclaim,
    BehaviourError,
    Error,
    "A behaviour did not load or start: `problems` lists every problem of every file as \
     `(file, line, column, message)` (line and column 1-based, 0 when the problem is the file as \
     a whole); the message renders them all."
);
create_exception!(
    proclaim,
    BehaviourWarning,
    PyUserWarning,
    "Something a behaviour was given does not match its machines, and the behaviour runs anyway: \
     a host function a machine calls that no callable in `hosts` answers (the call is skipped). \
     `warnings.simplefilter(\"error\", proclaim.BehaviourWarning)` makes it an error."
);
create_exception!(
    proclaim,
    CallbackError,
    Error,
    "A Python callable given to a behaviour (a host function, an expert) raised while the \
     behaviour ran. `callable` says which; `__cause__` is the exception it raised. An expert \
     that raised answered its label false; the behaviour goes on and may be stepped again."
);

/// The exception for a behaviour that did not start, with each problem as data.
pub(crate) fn behaviour_error(
    py: Python<'_>,
    folder: &std::path::Path,
    error: proclaim_behaviour::BehaviourError,
) -> PyErr {
    let problems: Vec<(String, usize, usize, String)> = match &error {
        proclaim_behaviour::BehaviourError::Files(diagnostics) => diagnostics
            .iter()
            .map(|d| {
                (
                    d.file.clone(),
                    d.line.unwrap_or(0),
                    d.column.unwrap_or(0),
                    d.message.clone(),
                )
            })
            .collect(),
        other => vec![(folder.display().to_string(), 0, 0, other.to_string())],
    };
    let raised = BehaviourError::new_err(format!(
        "the behaviour in {} did not start:\n{error}",
        folder.display()
    ));
    match raised.value(py).setattr("problems", problems) {
        Ok(()) => raised,
        Err(failed) => failed,
    }
}

/// The exception for what `callable` raised (`error`), mentioning how many others raised too.
pub(crate) fn callback_error(py: Python<'_>, callable: &str, error: PyErr, others: usize) -> PyErr {
    let also = match others {
        0 => String::new(),
        1 => " (and one more callable raised after it)".to_string(),
        n => format!(" (and {n} more callables raised after it)"),
    };
    let raised = CallbackError::new_err(format!("{callable} raised {error}{also}"));
    raised.set_cause(py, Some(error));
    match raised.value(py).setattr("callable", callable) {
        Ok(()) => raised,
        Err(failed) => failed,
    }
}
