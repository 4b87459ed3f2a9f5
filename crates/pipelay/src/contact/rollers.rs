//! Rollers on the vessel: unilateral contact of the pipe's outer surface with vessel-fixed cylinders, in
//! statics and in the energy–momentum step.
//!
//! **Geometry.** A roller has an axis line (centre c, unit direction a) and radius r_r; it is fixed in the
//! frame of the vessel's end node N, where the pipe's nodes have local coordinates y_j = Λ_Nᵀ(x_j − x_N).
//! The pipe's centreline is the Catmull–Rom spline through the nodes: on element i,
//! r(ξ) = Σ_j w_j(ξ) y_j over the nodes i − 1 … i + 2 (ξ ∈ [0, 1]; at an end of the rod, and at a joint of
//! elements of different diameters, the missing node is mirrored, y_{−1} = 2y_0 − y_1), which passes through
//! the nodes with a continuous tangent. Its distance
//! from the axis, in the plane normal to a, is d = min over ξ of |(I − a aᵀ)(r(ξ) − c)| on the elements next
//! to the nearest chord, counted negative on the far side of the axis (against the roller's normal, the side
//! the pipe rests on). The surfaces overlap by δ = r_r + d_o/2 − d; the contact potential is V = ½ k δ₊²
//! (k the roller stiffness, N/m), pushing only, so the pipe lifts off freely. Because the spline has no
//! kinks, V changes smoothly as the pipe slides over a roller: the chord polygon, whose nodes stand out of
//! its chords by the sagitta ℓ²/8R on a stinger of radius R, bumped every roller once per element, and a
//! stiff contact rang with it. At the foot ξ*, ∂d/∂y_j = w_j(ξ*) n (n the unit foot direction).
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
use crate::contact::rule::ContactRule;
use crate::contact::sinks::EntrySink;
use crate::rod::Rod;
use crate::so3::{cayley, exp, skew};
use crate::vessel::lay::Roller;
use crate::vessel::VesselAttachment;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

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
    /// The line's surface along each element of the rod.
    surfaces: Surfaces,
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

/// One element of the spline: the indices, in a roller's node list, of its control nodes i − 1, i, i + 1 and
/// i + 2 ([`Surfaces::control_nodes`]), and whether the first or the last is mirrored ([`Surfaces::spline_ends`]).
#[derive(Debug, Clone, Copy)]
struct Segment {
    element: usize,
    control: [usize; 4],
    mirrored: [bool; 2],
}

/// What one roller's residual is evaluated on: the spline's elements near it, the nodes that control them
/// (sorted) and, in a step, the contact energy at the step's start.
struct Spline<'a> {
    segments: &'a [Segment],
    nodes: &'a [usize],
    value_start: f64,
}

/// Catmull–Rom weights w_j(ξ) of the four control nodes and their first and second derivatives in ξ, with a
/// mirrored end (y_{i−1} = 2y_i − y_{i+1}, y_{i+2} = 2y_{i+1} − y_i) folded into the nodes that stand for it.
fn spline_weights(xi: f64, mirrored: [bool; 2]) -> [[f64; 4]; 3] {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    let mut weights = [
        [
            0.5 * (-x3 + 2.0 * x2 - xi),
            0.5 * (3.0 * x3 - 5.0 * x2 + 2.0),
            0.5 * (-3.0 * x3 + 4.0 * x2 + xi),
            0.5 * (x3 - x2),
        ],
        [
            0.5 * (-3.0 * x2 + 4.0 * xi - 1.0),
            0.5 * (9.0 * x2 - 10.0 * xi),
            0.5 * (-9.0 * x2 + 8.0 * xi + 1.0),
            0.5 * (3.0 * x2 - 2.0 * xi),
        ],
        [
            0.5 * (-6.0 * xi + 4.0),
            0.5 * (18.0 * xi - 10.0),
            0.5 * (-18.0 * xi + 8.0),
            0.5 * (6.0 * xi - 2.0),
        ],
    ];
    for w in &mut weights {
        if mirrored[0] {
            w[1] += 2.0 * w[0];
            w[2] -= w[0];
            w[0] = 0.0;
        }
        if mirrored[1] {
            w[2] += 2.0 * w[3];
            w[1] -= w[3];
            w[3] = 0.0;
        }
    }
    weights
}

/// Signed distance d from the roller's axis to the spline element through `points` (see [`chord_distance`]
/// for the sign), the weights w_j(ξ*) at its foot and the signed unit foot direction ±n, so that
/// ∂d/∂y_j = w_j(ξ*) (±n). The foot ξ* ∈ [0, 1] is found by Newton's method on ∂|u(ξ)|²/∂ξ = 0 from the
/// chord's foot, u(ξ) the spline point's offset from the axis in the plane normal to it.
fn spline_distance(
    roller: &LocalRoller,
    reach: f64,
    points: &[Vector3<f64>; 4],
    mirrored: [bool; 2],
) -> (f64, [f64; 4], Vector3<f64>) {
    let offsets = points.map(|y| roller.projector * (y - roller.centre));
    let combine = |w: &[f64; 4]| -> Vector3<f64> {
        w.iter()
            .zip(&offsets)
            .map(|(w, u)| *w * u)
            .sum::<Vector3<f64>>()
    };
    let chord = offsets[2] - offsets[1];
    let length2 = chord.norm_squared();
    let mut xi = if length2 > 0.0 {
        (-offsets[1].dot(&chord) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    for _ in 0..30 {
        let [w, dw, ddw] = spline_weights(xi, mirrored);
        let (foot, tangent, bend) = (combine(&w), combine(&dw), combine(&ddw));
        let metric = tangent.norm_squared();
        if metric == 0.0 {
            break;
        }
        // Newton's step, or Gauss–Newton's where the curvature term would make it climb.
        let curvature = metric + foot.dot(&bend);
        let slope = foot.dot(&tangent);
        let next = (xi - slope / curvature.max(0.5 * metric)).clamp(0.0, 1.0);
        let converged = (next - xi).abs() <= 1e-15;
        xi = next;
        if converged {
            break;
        }
    }
    let [weights, _, _] = spline_weights(xi, mirrored);
    let foot = combine(&weights);
    let d = foot.norm();
    let normal = if d > 0.0 { foot / d } else { Vector3::zeros() };
    if foot.dot(&roller.normal) >= 0.0 {
        (d, weights, normal)
    } else if d < 2.0 * reach {
        (-d, weights, -normal)
    } else {
        (f64::INFINITY, [0.0; 4], Vector3::zeros())
    }
}

/// The line's surface along each element: half its hydrodynamic diameter (m), and whether it is a cable's
/// bar (whose centreline is its chord, kinked at the nodes).
#[derive(Debug, Clone)]
struct Surfaces {
    half_diameters: Vec<f64>,
    cables: Vec<bool>,
}

impl Surfaces {
    fn new(rod: &Rod) -> Self {
        let sections = (0..rod.element_count()).map(|e| rod.section(e));
        Surfaces {
            half_diameters: sections
                .clone()
                .map(|s| 0.5 * s.hydrodynamic_diameter)
                .collect(),
            cables: sections.map(|s| s.cable).collect(),
        }
    }

    /// Whether element e's spline ends at its first or last node (mirrored there): at an end of the rod, at
    /// a joint of two elements of different diameters (a pipe's end and the wire fitted to it, say), so
    /// that the one's direction does not bend the other's surface, and at both ends of a cable's bar, which
    /// makes the spline its chord.
    fn spline_ends(&self, e: usize) -> [bool; 2] {
        let (diameters, cables) = (&self.half_diameters, &self.cables);
        let joint = |other: usize| diameters[other] != diameters[e] || cables[other] || cables[e];
        [
            e == 0 || joint(e - 1),
            e + 1 == diameters.len() || joint(e + 1),
        ]
    }

    /// Element e's control nodes e − 1, e, e + 1, e + 2 and its [`Self::spline_ends`]; a mirrored node's slot
    /// holds its neighbour in the element (its weight is zero: any node stands for it).
    fn control_nodes(&self, e: usize) -> ([usize; 4], [bool; 2]) {
        let ends = self.spline_ends(e);
        let first = if ends[0] { e } else { e - 1 };
        let last = if ends[1] { e + 1 } else { e + 2 };
        ([first, e, e + 1, last], ends)
    }
}

/// Of the spline's elements next to the nearest chord `chord` (itself and its neighbours within
/// `elements`), the one whose surface is nearest `roller`, and its gap d − D/2 − r_r (m), the nodes'
/// coordinates in the roller's frame given by `local`.
fn nearest_spline_element(
    roller: &LocalRoller,
    surfaces: &Surfaces,
    elements: std::ops::Range<usize>,
    chord: usize,
    local: &dyn Fn(usize) -> Vector3<f64>,
) -> (f64, usize) {
    let mut best = (f64::INFINITY, chord);
    for e in [chord.wrapping_sub(1), chord, chord + 1] {
        if !elements.contains(&e) {
            continue;
        }
        let (control, mirrored) = surfaces.control_nodes(e);
        let points = control.map(local);
        let half_diameter = surfaces.half_diameters[e];
        let (d, _, _) = spline_distance(roller, roller.radius + half_diameter, &points, mirrored);
        if d - half_diameter < best.0 {
            best = (d - half_diameter, e);
        }
    }
    (best.0 - roller.radius, best.1)
}

/// The gap (m) between the line's surface and `roller` (in the vessel's body frame, whose rotation to e is
/// `body` and whose roller frame origin lies at `origin` in e) as the contact measures it: from the spline's
/// element nearest the roller next to the chord `chord`; ≤ 0 in contact (minus the overlap).
pub fn roller_gap(
    rod: &Rod,
    positions: &[Vector3<f64>],
    roller: &Roller,
    body: &Matrix3<f64>,
    origin: &Vector3<f64>,
    chord: usize,
) -> f64 {
    let axis = roller.axis;
    let local = LocalRoller {
        centre: roller.centre,
        normal: roller.normal,
        axis,
        projector: Matrix3::identity() - axis * axis.transpose(),
        radius: roller.radius,
    };
    let surfaces = Surfaces::new(rod);
    let elements = 0..surfaces.half_diameters.len();
    let in_body = |node: usize| body.transpose() * (positions[node] - origin);
    nearest_spline_element(&local, &surfaces, elements, chord, &in_body).0
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
            surfaces: Surfaces::new(rod),
            elements,
            energy_end: 0.0,
        })
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

    /// V and ∂V/∂y_j over the spline's `segments` (nodes' local coordinates `y`, in the roller's node order).
    fn potential(
        &self,
        k: usize,
        segments: &[Segment],
        y: &[Vector3<f64>],
    ) -> (f64, [Vector3<f64>; MAX_NODES]) {
        let roller = &self.rollers[k];
        // The element whose surface is nearest: the smallest gap d − D/2.
        let mut best: Option<(f64, Segment, [f64; 4], Vector3<f64>)> = None;
        for segment in segments {
            let half_diameter = self.surfaces.half_diameters[segment.element];
            let reach = roller.radius + half_diameter;
            let points = segment.control.map(|i| y[i]);
            let (d, weights, direction) = spline_distance(roller, reach, &points, segment.mirrored);
            if best.is_none_or(|b| d - half_diameter < b.0) {
                best = Some((d - half_diameter, *segment, weights, direction));
            }
        }
        let mut gradient = [Vector3::zeros(); MAX_NODES];
        let Some((gap, segment, weights, direction)) = best else {
            return (0.0, gradient);
        };
        let overlap = roller.radius - gap;
        if overlap <= 0.0 {
            return (0.0, gradient);
        }
        for (i, w) in segment.control.iter().zip(weights) {
            gradient[*i] -= self.stiffness * overlap * w * direction;
        }
        (0.5 * self.stiffness * overlap * overlap, gradient)
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
            // The energy at the step's start does not depend on the unknowns: once per roller.
            let value_start = if stepping {
                let y_start: [Vector3<f64>; MAX_NODES] = std::array::from_fn(|i| {
                    nodes
                        .get(i)
                        .map_or_else(Vector3::zeros, |&node| start_local(node))
                });
                self.potential(k, segments, &y_start[..count]).0
            } else {
                0.0
            };
            let contact = Spline {
                segments,
                nodes,
                value_start,
            };
            let variables = 3 * count + 6;
            // Unknowns: Δx of each node of R, then Δx and θ of N; residual in the same order.
            let mut base = [0.0; MAX_VARIABLES];
            for (i, &node) in nodes.iter().enumerate() {
                base[3 * i..3 * i + 3].copy_from_slice(step_of(node).as_slice());
            }
            base[3 * count..3 * count + 3].copy_from_slice(step_of(n).as_slice());
            base[3 * count + 3..variables].copy_from_slice(theta.as_slice());
            let (forces, value, normal_force) =
                self.roller_residual(k, rule, &contact, positions, &start, &base, &update);
            self.forces[k] = normal_force;
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
                    let (fp, _, _) =
                        self.roller_residual(k, rule, &contact, positions, &start, &plus, &update);
                    let (fm, _, _) =
                        self.roller_residual(k, rule, &contact, positions, &start, &minus, &update);
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

    /// Roller k's residual over its unknowns `step` (see [`Self::evaluate`]) on the spline `contact`, the
    /// contact energy at the end and the roller's normal force there.
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
    ) -> ([f64; MAX_VARIABLES], f64, f64) {
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
        let (value_end, gradient_end) = self.potential(k, contact.segments, &y_end[..count]);
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
                let value_start = contact.value_start;
                let (_, mut gradient) = self.potential(k, contact.segments, &y_mid[..count]);
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
            projector: Matrix3::identity() - axis * axis.transpose(),
            radius,
        }];
        contact.forces = vec![0.0];
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
