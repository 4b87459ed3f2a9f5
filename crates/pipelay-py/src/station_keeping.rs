//! Python classes of station keeping: Thruster, Allocation, Observer, Wind, HullCoefficients and
//! DriftCoefficients.
use crate::convert::{array, float_array, shaped, to_numpy, vector};
use crate::errors::{input, to_py};
use nalgebra::{Vector2, Vector3, Vector6};
use numpy::PyArray1;
use pipelay::environment::wind::Wind as EngineWind;
use pipelay::vessel::allocation::Allocation as EngineAllocation;
use pipelay::vessel::hull_loads::{DriftCoefficients as EngineDrift, HullCoefficients as Table};
use pipelay::vessel::observer::ObserverSettings;
use pipelay::vessel::thrusters::{Thruster as EngineThruster, ThrusterKind};
use pyo3::prelude::*;
use std::path::PathBuf;

/// A thruster: `kind` "tunnel" (pushes to starboard when positive), "azimuth" (pushes along an azimuth it
/// turns) or "main" (pushes ahead when positive), at `position` (l_x, l_y) (m, body frame from CO), with its
/// largest forward and reverse thrust (N; reverse defaults to the forward for tunnel and main, none for an
/// azimuth thruster), its rate limits (N/s, rad/s; None: unbounded) and the time constant of its thrust's
/// first-order response (s).
#[pyclass(module = "pipelay", name = "Thruster", frozen)]
#[derive(Clone)]
pub struct Thruster(pub EngineThruster);

#[pymethods]
impl Thruster {
    #[new]
    #[pyo3(signature = (kind, position, max_thrust, reverse_thrust=None, thrust_rate=None, azimuth_rate=None, time_constant=1.0))]
    fn new(
        kind: &str,
        position: &Bound<'_, PyAny>,
        max_thrust: f64,
        reverse_thrust: Option<f64>,
        thrust_rate: Option<f64>,
        azimuth_rate: Option<f64>,
        time_constant: f64,
    ) -> PyResult<Self> {
        let kind = ThrusterKind::parse(kind).map_err(to_py)?;
        let position = Vector2::from(array::<2>(position, "position")?);
        EngineThruster::new(
            kind,
            position,
            max_thrust,
            reverse_thrust,
            thrust_rate,
            azimuth_rate,
            time_constant,
        )
        .map(Thruster)
        .map_err(to_py)
    }
    /// "tunnel", "azimuth" or "main".
    #[getter]
    fn kind(&self) -> &'static str {
        self.0.kind.name()
    }
    /// (l_x, l_y) (m, body frame from CO).
    #[getter]
    fn position(&self) -> (f64, f64) {
        (self.0.position.x, self.0.position.y)
    }
    /// Largest forward thrust (N).
    #[getter]
    fn max_thrust(&self) -> f64 {
        self.0.max_thrust
    }
    /// Largest reverse thrust (N).
    #[getter]
    fn reverse_thrust(&self) -> f64 {
        self.0.reverse_thrust
    }
    /// Bound on the thrust's rate (N/s), if any.
    #[getter]
    fn thrust_rate(&self) -> Option<f64> {
        self.0.thrust_rate
    }
    /// Bound on the azimuth's rate (rad/s), if any.
    #[getter]
    fn azimuth_rate(&self) -> Option<f64> {
        self.0.azimuth_rate
    }
    /// Time constant of the thrust's response (s).
    #[getter]
    fn time_constant(&self) -> f64 {
        self.0.time_constant
    }
    fn __repr__(&self) -> String {
        format!(
            "Thruster(kind={:?}, position=({}, {}), max_thrust={})",
            self.0.kind.name(),
            self.0.position.x,
            self.0.position.y,
            self.0.max_thrust
        )
    }
}

/// One thrust allocation: each thruster's thrust (N) and azimuth (rad), the τ they deliver (6,) and whether
/// the command was beyond the thrusters.
#[pyclass(module = "pipelay", name = "Allocation", frozen)]
pub struct Allocation(pub EngineAllocation);

#[pymethods]
impl Allocation {
    /// Each thruster's thrust (k,) (N).
    #[getter]
    fn thrust<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, &self.0.thrust)
    }
    /// Each thruster's azimuth (k,) (rad, from the bow toward starboard).
    #[getter]
    fn azimuth<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, &self.0.azimuth)
    }
    /// The τ delivered (6,) (body frame, N and N·m).
    #[getter]
    fn tau<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, self.0.tau.as_slice())
    }
    /// Whether the thrusters could not deliver the command.
    #[getter]
    fn saturated(&self) -> bool {
        self.0.saturated
    }
}

/// A position observer for the DP controller.
#[pyclass(module = "pipelay", name = "Observer", frozen)]
#[derive(Clone)]
pub struct Observer(pub ObserverSettings);

#[pymethods]
impl Observer {
    /// Fossen's nonlinear passive observer on measurements of x, y (m) and ψ (rad) with Gaussian noise of
    /// standard deviations `noise` (3,), drawn from `seed`; its wave filter notches `wave_period` (s; None:
    /// the sea's peak period when the run starts, else 10 s).
    #[staticmethod]
    #[pyo3(signature = (noise=None, seed=0, wave_period=None))]
    fn passive(
        noise: Option<&Bound<'_, PyAny>>,
        seed: i64,
        wave_period: Option<f64>,
    ) -> PyResult<Self> {
        let seed = crate::waves::checked_seed(seed)?;
        let noise = match noise {
            Some(noise) => Vector3::from(array::<3>(noise, "noise")?),
            None => Vector3::zeros(),
        };
        ObserverSettings::new(noise, seed, wave_period)
            .map(Observer)
            .map_err(to_py)
    }
    /// Noise standard deviations (x, y, ψ) (m, m, rad).
    #[getter]
    fn noise(&self) -> (f64, f64, f64) {
        (self.0.noise.x, self.0.noise.y, self.0.noise.z)
    }
    /// The noise's seed.
    #[getter]
    fn seed(&self) -> u64 {
        self.0.seed
    }
}

/// Wind of 1-hour mean speed `speed` (m/s, at 10 m) blowing toward `direction` (rad, from e1 toward e2, as
/// the current and waves), with gusts from `spectrum` ("NPD", ISO 19901-1; None: steady), phases from `seed`.
#[pyclass(module = "pipelay", name = "Wind", frozen)]
#[derive(Clone)]
pub struct Wind(pub EngineWind);

#[pymethods]
impl Wind {
    #[new]
    #[pyo3(signature = (speed, direction=0.0, spectrum=Some("NPD".to_string()), seed=0))]
    fn new(speed: f64, direction: f64, spectrum: Option<String>, seed: i64) -> PyResult<Self> {
        let seed = crate::waves::checked_seed(seed)?;
        EngineWind::new(speed, direction, spectrum.as_deref(), seed)
            .map(Wind)
            .map_err(to_py)
    }
    /// Mean speed (m/s).
    #[getter]
    fn speed(&self) -> f64 {
        self.0.speed
    }
    /// Direction it blows toward (rad).
    #[getter]
    fn direction(&self) -> f64 {
        self.0.direction
    }
    /// The speed at time `t` (s): mean plus gust (m/s).
    fn speed_at(&self, t: f64) -> f64 {
        self.0.speed_at(t)
    }
}

/// Coefficients C_j(γ) of a flow's load on the hull (m² for forces, m³ for moments): F_j = ½ρV_r²C_j(γ), γ the
/// direction the flow travels relative to the bow (deg, toward starboard: 0 from astern, 180 head-on).
#[pyclass(module = "pipelay", name = "HullCoefficients", frozen)]
#[derive(Clone)]
pub struct HullCoefficients(pub Table);

#[pymethods]
impl HullCoefficients {
    /// A table: `angles` (n,) (deg, increasing in [0, 360)) and `values` (n, 6).
    #[new]
    fn new(angles: &Bound<'_, PyAny>, values: &Bound<'_, PyAny>) -> PyResult<Self> {
        let angles = vector(angles, "angles")?;
        let (flat, shape) = float_array(values, "values")?;
        if shape.len() != 2 || shape[1] != 6 {
            return Err(input(
                "values",
                format!("shape {shape:?}"),
                "must have shape (n, 6)",
            ));
        }
        let rows = flat.chunks(6).map(Vector6::from_column_slice).collect();
        Table::new("values", angles, rows)
            .map(HullCoefficients)
            .map_err(to_py)
    }
    /// A table from a CSV file with columns angle_deg, surge, sway, heave, roll, pitch, yaw.
    #[staticmethod]
    fn read(path: PathBuf) -> PyResult<Self> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(&path)
            .map_err(|e| input("path", &shown, &format!("must be a readable table ({e})")))?;
        Table::from_csv("path", &text, &shown)
            .map(HullCoefficients)
            .map_err(to_py)
    }
    /// Angles (n,) (deg).
    #[getter]
    fn angles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, &self.0.angles)
    }
    /// Coefficients (n, 6) (m², m³).
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let flat: Vec<f64> = self
            .0
            .values
            .iter()
            .flat_map(|v| v.iter().copied())
            .collect();
        shaped(py, &flat, &[self.0.values.len(), 6])
    }
    /// C(γ) (6,) at a relative angle (deg).
    fn at<'py>(&self, py: Python<'py>, angle: f64) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, self.0.at(angle).as_slice())
    }
    /// ½ρV_r²C(γ) (6,) for a flow of velocity `relative` (2,) relative to the vessel, body frame (m/s), and
    /// density ρ (kg/m³).
    fn load<'py>(
        &self,
        py: Python<'py>,
        density: f64,
        relative: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let relative = Vector2::from(array::<2>(relative, "relative")?);
        Ok(to_numpy(py, self.0.load(density, &relative).as_slice()))
    }
}

/// Mean wave-drift coefficients D_j(T, heading) (N/m², N·m/m²; body frame) on a period × heading grid
/// (heading: the direction the waves travel relative to the bow, deg, as the RAOs').
#[pyclass(module = "pipelay", name = "DriftCoefficients", frozen)]
#[derive(Clone)]
pub struct DriftCoefficients(pub EngineDrift);

#[pymethods]
impl DriftCoefficients {
    /// A table from a CSV file with columns period_s, heading_deg, surge, sway, heave, roll, pitch, yaw.
    #[staticmethod]
    fn read(path: PathBuf) -> PyResult<Self> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(&path)
            .map_err(|e| input("path", &shown, &format!("must be a readable table ({e})")))?;
        EngineDrift::from_csv(&text, &shown)
            .map(DriftCoefficients)
            .map_err(to_py)
    }
    /// Periods (s).
    #[getter]
    fn periods<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, &self.0.table.periods)
    }
    /// Headings (deg).
    #[getter]
    fn headings<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, &self.0.table.headings)
    }
    /// D (periods, headings, 6).
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let table = &self.0.table;
        let flat: Vec<f64> = table.values.iter().map(|v| v.re).collect();
        shaped(py, &flat, &[table.periods.len(), table.headings.len(), 6])
    }
    /// D (6,) at a period (s) and relative heading (deg).
    fn at<'py>(
        &self,
        py: Python<'py>,
        period: f64,
        heading: f64,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let value = self.0.at(period, heading).map_err(to_py)?;
        Ok(to_numpy(py, value.as_slice()))
    }
}
