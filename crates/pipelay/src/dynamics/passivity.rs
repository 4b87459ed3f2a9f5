//! The time-domain passivity observer and controller of the DP loop (after Hannaford & Ryu 2002, "Time-domain
//! passivity control of haptic interfaces"), on the port between the controller (with its allocation,
//! thrusters and observer, or an FMU) and the vessel.
//!
//! **Observer.** The controller's work on the vessel over a step, W_k = Δt ν_{k+½}·τ_k (the thrust it holds
//! over the step, or the implicit PID's, with the midpoint velocity: exactly the thrust's part of the energy
//! ledger's supplied work), summed, W_c(n) = Σ_{k<n} W_k. The controller is passive on its port if it never gives
//! the vessel more than its initial storage E₀ (the PID's ½η̃ᵀK_pη̃ at the start, zero for a controller from
//! outside): its reserve R(n) = E₀ − W_c(n) ≥ 0 for all n.
//!
//! **Controller.** Where a step's solution would give the vessel more than the reserve, W_k > R, the step is
//! solved again with the thrust scaled by s ∈ [0, 1): first s = R/W_k (the work scales with the thrust at an
//! unchanged velocity), then, while the new solution still gives too much, by the same rule from there; at
//! s = 0 the controller does no work at all, so a scale that fits always exists. The first solution within the
//! reserve (to its round-off, 1e-12 of the work through the port) is taken. Hannaford and Ryu's controller is a
//! damper on the port's velocity; its work falls only as 1/α where the velocity is small, so that near rest no
//! bounded damping fits a step into an exhausted reserve: scaling the controller's output does, exactly.
//!
//! **Certificate.** With the plant's ledger exact, E(n) − E(0) = W(n) − D(n), and W = W_c + W_env (the
//! environment's work): E(n) − E(0) − W_env(n) = W_c(n) − D(n) ≤ E₀. The closed loop, allocation, thrust lag,
//! saturation and observer inside it, stores no more energy than the environment supplies and the controller
//! held at the start, step by step.

/// How many times a step may be solved again with a smaller thrust before the controller is cut for the step.
pub const MAX_SOLVES: usize = 8;

/// The passivity observer's ledger of a run (carried in the vessel's state and its checkpoints).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PassivityLedger {
    /// W_c: the controller's work on the vessel since the start (J), as scaled by the passivity controller.
    pub controller_work: f64,
    /// E₀: the controller's storage at the start (J).
    pub budget: f64,
    /// The work the passivity controller withheld: Σ (W_k at full thrust − W_k as taken) (J).
    pub withheld: f64,
    /// The steps in which the passivity controller acted.
    pub steps: u64,
    /// Σ |W_k|: the work through the port since the start (J), the scale of its round-off.
    pub throughput: f64,
}

impl PassivityLedger {
    /// R = E₀ − W_c: what the controller may still give the vessel (J).
    pub fn reserve(&self) -> f64 {
        self.budget - self.controller_work
    }

    /// The round-off of the port's ledger (J): 1e-12 of the work through it (and of the step's).
    pub fn round_off(&self, work: f64) -> f64 {
        1e-12 * (self.throughput + self.budget.abs() + work.abs())
    }

    /// Whether a step whose controller work is `work` (J) fits the reserve, to the ledger's round-off.
    pub fn fits(&self, work: f64) -> bool {
        work <= self.reserve() + self.round_off(work)
    }

    /// The thrust scale to solve the step with next, after a solution with the scale `scale` gave the work
    /// `work` (J) that does not fit: the scale that would fit at an unchanged velocity, R/W of the scaled
    /// thrust's work per unit scale, a little below (by the round-off); 0 if the reserve is spent.
    pub fn next_scale(&self, scale: f64, work: f64) -> f64 {
        let reserve = self.reserve() - self.round_off(work);
        if reserve <= 0.0 || work <= 0.0 {
            return 0.0;
        }
        (scale * reserve / work).clamp(0.0, scale)
    }

    /// Books a step: its controller work `work` (J) as taken with the thrust scale `scale`, and the work `full`
    /// (J) its first solution, at the full thrust, would have done.
    pub fn book(&mut self, work: f64, scale: f64, full: f64) {
        self.controller_work += work;
        self.throughput += work.abs();
        if scale < 1.0 {
            self.withheld += full - work;
            self.steps += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A step that fits is left alone; one that does not is scaled to the reserve at its velocity, or cut where
    /// the reserve is spent; booking counts the step and the work withheld.
    #[test]
    fn the_thrust_is_scaled_to_the_reserve() {
        let mut ledger = PassivityLedger {
            controller_work: -50.0,
            budget: 10.0,
            withheld: 0.0,
            steps: 0,
            throughput: 1e3,
        };
        assert!((ledger.reserve() - 60.0).abs() < 1e-12);
        assert!(ledger.fits(60.0) && ledger.fits(60.0 + 1e-10) && !ledger.fits(61.0));
        let scale = ledger.next_scale(1.0, 80.0);
        assert!((scale - 60.0 / 80.0).abs() < 1e-9, "{scale}");
        // Solved again at that scale, the work at an unchanged velocity is the reserve: it fits.
        let work = 80.0 * scale;
        assert!(ledger.fits(work));
        ledger.book(work, scale, 80.0);
        assert_eq!(ledger.steps, 1);
        assert!((ledger.withheld - (80.0 - work)).abs() < 1e-12);
        assert!(ledger.reserve() >= -ledger.round_off(0.0));
        // The reserve spent: the controller is cut for the step.
        assert!(ledger.next_scale(0.5, 3.0) < 1e-9);
    }
}
