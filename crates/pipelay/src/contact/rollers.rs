//! Rollers on the vessel: unilateral contact of the pipe's outer surface with vessel-fixed cylinders, in
//! statics and in the energy–momentum step.
//!
//! **Geometry** ([`super::roller_geometry`]). The distance d from a roller of finite length to the spline
//! through the pipe's nodes, nearest it, in the frame of the vessel's end node N. The surfaces overlap by
//! δ = r_r + d_o/2 − d; the contact potential is V = ½ k δ₊² (k the roller stiffness, N/m), pushing only, so
//! the pipe lifts off freely. At the foot ξ*, ∂d/∂y_j = w_j(ξ*) n, and the roller pushes the pipe with
//! k δ n: its reaction vector, recorded with the foot's offset along the roller.
//!
//! **Forces on pipe and vessel.** With g_j = ∂V/∂y_j, node j carries f_j = Λ_N g_j, and N, which is the
//! vessel, carries the reaction −Σ f_j and the moment Σ f_j × (x_j − x_N): roller forces act on the vessel in
//! the same monolithic system, so energy and passivity ledgers close.
//!
//! **Energy–momentum step.** V is taken as a function of the local coordinates of the nodes R of the
//! spline's elements near the roller at the step's start, end and midpoint, and Gonzalez's discrete gradient
//! ∇̄V = ∇V(ȳ) + [ΔV − ∇V(ȳ)·Δy]Δy/|Δy|² replaces g. Under the Cayley update Λ_{n+1} = cay(θ)Λ_n,
//! Δy_j = Λ_nᵀ(Δd_j − θ × w_j) with d_j = x_j − x_N and w_j = (I + ½θ̂)⁻¹d_j,{n+1}, so the forces
//! f_j = Λ_n ∇̄V_j on node j, −Σf_j and Σ f_j × w_j on N do work ΔV exactly. (The correction term is left out
//! where it is below the round-off of V: dividing that by a tiny |Δy|² would only make noise.)
//!
//! **Tangent.** Central differences of each active roller's residual in its few nodal unknowns (at most
//! [`MAX_NODES`] pipe nodes and N), checked against differences of the assembled residual in the tests.
// Indexing cannot go out of bounds here: Roller, node and element indices of the contact's own mesh and roller list.
#![allow(clippy::indexing_slicing)]
use crate::contact::roller_friction;
use crate::contact::roller_geometry::{
    nearest, nearest_spline_element, spline_distance, LocalRoller, Segment, Surfaces,
};
use crate::contact::rule::ContactRule;
use crate::contact::sinks::EntrySink;
use crate::rod::Rod;
use crate::so3::{cayley, exp, skew};
use crate::vessel::VesselAttachment;
use nalgebra::{Matrix3, UnitQuaternion, Vector2, Vector3};

/// Most pipe nodes one roller's discrete gradient spans: those of the spline's elements nearest it at the
/// step's start, end and midpoint, four each.
pub const MAX_NODES: usize = 12;
/// How many nodes apart a roller couples the pipe's nodes when its nearest spline elements in a step are
/// neighbours (e and e + 1, nodes e − 1 … e + 3): the width of the tangent's band on the stinger. (A step
/// whose nearest elements lie further apart, a pipe sliding more than an element in one step, leaves the
/// entries beyond out of the tangent; the residual stays exact.)
pub const COUPLING_REACH: usize = 4;
/// In statics, the central differences' step of the tangent on the nodes' and the end node's positions (m): far below the
/// overlap of a roller carrying a few kilonewtons (its force over its stiffness, ~1e-4 m), so that a contact near
/// its start is differenced on one side of it, and far above the positions' round-off (ε|x| ≤ 1e-12 m).
const TANGENT_STEP: f64 = 1e-6;
/// The lever (m) that turns the end node's rotation step into a move of the rollers of about [`TANGENT_STEP`]: they
/// stand up to ~100 m from it.
const ROTATION_LEVER: f64 = 100.0;
/// In a time step, the relative step of the positions' differences (times 1 + |x| m) and the rotations' (rad).
const STEP_TANGENT_STEP: f64 = 1e-6;
const STEP_TANGENT_ROTATION: f64 = 1e-7;

/// Most spline elements one roller's distance is minimised over: one per state of the step.
const MAX_SEGMENTS: usize = 3;
const MAX_VARIABLES: usize = 3 * MAX_NODES + 6;

/// The rollers of a model and their state at the last evaluation.
#[derive(Debug, Clone)]
pub struct RollerContact {
    pub(super) rollers: Vec<LocalRoller>,
    stiffness: f64,
    end_node: usize,
    /// The line's surface along each element of the rod.
    surfaces: Surfaces,
    /// The elements that may touch a roller (those within reach of the held end).
    elements: std::ops::Range<usize>,
    /// Normal force of each roller at the evaluated (end) state (N, ≥ 0).
    pub forces: Vec<f64>,
    /// Each roller's force on the pipe there, in the vessel's body frame (N; zero out of contact).
    pub reactions: Vec<Vector3<f64>>,
    /// Where each roller's contact lies along it there, from its centre along its axis (m; NaN out of
    /// contact).
    pub offsets: Vec<f64>,
    /// The rotation from the body frame to the end node's frame (R_t^b transposed).
    to_end: Matrix3<f64>,
    /// The element nearest each roller there.
    pub nearest_elements: Vec<usize>,
    /// Contact energy at the evaluated (end) state (J), the friction springs' included.
    pub energy_end: f64,
    /// Energy the rollers' friction dissipated over the evaluated step (J).
    pub dissipated: f64,
    /// Each roller's elastic friction slip (ĉ, â; m): at the last committed state, and at the evaluated end.
    slips: Vec<Vector2<f64>>,
    slips_end: Vec<Vector2<f64>>,
    /// Local coordinates of the nodes of `elements` at the end, start and midpoint of the evaluated step
    /// (scratch, filled once per evaluation and shared by the rollers).
    locals: [Vec<Vector3<f64>>; 3],
}

/// What one roller's residual is evaluated on: the spline's elements near it, the nodes that control them
/// (sorted) and, in a step, the contact energy at the step's start.
struct Spline<'a> {
    segments: &'a [Segment],
    nodes: &'a [usize],
    value_start: f64,
    /// In a step, the friction's frame at its start, where the roller resists sliding and touched the pipe.
    friction: Option<FrictionFrame>,
}

/// A roller's contact at one state: its force on the pipe (local frame, N), the foot's offset along the
/// roller (m), and the foot's control nodes (indices into the roller's node list), spline weights and unit
/// normal.
#[derive(Debug, Clone, Copy)]
struct Touch {
    reaction: Vector3<f64>,
    along: f64,
    control: [usize; 4],
    weights: [f64; 4],
    normal: Vector3<f64>,
}

/// Friction over a step at a roller, frozen at the step's start ([`roller_friction`]): the foot's control
/// nodes and weights, the tangent directions (ĉ, â) and the elastic slip there.
#[derive(Debug, Clone, Copy)]
struct FrictionFrame {
    control: [usize; 4],
    weights: [f64; 4],
    directions: [Vector3<f64>; 2],
    slip_start: Vector2<f64>,
}

/// One evaluation of a roller's residual ([`RollerContact::roller_residual`]): the residual over its
/// unknowns, the contact energy at the end (with the friction spring's), the contact there, and the
/// friction's slip at the end and dissipation over the step.
struct RollerStep {
    residual: [f64; MAX_VARIABLES],
    energy: f64,
    touch: Option<Touch>,
    slip: Vector2<f64>,
    dissipated: f64,
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
            .map(|r| LocalRoller::new(r, &to_end, &hold))
            .collect::<Vec<_>>();
        Some(RollerContact {
            forces: vec![0.0; rollers.len()],
            reactions: vec![Vector3::zeros(); rollers.len()],
            offsets: vec![f64::NAN; rollers.len()],
            slips: vec![Vector2::zeros(); rollers.len()],
            slips_end: vec![Vector2::zeros(); rollers.len()],
            dissipated: 0.0,
            to_end,
            nearest_elements: vec![0; rollers.len()],
            rollers,
            stiffness: lay.roller_stiffness,
            end_node,
            locals: std::array::from_fn(|_| Vec::with_capacity(elements.len() + 1)),
            surfaces: Surfaces::new(rod),
            elements,
            energy_end: 0.0,
        })
    }

    /// Takes the friction slips of the evaluated step as the committed ones (the step is accepted).
    pub fn commit_slips(&mut self) {
        self.slips.clone_from(&self.slips_end);
    }

    /// Keeps the friction slips of `old`, the same rollers' contact before the mesh changed.
    pub fn carry_slips(&mut self, old: &RollerContact) {
        self.slips.clone_from(&old.slips);
        self.slips_end.clone_from(&old.slips_end);
    }

    /// The nodes coupled to the end node through the rollers: those of `elements` and, as the spline's
    /// control nodes, one more on each side.
    pub fn nodes(&self) -> std::ops::RangeInclusive<usize> {
        let last_node = self.surfaces.half_diameters.len();
        self.elements.start.saturating_sub(1)..=(self.elements.end + 1).min(last_node)
    }

    /// Fills `locals[slot]` with `local(node)` for the nodes of `elements`.
    fn fill_locals(&mut self, slot: usize, local: impl Fn(usize) -> Vector3<f64>) {
        let nodes = self.elements.start..=self.elements.end;
        let locals = &mut self.locals[slot];
        locals.clear();
        locals.extend(nodes.map(local));
    }

    /// V and ∂V/∂y_j over the spline's `segments` (nodes' local coordinates `y`, in the roller's node order),
    /// and the contact, if the pipe touches the roller.
    fn potential(
        &self,
        k: usize,
        segments: &[Segment],
        y: &[Vector3<f64>],
    ) -> (f64, [Vector3<f64>; MAX_NODES], Option<Touch>) {
        let roller = &self.rollers[k];
        // The element whose surface is nearest: the smallest gap d − D/2.
        // The gap, the segment, and the foot's weights, direction and offset along the roller.
        type Foot = (f64, Segment, [f64; 4], Vector3<f64>, f64);
        let mut best: Option<Foot> = None;
        for segment in segments {
            let half_diameter = self.surfaces.half_diameters[segment.element];
            let reach = roller.radius + half_diameter;
            let points = segment.control.map(|i| y[i]);
            let (d, weights, direction, along) =
                spline_distance(roller, reach, &points, segment.mirrored);
            if best.is_none_or(|b| d - half_diameter < b.0) {
                best = Some((d - half_diameter, *segment, weights, direction, along));
            }
        }
        let mut gradient = [Vector3::zeros(); MAX_NODES];
        let Some((gap, segment, weights, direction, along)) = best else {
            return (0.0, gradient, None);
        };
        let overlap = roller.radius - gap;
        if overlap <= 0.0 {
            return (0.0, gradient, None);
        }
        for (i, w) in segment.control.iter().zip(weights) {
            gradient[*i] -= self.stiffness * overlap * w * direction;
        }
        let touch = Touch {
            reaction: self.stiffness * overlap * direction,
            along,
            control: segment.control,
            weights,
            normal: direction,
        };
        (
            0.5 * self.stiffness * overlap * overlap,
            gradient,
            Some(touch),
        )
    }

    /// Of the spline's elements next to the nearest chord `chord`, the one whose surface is nearest roller k
    /// ([`nearest_spline_element`]).
    fn nearest_segment(
        &self,
        k: usize,
        chord: usize,
        local: &dyn Fn(usize) -> Vector3<f64>,
    ) -> usize {
        let elements = self.elements.clone();
        nearest_spline_element(&self.rollers[k], &self.surfaces, elements, chord, local).1
    }

    /// The spline's `elements` (repeats allowed) as segments, and the sorted nodes that control them; a
    /// segment's control indices point into the nodes.
    fn segments(
        &self,
        elements: &[usize],
    ) -> ([Segment; MAX_SEGMENTS], usize, [usize; MAX_NODES], usize) {
        let mut unique = [0usize; MAX_SEGMENTS];
        let mut count = 0;
        for &e in elements {
            if !unique[..count].contains(&e) {
                unique[count] = e;
                count += 1;
            }
        }
        unique[..count].sort_unstable();
        let mut nodes = [0usize; MAX_NODES];
        let mut node_count = 0;
        for &e in &unique[..count] {
            let (control, _) = self.surfaces.control_nodes(e);
            for node in control[0]..=control[3] {
                if !nodes[..node_count].contains(&node) {
                    nodes[node_count] = node;
                    node_count += 1;
                }
            }
        }
        nodes[..node_count].sort_unstable();
        let index = |node: usize| nodes[..node_count].partition_point(|&n| n < node);
        let mut segments = [Segment {
            element: 0,
            control: [0; 4],
            mirrored: [false; 2],
        }; MAX_SEGMENTS];
        for (segment, &e) in segments.iter_mut().zip(&unique[..count]) {
            let (control, mirrored) = self.surfaces.control_nodes(e);
            *segment = Segment {
                element: e,
                control: control.map(index),
                mirrored,
            };
        }
        (segments, count, nodes, node_count)
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
        self.dissipated = 0.0;
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
            let diameters = &self.surfaces.half_diameters;
            let mut chords = [nearest(roller, diameters, first, &self.locals[0]); 3];
            let mut elements = [self.nearest_segment(k, chords[0], &end_local); 3];
            let states = if stepping { 3 } else { 1 };
            if stepping {
                chords[1] = nearest(roller, diameters, first, &self.locals[1]);
                chords[2] = nearest(roller, diameters, first, &self.locals[2]);
                elements[1] = self.nearest_segment(k, chords[1], &start_local);
                let mid_local = |node: usize| 0.5 * (start_local(node) + end_local(node));
                elements[2] = self.nearest_segment(k, chords[2], &mid_local);
            }
            let (segments, segment_count, nodes, count) = self.segments(&elements[..states]);
            let (segments, nodes) = (&segments[..segment_count], &nodes[..count]);
            // The energy and the contact at the step's start do not depend on the unknowns: once per roller.
            let (value_start, touch_start) = if stepping {
                let y_start: [Vector3<f64>; MAX_NODES] = std::array::from_fn(|i| {
                    nodes
                        .get(i)
                        .map_or_else(Vector3::zeros, |&node| start_local(node))
                });
                let (value, _, touch) = self.potential(k, segments, &y_start[..count]);
                (value, touch)
            } else {
                (0.0, None)
            };
            let roller = &self.rollers[k];
            let friction = touch_start
                .filter(|_| !roller.friction.is_frictionless())
                .map(|touch| FrictionFrame {
                    control: touch.control,
                    weights: touch.weights,
                    directions: roller_friction::tangent_directions(&touch.normal, &roller.axis),
                    slip_start: self.slips[k],
                });
            let contact = Spline {
                segments,
                nodes,
                value_start,
                friction,
            };
            let variables = 3 * count + 6;
            // Unknowns: Δx of each node of R, then Δx and θ of N; residual in the same order.
            let mut base = [0.0; MAX_VARIABLES];
            for (i, &node) in nodes.iter().enumerate() {
                base[3 * i..3 * i + 3].copy_from_slice(step_of(node).as_slice());
            }
            base[3 * count..3 * count + 3].copy_from_slice(step_of(n).as_slice());
            base[3 * count + 3..variables].copy_from_slice(theta.as_slice());
            let RollerStep {
                residual: forces,
                energy: value,
                touch,
                slip,
                dissipated,
            } = self.roller_residual(k, rule, &contact, positions, &start, &base, &update);
            self.slips_end[k] = slip;
            self.dissipated += dissipated;
            // The reaction in the end node's frame at the end state, turned to the body frame.
            let (reaction, offset) = touch.map_or((Vector3::zeros(), f64::NAN), |touch| {
                (self.to_end.transpose() * touch.reaction, touch.along)
            });
            let normal_force = reaction.norm();
            self.forces[k] = normal_force;
            self.reactions[k] = reaction;
            self.offsets[k] = offset;
            self.nearest_elements[k] = chords[0];
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
                // A step's residual is a discrete gradient, itself a difference over the step: differenced on
                // the positions' scale ([`STEP_TANGENT_STEP`]) so that its digits are not lost.
                let (step, rotation_step) = if stepping {
                    let step = STEP_TANGENT_STEP * (1.0 + positions[n].norm());
                    (step, STEP_TANGENT_ROTATION)
                } else {
                    (TANGENT_STEP, TANGENT_STEP / ROTATION_LEVER)
                };
                for j in 0..variables {
                    let h = if j < 3 * count + 3 {
                        step
                    } else {
                        rotation_step
                    };
                    let mut plus = base;
                    let mut minus = base;
                    plus[j] += h;
                    minus[j] -= h;
                    let fp = self
                        .roller_residual(k, rule, &contact, positions, &start, &plus, &update)
                        .residual;
                    let fm = self
                        .roller_residual(k, rule, &contact, positions, &start, &minus, &update)
                        .residual;
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

    /// Roller k's residual over its unknowns `step` (see [`Self::evaluate`]) on the spline `contact`, with its
    /// friction: the contact energy at the end and the contact there, and the friction's slip and
    /// dissipation.
    #[allow(clippy::too_many_arguments)]
    fn roller_residual(
        &self,
        k: usize,
        rule: ContactRule,
        contact: &Spline,
        positions: &[Vector3<f64>],
        start: &Pose,
        step: &[f64; MAX_VARIABLES],
        update: &dyn Fn(&Vector3<f64>) -> Matrix3<f64>,
    ) -> RollerStep {
        let nodes = contact.nodes;
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
        let (value_end, mut gradient_end, touch) =
            self.potential(k, contact.segments, &y_end[..count]);
        let roller = &self.rollers[k];
        let mut slip = Vector2::zeros();
        let mut dissipated = 0.0;
        let mut friction_energy = 0.0;
        let mut out = [0.0; MAX_VARIABLES];
        let (gradient, frame, arms) = match rule {
            ContactRule::Static => {
                // The pipe slides out over the rollers: held back toward the hold point with the limit force.
                if let Some(touch) = touch.filter(|_| !roller.friction.is_frictionless()) {
                    let y = |slot: usize| y_end[touch.control[slot]];
                    let toward_hold = if self.end_node == 0 { -1.0 } else { 1.0 } * (y(2) - y(1));
                    let force = roller_friction::static_force(
                        &roller.friction,
                        &touch.normal,
                        &toward_hold,
                        touch.reaction.norm(),
                    );
                    for (i, w) in touch.control.iter().zip(touch.weights) {
                        gradient_end[*i] -= w * force;
                    }
                }
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
                let value_start = contact.value_start;
                let (_, mut gradient, _) = self.potential(k, contact.segments, &y_mid[..count]);
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
                // Friction on the material point's move Δu = Σ w_j Δy_j, in the directions of the step's start.
                if let Some(frame) = &contact.friction {
                    let moved: Vector3<f64> = frame
                        .control
                        .iter()
                        .zip(frame.weights)
                        .map(|(&i, w)| w * (y_end[i] - y_start[i]))
                        .sum();
                    let normal_force = touch.map_or(0.0, |t| t.reaction.norm());
                    let step = roller_friction::step(
                        &roller.friction,
                        &frame.directions,
                        &frame.slip_start,
                        &moved,
                        normal_force,
                        self.stiffness,
                    );
                    for (i, w) in frame.control.iter().zip(frame.weights) {
                        gradient[*i] -= w * step.force;
                    }
                    (slip, dissipated, friction_energy) = (step.slip, step.dissipated, step.energy);
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
        RollerStep {
            residual: out,
            energy: value_end + friction_energy,
            touch,
            slip,
            dissipated,
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::contact::roller_geometry::spline_weights;
    use crate::vessel::lay::{stinger_rollers, LayEquipment};
    use std::collections::HashMap;

    struct Dense(HashMap<(usize, usize), f64>);
    impl EntrySink for Dense {
        fn add_entry(&mut self, row: usize, column: usize, value: f64) {
            *self.0.entry((row, column)).or_insert(0.0) += value;
        }
    }

    /// The roller contact of `lay` with a straight pipe 0.6 m across from `start` to `end` in `elements`
    /// elements, held by the vessel at its last node.
    pub(in crate::contact) fn held_pipe(
        lay: LayEquipment,
        start: Vector3<f64>,
        end: Vector3<f64>,
        elements: usize,
    ) -> RollerContact {
        let attachment = VesselAttachment {
            node: elements,
            vessel: crate::vessel::rigid_body::Vessel::osv(),
            angle: lay.end_frame.transpose(),
            eta: nalgebra::Vector6::zeros(),
            controller: None,
            environment: Vec::new(),
            surface: 0.0,
            lay: Some(lay),
            winch: None,
            hull_loads: false,
        };
        let section = crate::rod::section::Section::pipe(
            0.6, 0.02, 7850.0, 207e9, 0.3, 0.0, [0.0; 2], [0.0; 2],
        )
        .unwrap();
        let rod = Rod::straight(start, end, elements, section).unwrap();
        RollerContact::new(&attachment, &rod, &rod.arc_lengths()).unwrap()
    }

    /// A pipe of 12 nodes, 5 m apart, laid over a stinger of 6 rollers fixed to the frame of its last node.
    pub(in crate::contact) fn pipe_over_stinger(
    ) -> (RollerContact, Vec<Vector3<f64>>, Vec<UnitQuaternion<f64>>) {
        let rollers =
            stinger_rollers(40.0, 30.0, 6, Vector3::new(-5.0, 0.0, 0.0), 0.0, 0.25).unwrap();
        let lay = LayEquipment::s_lay(Vector3::new(0.0, 0.0, -0.3), rollers, 1e7).unwrap();
        // A pipe 0.6 m across, 55 m in 11 elements.
        let contact = held_pipe(lay, Vector3::zeros(), Vector3::new(55.0, 0.0, 0.0), 11);
        // The pipe follows the stinger's arc 6 cm too low (pressed into the rollers), then hangs straight.
        let centre = Vector3::new(-5.0, 0.0, 40.0);
        let positions = (0..12)
            .map(|i| {
                let s = 5.0 * (11 - i) as f64;
                let angle = (s - 5.0).max(0.0) / 40.0;
                let radius = 40.0 + 0.3 - 0.06;
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

    /// A pipe bent to a circle of radius R = 200 m in elements of ℓ = 5 m slides over a roller inside the bend
    /// (at the distance from the circle's centre that presses it in by δ₀ = 1 cm): the roller's force stays
    /// k δ₀ within 2e-4 of it over a whole element of sliding, where the chord polygon's force would swing
    /// by k ℓ²/8R (1.56 kN for every 10 kN).
    #[test]
    fn a_pipe_sliding_over_a_roller_is_pressed_in_evenly() {
        let (mut contact, _, _) = pipe_over_stinger();
        let (bend, length, overlap) = (200.0, 5.0, 0.01);
        let angle = length / bend;
        let half_diameter = contact.surfaces.half_diameters[0];
        let radius = 0.25;
        let centre = Vector3::new(0.0, 0.0, bend);
        let axis = Vector3::y();
        contact.rollers = vec![LocalRoller {
            centre: centre - (bend - radius - half_diameter + overlap) * Vector3::z(),
            normal: -Vector3::z(),
            axis,
            half_length: f64::INFINITY,
            radius,
            friction: crate::vessel::lay::RollerFriction::default(),
        }];
        contact.forces = vec![0.0];
        contact.reactions = vec![Vector3::zeros()];
        contact.offsets = vec![f64::NAN];
        contact.nearest_elements = vec![0];
        // Elements away from the end node N, which stays at the origin: local coordinates are positions.
        contact.elements = 0..9;
        let rotations = vec![UnitQuaternion::identity(); 12];
        let expected = contact.stiffness * overlap;
        let mut worst: f64 = 0.0;
        for slide in 0..=20 {
            let shift = angle * f64::from(slide) / 20.0;
            let on_circle = |j: usize| {
                let theta = (j as f64 - 5.5) * angle + shift;
                centre + bend * Vector3::new(theta.sin(), 0.0, -theta.cos())
            };
            let positions: Vec<Vector3<f64>> = (0..12)
                .map(|j| {
                    if j < 11 {
                        on_circle(j)
                    } else {
                        Vector3::zeros()
                    }
                })
                .collect();
            let mut residual = vec![0.0; 72];
            contact.evaluate(
                ContactRule::Static,
                &positions,
                &rotations,
                None,
                &mut residual,
                None,
                None,
            );
            assert_eq!(contact.nearest_elements[0], if slide < 10 { 5 } else { 4 });
            worst = worst.max((contact.forces[0] / expected - 1.0).abs());
        }
        println!("largest relative change of the roller force {worst:.3e}");
        assert!(worst < 2e-4, "{worst:e}");
    }

    /// Where the pipe (elements 0–6) meets a thin wire (elements 7–10), each side's spline ends at the joint
    /// node 7: the pipe's last element is controlled by nodes 5–7 only, so swinging the wire 2 m about the
    /// joint leaves the pipe's distance from a roller unchanged (a spline running on into the wire would
    /// move it by centimetres). A cable's bars are their chords (linear weights).
    #[test]
    fn a_wire_fitted_to_the_pipe_does_not_bend_the_pipes_surface() {
        let (mut contact, positions, _) = pipe_over_stinger();
        for e in 7..11 {
            contact.surfaces.half_diameters[e] = 0.04;
        }
        assert_eq!(contact.surfaces.spline_ends(6), [false, true]);
        assert_eq!(contact.surfaces.spline_ends(7), [true, false]);
        let (_, count, nodes, node_count) = contact.segments(&[6]);
        assert_eq!((count, &nodes[..node_count]), (1, &[5, 6, 7][..]));
        let roller = &contact.rollers[0];
        // The roller's centre 0.5 m under the middle of element 6, as laid and with node 8 swung.
        let mut local = *roller;
        local.centre = 0.5 * (positions[6] + positions[7]) - 0.5 * roller.normal;
        let mut swung = positions.clone();
        swung[8] += Vector3::new(0.0, 2.0, 1.0);
        let distance = |y: &[Vector3<f64>], ends: [bool; 2]| {
            spline_distance(&local, 1.0, &[y[5], y[6], y[7], y[8]], ends).0
        };
        let ends = contact.surfaces.spline_ends(6);
        assert_eq!(distance(&positions, ends), distance(&swung, ends));
        let running_on = [false, false];
        let change = (distance(&positions, running_on) - distance(&swung, running_on)).abs();
        assert!(change > 0.01, "{change}");
        // A cable's bars are their chords: the spline ends at each of their nodes.
        for e in 7..11 {
            contact.surfaces.cables[e] = true;
        }
        assert_eq!(contact.surfaces.spline_ends(8), [true, true]);
        let [weights, _, _] = spline_weights(0.3, [true, true]);
        for (w, linear) in weights.iter().zip([0.0, 0.7, 0.3, 0.0]) {
            assert!((w - linear).abs() < 1e-15, "{weights:?}");
        }
    }

    /// The energy–momentum residual's tangent (central differences of the kernel) matches central
    /// differences of the assembled residual in the step's increments, the vessel node's rotation included,
    /// on frictionless rollers and on locked ones with friction slips from an earlier step.
    #[test]
    fn step_tangent_matches_differences_of_the_residual() {
        for locked in [false, true] {
            let (mut contact, positions, rotations) = pipe_over_stinger();
            if locked {
                for (k, roller) in contact.rollers.iter_mut().enumerate() {
                    roller.friction =
                        crate::vessel::lay::RollerFriction::new(0.3, 0.0, true).unwrap();
                    contact.slips[k] = Vector2::new(1e-5 * k as f64, -2e-6);
                }
            }
            step_tangent_matches(&mut contact, &positions, &rotations);
        }
    }

    fn step_tangent_matches(
        contact: &mut RollerContact,
        positions: &[Vector3<f64>],
        rotations: &[UnitQuaternion<f64>],
    ) {
        let rule = ContactRule::EnergyMomentum { time_step: 0.1 };
        let dofs = 6 * positions.len();
        let increments: Vec<f64> = (0..dofs)
            .map(|i| 1e-3 * ((i as f64) * 0.37).sin())
            .collect();
        let residual = |contact: &mut RollerContact, inc: &[f64]| {
            let mut r = vec![0.0; dofs];
            contact.evaluate(rule, positions, rotations, Some(inc), &mut r, None, None);
            r
        };
        let mut dense = Dense(HashMap::new());
        let mut r = vec![0.0; dofs];
        contact.evaluate(
            rule,
            positions,
            rotations,
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
        let sliding = contact.dissipated > 0.0;
        let mut worst: f64 = 0.0;
        let mut largest: f64 = 0.0;
        for column in 0..dofs {
            let h = if column % 6 < 3 { 1e-6 } else { 1e-8 };
            let mut plus = increments.clone();
            let mut minus = increments.clone();
            plus[column] += h;
            minus[column] -= h;
            let (rp, rm) = (residual(contact, &plus), residual(contact, &minus));
            for row in 0..dofs {
                let fd = (rp[row] - rm[row]) / (2.0 * h);
                let entry = dense.0.get(&(row, column)).copied().unwrap_or(0.0);
                worst = worst.max((fd - entry).abs());
                largest = largest.max(entry.abs());
            }
        }
        println!("worst tangent error {worst:.3e} of {largest:.3e} (sliding: {sliding})");
        assert!(worst < 1e-5 * largest, "{worst:e} of {largest:e}");
    }
}

#[cfg(test)]
mod box_tests {
    use super::tests::held_pipe;
    use super::*;
    use crate::vessel::lay::LayEquipment;
    use crate::vessel::roller_box::{BoxShape, RollerBox};

    /// A straight pipe 0.6 m across on a frictionless V box (half-angle θ = 30°, rollers 1.2 m long) standing
    /// 5 m from the held end, loaded by F down and L to starboard: the pipe's offset (m, lateral and down)
    /// where the rollers balance the load, or where the search for it ends unbalanced, whether they balance
    /// it, and each roller's reaction (N) and contact offset (m) there.
    fn pipe_in_a_v(load_down: f64, load_lateral: f64) -> (Vector3<f64>, bool, Vec<f64>, Vec<f64>) {
        let theta = std::f64::consts::FRAC_PI_6;
        let roller_box = RollerBox::new(BoxShape::V, theta, 1.2, false, false).unwrap();
        let station = Vector3::new(-5.0, 0.0, 0.0);
        let rollers = roller_box.rollers(station, -Vector3::z(), Vector3::y(), 0.25, 0);
        let lay = LayEquipment::s_lay(Vector3::zeros(), rollers, 1e7).unwrap();
        let mut contact = held_pipe(lay, Vector3::new(-10.0, 0.0, 0.0), Vector3::zeros(), 10);
        let rotations = vec![UnitQuaternion::identity(); 11];
        // The pipe's nodes but the held one moved by (lateral, down); the rollers' total force on it.
        let mut total = |offset: &Vector3<f64>| {
            let positions: Vec<Vector3<f64>> = (0..11)
                .map(|i| {
                    let x = Vector3::new(-10.0 + i as f64, 0.0, 0.0);
                    if i < 10 {
                        x + offset
                    } else {
                        x
                    }
                })
                .collect();
            let mut residual = vec![0.0; 66];
            contact.evaluate(
                ContactRule::Static,
                &positions,
                &rotations,
                None,
                &mut residual,
                None,
                None,
            );
            let force: Vector3<f64> = contact.reactions.iter().sum();
            (
                force + Vector3::new(0.0, load_lateral, load_down),
                contact.reactions.clone(),
                contact.offsets.clone(),
            )
        };
        // Damped Newton on the pipe's lateral and vertical offset, the Jacobian by central differences. On a
        // single roller the contact is stiff only along its normal: along the roller the pipe moves with the
        // unbalanced force instead, by up to 2 cm a step.
        let mut offset = Vector3::new(0.0, 0.0, -0.3 / theta.cos());
        for _ in 0..200 {
            let (r, _, _) = total(&offset);
            if r.yz().norm() < 1e-6 * load_down {
                break;
            }
            let h = 1e-7;
            let mut jacobian = nalgebra::Matrix2::zeros();
            for j in 0..2 {
                let mut step = Vector3::zeros();
                step[j + 1] = h;
                let difference =
                    (total(&(offset + step)).0 - total(&(offset - step)).0) / (2.0 * h);
                jacobian.set_column(j, &difference.yz());
            }
            let svd = jacobian.svd(true, true);
            let (u, v_t) = (svd.u.unwrap(), svd.v_t.unwrap());
            let mut delta = nalgebra::Vector2::zeros();
            let mut unbalanced = r.yz();
            for i in 0..2 {
                let (u_i, v_i) = (u.column(i), v_t.row(i).transpose());
                if svd.singular_values[i] > 1e-6 * svd.singular_values.max() {
                    delta -= u_i.dot(&r.yz()) / svd.singular_values[i] * v_i;
                    unbalanced -= u_i.dot(&r.yz()) * u_i;
                }
            }
            if unbalanced.norm() > 1e-9 * load_down {
                delta += 0.02 * unbalanced.normalize();
            }
            let scale = (0.02 / delta.norm()).min(1.0);
            offset += Vector3::new(0.0, scale * delta.x, scale * delta.y);
        }
        let (r, reactions, offsets) = total(&offset);
        let magnitudes = reactions.iter().map(|f| f.norm()).collect();
        (
            offset,
            r.yz().norm() < 1e-6 * load_down,
            magnitudes,
            offsets,
        )
    }

    /// Frictionless, symmetric V under a vertical load F: each roller carries F/(2 cos θ), and the pipe rests
    /// R tan θ up each roller from its lower end; with a lateral load L both carry F/(2 cos θ) ± L/(2 sin θ).
    #[test]
    fn v_box_reactions_match_the_closed_form() {
        let (theta, load) = (std::f64::consts::FRAC_PI_6, 50e3);
        let (_, balanced, reactions, offsets) = pipe_in_a_v(load, 0.0);
        assert!(balanced);
        for (reaction, offset) in reactions.iter().zip(&offsets) {
            let expected = load / (2.0 * theta.cos());
            assert!(
                (reaction / expected - 1.0).abs() < 1e-6,
                "{reaction} vs {expected}"
            );
            // R tan θ from the lower end, 0.6 m below the centre, less the overlap's shift along the roller.
            assert!(
                (offset - (0.3 * theta.tan() - 0.6)).abs() < 2e-3,
                "{offset}"
            );
        }
        let lateral = 0.5 * load * theta.tan();
        let (_, balanced, reactions, _) = pipe_in_a_v(load, lateral);
        assert!(balanced);
        let expected = [
            load / (2.0 * theta.cos()) - lateral / (2.0 * theta.sin()),
            load / (2.0 * theta.cos()) + lateral / (2.0 * theta.sin()),
        ];
        for (reaction, expected) in reactions.iter().zip(expected) {
            assert!(
                (reaction / expected - 1.0).abs() < 1e-6,
                "{reaction} vs {expected}"
            );
        }
    }

    /// The pipe climbs out of the V at a lateral load of F tan θ: at 0.97 F tan θ it rests on both rollers
    /// inside the box, the port roller's share F/(2 cos θ) − L/(2 sin θ) small but positive; at 1.03 F tan θ
    /// no place in the box balances the load: the port roller unloads and the pipe slides up the starboard
    /// roller to its upper end (within 1 mm), where it leaves the box.
    #[test]
    fn a_pipe_climbs_out_of_the_v_at_f_tan_theta() {
        let (theta, load) = (std::f64::consts::FRAC_PI_6, 50e3);
        let lateral = 0.97 * load * theta.tan();
        let (_, balanced, reactions, offsets) = pipe_in_a_v(load, lateral);
        let port = load / (2.0 * theta.cos()) - lateral / (2.0 * theta.sin());
        assert!(
            balanced && (reactions[0] / port - 1.0).abs() < 1e-6,
            "{reactions:?}"
        );
        assert!(offsets.iter().all(|o| o.abs() < 0.5), "{offsets:?}");
        let (offset, balanced, reactions, offsets) = pipe_in_a_v(load, 1.03 * load * theta.tan());
        assert!(!balanced);
        assert_eq!(reactions[0], 0.0, "{reactions:?}");
        assert!(offsets[1] > 0.599, "{offsets:?}");
        // The pipe's centre has risen with it, to about the V's upper ends (0.6 m above the station).
        assert!(-offset.z > 0.8 && offset.y > 0.85, "{offset}");
    }
}
