//! The rod's share of an energy–momentum step: each element's internal forces, submerged weight, waves'
//! inertia load and Morison drag, and each node's inertia and rotational damping, with their tangents.
//!
//! **In parallel, and the same bits as in series.** The elements are split in halves recursively
//! ([`pool::join`]) down to runs of [`pool::SERIAL_RUN`]; each half writes the rows and columns of its own nodes
//! only ([`RodSink`]), and the element at a split (whose two nodes fall in different halves) is added after
//! both halves. Every element first sums its terms locally and each residual, magnitude or tangent entry
//! then receives at most two element contributions from zero (0 + a + b = 0 + b + a exactly), so the result
//! does not depend on how the work was split or on the number of threads. The step's work is summed over the
//! elements in order, afterwards. Nodes write their own entries alone.
// Indexing cannot go out of bounds here: Node and element indices of the mesh (slices sized to it).
#![allow(clippy::indexing_slicing)]
use crate::assembly::dofs::NODE_DOFS;
use crate::assembly::scatter::RodSink;
use crate::environment::drag::{morison_drag, morison_force};
use crate::environment::waves::Kinematics;
use crate::linalg::pool;
use crate::model::Model;
use crate::rod::cable::{damping_step as cable_damping_step, step as cable_step};
use crate::rod::dynamic_element::{
    damping_matrices, elastic_step_law, step as element_step, step_with as element_step_with,
    with_damping, GaussPoint, StepStrains, StressRule,
};
use crate::rod::element::{ElementMatrix, ElementVector};
use crate::rod::plastic_state::PlasticState;
use crate::so3::{cayley, cayley_tangent, skew};
use crate::vessel::winch::WinchLaw;
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
use std::ops::{AddAssign, Range};

/// What a node's inertia and damping terms need from the step's start, computed once per step: the spatial
/// inertia I_n = Λ_n J Λ_nᵀ, the spatial angular momentum π_n = Λ_n J W_n, the damping c = Λ_n D Λ_nᵀ and the
/// node's axis t_n = Λ_n e1.
#[derive(Debug, Clone, Copy, Default)]
pub struct NodeStart {
    pub inertia: Matrix3<f64>,
    pub momentum: Vector3<f64>,
    pub damping: Matrix3<f64>,
    pub axis: Vector3<f64>,
}

/// Energy terms of one element in a step (J).
#[derive(Debug, Clone, Copy, Default)]
pub struct ElementWork {
    /// Work supplied by the waves' inertia load and the flow's drag.
    pub supplied: f64,
    /// Energy the drag dissipates.
    pub dissipated: f64,
    /// Work of the internal forces F·Δ less the high-frequency damping's (for the element that grows with
    /// pay-out: the stresses' work, whose difference from the stored energy's change pay-out brings in).
    pub internal: f64,
    /// The plastic part of `dissipated`: a yielding wall's.
    pub plastic: f64,
}

/// A segment's section's and the sea's constants its elements use.
#[derive(Debug, Clone, Copy)]
pub struct SegmentConstants {
    c_t: Matrix3<f64>,
    c_r: Matrix3<f64>,
    /// Submerged weight per length (N/m).
    weight: f64,
    /// Morison drag coefficients ½ρ C_d d, axial and normal.
    drag: (f64, f64),
    /// Whether the segment is a cable.
    cable: bool,
    /// A cable's axial internal damping B (N·s), its structural damping's included.
    axial_damping: f64,
    /// A rod's structural damping matrices (B_T, B_R) (N·s, N·m²·s), if it has any.
    structural_damping: Option<(Matrix3<f64>, Matrix3<f64>)>,
}

/// The constants of each segment of a model's line.
pub type RodConstants = Vec<SegmentConstants>;

/// The constants of `model`'s segments.
pub fn rod_constants(model: &Model) -> RodConstants {
    model
        .rod
        .sections
        .iter()
        .map(|section| {
            let (c_t, c_r) = (section.c_t(), section.c_r());
            let structural_damping = section
                .structural_damping
                .filter(|_| !section.cable)
                .map(|damping| damping.matrices(&c_t, &c_r));
            SegmentConstants {
                c_t,
                c_r,
                weight: model.submerged_weight_of(section),
                drag: model.drag_coefficients_of(section),
                cable: section.cable,
                axial_damping: section.cable_axial_damping(),
                structural_damping,
            }
        })
        .collect()
}

/// The step's inputs the rod's terms read.
pub struct RodStep<'a> {
    pub model: &'a Model,
    pub constants: &'a [SegmentConstants],
    /// Positions, velocities and Gauss points at the step's start.
    pub positions: &'a [Vector3<f64>],
    pub velocities: &'a [Vector3<f64>],
    pub gauss: &'a [GaussPoint],
    /// Nodal translational masses across the pipe and what the axial added mass adds along it (kg), and what
    /// the rotational terms need.
    pub mass: &'a [f64],
    pub axial_added_mass: &'a [f64],
    /// What the axial added mass adds along each cable element's chord (kg; zero for a rod's).
    pub element_axial: &'a [f64],
    pub node_start: &'a [NodeStart],
    /// The step's unknowns on all DOFs [Δφ_I, θ_I].
    pub increments: &'a [f64],
    /// The waves' kinematics at each element's midpoint (empty without waves).
    pub waves: &'a [Kinematics],
    /// With pay-out: the growing element and its length at the step's start (m).
    pub growth: Option<(usize, f64)>,
    /// The winch's law over the step, where its speed depends on its wire's tension (the growing element is
    /// then the wire's top).
    pub winch: Option<WinchLaw>,
    /// High-frequency damping ξ ([`with_damping`]; 0: none).
    pub high_frequency_damping: f64,
    pub stress_rule: StressRule,
    /// The yielding elements' wall fibres (None: no wall yields), and each element's fibres' plastic strains
    /// at the step's start (empty where it does not yield).
    pub fibres: Option<&'a PlasticState>,
    pub plastic: &'a [Vec<f64>],
    /// Elements and nodes assembled in one run ([`pool::SERIAL_RUN`]; the result does not depend on it).
    pub serial_run: usize,
    /// Time step and the step's mid-time (s).
    pub dt: f64,
    pub time_mid: f64,
}

/// One element's terms: forces on [x1, θ1, x2, θ2], their sizes and the Gauss point at n+1.
struct ElementShare {
    forces: ElementVector,
    magnitude: ElementVector,
    next: GaussPoint,
    work: ElementWork,
}

/// Per element, what a step writes besides the residual and tangent.
pub struct ElementOutputs<'a> {
    pub next_gauss: &'a mut [GaussPoint],
    pub work: &'a mut [ElementWork],
    /// A yielding element's fibres' plastic strains at the step's end.
    pub next_plastic: &'a mut [Vec<f64>],
}

impl RodStep<'_> {
    /// Adds every element's terms to `sink` (the whole rod) and writes `outputs`.
    pub fn add_elements(&self, sink: &mut RodSink, outputs: ElementOutputs, with_tangent: bool) {
        let elements = self.model.rod.element_count();
        self.add_element_run(0..elements, sink, outputs, with_tangent);
    }

    /// Elements `range` into `sink`, which holds the nodes from `range.start` to `range.end`; `outputs` holds
    /// the range's elements.
    fn add_element_run(
        &self,
        range: Range<usize>,
        sink: &mut RodSink,
        outputs: ElementOutputs,
        with_tangent: bool,
    ) {
        // The element tangent of the run, written whole by each element that asks for it.
        let mut tangent = ElementMatrix::zeros();
        if range.len() <= self.serial_run.max(1) {
            for (e, ((next, work), plastic)) in range.clone().zip(
                outputs
                    .next_gauss
                    .iter_mut()
                    .zip(outputs.work.iter_mut())
                    .zip(outputs.next_plastic.iter_mut()),
            ) {
                let share = self.element(e, with_tangent.then_some(&mut tangent), plastic);
                sink.add_element(e, &share.forces, &share.magnitude, &tangent);
                *next = share.next;
                *work = share.work;
            }
            return;
        }
        // Elements before the split, the split element, elements after it.
        let split = range.start + range.len() / 2;
        let local = split - range.start;
        let (next_left, next_rest) = outputs.next_gauss.split_at_mut(local);
        let (next_split, next_right) = next_rest.split_at_mut(1);
        let (work_left, work_rest) = outputs.work.split_at_mut(local);
        let (work_split, work_right) = work_rest.split_at_mut(1);
        let (plastic_left, plastic_rest) = outputs.next_plastic.split_at_mut(local);
        let (plastic_split, plastic_right) = plastic_rest.split_at_mut(1);
        let share = {
            let (mut left, mut right) = sink.split_at_node(split + 1);
            let left_outputs = ElementOutputs {
                next_gauss: next_left,
                work: work_left,
                next_plastic: plastic_left,
            };
            let right_outputs = ElementOutputs {
                next_gauss: next_right,
                work: work_right,
                next_plastic: plastic_right,
            };
            let (_, share) = pool::join(
                true,
                || self.add_element_run(range.start..split, &mut left, left_outputs, with_tangent),
                || {
                    let share = self.element(
                        split,
                        with_tangent.then_some(&mut tangent),
                        &mut plastic_split[0],
                    );
                    self.add_element_run(
                        split + 1..range.end,
                        &mut right,
                        right_outputs,
                        with_tangent,
                    );
                    share
                },
            );
            share
        };
        sink.add_element(split, &share.forces, &share.magnitude, &tangent);
        next_split[0] = share.next;
        work_split[0] = share.work;
    }

    /// Element `e`'s terms, and with `tangent` its tangent (all 144 entries written); a yielding element's
    /// plastic state at the step's end into `plastic_end`.
    fn element(
        &self,
        e: usize,
        mut tangent: Option<&mut ElementMatrix>,
        plastic_end: &mut [f64],
    ) -> ElementShare {
        let model = self.model;
        let reference = &model.rod.elements[e];
        let section = model.rod.section(e);
        let SegmentConstants {
            c_t,
            c_r,
            weight,
            drag: (k_axial, k_normal),
            cable,
            axial_damping,
            structural_damping,
        } = self.constants[model.rod.segment_of[e]];
        let dt = self.dt;
        let base = NODE_DOFS * e;
        let increments = ElementVector::from_column_slice(&self.increments[base..base + 12]);
        let positions = self.positions;
        let chord = positions[e + 1] - positions[e];
        let length_start = self
            .growth
            .filter(|&(element, _)| element == e)
            .map_or(reference.length, |(_, length)| length);
        let mut plastic_dissipated = 0.0;
        let mut damping_dissipated = 0.0;
        let damping = self.high_frequency_damping;
        let damped = damping > 0.0 || structural_damping.is_some();
        let step = if cable {
            let ea = c_t[(0, 0)];
            let winch = self
                .winch
                .filter(|_| self.growth.is_some_and(|(element, _)| element == e));
            let rendered = winch.map(|law| move |l: f64| law.length(ea, length_start, dt, l));
            cable_step(
                &chord,
                &increments,
                length_start,
                reference,
                ea,
                self.stress_rule,
                rendered
                    .as_ref()
                    .map(|law| law as &dyn Fn(f64) -> (f64, f64)),
                tangent.as_deref_mut(),
            )
        } else if let Some(fibres) = self
            .fibres
            .and_then(|p| p.fibres(e))
            .map(Some)
            .or(damped.then_some(None))
        {
            // A yielding wall's resultants averaged over its fibres' strain paths (its dissipation booked), or
            // the elastic law's; then the high-frequency and structural damping's stresses.
            let start = &self.plastic[e];
            let (d_t, d_r) = damping_matrices(damping, &c_t, &c_r, structural_damping.as_ref(), dt);
            let mut law = |strains: &StepStrains| {
                let law = match fibres {
                    Some(fibres) => {
                        let law = fibres.step_law(&strains.start, &strains.end, start, plastic_end);
                        plastic_dissipated = reference.length * law.dissipated;
                        law
                    }
                    None => elastic_step_law(&c_t, &c_r, strains),
                };
                let (law, damped) = with_damping(law, strains, &d_t, &d_r);
                damping_dissipated = reference.length * damped;
                law
            };
            element_step_with(
                &chord,
                &increments,
                &self.gauss[e],
                length_start,
                reference,
                self.stress_rule,
                &mut law,
                tangent.as_deref_mut(),
            )
        } else {
            element_step(
                &chord,
                &increments,
                &self.gauss[e],
                length_start,
                reference,
                &c_t,
                &c_r,
                self.stress_rule,
                tangent.as_deref_mut(),
            )
        };
        let mut work = ElementWork {
            internal: step.forces.dot(&increments) - damping_dissipated,
            dissipated: plastic_dissipated + damping_dissipated,
            plastic: plastic_dissipated,
            ..ElementWork::default()
        };
        let mut forces = step.forces;
        // A cable's high-frequency damping: ξ EA Δε, the axial damping B ε̇ with B = ξ EA Δt.
        let cable_damping = axial_damping + damping * c_t[(0, 0)] * dt;
        if cable && cable_damping > 0.0 {
            let (damping, dissipated) = cable_damping_step(
                &chord,
                &increments,
                length_start,
                reference.length,
                cable_damping,
                dt,
                tangent.as_deref_mut(),
            );
            forces += damping;
            work.dissipated += dissipated;
        }
        let mut magnitude = forces.abs();
        // Submerged weight, a dead load: −½L0 w e3 in the residual of each node.
        let nodal_weight = 0.5 * reference.length * weight;
        forces[2] -= nodal_weight;
        forces[8] -= nodal_weight;
        magnitude[2] += nodal_weight.abs();
        magnitude[8] += nodal_weight.abs();
        let dphi1 = increments.fixed_rows::<3>(0).into_owned();
        let dphi2 = increments.fixed_rows::<3>(6).into_owned();
        if self.element_axial[e] != 0.0 {
            self.cable_axial_inertia(
                e,
                &dphi1,
                &dphi2,
                &mut forces,
                &mut magnitude,
                tangent.as_deref_mut(),
            );
        }
        // Half of a force on the element's midpoint to each node.
        let mut share_force = |force: &Vector3<f64>| {
            for a in 0..2 {
                for i in 0..3 {
                    forces[NODE_DOFS * a + i] -= 0.5 * force[i];
                    magnitude[NODE_DOFS * a + i] += 0.5 * force[i].abs();
                }
            }
        };
        // The waves at the element's midpoint, and their Froude–Krylov and added-mass load
        // ρ A [(1 + C_an)(u̇ − (t·u̇)t) + (1 + C_aa)(t·u̇)t] (t the element's direction at the step's start),
        // whose work is supplied. They are taken at the predictor's midpoint, once per step: the sum over the
        // sea's components costs more than the rest of the element, and the position error is the
        // predictor's, O(Δt³).
        let waves = match (self.waves.get(e), &model.sea) {
            (Some(kinematics), Some(sea)) => {
                let [axial, normal] = section.added_mass;
                let inertia = if axial == normal {
                    (1.0 + normal)
                        * sea.density
                        * section.displaced_area
                        * reference.length
                        * kinematics.acceleration
                } else {
                    let t = chord.normalize();
                    let along = t * t.dot(&kinematics.acceleration);
                    sea.density
                        * section.displaced_area
                        * reference.length
                        * ((1.0 + normal) * (kinematics.acceleration - along)
                            + (1.0 + axial) * along)
                };
                work.supplied += 0.5 * inertia.dot(&(dphi1 + dphi2));
                share_force(&inertia);
                Some(kinematics)
            }
            _ => None,
        };
        if let (Some(sea), true) = (&model.sea, k_axial + k_normal > 0.0) {
            let tangent_mid = (chord + 0.5 * (dphi2 - dphi1)) / reference.length;
            let stretch = tangent_mid.norm();
            let t = tangent_mid / stretch;
            let length = reference.length * stretch;
            let z_mid = 0.5 * (positions[e].z + positions[e + 1].z) + 0.25 * (dphi1.z + dphi2.z);
            let (current, current_shear) = sea.current_at(z_mid, self.time_mid);
            let mut flow = current;
            if let Some(kinematics) = waves {
                flow += kinematics.velocity;
            }
            let velocity = 0.5 * (dphi1 + dphi2) / dt;
            let relative = flow - velocity;
            // With a tangent, the drag's derivatives too (they include the force).
            let drag = tangent
                .is_some()
                .then(|| morison_drag(&relative, &t, k_axial, k_normal));
            let drag_force = drag.as_ref().map_or_else(
                || morison_force(&relative, &t, k_axial, k_normal),
                |drag| drag.force,
            );
            let force = length * drag_force;
            work.supplied += dt * force.dot(&flow);
            work.dissipated += dt * length * drag_force.dot(&relative);
            share_force(&force);
            // dF/dΔφ_b for b = 1, 2 (s_b = ∓1): through ℓ and t (via φ′_{n+½}) and the relative flow.
            if let (Some(tangent), Some(drag)) = (tangent, drag) {
                let projector = Matrix3::identity() - t * t.transpose();
                let d_chord = 0.5 * (drag.force * t.transpose() + drag.d_tangent * projector);
                let d_flow = length * drag.d_flow;
                let d_velocity = -0.5 / dt * d_flow;
                // Through the midpoint's depth, where the current is sheared: ∂U/∂x = U′(z) e3ᵀ at the
                // midpoint (the waves are held over the step).
                let (d1, d2) = if current_shear == Vector3::zeros() {
                    (-d_chord + d_velocity, d_chord + d_velocity)
                } else {
                    let flow_gradient = current_shear * Vector3::z().transpose();
                    let d_depth = 0.25 * d_flow * flow_gradient;
                    (
                        -d_chord + d_depth + d_velocity,
                        d_chord + d_depth + d_velocity,
                    )
                };
                for a in 0..2 {
                    let mut by_phi1 = tangent.fixed_view_mut::<3, 3>(NODE_DOFS * a, 0);
                    by_phi1 -= 0.5 * d1;
                    let mut by_phi2 = tangent.fixed_view_mut::<3, 3>(NODE_DOFS * a, NODE_DOFS);
                    by_phi2 -= 0.5 * d2;
                }
            }
        }
        ElementShare {
            forces,
            magnitude,
            next: step.next,
            work,
        }
    }

    /// The inertia of cable element `e`'s axial added mass: with P(t, ū) = d t (t·ū) (t the unit chord, ū the
    /// element's mean velocity), the force ½(P_{n+1} − P_n)/Δt on each node conserves the momentum; its work
    /// ū̄·ΔP exceeds the change of ½d(t·ū)² by Δg = d (S t̄)·Δt (S = ½(ū_n ū_{n+1}ᵀ + ū_{n+1} ū_nᵀ), as at a rod's
    /// node). The chord forces ∓∇̄h, ∇̄h the discrete gradient (Gonzalez) of h(c) = w·c/|c| with w = d S t̄, do
    /// the work −Δg: the inertia's work is the kinetic energy's change to round-off. Its tangent holds the
    /// momentum's derivatives; the chord forces' (of order d|ū|²/l) are left out, which Newton absorbs.
    fn cable_axial_inertia(
        &self,
        e: usize,
        dphi1: &Vector3<f64>,
        dphi2: &Vector3<f64>,
        forces: &mut ElementVector,
        magnitude: &mut ElementVector,
        tangent: Option<&mut ElementMatrix>,
    ) {
        let dt = self.dt;
        let d = self.element_axial[e];
        let chord_n = self.positions[e + 1] - self.positions[e];
        let chord_next = chord_n + dphi2 - dphi1;
        let (length_n, length_next) = (chord_n.norm(), chord_next.norm());
        let (t_n, t_next) = (chord_n / length_n, chord_next / length_next);
        let u_n = 0.5 * (self.velocities[e] + self.velocities[e + 1]);
        let u_next = (dphi1 + dphi2) / dt - u_n;
        let half_force = 0.5 * d * (t_next * t_next.dot(&u_next) - t_n * t_n.dot(&u_n)) / dt;
        let t_mean = 0.5 * (t_n + t_next);
        let w = d * 0.5 * (u_n * u_next.dot(&t_mean) + u_next * u_n.dot(&t_mean));
        // ∇̄h: ∇h at the mean chord, plus the part along Δc that makes ∇̄h·Δc = h(c_{n+1}) − h(c_n) exactly.
        let chord_mean = 0.5 * (chord_n + chord_next);
        let length_mean = chord_mean.norm();
        let t_mid = chord_mean / length_mean;
        let mut gradient = (w - t_mid * t_mid.dot(&w)) / length_mean;
        let change = chord_next - chord_n;
        let change2 = change.norm_squared();
        if change2 > 1e-24 * length_mean * length_mean {
            let exact = w.dot(&(t_next - t_n));
            gradient += change * ((exact - gradient.dot(&change)) / change2);
        }
        for (node, sign) in [(0, 1.0), (NODE_DOFS, -1.0)] {
            for i in 0..3 {
                let value = half_force[i] + sign * gradient[i];
                forces[node + i] += value;
                magnitude[node + i] += value.abs();
            }
        }
        if let Some(tangent) = tangent {
            // ∂(½P_{n+1}/Δt)/∂Δφ_a: through ū_{n+1} (∂/∂Δφ_a = I/Δt) and t_{n+1} (∓(I − t tᵀ)/|c|).
            let by_velocity = t_next * t_next.transpose() * (0.5 * d / (dt * dt));
            let by_chord = (Matrix3::identity() * t_next.dot(&u_next)
                + t_next * u_next.transpose())
                * (Matrix3::identity() - t_next * t_next.transpose())
                * (0.5 * d / (dt * length_next));
            for row in [0, NODE_DOFS] {
                let mut first = tangent.fixed_view_mut::<3, 3>(row, 0);
                first += by_velocity - by_chord;
                let mut second = tangent.fixed_view_mut::<3, 3>(row, NODE_DOFS);
                second += by_velocity + by_chord;
            }
        }
    }

    /// Adds every node's inertia and rotational damping to `sink` (the whole rod); writes each node's
    /// dissipation into `dissipated`.
    pub fn add_nodes(&self, sink: &mut RodSink, dissipated: &mut [f64], with_tangent: bool) {
        self.add_node_run(0..dissipated.len(), sink, dissipated, with_tangent);
    }

    fn add_node_run(
        &self,
        range: Range<usize>,
        sink: &mut RodSink,
        dissipated: &mut [f64],
        with_tangent: bool,
    ) {
        if range.len() <= self.serial_run.max(1) {
            for (node, dissipated) in range.zip(dissipated.iter_mut()) {
                *dissipated = self.node(node, sink, with_tangent);
            }
            return;
        }
        let split = range.start + range.len() / 2;
        let (mut left, mut right) = sink.split_at_node(split);
        let (dissipated_left, dissipated_right) = dissipated.split_at_mut(split - range.start);
        pool::join(
            true,
            || self.add_node_run(range.start..split, &mut left, dissipated_left, with_tangent),
            || self.add_node_run(split..range.end, &mut right, dissipated_right, with_tangent),
        );
    }

    /// Adds node `node`'s inertia and damping terms to `sink`; returns the energy its damping dissipates (J).
    fn node(&self, node: usize, sink: &mut RodSink, with_tangent: bool) -> f64 {
        let dt = self.dt;
        let base = NODE_DOFS * node;
        let dphi = Vector3::from_column_slice(&self.increments[base..base + 3]);
        let theta = Vector3::from_column_slice(&self.increments[base + 3..base + 6]);
        // Translational inertia: M(v_{n+1} − v_n)/Δt with v_{n+1} = 2Δφ/Δt − v_n.
        let mass = self.mass[node];
        let inertia_force = mass * (2.0 * dphi / dt - 2.0 * self.velocities[node]) / dt;
        // Rotational inertia in spatial momentum: (π_{n+1} − π_n)/Δt, π_{n+1} = cay(θ)[(2/Δt)I_nθ − π_n].
        let NodeStart {
            inertia: inertia_n,
            momentum: momentum_n,
            damping,
            ..
        } = self.node_start[node];
        let q = cayley(&theta);
        let momentum_next = q * (2.0 / dt * inertia_n * theta - momentum_n);
        // Rotational damping D_R: m = −cθ/Δt, c = Λ_n D Λ_nᵀ.
        let moment = (momentum_next - momentum_n) / dt + damping * theta / dt;
        let mut forces = Vector6::zeros();
        forces.fixed_rows_mut::<3>(0).copy_from(&inertia_force);
        forces.fixed_rows_mut::<3>(3).copy_from(&moment);
        let tangent = with_tangent.then(|| {
            let mut block = Matrix6::zeros();
            let rotation_block =
                (2.0 / dt * q * inertia_n - skew(&momentum_next) * cayley_tangent(&theta)) / dt
                    + damping / dt;
            block
                .fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&(Matrix3::identity() * (2.0 * mass / (dt * dt))));
            block
                .fixed_view_mut::<3, 3>(3, 3)
                .copy_from(&rotation_block);
            block
        });
        let mut tangent = tangent;
        if self.axial_added_mass[node] != 0.0 {
            let (force, moment) =
                self.axial_added_mass_terms(node, &dphi, &theta, &q, tangent.as_mut());
            forces.fixed_rows_mut::<3>(0).add_assign(&force);
            forces.fixed_rows_mut::<3>(3).add_assign(&moment);
        }
        sink.add_node(node, &forces, &forces.abs(), tangent.as_ref());
        theta.dot(&(damping * theta)) / dt
    }

    /// The axial added mass's part of node `node`'s inertia, and its derivatives added to `tangent`.
    ///
    /// With M(t) = m I + d t tᵀ (d = `axial_added_mass`, t the node's axis), the translational inertia is
    /// (M(t_{n+1}) v_{n+1} − M(t_n) v_n)/Δt, which conserves the momentum M v; its work over the step,
    /// v̄·(M_{n+1}v_{n+1} − M_n v_n), exceeds the change of ½vᵀMv by ½ v_nᵀ(M_{n+1} − M_n)v_{n+1} = g(t_{n+1}) −
    /// g(t_n), g(t) = ½ d (t·v_n)(t·v_{n+1}). That g is quadratic in t, so g(t_{n+1}) − g(t_n) = d (S t̄)·Δt
    /// exactly (S = ½(v_n v_{n+1}ᵀ + v_{n+1}v_nᵀ), t̄ the mean axis), and the Cayley update makes
    /// Δt = θ × t̄ exactly. The moment m = −d t̄ × (S t̄) does the work −(g(t_{n+1}) − g(t_n)): the inertia's
    /// work is then the kinetic energy's change to round-off (a discrete gradient in t).
    fn axial_added_mass_terms(
        &self,
        node: usize,
        dphi: &Vector3<f64>,
        theta: &Vector3<f64>,
        q: &Matrix3<f64>,
        tangent: Option<&mut Matrix6<f64>>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let dt = self.dt;
        let d = self.axial_added_mass[node];
        let start = self.node_start[node].axis;
        let v_n = self.velocities[node];
        let v_next = 2.0 * dphi / dt - v_n;
        let end = q * start;
        let mean = 0.5 * (start + end);
        let force = d * (end * end.dot(&v_next) - start * start.dot(&v_n)) / dt;
        let s_mean = 0.5 * (v_n * v_next.dot(&mean) + v_next * v_n.dot(&mean));
        let moment = -d * mean.cross(&s_mean);
        if let Some(block) = tangent {
            // ∂t_{n+1}/∂θ = −t̂_{n+1} T(θ); ∂v_{n+1}/∂Δφ = (2/Δt) I.
            let turn = -skew(&end) * cayley_tangent(theta);
            let force_dphi = end * end.transpose() * (2.0 * d / (dt * dt));
            let force_theta = (Matrix3::identity() * end.dot(&v_next) + end * v_next.transpose())
                * turn
                * (d / dt);
            let s = 0.5 * (v_n * v_next.transpose() + v_next * v_n.transpose());
            let moment_theta = (skew(&s_mean) - skew(&mean) * s) * (0.5 * d) * turn;
            let moment_dphi = -skew(&mean)
                * (v_n * mean.transpose() + Matrix3::identity() * v_n.dot(&mean))
                * (d / dt);
            let mut add = |row: usize, column: usize, part: &Matrix3<f64>| {
                let mut view = block.fixed_view_mut::<3, 3>(row, column);
                view += part;
            };
            add(0, 0, &force_dphi);
            add(0, 3, &force_theta);
            add(3, 0, &moment_dphi);
            add(3, 3, &moment_theta);
        }
        (force, moment)
    }
}
