//! Python class Raos: a vessel's first-order displacement RAOs (amplitude and phase per period, heading, DOF).
use crate::errors::{input, to_py};
use numpy::ndarray::Array3;
use numpy::{Complex64, IntoPyArray, PyArray1, PyArray3};
use pipelay::vessel::raos::Raos as Table;
use pyo3::prelude::*;
use std::path::PathBuf;

/// RAOs: for the wave elevation a cos(ωt) at CO the motion of DOF j (surge, sway, heave in m/m; roll, pitch,
/// yaw in rad/m; body frame, z down) is |R_j| a cos(ωt + arg R_j), tabulated over periods and relative
/// headings (deg: 0 following seas, 90 from port to starboard, 180 head seas).
#[pyclass(module = "pipelay", name = "Raos", frozen)]
#[derive(Clone)]
pub struct Raos(pub Table);

#[pymethods]
impl Raos {
    /// The built-in OSV's table (computed with Capytaine by scripts/osv_raos.py).
    #[staticmethod]
    fn osv() -> PyResult<Self> {
        Table::osv().map(Raos).map_err(to_py)
    }

    /// A table from a CSV file with the columns period_s, heading_deg and <dof>_amp, <dof>_phase (rad) for
    /// surge, sway, heave, roll, pitch and yaw, on a full grid of periods × headings.
    #[staticmethod]
    fn read(path: PathBuf) -> PyResult<Self> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(&path).map_err(|e| {
            input(
                "path",
                &shown,
                &format!("must be a readable RAO table ({e})"),
            )
        })?;
        Table::from_csv(&text, &shown).map(Raos).map_err(to_py)
    }

    /// The table's periods (s, increasing).
    #[getter]
    fn periods<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.0.periods)
    }

    /// The table's circular frequencies 2π/T (rad/s), one per period (so decreasing).
    #[getter]
    fn frequencies<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let values: Vec<f64> = self
            .0
            .periods
            .iter()
            .map(|t| std::f64::consts::TAU / t)
            .collect();
        PyArray1::from_vec(py, values)
    }

    /// The table's relative headings (deg, increasing in [0, 360)).
    #[getter]
    fn headings<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.0.headings)
    }

    /// The complex RAOs, (periods, headings, 6).
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<Complex64>>> {
        let shape = (self.0.periods.len(), self.0.headings.len(), 6);
        Array3::from_shape_vec(shape, self.0.values.clone())
            .map(|a| a.into_pyarray(py))
            .map_err(|e| input("raos", "its values", &format!("must fill the grid ({e})")))
    }

    /// The complex RAOs of the 6 DOF at `period` (s) and relative `heading` (deg), interpolated bilinearly.
    fn at<'py>(
        &self,
        py: Python<'py>,
        period: f64,
        heading: f64,
    ) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
        let values = self.0.at(period, heading).map_err(to_py)?;
        Ok(PyArray1::from_slice(py, &values))
    }

    fn __repr__(&self) -> String {
        format!(
            "Raos({} periods × {} headings)",
            self.0.periods.len(),
            self.0.headings.len()
        )
    }
}
