//! Maps on the rotation group SO(3) (formulary `rod-statics.md` §5, Cayley map from
//! `rod-dynamics.md` §1–2).
//!
//! Rotations map material (body) coordinates to spatial (inertial) ones. `skew(a) b = a × b`.
//! Every map that divides by a power of θ = |θ| switches to its Taylor series for
//! θ < `SERIES_MAX`, so all of them are accurate to machine precision near θ = 0 and never
//! return NaN there.

use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// Below this angle the trigonometric coefficients are evaluated by their Taylor series
/// (six terms in θ², truncation error below 1e-17 relative at θ = 0.25).
const SERIES_MAX: f64 = 0.25;

/// Below this ratio |v|/w the quaternion logarithm uses the arctangent series (three terms,
/// truncation error below 2e-19 relative).
const ATAN_SERIES_MAX: f64 = 1e-3;

/// `minimal_rotation` treats obtuse `from`, `to` as antiparallel when |from × to| is below this
/// and then picks the half-turn axis by its e3 rule instead of from the cross product.
const ANTIPARALLEL_TOL: f64 = 1e-12;

/// Evaluates Σ cₖ xᵏ by Horner's rule.
fn horner(x: f64, coeffs: &[f64]) -> f64 {
    coeffs.iter().rev().fold(0.0, |acc, &c| acc * x + c)
}

/// sin θ / θ = Σ (−1)ᵏ θ²ᵏ/(2k+1)!.
fn sinc(t: f64) -> f64 {
    if t.abs() < SERIES_MAX {
        const C: [f64; 6] = [
            1.0,
            -1.0 / 6.0,
            1.0 / 120.0,
            -1.0 / 5_040.0,
            1.0 / 362_880.0,
            -1.0 / 39_916_800.0,
        ];
        horner(t * t, &C)
    } else {
        t.sin() / t
    }
}

/// (1 − cos θ)/θ² = ½ (sin(θ/2)/(θ/2))², free of cancellation for every θ.
fn one_minus_cos_over_sq(t: f64) -> f64 {
    let s = sinc(0.5 * t);
    0.5 * s * s
}

/// (θ − sin θ)/θ³ = Σ (−1)ᵏ θ²ᵏ/(2k+3)!.
fn theta_minus_sin_over_cube(t: f64) -> f64 {
    if t < SERIES_MAX {
        const C: [f64; 6] = [
            1.0 / 6.0,
            -1.0 / 120.0,
            1.0 / 5_040.0,
            -1.0 / 362_880.0,
            1.0 / 39_916_800.0,
            -1.0 / 6_227_020_800.0,
        ];
        horner(t * t, &C)
    } else {
        (t - t.sin()) / (t * t * t)
    }
}

/// γ = (1 − (θ/2) cot(θ/2))/θ² = Σ |B₂ₙ| θ²ⁿ⁻²/(2n)! = 1/12 + θ²/720 + θ⁴/30240 + …
fn dexp_inv_gamma(t: f64) -> f64 {
    if t < SERIES_MAX {
        const C: [f64; 6] = [
            1.0 / 12.0,
            1.0 / 720.0,
            1.0 / 30_240.0,
            1.0 / 1_209_600.0,
            1.0 / 47_900_160.0,
            691.0 / 1_307_674_368_000.0,
        ];
        horner(t * t, &C)
    } else {
        let h = 0.5 * t;
        (1.0 - h * h.cos() / h.sin()) / (t * t)
    }
}

/// Skew-symmetric matrix â with â b = a × b.
pub fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Axial vector of the skew part ½(m − mᵀ), the inverse of [`skew`].
pub fn axial(m: &Matrix3<f64>) -> Vector3<f64> {
    0.5 * Vector3::new(
        m[(2, 1)] - m[(1, 2)],
        m[(0, 2)] - m[(2, 0)],
        m[(1, 0)] - m[(0, 1)],
    )
}

/// Rodrigues: exp(θ̂) = I + (sin θ/θ) θ̂ + ((1 − cos θ)/θ²) θ̂².
pub fn exp(theta: &Vector3<f64>) -> Matrix3<f64> {
    let t = theta.norm();
    let w = skew(theta);
    Matrix3::identity() + w * sinc(t) + w * w * one_minus_cos_over_sq(t)
}

/// exp as a unit quaternion: (cos(θ/2), (sin(θ/2)/θ) θ).
pub fn exp_quat(theta: &Vector3<f64>) -> UnitQuaternion<f64> {
    let h = 0.5 * theta.norm();
    let v = theta * (0.5 * sinc(h));
    UnitQuaternion::new_unchecked(Quaternion::new(h.cos(), v.x, v.y, v.z))
}

/// Rotation vector of R (|θ| ≤ π): Shepperd's quaternion extraction, then [`log_quat`].
pub fn log(r: &Matrix3<f64>) -> Vector3<f64> {
    log_quat(&quat_from_matrix(r))
}

/// Rotation vector of q (|θ| ≤ π): flip q so that w ≥ 0, then θ = 2 atan2(|v|, w) v/|v|,
/// with 2 atan2(|v|, w)/|v| = (2/w)(1 − r²/3 + r⁴/5), r = |v|/w, for small r.
pub fn log_quat(q: &UnitQuaternion<f64>) -> Vector3<f64> {
    let (w, v) = if q.w < 0.0 {
        (-q.w, -q.imag())
    } else {
        (q.w, q.imag())
    };
    let n = v.norm();
    if n < ATAN_SERIES_MAX * w {
        let r2 = (n / w).powi(2);
        v * (2.0 / w * horner(r2, &[1.0, -1.0 / 3.0, 1.0 / 5.0]))
    } else {
        v * (2.0 * n.atan2(w) / n)
    }
}

/// Unit quaternion of R by Shepperd's method: the largest of 4w², 4x², 4y², 4z² (from the
/// trace and the diagonal) is taken by a square root, the others from off-diagonal sums.
pub fn quat_from_matrix(r: &Matrix3<f64>) -> UnitQuaternion<f64> {
    let tr = r.trace();
    let (r11, r22, r33) = (r[(0, 0)], r[(1, 1)], r[(2, 2)]);
    let q = if tr >= r11 && tr >= r22 && tr >= r33 {
        let s = 2.0 * (1.0 + tr).max(0.0).sqrt(); // 4w
        Quaternion::new(
            0.25 * s,
            (r[(2, 1)] - r[(1, 2)]) / s,
            (r[(0, 2)] - r[(2, 0)]) / s,
            (r[(1, 0)] - r[(0, 1)]) / s,
        )
    } else if r11 >= r22 && r11 >= r33 {
        let s = 2.0 * (1.0 + r11 - r22 - r33).max(0.0).sqrt(); // 4x
        Quaternion::new(
            (r[(2, 1)] - r[(1, 2)]) / s,
            0.25 * s,
            (r[(0, 1)] + r[(1, 0)]) / s,
            (r[(0, 2)] + r[(2, 0)]) / s,
        )
    } else if r22 >= r33 {
        let s = 2.0 * (1.0 - r11 + r22 - r33).max(0.0).sqrt(); // 4y
        Quaternion::new(
            (r[(0, 2)] - r[(2, 0)]) / s,
            (r[(0, 1)] + r[(1, 0)]) / s,
            0.25 * s,
            (r[(1, 2)] + r[(2, 1)]) / s,
        )
    } else {
        let s = 2.0 * (1.0 - r11 - r22 + r33).max(0.0).sqrt(); // 4z
        Quaternion::new(
            (r[(1, 0)] - r[(0, 1)]) / s,
            (r[(0, 2)] + r[(2, 0)]) / s,
            (r[(1, 2)] + r[(2, 1)]) / s,
            0.25 * s,
        )
    };
    UnitQuaternion::new_normalize(q)
}

/// Spatial dexp: T_L = I + ((1 − cos θ)/θ²) θ̂ + ((θ − sin θ)/θ³) θ̂², so that
/// R = exp(θ̂(t)) has Ṙ Rᵀ = (T_L θ̇)^.
pub fn tangent_left(theta: &Vector3<f64>) -> Matrix3<f64> {
    let t = theta.norm();
    let w = skew(theta);
    Matrix3::identity() + w * one_minus_cos_over_sq(t) + w * w * theta_minus_sin_over_cube(t)
}

/// Material dexp: T_R = T_Lᵀ = I − ((1 − cos θ)/θ²) θ̂ + ((θ − sin θ)/θ³) θ̂², so that
/// Rᵀ Ṙ = (T_R θ̇)^.
pub fn tangent_right(theta: &Vector3<f64>) -> Matrix3<f64> {
    let t = theta.norm();
    let w = skew(theta);
    Matrix3::identity() - w * one_minus_cos_over_sq(t) + w * w * theta_minus_sin_over_cube(t)
}

/// T_L⁻¹ = I − ½θ̂ + γθ̂², γ = (1 − (θ/2) cot(θ/2))/θ² (singular at θ = 2π).
pub fn tangent_left_inv(theta: &Vector3<f64>) -> Matrix3<f64> {
    let w = skew(theta);
    Matrix3::identity() - w * 0.5 + w * w * dexp_inv_gamma(theta.norm())
}

/// T_R⁻¹ = I + ½θ̂ + γθ̂², γ = (1 − (θ/2) cot(θ/2))/θ² (singular at θ = 2π).
pub fn tangent_right_inv(theta: &Vector3<f64>) -> Matrix3<f64> {
    let w = skew(theta);
    Matrix3::identity() + w * 0.5 + w * w * dexp_inv_gamma(theta.norm())
}

/// Cayley map cay(θ) = (I − ½θ̂)⁻¹(I + ½θ̂) = I + (θ̂ + ½θ̂²)/(1 + |θ|²/4).
#[inline]
pub fn cayley(theta: &Vector3<f64>) -> Matrix3<f64> {
    // θ̂² = θθᵀ − |θ|²I, written out rather than multiplied.
    let norm2 = theta.norm_squared();
    let factor = 1.0 / (1.0 + 0.25 * norm2);
    let w = skew(theta) * factor;
    let half = 0.5 * factor;
    Matrix3::identity() * (1.0 - half * norm2) + w + theta * theta.transpose() * half
}

/// The Cayley parameter θ of a rotation: cay(θ) = R (quaternion (w, v) ↦ 2v/w).
pub fn cayley_parameter(rotation: &UnitQuaternion<f64>) -> Vector3<f64> {
    let q = rotation.quaternion();
    let sign = if q.w < 0.0 { -1.0 } else { 1.0 };
    2.0 * sign * q.imag() / q.w.abs().max(1e-300)
}

/// The unit quaternion of cay(θ): (1, θ/2) normalised.
pub fn cayley_quaternion(theta: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        1.0,
        0.5 * theta.x,
        0.5 * theta.y,
        0.5 * theta.z,
    ))
}

/// Spatial tangent of the Cayley map: δQ Qᵀ = (T δθ)^ for Q = cay(θ), with
/// T = (I + ½θ̂)/(1 + |θ|²/4).
pub fn cayley_tangent(theta: &Vector3<f64>) -> Matrix3<f64> {
    (Matrix3::identity() + skew(theta) * 0.5) / (1.0 + 0.25 * theta.norm_squared())
}

/// Rotation by ∠(f, t) about f × t for f·t ≥ 0: the unit quaternion ∝ (1 + f·t, f × t).
fn acute_rotation(f: &Vector3<f64>, t: &Vector3<f64>) -> Matrix3<f64> {
    UnitQuaternion::new_normalize(Quaternion::from_parts(1.0 + f.dot(t), f.cross(t)))
        .to_rotation_matrix()
        .into_inner()
}

/// Smallest rotation taking the direction of `from` to that of `to` (the inputs are
/// normalised; the identity is returned if either is zero).
///
/// For f·t ≥ 0 it is the unit quaternion ∝ (1 + f·t, f × t). For f·t < 0 it is composed as
/// a half turn 2aaᵀ − I about the unit axis a ∝ f × t (made exactly ⟂ f), which takes f to −f,
/// followed by the acute rotation −f → t; both turn about the same axis, so the sum of the
/// angles is ∠(f, t), and R f = t holds to rounding even for nearly antiparallel inputs.
/// If |f × t| < 1e-12 (antiparallel) the axis is a ∝ f × e3 (⟂ f and e3), or e1 when f = ±e3.
pub fn minimal_rotation(from: &Vector3<f64>, to: &Vector3<f64>) -> Matrix3<f64> {
    let (Some(f), Some(t)) = (from.try_normalize(0.0), to.try_normalize(0.0)) else {
        return Matrix3::identity();
    };
    if f.dot(&t) >= 0.0 {
        return acute_rotation(&f, &t);
    }
    let n = f.cross(&t);
    let axis = if n.norm() >= ANTIPARALLEL_TOL {
        (n - f * n.dot(&f)).normalize()
    } else {
        f.cross(&Vector3::z())
            .try_normalize(0.0)
            .unwrap_or_else(|| (Vector3::x() - f * f.x).normalize())
    };
    let half_turn = axis * axis.transpose() * 2.0 - Matrix3::identity();
    acute_rotation(&-f, &t) * half_turn
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::PI;

    #[test]
    fn cayley_parameter_inverts_the_cayley_map() {
        let theta = Vector3::new(0.3, -1.2, 2.5);
        let q = cayley_quaternion(&theta);
        assert!((cayley_parameter(&q) - theta).norm() < 1e-12);
        let m = q.to_rotation_matrix().into_inner();
        assert!((m - cayley(&theta)).abs().max() < 1e-14);
    }

    /// Random rotation vectors: |θ| uniform in [0, 3.1) or log-uniform in [1e-10, 1e-3).
    fn rotvec() -> impl Strategy<Value = Vector3<f64>> {
        let dir = (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
            .prop_filter("non-degenerate direction", |(x, y, z)| {
                x * x + y * y + z * z > 1e-4
            })
            .prop_map(|(x, y, z)| Vector3::new(x, y, z).normalize());
        let mag = prop_oneof![0.0..3.1f64, (-10.0..-3.0f64).prop_map(|e| 10f64.powf(e)),];
        (dir, mag).prop_map(|(d, m)| d * m)
    }

    fn unit_vec() -> impl Strategy<Value = Vector3<f64>> {
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
            .prop_filter("non-degenerate direction", |(x, y, z)| {
                x * x + y * y + z * z > 1e-4
            })
            .prop_map(|(x, y, z)| Vector3::new(x, y, z).normalize())
    }

    fn orthogonality_error(r: &Matrix3<f64>) -> f64 {
        (r.transpose() * r - Matrix3::identity()).norm()
    }

    /// Columns k of axial((F(θ + h e_k) − F(θ − h e_k))/(2h) · F(θ)ᵀ): central FD of the
    /// spatial tangent of a map F into SO(3).
    fn fd_spatial_tangent(
        f: impl Fn(&Vector3<f64>) -> Matrix3<f64>,
        theta: &Vector3<f64>,
    ) -> Matrix3<f64> {
        let h = 1e-6;
        let r0 = f(theta);
        let mut t = Matrix3::zeros();
        for k in 0..3 {
            let mut e = Vector3::zeros();
            e[k] = h;
            let dr = (f(&(theta + e)) - f(&(theta - e))) / (2.0 * h);
            t.set_column(k, &axial(&(dr * r0.transpose())));
        }
        t
    }

    #[test]
    fn skew_is_cross_product_and_axial_inverts_it() {
        let a = Vector3::new(0.3, -1.2, 2.5);
        let b = Vector3::new(-0.7, 0.4, 1.1);
        assert!((skew(&a) * b - a.cross(&b)).norm() < 1e-15);
        assert_eq!(axial(&skew(&a)), a);
        // axial takes only the skew part.
        let sym = Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 5.0, 3.0, 5.0, 6.0);
        assert!((axial(&(skew(&a) + sym)) - a).norm() < 1e-15);
    }

    #[test]
    fn zero_rotation_is_exact() {
        let z = Vector3::zeros();
        let i = Matrix3::identity();
        assert_eq!(exp(&z), i);
        assert_eq!(exp_quat(&z), UnitQuaternion::identity());
        assert_eq!(log(&i), z);
        assert_eq!(log_quat(&UnitQuaternion::identity()), z);
        assert_eq!(tangent_left(&z), i);
        assert_eq!(tangent_right(&z), i);
        assert_eq!(tangent_left_inv(&z), i);
        assert_eq!(tangent_right_inv(&z), i);
        assert_eq!(cayley(&z), i);
        assert_eq!(cayley_tangent(&z), i);
    }

    #[test]
    fn series_coefficients_are_continuous_at_the_switch() {
        let below = f64::from_bits(SERIES_MAX.to_bits() - 1); // the next float down
        let above = SERIES_MAX;
        // The direct (θ − sin θ)/θ³ and γ lose ~ε/θ² to cancellation (ε-level in the matrices).
        let jump = |f: fn(f64) -> f64| (f(below) - f(above)).abs() / f(above).abs();
        assert!(jump(sinc) < 1e-15, "sinc: {:e}", jump(sinc));
        let c = jump(theta_minus_sin_over_cube);
        assert!(c < 1e-14, "(θ − sin θ)/θ³: {c:e}");
        let g = jump(dexp_inv_gamma);
        assert!(g < 5e-14, "γ: {g:e}");
    }

    #[test]
    fn exp_small_angle_matches_first_order() {
        let theta = Vector3::new(1e-9, -2e-9, 3e-9);
        let r = exp(&theta);
        // exp(θ̂) = I + θ̂ + ½θ̂² + O(θ³); the quadratic term is ~1e-17.
        let first = Matrix3::identity() + skew(&theta);
        assert!((r - first).amax() < 1e-16);
        let back = log(&r);
        assert!((back - theta).norm() <= 1e-15 * theta.norm());
    }

    #[test]
    fn log_near_and_at_pi() {
        for axis in [
            Vector3::new(1.0, 2.0, -0.5).normalize(),
            Vector3::z(),
            Vector3::new(-1.0, 0.0, 0.0),
        ] {
            let theta = axis * (PI - 1e-7);
            let err = (log(&exp(&theta)) - theta).norm();
            assert!(err < 1e-14, "near π: {err:e}");
            let r = exp(&(axis * PI));
            let back = log(&r);
            assert!((back.norm() - PI).abs() < 1e-15);
            assert!((exp(&back) - r).norm() < 1e-15);
        }
    }

    #[test]
    fn minimal_rotation_special_cases() {
        let e = [Vector3::x(), Vector3::y(), Vector3::z()];
        for a in &e {
            // Parallel: the identity.
            assert!((minimal_rotation(a, a) - Matrix3::identity()).norm() < 1e-15);
            // Antiparallel: a half turn about an axis ⟂ `from`, ⟂ e3 when `from` is not ±e3.
            let r = minimal_rotation(a, &-a);
            assert!((r * a + a).norm() < 1e-15);
            assert!(orthogonality_error(&r) < 1e-15);
            assert!((r.determinant() - 1.0).abs() < 1e-15);
            let axis = log(&r);
            assert!((axis.norm() - PI).abs() < 1e-15);
            assert!(axis.dot(a).abs() < 1e-15);
            assert!(axis.z.abs() < 1e-15);
        }
        // Deterministic choices of the axis.
        assert!(
            (log(&minimal_rotation(&Vector3::x(), &-Vector3::x()))
                .normalize()
                .y
                .abs()
                - 1.0)
                .abs()
                < 1e-15
        );
        assert!(
            (log(&minimal_rotation(&Vector3::z(), &-Vector3::z()))
                .normalize()
                .x
                .abs()
                - 1.0)
                .abs()
                < 1e-15
        );
        // A general antiparallel pair, not normalised on input.
        let f = Vector3::new(1.0, 2.0, 3.0);
        let r = minimal_rotation(&f, &(-2.0 * f));
        assert!((r * f.normalize() + f.normalize()).norm() < 1e-15);
        assert!(log(&r).z.abs() < 1e-15);
        // Degenerate input.
        assert_eq!(
            minimal_rotation(&Vector3::zeros(), &Vector3::x()),
            Matrix3::identity()
        );
        // Nearly antiparallel (also below the axis tolerance): still maps from → to, and the
        // angle is ∠(from, to) up to the tolerance.
        let f = Vector3::new(0.6, -0.8, 0.0);
        for eps in [1e-3, 1e-7, 1e-10, 1e-14] {
            let t = -(f + Vector3::new(0.3, 0.2, 1.0) * eps).normalize();
            let r = minimal_rotation(&f, &t);
            assert!((r * f - t).norm() < 1e-15, "eps {eps:e}");
            assert!(orthogonality_error(&r) < 1e-15);
            let angle = f.cross(&t).norm().atan2(f.dot(&t));
            assert!((log(&r).norm() - angle).abs() < 1e-12);
        }
    }

    proptest! {
        #[test]
        fn exp_is_a_rotation(theta in rotvec()) {
            let r = exp(&theta);
            prop_assert!(orthogonality_error(&r) < 1e-14);
            prop_assert!((r.determinant() - 1.0).abs() < 1e-14);
        }

        #[test]
        fn log_inverts_exp(theta in rotvec()) {
            let err = (log(&exp(&theta)) - theta).norm();
            prop_assert!(err <= 1e-14 * theta.norm(), "err {:e} for |θ| = {}", err, theta.norm());
            let errq = (log_quat(&exp_quat(&theta)) - theta).norm();
            prop_assert!(errq <= 1e-14 * theta.norm(), "quat err {:e}", errq);
        }

        #[test]
        fn exp_inverts_log(theta in rotvec(), turns in -2i32..3) {
            // Any rotation, including those given by vectors beyond π.
            let big = theta + theta.try_normalize(0.0).unwrap_or(Vector3::x()) * (2.0 * PI * f64::from(turns));
            let r = exp(&big);
            let back = log(&r);
            prop_assert!(back.norm() <= PI + 1e-15);
            prop_assert!((exp(&back) - r).norm() < 1e-14);
        }

        #[test]
        fn exp_quat_agrees_with_exp(theta in rotvec()) {
            let q = exp_quat(&theta);
            prop_assert!((q.to_rotation_matrix().into_inner() - exp(&theta)).norm() < 1e-15 * 4.0);
            prop_assert!((quat_from_matrix(&exp(&theta)).angle_to(&q)) < 1e-14);
            prop_assert!((q.norm() - 1.0).abs() < 1e-15);
        }

        #[test]
        fn tangents_match_finite_differences(theta in rotvec()) {
            let tl = tangent_left(&theta);
            let tr = tangent_right(&theta);
            prop_assert!((tl - fd_spatial_tangent(exp, &theta)).norm() < 1e-7);
            // Material tangent: Rᵀ Ṙ = Rᵀ (Ṙ Rᵀ) R.
            let r = exp(&theta);
            let tr_fd = r.transpose() * fd_spatial_tangent(exp, &theta);
            prop_assert!((tr - tr_fd).norm() < 1e-7);
            prop_assert!((tr - tl.transpose()).norm() < 1e-15);
            prop_assert!((tl - r * tr).norm() < 1e-14);
        }

        #[test]
        fn tangent_inverses(theta in rotvec()) {
            let i = Matrix3::identity();
            prop_assert!((tangent_left_inv(&theta) * tangent_left(&theta) - i).norm() < 1e-14);
            prop_assert!((tangent_right_inv(&theta) * tangent_right(&theta) - i).norm() < 1e-14);
        }

        #[test]
        fn cayley_is_a_rotation_with_its_tangent(theta in rotvec()) {
            let q = cayley(&theta);
            prop_assert!(orthogonality_error(&q) < 1e-14);
            prop_assert!((q.determinant() - 1.0).abs() < 1e-14);
            let w = skew(&theta);
            let i = Matrix3::identity();
            let lu = (i - w * 0.5).lu();
            let q_def = lu.solve(&(i + w * 0.5));
            prop_assert!(q_def.is_some_and(|m| (m - q).norm() < 1e-14));
            prop_assert!((cayley_tangent(&theta) - fd_spatial_tangent(cayley, &theta)).norm() < 1e-7);
        }

        #[test]
        fn minimal_rotation_maps_from_to(from in unit_vec(), to in unit_vec()) {
            let r = minimal_rotation(&from, &to);
            prop_assert!((r * from - to).norm() < 1e-14);
            prop_assert!(orthogonality_error(&r) < 1e-14);
            // Smallest: the angle equals ∠(from, to) and the axis is ⟂ both.
            let theta = log(&r);
            let angle = from.cross(&to).norm().atan2(from.dot(&to));
            prop_assert!((theta.norm() - angle).abs() < 1e-14);
            prop_assert!(theta.dot(&from).abs() < 1e-14 && theta.dot(&to).abs() < 1e-14);
            let back = minimal_rotation(&to, &from);
            prop_assert!((back * r - Matrix3::identity()).norm() < 1e-14);
        }
    }
}
