//! Statics: Newton–Raphson with adaptive load stepping and continuation ([`solve`]) along a path on which
//! the loads grow and then the supports move ([`supports`]), started where the model allows from a catenary
//! guess ([`start`]: [`catenary`] for a line hanging between its ends, [`laid_catenary`] for one that lies on
//! the seabed); [`options`]: what statics are asked and return.
//!
//! May use: the model and its parts, [`crate::assembly`], [`crate::linalg`] and [`crate::response`].
pub mod catenary;
pub mod continuation;
pub mod laid_catenary;
pub mod newton;
pub mod options;
pub mod physical;
pub mod relaxation;
pub mod solve;
pub mod start;
pub mod supports;
