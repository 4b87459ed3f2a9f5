//! Python classes Stinger, SLay and JLay: lay equipment on the vessel (body frame b: forward, starboard,
//! down; metres from the vessel's reference point CO).
use crate::convert::{points, vector3};
use crate::errors::{input, to_py};
use numpy::PyArray2;
use pipelay::vessel::lay::{self, LayEquipment, Roller};
use pyo3::prelude::*;

/// A stinger: `rollers` rollers spread evenly over a circular arc of `radius` and `length` (m), the rollers'
/// top line, starting at `origin` (body frame, m) with the slope `angle` (rad below the horizontal) and
/// running aft while bending down. `roller_radius` (m). `Stinger.from_rollers(positions, axes)` places
/// rollers at given top points instead.
#[pyclass(module = "pipelay", name = "Stinger", frozen)]
#[derive(Clone)]
pub struct Stinger(pub Vec<Roller>);

#[pymethods]
impl Stinger {
    #[new]
    #[pyo3(signature = (radius, length, rollers, *, origin=None, angle=0.0, roller_radius=lay::ROLLER_RADIUS))]
    fn new(
        radius: f64,
        length: f64,
        rollers: i64,
        origin: Option<&Bound<'_, PyAny>>,
        angle: f64,
        roller_radius: f64,
    ) -> PyResult<Self> {
        let count = usize::try_from(rollers)
            .ok()
            .filter(|&c| (1..=1000).contains(&c))
            .ok_or_else(|| input("rollers", rollers, "must be an integer from 1 to 1000"))?;
        pipelay::error::positive("roller_radius", roller_radius, "m").map_err(to_py)?;
        let origin = origin
            .map(|o| vector3(o, "origin"))
            .transpose()?
            .unwrap_or_else(nalgebra::Vector3::zeros);
        lay::stinger_rollers(radius, length, count, origin, angle, roller_radius)
            .map(Stinger)
            .map_err(to_py)
    }

    /// Rollers at `positions` (k, 3), their top points (where the pipe's bottom rests), with axes `axes`
    /// (k, 3) (default: athwartships, b2), body frame (m).
    #[staticmethod]
    #[pyo3(signature = (positions, axes=None, roller_radius=lay::ROLLER_RADIUS))]
    fn from_rollers(
        positions: &Bound<'_, PyAny>,
        axes: Option<&Bound<'_, PyAny>>,
        roller_radius: f64,
    ) -> PyResult<Self> {
        pipelay::error::positive("roller_radius", roller_radius, "m").map_err(to_py)?;
        let tops = points(positions, "positions")?;
        if tops.is_empty() || tops.len() > 1000 {
            return Err(input(
                "positions",
                format!("{} rollers", tops.len()),
                "must hold 1 to 1000 rows",
            ));
        }
        let axes = match axes {
            Some(a) => points(a, "axes")?,
            None => vec![nalgebra::Vector3::y(); tops.len()],
        };
        if axes.len() != tops.len() {
            return Err(input(
                "axes",
                format!("{} rows", axes.len()),
                &format!("must have one row per roller ({})", tops.len()),
            ));
        }
        lay::rollers_at(&tops, &axes, roller_radius)
            .map(Stinger)
            .map_err(to_py)
    }

    /// The rollers' top points (k, 3), body frame (m).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let tops: Vec<_> = self
            .0
            .iter()
            .map(|r| r.centre + r.radius * r.normal)
            .collect();
        crate::convert::points_to_numpy(py, &tops)
    }

    fn __len__(&self) -> usize {
        self.0.len()
    }

    fn __repr__(&self) -> String {
        format!("Stinger({} rollers)", self.0.len())
    }
}

/// S-lay: the pipe held by the tensioner at `tensioner` (body frame, m) on a horizontal firing line along
/// the vessel's axis, running aft over the stinger's rollers. `friction`: roller friction along the pipe
/// (only 0.0, frictionless rollers, is modelled). `roller_stiffness`: contact stiffness (N/m).
#[pyclass(module = "pipelay", name = "SLay", frozen)]
#[derive(Clone)]
pub struct SLay(pub LayEquipment);

#[pymethods]
impl SLay {
    #[new]
    #[pyo3(signature = (tensioner, stinger=None, friction=0.0, *, roller_stiffness=lay::ROLLER_STIFFNESS))]
    fn new(
        tensioner: &Bound<'_, PyAny>,
        stinger: Option<&Stinger>,
        friction: f64,
        roller_stiffness: f64,
    ) -> PyResult<Self> {
        if friction != 0.0 {
            return Err(input(
                "friction",
                friction,
                "must be 0.0: roller friction is not modelled (rollers turn freely)",
            ));
        }
        let tensioner = vector3(tensioner, "tensioner")?;
        let rollers = stinger.map(|s| s.0.clone()).unwrap_or_default();
        LayEquipment::s_lay(tensioner, rollers, roller_stiffness)
            .map(SLay)
            .map_err(to_py)
    }

    /// The tensioner's position (body frame, m).
    #[getter]
    fn tensioner(&self) -> (f64, f64, f64) {
        let p = self.0.hang_off;
        (p.x, p.y, p.z)
    }

    /// The stinger's rollers (body frame), as a Stinger.
    #[getter]
    fn stinger(&self) -> Stinger {
        Stinger(self.0.rollers.clone())
    }

    fn __repr__(&self) -> String {
        let p = self.0.hang_off;
        format!(
            "SLay(tensioner=({}, {}, {}), {} rollers)",
            p.x,
            p.y,
            p.z,
            self.0.rollers.len()
        )
    }
}

/// J-lay: the pipe held at the tower exit `position` (body frame, m), along the tower, which leans `angle`
/// (rad) from the vertical toward the bow.
#[pyclass(module = "pipelay", name = "JLay", frozen)]
#[derive(Clone)]
pub struct JLay(pub LayEquipment);

#[pymethods]
impl JLay {
    #[new]
    #[pyo3(signature = (position, angle=0.0))]
    fn new(position: &Bound<'_, PyAny>, angle: f64) -> PyResult<Self> {
        let position = vector3(position, "position")?;
        LayEquipment::j_lay(position, angle)
            .map(JLay)
            .map_err(to_py)
    }

    /// The tower exit's position (body frame, m).
    #[getter]
    fn position(&self) -> (f64, f64, f64) {
        let p = self.0.hang_off;
        (p.x, p.y, p.z)
    }

    fn __repr__(&self) -> String {
        let p = self.0.hang_off;
        format!("JLay(position=({}, {}, {}))", p.x, p.y, p.z)
    }
}

/// The lay equipment of a Python SLay or JLay object.
pub fn equipment(value: &Bound<'_, PyAny>) -> PyResult<LayEquipment> {
    if let Ok(s) = value.cast::<SLay>() {
        return Ok(s.get().0.clone());
    }
    if let Ok(j) = value.cast::<JLay>() {
        return Ok(j.get().0.clone());
    }
    Err(input(
        "lay",
        value.repr().map_or("?".into(), |r| r.to_string()),
        "must be a pl.SLay or a pl.JLay",
    ))
}
