//! The reasoner as the Python module `proclaim._native`, re-exported by `proclaim/__init__.py`:
//! [`load`] and [`load_file`] give a [`Theory`], whose sessions set inputs and prove literals;
//! [`Behaviour`] starts a behaviour with Python callables as host functions and experts.
//! Typed stubs are `proclaim/__init__.pyi`.

mod behaviour;
mod board;
mod checks;
mod clock;
mod errors;
mod events;
mod session;
mod theory;

use pyo3::prelude::*;
use pyo3::types::PyTuple;

#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = module.py();
    module.add_function(wrap_pyfunction!(theory::load, module)?)?;
    module.add_function(wrap_pyfunction!(theory::load_file, module)?)?;
    module.add_class::<theory::Theory>()?;
    module.add_class::<session::Session>()?;
    module.add_class::<behaviour::Behaviour>()?;
    module.add_class::<board::Board>()?;
    // A tuple: the list of algorithms is not for callers to change.
    module.add(
        "ALGORITHMS",
        PyTuple::new(
            py,
            proclaim_cdl::Algorithm::ALL.map(proclaim_cdl::Algorithm::name),
        )?,
    )?;
    module.add("Error", py.get_type::<errors::Error>())?;
    module.add("TheoryError", py.get_type::<errors::TheoryError>())?;
    module.add("Undecided", py.get_type::<errors::Undecided>())?;
    module.add("InputConflict", py.get_type::<errors::InputConflict>())?;
    module.add("BehaviourError", py.get_type::<errors::BehaviourError>())?;
    module.add(
        "BehaviourWarning",
        py.get_type::<errors::BehaviourWarning>(),
    )?;
    module.add("CallbackError", py.get_type::<errors::CallbackError>())?;
    Ok(())
}
