//! Whether a converged static state is physical: the vessel afloat, and the pipe on its rollers.
//!
//! A vessel upside down or on its side (its body axis b3 more than 60° from the vertical) is an equilibrium of
//! the restoring's director form that no vessel floats in.
//!
//! A rod over one-sided roller contacts has several equilibria, and Newton may converge to one no lay spread
//! holds: the pipe passed through a roller to its far side, or hanging under the stinger between its first and
//! last roller (the stinger's structure is there). Each roller's contact sees only the pipe near it, so neither
//! shows in the residual. With the rollers' tops t_k (the hold point t_0 first), the line the pipe rests on is the
//! polyline t_0 t_1 … t_m in the vessel's body frame; a node whose body x lies between those of t_k and t_{k+1}
//! stands h above it, measured along the body's vertical. Resting on the rollers, the pipe's centreline stands
//! half a diameter above, and between two supports a span s sags by w s²/(8T) under its weight; a node more than
//! a diameter and a twentieth of the span below its resting height (h < −D/2 − s/20, a sag that would need a
//! tension as low as 2.5 w s) is under the stinger.
// Indexing cannot go out of bounds here: node and roller indices of the state's own model.
#![allow(clippy::indexing_slicing)]
use crate::contact::roller_geometry::roller_gap;
use crate::model::Model;
use nalgebra::{UnitQuaternion, Vector3};
use std::fmt;

/// The sag below the rollers' line allowed per length of the span between two supports: a twentieth.
const SAG_PER_SPAN: f64 = 0.05;

/// What makes a converged static state unphysical.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Unphysical {
    /// The vessel's equilibrium found is capsized (roll and pitch, rad).
    Capsized { roll: f64, pitch: f64 },
    /// The pipe's centreline passed roller `roller`'s axis to its far side, or, on a box's roller, overlaps it
    /// by more than the pipe's radius: the pipe went through it.
    ThroughRoller {
        /// The roller, counted from 1 along the pipe from the hold point.
        roller: usize,
        /// How far the pipe's surface overlaps the roller's (m).
        overlap: f64,
    },
    /// Roller `roller` (counted from 1 along the stinger) of support `support` (a box, counted from 1) pushes
    /// the pipe down, away from the stinger: the pipe lies under it, outside its box.
    UnderRoller {
        roller: usize,
        support: usize,
        /// The roller's force on the pipe (N).
        force: f64,
    },
    /// Node `node` hangs under the stinger, between roller `after` (0: the hold point) and the next.
    UnderStinger {
        node: usize,
        /// The roller before the node along the stinger, counted from 1 (0: the hold point).
        after: usize,
        /// How far the pipe's centreline lies below the rollers' line (m).
        depth: f64,
    },
}

impl fmt::Display for Unphysical {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Unphysical::Capsized { roll, pitch } => write!(
                f,
                "the vessel's equilibrium found is capsized (roll {roll:.3} rad, pitch {pitch:.3} rad)"
            ),
            Unphysical::ThroughRoller { roller, overlap } => write!(
                f,
                "the pipe passes through roller {roller} (its surface overlaps the roller's by {overlap:.3} m, \
                 its centreline beyond the roller's axis)"
            ),
            Unphysical::UnderRoller {
                roller,
                support,
                force,
            } => write!(
                f,
                "the pipe lies under roller {roller} of box {support}, outside the box: the roller pushes it \
                 down with {:.1} kN",
                force / 1e3
            ),
            Unphysical::UnderStinger { node, after, depth } => {
                let place = if *after == 0 {
                    "between the hold point and roller 1".to_string()
                } else {
                    format!("between rollers {after} and {}", after + 1)
                };
                write!(
                    f,
                    "the pipe hangs under the stinger: node {node} lies {depth:.2} m below the rollers' line \
                     {place}"
                )
            }
        }
    }
}

impl Unphysical {
    /// What a user may change to reach a physical state.
    pub fn advice(&self) -> &'static str {
        match self {
            Unphysical::Capsized { .. } => {
                "check the vessel's position and the line's length for a line that can hang from it, or start \
                 from the catenary (start=\"auto\")"
            }
            Unphysical::ThroughRoller { .. }
            | Unphysical::UnderStinger { .. }
            | Unphysical::UnderRoller { .. } => {
                "the tension is too low for the stinger, or the line is slack between the vessel and the seabed: \
                 move the vessel forward along the lay (η's x) to raise the tension, or lay with a stinger that \
                 leaves the pipe steeper"
            }
        }
    }
}

/// The first reason the state `positions`, `rotations` of `model` is not physical, given the element nearest
/// each roller (`nearest_elements`, as the roller contact reports them); `None` if it is physical.
pub fn check(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[UnitQuaternion<f64>],
    hinge_angles: &[f64],
    nearest_elements: &[usize],
) -> Option<Unphysical> {
    let attachment = model.vessel.as_ref()?;
    let node = attachment.node;
    let body = crate::vessel::coupling::body_rotation(attachment, &rotations[node]);
    if body.column(2).z < 0.5 {
        let angles = crate::vessel::euler::angles_from_rotation(&body);
        return Some(Unphysical::Capsized {
            roll: angles.x,
            pitch: angles.y,
        });
    }
    let rollers = attachment.placed_rollers(hinge_angles);
    if rollers.is_empty() {
        return None;
    }
    // The body frame's origin as the rollers place it: the hold point at the end node.
    let hang_off = attachment.hang_off();
    let origin = positions[node] - body * hang_off;
    for (k, (roller, &element)) in rollers.iter().zip(nearest_elements).enumerate() {
        let gap = roller_gap(&model.rod, positions, roller, &body, &origin, element);
        let diameter = model.rod.section(element).hydrodynamic_diameter;
        // A box's roller (finite) pinching the pipe by more than its radius has it wedged through the box.
        let through = if roller.length.is_finite() {
            0.5 * diameter
        } else {
            roller.radius + 0.5 * diameter
        };
        if gap < -through {
            return Some(Unphysical::ThroughRoller {
                roller: k + 1,
                overlap: -gap,
            });
        }
    }
    // The rollers' line: the hold point, then each support's station.
    let line: Vec<Vector3<f64>> = std::iter::once(hang_off)
        .chain(
            crate::vessel::lay::supports(&rollers)
                .into_iter()
                .map(|s| s.0),
        )
        .collect();
    let mut deepest: Option<Unphysical> = None;
    for (i, x) in positions.iter().enumerate() {
        let local = body.transpose() * (x - origin);
        let diameter = model
            .rod
            .section(i.min(model.rod.element_count() - 1))
            .hydrodynamic_diameter;
        for (k, pair) in line.windows(2).enumerate() {
            let Some(depth) = depth_below(&local, &pair[0], &pair[1]) else {
                continue;
            };
            let deeper = match deepest {
                Some(Unphysical::UnderStinger { depth: worst, .. }) => depth > worst,
                _ => true,
            };
            let span = (pair[1] - pair[0]).norm();
            if depth > 0.5 * diameter + SAG_PER_SPAN * span && deeper {
                deepest = Some(Unphysical::UnderStinger {
                    node: i,
                    after: k,
                    depth,
                });
            }
        }
    }
    deepest
}

/// The first roller that pushes the pipe down in a converged state of `model`, given each roller's force on the
/// pipe (`reactions`, body frame): one whose force points against its support's outward normal by more than
/// 60° ([`crate::vessel::lay::supports`]). A lone roller cannot (its contact pushes along its normal); a box's
/// roller does where the pipe has left the box under it.
pub fn pushed_down(
    model: &Model,
    hinge_angles: &[f64],
    reactions: &[Vector3<f64>],
) -> Option<Unphysical> {
    let rollers = model.vessel.as_ref()?.placed_rollers(hinge_angles);
    let supports = crate::vessel::lay::supports(&rollers);
    rollers
        .iter()
        .zip(reactions)
        .enumerate()
        .find(|(_, (roller, force))| {
            let up = supports.get(roller.support).map_or(roller.normal, |s| s.1);
            force.dot(&up) < -0.5 * force.norm()
        })
        .map(|(k, (roller, force))| Unphysical::UnderRoller {
            roller: k + 1,
            support: roller.support + 1,
            force: force.norm(),
        })
}

/// How far `y` lies below the segment of the rollers' line from `start` to `end` (body frame, m), if it lies
/// fore and aft between them: the body's z (down) of `y` less the segment's at y's x.
fn depth_below(y: &Vector3<f64>, start: &Vector3<f64>, end: &Vector3<f64>) -> Option<f64> {
    let span = end.x - start.x;
    if span == 0.0 {
        return None;
    }
    let t = (y.x - start.x) / span;
    (0.0..=1.0)
        .contains(&t)
        .then(|| y.z - (start.z + t * (end.z - start.z)))
}
