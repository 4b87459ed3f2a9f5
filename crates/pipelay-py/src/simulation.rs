//! Python class Simulation: time stepping with a progress bar, the GIL released while the engine steps,
//! checkpoints and their restoring.
use crate::callables::take_interrupt;
use crate::convert::{flat, shaped};
use crate::errors::{input, to_py};
use crate::results::Results;
use crate::state::State;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3, Vector6};
use pipelay::dynamics::history::History;
use pipelay::dynamics::integrator::{DynamicOptions, Integrator};
use pipelay::dynamics::ledger::Ledger;
use pipelay::dynamics::passivity::PassivityLedger;
use pipelay::dynamics::stages::Stages;
use pipelay::dynamics::state::{DynamicState, VesselMotion};
use pipelay::model::Model;
use pipelay::rod::dynamic_element::GaussPoint;
use pipelay::vessel::winch::HandBack;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A time simulation of a model (energy–momentum conserving integrator).
#[pyclass(module = "pipelay", name = "Simulation")]
pub struct Simulation {
    integrator: Integrator,
    last_iterations: usize,
    /// The fingerprint of the model as given (before stages changed it): what a checkpoint stores.
    fingerprint: Vec<(&'static str, String)>,
}

impl Simulation {
    /// A simulation of `model` from `state` with time step `dt` (s); `stages`, if given, are already applied
    /// to `model` ([`Stages::apply`]).
    pub fn from_state(
        model: Model,
        state: DynamicState,
        dt: f64,
        high_frequency_damping: f64,
        stages: Option<Stages>,
        fingerprint: Vec<(&'static str, String)>,
    ) -> PyResult<Self> {
        pipelay::error::non_negative("high_frequency_damping", high_frequency_damping, "")
            .map_err(to_py)?;
        let options = DynamicOptions {
            time_step: dt,
            high_frequency_damping,
            ..DynamicOptions::default()
        };
        let mut integrator = Integrator::new(model, state, options).map_err(to_py)?;
        if let Some(stages) = stages {
            integrator.set_applied_stages(stages);
        }
        Ok(Simulation {
            integrator,
            last_iterations: 0,
            fingerprint,
        })
    }
}

/// The checkpoint's array `name` of `count` values, if it has one (`allowed`: what it must hold).
fn optional_values(
    arrays: &Bound<'_, PyDict>,
    name: &str,
    count: usize,
    allowed: &str,
) -> PyResult<Option<Vec<f64>>> {
    let Some(value) = arrays.get_item(name)? else {
        return Ok(None);
    };
    let data = flat(&value, name)?;
    if data.len() != count {
        return Err(input(name, format!("{} values", data.len()), allowed));
    }
    Ok(Some(data))
}

/// Checks that a checkpoint's model fingerprint (if it has one: older checkpoints do not) matches `now`, the
/// model's it resumes into, but in the parts named in `allow`; names the parts that differ.
fn check_fingerprint(
    arrays: &Bound<'_, PyDict>,
    now: &[(&'static str, String)],
    allow: &[String],
) -> PyResult<()> {
    let parts = pipelay::fingerprint::PARTS;
    if let Some(unknown) = allow.iter().find(|a| !parts.contains(&a.as_str())) {
        return Err(input(
            "allow",
            format!("{unknown:?}"),
            &format!("must name parts of a model: {}", parts.join(", ")),
        ));
    }
    let Some(stored) = arrays.get_item("fingerprint")? else {
        return Ok(());
    };
    let stored: Vec<String> = stored
        .try_iter()?
        .map(|item| item.and_then(|i| i.str().map(|s| s.to_string())))
        .collect::<PyResult<_>>()?;
    let stored: std::collections::HashMap<&str, &str> = stored
        .iter()
        .filter_map(|entry| entry.split_once('='))
        .collect();
    let differing: Vec<&str> = now
        .iter()
        .filter(|(part, digest)| stored.get(part).is_some_and(|d| d != digest))
        .map(|(part, _)| *part)
        .filter(|part| !allow.iter().any(|a| a == part))
        .collect();
    if differing.is_empty() {
        return Ok(());
    }
    Err(input(
        "model",
        format!("a model that differs from the checkpoint's in {}", differing.join(", ")),
        &format!(
            "must be the model the checkpoint was saved from, so that the run continues as it would have \
             (a deliberate change: pl.resume(..., allow=[{}]))",
            differing
                .iter()
                .map(|p| format!("{p:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    ))
}

/// The stages of `list` from `start_time`, checked and applied to `model` stepped with `dt` (s).
fn applied_stages(
    model: &mut Model,
    list: &crate::stages::Stages,
    start_time: f64,
    dt: f64,
) -> PyResult<Stages> {
    let mut stages = Stages::new(list.0.clone(), start_time).map_err(to_py)?;
    stages.apply(model, dt).map_err(to_py)?;
    Ok(stages)
}

/// The rod of a checkpoint written with pay-out (arrays `mesh_nodes`, `mesh_frames`, `mesh_elements` and,
/// for a line of segments, `mesh_segments`).
fn restored_rod(
    model: &Model,
    get: &dyn Fn(&str) -> PyResult<Vec<f64>>,
    segments: Option<Vec<f64>>,
) -> PyResult<pipelay::rod::Rod> {
    let (nodes, frames, elements) = (
        get("mesh_nodes")?,
        get("mesh_frames")?,
        get("mesh_elements")?,
    );
    let count = elements.len() / 7;
    if elements.len() != 7 * count
        || nodes.len() != 3 * (count + 1)
        || frames.len() != 4 * (count + 1)
    {
        return Err(input(
            "mesh_elements",
            format!(
                "{} element, {} node and {} frame values",
                elements.len(),
                nodes.len(),
                frames.len()
            ),
            "must hold n × 7, (n + 1) × 3 and (n + 1) × 4 values",
        ));
    }
    if let Some(segments) = segments.as_ref().filter(|s| s.len() != count) {
        return Err(input(
            "mesh_segments",
            format!("{} values", segments.len()),
            &format!("must hold one per element ({count})"),
        ));
    }
    let vector = |v: &[f64]| Vector3::from_column_slice(v);
    Ok(pipelay::rod::Rod {
        nodes: nodes.chunks_exact(3).map(vector).collect(),
        frames: frames
            .chunks_exact(4)
            .map(|q| UnitQuaternion::new_normalize(Quaternion::new(q[3], q[0], q[1], q[2])))
            .collect(),
        elements: elements
            .chunks_exact(7)
            .map(|e| pipelay::rod::element::ElementReference {
                length: e[0],
                strain: vector(&e[1..4]),
                curvature: vector(&e[4..7]),
            })
            .collect(),
        segment_of: match segments {
            // A checkpoint of a line of one segment may not carry them.
            None => vec![0; count],
            Some(segments) => segments
                .iter()
                .map(|&k| {
                    let valid =
                        k >= 0.0 && k.fract() == 0.0 && (k as usize) < model.rod.sections.len();
                    valid.then_some(k as usize).ok_or_else(|| {
                        input(
                            "mesh_segments",
                            k,
                            &format!("must be segment indices in 0..{}", model.rod.sections.len()),
                        )
                    })
                })
                .collect::<PyResult<Vec<usize>>>()?,
        },
        sections: model.rod.sections.clone(),
    })
}

#[pymethods]
impl Simulation {
    /// A time simulation of `model` from `state` (default: `model.static()`) with time step `dt` (s), using the
    /// energy–momentum conserving integrator. `Model.simulation(state, dt)` is the same.
    /// `stages`: a pl.Stages to run through (`run()` then runs to their end).
    /// `high_frequency_damping` ξ ≥ 0: damps the line's strains by ξ C ΔΓ over each step, so a mode of
    /// circular frequency ω at the ratio ξωΔt/2 (those the step resolves keep most of their energy; the stiff
    /// axial modes and contact impacts it cannot resolve decay by (1 − 2ξ)/(1 + 2ξ) a step); its work is booked
    /// as dissipation. 0 (the default) conserves energy.
    #[new]
    #[pyo3(signature = (model, state=None, dt=0.05, stages=None, high_frequency_damping=0.0))]
    fn new(
        py: Python<'_>,
        model: &crate::model::Model,
        state: Option<&State>,
        dt: f64,
        stages: Option<&crate::stages::Stages>,
        high_frequency_damping: f64,
    ) -> PyResult<Self> {
        pipelay::error::positive("dt", dt, "s").map_err(to_py)?;
        let state = match state {
            Some(s) => s.dynamic_state(&model.0).map_err(to_py)?,
            None => model
                .r#static(py, None, "auto")?
                .dynamic_state(&model.0)
                .map_err(to_py)?,
        };
        let fingerprint = model.0.fingerprint();
        let mut engine = model.0.clone();
        let stages = stages
            .map(|list| applied_stages(&mut engine, list, state.time, dt))
            .transpose()?;
        Simulation::from_state(
            engine,
            state,
            dt,
            high_frequency_damping,
            stages,
            fingerprint,
        )
    }

    /// The high-frequency damping ξ of the line's strains (0: energy conserving).
    #[getter]
    fn high_frequency_damping(&self) -> f64 {
        self.integrator.options().high_frequency_damping
    }

    /// The stages' names, None without stages.
    #[getter]
    fn stage_names(&self) -> Option<Vec<String>> {
        self.integrator
            .stages()
            .map(|s| s.stages.iter().map(|stage| stage.name.clone()).collect())
    }
    /// Each stage's start time and the last one's end (s), None without stages.
    #[getter]
    fn stage_starts(&self) -> Option<Vec<f64>> {
        self.integrator.stages().map(|s| s.starts.clone())
    }

    /// Each segment's steel wall, (outer diameter, wall thickness) (m), None for one without (what
    /// `Results.pipe_walls` gives).
    #[getter]
    fn pipe_walls(&self) -> Vec<Option<(f64, f64)>> {
        crate::results::LineRecord::of(self.integrator.model()).walls
    }
    /// The sea's (depth (m), density (kg/m³)), None without a sea (what `Results.water` gives).
    #[getter]
    fn water(&self) -> Option<(f64, f64)> {
        crate::results::LineRecord::of(self.integrator.model()).water
    }

    /// The end of the last stage (s), None without stages.
    #[getter]
    fn stages_end(&self) -> Option<f64> {
        self.integrator.stages().map(|s| s.end())
    }

    /// The A&R winch's tension limit (N), None without a winch or a limit.
    #[getter]
    fn winch_tension_limit(&self) -> Option<f64> {
        self.integrator
            .model()
            .vessel
            .as_ref()
            .and_then(|v| v.winch.as_ref())
            .and_then(|w| w.tension_limit)
    }

    /// The segment index of the A&R winch's wire (in `Results.segment`), None without a winch.
    #[getter]
    fn winch_wire_segment(&self) -> Option<usize> {
        self.integrator
            .model()
            .vessel
            .as_ref()
            .and_then(|v| v.winch.as_ref())
            .map(|w| w.wire)
    }

    /// The axial force the A&R wire took on at the hand-over (N), None if no hand-over happened in this run.
    #[getter]
    fn hand_over_tension(&self) -> Option<f64> {
        self.integrator.handed_over()
    }

    /// When the tensioner took the pipe back from the A&R winch (s), None if no hand-back happened in this run.
    #[getter]
    fn hand_back_time(&self) -> Option<f64> {
        self.integrator.handed_back()
    }

    /// Advances one time step dt. Raises ConvergenceError if Newton fails (the state is then unchanged).
    fn step(&mut self, py: Python<'_>) -> PyResult<()> {
        let integrator = &mut self.integrator;
        let report = py.detach(|| integrator.step()).map_err(to_py)?;
        self.last_iterations = report.iterations;
        Ok(())
    }

    /// Runs to `t_end` (s) and returns the Results: the current state and every `record_every`-th step after
    /// it. A progress bar (tqdm) shows on long runs unless `progress=False`. Ctrl-C stops the run between
    /// steps and returns what was computed so far (with a warning); a failed step raises ConvergenceError
    /// (or InputError when a drive or scale callable fails) whose `results` attribute holds the steps before it.
    #[pyo3(signature = (t_end=None, progress=true, record_every=1))]
    fn run(
        &mut self,
        py: Python<'_>,
        t_end: Option<f64>,
        progress: bool,
        record_every: i64,
    ) -> PyResult<Results> {
        let dt = self.time_step();
        let start = self.integrator.state().time;
        let Some(t_end) = t_end.or(self.stages_end()) else {
            return Err(input(
                "t_end",
                "None",
                "must be given for a simulation without stages",
            ));
        };
        if !t_end.is_finite() || t_end < start {
            return Err(input(
                "t_end",
                t_end,
                &format!("must be a finite time >= the current time {start} s"),
            ));
        }
        if record_every < 1 {
            return Err(input(
                "record_every",
                record_every,
                "must be an integer >= 1",
            ));
        }
        let steps = ((t_end - start) / dt - 1e-9).ceil().max(0.0) as usize;
        let records = steps / record_every as usize + 1;
        let nodes = self.integrator.model().rod.node_count();
        pipelay::memory::check(
            "t_end",
            t_end,
            records as f64 * nodes as f64 * pipelay::memory::RECORD_BYTES_PER_NODE,
            &format!(
                "{records} records of {nodes} nodes (stream them with output=, or raise record_every)"
            ),
        )
        .map_err(to_py)?;
        let mut history = History::starting_at(&self.integrator.snapshot(0, 1)).map_err(to_py)?;
        history.reserve_records(records - 1).map_err(to_py)?;
        let bar = if progress && steps >= 200 {
            let tqdm = py.import("tqdm")?.getattr("tqdm")?;
            let kwargs = PyDict::new(py);
            kwargs.set_item("total", steps)?;
            kwargs.set_item("unit", "step")?;
            kwargs.set_item("desc", "pipelay")?;
            Some(tqdm.call((), Some(&kwargs))?)
        } else {
            None
        };
        // Steps go in chunks of about CHUNK_SECONDS without the GIL: long enough that another thread's Python
        // (or a second simulation) is not kept waiting for the GIL at every step, short enough that Ctrl-C and
        // the progress bar respond at once. The first chunk is one step, to measure a step's time.
        const CHUNK_SECONDS: f64 = 0.1;
        let mut chunk = 1;
        let mut done = 0;
        let mut counter = 0;
        let mut outcome = Ok(());
        while done < steps {
            let count = chunk.min(steps - done);
            let integrator = &mut self.integrator;
            let history_ref = &mut history;
            let counter_ref = &mut counter;
            let started = std::time::Instant::now();
            let result = py.detach(|| {
                integrator.advance(count, record_every as usize, history_ref, counter_ref)
            });
            let per_step = started.elapsed().as_secs_f64() / count as f64;
            chunk = ((CHUNK_SECONDS / per_step.max(1e-9)) as usize).clamp(1, 10_000);
            done = counter;
            if let Some(bar) = &bar {
                bar.call_method1("update", (count,))?;
            }
            let interrupted = match result {
                Err(error) if !take_interrupt() => {
                    outcome = Err(error);
                    break;
                }
                Err(_) => true,
                Ok(()) => match py.check_signals() {
                    Err(e) if e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) => true,
                    Err(e) => return Err(e),
                    Ok(()) => false,
                },
            };
            if interrupted {
                let message = format!(
                    "run interrupted at t = {:.6} s: returning the results so far",
                    self.integrator.state().time
                );
                py.import("warnings")?.call_method1("warn", (message,))?;
                break;
            }
        }
        if let Some(bar) = &bar {
            bar.call_method0("close")?;
        }
        let results = Results::from_history(history)
            .with_stages(self.integrator.stages())
            .with_line(self.integrator.model());
        match outcome {
            Ok(()) => Ok(results),
            Err(error) => {
                let err = to_py(error);
                err.value(py).setattr("results", Py::new(py, results)?)?;
                Err(err)
            }
        }
    }

    /// The integrator's complete state as arrays (time, Δt, positions, quaternions, velocities, body angular
    /// velocities, the predictor's accelerations, Gauss-point rotations and strains, vessel motion and
    /// acceleration): what `checkpoint` writes.
    fn _checkpoint<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let state = self.integrator.state();
        let dict = PyDict::new(py);
        let rows = |name: &str, data: Vec<f64>, width: usize| -> PyResult<()> {
            let count = data.len() / width.max(1);
            dict.set_item(name, shaped(py, &data, &[count, width])?)
        };
        rows("time", vec![state.time], 1)?;
        rows("pay_out_speed", vec![state.pay_out_speed], 1)?;
        rows(
            "high_frequency_damping",
            vec![self.integrator.options().high_frequency_damping],
            1,
        )?;
        rows("dt", vec![self.time_step()], 1)?;
        let ledger = self.integrator.ledger();
        rows(
            "ledger",
            vec![
                ledger.supplied_work(),
                ledger.dissipated(),
                ledger.pay_out_energy(),
                ledger.plastic_dissipated(),
            ],
            4,
        )?;
        if let Some(stages) = self.integrator.stages() {
            rows("stage_starts", stages.starts.clone(), 1)?;
        }
        // The hand-back's clamp: its time, the hold point and the clamp's angle.
        if let Some(back) = self
            .integrator
            .model()
            .vessel
            .as_ref()
            .and_then(|v| v.winch.as_ref())
            .and_then(|w| w.hand_back)
        {
            let mut values = vec![back.time];
            values.extend(back.hang_off.iter());
            values.extend(back.angle.iter());
            rows("hand_back", values, 13)?;
        }
        let fingerprint: Vec<String> = self
            .fingerprint
            .iter()
            .map(|(part, digest)| format!("{part}={digest}"))
            .collect();
        dict.set_item("fingerprint", fingerprint)?;
        let model = self.integrator.model();
        if model.pay_out.is_some() {
            // Pay-out changes the mesh: the checkpoint carries the rod's reference as it is now.
            let rod = &model.rod;
            rows(
                "mesh_nodes",
                rod.nodes.iter().flat_map(|p| p.iter().copied()).collect(),
                3,
            )?;
            rows(
                "mesh_frames",
                rod.frames
                    .iter()
                    .flat_map(|q| q.coords.iter().copied())
                    .collect(),
                4,
            )?;
            rows(
                "mesh_elements",
                rod.elements
                    .iter()
                    .flat_map(|e| {
                        std::iter::once(e.length)
                            .chain(e.strain.iter().copied())
                            .chain(e.curvature.iter().copied())
                    })
                    .collect(),
                7,
            )?;
            rows(
                "mesh_segments",
                rod.segment_of.iter().map(|&k| k as f64).collect(),
                1,
            )?;
        }
        rows(
            "positions",
            state
                .configuration
                .positions
                .iter()
                .flat_map(|p| p.iter().copied())
                .collect(),
            3,
        )?;
        rows(
            "quaternions",
            state
                .configuration
                .rotations
                .iter()
                .flat_map(|q| q.coords.iter().copied())
                .collect(),
            4,
        )?;
        rows(
            "velocities",
            state
                .velocities
                .iter()
                .flat_map(|v| v.iter().copied())
                .collect(),
            3,
        )?;
        rows(
            "body_angular_velocities",
            state
                .body_angular_velocities
                .iter()
                .flat_map(|v| v.iter().copied())
                .collect(),
            3,
        )?;
        rows(
            "accelerations",
            state
                .accelerations
                .iter()
                .flat_map(|v| v.iter().copied())
                .collect(),
            3,
        )?;
        rows(
            "gauss_rotations",
            state
                .gauss
                .iter()
                .flat_map(|g| g.rotation.iter().copied())
                .collect(),
            9,
        )?;
        rows(
            "gauss_strains",
            state
                .gauss
                .iter()
                .flat_map(|g| g.strain.iter().copied())
                .collect(),
            3,
        )?;
        rows(
            "gauss_curvatures",
            state
                .gauss
                .iter()
                .flat_map(|g| g.curvature.iter().copied())
                .collect(),
            3,
        )?;
        if self.integrator.model().seabed().is_some() {
            rows(
                "friction_slips",
                state.slips.iter().flat_map(|e| e.iter().copied()).collect(),
                2,
            )?;
        }
        // The yielding walls' fibres' plastic strains, element after element.
        if state.plastic.iter().any(|p| !p.is_empty()) {
            rows(
                "plastic",
                state.plastic.iter().flatten().copied().collect(),
                1,
            )?;
        }
        // An articulated stinger's hinge angles and rates, and its sections' points' velocities.
        if !state.hinge_rates.is_empty() {
            rows(
                "hinges",
                state
                    .configuration
                    .hinge_angles
                    .iter()
                    .zip(&state.hinge_rates)
                    .flat_map(|(a, r)| [*a, *r])
                    .collect(),
                2,
            )?;
            rows(
                "section_velocities",
                state
                    .section_velocities
                    .iter()
                    .flat_map(|v| v.iter().copied())
                    .collect(),
                3,
            )?;
        }
        if let Some(v) = &state.vessel {
            let parts = [
                v.velocity,
                v.integral,
                v.hold_thrust,
                v.thrust,
                v.pipe_force,
            ];
            rows(
                "vessel",
                parts.iter().flat_map(|p| p.iter().copied()).collect(),
                6,
            )?;
            rows(
                "tension_loop",
                vec![v.setpoint_offset, v.filtered_tension],
                2,
            )?;
            rows(
                "vessel_acceleration",
                v.acceleration.iter().copied().collect(),
                6,
            )?;
            let p = &v.passivity;
            rows(
                "passivity",
                vec![
                    p.controller_work,
                    p.budget,
                    p.withheld,
                    p.steps as f64,
                    p.throughput,
                ],
                5,
            )?;
        }
        Ok(dict)
    }

    /// A simulation of `model` restored from `_checkpoint` arrays: it continues exactly as the original.
    /// `stages`: those the original ran through. The model must be the one the checkpoint was saved from,
    /// but in the parts named in `allow` (a deliberate change).
    #[staticmethod]
    #[pyo3(signature = (model, arrays, stages=None, allow=Vec::new()))]
    fn _restore(
        model: &crate::model::Model,
        arrays: &Bound<'_, PyDict>,
        stages: Option<&crate::stages::Stages>,
        allow: Vec<String>,
    ) -> PyResult<Simulation> {
        let fingerprint = model.0.fingerprint();
        check_fingerprint(arrays, &fingerprint, &allow)?;
        let get = |key: &str| -> PyResult<Vec<f64>> {
            match arrays.get_item(key)? {
                Some(value) => flat(&value, key),
                None => Err(input(key, "missing", "must be present in the checkpoint")),
            }
        };
        // The stages are applied to the model as it was at the start, before its rod is replaced by the
        // checkpoint's (which may be the winch's already).
        let dt = get("dt")?.first().copied().unwrap_or(f64::NAN);
        let mut original = model.0.clone();
        let stages = match stages {
            Some(list) => {
                let start = match arrays.get_item("stage_starts")? {
                    Some(value) => flat(&value, "stage_starts")?.first().copied(),
                    None => None,
                };
                Some(applied_stages(
                    &mut original,
                    list,
                    start.unwrap_or(0.0),
                    dt,
                )?)
            }
            None => None,
        };
        let model = match arrays.get_item("mesh_elements")? {
            Some(_) => original
                .with_rod(restored_rod(
                    &original,
                    &get,
                    arrays
                        .get_item("mesh_segments")?
                        .map(|v| flat(&v, "mesh_segments"))
                        .transpose()?,
                )?)
                .map_err(to_py)?,
            None => original,
        };
        // A run resumed after the hand-back: the tensioner holds the pipe with the clamp it made then.
        let mut model = model;
        if let Some(values) = optional_values(
            arrays,
            "hand_back",
            13,
            "must hold the hand-back's time, hold point (3) and clamp angle (9)",
        )? {
            let back = HandBack {
                time: values[0],
                hang_off: Vector3::from_column_slice(&values[1..4]),
                angle: Matrix3::from_column_slice(&values[4..13]),
            };
            model.hand_back(back);
            if let Some(stages) = &stages {
                stages.rest_after_hand_back(&mut model, back.time);
            }
        }
        let nodes = model.rod.node_count();
        let elements = model.rod.element_count();
        let vectors = |key: &str, count: usize| -> PyResult<Vec<Vector3<f64>>> {
            let data = get(key)?;
            if data.len() != 3 * count {
                return Err(input(
                    key,
                    format!("{} values", data.len()),
                    &format!("must hold {count} × 3 values for this model"),
                ));
            }
            Ok(data
                .chunks_exact(3)
                .map(Vector3::from_column_slice)
                .collect())
        };
        let quaternions = get("quaternions")?;
        if quaternions.len() != 4 * nodes {
            return Err(input(
                "quaternions",
                format!("{} values", quaternions.len()),
                "must hold (n + 1) × 4 values",
            ));
        }
        let rotations = quaternions
            .chunks_exact(4)
            .map(|q| UnitQuaternion::new_unchecked(Quaternion::new(q[3], q[0], q[1], q[2])))
            .collect();
        let gauss_rotations = get("gauss_rotations")?;
        if gauss_rotations.len() != 9 * elements {
            return Err(input(
                "gauss_rotations",
                format!("{} values", gauss_rotations.len()),
                "must hold n × 9 values",
            ));
        }
        let strains = vectors("gauss_strains", elements)?;
        let curvatures = vectors("gauss_curvatures", elements)?;
        let gauss = gauss_rotations
            .chunks_exact(9)
            .zip(strains.iter().zip(&curvatures))
            .map(|(r, (strain, curvature))| GaussPoint {
                rotation: Matrix3::from_column_slice(r),
                strain: *strain,
                curvature: *curvature,
            })
            .collect();
        let vessel = match optional_values(arrays, "vessel", 30, "must hold 5 × 6 values")? {
            Some(data) => {
                let part = |k: usize| Vector6::from_column_slice(&data[6 * k..6 * k + 6]);
                // The lay-tension loop's state and the vessel's acceleration over the last step (checkpoints
                // written before they existed have none).
                let tension_loop = optional_values(
                    arrays,
                    "tension_loop",
                    2,
                    "must hold the set-point offset and the filtered tension",
                )?
                .unwrap_or_else(|| vec![0.0, 0.0]);
                let acceleration =
                    optional_values(arrays, "vessel_acceleration", 6, "must hold 6 values")?
                        .map_or_else(Vector6::zeros, |data| Vector6::from_column_slice(&data));
                Some(VesselMotion {
                    velocity: part(0),
                    acceleration,
                    integral: part(1),
                    hold_thrust: part(2),
                    thrust: part(3),
                    pipe_force: part(4),
                    setpoint_offset: tension_loop[0],
                    filtered_tension: tension_loop[1],
                    passivity: optional_values(
                        arrays,
                        "passivity",
                        5,
                        "must hold the controller's work, its budget, the work withheld, the steps and \
                         the throughput",
                    )?
                    .map_or_else(Default::default, |p| PassivityLedger {
                        controller_work: p[0],
                        budget: p[1],
                        withheld: p[2],
                        steps: p[3] as u64,
                        throughput: p[4],
                    }),
                })
            }
            None => None,
        };
        let slips = optional_values(
            arrays,
            "friction_slips",
            2 * nodes,
            "must hold (n + 1) × 2 values",
        )?
        .map_or_else(
            || vec![nalgebra::Vector2::zeros(); nodes],
            |data| {
                data.chunks_exact(2)
                    .map(nalgebra::Vector2::from_column_slice)
                    .collect()
            },
        );
        // The yielding walls' plastic strains, each element's as many as its wall's state holds (checkpoints
        // of elastic lines, and older ones, have none: the state is then the one at rest).
        let at_rest = model
            .plastic_state()
            .map_or_else(|| vec![Vec::new(); nodes - 1], |state| state.start);
        let sizes: Vec<usize> = at_rest.iter().map(Vec::len).collect();
        let total: usize = sizes.iter().sum();
        let plastic = match optional_values(
            arrays,
            "plastic",
            total,
            "must hold every yielding element's plastic strains",
        )? {
            Some(data) => {
                let mut rest = &data[..];
                sizes
                    .iter()
                    .map(|&size| {
                        let (head, tail) = rest.split_at(size);
                        rest = tail;
                        head.to_vec()
                    })
                    .collect()
            }
            None => at_rest,
        };
        let hinge_count = model.hinge_count();
        let hinges = optional_values(
            arrays,
            "hinges",
            2 * hinge_count,
            "must hold each hinge's angle and rate",
        )?
        .unwrap_or_else(|| vec![0.0; 2 * hinge_count]);
        let section_velocities = optional_values(
            arrays,
            "section_velocities",
            6 * hinge_count,
            "must hold 3 values for each of the sections' 2 points",
        )?
        .map_or_else(
            || vec![Vector3::zeros(); 2 * hinge_count],
            |data| {
                data.chunks_exact(3)
                    .map(Vector3::from_column_slice)
                    .collect()
            },
        );
        let time = get("time")?.first().copied().unwrap_or(0.0);
        let state = DynamicState {
            time,
            configuration: pipelay::assembly::configuration::Configuration {
                positions: vectors("positions", nodes)?,
                rotations,
                hinge_angles: hinges.iter().step_by(2).copied().collect(),
            },
            hinge_rates: hinges.iter().skip(1).step_by(2).copied().collect(),
            plastic,
            section_velocities,
            velocities: vectors("velocities", nodes)?,
            body_angular_velocities: vectors("body_angular_velocities", nodes)?,
            // The predictor's accelerations (checkpoints written before they existed have none).
            accelerations: match arrays.get_item("accelerations")? {
                Some(_) => vectors("accelerations", nodes)?,
                None => vec![Vector3::zeros(); nodes],
            },
            gauss,
            vessel,
            slips,
            // The last step's pay-out speed (checkpoints written before it was kept have none: the speed
            // commanded then).
            pay_out_speed: match optional_values(arrays, "pay_out_speed", 1, "must hold one speed")?
            {
                Some(data) => data[0],
                None => model
                    .pay_out
                    .as_ref()
                    .map_or(Ok(0.0), |p| p.speed_at(time))
                    .map_err(to_py)?,
            },
        };
        let ledger = get("ledger")?;
        // Checkpoints written before the option existed ran without it.
        let damping = optional_values(arrays, "high_frequency_damping", 1, "must hold one value")?
            .map_or(0.0, |data| data[0]);
        let mut simulation =
            Simulation::from_state(model, state, dt, damping, stages, fingerprint)?;
        match ledger[..] {
            [supplied, dissipated] => simulation
                .integrator
                .restore_ledger(Ledger::new(supplied, dissipated, 0.0)),
            [supplied, dissipated, pay_out] => simulation
                .integrator
                .restore_ledger(Ledger::new(supplied, dissipated, pay_out)),
            [supplied, dissipated, pay_out, plastic] => simulation.integrator.restore_ledger(
                Ledger::new(supplied, dissipated, pay_out).with_plastic_dissipated(plastic),
            ),
            _ => return Err(input(
                "ledger",
                format!("{} values", ledger.len()),
                "must hold the supplied work, the dissipation, the pay-out energy and the plastic \
                     dissipation",
            )),
        }
        Ok(simulation)
    }

    /// Current time (s).
    #[getter]
    fn time(&self) -> f64 {
        self.integrator.state().time
    }
    /// Time step (s).
    #[getter(dt)]
    fn time_step(&self) -> f64 {
        self.integrator.options().time_step
    }
    /// The current state.
    #[getter]
    fn state(&self) -> State {
        State::from_integrator(&self.integrator, self.last_iterations)
    }
    /// The vessel's low-frequency pose now (6,) in e (m, rad), what the DP controls; None without a vessel.
    #[getter]
    fn eta_low_frequency<'py>(&self, py: Python<'py>) -> Option<Bound<'py, numpy::PyArray1<f64>>> {
        self.integrator
            .observe()
            .vessel_low_frequency()
            .map(|eta| crate::convert::to_numpy(py, eta.as_slice()))
    }
    /// The system's energy now (J): the ledger's total, E(t) − E(0) = W(t) − D(t).
    #[getter]
    fn energy(&self) -> f64 {
        self.integrator.observe().energy().total()
    }
    /// Work supplied since the simulation started (J).
    #[getter]
    fn supplied_work(&self) -> f64 {
        self.integrator.ledger().supplied_work()
    }
    /// Energy dissipated since the simulation started (J).
    #[getter]
    fn dissipated(&self) -> f64 {
        self.integrator.ledger().dissipated()
    }
    /// Linear momentum (3,) (kg·m/s).
    fn linear_momentum(&self) -> (f64, f64, f64) {
        let p = self.integrator.observe().linear_momentum();
        (p.x, p.y, p.z)
    }
    /// Angular momentum about the origin (3,) (kg·m²/s).
    fn angular_momentum(&self) -> (f64, f64, f64) {
        let j = self.integrator.observe().angular_momentum();
        (j.x, j.y, j.z)
    }
}
