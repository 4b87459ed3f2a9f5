//! The stages of a lay: one run through a sequence of durations, each setting what changes from its start —
//! the pay-out speed at the tensioner, the route speed of the DP reference, who holds the line (the tensioner
//! or the A&R winch) and the winch's speed. What a stage does not set carries on from the stage before.
//!
//! The stages become functions of time on the model ([`Stages::apply`]): a piecewise-constant pay-out speed
//! and a route in legs. Only the hand-over changes the model itself, at the start of the first stage the winch
//! holds ([`crate::dynamics::hand_over`]); so a run resumed in the middle of a stage continues as the original.
// Indexing cannot go out of bounds here: `starts` holds one more entry than `stages`, `holds` one per stage.
#![allow(clippy::indexing_slicing)]
use crate::error::{Error, Result};
use crate::model::{Model, PayOutSpeed};
use crate::table::Leg;
use crate::vessel::control::Reference;
use nalgebra::Vector6;

/// Who holds the line's top end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hold {
    /// The tensioner of an S-lay or the tower clamp of a J-lay holds the pipe.
    Tensioner,
    /// The A&R winch holds its wire, fixed to the pipe's end.
    Winch,
}

impl Hold {
    /// "tensioner" or "winch".
    pub fn parse(key: &str, value: &str) -> Result<Self> {
        match value {
            "tensioner" => Ok(Hold::Tensioner),
            "winch" => Ok(Hold::Winch),
            other => Err(Error::input(
                key,
                format!("{other:?}"),
                "must be \"tensioner\" or \"winch\"",
            )),
        }
    }
}

/// One stage: a name, a duration (s) and what changes at its start.
#[derive(Debug, Clone, PartialEq)]
pub struct Stage {
    pub name: String,
    pub duration: f64,
    /// Pay-out speed at the tensioner (m/s; negative: pay-in).
    pub pay_out: Option<f64>,
    /// Speed of the DP reference along its route (m/s).
    pub route_speed: Option<f64>,
    pub hold: Option<Hold>,
    /// The winch's pay-out speed (m/s; negative: haul-in; zero: the brake holds).
    pub winch_speed: Option<f64>,
    /// The tension the winch holds in constant-tension mode (N): it renders above the band around it and hauls
    /// below (a later stage's `winch_speed` returns it to a commanded speed).
    pub winch_tension: Option<f64>,
    /// A new DP set-point (x, y (m), heading ψ (rad)): the reference jumps there and waits (until a route speed
    /// moves it along ψ).
    pub setpoint: Option<[f64; 3]>,
    /// Whether the stage starts from statics of its own configuration: the line and vessel as they are then,
    /// brought to rest in equilibrium (the vessel held where it is) before the stage's first step.
    pub statics: bool,
    /// The time the stage's speed changes take, from the speeds before (s); `None`: [`DEFAULT_RAMP`] or the
    /// duration if shorter.
    pub ramp: Option<f64>,
}

/// The time a stage's changes of speed take unless it says (s): tensioners, winches and DP references do not
/// change speed at once, and a step of the pay-out speed Δv sends an axial wave of force √(EA·m)·Δv down the
/// pipe (540 kN for 0.3 m/s on a 0.6 m steel pipe), which a ramp much longer than the pipe's axial period
/// 2L/c (under a second) avoids.
pub const DEFAULT_RAMP: f64 = 10.0;

impl Stage {
    /// A stage of `duration` (s) that changes nothing.
    pub fn lasting(name: String, duration: f64) -> Self {
        Stage {
            name,
            duration,
            pay_out: None,
            route_speed: None,
            hold: None,
            winch_speed: None,
            winch_tension: None,
            setpoint: None,
            statics: false,
            ramp: None,
        }
    }

    /// Checks the stage's own values: a positive, finite duration and finite speeds; errors name the key
    /// after `prefix` (e.g. "stages[2].").
    pub fn check(&self, prefix: &str) -> Result<()> {
        if !(self.duration.is_finite() && self.duration > 0.0) {
            return Err(Error::input(
                format!("{prefix}duration"),
                self.duration,
                "must be a positive, finite duration (s)",
            ));
        }
        for (key, value) in [
            ("pay_out", self.pay_out),
            ("route_speed", self.route_speed),
            ("winch_speed", self.winch_speed),
        ] {
            if let Some(value) = value.filter(|v| !v.is_finite()) {
                return Err(Error::input(
                    format!("{prefix}{key}"),
                    value,
                    "must be a finite speed (m/s)",
                ));
            }
        }
        if let Some(setpoint) = self.setpoint {
            crate::error::finite(&format!("{prefix}setpoint"), &setpoint)?;
        }
        if let Some(tension) = self.winch_tension {
            crate::error::positive(&format!("{prefix}winch_tension"), tension, "N")?;
            if self.winch_speed.is_some() {
                return Err(Error::input(
                    format!("{prefix}winch_tension"),
                    tension,
                    "gives the winch a tension to hold, and winch_speed a speed: give one of them",
                ));
            }
        }
        if let Some(ramp) = self.ramp {
            if !(ramp.is_finite() && (0.0..=self.duration).contains(&ramp)) {
                return Err(Error::input(
                    format!("{prefix}ramp"),
                    ramp,
                    format!("must be a time in [0, duration = {} s]", self.duration),
                ));
            }
        }
        Ok(())
    }

    /// The time its speed changes take (s).
    pub fn ramp_time(&self) -> f64 {
        self.ramp.unwrap_or(DEFAULT_RAMP.min(self.duration))
    }

    /// The leg of speed `speed` (m/s) this stage starts at `start` (s).
    fn leg(&self, start: f64, speed: f64) -> Leg {
        Leg {
            start,
            speed,
            ramp: self.ramp_time(),
        }
    }
}

/// A sequence of stages from a start time.
#[derive(Debug, Clone, PartialEq)]
pub struct Stages {
    pub stages: Vec<Stage>,
    /// Each stage's start time (s); the last entry is the end of the last stage.
    pub starts: Vec<f64>,
    /// Who holds the line in each stage.
    pub holds: Vec<Hold>,
}

impl Stages {
    /// Stages from `start_time` (s); each duration must be positive and finite.
    pub fn new(stages: Vec<Stage>, start_time: f64) -> Result<Self> {
        if stages.is_empty() {
            return Err(Error::input(
                "stages",
                "an empty list",
                "must hold at least one pl.Stage",
            ));
        }
        let mut starts = vec![start_time];
        for (k, stage) in stages.iter().enumerate() {
            stage.check(&format!("stages[{k}]."))?;
            let end = starts[k] + stage.duration;
            if !end.is_finite() {
                return Err(Error::input(
                    format!("stages[{k}].duration"),
                    stage.duration,
                    "must keep the stages' end finite (their durations add up beyond the largest number)",
                ));
            }
            starts.push(end);
        }
        Ok(Stages {
            holds: vec![Hold::Tensioner; stages.len()],
            stages,
            starts,
        })
    }

    /// The index of the stage a record at `time` belongs to: the stage whose steps end there (a record at a
    /// boundary closes the stage before it; the first record opens stage 0); past the end, the last.
    pub fn index_at(&self, time: f64) -> usize {
        let tolerance = 1e-9 * (1.0 + time.abs());
        self.starts[1..]
            .iter()
            .position(|&end| time <= end + tolerance)
            .unwrap_or(self.stages.len() - 1)
    }

    /// The index of the stage a step from `time` is taken in.
    pub fn stepping_at(&self, time: f64) -> usize {
        let tolerance = 1e-9 * (1.0 + time.abs());
        self.starts[1..]
            .iter()
            .position(|&end| time < end - tolerance)
            .unwrap_or(self.stages.len() - 1)
    }

    /// The end of the last stage (s).
    pub fn end(&self) -> f64 {
        self.starts[self.stages.len()]
    }

    /// Checks the stages against `model` stepped with `dt` (s) and sets them on it: the pay-out speed becomes
    /// the stages' (pay-out is set at the vessel's end if a stage needs it) and the DP reference takes their
    /// set-points and route speeds. Errors name the stage's key: `stages[k].hold` for a winch that is not there, and so on.
    pub fn apply(&mut self, model: &mut Model, dt: f64) -> Result<()> {
        let winch = model.vessel.as_ref().and_then(|v| v.winch.as_ref());
        let mut hold = if winch.is_some_and(|w| w.holds) {
            Hold::Winch
        } else {
            Hold::Tensioner
        };
        let mut speed = match model.pay_out.as_ref().map(|p| &p.speed) {
            Some(PayOutSpeed::Constant(v)) => *v,
            _ => 0.0,
        };
        let mut speeds = Vec::with_capacity(self.stages.len());
        let mut modes = Vec::new();
        let mut route = Vec::new();
        let mut pays_out = false;
        for (k, stage) in self.stages.iter().enumerate() {
            let key = |name: &str| format!("stages[{k}].{name}");
            let steps = stage.duration / dt;
            if (steps - steps.round()).abs() > 1e-6 * steps.max(1.0) {
                return Err(Error::input(
                    key("duration"),
                    stage.duration,
                    format!("must be a whole number of time steps dt = {dt} s"),
                ));
            }
            match (stage.hold, hold) {
                (Some(Hold::Winch), _) if winch.is_none() => {
                    return Err(Error::input(
                        key("hold"),
                        "\"winch\"",
                        "needs a winch on the vessel: attach_vessel(..., winch=pl.Winch(...))",
                    ))
                }
                (Some(Hold::Tensioner), Hold::Winch) => {
                    // The tensioner has taken the pipe back at rest (the hand-back, when the winch hauled the
                    // pipe's end to the hold point) and starts from there.
                    hold = Hold::Tensioner;
                    speed = 0.0;
                    pays_out = true;
                }
                (Some(Hold::Winch), Hold::Tensioner) => {
                    hold = Hold::Winch;
                    // The winch takes over at the tensioner's speed and ramps to rest (its brake then holds)
                    // unless the stage gives it a speed.
                    speed = 0.0;
                    pays_out = true;
                }
                _ => {}
            }
            if let Some(value) = stage.winch_speed {
                if winch.is_none() {
                    return Err(Error::input(
                        key("winch_speed"),
                        value,
                        "needs a winch on the vessel: attach_vessel(..., winch=pl.Winch(...))",
                    ));
                }
                if hold != Hold::Winch {
                    return Err(Error::input(
                        key("winch_speed"),
                        value,
                        "the tensioner holds the line in this stage: hand over first (hold=\"winch\")",
                    ));
                }
                if let Some(limit) = winch.map(|w| w.drive.speed_limit) {
                    if value.abs() > limit {
                        return Err(Error::input(
                            key("winch_speed"),
                            value,
                            format!("must be within the winch's speed_limit, ±{limit} m/s"),
                        ));
                    }
                }
                speed = value;
                pays_out = true;
                modes.push((self.starts[k], None));
            }
            if let Some(value) = stage.winch_tension {
                if winch.is_none() || hold != Hold::Winch {
                    return Err(Error::input(
                        key("winch_tension"),
                        value,
                        "needs the winch to hold the line in this stage: hand over first (hold=\"winch\")",
                    ));
                }
                pays_out = true;
                modes.push((self.starts[k], Some(value)));
            }
            if let Some(value) = stage.pay_out {
                if hold == Hold::Winch {
                    return Err(Error::input(
                        key("pay_out"),
                        value,
                        "the winch holds the line in this stage: set winch_speed",
                    ));
                }
                speed = value;
                pays_out = true;
            }
            if stage.setpoint.is_some() || stage.route_speed.is_some() {
                route.push(k);
            }
            if stage.statics && model.waves.is_some() {
                return Err(Error::input(
                    key("statics"),
                    "true, in waves",
                    "a stage can start from statics in calm water only (statics has no waves)",
                ));
            }
            let handed_back = k > 0 && hold == Hold::Tensioner && self.holds[k - 1] == Hold::Winch;
            self.holds[k] = hold;
            if stage.statics || handed_back {
                // Statics bring the line to rest: the stage's speed ramps up from zero, not from the speed
                // before (a pipe at rest fed at speed v takes an axial shock √(EA·m)·v).
                speeds.push(Leg {
                    start: self.starts[k],
                    speed: 0.0,
                    ramp: 0.0,
                });
            }
            speeds.push(stage.leg(self.starts[k], speed));
        }
        if pays_out {
            self.set_pay_out(model, speeds)?;
        }
        if let Some(winch) = model.vessel.as_mut().and_then(|v| v.winch.as_mut()) {
            winch.modes = modes;
        }
        if let Some(&first) = route.first() {
            let key = if self.stages[first].setpoint.is_some() {
                format!("stages[{first}].setpoint")
            } else {
                format!("stages[{first}].route_speed")
            };
            let controller = model
                .vessel
                .as_mut()
                .and_then(|v| v.controller.as_mut())
                .ok_or_else(|| {
                    Error::input(
                        &key,
                        "a DP change",
                        "needs a DP controller on the vessel: attach_vessel(..., controller=pl.PID(...))",
                    )
                })?;
            controller.reference = self.staged_reference(&controller.reference, &route)?;
        }
        Ok(())
    }

    /// The DP reference through the stages: from `base`, each of the stages `route` (by index) that sets a
    /// set-point starts a new piece there, and one that sets a route speed changes the speed from its start.
    fn staged_reference(&self, base: &Reference, route: &[usize]) -> Result<Reference> {
        let mut pieces = vec![(f64::NEG_INFINITY, base.clone())];
        for &k in route {
            let start = self.starts[k];
            let (setpoint, speed) = (self.stages[k].setpoint, self.stages[k].route_speed);
            if let Some([x, y, heading]) = setpoint {
                let fixed = Vector6::new(x, y, 0.0, 0.0, 0.0, heading);
                pieces.push((start, Reference::Fixed(fixed)));
            }
            if let Some(speed) = speed {
                let leg = self.stages[k].leg(start, speed);
                let key = format!("stages[{k}].route_speed");
                if let Some((_, last)) = pieces.last_mut() {
                    *last = last.with_speed_changes(&[leg], &key)?;
                }
            }
        }
        Ok(match pieces.len() {
            1 => pieces.swap_remove(0).1,
            _ => Reference::Pieces(pieces),
        })
    }

    /// Sets the stages' pay-out speeds on the model, paying out at the vessel's end if it does not yet.
    fn set_pay_out(&self, model: &mut Model, speeds: Vec<Leg>) -> Result<()> {
        if let Some(pay_out) = &model.pay_out {
            if let PayOutSpeed::Function(_) = pay_out.speed {
                return Err(Error::input(
                    "stages",
                    "stages that set a pay-out speed, on a model whose pay-out speed is a function of time",
                    "give the speed one way: a number in pay_out, or the stages",
                ));
            }
            if pay_out.at_start {
                return Err(Error::input(
                    "stages",
                    "stages that pay out, on a model paying out at end A",
                    "stages pay out at the vessel's end B",
                ));
            }
        } else {
            model.pay_out("B", PayOutSpeed::Constant(0.0))?;
        }
        if let Some(pay_out) = model.pay_out.as_mut() {
            pay_out.speed = PayOutSpeed::Staged(speeds);
        }
        Ok(())
    }

    /// The stage that starts at `time` (s) from statics of its configuration, if one does: a step from its start
    /// (a run resumed within the stage does not start it again).
    pub fn statics_due(&self, time: f64) -> Option<usize> {
        let tolerance = 1e-9 * (1.0 + time.abs());
        let k = self.stepping_at(time);
        (self.stages[k].statics && (time - self.starts[k]).abs() <= tolerance).then_some(k)
    }

    /// Whether the line must be handed over to the winch before a step from `time` (s): the stage holds it by
    /// the winch, and the winch neither holds it yet nor has handed it back.
    pub fn hand_over_due(&self, model: &Model, time: f64) -> bool {
        let done = model
            .vessel
            .as_ref()
            .and_then(|v| v.winch.as_ref())
            .is_some_and(|w| w.holds || w.hand_back.is_some());
        !done && self.holds[self.stepping_at(time)] == Hold::Winch
    }

    /// Checks that the tensioner holds the line when a step from `time` (s) is in a stage where it should after
    /// the winch held it: the winch must have hauled the pipe's end back to the hold point by then (the
    /// hand-back). `remaining`: how much more wire there is to haul in (m), if known.
    pub fn check_handed_back(
        &self,
        model: &Model,
        time: f64,
        remaining: Option<f64>,
    ) -> Result<()> {
        let k = self.stepping_at(time);
        let holds = model
            .vessel
            .as_ref()
            .and_then(|v| v.holding_winch())
            .is_some();
        if !holds || self.holds[k] != Hold::Tensioner {
            return Ok(());
        }
        let left = remaining.map_or_else(
            || "the winch's wire is still out".to_string(),
            |r| format!("{r:.3} m of wire is still out beyond the hold point"),
        );
        Err(Error::input(
            format!("stages[{k}].hold"),
            format!("\"tensioner\" at t = {time} s"),
            format!(
                "the tensioner takes the pipe back when the winch has hauled its end to the hold point, and \
                 {left}: haul in longer or faster before this stage"
            ),
        ))
    }

    /// After the hand-back at `time` (s): the tensioner holds the pipe at rest until the next stage that
    /// holds it by the tensioner (the winch's speeds of the stages until then no longer pay anything out).
    pub fn rest_after_hand_back(&self, model: &mut Model, time: f64) {
        let next = self
            .starts
            .iter()
            .zip(&self.holds)
            .find(|&(&start, &hold)| start > time && hold == Hold::Tensioner)
            .map_or(f64::INFINITY, |(&start, _)| start);
        if let Some(PayOutSpeed::Staged(legs)) = model.pay_out.as_mut().map(|p| &mut p.speed) {
            legs.retain(|leg| leg.start < time || leg.start >= next);
            let at = legs.partition_point(|leg| leg.start < time);
            legs.insert(
                at,
                Leg {
                    start: time,
                    speed: 0.0,
                    ramp: 0.0,
                },
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stage(name: &str, duration: f64) -> Stage {
        Stage::lasting(name.into(), duration)
    }

    #[test]
    fn records_and_steps_find_their_stage() {
        let stages = Stages::new(vec![stage("a", 1.0), stage("b", 2.0)], 10.0).unwrap();
        assert_eq!(stages.starts, vec![10.0, 11.0, 13.0]);
        assert_eq!(stages.index_at(10.0), 0);
        assert_eq!(stages.index_at(11.0), 0);
        assert_eq!(stages.index_at(11.05), 1);
        assert_eq!(stages.index_at(99.0), 1);
        assert_eq!(stages.stepping_at(10.95), 0);
        assert_eq!(stages.stepping_at(11.0), 1);
        assert_eq!(stages.stepping_at(13.0), 1);
        assert!(Stages::new(vec![stage("a", 0.0)], 0.0).is_err());
        assert!(Stages::new(vec![], 0.0).is_err());
    }
}
