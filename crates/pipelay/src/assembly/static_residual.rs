//! The static residual r = f_int − λ f_ext over all DOFs and its tangent on the free DOFs: internal forces,
//! submerged weight, current drag on the rod held still, point loads, the vessel's static forces, seabed and
//! roller contact.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the mesh the assembler was built for.
#![allow(clippy::indexing_slicing)]
use crate::assembly::assembler::Assembler;
use crate::assembly::configuration::Configuration;
use crate::assembly::dofs::NODE_DOFS;
use crate::assembly::scatter::Entries;
use crate::contact::rule::ContactRule;
use crate::contact::sinks::EntrySink;
use crate::environment::drag::{element_current_drag, quadratic_jacobian};
use crate::model::Model;
use crate::rod::cable;
use crate::rod::element::{elastic_law, evaluate_with, ElementMatrix};
use crate::so3::exp_quat;
use crate::vessel::coupling::{static_forces, StaticTarget};
use crate::vessel::stinger_sections::Water;
use crate::vessel::VesselAttachment;
use nalgebra::{Matrix3, Matrix6, UnitQuaternion, Vector3};

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

impl Assembler {
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
        let has_current = model.sea.as_ref().is_some_and(|sea| sea.current.is_some());
        let mut strain_energy = 0.0;
        let mut max_element_rotation: f64 = 0.0;
        let mut k = ElementMatrix::zeros();
        // The continuation from a cable scales bending only: a free twist would leave the frames undetermined
        // about the tangent once a load leaves the pipe's plane.
        let rotational_scale = Vector3::new(1.0, self.bending_scale, self.bending_scale);
        let drag_factor = load_factor * self.current_scale;
        for (e, reference) in model.rod.elements.iter().enumerate() {
            let section = model.rod.section(e);
            let weight = model.submerged_weight(e);
            let (k_axial, k_normal) = model.drag_coefficients(e);
            let has_drag = has_current && k_axial + k_normal > 0.0;
            let (x1, x2) = (&config.positions[e], &config.positions[e + 1]);
            let forces = if section.cable {
                let response = cable::evaluate(
                    x1,
                    x2,
                    reference,
                    section.translational_stiffness.x,
                    with_tangent.then_some(&mut k),
                );
                strain_energy += response.energy;
                response.forces
            } else {
                let c_t = section.c_t();
                let c_r = Matrix3::from_diagonal(
                    &section
                        .rotational_stiffness
                        .component_mul(&rotational_scale),
                );
                let bending_scale = self.bending_scale;
                let plastic = &mut self.plastic;
                // A yielding wall's law from its fibres, else the elastic one.
                let mut law = |strain: &Vector3<f64>, curvature: &Vector3<f64>| {
                    plastic
                        .as_mut()
                        .and_then(|p| p.law(e, strain, curvature, bending_scale))
                        .unwrap_or_else(|| elastic_law(&c_t, &c_r, strain, curvature))
                };
                let response = evaluate_with(
                    x1,
                    x2,
                    &config.rotations[e],
                    &config.rotations[e + 1],
                    reference,
                    &mut law,
                    with_tangent.then_some(&mut k),
                );
                strain_energy += response.energy;
                max_element_rotation = max_element_rotation.max(response.relative_rotation);
                response.forces
            };
            let base = NODE_DOFS * e;
            for (i, f) in forces.iter().enumerate() {
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
                            self.external[base + NODE_DOFS * a + i] +=
                                self.current_scale * force[i];
                        }
                    }
                    if with_tangent {
                        // r = f_int − λ f_ext: the load stiffness enters with −λ.
                        for a in 0..2 {
                            for (b, d) in [d1, d2].iter().enumerate() {
                                for i in 0..3 {
                                    for j in 0..3 {
                                        k[(NODE_DOFS * a + i, NODE_DOFS * b + j)] -=
                                            drag_factor * d[(i, j)];
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
        self.add_static_attachments(model, config, load_factor, with_tangent);
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
        self.add_static_sections(model, config, with_tangent);
        if with_tangent {
            self.shift_rotations();
        }
        AssemblySummary {
            external_norm: external_norm2.sqrt().max(self.external_vessel_norm),
            strain_energy,
            max_element_rotation,
        }
    }

    /// An articulated stinger's sections: weight less buoyancy, drag in the current at t = 0 and hinge springs
    /// ([`crate::vessel::stinger_sections`]).
    fn add_static_sections(&mut self, model: &Model, config: &Configuration, with_tangent: bool) {
        let (Some(sections), Some(attachment)) = (&self.sections, &model.vessel) else {
            return;
        };
        let current_scale = self.current_scale;
        let current = |x: &Vector3<f64>| {
            model.sea.as_ref().map_or_else(Vector3::zeros, |sea| {
                current_scale * sea.current_at(x.z, 0.0).0
            })
        };
        let water = Water {
            density: model.water_density(),
            surface: attachment.surface,
            velocity: &current,
        };
        let node = attachment.node;
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
        sections.add_static(
            &config.positions[node],
            &config.rotations[node],
            &config.hinge_angles,
            &water,
            &mut self.residual,
            sink,
        );
    }

    /// The attachments' weight less buoyancy and their drag in the current at t = 0 (the line held still) as
    /// external loads on their elements' nodes, with the drag's tangent through a sheared current's depth.
    fn add_static_attachments(
        &mut self,
        model: &Model,
        config: &Configuration,
        load_factor: f64,
        with_tangent: bool,
    ) {
        let density = model.water_density();
        for (attachment, place) in model.placed_attachments() {
            let e = place.element;
            let point = place.point(&config.positions[e], &config.positions[e + 1]);
            let mut force = Vector3::z() * attachment.net_weight(density, model.gravity);
            let mut stiffness = None;
            if let Some(sea) = &model.sea {
                let (current, shear) = sea.current_at(point.z, 0.0);
                force += self.current_scale * attachment.drag(density, &current);
                if with_tangent && shear != Vector3::zeros() && attachment.drag_area > 0.0 {
                    let jacobian =
                        quadratic_jacobian(&current) * (0.5 * density * attachment.drag_area);
                    stiffness = Some(jacobian * shear);
                }
            }
            for (node, weight) in [e, e + 1].into_iter().zip(place.weights) {
                for i in 0..3 {
                    self.external[NODE_DOFS * node + i] += weight * force[i];
                }
            }
            // r = f_int − λ f_ext: ∂F/∂x_j = (∂F/∂U)(dU/dz) e3ᵀ N_j, entering with −λ N_i.
            if let Some(d_force) = stiffness {
                let mut k = ElementMatrix::zeros();
                for (a, &weight_a) in place.weights.iter().enumerate() {
                    for (b, &weight_b) in place.weights.iter().enumerate() {
                        for i in 0..3 {
                            k[(NODE_DOFS * a + i, NODE_DOFS * b + 2)] -=
                                load_factor * self.current_scale * weight_a * weight_b * d_force[i];
                        }
                    }
                }
                self.add_element_matrix(e, &k);
            }
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
}
