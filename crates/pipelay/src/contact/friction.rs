//! The seabed's friction at one node: an elastic slip returned radially onto the friction circle, and its
//! exact derivatives (see [`crate::contact::seabed`] for the model and its energy–momentum form).
//!
//! With n̂ the seabed's outward normal at the evaluation point, the axial direction is â = b/|b|,
//! b = (I − n̂n̂ᵀ)t1, and the lateral one l̂ = n̂ × â. A step moves the slip by Δu = (â·Δx, l̂·Δx); the trial
//! e_tr = e_n + Δu returns to e = r e_tr/|e_tr| when it leaves the circle of radius r = δ_m N/(w ℓ_a), else
//! e = e_tr; Δp = e_tr − e is the slip. The force is −Q K e (statics) or −Q K ē − ½(KΔe·Δp)Δx/|Δx|² (the
//! energy–momentum step), Q = [â l̂]. Its derivatives with respect to Δx, t1 and N follow the same chain, on
//! the branch (sticking or sliding) the return map took.
use crate::contact::rule::ContactRule;
use crate::environment::bathymetry::Bathymetry;
use crate::so3::skew;
use nalgebra::{Matrix2, Matrix2x3, Matrix3, RowVector3, Vector2, Vector3};

/// One node's friction in a step: the force on the node, the elastic slip at the end and the dissipation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionStep {
    pub force: Vector3<f64>,
    pub slip: Vector2<f64>,
    pub dissipated: f64,
    /// ∂force/∂Δx, ∂force/∂t1 and ∂force/∂N, when asked for.
    pub tangent: Option<FrictionTangent>,
}

/// Derivatives of the friction force of one node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionTangent {
    pub displacement: Matrix3<f64>,
    pub axis: Matrix3<f64>,
    pub normal_force: Vector3<f64>,
}

/// What a friction evaluation needs of one node: start position and elastic slip, friction spring and
/// elastic radius per newton of normal force.
#[derive(Debug, Clone, Copy)]
pub struct FrictionNode<'a> {
    pub bathymetry: &'a Bathymetry,
    pub start: Vector3<f64>,
    pub slip_start: Vector2<f64>,
    /// K = diag(axial, lateral) (N/m).
    pub stiffness: Vector2<f64>,
    /// δ_m/(w ℓ_a) (m/N).
    pub yield_per_force: f64,
}

/// A unit direction and its derivatives with respect to Δx and t1.
#[derive(Debug, Clone, Copy)]
struct Direction {
    value: Vector3<f64>,
    displacement: Matrix3<f64>,
    axis: Matrix3<f64>,
}

impl FrictionNode<'_> {
    /// The friction of a step by displacement Δx, with section axis t1 at the evaluation point and normal force
    /// N (N) at the step's end; with `with_tangent`, its exact derivatives too.
    pub fn step(
        &self,
        rule: ContactRule,
        displacement: &Vector3<f64>,
        axis: &Vector3<f64>,
        normal_force: f64,
        with_tangent: bool,
    ) -> FrictionStep {
        let (normal, d_normal) = self.normal(rule, displacement);
        let (axial, lateral) = directions(&normal, with_tangent.then_some(&d_normal), axis);
        let dx = displacement;
        // Δu = (â·Δx, l̂·Δx).
        let du = Vector2::new(axial.value.dot(dx), lateral.value.dot(dx));
        let trial = self.slip_start + du;
        let radius = self.yield_per_force * normal_force.max(0.0);
        let size = trial.norm();
        let sliding = size > radius;
        // The return map e(e_tr, N) and its derivatives.
        let (slip, slip_by_trial, slip_by_normal) = if sliding && size > 0.0 {
            let direction = trial / size;
            let by_radius = if normal_force > 0.0 {
                self.yield_per_force
            } else {
                0.0
            };
            (
                direction * radius,
                (Matrix2::identity() - direction * direction.transpose()) * (radius / size),
                direction * by_radius,
            )
        } else {
            (trial, Matrix2::identity(), Vector2::zeros())
        };
        let plastic = trial - slip;
        let stiffness = Matrix2::from_diagonal(&self.stiffness);
        // The slip the spring acts on: the end's (statics) or the step's mean (energy–momentum).
        let (acting, share) = match rule {
            ContactRule::Static => (slip, 1.0),
            ContactRule::EnergyMomentum { .. } => (0.5 * (self.slip_start + slip), 0.5),
        };
        let spring = stiffness * acting;
        let mut force = -(axial.value * spring.x + lateral.value * spring.y);
        let mut dissipated = 0.0;
        // The energy–momentum correction −φΔx, φ = ½(KΔe·Δp)/|Δx|².
        let d2 = dx.norm_squared();
        let correction = matches!(rule, ContactRule::EnergyMomentum { .. }) && d2 > 1e-40;
        let change = slip - self.slip_start;
        let phi = if correction {
            0.5 * (stiffness * change).dot(&plastic) / d2
        } else {
            0.0
        };
        force -= dx * phi;
        if matches!(rule, ContactRule::EnergyMomentum { .. }) {
            dissipated = (stiffness * slip).dot(&plastic);
        }
        let tangent = with_tangent.then(|| {
            let q = nalgebra::Matrix3x2::from_columns(&[axial.value, lateral.value]);
            // dΔu (2×3).
            let du_dx = Matrix2x3::from_rows(&[
                axial.value.transpose() + dx.transpose() * axial.displacement,
                lateral.value.transpose() + dx.transpose() * lateral.displacement,
            ]);
            let du_da =
                Matrix2x3::from_rows(&[dx.transpose() * axial.axis, dx.transpose() * lateral.axis]);
            let slip_dx = slip_by_trial * du_dx;
            let slip_da = slip_by_trial * du_da;
            // −d(Q K e_acting) = −Q K share de − dâ (K e_acting)_x − dl̂ (K e_acting)_y.
            let spring_part =
                |slip_d: &Matrix2x3<f64>, axial_d: &Matrix3<f64>, lateral_d: &Matrix3<f64>| {
                    -(q * stiffness * slip_d * share + axial_d * spring.x + lateral_d * spring.y)
                };
            let mut by_dx = spring_part(&slip_dx, &axial.displacement, &lateral.displacement);
            let mut by_axis = spring_part(&slip_da, &axial.axis, &lateral.axis);
            let mut by_normal = -(q * stiffness * slip_by_normal * share);
            if correction {
                // dφ = ½[(K de)·Δp + (KΔe)·(de_tr − de)]/|Δx|², less 2φ Δxᵀ/|Δx|² for Δx.
                let k_plastic = (stiffness * plastic).transpose();
                let k_change = (stiffness * change).transpose();
                let phi_by =
                    |slip_d: &Matrix2x3<f64>, trial_d: &Matrix2x3<f64>| -> RowVector3<f64> {
                        0.5 * (k_plastic * slip_d + k_change * (trial_d - slip_d)) / d2
                    };
                let phi_dx = phi_by(&slip_dx, &du_dx) - dx.transpose() * (2.0 * phi / d2);
                let phi_da = phi_by(&slip_da, &du_da);
                let phi_dn = 0.5 * (stiffness * (plastic - change)).dot(&slip_by_normal) / d2;
                by_dx -= Matrix3::identity() * phi + dx * phi_dx;
                by_axis -= dx * phi_da;
                by_normal -= dx * phi_dn;
            }
            FrictionTangent {
                displacement: by_dx,
                axis: by_axis,
                normal_force: by_normal,
            }
        });
        FrictionStep {
            force,
            slip,
            dissipated,
            tangent,
        }
    }

    /// The seabed's outward normal where the friction is taken (the step's end in statics, its midpoint in the
    /// energy–momentum step) and its derivative with respect to Δx: n̂ = −∇δ/|∇δ|,
    /// dn̂ = −(I − n̂n̂ᵀ)∇²δ/|∇δ| d(evaluation point).
    fn normal(
        &self,
        rule: ContactRule,
        displacement: &Vector3<f64>,
    ) -> (Vector3<f64>, Matrix3<f64>) {
        let share = match rule {
            ContactRule::Static => 1.0,
            ContactRule::EnergyMomentum { .. } => 0.5,
        };
        let at = self.start + share * displacement;
        if self.bathymetry.is_plane() {
            return (self.bathymetry.outward_normal(&at), Matrix3::zeros());
        }
        let penetration = self.bathymetry.penetration(&at);
        let size = penetration.gradient.norm();
        let normal = -penetration.gradient / size;
        let d_normal = -(Matrix3::identity() - normal * normal.transpose())
            * penetration.hessian
            * (share / size);
        (normal, d_normal)
    }
}

/// The axial and lateral directions â and l̂ = n̂ × â from the normal n̂ and the section axis t1; with
/// `d_normal` (dn̂/dΔx), their derivatives too (else zero). When t1 stands along n̂ (the pipe end-on on the
/// seabed), any direction of the plane serves as "axial": n̂ × e2, or n̂ × e1.
fn directions(
    normal: &Vector3<f64>,
    d_normal: Option<&Matrix3<f64>>,
    axis: &Vector3<f64>,
) -> (Direction, Direction) {
    let along_normal = normal.dot(axis);
    let mut along = axis - normal * along_normal;
    // The fixed direction of the end-on case.
    let mut fixed = None;
    for e in [Vector3::y(), Vector3::x()] {
        if along.norm() >= 1e-9 {
            break;
        }
        along = normal.cross(&e);
        fixed = Some(e);
    }
    let length = along.norm();
    let axial = along / length;
    let lateral = normal.cross(&axial);
    let zero = Matrix3::zeros();
    let [axial_dx, axial_da, lateral_dx, lateral_da] = d_normal.map_or([zero; 4], |d_normal| {
        // db = −[(n̂·t1) I + n̂ t1ᵀ] dn̂ + (I − n̂n̂ᵀ) dt1 (end-on: b = n̂ × e, db = −[e]× dn̂).
        let (along_dx, along_da) = match fixed {
            None => (
                -(Matrix3::identity() * along_normal + normal * axis.transpose()) * d_normal,
                Matrix3::identity() - normal * normal.transpose(),
            ),
            Some(e) => (-skew(&e) * d_normal, zero),
        };
        let project = (Matrix3::identity() - axial * axial.transpose()) / length;
        let axial_dx = project * along_dx;
        let axial_da = project * along_da;
        // dl̂ = −[â]× dn̂ + [n̂]× dâ.
        [
            axial_dx,
            axial_da,
            -skew(&axial) * d_normal + skew(normal) * axial_dx,
            skew(normal) * axial_da,
        ]
    });
    (
        Direction {
            value: axial,
            displacement: axial_dx,
            axis: axial_da,
        },
        Direction {
            value: lateral,
            displacement: lateral_dx,
            axis: lateral_da,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::test_support::wavy_seabed;
    use crate::environment::bathymetry::Bathymetry;

    /// Each derivative against central differences of the force, both rules, on a plane and a grid: sticking,
    /// sliding, and sliding with the axis steep to the seabed.
    #[test]
    fn tangent_matches_central_differences() {
        let plane = Bathymetry::plane(0.0, Vector2::new(0.05, -0.02)).expect("plane");
        for bathymetry in [plane, wavy_seabed()] {
            for rule in [
                ContactRule::Static,
                ContactRule::EnergyMomentum {
                    time_step: 0.1,
                    damping: 0.0,
                },
            ] {
                for (slip_start, normal_force, axis, sliding) in [
                    (
                        Vector2::new(1e-3, -2e-3),
                        900.0,
                        Vector3::new(0.9, 0.3, 0.1),
                        false,
                    ),
                    (
                        Vector2::new(8e-3, 6e-3),
                        900.0,
                        Vector3::new(0.9, 0.3, 0.1),
                        true,
                    ),
                    (
                        Vector2::new(-2e-3, 1e-3),
                        50.0,
                        Vector3::new(0.02, 0.01, 1.0),
                        true,
                    ),
                ] {
                    let node = FrictionNode {
                        bathymetry: &bathymetry,
                        start: Vector3::new(0.3, -0.2, 0.05),
                        slip_start,
                        stiffness: Vector2::new(4e4, 7e4),
                        yield_per_force: 1e-5,
                    };
                    let dx = Vector3::new(2e-3, -1e-3, 3e-4);
                    let force = |dx: &Vector3<f64>, axis: &Vector3<f64>, n: f64| {
                        node.step(rule, dx, axis, n, false).force
                    };
                    let exact = node.step(rule, &dx, &axis, normal_force, true);
                    let radius = node.yield_per_force * normal_force;
                    assert_eq!(exact.slip.norm() >= radius * (1.0 - 1e-12), sliding);
                    let tangent = exact.tangent.expect("asked for");
                    let h = 1e-8;
                    let central = |change: &dyn Fn(f64) -> Vector3<f64>, h: f64| {
                        (change(h) - change(-h)) / (2.0 * h)
                    };
                    for k in 0..3 {
                        let e = Vector3::ith(k, 1.0);
                        let by_dx = central(&|s| force(&(dx + e * s), &axis, normal_force), h);
                        let by_axis = central(&|s| force(&dx, &(axis + e * s), normal_force), h);
                        let size = tangent.displacement.abs().max();
                        assert!((by_dx - tangent.displacement.column(k)).norm() < 1e-6 * size);
                        assert!((by_axis - tangent.axis.column(k)).norm() < 1e-6 * size);
                    }
                    let by_n = central(&|s| force(&dx, &axis, normal_force + s), 1e-4);
                    let size = tangent.normal_force.norm().max(1e-3);
                    assert!(
                        (by_n - tangent.normal_force).norm() < 1e-6 * size,
                        "{rule:?} {slip_start:?}: {by_n} against {}",
                        tangent.normal_force
                    );
                }
            }
        }
    }
}
