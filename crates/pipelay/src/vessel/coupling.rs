//! The vessel on the rod's end node (eqs. 5, 22–23): the node is the vessel's hold point (CO itself, or a
//! tensioner or tower exit at a fixed body-frame offset r from CO, [`crate::vessel::lay`]) and turns with the
//! vessel, so pipe and vessel share the node's unknowns and the interface does no spurious work. With the
//! offset a = Λ_B r, the vessel's pose is x_C = x_N − a; its force f and moment m_C about CO act on the node
//! as f and m_C − a × f (in a time step, with the step's mean offset ā, so the work pairs exactly with the
//! Cayley update a_{n+1} = cay(θ)a_n).
//!
//! In waves the node follows the vessel's total motion, the low-frequency pose moved rigidly by the RAOs'
//! wave-frequency offset (u, Q) of [`crate::vessel::wave_motion`]: x_C = x_N − a − u, Λ_B = Qᵀ Λ_N R_b^t with
//! a = Λ_N R_b^t r. A step's increment of the low-frequency pose is Δx_C = Δx_N − (a_{n+1} − a_n) − Δu and
//! cay(θ_B) = Q_{n+1}ᵀ cay(θ) Q_n; the vessel's moment acts on the node as Q_{n+1} m_B, and the interface work
//! this mismatch leaves, r_f·Δu + r_m·(Q_{n+1}ᵀθ − θ_B), is the work of the prescribed wave motion, booked
//! as supplied.
//!
//! Statics: heave, roll and pitch find their equilibrium against the hydrostatic restoring; surge, sway and
//! yaw are held at η by stiff springs whose force is the holding thrust (or, with a controller active at
//! t = 0, by the controller's K_p). Dynamics: the vessel's momentum-form step of [`crate::vessel::rigid_body`], with
//! damping, thrust (hold or PID) and environment as a body-frame generalised force at the step midpoint.
// Indexing cannot go out of bounds here: 6-vectors and the vessel node of the mesh (set by attach_vessel).
#![allow(clippy::indexing_slicing)]
use super::control::{clamp_integral, eta_error, pid_thrust, thrust_only, Pid};
use super::euler;
use super::rigid_body::{vessel_step, VesselState};
use super::wave_motion::WaveOffset;
use super::VesselAttachment;
use crate::so3::{cayley, cayley_parameter, exp, log, quat_from_matrix, skew};
use nalgebra::{Matrix3, Matrix6, UnitQuaternion, Vector3, Vector6};

/// Stiffness of the holding springs relative to the vessel's heave restoring G33 (translation) and pitch
/// restoring G55 (yaw): large enough that η is held to ~1e-4 m under a pull of 1 MN (1.2e10 N/m for the OSV),
/// small enough for a tangent that Newton's corrections stay accurate in. Stiffer springs turned the positions'
/// round-off into residuals of newtons to tens of newtons and, through the lever from CO to the hold point, the
/// node's pitch into 1e13–1e15 N·m/rad: deep S-lays that converge at 1e3 failed at 1e4 and 1e6 (campaign cases
/// 19, 70, 116, the pipe jumping through rollers), and at 1e2 a shallow one did (case 51).
const HOLD_STIFFNESS: f64 = 1e3;

/// The vessel's frame from the end node's: Λ_B = Λ_N R_b^t.
pub fn body_rotation(
    attachment: &VesselAttachment,
    node_rotation: &UnitQuaternion<f64>,
) -> Matrix3<f64> {
    node_rotation.to_rotation_matrix().into_inner() * attachment.angle
}

/// Round-off of the vessel's static forces (N): the holding springs, or the gains of a controller that holds the
/// vessel in statics, turn the last bits of positions of size `extent` (m) into force (and of the heading into
/// moment).
pub fn static_round_off(attachment: &VesselAttachment, extent: f64) -> f64 {
    let (k, k_yaw) = match attachment
        .controller
        .as_ref()
        .filter(|c| c.holds_in_statics())
    {
        Some(controller) => (
            controller.kp[(0, 0)].max(controller.kp[(1, 1)]),
            controller.kp[(5, 5)],
        ),
        None => {
            let restoring = &attachment.vessel.restoring;
            (
                HOLD_STIFFNESS * restoring[(2, 2)].max(1.0),
                HOLD_STIFFNESS * restoring[(4, 4)].max(1.0),
            )
        }
    };
    8.0 * f64::EPSILON * (k * (extent + attachment.hang_off().norm()) + k_yaw)
}

/// The vessel's pose (CO position, body frame) from the end node's.
pub fn vessel_pose(
    attachment: &VesselAttachment,
    node_position: &Vector3<f64>,
    node_rotation: &UnitQuaternion<f64>,
) -> (Vector3<f64>, Matrix3<f64>) {
    let body = body_rotation(attachment, node_rotation);
    (node_position - body * attachment.hang_off(), body)
}

/// The vessel's low-frequency pose (CO position, body frame) from the end node's, which the waves displace by
/// `offset` (`None`: no waves, the pose itself).
pub fn low_frequency_pose(
    attachment: &VesselAttachment,
    node_position: &Vector3<f64>,
    node_rotation: &UnitQuaternion<f64>,
    offset: Option<&WaveOffset>,
) -> (Vector3<f64>, Matrix3<f64>) {
    let (position, body) = vessel_pose(attachment, node_position, node_rotation);
    match offset {
        Some(offset) => (
            position - offset.translation,
            offset.rotation.transpose() * body,
        ),
        None => (position, body),
    }
}

/// The predictor's increment (Δx, θ) of the end node over a step of Δt: the vessel's low-frequency motion
/// with its body velocity ν_n (m/s, rad/s) changing at its last step's rate ν̇ (the midpoint rule's
/// ν_{n+½} = ν_n + ½ν̇Δt, so θ_B = Λ_B ω_{n+½} Δt and Δx_C = (I − ½θ̂_B)⁻¹ Λ_B u_{n+½} Δt, the inverse of
/// [`vessel_step`]'s velocity update), moved by the waves' offsets `now` → `next`: cay(θ) = Q_{n+1} cay(θ_B)
/// Q_nᵀ and Δx_N = Δx_C + (a_{n+1} − a_n) + Δu. A vessel that pitches and rolls at wave frequency so has its
/// node predicted from the motion its RAOs prescribe, where the rod's nodes' predictor would hold the node's
/// angular velocity.
pub fn predicted_node_increment(
    attachment: &VesselAttachment,
    node_position: &Vector3<f64>,
    node_rotation: &UnitQuaternion<f64>,
    velocity: &Vector6<f64>,
    acceleration: &Vector6<f64>,
    waves: Option<(&WaveOffset, &WaveOffset)>,
    dt: f64,
) -> Vector6<f64> {
    let (_, body) = low_frequency_pose(
        attachment,
        node_position,
        node_rotation,
        waves.map(|(now, _)| now),
    );
    let velocity_mid = velocity + 0.5 * dt * acceleration;
    let theta_body = body * velocity_mid.fixed_rows::<3>(3) * dt;
    let co_shift = body * velocity_mid.fixed_rows::<3>(0) * dt;
    let dx_co = (Matrix3::identity() - 0.5 * skew(&theta_body))
        .lu()
        .solve(&co_shift)
        .unwrap_or(co_shift);
    let (turn, wave_shift) = match waves {
        Some((now, next)) => (
            next.rotation * cayley(&theta_body) * now.rotation.transpose(),
            next.translation - now.translation,
        ),
        None => (cayley(&theta_body), Vector3::zeros()),
    };
    let theta = cayley_parameter(&quat_from_matrix(&turn));
    let arm = body_rotation(attachment, node_rotation) * attachment.hang_off();
    let dx = dx_co + (cayley(&theta) * arm - arm) + wave_shift;
    let mut increment = Vector6::zeros();
    increment.fixed_rows_mut::<3>(0).copy_from(&dx);
    increment.fixed_rows_mut::<3>(3).copy_from(&theta);
    increment
}

/// The end node's position for a vessel pose (CO position, body frame).
pub fn node_position(
    attachment: &VesselAttachment,
    position: &Vector3<f64>,
    body: &Matrix3<f64>,
) -> Vector3<f64> {
    position + body * attachment.hang_off()
}

/// χ, the pipe's force on the vessel (low-frequency body frame, moment about CO), from the vessel's force and
/// moment on the end node (spatial, = the rod's internal force there at equilibrium); the pipe pushes back
/// with its negative at the node. `offset`: the waves' displacement of the vessel, if any.
pub fn pipe_force_on_vessel(
    attachment: &VesselAttachment,
    node_rotation: &UnitQuaternion<f64>,
    force_on_rod: &Vector6<f64>,
    offset: Option<&WaveOffset>,
) -> Vector6<f64> {
    let total = body_rotation(attachment, node_rotation);
    let arm = total * attachment.hang_off();
    let body = offset.map_or(total, |o| o.rotation.transpose() * total);
    let force = force_on_rod.fixed_rows::<3>(0).into_owned();
    let moment = force_on_rod.fixed_rows::<3>(3) + arm.cross(&force);
    let mut chi = Vector6::zeros();
    chi.fixed_rows_mut::<3>(0)
        .copy_from(&(-(body.transpose() * force)));
    chi.fixed_rows_mut::<3>(3)
        .copy_from(&(-(body.transpose() * moment)));
    chi
}

/// The end node's frame for a vessel pose: Λ_N = R(Θ) R_b^tᵀ.
pub fn node_rotation(attachment: &VesselAttachment, eta: &Vector6<f64>) -> Matrix3<f64> {
    euler::rotation(&eta.fixed_rows::<3>(3).into_owned()) * attachment.angle.transpose()
}

/// η = [x, y, z, φ, θ, ψ] of a pose.
pub fn eta_of(position: &Vector3<f64>, body: &Matrix3<f64>) -> Vector6<f64> {
    let angles = euler::angles_from_rotation(body);
    Vector6::new(
        position.x, position.y, position.z, angles.x, angles.y, angles.z,
    )
}

/// The target pose of the vessel in statics at support motion μ: from the end node's reference pose to η's
/// x, y and heading at the surface, upright.
#[derive(Debug, Clone, Copy)]
pub struct StaticTarget {
    pub position: Vector3<f64>,
    pub rotation: Matrix3<f64>,
    /// Surface elevation for the restoring at this μ.
    pub surface: f64,
}

impl StaticTarget {
    pub fn at(
        attachment: &VesselAttachment,
        reference_position: &Vector3<f64>,
        reference_rotation: &UnitQuaternion<f64>,
        motion: f64,
    ) -> Self {
        let final_position = Vector3::new(attachment.eta[0], attachment.eta[1], attachment.surface);
        let final_rotation = euler::rotation(&Vector3::new(0.0, 0.0, attachment.eta[5]));
        let (reference_position, start_rotation) =
            vessel_pose(attachment, reference_position, reference_rotation);
        let turn = log(&(final_rotation * start_rotation.transpose()));
        StaticTarget {
            position: reference_position + motion * (final_position - reference_position),
            rotation: exp(&(motion * turn)) * start_rotation,
            surface: reference_position.z + motion * (attachment.surface - reference_position.z),
        }
    }
}

/// Static forces of the vessel on the end node (spatial force and moment, work-conjugate to (Δx, θ) of the
/// node at `node_position`) and the holding thrust (body frame): restoring of the body toward the target's
/// heave, roll and pitch, and holding springs (or the active controller's K_p) in surge, sway and yaw.
pub fn static_forces(
    attachment: &VesselAttachment,
    node_position: &Vector3<f64>,
    node_rotation: &UnitQuaternion<f64>,
    target: &StaticTarget,
) -> (Vector6<f64>, Vector6<f64>) {
    let vessel = &attachment.vessel;
    let (co, body) = vessel_pose(attachment, node_position, node_rotation);
    let position = &co;
    let e3 = Vector3::z();
    // Restoring toward the target: V = ½(q − q_t)ᵀG_r(q − q_t), q = (z − z0, (Λe2)·e3, −(Λe1)·e3).
    let q = super::rigid_body::Vessel::restoring_coordinates(position, &body, target.surface);
    let q_target = super::rigid_body::Vessel::restoring_coordinates(
        &target.position,
        &target.rotation,
        target.surface,
    );
    let g = Matrix3::from_fn(|i, j| vessel.restoring[(i + 2, j + 2)]);
    let gradient = g * (q - q_target);
    let mut force = -gradient[0] * e3;
    let mut moment =
        -(gradient[1] * body.column(1).cross(&e3) - gradient[2] * body.column(0).cross(&e3));
    // Surge, sway, yaw.
    let (hold_force, hold_moment) = match attachment
        .controller
        .as_ref()
        .filter(|c| c.holds_in_statics())
    {
        Some(controller) => controller_static(controller, attachment, position, &body, target),
        None => {
            // Thrusters push along the body's surge and sway axes and turn it about its heave axis.
            let k = HOLD_STIFFNESS * vessel.restoring[(2, 2)].max(1.0);
            let k_yaw = HOLD_STIFFNESS * vessel.restoring[(4, 4)].max(1.0);
            let horizontal = position - target.position;
            let offset = body.transpose() * Vector3::new(horizontal.x, horizontal.y, 0.0);
            let f = body * Vector3::new(-k * offset.x, -k * offset.y, 0.0);
            // Yaw error ≈ (Λe1)·(R_t e2).
            let yaw_error = body.column(0).dot(&target.rotation.column(1));
            let m = body * Vector3::new(0.0, 0.0, -k_yaw * yaw_error);
            (f, m)
        }
    };
    force += hold_force;
    moment += hold_moment;
    let mut thrust = Vector6::zeros();
    thrust
        .fixed_rows_mut::<3>(0)
        .copy_from(&(body.transpose() * hold_force));
    thrust
        .fixed_rows_mut::<3>(3)
        .copy_from(&(body.transpose() * hold_moment));
    // About the node rather than CO.
    let arm = node_position - position;
    let mut out = Vector6::zeros();
    out.fixed_rows_mut::<3>(0).copy_from(&force);
    out.fixed_rows_mut::<3>(3)
        .copy_from(&(moment - arm.cross(&force)));
    (out, thrust_only(thrust, None))
}

/// The controller's static force: −Jᵀ(η)K_p η̃ in surge, sway and yaw, as spatial force and moment. Statics hold
/// the reference's pose at t = 0, at rest, moved with the static target along statics' path: by the target's
/// offset from η's x, y and heading (none at the path's end).
fn controller_static(
    controller: &Pid,
    attachment: &VesselAttachment,
    position: &Vector3<f64>,
    body: &Matrix3<f64>,
    target: &StaticTarget,
) -> (Vector3<f64>, Vector3<f64>) {
    let eta = eta_of(position, body);
    let mut pose = controller
        .reference
        .at(0.0)
        .map_or_else(|_| Vector6::zeros(), |r| r.0);
    let heading = euler::angles_from_rotation(&target.rotation).z;
    pose[0] += target.position.x - attachment.eta[0];
    pose[1] += target.position.y - attachment.eta[1];
    pose[5] += super::thrusters::wrap(heading - attachment.eta[5]);
    let tau = pid_thrust(
        controller,
        &eta,
        &Vector6::zeros(),
        &Vector6::zeros(),
        &(pose, Vector6::zeros()),
    );
    (body * tau.fixed_rows::<3>(0), body * tau.fixed_rows::<3>(3))
}

/// The environmental forces acting at time t (body frame).
fn environment_at(attachment: &VesselAttachment, time: f64) -> Vector6<f64> {
    attachment
        .environment
        .iter()
        .filter(|w| time >= w.start)
        .map(|w| w.value)
        .sum()
}

/// The vessel's part of the end node's residual in a time step, with its tangent by forward differences
/// (a 6×6 block), the body-frame thrust and the step's work.
pub struct DynamicVessel<'a> {
    pub attachment: &'a VesselAttachment,
    /// ν at step n.
    pub velocity: Vector6<f64>,
    /// ∫η̃ at step n.
    pub integral: Vector6<f64>,
    /// Thrust applied before the controller starts (the static holding thrust).
    pub hold_thrust: Vector6<f64>,
    /// The controller's reference pose and rate at the step's midpoint.
    pub reference: (Vector6<f64>, Vector6<f64>),
    /// In waves: the wave-frequency offsets at the step's start and end.
    pub waves: Option<(WaveOffset, WaveOffset)>,
    /// The thrust a sampled controller holds over the step (body frame), instead of the implicit PID's.
    pub applied_thrust: Option<Vector6<f64>>,
    /// Wind, current and wave drift on the hull over the step, if the vessel feels them.
    pub hull: Option<super::hull_loads::HullStep<'a>>,
    /// The passivity controller's scale of the controller's thrust over the step (1: as commanded;
    /// [`crate::dynamics::passivity`]).
    pub passivity_scale: f64,
}

/// Outcome of the vessel's contribution at trial increments.
#[derive(Debug, Clone, Copy)]
pub struct VesselContribution {
    pub residual: Vector6<f64>,
    pub tangent: Matrix6<f64>,
    pub velocity_next: Vector6<f64>,
    pub velocity_mid: Vector6<f64>,
    /// Scale of the residual's terms per row.
    pub magnitude: Vector6<f64>,
    pub thrust: Vector6<f64>,
    /// η̃ at the midpoint (for the integral update).
    pub error_mid: Vector6<f64>,
    /// Work of thrust and environment (constant forces and the hull's loads), Δt ν_{n+½}·(τ + w), and of the
    /// wave motion (J).
    pub supplied: f64,
    /// Δt ν_{n+½}·D(ν_{n+½}) (J).
    pub dissipated: f64,
    /// The controller's part of `supplied`, Δt ν_{n+½}·τ, while it acts (J; zero before its start).
    pub controller_work: f64,
}

impl DynamicVessel<'_> {
    /// Body-frame generalised force at the midpoint, the thrust in it, the controller's error and the
    /// environment's part (constant forces and the hull's loads).
    fn body_force(
        &self,
        position_mid: &Vector3<f64>,
        body_mid: &Matrix3<f64>,
        velocity_mid: &Vector6<f64>,
        time_mid: f64,
        dt: f64,
    ) -> [Vector6<f64>; 4] {
        let attachment = self.attachment;
        let eta = eta_of(position_mid, body_mid);
        let (thrust, error) = match attachment
            .controller
            .as_ref()
            .filter(|c| time_mid >= c.start)
        {
            // The controller's thrust, as the passivity controller scales it.
            Some(_) if self.applied_thrust.is_some() => (
                self.passivity_scale * self.applied_thrust.unwrap_or_else(Vector6::zeros),
                Vector6::zeros(),
            ),
            Some(controller) => {
                let error = eta_error(&eta, &self.reference.0);
                let integral = clamp_integral(controller, &(self.integral + 0.5 * dt * error));
                (
                    self.passivity_scale
                        * pid_thrust(controller, &eta, velocity_mid, &integral, &self.reference),
                    error,
                )
            }
            None => (self.hold_thrust, Vector6::zeros()),
        };
        let mut environment = environment_at(attachment, time_mid);
        if let Some(hull) = &self.hull {
            environment += hull.load(body_mid, velocity_mid);
        }
        let force = thrust + environment - attachment.vessel.damping_force(velocity_mid);
        [force, thrust, error, environment]
    }

    /// Residual, work and (with `with_tangent`, else zero) tangent at increments (Δx, θ) of the end node,
    /// whose state at n is given.
    pub fn contribution(
        &self,
        node_position: &Vector3<f64>,
        node_rotation: &UnitQuaternion<f64>,
        increment: &Vector6<f64>,
        dt: f64,
        time_mid: f64,
        with_tangent: bool,
    ) -> VesselContribution {
        let attachment = self.attachment;
        let waves = self.waves.as_ref();
        let (position, body) = low_frequency_pose(
            attachment,
            node_position,
            node_rotation,
            waves.map(|w| &w.0),
        );
        let arm = body_rotation(attachment, node_rotation) * attachment.hang_off();
        let state = VesselState {
            position,
            rotation: quat_from_matrix(&body),
            velocity: self.velocity,
        };
        let evaluate = |inc: &Vector6<f64>| {
            let theta = inc.fixed_rows::<3>(3).into_owned();
            // CO moves by Δx_N − (a_{n+1} − a_n) − Δu, a_{n+1} − a_n = θ × ā.
            let arm_next = cayley(&theta) * arm;
            let arm_mean = 0.5 * (arm + arm_next);
            let mut dx = inc.fixed_rows::<3>(0) - (arm_next - arm);
            let mut theta_body = theta;
            if let Some((now, next)) = waves {
                dx -= next.translation - now.translation;
                theta_body = cayley_parameter(&quat_from_matrix(
                    &(next.rotation.transpose() * cayley(&theta) * now.rotation),
                ));
            }
            let mut co_increment = *inc;
            co_increment.fixed_rows_mut::<3>(0).copy_from(&dx);
            co_increment.fixed_rows_mut::<3>(3).copy_from(&theta_body);
            let position_mid = position + 0.5 * dx;
            let body_mid = cayley(&(0.5 * theta_body)) * body;
            // The thrust and the controller's error of the body force vessel_step evaluates (once).
            let control =
                std::cell::Cell::new((Vector6::zeros(), Vector6::zeros(), Vector6::zeros()));
            let mut step = vessel_step(
                &attachment.vessel,
                &state,
                &co_increment,
                dt,
                attachment.surface,
                &|v| {
                    let [force, thrust, error, environment] =
                        self.body_force(&position_mid, &body_mid, v, time_mid, dt);
                    control.set((thrust, error, environment));
                    force
                },
            );
            let force = step.residual.fixed_rows::<3>(0).into_owned();
            let mut moment = step.residual.fixed_rows::<3>(3).into_owned();
            // The wave motion's work: what the node's residual does on (Δx_N, θ) beyond the vessel's on its
            // own increment.
            let mut wave_work = 0.0;
            if let Some((now, next)) = waves {
                wave_work = force.dot(&(next.translation - now.translation))
                    + moment.dot(&(next.rotation.transpose() * theta - theta_body));
                moment = next.rotation * moment;
            }
            step.residual
                .fixed_rows_mut::<3>(3)
                .copy_from(&(moment - arm_mean.cross(&force)));
            let force_scale = arm_mean.norm() * step.magnitude.fixed_rows::<3>(0).norm();
            for k in 3..6 {
                step.magnitude[k] += force_scale;
            }
            let (thrust, error, environment) = control.get();
            (step, thrust, error, environment, wave_work)
        };
        let (step, thrust, error_mid, environment, wave_work) = evaluate(increment);
        // Tangent by forward differences (6 extra evaluations; O(h) accurate, enough for Newton).
        let mut tangent = Matrix6::zeros();
        for j in (0..6).filter(|_| with_tangent) {
            let h = if j < 3 {
                1e-7 * (1.0 + increment.fixed_rows::<3>(0).norm())
            } else {
                1e-8
            };
            let mut plus = *increment;
            plus[j] += h;
            tangent.set_column(j, &((evaluate(&plus).0.residual - step.residual) / h));
        }
        let v = step.velocity_mid;
        let acting = attachment
            .controller
            .as_ref()
            .is_some_and(|c| time_mid >= c.start);
        VesselContribution {
            residual: step.residual,
            tangent,
            velocity_next: step.velocity_next,
            velocity_mid: v,
            magnitude: step.magnitude,
            thrust,
            error_mid,
            supplied: dt * v.dot(&(thrust + environment)) - wave_work,
            dissipated: dt * v.dot(&attachment.vessel.damping_force(&v)),
            controller_work: if acting { dt * v.dot(&thrust) } else { 0.0 },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::so3::exp_quat;
    use crate::vessel::lay::LayEquipment;
    use crate::vessel::rigid_body::Vessel;

    /// The built-in OSV holding the pipe at a J-lay tower's exit 10 m above CO, leaning 0.2 rad.
    fn tower() -> VesselAttachment {
        let lay = LayEquipment::j_lay(Vector3::new(0.0, 0.0, -10.0), 0.2).unwrap();
        VesselAttachment {
            node: 0,
            vessel: Vessel::osv(),
            angle: lay.end_frame.transpose(),
            eta: Vector6::zeros(),
            controller: None,
            environment: Vec::new(),
            surface: 0.0,
            lay: Some(lay),
            winch: None,
            hull_loads: false,
        }
    }

    #[test]
    fn the_predicted_node_moves_the_vessel_at_its_extrapolated_velocity() {
        // The vessel's own step at the predicted node increment gives ν_{n+1} = ν_n + ν̇Δt, in calm water and
        // with the waves turning and shifting it between the step's start and end.
        let attachment = tower();
        let node_position = Vector3::new(880.0, 3.0, -815.0);
        let node_rotation = exp_quat(&Vector3::new(0.3, -1.1, 0.4));
        let velocity = Vector6::new(0.4, -0.2, 0.05, 0.01, -0.02, 0.003);
        let acceleration = Vector6::new(0.03, 0.01, -0.2, 0.05, 0.04, -0.001);
        let dt = 0.1;
        let now = WaveOffset {
            translation: Vector3::new(0.2, -0.1, 0.5),
            rotation: exp(&Vector3::new(0.02, -0.03, 0.01)),
        };
        let next = WaveOffset {
            translation: Vector3::new(0.25, -0.05, 0.3),
            rotation: exp(&Vector3::new(0.03, -0.01, 0.015)),
        };
        for waves in [None, Some((now, next))] {
            let increment = predicted_node_increment(
                &attachment,
                &node_position,
                &node_rotation,
                &velocity,
                &acceleration,
                waves.as_ref().map(|(now, next)| (now, next)),
                dt,
            );
            let vessel = DynamicVessel {
                attachment: &attachment,
                velocity,
                integral: Vector6::zeros(),
                hold_thrust: Vector6::zeros(),
                reference: (Vector6::zeros(), Vector6::zeros()),
                waves,
                applied_thrust: None,
                hull: None,
                passivity_scale: 1.0,
            };
            let step =
                vessel.contribution(&node_position, &node_rotation, &increment, dt, 0.0, false);
            let error = (step.velocity_next - (velocity + dt * acceleration)).amax();
            assert!(
                error < 1e-13,
                "waves {}: ν_n+1 off by {error:e}",
                waves.is_some()
            );
        }
    }
}
