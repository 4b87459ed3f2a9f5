//! Friction between the pipe and a roller: what a free-turning roller resists (its rolling resistance along
//! the pipe, Coulomb friction along its axis) and what a braked or locked one does (Coulomb friction in every
//! direction of the contact's tangent plane).
//!
//! **The contact's tangent plane.** At the contact, with n the unit normal (from the roller toward the pipe)
//! and a the roller's axis, the plane normal to n holds â = a − (a·n)n (normalised: along the roller) and
//! ĉ = n × â (around the roller: the pipe's way when it runs over it). The pipe's material point at the
//! contact moves by Δu = Σ_j w_j Δy_j in the roller's frame (w_j the spline's weights at the foot, Δy_j the
//! nodes' moves in the vessel's frame), whose components along ĉ and â slide the contact.
//!
//! **Energy–momentum step (stick–slip).** As the seabed's friction ([`crate::contact::friction`]): an
//! elastic slip e, spring K (the roller's contact stiffness), returned radially onto the friction limit r =
//! μ N/K when the trial e_tr = e_n + Δu leaves it. A free-turning roller has two independent limits, its rolling
//! resistance f_r N around it (along ĉ) and μ N along it (along â); a locked roller one circle of radius μ N/K
//! in the plane. The force on the pipe is −K ē, ē = ½(e_n + e_{n+1}), frozen at the step's start in its
//! directions and weights, so that its work on the step is exactly −K ē·Δu = −ΔV_f − K ē·Δp: the spring's
//! energy V_f = ½K|e|² is stored with the contact and D = K ē·Δp ≥ 0 (Δp = e_tr − e_{n+1}, parallel to
//! e_{n+1}, and |e_n| ≤ |e_{n+1}| on a limit) is dissipated.
//!
//! **Statics.** A static state has no history: the pipe is taken sliding out over the rollers, as it does
//! when paid out, so each roller in contact holds it back toward the vessel with the limit force, f N along
//! the pipe (f the rolling resistance of a free-turning roller, μ of a locked one). The tension then rises
//! toward the hold point by f N at each roller: by μ ΣN over a stinger of locked rollers.
use crate::vessel::lay::RollerFriction;
use nalgebra::{Vector2, Vector3};

/// The contact's tangent directions: (ĉ, â), around and along the roller, from the contact's normal `normal`
/// and the roller's axis `axis` (unit; the axis's part along the normal is removed).
pub fn tangent_directions(normal: &Vector3<f64>, axis: &Vector3<f64>) -> [Vector3<f64>; 2] {
    let along = (axis - axis.dot(normal) * normal)
        .try_normalize(1e-12)
        .unwrap_or_else(|| normal.cross(&Vector3::x()).normalize());
    [normal.cross(&along), along]
}

/// One step's friction at a roller: the elastic slip at the end (m, along ĉ and â), the force on the pipe in
/// the roller's frame (N), the spring's energy at the end (J) and the energy dissipated (J).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionStep {
    pub slip: Vector2<f64>,
    pub force: Vector3<f64>,
    pub energy: f64,
    pub dissipated: f64,
}

/// The friction of a step that moves the contact's material point by `moved` (roller's frame), from the elastic
/// slip `slip_start`, with the tangent directions `directions` (ĉ, â) frozen at the step's start, the normal
/// force `normal_force` (N) at its end and the spring `stiffness` (N/m).
pub fn step(
    friction: &RollerFriction,
    directions: &[Vector3<f64>; 2],
    slip_start: &Vector2<f64>,
    moved: &Vector3<f64>,
    normal_force: f64,
    stiffness: f64,
) -> FrictionStep {
    let trial = slip_start + Vector2::new(directions[0].dot(moved), directions[1].dot(moved));
    let limit = |coefficient: f64| coefficient * normal_force.max(0.0) / stiffness;
    let slip = if friction.locked {
        let radius = limit(friction.friction);
        let size = trial.norm();
        if size > radius {
            trial * (radius / size)
        } else {
            trial
        }
    } else {
        let (around, along) = (limit(friction.rolling_resistance), limit(friction.friction));
        Vector2::new(trial.x.clamp(-around, around), trial.y.clamp(-along, along))
    };
    let mean = 0.5 * (slip_start + slip);
    let spring = stiffness * mean;
    FrictionStep {
        slip,
        force: -(directions[0] * spring.x + directions[1] * spring.y),
        energy: 0.5 * stiffness * slip.norm_squared(),
        dissipated: spring.dot(&(trial - slip)),
    }
}

/// The static friction force on the pipe at a roller in contact with normal force `normal_force` (N): the
/// limit along the pipe, `toward_hold` (unit, the pipe's direction toward the hold point, in the contact's
/// tangent plane once its part along the normal `normal` is removed).
pub fn static_force(
    friction: &RollerFriction,
    normal: &Vector3<f64>,
    toward_hold: &Vector3<f64>,
    normal_force: f64,
) -> Vector3<f64> {
    let coefficient = if friction.locked {
        friction.friction
    } else {
        friction.rolling_resistance
    };
    let along = (toward_hold - toward_hold.dot(normal) * normal)
        .try_normalize(1e-12)
        .unwrap_or_else(Vector3::zeros);
    coefficient * normal_force.max(0.0) * along
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A locked roller's step dissipates what its force's work and the spring's energy leave over, never less
    /// than nothing, over a path that sticks, slides, reverses and lifts off; a free-turning roller slides
    /// along the pipe against its rolling resistance and across it against μ.
    #[test]
    fn steps_close_the_energy_and_dissipate() {
        let directions = [Vector3::x(), Vector3::y()];
        let (stiffness, normal) = (1e7, 20e3);
        for friction in [
            RollerFriction {
                friction: 0.3,
                rolling_resistance: 0.0,
                locked: true,
            },
            RollerFriction {
                friction: 0.3,
                rolling_resistance: 0.02,
                locked: false,
            },
        ] {
            let mut slip = Vector2::zeros();
            let mut energy = 0.0;
            let mut sliding = 0;
            for k in 0..40 {
                let t = f64::from(k);
                let moved = 2e-4 * Vector3::new((0.3 * t).sin() + 0.5, (0.2 * t).cos(), 0.0);
                let force = if k == 30 { 0.0 } else { normal };
                let step = step(&friction, &directions, &slip, &moved, force, stiffness);
                let work = step.force.dot(&moved);
                // The force's work on the pipe is minus the spring's gain and the dissipation.
                let balance = work + (step.energy - energy) + step.dissipated;
                assert!(
                    balance.abs() < 1e-9 * (step.energy + 1.0),
                    "{k}: {balance:e}"
                );
                assert!(step.dissipated >= -1e-12, "{k}: {}", step.dissipated);
                sliding += usize::from(step.dissipated > 0.0);
                let limits = if friction.locked {
                    [0.3 * force; 2]
                } else {
                    [0.02 * force, 0.3 * force]
                };
                let end_force = stiffness * step.slip;
                if friction.locked {
                    assert!(end_force.norm() <= limits[0] * (1.0 + 1e-12) + 1e-9);
                } else {
                    assert!(end_force.x.abs() <= limits[0] * (1.0 + 1e-12) + 1e-9);
                    assert!(end_force.y.abs() <= limits[1] * (1.0 + 1e-12) + 1e-9);
                }
                (slip, energy) = (step.slip, step.energy);
            }
            assert!(sliding > 5, "{sliding}");
        }
    }

    /// In statics a locked roller holds the pipe back toward the hold point with μ N, a free-turning one with
    /// its rolling resistance, both in the contact's tangent plane.
    #[test]
    fn static_friction_holds_the_pipe_toward_the_hold_point() {
        let normal = Vector3::new(0.0, 0.0, -1.0);
        let toward = Vector3::new(1.0, 0.0, -0.1).normalize();
        let locked = RollerFriction {
            friction: 0.25,
            rolling_resistance: 0.01,
            locked: true,
        };
        let force = static_force(&locked, &normal, &toward, 4e4);
        assert!((force - Vector3::new(1e4, 0.0, 0.0)).norm() < 1e-9);
        let free = RollerFriction {
            locked: false,
            ..locked
        };
        assert!((static_force(&free, &normal, &toward, 4e4).norm() - 400.0).abs() < 1e-9);
    }
}
