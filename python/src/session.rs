//! A session from Python: set inputs, prove and explain literals.

use crate::errors;
use proclaim_cdl::{Algorithm, Atom, Formula, Lit, Theory};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;

/// Input values and cached answers over one theory. Changing an input re-proves only what it
/// reaches, when next asked. A closed session (`close()`, or the end of a `with` block) raises
/// ValueError on every call.
#[pyclass(module = "proclaim")]
pub(crate) struct Session {
    /// `None` once closed: the memory is freed at once rather than when Python collects it.
    open: Option<proclaim_cdl::Session>,
    /// The theory's file name (or the name it was loaded under), for errors.
    file: String,
}

impl Session {
    pub(crate) fn new(session: proclaim_cdl::Session, file: String) -> Session {
        Session {
            open: Some(session),
            file,
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

/// `query` in the command line's query language (`cook`, `~cook`, `\/{a, b}`,
/// `/\{a, \/{b, c}}`): KeyError naming an atom the theory does not have (with the nearest one
/// it has), ValueError for text that is no query; both name the theory's file.
fn formula(theory: &Theory, file: &str, query: &str) -> PyResult<Formula> {
    Formula::parse(query, theory).map_err(|diagnostics| {
        let unknown = diagnostics.iter().find(|d| d.label == "unknown atom");
        match unknown {
            Some(d) => {
                let hint = d
                    .hint
                    .as_ref()
                    .map(|h| format!("; {h}"))
                    .unwrap_or_default();
                PyKeyError::new_err(format!("{} (in {file}){hint}", d.message))
            }
            None => PyValueError::new_err(format!(
                "`{query}` is not a query (a literal `a`, `~a`, a clause `\\/{{a, b}}` or a \
                 conjunction `/\\{{a, \\/{{b, c}}}}`):\n{}",
                proclaim_syntax::render(&diagnostics, &format!("query (for {file})"), query, false)
            )),
        }
    })
}

/// A literal (`cook`, `~cook`), as [`formula`] reads it.
fn literal(theory: &Theory, file: &str, text: &str) -> PyResult<Lit> {
    match formula(theory, file, text)? {
        Formula::Lit(lit) => Ok(lit),
        _ => Err(PyValueError::new_err(format!(
            "`{text}` is not a literal: only a literal (`cook`, `~cook`) is explained"
        ))),
    }
}

/// The atom `name` of `theory`, or KeyError naming it and the nearest atom the theory has.
pub(crate) fn atom(theory: &Theory, file: &str, name: &str) -> PyResult<Atom> {
    let name = name.trim();
    theory.atom(name).ok_or_else(|| {
        let names = (0..theory.atom_count()).map(|i| theory.atom_name(Atom(i as u32)));
        let hint = proclaim_syntax::nearest(names, name)
            .map(|close| format!("; did you mean `{close}`?"))
            .unwrap_or_default();
        PyKeyError::new_err(format!("the theory has no atom `{name}` (in {file}){hint}"))
    })
}

/// The input atom `name`: when the theory declares its inputs only those may be set, as
/// `proclaim prove --set` has it (anything else is concluded, not observed).
fn input(session: &proclaim_cdl::Session, file: &str, name: &str) -> PyResult<Atom> {
    let theory = session.engine().theory();
    let atom = atom(theory, file, name)?;
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
        let file = self.file.clone();
        let session = self.open()?;
        let atom = input(session, &file, atom)?;
        session
            .set_input(atom, value)
            .map_err(|conflict| errors::input_conflict(py, conflict))
    }

    /// The value an input was set to: True, False or None (unknown).
    fn get(&mut self, atom: &str) -> PyResult<Option<bool>> {
        let file = self.file.clone();
        let session = self.open()?;
        let atom = input(session, &file, atom)?;
        Ok(session.input(atom))
    }

    /// Whether `algorithm` (mu, pi, beta, alpha, delta) proves `query` given the inputs set:
    /// a literal (`cook`, `~cook`), a clause (`\/{a, b}`: one member proved, or the clause
    /// follows from the axioms) or a conjunction of clauses (`/\{a, \/{b, c}}`), written as
    /// `proclaim prove` takes them. Raises Undecided when the search could not decide within its
    /// budget, KeyError for an atom the theory does not have (with the nearest one it has),
    /// ValueError for text that is no query or an unknown algorithm. The interpreter lock is
    /// released while proving, so other threads run during a long search.
    #[pyo3(signature = (query, algorithm = "beta"))]
    fn prove(&mut self, py: Python<'_>, query: &str, algorithm: &str) -> PyResult<bool> {
        let algorithm = self::algorithm(algorithm)?;
        let file = self.file.clone();
        let session = self.open()?;
        let formula = self::formula(session.engine().theory(), &file, query)?;
        py.detach(|| session.decide_formula(algorithm, &formula))
            .map_err(|stalled| errors::undecided(py, stalled))
    }

    /// Why `algorithm` proves or refutes `literal`, as `proclaim explain` prints it: the
    /// supporting rule, each attacker and what became of it, antecedents `depth` levels down.
    #[pyo3(signature = (literal, algorithm = "beta", depth = 1))]
    fn explain(&mut self, literal: &str, algorithm: &str, depth: usize) -> PyResult<String> {
        let algorithm = self::algorithm(algorithm)?;
        let file = self.file.clone();
        let session = self.open()?;
        let literal = self::literal(session.engine().theory(), &file, literal)?;
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
