//! A step's residual and tangent at the current increments: the rod's elements and nodes
//! ([`crate::dynamics::rod_step`]), seabed contact, rollers, point loads and the vessel, with the step's
//! work and dissipation; and the predictor the increments start from.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the integrator's own mesh (rebuilt with it at every pay-out change).
#![allow(clippy::indexing_slicing)]
use crate::assembly::dofs::NODE_DOFS;
use crate::assembly::scatter::Entries;
use crate::contact::rule::ContactRule;
use crate::contact::seabed::{NodeStep, PARALLEL_NODES as PARALLEL_CONTACT_NODES};
use crate::contact::sinks::EntrySink;
use crate::dynamics::integrator::Integrator;
use crate::dynamics::ledger::StepWork;
use crate::dynamics::rod_step::{ElementOutputs, RodStep};
use crate::environment::drag::quadratic_jacobian;
use crate::error::Result;
use crate::linalg::pool;
use crate::model::SupportTarget;
use crate::rod::element::ElementMatrix;
use crate::so3::{cayley, cayley_parameter, cayley_tangent};
use crate::vessel::coupling::{predicted_node_increment, DynamicVessel};
use crate::vessel::hull_loads::HullStep;
use crate::vessel::stinger_sections::{SectionStep, Water};
use nalgebra::{Vector3, Vector6};
use rayon::prelude::*;

impl Integrator {
    /// Predictor: for free nodes, the last step's acceleration held, Δφ = v_n Δt + ½ a Δt² (the scheme's
    /// Δφ = ½(v_n + v_n+1)Δt with v_n+1 = v_n + aΔt), and constant angular velocity; the vessel's node with
    /// the vessel ([`predicted_node_increment`]); prescribed increments for supported DOFs. A stiff line's
    /// residual at the predictor is dominated by the axial strain of its error, O(Δt³) with the acceleration
    /// against O(Δt²) without. In a sea the vessel's node carries the largest error unless it follows the
    /// motion its RAOs prescribe: the J-lay of `examples/j_lay_waves.toml` starts its steps 0.2–0.3 off (relative
    /// residual) with the node's angular velocity held, 2e-3 so, and one factorisation a step then suffices.
    pub(super) fn predict(&mut self, targets: &[SupportTarget], dt: f64) {
        let state = &self.state;
        for node in 0..self.model.rod.node_count() {
            let dphi = (state.velocities[node] + 0.5 * dt * state.accelerations[node]) * dt;
            let theta =
                state.configuration.rotations[node] * state.body_angular_velocities[node] * dt;
            let base = NODE_DOFS * node;
            self.increments[base..base + 3].copy_from_slice(dphi.as_slice());
            self.increments[base + 3..base + 6].copy_from_slice(theta.as_slice());
        }
        // The vessel's node moves with the vessel: its low-frequency motion and its waves' offsets.
        if let (Some(attachment), Some(motion)) = (&self.model.vessel, &state.vessel) {
            let node = attachment.node;
            let increment = predicted_node_increment(
                attachment,
                &state.configuration.positions[node],
                &state.configuration.rotations[node],
                &motion.velocity,
                &motion.acceleration,
                self.vessel_waves.as_ref().map(|w| (&w.now, &w.next)),
                dt,
            );
            let base = NODE_DOFS * node;
            self.increments[base..base + 6].copy_from_slice(increment.as_slice());
        }
        for (i, rate) in state.hinge_rates.iter().enumerate() {
            self.increments[self.model.hinge_dof(i)] = rate * dt;
        }
        for target in targets {
            let base = NODE_DOFS * target.node;
            let dphi = target.position - state.configuration.positions[target.node];
            self.increments[base..base + 3].copy_from_slice(dphi.as_slice());
            if let Some(rotation) = target.rotation {
                let theta = cayley_parameter(
                    &(rotation * state.configuration.rotations[target.node].inverse()),
                );
                self.increments[base + 3..base + 6].copy_from_slice(theta.as_slice());
            }
        }
    }

    /// The waves' kinematics at each element's midpoint at the current increments (the predictor's), once per
    /// step.
    fn ensure_wave_kinematics(&mut self, time_mid: f64) {
        let Some(waves) = &self.model.waves else {
            return;
        };
        if self.model.sea.is_none() || !self.wave_kinematics.is_empty() {
            return;
        }
        let positions = &self.state.configuration.positions;
        let increments = &self.increments;
        let midpoint = |e: usize| {
            let moved = |node: usize| {
                Vector3::from_column_slice(&increments[NODE_DOFS * node..NODE_DOFS * node + 3])
            };
            0.5 * (positions[e] + positions[e + 1]) + 0.25 * (moved(e) + moved(e + 1))
        };
        let elements = self.model.rod.element_count();
        let kinematics = |e: usize| waves.kinematics(&midpoint(e), time_mid);
        if self.parallel() {
            pool::run(true, || {
                (0..elements)
                    .into_par_iter()
                    .map(kinematics)
                    .collect_into_vec(&mut self.wave_kinematics);
            });
        } else {
            self.wave_kinematics.extend((0..elements).map(kinematics));
        }
    }

    /// Residual (all DOFs), per-DOF magnitude, the step's work and, with `with_tangent`, the tangent (free
    /// DOFs), at the current increments.
    pub(super) fn assemble(
        &mut self,
        scales: &[f64],
        time_mid: f64,
        dt: f64,
        with_tangent: bool,
    ) -> Result<()> {
        self.assembler.clear(with_tangent);
        self.magnitude.iter_mut().for_each(|m| *m = 0.0);
        let mut work = StepWork::default();
        self.ensure_wave_kinematics(time_mid);
        let model = &self.model;
        let state = &self.state;
        // The yielding walls' fibres, held apart from the assembler while the rod's sink writes into it.
        let plastic = self.assembler.plastic.take();
        let rod = RodStep {
            model,
            constants: &self.segment_constants,
            positions: &state.configuration.positions,
            velocities: &state.velocities,
            gauss: &state.gauss,
            mass: &self.nodal.mass,
            axial_added_mass: &self.nodal.axial_added_mass,
            element_axial: &self.nodal.element_axial,
            node_start: &self.node_start,
            increments: &self.increments,
            waves: &self.wave_kinematics,
            growth: self.growth.map(|g| (g.element, g.length_start)),
            winch: self.growth.and_then(|g| g.winch),
            high_frequency_damping: self.options.high_frequency_damping,
            stress_rule: self.options.stress_rule,
            fibres: plastic.as_ref(),
            plastic: &state.plastic,
            serial_run: self.serial_run,
            dt,
            time_mid,
        };
        let mut sink = self.assembler.rod_sink(&mut self.magnitude, with_tangent);
        let outputs = ElementOutputs {
            next_plastic: &mut self.next_plastic,
            next_gauss: &mut self.next_gauss,
            work: &mut self.element_work,
        };
        rod.add_elements(&mut sink, outputs, with_tangent);
        rod.add_nodes(&mut sink, &mut self.node_dissipation, with_tangent);
        self.assembler.plastic = plastic;
        for element in &self.element_work {
            work.supplied += element.supplied;
            work.dissipated += element.dissipated;
            work.plastic += element.plastic;
        }
        work.dissipated += self.node_dissipation.iter().sum::<f64>();
        if let Some(growth) = self.growth.as_mut() {
            growth.internal_work = self.element_work[growth.element].internal;
        }
        if let Some(mut contact) = self.contact.take() {
            let increments = &self.increments;
            let positions = &state.configuration.positions;
            let (nodes, cable_nodes) = contact.steps_and_cable_nodes();
            nodes
                .par_iter_mut()
                .with_min_len(PARALLEL_CONTACT_NODES)
                .enumerate()
                .for_each(|(node, step)| {
                    let base = NODE_DOFS * node;
                    let displacement = Vector3::from_column_slice(&increments[base..base + 3]);
                    // A cable node's axis is its chords' at the step's start, held over the step.
                    if cable_nodes[node] {
                        *step = NodeStep {
                            start: positions[node],
                            displacement,
                            axis: crate::rod::chord_axis(positions, node),
                            axis_map: nalgebra::Matrix3::zeros(),
                        };
                        return;
                    }
                    let half_theta =
                        0.5 * Vector3::from_column_slice(&increments[base + 3..base + 6]);
                    let rotation_mid = cayley(&half_theta)
                        * state.configuration.rotations[node].to_rotation_matrix();
                    *step = NodeStep {
                        start: positions[node],
                        displacement,
                        axis: rotation_mid.column(0).into_owned(),
                        axis_map: 0.5 * cayley_tangent(&half_theta),
                    };
                });
            let rule = ContactRule::EnergyMomentum {
                time_step: dt,
                damping: self.options.high_frequency_damping,
            };
            self.assembler
                .add_contact(&mut contact, rule, &state.slips, with_tangent);
            for (node, force) in contact.forces.iter().enumerate() {
                for k in 0..3 {
                    self.magnitude[NODE_DOFS * node + k] += force[k].abs();
                }
            }
            work.dissipated += contact.dissipated;
            self.contact = Some(contact);
        }
        self.assembler.add_rollers(
            ContactRule::EnergyMomentum {
                time_step: dt,
                damping: self.options.high_frequency_damping,
            },
            &state.configuration,
            Some(&self.increments),
            Some(&mut self.magnitude),
            with_tangent,
        );
        // The rollers' friction dissipates what its springs do not store.
        work.dissipated += self
            .assembler
            .rollers
            .as_ref()
            .map_or(0.0, |r| r.dissipated);
        for (load, scale) in model.point_loads.iter().zip(scales) {
            let base = NODE_DOFS * load.node;
            let force = load.force * *scale;
            let moment = load.moment * *scale;
            for i in 0..3 {
                self.assembler.residual[base + i] -= force[i];
                self.assembler.residual[base + 3 + i] -= moment[i];
                self.magnitude[base + i] += force[i].abs();
                self.magnitude[base + 3 + i] += moment[i].abs();
            }
            let dphi = Vector3::from_column_slice(&self.increments[base..base + 3]);
            let theta = Vector3::from_column_slice(&self.increments[base + 3..base + 6]);
            work.supplied += force.dot(&dphi) + moment.dot(&theta);
        }
        // Before the vessel's: what the attachments put on the vessel's node is the line's force on it, and
        // the sections' loads join the rollers' there.
        if !model.attachments.is_empty() {
            self.add_attachments(time_mid, dt, with_tangent, &mut work);
        }
        self.add_sections(time_mid, dt, with_tangent, &mut work);
        let (model, state) = (&self.model, &self.state);
        self.vessel_step = None;
        if let (Some(attachment), Some(motion)) = (&model.vessel, &state.vessel) {
            let node = attachment.node;
            let base = NODE_DOFS * node;
            let increment = Vector6::from_column_slice(&self.increments[base..base + 6]);
            let vessel = DynamicVessel {
                attachment,
                velocity: motion.velocity,
                integral: motion.integral,
                hold_thrust: motion.hold_thrust,
                reference: self.reference_mid,
                waves: self.vessel_waves.as_ref().map(|w| (w.now, w.next)),
                applied_thrust: self.applied_thrust,
                hull: self.hull.as_ref().map(|environment| HullStep {
                    environment,
                    values: self.hull_values,
                }),
                passivity_scale: self.passivity_scale,
            };
            let contribution = vessel.contribution(
                &state.configuration.positions[node],
                &state.configuration.rotations[node],
                &increment,
                dt,
                time_mid,
                with_tangent,
            );
            self.rod_force_at_vessel =
                Vector6::from_column_slice(&self.assembler.residual[base..base + 6]);
            for i in 0..NODE_DOFS {
                self.assembler.residual[base + i] += contribution.residual[i];
                self.magnitude[base + i] += contribution.magnitude[i];
            }
            if with_tangent {
                self.assembler.add_node_matrix(node, &contribution.tangent);
            }
            work.supplied += contribution.supplied;
            work.dissipated += contribution.dissipated;
            self.vessel_step = Some(contribution);
        }
        self.work = work;
        Ok(())
    }

    /// An articulated stinger's sections over the step ([`crate::vessel::stinger_sections`]), in the current at
    /// the step's mid-time.
    fn add_sections(&mut self, time_mid: f64, dt: f64, with_tangent: bool, work: &mut StepWork) {
        let model = &self.model;
        let (Some(sections), Some(attachment)) = (&self.assembler.sections, &model.vessel) else {
            return;
        };
        // The current and the waves' particle velocity at a point.
        let velocity = |x: &Vector3<f64>| {
            let current = model
                .sea
                .as_ref()
                .map_or_else(Vector3::zeros, |sea| sea.current_at(x.z, time_mid).0);
            let waves = model
                .waves
                .as_ref()
                .map_or_else(Vector3::zeros, |w| w.kinematics(x, time_mid).velocity);
            current + waves
        };
        let water = Water {
            density: model.water_density(),
            surface: attachment.surface,
            velocity: &velocity,
        };
        let config = &self.state.configuration;
        let node = attachment.node;
        let step = SectionStep {
            position: config.positions[node],
            rotation: config.rotations[node],
            angles: &config.hinge_angles,
            velocities: &self.state.section_velocities,
            increments: &self.increments,
            dt,
        };
        let mut entries = Entries {
            values: &mut self.assembler.values,
            dofs: &self.assembler.dofs,
            lu: &self.assembler.lu,
        };
        let sink: Option<&mut dyn EntrySink> = if with_tangent {
            Some(&mut entries)
        } else {
            None
        };
        let section_work = sections.add_step(
            &step,
            &water,
            &mut self.assembler.residual,
            Some(&mut self.magnitude),
            sink,
        );
        work.supplied += section_work.supplied;
        work.dissipated += section_work.dissipated;
        self.section_work = section_work;
    }

    /// The attachments' weight less buoyancy (a dead load, its work the gravity potential's change) and drag
    /// on their elements' nodes, at the increments. The drag f = ½ρ C_dA |u|u acts on the flow relative to the
    /// point's mean velocity over the step, u = U − (N_a Δφ_a + N_b Δφ_b)/Δt, with the current U at the point's
    /// start and the step's mid-time; its work splits exactly into Δt f·U supplied and Δt ½ρ C_dA |u|³
    /// dissipated.
    fn add_attachments(&mut self, time_mid: f64, dt: f64, with_tangent: bool, work: &mut StepWork) {
        let model = &self.model;
        let positions = &self.state.configuration.positions;
        let density = model.water_density();
        for (attachment, place) in model.placed_attachments() {
            let e = place.element;
            let moved = |node: usize| {
                Vector3::from_column_slice(&self.increments[NODE_DOFS * node..NODE_DOFS * node + 3])
            };
            let displacement = place.point(&moved(e), &moved(e + 1));
            let mut force = Vector3::z() * attachment.net_weight(density, model.gravity);
            let mut d_flow = None;
            if let Some(sea) = &model.sea {
                let start = place.point(&positions[e], &positions[e + 1]);
                let (current, _) = sea.current_at(start.z, time_mid);
                let flow = current - displacement / dt;
                let drag = attachment.drag(density, &flow);
                force += drag;
                work.supplied += dt * drag.dot(&current);
                work.dissipated += dt * drag.dot(&flow);
                if with_tangent {
                    d_flow =
                        Some(quadratic_jacobian(&flow) * (0.5 * density * attachment.drag_area));
                }
            }
            for (node, weight) in [e, e + 1].into_iter().zip(place.weights) {
                for i in 0..3 {
                    self.assembler.residual[NODE_DOFS * node + i] -= weight * force[i];
                    self.magnitude[NODE_DOFS * node + i] += (weight * force[i]).abs();
                }
            }
            // ∂r_i/∂Δφ_j = −N_i ∂f/∂u ∂u/∂Δφ_j = N_i N_j (∂f/∂u)/Δt.
            if let Some(d_flow) = d_flow {
                let mut k = ElementMatrix::zeros();
                for (a, &weight_a) in place.weights.iter().enumerate() {
                    for (b, &weight_b) in place.weights.iter().enumerate() {
                        k.fixed_view_mut::<3, 3>(NODE_DOFS * a, NODE_DOFS * b)
                            .copy_from(&(d_flow * (weight_a * weight_b / dt)));
                    }
                }
                self.assembler.add_element_matrix(e, &k);
            }
        }
    }
}
