//! Global assembly: the residual r = f_int − f_ext over all nodal DOFs and the tangent K = ∂r/∂q on the free
//! DOFs, scattered into a fixed sparse pattern (node-major [x_a, θ_a], block tridiagonal but for rollers).
//!
//! May use: the model and its parts, [`crate::contact`] and [`crate::linalg`]. Used by statics, dynamics and
//! the response.
//! - [`dofs`]: six DOFs per node and which are free; [`configuration`]: nodal positions and rotations;
//! - [`pattern`]: the tangent's sparsity; [`scatter`]: where blocks go in its values;
//! - [`assembler`]: the storage and the adding of blocks, contact and rollers;
//! - [`static_residual`]: the static residual and tangent.
pub mod assembler;
pub mod configuration;
pub mod dofs;
pub mod pattern;
pub mod scatter;
pub mod static_residual;
