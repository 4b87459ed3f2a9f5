//! Seabed contact of the rod, in statics and in the energy–momentum step.
//!
//! **Normal contact, integrated along each element.** With δ_a = δ(x_a) the penetration of node a (see
//! [`crate::environment::bathymetry`]) and the penetration interpolated linearly along the element, the
//! element's contact energy is V_e = ½ k d L0 I(δ1, δ2), I = ∫₀¹ ((1 − ξ)δ1 + ξδ2)₊² dξ, in closed form:
//! (δ1² + δ1δ2 + δ2²)/3 when both nodes penetrate, δ1³/(3(δ1 − δ2)) when only node 1 does, 0 when neither.
//! I is C¹ (C² where one node crosses zero), so the touchdown moves smoothly through an element. The force on
//! node a is −P_a ∇δ_a with the nodal resultant P_a = Σ_e ∂V_e/∂δ_a (N).
//!
//! **Energy–momentum step.** The contact enters through a discrete gradient: Gonzalez's
//! ∇̄V = ∇V(mid) + [ΔV − ∇V(mid)·Δ]Δ/|Δ|², first for each element's V_e(δ1, δ2) in the nodal penetrations, then
//! for each node's δ(x) in its position (exact and constant for a plane). So Σ_a F_a·Δx_a = −ΔV exactly.
//! Normal damping −c d ℓ_a χ (n̄·v̄)n̄ acts at nodes in contact at the step midpoint (ℓ_a the tributary length,
//! v̄ = Δx/Δt, χ rising smoothly from 0 to 1 over the first resting penetration w/(k d) of the mean
//! penetration), dissipating c d ℓ_a χ (n̄·Δx)²/Δt ≥ 0.
//!
//! **Friction, elastic then sliding, at the nodes.** Each node carries an elastic slip e = (axial, lateral)
//! in the seabed's tangent plane, along t̂ (the section axis t1 projected on the plane) and l̂ = n̂ × t̂. A step
//! moves it by Δu = (t̂·Δx, l̂·Δx); the trial e + Δu returns radially onto |e| ≤ r = δ_m N/(w ℓ_a) (N the
//! node's normal force at the step's end, w the submerged weight per length). The friction spring has the
//! constant stiffness K = diag(μ_axial, μ_lateral) w ℓ_a/δ_m, so a pipe pressed by its own weight mobilises
//! μN at the mobilisation distance δ_m, and its stored energy ½eᵀKe belongs to the seabed's energy. In
//! statics the force is −Ke at the current state. In the energy–momentum step it is −Kē (ē the step's mean)
//! plus −½(KΔe·Δp)Δx/|Δx|², which makes the work exactly −Δψ − D with the dissipation D = (Ke_{n+1})·Δp ≥ 0
//! (Δp the slip of the return map). The kernel and its exact tangent are [`crate::contact::friction`]'s.
// Indexing cannot go out of bounds here: Node and element indices of the mesh the contact was built for.
#![allow(clippy::indexing_slicing)]
use crate::contact::friction::FrictionNode;
use crate::contact::rule::ContactRule;
use crate::contact::sinks::TangentSink;
use crate::contact::touchdown::{touchdown, Touchdown};
use crate::environment::bathymetry::{Bathymetry, Penetration};
use crate::environment::seabed::Seabed;
use crate::rod::element::ElementMatrix;
use crate::so3::skew;
use nalgebra::{Matrix2, Matrix3, Matrix6, UnitQuaternion, Vector2, Vector3};
use rayon::prelude::*;

/// Nodes per parallel task in a contact evaluation, and where the integrator sets up the nodes' steps.
pub const PARALLEL_NODES: usize = 512;

/// I(δ1, δ2) = ∫₀¹ ((1 − ξ)δ1 + ξδ2)₊² dξ with its gradient and Hessian.
fn contact_integral(d1: f64, d2: f64) -> (f64, Vector2<f64>, Matrix2<f64>) {
    if d1 >= 0.0 && d2 >= 0.0 {
        (
            (d1 * d1 + d1 * d2 + d2 * d2) / 3.0,
            Vector2::new(2.0 * d1 + d2, d1 + 2.0 * d2) / 3.0,
            Matrix2::new(2.0, 1.0, 1.0, 2.0) / 3.0,
        )
    } else if d1 <= 0.0 && d2 <= 0.0 {
        (0.0, Vector2::zeros(), Matrix2::zeros())
    } else if d1 > 0.0 {
        let span = d1 - d2;
        let (r, r2) = (d1 / span, (d1 / span).powi(2));
        let value = d1 * d1 * r / 3.0;
        let gradient = Vector2::new(d1 * r - d1 * r2 / 3.0, d1 * r2 / 3.0);
        let h11 = 2.0 * r - 2.0 * r2 + 2.0 * r2 * r / 3.0;
        let h12 = r2 - 2.0 * r2 * r / 3.0;
        let h22 = 2.0 * r2 * r / 3.0;
        (value, gradient, Matrix2::new(h11, h12, h12, h22))
    } else if d2 > 0.0 {
        let (value, g, h) = contact_integral(d2, d1);
        (
            value,
            Vector2::new(g.y, g.x),
            Matrix2::new(h[(1, 1)], h[(1, 0)], h[(0, 1)], h[(0, 0)]),
        )
    } else {
        // A NaN penetration (a state gone non-finite): NaN out, for the solver's finiteness checks to report.
        (
            f64::NAN,
            Vector2::repeat(f64::NAN),
            Matrix2::repeat(f64::NAN),
        )
    }
}

/// Whether I(δ1, δ2) vanishes with its derivatives: neither node penetrates and one stands clear (at
/// δ1 = δ2 = 0 the Hessian is not zero).
fn clear(penetrations: &Vector2<f64>) -> bool {
    penetrations.max() <= 0.0 && penetrations.min() < 0.0
}

/// Gonzalez's discrete gradient of f between a and a + u, given f, ∇f at both ends and ∇f, ∇²f at the
/// midpoint; returns it and its derivative with respect to u.
fn gonzalez<const D: usize>(
    change: f64,
    u: &nalgebra::SVector<f64, D>,
    gradient_end: &nalgebra::SVector<f64, D>,
    gradient_mid: &nalgebra::SVector<f64, D>,
    hessian_mid: &nalgebra::SMatrix<f64, D, D>,
    tiny: f64,
) -> (nalgebra::SVector<f64, D>, nalgebra::SMatrix<f64, D, D>) {
    let u2 = u.norm_squared();
    if u2 <= tiny * tiny {
        return (*gradient_mid, 0.5 * hessian_mid);
    }
    let c = (change - gradient_mid.dot(u)) / u2;
    let dc = (gradient_end - gradient_mid - 0.5 * hessian_mid * u) / u2 - u * (2.0 * c / u2);
    (
        gradient_mid + u * c,
        0.5 * hessian_mid + u * dc.transpose() + nalgebra::SMatrix::<f64, D, D>::identity() * c,
    )
}

/// The state of one node entering a contact evaluation.
#[derive(Debug, Clone, Copy, Default)]
pub struct NodeStep {
    /// Position at the step's start (statics: at the last converged load step).
    pub start: Vector3<f64>,
    /// Displacement over the step Δx (the unknown).
    pub displacement: Vector3<f64>,
    /// Section axis t1 where friction's directions are taken (statics: now; dynamics: at the midpoint).
    pub axis: Vector3<f64>,
    /// δt1 = −t̂1 M δθ: how the axis turns with the node's rotation unknowns.
    pub axis_map: Matrix3<f64>,
}

/// Seabed contact of one model: constants and per-node work space, reused every evaluation.
#[derive(Debug, Clone)]
pub struct SeabedContact {
    bathymetry: Bathymetry,
    /// ½ k d L0 per element (N/m).
    element_scale: Vec<f64>,
    /// Each element's reference length (m).
    element_lengths: Vec<f64>,
    /// The nodes whose friction directions follow their chords (a cable's, without a rotation).
    cable_nodes: Vec<bool>,
    /// c d ℓ_a per node (N·s/m).
    damping: Vec<f64>,
    /// Penetration over which damping grows to its full value: the resting penetration w/(k d) (m).
    damping_ramp: f64,
    /// Friction stiffness diag(μ_a, μ_l) w ℓ_a / δ_m per node (N/m); zero without friction.
    friction_stiffness: Vec<Vector2<f64>>,
    /// δ_m / (w ℓ_a) per node: the elastic radius per newton of normal force (m/N).
    yield_per_force: Vec<f64>,
    has_friction: bool,
    /// Factor on the friction forces (statics' continuation from a frictionless seabed; 1 otherwise).
    pub friction_scale: f64,
    /// Inputs of the last evaluation.
    pub nodes: Vec<NodeStep>,
    gap_start: Vec<f64>,
    gap_end: Vec<Penetration>,
    /// Discrete gradient of δ at each node and its derivative (statics: ∇δ and ∇²δ at the end).
    gap_gradient: Vec<Vector3<f64>>,
    gap_gradient_derivative: Vec<Matrix3<f64>>,
    /// Per element: d(P_e)/dδ_end (2×2) of the (discrete) gradient and ∇²V_e at the end.
    element_jacobian: Vec<Matrix2<f64>>,
    element_hessian_end: Vec<Matrix2<f64>>,
    /// Nodal resultants: of the (discrete) gradient, and exact at the end (the normal force N).
    resultant: Vec<f64>,
    normal_force: Vec<f64>,
    /// ∂F_friction/∂N per node.
    friction_by_normal: Vec<Vector3<f64>>,
    /// Elastic slips at the end of the last evaluation (to be committed).
    pub slip_end: Vec<Vector2<f64>>,
    /// The seabed's force on each node in the last evaluation (N, in e).
    pub forces: Vec<Vector3<f64>>,
    /// Contact energy at the end of the last evaluation (J): normal and friction springs.
    pub energy_end: f64,
    /// Energy dissipated over the step by friction and damping (J).
    pub dissipated: f64,
}

/// What the seabed contact needs of an element: its reference length (m), the diameter it rests on (m) and its
/// submerged weight per length (N/m).
#[derive(Debug, Clone, Copy)]
pub struct ContactElement {
    pub length: f64,
    pub diameter: f64,
    pub weight: f64,
}

impl SeabedContact {
    /// Contact for a rod of `elements` (their lengths, diameters and submerged weights: the seabed's
    /// stiffness acts over the diameter, friction's reference force is the weight); `cable_nodes` marks the
    /// nodes without a rotation (a cable's), whose friction directions follow their chords.
    pub fn new(seabed: &Seabed, elements: Vec<ContactElement>, cable_nodes: Vec<bool>) -> Self {
        let nodes = elements.len() + 1;
        let mut tributary = vec![0.0; nodes];
        let mut damping = vec![0.0; nodes];
        let mut reference_force = vec![0.0; nodes];
        for (e, element) in elements.iter().enumerate() {
            let kd = seabed.stiffness * element.diameter;
            // Friction's reference force per length: the weight, or for a weightless line the force that
            // presses it by the mobilisation distance.
            let reference_weight = if element.weight.abs() > 0.0 {
                element.weight.abs()
            } else {
                kd * seabed.mobilisation
            };
            for node in [e, e + 1] {
                tributary[node] += 0.5 * element.length;
                damping[node] += seabed.damping * element.diameter * 0.5 * element.length;
                reference_force[node] += reference_weight * 0.5 * element.length;
            }
        }
        let mu = Vector2::new(seabed.friction[0], seabed.friction[1]);
        let kd_mean = elements
            .iter()
            .map(|e| seabed.stiffness * e.diameter * e.length)
            .sum::<f64>()
            / tributary.iter().sum::<f64>();
        let weight_mean = reference_force.iter().sum::<f64>() / tributary.iter().sum::<f64>();
        SeabedContact {
            bathymetry: seabed.bathymetry.clone(),
            element_scale: elements
                .iter()
                .map(|e| 0.5 * seabed.stiffness * e.diameter * e.length)
                .collect(),
            element_lengths: elements.iter().map(|e| e.length).collect(),
            damping,
            damping_ramp: weight_mean / kd_mean,
            friction_stiffness: reference_force
                .iter()
                .map(|force| mu * (force / seabed.mobilisation))
                .collect(),
            yield_per_force: reference_force
                .iter()
                .map(|force| seabed.mobilisation / force)
                .collect(),
            cable_nodes,
            has_friction: seabed.has_friction(),
            friction_scale: 1.0,
            nodes: vec![NodeStep::default(); nodes],
            gap_start: vec![0.0; nodes],
            gap_end: vec![
                Penetration {
                    value: 0.0,
                    gradient: Vector3::zeros(),
                    hessian: Matrix3::zeros(),
                };
                nodes
            ],
            gap_gradient: vec![Vector3::zeros(); nodes],
            gap_gradient_derivative: vec![Matrix3::zeros(); nodes],
            element_jacobian: vec![Matrix2::zeros(); nodes - 1],
            element_hessian_end: vec![Matrix2::zeros(); nodes - 1],
            resultant: vec![0.0; nodes],
            normal_force: vec![0.0; nodes],
            friction_by_normal: vec![Vector3::zeros(); nodes],
            slip_end: vec![Vector2::zeros(); nodes],
            forces: vec![Vector3::zeros(); nodes],
            energy_end: 0.0,
            dissipated: 0.0,
        }
    }

    /// The nodes' step inputs to set, and which nodes are a cable's (no rotation: their friction directions
    /// follow their chords).
    pub fn steps_and_cable_nodes(&mut self) -> (&mut [NodeStep], &[bool]) {
        (&mut self.nodes, &self.cable_nodes)
    }

    /// Whether the seabed has friction.
    pub fn has_friction(&self) -> bool {
        self.has_friction
    }

    /// Sets the nodes of a static evaluation: from `start` (positions at the last converged load step) to
    /// `positions` with `rotations` now.
    pub fn set_static_nodes(
        &mut self,
        start: &[Vector3<f64>],
        positions: &[Vector3<f64>],
        rotations: &[UnitQuaternion<f64>],
    ) {
        for (index, ((s, p), q)) in start.iter().zip(positions).zip(rotations).enumerate() {
            // A cable node's axis is its chords' at the load step's start, held over the step.
            let axis = if self.cable_nodes[index] {
                crate::rod::chord_axis(start, index)
            } else {
                q * Vector3::x()
            };
            self.nodes[index] = NodeStep {
                start: *s,
                displacement: p - s,
                axis,
                axis_map: Matrix3::identity(),
            };
        }
    }

    /// Contact energy of a configuration with elastic slips `slips` (J): Σ V_e + Σ ½eᵀKe.
    pub fn energy(&self, positions: &[Vector3<f64>], slips: &[Vector2<f64>]) -> f64 {
        let gaps: Vec<f64> = positions
            .iter()
            .map(|p| self.bathymetry.penetration(p).value)
            .collect();
        let normal: f64 = self
            .element_scale
            .iter()
            .enumerate()
            .map(|(e, s)| s * contact_integral(gaps[e], gaps[e + 1]).0)
            .sum();
        normal + self.spring_energy(slips)
    }

    fn spring_energy(&self, slips: &[Vector2<f64>]) -> f64 {
        slips
            .iter()
            .zip(&self.friction_stiffness)
            .map(|(e, k)| 0.5 * self.friction_scale * e.dot(&k.component_mul(e)))
            .sum()
    }

    /// Evaluates the contact at the nodes set in [`Self::nodes`], from elastic slips `slips_start`: adds the
    /// residual −F (force units, 6 DOFs per node, rotations untouched) to `residual` and, with
    /// `add_element`/`add_node`, the tangent −∂F/∂[Δx, θ] as element 12×12 and node 6×6 blocks. Returns the
    /// work of the contact forces over the step Σ F_a·Δx_a (J).
    pub fn evaluate(
        &mut self,
        rule: ContactRule,
        slips_start: &[Vector2<f64>],
        residual: &mut [f64],
        mut tangent: Option<&mut dyn TangentSink>,
    ) -> f64 {
        let energy_momentum = matches!(rule, ContactRule::EnergyMomentum { .. });
        // 1. Nodal penetrations and the gradients of δ that carry the forces (node by node, in parallel).
        let bathymetry = &self.bathymetry;
        self.nodes
            .par_iter()
            .zip(self.gap_end.par_iter_mut())
            .zip(self.gap_start.par_iter_mut())
            .zip(
                self.gap_gradient
                    .par_iter_mut()
                    .zip(self.gap_gradient_derivative.par_iter_mut()),
            )
            .with_min_len(PARALLEL_NODES)
            .for_each(|(((node, gap_end), gap_start), (gradient, derivative))| {
                let end = node.start + node.displacement;
                *gap_end = bathymetry.penetration(&end);
                if energy_momentum {
                    *gap_start = bathymetry.penetration(&node.start).value;
                }
                if energy_momentum && !bathymetry.is_plane() {
                    let mid = bathymetry.penetration(&(node.start + 0.5 * node.displacement));
                    (*gradient, *derivative) = gonzalez(
                        gap_end.value - *gap_start,
                        &node.displacement,
                        &gap_end.gradient,
                        &mid.gradient,
                        &mid.hessian,
                        1e-10,
                    );
                } else {
                    *gradient = gap_end.gradient;
                    *derivative = gap_end.hessian;
                }
            });
        // 2. Element resultants: the discrete (or exact) gradient of V_e and its Jacobian.
        self.resultant.iter_mut().for_each(|p| *p = 0.0);
        self.normal_force.iter_mut().for_each(|p| *p = 0.0);
        let mut energy_end = 0.0;
        for (e, scale) in self.element_scale.iter().enumerate() {
            let end = Vector2::new(self.gap_end[e].value, self.gap_end[e + 1].value);
            let start = Vector2::new(self.gap_start[e], self.gap_start[e + 1]);
            // Clear of the seabed at the end (and, in a step, at the start): no force, no tangent.
            if clear(&end) && (!energy_momentum || clear(&start)) {
                self.element_hessian_end[e] = Matrix2::zeros();
                self.element_jacobian[e] = Matrix2::zeros();
                continue;
            }
            let (value_end, gradient_end, hessian_end) = contact_integral(end.x, end.y);
            energy_end += scale * value_end;
            self.element_hessian_end[e] = hessian_end * *scale;
            let (gradient, jacobian) = if energy_momentum {
                let regime = |d: &Vector2<f64>| {
                    if d.x >= 0.0 && d.y >= 0.0 {
                        1
                    } else if d.x <= 0.0 && d.y <= 0.0 {
                        -1
                    } else {
                        0
                    }
                };
                let mid = 0.5 * (start + end);
                let (_, gradient_mid, hessian_mid) = contact_integral(mid.x, mid.y);
                if regime(&start) == regime(&end) && regime(&start) != 0 {
                    // Quadratic (or zero) along the whole path: the midpoint gradient is exact.
                    (gradient_mid, 0.5 * hessian_mid)
                } else {
                    let change = value_end - contact_integral(start.x, start.y).0;
                    gonzalez(
                        change,
                        &(end - start),
                        &gradient_end,
                        &gradient_mid,
                        &hessian_mid,
                        1e-12,
                    )
                }
            } else {
                (gradient_end, hessian_end)
            };
            self.element_jacobian[e] = jacobian * *scale;
            self.resultant[e] += scale * gradient.x;
            self.resultant[e + 1] += scale * gradient.y;
            self.normal_force[e] += scale * gradient_end.x;
            self.normal_force[e + 1] += scale * gradient_end.y;
        }
        // 3. Nodal forces: normal, damping, friction.
        let mut work = 0.0;
        self.dissipated = 0.0;
        for a in 0..self.nodes.len() {
            self.slip_end[a] = slips_start[a];
            self.friction_by_normal[a] = Vector3::zeros();
            self.forces[a] = Vector3::zeros();
            let damped = energy_momentum
                && self.damping[a] > 0.0
                && self.gap_start[a] + self.gap_end[a].value > 0.0;
            let rubbing = self.has_friction
                && self.friction_scale > 0.0
                && (self.normal_force[a] > 0.0 || slips_start[a] != Vector2::zeros());
            if self.resultant[a] == 0.0 && !damped && !rubbing {
                continue;
            }
            let node = self.nodes[a];
            let dx = node.displacement;
            let q = self.gap_gradient[a];
            let mut force = -self.resultant[a] * q;
            let mut block = Matrix6::zeros();
            let mut stiffness = self.gap_gradient_derivative[a] * self.resultant[a];
            if let ContactRule::EnergyMomentum { time_step, .. } = rule {
                let gap_mid = 0.5 * (self.gap_start[a] + self.gap_end[a].value);
                if self.damping[a] > 0.0 && gap_mid > 0.0 {
                    let mid = self.bathymetry.penetration(&(node.start + 0.5 * dx));
                    let size = mid.gradient.norm();
                    let normal = -mid.gradient / size;
                    let d_normal =
                        -0.5 * (Matrix3::identity() - normal * normal.transpose()) * mid.hessian
                            / size;
                    // The damping grows smoothly (C¹) to its full value over the first resting
                    // penetration, so that a node entering the seabed does not switch it on at once.
                    let (share, d_share) = crate::smooth::smoothstep(gap_mid / self.damping_ramp);
                    let c = self.damping[a] * share;
                    let rate = normal.dot(&dx) / time_step;
                    force -= c * rate * normal;
                    stiffness += c
                        * (normal * normal.transpose() / time_step
                            + rate * d_normal
                            + normal * (dx.transpose() * d_normal) / time_step)
                        + normal
                            * self.gap_end[a].gradient.transpose()
                            * (self.damping[a] * rate * 0.5 * d_share / self.damping_ramp);
                    self.dissipated += c * normal.dot(&dx).powi(2) / time_step;
                }
            }
            if rubbing {
                let friction = FrictionNode {
                    bathymetry: &self.bathymetry,
                    start: node.start,
                    slip_start: slips_start[a],
                    stiffness: self.friction_stiffness[a] * self.friction_scale,
                    yield_per_force: self.yield_per_force[a],
                };
                let step = friction.step(
                    rule,
                    &dx,
                    &node.axis,
                    self.normal_force[a],
                    tangent.is_some(),
                );
                force += step.force;
                self.slip_end[a] = step.slip;
                self.dissipated += step.dissipated;
                if let Some(derivatives) = step.tangent {
                    self.friction_by_normal[a] = derivatives.normal_force;
                    stiffness -= derivatives.displacement;
                    let rotation_block = derivatives.axis * skew(&node.axis) * node.axis_map;
                    block
                        .fixed_view_mut::<3, 3>(0, 3)
                        .copy_from(&rotation_block);
                }
            }
            block.fixed_view_mut::<3, 3>(0, 0).copy_from(&stiffness);
            self.forces[a] = force;
            work += force.dot(&dx);
            for k in 0..3 {
                residual[6 * a + k] -= force[k];
            }
            if let Some(sink) = tangent.as_mut() {
                sink.add_node(a, &block);
            }
        }
        self.energy_end = energy_end + self.spring_energy(&self.slip_end);
        // 4. Element blocks: normal contact coupling and friction's dependence on the normal force.
        if let Some(sink) = tangent.as_mut() {
            let mut k = ElementMatrix::zeros();
            for e in 0..self.element_scale.len() {
                let jacobian = &self.element_jacobian[e];
                let hessian = &self.element_hessian_end[e];
                if *jacobian == Matrix2::zeros() && *hessian == Matrix2::zeros() {
                    continue;
                }
                k.as_mut_slice().fill(0.0);
                for i in 0..2 {
                    for j in 0..2 {
                        let q = self.gap_gradient[e + i];
                        let g = self.gap_end[e + j].gradient;
                        let block = q * g.transpose() * jacobian[(i, j)]
                            - self.friction_by_normal[e + i] * g.transpose() * hessian[(i, j)];
                        k.fixed_view_mut::<3, 3>(6 * i, 6 * j).copy_from(&block);
                    }
                }
                sink.add_element(e, &k);
            }
        }
        work
    }

    /// Where the pipe at `positions` leaves the seabed (seen from end A) and how much of it lies on it.
    pub fn touchdown(&self, positions: &[Vector3<f64>]) -> Touchdown {
        let lengths = &self.element_lengths;
        let (point, laid_length) = touchdown(&self.penetrations(positions), lengths);
        let point = point.map(|(e, xi)| {
            let arc = lengths[..e].iter().sum::<f64>() + xi * lengths[e];
            (arc, positions[e] * (1.0 - xi) + positions[e + 1] * xi)
        });
        Touchdown { point, laid_length }
    }

    /// The elastic slip e per node after the last evaluation.
    pub fn slips(&self) -> &[Vector2<f64>] {
        &self.slip_end
    }

    /// Penetration δ of each node at `positions` (m).
    pub fn penetrations(&self, positions: &[Vector3<f64>]) -> Vec<f64> {
        positions
            .iter()
            .map(|p| self.bathymetry.penetration(p).value)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_integral_of_a_nan_penetration_is_nan() {
        for (d1, d2) in [
            (f64::NAN, 0.1),
            (0.1, f64::NAN),
            (f64::NAN, -0.1),
            (f64::NAN, f64::NAN),
        ] {
            // Returns (once: it used to recurse without end), and NaN for the solver to report.
            let (value, _, hessian) = contact_integral(d1, d2);
            assert!(
                value.is_nan() && hessian.iter().all(|v| v.is_nan()),
                "{d1}, {d2}"
            );
        }
    }

    #[test]
    fn contact_integral_is_the_integral_and_its_derivatives_match() {
        for (d1, d2) in [
            (0.3, 0.1),
            (0.3, -0.2),
            (-0.1, 0.4),
            (-0.1, -0.3),
            (0.2, 0.0),
            (1e-9, -0.5),
        ] {
            // Midpoint rule on a fine grid of ξ.
            let m = 200_000;
            let quadrature: f64 = (0..m)
                .map(|k| {
                    let xi = (k as f64 + 0.5) / m as f64;
                    ((1.0 - xi) * d1 + xi * d2).max(0.0).powi(2)
                })
                .sum::<f64>()
                / m as f64;
            let (value, gradient, hessian) = contact_integral(d1, d2);
            assert!(
                (value - quadrature).abs() < 1e-9,
                "I({d1}, {d2}) = {value} vs {quadrature}"
            );
            let h = 1e-7;
            for k in 0..2 {
                let mut e = Vector2::zeros();
                e[k] = h;
                let p = contact_integral(d1 + e.x, d2 + e.y);
                let q = contact_integral(d1 - e.x, d2 - e.y);
                assert!(((p.0 - q.0) / (2.0 * h) - gradient[k]).abs() < 1e-7);
                assert!(((p.1 - q.1) / (2.0 * h) - hessian.column(k)).norm() < 1e-6);
            }
        }
    }

    use crate::contact::test_support::wavy_seabed;
    use crate::environment::bathymetry::Bathymetry;
    use crate::so3::exp;

    struct Dense(nalgebra::DMatrix<f64>);

    impl TangentSink for Dense {
        fn add_element(&mut self, e: usize, block: &ElementMatrix) {
            for i in 0..12 {
                for j in 0..12 {
                    self.0[(6 * e + i, 6 * e + j)] += block[(i, j)];
                }
            }
        }
        fn add_node(&mut self, a: usize, block: &Matrix6<f64>) {
            for i in 0..6 {
                for j in 0..6 {
                    self.0[(6 * a + i, 6 * a + j)] += block[(i, j)];
                }
            }
        }
    }

    fn seabed(bathymetry: Bathymetry, damping: f64) -> Seabed {
        Seabed::new(2e5, damping, [0.5, 0.8], 0.02, bathymetry).expect("valid seabed")
    }

    /// Elastic slips at the step's start: two nodes with slip, two without.
    fn start_slips() -> [Vector2<f64>; 4] {
        [
            Vector2::new(0.004, -0.002),
            Vector2::new(0.0, 0.0),
            Vector2::new(-0.001, 0.003),
            Vector2::new(0.0, 0.0),
        ]
    }

    /// Four nodes crossing the seabed: two in contact, one just out, one well above.
    fn nodes(scale: f64) -> Vec<NodeStep> {
        let start = [
            Vector3::new(0.0, 0.1, 0.03),
            Vector3::new(1.9, 0.0, 0.02),
            Vector3::new(4.1, -0.1, -0.01),
            Vector3::new(6.0, 0.2, -0.6),
        ];
        let moves = [
            Vector3::new(0.011, -0.004, 0.002),
            Vector3::new(0.006, 0.009, -0.004),
            Vector3::new(-0.003, 0.002, 0.025),
            Vector3::new(0.01, 0.0, 0.03),
        ];
        (0..4)
            .map(|a| NodeStep {
                start: start[a],
                displacement: moves[a] * scale,
                axis: exp(&Vector3::new(0.1 * a as f64, -0.2, 0.3)) * Vector3::x(),
                axis_map: Matrix3::identity(),
            })
            .collect()
    }

    fn residual_of(
        contact: &mut SeabedContact,
        rule: ContactRule,
        steps: &[NodeStep],
        slips: &[Vector2<f64>],
    ) -> Vec<f64> {
        contact.nodes.copy_from_slice(steps);
        let mut r = vec![0.0; 24];
        contact.evaluate(rule, slips, &mut r, None);
        r
    }

    /// The tangent (element and node blocks) against central differences of the residual, in statics and
    /// the energy–momentum rule, on a plane and a grid, with friction (sticking and sliding) and damping.
    /// Three elements of 2, 2.2 and 2 m, 0.5 m across, weighing 900 N/m.
    fn test_elements() -> Vec<ContactElement> {
        [2.0, 2.2, 2.0]
            .map(|length| ContactElement {
                length,
                diameter: 0.5,
                weight: 900.0,
            })
            .to_vec()
    }

    #[test]
    fn tangent_matches_finite_differences() {
        let slips = start_slips();
        let plane = Bathymetry::plane(0.0, Vector2::new(0.05, -0.02)).expect("plane");
        for bathymetry in [plane, wavy_seabed()] {
            for rule in [
                ContactRule::Static,
                ContactRule::EnergyMomentum {
                    time_step: 0.1,
                    damping: 0.0,
                },
            ] {
                for scale in [0.3, 1.0] {
                    let mut contact = SeabedContact::new(
                        &seabed(bathymetry.clone(), 3e3),
                        test_elements(),
                        vec![false; 4],
                    );
                    let steps = nodes(scale);
                    let mut sink = Dense(nalgebra::DMatrix::<f64>::zeros(24, 24));
                    contact.nodes.copy_from_slice(&steps);
                    let mut r = vec![0.0; 24];
                    contact.evaluate(rule, &slips, &mut r, Some(&mut sink));
                    let k = sink.0;
                    let h = 1e-6;
                    let mut worst: f64 = 0.0;
                    for a in 0..4 {
                        for j in 0..6 {
                            let perturbed = |sign: f64| {
                                let mut s = steps.clone();
                                let mut e = Vector3::zeros();
                                e[j % 3] = sign * h;
                                if j < 3 {
                                    s[a].displacement += e;
                                } else {
                                    s[a].axis = exp(&e) * s[a].axis;
                                }
                                s
                            };
                            let rp = residual_of(&mut contact, rule, &perturbed(1.0), &slips);
                            let rm = residual_of(&mut contact, rule, &perturbed(-1.0), &slips);
                            for i in 0..24 {
                                let fd = (rp[i] - rm[i]) / (2.0 * h);
                                worst = worst.max((fd - k[(i, 6 * a + j)]).abs());
                            }
                        }
                    }
                    let size = k.abs().max();
                    assert!(
                        worst < 1e-6 * size,
                        "{rule:?} scale {scale}: {worst:e} of {size:e}"
                    );
                }
            }
        }
    }

    /// Energy–momentum rule: the contact forces' work equals −ΔE_contact − D exactly, D ≥ 0.
    #[test]
    fn step_work_is_the_energy_change_less_dissipation() {
        let slips = start_slips();
        let plane = Bathymetry::plane(0.0, Vector2::new(0.05, -0.02)).expect("plane");
        for bathymetry in [plane, wavy_seabed()] {
            for scale in [0.01, 0.3, 1.0, 3.0] {
                let mut contact = SeabedContact::new(
                    &seabed(bathymetry.clone(), 3e3),
                    test_elements(),
                    vec![false; 4],
                );
                let steps = nodes(scale);
                let start: Vec<Vector3<f64>> = steps.iter().map(|s| s.start).collect();
                let before = contact.energy(&start, &slips);
                contact.nodes.copy_from_slice(&steps);
                let mut r = vec![0.0; 24];
                let work = contact.evaluate(
                    ContactRule::EnergyMomentum {
                        time_step: 0.1,
                        damping: 0.0,
                    },
                    &slips,
                    &mut r,
                    None,
                );
                let imbalance = work + (contact.energy_end - before) + contact.dissipated;
                assert!(contact.dissipated >= 0.0);
                assert!(
                    imbalance.abs() < 1e-12 * (before.abs() + work.abs()),
                    "scale {scale}: {imbalance:e} (work {work:e})"
                );
            }
        }
    }
}
