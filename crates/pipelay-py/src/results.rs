//! Python class Results: the time series a simulation recorded, and their rebuilding from arrays read back
//! from a file.
use crate::convert::{flat, shaped};
use crate::errors::input;
use numpy::{PyArray1, PyArrayMethods};
use pipelay::dynamics::history::History;
use pipelay::dynamics::stages::{Stage, Stages};
use pipelay::model::Model;
use pipelay::response::lay_summary::LAY_FIELDS;
use pyo3::prelude::*;

use pyo3::types::PyDict;
/// Time series of a run (SI units, frame e); arrays are copies you own.
#[pyclass(module = "pipelay", name = "Results", frozen)]
pub struct Results {
    history: History,
    last_node: usize,
    /// The run's stages: their names and start times (the last entry the end of the last), if it had any.
    stages: Option<(Vec<String>, Vec<f64>)>,
    /// The line's steel walls and the sea, as the fatigue of the run needs them.
    line: LineRecord,
}

/// What a run's stresses need of its model: each segment's steel wall and the sea.
#[derive(Clone, Debug, Default)]
pub struct LineRecord {
    /// Each segment's (outer diameter, wall thickness) of its steel tube (m); None for a segment without a
    /// wall (a cable, or a section given by its stiffnesses).
    pub walls: Vec<Option<(f64, f64)>>,
    /// The sea's (depth (m), density (kg/m³)), None without a sea.
    pub water: Option<(f64, f64)>,
}

impl LineRecord {
    /// The record of `model`'s line and sea.
    pub fn of(model: &Model) -> Self {
        LineRecord {
            walls: model
                .rod
                .sections
                .iter()
                .map(|section| match (&section.wall, section.cable) {
                    (Some(wall), false) => Some((section.outer_diameter, wall.thickness)),
                    _ => None,
                })
                .collect(),
            water: model.sea.as_ref().map(|sea| (sea.depth, sea.density)),
        }
    }
}

impl Results {
    /// Results from a finished history.
    pub fn from_history(history: History) -> Self {
        let last_node = history.nodes.saturating_sub(1);
        Results {
            history,
            last_node,
            stages: None,
            line: LineRecord::default(),
        }
    }

    /// These results marked with the line and sea of the model that made them.
    pub fn with_line(mut self, model: &Model) -> Self {
        self.line = LineRecord::of(model);
        self
    }

    /// These results marked with the stages of their run.
    pub fn with_stages(mut self, stages: Option<&Stages>) -> Self {
        self.stages = stages.map(|s| {
            (
                s.stages.iter().map(|stage| stage.name.clone()).collect(),
                s.starts.clone(),
            )
        });
        self
    }

    fn series<'py>(&self, py: Python<'py>, data: &[f64]) -> PyResult<Option<Bound<'py, PyAny>>> {
        if data.is_empty() {
            return Ok(None);
        }
        shaped(py, data, &[self.history.len(), 6]).map(Some)
    }

    /// A (T, k) series of the thrusters, if any.
    fn per_thruster<'py>(
        &self,
        py: Python<'py>,
        data: &[f64],
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let k = self.history.thrusters_count;
        if k == 0 {
            return Ok(None);
        }
        shaped(py, data, &[self.history.len(), k]).map(Some)
    }
}

#[pymethods]
impl Results {
    /// Times (T,) (s).
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.history.time)
    }
    /// Node positions (T, n + 1, 3) (m).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        shaped(
            py,
            &self.history.positions,
            &[self.history.len(), self.last_node + 1, 3],
        )
    }
    /// Nodal rotations R_t^e (T, n + 1, 3, 3).
    #[getter]
    fn rotations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        shaped(
            py,
            &self.history.rotations,
            &[self.history.len(), self.last_node + 1, 3, 3],
        )
    }
    /// Node velocities (T, n + 1, 3) (m/s).
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        shaped(
            py,
            &self.history.velocities,
            &[self.history.len(), self.last_node + 1, 3],
        )
    }
    /// Material force (N) and moment (N·m) at element midpoints (T, n, 6).
    #[getter]
    fn section_forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        shaped(
            py,
            &self.history.section_forces,
            &[self.history.len(), self.last_node, 6],
        )
    }
    /// The segment of each element (T, n), as a float: NaN where a record had fewer elements (pay-out).
    #[getter]
    fn segment<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        shaped(
            py,
            &self.history.segment,
            &[self.history.len(), self.last_node],
        )
    }
    /// Axial force at element midpoints (T, n) (N).
    #[getter]
    fn tension<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let tension: Vec<f64> = self
            .history
            .section_forces
            .chunks_exact(6)
            .map(|f| f[0])
            .collect();
        shaped(py, &tension, &[self.history.len(), self.last_node])
    }
    /// Force (N) and moment (N·m) the rod exerts on the support at end "A" or "B" (T, 6), in e. Each record is
    /// the mean over the step that ended at that time (second-order accurate at the step's midpoint
    /// t − Δt/2); the first record is the reaction of the starting state. At an end held by a vessel: the
    /// rod's force and moment on the vessel, in e (`chi` is the same in the body frame).
    fn reaction<'py>(&self, py: Python<'py>, end: &str) -> PyResult<Bound<'py, PyAny>> {
        let data = match end {
            "A" => &self.history.reaction_a,
            "B" => &self.history.reaction_b,
            other => {
                return Err(input(
                    "end",
                    format!("{other:?}"),
                    "must be \"A\" (node 0) or \"B\" (node n)",
                ))
            }
        };
        shaped(py, data, &[self.history.len(), 6])
    }
    /// Touchdown positions (T, 3) (m, in e), NaN rows where the pipe does not touch the seabed; None without a
    /// seabed.
    #[getter]
    fn touchdown<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        if self.history.touchdown_arc_length.is_empty() {
            return Ok(None);
        }
        shaped(py, &self.history.touchdown, &[self.history.len(), 3]).map(Some)
    }
    /// Touchdown arc length along the reference from end A (T,) (m), NaN where the pipe does not touch; None
    /// without a seabed.
    #[getter]
    fn touchdown_arc_length<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        (!self.history.touchdown_arc_length.is_empty())
            .then(|| PyArray1::from_slice(py, &self.history.touchdown_arc_length))
    }
    /// Reference length of pipe on the seabed (T,) (m); None without a seabed.
    #[getter]
    fn laid_length<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        (!self.history.laid_length.is_empty())
            .then(|| PyArray1::from_slice(py, &self.history.laid_length))
    }
    /// Energy parts (T,) each (J): keys as State.energy(), and plastic_dissipation: the energy the yielding
    /// walls dissipated since the run's start (part of `dissipated`, not of the total).
    #[getter]
    fn energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let h = &self.history;
        let total: Vec<f64> = (0..h.len()).map(|i| h.total_energy(i)).collect();
        let dict = PyDict::new(py);
        dict.set_item("pipe_kinetic", PyArray1::from_slice(py, &h.kinetic))?;
        dict.set_item("pipe_strain", PyArray1::from_slice(py, &h.strain))?;
        dict.set_item("pipe_gravity", PyArray1::from_slice(py, &h.gravity))?;
        dict.set_item(
            "vessel_kinetic",
            PyArray1::from_slice(py, &h.vessel_kinetic),
        )?;
        dict.set_item(
            "vessel_potential",
            PyArray1::from_slice(py, &h.vessel_potential),
        )?;
        dict.set_item("seabed", PyArray1::from_slice(py, &h.seabed))?;
        dict.set_item("rollers", PyArray1::from_slice(py, &h.rollers))?;
        dict.set_item("stinger", PyArray1::from_slice(py, &h.stinger))?;
        dict.set_item(
            "plastic_dissipation",
            PyArray1::from_slice(py, &h.plastic_dissipation),
        )?;
        dict.set_item("total", PyArray1::from_slice(py, &total))?;
        Ok(dict)
    }
    /// Work done on the system since the start of the run (T,) (J): point loads, driven supports, the
    /// current's share of the drag and the energy pay-out brought in.
    #[getter]
    fn supplied_work<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.history.supplied_work)
    }
    /// The pipe's unstretched length at each record (T,) (m): it changes with pay-out.
    #[getter]
    fn length<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.history.length)
    }
    /// The pay-out speed of the step that led to each record (T,) (m/s; < 0: pay-in): the tensioner's, or the
    /// A&R winch's once it holds the line (in constant-tension mode, the speed it rendered or hauled at).
    #[getter]
    fn pay_out_speed<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.history.pay_out_speed)
    }
    /// Energy pay-out brought in since the start of the run (T,) (J), part of `supplied_work`: the work of the
    /// tensioner (or driven end) on the pipe it lets out, the energy the added pipe carries, and the energy
    /// change of mesh changes. Once the A&R winch holds the line, it is the winch's work on its wire and the
    /// energy of the wire it pays out: its power, the rate of change, is −T·v to first order (T the wire's
    /// tension, v the `pay_out_speed`).
    #[getter]
    fn pay_out_energy<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.history.pay_out_energy)
    }
    /// Energy dissipated since the start of the run (T,) (J): never decreasing.
    #[getter]
    fn dissipated<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.history.dissipated)
    }
    /// Newton iterations of the step leading to each record (T,).
    #[getter]
    fn iterations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let its: Vec<f64> = self.history.iterations.iter().map(|&i| i as f64).collect();
        PyArray1::from_slice(py, &its)
    }
    /// The most substeps any step since the record before was taken in (T,): 1 where no step was split; a step
    /// whose Newton failed or whose state was rejected is retried in 2, 4, … substeps.
    #[getter]
    fn substeps<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let counts: Vec<f64> = self.history.substeps.iter().map(|&i| i as f64).collect();
        PyArray1::from_slice(py, &counts)
    }
    /// Normal force of each roller (T, k) (N); None without rollers.
    #[getter]
    fn roller_reactions<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let h = &self.history;
        if h.rollers_count == 0 {
            return Ok(None);
        }
        let array = PyArray1::from_slice(py, &h.roller_reactions);
        Ok(Some(array.reshape([h.len(), h.rollers_count])?.into_any()))
    }
    /// Each roller's force on the pipe (T, k, 3) in the vessel's body frame (forward, starboard, down; N);
    /// None without rollers, or from a file written before they were recorded.
    #[getter]
    fn roller_reaction_vectors<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let h = &self.history;
        if h.rollers_count == 0 || h.roller_vectors.is_empty() {
            return Ok(None);
        }
        let array = PyArray1::from_slice(py, &h.roller_vectors);
        Ok(Some(
            array.reshape([h.len(), h.rollers_count, 3])?.into_any(),
        ))
    }
    /// An articulated stinger's hinge angles (T, h) (rad; positive: a section's aft end turned down); None
    /// without.
    #[getter]
    fn hinge_angles<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let h = &self.history;
        if h.hinges_count == 0 {
            return Ok(None);
        }
        let array = PyArray1::from_slice(py, &h.hinge_angles);
        Ok(Some(array.reshape([h.len(), h.hinges_count])?.into_any()))
    }
    /// The lay summary over time: a dict of (T,) arrays with the keys of State.lay_summary()
    /// (liftoff_roller as a number, NaN: none); None without a vessel.
    fn lay_summary<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let h = &self.history;
        if h.lay.is_empty() {
            return Ok(None);
        }
        let dict = PyDict::new(py);
        let width = LAY_FIELDS.len();
        for (k, name) in LAY_FIELDS.iter().enumerate() {
            let series: Vec<f64> = h.lay.iter().skip(k).step_by(width).copied().collect();
            dict.set_item(name, PyArray1::from_slice(py, &series))?;
        }
        Ok(Some(dict))
    }
    /// Vessel pose η (T, 6) in e (m, rad), its total motion (low and wave frequency): None without a vessel.
    #[getter]
    fn eta<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.series(py, &self.history.eta)
    }
    /// The low-frequency pose (T, 6), what the DP controls (η itself without waves): None without a vessel.
    #[getter]
    fn eta_low_frequency<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.series(py, &self.history.eta_low_frequency)
    }
    /// The wave-frequency motion η − η_LF (T, 6) (angles wrapped to (−π, π]): None without a vessel.
    #[getter]
    fn eta_wave_frequency<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let h = &self.history;
        if h.eta_low_frequency.len() != h.eta.len() {
            return Ok(None);
        }
        let wave: Vec<f64> = h
            .eta
            .iter()
            .zip(&h.eta_low_frequency)
            .enumerate()
            .map(|(k, (total, low))| {
                let difference = total - low;
                if k % 6 >= 3 {
                    pipelay::vessel::thrusters::wrap(difference)
                } else {
                    difference
                }
            })
            .collect();
        self.series(py, &wave)
    }
    /// The observer's estimate of the low-frequency pose (T, 6) (x̂, ŷ, ψ̂; z, φ, θ zero): None without an
    /// observer.
    #[getter]
    fn eta_estimate<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.series(py, &self.history.eta_estimate)
    }
    /// The controller's command τ_c (T, 6), body frame (N, N·m): None without a vessel.
    #[getter]
    fn tau_commanded<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.series(py, &self.history.tau_commanded)
    }
    /// Each thruster's delivered thrust (T, k) (N): None without allocation.
    #[getter]
    fn thrust<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.per_thruster(py, &self.history.thrust)
    }
    /// Each thruster's azimuth (T, k) (rad): None without allocation.
    #[getter]
    fn azimuth<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.per_thruster(py, &self.history.azimuth)
    }
    /// Vessel velocity ν (T, 6), body frame: None without a vessel.
    #[getter]
    fn nu<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.series(py, &self.history.nu)
    }
    /// Thrust actually applied τ (T, 6), body frame (N, N·m): None without a vessel.
    #[getter]
    fn tau<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.series(py, &self.history.tau)
    }
    /// The pipe's force and moment on the vessel χ (T, 6), body frame: None without a vessel.
    #[getter]
    fn chi<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.series(py, &self.history.chi)
    }
    /// Passivity margin max over t of E(t) − E(0) − W(t) (J), W the supplied work (thrust and environment): the
    /// plant's certificate, never above the solver's tolerance. With `loop_=True` (Python: `loop=True`), the
    /// closed loop's, for a controller that certifies it (`passivity="certify"`): max over t of
    /// E(t) − E(0) − W_env(t) − R(0) = E(t) − E(0) − W(t) − R(t), R the `passivity_reserve` (the energy the
    /// controller may still give): ≤ 0 when the loop, allocation, thrusters and observer in it, stores no more
    /// than the environment supplied and the controller held. InputError for a run without it.
    #[pyo3(signature = (r#loop = false))]
    fn passivity_margin(&self, r#loop: bool) -> PyResult<f64> {
        let h = &self.history;
        if r#loop && h.passivity_reserve.len() != h.len() {
            return Err(input(
                "loop",
                "True",
                "needs a run whose controller certifies the loop (passivity=\"certify\")",
            ));
        }
        let reserve = |i: usize| if r#loop { h.passivity_reserve[i] } else { 0.0 };
        Ok((0..h.len())
            .map(|i| h.total_energy(i) - h.total_energy(0) - h.supplied_work[i] - reserve(i))
            .fold(f64::NEG_INFINITY, f64::max))
    }
    /// With a controller that certifies the loop (`passivity="certify"`): the energy it may still give the
    /// vessel (T,) (J), its storage at the start less its work on the vessel since; ≥ 0 at every record when
    /// certified. None otherwise.
    #[getter]
    fn passivity_reserve<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        let data = &self.history.passivity_reserve;
        (!data.is_empty()).then(|| PyArray1::from_slice(py, data))
    }
    /// With a controller that certifies the loop: the work its passivity controller withheld from the
    /// controller (the work at full thrust less the work done, summed) since the simulation started (T,) (J).
    /// None otherwise.
    #[getter]
    fn passivity_withheld<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        let data = &self.history.passivity_withheld;
        (!data.is_empty()).then(|| PyArray1::from_slice(py, data))
    }
    /// With a controller that certifies the loop: the steps its passivity controller acted in since the
    /// simulation started (T,). None otherwise.
    #[getter]
    fn passivity_steps<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        let data = &self.history.passivity_steps;
        (!data.is_empty()).then(|| PyArray1::from_slice(py, data))
    }

    fn __len__(&self) -> usize {
        self.history.len()
    }

    /// The stage of each record (T,): the index of the stage whose steps end there (the first record opens
    /// stage 0); None for a run without stages.
    #[getter]
    fn stage<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<i64>>> {
        let (names, starts) = self.stages.as_ref()?;
        let table = stage_table(names, starts).ok()?;
        let index: Vec<i64> = self
            .history
            .time
            .iter()
            .map(|&t| table.index_at(t) as i64)
            .collect();
        Some(PyArray1::from_vec(py, index))
    }
    /// The stages' names, in order; None for a run without stages.
    #[getter]
    fn stage_names(&self) -> Option<Vec<String>> {
        self.stages.as_ref().map(|(names, _)| names.clone())
    }
    /// Each stage's start time (s), and last the end of the last stage (stages + 1,); None without stages.
    #[getter]
    fn stage_starts<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.stages
            .as_ref()
            .map(|(_, starts)| PyArray1::from_slice(py, starts))
    }

    /// These results marked with stages of `names` starting at `starts` (s; one more, the end): used by
    /// `pl.load`.
    fn _with_stages(&self, names: Vec<String>, starts: Vec<f64>) -> PyResult<Results> {
        stage_table(&names, &starts)?;
        Ok(Results {
            history: self.history.clone(),
            last_node: self.last_node,
            stages: Some((names, starts)),
            line: self.line.clone(),
        })
    }

    /// These results marked with the steel walls of the line's segments, (outer diameter, wall thickness) (m)
    /// or None each, and the sea's (depth (m), density (kg/m³)) or None: used by `pl.load`.
    fn _with_line(
        &self,
        walls: Vec<Option<(f64, f64)>>,
        water: Option<(f64, f64)>,
    ) -> PyResult<Results> {
        for (k, wall) in walls.iter().enumerate() {
            if let Some((diameter, thickness)) = wall {
                if !(diameter.is_finite()
                    && thickness.is_finite()
                    && 0.0 < *thickness
                    && 2.0 * thickness <= *diameter)
                {
                    return Err(input(
                        &format!("pipe_walls[{k}]"),
                        format!("({diameter}, {thickness})"),
                        "must be a finite outer diameter and a wall thickness in (0, diameter/2] (m)",
                    ));
                }
            }
        }
        if let Some((depth, density)) = water {
            if !(depth.is_finite() && depth > 0.0 && density.is_finite() && density > 0.0) {
                return Err(input(
                    "water",
                    format!("({depth}, {density})"),
                    "must be a positive depth (m) and density (kg/m³)",
                ));
            }
        }
        Ok(Results {
            history: self.history.clone(),
            last_node: self.last_node,
            stages: self.stages.clone(),
            line: LineRecord { walls, water },
        })
    }

    /// Each segment's steel wall, (outer diameter, wall thickness) (m), from end A; None for a segment without
    /// one (a cable, or a section given by its stiffnesses); an empty list when the results do not say.
    #[getter]
    fn pipe_walls(&self) -> Vec<Option<(f64, f64)>> {
        self.line.walls.clone()
    }
    /// The sea's (depth (m), density (kg/m³)) of the run, None without a sea or when the results do not say.
    #[getter]
    fn water(&self) -> Option<(f64, f64)> {
        self.line.water
    }

    /// Results rebuilt from arrays (as written by `to_netcdf`): `nodes` (n + 1) and a mapping of the names
    /// time, positions, rotations, velocities, section_forces, reaction_A, reaction_B, pipe_kinetic,
    /// pipe_strain, pipe_gravity, vessel_kinetic, vessel_potential, supplied_work, dissipated, iterations, substeps and,
    /// with a vessel, eta, nu, tau, chi (and, if recorded, eta_low_frequency, tau_commanded, eta_estimate,
    /// thrust, azimuth). Used by `pl.load`.
    #[staticmethod]
    fn _from_arrays(nodes: usize, arrays: &Bound<'_, PyDict>) -> PyResult<Results> {
        let get = |key: &str| -> PyResult<Vec<f64>> {
            match arrays.get_item(key)? {
                Some(value) => flat(&value, key),
                None => Err(input(key, "missing", "must be present in the results")),
            }
        };
        let optional = |key: &str| -> PyResult<Vec<f64>> {
            match arrays.get_item(key)? {
                Some(value) => flat(&value, key),
                None => Ok(Vec::new()),
            }
        };
        let mut h = History::empty(nodes);
        h.time = get("time")?;
        h.positions = get("positions")?;
        h.rotations = get("rotations")?;
        h.velocities = get("velocities")?;
        h.section_forces = get("section_forces")?;
        // Results written before lines of segments existed have none: one segment.
        h.segment = optional("segment")?;
        if h.segment.is_empty() {
            h.segment = h
                .section_forces
                .chunks_exact(6)
                .map(|f| if f[0].is_nan() { f64::NAN } else { 0.0 })
                .collect();
        }
        h.reaction_a = get("reaction_A")?;
        h.reaction_b = get("reaction_B")?;
        h.kinetic = get("pipe_kinetic")?;
        h.strain = get("pipe_strain")?;
        h.gravity = get("pipe_gravity")?;
        h.vessel_kinetic = get("vessel_kinetic")?;
        h.vessel_potential = get("vessel_potential")?;
        h.supplied_work = get("supplied_work")?;
        h.dissipated = get("dissipated")?;
        h.iterations = get("iterations")?.iter().map(|&i| i as usize).collect();
        // Results written before substeps were recorded: none taken.
        h.substeps = optional("substeps")?.iter().map(|&i| i as usize).collect();
        if h.substeps.is_empty() {
            h.substeps = vec![1; h.time.len()];
        }
        // Results written before pay-out existed have neither: the length is then unknown (NaN).
        h.length = optional("length")?;
        if h.length.is_empty() {
            h.length = vec![f64::NAN; h.time.len()];
        }
        // Files written before the pay-out speed was recorded: unknown (NaN).
        h.pay_out_speed = optional("pay_out_speed")?;
        if h.pay_out_speed.is_empty() {
            h.pay_out_speed = vec![f64::NAN; h.time.len()];
        }
        h.pay_out_energy = optional("pay_out_energy")?;
        if h.pay_out_energy.is_empty() {
            h.pay_out_energy = vec![0.0; h.time.len()];
        }
        h.passivity_reserve = optional("passivity_reserve")?;
        h.passivity_withheld = optional("passivity_withheld")?;
        h.passivity_steps = optional("passivity_steps")?;
        // Files written before yielding walls existed have none: nothing yielded.
        h.plastic_dissipation = optional("plastic_dissipation")?;
        if h.plastic_dissipation.is_empty() {
            h.plastic_dissipation = vec![0.0; h.time.len()];
        }
        h.seabed = optional("seabed_energy")?;
        if h.seabed.is_empty() {
            h.seabed = vec![0.0; h.time.len()];
        }
        h.rollers = optional("roller_energy")?;
        if h.rollers.is_empty() {
            h.rollers = vec![0.0; h.time.len()];
        }
        // Files written before articulated stingers existed have neither.
        h.stinger = optional("stinger_energy")?;
        if h.stinger.is_empty() {
            h.stinger = vec![0.0; h.time.len()];
        }
        h.hinge_angles = optional("hinge_angles")?;
        h.hinges_count = h.hinge_angles.len() / h.time.len().max(1);
        h.roller_reactions = optional("roller_reactions")?;
        h.rollers_count = h.roller_reactions.len() / h.time.len().max(1);
        // Files written before roller boxes existed have no reaction vectors.
        h.roller_vectors = optional("roller_reaction_vectors")?;
        // Without a seabed no touchdown_arc_length is written: the lay summary's is NaN throughout.
        let lay: Vec<Vec<f64>> = LAY_FIELDS
            .iter()
            .map(|name| match optional(name) {
                // Files written before the tip clearance existed have none either.
                Ok(series)
                    if series.is_empty()
                        && (*name == "touchdown_arc_length"
                            || *name == "tip_clearance"
                            || *name == "tip_offset"
                            || *name == "residual_curvature") =>
                {
                    Ok(vec![f64::NAN; h.time.len()])
                }
                // Files written before roller boxes existed: the pipe stayed on endless rollers.
                Ok(series) if series.is_empty() && *name == "boxes_left" => {
                    Ok(vec![0.0; h.time.len()])
                }
                other => other,
            })
            .collect::<PyResult<_>>()?;
        if lay.iter().all(|series| series.len() == h.time.len()) {
            h.lay = (0..h.time.len())
                .flat_map(|i| lay.iter().map(move |series| series[i]))
                .collect();
        }
        h.touchdown = optional("touchdown")?;
        h.touchdown_arc_length = optional("touchdown_arc_length")?;
        h.laid_length = optional("laid_length")?;
        h.eta = optional("eta")?;
        h.nu = optional("nu")?;
        h.tau = optional("tau")?;
        h.chi = optional("chi")?;
        h.eta_low_frequency = optional("eta_low_frequency")?;
        h.tau_commanded = optional("tau_commanded")?;
        h.eta_estimate = optional("eta_estimate")?;
        h.thrust = optional("thrust")?;
        h.azimuth = optional("azimuth")?;
        h.thrusters_count = h.thrust.len() / h.time.len().max(1);
        h.check()
            .map_err(|message| input("results", message, "arrays must have matching lengths"))?;
        Ok(Results::from_history(h))
    }

    /// Number of nodes n + 1.
    #[getter]
    fn nodes(&self) -> usize {
        self.last_node + 1
    }

    fn __repr__(&self) -> String {
        let t = &self.history.time;
        format!(
            "Results(records={}, t=[{}, {}] s)",
            t.len(),
            t.first().copied().unwrap_or(0.0),
            t.last().copied().unwrap_or(0.0)
        )
    }
}

/// The stage table of `names` and `starts` (one more start than names: the end).
fn stage_table(names: &[String], starts: &[f64]) -> PyResult<Stages> {
    if starts.len() != names.len() + 1 || names.is_empty() {
        return Err(input(
            "stage_starts",
            format!("{} values for {} stages", starts.len(), names.len()),
            "must hold each stage's start and the last one's end",
        ));
    }
    let stages = names
        .iter()
        .zip(starts.windows(2))
        .map(|(name, w)| Stage::lasting(name.clone(), w[1] - w[0]))
        .collect();
    Stages::new(stages, starts[0]).map_err(crate::errors::to_py)
}
