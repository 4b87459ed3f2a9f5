//! The DP controller (eqs. 44–45): PID on η with a bounded integral, thrust in surge, sway and yaw.
use super::euler;
use nalgebra::{Matrix6, Vector3, Vector6};

/// A PID controller on the vessel's η (eqs. 44–45): τ = −Jᵀ(η)(K_p η̃ + K_d η̃̇ + K_i ∫η̃), η̃ = η − η_ref,
/// active from `start`; thrust acts in surge, sway and yaw only.
#[derive(Debug, Clone, PartialEq)]
pub struct Pid {
    pub kp: nalgebra::Matrix6<f64>,
    pub kd: nalgebra::Matrix6<f64>,
    pub ki: nalgebra::Matrix6<f64>,
    /// η_ref = [x, y, z, φ, θ, ψ] in e (m, rad).
    pub reference: nalgebra::Vector6<f64>,
    /// Time the controller starts (s).
    pub start: f64,
    /// Bound on each component of ∫η̃ (keeps the PID passive, §III.B); `None`: unbounded.
    pub integral_limit: Option<nalgebra::Vector6<f64>>,
    /// Bounds on the thrust in surge (N), sway (N) and yaw (N·m); `None`: unbounded.
    pub thrust_limit: Option<Vector3<f64>>,
}

/// Wraps an angle to (−π, π].
fn wrap(angle: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let a = angle.rem_euclid(two_pi);
    if a > std::f64::consts::PI {
        a - two_pi
    } else {
        a
    }
}

/// η − η_ref with angles wrapped.
pub fn eta_error(eta: &Vector6<f64>, reference: &Vector6<f64>) -> Vector6<f64> {
    let mut e = eta - reference;
    for k in 3..6 {
        e[k] = wrap(e[k]);
    }
    e
}

/// Keeps thrust to surge, sway and yaw, within the limits.
pub fn thrust_only(mut tau: Vector6<f64>, limit: Option<&Vector3<f64>>) -> Vector6<f64> {
    tau[2] = 0.0;
    tau[3] = 0.0;
    tau[4] = 0.0;
    if let Some(limit) = limit {
        for (k, l) in [(0, limit.x), (1, limit.y), (5, limit.z)] {
            tau[k] = tau[k].clamp(-l, l);
        }
    }
    tau
}

/// τ = −Jᵀ(η)(K_p η̃ + K_d η̃̇ + K_i z) (body frame), thrust in surge, sway, yaw within the limits.
pub fn pid_thrust(
    controller: &Pid,
    eta: &Vector6<f64>,
    velocity: &Vector6<f64>,
    integral: &Vector6<f64>,
) -> Vector6<f64> {
    let error = eta_error(eta, &controller.reference);
    let jacobian = euler::jacobian(eta).unwrap_or_else(Matrix6::identity);
    let rate = jacobian * velocity;
    let tau_pid = controller.kp * error + controller.kd * rate + controller.ki * integral;
    thrust_only(
        -jacobian.transpose() * tau_pid,
        controller.thrust_limit.as_ref(),
    )
}

/// ∫η̃ within the controller's bound.
pub fn clamp_integral(controller: &Pid, integral: &Vector6<f64>) -> Vector6<f64> {
    match &controller.integral_limit {
        Some(limit) => integral.zip_map(limit, |z, l| z.clamp(-l, l)),
        None => *integral,
    }
}
