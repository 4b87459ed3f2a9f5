//! The assembler: the storage of one model's residual and tangent (its pattern analysed and its
//! factorisation set up once), and the adding of blocks, contact and rollers into it.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the mesh the assembler was built for (sizes fixed at construction).
#![allow(clippy::indexing_slicing)]
use crate::assembly::configuration::Configuration;
use crate::assembly::dofs::{DofMap, NODE_DOFS};
use crate::assembly::pattern::TangentPattern;
use crate::assembly::scatter::{Entries, RodSink, Scatter, ScatterMap, FIXED};
use crate::contact::rollers::RollerContact;
use crate::contact::rule::ContactRule;
use crate::contact::seabed::{ContactElement, SeabedContact};
use crate::contact::sinks::{EntrySink, TangentSink};
use crate::linalg::largest::largest_magnitude;
use crate::linalg::tangent_lu::TangentLu;
use crate::model::Model;
use crate::rod::element::ElementMatrix;
use crate::rod::plastic_state::PlasticState;
use crate::vessel::stinger_sections::StingerSections;
use nalgebra::{Matrix6, Vector2, Vector3, Vector6};

/// Assembles residuals and tangents of one model into preallocated storage.
pub struct Assembler {
    pub dofs: DofMap,
    /// The LU of the tangent's pattern.
    pub lu: TangentLu,
    /// Tangent values in pattern order.
    pub values: Vec<f64>,
    /// Residual over all DOFs.
    pub residual: Vec<f64>,
    /// K_fc Δu_c: the tangent's prescribed columns times the prescribed increments (all DOFs).
    pub support_coupling: Vec<f64>,
    pub(super) external: Vec<f64>,
    /// Where each element's 12×12 tangent block goes in `values`.
    pub(super) scatter: ScatterMap,
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
    /// Factor on the bending stiffnesses of C_R, not on the torsional one (statics' continuation from a cable to
    /// the pipe; 1 otherwise).
    pub bending_scale: f64,
    /// Factor on the current's drag on the rod and its attachments (statics' continuation from still water to
    /// the current; 1 otherwise).
    pub current_scale: f64,
    /// Seabed contact, if the model has a seabed.
    pub contact: Option<SeabedContact>,
    /// Where statics' contact starts from: the positions and elastic friction slips of the last converged
    /// load step (initially the reference, without slip).
    pub contact_start: Vec<Vector3<f64>>,
    pub contact_slips: Vec<Vector2<f64>>,
    /// The vessel's rollers, if it has any.
    pub rollers: Option<RollerContact>,
    /// An articulated stinger's sections, if the vessel has one.
    pub sections: Option<StingerSections>,
    /// The yielding elements' plastic state, if any segment's wall yields.
    pub plastic: Option<PlasticState>,
    /// Whether statics' Newton corrections are kept from carrying the line through the rollers
    /// ([`crate::statics::newton::roller_step_factor`]).
    pub limit_roller_steps: bool,
}

/// Relative size of the shift added to the rotational diagonal of the tangent. It removes the exact
/// singularity of zero-stiffness rotation modes (a straight rod pinned at both ends spins freely about its
/// chord) and changes Newton's steps by about this relative amount; the residual, hence the solution, is
/// untouched.
const ROTATION_SHIFT: f64 = 1e-12;

impl Assembler {
    /// Makes the yielding walls' evaluations start from the plastic states `plastic` (each element's fibres', as
    /// a run keeps them) instead of the model's state at rest ([`PlasticState::start_from`]).
    pub fn start_plastic_from(&mut self, plastic: &[Vec<f64>]) {
        if let Some(state) = self.plastic.as_mut() {
            state.start_from(plastic);
        }
    }

    /// Builds the pattern and its symbolic factorisation for `model`.
    pub fn new(model: &Model) -> Self {
        let dofs = DofMap::new(model);
        let elements = model.rod.element_count();
        let global = |e: usize, local: usize| NODE_DOFS * e + local;
        let rollers = model.vessel.as_ref().and_then(|attachment| {
            RollerContact::new(attachment, &model.rod, &model.rod.arc_lengths())
        });
        let TangentPattern {
            pattern,
            border,
            node_values,
        } = TangentPattern::new(model, &dofs, rollers.as_ref());
        let lu = TangentLu::for_rod(&dofs.free_dofs, pattern, &border);
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
        let node_dofs = NODE_DOFS * model.rod.node_count();
        let total = node_dofs + model.hinge_count();
        let rotation_diagonal = dofs
            .equation
            .iter()
            .enumerate()
            .filter(|(dof, _)| *dof < node_dofs && dof % NODE_DOFS >= 3)
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
            let elements = (0..elements).map(|e| ContactElement {
                length: model.rod.elements[e].length,
                diameter: model.rod.section(e).hydrodynamic_diameter,
                weight: model.submerged_weight(e),
            });
            SeabedContact::new(seabed, elements.collect(), model.rod.cable_nodes())
        });
        let sections = model.vessel.as_ref().and_then(|attachment| {
            StingerSections::new(attachment, model.rod.node_count(), model.gravity)
        });
        Assembler {
            plastic: model.plastic_state(),
            rollers,
            sections,
            bending_scale: 1.0,
            current_scale: 1.0,
            limit_roller_steps: true,
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
            &config.hinge_angles,
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

    /// Adds the small shift on the rotational diagonal (see `ROTATION_SHIFT`) once a tangent is complete.
    pub fn shift_rotations(&mut self) {
        let largest = largest_magnitude(&self.values);
        for &p in &self.rotation_diagonal {
            self.values[p] += ROTATION_SHIFT * largest;
        }
    }
}
