//! pipelay engine: geometrically exact (Simo–Reissner) rods for offshore pipelay analysis.
//!
//! Layers, bottom up: [`so3`] and [`euler`] (rotations), [`section`], [`rod`] (reference and element),
//! [`hydro`] (sea, current, drag), [`model`] (supports, loads), [`assembly`] and [`linsolve`]
//! (global system), [`statics`] (Newton with load stepping), [`dynamics`] (energy–momentum time
//! stepping), [`response`] (what users read off a state).
pub mod assembly;
pub mod catenary;
pub mod coupling;
pub mod dynamics;
pub mod error;
pub mod euler;
pub mod history;
pub mod hydro;
pub mod linsolve;
pub mod model;
pub mod response;
pub mod rod;
pub mod section;
pub mod so3;
pub mod statics;
pub mod vessel;

pub use error::{Error, Result};
