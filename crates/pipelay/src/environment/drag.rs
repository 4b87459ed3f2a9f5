//! Morison drag (eq. 18) on a pipe in a flow, with its Jacobians.
use super::sea::Sea;
use nalgebra::{Matrix3, Vector3};

/// Morison drag per unit length with its Jacobians.
#[derive(Debug, Clone, Copy)]
pub struct Drag {
    /// Force per unit current length f = k_a|u_t|u_t + k_n|u_n|u_n (N/m).
    pub force: Vector3<f64>,
    /// ∂f/∂u.
    pub d_flow: Matrix3<f64>,
    /// ∂f/∂t.
    pub d_tangent: Matrix3<f64>,
}

/// ∂(|v|v)/∂v = |v|I + v⊗v/|v| (zero at v = 0).
pub fn quadratic_jacobian(v: &Vector3<f64>) -> Matrix3<f64> {
    let speed = v.norm();
    if speed == 0.0 {
        Matrix3::zeros()
    } else {
        Matrix3::identity() * speed + v * v.transpose() / speed
    }
}

/// Morison drag (eq. 18) on a pipe with unit tangent `t` in a flow `u` relative to the pipe:
/// axial and normal parts with coefficients k = ½ρ_w C_D d_o.
pub fn morison_drag(u: &Vector3<f64>, t: &Vector3<f64>, k_axial: f64, k_normal: f64) -> Drag {
    let u_t = t * t.dot(u);
    let u_n = u - u_t;
    let g_t = quadratic_jacobian(&u_t) * k_axial;
    let g_n = quadratic_jacobian(&u_n) * k_normal;
    let tt = t * t.transpose();
    Drag {
        force: morison_force(u, t, k_axial, k_normal),
        d_flow: g_t * tt + g_n * (Matrix3::identity() - tt),
        d_tangent: (g_t - g_n) * (t * u.transpose() + Matrix3::identity() * t.dot(u)),
    }
}

/// The force of [`morison_drag`] alone, f = k_a|u_t|u_t + k_n|u_n|u_n (N/m).
pub fn morison_force(
    u: &Vector3<f64>,
    t: &Vector3<f64>,
    k_axial: f64,
    k_normal: f64,
) -> Vector3<f64> {
    let u_t = t * t.dot(u);
    let u_n = u - u_t;
    u_t * (k_axial * u_t.norm()) + u_n * (k_normal * u_n.norm())
}

/// Nodal drag forces of one element held still in a steady current (statics), and their derivatives:
/// F = ½ℓ f(U(z_m), t) on each node, ℓ = |x2 − x1|, t = (x2 − x1)/ℓ, z_m the midpoint elevation.
/// Returns F and ∂F/∂x1, ∂F/∂x2.
pub fn element_current_drag(
    x1: &Vector3<f64>,
    x2: &Vector3<f64>,
    sea: &Sea,
    time: f64,
    k_axial: f64,
    k_normal: f64,
) -> (Vector3<f64>, Matrix3<f64>, Matrix3<f64>) {
    let chord = x2 - x1;
    let length = chord.norm();
    let t = chord / length;
    let (flow, flow_gradient) = sea.current_at(0.5 * (x1.z + x2.z), time);
    let drag = morison_drag(&flow, &t, k_axial, k_normal);
    let projector = Matrix3::identity() - t * t.transpose();
    let d_chord = 0.5 * (drag.force * t.transpose() + drag.d_tangent * projector);
    let d_depth = 0.5 * length * drag.d_flow * flow_gradient;
    let depth_part = 0.5 * d_depth * Vector3::z().transpose();
    (
        0.5 * length * drag.force,
        depth_part - d_chord,
        depth_part + d_chord,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::current::{Current, CurrentProfile};

    #[test]
    fn element_drag_jacobian_matches_finite_differences() {
        let current = Current::new(
            CurrentProfile::Linear {
                surface: Vector3::new(0.3, -0.8, 0.1),
            },
            0.0,
        )
        .expect("valid current");
        let sea = Sea::new(800.0, 1025.0, Some(current), None).expect("valid sea");
        let x1 = Vector3::new(10.0, 2.0, -300.0);
        let x2 = Vector3::new(14.0, -1.0, -310.0);
        let (_, d1, d2) = element_current_drag(&x1, &x2, &sea, 0.0, 0.2, 1.7);
        let h = 1e-6;
        for k in 0..3 {
            let mut e = Vector3::zeros();
            e[k] = h;
            let fd1 = (element_current_drag(&(x1 + e), &x2, &sea, 0.0, 0.2, 1.7).0
                - element_current_drag(&(x1 - e), &x2, &sea, 0.0, 0.2, 1.7).0)
                / (2.0 * h);
            let fd2 = (element_current_drag(&x1, &(x2 + e), &sea, 0.0, 0.2, 1.7).0
                - element_current_drag(&x1, &(x2 - e), &sea, 0.0, 0.2, 1.7).0)
                / (2.0 * h);
            assert!((fd1 - d1.column(k)).norm() < 1e-7 * d1.norm());
            assert!((fd2 - d2.column(k)).norm() < 1e-7 * d2.norm());
        }
    }
}
