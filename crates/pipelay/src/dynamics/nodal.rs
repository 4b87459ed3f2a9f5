//! The rod's lumped (nodal) inertia and damping: half of each element's translational mass (added mass
//! included), rotational inertia and rotational damping at each of its nodes.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the integrator's own mesh (rebuilt with it at every pay-out change).
#![allow(clippy::indexing_slicing)]
use crate::dynamics::rod_step::NodeStart;
use crate::dynamics::state::DynamicState;
use crate::model::Model;
use nalgebra::{Matrix3, Vector3};

/// Nodal (lumped) inertia and damping of the rod.
#[derive(Debug, Clone)]
pub struct NodalProperties {
    /// Translational mass, added mass included (kg).
    pub mass: Vec<f64>,
    /// Rotational inertia about the material axes (kg·m²).
    pub inertia: Vec<Vector3<f64>>,
    /// Rotational damping about the material axes (N·m·s).
    pub damping: Vec<Vector3<f64>>,
}

impl NodalProperties {
    /// Added mass per unit length (kg/m).
    fn added_mass(model: &Model) -> f64 {
        let section = &model.rod.section;
        model.sea.as_ref().map_or(0.0, |sea| {
            section.added_mass[1]
                * sea.density
                * std::f64::consts::FRAC_PI_4
                * section.hydrodynamic_diameter.powi(2)
        })
    }

    /// Recomputes the lumps of `node` from the lengths of its elements.
    pub fn recompute(&mut self, model: &Model, node: usize) {
        let section = &model.rod.section;
        let elements = &model.rod.elements;
        let tributary = 0.5
            * (node.checked_sub(1).map_or(0.0, |e| elements[e].length)
                + elements.get(node).map_or(0.0, |e| e.length));
        self.mass[node] = tributary * (section.mass + Self::added_mass(model));
        self.inertia[node] = tributary * section.inertia;
        self.damping[node] = tributary * section.rotational_damping;
    }

    /// The lumps of `model`'s rod: half of each element's mass, inertia and damping at each of its nodes.
    pub fn new(model: &Model) -> Self {
        let section = &model.rod.section;
        let added = Self::added_mass(model);
        let count = model.rod.node_count();
        let mut props = NodalProperties {
            mass: vec![0.0; count],
            inertia: vec![Vector3::zeros(); count],
            damping: vec![Vector3::zeros(); count],
        };
        for (e, reference) in model.rod.elements.iter().enumerate() {
            let half = 0.5 * reference.length;
            for node in [e, e + 1] {
                props.mass[node] += half * (section.mass + added);
                props.inertia[node] += half * section.inertia;
                props.damping[node] += half * section.rotational_damping;
            }
        }
        props
    }
}

/// What node `node`'s inertia and damping terms need from the step's start.
pub fn node_start(nodal: &NodalProperties, state: &DynamicState, node: usize) -> NodeStart {
    let rotation = state.configuration.rotations[node]
        .to_rotation_matrix()
        .into_inner();
    let spatial = |d: &Vector3<f64>| rotation * Matrix3::from_diagonal(d) * rotation.transpose();
    NodeStart {
        inertia: spatial(&nodal.inertia[node]),
        momentum: rotation
            * nodal.inertia[node].component_mul(&state.body_angular_velocities[node]),
        damping: spatial(&nodal.damping[node]),
    }
}
