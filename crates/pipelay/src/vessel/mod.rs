//! The DP vessel: a rigid body (eq. 10), its Euler angles, its coupling to the pipe's end and its control.
pub mod coupling;
pub mod euler;
pub mod rigid_body;
