//! The rollers' geometry: where the pipe's surface is nearest a roller of finite length.
//!
//! A roller has an axis segment (centre c, unit direction a, half-length h; h = ∞ for the long cylinders of a
//! plain stinger) and radius r_r; it is fixed in the frame of the vessel's end node N, where the pipe's nodes
//! have local coordinates y_j = Λ_Nᵀ(x_j − x_N). A point y's offset from the axis segment is
//! u(y) = v − clamp(a·v, −h, h) a with v = y − c: normal to a beside the roller, and pointing from the
//! nearer end of the axis beyond it, so that the roller's ends are rounded (a capsule) and the distance |u|
//! has a continuous gradient u/|u| everywhere.
//!
//! The pipe's centreline is the Catmull–Rom spline through the nodes: on element i,
//! r(ξ) = Σ_j w_j(ξ) y_j over the nodes i − 1 … i + 2 (ξ ∈ [0, 1]; at an end of the rod, and at a joint of
//! elements of different diameters, the missing node is mirrored, y_{−1} = 2y_0 − y_1), which passes through
//! the nodes with a continuous tangent. Its distance from the roller is d = min over ξ of |u(r(ξ))| on the
//! elements next to the nearest chord, counted negative beside the roller on the far side of its axis (against
//! the roller's normal, the side the pipe rests on) so that a pipe pushed through is pushed back. Because the
//! spline has no kinks, the distance changes smoothly as the pipe slides over a roller: the chord polygon,
//! whose nodes stand out of its chords by the sagitta ℓ²/8R on a stinger of radius R, bumped every roller
//! once per element, and a stiff contact rang with it. At the foot ξ*, ∂d/∂y_j = w_j(ξ*) n (n the unit foot
//! direction, u/|u|), whether the foot lies beside the roller or beyond its end.
// Indexing cannot go out of bounds here: node and element indices of the contact's own mesh.
#![allow(clippy::indexing_slicing)]
use crate::rod::Rod;
use crate::vessel::lay::{Roller, RollerFriction};
use nalgebra::{Matrix3, Vector3};

/// A roller in the end node's frame.
#[derive(Debug, Clone, Copy)]
pub(super) struct LocalRoller {
    pub(super) centre: Vector3<f64>,
    /// The side the pipe rests on (unit, normal to the axis).
    pub(super) normal: Vector3<f64>,
    /// The axis a (unit).
    pub(super) axis: Vector3<f64>,
    /// Half the roller's length h (m; infinite for a long cylinder).
    pub(super) half_length: f64,
    /// The roller's radius r_r (m).
    pub(super) radius: f64,
    pub(super) friction: RollerFriction,
    /// The articulated stinger's section the roller rides on (its frame the section's at φ = 0), if any.
    pub(super) section: Option<usize>,
}

impl LocalRoller {
    /// `roller` (body frame) in the frame whose rotation from the body frame is `rotation` and whose origin
    /// lies at `origin` in the body frame.
    pub(super) fn new(roller: &Roller, rotation: &Matrix3<f64>, origin: &Vector3<f64>) -> Self {
        LocalRoller {
            centre: rotation * (roller.centre - origin),
            normal: rotation * roller.normal,
            axis: rotation * roller.axis,
            half_length: 0.5 * roller.length,
            radius: roller.radius,
            friction: roller.friction,
            section: roller.section,
        }
    }

    /// The offset u(y) of the point y from the axis segment.
    pub(super) fn offset(&self, y: &Vector3<f64>) -> Vector3<f64> {
        self.offset_from_centre(&(y - self.centre))
    }

    /// The position along the axis a·v of the point at `v` = y − c from the centre, clamped to the roller (m).
    /// Points are taken relative to the centre, so that the foot's search sees them to the round-off of their
    /// distance from the roller, not of their distance from the vessel.
    fn along_from_centre(&self, v: &Vector3<f64>) -> f64 {
        self.axis.dot(v).clamp(-self.half_length, self.half_length)
    }

    /// [`Self::offset`] of the point at `v` = y − c from the centre.
    fn offset_from_centre(&self, v: &Vector3<f64>) -> Vector3<f64> {
        v - self.along_from_centre(v) * self.axis
    }

    /// Whether the point at `v` = y − c from the centre lies beyond an end of the roller (its offset points
    /// from the axis's end).
    fn beyond_from_centre(&self, v: &Vector3<f64>) -> bool {
        self.axis.dot(v).abs() > self.half_length
    }

    /// The signed distance of a point whose offset is `foot` (and that lies beyond the roller's end if
    /// `beyond`), the sign of its gradient, or None out of reach on the far side: see [`chord_distance`].
    fn signed(&self, foot: &Vector3<f64>, beyond: bool, reach: f64) -> Option<(f64, f64)> {
        let d = foot.norm();
        if beyond || foot.dot(&self.normal) >= 0.0 {
            Some((d, 1.0))
        } else if d < 2.0 * reach {
            Some((-d, -1.0))
        } else {
            None
        }
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
pub(super) fn nearest(
    roller: &LocalRoller,
    half_diameters: &[f64],
    first: usize,
    locals: &[Vector3<f64>],
) -> usize {
    // Squared distance of a node from the axis segment, |u(y)|².
    let axis_distance2 = |y: &Vector3<f64>| roller.offset(y).norm_squared();
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
        let d = chord_distance(roller, reach, &chord[0], &chord[1]);
        if d - half_diameter < best.0 {
            best = (d - half_diameter, e);
        }
    }
    best.1
}

/// Distance from the roller's axis segment to the chord (y0, y1): the least |u| over the chord's points.
/// Negative where the nearest point lies beside the roller on the far side of its axis (against the roller's
/// normal) and still within twice the contact distance `reach`: the contact then pushes it back. Far beyond,
/// the chord is out of the roller's reach r_r + d/2 (infinite distance).
pub(super) fn chord_distance(
    roller: &LocalRoller,
    reach: f64,
    y0: &Vector3<f64>,
    y1: &Vector3<f64>,
) -> f64 {
    // The nearest points of two segments, p(s) = y0 + s(y1 − y0) and q(t) = c + t a, |t| ≤ h: the chord's
    // parameter minimises |u(p(s))|, which is convex in s; from the infinite line's answer, a few projected
    // Newton steps on |u|² (a piecewise quadratic) settle it where the roller's end matters.
    let chord = y1 - y0;
    let across = chord - roller.axis.dot(&chord) * roller.axis;
    let across2 = across.norm_squared();
    let v0 = y0 - roller.centre;
    let mut s = if across2 > 0.0 {
        (-(v0 - roller.axis.dot(&v0) * roller.axis).dot(&across) / across2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    if roller.half_length.is_finite() {
        for _ in 0..8 {
            let v = v0 + s * chord;
            let metric = if roller.beyond_from_centre(&v) {
                chord.norm_squared()
            } else {
                across2
            };
            if metric == 0.0 {
                break;
            }
            let next = (s - roller.offset_from_centre(&v).dot(&chord) / metric).clamp(0.0, 1.0);
            if (next - s).abs() <= 1e-14 {
                s = next;
                break;
            }
            s = next;
        }
    }
    let v = v0 + s * chord;
    roller
        .signed(
            &roller.offset_from_centre(&v),
            roller.beyond_from_centre(&v),
            reach,
        )
        .map_or(f64::INFINITY, |(d, _)| d)
}

/// One element of the spline: the indices, in a roller's node list, of its control nodes i − 1, i, i + 1 and
/// i + 2 ([`Surfaces::control_nodes`]), and whether the first or the last is mirrored ([`Surfaces::spline_ends`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Segment {
    pub(super) element: usize,
    pub(super) control: [usize; 4],
    pub(super) mirrored: [bool; 2],
}

/// Catmull–Rom weights w_j(ξ) of the four control nodes and their first and second derivatives in ξ, with a
/// mirrored end (y_{i−1} = 2y_i − y_{i+1}, y_{i+2} = 2y_{i+1} − y_i) folded into the nodes that stand for it.
pub(super) fn spline_weights(xi: f64, mirrored: [bool; 2]) -> [[f64; 4]; 3] {
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

/// Where a roller is nearest a spline element: the signed distance d from its axis (see [`chord_distance`] for
/// the sign), the weights w_j(ξ*) at the foot ξ*, the signed unit foot direction ±n, the foot's position along
/// the roller from its centre, a·(r(ξ*) − c) clamped to the roller (m), and ξ*.
#[derive(Debug, Clone, Copy)]
pub(super) struct Foot {
    pub(super) distance: f64,
    pub(super) weights: [f64; 4],
    pub(super) direction: Vector3<f64>,
    pub(super) along: f64,
    pub(super) xi: f64,
}

/// The element's surface radius at ξ: `half_diameter` at its first node, changing by `taper` (m) to its
/// second (a laydown head's nose; zero for a cylinder).
fn radius_at(half_diameter: f64, taper: f64, xi: f64) -> f64 {
    half_diameter + taper * xi
}

/// The foot of the roller on the spline element through `points` whose surface radius changes by `taper` (m)
/// along it: ξ* ∈ [0, 1] minimises the gap |u(r(ξ))| − taper·ξ (for a cylinder, the distance), so that the
/// gap's gradient is ∂(d − ρ(ξ*))/∂y_j = w_j(ξ*) (±n) whether ξ* is inside the element or at an end. Newton's
/// method on the gap's derivative (u·r′/|u| − taper) from the chord's foot, Gauss–Newton's where the
/// curvature term would make it climb.
pub(super) fn spline_distance(
    roller: &LocalRoller,
    reach: f64,
    points: &[Vector3<f64>; 4],
    mirrored: [bool; 2],
    taper: f64,
) -> Foot {
    let relative = points.map(|y| y - roller.centre);
    let combine = |w: &[f64; 4]| -> Vector3<f64> {
        w.iter()
            .zip(&relative)
            .map(|(w, v)| *w * v)
            .sum::<Vector3<f64>>()
    };
    let across = |v: Vector3<f64>| v - roller.axis.dot(&v) * roller.axis;
    let chord = across(relative[2] - relative[1]);
    let length2 = chord.norm_squared();
    let mut xi = if length2 > 0.0 {
        (-across(relative[1]).dot(&chord) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    for _ in 0..30 {
        let [w, dw, ddw] = spline_weights(xi, mirrored);
        let point = combine(&w);
        let (foot, tangent, bend) = (
            roller.offset_from_centre(&point),
            combine(&dw),
            combine(&ddw),
        );
        // Beside the roller u = (I − a aᵀ)(r − c), so u′ = (I − a aᵀ) r′; beyond its end u′ = r′.
        let moving = if roller.beyond_from_centre(&point) {
            tangent
        } else {
            across(tangent)
        };
        let metric = moving.norm_squared();
        if metric == 0.0 {
            break;
        }
        // Newton's step, or Gauss–Newton's where the curvature term would make it climb; on ½|u|² for a
        // cylinder, on |u| − taper·ξ for a taper.
        let (slope, curvature) = if taper == 0.0 {
            (foot.dot(&tangent), metric + foot.dot(&bend))
        } else {
            let d = foot.norm().max(f64::MIN_POSITIVE);
            let rate = foot.dot(&moving) / d;
            (rate - taper, (metric + foot.dot(&bend) - rate * rate) / d)
        };
        let floor = if taper == 0.0 {
            0.5 * metric
        } else {
            0.5 * metric / foot.norm().max(f64::MIN_POSITIVE)
        };
        let next = (xi - slope / curvature.max(floor)).clamp(0.0, 1.0);
        let converged = (next - xi).abs() <= 1e-15;
        xi = next;
        if converged {
            break;
        }
    }
    let [weights, _, _] = spline_weights(xi, mirrored);
    let point = combine(&weights);
    let foot = roller.offset_from_centre(&point);
    let along = roller.along_from_centre(&point);
    let d = foot.norm();
    let normal = if d > 0.0 { foot / d } else { Vector3::zeros() };
    match roller.signed(&foot, roller.beyond_from_centre(&point), reach) {
        Some((distance, sign)) => Foot {
            distance,
            weights,
            direction: sign * normal,
            along,
            xi,
        },
        None => Foot {
            distance: f64::INFINITY,
            weights: [0.0; 4],
            direction: Vector3::zeros(),
            along,
            xi,
        },
    }
}

/// The line's surface along each element: half its hydrodynamic diameter at its first node (m), the change
/// of that radius to its second (m; a laydown head's taper, else zero), and whether it is a cable's bar (whose
/// centreline is its chord, kinked at the nodes).
#[derive(Debug, Clone)]
pub(super) struct Surfaces {
    pub(super) half_diameters: Vec<f64>,
    pub(super) tapers: Vec<f64>,
    pub(super) cables: Vec<bool>,
}

impl Surfaces {
    pub(super) fn new(rod: &Rod) -> Self {
        let sections = (0..rod.element_count()).map(|e| rod.section(e));
        Surfaces {
            half_diameters: sections
                .clone()
                .map(|s| 0.5 * s.hydrodynamic_diameter)
                .collect(),
            tapers: sections
                .clone()
                .map(|s| {
                    s.nose_diameter
                        .map_or(0.0, |d| 0.5 * (d - s.hydrodynamic_diameter))
                })
                .collect(),
            cables: sections.map(|s| s.cable).collect(),
        }
    }

    /// Element e's surface gap from a roller's axis at `foot`: the distance less the surface's radius there.
    pub(super) fn gap(&self, e: usize, foot: &Foot) -> f64 {
        foot.distance - radius_at(self.half_diameters[e], self.tapers[e], foot.xi)
    }

    /// Whether element e's spline ends at its first or last node (mirrored there): at an end of the rod and at
    /// a joint of two elements of different diameters or kinds (a pipe's end and the wire fitted to it, say),
    /// so that the one's direction does not bend the other's surface. A cable's bars run on through the
    /// spline like a rod's elements: as a wire pays out over rollers or a guide its nodes pass them, and on
    /// its chords each passage would kink the surface the roller sees (the spline lies about ℓθ/16 outside
    /// the chords where the wire bends by θ).
    pub(super) fn spline_ends(&self, e: usize) -> [bool; 2] {
        let (diameters, cables) = (&self.half_diameters, &self.cables);
        let joint = |other: usize| diameters[other] != diameters[e] || cables[other] != cables[e];
        [
            e == 0 || joint(e - 1),
            e + 1 == diameters.len() || joint(e + 1),
        ]
    }

    /// Element e's control nodes e − 1, e, e + 1, e + 2 and its [`Self::spline_ends`]; a mirrored node's slot
    /// holds its neighbour in the element (its weight is zero: any node stands for it).
    pub(super) fn control_nodes(&self, e: usize) -> ([usize; 4], [bool; 2]) {
        let ends = self.spline_ends(e);
        let first = if ends[0] { e } else { e - 1 };
        let last = if ends[1] { e + 1 } else { e + 2 };
        ([first, e, e + 1, last], ends)
    }
}

/// Of the spline's elements next to the nearest chord `chord` (itself and its neighbours within
/// `elements`), the one whose surface is nearest `roller`, and its gap d − D/2 − r_r (m), the nodes'
/// coordinates in the roller's frame given by `local`.
pub(super) fn nearest_spline_element(
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
        let foot = spline_distance(
            roller,
            roller.radius + half_diameter,
            &points,
            mirrored,
            surfaces.tapers[e],
        );
        let gap = surfaces.gap(e, &foot);
        if gap < best.0 {
            best = (gap, e);
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
    let local = LocalRoller::new(roller, &Matrix3::identity(), &Vector3::zeros());
    let surfaces = Surfaces::new(rod);
    let elements = 0..surfaces.half_diameters.len();
    let in_body = |node: usize| body.transpose() * (positions[node] - origin);
    nearest_spline_element(&local, &surfaces, elements, chord, &in_body).0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::rollers::tests::pipe_over_stinger;

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
                let d = chord_distance(roller, reach, &locals[e], &locals[e + 1]);
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
}
