//! `mintorque._mintorque`: the Python binding (pyo3, abi3). A thin shell over the Rust library, as the CLI
//! is: models and the dynamics on NumPy arrays (batched over states without a Python loop), planning a task
//! file or a dict, sweeps. Every library error becomes a `mintorque.MintorqueError` (a `ValueError`)
//! carrying the file/field message; planning releases the GIL. The Python package (`mintorque/`) wraps
//! this module with docstrings, type stubs and the pandas conversion.

mod dynamics;
mod planning;

use pyo3::prelude::*;

pyo3::create_exception!(
    _mintorque,
    MintorqueError,
    pyo3::exceptions::PyValueError,
    "A mintorque error: bad input (the message names the file and field) or a failed plan."
);

/// The Python exception of a library error.
pub(crate) fn error(e: impl std::fmt::Display) -> PyErr {
    MintorqueError::new_err(e.to_string())
}

#[pymodule]
fn _mintorque(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("MintorqueError", m.py().get_type::<MintorqueError>())?;
    m.add_class::<dynamics::Model>()?;
    m.add_class::<planning::PlanResult>()?;
    m.add_function(wrap_pyfunction!(planning::plan, m)?)?;
    m.add_function(wrap_pyfunction!(planning::sweep_table, m)?)?;
    m.add_function(wrap_pyfunction!(planning::sweep_size, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
