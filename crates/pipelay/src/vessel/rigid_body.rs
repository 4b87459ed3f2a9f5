//! The DP vessel of eq. (10): M ν̇ + C(ν)ν + D(ν)ν + g(η) = τ + χ + w, as a rigid body in the
//! energy–momentum framework (formulary `numerics/rod-dynamics.md` §4, "monolithic rigid body").
//!
//! The vessel's reference point (CO, where M, D and G are given) has position x in e and frame Λ_B
//! (body axes b: forward, starboard, down). Its velocities ν = (U, W) are body-frame. Momenta
//! μ = 𝕄ν with 𝕄 = M_RB + M_A, p = Λ_B μ_U, π = Λ_B μ_W; Kirchhoff's equations in these momenta give
//! Fossen's C_RB(ν) + C_A(ν) (the m2c form, [`Vessel::coriolis`]). One step with unknowns (Δx, θ),
//! Λ_{n+1} = cay(θ)Λ_n, Λ̄ = ½(Λ_n + Λ_{n+1}):
//! - U_{n+1} = 2Λ̄⁻¹Δx/Δt − U_n, W_{n+1} = 2Λ_nᵀθ/Δt − W_n;
//! - (p_{n+1} − p_n)/Δt = F, (π_{n+1} − π_n + Δx × p̄)/Δt = M;
//! - a body-frame generalised force f_b does the work Δt f_b·ν_{n+½} when F = Λ̄⁻ᵀ f_U, M = Λ_n f_W.
//!
//! Hydrostatic restoring g(η) = Gη is the gradient of V = ½qᵀG_r q in director form,
//! q = (z − z_0, (Λe2)·e3, −(Λe1)·e3) ≈ (heave, roll, pitch) for small angles: yaw-invariant and, being
//! quadratic in q with q linear in (x, Λ), exactly integrated by the midpoint of q.
// Indexing cannot go out of bounds here: 6×6 matrices and 6-vectors indexed by constants.
#![allow(clippy::indexing_slicing)]
use super::hull_loads::{DriftCoefficients, HullCoefficients};
use super::raos::Raos;
use super::thrusters::{check_on_hull, mss_supply_vessel, Thruster};
use crate::error::{finite, Error, Result};
use crate::so3::{cayley, skew};
use nalgebra::{Matrix3, Matrix6, UnitQuaternion, Vector3, Vector6};

/// The vessel's mass, damping and restoring matrices (6×6, about CO, surge…yaw).
#[derive(Debug, Clone, PartialEq)]
pub struct Vessel {
    /// Rigid-body mass M_RB.
    pub rigid_body_mass: Matrix6<f64>,
    /// Added mass M_A (constant, zero-frequency).
    pub added_mass: Matrix6<f64>,
    /// Linear damping D.
    pub damping: Matrix6<f64>,
    /// Restoring G (heave, roll and pitch rows and columns only).
    pub restoring: Matrix6<f64>,
    /// Optional quadratic damping: D_q |ν|ν component-wise (D(ν)ν = Dν + D_q(|ν|∘ν)).
    pub quadratic_damping: Option<Matrix6<f64>>,
    /// First-order displacement RAOs: the wave-frequency motion in waves; `None`: the vessel moves only at low
    /// frequency.
    pub raos: Option<Raos>,
    /// Overall length (m, CO amidships), if known: where thrusters may sit.
    pub length: Option<f64>,
    /// Its thrusters (empty: the controller's τ acts directly).
    pub thrusters: Vec<Thruster>,
    /// Wind, current and wave-drift coefficients of the hull, if any ([`super::hull_loads`]).
    pub wind_coefficients: Option<HullCoefficients>,
    pub current_coefficients: Option<HullCoefficients>,
    pub drift_coefficients: Option<DriftCoefficients>,
}

/// Heave, roll and pitch: the DOFs hydrostatics restores.
const RESTORED: [usize; 3] = [2, 3, 4];

fn symmetric(argument: &str, m: &Matrix6<f64>) -> Result<()> {
    let asymmetry = (m - m.transpose()).abs().max();
    if asymmetry > 1e-9 * m.abs().max().max(1.0) {
        return Err(Error::input(
            argument,
            format!("a matrix with |A − Aᵀ| = {asymmetry:.3e}"),
            "must be symmetric",
        ));
    }
    Ok(())
}

fn positive_semidefinite(argument: &str, m: &Matrix6<f64>, strict: bool) -> Result<()> {
    let sym = 0.5 * (m + m.transpose());
    let eigen = sym.symmetric_eigenvalues();
    let smallest = eigen.min();
    let floor = if strict {
        0.0
    } else {
        -1e-9 * eigen.abs().max()
    };
    if smallest <= floor && (strict || smallest < floor) {
        let kind = if strict {
            "positive definite"
        } else {
            "positive semi-definite"
        };
        return Err(Error::input(
            argument,
            format!("a matrix with smallest eigenvalue {smallest:.4e}"),
            format!("must be {kind}"),
        ));
    }
    Ok(())
}

impl Vessel {
    /// A vessel from M = M_RB + M_A, D and G; `rigid_body_mass` splits M (default: all of M rigid).
    pub fn new(
        mass: Matrix6<f64>,
        damping: Matrix6<f64>,
        restoring: Matrix6<f64>,
        rigid_body_mass: Option<Matrix6<f64>>,
        quadratic_damping: Option<Matrix6<f64>>,
    ) -> Result<Self> {
        finite("M", mass.as_slice())?;
        finite("D", damping.as_slice())?;
        finite("G", restoring.as_slice())?;
        symmetric("M", &mass)?;
        positive_semidefinite("M", &mass, true)?;
        positive_semidefinite("D", &damping, false)?;
        symmetric("G", &restoring)?;
        for i in 0..6 {
            for j in 0..6 {
                if restoring[(i, j)] != 0.0 && !(RESTORED.contains(&i) && RESTORED.contains(&j)) {
                    return Err(Error::input(
                        "G",
                        format!("G[{i}][{j}] = {}", restoring[(i, j)]),
                        "only heave, roll and pitch (rows and columns 2, 3, 4) may have restoring terms",
                    ));
                }
            }
        }
        let rigid = match rigid_body_mass {
            Some(m) => {
                finite("M_RB", m.as_slice())?;
                symmetric("M_RB", &m)?;
                positive_semidefinite("M_RB", &m, true)?;
                m
            }
            None => mass,
        };
        if let Some(q) = &quadratic_damping {
            finite("quadratic_damping", q.as_slice())?;
            positive_semidefinite("quadratic_damping", q, false)?;
        }
        Ok(Vessel {
            rigid_body_mass: rigid,
            added_mass: mass - rigid,
            damping,
            restoring,
            quadratic_damping,
            raos: None,
            length: None,
            thrusters: Vec::new(),
            wind_coefficients: None,
            current_coefficients: None,
            drift_coefficients: None,
        })
    }

    /// The same vessel with thrusters on a hull of length `length` (m), each checked to lie on it.
    pub fn with_thrusters(mut self, thrusters: Vec<Thruster>, length: Option<f64>) -> Result<Self> {
        if let Some(length) = length {
            check_on_hull(&thrusters, length)?;
        } else if !thrusters.is_empty() {
            return Err(Error::input(
                "length",
                "None",
                "must be given with thrusters (m, overall length): thrusters must lie on the hull",
            ));
        }
        self.length = length;
        self.thrusters = thrusters;
        Ok(self)
    }

    /// The same vessel with wind, current and wave-drift coefficients (`None`: none of that kind).
    pub fn with_hull_coefficients(
        mut self,
        wind: Option<HullCoefficients>,
        current: Option<HullCoefficients>,
        drift: Option<DriftCoefficients>,
    ) -> Self {
        self.wind_coefficients = wind;
        self.current_coefficients = current;
        self.drift_coefficients = drift;
        self
    }

    /// The same vessel with the RAO table `raos` (`None`: none).
    pub fn with_raos(mut self, raos: Option<Raos>) -> Self {
        self.raos = raos;
        self
    }

    /// The 83 m offshore supply vessel of Fossen's MSS toolbox (`osv.m`, Fossen 2021 eqs. 6.111–6.116):
    /// M_RB, M_A (hard-coded in osv.m), D = diag(M11/T1, M22/T2, 2ζ3ω3M33, 2ζ4ω4M44, 2ζ5ω5M55, M66/T6), G;
    /// with the RAOs computed for its hull by Capytaine (`Raos::osv`), the six thrusters of the MSS supply
    /// vessel ([`mss_supply_vessel`]) and its wind, current and wave-drift coefficients ([`super::hull_loads`]).
    pub fn osv() -> Self {
        let m_rb = Matrix6::from_row_slice(&[
            4976887.5,
            0.0,
            0.0,
            0.0,
            -5972265.0,
            0.0, //
            0.0,
            4976887.5,
            0.0,
            5972265.0,
            0.0,
            -22395993.75, //
            0.0,
            0.0,
            4976887.5,
            0.0,
            22395993.75,
            0.0, //
            0.0,
            5972265.0,
            0.0,
            204699382.9,
            0.0,
            -26875192.5, //
            -5972265.0,
            0.0,
            22395993.75,
            0.0,
            2250809814.0,
            0.0, //
            0.0,
            -22395993.75,
            0.0,
            -26875192.5,
            0.0,
            2243643096.0,
        ]);
        let m_a = Matrix6::from_row_slice(&[
            600000.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0, //
            0.0,
            2000000.0,
            0.0,
            3100000.0,
            0.0,
            -9100000.0, //
            0.0,
            0.0,
            8300000.0,
            0.0,
            90700000.0,
            0.0, //
            0.0,
            3100000.0,
            0.0,
            74800000.0,
            0.0,
            -112700000.0, //
            0.0,
            0.0,
            90700000.0,
            0.0,
            3987500000.0,
            0.0, //
            0.0,
            -9100000.0,
            0.0,
            -112700000.0,
            0.0,
            1241600000.0,
        ]);
        let damping = Matrix6::from_diagonal(&Vector6::new(
            55768.875,
            69768.875,
            5052715.642,
            50369129.38,
            3632218967.0,
            3485243096.0,
        ));
        let restoring = Matrix6::from_row_slice(&[
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0, //
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0, //
            0.0,
            0.0,
            12018034.8,
            0.0,
            6009017.4,
            0.0, //
            0.0,
            0.0,
            0.0,
            100856879.2,
            0.0,
            0.0, //
            0.0,
            0.0,
            6009017.4,
            0.0,
            5874549987.0,
            0.0, //
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ]);
        Vessel {
            rigid_body_mass: m_rb,
            added_mass: m_a,
            damping,
            restoring,
            quadratic_damping: None,
            // The tables are shipped with the crate and read by unit tests.
            raos: Raos::osv().ok(),
            length: Some(83.0),
            thrusters: mss_supply_vessel(),
            wind_coefficients: HullCoefficients::osv_wind().ok(),
            current_coefficients: HullCoefficients::osv_current().ok(),
            drift_coefficients: DriftCoefficients::osv().ok(),
        }
    }

    /// M = M_RB + M_A.
    pub fn mass(&self) -> Matrix6<f64> {
        self.rigid_body_mass + self.added_mass
    }

    /// Fossen's C(ν) = C_RB(ν) + C_A(ν) in the m2c form: with ∂T/∂ν1 = M11ν1 + M12ν2 and
    /// ∂T/∂ν2 = M21ν1 + M22ν2, C = [[0, −S(∂T/∂ν1)], [−S(∂T/∂ν1), −S(∂T/∂ν2)]]. Skew-symmetric.
    pub fn coriolis(&self, nu: &Vector6<f64>) -> Matrix6<f64> {
        let m = self.mass();
        let dt_dnu = m * nu;
        let s1 = skew(&dt_dnu.fixed_rows::<3>(0).into_owned());
        let s2 = skew(&dt_dnu.fixed_rows::<3>(3).into_owned());
        let mut c = Matrix6::zeros();
        c.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-s1));
        c.fixed_view_mut::<3, 3>(3, 0).copy_from(&(-s1));
        c.fixed_view_mut::<3, 3>(3, 3).copy_from(&(-s2));
        c
    }

    /// Damping force D(ν)ν (body frame).
    pub fn damping_force(&self, nu: &Vector6<f64>) -> Vector6<f64> {
        let linear = self.damping * nu;
        match &self.quadratic_damping {
            Some(q) => linear + q * nu.map(|v| v.abs() * v),
            None => linear,
        }
    }

    /// The 3×3 block of G over heave, roll and pitch.
    fn restoring_block(&self) -> Matrix3<f64> {
        Matrix3::from_fn(|i, j| self.restoring[(RESTORED[i], RESTORED[j])])
    }

    /// Restoring coordinates q = (z − z_0, (Λe2)·e3, −(Λe1)·e3) of a pose (≈ heave, roll, pitch).
    pub fn restoring_coordinates(
        position: &Vector3<f64>,
        rotation: &Matrix3<f64>,
        z0: f64,
    ) -> Vector3<f64> {
        Vector3::new(position.z - z0, rotation[(2, 1)], -rotation[(2, 0)])
    }

    /// Restoring potential V = ½qᵀG_r q (J).
    pub fn restoring_energy(
        &self,
        position: &Vector3<f64>,
        rotation: &Matrix3<f64>,
        z0: f64,
    ) -> f64 {
        let q = Self::restoring_coordinates(position, rotation, z0);
        0.5 * q.dot(&(self.restoring_block() * q))
    }
}

/// Pose and velocity of a vessel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VesselState {
    /// Position of CO in e (m).
    pub position: Vector3<f64>,
    /// Body frame Λ_B (b → e).
    pub rotation: UnitQuaternion<f64>,
    /// ν = (U, W), body frame (m/s, rad/s).
    pub velocity: Vector6<f64>,
}

/// The vessel's part of one step at trial increments (Δx, θ).
#[derive(Debug, Clone, Copy)]
pub struct VesselStep {
    /// Residual rows [force; moment] (N, N·m), spatial, conjugate to (Δx, θ): inertia − restoring − body forces.
    pub residual: Vector6<f64>,
    /// ν at n+1.
    pub velocity_next: Vector6<f64>,
    /// ν_{n+½}.
    pub velocity_mid: Vector6<f64>,
    /// Size of the residual's terms per row (inertia, restoring, forces), its scale for convergence.
    pub magnitude: Vector6<f64>,
}

/// The vessel's residual for one step: inertia in momentum form, hydrostatic restoring as a discrete
/// gradient, and the body-frame generalised force `body_force(ν_{n+½}, pose_{n+½})` (damping, thrust,
/// environment), all work-conjugate to (Δx, θ).
pub fn vessel_step(
    vessel: &Vessel,
    state: &VesselState,
    increment: &Vector6<f64>,
    dt: f64,
    z0: f64,
    body_force: &dyn Fn(&Vector6<f64>) -> Vector6<f64>,
) -> VesselStep {
    let dx = increment.fixed_rows::<3>(0).into_owned();
    let theta = increment.fixed_rows::<3>(3).into_owned();
    let rotation_n = state.rotation.to_rotation_matrix().into_inner();
    let rotation_next = cayley(&theta) * rotation_n;
    let mean = 0.5 * (rotation_n + rotation_next);
    let mean_inverse = rotation_n.transpose() * (Matrix3::identity() - 0.5 * skew(&theta));
    let u_n = state.velocity.fixed_rows::<3>(0).into_owned();
    let w_n = state.velocity.fixed_rows::<3>(3).into_owned();
    let u_next = 2.0 * mean_inverse * dx / dt - u_n;
    let w_next = 2.0 * rotation_n.transpose() * theta / dt - w_n;
    let mut velocity_next = Vector6::zeros();
    velocity_next.fixed_rows_mut::<3>(0).copy_from(&u_next);
    velocity_next.fixed_rows_mut::<3>(3).copy_from(&w_next);
    let velocity_mid = 0.5 * (state.velocity + velocity_next);
    let mass = vessel.mass();
    let momentum_n = mass * state.velocity;
    let momentum_next = mass * velocity_next;
    let p_n = rotation_n * momentum_n.fixed_rows::<3>(0);
    let p_next = rotation_next * momentum_next.fixed_rows::<3>(0);
    let pi_n = rotation_n * momentum_n.fixed_rows::<3>(3);
    let pi_next = rotation_next * momentum_next.fixed_rows::<3>(3);
    let p_mean = 0.5 * (p_n + p_next);
    let force_body = body_force(&velocity_mid);
    let force = mean_inverse.transpose() * force_body.fixed_rows::<3>(0);
    let moment = rotation_n * force_body.fixed_rows::<3>(3);
    // Restoring: −∂V/∂q at the mean q, mapped by Δq = (Δz, θ·(Λ̄e2 × e3), −θ·(Λ̄e1 × e3)).
    let q_mean = 0.5
        * (Vessel::restoring_coordinates(&state.position, &rotation_n, z0)
            + Vessel::restoring_coordinates(&(state.position + dx), &rotation_next, z0));
    let gradient = vessel.restoring_block() * q_mean;
    let e3 = Vector3::z();
    let restoring_force = -gradient[0] * e3;
    let restoring_moment =
        -(gradient[1] * mean.column(1).cross(&e3) - gradient[2] * mean.column(0).cross(&e3));
    let inertia_force = (p_next - p_n) / dt;
    let inertia_moment = (pi_next - pi_n + dx.cross(&p_mean)) / dt;
    let mut residual = Vector6::zeros();
    residual
        .fixed_rows_mut::<3>(0)
        .copy_from(&(inertia_force - force - restoring_force));
    residual
        .fixed_rows_mut::<3>(3)
        .copy_from(&(inertia_moment - moment - restoring_moment));
    let mut magnitude = Vector6::zeros();
    magnitude
        .fixed_rows_mut::<3>(0)
        .copy_from(&(inertia_force.abs() + force.abs() + restoring_force.abs()));
    magnitude
        .fixed_rows_mut::<3>(3)
        .copy_from(&(inertia_moment.abs() + moment.abs() + restoring_moment.abs()));
    VesselStep {
        residual,
        velocity_next,
        velocity_mid,
        magnitude,
    }
}

/// Kinetic energy ½νᵀMν (J).
pub fn kinetic_energy(vessel: &Vessel, velocity: &Vector6<f64>) -> f64 {
    0.5 * velocity.dot(&(vessel.mass() * velocity))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::so3::exp_quat;

    #[test]
    fn coriolis_is_skew_symmetric_and_osv_is_valid() {
        let vessel = Vessel::osv();
        let nu = Vector6::new(1.0, -0.5, 0.2, 0.01, -0.02, 0.05);
        let c = vessel.coriolis(&nu);
        assert!((c + c.transpose()).abs().max() < 1e-9 * c.abs().max());
        let rebuilt = Vessel::new(
            vessel.mass(),
            vessel.damping,
            vessel.restoring,
            Some(vessel.rigid_body_mass),
            None,
        )
        .expect("the built-in vessel is valid");
        assert!((rebuilt.added_mass - vessel.added_mass).abs().max() < 1e-6);
    }

    #[test]
    fn bad_matrices_are_rejected() {
        let v = Vessel::osv();
        let mut g = v.restoring;
        g[(0, 0)] = 1.0;
        assert!(
            matches!(Vessel::new(v.mass(), v.damping, g, None, None), Err(Error::Input { argument, .. }) if argument == "G")
        );
        assert!(
            matches!(Vessel::new(-v.mass(), v.damping, v.restoring, None, None), Err(Error::Input { argument, .. }) if argument == "M")
        );
        assert!(
            matches!(Vessel::new(v.mass(), -v.damping, v.restoring, None, None), Err(Error::Input { argument, .. }) if argument == "D")
        );
    }

    /// Inertia and restoring do work equal to the change of kinetic plus restoring energy; a body force
    /// does work Δt f·ν_{n+½}.
    #[test]
    fn one_step_balances_energy_exactly() {
        let vessel = Vessel::osv();
        let state = VesselState {
            position: Vector3::new(3.0, -2.0, 0.7),
            rotation: exp_quat(&Vector3::new(0.05, -0.03, 0.8)),
            velocity: Vector6::new(1.2, -0.4, 0.3, 0.02, -0.015, 0.04),
        };
        let increment = Vector6::new(0.05, 0.02, -0.03, 0.004, 0.002, -0.006);
        let dt = 0.1;
        let force = Vector6::new(1e5, -2e5, 3e4, 1e6, -2e6, 5e5);
        let step = vessel_step(&vessel, &state, &increment, dt, 0.0, &|_| force);
        let rotation_n = state.rotation.to_rotation_matrix().into_inner();
        let rotation_next = cayley(&increment.fixed_rows::<3>(3).into_owned()) * rotation_n;
        let position_next = state.position + increment.fixed_rows::<3>(0);
        let energy = |v: &Vector6<f64>, p: &Vector3<f64>, r: &Matrix3<f64>| {
            kinetic_energy(&vessel, v) + vessel.restoring_energy(p, r, 0.0)
        };
        let change = energy(&step.velocity_next, &position_next, &rotation_next)
            - energy(&state.velocity, &state.position, &rotation_n);
        let work_of_residual = step.residual.dot(&increment);
        let supplied = dt * force.dot(&step.velocity_mid);
        // residual·Δ = ΔE − supplied work.
        assert!(
            (work_of_residual - (change - supplied)).abs()
                < 1e-9 * change.abs().max(supplied.abs())
        );
    }
}
