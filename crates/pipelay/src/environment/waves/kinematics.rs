//! The components of a sea state resolved in a depth (the dispersion relation) and the kinematics they make:
//! Airy velocity, acceleration and velocity gradient with the build-up ramp and Wheeler stretching, summed four
//! components at a time (see the parent module's formulas).
// Indexing cannot go out of bounds here: lanes of four filled from slices checked to fit.
#![allow(clippy::indexing_slicing)]
use super::limits::check_breaking;
use super::Waves;
use crate::error::{non_negative, positive, Error, Result};
use nalgebra::{Matrix3, Vector3};
use wide::f64x4;

/// The wave number k of ω in depth h: ω² = g k tanh(k h), by Newton from the deep-water value.
pub fn wave_number(frequency: f64, depth: f64, gravity: f64) -> f64 {
    let deep = frequency * frequency / gravity;
    // Shallow start (k = ω/√(gh)) where that is larger: Newton on f(k) = g k tanh(kh) − ω² is monotone
    // from above.
    let mut k = deep.max(frequency / (gravity * depth).sqrt());
    for _ in 0..100 {
        let t = (k * depth).tanh();
        let f = gravity * k * t - frequency * frequency;
        let df = gravity * (t + k * depth * (1.0 - t * t));
        let step = f / df;
        k -= step;
        if step.abs() <= 1e-15 * k {
            break;
        }
    }
    k
}

/// Components whose phases are computed together ([`WaveField::kinematics`]).
const LANES: usize = 4;

/// `value` of each of up to [`LANES`] items (components or their phases), zero in the lanes past the last.
fn lanes<T>(items: &[T], value: impl Fn(&T) -> f64) -> f64x4 {
    let mut array = [0.0; LANES];
    for (entry, c) in array.iter_mut().zip(items) {
        *entry = value(c);
    }
    f64x4::new(array)
}

thread_local! {
    /// Each component's (sin θ, cos θ) at the point whose kinematics are being summed: one buffer a thread,
    /// grown once.
    static PHASES: std::cell::RefCell<Vec<(f64, f64)>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Fluid velocity and acceleration at a point and its velocity's gradient ∂u/∂x (all in e).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Kinematics {
    pub velocity: Vector3<f64>,
    pub acceleration: Vector3<f64>,
    pub velocity_gradient: Matrix3<f64>,
}

/// A resolved component: its wave number and direction cosines in this depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resolved {
    /// Amplitude a (m).
    pub amplitude: f64,
    /// Circular frequency ω (rad/s).
    pub frequency: f64,
    /// Wave number k (rad/m).
    pub number: f64,
    /// 1/(1 − e^{−2kh}) in the field's depth h.
    profile_scale: f64,
    /// The depth below the (stretched) surface beyond which the component's velocity, acceleration and
    /// velocity gradient are below [`NEGLIGIBLE`] of the sea's (m; 0: negligible everywhere).
    negligible_below: f64,
    /// Direction of travel β (rad) and its cosine and sine.
    pub direction: f64,
    pub cos: f64,
    pub sin: f64,
    /// Phase φ (rad).
    pub phase: f64,
}

impl Resolved {
    /// The phase angle θ = k(x cos β + y sin β) − ωt + φ at (x, y) and time t.
    pub fn angle(&self, x: f64, y: f64, time: f64) -> f64 {
        self.number * (x * self.cos + y * self.sin) - self.frequency * time + self.phase
    }
}

/// The smooth build-up r(t) = 3τ² − 2τ³ (τ = t/T_r clipped to [0, 1]) and its rate ṙ (1/s); 1 and 0
/// without a ramp.
pub fn ramp_factor(time: f64, ramp: f64) -> (f64, f64) {
    if ramp <= 0.0 {
        return (1.0, 0.0);
    }
    let (r, rate) = crate::smooth::smoothstep(time / ramp);
    (r, rate / ramp)
}

/// A sea state in water of a given depth: what the pipe and the vessel see.
#[derive(Debug, Clone, PartialEq)]
pub struct WaveField {
    components: Vec<Resolved>,
    depth: f64,
    ramp: f64,
    /// Σ a: no surface elevation exceeds it.
    surface_bound: f64,
}

/// A component is left out of the kinematics at a point where each of its velocity, acceleration and velocity
/// gradient, a ω^j k^l e^{−k d} at the depth d below the surface, is below this fraction of the sea's own
/// scale (Σ a ω, Σ a ω², Σ a ω k over the components): all those left out at a point add up to less than
/// 2e-5 of the scale (measured: 6.6e-6 for a 300-component JONSWAP sea; the tests).
pub const NEGLIGIBLE: f64 = 1e-6;

/// The depth below which each component is negligible ([`NEGLIGIBLE`]), for components of the given
/// amplitudes, frequencies and wave numbers.
fn negligible_depths(components: &mut [Resolved]) {
    let scale = |weight: &dyn Fn(&Resolved) -> f64| components.iter().map(weight).sum::<f64>();
    let velocity = |c: &Resolved| c.amplitude * c.frequency;
    let acceleration = |c: &Resolved| c.amplitude * c.frequency * c.frequency;
    let gradient = |c: &Resolved| c.amplitude * c.frequency * c.number;
    let scales = [scale(&velocity), scale(&acceleration), scale(&gradient)];
    for c in components.iter_mut() {
        let share = [velocity(c), acceleration(c), gradient(c)]
            .iter()
            .zip(&scales)
            .map(|(own, total)| if *total > 0.0 { own / total } else { 0.0 })
            .fold(0.0, f64::max);
        // a e^{−k d} < NEGLIGIBLE · scale beyond d = ln(share / NEGLIGIBLE) / k.
        c.negligible_below = if share > NEGLIGIBLE && c.number > 0.0 {
            (share / NEGLIGIBLE).ln() / c.number
        } else {
            0.0
        };
    }
}

impl WaveField {
    /// The waves resolved in water of `depth` (m) under gravity `gravity` (m/s²).
    pub fn new(waves: &Waves, depth: f64, gravity: f64) -> Result<Self> {
        positive("depth", depth, "m")?;
        non_negative("gravity", gravity, "m/s²")?;
        if gravity == 0.0 {
            return Err(Error::input(
                "gravity",
                0.0,
                "must be > 0 for waves (they are gravity waves)",
            ));
        }
        let mut components: Vec<Resolved> = waves
            .components
            .iter()
            .map(|c| {
                let number = wave_number(c.frequency, depth, gravity);
                Resolved {
                    amplitude: c.amplitude,
                    frequency: c.frequency,
                    number,
                    profile_scale: 1.0 / (1.0 - (-2.0 * number * depth).exp()),
                    negligible_below: f64::INFINITY,
                    direction: c.direction,
                    cos: c.direction.cos(),
                    sin: c.direction.sin(),
                    phase: c.phase,
                }
            })
            .collect();
        check_breaking(waves, &components, depth)?;
        negligible_depths(&mut components);
        // Deepest-reaching first, so that a point's sum stops at the first component negligible there.
        components.sort_by(|a, b| b.negligible_below.total_cmp(&a.negligible_below));
        let surface_bound = components.iter().map(|c| c.amplitude).sum();
        Ok(WaveField {
            components,
            depth,
            ramp: waves.ramp,
            surface_bound,
        })
    }

    /// The components resolved in this depth.
    pub fn components(&self) -> &[Resolved] {
        &self.components
    }

    /// The ramp time T_r (s).
    pub fn ramp(&self) -> f64 {
        self.ramp
    }

    /// Surface elevation η (m, up) at (x, y) and time t.
    pub fn elevation(&self, x: f64, y: f64, time: f64) -> f64 {
        let (ramp, _) = ramp_factor(time, self.ramp);
        ramp * self
            .components
            .iter()
            .map(|c| c.amplitude * c.angle(x, y, time).cos())
            .sum::<f64>()
    }

    /// Velocity, acceleration and velocity gradient of the water at `position` (e, e3 down) and time t, with
    /// Wheeler's stretching (the acceleration is the stretched profile of the linear one); zero above the
    /// surface.
    pub fn kinematics(&self, position: &Vector3<f64>, time: f64) -> Kinematics {
        let (ramp, ramp_rate) = ramp_factor(time, self.ramp);
        if ramp == 0.0 {
            return Kinematics::default();
        }
        let (x, y) = (position.x, position.y);
        let h = self.depth;
        let height = -position.z;
        // The stretched depth below the surface is at least h − height·h/(h − Σa): deeper than every
        // component reaches, the water is still.
        let reach = self.components.first().map_or(0.0, |c| c.negligible_below);
        if self.surface_bound < h && h - height.max(0.0) * h / (h - self.surface_bound) > reach {
            return Kinematics::default();
        }
        PHASES.with_borrow_mut(|phases| {
            let (surface, surface_gradient) = self.surface_and_phases(x, y, time, ramp, phases);
            if height > h + surface || h + surface <= 0.0 {
                return Kinematics::default();
            }
            self.sum(phases, ramp, ramp_rate, height, surface, &surface_gradient)
        })
    }

    /// The surface elevation η (m) at (x, y) and time t with its horizontal gradient, under the build-up
    /// factor `ramp`; `phases` becomes each component's (sin θ, cos θ) there. Four components at a time
    /// (`wide`'s sine and cosine, within an ulp of the standard library's: the tests).
    fn surface_and_phases(
        &self,
        x: f64,
        y: f64,
        time: f64,
        ramp: f64,
        phases: &mut Vec<(f64, f64)>,
    ) -> (f64, Vector3<f64>) {
        phases.clear();
        let mut surface = f64x4::ZERO;
        let mut gradient_x = f64x4::ZERO;
        let mut gradient_y = f64x4::ZERO;
        for chunk in self.components.chunks(LANES) {
            // Lanes past the last component have zero amplitude: they add nothing.
            let (sin, cos) = lanes(chunk, |c| c.angle(x, y, time)).sin_cos();
            let amplitude = lanes(chunk, |c| ramp * c.amplitude);
            surface += amplitude * cos;
            let slope = amplitude * lanes(chunk, |c| c.number) * sin;
            gradient_x -= lanes(chunk, |c| c.cos) * slope;
            gradient_y -= lanes(chunk, |c| c.sin) * slope;
            let (sin, cos) = (sin.to_array(), cos.to_array());
            phases.extend(sin.into_iter().zip(cos).take(chunk.len()));
        }
        let gradient = Vector3::new(gradient_x.reduce_add(), gradient_y.reduce_add(), 0.0);
        (surface.reduce_add(), gradient)
    }

    /// The kinematics at the stretched height of a point `height` above the seabed under the surface
    /// `surface` (of gradient `surface_gradient`), from each component's phase (sin θ, cos θ) there.
    fn sum(
        &self,
        phases: &[(f64, f64)],
        ramp: f64,
        ramp_rate: f64,
        height: f64,
        surface: f64,
        surface_gradient: &Vector3<f64>,
    ) -> Kinematics {
        let h = self.depth;
        // s′ = h s/(h + η): ∂s′/∂z = −h/(h + η) (s = −z), ∂s′/∂x_j = −h s/(h + η)² ∂η/∂x_j.
        let stretch = h / (h + surface);
        let s = height * stretch;
        let d_s = -surface_gradient * (s / (h + surface)) - Vector3::z() * stretch;
        // The components that reach the point: a prefix (they are sorted by reach), four at a time. With
        // dir = (cos β, sin β, 0) and each component's aω scaled by the build-up, H = aω ch cos θ,
        // U = aω sh sin θ, P = aω ch sin θ and Q = k aω sh cos θ: u = Σ (H dir − U e3),
        // a = Σ ω (P dir + (Q/k) e3) + ṙ/r u and ∂u/∂x = Σ [dir ⊗ (Q ∇s′ − kP dir) − e3 ⊗ (Q dir + kP ∇s′)].
        let below = h - s.max(0.0);
        let reaching = self
            .components
            .partition_point(|c| below <= c.negligible_below);
        let depth_factor = f64x4::splat(s.max(0.0));
        let mut velocity = [f64x4::ZERO; 3];
        let mut acceleration = [f64x4::ZERO; 3];
        // Σ kP cos²β, Σ kP cos β sin β, Σ kP sin²β, Σ kP, Σ Q cos β, Σ Q sin β.
        let mut gradient = [f64x4::ZERO; 6];
        for (chunk, phase) in self.components[..reaching]
            .chunks(LANES)
            .zip(phases.chunks(LANES))
        {
            let number = lanes(chunk, |c| c.number);
            let frequency = lanes(chunk, |c| c.frequency);
            let (cos_beta, sin_beta) = (lanes(chunk, |c| c.cos), lanes(chunk, |c| c.sin));
            let (sin, cos) = (lanes(phase, |p| p.0), lanes(phase, |p| p.1));
            // ch = cosh(k s′)/sinh(k h) and sh = sinh(k s′)/sinh(k h) without overflow (s′ ≤ h, k h possibly
            // large): e^{k(s′−h)}(1 ± e^{−2ks′})/(1 − e^{−2kh}).
            let e_s = (number * depth_factor * -2.0).exp();
            let ratio = (number * (depth_factor - h)).exp() * lanes(chunk, |c| c.profile_scale);
            let (ch, sh) = (ratio * (e_s + 1.0), ratio * (1.0 - e_s));
            let aw = lanes(chunk, |c| ramp * c.amplitude * c.frequency);
            let horizontal = aw * ch * cos;
            let up = aw * sh * sin;
            let p = aw * ch * sin;
            let r = aw * sh * cos;
            velocity[0] += cos_beta * horizontal;
            velocity[1] += sin_beta * horizontal;
            velocity[2] -= up;
            acceleration[0] += cos_beta * frequency * p;
            acceleration[1] += sin_beta * frequency * p;
            acceleration[2] += frequency * r;
            let kp = number * p;
            let q = number * r;
            gradient[0] += kp * cos_beta * cos_beta;
            gradient[1] += kp * cos_beta * sin_beta;
            gradient[2] += kp * sin_beta * sin_beta;
            gradient[3] += kp;
            gradient[4] += q * cos_beta;
            gradient[5] += q * sin_beta;
        }
        let (u, a, g) = (
            velocity.map(f64x4::reduce_add),
            acceleration.map(f64x4::reduce_add),
            gradient.map(f64x4::reduce_add),
        );
        let velocity = Vector3::new(u[0], u[1], u[2]);
        // The build-up's rate adds ṙ u (velocity / r).
        let acceleration = Vector3::new(a[0], a[1], a[2]) + velocity * (ramp_rate / ramp);
        let q_dir = Vector3::new(g[4], g[5], 0.0);
        let kp_dir_dir = Matrix3::new(g[0], g[1], 0.0, g[1], g[2], 0.0, 0.0, 0.0, 0.0);
        let e3 = Vector3::z();
        let velocity_gradient =
            q_dir * d_s.transpose() - kp_dir_dir - e3 * (q_dir + d_s * g[3]).transpose();
        Kinematics {
            velocity,
            acceleration,
            velocity_gradient,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;
    /// cosh(k s)/sinh(k h) and sinh(k s)/sinh(k h) without overflow (s ≤ h, k h possibly large).
    fn profiles(k: f64, s: f64, h: f64) -> (f64, f64) {
        let e_s = (-2.0 * k * s.max(0.0)).exp();
        let ratio = (k * (s.max(0.0) - h)).exp() / (1.0 - (-2.0 * k * h).exp());
        (ratio * (1.0 + e_s), ratio * (1.0 - e_s))
    }

    /// The surface elevation η (m) at (x, y) and time t under the build-up factor `ramp`, and its horizontal
    /// gradient, component by component with the standard library's sine and cosine.
    fn surface_one_by_one(
        field: &WaveField,
        x: f64,
        y: f64,
        time: f64,
        ramp: f64,
    ) -> (f64, Vector3<f64>) {
        let mut surface = 0.0;
        let mut gradient = Vector3::zeros();
        for c in &field.components {
            let (sin, cos) = c.angle(x, y, time).sin_cos();
            surface += ramp * c.amplitude * cos;
            gradient -= Vector3::new(c.cos, c.sin, 0.0) * (ramp * c.amplitude * c.number * sin);
        }
        (surface, gradient)
    }

    /// The kinematics component by component, with the standard library's functions: Wheeler-stretched
    /// linear velocity, acceleration (with the build-up's rate) and velocity gradient, each component that
    /// reaches the point in turn.
    fn kinematics_one_by_one(field: &WaveField, position: &Vector3<f64>, time: f64) -> Kinematics {
        let (ramp, ramp_rate) = ramp_factor(time, field.ramp);
        let (h, height) = (field.depth, -position.z);
        let (surface, surface_gradient) =
            surface_one_by_one(field, position.x, position.y, time, ramp);
        if height > h + surface {
            return Kinematics::default(); // above the water
        }
        let stretch = h / (h + surface);
        let s = height * stretch;
        let d_s = -surface_gradient * (s / (h + surface)) - Vector3::z() * stretch;
        let mut k = Kinematics::default();
        for c in field
            .components
            .iter()
            .filter(|c| h - s.max(0.0) <= c.negligible_below)
        {
            let (sin, cos) = c.angle(position.x, position.y, time).sin_cos();
            let (ch, sh) = profiles(c.number, s, h);
            let aw = ramp * c.amplitude * c.frequency;
            let direction = Vector3::new(c.cos, c.sin, 0.0);
            let velocity = direction * (aw * ch * cos) - Vector3::z() * (aw * sh * sin);
            k.velocity += velocity;
            k.acceleration += direction * (aw * c.frequency * ch * sin)
                + Vector3::z() * (aw * c.frequency * sh * cos)
                + velocity * (ramp_rate / ramp);
            let d_theta = direction * c.number;
            let d_horizontal = -d_theta * (aw * ch * sin) + d_s * (aw * c.number * sh * cos);
            let d_up = d_theta * (aw * sh * cos) + d_s * (aw * c.number * ch * sin);
            k.velocity_gradient +=
                direction * d_horizontal.transpose() - Vector3::z() * d_up.transpose();
        }
        k
    }

    /// The kinematics summed four components at a time are those summed one by one with the standard
    /// library's functions, to round-off (relative to the sea's scales Σ aω, Σ aω², Σ aωk), at points from the
    /// surface to the bottom of a 300 m sea, during and after its build-up.
    #[test]
    fn kinematics_four_at_a_time_match_the_sum_one_by_one() {
        let mut waves = Waves::jonswap(4.0, 9.0, 3.3, 0.3, Some(6.0), 11, 203).unwrap();
        waves.ramp = 20.0;
        let field = WaveField::new(&waves, 300.0, G).unwrap();
        let scale = |f: &dyn Fn(&Resolved) -> f64| field.components().iter().map(f).sum::<f64>();
        let velocity = scale(&|c| c.amplitude * c.frequency);
        let acceleration = scale(&|c| c.amplitude * c.frequency * c.frequency);
        let gradient = scale(&|c| c.amplitude * c.frequency * c.number);
        let mut worst: f64 = 0.0;
        let mut moving = 0;
        for below in [0.0, 1.5, 10.0, 40.0, 120.0, 299.0] {
            for (x, t) in [(-40.0, 7.0), (310.0, 1234.5), (2500.0, 10890.0)] {
                let point = Vector3::new(x, 12.0, -(300.0 - below));
                let (four, one) = (
                    field.kinematics(&point, t),
                    kinematics_one_by_one(&field, &point, t),
                );
                moving += usize::from(one.velocity.norm() > 1e-3 * velocity);
                worst = worst
                    .max((four.velocity - one.velocity).norm() / velocity)
                    .max((four.acceleration - one.acceleration).norm() / acceleration)
                    .max((four.velocity_gradient - one.velocity_gradient).norm() / gradient);
            }
        }
        assert!(moving >= 9, "{moving} points in moving water");
        assert!(worst < 1e-15, "worst relative difference {worst:e}"); // measured: 9.6e-17
    }

    #[test]
    fn dispersion_relation_and_its_limits() {
        for (omega, h) in [(0.3, 20.0), (0.7, 150.0), (1.5, 800.0), (0.1, 3000.0)] {
            let k = wave_number(omega, h, G);
            assert!((G * k * (k * h).tanh() - omega * omega).abs() < 1e-13 * omega * omega);
        }
        // Deep water: k = ω²/g; shallow: k = ω/√(gh).
        let deep = wave_number(1.0, 2000.0, G);
        assert!((deep - 1.0 / G).abs() < 1e-12 * deep);
        let shallow = wave_number(0.05, 5.0, G);
        assert!((shallow - 0.05 / (G * 5.0).sqrt()).abs() < 1e-3 * shallow);
    }

    /// Deep water: velocity amplitude aω e^{kζ} at depth −ζ, circular orbits; shallow water: horizontal
    /// velocity a√(g/h), uniform over depth.
    #[test]
    fn kinematics_in_deep_and_shallow_water() {
        // A small amplitude (1 mm), so that the stretching (relative k a = 6e-5) is below the tolerance.
        let waves = Waves::regular(2e-3, 8.0, 0.0).unwrap();
        let h = 1000.0;
        let field = WaveField::new(&waves, h, G).unwrap();
        let omega = std::f64::consts::TAU / 8.0;
        let k = omega * omega / G;
        for below in [5.0, 20.0, 50.0] {
            let position = Vector3::new(0.0, 0.0, -(h - below));
            let expected = 1e-3 * omega * (-k * below).exp();
            let mut largest: f64 = 0.0;
            for i in 0..64 {
                let t = 8.0 * i as f64 / 64.0;
                let v = field.kinematics(&position, t).velocity;
                largest = largest.max(v.norm());
                assert!(
                    (v.norm() - expected).abs() < 1e-4 * expected,
                    "orbit not circular"
                );
            }
            assert!((largest - expected).abs() < 1e-4 * expected);
        }
        // kh = 0.03: the long-wave limit to O((kh)²).
        let shallow = Waves::regular(2e-3, 200.0, 0.0).unwrap();
        let h = 10.0;
        let field = WaveField::new(&shallow, h, G).unwrap();
        let expected = 1e-3 * (G / h).sqrt();
        for height in [0.0, 5.0, 9.9] {
            let u = field
                .kinematics(&Vector3::new(0.0, 0.0, -height), 0.0)
                .velocity
                .x;
            assert!((u - expected).abs() < 2e-3 * expected, "{u} vs {expected}");
        }
    }

    /// The sum leaves out components where they are negligible ([`NEGLIGIBLE`]): against the full sum over
    /// every component, from the surface to the seabed in 800 m and in 60 m of water, the velocity,
    /// acceleration and velocity gradient differ by less than 2e-5 of the sea's scale (Σ a ω, Σ a ω², Σ a ω k;
    /// measured: 6.6e-6 at most); below the deepest reach (307 m here) the water is still.
    #[test]
    fn negligible_components_are_left_out_within_the_tolerance() {
        let waves = Waves::jonswap(4.0, 9.0, 3.3, 0.3, None, 5, 300).unwrap();
        let mut worst: f64 = 0.0;
        for h in [800.0, 60.0] {
            let field = WaveField::new(&waves, h, G).unwrap();
            let mut full = field.clone();
            full.components
                .iter_mut()
                .for_each(|c| c.negligible_below = f64::INFINITY);
            let scale =
                |f: &dyn Fn(&Resolved) -> f64| field.components().iter().map(f).sum::<f64>();
            let velocity = scale(&|c| c.amplitude * c.frequency);
            let acceleration = scale(&|c| c.amplitude * c.frequency * c.frequency);
            let gradient = scale(&|c| c.amplitude * c.frequency * c.number);
            for k in 0..=40 {
                let below = h * f64::from(k) / 40.0;
                for t in [31.0, 47.5] {
                    let point = Vector3::new(20.0, 3.0, -(h - below));
                    let (cut, all) = (field.kinematics(&point, t), full.kinematics(&point, t));
                    let errors = [
                        (cut.velocity - all.velocity).norm() / velocity,
                        (cut.acceleration - all.acceleration).norm() / acceleration,
                        (cut.velocity_gradient - all.velocity_gradient).norm() / gradient,
                    ];
                    worst = errors.iter().fold(worst, |w, e| w.max(*e));
                }
            }
        }
        assert!(worst < 2e-5, "worst relative error {worst:e}");
        let field = WaveField::new(&waves, 800.0, G).unwrap();
        let reach = field.components()[0].negligible_below;
        assert!(reach > 50.0 && reach < 700.0, "{reach}");
        let deep = field.kinematics(&Vector3::new(0.0, 0.0, -(800.0 - reach - 20.0)), 31.0);
        assert_eq!(deep, Kinematics::default());
    }

    /// The phases computed four components at a time are the standard library's sine and cosine of each
    /// component's angle to within an ulp (measured: half of one), and the surface elevation and its
    /// gradient their sums one by one, over a 3-hour storm's times and a 3 km stretch of sea (angles up to
    /// 3e4 rad); 203 components, so that the last lanes are empty.
    #[test]
    fn phases_four_at_a_time_match_the_scalar_sums() {
        let waves = Waves::jonswap(4.0, 9.0, 3.3, 0.3, Some(6.0), 11, 203).unwrap();
        let field = WaveField::new(&waves, 300.0, G).unwrap();
        let mut phases = Vec::new();
        let (mut worst_phase, mut worst_surface, mut worst_gradient): (f64, f64, f64) =
            (0.0, 0.0, 0.0);
        for (x, y, t) in [
            (0.0, 0.0, 0.0),
            (-1200.0, 35.0, 10890.0),
            (3000.0, -800.0, 5471.3),
            (17.0, 4.0, 0.7),
        ] {
            let (surface, gradient) = field.surface_and_phases(x, y, t, 0.8, &mut phases);
            assert_eq!(phases.len(), 203);
            for (c, &(sin, cos)) in field.components().iter().zip(&phases) {
                let (sin_std, cos_std) = c.angle(x, y, t).sin_cos();
                worst_phase = worst_phase
                    .max((sin - sin_std).abs())
                    .max((cos - cos_std).abs());
            }
            let (plain, plain_gradient) = surface_one_by_one(&field, x, y, t, 0.8);
            worst_surface = worst_surface.max((surface - plain).abs());
            worst_gradient = worst_gradient.max((gradient - plain_gradient).norm());
        }
        assert!(worst_phase <= f64::EPSILON, "phase {worst_phase:e}");
        // The sums' round-off (measured 7.8e-16 m and 5.9e-17).
        assert!(
            worst_surface < 4e-15 && worst_gradient < 1e-15,
            "{worst_surface:e} {worst_gradient:e}"
        );
    }

    /// The velocity gradient matches central differences (stretching included); the acceleration is ∂u/∂t
    /// up to the stretching's time dependence (relative k H_s ≈ 0.1 here near the surface, 1e-3 at depth).
    #[test]
    fn gradient_and_acceleration_match_differences() {
        let waves = Waves::jonswap(3.0, 9.0, 3.3, 0.4, Some(8.0), 7, 30).unwrap();
        let field = WaveField::new(&waves, 200.0, G).unwrap();
        let point = Vector3::new(13.0, -4.0, -170.0);
        let t = 21.0;
        let k = field.kinematics(&point, t);
        let h = 1e-5;
        for j in 0..3 {
            let mut e = Vector3::zeros();
            e[j] = h;
            let fd = (field.kinematics(&(point + e), t).velocity
                - field.kinematics(&(point - e), t).velocity)
                / (2.0 * h);
            assert!(
                (fd - k.velocity_gradient.column(j)).norm() < 1e-7 * k.velocity_gradient.norm(),
                "{j}"
            );
        }
        // A low sea (Hs 3 cm), where the stretching's time dependence is negligible.
        let low = Waves::jonswap(0.03, 9.0, 3.3, 0.4, Some(8.0), 7, 30).unwrap();
        let field = WaveField::new(&low, 200.0, G).unwrap();
        let k = field.kinematics(&point, t);
        let dt = (field.kinematics(&point, t + h).velocity
            - field.kinematics(&point, t - h).velocity)
            / (2.0 * h);
        assert!(
            (dt - k.acceleration).norm() < 1e-3 * k.acceleration.norm(),
            "{dt} {}",
            k.acceleration
        );
    }

    #[test]
    fn above_the_surface_the_water_is_gone() {
        let waves = Waves::regular(4.0, 10.0, 0.0).unwrap();
        let field = WaveField::new(&waves, 100.0, G).unwrap();
        // At t = 0, x = 0 the crest is 2 m up: 1 m up is wet, 3 m up dry.
        assert!(
            field
                .kinematics(&Vector3::new(0.0, 0.0, -101.0), 0.0)
                .velocity
                .norm()
                > 0.0
        );
        assert_eq!(
            field.kinematics(&Vector3::new(0.0, 0.0, -103.0), 0.0),
            Kinematics::default()
        );
        // Wheeler: the crest has the mean level's kinematics.
        let crest = field
            .kinematics(&Vector3::new(0.0, 0.0, -102.0), 0.0)
            .velocity;
        let waves_flat = WaveField::new(&waves, 100.0, G).unwrap();
        let mean_level = waves_flat.kinematics(&Vector3::new(0.0, 0.0, -100.0), 0.0);
        let unstretched = {
            let k = wave_number(std::f64::consts::TAU / 10.0, 100.0, G);
            let (ch, _) = profiles(k, 100.0, 100.0);
            2.0 * std::f64::consts::TAU / 10.0 * ch
        };
        assert!((crest.x - unstretched).abs() < 1e-12 * unstretched);
        assert!(mean_level.velocity.x < crest.x);
    }
}
