//! The DP capability functions: the envelope of a vessel's thrusters and the environment's mean load.
use crate::convert::{array, to_numpy, vector};
use crate::errors::to_py;
use crate::vessel::Vessel;
use nalgebra::Vector6;
use numpy::PyArray1;
use pyo3::prelude::*;

/// The largest wind speed (m/s) the vessel's thrusters hold at each heading (rad, the environment coming
/// from, relative to the bow), with the pipe's load `pipe_load` (6,) (body frame) and a co-linear current
/// (m/s) and fully developed sea; `max_wind` if held up to it, 0 if calm cannot be held.
#[pyfunction]
#[pyo3(signature = (vessel, headings, pipe_load, current=0.75, max_wind=60.0))]
pub fn dp_capability_wind<'py>(
    py: Python<'py>,
    vessel: &Vessel,
    headings: &Bound<'_, PyAny>,
    pipe_load: &Bound<'_, PyAny>,
    current: f64,
    max_wind: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let headings = vector(headings, "headings")?;
    let pipe_load = Vector6::from(array::<6>(pipe_load, "pipe_load")?);
    let vessel = vessel.0.clone();
    let speeds = py
        .detach(|| {
            pipelay::vessel::capability::capability(
                &vessel, &headings, &pipe_load, current, max_wind,
            )
        })
        .map_err(to_py)?;
    Ok(PyArray1::from_vec(py, speeds))
}

/// The mean environmental load (6,) (body frame) of a wind speed (m/s) from `heading` (rad, relative to the
/// bow) with its current (m/s) and fully developed sea.
#[pyfunction]
#[pyo3(signature = (vessel, wind_speed, heading, current=0.75))]
pub fn environment_load<'py>(
    py: Python<'py>,
    vessel: &Vessel,
    wind_speed: f64,
    heading: f64,
    current: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let load =
        pipelay::vessel::capability::environment_load(&vessel.0, wind_speed, heading, current)
            .map_err(to_py)?;
    Ok(to_numpy(py, load.as_slice()))
}
