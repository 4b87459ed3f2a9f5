//! The seabed: elastic normal contact with optional damping, and Coulomb friction that is elastic up to a
//! mobilisation distance, then slides (axial and lateral coefficients apart); see [`crate::contact::seabed`]
//! for how it enters statics and the energy–momentum step.
use super::bathymetry::Bathymetry;
use crate::error::{non_negative, positive, Result};

/// Seabed properties. Forces per unit length of pipe refer to the contact width d, the section's outer
/// diameter (MoorDyn's kBot convention): the normal force is k·d·δ for a penetration δ of the centreline.
#[derive(Debug, Clone, PartialEq)]
pub struct Seabed {
    /// Normal stiffness k per unit contact area per metre of penetration (Pa/m).
    pub stiffness: f64,
    /// Normal damping c per unit contact area (Pa·s/m): force per length c·d·(normal velocity), in contact.
    pub damping: f64,
    /// Coulomb coefficients (axial, lateral).
    pub friction: [f64; 2],
    /// Sliding distance at which friction reaches μN for a pipe pressed by its own submerged weight (m).
    pub mobilisation: f64,
    /// The seabed's shape.
    pub bathymetry: Bathymetry,
}

impl Seabed {
    /// Checks and builds a seabed.
    pub fn new(
        stiffness: f64,
        damping: f64,
        friction: [f64; 2],
        mobilisation: f64,
        bathymetry: Bathymetry,
    ) -> Result<Self> {
        positive("stiffness", stiffness, "Pa/m")?;
        non_negative("damping", damping, "Pa·s/m")?;
        for mu in friction {
            non_negative("friction", mu, "(a Coulomb coefficient)")?;
        }
        positive("mobilisation", mobilisation, "m")?;
        Ok(Seabed {
            stiffness,
            damping,
            friction,
            mobilisation,
            bathymetry,
        })
    }

    /// Whether the seabed has friction.
    pub fn has_friction(&self) -> bool {
        self.friction.iter().any(|&mu| mu > 0.0)
    }
}
