//! The hand-back of the line from the A&R winch to the tensioner at the end of a recovery, the reverse of the
//! hand-over ([`crate::dynamics::hand_over`]). The winch hauls its wire in until the pipe's end is back at the
//! hold point (the wire's last element as long as at the hand-over, under its tension; with a head body, its
//! nose there), slowing down over the
//! last metres within its acceleration limit ([`approach_speed`]). The tensioner then closes on the pipe where
//! its end is, with the end's rotation (the clamp takes the end's pose relative to the vessel, so neither the
//! pipe's shape nor its forces jump); the wire's element and the winch's node leave the mesh; the pipe's end
//! takes the vessel's rigid motion (its own motion relative to the vessel, the winch's last creep, stops); the
//! laydown head is taken off. The energy this changes is booked with pay-out's by the integrator.
// Indexing cannot go out of bounds here: the vessel's node is end B, the last node of the mesh, and the pipe's
// end the one before it.
#![allow(clippy::indexing_slicing)]
use crate::dynamics::state::DynamicState;
use crate::error::Result;
use crate::model::Model;
use crate::vessel::coupling::vessel_pose;
use crate::vessel::winch::HandBack;
use nalgebra::Vector6;

/// How far the pipe's end may be from the hold point along the wire for the tensioner to close on it (m).
pub const CLOSING_GAP: f64 = 1e-3;

/// With the winch holding and its wire one element long: how much longer that element is than at the hold
/// point under its present tension (m); `None` otherwise, or without lay equipment to hand back to.
pub fn remaining(model: &Model, state: &DynamicState) -> Option<f64> {
    let attachment = model.vessel.as_ref()?;
    let winch = attachment.holding_winch()?;
    let lay = attachment.lay.as_ref()?;
    let element = model.rod.element_count().checked_sub(1)?;
    if !model.is_last_wire_element(element) {
        return None;
    }
    let ea = model.rod.section(element).translational_stiffness.x;
    let tension = ea * state.gauss[element].strain.x;
    Some(model.rod.elements[element].length - winch.hand_back_length(&lay.hang_off, tension, ea))
}

/// The haul-in speed (m/s, ≤ 0) the winch may not exceed with `remaining` metres (≥ 0) left over a step of
/// `dt` (s) at its acceleration limit `deceleration` (m/s²): −min(√(2 a r), r/Δt), so that it stops at the hold
/// point without overshooting it.
pub fn approach_speed(remaining: f64, deceleration: f64, dt: f64) -> f64 {
    let r = remaining.max(0.0);
    -(2.0 * deceleration * r).sqrt().min(r / dt)
}

/// Whether the tensioner takes the line back before the next step: the winch, told to haul in (the stages'
/// speed at the state's time negative), has hauled the pipe's end to within [`CLOSING_GAP`] of the hold point.
pub fn due(model: &Model, state: &DynamicState) -> Result<bool> {
    let hauling = match &model.pay_out {
        Some(pay_out) => pay_out.speed_at(state.time)? < 0.0,
        None => false,
    };
    Ok(hauling && remaining(model, state).is_some_and(|r| r <= CLOSING_GAP))
}

/// Hands the line back to the tensioner at the state's time: removes the wire's element and the winch's node,
/// clamps the pipe's end where it is, with its rotation, and gives it the vessel's rigid motion. `reactions`
/// follow the nodes. Returns the hand-back made.
pub fn hand_back(
    model: &mut Model,
    state: &mut DynamicState,
    reactions: &mut Vec<Vector6<f64>>,
) -> Option<HandBack> {
    let attachment = model.vessel.as_ref()?;
    let winch_node = attachment.node;
    // The elements that come off: the wire's and a head body's.
    let removed = 1 + usize::from(
        attachment
            .winch
            .as_ref()
            .is_some_and(|w| w.head_body.is_some()),
    );
    let end = winch_node.checked_sub(removed)?;
    let configuration = &state.configuration;
    let (origin, body) = vessel_pose(
        attachment,
        &configuration.positions[winch_node],
        &configuration.rotations[winch_node],
    );
    let end_rotation = configuration.rotations[end]
        .to_rotation_matrix()
        .into_inner();
    let back = HandBack {
        time: state.time,
        hang_off: body.transpose() * (configuration.positions[end] - origin),
        angle: end_rotation.transpose() * body,
    };
    // The vessel's rigid motion at the pipe's end: its node's velocity and spin carried over the lever.
    let spin = configuration.rotations[winch_node] * state.body_angular_velocities[winch_node];
    let lever = configuration.positions[end] - configuration.positions[winch_node];
    state.velocities[end] = state.velocities[winch_node] + spin.cross(&lever);
    state.body_angular_velocities[end] = configuration.rotations[end].inverse() * spin;
    state.accelerations[end] = state.accelerations[winch_node];

    let rod = &mut model.rod;
    rod.nodes.truncate(end + 1);
    rod.frames.truncate(end + 1);
    rod.elements.truncate(end);
    rod.segment_of.truncate(end);
    let configuration = &mut state.configuration;
    configuration.positions.truncate(end + 1);
    configuration.rotations.truncate(end + 1);
    state.velocities.truncate(end + 1);
    state.accelerations.truncate(end + 1);
    state.body_angular_velocities.truncate(end + 1);
    state.slips.truncate(end + 1);
    state.gauss.truncate(end);
    state.plastic.truncate(end);
    state.pay_out_speed = 0.0;
    reactions.truncate(end + 1);
    if let Some(attachment) = model.vessel.as_mut() {
        attachment.node = end;
    }
    model.hand_back(back);
    Some(back)
}
