//! How a contact evaluation treats a step: forces at the trial state (statics) or the energy–momentum
//! discrete gradient over the step (dynamics).

/// How a contact evaluation treats the step from the start state to the trial state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactRule {
    /// Forces at the trial state (statics; the start is the last converged load step, for friction).
    Static,
    /// Discrete gradient over the step, friction at the step mean, damping (time step Δt, s); the rollers'
    /// high-frequency damping ξ (0: none), ξ k Δδ on the overlap's change over the step.
    EnergyMomentum { time_step: f64, damping: f64 },
}
