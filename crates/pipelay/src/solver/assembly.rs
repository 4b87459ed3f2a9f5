//! Global assembly: the residual r = f_int − f_ext over all nodal DOFs and the tangent K = ∂r/∂q on
//! the free DOFs, scattered into a fixed sparse pattern (node-major [x_a, θ_a], block tridiagonal).
// Indexing cannot go out of bounds here: Node, element and DOF indices of the mesh the assembler was built for (sizes fixed at construction).
#![allow(clippy::indexing_slicing)]
use crate::environment::drag::element_current_drag;
use crate::model::Model;
use crate::rod::element::{evaluate, ElementMatrix, ElementVector};
use crate::so3::exp_quat;
use crate::solver::contact::{ContactRule, SeabedContact, TangentSink};
use crate::solver::linsolve::{largest_magnitude, SparseLu};
use crate::solver::rollers::{EntrySink, RollerContact};
use crate::vessel::coupling::{static_forces, StaticTarget};
use crate::vessel::VesselAttachment;
use nalgebra::{Matrix6, UnitQuaternion, Vector2, Vector3, Vector6};

/// Degrees of freedom per node: position (3) and spatial spin (3).
pub const NODE_DOFS: usize = 6;
const FIXED: u32 = u32::MAX;

/// A configuration of the rod: nodal positions and rotations.
#[derive(Debug, Clone, PartialEq)]
pub struct Configuration {
    pub positions: Vec<Vector3<f64>>,
    pub rotations: Vec<UnitQuaternion<f64>>,
}

impl Configuration {
    /// The rod's stress-free reference.
    pub fn reference(model: &Model) -> Self {
        Configuration {
            positions: model.rod.nodes.clone(),
            rotations: model.rod.frames.clone(),
        }
    }
}

/// Which DOFs are free, and their equation numbers.
#[derive(Debug, Clone)]
pub struct DofMap {
    /// Equation number of each global DOF (node·6 + k), `None` when prescribed.
    pub equation: Vec<Option<usize>>,
    /// Number of free DOFs.
    pub free: usize,
    /// The global DOF of each equation (increasing: equations are numbered in node order).
    pub free_dofs: Vec<usize>,
}

impl DofMap {
    /// Free DOFs of a model: all but those its supports prescribe.
    pub fn new(model: &Model) -> Self {
        let mut fixed = vec![false; NODE_DOFS * model.rod.node_count()];
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

/// Results of one assembly besides the residual and tangent.
#[derive(Debug, Clone, Copy, Default)]
pub struct AssemblySummary {
    /// Euclidean norm of the external load vector (N, N·m mixed).
    pub external_norm: f64,
    /// Strain energy Σ Π_e (J).
    pub strain_energy: f64,
    /// Largest relative rotation |ψ| between the two nodes of an element (rad).
    pub max_element_rotation: f64,
}

/// Assembles residuals and tangents of one model into preallocated storage.
pub struct Assembler {
    pub dofs: DofMap,
    /// Sparse LU with the tangent's pattern.
    pub lu: SparseLu,
    /// Tangent values in pattern order.
    pub values: Vec<f64>,
    /// Residual over all DOFs.
    pub residual: Vec<f64>,
    /// K_fc Δu_c: the tangent's prescribed columns times the prescribed increments (all DOFs).
    pub support_coupling: Vec<f64>,
    external: Vec<f64>,
    /// Where each element's 12×12 tangent block goes in `values`.
    scatter: ScatterMap,
    /// Value positions of the diagonal entries of free rotational DOFs.
    rotation_diagonal: Vec<usize>,
    /// Factor of each point load (its scale function at the time of the solve; 1 by default).
    pub point_load_scales: Vec<f64>,
    /// Where each node's 6×6 diagonal block goes in `values`.
    node_scatter: ScatterMap,
    /// Where the columns of each node begin in `values` (and, last, their end): the rod's elements and nodes
    /// write only in their own nodes' columns.
    node_values: Vec<usize>,
    /// How far a vessel's static target has moved from the end node's reference pose (0 to 1).
    pub vessel_motion: f64,
    /// The holding thrust of the last static assembly (body frame).
    pub vessel_thrust: Vector6<f64>,
    /// The vessel's force and moment on its node in the last static assembly (spatial).
    pub vessel_force: Vector6<f64>,
    /// Size of the vessel's static force in the last assembly (N).
    pub external_vessel_norm: f64,
    /// Factor on the rotational stiffness C_R (statics' continuation from a cable to the pipe; 1 otherwise).
    pub bending_scale: f64,
    /// Seabed contact, if the model has a seabed.
    pub contact: Option<SeabedContact>,
    /// Where statics' contact starts from: the positions and elastic friction slips of the last converged
    /// load step (initially the reference, without slip).
    pub contact_start: Vec<Vector3<f64>>,
    pub contact_slips: Vec<Vector2<f64>>,
    /// The vessel's rollers, if it has any.
    pub rollers: Option<RollerContact>,
}

/// The residual, magnitude and tangent entries of a run of consecutive nodes: everything their own DOFs' rows
/// (residual) and columns (tangent) hold. Two sinks split at a node write disjoint memory, so the rod's
/// elements and nodes can be assembled in parallel (see [`crate::solver::rod_step`]).
pub struct RodSink<'a> {
    /// The first node of the run.
    first_node: usize,
    residual: &'a mut [f64],
    magnitude: &'a mut [f64],
    /// The tangent values of the run's columns (`None`: residual only), from position `values_offset`.
    values: Option<&'a mut [f64]>,
    values_offset: usize,
    node_values: &'a [usize],
    elements: &'a ScatterMap,
    nodes: &'a ScatterMap,
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
struct Entries<'a> {
    values: &'a mut [f64],
    dofs: &'a DofMap,
    lu: &'a SparseLu,
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
struct ScatterMap {
    /// (first entry in the block, first value position, length), block after block.
    runs: Vec<(u32, u32, u32)>,
    /// Block b's runs are `runs[first[b]..first[b + 1]]`.
    first: Vec<usize>,
}

impl ScatterMap {
    /// From each block's value position of every entry (FIXED where the entry's row or column is prescribed).
    fn new<const N: usize>(positions: impl Iterator<Item = [u32; N]>) -> Self {
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
    fn add(&self, values: &mut [f64], index: usize, block: &[f64]) {
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
struct Scatter<'a> {
    values: &'a mut [f64],
    elements: &'a ScatterMap,
    nodes: &'a ScatterMap,
}

impl TangentSink for Scatter<'_> {
    fn add_element(&mut self, element: usize, block: &ElementMatrix) {
        self.elements.add(self.values, element, block.as_slice());
    }
    fn add_node(&mut self, node: usize, block: &Matrix6<f64>) {
        self.nodes.add(self.values, node, block.as_slice());
    }
}

/// Relative size of the shift added to the rotational diagonal of the tangent. It removes the exact
/// singularity of zero-stiffness rotation modes (a straight rod pinned at both ends spins freely about its
/// chord) and changes Newton's steps by about this relative amount; the residual, hence the solution, is
/// untouched.
const ROTATION_SHIFT: f64 = 1e-12;

impl Assembler {
    /// Builds the pattern and its symbolic factorisation for `model`.
    pub fn new(model: &Model) -> Self {
        let dofs = DofMap::new(model);
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
        let rollers = model.vessel.as_ref().and_then(|attachment| {
            RollerContact::new(
                attachment,
                model.rod.section.outer_diameter,
                &model.rod.arc_lengths(),
            )
        });
        if let (Some(rollers), Some(attachment)) = (&rollers, &model.vessel) {
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
                for b in nodes.clone().filter(|b| b.abs_diff(a) <= 3) {
                    couple(a, b);
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
        // With rollers, the vessel node's free unknowns are the border of the factorisation.
        let border: Vec<usize> = match (&rollers, &model.vessel) {
            (Some(_), Some(attachment)) => (0..NODE_DOFS)
                .filter_map(|k| dofs.equation[NODE_DOFS * attachment.node + k])
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
        let lu = SparseLu::for_rod(&dofs.free_dofs, col_ptr, row_idx, &border);
        let scatter = ScatterMap::new((0..elements).map(|e| {
            let mut map = [FIXED; 144];
            for j in 0..12 {
                for i in 0..12 {
                    if let (Some(row), Some(col)) =
                        (dofs.equation[global(e, i)], dofs.equation[global(e, j)])
                    {
                        // The pattern was built from these very element blocks.
                        #[allow(clippy::expect_used)]
                        let position = lu.position(row, col).expect("entry in the pattern");
                        map[12 * j + i] = position as u32;
                    }
                }
            }
            map
        }));
        let total = NODE_DOFS * model.rod.node_count();
        let rotation_diagonal = dofs
            .equation
            .iter()
            .enumerate()
            .filter(|(dof, _)| dof % NODE_DOFS >= 3)
            .filter_map(|(_, eq)| eq.and_then(|i| lu.position(i, i)))
            .collect();
        let node_scatter = ScatterMap::new((0..model.rod.node_count()).map(|node| {
            let mut map = [FIXED; 36];
            for j in 0..NODE_DOFS {
                for i in 0..NODE_DOFS {
                    let (row, col) = (
                        dofs.equation[NODE_DOFS * node + i],
                        dofs.equation[NODE_DOFS * node + j],
                    );
                    if let (Some(row), Some(col)) = (row, col) {
                        // The pattern was built from these very node blocks.
                        #[allow(clippy::expect_used)]
                        let position = lu.position(row, col).expect("entry in the pattern");
                        map[NODE_DOFS * j + i] = position as u32;
                    }
                }
            }
            map
        }));
        let contact = model.seabed().map(|seabed| {
            let lengths: Vec<f64> = model.rod.elements.iter().map(|e| e.length).collect();
            SeabedContact::new(
                seabed,
                &lengths,
                model.rod.section.outer_diameter,
                model.submerged_weight(),
            )
        });
        Assembler {
            rollers,
            bending_scale: 1.0,
            contact,
            contact_start: model.rod.nodes.clone(),
            contact_slips: vec![Vector2::zeros(); model.rod.node_count()],
            vessel_motion: 1.0,
            vessel_thrust: Vector6::zeros(),
            vessel_force: Vector6::zeros(),
            external_vessel_norm: 0.0,
            node_scatter,
            node_values,
            rotation_diagonal,
            point_load_scales: vec![1.0; model.point_loads.len()],
            values: vec![0.0; lu.nnz()],
            dofs,
            lu,
            residual: vec![0.0; total],
            support_coupling: vec![0.0; total],
            external: vec![0.0; total],
            scatter,
        }
    }

    /// Residual r = f_int − λ f_ext (all DOFs) and, if `with_tangent`, the free-DOF tangent at `config`.
    /// With `support_increment` (prescribed increments on all DOFs, zero where free) and a tangent, also
    /// K_fc Δu_c into `support_coupling`. Statics: drag from the current at t = 0 on the rod held still.
    pub fn assemble(
        &mut self,
        model: &Model,
        config: &Configuration,
        load_factor: f64,
        with_tangent: bool,
        support_increment: Option<&[f64]>,
    ) -> AssemblySummary {
        self.support_coupling.iter_mut().for_each(|r| *r = 0.0);
        self.external.iter_mut().for_each(|r| *r = 0.0);
        self.clear(with_tangent);
        let section = &model.rod.section;
        let (c_t, c_r) = (section.c_t(), section.c_r() * self.bending_scale);
        let weight = model.submerged_weight();
        let (k_axial, k_normal) = model.drag_coefficients();
        let has_drag = model
            .sea
            .as_ref()
            .is_some_and(|sea| sea.current.is_some() && k_axial + k_normal > 0.0);
        let mut strain_energy = 0.0;
        let mut max_element_rotation: f64 = 0.0;
        let mut k = ElementMatrix::zeros();
        for (e, reference) in model.rod.elements.iter().enumerate() {
            let (x1, x2) = (&config.positions[e], &config.positions[e + 1]);
            let response = evaluate(
                x1,
                x2,
                &config.rotations[e],
                &config.rotations[e + 1],
                reference,
                &c_t,
                &c_r,
                with_tangent.then_some(&mut k),
            );
            strain_energy += response.energy;
            max_element_rotation = max_element_rotation.max(response.relative_rotation);
            let base = NODE_DOFS * e;
            for (i, f) in response.forces.iter().enumerate() {
                self.residual[base + i] += f;
            }
            // Submerged weight: ½ L0 w e3 on each node (a dead load, no stiffness).
            let nodal_weight = 0.5 * reference.length * weight;
            self.external[base + 2] += nodal_weight;
            self.external[base + NODE_DOFS + 2] += nodal_weight;
            if has_drag {
                if let Some(sea) = &model.sea {
                    let (force, d1, d2) = element_current_drag(x1, x2, sea, 0.0, k_axial, k_normal);
                    for a in 0..2 {
                        for i in 0..3 {
                            self.external[base + NODE_DOFS * a + i] += force[i];
                        }
                    }
                    if with_tangent {
                        // r = f_int − λ f_ext: the load stiffness enters with −λ.
                        for a in 0..2 {
                            for (b, d) in [d1, d2].iter().enumerate() {
                                for i in 0..3 {
                                    for j in 0..3 {
                                        k[(NODE_DOFS * a + i, NODE_DOFS * b + j)] -=
                                            load_factor * d[(i, j)];
                                    }
                                }
                            }
                        }
                    }
                }
            }
            if let (true, Some(increment)) = (with_tangent, support_increment) {
                for j in 0..12 {
                    let du = increment[base + j];
                    if du != 0.0 && self.dofs.equation[base + j].is_none() {
                        for i in 0..12 {
                            self.support_coupling[base + i] += k[(i, j)] * du;
                        }
                    }
                }
            }
            if with_tangent {
                self.add_element_matrix(e, &k);
            }
        }
        for (load, scale) in model.point_loads.iter().zip(&self.point_load_scales) {
            let base = NODE_DOFS * load.node;
            for i in 0..3 {
                self.external[base + i] += scale * load.force[i];
                self.external[base + 3 + i] += scale * load.moment[i];
            }
        }
        let mut external_norm2 = 0.0;
        for (r, f) in self.residual.iter_mut().zip(&self.external) {
            *r -= load_factor * f;
            external_norm2 += (load_factor * f).powi(2);
        }
        self.external_vessel_norm = 0.0;
        if let Some(attachment) = &model.vessel {
            self.add_static_vessel(model, attachment, config, with_tangent);
        }
        if let Some(mut contact) = self.contact.take() {
            contact.set_static_nodes(&self.contact_start, &config.positions, &config.rotations);
            let slips = std::mem::take(&mut self.contact_slips);
            self.add_contact(&mut contact, ContactRule::Static, &slips, with_tangent);
            self.contact_slips = slips;
            self.contact = Some(contact);
        }
        self.add_rollers(ContactRule::Static, config, None, None, with_tangent);
        if with_tangent {
            self.shift_rotations();
        }
        AssemblySummary {
            external_norm: external_norm2.sqrt().max(self.external_vessel_norm),
            strain_energy,
            max_element_rotation,
        }
    }

    /// The vessel's static forces on its node (restoring, holding springs) with their tangent by central
    /// differences; records the holding thrust.
    fn add_static_vessel(
        &mut self,
        model: &Model,
        attachment: &VesselAttachment,
        config: &Configuration,
        with_tangent: bool,
    ) {
        let node = attachment.node;
        let target = StaticTarget::at(
            attachment,
            &model.rod.nodes[node],
            &model.rod.frames[node],
            self.vessel_motion,
        );
        let forces = |position: &Vector3<f64>, rotation: &UnitQuaternion<f64>| {
            static_forces(attachment, position, rotation, &target)
        };
        let (position, rotation) = (config.positions[node], config.rotations[node]);
        let (force, thrust) = forces(&position, &rotation);
        self.vessel_thrust = thrust;
        self.vessel_force = force;
        let base = NODE_DOFS * node;
        for i in 0..NODE_DOFS {
            self.residual[base + i] -= force[i];
        }
        self.external_vessel_norm = force.norm();
        if with_tangent {
            let mut block = Matrix6::zeros();
            for j in 0..NODE_DOFS {
                let h = if j < 3 {
                    1e-6 * (1.0 + position.norm())
                } else {
                    1e-7
                };
                let perturbed = |step: f64| {
                    let mut delta = Vector3::zeros();
                    delta[j % 3] = step;
                    if j < 3 {
                        forces(&(position + delta), &rotation).0
                    } else {
                        forces(&position, &(exp_quat(&delta) * rotation)).0
                    }
                };
                let column = (perturbed(h) - perturbed(-h)) / (2.0 * h);
                block.set_column(j, &(-column));
            }
            self.add_node_matrix(node, &block);
        }
    }

    /// Zeroes the residual and, with `with_tangent`, the tangent values.
    pub fn clear(&mut self, with_tangent: bool) {
        self.residual.iter_mut().for_each(|r| *r = 0.0);
        if with_tangent {
            self.values.iter_mut().for_each(|v| *v = 0.0);
        }
    }

    /// Adds an element's 12×12 tangent block (free entries only).
    pub fn add_element_matrix(&mut self, element: usize, k: &ElementMatrix) {
        self.scatter.add(&mut self.values, element, k.as_slice());
    }

    /// Adds a node's 6×6 tangent block (free entries only).
    pub fn add_node_matrix(&mut self, node: usize, k: &Matrix6<f64>) {
        self.node_scatter.add(&mut self.values, node, k.as_slice());
    }

    /// Where the rod's elements and nodes put their residual (all DOFs), its per-DOF magnitude `magnitude`
    /// and, with `with_tangent`, their tangent blocks: the whole rod.
    pub fn rod_sink<'a>(&'a mut self, magnitude: &'a mut [f64], with_tangent: bool) -> RodSink<'a> {
        RodSink {
            first_node: 0,
            residual: &mut self.residual,
            magnitude,
            values: with_tangent.then_some(&mut self.values[..]),
            values_offset: 0,
            node_values: &self.node_values,
            elements: &self.scatter,
            nodes: &self.node_scatter,
        }
    }

    /// Evaluates `contact` at the nodes set in it, from elastic slips `slips`, and adds its residual and (with
    /// `with_tangent`) its tangent. Returns the contact forces' work over the step (J).
    pub fn add_contact(
        &mut self,
        contact: &mut SeabedContact,
        rule: ContactRule,
        slips: &[Vector2<f64>],
        with_tangent: bool,
    ) -> f64 {
        let mut sink = Scatter {
            values: &mut self.values,
            elements: &self.scatter,
            nodes: &self.node_scatter,
        };
        let sink: Option<&mut dyn TangentSink> = if with_tangent { Some(&mut sink) } else { None };
        contact.evaluate(rule, slips, &mut self.residual, sink)
    }

    /// Adds the rollers' residual (and with `with_tangent` their tangent) at `config` + `increments` (see
    /// [`RollerContact::evaluate`]), and their forces' sizes to `magnitude`.
    pub fn add_rollers(
        &mut self,
        rule: ContactRule,
        config: &Configuration,
        increments: Option<&[f64]>,
        magnitude: Option<&mut [f64]>,
        with_tangent: bool,
    ) {
        let Some(rollers) = self.rollers.as_mut() else {
            return;
        };
        let mut entries = Entries {
            values: &mut self.values,
            dofs: &self.dofs,
            lu: &self.lu,
        };
        let sink: Option<&mut dyn EntrySink> = if with_tangent {
            Some(&mut entries)
        } else {
            None
        };
        rollers.evaluate(
            rule,
            &config.positions,
            &config.rotations,
            increments,
            &mut self.residual,
            magnitude,
            sink,
        );
    }

    /// Makes `config` (and the friction it mobilised) the start of statics' next load step.
    pub fn commit_contact(&mut self, config: &Configuration) {
        if let Some(contact) = &self.contact {
            self.contact_start.clone_from(&config.positions);
            self.contact_slips.clone_from(&contact.slip_end);
        }
    }

    /// Adds the small shift on the rotational diagonal (see [`ROTATION_SHIFT`]) once a tangent is complete.
    pub fn shift_rotations(&mut self) {
        let largest = largest_magnitude(&self.values);
        for &p in &self.rotation_diagonal {
            self.values[p] += ROTATION_SHIFT * largest;
        }
    }

    /// Gravity potential of the submerged weight, −Σ ½L0 w (z1 + z2) (J).
    pub fn gravity_potential(model: &Model, config: &Configuration) -> f64 {
        let weight = model.submerged_weight();
        model
            .rod
            .elements
            .iter()
            .enumerate()
            .map(|(e, r)| {
                -0.5 * r.length * weight * (config.positions[e].z + config.positions[e + 1].z)
            })
            .sum()
    }
}
