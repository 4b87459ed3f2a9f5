//! The roller contact's tests: the pruned search, a pipe sliding over a roller, a wire's joint, and the
//! energy–momentum residual's tangent.
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

/// Evaluates `contact` in statics at `positions` and `rotations` (its forces, reactions and offsets).
pub(in crate::contact) fn evaluate_static(
    contact: &mut RollerContact,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
) {
    let mut residual = vec![0.0; 6 * positions.len()];
    contact.evaluate(
        ContactRule::Static,
        positions,
        rotations,
        &[],
        None,
        &mut residual,
        None,
        None,
    );
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
    let section =
        crate::rod::section::Section::pipe(0.6, 0.02, 7850.0, 207e9, 0.3, 0.0, [0.0; 2], [0.0; 2])
            .unwrap();
    let rod = Rod::straight(start, end, elements, section).unwrap();
    RollerContact::new(&attachment, &rod, &rod.arc_lengths()).unwrap()
}

/// A pipe of 12 nodes, 5 m apart, laid over a stinger of 6 rollers fixed to the frame of its last node.
pub(in crate::contact) fn pipe_over_stinger(
) -> (RollerContact, Vec<Vector3<f64>>, Vec<UnitQuaternion<f64>>) {
    let rollers = stinger_rollers(40.0, 30.0, 6, Vector3::new(-5.0, 0.0, 0.0), 0.0, 0.25).unwrap();
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
        section: None,
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
        evaluate_static(&mut contact, &positions, &rotations);
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
        spline_distance(&local, 1.0, &[y[5], y[6], y[7], y[8]], ends, 0.0).distance
    };
    let ends = contact.surfaces.spline_ends(6);
    assert_eq!(distance(&positions, ends), distance(&swung, ends));
    let running_on = [false, false];
    let change = (distance(&positions, running_on) - distance(&swung, running_on)).abs();
    assert!(change > 0.01, "{change}");
    // A cable's bars run on through the spline; it ends where a cable meets a rod of the same diameter.
    for e in 7..11 {
        contact.surfaces.cables[e] = true;
    }
    assert_eq!(contact.surfaces.spline_ends(8), [false, false]);
    contact.surfaces.half_diameters[6] = 0.04;
    assert_eq!(contact.surfaces.spline_ends(6), [true, true]);
    assert_eq!(contact.surfaces.spline_ends(7), [true, false]);
    // A mirrored end at both nodes makes the spline its chord.
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
                roller.friction = crate::vessel::lay::RollerFriction::new(0.3, 0.0, true).unwrap();
                contact.slips[k] = Vector2::new(1e-5 * k as f64, -2e-6);
            }
        }
        step_tangent_matches(&mut contact, &positions, &rotations, 0.0);
    }
}

fn step_tangent_matches(
    contact: &mut RollerContact,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    damping: f64,
) {
    let rule = ContactRule::EnergyMomentum {
        time_step: 0.1,
        damping,
    };
    let dofs = 6 * positions.len();
    let increments: Vec<f64> = (0..dofs)
        .map(|i| 1e-3 * ((i as f64) * 0.37).sin())
        .collect();
    let residual = |contact: &mut RollerContact, inc: &[f64]| {
        let mut r = vec![0.0; dofs];
        contact.evaluate(
            rule,
            positions,
            rotations,
            &[],
            Some(inc),
            &mut r,
            None,
            None,
        );
        r
    };
    let mut dense = Dense(HashMap::new());
    let mut r = vec![0.0; dofs];
    contact.evaluate(
        rule,
        positions,
        rotations,
        &[],
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

/// A laydown head's taper: under a roller whose axis runs across a straight element (from 0.3 m to 0.04 m of
/// radius along it, the roller's axis 1 m below it at x_c), the foot is where the gap √((x − x_c)² + h²) − r(x)
/// is least, x* = x_c + s h/√(1 − s²) (s < 0 the radius's slope: toward the thicker end), not under the axis;
/// the gap is the closed form's, and its gradient in the nodes' positions is w_j(ξ*) n (central differences),
/// as for a cylinder.
#[test]
fn a_tapered_element_touches_a_roller_where_its_gap_is_least() {
    let (contact, _, _) = pipe_over_stinger();
    let mut roller = contact.rollers[0];
    roller.axis = Vector3::y();
    roller.normal = Vector3::z();
    roller.half_length = f64::INFINITY;
    let (length, x_c, h) = (4.0, 1.5, 1.0);
    roller.centre = Vector3::new(x_c, 0.0, -h);
    let (r0, r1) = (0.3, 0.04);
    let taper = r1 - r0;
    let nodes = [0.0, length / 3.0, 2.0 * length / 3.0, length].map(|x| Vector3::new(x, 0.0, 0.0));
    let points = [nodes[0], nodes[0], nodes[1], nodes[1]];
    let ends = [true, true];
    // The element from node 0 to node 1 of a line straight along x, one third of it: 4/3 m.
    let span = length / 3.0;
    let foot = spline_distance(&roller, 2.0, &points, ends, taper);
    let slope = taper / span;
    let expected_x = x_c + slope * h / (1.0 - slope * slope).sqrt();
    assert!(
        (foot.xi * span - expected_x).abs() < 1e-9,
        "{} vs {expected_x}",
        foot.xi * span
    );
    let gap = foot.distance - (r0 + taper * foot.xi);
    let closed = ((expected_x - x_c).powi(2) + h * h).sqrt() - (r0 + slope * expected_x);
    assert!((gap - closed).abs() < 1e-12, "{gap} vs {closed}");
    // The gap's gradient: w_j n by the envelope theorem; central differences of the gap in node 1's z.
    let gap_at = |points: &[Vector3<f64>; 4]| {
        let foot = spline_distance(&roller, 2.0, points, ends, taper);
        foot.distance - (r0 + taper * foot.xi)
    };
    let d = 1e-6;
    for (slot, node) in [(1usize, 0usize), (2, 1)] {
        for axis in 0..3 {
            let mut plus = points;
            let mut minus = points;
            // A mirrored end's slot holds its neighbour: move both slots of the node.
            for s in [slot, if slot == 1 { 0 } else { 3 }] {
                plus[s][axis] += d;
                minus[s][axis] -= d;
            }
            let difference = (gap_at(&plus) - gap_at(&minus)) / (2.0 * d);
            let analytic = foot.weights[slot] * foot.direction[axis];
            assert!(
                (difference - analytic).abs() < 1e-6,
                "node {node} axis {axis}: {difference} vs {analytic}"
            );
        }
    }
}

/// The rollers' high-frequency damping ξ k Δδ: over a step the contact forces do the work of the contact
/// energy's change plus what they dissipate (to round-off), that dissipation is positive with damping and zero
/// without, and the damped step's tangent still matches differences of its residual.
#[test]
fn damped_rollers_dissipate_their_work() {
    let (mut contact, positions, rotations) = pipe_over_stinger();
    let dofs = 6 * positions.len();
    let increments: Vec<f64> = (0..dofs)
        .map(|i| 2e-3 * ((i as f64) * 0.37).sin())
        .collect();
    let zero = vec![0.0; dofs];
    for damping in [0.0, 0.25] {
        let rule = ContactRule::EnergyMomentum {
            time_step: 0.1,
            damping,
        };
        let mut residual = vec![0.0; dofs];
        let evaluate = |contact: &mut RollerContact, inc: &[f64], residual: &mut [f64]| {
            residual.fill(0.0);
            contact.evaluate(
                rule,
                &positions,
                &rotations,
                &[],
                Some(inc),
                residual,
                None,
                None,
            );
        };
        evaluate(&mut contact, &zero, &mut residual);
        let start = contact.energy_end;
        evaluate(&mut contact, &increments, &mut residual);
        let work: f64 = residual.iter().zip(&increments).map(|(r, d)| r * d).sum();
        let change = contact.energy_end - start;
        let dissipated = contact.dissipated;
        assert!(
            (work - change - dissipated).abs() < 1e-9 * (change.abs() + dissipated + 1.0),
            "ξ = {damping}: work {work} vs {change} + {dissipated}"
        );
        assert_eq!(dissipated > 0.0, damping > 0.0, "{dissipated}");
    }
    step_tangent_matches(&mut pipe_over_stinger().0, &positions, &rotations, 0.25);
}
