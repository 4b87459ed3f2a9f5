//! What a lay engineer reads off a configuration held by lay equipment: top tension, departure, lift-off,
//! layback, touchdown, and the largest strain and moment in the overbend and the sagbend.
//!
//! The pipe leaves the equipment at the **lift-off point**: the last roller in contact counted along the pipe
//! from the hold point (tensioner, tower exit), or the hold point itself without rollers in contact. Going
//! down from the hold point the pipe steepens over the **overbend** and flattens again over the **sagbend**
//! to the touchdown (end A without a seabed contact); they meet at the inflection point, where the pipe is
//! steepest.
// Indexing cannot go out of bounds here: Node and element indices of the state summarised (the vessel's node is a node of its mesh).
#![allow(clippy::indexing_slicing)]
use crate::contact::roller_geometry::roller_gap;
use crate::contact::touchdown::Touchdown;
use crate::model::Model;
use crate::vessel::lay::Roller;
use nalgebra::{UnitQuaternion, Vector3, Vector6};

/// What the roller contact reports of a configuration, per roller: its normal force (N), the element
/// nearest it, and where its contact lies along it from its centre (m; NaN out of contact).
#[derive(Debug, Clone, Copy)]
pub struct RollerContacts<'a> {
    pub forces: &'a [f64],
    pub elements: &'a [usize],
    pub offsets: &'a [f64],
}

/// The lay summary of one configuration (SI units; angles in rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaySummary {
    /// Effective tension of the element at the hold point (N).
    pub top_tension: f64,
    /// Angle of the pipe below the horizontal where it leaves the equipment (rad).
    pub departure_angle: f64,
    /// The 0-based index of the lift-off roller (the last in contact) among the stinger's supports (lone
    /// rollers or roller boxes), `None` if the pipe touches no roller.
    pub liftoff_roller: Option<usize>,
    /// Arc length of the lift-off point from end A along the reference (m).
    pub liftoff_arc_length: f64,
    /// Arc length of the inflection point (the steepest, between overbend and sagbend) from end A (m).
    pub inflection_arc_length: f64,
    /// Horizontal distance from the hold point to the touchdown point (m); NaN without touchdown.
    pub layback: f64,
    /// Touchdown's arc length from end A (m); NaN without touchdown.
    pub touchdown_arc_length: f64,
    /// Largest strain in the overbend and in the sagbend (−).
    pub overbend_strain: f64,
    pub sagbend_strain: f64,
    /// Largest bending moment in the sagbend (N·m).
    pub sagbend_moment: f64,
    /// The gap between the line's surface and the stinger's last roller (m): the distance from the roller's
    /// axis to the nearest element's chord less the roller's radius and the element's half diameter (≤ 0: in
    /// contact); NaN without rollers.
    pub tip_clearance: f64,
    /// The pipe's centreline's lateral offset (m, to starboard) from the last support's station, where it
    /// crosses the support's plane (normal to the stinger); NaN without rollers or where it does not cross.
    pub tip_offset: f64,
    /// The laid pipe's largest residual curvature (1/m): beyond the touchdown (beyond the inflection without a
    /// seabed), from the pipe's history through the lay
    /// ([`crate::response::configuration::plastic_field`]); NaN where no wall yields.
    pub residual_curvature: f64,
    /// How many roller boxes the pipe is leaving: those with a contact at a roller's end (0: the pipe stays in
    /// its boxes; always 0 on lone rollers, which are endless).
    pub boxes_left: usize,
}

/// The ends of each roller's top line in a configuration (in e, m): the line the pipe rests on along a roller of
/// a box, its length long; a lone roller's top point twice (it is endless). Empty without rollers.
pub fn roller_lines(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    hinge_angles: &[f64],
) -> Vec<[Vector3<f64>; 2]> {
    let tops = roller_tops(model, positions, rotations, hinge_angles);
    let Some(attachment) = model.vessel.as_ref() else {
        return Vec::new();
    };
    let body = crate::vessel::coupling::body_rotation(attachment, &rotations[attachment.node]);
    attachment
        .placed_rollers(hinge_angles)
        .iter()
        .zip(tops)
        .map(|(roller, top)| {
            let half = if roller.length.is_finite() {
                0.5 * roller.length * (body * roller.axis)
            } else {
                Vector3::zeros()
            };
            [top - half, top + half]
        })
        .collect()
}

/// Each element's largest longitudinal strain in a configuration: the axial strain plus bending at the outer
/// fibre, ε₀ + (D/2)|κ|, taken from the configuration's strains where the wall yields (computed, not
/// estimated), from the section forces elastically elsewhere ([`crate::rod::section::Section::strain`]: the
/// same where the wall stays elastic).
pub fn element_strains(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    section_forces: &[Vector6<f64>],
) -> Vec<f64> {
    section_forces
        .iter()
        .enumerate()
        .map(|(e, forces)| {
            let section = model.rod.section(e);
            if !section.yields() {
                return section.strain(forces);
            }
            let (strain, curvature) = model.rod.strain_changes(e, positions, rotations);
            strain.x + 0.5 * section.outer_diameter * curvature.yz().norm()
        })
        .collect()
}

/// Each element's residual curvature |κ − m/EI| (1/m) from the configuration's curvature and the section
/// forces' moments (0 where the wall does not yield): a run's, whose own plastic state made the forces.
pub fn residual_curvatures(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    section_forces: &[Vector6<f64>],
) -> Vec<f64> {
    section_forces
        .iter()
        .enumerate()
        .map(|(e, forces)| {
            let section = model.rod.section(e);
            if !section.yields() {
                return 0.0;
            }
            let (_, curvature) = model.rod.strain_changes(e, positions, rotations);
            section.residual_curvature(&curvature, &forces.fixed_rows::<3>(3).into_owned())
        })
        .collect()
}

/// Where an articulated stinger's sections are in a configuration (in e, m): each section's hinge and far
/// end on the stinger's top line. Empty without.
pub fn section_lines(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    hinge_angles: &[f64],
) -> Vec<[Vector3<f64>; 2]> {
    let Some((attachment, articulation)) = model.vessel.as_ref().and_then(|attachment| {
        let articulation = attachment.lay.as_ref()?.articulation.as_ref()?;
        Some((attachment, articulation))
    }) else {
        return Vec::new();
    };
    let node = attachment.node;
    let body = crate::vessel::coupling::body_rotation(attachment, &rotations[node]);
    let origin = positions[node] - body * attachment.hang_off();
    (0..articulation.sections.len())
        .map(|j| {
            let (rotation, translation) = articulation.chain.placement(hinge_angles, j);
            [articulation.chain.hinges[j], articulation.ends[j]]
                .map(|p| origin + body * (rotation * p + translation))
        })
        .collect()
}

/// Where the rollers' top points are in a configuration (in e, m); empty without rollers.
pub fn roller_tops(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    hinge_angles: &[f64],
) -> Vec<Vector3<f64>> {
    let Some(attachment) = model.vessel.as_ref() else {
        return Vec::new();
    };
    let node = attachment.node;
    let body = crate::vessel::coupling::body_rotation(attachment, &rotations[node]);
    attachment
        .placed_rollers(hinge_angles)
        .iter()
        .map(|r| positions[node] + body * (r.centre + r.radius * r.normal - attachment.hang_off()))
        .collect()
}

/// Names of [`LaySummary::values`], in order (`liftoff_roller` as a number, NaN: none).
pub const LAY_FIELDS: [&str; 14] = [
    "top_tension",
    "departure_angle",
    "liftoff_roller",
    "liftoff_arc_length",
    "inflection_arc_length",
    "layback",
    "touchdown_arc_length",
    "overbend_strain",
    "sagbend_strain",
    "sagbend_moment",
    "tip_clearance",
    "tip_offset",
    "boxes_left",
    "residual_curvature",
];

impl LaySummary {
    /// The fields as numbers, in the order of [`LAY_FIELDS`].
    pub fn values(&self) -> [f64; 14] {
        [
            self.top_tension,
            self.departure_angle,
            self.liftoff_roller.map_or(f64::NAN, |k| k as f64),
            self.liftoff_arc_length,
            self.inflection_arc_length,
            self.layback,
            self.touchdown_arc_length,
            self.overbend_strain,
            self.sagbend_strain,
            self.sagbend_moment,
            self.tip_clearance,
            self.tip_offset,
            self.boxes_left as f64,
            self.residual_curvature,
        ]
    }
}

/// The summary of a configuration of `model` (which must hold its end with a vessel; `None` otherwise):
/// `rollers` as the roller contact reports them, `touchdown` from the seabed contact, `residual_curvatures`
/// each element's where a wall yields (statics: [`crate::response::configuration::Response::plastic`]'s, from
/// the pipe's history marched through the lay; a run: [`residual_curvatures`] of its section forces).
#[allow(clippy::too_many_arguments)]
pub fn lay_summary(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    hinge_angles: &[f64],
    section_forces: &[Vector6<f64>],
    rollers: Option<RollerContacts>,
    touchdown: Option<&Touchdown>,
    residual_curvatures: Option<&[f64]>,
) -> Option<LaySummary> {
    let attachment = model.vessel.as_ref()?;
    let node = attachment.node;
    let elements = model.rod.element_count();
    let top_element = if node == 0 { 0 } else { elements - 1 };
    let arc_of_node = model.rod.arc_lengths();
    // The lift-off element: of the rollers in contact, the one farthest from the hold point along the pipe.
    let liftoff = rollers.and_then(|contacts| {
        contacts
            .forces
            .iter()
            .zip(contacts.elements)
            .enumerate()
            .filter(|(_, (f, _))| **f > 0.0)
            .map(|(k, (_, e))| (k, *e))
            .min_by_key(|(_, e)| if node == 0 { usize::MAX - e } else { *e })
    });
    // A J-lay guide's roller is no stinger's: the line leaves there, but at no numbered roller.
    let support = |k: usize| match attachment.rollers().get(k) {
        Some(roller) if roller.guide => None,
        Some(roller) => Some(roller.support),
        None => Some(k),
    };
    let (liftoff_roller, liftoff_node) = match liftoff {
        Some((k, e)) => (support(k), if node == 0 { e + 1 } else { e }),
        None => (None, node),
    };
    // The pipe's angle below the horizontal at each node, going down from the hold point; a cable's node (the
    // winch's too, whose rotation is the vessel's) takes its tangent toward B from the chord of its element
    // toward A (from the first element at node 0).
    let slope = |i: usize| {
        let tangent = if model.rod.is_cable_node(i) {
            let (a, b) = if i == 0 { (0, 1) } else { (i - 1, i) };
            (positions[b] - positions[a]).normalize()
        } else {
            rotations[i] * Vector3::x()
        };
        let down = if node == 0 { tangent } else { -tangent };
        down.z.atan2(down.xy().norm())
    };
    let departure_angle = slope(liftoff_node);
    let (touchdown_arc, touchdown_point) = touchdown
        .and_then(|t| t.point)
        .map_or((f64::NAN, None), |(arc, p)| (arc, Some(p)));
    // The inflection: the steepest node between the touchdown and the hold point.
    let suspended = |i: usize| {
        !touchdown_arc.is_finite()
            || if node == 0 {
                arc_of_node[i] <= touchdown_arc
            } else {
                arc_of_node[i] >= touchdown_arc
            }
    };
    let inflection = (0..positions.len())
        .filter(|&i| suspended(i))
        .max_by(|&a, &b| slope(a).total_cmp(&slope(b)))
        .unwrap_or(node);
    let inflection_arc = arc_of_node[inflection];
    let layback = touchdown_point.map_or(f64::NAN, |p| (positions[node] - p).xy().norm());
    let liftoff_arc = arc_of_node[liftoff_node];
    let split = inflection_arc;
    let (mut overbend_strain, mut sagbend_strain, mut sagbend_moment) =
        (f64::NEG_INFINITY, f64::NEG_INFINITY, 0.0_f64);
    let strains = element_strains(model, positions, rotations, section_forces);
    for (e, (forces, &strain)) in section_forces.iter().zip(&strains).enumerate() {
        let middle = 0.5 * (arc_of_node[e] + arc_of_node[e + 1]);
        let toward_hold = if node == 0 {
            middle <= split
        } else {
            middle >= split
        };
        if toward_hold {
            overbend_strain = overbend_strain.max(strain);
        } else {
            let beyond_touchdown = touchdown_arc.is_finite()
                && if node == 0 {
                    middle > touchdown_arc
                } else {
                    middle < touchdown_arc
                };
            if !beyond_touchdown {
                sagbend_strain = sagbend_strain.max(strain);
                sagbend_moment = sagbend_moment.max(forces.fixed_rows::<2>(4).norm());
            }
        }
    }
    let placed = attachment.placed_rollers(hinge_angles);
    let tip_clearance = tip_clearance(model, positions, rotations, &placed, rollers);
    let tip_offset = tip_offset(model, positions, rotations, &placed);
    let boxes_left = rollers.map_or(0, |contacts| boxes_left(attachment.rollers(), contacts));
    let nan_if_empty = |v: f64| if v.is_finite() { v } else { f64::NAN };
    // The laid pipe: beyond the touchdown, or beyond the inflection without one.
    let laid_from = if touchdown_arc.is_finite() {
        touchdown_arc
    } else {
        inflection_arc
    };
    let residual_curvature = residual_curvatures.map_or(f64::NAN, |residuals| {
        residuals
            .iter()
            .enumerate()
            .filter(|&(e, _)| {
                let middle = 0.5 * (arc_of_node[e] + arc_of_node[e + 1]);
                if node == 0 {
                    middle > laid_from
                } else {
                    middle < laid_from
                }
            })
            .map(|(_, &c)| c)
            .fold(f64::NEG_INFINITY, f64::max)
    });
    Some(LaySummary {
        top_tension: section_forces[top_element][0],
        departure_angle,
        liftoff_roller,
        liftoff_arc_length: liftoff_arc,
        inflection_arc_length: inflection_arc,
        layback,
        touchdown_arc_length: touchdown_arc,
        overbend_strain: nan_if_empty(overbend_strain),
        sagbend_strain: nan_if_empty(sagbend_strain),
        sagbend_moment,
        tip_clearance,
        tip_offset,
        boxes_left,
        residual_curvature: nan_if_empty(residual_curvature),
    })
}

/// The number of supports with a contact at a roller's end (within 1 mm of it, or beyond): a pipe climbing
/// out of its box ([`crate::vessel::roller_box`]).
fn boxes_left(rollers: &[crate::vessel::lay::Roller], contacts: RollerContacts) -> usize {
    let mut left: Vec<usize> = rollers
        .iter()
        .zip(contacts.offsets)
        .filter(|(roller, offset)| offset.abs() >= 0.5 * roller.length - 1e-3)
        .map(|(roller, _)| roller.support)
        .collect();
    left.dedup();
    left.len()
}

/// The lateral offset (m) of the line's centreline from the last support's station, in the vessel's body
/// frame, where the centreline crosses the support's plane (through the station, normal to the stinger's
/// tangent there, the plane of the outward normal and b2); NaN without rollers or where it does not cross it.
fn tip_offset(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    placed: &[Roller],
) -> f64 {
    let Some(attachment) = model.vessel.as_ref() else {
        return f64::NAN;
    };
    let Some(&(station, up)) = crate::vessel::lay::supports(placed).last() else {
        return f64::NAN;
    };
    let node = attachment.node;
    let body = crate::vessel::coupling::body_rotation(attachment, &rotations[node]);
    let origin = positions[node] - body * attachment.hang_off();
    // The plane of the outward normal and b2 (an articulated stinger turns only about b2).
    let tangent = Vector3::y().cross(&up);
    let local = |x: &Vector3<f64>| body.transpose() * (x - origin) - station;
    // The crossing nearest the station, between consecutive nodes on either side of the plane.
    let mut best = (f64::INFINITY, f64::NAN);
    for pair in positions.windows(2) {
        let (a, b) = (local(&pair[0]), local(&pair[1]));
        let (da, db) = (a.dot(&tangent), b.dot(&tangent));
        if da * db > 0.0 || da == db {
            continue;
        }
        let point = a + (da / (da - db)) * (b - a);
        if point.norm() < best.0 {
            best = (point.norm(), point.y);
        }
    }
    best.1
}

/// The gap between the line and the last support (m; `placed`: the rollers where they are): the least over its rollers (a lone roller, or a box's),
/// as the roller contact measures it, from the element nearest each that the contact reports (`rollers`:
/// forces and nearest elements); NaN without rollers.
fn tip_clearance(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    placed: &[Roller],
    rollers: Option<RollerContacts>,
) -> f64 {
    let (Some(attachment), Some(RollerContacts { elements, .. })) =
        (model.vessel.as_ref(), rollers)
    else {
        return f64::NAN;
    };
    // The stinger's last support (a J-lay guide has no tip).
    let Some(last) = placed.iter().rev().find(|r| !r.guide).map(|r| r.support) else {
        return f64::NAN;
    };
    let node = attachment.node;
    let body = crate::vessel::coupling::body_rotation(attachment, &rotations[node]);
    // The body frame's origin as the rollers place it: the hold point at the end node.
    let origin = positions[node] - body * attachment.hang_off();
    placed
        .iter()
        .zip(elements)
        .filter(|(roller, _)| !roller.guide && roller.support == last)
        .map(|(roller, &element)| {
            roller_gap(&model.rod, positions, roller, &body, &origin, element)
        })
        .fold(f64::NAN, f64::min)
}
