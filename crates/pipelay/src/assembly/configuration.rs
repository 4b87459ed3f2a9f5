//! A configuration of the rod: its nodal positions and rotations, and the hinge angles of its vessel's
//! articulated stinger.
// Indexing cannot go out of bounds here: node indices of the model's own elements.
#![allow(clippy::indexing_slicing)]
use crate::model::Model;
use nalgebra::{UnitQuaternion, Vector3};

/// A configuration of the rod: nodal positions and rotations, and hinge angles.
#[derive(Debug, Clone, PartialEq)]
pub struct Configuration {
    pub positions: Vec<Vector3<f64>>,
    pub rotations: Vec<UnitQuaternion<f64>>,
    /// Each stinger section's hinge angle φ_i (rad; [`crate::vessel::articulation`]); empty without.
    pub hinge_angles: Vec<f64>,
}

impl Configuration {
    /// The rod's stress-free reference.
    pub fn reference(model: &Model) -> Self {
        Configuration {
            positions: model.rod.nodes.clone(),
            rotations: model.rod.frames.clone(),
            hinge_angles: vec![0.0; model.hinge_count()],
        }
    }

    /// Gravity potential of the submerged weight, −Σ ½L0 w (z1 + z2), and of the attachments' (J).
    pub fn gravity_potential(&self, model: &Model) -> f64 {
        model
            .rod
            .elements
            .iter()
            .enumerate()
            .map(|(e, r)| {
                -0.5 * r.length
                    * model.submerged_weight(e)
                    * (self.positions[e].z + self.positions[e + 1].z)
            })
            .sum::<f64>()
            - self.attachment_potential(model)
    }

    /// Σ W (N_a z_a + N_b z_b) over the attachments, W the weight less buoyancy of each (J; 0 without).
    fn attachment_potential(&self, model: &Model) -> f64 {
        let density = model.water_density();
        model
            .placed_attachments()
            .map(|(attachment, place)| {
                let e = place.element;
                attachment.net_weight(density, model.gravity)
                    * place.point(&self.positions[e], &self.positions[e + 1]).z
            })
            .sum()
    }
}
