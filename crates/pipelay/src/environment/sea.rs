//! The sea: depth, water density, current profiles, and Morison drag (eq. 18).
use crate::error::{finite, non_negative, positive, Error, Result};
use nalgebra::{Matrix3, Vector3};

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

/// Water depth, density and current. The seabed is z = 0, the surface z = −depth.
#[derive(Debug, Clone, PartialEq)]
pub struct Sea {
    pub depth: f64,
    pub density: f64,
    pub current: Option<Current>,
}

impl Sea {
    /// Checks and builds a sea.
    pub fn new(depth: f64, density: f64, current: Option<Current>) -> Result<Self> {
        positive("depth", depth, "m")?;
        non_negative("density", density, "kg/m³")?;
        Ok(Sea {
            depth,
            density,
            current,
        })
    }

    /// Current velocity and depth gradient at elevation z and time t.
    pub fn current_at(&self, z: f64, time: f64) -> (Vector3<f64>, Vector3<f64>) {
        match &self.current {
            Some(c) => c.velocity_and_gradient(z, self.depth, time),
            None => (Vector3::zeros(), Vector3::zeros()),
        }
    }
}

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
fn quadratic_jacobian(v: &Vector3<f64>) -> Matrix3<f64> {
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
        force: u_t * (k_axial * u_t.norm()) + u_n * (k_normal * u_n.norm()),
        d_flow: g_t * tt + g_n * (Matrix3::identity() - tt),
        d_tangent: (g_t - g_n) * (t * u.transpose() + Matrix3::identity() * t.dot(u)),
    }
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

    #[test]
    fn element_drag_jacobian_matches_finite_differences() {
        let current = Current::new(
            CurrentProfile::Linear {
                surface: Vector3::new(0.3, -0.8, 0.1),
            },
            0.0,
        )
        .expect("valid current");
        let sea = Sea::new(800.0, 1025.0, Some(current)).expect("valid sea");
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
