//! Loading a theory, and what a loaded theory tells: its atoms, inputs and truth table.

use crate::errors;
use crate::session::Session;
use proclaim_cdl::{load_named, truth_table, Atom, Engine, Language, SearchLimits};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::Arc;

/// A checked theory, immutable: any number of sessions share it, and they keep it alive.
#[pyclass(module = "proclaim", frozen)]
pub(crate) struct Theory {
    pub(crate) engine: Arc<Engine>,
    /// The name it was loaded under (its file's path for `load_file`), which errors give.
    file: String,
}

fn language_of(name: &str) -> Language {
    if name.ends_with(".dfl") {
        Language::Dfl
    } else {
        Language::Dl
    }
}

fn loaded(py: Python<'_>, name: &str, source: &str) -> PyResult<Theory> {
    load_named(name, source, language_of(name))
        .map(|theory| Theory {
            engine: Arc::new(Engine::new(theory)),
            file: name.to_string(),
        })
        .map_err(|error| errors::load_error(py, name, source, &error))
}

/// Loads a theory from its text (`.dl`; DFL when `name` ends in `.dfl`); `name` is what errors
/// call it. Raises TheoryError, with the first error's line and column, when it does not load.
#[pyfunction]
#[pyo3(signature = (text, name = "theory"))]
pub(crate) fn load(py: Python<'_>, text: &str, name: &str) -> PyResult<Theory> {
    loaded(py, name, text)
}

/// Loads a theory file (`.dl`, or `.dfl`). Raises OSError when it cannot be read
/// (FileNotFoundError when it is not there), with `filename` set to the path, and TheoryError
/// when it does not load (text that is not UTF-8 included, placed at the bad byte).
#[pyfunction]
pub(crate) fn load_file(py: Python<'_>, path: PathBuf) -> PyResult<Theory> {
    let name = path.display().to_string();
    // Within the bound every source is read within; past it, an OSError saying the size.
    let bytes = proclaim_syntax::read_within(&path, proclaim_syntax::MAX_SOURCE_BYTES)
        .map_err(|unread| {
            let error = match unread {
                proclaim_syntax::Unread::Io(e) => e,
                proclaim_syntax::Unread::TooLarge(size) => std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    proclaim_syntax::too_large(size),
                ),
            };
            errors::os_error(py, error, &name)
        })?;
    match std::str::from_utf8(&bytes) {
        Ok(source) => loaded(py, &name, source),
        Err(bad) => {
            let valid = std::str::from_utf8(&bytes[..bad.valid_up_to()]).unwrap_or_default();
            let place = proclaim_syntax::line_column(valid, valid.len());
            Err(errors::theory_error(
                py,
                &name,
                Some(place),
                format!("{name} is not UTF-8 (byte {} is not)", bad.valid_up_to()),
            ))
        }
    }
}

#[pymethods]
impl Theory {
    /// A new session over this theory, every input unknown. `budget` is how many goals the
    /// search may expand inside one attack cycle before answering Undecided (10,000,000 unless
    /// given).
    #[pyo3(signature = (budget = None))]
    fn session(&self, budget: Option<u64>) -> PyResult<Session> {
        let mut limits = SearchLimits::default();
        if let Some(steps) = budget {
            if steps == 0 {
                return Err(PyValueError::new_err(
                    "the budget must be at least one step",
                ));
            }
            limits.steps = steps;
        }
        Ok(Session::new(
            proclaim_cdl::Session::with_limits(self.engine.clone(), limits),
            self.file.clone(),
        ))
    }

    /// The name the theory gives itself (`name{microwave}.`), if any.
    #[getter]
    fn name(&self) -> Option<String> {
        self.engine.theory().name().map(str::to_string)
    }

    /// Every atom the theory mentions, in the order it first mentions them.
    #[getter]
    fn atoms(&self) -> Vec<String> {
        let theory = self.engine.theory();
        (0..theory.atom_count())
            .map(|i| theory.atom_name(Atom(i as u32)).to_string())
            .collect()
    }

    /// The declared input atoms (`input{doorOpen}.`), the atoms `Session.set` accepts.
    #[getter]
    fn inputs(&self) -> Vec<String> {
        let theory = self.engine.theory();
        theory
            .input_atoms()
            .map(|a| theory.atom_name(a).to_string())
            .collect()
    }

    /// The truth table of the declared outputs over every combination of the declared inputs,
    /// as `proclaim table --format json` gives its rows: a list of
    /// `{"inputs": {atom: bool}, "outputs": {"beta cook": bool} or None}`, None when the inputs
    /// contradict the axioms. Raises ValueError past 2**20 rows.
    fn table<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let table = truth_table(self.engine.clone())
            .map_err(|error| PyValueError::new_err(error.to_string()))?;
        table
            .rows
            .iter()
            .map(|row| {
                let inputs = PyDict::new(py);
                for (name, value) in table.inputs.iter().zip(&row.inputs) {
                    inputs.set_item(name, value)?;
                }
                let dict = PyDict::new(py);
                dict.set_item("inputs", inputs)?;
                match &row.outputs {
                    Some(values) => {
                        let outputs = PyDict::new(py);
                        for (column, value) in table.columns.iter().zip(values) {
                            outputs.set_item(&column.heading, value)?;
                        }
                        dict.set_item("outputs", outputs)?;
                    }
                    None => dict.set_item("outputs", py.None())?,
                }
                Ok(dict)
            })
            .collect()
    }

    fn __repr__(&self) -> String {
        let theory = self.engine.theory();
        format!(
            "<proclaim.Theory {} with {} rules>",
            theory.name().unwrap_or("(unnamed)"),
            theory.written_rule_count()
        )
    }
}
