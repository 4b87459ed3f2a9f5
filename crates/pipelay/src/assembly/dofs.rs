//! The rod's degrees of freedom: six per node, and which of them are free (not prescribed by a support, and
//! not the rotation of a cable node, which has none); after the nodes', the hinge angles of an articulated
//! stinger, all free.
// Indexing cannot go out of bounds here: DOF indices of the model's own nodes (supports are checked against them).
#![allow(clippy::indexing_slicing)]
use crate::model::Model;

pub use crate::model::NODE_DOFS;

/// Which DOFs are free, and their equation numbers.
#[derive(Debug, Clone)]
pub struct DofMap {
    /// Equation number of each global DOF (node·6 + k, then the hinges'), `None` when prescribed.
    pub equation: Vec<Option<usize>>,
    /// Number of free DOFs.
    pub free: usize,
    /// The global DOF of each equation (increasing: equations are numbered in node order).
    pub free_dofs: Vec<usize>,
}

impl DofMap {
    /// Free DOFs of a model: all but those its supports prescribe and the rotations of its cable nodes.
    pub fn new(model: &Model) -> Self {
        let mut fixed = vec![false; NODE_DOFS * model.rod.node_count() + model.hinge_count()];
        for node in (0..model.rod.node_count()).filter(|&a| model.is_rotationless(a)) {
            let base = NODE_DOFS * node;
            fixed[base + 3..base + 6].iter_mut().for_each(|f| *f = true);
        }
        for support in &model.supports {
            let base = NODE_DOFS * support.node;
            let count = if support.holds_rotation() { 6 } else { 3 };
            fixed[base..base + count].iter_mut().for_each(|f| *f = true);
        }
        let mut free = 0;
        let equation = fixed
            .iter()
            .map(|&is_fixed| {
                (!is_fixed).then(|| {
                    free += 1;
                    free - 1
                })
            })
            .collect();
        let free_dofs = (0..fixed.len()).filter(|&dof| !fixed[dof]).collect();
        DofMap {
            equation,
            free,
            free_dofs,
        }
    }
}
