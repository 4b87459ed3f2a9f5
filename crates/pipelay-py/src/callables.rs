//! Python callables of time as engine time functions: they take the GIL when the engine calls them.
use crate::convert::{matrix3, vector3};
use crate::errors::remember_callable_error;
use nalgebra::{Matrix3, Vector3};
use pipelay::table::TimeFunction;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Set when a callable was interrupted by Ctrl-C (KeyboardInterrupt raised inside it), so that a run can
/// stop cleanly instead of reporting a failed callable.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Whether a callable saw Ctrl-C since the last call; clears the flag.
pub fn take_interrupt() -> bool {
    INTERRUPTED.swap(false, Ordering::SeqCst)
}

/// Wraps `callable(t)`, converting its result with `convert`; a Python error becomes the message (and is kept
/// for [`crate::errors::to_py`]).
fn wrap<T: 'static>(
    callable: Py<PyAny>,
    argument: &'static str,
    convert: fn(&Bound<'_, PyAny>, &str) -> PyResult<T>,
) -> TimeFunction<T> {
    Arc::new(move |time| {
        Python::attach(|py| {
            let value = callable
                .bind(py)
                .call1((time,))
                .map_err(|e| raised(py, e, argument, time))?;
            convert(&value, argument).map_err(|e| e.to_string())
        })
    })
}

/// The message of the error `error` that `argument`, called at `time`, raised (kept for
/// [`crate::errors::to_py`]); Ctrl-C is remembered ([`take_interrupt`]).
fn raised(py: Python<'_>, error: PyErr, argument: &str, time: f64) -> String {
    if error.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
        INTERRUPTED.store(true, Ordering::SeqCst);
    }
    let kind = error
        .get_type(py)
        .name()
        .map_or_else(|_| "Exception".to_string(), |n| n.to_string());
    let message = format!("{argument}({time}) raised {kind}: {}", error.value(py));
    remember_callable_error(&message, error);
    message
}

/// A callable of (t, Δt, η (6,), ν (6,)) returning τ (6,): an external controller's command law
/// ([`pipelay::vessel::control::CommandLaw`]).
pub fn command_law(
    callable: &Bound<'_, PyAny>,
    argument: &'static str,
) -> PyResult<pipelay::vessel::control::CommandLaw> {
    if !callable.is_callable() {
        return Err(crate::errors::input(
            argument,
            callable.repr().map_or("?".into(), |r| r.to_string()),
            "must be a callable of (t, dt, η (6,), ν (6,)) returning τ (6,)",
        ));
    }
    let callable = callable.clone().unbind();
    Ok(Arc::new(move |time, dt, eta, velocity| {
        Python::attach(|py| {
            let eta = crate::convert::to_numpy(py, eta.as_slice());
            let velocity = crate::convert::to_numpy(py, velocity.as_slice());
            let value = callable
                .bind(py)
                .call1((time, dt, eta, velocity))
                .map_err(|e| raised(py, e, argument, time))?;
            vector6(&value, argument).map_err(|e| e.to_string())
        })
    }))
}

fn scalar(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<f64> {
    value.extract::<f64>().map_err(|_| {
        crate::errors::input(
            argument,
            value.repr().map_or("?".into(), |r| r.to_string()),
            "must return a number",
        )
    })
}

/// A callable of t returning a (3,) vector.
pub fn vector_function(
    callable: &Bound<'_, PyAny>,
    argument: &'static str,
) -> PyResult<TimeFunction<Vector3<f64>>> {
    check_callable(callable, argument)?;
    Ok(wrap(callable.clone().unbind(), argument, vector3))
}

/// A callable of t returning a (3, 3) rotation matrix.
pub fn matrix_function(
    callable: &Bound<'_, PyAny>,
    argument: &'static str,
) -> PyResult<TimeFunction<Matrix3<f64>>> {
    check_callable(callable, argument)?;
    Ok(wrap(callable.clone().unbind(), argument, matrix3))
}

fn vector6(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<nalgebra::Vector6<f64>> {
    crate::convert::array::<6>(value, argument).map(nalgebra::Vector6::from)
}

/// A callable of t returning a (6,) vector.
pub fn vector6_function(
    callable: &Bound<'_, PyAny>,
    argument: &'static str,
) -> PyResult<TimeFunction<nalgebra::Vector6<f64>>> {
    check_callable(callable, argument)?;
    Ok(wrap(callable.clone().unbind(), argument, vector6))
}

/// A callable of t returning a number.
pub fn scalar_function(
    callable: &Bound<'_, PyAny>,
    argument: &'static str,
) -> PyResult<TimeFunction<f64>> {
    check_callable(callable, argument)?;
    Ok(wrap(callable.clone().unbind(), argument, scalar))
}

/// A table of rows [t, `width` values] (shape (k, 1 + width)) given where a function of time may be, or `None`
/// if `value` is callable; `allowed` says what the argument may be, for the error.
pub fn table(
    value: &Bound<'_, PyAny>,
    argument: &str,
    width: usize,
    allowed: &str,
) -> PyResult<Option<pipelay::table::Table>> {
    if value.is_callable() {
        return Ok(None);
    }
    let wrong = || {
        crate::errors::input(
            argument,
            value.repr().map_or("?".into(), |r| r.to_string()),
            allowed,
        )
    };
    let (rows, shape) = crate::convert::float_array(value, argument).map_err(|_| wrong())?;
    if shape.len() != 2 || shape[1] != width + 1 {
        return Err(wrong());
    }
    pipelay::table::Table::new(argument, &rows, width)
        .map(Some)
        .map_err(crate::errors::to_py)
}

fn check_callable(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<()> {
    if value.is_callable() {
        Ok(())
    } else {
        Err(crate::errors::input(
            argument,
            value.repr().map_or("?".into(), |r| r.to_string()),
            "must be a callable of time t (s)",
        ))
    }
}
