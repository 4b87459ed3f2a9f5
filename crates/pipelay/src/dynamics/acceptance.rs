//! Whether a converged step is accepted: Newton's residual is relative to the step's own force scale, so a step
//! that has blown up (positions of 1e51 m, energies of 1e144 J) can converge as well as a sound one. Before it
//! is committed a step must keep its energy balance and its motions within physical bounds; a rejected step is
//! retried in substeps (see [`super::integrator`]).
// Indexing cannot go out of bounds here: node and DOF indices of the mesh being stepped.
#![allow(clippy::indexing_slicing)]
use crate::dynamics::integrator::{Integrator, StepReport};
use crate::error::{Error, Result};
use nalgebra::Vector3;

/// The fastest any point of a pipe, wire or vessel may move (m/s): the axial wave speed of steel, √(E/ρ). A
/// material point moving at v carries an axial strain of about v/c, so no elastic line reaches it.
pub const MAX_SPEED: f64 = 5_200.0;
/// The fastest a node's frame may turn (rad/s): a pipe's surface at MAX_SPEED on a radius of a centimetre.
pub const MAX_TURN_RATE: f64 = MAX_SPEED / 0.01;
/// The largest energy error a step may make relative to the energy it works on (its kinetic and stored
/// energies before the step, the work supplied and dissipated in it): far above Newton's tolerance (a
/// converged step's error is the residual's work on the increments, ~1e-8 of it), far below a blow-up.
pub const LEDGER_TOLERANCE: f64 = 1e-6;

impl Integrator {
    /// Checks the converged step of size `dt` before it is committed: every node's and the vessel's velocity at
    /// the step's end finite and below [`MAX_SPEED`] (turn rates below [`MAX_TURN_RATE`]), and the step's
    /// energy error, the residual's work Σ rᵢ Δuᵢ on the increments of the free DOFs (the amount by which
    /// E(t+Δt) − E(t) misses the work booked, for the energy–momentum step), within [`LEDGER_TOLERANCE`].
    pub(super) fn accept_step(&self, dt: f64, report: &StepReport) -> Result<()> {
        let state = &self.state;
        for node in 0..self.model.rod.node_count() {
            let base = 6 * node;
            let dphi = Vector3::from_column_slice(&self.increments[base..base + 3]);
            let theta = Vector3::from_column_slice(&self.increments[base + 3..base + 6]);
            let speed = (2.0 * dphi / dt - state.velocities[node]).norm();
            let turn = (2.0 * theta / dt).norm() + state.body_angular_velocities[node].norm();
            let bounded = speed <= MAX_SPEED && turn <= MAX_TURN_RATE;
            if !bounded {
                return Err(self.rejected(
                    report,
                    format!(
                    "node {node} would move at {speed:.3e} m/s and turn at {turn:.3e} rad/s (at most \
                     {MAX_SPEED} m/s, the axial wave speed of steel, and {MAX_TURN_RATE:.0} rad/s)"
                )));
            }
        }
        if let Some(step) = &self.vessel_step {
            let speed = step.velocity_next.fixed_rows::<3>(0).norm();
            let bounded = speed <= MAX_SPEED && step.velocity_next.iter().all(|v| v.is_finite());
            if !bounded {
                return Err(self.rejected(
                    report,
                    format!("the vessel would move at {speed:.3e} m/s (at most {MAX_SPEED} m/s)"),
                ));
            }
        }
        let error: f64 = self
            .assembler
            .dofs
            .free_dofs
            .iter()
            .map(|&dof| self.assembler.residual[dof] * self.increments[dof])
            .sum();
        // The step's own work bounds what it works on from below: only an error beyond it needs the energies.
        let booked = self.work.supplied.abs() + self.work.dissipated.abs();
        if error.abs() <= LEDGER_TOLERANCE * booked.max(1.0) {
            return Ok(());
        }
        let energy = self.observe().energy();
        let worked = energy.kinetic
            + energy.strain
            + energy.vessel_kinetic
            + energy.vessel_potential.abs()
            + energy.seabed.abs()
            + energy.rollers.abs()
            + energy.stinger.abs()
            + booked;
        let within = error.abs() <= LEDGER_TOLERANCE * worked.max(1.0);
        if !within {
            return Err(self.rejected(
                    report,
                    format!(
                "its energy error {error:.3e} J exceeds {LEDGER_TOLERANCE:e} of the {worked:.3e} J it works on"
            )));
        }
        Ok(())
    }

    /// The error of a rejected step from the state's time, whose Newton `report`ed convergence: `why` it was
    /// rejected.
    fn rejected(&self, report: &StepReport, why: String) -> Error {
        Error::Convergence {
            context: "time step".into(),
            reached: self.state.time,
            iterations: report.iterations,
            residual: report.residual,
            reason: format!(
                "the step from t = {:.6} s converged to a state out of physical bounds and was rejected: {why}",
                self.state.time
            ),
        }
    }
}
