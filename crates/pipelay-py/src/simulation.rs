//! Python classes Simulation and Results: time stepping with a progress bar, the GIL released while the
//! engine steps, and the recorded time series.
use crate::callables::take_interrupt;
use crate::convert::flat;
use crate::errors::{input, to_py};
use crate::state::State;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3, Vector6};
use numpy::{PyArray1, PyArrayMethods};
use pipelay::dynamics::history::History;
use pipelay::dynamics::integrator::{DynamicOptions, Integrator};
use pipelay::dynamics::ledger::Ledger;
use pipelay::dynamics::state::{DynamicState, VesselMotion};
use pipelay::model::Model;
use pipelay::response::lay_summary::LAY_FIELDS;
use pipelay::rod::dynamic_element::GaussPoint;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A time simulation of a model (energy–momentum conserving integrator).
#[pyclass(module = "pipelay", name = "Simulation")]
pub struct Simulation {
    integrator: Integrator,
    last_iterations: usize,
}

impl Simulation {
    /// A simulation of `model` from `state` with time step `dt` (s).
    pub fn from_state(model: Model, state: DynamicState, dt: f64) -> PyResult<Self> {
        let options = DynamicOptions {
            time_step: dt,
            ..DynamicOptions::default()
        };
        let integrator = Integrator::new(model, state, options).map_err(to_py)?;
        Ok(Simulation {
            integrator,
            last_iterations: 0,
        })
    }
}

/// The rod of a checkpoint written with pay-out (arrays `mesh_nodes`, `mesh_frames`, `mesh_elements`).
fn restored_rod(
    model: &Model,
    get: &dyn Fn(&str) -> PyResult<Vec<f64>>,
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
        section: model.rod.section.clone(),
    })
}

/// Array of `shape` from flat row-major data.
fn shaped<'py>(py: Python<'py>, data: &[f64], shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_slice(py, data)
        .reshape(shape.to_vec())?
        .into_any())
}

#[pymethods]
impl Simulation {
    /// A time simulation of `model` from `state` (default: `model.static()`) with time step `dt` (s), using the
    /// energy–momentum conserving integrator. `Model.simulation(state, dt)` is the same.
    #[new]
    #[pyo3(signature = (model, state=None, dt=0.05))]
    fn new(
        py: Python<'_>,
        model: &crate::model::Model,
        state: Option<&State>,
        dt: f64,
    ) -> PyResult<Self> {
        pipelay::error::positive("dt", dt, "s").map_err(to_py)?;
        let state = match state {
            Some(s) => s.dynamic_state(&model.0).map_err(to_py)?,
            None => model
                .r#static(py, None, "auto")?
                .dynamic_state(&model.0)
                .map_err(to_py)?,
        };
        Simulation::from_state(model.0.clone(), state, dt)
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
    #[pyo3(signature = (t_end, progress=true, record_every=1))]
    fn run(
        &mut self,
        py: Python<'_>,
        t_end: f64,
        progress: bool,
        record_every: i64,
    ) -> PyResult<Results> {
        let dt = self.time_step();
        let start = self.integrator.state().time;
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
        let mut history = History::starting_at(&self.integrator.snapshot(0)).map_err(to_py)?;
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
        let results = Results::from_history(history);
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
    /// velocities, the predictor's accelerations, Gauss-point rotations and strains, vessel motion): what
    /// `checkpoint` writes.
    fn _checkpoint<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let state = self.integrator.state();
        let dict = PyDict::new(py);
        let rows = |name: &str, data: Vec<f64>, width: usize| -> PyResult<()> {
            let count = data.len() / width.max(1);
            dict.set_item(name, shaped(py, &data, &[count, width])?)
        };
        rows("time", vec![state.time], 1)?;
        rows("dt", vec![self.time_step()], 1)?;
        let ledger = self.integrator.ledger();
        rows(
            "ledger",
            vec![
                ledger.supplied_work(),
                ledger.dissipated(),
                ledger.pay_out_energy(),
            ],
            3,
        )?;
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
        }
        Ok(dict)
    }

    /// A simulation of `model` restored from `_checkpoint` arrays: it continues exactly as the original.
    #[staticmethod]
    fn _restore(model: &crate::model::Model, arrays: &Bound<'_, PyDict>) -> PyResult<Simulation> {
        let get = |key: &str| -> PyResult<Vec<f64>> {
            match arrays.get_item(key)? {
                Some(value) => flat(&value, key),
                None => Err(input(key, "missing", "must be present in the checkpoint")),
            }
        };
        let model = match arrays.get_item("mesh_elements")? {
            Some(_) => model
                .0
                .with_rod(restored_rod(&model.0, &get)?)
                .map_err(to_py)?,
            None => model.0.clone(),
        };
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
        let vessel = match arrays.get_item("vessel")? {
            Some(value) => {
                let data = flat(&value, "vessel")?;
                if data.len() != 30 {
                    return Err(input(
                        "vessel",
                        format!("{} values", data.len()),
                        "must hold 5 × 6 values",
                    ));
                }
                let part = |k: usize| Vector6::from_column_slice(&data[6 * k..6 * k + 6]);
                // The lay-tension loop's state (checkpoints written before it existed have none).
                let tension_loop = match arrays.get_item("tension_loop")? {
                    Some(value) => {
                        let loop_state = flat(&value, "tension_loop")?;
                        if loop_state.len() != 2 {
                            return Err(input(
                                "tension_loop",
                                format!("{} values", loop_state.len()),
                                "must hold the set-point offset and the filtered tension",
                            ));
                        }
                        [loop_state[0], loop_state[1]]
                    }
                    None => [0.0, 0.0],
                };
                Some(VesselMotion {
                    velocity: part(0),
                    integral: part(1),
                    hold_thrust: part(2),
                    thrust: part(3),
                    pipe_force: part(4),
                    setpoint_offset: tension_loop[0],
                    filtered_tension: tension_loop[1],
                })
            }
            None => None,
        };
        let slips = match arrays.get_item("friction_slips")? {
            Some(value) => {
                let data = flat(&value, "friction_slips")?;
                if data.len() != 2 * nodes {
                    return Err(input(
                        "friction_slips",
                        format!("{} values", data.len()),
                        "must hold (n + 1) × 2 values",
                    ));
                }
                data.chunks_exact(2)
                    .map(nalgebra::Vector2::from_column_slice)
                    .collect()
            }
            None => vec![nalgebra::Vector2::zeros(); nodes],
        };
        let time = get("time")?.first().copied().unwrap_or(0.0);
        let dt = get("dt")?.first().copied().unwrap_or(f64::NAN);
        let state = DynamicState {
            time,
            configuration: pipelay::assembly::configuration::Configuration {
                positions: vectors("positions", nodes)?,
                rotations,
            },
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
        };
        let ledger = get("ledger")?;
        let mut simulation = Simulation::from_state(model, state, dt)?;
        match ledger[..] {
            [supplied, dissipated] => simulation
                .integrator
                .restore_ledger(Ledger::new(supplied, dissipated, 0.0)),
            [supplied, dissipated, pay_out] => simulation
                .integrator
                .restore_ledger(Ledger::new(supplied, dissipated, pay_out)),
            _ => {
                return Err(input(
                    "ledger",
                    format!("{} values", ledger.len()),
                    "must hold the supplied work, the dissipation and the pay-out energy",
                ))
            }
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

/// Time series of a run (SI units, frame e); arrays are copies you own.
#[pyclass(module = "pipelay", name = "Results", frozen)]
pub struct Results {
    history: History,
    last_node: usize,
}

impl Results {
    /// Results from a finished history.
    pub fn from_history(history: History) -> Self {
        let last_node = history.nodes.saturating_sub(1);
        Results { history, last_node }
    }

    fn series<'py>(&self, py: Python<'py>, data: &[f64]) -> PyResult<Option<Bound<'py, PyAny>>> {
        if data.is_empty() {
            return Ok(None);
        }
        shaped(py, data, &[self.history.len(), 6]).map(Some)
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
    /// Energy parts (T,) each (J): keys as State.energy().
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
    /// Energy pay-out brought in since the start of the run (T,) (J), part of `supplied_work`: the work of the
    /// tensioner (or driven end) on the pipe it lets out, the energy the added pipe carries, and the energy
    /// change of mesh changes.
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
    /// Vessel pose η (T, 6) in e (m, rad): None without a vessel.
    #[getter]
    fn eta<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.series(py, &self.history.eta)
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
    /// Passivity margin max over t of E(t) − E(0) − ∫νᵀτ (J), with ∫νᵀτ the work of the thrust (here: all
    /// supplied work). Never above solver tolerance for a passive system.
    fn passivity_margin(&self) -> f64 {
        let h = &self.history;
        (0..h.len())
            .map(|i| h.total_energy(i) - h.total_energy(0) - h.supplied_work[i])
            .fold(f64::NEG_INFINITY, f64::max)
    }

    fn __len__(&self) -> usize {
        self.history.len()
    }

    /// Results rebuilt from arrays (as written by `to_netcdf`): `nodes` (n + 1) and a mapping of the names
    /// time, positions, rotations, velocities, section_forces, reaction_A, reaction_B, pipe_kinetic,
    /// pipe_strain, pipe_gravity, vessel_kinetic, vessel_potential, supplied_work, dissipated, iterations and,
    /// with a vessel, eta, nu, tau, chi. Used by `pl.load`.
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
        // Results written before pay-out existed have neither: the length is then unknown (NaN).
        h.length = optional("length")?;
        if h.length.is_empty() {
            h.length = vec![f64::NAN; h.time.len()];
        }
        h.pay_out_energy = optional("pay_out_energy")?;
        if h.pay_out_energy.is_empty() {
            h.pay_out_energy = vec![0.0; h.time.len()];
        }
        h.seabed = optional("seabed_energy")?;
        if h.seabed.is_empty() {
            h.seabed = vec![0.0; h.time.len()];
        }
        h.rollers = optional("roller_energy")?;
        if h.rollers.is_empty() {
            h.rollers = vec![0.0; h.time.len()];
        }
        h.roller_reactions = optional("roller_reactions")?;
        h.rollers_count = h.roller_reactions.len() / h.time.len().max(1);
        // Without a seabed no touchdown_arc_length is written: the lay summary's is NaN throughout.
        let lay: Vec<Vec<f64>> = LAY_FIELDS
            .iter()
            .map(|name| match optional(name) {
                Ok(series) if series.is_empty() && *name == "touchdown_arc_length" => {
                    Ok(vec![f64::NAN; h.time.len()])
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
