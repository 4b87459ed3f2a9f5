//! Irvine's elastic catenary (H. M. Irvine, *Cable Structures*, 1981).
//!
//! A cable of unstretched length `L`, axial stiffness `EA` and weight `w` per
//! unstretched length hangs between two points `A` and `B`. The project frame
//! has **e3 pointing down** (gravity along +e3), so "up" is −e3.
//!
//! In the vertical plane through `A` and `B` let `x` be the horizontal distance
//! from `A` (towards `B`) and `z` the height above `A` (`z = −Δe3`). With the
//! unstretched arc length `s ∈ [0, L]` measured from `A`, the horizontal
//! tension `H` is constant and the vertical tension component (positive up,
//! acting on the part `[0, s]` from the part beyond `s`) is
//!
//! ```text
//! V(s) = V0 + w s,            T(s) = sqrt(H² + V(s)²).
//! ```
//!
//! Hooke's law `ds_stretched = (1 + T/EA) ds` and the tangent `(H, V)/T` give
//!
//! ```text
//! dx/ds = H/T + H/EA,         dz/ds = V/T + V/EA,
//! x(s)  = H s/EA + (H/w) [asinh(V(s)/H) − asinh(V0/H)],          (Irvine 2.33)
//! z(s)  = (V0 s + w s²/2)/EA + (T(s) − T(0))/w.                   (Irvine 2.34)
//! ```
//!
//! The unknowns `(H, V0)` follow from the closure `x(L) = ℓ`, `z(L) = h`.
//! These residuals are the gradient of the strictly convex complementary
//! energy
//!
//! ```text
//! Φ(H, V0) = ∫ T ds + ∫ T²/(2 EA) ds − H ℓ − V0 h,
//! ```
//!
//! so the closure is solved by Newton's method (the Jacobian is the symmetric
//! positive definite flexibility matrix) with an Armijo line search on `Φ`,
//! which converges from any start with `H > 0`. The start is the exact
//! inextensible catenary for a slack cable (`sqrt(L² − h²) = ℓ sinh λ / λ`,
//! `λ = w ℓ / (2H)`) and a straight elastic bar for a taut one.

use nalgebra::Vector3;
use std::fmt;

/// Relative closure tolerance of the Newton iteration.
const REL_TOL: f64 = 1e-12;
/// Maximum number of Newton iterations.
const MAX_ITER: usize = 500;
/// A span below this fraction of the chord is treated as vertical.
const VERTICAL_SPAN_REL: f64 = 1e-12;

/// Error returned by [`Catenary::solve`].
#[derive(Debug, Clone, PartialEq)]
pub enum CatenaryError {
    /// An input is NaN or infinite.
    NotFinite {
        /// Name of the offending input.
        what: &'static str,
    },
    /// An input that must be strictly positive is not.
    NotPositive {
        /// Name of the offending input.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// No hanging-cable solution exists or the iteration failed.
    NoSolution(String),
}

impl fmt::Display for CatenaryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite { what } => write!(f, "catenary: {what} is not finite"),
            Self::NotPositive { what, value } => {
                write!(f, "catenary: {what} must be positive, got {value}")
            }
            Self::NoSolution(msg) => write!(f, "catenary: no solution: {msg}"),
        }
    }
}

impl std::error::Error for CatenaryError {}

/// Solved elastic catenary between two points.
#[derive(Debug, Clone)]
pub struct Catenary {
    /// End `A` (s = 0).
    a: Vector3<f64>,
    /// Unit horizontal direction from `A` towards `B` (zero for a vertical cable).
    e_h: Vector3<f64>,
    /// Horizontal tension `H ≥ 0`.
    h: f64,
    /// Vertical tension component at `A`, positive up.
    v0: f64,
    /// Weight per unstretched length.
    w: f64,
    /// Axial stiffness.
    ea: f64,
    /// Unstretched length.
    length: f64,
    /// Vertical cable (`H = 0`): +1 if it rises from `A` to `B`, −1 if it falls.
    vertical_sign: f64,
}

/// The "up" unit vector, −e3.
fn up() -> Vector3<f64> {
    -Vector3::z()
}

/// `asinh((v0 + ws)/h) − asinh(v0/h)` for `h > 0`, free of cancellation.
///
/// For `v0` and `v1 = v0 + ws` of equal sign it uses
/// `asinh a − asinh b = asinh(a√(1+b²) − b√(1+a²))` with
/// `a√(1+b²) − b√(1+a²) = (v1² − v0²)/(v1 T0 + v0 T1)`.
pub(crate) fn asinh_diff(h: f64, v0: f64, ws: f64) -> f64 {
    let v1 = v0 + ws;
    if v0 * v1 > 0.0 {
        let t0 = h.hypot(v0);
        let t1 = h.hypot(v1);
        (ws * (v1 + v0) / (v1 * t0 + v0 * t1)).asinh()
    } else {
        (v1 / h).asinh() - (v0 / h).asinh()
    }
}

/// `V1/T1 − V0/T0` (difference of the vertical direction cosines), free of cancellation.
fn cos_diff(h: f64, v0: f64, ws: f64) -> f64 {
    let v1 = v0 + ws;
    let t0 = h.hypot(v0);
    let t1 = h.hypot(v1);
    if v0 * v1 > 0.0 {
        // V1 T0 − V0 T1 = H² (V1² − V0²)/(V1 T0 + V0 T1)
        h * h * ws * (v1 + v0) / ((v1 * t0 + v0 * t1) * t0 * t1)
    } else {
        v1 / t1 - v0 / t0
    }
}

/// `T(s) − T(0) = w s (2 V0 + w s)/(T(s) + T(0))`, free of cancellation.
pub(crate) fn tension_diff(h: f64, v0: f64, ws: f64) -> f64 {
    let v1 = v0 + ws;
    let sum = h.hypot(v1) + h.hypot(v0);
    if sum > 0.0 {
        ws * (v1 + v0) / sum
    } else {
        0.0
    }
}

/// Closure data of one trial `(H, V0)`.
struct Eval {
    /// Residual `(x(L) − ℓ, z(L) − h)` = gradient of `Φ`.
    r: [f64; 2],
    /// Jacobian (flexibility matrix) `[[∂x/∂H, ∂x/∂V0], [∂z/∂H, ∂z/∂V0]]`, symmetric.
    j: [[f64; 2]; 2],
}

/// The closure problem: span `ell`, rise `rise`, cable data.
struct Problem {
    ell: f64,
    rise: f64,
    length: f64,
    w: f64,
    ea: f64,
}

impl Problem {
    /// Closure residual and Jacobian at `(H, V0)` (Irvine 2.33–2.34 at s = L).
    fn eval(&self, h: f64, v0: f64) -> Eval {
        let (l, w, ea) = (self.length, self.w, self.ea);
        let wl = w * l;
        let v1 = v0 + wl;
        let t0 = h.hypot(v0);
        let t1 = h.hypot(v1);
        let d = asinh_diff(h, v0, wl);
        let g = cos_diff(h, v0, wl);
        let x = h * l / ea + h / w * d;
        let z = (v0 * l + 0.5 * w * l * l) / ea + tension_diff(h, v0, wl) / w;
        let jxh = l / ea + (d - g) / w;
        let jxv = h / w * (1.0 / t1 - 1.0 / t0);
        let jzv = l / ea + g / w;
        Eval {
            r: [x - self.ell, z - self.rise],
            j: [[jxh, jxv], [jxv, jzv]],
        }
    }

    /// Complementary energy `Φ(H, V0)` and a magnitude scale for round-off.
    fn phi(&self, h: f64, v0: f64) -> (f64, f64) {
        let (l, w, ea) = (self.length, self.w, self.ea);
        let wl = w * l;
        let v1 = v0 + wl;
        let t0 = h.hypot(v0);
        let t1 = h.hypot(v1);
        // ∫ T ds = [V T + H² asinh(V/H)] / (2w)
        let int_t_parts = [v1 * t1, -v0 * t0, h * h * asinh_diff(h, v0, wl)];
        // ∫ T² ds = H² L + (V1³ − V0³)/(3w)
        let int_t2 = h * h * l + l * (v1 * v1 + v1 * v0 + v0 * v0) / 3.0;
        let work = [-h * self.ell, -v0 * self.rise];
        let value =
            int_t_parts.iter().sum::<f64>() / (2.0 * w) + int_t2 / (2.0 * ea) + work[0] + work[1];
        let scale = int_t_parts.iter().map(|t| t.abs()).sum::<f64>() / (2.0 * w)
            + int_t2.abs() / (2.0 * ea)
            + work[0].abs()
            + work[1].abs();
        (value, scale)
    }
}

/// `ln(sinh λ / λ)` for `λ ≥ 0`, without overflow.
fn ln_sinhc(lambda: f64) -> f64 {
    if lambda < 1e-3 {
        let l2 = lambda * lambda;
        l2 / 6.0 - l2 * l2 / 180.0
    } else if lambda < 20.0 {
        (lambda.sinh() / lambda).ln()
    } else {
        lambda + (-(-2.0 * lambda).exp()).ln_1p() - std::f64::consts::LN_2 - lambda.ln()
    }
}

/// Solve `sinh λ / λ = ρ` (ρ > 1) for `λ > 0` by bisection (inextensible catenary).
fn solve_sinhc(rho: f64) -> f64 {
    let target = rho.ln();
    let mut lo = 0.0_f64;
    let mut hi = 1.0_f64;
    while ln_sinhc(hi) < target && hi < 1e6 {
        lo = hi;
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if ln_sinhc(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-15 * hi {
            break;
        }
    }
    0.5 * (lo + hi)
}

fn check_vector(what: &'static str, v: &Vector3<f64>) -> Result<(), CatenaryError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(CatenaryError::NotFinite { what })
    }
}

fn check_positive(what: &'static str, value: f64) -> Result<(), CatenaryError> {
    if !value.is_finite() {
        Err(CatenaryError::NotFinite { what })
    } else if value <= 0.0 {
        Err(CatenaryError::NotPositive { what, value })
    } else {
        Ok(())
    }
}

impl Catenary {
    /// Solve the elastic catenary (Irvine 2.33–2.34) through `a` (s = 0) and `b` (s = L).
    ///
    /// `length` is the unstretched length, `weight` the weight per unstretched
    /// length (acting along +e3) and `ea` the axial stiffness. The closure for
    /// `(H, V0)` is solved by Newton's method with a line search on the
    /// complementary energy, to `1e-12` relative. A vertical chord gives a
    /// straight hanging bar; if that bar would need compression (cable longer
    /// than the hanging chord) there is no hanging-line solution and an error
    /// is returned.
    pub fn solve(
        a: Vector3<f64>,
        b: Vector3<f64>,
        length: f64,
        weight: f64,
        ea: f64,
    ) -> Result<Catenary, CatenaryError> {
        check_vector("a", &a)?;
        check_vector("b", &b)?;
        check_positive("length", length)?;
        check_positive("weight", weight)?;
        check_positive("ea", ea)?;

        let d = b - a;
        let chord = d.norm();
        let size = a.norm().max(b.norm()).max(length);
        if chord <= 1e-14 * size {
            return Err(CatenaryError::NoSolution(format!(
                "end points coincide (chord {chord:e})"
            )));
        }
        let rise = -d.z;
        let d_h = Vector3::new(d.x, d.y, 0.0);
        let ell = d_h.norm();

        if ell <= VERTICAL_SPAN_REL * chord {
            return Self::solve_vertical(a, rise, length, weight, ea);
        }
        let e_h = d_h / ell;
        let problem = Problem {
            ell,
            rise,
            length,
            w: weight,
            ea,
        };
        let (h, v0) = Self::newton(&problem, chord)?;
        Ok(Catenary {
            a,
            e_h,
            h,
            v0,
            w: weight,
            ea,
            length,
            vertical_sign: 0.0,
        })
    }

    /// Straight vertical elastic bar: `z(L) = σ L + (V0 L + w L²/2)/EA = rise`.
    fn solve_vertical(
        a: Vector3<f64>,
        rise: f64,
        length: f64,
        w: f64,
        ea: f64,
    ) -> Result<Catenary, CatenaryError> {
        let sigma = rise.signum();
        let v0 = ea * (rise - sigma * length) / length - 0.5 * w * length;
        // Tension along the bar must not become compressive.
        let t_min = if sigma > 0.0 { v0 } else { -(v0 + w * length) };
        let tol = 1e-12 * (ea + w * length);
        if !v0.is_finite() || t_min < -tol {
            return Err(CatenaryError::NoSolution(format!(
                "vertical chord {} too short for a hanging line of length {length} \
                 (would need compression {t_min:e} N)",
                rise.abs()
            )));
        }
        Ok(Catenary {
            a,
            e_h: Vector3::zeros(),
            h: 0.0,
            v0,
            w,
            ea,
            length,
            vertical_sign: sigma,
        })
    }

    /// Start value of `(H, V0)`: inextensible catenary (slack) or elastic bar (taut).
    fn initial_guess(p: &Problem, chord: f64) -> (f64, f64) {
        let (l, w) = (p.length, p.w);
        if l > chord {
            // Inextensible catenary: sqrt(L² − h²) = ℓ sinh λ/λ, λ = wℓ/(2H);
            // V0 = H sinh(β − λ), sinh β = h λ/(ℓ sinh λ).
            let rho = ((l - p.rise) * (l + p.rise)).sqrt() / p.ell;
            let lambda = solve_sinhc(rho).max(1e-8);
            let h = w * p.ell / (2.0 * lambda);
            let beta = (p.rise * lambda / (p.ell * lambda.sinh())).asinh();
            let v0 = h * (beta - lambda).sinh();
            if h.is_finite() && v0.is_finite() && h > 0.0 {
                return (h, v0);
            }
        }
        // Straight elastic bar along the chord carrying half the weight at each end.
        let t_bar = p.ea * (chord / l - 1.0).max(0.0) + 0.5 * w * l;
        let h = t_bar * p.ell / chord;
        let v_mid = t_bar * p.rise / chord;
        (h.max(1e-3 * w * l), v_mid - 0.5 * w * l)
    }

    /// Damped Newton on the closure (gradient of the convex `Φ`), Armijo line search on `Φ`.
    fn newton(p: &Problem, chord: f64) -> Result<(f64, f64), CatenaryError> {
        let scale = chord.max(p.length);
        let tol = REL_TOL * scale;
        let (mut h, mut v0) = Self::initial_guess(p, chord);
        let mut at_floor = false;
        for _ in 0..MAX_ITER {
            let e = p.eval(h, v0);
            let rn = e.r[0].hypot(e.r[1]);
            if !rn.is_finite() {
                return Err(CatenaryError::NoSolution(format!(
                    "non-finite closure residual at H = {h:e}, V0 = {v0:e}"
                )));
            }
            if rn <= tol || (at_floor && rn <= 1e3 * tol) {
                return Ok((h, v0));
            }
            let [[j11, j12], [j21, j22]] = e.j;
            let det = j11 * j22 - j12 * j21;
            if !(det.is_finite() && det > 0.0) {
                return Err(CatenaryError::NoSolution(format!(
                    "singular flexibility matrix (det {det:e}) at H = {h:e}, V0 = {v0:e}"
                )));
            }
            let dh = -(j22 * e.r[0] - j12 * e.r[1]) / det;
            let dv = -(j11 * e.r[1] - j21 * e.r[0]) / det;
            // Keep H positive.
            let mut alpha: f64 = if dh < 0.0 {
                (0.9 * h / -dh).min(1.0)
            } else {
                1.0
            };
            let slope = e.r[0] * dh + e.r[1] * dv; // ∇Φ·δ < 0
            let (phi0, phi_scale) = p.phi(h, v0);
            let slack = 64.0 * f64::EPSILON * phi_scale;
            let mut accepted = false;
            for _ in 0..80 {
                let hn = h + alpha * dh;
                let vn = v0 + alpha * dv;
                let (phi1, phi1_scale) = p.phi(hn, vn);
                let slack = slack.max(64.0 * f64::EPSILON * phi1_scale);
                if phi1.is_finite() && phi1 <= phi0 + 1e-4 * alpha * slope + slack {
                    accepted = true;
                    break;
                }
                alpha *= 0.5;
            }
            if !accepted {
                if rn <= 1e3 * tol {
                    return Ok((h, v0));
                }
                return Err(CatenaryError::NoSolution(format!(
                    "line search failed at H = {h:e}, V0 = {v0:e}, residual {rn:e}"
                )));
            }
            let step_h = alpha * dh;
            let step_v = alpha * dv;
            at_floor = step_h.abs() <= 4.0 * f64::EPSILON * h
                && step_v.abs() <= 4.0 * f64::EPSILON * (v0.abs() + h + p.w * p.length);
            h += step_h;
            v0 += step_v;
        }
        Err(CatenaryError::NoSolution(format!(
            "no convergence in {MAX_ITER} iterations (H = {h:e}, V0 = {v0:e})"
        )))
    }

    /// Horizontal tension `H ≥ 0` (N).
    pub fn horizontal_tension(&self) -> f64 {
        self.h
    }

    /// Vertical tension component `V(s) = V0 + w s` (positive up).
    fn vertical(&self, s: f64) -> f64 {
        self.v0 + self.w * s
    }

    /// Effective tension `T(s) = sqrt(H² + (V0 + w s)²)` at unstretched arc length `s` from `A` (N).
    pub fn tension(&self, s: f64) -> f64 {
        self.h.hypot(self.vertical(s))
    }

    /// Point at unstretched arc length `s` (Irvine 2.33–2.34): `x(s) e_h + z(s) (−e3)` from `A`.
    pub fn position(&self, s: f64) -> Vector3<f64> {
        let (w, ea, v0) = (self.w, self.ea, self.v0);
        let z_elastic = (v0 * s + 0.5 * w * s * s) / ea;
        if self.h > 0.0 {
            let ws = w * s;
            let x = self.h * s / ea + self.h / w * asinh_diff(self.h, v0, ws);
            let z = z_elastic + tension_diff(self.h, v0, ws) / w;
            self.a + self.e_h * x + up() * z
        } else {
            self.a + up() * (self.vertical_sign * s + z_elastic)
        }
    }

    /// Unit tangent `(H e_h + V(s) (−e3)) / T(s)`, pointing from `A` towards `B`.
    pub fn tangent(&self, s: f64) -> Vector3<f64> {
        if self.h > 0.0 {
            (self.e_h * self.h + up() * self.vertical(s)) / self.tension(s)
        } else {
            up() * self.vertical_sign
        }
    }

    /// Force the cable exerts on the support at `B`: `−T(L) t(L)` (N).
    pub fn force_at_b(&self) -> Vector3<f64> {
        -(self.e_h * self.h + up() * self.vertical(self.length))
    }

    /// Force the cable exerts on the support at `A`: `T(0) t(0)` (N).
    pub fn force_at_a(&self) -> Vector3<f64> {
        self.e_h * self.h + up() * self.v0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel_close(x: Vector3<f64>, y: Vector3<f64>, scale: f64, tol: f64) -> bool {
        (x - y).norm() <= tol * scale
    }

    fn check_closure(a: Vector3<f64>, b: Vector3<f64>, l: f64, w: f64, ea: f64) -> Catenary {
        let c = match Catenary::solve(a, b, l, w, ea) {
            Ok(c) => c,
            Err(e) => panic!("solve failed for a={a:?} b={b:?} L={l} w={w} EA={ea}: {e}"),
        };
        let scale = (b - a).norm().max(l).max(a.norm()).max(b.norm());
        assert!(
            rel_close(c.position(0.0), a, scale, 1e-9),
            "position(0) = {:?}, a = {a:?}",
            c.position(0.0)
        );
        assert!(
            rel_close(c.position(l), b, scale, 1e-9),
            "position(L) = {:?}, b = {b:?}, err {:e}",
            c.position(l),
            (c.position(l) - b).norm()
        );
        assert!(c.horizontal_tension() >= 0.0);
        c
    }

    fn check_equilibrium(c: &Catenary, l: f64, w: f64) {
        // Forces the cable exerts on its supports carry its whole weight:
        // the support reactions −F_A, −F_B and the weight w L e3 balance.
        let weight = Vector3::z() * (w * l);
        let sum = -c.force_at_a() - c.force_at_b() + weight;
        let scale = c.force_at_a().norm() + c.force_at_b().norm() + w * l;
        assert!(sum.norm() <= 1e-9 * scale, "unbalanced force {sum:?}");
        assert!((c.force_at_a().norm() - c.tension(0.0)).abs() <= 1e-12 * scale);
        assert!((c.force_at_b().norm() - c.tension(l)).abs() <= 1e-12 * scale);
    }

    /// (a, b, L, w, EA)
    type Case = (Vector3<f64>, Vector3<f64>, f64, f64, f64);

    fn cases() -> Vec<Case> {
        vec![
            // slack, B above A
            (
                Vector3::zeros(),
                Vector3::new(100.0, 0.0, -50.0),
                150.0,
                100.0,
                1e7,
            ),
            // taut: L < chord (chord = 111.8)
            (
                Vector3::zeros(),
                Vector3::new(100.0, 0.0, -50.0),
                111.0,
                100.0,
                1e7,
            ),
            // A higher than B
            (
                Vector3::new(0.0, 0.0, -100.0),
                Vector3::new(80.0, 0.0, 0.0),
                150.0,
                50.0,
                1e8,
            ),
            // lowest point outside the span (below A): barely slack
            (
                Vector3::zeros(),
                Vector3::new(100.0, 0.0, -50.0),
                112.5,
                100.0,
                1e9,
            ),
            // 3-D span not in the e1 plane
            (
                Vector3::new(1.0, 2.0, 3.0),
                Vector3::new(40.0, -30.0, -20.0),
                80.0,
                20.0,
                5e6,
            ),
            // very slack, short span
            (
                Vector3::zeros(),
                Vector3::new(1.0, 1.0, -10.0),
                200.0,
                10.0,
                1e6,
            ),
            // very soft cable
            (
                Vector3::zeros(),
                Vector3::new(100.0, 0.0, 0.0),
                90.0,
                100.0,
                1e4,
            ),
            // equal heights, stiff
            (
                Vector3::zeros(),
                Vector3::new(300.0, 0.0, 0.0),
                350.0,
                500.0,
                1e15,
            ),
        ]
    }

    #[test]
    fn closure_and_equilibrium() {
        for (a, b, l, w, ea) in cases() {
            let c = check_closure(a, b, l, w, ea);
            check_equilibrium(&c, l, w);
        }
    }

    #[test]
    fn lowest_point_outside_span() {
        let c = check_closure(
            Vector3::zeros(),
            Vector3::new(100.0, 0.0, -50.0),
            112.5,
            100.0,
            1e9,
        );
        // At A the cable already rises (tangent has an upward, −e3, component).
        assert!(c.tangent(0.0).z < 0.0, "tangent at A {:?}", c.tangent(0.0));
        // Taut cable: also rises from A.
        let c = check_closure(
            Vector3::zeros(),
            Vector3::new(100.0, 0.0, -50.0),
            111.0,
            100.0,
            1e7,
        );
        assert!(c.tangent(0.0).z < 0.0);
        // A higher than B, still descending at B: lowest point past B.
        let c = check_closure(
            Vector3::new(0.0, 0.0, -100.0),
            Vector3::new(80.0, 0.0, 0.0),
            128.5,
            50.0,
            1e9,
        );
        assert!(
            c.tangent(128.5).z > 0.0,
            "tangent at B {:?}",
            c.tangent(128.5)
        );
    }

    #[test]
    fn stretch_matches_tension() {
        for (a, b, l, w, ea) in cases() {
            let c = check_closure(a, b, l, w, ea);
            let ds = 1e-5 * l;
            for k in 1..10 {
                let s = l * k as f64 / 10.0;
                let p0 = c.position(s - ds);
                let p1 = c.position(s + ds);
                let stretch = (p1 - p0).norm() / (2.0 * ds);
                let expected = 1.0 + c.tension(s) / ea;
                assert!(
                    (stretch - expected).abs() <= 1e-6 * expected,
                    "s={s}: stretch {stretch} vs 1 + T/EA = {expected}"
                );
                // The tangent is the normalised derivative.
                let t_fd = (p1 - p0).normalize();
                let t_err = (t_fd - c.tangent(s)).norm();
                assert!(t_err <= 1e-6, "s={s}: tangent error {t_err:e}");
            }
        }
    }

    #[test]
    fn inextensible_symmetric_limit() {
        let (span, l, w) = (300.0, 350.0, 500.0);
        let c = check_closure(Vector3::zeros(), Vector3::new(span, 0.0, 0.0), l, w, 1e15);
        // Classic catenary: L = (2H/w) sinh(w ℓ/(2H)), by bisection on H.
        let f = |h: f64| 2.0 * h / w * (w * span / (2.0 * h)).sinh() - l;
        let (mut lo, mut hi) = (1.0, 1e9);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let h_ref = 0.5 * (lo + hi);
        let sag_ref = h_ref / w * ((w * span / (2.0 * h_ref)).cosh() - 1.0);
        let h = c.horizontal_tension();
        assert!((h - h_ref).abs() <= 1e-8 * h_ref, "H {h} vs {h_ref}");
        let mid = c.position(0.5 * l);
        assert!((mid.x - 0.5 * span).abs() <= 1e-8 * span);
        assert!(
            (mid.z - sag_ref).abs() <= 1e-8 * sag_ref,
            "sag {} vs {sag_ref}",
            mid.z
        );
        // Symmetric end forces.
        assert!((c.tension(0.0) - c.tension(l)).abs() <= 1e-9 * c.tension(0.0));
    }

    #[test]
    fn steel_pipe_1200m() {
        let (a, b) = (Vector3::zeros(), Vector3::new(850.0, 0.0, -800.0));
        let (l, w, ea) = (1200.0, 1848.0, 3.6e9);
        let c = check_closure(a, b, l, w, ea);
        check_equilibrium(&c, l, w);
        let h = c.horizontal_tension();
        let t_top = c.tension(l);
        println!("1200 m pipe: H = {h:.6} N, top tension = {t_top:.6} N");
        println!(
            "  tension at A = {:.6} N, top angle from vertical = {:.4} deg",
            c.tension(0.0),
            (h / t_top).asin().to_degrees()
        );
        assert!(h > 0.0);
        assert!(t_top > h && t_top > w * 800.0);
    }

    #[test]
    fn vertical_bar() {
        let (l, w, ea) = (100.0, 50.0, 1e6);
        // Rising from A: chord longer than L, bar stretched.
        let b = Vector3::new(0.0, 0.0, -100.5);
        let c = check_closure(Vector3::zeros(), b, l, w, ea);
        check_equilibrium(&c, l, w);
        assert_eq!(c.horizontal_tension(), 0.0);
        // Tension varies linearly, top minus bottom = weight.
        assert!((c.tension(l) - c.tension(0.0) - w * l).abs() <= 1e-9 * c.tension(l));
        assert!((c.tangent(30.0) - (-Vector3::z())).norm() <= 1e-15);
        // Falling from A (A above B).
        let c = check_closure(
            Vector3::new(3.0, 4.0, -100.5),
            Vector3::new(3.0, 4.0, 0.0),
            l,
            w,
            ea,
        );
        check_equilibrium(&c, l, w);
        assert!((c.tangent(30.0) - Vector3::z()).norm() <= 1e-15);
        // Slack vertical line: no hanging solution.
        let r = Catenary::solve(Vector3::zeros(), Vector3::new(0.0, 0.0, -90.0), l, w, ea);
        assert!(matches!(r, Err(CatenaryError::NoSolution(_))), "{r:?}");
    }

    #[test]
    fn bad_input() {
        let (a, b) = (Vector3::zeros(), Vector3::new(10.0, 0.0, -5.0));
        let bad = [
            Catenary::solve(a, b, 0.0, 1.0, 1.0),
            Catenary::solve(a, b, -1.0, 1.0, 1.0),
            Catenary::solve(a, b, 12.0, 0.0, 1.0),
            Catenary::solve(a, b, 12.0, -3.0, 1.0),
            Catenary::solve(a, b, 12.0, 1.0, 0.0),
            Catenary::solve(a, b, 12.0, 1.0, -1e9),
            Catenary::solve(a, b, f64::NAN, 1.0, 1.0),
            Catenary::solve(a, b, 12.0, f64::NAN, 1.0),
            Catenary::solve(a, b, 12.0, 1.0, f64::NAN),
            Catenary::solve(a, b, f64::INFINITY, 1.0, 1.0),
            Catenary::solve(Vector3::new(f64::NAN, 0.0, 0.0), b, 12.0, 1.0, 1.0),
            Catenary::solve(a, Vector3::new(0.0, f64::INFINITY, 0.0), 12.0, 1.0, 1.0),
            Catenary::solve(b, b, 12.0, 1.0, 1.0),
        ];
        for (i, r) in bad.iter().enumerate() {
            assert!(r.is_err(), "case {i} accepted: {r:?}");
            if let Err(e) = r {
                assert!(!e.to_string().is_empty());
            }
        }
        assert_eq!(
            Catenary::solve(a, b, -1.0, 1.0, 1.0).err(),
            Some(CatenaryError::NotPositive {
                what: "length",
                value: -1.0
            })
        );
    }

    #[test]
    fn random_configurations_converge() {
        // Deterministic LCG: broad sweep of slack/taut, up/down, stiff/soft cables.
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..2000 {
            let a = Vector3::new(next() * 100.0 - 50.0, next() * 100.0 - 50.0, next() * 100.0);
            let dir = Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5);
            if dir.norm() < 1e-3 {
                continue;
            }
            let chord = 1.0 + next() * 2000.0;
            let b = a + dir.normalize() * chord;
            let ratio = 0.9 + next() * 3.0;
            let l = chord * ratio;
            let w = 10f64.powf(next() * 4.0);
            let ea = 10f64.powf(4.0 + next() * 11.0);
            match Catenary::solve(a, b, l, w, ea) {
                Ok(_) => {
                    let c = check_closure(a, b, l, w, ea);
                    check_equilibrium(&c, l, w);
                }
                Err(e) => panic!("a={a:?} b={b:?} L={l} w={w} EA={ea}: {e}"),
            }
        }
    }
}
