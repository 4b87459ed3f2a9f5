//! What users read off a configuration: section forces, support reactions, energies and contact
//! ([`configuration`]), and what a lay engineer reads off a lay ([`lay_summary`]).
//!
//! May use: the model and its parts, [`crate::assembly`] and [`crate::contact`]. Used by statics and dynamics.
pub mod configuration;
pub mod lay_summary;
