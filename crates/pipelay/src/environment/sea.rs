//! The sea: depth, water density, current, waves and the seabed.
use super::current::Current;
use super::seabed::Seabed;
use super::waves::Waves;
use crate::error::{non_negative, positive, Error, Result};
use nalgebra::{Vector2, Vector3};

/// Water depth, density, current and seabed. The surface is z = −depth (e3 down); the depth is measured from
/// z = 0, the level of the seabed end's reference.
#[derive(Debug, Clone, PartialEq)]
pub struct Sea {
    pub depth: f64,
    pub density: f64,
    pub current: Option<Current>,
    /// Contact with the seabed; `None`: the pipe passes through it.
    pub seabed: Option<Seabed>,
    /// The sea state, if any (resolved for the depth and gravity by the model).
    pub waves: Option<Waves>,
    /// The wind, if any: it acts on a vessel's hull ([`crate::vessel::hull_loads`]).
    pub wind: Option<super::wind::Wind>,
}

impl Sea {
    /// Checks and builds a sea.
    pub fn new(
        depth: f64,
        density: f64,
        current: Option<Current>,
        seabed: Option<Seabed>,
    ) -> Result<Self> {
        positive("depth", depth, "m")?;
        non_negative("density", density, "kg/m³")?;
        let sea = Sea {
            depth,
            density,
            current,
            seabed,
            waves: None,
            wind: None,
        };
        sea.check_seabed_below_surface(&[Vector2::zeros()])?;
        Ok(sea)
    }

    /// The same sea with wind.
    pub fn with_wind(mut self, wind: super::wind::Wind) -> Self {
        self.wind = Some(wind);
        self
    }

    /// The same sea with waves.
    pub fn with_waves(mut self, waves: Waves) -> Self {
        self.waves = Some(waves);
        self
    }

    /// Checks that the seabed lies below the surface at the horizontal points `points` (and everywhere on a
    /// grid).
    pub fn check_seabed_below_surface(&self, points: &[Vector2<f64>]) -> Result<()> {
        let Some(seabed) = &self.seabed else {
            return Ok(());
        };
        let shallowest = seabed.bathymetry.shallowest(points);
        if shallowest <= -self.depth {
            return Err(Error::input(
                "bathymetry",
                format!("a seabed reaching z = {shallowest} m"),
                format!(
                    "must lie below the sea surface z = −depth = {} m (e3 points down)",
                    -self.depth
                ),
            ));
        }
        Ok(())
    }

    /// Current velocity and depth gradient at elevation z and time t.
    pub fn current_at(&self, z: f64, time: f64) -> (Vector3<f64>, Vector3<f64>) {
        match &self.current {
            Some(c) => c.velocity_and_gradient(z, self.depth, time),
            None => (Vector3::zeros(), Vector3::zeros()),
        }
    }
}
