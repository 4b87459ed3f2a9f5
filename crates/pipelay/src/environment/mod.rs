//! What the pipe is immersed in: the sea, its current and the drag it exerts.
pub mod current;
pub mod drag;
pub mod sea;
