//! Where contact evaluations put their tangents: the assembler implements these over the global pattern.
use crate::rod::element::ElementMatrix;
use nalgebra::Matrix6;

/// Where a contact evaluation puts its tangent: element 12×12 blocks and node 6×6 blocks (ordering
/// [x1, θ1, x2, θ2] and [x, θ]), added to what is there.
pub trait TangentSink {
    fn add_element(&mut self, element: usize, block: &ElementMatrix);
    fn add_node(&mut self, node: usize, block: &Matrix6<f64>);
}

/// Receives tangent entries ∂r_i/∂q_j by global DOF (node·6 + k).
pub trait EntrySink {
    fn add_entry(&mut self, row: usize, column: usize, value: f64);
}
