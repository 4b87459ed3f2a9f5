//! Python classes Seabed, Bathymetry and Touchdown.
use crate::convert::{array, vector};
use crate::errors::{input, to_py};
use nalgebra::{Vector2, Vector3};
use numpy::PyArray1;
use pipelay::environment::bathymetry;
use pipelay::environment::seabed;
use pyo3::prelude::*;

/// The seabed's shape: `Bathymetry.flat(z)`, `Bathymetry.plane(z, gradient)` or `Bathymetry.grid(x, y, z)`.
/// Elevations z are in frame e (e3 down: larger z is deeper).
#[pyclass(module = "pipelay", name = "Bathymetry", frozen)]
#[derive(Clone)]
pub struct Bathymetry(pub bathymetry::Bathymetry);

#[pymethods]
impl Bathymetry {
    /// The horizontal plane at elevation `z` (m, e3 down).
    #[staticmethod]
    #[pyo3(signature = (z=0.0))]
    fn flat(z: f64) -> PyResult<Self> {
        bathymetry::Bathymetry::flat(z)
            .map(Bathymetry)
            .map_err(to_py)
    }

    /// The plane b(x, y) = z + gradient[0]·x + gradient[1]·y (m; e3 down, so a positive gradient deepens).
    #[staticmethod]
    #[pyo3(signature = (z=0.0, gradient=None))]
    fn plane(z: f64, gradient: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let g = gradient
            .map(|g| array::<2>(g, "gradient"))
            .transpose()?
            .unwrap_or([0.0; 2]);
        bathymetry::Bathymetry::plane(z, Vector2::from(g))
            .map(Bathymetry)
            .map_err(to_py)
    }

    /// A grid: `x` (nx,) and `y` (ny,) strictly increasing (m), `z` (nx, ny) seabed elevations (m, e3 down),
    /// interpolated bilinearly and held constant outside the grid.
    #[staticmethod]
    fn grid(x: &Bound<'_, PyAny>, y: &Bound<'_, PyAny>, z: &Bound<'_, PyAny>) -> PyResult<Self> {
        let x = vector(x, "x")?;
        let y = vector(y, "y")?;
        let (z, shape) = crate::convert::float_array(z, "z")?;
        if shape != [x.len(), y.len()] {
            return Err(input(
                "z",
                format!("an array of shape {shape:?}"),
                &format!(
                    "must have shape (len(x), len(y)) = ({}, {})",
                    x.len(),
                    y.len()
                ),
            ));
        }
        bathymetry::Bathymetry::grid(x, y, z)
            .map(Bathymetry)
            .map_err(to_py)
    }

    /// Seabed elevation b(x, y) (m, e3 down).
    fn elevation(&self, x: f64, y: f64) -> f64 {
        self.0.elevation(x, y)
    }

    fn __repr__(&self) -> String {
        match &self.0 {
            bathymetry::Bathymetry::Plane { z, gradient } => {
                format!(
                    "Bathymetry.plane(z={z}, gradient=({}, {}))",
                    gradient.x, gradient.y
                )
            }
            bathymetry::Bathymetry::Grid(grid) => {
                format!(
                    "Bathymetry.grid({} × {} points)",
                    grid.x.len(),
                    grid.y.len()
                )
            }
        }
    }
}

/// Seabed contact: `stiffness` k (Pa/m: force per length k·d·penetration of the centreline, d the section's
/// outer diameter, as MoorDyn's kBot), normal `damping` (Pa·s/m), Coulomb `friction` (a number, or
/// (axial, lateral)), `mobilisation` distance (m) at which friction reaches μN for a pipe resting under its
/// own weight, and `bathymetry` (None: the plane z = 0 through end A's reference).
#[pyclass(module = "pipelay", name = "Seabed", frozen)]
#[derive(Clone)]
pub struct Seabed(pub seabed::Seabed);

#[pymethods]
impl Seabed {
    #[new]
    #[pyo3(signature = (stiffness=1e5, damping=0.0, friction=None, mobilisation=0.01, bathymetry=None))]
    fn new(
        stiffness: f64,
        damping: f64,
        friction: Option<&Bound<'_, PyAny>>,
        mobilisation: f64,
        bathymetry: Option<&Bathymetry>,
    ) -> PyResult<Self> {
        let friction = friction
            .map(|f| crate::convert::scalar_or_array::<2>(f, "friction"))
            .transpose()?
            .unwrap_or([0.0; 2]);
        let shape = match bathymetry {
            Some(b) => b.0.clone(),
            None => bathymetry::Bathymetry::flat(0.0).map_err(to_py)?,
        };
        seabed::Seabed::new(stiffness, damping, friction, mobilisation, shape)
            .map(Seabed)
            .map_err(to_py)
    }

    /// Normal stiffness k (Pa/m).
    #[getter]
    fn stiffness(&self) -> f64 {
        self.0.stiffness
    }
    /// Normal damping (Pa·s/m).
    #[getter]
    fn damping(&self) -> f64 {
        self.0.damping
    }
    /// Friction coefficients (axial, lateral).
    #[getter]
    fn friction(&self) -> (f64, f64) {
        (self.0.friction[0], self.0.friction[1])
    }
    /// Mobilisation distance (m).
    #[getter]
    fn mobilisation(&self) -> f64 {
        self.0.mobilisation
    }
    /// The seabed's shape.
    #[getter]
    fn bathymetry(&self) -> Bathymetry {
        Bathymetry(self.0.bathymetry.clone())
    }

    fn __repr__(&self) -> String {
        let s = &self.0;
        format!(
            "Seabed(stiffness={}, damping={}, friction=({}, {}), mobilisation={})",
            s.stiffness, s.damping, s.friction[0], s.friction[1], s.mobilisation
        )
    }
}

/// Where the pipe leaves the seabed, seen from end A: `arc_length` (m along the reference from A) and
/// `position` (3,) (m, in e).
#[pyclass(module = "pipelay", name = "Touchdown", frozen)]
pub struct Touchdown {
    /// Arc length along the reference from end A (m).
    #[pyo3(get)]
    arc_length: f64,
    position: Vector3<f64>,
}

impl Touchdown {
    pub fn new(arc_length: f64, position: Vector3<f64>) -> Self {
        Touchdown {
            arc_length,
            position,
        }
    }
}

#[pymethods]
impl Touchdown {
    /// Position (3,) (m, in e).
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.position.as_slice())
    }

    fn __repr__(&self) -> String {
        format!(
            "Touchdown(arc_length={:.6} m, position=[{:.6}, {:.6}, {:.6}])",
            self.arc_length, self.position.x, self.position.y, self.position.z
        )
    }
}
