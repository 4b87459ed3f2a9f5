//! The one place where engine errors become Python exceptions.
use pyo3::create_exception;
use pyo3::exceptions::{PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::PyErr;
use std::sync::{Mutex, MutexGuard};

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

/// The exception a user callable raised last, with the message the engine carries for it: the error that
/// reaches Python is chained to it (`raise ... from`), so the user's own exception and traceback are kept.
/// Process-wide, since the engine calls the callables from its own threads.
static FAILED_CALLABLE: Mutex<Option<(String, PyErr)>> = Mutex::new(None);

/// The failed callable's slot, whether or not a thread panicked while holding it.
fn failed_callable() -> MutexGuard<'static, Option<(String, PyErr)>> {
    FAILED_CALLABLE
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The exception behind an engine error whose message contains a failed callable's message, if any.
fn take_callable_error(message: &str) -> Option<PyErr> {
    let mut slot = failed_callable();
    match slot.as_ref() {
        Some((text, _)) if message.contains(text.as_str()) => slot.take().map(|(_, e)| e),
        _ => None,
    }
}

/// Keeps `error`, raised by a user callable, under the `message` the engine carries for it.
pub fn remember_callable_error(message: &str, error: PyErr) {
    *failed_callable() = Some((message.to_string(), error));
}

/// Engine error → Python exception; one caused by a user callable that raised is chained to that exception.
pub fn to_py(error: pipelay::Error) -> PyErr {
    let message = error.to_string();
    let err = engine_error(error);
    if let Some(cause) = take_callable_error(&message) {
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
