//! Waves: sea states as sums of linear (Airy) components and their kinematics at finite depth.
//!
//! A sea state is a list of components of amplitude a_i, circular frequency ω_i, direction β_i (the way
//! they travel, from e1 toward e2) and phase φ_i. In water of depth h each has the wave number k_i of the
//! dispersion relation ω² = g k tanh(k h). With s the height above the seabed level (s = −z, e3 down) and
//! θ_i = k_i(x cos β_i + y sin β_i) − ω_i t + φ_i (Airy; e.g. Faltinsen, Sea Loads, ch. 2):
//! - elevation (up) η = Σ a_i cos θ_i;
//! - horizontal velocity u_i = a_i ω_i cosh(k_i s)/sinh(k_i h) cos θ_i along (cos β_i, sin β_i);
//! - vertical velocity (up) w_i = a_i ω_i sinh(k_i s)/sinh(k_i h) sin θ_i;
//! - accelerations ∂u/∂t and ∂w/∂t.
//!
//! The sea may build up over a ramp time T_r: every amplitude is scaled by r(t) = 3τ² − 2τ³, τ = t/T_r clipped
//! to [0, 1] (velocity r u, acceleration r u̇ + ṙ u), so that a run starting from rest is not shaken at once.
//!
//! Above the mean level the profile is Wheeler-stretched, s′ = h s/(h + η), so that the surface η has the
//! kinematics the mean level has without it; above the surface the water is gone (zero kinematics).
//!
//! JONSWAP: S(ω) = α g² ω⁻⁵ exp(−5/4 (ω_p/ω)⁴) γ^r, r = exp(−(ω − ω_p)²/(2σ²ω_p²)), σ = 0.07 (ω ≤ ω_p)
//! or 0.09, scaled so that ∫S dω = H_s²/16 over the discretised band (DNV-RP-C205 §3.5.5). Components
//! a_i = √(2 S(ω_i) Δω) at one random frequency in each of N equal bins over [0.5, 4] ω_p (no repetition
//! period), random phases, and with spreading cos^{2s}((β − β₀)/2) a random direction each (single
//! summation: no phase locking), all from the seed.
//!
//! This file holds the sea states and their spectra; `kinematics` the components resolved in a depth and the
//! fluid's velocity and acceleration they make; `limits` the bounds of the theory (steepness, breaking).
// Indexing cannot go out of bounds here: windows of 2 and the first/last entries of spectra checked to hold
// at least 2 frequencies, and interpolation indices clamped to them.
#![allow(clippy::indexing_slicing)]
use crate::error::{finite, non_negative, positive, Error, Result};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod kinematics;
mod limits;

pub use kinematics::{ramp_factor, wave_number, Kinematics, Resolved, WaveField, NEGLIGIBLE};
use limits::check_steepness;
pub use limits::steepness_limit;

/// One linear wave component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveComponent {
    /// Amplitude a (m).
    pub amplitude: f64,
    /// Circular frequency ω (rad/s).
    pub frequency: f64,
    /// Direction of travel β (rad, from e1 toward e2).
    pub direction: f64,
    /// Phase φ (rad).
    pub phase: f64,
}

/// A sea state: the components, whatever spectrum they came from, and the time it builds up over.
#[derive(Debug, Clone, PartialEq)]
pub struct Waves {
    pub components: Vec<WaveComponent>,
    /// Ramp time T_r (s): the sea grows smoothly from calm over [0, T_r]; 0: at full height from t = 0.
    pub ramp: f64,
}

/// Largest spreading exponent s of cos^2s.
pub const MAX_SPREADING: f64 = 1000.0;

/// Most components a sea state may have (each costs every element a cosh, sinh, cos and sin per step).
pub const MAX_COMPONENTS: usize = 100_000;

impl Waves {
    /// A regular (Airy) wave of crest-to-trough `height` (m) and `period` (s) travelling along `direction`.
    pub fn regular(height: f64, period: f64, direction: f64) -> Result<Self> {
        positive("height", height, "m")?;
        positive("period", period, "s")?;
        finite("direction", &[direction])?;
        Ok(Waves {
            components: vec![WaveComponent {
                amplitude: 0.5 * height,
                frequency: std::f64::consts::TAU / period,
                direction,
                phase: 0.0,
            }],
            ramp: 0.0,
        })
    }

    /// The same sea building up over `ramp` seconds (≥ 0).
    pub fn with_ramp(mut self, ramp: f64) -> Result<Self> {
        non_negative("ramp", ramp, "s")?;
        self.ramp = ramp;
        Ok(self)
    }

    /// The period 2π/ω of the largest component (s): a regular wave's period, a random sea's peak.
    pub fn peak_period(&self) -> f64 {
        self.components
            .iter()
            .max_by(|a, b| a.amplitude.total_cmp(&b.amplitude))
            .map_or(0.0, |c| std::f64::consts::TAU / c.frequency)
    }

    /// A JONSWAP sea state of significant height `hs` (m), peak period `tp` (s) and peak enhancement `gamma`,
    /// mean direction `direction` (rad), cos^{2s} spreading with exponent `spreading` (None: long-crested),
    /// `components` components drawn from `seed`.
    pub fn jonswap(
        hs: f64,
        tp: f64,
        gamma: f64,
        direction: f64,
        spreading: Option<f64>,
        seed: u64,
        components: usize,
    ) -> Result<Self> {
        positive("hs", hs, "m")?;
        positive("tp", tp, "s")?;
        if !(gamma.is_finite() && (1.0..=10.0).contains(&gamma)) {
            return Err(Error::input(
                "gamma",
                gamma,
                "must be a peak enhancement factor from 1 (Pierson–Moskowitz) to 10",
            ));
        }
        check_steepness(hs, tp)?;
        let peak = std::f64::consts::TAU / tp;
        let density = |omega: f64| {
            let sigma = if omega <= peak { 0.07 } else { 0.09 };
            let r = (-(omega - peak).powi(2) / (2.0 * sigma * sigma * peak * peak)).exp();
            omega.powi(-5) * (-1.25 * (peak / omega).powi(4)).exp() * gamma.powf(r)
        };
        Self::from_density(
            density,
            (0.5 * peak, 4.0 * peak),
            hs,
            direction,
            spreading,
            seed,
            components,
        )
    }

    /// A sea state from a user spectrum: `frequencies` ω (rad/s, increasing) and `densities` S(ω) (m²·s/rad)
    /// interpolated linearly; `components` components over its band, drawn from `seed`.
    pub fn from_spectrum(
        frequencies: &[f64],
        densities: &[f64],
        direction: f64,
        spreading: Option<f64>,
        seed: u64,
        components: usize,
    ) -> Result<Self> {
        if frequencies.len() < 2 || frequencies.len() != densities.len() {
            return Err(Error::input(
                "frequencies",
                format!(
                    "{} frequencies, {} densities",
                    frequencies.len(),
                    densities.len()
                ),
                "must be at least 2 frequencies with one density each",
            ));
        }
        finite("frequencies", frequencies)?;
        finite("densities", densities)?;
        if frequencies.windows(2).any(|w| w[1] <= w[0]) || frequencies[0] <= 0.0 {
            return Err(Error::input(
                "frequencies",
                format!("{frequencies:?}"),
                "must be increasing and > 0 (rad/s)",
            ));
        }
        if let Some(d) = densities.iter().find(|d| **d < 0.0) {
            return Err(Error::input("densities", d, "must be >= 0 (m²·s/rad)"));
        }
        let m0: f64 = frequencies
            .windows(2)
            .zip(densities.windows(2))
            .map(|(w, s)| 0.5 * (s[0] + s[1]) * (w[1] - w[0]))
            .sum();
        if m0 <= 0.0 {
            return Err(Error::input(
                "densities",
                "all zero",
                "must hold some energy",
            ));
        }
        let density = |omega: f64| {
            let i = frequencies
                .partition_point(|w| *w <= omega)
                .clamp(1, frequencies.len() - 1);
            let (w0, w1) = (frequencies[i - 1], frequencies[i]);
            let t = ((omega - w0) / (w1 - w0)).clamp(0.0, 1.0);
            densities[i - 1] + t * (densities[i] - densities[i - 1])
        };
        let band = (frequencies[0], frequencies[frequencies.len() - 1]);
        Self::from_density(
            density,
            band,
            4.0 * m0.sqrt(),
            direction,
            spreading,
            seed,
            components,
        )
    }

    /// Components of the spectrum shape `density` over `band`, scaled to significant height `hs`.
    fn from_density(
        density: impl Fn(f64) -> f64,
        band: (f64, f64),
        hs: f64,
        direction: f64,
        spreading: Option<f64>,
        seed: u64,
        components: usize,
    ) -> Result<Self> {
        finite("direction", &[direction])?;
        if components == 0 || components > MAX_COMPONENTS {
            return Err(Error::input(
                "components",
                components,
                format!("must be an integer from 1 to {MAX_COMPONENTS}"),
            ));
        }
        if let Some(s) = spreading {
            // Sampling cos^2s by rejection accepts about √(4/(πs)) of the tries; beyond s = 1000 the sea is
            // long-crested to a tenth of a degree anyway.
            if !(s.is_finite() && s > 0.0 && s <= MAX_SPREADING) {
                return Err(Error::input(
                    "spreading",
                    s,
                    format!("must be the exponent s of cos^2s in (0, {MAX_SPREADING}] (None: long-crested)"),
                ));
            }
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let width = (band.1 - band.0) / components as f64;
        let mut list = crate::memory::vec_with_capacity(components, "the wave components")?;
        for i in 0..components {
            let frequency = band.0 + width * (i as f64 + rng.random::<f64>());
            let phase = std::f64::consts::TAU * rng.random::<f64>();
            let direction = match spreading {
                Some(s) => direction + spread_angle(&mut rng, s),
                None => direction,
            };
            list.push(WaveComponent {
                amplitude: (2.0 * density(frequency) * width).sqrt(),
                frequency,
                direction,
                phase,
            });
        }
        // Scale to the asked significant height: Σ a²/2 = m0 = hs²/16.
        let m0: f64 = list.iter().map(|c| 0.5 * c.amplitude * c.amplitude).sum();
        if m0.is_nan() || m0 <= 0.0 {
            return Err(Error::input(
                "hs",
                hs,
                "gives a spectrum without energy in its band",
            ));
        }
        let scale = 0.25 * hs / m0.sqrt();
        list.iter_mut().for_each(|c| c.amplitude *= scale);
        Ok(Waves {
            components: list,
            ramp: 0.0,
        })
    }

    /// The significant height 4√m0 of the components (m).
    pub fn significant_height(&self) -> f64 {
        4.0 * self
            .components
            .iter()
            .map(|c| 0.5 * c.amplitude * c.amplitude)
            .sum::<f64>()
            .sqrt()
    }
}

/// A direction offset from cos^{2s}(Δ/2) on (−π, π], by rejection.
fn spread_angle(rng: &mut ChaCha8Rng, s: f64) -> f64 {
    loop {
        let angle = std::f64::consts::PI * (2.0 * rng.random::<f64>() - 1.0);
        if rng.random::<f64>() <= (0.5 * angle).cos().powf(2.0 * s) {
            return angle;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;
    /// The spectrum's significant height is the asked one, and a long record's 4σ(η) is within 3 % of it.
    #[test]
    fn jonswap_realises_its_significant_height() {
        let waves = Waves::jonswap(2.5, 9.0, 3.3, 0.0, None, 1, 400).unwrap();
        assert!((waves.significant_height() - 2.5).abs() < 1e-12);
        let field = WaveField::new(&waves, 800.0, G).unwrap();
        let samples: Vec<f64> = (0..36000)
            .map(|i| field.elevation(0.0, 0.0, 0.5 * i as f64))
            .collect();
        let mean = samples.iter().sum::<f64>() / samples.len() as f64;
        let variance =
            samples.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / samples.len() as f64;
        let realised = 4.0 * variance.sqrt();
        assert!((realised - 2.5).abs() < 0.03 * 2.5, "{realised}");
    }

    #[test]
    fn bad_sea_states_are_refused() {
        assert!(Waves::jonswap(0.0, 9.0, 3.3, 0.0, None, 0, 100).is_err());
        assert!(Waves::jonswap(2.0, f64::NAN, 3.3, 0.0, None, 0, 100).is_err());
        assert!(Waves::jonswap(2.0, 9.0, 0.5, 0.0, None, 0, 100).is_err());
        assert!(Waves::jonswap(2.0, 9.0, 3.3, 0.0, None, 0, 0).is_err());
        assert!(Waves::regular(-1.0, 9.0, 0.0).is_err());
        assert!(Waves::jonswap(2.0, 9.0, 3.3, 0.0, Some(1e300), 0, 10).is_err());
        assert!(Waves::jonswap(2.0, 9.0, 3.3, 0.0, Some(1000.0), 0, 10).is_ok());
        assert!(Waves::from_spectrum(&[0.5, 0.4], &[1.0, 1.0], 0.0, None, 0, 10).is_err());
        assert!(Waves::from_spectrum(&[0.4, 0.5], &[1.0, f64::NAN], 0.0, None, 0, 10).is_err());
    }

    /// Seas beyond the theory are refused, naming the limit: a regular wave of H/L ≈ 1.3, one higher than the
    /// depth-limited 0.78 h, and JONSWAP seas steeper than DNV-RP-C205's S_p limits; the limits themselves
    /// are accepted.
    #[test]
    fn seas_beyond_breaking_or_steepness_are_refused() {
        let field = |waves: Waves, depth: f64| WaveField::new(&waves, depth, 9.81);
        // H 50 m at T 5 s: L = 39 m in deep water.
        let message = field(Waves::regular(50.0, 5.0, 0.0).unwrap(), 800.0)
            .unwrap_err()
            .to_string();
        assert!(
            message.starts_with("waves: must not break") && message.contains("Miche"),
            "{message}"
        );
        // The deep-water limit H = L/7 (L = gT²/2π = 39.03 m at 5 s): 5.57 m breaks at 1.01 of it, not 0.99.
        let limit = 9.81 * 25.0 / std::f64::consts::TAU / 7.0;
        assert!(field(Waves::regular(0.99 * limit, 5.0, 0.0).unwrap(), 800.0).is_ok());
        assert!(field(Waves::regular(1.01 * limit, 5.0, 0.0).unwrap(), 800.0).is_err());
        // In 10 m of water a 9 m, 20 s swell exceeds 0.78 h = 7.8 m.
        assert!(field(Waves::regular(9.0, 20.0, 0.0).unwrap(), 10.0).is_err());
        assert!(field(Waves::regular(7.0, 20.0, 0.0).unwrap(), 10.0).is_ok());
        // JONSWAP Hs 30 m at Tp 4 s: S_p = 1.2; at Tp 8 s the limit 1/15 is Hs = 6.66 m, at 15 s 1/25: 14.05 m.
        let error = Waves::jonswap(30.0, 4.0, 3.3, 0.0, None, 0, 10)
            .unwrap_err()
            .to_string();
        assert!(
            error.starts_with("hs: must keep the sea within DNV-RP-C205"),
            "{error}"
        );
        let largest = |tp: f64| steepness_limit(tp) * 9.81 * tp * tp / std::f64::consts::TAU;
        assert!((largest(8.0) - 6.662).abs() < 1e-3 && (largest(15.0) - 14.05).abs() < 1e-2);
        for tp in [6.0, 8.0, 11.5, 15.0, 20.0] {
            assert!(Waves::jonswap(0.999 * largest(tp), tp, 3.3, 0.0, None, 0, 10).is_ok());
            assert!(Waves::jonswap(1.001 * largest(tp), tp, 3.3, 0.0, None, 0, 10).is_err());
        }
        // A sea of Hs 6 m in 5 m of water breaks.
        let sea = Waves::jonswap(6.0, 12.0, 3.3, 0.0, None, 0, 50).unwrap();
        assert!(field(sea, 5.0).unwrap_err().to_string().contains("0.78 h"));
    }
}
