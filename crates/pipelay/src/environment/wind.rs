//! Wind: a mean speed and direction, with gusts from the NPD (Frøya) spectrum of ISO 19901-1 / DNV-RP-C205
//! (eq. 2.3.x there):
//!   S(f) = 320 (U₀/10)² (z/10)^0.45 / (1 + f̃ⁿ)^{5/(3n)},  f̃ = 172 f (z/10)^{2/3} (U₀/10)^{−3/4},  n = 0.468,
//! S in m²/s²/Hz, f in Hz, U₀ the 1-hour mean speed at z = 10 m above the surface. The gust is the sum of
//! harmonics u(t) = Σ_i √(2 S(f_i) Δf) cos(2π f_i t + φ_i) at equally spaced frequencies with seeded random
//! phases; the wind's velocity is (U₀ + u(t)) (cos β, sin β), β the direction it blows toward (from e1
//! toward e2, as the current and the waves).
use crate::error::{finite, Error, Result};
use nalgebra::Vector2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The largest mean wind speed accepted (m/s): well beyond any storm's 1-hour mean at 10 m.
pub const MAX_SPEED: f64 = 100.0;
/// Air density at 15 °C (kg/m³).
pub const AIR_DENSITY: f64 = 1.226;
/// The reference height of the speed (m).
const REFERENCE_HEIGHT: f64 = 10.0;
/// The gust's harmonics: count and frequency band (Hz): periods from about 17 min down to 2 s.
const GUST_COMPONENTS: usize = 512;
const LOWEST_FREQUENCY: f64 = 1e-3;
const HIGHEST_FREQUENCY: f64 = 0.5;

/// A gust spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GustSpectrum {
    /// The NPD (Frøya) spectrum.
    Npd,
}

/// The wind.
#[derive(Debug, Clone, PartialEq)]
pub struct Wind {
    /// 1-hour mean speed U₀ at 10 m (m/s).
    pub speed: f64,
    /// Direction β it blows toward (rad, from e1 toward e2).
    pub direction: f64,
    pub spectrum: Option<GustSpectrum>,
    pub seed: u64,
    /// The gust's harmonics: (amplitude (m/s), frequency (rad/s), phase (rad)).
    gust: Vec<(f64, f64, f64)>,
}

/// The NPD spectrum S(f) (m²/s²/Hz) for a 1-hour mean speed `speed` (m/s) at height z = 10 m.
pub fn npd_spectrum(speed: f64, frequency: f64) -> f64 {
    let n = 0.468;
    let z = REFERENCE_HEIGHT / 10.0;
    let f_tilde = 172.0 * frequency * z.powf(2.0 / 3.0) * (speed / 10.0).powf(-0.75);
    320.0 * (speed / 10.0).powi(2) * z.powf(0.45) / (1.0 + f_tilde.powf(n)).powf(5.0 / (3.0 * n))
}

impl Wind {
    /// A checked wind: speed ≥ 0 (m/s), finite direction (rad), spectrum "NPD" or none (a steady wind).
    pub fn new(speed: f64, direction: f64, spectrum: Option<&str>, seed: u64) -> Result<Self> {
        if !(speed.is_finite() && (0.0..=MAX_SPEED).contains(&speed)) {
            return Err(Error::input(
                "speed",
                speed,
                format!(
                    "must be a mean wind speed from 0 to {MAX_SPEED} m/s (1-hour mean at 10 m; the NPD \
                     spectrum is fitted below 40 m/s)"
                ),
            ));
        }
        finite("direction", &[direction])?;
        let spectrum = match spectrum {
            None => None,
            Some("NPD") => Some(GustSpectrum::Npd),
            Some(other) => {
                return Err(Error::input(
                    "spectrum",
                    format!("{other:?}"),
                    "must be \"NPD\" (ISO 19901-1) or None (a steady wind)",
                ))
            }
        };
        let mut gust = Vec::new();
        if spectrum.is_some() && speed > 0.0 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let df = (HIGHEST_FREQUENCY - LOWEST_FREQUENCY) / GUST_COMPONENTS as f64;
            for i in 0..GUST_COMPONENTS {
                let f = LOWEST_FREQUENCY + (i as f64 + 0.5) * df;
                let amplitude = (2.0 * npd_spectrum(speed, f) * df).sqrt();
                let phase = rng.random::<f64>() * std::f64::consts::TAU;
                gust.push((amplitude, std::f64::consts::TAU * f, phase));
            }
        }
        Ok(Wind {
            speed,
            direction,
            spectrum,
            seed,
            gust,
        })
    }

    /// The wind's speed at time t (s): the mean plus the gust (m/s).
    pub fn speed_at(&self, time: f64) -> f64 {
        self.speed
            + self
                .gust
                .iter()
                .map(|(a, w, phase)| a * (w * time + phase).cos())
                .sum::<f64>()
    }

    /// The wind's velocity (e1, e2) at time t (m/s).
    pub fn velocity(&self, time: f64) -> Vector2<f64> {
        let (sin, cos) = self.direction.sin_cos();
        self.speed_at(time) * Vector2::new(cos, sin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gust's variance is the spectrum's integral over the band; the mean is the mean speed.
    #[test]
    fn the_gust_has_the_spectrum_s_variance() {
        let wind = Wind::new(20.0, 0.3, Some("NPD"), 7).unwrap();
        let df = (HIGHEST_FREQUENCY - LOWEST_FREQUENCY) / GUST_COMPONENTS as f64;
        let variance: f64 = (0..GUST_COMPONENTS)
            .map(|i| npd_spectrum(20.0, LOWEST_FREQUENCY + (i as f64 + 0.5) * df) * df)
            .sum();
        let dt = 0.5;
        let samples: Vec<f64> = (0..2_000_000 / 100)
            .map(|k| wind.speed_at(k as f64 * dt * 7.4))
            .collect();
        let mean = samples.iter().sum::<f64>() / samples.len() as f64;
        let sample_variance =
            samples.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / samples.len() as f64;
        assert!((mean - 20.0).abs() < 0.05, "{mean}");
        assert!(
            (sample_variance / variance - 1.0).abs() < 0.05,
            "{sample_variance} vs {variance}"
        );
        // The NPD spectrum at 20 m/s: its turbulence intensity over the band is about 10 %.
        assert!((0.06..0.15).contains(&(variance.sqrt() / 20.0)));
        assert!(Wind::new(10.0, 0.0, Some("API"), 0)
            .unwrap_err()
            .to_string()
            .starts_with("spectrum"));
    }
}
