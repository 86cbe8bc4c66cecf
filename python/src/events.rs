//! A behaviour's events as Python dicts, the JSON lines `proclaim run --trace` writes read as
//! `json.loads` would (one serialisation, so the two never disagree), and the host calls among
//! them (`{"event": "called", "function": "beep", "argument": 3, "round": 7}`), which only the
//! embedding program sees.

use crate::clock::Logged;
use proclaim_fsm::Argument;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value as Json;

pub(crate) fn to_python<'py>(
    py: Python<'py>,
    events: &[Logged<'_>],
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for event in events {
        match event {
            Logged::Runner(event) => {
                let json = serde_json::to_value(event).map_err(|error| {
                    pyo3::exceptions::PyRuntimeError::new_err(format!(
                        "an event did not serialise: {error}"
                    ))
                })?;
                list.append(json_to_python(py, &json)?)?;
            }
            Logged::Called(call, round) => {
                let dict = PyDict::new(py);
                dict.set_item("event", "called")?;
                dict.set_item("function", &call.function)?;
                match &call.argument {
                    None => dict.set_item("argument", py.None())?,
                    Some(Argument::Int(i)) => dict.set_item("argument", i)?,
                    Some(Argument::Str(s) | Argument::Word(s)) => dict.set_item("argument", s)?,
                }
                dict.set_item("round", round)?;
                list.append(dict)?;
            }
        }
    }
    Ok(list)
}

fn json_to_python<'py>(py: Python<'py>, json: &Json) -> PyResult<Bound<'py, PyAny>> {
    Ok(match json {
        Json::Null => py.None().into_bound(py),
        Json::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Json::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => i.into_pyobject(py)?.into_any(),
            (None, Some(f)) => f.into_pyobject(py)?.into_any(),
            (None, None) => n.to_string().into_pyobject(py)?.into_any(),
        },
        Json::String(s) => s.into_pyobject(py)?.into_any(),
        Json::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json_to_python(py, item)?)?;
            }
            list.into_any()
        }
        Json::Object(fields) => {
            let dict = PyDict::new(py);
            for (key, value) in fields {
                dict.set_item(key, json_to_python(py, value)?)?;
            }
            dict.into_any()
        }
    })
}
