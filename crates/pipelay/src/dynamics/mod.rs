//! Dynamics: the energy–momentum conserving time step of the rod and its vessel, and the record of a run.
//!
//! May use: the model and its parts, [`crate::assembly`], [`crate::contact`], [`crate::linalg`],
//! [`crate::response`] (for the reactions and lay summary of a state) and [`crate::statics`] (a stage's start
//! from statics, the roller step limit). Nothing below imports it.
//! - [`acceptance`]: whether a converged step is kept or retried in substeps;
//! - [`state`]: the state of the rod and vessel at one time; [`nodal`]: its lumped inertia;
//! - [`integrator`]: the time step as a whole (predict, solve, commit); [`step_residual`]: a step's residual
//!   and tangent, of which [`rod_step`] is the rod's share; [`newton`]: Newton's method on the increments;
//! - [`vessel_waves`]: the vessel's wave-frequency motion over a step;
//! - [`pay_out`]: the growing end element within a step; [`remesh`]: the mesh change that follows;
//! - [`stages`]: the stages of a lay as functions of time; [`hand_over`]: the line passed to the A&R winch;
//!   [`hand_back`]: and back to the tensioner;
//! - [`ledger`]: the storage function and the work supplied and dissipated;
//! - [`observables`]: what users read off a state; [`history`]: the record of a run.
pub mod acceptance;
pub mod hand_back;
pub mod hand_over;
pub mod history;
pub mod integrator;
pub mod ledger;
pub mod newton;
pub mod nodal;
pub mod observables;
pub mod passivity;
pub mod pay_out;
pub mod remesh;
pub mod rod_step;
pub mod stages;
pub mod state;
pub mod station_keeping;
pub mod step_residual;
pub mod vessel_waves;
