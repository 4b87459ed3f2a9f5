//! Fossen's zyx Euler angles Θ = [φ, θ, ψ] (roll, pitch, yaw) for 6-DOF vessel kinematics
//! (Fossen, *Handbook of Marine Craft Hydrodynamics and Motion Control*, §2.2).
//!
//! R(Θ) = Rz(ψ) Ry(θ) Rx(φ) maps body coordinates to inertial ones.

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
use std::f64::consts::PI;

/// |cos θ| below which the angle-rate map T(Θ) is treated as singular (gimbal lock).
const GIMBAL_TOL: f64 = 1e-12;

/// |cos θ| = √(r32² + r33²) below which `angles_from_rotation` sets φ = 0. Setting φ = 0
/// changes the reconstructed R by about 2|cos θ|, so this is kept at rounding level.
const GIMBAL_LOCK_COS: f64 = 64.0 * f64::EPSILON;

/// R(Θ) = Rz(ψ) Ry(θ) Rx(φ) =
/// [[cψcθ, −sψcφ + cψsθsφ, sψsφ + cψcφsθ], [sψcθ, cψcφ + sφsθsψ, −cψsφ + sθsψcφ], [−sθ, cθsφ, cθcφ]].
pub fn rotation(angles: &Vector3<f64>) -> Matrix3<f64> {
    let (sf, cf) = angles.x.sin_cos();
    let (st, ct) = angles.y.sin_cos();
    let (sp, cp) = angles.z.sin_cos();
    Matrix3::new(
        cp * ct,
        -sp * cf + cp * st * sf,
        sp * sf + cp * cf * st,
        sp * ct,
        cp * cf + sf * st * sp,
        -cp * sf + st * sp * cf,
        -st,
        ct * sf,
        ct * cf,
    )
}

/// Fossen's T(Θ) with Θ̇ = T(Θ) ω_body:
/// [[1, sφtθ, cφtθ], [0, cφ, −sφ], [0, sφ/cθ, cφ/cθ]]; `None` when |cos θ| < 1e-12.
pub fn angle_rate_map(angles: &Vector3<f64>) -> Option<Matrix3<f64>> {
    let (sf, cf) = angles.x.sin_cos();
    let (st, ct) = angles.y.sin_cos();
    if ct.abs() < GIMBAL_TOL {
        return None;
    }
    let tt = st / ct;
    Some(Matrix3::new(
        1.0,
        sf * tt,
        cf * tt,
        0.0,
        cf,
        -sf,
        0.0,
        sf / ct,
        cf / ct,
    ))
}

/// J(η) = diag(R(Θ), T(Θ)) with η = [x, y, z, φ, θ, ψ] and η̇ = J(η) ν; `None` at gimbal lock.
pub fn jacobian(eta: &Vector6<f64>) -> Option<Matrix6<f64>> {
    let angles: Vector3<f64> = eta.fixed_rows::<3>(3).into_owned();
    let t = angle_rate_map(&angles)?;
    let mut j = Matrix6::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(&rotation(&angles));
    j.fixed_view_mut::<3, 3>(3, 3).copy_from(&t);
    Some(j)
}

/// Π_e (paper eq. (9)): spatial angular velocity w = Π_e Θ̇ with
/// Π_e = [[cθcψ, −sψ, 0], [cθsψ, cψ, 0], [−sθ, 0, 1]] = R(Θ) T(Θ)⁻¹ (columns: ψ̇ e3,
/// θ̇ Rz e2, φ̇ Rz Ry e1).
pub fn spatial_rate_map(angles: &Vector3<f64>) -> Matrix3<f64> {
    let (st, ct) = angles.y.sin_cos();
    let (sp, cp) = angles.z.sin_cos();
    Matrix3::new(ct * cp, -sp, 0.0, ct * sp, cp, 0.0, -st, 0.0, 1.0)
}

/// Maps an angle from atan2's [−π, π] to (−π, π].
fn wrap(a: f64) -> f64 {
    if a <= -PI {
        a + 2.0 * PI
    } else {
        a
    }
}

/// Inverse of [`rotation`]: φ = atan2(r32, r33), θ = atan2(−r31, √(r32² + r33²)) ∈ [−π/2, π/2],
/// and ψ from R Rx(φ)ᵀ = Rz(ψ) Ry(θ), whose second column is (−sψ, cψ, 0):
/// ψ = atan2(sφ r13 − cφ r12, cφ r22 − sφ r23). Because ψ is taken consistently with the
/// computed φ, R is reproduced to rounding also near θ = ±π/2; at gimbal lock
/// (√(r32² + r33²) < 64ε) φ = 0. φ, ψ ∈ (−π, π].
pub fn angles_from_rotation(r: &Matrix3<f64>) -> Vector3<f64> {
    let ct = r[(2, 1)].hypot(r[(2, 2)]);
    let phi = if ct < GIMBAL_LOCK_COS {
        0.0
    } else {
        wrap(r[(2, 1)].atan2(r[(2, 2)]))
    };
    let theta = (-r[(2, 0)]).atan2(ct);
    let (sf, cf) = phi.sin_cos();
    let psi = wrap((sf * r[(0, 2)] - cf * r[(0, 1)]).atan2(cf * r[(1, 1)] - sf * r[(1, 2)]));
    Vector3::new(phi, theta, psi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::so3::{axial, exp, skew};
    use nalgebra::{Rotation3, UnitQuaternion};
    use proptest::prelude::*;
    use std::f64::consts::FRAC_PI_2;

    /// Angles with φ, ψ ∈ (−π, π] and θ ∈ [−π/2, π/2].
    fn angles() -> impl Strategy<Value = Vector3<f64>> {
        (-PI..PI, -FRAC_PI_2..FRAC_PI_2, -PI..PI).prop_map(|(a, b, c)| Vector3::new(a, b, c))
    }

    /// Random rotations (normalised 4-vectors as quaternions).
    fn rotation_matrix() -> impl Strategy<Value = Matrix3<f64>> {
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
            .prop_filter("non-degenerate", |(w, x, y, z)| {
                w * w + x * x + y * y + z * z > 1e-4
            })
            .prop_map(|(w, x, y, z)| {
                UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z))
                    .to_rotation_matrix()
                    .into_inner()
            })
    }

    /// Difference of angles modulo 2π, in (−π, π].
    fn angle_diff(a: &Vector3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
        (a - b).map(|d| wrap((d + PI).rem_euclid(2.0 * PI) - PI))
    }

    #[test]
    fn rotation_matches_composition_of_elementary_rotations() {
        let a = Vector3::new(0.3, -0.7, 2.1);
        let rz = Rotation3::from_axis_angle(&Vector3::z_axis(), a.z);
        let ry = Rotation3::from_axis_angle(&Vector3::y_axis(), a.y);
        let rx = Rotation3::from_axis_angle(&Vector3::x_axis(), a.x);
        let expected = (rz * ry * rx).into_inner();
        assert!((rotation(&a) - expected).norm() < 1e-15);
        let nalg = Rotation3::from_euler_angles(a.x, a.y, a.z).into_inner();
        assert!((rotation(&a) - nalg).norm() < 1e-15);
    }

    #[test]
    fn jacobian_structure_and_singularity() {
        let eta = Vector6::new(1.0, 2.0, 3.0, 0.2, -0.4, 1.3);
        let angles = Vector3::new(0.2, -0.4, 1.3);
        let j = jacobian(&eta);
        let t = angle_rate_map(&angles);
        assert!(j.is_some() && t.is_some());
        if let (Some(j), Some(t)) = (j, t) {
            assert_eq!(j.fixed_view::<3, 3>(0, 0), rotation(&angles));
            assert_eq!(j.fixed_view::<3, 3>(3, 3), t);
            assert_eq!(j.fixed_view::<3, 3>(0, 3), Matrix3::zeros());
            assert_eq!(j.fixed_view::<3, 3>(3, 0), Matrix3::zeros());
        }
        for pitch in [FRAC_PI_2, -FRAC_PI_2] {
            let eta = Vector6::new(0.0, 0.0, 0.0, 0.3, pitch, -1.0);
            assert!(jacobian(&eta).is_none());
            assert!(angle_rate_map(&Vector3::new(0.3, pitch, -1.0)).is_none());
        }
        assert!(angle_rate_map(&Vector3::new(0.3, FRAC_PI_2 - 1e-6, -1.0)).is_some());
    }

    #[test]
    fn gimbal_lock_reconstructs_rotation() {
        for pitch in [FRAC_PI_2, -FRAC_PI_2] {
            for (roll, yaw) in [(0.3, -1.0), (-2.5, 3.0), (PI, PI), (0.0, 0.0)] {
                let r = rotation(&Vector3::new(roll, pitch, yaw));
                let a = angles_from_rotation(&r);
                assert_eq!(a.x, 0.0);
                assert!((a.y - pitch).abs() < 1e-15);
                assert!((rotation(&a) - r).norm() < 1e-15);
            }
        }
        // Identity and the ±π boundaries of the range.
        assert_eq!(angles_from_rotation(&Matrix3::identity()), Vector3::zeros());
        let a = angles_from_rotation(&rotation(&Vector3::new(PI, 0.0, -PI)));
        assert!((a - Vector3::new(PI, 0.0, PI)).norm() < 1e-15);
    }

    proptest! {
        #[test]
        fn rotation_is_orthogonal(a in angles()) {
            let r = rotation(&a);
            prop_assert!((r.transpose() * r - Matrix3::identity()).norm() < 1e-15 * 4.0);
            prop_assert!((r.determinant() - 1.0).abs() < 1e-15 * 4.0);
        }

        #[test]
        fn angles_round_trip_random_rotation(r in rotation_matrix()) {
            let a = angles_from_rotation(&r);
            prop_assert!((rotation(&a) - r).norm() < 1e-14);
            prop_assert!(a.x > -PI && a.x <= PI && a.z > -PI && a.z <= PI);
            prop_assert!(a.y.abs() <= FRAC_PI_2);
        }

        #[test]
        fn angles_round_trip_away_from_singularity(
            a in (-PI..PI, -(FRAC_PI_2 - 1e-3)..(FRAC_PI_2 - 1e-3), -PI..PI)
        ) {
            let a = Vector3::new(a.0, a.1, a.2);
            let back = angles_from_rotation(&rotation(&a));
            prop_assert!(angle_diff(&back, &a).norm() < 1e-9);
        }

        #[test]
        fn angles_round_trip_near_gimbal_lock(
            roll in -PI..PI, yaw in -PI..PI, delta in 0.0..1e-9f64, sign in prop::bool::ANY,
        ) {
            let pitch = if sign { FRAC_PI_2 - delta } else { -FRAC_PI_2 + delta };
            let r = rotation(&Vector3::new(roll, pitch, yaw));
            let a = angles_from_rotation(&r);
            prop_assert!((rotation(&a) - r).norm() < 1e-13);
            prop_assert!((a.y - pitch).abs() < 1e-13);
        }

        #[test]
        fn angle_rate_map_matches_finite_differences(
            a in (-3.0..3.0f64, -1.4..1.4f64, -3.0..3.0f64),
            w in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
        ) {
            let a = Vector3::new(a.0, a.1, a.2);
            let w = Vector3::new(w.0, w.1, w.2);
            let h = 1e-6;
            let r = rotation(&a);
            // dR/dt = R ω̂ (body angular velocity): R(±h) = R exp(±h ω).
            let plus = angles_from_rotation(&(r * exp(&(w * h))));
            let minus = angles_from_rotation(&(r * exp(&(-w * h))));
            let rate_fd = angle_diff(&plus, &minus) / (2.0 * h);
            let t = angle_rate_map(&a);
            prop_assert!(t.is_some_and(|t| (t * w - rate_fd).norm() < 1e-7));
        }

        #[test]
        fn spatial_rate_map_matches_finite_differences(a in angles(), rate in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)) {
            let rate = Vector3::new(rate.0, rate.1, rate.2);
            let h = 1e-6;
            let dr = (rotation(&(a + rate * h)) - rotation(&(a - rate * h))) / (2.0 * h);
            let w_fd = axial(&(dr * rotation(&a).transpose()));
            let pi_e = spatial_rate_map(&a);
            prop_assert!((pi_e * rate - w_fd).norm() < 1e-8);
            // Exactly skew: Ṙ Rᵀ has no symmetric part beyond FD error.
            prop_assert!((dr * rotation(&a).transpose() - skew(&w_fd)).norm() < 1e-8);
        }

        #[test]
        fn spatial_rate_map_is_r_times_t_inverse(a in (-PI..PI, -1.5..1.5f64, -PI..PI)) {
            let a = Vector3::new(a.0, a.1, a.2);
            let t = angle_rate_map(&a);
            prop_assert!(t.is_some_and(|t| (spatial_rate_map(&a) * t - rotation(&a)).norm() < 1e-13));
        }
    }
}
