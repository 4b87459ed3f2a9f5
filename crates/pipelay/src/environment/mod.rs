//! What the pipe is immersed in and rests on: the sea, its current and the drag it exerts, the waves, the
//! seabed and its shape, and the wind.
//!
//! May use: the basics (errors, memory, smooth steps).
pub mod bathymetry;
pub mod current;
pub mod drag;
pub mod sea;
pub mod seabed;
pub mod waves;
pub mod wind;
