//! Bodies attached at a point of the line: clump weights, buoyancy modules, in-line structures, laydown
//! heads. Each acts at its arc length from end A along the reference, spread onto the two nodes of its
//! element by the linear shape functions N_a = 1 − ξ, N_b = ξ: its weight less its buoyancy (a dead load along
//! e3, whose potential joins the gravity potential), its mass with its added mass (lumped at the two nodes) and
//! its drag ½ρ C_dA |u|u on the flow's velocity relative to the point.
// Indexing cannot go out of bounds here: element indices below the rod's element count.
#![allow(clippy::indexing_slicing)]
use crate::error::{finite, non_negative, Result};
use crate::rod::Rod;
use nalgebra::Vector3;

/// A body at a point of the line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attachment {
    /// Arc length from end A along the reference (m).
    pub arc_length: f64,
    /// Mass in air (kg).
    pub mass: f64,
    /// Displaced volume (m³).
    pub volume: f64,
    /// Drag area C_d·A (m²).
    pub drag_area: f64,
    /// Added-mass coefficient on the displaced volume (isotropic).
    pub added_mass: f64,
}

/// Where an attachment acts: its element and the weights of the element's two nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Place {
    pub element: usize,
    /// (N_a, N_b) = (1 − ξ, ξ), ξ the fraction of the element's reference length from its first node.
    pub weights: [f64; 2],
}

impl Place {
    /// The point of the element at the weights, between `first` and `second` (m).
    pub fn point(&self, first: &Vector3<f64>, second: &Vector3<f64>) -> Vector3<f64> {
        first * self.weights[0] + second * self.weights[1]
    }
}

impl Attachment {
    /// An attachment of `mass` (kg), displaced `volume` (m³), drag area C_d·A `drag_area` (m²) and
    /// added-mass coefficient `added_mass` at `arc_length` (m from end A; checked against the line by
    /// [`crate::model::Model::attach`]).
    pub fn new(
        arc_length: f64,
        mass: f64,
        volume: f64,
        drag_area: f64,
        added_mass: f64,
    ) -> Result<Self> {
        finite("arc_length", &[arc_length])?;
        Ok(Attachment {
            arc_length,
            mass: non_negative("mass", mass, "kg")?,
            volume: non_negative("volume", volume, "m³")?,
            drag_area: non_negative("drag_area", drag_area, "m²")?,
            added_mass: non_negative("added_mass", added_mass, "(dimensionless)")?,
        })
    }

    /// Where it acts on `rod`: the last element whose start lies at or before its arc length.
    pub fn place(&self, rod: &Rod) -> Place {
        let mut start = 0.0;
        let last = rod.element_count() - 1;
        for (element, reference) in rod.elements.iter().enumerate() {
            if self.arc_length <= start + reference.length || element == last {
                let xi = ((self.arc_length - start) / reference.length).clamp(0.0, 1.0);
                return Place {
                    element,
                    weights: [1.0 - xi, xi],
                };
            }
            start += reference.length;
        }
        Place {
            element: last,
            weights: [0.0, 1.0],
        }
    }

    /// Weight less buoyancy (N, along +e3) in water of `density` (kg/m³; 0 in air) under `gravity`.
    pub fn net_weight(&self, density: f64, gravity: f64) -> f64 {
        (self.mass - density * self.volume) * gravity
    }

    /// Mass with the added mass (kg) in water of `density`.
    pub fn inertial_mass(&self, density: f64) -> f64 {
        self.mass + self.added_mass * density * self.volume
    }

    /// The drag force on a relative flow `flow` (m/s), ½ρ C_dA |u|u (N), in water of `density`.
    pub fn drag(&self, density: f64, flow: &Vector3<f64>) -> Vector3<f64> {
        flow * (0.5 * density * self.drag_area * flow.norm())
    }
}
