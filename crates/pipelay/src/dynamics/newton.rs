//! Newton's method on a step's increments: full Newton at the predictor, simplified Newton (the last
//! factorisation reused) while the residual falls fast enough, a polishing correction near the tolerance.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the integrator's own mesh (rebuilt with it at every pay-out change).
#![allow(clippy::indexing_slicing)]
use crate::dynamics::integrator::{Integrator, StepReport};
use crate::error::{Error, Result};
use crate::linalg::factorisation::Factorisation;
use crate::statics::newton::roller_step_factor;

/// Largest residual ratio at which a Newton iteration keeps an earlier iterate's factorisation (simplified
/// Newton); a slower fall refreshes the tangent.
const SIMPLIFIED_RATE: f64 = 0.1;

/// Largest relative residual (residual over the force scale) at an iterate whose block-tridiagonal
/// factorisation later iterations may reuse. Over a correction the forces, hence the tangent, change by about
/// that relative amount, which is the contraction a simplified iteration then achieves: on the driven hanging
/// line at n = 1000 the predictor's relative residual is 0.1–0.4 and the simplified correction after it cut
/// the residual by only 0.3–0.4 (0.01: 2.9 ms per step; 1: 4.0 ms). Where the factorisation is the bordered
/// or sparse one (rollers), several times an assembly's cost, a simplified correction is always tried first:
/// the S-lay example at n = 1000 takes 7.5 ms per step so, 11.1 ms with 0.01.
const REUSE_BELOW: f64 = 0.01;

/// Fraction of the tolerance below which a converged iterate needs no polishing correction.
const POLISHED_BELOW: f64 = 1e-2;

impl Integrator {
    /// Norms of the residual and of the per-DOF force magnitudes over the free DOFs.
    fn residual_norms(&self) -> (f64, f64) {
        let mut free2 = 0.0;
        let mut scale2 = 0.0;
        for &dof in &self.assembler.dofs.free_dofs {
            free2 += self.assembler.residual[dof].powi(2);
            scale2 += self.magnitude[dof].powi(2);
        }
        (free2.sqrt(), scale2.sqrt())
    }

    /// Newton's method on the step's increments, to the residual tolerance. The tangent is assembled and
    /// factorised at the predictor; later iterates reuse the last factors (a simplified Newton step costs a
    /// residual and a solve) while the residual falls by [`SIMPLIFIED_RATE`] or faster per iteration, and
    /// the tangent is refreshed at the iterate where it does not, or, for a block-tridiagonal factorisation,
    /// where the residual at the factorised iterate exceeded [`REUSE_BELOW`]. A converged iterate above
    /// [`POLISHED_BELOW`] of the tolerance gets one more correction. Everything depends on the step's start
    /// alone, so a resumed run repeats the same iterations.
    pub(super) fn newton(&mut self, scales: &[f64], time_mid: f64, dt: f64) -> Result<StepReport> {
        let mut residual = f64::INFINITY;
        let mut converged = false;
        let mut iterations = 0;
        // Whether this iterate's tangent is to be assembled and factorised; the residual of the last correction;
        // whether a polishing correction was made.
        let mut fresh = true;
        let mut last = f64::INFINITY;
        let mut polished = false;
        // The relative residual at the iterate whose tangent is factorised.
        let mut factorised_at = f64::INFINITY;
        let mut factorisations = 0;
        let mut predictor_residual = f64::INFINITY;
        for iteration in 0..=self.options.max_iterations {
            iterations = iteration;
            self.assemble(scales, time_mid, dt, fresh)?;
            let (norm, scale) = self.residual_norms();
            residual = norm;
            if iteration == 0 {
                predictor_residual = norm / scale;
            }
            if !residual.is_finite() {
                break;
            }
            if residual <= self.options.tolerance * scale + self.round_off
                || (iteration > 0 && residual == 0.0)
            {
                // An iterate just below the tolerance is corrected once more with the factors at hand (a
                // residual and a solve), so that energy and momentum balance to round-off, as when full
                // Newton from the constant-velocity predictor overshot the tolerance quadratically.
                if residual <= POLISHED_BELOW * self.options.tolerance * scale
                    || polished
                    || residual == 0.0
                    || iteration == self.options.max_iterations
                {
                    converged = true;
                    break;
                }
                polished = true;
            }
            if iteration == self.options.max_iterations {
                break;
            }
            if !fresh && residual > SIMPLIFIED_RATE * last {
                self.assemble(scales, time_mid, dt, true)?;
                fresh = true;
            }
            if fresh {
                self.assembler.shift_rotations();
                if self.assembler.lu.factorise(&self.assembler.values).is_err() {
                    break;
                }
                factorisations += 1;
                factorised_at = residual / scale;
            }
            last = residual;
            // The forces, hence the tangent, change over this correction by about the relative residual at
            // the factorised iterate: the contraction a simplified iteration would achieve.
            fresh = self.assembler.lu.is_block_tridiagonal() && factorised_at > REUSE_BELOW;
            for (correction, &dof) in self
                .correction
                .iter_mut()
                .zip(&self.assembler.dofs.free_dofs)
            {
                *correction = -self.assembler.residual[dof];
            }
            if self
                .assembler
                .lu
                .solve_in_place(&mut self.correction)
                .is_err()
            {
                break;
            }
            // A correction that would carry a node near the rollers through them is shortened, as in statics: the
            // contact sees the line only within its reach on the rollers' far side.
            let factor = roller_step_factor(
                &self.model,
                &self.assembler,
                &self.state.configuration,
                &self.correction,
            );
            let mut correction2 = 0.0;
            let mut size2 = 0.0;
            for (correction, &dof) in self.correction.iter().zip(&self.assembler.dofs.free_dofs) {
                let correction = factor * correction;
                self.increments[dof] += correction;
                correction2 += correction.powi(2);
                size2 += self.increments[dof].powi(2);
            }
            // A correction at round-off of the increments: the residual cannot fall further.
            if correction2 <= 1e-30 * size2 && residual <= 1e3 * self.options.tolerance * scale {
                self.assemble(scales, time_mid, dt, false)?;
                converged = true;
                iterations += 1;
                break;
            }
        }
        if !converged {
            return Err(Error::Convergence {
                context: "time step".into(),
                reached: self.state.time,
                iterations,
                residual,
                reason: format!(
                    "Newton did not converge in the step from t = {:.6} s",
                    self.state.time
                ),
            });
        }
        Ok(StepReport {
            iterations,
            factorisations,
            residual,
            predictor_residual,
            substeps: 1,
        })
    }
}
