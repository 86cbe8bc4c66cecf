//! A session from Python: set inputs, prove and explain literals.

use crate::errors;
use proclaim_cdl::{Algorithm, Atom, Lit};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;

/// Input values and cached answers over one theory. Changing an input re-proves only what it
/// reaches, when next asked. A closed session (`close()`, or the end of a `with` block) raises
/// ValueError on every call.
#[pyclass(module = "proclaim")]
pub(crate) struct Session {
    /// `None` once closed: the memory is freed at once rather than when Python collects it.
    open: Option<proclaim_cdl::Session>,
}

impl Session {
    pub(crate) fn new(session: proclaim_cdl::Session) -> Session {
        Session {
            open: Some(session),
        }
    }

    fn open(&mut self) -> PyResult<&mut proclaim_cdl::Session> {
        self.open
            .as_mut()
            .ok_or_else(|| PyValueError::new_err("the session is closed"))
    }
}

fn algorithm(name: &str) -> PyResult<Algorithm> {
    Algorithm::from_name(name).ok_or_else(|| {
        PyValueError::new_err(format!(
            "`{name}` is not an algorithm; use one of mu, pi, beta, alpha, delta"
        ))
    })
}

fn literal(session: &proclaim_cdl::Session, text: &str) -> PyResult<Lit> {
    session
        .engine()
        .theory()
        .lit(text.trim())
        .ok_or_else(|| PyKeyError::new_err(format!("the theory has no atom for `{text}`")))
}

/// The input atom `name`: when the theory declares its inputs only those may be set, as
/// `proclaim prove --set` has it (anything else is concluded, not observed).
fn input(session: &proclaim_cdl::Session, name: &str) -> PyResult<Atom> {
    let theory = session.engine().theory();
    let atom = theory
        .atom(name.trim())
        .ok_or_else(|| PyKeyError::new_err(format!("the theory has no atom `{name}`")))?;
    let declared: Vec<Atom> = theory.input_atoms().collect();
    if !declared.is_empty() && !declared.contains(&atom) {
        return Err(PyValueError::new_err(format!(
            "`{name}` is not an input of the theory, so it is concluded, not set"
        )));
    }
    Ok(atom)
}

#[pymethods]
impl Session {
    /// Sets an input atom to True, False or None (unknown). Setting one atom of an input group
    /// (`input{a, b, c}`) True sets the others False. Raises KeyError for an atom the theory
    /// does not have, ValueError for one it concludes rather than takes as input, TypeError for
    /// a value that is not a bool or None, and InputConflict when the value contradicts the
    /// axioms (the session is left as it was).
    fn set(&mut self, py: Python<'_>, atom: &str, value: Option<bool>) -> PyResult<()> {
        let session = self.open()?;
        let atom = input(session, atom)?;
        session
            .set_input(atom, value)
            .map_err(|conflict| errors::input_conflict(py, conflict))
    }

    /// The value an input was set to: True, False or None (unknown).
    fn get(&mut self, atom: &str) -> PyResult<Option<bool>> {
        let session = self.open()?;
        let atom = input(session, atom)?;
        Ok(session.input(atom))
    }

    /// Whether `algorithm` (mu, pi, beta, alpha, delta) proves `literal` (`cook`, `~cook`) given
    /// the inputs set. Raises Undecided when the search could not decide within its budget,
    /// KeyError for an atom the theory does not have, ValueError for an unknown algorithm.
    /// The interpreter lock is released while proving, so other threads run during a long search.
    #[pyo3(signature = (literal, algorithm = "beta"))]
    fn prove(&mut self, py: Python<'_>, literal: &str, algorithm: &str) -> PyResult<bool> {
        let algorithm = self::algorithm(algorithm)?;
        let session = self.open()?;
        let literal = self::literal(session, literal)?;
        py.detach(|| session.decide(algorithm, literal))
            .map_err(|stalled| errors::undecided(py, stalled))
    }

    /// Why `algorithm` proves or refutes `literal`, as `proclaim explain` prints it: the
    /// supporting rule, each attacker and what became of it, antecedents `depth` levels down.
    #[pyo3(signature = (literal, algorithm = "beta", depth = 1))]
    fn explain(&mut self, literal: &str, algorithm: &str, depth: usize) -> PyResult<String> {
        let algorithm = self::algorithm(algorithm)?;
        let session = self.open()?;
        let literal = self::literal(session, literal)?;
        Ok(session.explain(algorithm, literal, depth).to_string())
    }

    /// Frees the session now; every later call raises ValueError. Closing twice is allowed.
    fn close(&mut self) {
        self.open = None;
    }

    #[getter]
    fn closed(&self) -> bool {
        self.open.is_none()
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    fn __exit__(
        &mut self,
        _kind: Option<Bound<'_, PyAny>>,
        _value: Option<Bound<'_, PyAny>>,
        _traceback: Option<Bound<'_, PyAny>>,
    ) -> bool {
        self.close();
        false
    }
}
