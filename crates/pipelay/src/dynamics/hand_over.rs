//! The hand-over of the line from the tensioner to the A&R winch, at the start of the first stage the winch
//! holds ([`crate::dynamics::stages`]). The winch's wire runs down the firing line from the winch to the
//! pipe's end at the hold point: it joins the mesh as one cable element, stretched to carry the pipe's axial
//! force at the hold point (its unstretched length l/(1 + N/EA)), so the axial force passes from the
//! tensioner to the wire without a jump. The vessel then holds the wire's end at the winch (a new node, where
//! the vessel's rigid motion puts it), and the pipe's end, released by the tensioner, keeps its state: its
//! rotation becomes free (the rod–cable joint is a pin) and the tensioner's shear and moment are let go; its
//! velocity becomes the material's, the vessel's plus the pay-out speed along the pipe (the winch takes over
//! at the tensioner's speed).
//! The laydown head is fitted at the pipe's end: a point body ([`crate::model::Model::hold_by_winch`]), or a
//! body with a length and a diameter, an element of the line from the pipe's end along the wire's way
//! ([`crate::rod::section::Section::head`]), stretched as the pipe by the axial force, the wire then running
//! from its nose. The energy the wire and head bring in is booked with pay-out's by the integrator.
// Indexing cannot go out of bounds here: the vessel's node is end B, the last node of the mesh.
#![allow(clippy::indexing_slicing)]
use crate::dynamics::state::{element_gauss_point, DynamicState};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::rod::cable::gauss_point as cable_gauss_point;
use crate::rod::dynamic_element::GaussPoint;
use crate::rod::element::ElementReference;
use crate::vessel::coupling::body_rotation;
use nalgebra::{Matrix3, Vector2, Vector3, Vector6};

/// Hands the line over to the winch: appends the wire's element and node and moves the vessel's hold to
/// it. `reactions` follow the nodes. Returns the axial force the wire takes on (N).
pub fn hand_over(
    model: &mut Model,
    state: &mut DynamicState,
    reactions: &mut Vec<Vector6<f64>>,
) -> Result<f64> {
    let Some((attachment, winch)) = model
        .vessel
        .as_ref()
        .and_then(|v| v.winch.as_ref().map(|w| (v, w)))
    else {
        return Err(Error::input(
            "hold",
            "\"winch\"",
            "needs a winch on the vessel: attach_vessel(..., winch=pl.Winch(...))",
        ));
    };
    let node = attachment.node;
    if node != model.rod.element_count() {
        return Err(Error::input(
            "hold",
            "\"winch\" with the vessel at end A",
            "the winch holds the line's end B: attach the vessel there",
        ));
    }
    let rotation = state.configuration.rotations[node];
    let offset = body_rotation(attachment, &rotation) * (winch.position - attachment.hang_off());
    let (wire, head) = (winch.wire, winch.head_body);
    // The axial force at the hold point: that of the top element.
    let force = state.axial_force(model, node - 1);
    let chord = offset.norm();
    let direction = offset / chord;

    // The pipe's end was a point of the vessel that pipe passed through at the pay-out speed: as the pipe's
    // material end it moves on with the pipe, at that speed away from the vessel along the top element.
    let speed = model
        .pay_out
        .as_ref()
        .map_or(Ok(0.0), |p| p.speed_at(state.time))?;
    let positions = &state.configuration.positions;
    let along = (positions[node - 1] - positions[node]).normalize() * speed;
    let spin = rotation * state.body_angular_velocities[node];
    let vessel_velocity = state.velocities[node];
    state.velocities[node] += along;

    // A head body first, from the pipe's end along the wire's way, stretched by the axial force; then the
    // wire, from its nose (or the pipe's end) to the winch.
    let mut reach = 0.0;
    let mut last = node;
    if let Some(head) = head {
        let stretch = 1.0 + force / model.rod.sections[head.section].translational_stiffness.x;
        reach = head.length * stretch;
        append(
            model,
            state,
            reactions,
            head.section,
            head.length,
            direction * head.length,
            direction * reach,
        );
        last += 1;
        // The head moves with the pipe's end.
        state.velocities[last] = state.velocities[node] + spin.cross(&(direction * reach));
        let gauss = element_gauss_point(model, &state.configuration, node);
        state.gauss[node] = gauss;
    }
    let length = (chord - reach)
        / (1.0 + force.max(0.0) / model.rod.sections[wire].translational_stiffness.x);
    append(
        model,
        state,
        reactions,
        wire,
        length,
        direction * length,
        offset - direction * reach,
    );
    // The winch's node is a point of the vessel.
    state.velocities[last + 1] = vessel_velocity + spin.cross(&offset);
    state.gauss[last] = cable_gauss_point(&(offset - direction * reach), length);
    // The vessel's reaction moves to the winch's node.
    reactions[node..=last].fill(Vector6::zeros());
    if let Some(attachment) = model.vessel.as_mut() {
        attachment.node = last + 1;
    }
    model.hold_by_winch();
    Ok(force)
}

/// Appends an element of `section` and `length` (m) at end B, its reference end `reference` (m) beyond the
/// last node's reference and its end `extent` (m) beyond the last node; the new node takes the last node's
/// rotation, acceleration, slip and reaction, and a velocity the caller sets.
fn append(
    model: &mut Model,
    state: &mut DynamicState,
    reactions: &mut Vec<Vector6<f64>>,
    section: usize,
    length: f64,
    reference: Vector3<f64>,
    extent: Vector3<f64>,
) {
    let last = model.rod.element_count();
    let rod = &mut model.rod;
    rod.nodes.push(rod.nodes[last] + reference);
    rod.frames.push(rod.frames[last]);
    rod.elements.push(ElementReference {
        length,
        strain: Vector3::zeros(),
        curvature: Vector3::zeros(),
    });
    rod.segment_of.push(section);
    let configuration = &mut state.configuration;
    configuration
        .positions
        .push(configuration.positions[last] + extent);
    configuration.rotations.push(configuration.rotations[last]);
    state.velocities.push(state.velocities[last]);
    state.accelerations.push(state.accelerations[last]);
    state
        .body_angular_velocities
        .push(state.body_angular_velocities[last]);
    state.slips.push(Vector2::zeros());
    // A placeholder the caller replaces with the element's own.
    state.gauss.push(GaussPoint {
        rotation: Matrix3::identity(),
        strain: Vector3::zeros(),
        curvature: Vector3::zeros(),
    });
    reactions.push(reactions[last]);
}
