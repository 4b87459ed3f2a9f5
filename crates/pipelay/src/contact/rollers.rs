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
//! **Rollers on an articulated stinger's section** ([`crate::vessel::articulation`]) stand still in the
//! section's frame, placed in the end node's by S(φ)(z) = R z + t. V is taken as a function of the nodes'
//! coordinates in the section's frame, z = S(φ)⁻¹(y), and its gradient g_z maps to the unknowns:
//! - statics: ∂V/∂y = R g_z and ∂V/∂φ_i = −e·Σ_j (y_j − H_i) × R g_z,j (H_i: hinge i, e: the hinges' axis);
//! - in a step, Δz = ½(R₀ᵀ + R₁ᵀ)Δy + S₁⁻¹(u) − S₀⁻¹(u) with u = ½(y₀ + y₁), exactly: Δy carries
//!   ½(R₀ + R₁) ∇̄V_z, and the angles the discrete gradient of ψ(φ) = Σ_j ∇̄V_z,j·S(φ)⁻¹(u_j), so that the
//!   work is ΔV exactly again.
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
use crate::vessel::articulation::{Chain, MAX_SECTIONS};
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
const MAX_VARIABLES: usize = 3 * MAX_NODES + 6 + MAX_SECTIONS;

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
    /// An articulated stinger's hinges in the end node's frame, and the global DOF of the first hinge angle.
    chain: Option<Chain>,
    hinge_base: usize,
    /// The hinge angles at the evaluated step's start and end (rad).
    angles: [[f64; MAX_SECTIONS]; 2],
    /// As `locals`, in each section's frame.
    section_locals: Vec<[Vec<Vector3<f64>>; 3]>,
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
        let chain = lay
            .articulation
            .as_ref()
            .map(|a| a.chain.in_frame(&to_end, &hold));
        let sections = chain.as_ref().map_or(0, |c| c.hinges.len());
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
            section_locals: (0..sections)
                .map(|_| std::array::from_fn(|_| Vec::with_capacity(elements.len() + 1)))
                .collect(),
            chain,
            hinge_base: 6 * rod.node_count(),
            angles: [[0.0; MAX_SECTIONS]; 2],
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

    /// Section j's placement S(φ) = (R, t) at the step's start (`state` 1), end (0) or the mean of the two
    /// angles (2).
    fn placement(&self, section: usize, state: usize) -> (Matrix3<f64>, Vector3<f64>) {
        let Some(chain) = &self.chain else {
            return (Matrix3::identity(), Vector3::zeros());
        };
        let angles: [f64; MAX_SECTIONS] = match state {
            2 => std::array::from_fn(|i| 0.5 * (self.angles[0][i] + self.angles[1][i])),
            _ => self.angles[state],
        };
        chain.placement(&angles, section)
    }

    /// Fills each section's locals from the end node's: z = S(φ)⁻¹(y) at the end and start angles, and the
    /// two's mean.
    fn fill_section_locals(&mut self, stepping: bool) {
        for j in 0..self.section_locals.len() {
            let states = if stepping { 2 } else { 1 };
            for state in 0..states {
                let (rotation, translation) = self.placement(j, state);
                let (locals, section_locals) = (&self.locals[state], &mut self.section_locals[j]);
                section_locals[state].clear();
                section_locals[state].extend(
                    locals
                        .iter()
                        .map(|y| rotation.transpose() * (y - translation)),
                );
            }
            if stepping {
                let [end, start, mid] = &mut self.section_locals[j];
                mid.clear();
                mid.extend(end.iter().zip(start.iter()).map(|(a, b)| 0.5 * (a + b)));
            }
        }
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
        type Nearest = (f64, Segment, [f64; 4], Vector3<f64>, f64);
        let mut best: Option<Nearest> = None;
        for segment in segments {
            let e = segment.element;
            let reach = roller.radius + self.surfaces.half_diameters[e];
            let points = segment.control.map(|i| y[i]);
            let taper = self.surfaces.tapers[e];
            let foot = spline_distance(roller, reach, &points, segment.mirrored, taper);
            let gap = self.surfaces.gap(e, &foot);
            if best.is_none_or(|b| gap < b.0) {
                best = Some((gap, *segment, foot.weights, foot.direction, foot.along));
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

    /// ∂δ/∂z of the overlap δ = √(2V/k) from the potential V and its gradient ∂V/∂z = k δ ∂δ/∂z at a state
    /// (zero out of contact).
    fn overlap_gradient(&self, value: f64, gradient: &[Vector3<f64>]) -> [Vector3<f64>; MAX_NODES] {
        let overlap = (2.0 * value / self.stiffness).max(0.0).sqrt();
        std::array::from_fn(|i| match gradient.get(i) {
            Some(g) if overlap > 0.0 => g / (self.stiffness * overlap),
            _ => Vector3::zeros(),
        })
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

    /// Adds the rollers' residual at the state `start` + `increments` (all DOFs, node-major [Δx, θ], then the
    /// hinge angles' Δφ; `None`: zero), and with `sink` their tangent. Statics (`ContactRule::Static`): the
    /// forces at that state, with rotations updated by exp(θ); the energy–momentum step: the discrete
    /// gradient over the step from `start`, with the Cayley update. `hinge_angles` are the start's. Sets
    /// `forces` and `energy_end` at the end state.
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate(
        &mut self,
        rule: ContactRule,
        positions: &[Vector3<f64>],
        rotations: &[UnitQuaternion<f64>],
        hinge_angles: &[f64],
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
        let hinges = self.section_locals.len();
        for (i, &angle) in hinge_angles.iter().enumerate().take(hinges) {
            self.angles[1][i] = angle;
            self.angles[0][i] = angle + increments.map_or(0.0, |inc| inc[self.hinge_base + i]);
        }
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
        self.fill_section_locals(stepping);
        let first = self.elements.start;
        for k in 0..self.rollers.len() {
            // The roller's frame: the end node's, or its section's.
            let section = self.rollers[k].section;
            let placements = section.map(|j| [self.placement(j, 0), self.placement(j, 1)]);
            let to_frame = |state: usize, y: Vector3<f64>| match &placements {
                Some(p) => p[state].0.transpose() * (y - p[state].1),
                None => y,
            };
            let frame_end = |node: usize| to_frame(0, end_local(node));
            let frame_start = |node: usize| to_frame(1, start_local(node));
            let frame_mid = |node: usize| 0.5 * (frame_start(node) + frame_end(node));
            let locals = match section {
                Some(j) => &self.section_locals[j],
                None => &self.locals,
            };
            // The nodes R: elements nearest at the end (and, in a step, at the start and midpoint).
            let roller = &self.rollers[k];
            let diameters = &self.surfaces.half_diameters;
            let mut chords = [nearest(roller, diameters, first, &locals[0]); 3];
            let mut elements = [self.nearest_segment(k, chords[0], &frame_end); 3];
            let states = if stepping { 3 } else { 1 };
            if stepping {
                chords[1] = nearest(roller, diameters, first, &locals[1]);
                chords[2] = nearest(roller, diameters, first, &locals[2]);
                elements[1] = self.nearest_segment(k, chords[1], &frame_start);
                elements[2] = self.nearest_segment(k, chords[2], &frame_mid);
            }
            let (segments, segment_count, nodes, count) = self.segments(&elements[..states]);
            let (segments, nodes) = (&segments[..segment_count], &nodes[..count]);
            // The energy and the contact at the step's start do not depend on the unknowns: once per roller.
            let (value_start, touch_start) = if stepping {
                let z_start: [Vector3<f64>; MAX_NODES] = std::array::from_fn(|i| {
                    nodes
                        .get(i)
                        .map_or_else(Vector3::zeros, |&node| frame_start(node))
                });
                let (value, _, touch) = self.potential(k, segments, &z_start[..count]);
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
            let angle_count = section.map_or(0, |j| j + 1);
            let variables = 3 * count + 6 + angle_count;
            // Unknowns: Δx of each node of R, then Δx and θ of N, then the angles of the section's hinges;
            // residual in the same order.
            let mut base = [0.0; MAX_VARIABLES];
            for (i, &node) in nodes.iter().enumerate() {
                base[3 * i..3 * i + 3].copy_from_slice(step_of(node).as_slice());
            }
            base[3 * count..3 * count + 3].copy_from_slice(step_of(n).as_slice());
            base[3 * count + 3..3 * count + 6].copy_from_slice(theta.as_slice());
            for i in 0..angle_count {
                base[3 * count + 6 + i] = self.angles[0][i] - self.angles[1][i];
            }
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
                let turn = placements.map_or_else(Matrix3::identity, |p| p[0].0);
                (self.to_end.transpose() * turn * touch.reaction, touch.along)
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
            let hinge_base = self.hinge_base;
            let dof = |i: usize| {
                if i < 3 * count {
                    6 * nodes[i / 3] + i % 3
                } else if i < 3 * count + 6 {
                    6 * n + (i - 3 * count)
                } else {
                    hinge_base + (i - 3 * count - 6)
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
        // In the roller's frame: the end node's, or its section's at the step's start and end angles.
        let hinged = self.rollers[k].section.zip(self.chain.as_ref());
        let mut angles = self.angles;
        if let Some((j, _)) = hinged {
            for i in 0..=j {
                angles[0][i] = angles[1][i] + step[3 * count + 6 + i];
            }
        }
        let placements = hinged.map(|(j, chain)| {
            [
                chain.placement(&angles[0], j),
                chain.placement(&angles[1], j),
            ]
        });
        let (mut z_start, mut z_end) = (y_start, y_end);
        if let Some([(r_end, t_end), (r_start, t_start)]) = &placements {
            for i in 0..count {
                z_end[i] = r_end.transpose() * (y_end[i] - t_end);
                z_start[i] = r_start.transpose() * (y_start[i] - t_start);
            }
        }
        let (value_end, mut gradient_end, touch) =
            self.potential(k, contact.segments, &z_end[..count]);
        let roller = &self.rollers[k];
        let mut slip = Vector2::zeros();
        let mut dissipated = 0.0;
        let mut friction_energy = 0.0;
        let mut out = [0.0; MAX_VARIABLES];
        let (gradient, frame, arms) = match rule {
            ContactRule::Static => {
                // The pipe slides out over the rollers: held back toward the hold point with the limit force.
                if let Some(touch) = touch.filter(|_| !roller.friction.is_frictionless()) {
                    let z = |slot: usize| z_end[touch.control[slot]];
                    let toward_hold = if self.end_node == 0 { -1.0 } else { 1.0 } * (z(2) - z(1));
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
                // ∂V/∂y = R g_z and ∂V/∂φ_i = −e·Σ_j (y_j − H_i) × R g_z,j.
                if let (Some((j, chain)), Some([(rotation, _), _])) = (hinged, &placements) {
                    let hinges = chain.hinge_positions(&angles[0], j);
                    for g in &mut gradient_end[..count] {
                        *g = rotation * *g;
                    }
                    for (h, hinge) in hinges[..=j].iter().enumerate() {
                        out[3 * count + 6 + h] = -chain.axis.dot(
                            &(0..count)
                                .map(|i| (y_end[i] - hinge).cross(&gradient_end[i]))
                                .sum::<Vector3<f64>>(),
                        );
                    }
                }
                let arms: [Vector3<f64>; MAX_NODES] =
                    std::array::from_fn(|i| x_end[i] - end.position);
                (gradient_end, end.rotation, arms)
            }
            ContactRule::EnergyMomentum { .. } => {
                let mut z_mid = [Vector3::zeros(); MAX_NODES];
                let mut change2 = 0.0;
                for i in 0..count {
                    z_mid[i] = 0.5 * (z_start[i] + z_end[i]);
                    change2 += (z_end[i] - z_start[i]).norm_squared();
                }
                let value_start = contact.value_start;
                let (value_mid, mut gradient, _) =
                    self.potential(k, contact.segments, &z_mid[..count]);
                let overlap_gradient = self.overlap_gradient(value_mid, &gradient[..count]);
                let along: f64 = (0..count)
                    .map(|i| gradient[i].dot(&(z_end[i] - z_start[i])))
                    .sum();
                // The correction where it rises above the round-off of V (positions known to ε|y|): below,
                // dividing by |Δz|² would turn that round-off into force.
                let extent = y_end[..count].iter().map(|y| y.norm()).fold(1.0, f64::max);
                let force: f64 = gradient[..count].iter().map(|g| g.norm()).sum();
                let noise = 64.0 * f64::EPSILON * (value_end + value_start + force * extent);
                let mismatch = value_end - value_start - along;
                if change2 > 0.0 && mismatch.abs() > noise {
                    let c = mismatch / change2;
                    for i in 0..count {
                        gradient[i] += c * (z_end[i] - z_start[i]);
                    }
                }
                // High-frequency damping of the contact: ξ k Δδ along the discrete gradient of the overlap δ,
                // whose work ξ k Δδ² ≥ 0 is all dissipated (the contact force stays a push for ξ ≤ ½).
                let damped = match rule {
                    ContactRule::EnergyMomentum { damping, .. } if damping > 0.0 => {
                        let overlap = |v: f64| (2.0 * v / self.stiffness).max(0.0).sqrt();
                        let change = overlap(value_end) - overlap(value_start);
                        let along: f64 = (0..count)
                            .map(|i| overlap_gradient[i].dot(&(z_end[i] - z_start[i])))
                            .sum();
                        let c = if change2 > 0.0 {
                            (change - along) / change2
                        } else {
                            0.0
                        };
                        let scale = damping * self.stiffness * change;
                        for i in 0..count {
                            gradient[i] +=
                                scale * (overlap_gradient[i] + c * (z_end[i] - z_start[i]));
                        }
                        scale * change
                    }
                    _ => 0.0,
                };
                // Friction on the material point's move Δu = Σ w_j Δz_j, in the directions of the step's start.
                if let Some(frame) = &contact.friction {
                    let moved: Vector3<f64> = frame
                        .control
                        .iter()
                        .zip(frame.weights)
                        .map(|(&i, w)| w * (z_end[i] - z_start[i]))
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
                dissipated += damped;
                if let (Some((j, chain)), Some([(r_end, _), (r_start, _)])) = (hinged, &placements)
                {
                    let u: [Vector3<f64>; MAX_NODES] =
                        std::array::from_fn(|i| 0.5 * (y_start[i] + y_end[i]));
                    let torques = section_gradient(
                        chain,
                        j,
                        &angles,
                        &gradient[..count],
                        &u[..count],
                        value_end + value_start + force * extent,
                    );
                    out[3 * count + 6..3 * count + 7 + j].copy_from_slice(&torques[..=j]);
                    let mean = 0.5 * (r_start + r_end);
                    for g in &mut gradient[..count] {
                        *g = mean * *g;
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
        RollerStep {
            residual: out,
            energy: value_end + friction_energy,
            touch,
            slip,
            dissipated,
        }
    }
}

/// The discrete gradient over a step of the section's hinge angles (0..=`section`) of
/// ψ(φ) = Σ_j g_j·S(φ)⁻¹(u_j), for the section's gradient `gradient` (g_z) and the nodes' mean local
/// coordinates `u`, from the start (`angles[1]`) to the end (`angles[0]`): ∇ψ(φ̄) + [Δψ − ∇ψ(φ̄)·Δφ]Δφ/|Δφ|²,
/// the correction left out below the round-off `scale`·ε. ∂S⁻¹(u)/∂φ_i = −Rᵀ(e × (u − H_i)).
fn section_gradient(
    chain: &Chain,
    section: usize,
    angles: &[[f64; MAX_SECTIONS]; 2],
    gradient: &[Vector3<f64>],
    u: &[Vector3<f64>],
    scale: f64,
) -> [f64; MAX_SECTIONS] {
    let psi = |phi: &[f64; MAX_SECTIONS]| {
        let (rotation, translation) = chain.placement(phi, section);
        gradient
            .iter()
            .zip(u)
            .map(|(g, u)| g.dot(&(rotation.transpose() * (u - translation))))
            .sum::<f64>()
    };
    let mid: [f64; MAX_SECTIONS] = std::array::from_fn(|i| 0.5 * (angles[0][i] + angles[1][i]));
    let (rotation, _) = chain.placement(&mid, section);
    let hinges = chain.hinge_positions(&mid, section);
    let mut result = [0.0; MAX_SECTIONS];
    for (i, hinge) in hinges[..=section].iter().enumerate() {
        result[i] = -chain.axis.dot(
            &gradient
                .iter()
                .zip(u)
                .map(|(g, u)| (u - hinge).cross(&(rotation * g)))
                .sum::<Vector3<f64>>(),
        );
    }
    let change: [f64; MAX_SECTIONS] = std::array::from_fn(|i| angles[0][i] - angles[1][i]);
    let change2: f64 = change[..=section].iter().map(|c| c * c).sum();
    let along: f64 = (0..=section).map(|i| result[i] * change[i]).sum();
    let mismatch = psi(&angles[0]) - psi(&angles[1]) - along;
    if change2 > 0.0 && mismatch.abs() > 64.0 * f64::EPSILON * scale {
        for i in 0..=section {
            result[i] += mismatch / change2 * change[i];
        }
    }
    result
}

#[cfg(test)]
#[path = "rollers_tests.rs"]
pub(super) mod tests;

#[cfg(test)]
#[path = "roller_box_tests.rs"]
mod box_tests;
