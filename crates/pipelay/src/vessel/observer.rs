//! Fossen's nonlinear passive observer (Fossen & Strand 1999; Fossen 2021, §13.4) on noisy measurements of
//! the vessel's position and heading y = (x, y, ψ) + noise: it separates the wave-frequency motion from the
//! low-frequency one, estimates the slowly varying force b (the pipe, wind, current and drift the model does not
//! know) and the low-frequency velocity ν̂, in surge, sway and yaw:
//!   ξ̂̇ = A_w ξ̂ + K₁ ỹ,                    ỹ = y − η̂ − C_w ξ̂,
//!   η̂̇ = R(ψ_y) ν̂ + K₂ ỹ,
//!   b̂̇ = −T⁻¹ b̂ + K₃ ỹ,
//!   M ν̂̇ = −D ν̂ + R(ψ_y)ᵀ b̂ + τ + R(ψ_y)ᵀ K₄ ỹ,
//! with the wave model A_w = [0 I; −Ω² −2ΛΩ], C_w = [0 I] (Ω = ω₀ I at the sea's peak frequency, Λ = λ I) and
//! Fossen's gains K₁ = [−2(ζ_n − λ)(ω_c/ω₀) I; 2ω₀(ζ_n − λ) I], K₂ = ω_c I (a notch at ω₀ and a cut-off at ω_c),
//! K₄ = 0.1 s⁻² diag(M), K₃ = 0.1 s⁻¹ K₄, T = 1000 s; these satisfy the passivity condition
//! 1/T ≪ K₃/K₄ < ω₀ < ω_c for peak periods up to 60 s.
// Indexing cannot go out of bounds here: 3-vectors of surge, sway, yaw indexed by constants.
#![allow(clippy::indexing_slicing)]
use crate::error::{finite, Error, Result};
use nalgebra::{Matrix3, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// The notch's relative damping ζ_n, the wave model's λ and the cut-off ω_c/ω₀ (Fossen 2021, Example 13.x).
const NOTCH_DAMPING: f64 = 1.0;
const WAVE_DAMPING: f64 = 0.1;
const CUTOFF_RATIO: f64 = 1.2255;
/// K₄ = 0.1 s⁻² diag(M), K₃ = 0.1 s⁻¹ K₄, bias time constant T (s).
const VELOCITY_GAIN: f64 = 0.1;
const BIAS_GAIN: f64 = 0.1;
const BIAS_TIME: f64 = 1000.0;
/// The longest integration step of the observer (s): its fastest mode is ω_c ≈ 1.2 ω₀.
const MAX_STEP: f64 = 0.05;

/// What the observer is given: the measurement noise and its seed, and the sea's peak period it notches.
#[derive(Debug, Clone, PartialEq)]
pub struct ObserverSettings {
    /// Standard deviations of the measured x, y (m) and ψ (rad).
    pub noise: Vector3<f64>,
    pub seed: u64,
    /// The wave model's peak period (s); `None`: the sea's peak period when the run starts (else 10 s).
    pub wave_period: Option<f64>,
}

impl ObserverSettings {
    /// Checked settings.
    pub fn new(noise: Vector3<f64>, seed: u64, wave_period: Option<f64>) -> Result<Self> {
        finite("noise", noise.as_slice())?;
        if noise.iter().any(|v| *v < 0.0) {
            return Err(Error::input(
                "noise",
                format!("{:?}", noise.as_slice()),
                "must hold standard deviations ≥ 0 (m, m, rad)",
            ));
        }
        if let Some(period) = wave_period {
            if !(period.is_finite() && period > 0.0 && period <= 60.0) {
                return Err(Error::input(
                    "wave_period",
                    period,
                    "must be a peak period in (0, 60] s",
                ));
            }
        }
        Ok(ObserverSettings {
            noise,
            seed,
            wave_period,
        })
    }
}

/// The observer's state and its gains.
#[derive(Debug, Clone)]
pub struct PassiveObserver {
    /// ξ̂ = (ξ̂₁, ξ̂₂): the wave model's states; η̂_w = ξ̂₂.
    wave: Vector6<f64>,
    /// η̂ = (x̂, ŷ, ψ̂): the low-frequency pose.
    pub pose: Vector3<f64>,
    /// b̂: the slowly varying force, earth frame (N, N, N·m).
    pub bias: Vector3<f64>,
    /// ν̂ = (û, v̂, r̂): the low-frequency velocity, body frame.
    pub velocity: Vector3<f64>,
    mass_inverse: Matrix3<f64>,
    damping: Matrix3<f64>,
    peak: f64,
    k4: Vector3<f64>,
    noise: Vector3<f64>,
    rng: ChaCha8Rng,
}

/// R(ψ) in the horizontal plane.
fn rotation(psi: f64) -> Matrix3<f64> {
    let (s, c) = psi.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// An angle in (−π, π].
fn wrap(angle: f64) -> f64 {
    super::thrusters::wrap(angle)
}

impl PassiveObserver {
    /// An observer for a vessel of surge–sway–yaw mass `mass` and damping `damping`, started at the pose
    /// `pose` and velocity `velocity` (its wave states and bias zero), notching the peak period `period` (s).
    pub fn new(
        settings: &ObserverSettings,
        mass: &Matrix3<f64>,
        damping: &Matrix3<f64>,
        period: f64,
        pose: Vector3<f64>,
        velocity: Vector3<f64>,
    ) -> Result<Self> {
        let mass_inverse = mass.try_inverse().ok_or_else(|| {
            Error::input(
                "M",
                "a singular surge–sway–yaw block",
                "must be invertible for the observer",
            )
        })?;
        Ok(PassiveObserver {
            wave: Vector6::zeros(),
            pose,
            bias: Vector3::zeros(),
            velocity,
            mass_inverse,
            damping: *damping,
            peak: std::f64::consts::TAU / period,
            k4: VELOCITY_GAIN * mass.diagonal(),
            noise: settings.noise,
            rng: ChaCha8Rng::seed_from_u64(settings.seed),
        })
    }

    /// A measurement of the true pose (x, y, ψ): the pose plus Gaussian noise of the settings' deviations.
    pub fn measure(&mut self, truth: &Vector3<f64>) -> Vector3<f64> {
        let mut measured = *truth;
        for k in 0..3 {
            if self.noise[k] > 0.0 {
                if let Ok(normal) = Normal::new(0.0, self.noise[k]) {
                    measured[k] += normal.sample(&mut self.rng);
                }
            }
        }
        measured
    }

    /// The wave-frequency estimate η̂_w (m, m, rad).
    pub fn wave_frequency(&self) -> Vector3<f64> {
        self.wave.fixed_rows::<3>(3).into_owned()
    }

    /// Time derivatives of (ξ̂, η̂, b̂, ν̂) for the measurement y and thrust τ (surge, sway, yaw).
    fn rates(
        &self,
        state: &(Vector6<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>),
        measured: &Vector3<f64>,
        tau: &Vector3<f64>,
    ) -> (Vector6<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let (wave, pose, bias, velocity) = state;
        let w0 = self.peak;
        let wc = CUTOFF_RATIO * w0;
        let mut error = measured - pose - wave.fixed_rows::<3>(3);
        error[2] = wrap(error[2]);
        let k1_low = -2.0 * (NOTCH_DAMPING - WAVE_DAMPING) * wc / w0;
        let k1_high = 2.0 * w0 * (NOTCH_DAMPING - WAVE_DAMPING);
        let mut wave_rate = Vector6::zeros();
        for k in 0..3 {
            wave_rate[k] = wave[k + 3] + k1_low * error[k];
            wave_rate[k + 3] =
                -w0 * w0 * wave[k] - 2.0 * WAVE_DAMPING * w0 * wave[k + 3] + k1_high * error[k];
        }
        let r = rotation(measured[2]);
        let pose_rate = r * velocity + wc * error;
        let bias_rate = -bias / BIAS_TIME + BIAS_GAIN * self.k4.component_mul(&error);
        let force = -self.damping * velocity
            + r.transpose() * bias
            + tau
            + r.transpose() * self.k4.component_mul(&error);
        (wave_rate, pose_rate, bias_rate, self.mass_inverse * force)
    }

    /// Advances the observer over `dt` (s) with the measurement `measured` and the thrust `tau` (surge, sway,
    /// yaw; body frame) held over it: classical Runge–Kutta in substeps of at most 0.05 s.
    pub fn advance(&mut self, measured: &Vector3<f64>, tau: &Vector3<f64>, dt: f64) {
        let count = (dt / MAX_STEP).ceil().max(1.0) as usize;
        let h = dt / count as f64;
        for _ in 0..count {
            let y0 = (self.wave, self.pose, self.bias, self.velocity);
            let add = |y: &(Vector6<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>),
                       k: &(Vector6<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>),
                       s: f64| {
                (y.0 + s * k.0, y.1 + s * k.1, y.2 + s * k.2, y.3 + s * k.3)
            };
            let k1 = self.rates(&y0, measured, tau);
            let k2 = self.rates(&add(&y0, &k1, 0.5 * h), measured, tau);
            let k3 = self.rates(&add(&y0, &k2, 0.5 * h), measured, tau);
            let k4 = self.rates(&add(&y0, &k3, h), measured, tau);
            let sum = |a: &Vector6<f64>, b: &Vector6<f64>, c: &Vector6<f64>, d: &Vector6<f64>| {
                (a + 2.0 * b + 2.0 * c + d) * (h / 6.0)
            };
            let sum3 = |a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>, d: &Vector3<f64>| {
                (a + 2.0 * b + 2.0 * c + d) * (h / 6.0)
            };
            self.wave += sum(&k1.0, &k2.0, &k3.0, &k4.0);
            self.pose += sum3(&k1.1, &k2.1, &k3.1, &k4.1);
            self.bias += sum3(&k1.2, &k2.2, &k3.2, &k4.2);
            self.velocity += sum3(&k1.3, &k2.3, &k3.3, &k4.3);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A vessel of the OSV's surge–sway–yaw mass held at rest while it moves in a wave of 9 s and 1 m in
    /// surge plus a 2 m offset: the estimate finds the offset and leaves the wave out.
    #[test]
    fn the_observer_filters_the_wave_frequency_motion() {
        let mass = Matrix3::from_diagonal(&Vector3::new(5.6e6, 7.0e6, 3.5e9));
        let damping = Matrix3::from_diagonal(&Vector3::new(5.6e4, 7.0e4, 3.5e9));
        let settings = ObserverSettings::new(Vector3::new(0.1, 0.1, 0.001), 3, None).unwrap();
        let mut observer = PassiveObserver::new(
            &settings,
            &mass,
            &damping,
            9.0,
            Vector3::zeros(),
            Vector3::zeros(),
        )
        .unwrap();
        let dt = 0.1;
        let w = std::f64::consts::TAU / 9.0;
        let (mut squares, mut count) = (0.0, 0.0);
        let mut wave_error: f64 = 0.0;
        for step in 0..20000 {
            let t = step as f64 * dt;
            let truth = Vector3::new(2.0 + (w * t).cos(), 0.0, 0.0);
            let measured = observer.measure(&truth);
            observer.advance(&measured, &Vector3::zeros(), dt);
            if t > 1500.0 {
                squares += (observer.pose.x - 2.0).powi(2);
                count += 1.0;
                let wave = (w * (t + dt)).cos();
                wave_error = wave_error.max((observer.wave_frequency().x - wave).abs());
            }
        }
        // The notch passes λ/ζ_n = 1/10 of the wave at ω₀: the wave's 1 m (RMS 0.71 m) in surge reaches the
        // low-frequency estimate as about 7 cm RMS, and the wave-frequency estimate holds the rest.
        let rms = (squares / count).sqrt();
        println!("low-frequency RMS error {rms:.4} m, wave-frequency error {wave_error:.4} m");
        assert!(rms < 0.1, "rms {rms}");
        assert!(wave_error < 0.3, "wave {wave_error}");
    }
}
