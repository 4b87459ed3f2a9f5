//! The sea: depth, water density and current.
use super::current::Current;
use crate::error::{non_negative, positive, Result};
use nalgebra::Vector3;

/// Water depth, density and current. The seabed is z = 0, the surface z = −depth.
#[derive(Debug, Clone, PartialEq)]
pub struct Sea {
    pub depth: f64,
    pub density: f64,
    pub current: Option<Current>,
}

impl Sea {
    /// Checks and builds a sea.
    pub fn new(depth: f64, density: f64, current: Option<Current>) -> Result<Self> {
        positive("depth", depth, "m")?;
        non_negative("density", density, "kg/m³")?;
        Ok(Sea {
            depth,
            density,
            current,
        })
    }

    /// Current velocity and depth gradient at elevation z and time t.
    pub fn current_at(&self, z: f64, time: f64) -> (Vector3<f64>, Vector3<f64>) {
        match &self.current {
            Some(c) => c.velocity_and_gradient(z, self.depth, time),
            None => (Vector3::zeros(), Vector3::zeros()),
        }
    }
}
