//! Python classes Model and State: supports, loads, the static solve and its results.
use crate::callables::{matrix_function, scalar_function, vector_function};
use crate::convert::{matrices_to_numpy, matrix3, points_to_numpy, to_numpy, vector3};
use crate::errors::{input, to_py};
use crate::structure::{Rod, Sea};
use nalgebra::{Matrix3, Vector3};
use numpy::{PyArray1, PyArray2, PyArray3};
use pipelay::assembly::Configuration;
use pipelay::response::Response;
use pipelay::statics::{self, Start, StaticOptions};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A rod with its sea, gravity, supports and loads.
#[pyclass(module = "pipelay", name = "Model")]
pub struct Model(pub pipelay::model::Model);

fn optional_vector(
    value: Option<&Bound<'_, PyAny>>,
    argument: &str,
) -> PyResult<Option<Vector3<f64>>> {
    value.map(|v| vector3(v, argument)).transpose()
}

#[pymethods]
impl Model {
    #[new]
    #[pyo3(signature = (rod, sea=None, gravity=9.81))]
    fn new(rod: &Rod, sea: Option<&Sea>, gravity: f64) -> PyResult<Self> {
        pipelay::model::Model::new(rod.0.clone(), sea.map(|s| s.0.clone()), gravity)
            .map(Model)
            .map_err(to_py)
    }

    /// Clamps end "A" or "B": position (3,) (m) and rotation (3, 3) held; defaults: the reference node and frame.
    #[pyo3(signature = (end, position=None, rotation=None))]
    fn clamp(
        &mut self,
        end: &str,
        position: Option<&Bound<'_, PyAny>>,
        rotation: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let position = optional_vector(position, "position")?;
        let rotation: Option<Matrix3<f64>> =
            rotation.map(|r| matrix3(r, "rotation")).transpose()?;
        self.0.clamp(end, position, rotation).map_err(to_py)
    }

    /// Pins end "A" or "B": position (3,) (m) held, rotation free; default: the reference node.
    #[pyo3(signature = (end, position=None))]
    fn pin(&mut self, end: &str, position: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        let position = optional_vector(position, "position")?;
        self.0.pin(end, position).map_err(to_py)
    }

    /// Drives end "A" or "B": `position(t)` (3,) (m), optional `velocity(t)` (3,) (m/s, the initial velocity
    /// of the node; default zero) and `rotation(t)` (3, 3); without `rotation` the end turns freely.
    #[pyo3(signature = (end, position, velocity=None, rotation=None))]
    fn drive(
        &mut self,
        end: &str,
        position: &Bound<'_, PyAny>,
        velocity: Option<&Bound<'_, PyAny>>,
        rotation: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let position = vector_function(position, "position")?;
        let velocity = velocity
            .map(|v| vector_function(v, "velocity"))
            .transpose()?;
        let rotation = rotation
            .map(|r| matrix_function(r, "rotation"))
            .transpose()?;
        self.0
            .drive(end, position, velocity, rotation)
            .map_err(to_py)
    }

    /// A fixed-direction force (3,) (N) and moment (3,) (N·m) in e at a node (index, negative from the end,
    /// or "A"/"B"), multiplied by `scale(t)` if given (statics uses `scale(0)`).
    #[pyo3(signature = (node, force=None, moment=None, scale=None))]
    fn point_load(
        &mut self,
        node: &Bound<'_, PyAny>,
        force: Option<&Bound<'_, PyAny>>,
        moment: Option<&Bound<'_, PyAny>>,
        scale: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let index = match node.extract::<String>() {
            Ok(end) => self.0.end_node(&end).map_err(to_py)? as i64,
            Err(_) => node.extract::<i64>().map_err(|_| {
                input(
                    "node",
                    node.repr().map_or("?".into(), |r| r.to_string()),
                    "must be an int or \"A\"/\"B\"",
                )
            })?,
        };
        let force = optional_vector(force, "force")?.unwrap_or_else(Vector3::zeros);
        let moment = optional_vector(moment, "moment")?.unwrap_or_else(Vector3::zeros);
        let scale = scale.map(|f| scalar_function(f, "scale")).transpose()?;
        self.0
            .point_load(index, force, moment, scale)
            .map_err(to_py)
    }

    /// Static equilibrium. `steps`: initial number of load steps (adaptive; default 1); `start`: "auto" (the
    /// elastic catenary when both ends are held and the pipe sinks, else the reference), "reference" or
    /// "catenary". Raises ConvergenceError with the load factor reached. The GIL is released while solving.
    #[pyo3(signature = (steps=None, start="auto"))]
    fn r#static(&self, py: Python<'_>, steps: Option<i64>, start: &str) -> PyResult<State> {
        let start = match start {
            "auto" => Start::Auto,
            "reference" => Start::Reference,
            "catenary" => Start::Catenary,
            other => {
                return Err(input(
                    "start",
                    format!("{other:?}"),
                    "must be \"auto\", \"reference\" or \"catenary\"",
                ))
            }
        };
        let initial_steps = match steps {
            None => 1,
            Some(s) if s >= 1 => s as usize,
            Some(s) => return Err(input("steps", s, "must be None or an integer >= 1")),
        };
        let options = StaticOptions {
            initial_steps,
            start,
            ..StaticOptions::default()
        };
        let model = &self.0;
        let solution = py
            .detach(|| statics::solve(model, &options))
            .map_err(to_py)?;
        Ok(State::new(
            model,
            solution.configuration,
            solution.response,
            1.0,
            solution.iterations,
            solution.steps,
        ))
    }

    /// The reference configuration at rest, without solving.
    fn rest(&self) -> State {
        let config = Configuration::reference(&self.0);
        let response = Response::new(&self.0, &config);
        State::new(&self.0, config, response, 0.0, 0, 0)
    }

    /// The rod.
    #[getter]
    fn rod(&self) -> Rod {
        Rod(self.0.rod.clone())
    }
    /// The sea, if any.
    #[getter]
    fn sea(&self) -> Option<Sea> {
        self.0.sea.clone().map(Sea)
    }
    /// Gravitational acceleration (m/s²).
    #[getter]
    fn gravity(&self) -> f64 {
        self.0.gravity
    }
    /// Submerged weight per unit length (N/m): (mass − ρ_w · displaced_area) g.
    #[getter]
    fn submerged_weight(&self) -> f64 {
        self.0.submerged_weight()
    }
}

/// A configuration of the model and what follows from it (SI units, frame e).
#[pyclass(module = "pipelay", name = "State", frozen)]
pub struct State {
    configuration: Configuration,
    response: Response,
    last_node: usize,
    /// Load factor reached (1.0 for a converged static state, 0.0 for `Model.rest()`).
    #[pyo3(get)]
    load_factor: f64,
    /// Newton iterations spent (all load steps).
    #[pyo3(get)]
    iterations: usize,
    /// Accepted load steps.
    #[pyo3(get)]
    steps: usize,
}

impl State {
    fn new(
        model: &pipelay::model::Model,
        configuration: Configuration,
        response: Response,
        load_factor: f64,
        iterations: usize,
        steps: usize,
    ) -> Self {
        State {
            configuration,
            response,
            last_node: model.rod.element_count(),
            load_factor,
            iterations,
            steps,
        }
    }

    fn end_node(&self, end: &str) -> PyResult<usize> {
        match end {
            "A" => Ok(0),
            "B" => Ok(self.last_node),
            other => Err(input(
                "end",
                format!("{other:?}"),
                "must be \"A\" (node 0) or \"B\" (node n)",
            )),
        }
    }
}

#[pymethods]
impl State {
    /// Node positions (n + 1, 3) (m).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_to_numpy(py, &self.configuration.positions)
    }
    /// Nodal rotations R_t^e (n + 1, 3, 3).
    #[getter]
    fn rotations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let matrices: Vec<Matrix3<f64>> = self
            .configuration
            .rotations
            .iter()
            .map(|q| q.to_rotation_matrix().into_inner())
            .collect();
        matrices_to_numpy(py, &matrices)
    }
    /// Nodal velocities (n + 1, 3) (m/s): zero in statics.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_to_numpy(py, &vec![Vector3::zeros(); self.last_node + 1])
    }
    /// Spatial angular velocities (n + 1, 3) (rad/s): zero in statics.
    #[getter]
    fn angular_velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.velocities(py)
    }
    /// Material-frame force (N) and moment (N·m) at element midpoints (n, 6): [N1, N2, N3, M1, M2, M3].
    #[getter]
    fn section_forces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let rows: Vec<Vec<f64>> = self
            .response
            .section_forces
            .iter()
            .map(|f| f.as_slice().to_vec())
            .collect();
        PyArray2::from_vec2(py, &rows).expect("rows of six")
    }
    /// Axial force N1 at element midpoints (n,) (N), positive in tension.
    #[getter]
    fn tension<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let tension: Vec<f64> = self.response.section_forces.iter().map(|f| f[0]).collect();
        to_numpy(py, &tension)
    }
    /// Force (N) and moment (N·m) (6,) the rod exerts on the support at end "A" or "B", in e.
    fn reaction<'py>(&self, py: Python<'py>, end: &str) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let node = self.end_node(end)?;
        Ok(to_numpy(py, self.response.nodal_reactions[node].as_slice()))
    }
    /// Vessel position η (6,): None without a vessel.
    #[getter]
    fn eta(&self) -> Option<Vec<f64>> {
        None
    }
    /// Vessel velocity ν (6,): None without a vessel.
    #[getter]
    fn nu(&self) -> Option<Vec<f64>> {
        None
    }
    /// Thrust τ (6,): None without a vessel.
    #[getter]
    fn tau(&self) -> Option<Vec<f64>> {
        None
    }
    /// Energy parts (J): pipe_kinetic, pipe_strain, pipe_gravity, vessel_kinetic, vessel_potential, total.
    fn energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let parts = [
            ("pipe_kinetic", 0.0),
            ("pipe_strain", self.response.strain_energy),
            ("pipe_gravity", self.response.gravity_energy),
            ("vessel_kinetic", 0.0),
            ("vessel_potential", 0.0),
        ];
        let dict = PyDict::new(py);
        let mut total = 0.0;
        for (name, value) in parts {
            dict.set_item(name, value)?;
            total += value;
        }
        dict.set_item("total", total)?;
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        format!(
            "State(nodes={}, load_factor={}, iterations={}, steps={})",
            self.last_node + 1,
            self.load_factor,
            self.iterations,
            self.steps
        )
    }
}
