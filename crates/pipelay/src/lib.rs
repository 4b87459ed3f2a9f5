//! pipelay engine: geometrically exact (Simo–Reissner) rods for offshore pipelay analysis.
//!
//! The folders show the architecture, bottom up:
//! - [`so3`] (rotations), [`error`], [`memory`], [`smooth`] and [`table`] (functions of time): what every layer
//!   uses;
//! - [`linalg`]: the LU factorisations of the tangent, and the engine's thread pool (uses nothing else);
//! - [`rod`]: the cross-section, the stress-free reference and the element (statics and dynamics);
//! - [`environment`]: the sea, its current and waves, Morison drag, the seabed and its bathymetry;
//! - [`vessel`]: the DP vessel as a rigid body, its Euler angles, its coupling to the pipe, its control and lay
//!   equipment;
//! - [`model`]: what is simulated: rod, environment, supports, loads, vessel;
//! - [`contact`]: the pipe's contact with the seabed (normal and friction) and with the vessel's rollers;
//! - [`assembly`]: the global residual and tangent over the nodal DOFs;
//! - [`response`]: what users read off a configuration (section forces, reactions, lay summary);
//! - [`statics`]: static equilibrium by Newton's method from a catenary start;
//! - [`dynamics`]: the energy–momentum time step, pay-out, the energy ledger and the record of a run.
//!
//! Data flows one way: a lower layer never imports a higher one.
//!
//! No user input may panic the engine: `unwrap`/`expect` are denied outside tests, and so is indexing, except
//! in the modules that say why their indices are in bounds (the mesh's own node, element and DOF numbers).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)
)]
pub mod assembly;
pub mod contact;
pub mod dynamics;
pub mod environment;
pub mod error;
pub mod fingerprint;
pub mod linalg;
pub mod memory;
pub mod model;
pub mod response;
pub mod rod;
pub mod smooth;
pub mod so3;
pub mod statics;
pub mod table;
pub mod vessel;

pub use error::{Error, Result};
