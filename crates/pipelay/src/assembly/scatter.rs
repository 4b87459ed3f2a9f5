//! Where assembled blocks go in the tangent's values: the scatter maps of element and node blocks, the
//! rod's sinks (one per run of nodes, for the parallel assembly) and the contact's sinks.
// Indexing cannot go out of bounds here: DOF and value positions of the pattern the maps were built from.
#![allow(clippy::indexing_slicing)]
use crate::assembly::dofs::{DofMap, NODE_DOFS};
use crate::contact::sinks::{EntrySink, TangentSink};
use crate::linalg::tangent_lu::TangentLu;
use crate::rod::element::{ElementMatrix, ElementVector};
use nalgebra::{Matrix6, Vector6};

/// A block entry whose row or column is prescribed: it has no place in the values.
pub const FIXED: u32 = u32::MAX;

/// The residual, magnitude and tangent entries of a run of consecutive nodes: everything their own DOFs' rows
/// (residual) and columns (tangent) hold. Two sinks split at a node write disjoint memory, so the rod's
/// elements and nodes can be assembled in parallel (see [`crate::dynamics::rod_step`]).
pub struct RodSink<'a> {
    /// The first node of the run.
    pub(super) first_node: usize,
    pub(super) residual: &'a mut [f64],
    pub(super) magnitude: &'a mut [f64],
    /// The tangent values of the run's columns (`None`: residual only), from position `values_offset`.
    pub(super) values: Option<&'a mut [f64]>,
    pub(super) values_offset: usize,
    pub(super) node_values: &'a [usize],
    pub(super) elements: &'a ScatterMap,
    pub(super) nodes: &'a ScatterMap,
}

impl RodSink<'_> {
    /// The run's nodes before `node` and from `node` on.
    pub fn split_at_node(&mut self, node: usize) -> (RodSink<'_>, RodSink<'_>) {
        let dofs = NODE_DOFS * (node - self.first_node);
        let (residual_left, residual_right) = self.residual.split_at_mut(dofs);
        let (magnitude_left, magnitude_right) = self.magnitude.split_at_mut(dofs);
        let split = self.node_values[node];
        let (values_left, values_right) = match self.values.as_deref_mut() {
            Some(values) => {
                let (left, right) = values.split_at_mut(split - self.values_offset);
                (Some(left), Some(right))
            }
            None => (None, None),
        };
        (
            RodSink {
                first_node: self.first_node,
                residual: residual_left,
                magnitude: magnitude_left,
                values: values_left,
                values_offset: self.values_offset,
                node_values: self.node_values,
                elements: self.elements,
                nodes: self.nodes,
            },
            RodSink {
                first_node: node,
                residual: residual_right,
                magnitude: magnitude_right,
                values: values_right,
                values_offset: split,
                node_values: self.node_values,
                elements: self.elements,
                nodes: self.nodes,
            },
        )
    }

    /// Adds element `element`'s forces (its 12 residual entries), their magnitudes and, with a tangent, its
    /// 12×12 block. Both its nodes must be in the run.
    pub fn add_element(
        &mut self,
        element: usize,
        forces: &ElementVector,
        magnitude: &ElementVector,
        tangent: &ElementMatrix,
    ) {
        let base = NODE_DOFS * (element - self.first_node);
        add(&mut self.residual[base..base + 12], forces.as_slice());
        add(&mut self.magnitude[base..base + 12], magnitude.as_slice());
        if let Some(values) = self.values.as_deref_mut() {
            self.elements
                .add_from(values, self.values_offset, element, tangent.as_slice());
        }
    }

    /// Adds node `node`'s forces, their magnitudes and its 6×6 tangent block (if the sink takes tangents).
    pub fn add_node(
        &mut self,
        node: usize,
        forces: &Vector6<f64>,
        magnitude: &Vector6<f64>,
        tangent: Option<&Matrix6<f64>>,
    ) {
        let base = NODE_DOFS * (node - self.first_node);
        add(
            &mut self.residual[base..base + NODE_DOFS],
            forces.as_slice(),
        );
        add(
            &mut self.magnitude[base..base + NODE_DOFS],
            magnitude.as_slice(),
        );
        if let (Some(values), Some(tangent)) = (self.values.as_deref_mut(), tangent) {
            self.nodes
                .add_from(values, self.values_offset, node, tangent.as_slice());
        }
    }
}

/// `target` += `terms`, entry by entry.
fn add(target: &mut [f64], terms: &[f64]) {
    for (t, x) in target.iter_mut().zip(terms) {
        *t += x;
    }
}

/// Tangent entries by global DOF, where the pattern has them.
pub struct Entries<'a> {
    pub values: &'a mut [f64],
    pub dofs: &'a DofMap,
    pub lu: &'a TangentLu,
}

impl EntrySink for Entries<'_> {
    fn add_entry(&mut self, row: usize, column: usize, value: f64) {
        if let (Some(r), Some(c)) = (self.dofs.equation[row], self.dofs.equation[column]) {
            if let Some(p) = self.lu.position(r, c) {
                self.values[p] += value;
            }
        }
    }
}

/// Where dense blocks (column-major) go in the tangent's values, as runs of consecutive entries that land on
/// consecutive positions: with the unknowns in node order, a column of an element's block is one run.
pub struct ScatterMap {
    /// (first entry in the block, first value position, length), block after block.
    runs: Vec<(u32, u32, u32)>,
    /// Block b's runs are `runs[first[b]..first[b + 1]]`.
    first: Vec<usize>,
}

impl ScatterMap {
    /// From each block's value position of every entry (FIXED where the entry's row or column is prescribed).
    pub fn new<const N: usize>(positions: impl Iterator<Item = [u32; N]>) -> Self {
        let mut runs: Vec<(u32, u32, u32)> = Vec::new();
        let mut first = vec![0];
        for map in positions {
            let block_start = runs.len();
            for (entry, &position) in map.iter().enumerate().filter(|(_, &p)| p != FIXED) {
                let extends = runs.len() > block_start
                    && runs.last().is_some_and(|run| {
                        (run.0 + run.2) as usize == entry && run.1 + run.2 == position
                    });
                match runs.last_mut() {
                    Some(run) if extends => run.2 += 1,
                    _ => runs.push((entry as u32, position, 1)),
                }
            }
            first.push(runs.len());
        }
        ScatterMap { runs, first }
    }

    /// Adds block `index` (column-major entries) to `values`.
    pub fn add(&self, values: &mut [f64], index: usize, block: &[f64]) {
        self.add_from(values, 0, index, block);
    }

    /// Adds block `index` to `values`, a slice of the tangent's values that starts at position `offset`.
    fn add_from(&self, values: &mut [f64], offset: usize, index: usize, block: &[f64]) {
        for &(entry, position, length) in &self.runs[self.first[index]..self.first[index + 1]] {
            let (entry, position, length) =
                (entry as usize, position as usize - offset, length as usize);
            for (value, term) in values[position..position + length]
                .iter_mut()
                .zip(&block[entry..entry + length])
            {
                *value += term;
            }
        }
    }
}

/// The tangent's values seen through the element and node scatter maps.
pub struct Scatter<'a> {
    pub values: &'a mut [f64],
    pub elements: &'a ScatterMap,
    pub nodes: &'a ScatterMap,
}

impl TangentSink for Scatter<'_> {
    fn add_element(&mut self, element: usize, block: &ElementMatrix) {
        self.elements.add(self.values, element, block.as_slice());
    }
    fn add_node(&mut self, node: usize, block: &Matrix6<f64>) {
        self.nodes.add(self.values, node, block.as_slice());
    }
}
