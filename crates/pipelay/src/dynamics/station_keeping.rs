//! Station keeping over a step, for a sampled controller: the loop a DP system runs once per step: measure, estimate (the observer), command (the PID on
//! the estimate), allocate (the QP) and deliver (each thruster's lag and rates), the delivered τ held over the
//! step. Its work enters the energy ledger as supplied, as the environment's does.
//!
//! The passivity certificate of the implicit PID (its storage ½η̃ᵀK_pη̃ and damping η̃̇ᵀK_dη̃̇ at the step's
//! midpoint) does not carry over to the sampled loop: the thrust is computed from the state at the step's
//! start (or from an estimate), lags the command and saturates. What holds exactly, step by step, is the
//! plant's balance: the pipe–vessel system's energy changes by the delivered thrust's work plus the
//! environment's, less what it dissipates.
// Indexing cannot go out of bounds here: 6-vectors of the vessel's DOFs and per-thruster lists built together.
#![allow(clippy::indexing_slicing)]
use crate::error::Result;
use crate::model::Model;
use crate::vessel::allocation::{allocate, Previous};
use crate::vessel::control::{clamp_integral, eta_error, pid_thrust, thrust_only, Pid};
use crate::vessel::observer::PassiveObserver;
use crate::vessel::thrusters::{generalised_force, ThrusterState};
use crate::vessel::VesselAttachment;
use nalgebra::{Matrix3, Vector3, Vector6};

/// What a sampled controller decided for the current step, kept until the step is accepted.
#[derive(Debug, Clone)]
struct Decision {
    thrusters: Vec<ThrusterState>,
    integral: Vector6<f64>,
    measured: Vector3<f64>,
    observer: Option<PassiveObserver>,
}

/// The sampled DP loop's state.
#[derive(Debug, Clone)]
pub struct StationKeeping {
    /// Each thruster's delivered thrust and azimuth (empty without allocation).
    pub thrusters: Vec<ThrusterState>,
    pub observer: Option<PassiveObserver>,
    /// The controller's command and the thrust delivered over the last step (body frame).
    pub tau_commanded: Vector6<f64>,
    pub tau: Vector6<f64>,
    /// Whether the last allocation could not deliver its command.
    pub saturated: bool,
    /// An external controller's last command (body frame), held until its next ([`Self::command`]).
    pub external_command: Option<Vector6<f64>>,
    decision: Option<Decision>,
}

/// (x, y, ψ) of a pose η.
fn planar(eta: &Vector6<f64>) -> Vector3<f64> {
    Vector3::new(eta[0], eta[1], eta[5])
}

/// The surge–sway–yaw block of a 6×6 matrix.
fn planar_block(m: &nalgebra::Matrix6<f64>) -> Matrix3<f64> {
    let dofs = [0, 1, 5];
    Matrix3::from_fn(|i, j| m[(dofs[i], dofs[j])])
}

impl StationKeeping {
    /// The loop of `model`'s sampled controller, if it has one, starting from the low-frequency pose `eta`
    /// and velocity `velocity` with the thrusters delivering `hold_thrust`.
    pub fn new(
        model: &Model,
        eta: &Vector6<f64>,
        velocity: &Vector6<f64>,
        hold_thrust: &Vector6<f64>,
    ) -> Result<Option<Self>> {
        let Some(attachment) = model.vessel.as_ref() else {
            return Ok(None);
        };
        let Some(controller) = attachment.controller.as_ref().filter(|c| c.is_sampled()) else {
            return Ok(None);
        };
        let vessel = &attachment.vessel;
        let thrusters = if controller.allocation {
            allocate(&vessel.thrusters, hold_thrust, None)?.states()
        } else {
            Vec::new()
        };
        let observer = match &controller.observer {
            Some(settings) => {
                let period = settings.wave_period.unwrap_or_else(|| peak_period(model));
                Some(PassiveObserver::new(
                    settings,
                    &planar_block(&vessel.mass()),
                    &planar_block(&vessel.damping),
                    period,
                    planar(eta),
                    planar(velocity),
                )?)
            }
            None => None,
        };
        let tau = if controller.allocation {
            generalised_force(&vessel.thrusters, &thrusters)
        } else {
            *hold_thrust
        };
        Ok(Some(StationKeeping {
            thrusters,
            observer,
            tau_commanded: *hold_thrust,
            tau,
            saturated: false,
            external_command: controller.external.as_ref().map(|_| *hold_thrust),
            decision: None,
        }))
    }

    /// An external controller's command for the step from `time` to `time` + `dt` (s), from the pose `eta` and velocity
    /// `velocity` it sees (the observer's estimate, if there is one, instead): called once per time step, before
    /// its substeps, so that a controller with a state of its own is stepped once per step.
    pub fn command(
        &mut self,
        controller: &Pid,
        time: f64,
        dt: f64,
        eta: &Vector6<f64>,
        velocity: &Vector6<f64>,
    ) -> Result<()> {
        if let Some(external) = &controller.external {
            let (seen, seen_velocity) = self.estimate().unwrap_or((*eta, *velocity));
            self.external_command = Some(external.over(time, dt, &seen, &seen_velocity)?);
        }
        Ok(())
    }

    /// The estimate (η̂, ν̂) of the low-frequency pose and velocity, if there is an observer.
    pub fn estimate(&self) -> Option<(Vector6<f64>, Vector6<f64>)> {
        self.observer.as_ref().map(|o| {
            (
                Vector6::new(o.pose.x, o.pose.y, 0.0, 0.0, 0.0, o.pose.z),
                Vector6::new(o.velocity.x, o.velocity.y, 0.0, 0.0, 0.0, o.velocity.z),
            )
        })
    }

    /// Decides the thrust for a step of `dt` from the state at its start: the vessel's total pose `total`
    /// (what is measured), its low-frequency pose `eta` and velocity `velocity` (what the controller sees
    /// without an observer), the PID's integral `integral` and the reference `reference` at the step.
    /// Returns the thrust held over the step (body frame).
    #[allow(clippy::too_many_arguments)]
    pub fn decide(
        &mut self,
        attachment: &VesselAttachment,
        controller: &Pid,
        total: &Vector6<f64>,
        eta: &Vector6<f64>,
        velocity: &Vector6<f64>,
        integral: &Vector6<f64>,
        reference: &(Vector6<f64>, Vector6<f64>),
        dt: f64,
    ) -> Result<Vector6<f64>> {
        let mut observer = self.observer.clone();
        let measured = match observer.as_mut() {
            Some(observer) => observer.measure(&planar(total)),
            None => planar(total),
        };
        let (seen, seen_velocity) = self.estimate().unwrap_or((*eta, *velocity));
        let command = match self.external_command {
            Some(command) => thrust_only(command, controller.thrust_limit.as_ref()),
            None => pid_thrust(controller, &seen, &seen_velocity, integral, reference),
        };
        let error = eta_error(&seen, &reference.0);
        let integral_next = clamp_integral(controller, &(integral + dt * error));
        let thrusters = &attachment.vessel.thrusters;
        let (states, tau, saturated) = if controller.allocation {
            let previous = Previous {
                states: &self.thrusters,
                dt,
            };
            let allocation = allocate(thrusters, &command, Some(&previous))?;
            let delivered: Vec<ThrusterState> = thrusters
                .iter()
                .zip(&self.thrusters)
                .zip(allocation.states())
                .map(|((thruster, now), commanded)| thruster.respond(now, &commanded, dt))
                .collect();
            let tau = generalised_force(thrusters, &delivered);
            (delivered, tau, allocation.saturated)
        } else {
            (Vec::new(), command, false)
        };
        self.tau_commanded = command;
        self.tau = tau;
        self.saturated = saturated;
        self.decision = Some(Decision {
            thrusters: states,
            integral: integral_next,
            measured,
            observer,
        });
        Ok(tau)
    }

    /// Accepts the step of `dt` decided last: the thrusters' new states, and the observer advanced over it
    /// with its measurement and the delivered thrust. Returns the PID's integral at the step's end.
    pub fn accept(&mut self, dt: f64) -> Option<Vector6<f64>> {
        let decision = self.decision.take()?;
        self.thrusters = decision.thrusters;
        self.observer = decision.observer;
        if let Some(observer) = self.observer.as_mut() {
            observer.advance(&decision.measured, &planar(&self.tau), dt);
        }
        Some(decision.integral)
    }
}

/// The peak period of the model's sea (s): its largest component's, else 10 s.
fn peak_period(model: &Model) -> f64 {
    model
        .waves
        .as_ref()
        .and_then(|field| {
            field
                .components()
                .iter()
                .max_by(|a, b| a.amplitude.total_cmp(&b.amplitude))
                .map(|c| std::f64::consts::TAU / c.frequency)
        })
        .map_or(10.0, |period| period.min(60.0))
}
