//! Statics: Newton–Raphson with adaptive load stepping ([`solve`]), started from a catenary where the model
//! allows ([`catenary`] for a line hanging between its ends, [`laid_catenary`] for one that lies on the
//! seabed).
//!
//! May use: the model and its parts, [`crate::assembly`], [`crate::linalg`] and [`crate::response`].
pub mod catenary;
pub mod laid_catenary;
pub mod solve;
