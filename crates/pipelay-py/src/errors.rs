//! The one place where engine errors become Python exceptions.
use pyo3::create_exception;
use pyo3::exceptions::{PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::PyErr;

create_exception!(
    pipelay,
    InputError,
    PyValueError,
    "Bad input: the message names the argument (or scenario key), the value and what is allowed."
);
create_exception!(
    pipelay,
    ConvergenceError,
    PyRuntimeError,
    "Newton failed: the message gives the load factor or time reached, iterations and residual."
);

/// Engine error → Python exception; one caused by a user callable that raised is chained to that exception.
pub fn to_py(error: pipelay::Error) -> PyErr {
    let message = error.to_string();
    let err = engine_error(error);
    if let Some(cause) = crate::callables::take_callable_error(&message) {
        pyo3::Python::attach(|py| err.set_cause(py, Some(cause)));
    }
    err
}

fn engine_error(error: pipelay::Error) -> PyErr {
    match error {
        pipelay::Error::Input { .. } => InputError::new_err(error.to_string()),
        pipelay::Error::Convergence { .. } => ConvergenceError::new_err(error.to_string()),
        pipelay::Error::Memory { .. } => PyMemoryError::new_err(error.to_string()),
    }
}

/// An [`InputError`] for `argument`.
pub fn input(argument: &str, value: impl std::fmt::Display, allowed: &str) -> PyErr {
    to_py(pipelay::Error::input(argument, value, allowed))
}
