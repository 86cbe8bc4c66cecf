//! The whiteboard from Python: what an expert's callable is given, and the values that cross
//! (bool, int, float, str, bytes and lists of them, as the whiteboard's own values).

use proclaim_board::{Value, Whiteboard};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyFloat, PyInt, PyList, PyString, PyTuple};

/// The module name Python's postings and answers carry on the whiteboard.
pub(crate) const MODULE: &str = "python";

/// A behaviour's whiteboard: `read` the latest value of a type, `post` one.
#[pyclass(module = "proclaim", frozen)]
pub(crate) struct Board {
    board: Whiteboard,
}

impl Board {
    pub(crate) fn new(board: Whiteboard) -> Board {
        Board { board }
    }
}

#[pymethods]
impl Board {
    /// The latest value of `type`, None when never posted.
    fn read<'py>(&self, py: Python<'py>, r#type: &str) -> PyResult<Bound<'py, PyAny>> {
        read(py, &self.board, r#type)
    }

    /// Posts `value` as `type`, from the module `python`.
    fn post(&self, r#type: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        post(&self.board, r#type, value)
    }

    /// `board["doorOpen"]` is `board.read("doorOpen")`.
    fn __getitem__<'py>(&self, py: Python<'py>, r#type: &str) -> PyResult<Bound<'py, PyAny>> {
        read(py, &self.board, r#type)
    }
}

pub(crate) fn read<'py>(
    py: Python<'py>,
    board: &Whiteboard,
    ty: &str,
) -> PyResult<Bound<'py, PyAny>> {
    match board.latest(ty) {
        Some(message) => to_python(py, &message.value),
        None => Ok(py.None().into_bound(py)),
    }
}

pub(crate) fn post(board: &Whiteboard, ty: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    if ty.trim().is_empty() {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "a whiteboard type is a non-empty name",
        ));
    }
    board.post(MODULE, ty, from_python(value)?);
    Ok(())
}

pub(crate) fn to_python<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Int(i) => i.into_pyobject(py)?.into_any(),
        Value::Float(f) => PyFloat::new(py, *f).into_any(),
        Value::Str(s) => PyString::new(py, s).into_any(),
        Value::Bytes(b) => PyBytes::new(py, b).into_any(),
        Value::List(items) => {
            let items = items
                .iter()
                .map(|item| to_python(py, item))
                .collect::<PyResult<Vec<_>>>()?;
            PyList::new(py, items)?.into_any()
        }
    })
}

pub(crate) fn from_python(value: &Bound<'_, PyAny>) -> PyResult<Value> {
    // bool before int: Python's True is an int too.
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if value.is_instance_of::<PyInt>() {
        return value.extract::<i64>().map(Value::Int).map_err(|_| {
            PyTypeError::new_err(format!(
                "{value} does not fit the whiteboard's 64-bit integers"
            ))
        });
    }
    if let Ok(f) = value.cast::<PyFloat>() {
        return Ok(Value::Float(f.value()));
    }
    if let Ok(s) = value.cast::<PyString>() {
        return Ok(Value::Str(s.to_cow()?.into_owned()));
    }
    if let Ok(b) = value.cast::<PyBytes>() {
        return Ok(Value::Bytes(b.as_bytes().to_vec()));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        return value
            .try_iter()?
            .map(|item| from_python(&item?))
            .collect::<PyResult<Vec<_>>>()
            .map(Value::List);
    }
    Err(PyTypeError::new_err(format!(
        "a whiteboard value is a bool, int, float, str, bytes or a list of them, not {}",
        value.get_type().name()?
    )))
}
