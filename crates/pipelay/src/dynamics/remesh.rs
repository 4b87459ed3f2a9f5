//! The mesh changes of a pipe whose length changes at one end (pay-out and pay-in).
//!
//! Between mesh changes the end element grows (or shrinks) with the pay-out speed; the time step handles
//! that (`rod::dynamic_element::step` with its start length). When the end element passes 1.5ℓ (ℓ the
//! pay-out element length) it is split into an element of length ℓ next to the pipe and a shorter end
//! element; on pay-in, when it falls below 0.5ℓ, it is joined with its neighbour.
//!
//! A split keeps the state the element describes: the new node's rotation is on the geodesic between the
//! element's end rotations, both halves keep the element's curvature K and the Gauss rotation interpolated
//! the same way, and the new node is placed where the two halves carry the same force (n₁ = n₂, a 3×3 solve),
//! so the tension through the split does not jump. Velocities and the seabed slips are interpolated.
// Indexing cannot go out of bounds here: The end element and its nodes, indices of the mesh being changed (checked non-empty).
#![allow(clippy::indexing_slicing)]
use crate::dynamics::state::{element_gauss_point, DynamicState};
use crate::model::Model;
use crate::rod::cable::gauss_point as cable_gauss_point;
use crate::rod::dynamic_element::GaussPoint;
use crate::so3::log_quat;
use nalgebra::{UnitQuaternion, Vector2, Vector3, Vector6};

/// What a mesh change did, for the integrator to follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshChange {
    /// A node was inserted at this index.
    Inserted(usize),
    /// The node at this index was removed.
    Removed(usize),
}

/// Splits or joins the end element if its length has left [0.5ℓ, 1.5ℓ]; `reactions` follow the nodes.
/// `speed` is the pay-out speed (m/s), with which the pipe leaves the end relative to it.
pub fn remesh(
    model: &mut Model,
    state: &mut DynamicState,
    reactions: &mut Vec<Vector6<f64>>,
    speed: f64,
) -> Option<MeshChange> {
    let pay_out = model.pay_out.as_ref()?;
    let (element, _) = model.growing_element()?;
    let nominal = pay_out.element_length;
    let at_start = pay_out.at_start;
    let length = model.rod.elements[element].length;
    if length > 1.5 * nominal {
        // The new element of length ℓ lies next to the pipe; the end element keeps the rest.
        let fraction = if at_start {
            (length - nominal) / length
        } else {
            nominal / length
        };
        let node = split(model, state, element, fraction, at_start, speed);
        take_fed_segments(model, state, node);
        reactions.insert(node, Vector6::zeros());
        model.renumber_nodes(node, 1);
        Some(MeshChange::Inserted(node))
    } else if length < 0.5 * nominal
        && model.rod.element_count() > 1
        && !model.is_last_wire_element(element)
    {
        let first = if at_start { 0 } else { element - 1 };
        join(model, state, first, at_start);
        reactions.remove(first + 1);
        model.renumber_nodes(first + 1, -1);
        Some(MeshChange::Removed(first + 1))
    } else {
        None
    }
}

/// Splits `element` at `fraction` of its length from its first node; returns the new node's index. The new
/// node is a material point: its velocity is interpolated between the inner node's and that of the pipe
/// leaving the end (the end's velocity plus `speed` along the element, away from the end).
fn split(
    model: &mut Model,
    state: &mut DynamicState,
    element: usize,
    fraction: f64,
    at_start: bool,
    speed: f64,
) -> usize {
    let (a, b) = (element, element + 1);
    let section = model.rod.section(element);
    let cable = section.cable;
    let parent = model.rod.elements[element];
    let gauss = state.gauss[element];
    let config = &state.configuration;
    let (ra, rb) = (config.rotations[a], config.rotations[b]);
    // Ψ: the material relative rotation of the element's ends; the rotation field is R_a exp(sΨ).
    let relative = log_quat(&(ra.inverse() * rb));
    let rotation = ra * UnitQuaternion::from_scaled_axis(relative * fraction);
    // Both halves keep the element's Gauss point: its rotation Λ, strain Γ and curvature K (the energy–momentum
    // step carries them as state; they are per length). With the node on the chord at `fraction`, each half's
    // strain Λᵀc_i/l_i − E1 is then the element's exactly, bent or not.
    let (first_length, second_length) =
        (fraction * parent.length, (1.0 - fraction) * parent.length);
    let (xa, xb) = (config.positions[a], config.positions[b]);
    // Moved off the chord by δ, the halves' forces differ by Λ C Λᵀ δ (1/l₁ + 1/l₂): the node carries its share
    // of the submerged weight when n₁ − n₂ = ½(l₁ + l₂) w e3 (the weight acts along e3).
    // (A cable's node stays on the chord: its halves' stiffness across it is the tension's, and small.)
    let offset = if cable {
        Vector3::zeros()
    } else {
        let stiffness = gauss.rotation
            * section.c_t()
            * gauss.rotation.transpose()
            * (1.0 / first_length + 1.0 / second_length);
        let weight = Vector3::z() * (0.5 * parent.length * model.submerged_weight(element));
        stiffness.lu().solve(&weight).unwrap_or_else(Vector3::zeros)
    };
    let position = xa + (xb - xa) * fraction + offset;
    // Both halves take the element's Gauss point as it is. The bending moment of a sheared rod varies along it
    // (m′ = −φ′ × n), which a one-point element cannot show: the new node is left with the moment ½ l n × φ′
    // unbalanced, released as a small vibration. Giving each half the moment at its own midpoint instead
    // balanced the node but added ½ Σ l_i Δm_i²/EI of strain energy at each split, which fed back through the
    // shear force and pumped a long J-lay run unstable; this embedding changes no energy at all.
    let half = |chord: Vector3<f64>, l: f64| {
        if cable {
            return cable_gauss_point(&chord, l);
        }
        GaussPoint {
            rotation: gauss.rotation,
            strain: gauss.rotation.transpose() * chord / l - Vector3::x(),
            curvature: gauss.curvature,
        }
    };
    let first = half(position - xa, first_length);
    let second = half(xb - position, second_length);
    let mix3 = |u: &Vector3<f64>, v: &Vector3<f64>| u * (1.0 - fraction) + v * fraction;
    let spin = mix3(
        &(ra * state.body_angular_velocities[a]),
        &(rb * state.body_angular_velocities[b]),
    );
    // Paid-out pipe moves from the end into the pipe: along a → b at end A, b → a at end B.
    let along = (xb - xa).normalize() * speed;
    let velocity = if at_start {
        mix3(&(state.velocities[a] + along), &state.velocities[b])
    } else {
        mix3(&state.velocities[a], &(state.velocities[b] - along))
    };
    let slip: Vector2<f64> = state.slips[a] * (1.0 - fraction) + state.slips[b] * fraction;

    state.configuration.positions.insert(b, position);
    state.configuration.rotations.insert(b, rotation);
    state.velocities.insert(b, velocity);
    let acceleration = mix3(&state.accelerations[a], &state.accelerations[b]);
    state.accelerations.insert(b, acceleration);
    state
        .body_angular_velocities
        .insert(b, rotation.inverse() * spin);
    state.slips.insert(b, slip);
    state.gauss[element] = first;
    state.gauss.insert(element + 1, second);
    // Both halves keep the element's wall fibres' state too: at the same strains, the same stresses.
    let plastic = state.plastic[element].clone();
    state.plastic.insert(element + 1, plastic);
    model.rod.split_element(element, fraction);
    b
}

/// Joins elements `first` and `first + 1` by removing the node between them, the joined element of the
/// segment of the one away from the end (`at_start`: the second), and with its wall fibres' state; its Gauss
/// point is that of its end nodes (the objective element's midpoint triad and strains).
fn join(model: &mut Model, state: &mut DynamicState, first: usize, at_start: bool) {
    model.rod.join_elements(first, usize::from(at_start));
    let removed = first + 1;
    let kept = state.plastic.remove(if at_start { removed } else { first });
    state.plastic.insert(first, kept);
    let config = &mut state.configuration;
    config.positions.remove(removed);
    config.rotations.remove(removed);
    state.velocities.remove(removed);
    state.accelerations.remove(removed);
    state.body_angular_velocities.remove(removed);
    state.slips.remove(removed);
    state.gauss.remove(removed);
    state.gauss[first] = element_gauss_point(model, config, first);
}

/// After a split that inserted node `node` at the paying end: the two elements at it take the section of the
/// material at their midpoints from the pay-out's feed (the material paid out most recently lies at the end).
/// An element that changes section keeps its axial force (its unstretched length set for the new stiffness)
/// and gets the Gauss point of its configuration and the wall state its segment's pipe enters in (unyielded,
/// or reeled); a node that becomes a cable's loses its spin.
fn take_fed_segments(model: &mut Model, state: &mut DynamicState, node: usize) {
    let Some(pay_out) = model.pay_out.as_ref() else {
        return;
    };
    if pay_out.feed.is_empty() {
        return;
    }
    let paid = model.rod.length() - pay_out.initial_length;
    let count = model.rod.element_count();
    // The two elements at the new node, and each one's midpoint's distance from the paying end.
    let arcs = model.rod.arc_lengths();
    let total = arcs[count];
    let mut changed = false;
    for element in [node - 1, node] {
        let middle = 0.5 * (arcs[element] + arcs[element + 1]);
        let from_end = if pay_out.at_start {
            middle
        } else {
            total - middle
        };
        let Some(segment) = pay_out.fed_segment(paid - from_end) else {
            continue;
        };
        if model.rod.segment_of[element] == segment {
            continue;
        }
        // The element's axial force under its old section, which the new one is to carry on: its unstretched
        // length becomes l/(1 + N/EA) of the new section's EA (a joint passes the tensioner under tension,
        // not by a jump of the strain's stiffness), and its Gauss point that of the configuration.
        let force = state.axial_force(model, element);
        model.rod.segment_of[element] = segment;
        changed = true;
        let positions = &state.configuration.positions;
        let chord = (positions[element + 1] - positions[element]).norm();
        let stretch = 1.0 + force / model.rod.sections[segment].translational_stiffness.x;
        if stretch > 0.0 {
            model.rod.elements[element].length = chord / stretch;
        }
    }
    if changed {
        model.rod.unstrain_cables();
        let entering = model.plastic_state();
        for element in [node - 1, node] {
            state.gauss[element] = element_gauss_point(model, &state.configuration, element);
            let segment = model.rod.segment_of[element];
            state.plastic[element] = entering
                .as_ref()
                .map_or_else(Vec::new, |s| s.entry(segment).to_vec());
        }
        for a in node - 1..=node + 1 {
            if model.is_rotationless(a) {
                state.body_angular_velocities[a] = Vector3::zeros();
            }
        }
    }
}
