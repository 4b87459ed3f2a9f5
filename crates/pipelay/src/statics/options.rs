//! What statics are asked and what they return: the solver's settings ([`StaticOptions`], where Newton starts)
//! and a converged solution ([`StaticSolution`]), shared by the paths of [`crate::statics::solve`].
use crate::assembly::configuration::Configuration;
use crate::response::configuration::Response;

/// Where Newton starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// The catenary when it applies (both ends held in position, non-zero submerged weight), else the reference.
    Auto,
    /// The stress-free reference, with load stepping.
    Reference,
    /// Irvine's elastic catenary through the two held ends, at full load.
    Catenary,
}

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// Initial number of equal load steps (halved on failure, grown on easy convergence).
    pub initial_steps: usize,
    pub start: Start,
    /// Relative residual tolerance ‖r_free‖ ≤ tol · force scale.
    pub tolerance: f64,
    /// Newton iterations allowed per load step.
    pub max_iterations: usize,
    /// Smallest load step before giving up.
    pub min_step: f64,
    /// Largest nodal rotation increment per Newton iteration (rad); larger corrections are scaled down.
    pub max_rotation_increment: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions {
            initial_steps: 1,
            start: Start::Auto,
            tolerance: 1e-9,
            max_iterations: 30,
            min_step: 1e-6,
            max_rotation_increment: 0.5,
        }
    }
}

/// A converged static solution and how it was reached.
#[derive(Debug, Clone)]
pub struct StaticSolution {
    pub configuration: Configuration,
    /// Total Newton iterations.
    pub iterations: usize,
    /// Accepted load steps (1 when solved at full load directly).
    pub steps: usize,
    /// Final residual norm over the free DOFs.
    pub residual: f64,
    /// Whether Newton started from the elastic catenary.
    pub from_catenary: bool,
    /// 1 where the state was reached by relaxation (statics' third path, or a stage's start where Newton
    /// failed), else 0.
    pub relaxations: usize,
    /// Section forces, reactions and energy of the solution.
    pub response: Response,
}
