//! Python classes Model and State: supports, loads, the static solve and its results.
use crate::callables::{matrix_function, scalar_function, table, vector_function};
use crate::convert::{array, matrix3, vector3};
use crate::errors::{input, to_py};
use crate::state::State;
use crate::structure::{Clump, Rod, Sea};
use crate::vessel::{PyForce, PyPid, Vessel};
use nalgebra::{Matrix3, Vector3};
use pipelay::assembly::configuration::Configuration;
use pipelay::model::PayOutSpeed;
use pipelay::response::configuration::Response;
use pipelay::statics::solve::{self as statics, Start, StaticOptions};
use pyo3::prelude::*;

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
    /// `position` and `velocity` may also be tables of rows [t, x, y, z], interpolated linearly in the engine
    /// (no Python call per step); a position table's slope is the default velocity.
    #[pyo3(signature = (end, position, velocity=None, rotation=None))]
    fn drive(
        &mut self,
        end: &str,
        position: &Bound<'_, PyAny>,
        velocity: Option<&Bound<'_, PyAny>>,
        rotation: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        const ALLOWED: &str = "must be a callable of time t (s) or a table of rows [t, x, y, z]";
        let (position, slope) = match table(position, "position", 3, ALLOWED)? {
            Some(table) => {
                let (position, slope) = table.vector();
                (position, Some(slope))
            }
            None => (vector_function(position, "position")?, None),
        };
        let velocity = match velocity {
            Some(v) => Some(match table(v, "velocity", 3, ALLOWED)? {
                Some(table) => table.vector().0,
                None => vector_function(v, "velocity")?,
            }),
            None => slope,
        };
        let rotation = rotation
            .map(|r| matrix_function(r, "rotation"))
            .transpose()?;
        self.0
            .drive(end, position, velocity, rotation)
            .map_err(to_py)
    }

    /// Pays pipe out at `end` ("A" or "B") during a simulation at `speed` (m/s of unstretched pipe; a number, a
    /// callable of t or a table of rows [t, speed] interpolated in the engine; negative pays in). The end must be held by the vessel (through its tensioner or tower)
    /// or driven; new elements have the end element's present length. `feed`: the line still on board, a list
    /// of (length (m), Section) in the order it is paid out after the end's segment (each new element takes
    /// the section of the material at its midpoint); None: paid-out pipe continues the end's segment.
    #[pyo3(signature = (end="B", speed=None, feed=None))]
    fn pay_out(
        &mut self,
        end: &str,
        speed: Option<&Bound<'_, PyAny>>,
        feed: Option<Vec<(f64, crate::structure::Section)>>,
    ) -> PyResult<()> {
        const ALLOWED: &str = "a number (m/s), a callable of t or a table of rows [t, speed]";
        let Some(speed) = speed else {
            return Err(input(
                "speed",
                "missing",
                &format!("must be given: {ALLOWED}"),
            ));
        };
        let speed = match speed.extract::<f64>() {
            Ok(v) => PayOutSpeed::Constant(v),
            Err(_) => PayOutSpeed::Function(
                match table(speed, "speed", 1, &format!("must be {ALLOWED}"))? {
                    Some(table) => table.scalar(),
                    None => scalar_function(speed, "speed")?,
                },
            ),
        };
        self.0.pay_out(end, speed).map_err(to_py)?;
        if let Some(feed) = feed {
            let feed = feed
                .into_iter()
                .map(|(length, section)| (length, section.0))
                .collect();
            self.0.feed_pay_out(feed).map_err(to_py)?;
        }
        Ok(())
    }

    /// Attaches `attachment` (a `pl.Clump`) at `arc_length` (m from end A along the reference); returns its
    /// index (the row of `State.attachment_forces`).
    fn attach(&mut self, arc_length: f64, attachment: &Clump) -> PyResult<usize> {
        let c = attachment.0;
        let placed = pipelay::rod::attachment::Attachment::new(
            arc_length,
            c.mass,
            c.volume,
            c.drag_area,
            c.added_mass,
        )
        .map_err(to_py)?;
        self.0.attach(placed).map_err(to_py)
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
    pub fn r#static(&self, py: Python<'_>, steps: Option<i64>, start: &str) -> PyResult<State> {
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
        Ok(State::from_static(
            model,
            solution.configuration,
            &solution.response,
            1.0,
            solution.iterations,
            solution.steps,
        ))
    }

    /// The reference configuration at rest, without solving.
    fn rest(&self) -> State {
        let config = Configuration::reference(&self.0);
        let response = Response::new(&self.0, &config);
        State::from_static(&self.0, config, &response, 0.0, 0, 0)
    }

    /// Attaches a vessel at `end` (usually "B"): the pipe's end is clamped to the vessel's reference point CO at
    /// the fixed angle β (`angle`, zyx Euler angles of R_b^t, rad). `eta` (6,) is the starting pose, its z at the
    /// sea surface z = −depth within 10 m (at most half the depth) and above the seabed; in statics
    /// heave, roll and pitch settle and surge, sway and yaw are held at eta by thrust (reported as
    /// `state.tau`), unless the controller is active at t = 0. Until the controller starts, simulations keep
    /// applying the holding thrust of their starting state. `environment`: pl.Force objects (body frame).
    /// `lay`: a pl.SLay, pl.JLay or pl.ReelLay holding the pipe at the tensioner, tower or ramp (then `angle` stays
    /// zero).
    /// `winch`: a pl.Winch, the A&R winch the line is handed over to (a stage with hold="winch"); a line whose
    /// top segment is a cable is held by it from the start.
    #[pyo3(signature = (end, vessel, *, eta, angle=None, controller=None, environment=None, lay=None, winch=None, hull_loads=false))]
    #[allow(clippy::too_many_arguments)]
    fn attach_vessel(
        &mut self,
        end: &str,
        vessel: &Vessel,
        eta: &Bound<'_, PyAny>,
        angle: Option<&Bound<'_, PyAny>>,
        controller: Option<&PyPid>,
        environment: Option<&Bound<'_, PyAny>>,
        lay: Option<&Bound<'_, PyAny>>,
        winch: Option<&crate::stages::Winch>,
        hull_loads: bool,
    ) -> PyResult<()> {
        let lay = lay.map(crate::lay::equipment).transpose()?;
        let mut forces = Vec::new();
        if let Some(items) = environment {
            for item in items.try_iter()? {
                let item = item?;
                let force = item.cast::<PyForce>().map_err(|_| {
                    input(
                        "environment",
                        item.repr().map_or("?".into(), |r| r.to_string()),
                        "must be a sequence of pl.Force",
                    )
                })?;
                forces.push(force.get().0);
            }
        }
        let eta = nalgebra::Vector6::from(array::<6>(eta, "eta")?);
        let angle = angle
            .map(|a| vector3(a, "angle"))
            .transpose()?
            .unwrap_or_else(Vector3::zeros);
        let previous = self.0.vessel.clone();
        self.0
            .attach_vessel(
                end,
                vessel.0.clone(),
                eta,
                angle,
                controller.map(|c| c.0.clone()),
                forces,
                lay,
            )
            .map_err(to_py)?;
        if hull_loads {
            if let Err(error) = self.0.enable_hull_loads() {
                self.0.vessel = previous;
                return Err(to_py(error));
            }
        }
        let Some(winch) = winch else {
            return Ok(());
        };
        let rod = &self.0.rod;
        let top = rod.element_count() - 1;
        let wire = match (&winch.wire, rod.section(top)) {
            (Some(wire), _) => wire.clone(),
            (None, section) if section.cable => section.clone(),
            (None, _) => {
                self.0.vessel = previous;
                return Err(input(
                    "winch.wire",
                    "None, with pipe at the line's top",
                    "must be the wire's section: pl.Winch(..., wire=pl.Section.cable(...))",
                ));
            }
        };
        let mut engine = winch.winch.clone();
        if engine.element_length == 0.0 {
            engine.element_length = rod.elements[top].length;
        }
        let outcome = self.0.add_winch(engine, wire);
        if outcome.is_err() {
            // A refused winch leaves the model as it was.
            self.0.vessel = previous;
        }
        outcome.map_err(to_py)
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
    /// The vessel attached to the model, if any.
    #[getter]
    fn vessel(&self) -> Option<Vessel> {
        self.0.vessel.as_ref().map(|a| Vessel(a.vessel.clone()))
    }
    /// The reel-lay equipment the vessel holds the pipe with (its reeling and ramp), None for other lay
    /// equipment or none.
    #[getter]
    fn reel_lay(&self) -> Option<crate::reeling::ReelLay> {
        let lay = self.0.vessel.as_ref()?.lay.as_ref()?;
        crate::reeling::ReelLay::of(lay)
    }
    /// Gravitational acceleration (m/s²).
    #[getter]
    fn gravity(&self) -> f64 {
        self.0.gravity
    }
    /// Submerged weight per unit length (N/m): (mass − ρ_w · displaced_area) g; for a line of segments, its
    /// length-weighted mean.
    #[getter]
    fn submerged_weight(&self) -> f64 {
        self.0.mean_submerged_weight()
    }
}
