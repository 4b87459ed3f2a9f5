//! Rollers on the vessel: unilateral contact of the pipe's outer surface with vessel-fixed cylinders, in
//! statics and in the energy–momentum step.
//!
//! **Geometry.** A roller has an axis line (centre c, unit direction a) and radius r_r; it is fixed in the
//! frame of the vessel's end node N, where the pipe's nodes have local coordinates y_j = Λ_Nᵀ(x_j − x_N).
//! In the plane normal to a, the pipe's centreline is the polyline of the projected nodes; its distance
//! from the axis is d = min over elements of the distance from c to the element's chord (closest point
//! clamped to the chord), counted negative on the far side of the axis (against the roller's normal, the
//! side the pipe rests on). The surfaces overlap by δ = r_r + d_o/2 − d; the contact potential is
//! V = ½ k δ₊² (k the roller stiffness, N/m), pushing only, so the pipe lifts off freely. V is C¹ where
//! the pipe wraps a roller (the chords' feet move continuously through the nodes).
//!
//! **Forces on pipe and vessel.** With g_j = ∂V/∂y_j, node j carries f_j = Λ_N g_j, and N, which is the
//! vessel, carries the reaction −Σ f_j and the moment Σ f_j × (x_j − x_N): roller forces act on the vessel in
//! the same monolithic system, so energy and passivity ledgers close.
//!
//! **Energy–momentum step.** V is taken as a function of the local coordinates of the nodes R of the
//! elements nearest the roller at the step's start, end and midpoint, and Gonzalez's discrete gradient
//! ∇̄V = ∇V(ȳ) + [ΔV − ∇V(ȳ)·Δy]Δy/|Δy|² replaces g. Under the Cayley update Λ_{n+1} = cay(θ)Λ_n,
//! Δy_j = Λ_nᵀ(Δd_j − θ × w_j) with d_j = x_j − x_N and w_j = (I + ½θ̂)⁻¹d_j,{n+1}, so the forces
//! f_j = Λ_n ∇̄V_j on node j, −Σf_j and Σ f_j × w_j on N do work ΔV exactly. (The correction term is left out
//! where it is below the round-off of V: dividing that by a tiny |Δy|² would only make noise.)
//!
//! **Tangent.** Central differences of each active roller's residual in its few nodal unknowns (at most
//! [`MAX_NODES`] pipe nodes and N), checked against differences of the assembled residual in the tests.
// Indexing cannot go out of bounds here: Roller, node and element indices of the contact's own mesh and roller list.
#![allow(clippy::indexing_slicing)]
use crate::contact::rule::ContactRule;
use crate::contact::sinks::EntrySink;
use crate::rod::Rod;
use crate::so3::{cayley, exp, skew};
use crate::vessel::lay::Roller;
use crate::vessel::VesselAttachment;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// Most pipe nodes one roller's discrete gradient spans (three elements).
pub const MAX_NODES: usize = 6;
const MAX_VARIABLES: usize = 3 * MAX_NODES + 6;

/// A roller in the end node's frame.
#[derive(Debug, Clone, Copy)]
struct LocalRoller {
    centre: Vector3<f64>,
    /// The side the pipe rests on (unit, normal to the axis).
    normal: Vector3<f64>,
    /// The axis a (unit) and the projector I − a aᵀ onto the plane normal to it.
    axis: Vector3<f64>,
    projector: Matrix3<f64>,
    /// The roller's radius r_r (m).
    radius: f64,
}

/// The rollers of a model and their state at the last evaluation.
#[derive(Debug, Clone)]
pub struct RollerContact {
    rollers: Vec<LocalRoller>,
    stiffness: f64,
    end_node: usize,
    /// Half the hydrodynamic diameter of each element of the rod (m).
    half_diameters: Vec<f64>,
    /// The elements that may touch a roller (those within reach of the held end).
    elements: std::ops::Range<usize>,
    /// Normal force of each roller at the evaluated (end) state (N, ≥ 0).
    pub forces: Vec<f64>,
    /// The element nearest each roller there.
    pub nearest_elements: Vec<usize>,
    /// Contact energy at the evaluated (end) state (J).
    pub energy_end: f64,
    /// Local coordinates of the nodes of `elements` at the end, start and midpoint of the evaluated step
    /// (scratch, filled once per evaluation and shared by the rollers).
    locals: [Vec<Vector3<f64>>; 3],
}

/// The end node's pose.
#[derive(Debug, Clone, Copy)]
struct Pose {
    position: Vector3<f64>,
    rotation: Matrix3<f64>,
}

impl Pose {
    fn local(&self, x: &Vector3<f64>) -> Vector3<f64> {
        self.rotation.transpose() * (x - self.position)
    }
}

/// The element nearest `roller` among those whose nodes have local coordinates `locals` (the first
/// element's index is `first`): the one whose surface is nearest, by [`chord_distance`] less its radius
/// (`half_diameters`, per element of the rod).
///
/// Every point of a chord lies within half the chord's length h of one of its ends, so its distance from
/// the axis is at least ρ − h, ρ the nearer end's distance. A chord with ρ − h above both the best gap so
/// far plus its radius and 2(r_r + d/2) (beyond which a chord on the far side is out of reach) cannot be
/// nearer, and its [`chord_distance`] is skipped: the same element is found for a fraction of the cost.
fn nearest(
    roller: &LocalRoller,
    half_diameters: &[f64],
    first: usize,
    locals: &[Vector3<f64>],
) -> usize {
    // Squared distance of a node from the axis, |(I − a aᵀ)(y − c)|² = |y − c|² − (a·(y − c))².
    let axis_distance2 = |y: &Vector3<f64>| {
        let v = y - roller.centre;
        v.norm_squared() - roller.axis.dot(&v).powi(2)
    };
    let mut best = (f64::INFINITY, first);
    let mut start_distance2 = locals.first().map_or(0.0, axis_distance2);
    for (e, chord) in (first..).zip(locals.windows(2)) {
        let end_distance2 = axis_distance2(&chord[1]);
        let nearer_end = start_distance2.min(end_distance2).max(0.0).sqrt();
        start_distance2 = end_distance2;
        let half_length = 0.5 * (chord[1] - chord[0]).norm();
        let half_diameter = half_diameters[e];
        let reach = roller.radius + half_diameter;
        // A relative margin of 1e-9 keeps the bound below the rounded chord_distance.
        if (nearer_end - half_length) * (1.0 - 1e-9) > (best.0 + half_diameter).max(2.0 * reach) {
            continue;
        }
        let (d, _, _) = chord_distance(roller, reach, &chord[0], &chord[1]);
        if d - half_diameter < best.0 {
            best = (d - half_diameter, e);
        }
    }
    best.1
}

/// Distance from the roller's axis to the chord (y0, y1) in the plane normal to the axis, with ∂d/∂y0 and
/// ∂d/∂y1. Negative where the chord has passed the axis to the far side (against the roller's normal) and
/// is still within twice the contact distance: the contact then pushes it back. Far beyond, the chord is
/// out of the roller's reach r_r + d/2 (infinite distance).
fn chord_distance(
    roller: &LocalRoller,
    reach: f64,
    y0: &Vector3<f64>,
    y1: &Vector3<f64>,
) -> (f64, Vector3<f64>, Vector3<f64>) {
    let u0 = roller.projector * (y0 - roller.centre);
    let chord = roller.projector * (y1 - y0);
    let length2 = chord.norm_squared();
    let s = if length2 > 0.0 {
        (-u0.dot(&chord) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let foot = u0 + s * chord;
    let d = foot.norm();
    let normal = if d > 0.0 { foot / d } else { Vector3::zeros() };
    if foot.dot(&roller.normal) >= 0.0 {
        (d, (1.0 - s) * normal, s * normal)
    } else if d < 2.0 * reach {
        (-d, -(1.0 - s) * normal, -s * normal)
    } else {
        (f64::INFINITY, Vector3::zeros(), Vector3::zeros())
    }
}

impl RollerContact {
    /// The rollers of `attachment` for the line `rod`, whose nodes lie at reference arc lengths `arcs` from end
    /// A ([`crate::rod::Rod::arc_lengths`]); `None` without rollers. The pipe's surface is that of the thickest
    /// element's surface (its hydrodynamic diameter).
    pub fn new(attachment: &VesselAttachment, rod: &Rod, arcs: &[f64]) -> Option<Self> {
        let lay = attachment.lay.as_ref().filter(|l| !l.rollers.is_empty())?;
        let to_end = attachment.angle;
        let count = arcs.len() - 1;
        let total = arcs[count];
        let longest = arcs.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
        // The hold point is the winch's once it holds the line: its wire runs down the firing line first.
        let hold = attachment.hang_off();
        let reach = 1.5 * (lay.reach() + (hold - lay.hang_off).norm()) + 3.0 * longest;
        let end_node = attachment.node;
        // Elements whose reference arc length from the held end is within reach: from end A, those starting
        // within it; from end B, those ending within it.
        let elements = if end_node == 0 {
            0..arcs[..count].iter().take_while(|&&s| s <= reach).count()
        } else {
            let first = arcs[1..]
                .iter()
                .position(|&s| total - s <= reach)
                .unwrap_or(count);
            first..count
        };
        let rollers = lay
            .rollers
            .iter()
            .map(|r: &Roller| {
                let axis = to_end * r.axis;
                LocalRoller {
                    centre: to_end * (r.centre - hold),
                    normal: to_end * r.normal,
                    axis,
                    projector: Matrix3::identity() - axis * axis.transpose(),
                    radius: r.radius,
                }
            })
            .collect::<Vec<_>>();
        Some(RollerContact {
            forces: vec![0.0; rollers.len()],
            nearest_elements: vec![0; rollers.len()],
            rollers,
            stiffness: lay.roller_stiffness,
            end_node,
            locals: std::array::from_fn(|_| Vec::with_capacity(elements.len() + 1)),
            half_diameters: (0..count)
                .map(|e| 0.5 * rod.section(e).hydrodynamic_diameter)
                .collect(),
            elements,
            energy_end: 0.0,
        })
    }

    /// The nodes coupled to the end node through the rollers.
    pub fn nodes(&self) -> std::ops::RangeInclusive<usize> {
        self.elements.start..=self.elements.end
    }

    /// Fills `locals[slot]` with `local(node)` for the nodes of `elements`.
    fn fill_locals(&mut self, slot: usize, local: impl Fn(usize) -> Vector3<f64>) {
        let nodes = self.nodes();
        let locals = &mut self.locals[slot];
        locals.clear();
        locals.extend(nodes.map(local));
    }

    /// V and ∂V/∂y_j over the chords between consecutive `nodes` entries that are elements (y given).
    fn potential(
        &self,
        k: usize,
        nodes: &[usize],
        y: &[Vector3<f64>],
    ) -> (f64, [Vector3<f64>; MAX_NODES]) {
        let roller = &self.rollers[k];
        // The chord whose surface is nearest: the smallest gap d − D/2.
        let mut best: Option<(f64, usize, Vector3<f64>, Vector3<f64>)> = None;
        for i in 0..nodes.len().saturating_sub(1) {
            if nodes[i + 1] != nodes[i] + 1 {
                continue;
            }
            let half_diameter = self.half_diameters[nodes[i]];
            let reach = roller.radius + half_diameter;
            let (d, g0, g1) = chord_distance(roller, reach, &y[i], &y[i + 1]);
            if best.is_none_or(|b| d - half_diameter < b.0) {
                best = Some((d - half_diameter, i, g0, g1));
            }
        }
        let mut gradient = [Vector3::zeros(); MAX_NODES];
        let Some((gap, i, g0, g1)) = best else {
            return (0.0, gradient);
        };
        let overlap = roller.radius - gap;
        if overlap <= 0.0 {
            return (0.0, gradient);
        }
        gradient[i] = -self.stiffness * overlap * g0;
        gradient[i + 1] = -self.stiffness * overlap * g1;
        (0.5 * self.stiffness * overlap * overlap, gradient)
    }

    /// Adds the rollers' residual at the state `start` + `increments` (all DOFs, node-major [Δx, θ]; `None`:
    /// zero), and
    /// with `sink` their tangent. Statics (`ContactRule::Static`): the forces at that state, with rotations
    /// updated by exp(θ); the energy–momentum step: the discrete gradient over the step from `start`, with the
    /// Cayley update. Sets `forces` and `energy_end` at the end state; returns the largest nodal force (N).
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate(
        &mut self,
        rule: ContactRule,
        positions: &[Vector3<f64>],
        rotations: &[UnitQuaternion<f64>],
        increments: Option<&[f64]>,
        residual: &mut [f64],
        magnitude: Option<&mut [f64]>,
        mut sink: Option<&mut dyn EntrySink>,
    ) {
        let n = self.end_node;
        let step_of = |node: usize| {
            increments.map_or_else(Vector3::zeros, |inc| {
                Vector3::from_column_slice(&inc[6 * node..6 * node + 3])
            })
        };
        let theta = increments.map_or_else(Vector3::zeros, |inc| {
            Vector3::from_column_slice(&inc[6 * n + 3..6 * n + 6])
        });
        let update = |theta: &Vector3<f64>| match rule {
            ContactRule::Static => exp(theta),
            ContactRule::EnergyMomentum { .. } => cayley(theta),
        };
        let rotation_n = rotations[n].to_rotation_matrix().into_inner();
        let start = Pose {
            position: positions[n],
            rotation: rotation_n,
        };
        let end = Pose {
            position: positions[n] + step_of(n),
            rotation: update(&theta) * rotation_n,
        };
        let mut magnitude = magnitude;
        self.energy_end = 0.0;
        // The nodes' local coordinates at the end (and, in a step, at the start and midpoint), once for all
        // rollers.
        let end_local = |node: usize| end.local(&(positions[node] + step_of(node)));
        let start_local = |node: usize| start.local(&positions[node]);
        self.fill_locals(0, end_local);
        let stepping = matches!(rule, ContactRule::EnergyMomentum { .. });
        if stepping {
            self.fill_locals(1, start_local);
            self.fill_locals(2, |node| 0.5 * (start_local(node) + end_local(node)));
        }
        let first = self.elements.start;
        for k in 0..self.rollers.len() {
            // The nodes R: elements nearest at the end (and, in a step, at the start and midpoint).
            let roller = &self.rollers[k];
            let diameters = &self.half_diameters;
            let mut elements = [nearest(roller, diameters, first, &self.locals[0]); 3];
            if stepping {
                elements[1] = nearest(roller, diameters, first, &self.locals[1]);
                elements[2] = nearest(roller, diameters, first, &self.locals[2]);
            }
            let mut nodes = [0usize; MAX_NODES];
            let mut count = 0;
            for e in elements {
                for node in [e, e + 1] {
                    if !nodes[..count].contains(&node) {
                        nodes[count] = node;
                        count += 1;
                    }
                }
            }
            nodes[..count].sort_unstable();
            let nodes = &nodes[..count];
            let variables = 3 * count + 6;
            // Unknowns: Δx of each node of R, then Δx and θ of N; residual in the same order.
            let mut base = [0.0; MAX_VARIABLES];
            for (i, &node) in nodes.iter().enumerate() {
                base[3 * i..3 * i + 3].copy_from_slice(step_of(node).as_slice());
            }
            base[3 * count..3 * count + 3].copy_from_slice(step_of(n).as_slice());
            base[3 * count + 3..variables].copy_from_slice(theta.as_slice());
            let (forces, value, normal_force) =
                self.roller_residual(k, rule, nodes, positions, &start, &base, &update);
            self.forces[k] = normal_force;
            self.nearest_elements[k] = elements[0];
            self.energy_end += value;
            if normal_force == 0.0 && forces[..variables].iter().all(|f| *f == 0.0) {
                continue;
            }
            let dof = |i: usize| {
                if i < 3 * count {
                    6 * nodes[i / 3] + i % 3
                } else {
                    6 * n + (i - 3 * count)
                }
            };
            for (i, f) in forces[..variables].iter().enumerate() {
                residual[dof(i)] += f;
                if let Some(m) = magnitude.as_deref_mut() {
                    m[dof(i)] += f.abs();
                }
            }
            if let Some(sink) = sink.as_deref_mut() {
                let scale = 1.0 + positions[n].norm();
                for j in 0..variables {
                    let h = if j < 3 * count + 3 {
                        1e-6 * scale
                    } else {
                        1e-7
                    };
                    let mut plus = base;
                    let mut minus = base;
                    plus[j] += h;
                    minus[j] -= h;
                    let (fp, _, _) =
                        self.roller_residual(k, rule, nodes, positions, &start, &plus, &update);
                    let (fm, _, _) =
                        self.roller_residual(k, rule, nodes, positions, &start, &minus, &update);
                    for i in 0..variables {
                        let value = (fp[i] - fm[i]) / (2.0 * h);
                        if value != 0.0 {
                            sink.add_entry(dof(i), dof(j), value);
                        }
                    }
                }
            }
        }
    }

    /// Roller k's residual over its unknowns `step` (see [`Self::evaluate`]), the contact energy at the end
    /// and the roller's normal force there.
    #[allow(clippy::too_many_arguments)]
    fn roller_residual(
        &self,
        k: usize,
        rule: ContactRule,
        nodes: &[usize],
        positions: &[Vector3<f64>],
        start: &Pose,
        step: &[f64; MAX_VARIABLES],
        update: &dyn Fn(&Vector3<f64>) -> Matrix3<f64>,
    ) -> ([f64; MAX_VARIABLES], f64, f64) {
        let count = nodes.len();
        let dx_n = Vector3::from_column_slice(&step[3 * count..3 * count + 3]);
        let theta = Vector3::from_column_slice(&step[3 * count + 3..3 * count + 6]);
        let end = Pose {
            position: start.position + dx_n,
            rotation: update(&theta) * start.rotation,
        };
        let mut x_end = [Vector3::zeros(); MAX_NODES];
        let mut y_start = [Vector3::zeros(); MAX_NODES];
        let mut y_end = [Vector3::zeros(); MAX_NODES];
        for (i, &node) in nodes.iter().enumerate() {
            x_end[i] = positions[node] + Vector3::from_column_slice(&step[3 * i..3 * i + 3]);
            y_start[i] = start.local(&positions[node]);
            y_end[i] = end.local(&x_end[i]);
        }
        let (value_end, gradient_end) = self.potential(k, nodes, &y_end[..count]);
        let normal_force = (2.0 * self.stiffness * value_end).sqrt();
        let mut out = [0.0; MAX_VARIABLES];
        let (gradient, frame, arms) = match rule {
            ContactRule::Static => {
                let arms: [Vector3<f64>; MAX_NODES] =
                    std::array::from_fn(|i| x_end[i] - end.position);
                (gradient_end, end.rotation, arms)
            }
            ContactRule::EnergyMomentum { .. } => {
                let mut y_mid = [Vector3::zeros(); MAX_NODES];
                let mut change2 = 0.0;
                for i in 0..count {
                    y_mid[i] = 0.5 * (y_start[i] + y_end[i]);
                    change2 += (y_end[i] - y_start[i]).norm_squared();
                }
                let (value_start, _) = self.potential(k, nodes, &y_start[..count]);
                let (_, mut gradient) = self.potential(k, nodes, &y_mid[..count]);
                let along: f64 = (0..count)
                    .map(|i| gradient[i].dot(&(y_end[i] - y_start[i])))
                    .sum();
                // The correction where it rises above the round-off of V (positions known to ε|y|): below,
                // dividing by |Δy|² would turn that round-off into force.
                let extent = y_end[..count].iter().map(|y| y.norm()).fold(1.0, f64::max);
                let force: f64 = gradient[..count].iter().map(|g| g.norm()).sum();
                let noise = 64.0 * f64::EPSILON * (value_end + value_start + force * extent);
                let mismatch = value_end - value_start - along;
                if change2 > 0.0 && mismatch.abs() > noise {
                    let c = mismatch / change2;
                    for i in 0..count {
                        gradient[i] += c * (y_end[i] - y_start[i]);
                    }
                }
                // w_j = (I + ½θ̂)⁻¹ d_j,{n+1}.
                let solve = (Matrix3::identity() + 0.5 * skew(&theta))
                    .try_inverse()
                    .unwrap_or_else(Matrix3::identity);
                let arms: [Vector3<f64>; MAX_NODES] =
                    std::array::from_fn(|i| solve * (x_end[i] - end.position));
                (gradient, start.rotation, arms)
            }
        };
        let mut force_n = Vector3::zeros();
        let mut moment_n = Vector3::zeros();
        for i in 0..count {
            let f = frame * gradient[i];
            out[3 * i..3 * i + 3].copy_from_slice(f.as_slice());
            force_n -= f;
            moment_n += f.cross(&arms[i]);
        }
        out[3 * count..3 * count + 3].copy_from_slice(force_n.as_slice());
        out[3 * count + 3..3 * count + 6].copy_from_slice(moment_n.as_slice());
        (out, value_end, normal_force)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vessel::lay::{stinger_rollers, LayEquipment};
    use std::collections::HashMap;

    struct Dense(HashMap<(usize, usize), f64>);
    impl EntrySink for Dense {
        fn add_entry(&mut self, row: usize, column: usize, value: f64) {
            *self.0.entry((row, column)).or_insert(0.0) += value;
        }
    }

    /// A pipe of 12 nodes, 5 m apart, laid over a stinger of 6 rollers fixed to the frame of its last node.
    fn pipe_over_stinger() -> (RollerContact, Vec<Vector3<f64>>, Vec<UnitQuaternion<f64>>) {
        let rollers =
            stinger_rollers(40.0, 30.0, 6, Vector3::new(-5.0, 0.0, 0.0), 0.0, 0.25).unwrap();
        let lay = LayEquipment::s_lay(Vector3::new(0.0, 0.0, -0.3), rollers, 1e7).unwrap();
        let attachment = VesselAttachment {
            node: 11,
            vessel: crate::vessel::rigid_body::Vessel::osv(),
            angle: lay.end_frame.transpose(),
            eta: nalgebra::Vector6::zeros(),
            controller: None,
            environment: Vec::new(),
            surface: 0.0,
            lay: Some(lay.clone()),
            winch: None,
            hull_loads: false,
        };
        // A pipe 0.6 m across, 55 m in 11 elements.
        let section = crate::rod::section::Section::pipe(
            0.6, 0.02, 7850.0, 207e9, 0.3, 0.0, [0.0; 2], [0.0; 2],
        )
        .unwrap();
        let rod =
            Rod::straight(Vector3::zeros(), Vector3::new(55.0, 0.0, 0.0), 11, section).unwrap();
        let contact = RollerContact::new(&attachment, &rod, &rod.arc_lengths()).unwrap();
        // The pipe follows the stinger's arc 1 cm too low (pressed into the rollers), then hangs straight.
        let centre = Vector3::new(-5.0, 0.0, 40.0);
        let positions = (0..12)
            .map(|i| {
                let s = 5.0 * (11 - i) as f64;
                let angle = (s - 5.0).max(0.0) / 40.0;
                let radius = 40.0 + 0.3 - 0.01;
                let on_arc = centre + radius * Vector3::new(-angle.sin(), 0.0, -angle.cos());
                if s < 5.0 {
                    Vector3::new(-s, 0.0, -0.3)
                } else {
                    on_arc + 0.003 * Vector3::new(0.0, (i as f64).sin(), 0.0)
                }
            })
            .collect();
        let rotations = (0..12)
            .map(|i| crate::so3::exp_quat(&Vector3::new(0.001 * i as f64, 0.002, -0.001)))
            .collect();
        (contact, positions, rotations)
    }

    /// The pruned search finds the element a full scan of [`chord_distance`] finds, for every roller, with
    /// the pipe pressed into the stinger, lifted off it by up to 3 m and pushed through it by up to 1 m, and
    /// with chords from 0.5 to 20 m.
    #[test]
    fn pruned_nearest_is_the_full_scan() {
        let (contact, positions, _) = pipe_over_stinger();
        // Half-diameters alternating along the refined polyline, as at joints of a line of segments.
        let half_diameters: Vec<f64> = (0..400).map(|e| [0.3, 0.04, 0.3][e % 3]).collect();
        let full_scan = |roller: &LocalRoller, locals: &[Vector3<f64>]| {
            let mut best = (f64::INFINITY, 0);
            for e in 0..locals.len() - 1 {
                let reach = roller.radius + half_diameters[e];
                let (d, _, _) = chord_distance(roller, reach, &locals[e], &locals[e + 1]);
                if d - half_diameters[e] < best.0 {
                    best = (d - half_diameters[e], e);
                }
            }
            best.1
        };
        let mut checked = 0;
        for lift in [-1.0, -0.3, 0.0, 0.2, 1.0, 3.0] {
            for refine in [1, 4, 10] {
                // The pipe's polyline subdivided `refine` times, moved by `lift` along the stinger's normal.
                let mut locals = Vec::new();
                for pair in positions.windows(2) {
                    for i in 0..refine {
                        let t = i as f64 / refine as f64;
                        locals.push(pair[0] * (1.0 - t) + pair[1] * t + Vector3::z() * lift);
                    }
                }
                locals.push(positions[positions.len() - 1] + Vector3::z() * lift);
                for roller in &contact.rollers {
                    assert_eq!(
                        nearest(roller, &half_diameters, 0, &locals),
                        full_scan(roller, &locals)
                    );
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 6 * 3 * contact.rollers.len());
    }

    /// The energy–momentum residual's tangent (central differences of the kernel) matches central
    /// differences of the assembled residual in the step's increments, the vessel node's rotation included.
    #[test]
    fn step_tangent_matches_differences_of_the_residual() {
        let (mut contact, positions, rotations) = pipe_over_stinger();
        let rule = ContactRule::EnergyMomentum { time_step: 0.1 };
        let dofs = 6 * positions.len();
        let increments: Vec<f64> = (0..dofs)
            .map(|i| 1e-3 * ((i as f64) * 0.37).sin())
            .collect();
        let residual = |contact: &mut RollerContact, inc: &[f64]| {
            let mut r = vec![0.0; dofs];
            contact.evaluate(rule, &positions, &rotations, Some(inc), &mut r, None, None);
            r
        };
        let mut dense = Dense(HashMap::new());
        let mut r = vec![0.0; dofs];
        contact.evaluate(
            rule,
            &positions,
            &rotations,
            Some(&increments),
            &mut r,
            None,
            Some(&mut dense),
        );
        assert!(
            contact.forces.iter().filter(|f| **f > 0.0).count() >= 3,
            "{:?}",
            contact.forces
        );
        let mut worst: f64 = 0.0;
        let mut largest: f64 = 0.0;
        for column in 0..dofs {
            let h = if column % 6 < 3 { 1e-6 } else { 1e-8 };
            let mut plus = increments.clone();
            let mut minus = increments.clone();
            plus[column] += h;
            minus[column] -= h;
            let (rp, rm) = (
                residual(&mut contact, &plus),
                residual(&mut contact, &minus),
            );
            for row in 0..dofs {
                let fd = (rp[row] - rm[row]) / (2.0 * h);
                let entry = dense.0.get(&(row, column)).copied().unwrap_or(0.0);
                worst = worst.max((fd - entry).abs());
                largest = largest.max(entry.abs());
            }
        }
        println!("worst tangent error {worst:.3e} of {largest:.3e}");
        assert!(worst < 1e-5 * largest, "{worst:e} of {largest:e}");
    }
}
