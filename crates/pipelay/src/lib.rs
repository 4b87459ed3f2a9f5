//! pipelay engine: geometrically exact (Simo–Reissner) rods for offshore pipelay analysis.
//!
//! The folders show the architecture, bottom up:
//! - [`so3`] (rotations), [`error`], [`memory`], [`smooth`] and [`table`] (functions of time as tables): what
//!   every layer uses;
//! - [`rod`]: the cross-section, the stress-free reference and the element (statics and dynamics);
//! - [`environment`]: the sea, its current and Morison drag;
//! - [`vessel`]: the DP vessel as a rigid body, its Euler angles, its coupling to the pipe and its control;
//! - [`model`]: what is simulated: rod, environment, supports, loads, vessel;
//! - [`solver`]: assembly and linear solves, statics, dynamics, the response and the record of a run.
//!
//! Data flows one way: a lower layer never imports a higher one.
//!
//! No user input may panic the engine: `unwrap`/`expect` are denied outside tests, and so is indexing, except
//! in the modules that say why their indices are in bounds (the mesh's own node, element and DOF numbers).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)
)]
pub mod environment;
pub mod error;
pub mod memory;
pub mod model;
pub mod rod;
pub mod smooth;
pub mod so3;
pub mod solver;
pub mod table;
pub mod vessel;

pub use error::{Error, Result};
