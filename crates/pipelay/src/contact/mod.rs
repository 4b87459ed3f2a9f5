//! Contact of the pipe's outer surface: with the seabed (normal springs integrated along each element,
//! friction at the nodes) and with the vessel's rollers, in statics and in the energy–momentum step.
//!
//! May use: the rod's element types, the environment (seabed, bathymetry), the vessel's lay equipment and
//! attachment. Not the assembly or the solvers: these evaluate contact through [`sinks`].
//! - [`rule`]: how an evaluation treats the step (static or energy–momentum);
//! - [`sinks`]: where contact puts its tangent;
//! - [`seabed`]: the seabed's normal contact and, through [`friction`], its friction;
//! - [`roller_friction`]: what a roller's surface resists along the contact (rolling resistance, Coulomb);
//! - [`roller_geometry`]: where the pipe's surface is nearest a roller of finite length;
//! - [`rollers`]: unilateral contact with the vessel's rollers, their reactions and the energy–momentum step;
//! - [`touchdown`]: where the pipe leaves the seabed.
pub mod friction;
pub mod roller_friction;
pub mod roller_geometry;
pub mod rollers;
pub mod rule;
pub mod seabed;
pub mod sinks;
#[cfg(test)]
mod test_support;
pub mod touchdown;
