//! A steady current: a velocity profile over depth that starts at a given time.
// Indexing cannot go out of bounds here: Profile indices found by searching the validated, increasing depths (at least 2, as many as velocities).
#![allow(clippy::indexing_slicing)]
use crate::error::{finite, Error, Result};
use nalgebra::Vector3;

/// How the current velocity varies with depth.
#[derive(Debug, Clone, PartialEq)]
pub enum CurrentProfile {
    /// The same velocity at every depth (m/s, in e).
    Uniform(Vector3<f64>),
    /// Linear shear: `surface` at the sea surface, zero at the seabed end's depth (z = 0).
    Linear { surface: Vector3<f64> },
    /// A table of depths below the surface (m, increasing) and velocities, interpolated linearly and held
    /// constant beyond its ends.
    Table {
        depths: Vec<f64>,
        velocities: Vec<Vector3<f64>>,
    },
}

/// A steady current that starts at `start` (s).
#[derive(Debug, Clone, PartialEq)]
pub struct Current {
    pub profile: CurrentProfile,
    pub start: f64,
}

impl Current {
    /// Checks and builds a current.
    pub fn new(profile: CurrentProfile, start: f64) -> Result<Self> {
        finite("start", &[start])?;
        match &profile {
            CurrentProfile::Uniform(v) => finite("velocity", v.as_slice())?,
            CurrentProfile::Linear { surface } => finite("surface_velocity", surface.as_slice())?,
            CurrentProfile::Table { depths, velocities } => {
                if depths.is_empty() || depths.len() != velocities.len() {
                    return Err(Error::input(
                        "depths",
                        format!(
                            "{} depths for {} velocities",
                            depths.len(),
                            velocities.len()
                        ),
                        "need at least one depth and one velocity (3,) per depth",
                    ));
                }
                finite("depths", depths)?;
                for v in velocities {
                    finite("velocities", v.as_slice())?;
                }
                if depths.windows(2).any(|w| w[1] <= w[0]) {
                    return Err(Error::input(
                        "depths",
                        format!("{depths:?}"),
                        "must increase strictly (m below the surface)",
                    ));
                }
            }
        }
        Ok(Current { profile, start })
    }

    /// Velocity U(z) and its depth gradient dU/dz at elevation z (e3 down), for a sea of depth `depth`,
    /// at time `time` (zero before `start`).
    pub fn velocity_and_gradient(
        &self,
        z: f64,
        depth: f64,
        time: f64,
    ) -> (Vector3<f64>, Vector3<f64>) {
        if time < self.start {
            return (Vector3::zeros(), Vector3::zeros());
        }
        match &self.profile {
            CurrentProfile::Uniform(v) => (*v, Vector3::zeros()),
            CurrentProfile::Linear { surface } => {
                let fraction = -z / depth;
                if (0.0..=1.0).contains(&fraction) {
                    (surface * fraction, -surface / depth)
                } else {
                    (surface * fraction.clamp(0.0, 1.0), Vector3::zeros())
                }
            }
            CurrentProfile::Table { depths, velocities } => {
                let below_surface = z + depth;
                let last = depths.len() - 1;
                if below_surface <= depths[0] {
                    return (velocities[0], Vector3::zeros());
                }
                if below_surface >= depths[last] {
                    return (velocities[last], Vector3::zeros());
                }
                let i = depths.partition_point(|&d| d <= below_surface) - 1;
                let span = depths[i + 1] - depths[i];
                let slope = (velocities[i + 1] - velocities[i]) / span;
                (velocities[i] + slope * (below_surface - depths[i]), slope)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_profile_interpolates_and_holds_its_ends() {
        let current = Current::new(
            CurrentProfile::Table {
                depths: vec![0.0, 100.0],
                velocities: vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(0.0, 0.0, 0.0)],
            },
            5.0,
        )
        .expect("valid current");
        let (v, g) = current.velocity_and_gradient(-750.0, 800.0, 6.0);
        assert!((v.x - 0.5).abs() < 1e-15 && (g.x + 0.01).abs() < 1e-15);
        assert_eq!(
            current.velocity_and_gradient(-300.0, 800.0, 6.0).0,
            Vector3::zeros()
        );
        assert_eq!(
            current.velocity_and_gradient(-790.0, 800.0, 4.0).0,
            Vector3::zeros()
        );
    }
}
