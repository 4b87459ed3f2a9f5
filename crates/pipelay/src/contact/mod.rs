//! Contact of the pipe's outer surface: with the seabed (normal springs integrated along each element,
//! friction at the nodes) and with the vessel's rollers, in statics and in the energy–momentum step.
//!
//! May use: the rod's element types, the environment (seabed, bathymetry), the vessel's lay equipment and
//! attachment. Not the assembly or the solvers: these evaluate contact through [`sinks`].
//! - [`rule`]: how an evaluation treats the step (static or energy–momentum);
//! - [`sinks`]: where contact puts its tangent;
//! - [`seabed`]: the seabed's normal contact and, through [`friction`], its friction;
//! - [`rollers`]: unilateral contact with the vessel's rollers;
//! - [`touchdown`]: where the pipe leaves the seabed.
pub mod friction;
pub mod rollers;
pub mod rule;
pub mod seabed;
pub mod sinks;
#[cfg(test)]
mod test_support;
pub mod touchdown;
