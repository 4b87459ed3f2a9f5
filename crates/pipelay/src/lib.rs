//! pipelay engine: geometrically exact (Simo–Reissner) rods for offshore pipelay analysis.
//!
//! The folders show the architecture, bottom up:
//! - [`so3`] (rotations) and [`error`]: what every layer uses;
//! - [`rod`]: the cross-section, the stress-free reference and the element (statics and dynamics);
//! - [`environment`]: the sea, its current and Morison drag;
//! - [`vessel`]: the DP vessel as a rigid body, its Euler angles, its coupling to the pipe and its control;
//! - [`model`]: what is simulated: rod, environment, supports, loads, vessel;
//! - [`solver`]: assembly and linear solves, statics, dynamics, the response and the record of a run.
//!
//! Data flows one way: a lower layer never imports a higher one.
pub mod environment;
pub mod error;
pub mod model;
pub mod rod;
pub mod so3;
pub mod solver;
pub mod vessel;

pub use error::{Error, Result};
