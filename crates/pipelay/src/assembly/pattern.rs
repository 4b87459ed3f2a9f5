//! The tangent's sparsity pattern over the free DOFs: each element couples its two nodes, and a vessel's
//! rollers couple the nodes within their reach to the vessel's node and to their neighbours up to
//! [`COUPLING_REACH`] nodes away, and an articulated stinger's hinge angles to those nodes, the vessel's node
//! and each other.
// Indexing cannot go out of bounds here: DOF, node and equation indices of the model's own mesh.
#![allow(clippy::indexing_slicing)]
use crate::assembly::dofs::{DofMap, NODE_DOFS};
use crate::contact::rollers::{RollerContact, COUPLING_REACH};
use crate::linalg::pattern::Pattern;
use crate::model::Model;

/// The tangent's pattern and how it divides.
pub struct TangentPattern {
    pub pattern: Pattern,
    /// With rollers, the vessel node's free unknowns and the hinge angles: the border of the factorisation.
    pub border: Vec<usize>,
    /// Where the columns of each node begin in the values (and, last, their end).
    pub node_values: Vec<usize>,
}

impl TangentPattern {
    /// The pattern of `model`'s tangent over the free DOFs `dofs`, with its `rollers` if it has any.
    pub fn new(model: &Model, dofs: &DofMap, rollers: Option<&RollerContact>) -> Self {
        let elements = model.rod.element_count();
        let global = |e: usize, local: usize| NODE_DOFS * e + local;
        // Rows of each free column: every free DOF of the elements that touch it.
        let mut columns: Vec<Vec<usize>> = vec![Vec::new(); dofs.free];
        for e in 0..elements {
            for j in 0..12 {
                if let Some(col) = dofs.equation[global(e, j)] {
                    columns[col].extend((0..12).filter_map(|i| dofs.equation[global(e, i)]));
                }
            }
        }
        // Rollers couple the nodes within their reach to the vessel's node and to near neighbours.
        if let (Some(rollers), Some(attachment)) = (rollers, &model.vessel) {
            let nodes = rollers.nodes();
            let mut couple = |a: usize, b: usize| {
                for j in 0..NODE_DOFS {
                    if let Some(col) = dofs.equation[NODE_DOFS * b + j] {
                        columns[col].extend(
                            (0..NODE_DOFS).filter_map(|i| dofs.equation[NODE_DOFS * a + i]),
                        );
                    }
                }
            };
            for a in nodes.clone() {
                couple(a, attachment.node);
                couple(attachment.node, a);
                for b in nodes.clone().filter(|b| b.abs_diff(a) <= COUPLING_REACH) {
                    couple(a, b);
                }
            }
            // Hinge angles: rows and columns over the nodes in reach, the vessel's node and the hinges.
            let hinges: Vec<usize> = (0..model.hinge_count())
                .filter_map(|i| dofs.equation[model.hinge_dof(i)])
                .collect();
            let node_equations = |node: usize| {
                (0..NODE_DOFS).filter_map(move |k| dofs.equation[NODE_DOFS * node + k])
            };
            let coupled: Vec<usize> = nodes
                .clone()
                .chain([attachment.node])
                .flat_map(node_equations)
                .chain(hinges.iter().copied())
                .collect();
            for &hinge in &hinges {
                columns[hinge].extend(&coupled);
                for &other in &coupled {
                    columns[other].push(hinge);
                }
            }
        }
        let mut col_ptr = Vec::with_capacity(dofs.free + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for rows in &mut columns {
            rows.sort_unstable();
            rows.dedup();
            row_idx.extend_from_slice(rows);
            col_ptr.push(row_idx.len());
        }
        // With rollers, the vessel node's free unknowns and the hinge angles are the border of the factorisation.
        let border: Vec<usize> = match (rollers, &model.vessel) {
            (Some(_), Some(attachment)) => (0..NODE_DOFS)
                .map(|k| NODE_DOFS * attachment.node + k)
                .chain((0..model.hinge_count()).map(|i| model.hinge_dof(i)))
                .filter_map(|dof| dofs.equation[dof])
                .collect(),
            _ => Vec::new(),
        };
        let mut node_values = Vec::with_capacity(model.rod.node_count() + 1);
        let mut equation = 0;
        for node in 0..model.rod.node_count() {
            node_values.push(col_ptr[equation]);
            equation += (0..NODE_DOFS)
                .filter(|k| dofs.equation[NODE_DOFS * node + k].is_some())
                .count();
        }
        node_values.push(col_ptr[equation]);
        TangentPattern {
            pattern: Pattern::new(col_ptr, row_idx),
            border,
            node_values,
        }
    }
}
