//! The rod's lumped (nodal) inertia and damping: half of each element's translational mass (added mass
//! included), rotational inertia and rotational damping at each of its nodes.
//!
//! **Added mass by direction.** A node's translational mass matrix is M = (m + m_a C_an) I + m_a (C_aa − C_an)
//! t tᵀ, with m_a = ρ_w π/4 D_h² its tributary length's displaced mass and t = Λ e1 the node's axis: the normal
//! coefficient across the pipe, the axial one along it. The kinetic energy ½vᵀMv then depends on the node's
//! rotation; the time step balances it exactly ([`crate::dynamics::rod_step`]). A cable has no rotation: what
//! its axial coefficient adds acts along each element's chord t_e on the element's mean velocity ū_e, with
//! kinetic energy ½ d_e (t_e·ū_e)², d_e = L_e m_a (C_aa − C_an), balanced exactly by the element's step.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the integrator's own mesh (rebuilt with it at every pay-out change).
#![allow(clippy::indexing_slicing)]
use crate::dynamics::rod_step::NodeStart;
use crate::dynamics::state::DynamicState;
use crate::model::Model;
use nalgebra::{Matrix3, Vector3};

/// Nodal (lumped) inertia and damping of the rod.
#[derive(Debug, Clone)]
pub struct NodalProperties {
    /// Translational mass across the pipe, the normal added mass included (kg).
    pub mass: Vec<f64>,
    /// What the axial added mass adds along the node's axis t, m_a (C_aa − C_an) (kg; negative where the axial
    /// coefficient is the smaller, zero without a sea).
    pub axial_added_mass: Vec<f64>,
    /// Rotational inertia about the material axes (kg·m²).
    pub inertia: Vec<Vector3<f64>>,
    /// Rotational damping about the material axes (N·m·s).
    pub damping: Vec<Vector3<f64>>,
    /// What the axial added mass adds along each cable element's chord, d_e (kg; zero for a rod's element,
    /// whose nodes carry it).
    pub element_axial: Vec<f64>,
}

impl NodalProperties {
    /// Added mass per unit length across element `element`, and what the axial coefficient adds along it
    /// (kg/m).
    fn added_mass(model: &Model, element: usize) -> (f64, f64) {
        let section = model.rod.section(element);
        model.sea.as_ref().map_or((0.0, 0.0), |sea| {
            let displaced =
                sea.density * std::f64::consts::FRAC_PI_4 * section.hydrodynamic_diameter.powi(2);
            (
                section.added_mass[1] * displaced,
                (section.added_mass[0] - section.added_mass[1]) * displaced,
            )
        })
    }

    /// Recomputes the lumps of `node` from the lengths of its elements.
    pub fn recompute(&mut self, model: &Model, node: usize) {
        self.mass[node] = 0.0;
        self.axial_added_mass[node] = 0.0;
        self.inertia[node] = Vector3::zeros();
        self.damping[node] = Vector3::zeros();
        let elements = node.saturating_sub(1)..(node + 1).min(model.rod.element_count());
        for e in elements {
            self.add_element(model, e, node);
            self.element_axial[e] = Self::cable_axial(model, e);
        }
        for (at, mass) in attachment_lumps(model) {
            if at == node {
                self.mass[node] += mass;
            }
        }
    }

    /// Adds half of element `element`'s mass, inertia and damping to its node `node`.
    fn add_element(&mut self, model: &Model, element: usize, node: usize) {
        let section = model.rod.section(element);
        let half = 0.5 * model.rod.elements[element].length;
        let (normal, axial) = Self::added_mass(model, element);
        self.mass[node] += half * (section.mass + normal);
        if !section.cable {
            self.axial_added_mass[node] += half * axial;
        }
        self.inertia[node] += half * section.inertia;
        self.damping[node] += half * section.rotational_damping;
    }

    /// d_e of element `element`: L_e m_a (C_aa − C_an) for a cable's, zero for a rod's.
    fn cable_axial(model: &Model, element: usize) -> f64 {
        if model.rod.section(element).cable {
            model.rod.elements[element].length * Self::added_mass(model, element).1
        } else {
            0.0
        }
    }

    /// The lumps of `model`'s rod: half of each element's mass, inertia and damping at each of its nodes.
    pub fn new(model: &Model) -> Self {
        let count = model.rod.node_count();
        let mut props = NodalProperties {
            mass: vec![0.0; count],
            axial_added_mass: vec![0.0; count],
            inertia: vec![Vector3::zeros(); count],
            damping: vec![Vector3::zeros(); count],
            element_axial: (0..model.rod.element_count())
                .map(|e| Self::cable_axial(model, e))
                .collect(),
        };
        for e in 0..model.rod.element_count() {
            props.add_element(model, e, e);
            props.add_element(model, e, e + 1);
        }
        for (node, mass) in attachment_lumps(model) {
            props.mass[node] += mass;
        }
        props
    }

    /// Kinetic energy of node `node` in `state` (J): ½vᵀMv + ½WᵀJW.
    pub fn kinetic_energy(&self, state: &DynamicState, node: usize) -> f64 {
        let (v, w) = (state.velocities[node], state.body_angular_velocities[node]);
        let energy = 0.5 * self.mass[node] * v.norm_squared()
            + 0.5 * w.dot(&self.inertia[node].component_mul(&w));
        match self.axial_added_mass[node] {
            0.0 => energy,
            axial => energy + 0.5 * axial * axis(state, node).dot(&v).powi(2),
        }
    }

    /// The kinetic energy the axial added mass of cable element `element` adds, ½ d_e (t_e·ū_e)² (J).
    pub fn element_kinetic_energy(&self, state: &DynamicState, element: usize) -> f64 {
        match self.element_axial[element] {
            0.0 => 0.0,
            d => {
                let (t, u) = chord_and_mean_velocity(state, element);
                0.5 * d * t.dot(&u).powi(2)
            }
        }
    }

    /// The momentum the axial added mass of cable element `element` adds, d_e t_e (t_e·ū_e) (kg·m/s), half
    /// of it at each of its nodes.
    pub fn element_momentum(&self, state: &DynamicState, element: usize) -> Vector3<f64> {
        match self.element_axial[element] {
            0.0 => Vector3::zeros(),
            d => {
                let (t, u) = chord_and_mean_velocity(state, element);
                t * (d * t.dot(&u))
            }
        }
    }

    /// Linear momentum M v of node `node` in `state` (kg·m/s).
    pub fn momentum(&self, state: &DynamicState, node: usize) -> Vector3<f64> {
        let v = state.velocities[node];
        match self.axial_added_mass[node] {
            0.0 => v * self.mass[node],
            axial => {
                let t = axis(state, node);
                v * self.mass[node] + t * (axial * t.dot(&v))
            }
        }
    }
}

/// Each attachment's inertial mass (its added mass included) shared by its element's nodes: (node, kg) pairs.
fn attachment_lumps(model: &Model) -> impl Iterator<Item = (usize, f64)> + '_ {
    let density = model.water_density();
    model
        .placed_attachments()
        .flat_map(move |(attachment, place)| {
            let mass = attachment.inertial_mass(density);
            [place.element, place.element + 1]
                .into_iter()
                .zip(place.weights)
                .map(move |(node, weight)| (node, weight * mass))
        })
}

/// The axis t = Λ e1 of node `node` in `state`.
fn axis(state: &DynamicState, node: usize) -> Vector3<f64> {
    state.configuration.rotations[node] * Vector3::x()
}

/// The unit chord t_e and the mean velocity ū_e of element `element` in `state`.
fn chord_and_mean_velocity(state: &DynamicState, element: usize) -> (Vector3<f64>, Vector3<f64>) {
    let positions = &state.configuration.positions;
    let t = (positions[element + 1] - positions[element]).normalize();
    let u = 0.5 * (state.velocities[element] + state.velocities[element + 1]);
    (t, u)
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
        axis: rotation.column(0).into_owned(),
    }
}
