//! Python classes Winch, Stage and Stages: the A&R winch on the vessel and the stages of a lay.
use crate::convert::vector3;
use crate::errors::{input, to_py};
use crate::structure::{Clump, Section};
use pipelay::dynamics::stages::{Hold, Stage as EngineStage};
use pipelay::vessel::winch::{Drive, Winch as EngineWinch};
use pyo3::prelude::*;

/// An abandonment and recovery (A&R) winch on the vessel. `position` (body frame, m): where its wire enters
/// the firing line, on the line through the tensioner (or tower exit) along the pipe, ahead of it (forward
/// in an S-lay, up the tower in a J-lay). `tension_limit` (N): the wire's rating, None for none. `wire`: the
/// wire's `pl.Section.cable` (default: the line's top segment, if it is a cable). `element_length` (m): of the
/// wire elements pay-out adds (default: the line's top element's). `head`: a `pl.Clump`, the laydown head
/// fitted to the pipe's end at the hand-over, a point body; with `head_length` and `head_diameter` (m) a body:
/// an element of the line from the pipe's end to the wire, of the pipe's stiffness and the head's mass,
/// volume, drag and added mass, whose surface tapers from `head_diameter` at the pipe's end to the wire's at its
/// padeye (the rollers and the seabed see it). The drive: `speed_limit` (m/s, default 1), `acceleration_limit`
/// (m/s², default 0.5) and `tension_band` (N, default 50 kN): in constant-tension mode (`pl.Stage(...,
/// winch_tension=)`) the winch stands within the set tension ± band and runs at full speed 2·band away from
/// it; with a `tension_limit` it renders from tension_limit − band, at full speed at the limit. Give it to
/// `Model.attach_vessel(..., winch=)`.
#[pyclass(module = "pipelay", name = "Winch", frozen)]
#[derive(Clone)]
pub struct Winch {
    pub winch: EngineWinch,
    pub wire: Option<pipelay::rod::section::Section>,
}

#[pymethods]
impl Winch {
    #[new]
    #[pyo3(signature = (position, tension_limit=None, *, wire=None, element_length=None, head=None, head_length=None, head_diameter=None, speed_limit=None, acceleration_limit=None, tension_band=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        position: &Bound<'_, PyAny>,
        tension_limit: Option<f64>,
        wire: Option<&Section>,
        element_length: Option<f64>,
        head: Option<&Clump>,
        head_length: Option<f64>,
        head_diameter: Option<f64>,
        speed_limit: Option<f64>,
        acceleration_limit: Option<f64>,
        tension_band: Option<f64>,
    ) -> PyResult<Self> {
        let defaults = Drive::default();
        let drive = Drive {
            speed_limit: speed_limit.unwrap_or(defaults.speed_limit),
            acceleration_limit: acceleration_limit.unwrap_or(defaults.acceleration_limit),
            tension_band: tension_band.unwrap_or(defaults.tension_band),
        }
        .checked()
        .map_err(to_py)?;
        let position = vector3(position, "position")?;
        // An element length of 0 stands for "the line's top element's", resolved by attach_vessel.
        if let Some(length) = element_length {
            pipelay::error::positive("element_length", length, "m").map_err(to_py)?;
        }
        let winch = EngineWinch::checked(
            position,
            tension_limit,
            element_length.unwrap_or(1.0),
            head.map(|h| h.0),
        )
        .map_err(to_py)?;
        let winch = EngineWinch {
            element_length: element_length.unwrap_or(0.0),
            drive,
            ..winch
        };
        let winch = match (head_length, head_diameter) {
            (None, None) => winch,
            (Some(length), Some(diameter)) => {
                winch.with_head_body(length, diameter).map_err(to_py)?
            }
            (Some(length), None) => {
                return Err(input(
                    "head_diameter",
                    "missing",
                    &format!("a head body of head_length {length} m needs its diameter (m)"),
                ))
            }
            (None, Some(diameter)) => {
                return Err(input(
                    "head_length",
                    "missing",
                    &format!("a head body of head_diameter {diameter} m needs its length (m)"),
                ))
            }
        };
        Ok(Winch {
            winch,
            wire: wire.map(|w| w.0.clone()),
        })
    }

    /// Where the wire enters the firing line (3,) (body frame, m).
    #[getter]
    fn position(&self) -> [f64; 3] {
        self.winch.position.into()
    }
    /// The wire's rating (N), None for none.
    #[getter]
    fn tension_limit(&self) -> Option<f64> {
        self.winch.tension_limit
    }
    /// The head body's length and diameter (m), None for a point head.
    #[getter]
    fn head_body(&self) -> Option<(f64, f64)> {
        self.winch.head_body.map(|b| (b.length, b.diameter))
    }
    /// The drive's largest speed either way (m/s).
    #[getter]
    fn speed_limit(&self) -> f64 {
        self.winch.drive.speed_limit
    }
    /// The drive's largest change of speed (m/s²).
    #[getter]
    fn acceleration_limit(&self) -> f64 {
        self.winch.drive.acceleration_limit
    }
    /// The constant-tension mode's band and the rendering's, below the limit (N).
    #[getter]
    fn tension_band(&self) -> f64 {
        self.winch.drive.tension_band
    }

    fn __repr__(&self) -> String {
        format!(
            "Winch(position={:?}, tension_limit={:?})",
            self.winch.position.as_slice(),
            self.winch.tension_limit
        )
    }
}

/// One stage of a lay: a `name`, a `duration` (s, a whole number of time steps) and what changes at its
/// start; what it leaves at None carries on from the stage before. `pay_out`: the tensioner's pay-out speed
/// (m/s; negative: pay-in). `route_speed`: the DP reference's speed along its route (m/s). `hold`:
/// "tensioner" or "winch" — the first stage the winch holds starts with the hand-over of the line to it.
/// `winch_speed`: the winch's pay-out speed once it holds (m/s; negative: haul-in; 0: the brake holds; within
/// its speed limit, and its tension limit rendered). `winch_tension`: the tension the winch holds in
/// constant-tension mode once it holds (N), within its drive's limits (`pl.Winch`).
/// `setpoint`: a new DP set-point (x, y, ψ) (m, rad): the reference jumps there and waits, until a route speed
/// (of this stage or a later one) moves it along ψ. `statics`: the stage starts from statics of its own
/// configuration (the line and vessel as they are, brought to rest in equilibrium, the vessel held where it is;
/// the energy this changes is booked as work supplied; its pay-out or winch speed ramps up from rest); calm
/// water only.
/// `ramp` (s): the time the stage's speed changes take (default 10 s, or the duration if shorter): a step of
/// the pay-out speed would send an axial wave of force √(EA·m)·Δv down the pipe.
#[pyclass(module = "pipelay", name = "Stage", frozen)]
#[derive(Clone)]
pub struct Stage(pub EngineStage);

#[pymethods]
impl Stage {
    #[new]
    #[pyo3(signature = (name, duration=None, *, pay_out=None, route_speed=None, hold=None, winch_speed=None, winch_tension=None, setpoint=None, statics=false, ramp=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        name: String,
        duration: Option<f64>,
        pay_out: Option<f64>,
        route_speed: Option<f64>,
        hold: Option<&str>,
        winch_speed: Option<f64>,
        winch_tension: Option<f64>,
        setpoint: Option<&Bound<'_, PyAny>>,
        statics: bool,
        ramp: Option<f64>,
    ) -> PyResult<Self> {
        let setpoint = setpoint
            .map(|p| crate::convert::array::<3>(p, "setpoint"))
            .transpose()?;
        let Some(duration) = duration else {
            return Err(input(
                "duration",
                "missing",
                &format!("stage {name:?} needs a duration (s)"),
            ));
        };
        let hold = hold
            .map(|h| Hold::parse("hold", h))
            .transpose()
            .map_err(to_py)?;
        let stage = EngineStage {
            name,
            duration,
            pay_out,
            route_speed,
            hold,
            winch_speed,
            winch_tension,
            setpoint,
            statics,
            ramp,
        };
        // Checked alone here; against the model when a simulation takes the stages.
        stage.check("").map_err(to_py)?;
        Ok(Stage(stage))
    }

    #[getter]
    fn name(&self) -> String {
        self.0.name.clone()
    }
    /// Duration (s).
    #[getter]
    fn duration(&self) -> f64 {
        self.0.duration
    }
    #[getter]
    fn pay_out(&self) -> Option<f64> {
        self.0.pay_out
    }
    #[getter]
    fn route_speed(&self) -> Option<f64> {
        self.0.route_speed
    }
    #[getter]
    fn hold(&self) -> Option<&'static str> {
        self.0.hold.map(|h| match h {
            Hold::Tensioner => "tensioner",
            Hold::Winch => "winch",
        })
    }
    #[getter]
    fn winch_speed(&self) -> Option<f64> {
        self.0.winch_speed
    }
    /// The tension the winch holds in constant-tension mode (N), None for none.
    #[getter]
    fn winch_tension(&self) -> Option<f64> {
        self.0.winch_tension
    }
    /// The DP set-point the stage moves the reference to, (x, y, ψ) (m, rad), None for none.
    #[getter]
    fn setpoint(&self) -> Option<[f64; 3]> {
        self.0.setpoint
    }
    /// Whether the stage starts from statics of its configuration.
    #[getter]
    fn statics(&self) -> bool {
        self.0.statics
    }
    /// The time the stage's speed changes take (s).
    #[getter]
    fn ramp(&self) -> f64 {
        self.0.ramp_time()
    }

    fn __repr__(&self) -> String {
        format!("Stage({:?}, duration={})", self.0.name, self.0.duration)
    }
}

/// The stages of a lay, in order: `Model.simulation(state, dt, stages=)` runs through them in one run.
#[pyclass(module = "pipelay", name = "Stages", frozen)]
#[derive(Clone)]
pub struct Stages(pub Vec<EngineStage>);

#[pymethods]
impl Stages {
    #[new]
    fn new(stages: &Bound<'_, PyAny>) -> PyResult<Self> {
        let mut list = Vec::new();
        let iterator = stages.try_iter().map_err(|_| {
            input(
                "stages",
                stages.repr().map_or("?".into(), |r| r.to_string()),
                "must be a sequence of pl.Stage (a list, even of one)",
            )
        })?;
        for (k, item) in iterator.enumerate() {
            let item = item?;
            let stage = item.cast::<Stage>().map_err(|_| {
                input(
                    &format!("stages[{k}]"),
                    item.repr().map_or("?".into(), |r| r.to_string()),
                    "must be a pl.Stage",
                )
            })?;
            list.push(stage.get().0.clone());
        }
        pipelay::dynamics::stages::Stages::new(list.clone(), 0.0).map_err(to_py)?;
        Ok(Stages(list))
    }

    fn __len__(&self) -> usize {
        self.0.len()
    }

    /// The stage at `index` (negative: from the end).
    fn __getitem__(&self, index: isize) -> PyResult<Stage> {
        let count = self.0.len() as isize;
        let at = if index < 0 { index + count } else { index };
        usize::try_from(at)
            .ok()
            .and_then(|k| self.0.get(k))
            .map(|stage| Stage(stage.clone()))
            .ok_or_else(|| {
                pyo3::exceptions::PyIndexError::new_err(format!(
                    "stage index {index} out of range for {count} stages"
                ))
            })
    }

    /// The stages' names.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.0.iter().map(|s| s.name.clone()).collect()
    }

    /// The total duration (s).
    #[getter]
    fn duration(&self) -> f64 {
        self.0.iter().map(|s| s.duration).sum()
    }

    fn __repr__(&self) -> String {
        format!("Stages({:?})", self.names())
    }
}
