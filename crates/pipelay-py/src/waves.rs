//! Python class Waves: a sea state (regular, JONSWAP or a given spectrum) and its surface elevation.
use crate::convert::flat;
use crate::errors::{input, to_py};
use numpy::PyArray1;
use pipelay::environment::waves::{WaveField, Waves as SeaState};
use pyo3::prelude::*;

/// Standard gravity for a sea state's own elevation (the model resolves it again with its gravity).
const GRAVITY: f64 = 9.81;

/// A sea state: linear wave components. `depth` (m) is the water depth it is resolved for (None: deep water,
/// until a pl.Sea takes it).
#[pyclass(module = "pipelay", name = "Waves", frozen)]
#[derive(Clone)]
pub struct Waves {
    pub sea_state: SeaState,
    pub depth: Option<f64>,
}

impl Waves {
    /// A sea state not yet resolved for a depth, building up over `ramp` seconds (None: its peak period).
    fn unresolved(sea_state: pipelay::Result<SeaState>, ramp: Option<f64>) -> PyResult<Self> {
        sea_state
            .and_then(|sea_state| {
                let ramp = ramp.unwrap_or_else(|| sea_state.peak_period());
                sea_state.with_ramp(ramp)
            })
            .map(|sea_state| Waves {
                sea_state,
                depth: None,
            })
            .map_err(to_py)
    }
}

/// A seed, checked non-negative.
pub(crate) fn checked_seed(seed: i64) -> PyResult<u64> {
    u64::try_from(seed).map_err(|_| input("seed", seed, "must be an integer >= 0"))
}

/// The number of components, checked non-negative (the engine checks the range).
fn component_count(components: i64) -> PyResult<usize> {
    usize::try_from(components)
        .map_err(|_| input("components", components, "must be an integer >= 1"))
}

#[pymethods]
impl Waves {
    /// A regular (Airy) wave: crest-to-trough `height` (m), `period` (s), travelling along `direction` (rad,
    /// from e1 toward e2), building up smoothly over `ramp` seconds (None: one period).
    #[staticmethod]
    #[pyo3(signature = (height, period, direction=0.0, ramp=None))]
    fn regular(height: f64, period: f64, direction: f64, ramp: Option<f64>) -> PyResult<Self> {
        Self::unresolved(SeaState::regular(height, period, direction), ramp)
    }

    /// A JONSWAP sea state: significant height `hs` (m), peak period `tp` (s), peak enhancement `gamma`,
    /// mean direction `direction` (rad), `components` components with random phases (and, with `spreading`
    /// s, directions from cos^2s) drawn from `seed`, building up over `ramp` seconds (None: one peak period).
    #[staticmethod]
    #[pyo3(signature = (hs, tp, gamma=3.3, direction=0.0, seed=0, components=200, spreading=None, ramp=None))]
    #[allow(clippy::too_many_arguments)]
    fn jonswap(
        hs: f64,
        tp: f64,
        gamma: f64,
        direction: f64,
        seed: i64,
        components: i64,
        spreading: Option<f64>,
        ramp: Option<f64>,
    ) -> PyResult<Self> {
        let count = component_count(components)?;
        let seed = checked_seed(seed)?;
        Self::unresolved(
            SeaState::jonswap(hs, tp, gamma, direction, spreading, seed, count),
            ramp,
        )
    }

    /// A sea state from a spectrum: `frequencies` ω (rad/s, increasing) and `densities` S(ω) (m²·s/rad),
    /// interpolated linearly; building up over `ramp` seconds (None: the period of the largest component).
    #[staticmethod]
    #[pyo3(signature = (frequencies, densities, direction=0.0, seed=0, components=200, spreading=None, ramp=None))]
    #[allow(clippy::too_many_arguments)]
    fn spectrum(
        frequencies: &Bound<'_, PyAny>,
        densities: &Bound<'_, PyAny>,
        direction: f64,
        seed: i64,
        components: i64,
        spreading: Option<f64>,
        ramp: Option<f64>,
    ) -> PyResult<Self> {
        let count = component_count(components)?;
        let seed = checked_seed(seed)?;
        Self::unresolved(
            SeaState::from_spectrum(
                &flat(frequencies, "frequencies")?,
                &flat(densities, "densities")?,
                direction,
                spreading,
                seed,
                count,
            ),
            ramp,
        )
    }

    /// Surface elevation (m, up) at times `t` (s; a number or an array) and the point (x, y) (m).
    #[pyo3(signature = (t, x=0.0, y=0.0))]
    fn elevation<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'_, PyAny>,
        x: f64,
        y: f64,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let times = flat(t, "t")?;
        pipelay::error::finite("x", &[x, y]).map_err(to_py)?;
        let field =
            WaveField::new(&self.sea_state, self.depth.unwrap_or(1e5), GRAVITY).map_err(to_py)?;
        let values: Vec<f64> = times
            .iter()
            .map(|&time| field.elevation(x, y, time))
            .collect();
        Ok(PyArray1::from_vec(py, values))
    }

    /// Time over which the sea builds up from calm (s).
    #[getter]
    fn ramp(&self) -> f64 {
        self.sea_state.ramp
    }

    /// Significant height 4√m0 of the components (m).
    #[getter]
    fn hs(&self) -> f64 {
        self.sea_state.significant_height()
    }

    /// The components as arrays (amplitude (m), frequency (rad/s), direction (rad), phase (rad)), (N,) each.
    #[getter]
    fn components<'py>(&self, py: Python<'py>) -> [Bound<'py, PyArray1<f64>>; 4] {
        let c = &self.sea_state.components;
        let column = |f: fn(&pipelay::environment::waves::WaveComponent) -> f64| {
            PyArray1::from_vec(py, c.iter().map(f).collect())
        };
        [
            column(|c| c.amplitude),
            column(|c| c.frequency),
            column(|c| c.direction),
            column(|c| c.phase),
        ]
    }

    fn __repr__(&self) -> String {
        format!(
            "Waves({} components, Hs = {:.3} m)",
            self.sea_state.components.len(),
            self.sea_state.significant_height()
        )
    }
}
