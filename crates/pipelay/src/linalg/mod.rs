//! Linear algebra of the global tangent: its sparsity [`pattern`], the LU factorisations that suit a rod's
//! tangent ([`tangent_lu`] chooses among them), and the engine's thread [`pool`].
//!
//! May use: nothing of the engine but itself (and faer, nalgebra, rayon). Kernels first, compositions after:
//! - [`band_lu`], [`block_lu`]: the band LU and the block-tridiagonal LU, on raw patterns and values;
//! - [`general_lu`]: a matrix of any pattern (band, dense or sparse LU);
//! - [`rod_lu`]: a rod's block-tridiagonal tangent, with the band LU where a block needs pivoting;
//! - [`window_lu`], [`border_lu`]: block elimination around a window of wider coupling and around border
//!   unknowns, on top of the LUs above ([`partition`] splits the pattern for them);
//! - [`tangent_lu`]: the global tangent's LU, made of those.
pub mod band_lu;
pub mod block_lu;
pub mod border_lu;
pub mod factorisation;
pub mod general_lu;
pub mod largest;
pub mod partition;
pub mod pattern;
pub mod pool;
pub mod rod_lu;
pub mod tangent_lu;
#[cfg(test)]
mod test_support;
pub mod window_lu;
