//! The Simo–Vu-Quoc 2-node rod element with one-point integration, objective (Crisfield–Jelenić)
//! strains and the Bubnov–Galerkin internal force, i.e. the exact gradient of the element energy.
//!
//! Formulary: `numerics/rod-statics.md` §1–§4 (our axis t1 = E1). Unknowns per node: position x_a and
//! rotation R_a; variations and increments are spatial spins δθ_a (δR = δθ̂ R). Node-major ordering
//! [x1, θ1, x2, θ2].
use crate::so3::{exp, log_quat, skew, tangent_left_inv, tangent_right_inv};
use nalgebra::{Matrix3, Matrix6, SMatrix, SVector, UnitQuaternion, Vector3};

/// 12-vector of element nodal forces [f_x1, m_1, f_x2, m_2].
pub type ElementVector = SVector<f64, 12>;
/// 12×12 element tangent.
pub type ElementMatrix = SMatrix<f64, 12, 12>;
pub(crate) type Block3x12 = SMatrix<f64, 3, 12>;

/// The 3×12 map of a nodal difference (u2 − u1)·scale for the 3 unknowns starting at `offset` of each
/// node (0: position, 3: rotation) in the element ordering [x1, θ1, x2, θ2].
pub(crate) fn nodal_difference(offset: usize, scale: f64) -> Block3x12 {
    let mut block = Block3x12::zeros();
    block.fixed_view_mut::<3, 3>(0, offset).fill_with_identity();
    block.fixed_view_mut::<3, 3>(0, offset).scale_mut(-scale);
    block
        .fixed_view_mut::<3, 3>(0, offset + 6)
        .fill_with_identity();
    block.fixed_view_mut::<3, 3>(0, offset + 6).scale_mut(scale);
    block
}

/// Reference data of one element: length and the stress-free strains.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementReference {
    /// Reference length L0 (m).
    pub length: f64,
    /// Reference strain Γ0 (computed with the same discrete formula as Γ).
    pub strain: Vector3<f64>,
    /// Reference curvature K0 (1/m).
    pub curvature: Vector3<f64>,
}

impl ElementReference {
    /// Reference data from the reference nodes and frames (formulary §1: Γ0, K0 by the discrete formulas).
    pub fn new(
        x1: &Vector3<f64>,
        x2: &Vector3<f64>,
        r1: &UnitQuaternion<f64>,
        r2: &UnitQuaternion<f64>,
        length: f64,
    ) -> Self {
        let zero = ElementReference {
            length,
            strain: Vector3::zeros(),
            curvature: Vector3::zeros(),
        };
        let (strain, curvature) = Kinematics::new(x1, x2, r1, r2, &zero).strains();
        ElementReference {
            length,
            strain,
            curvature,
        }
    }
}

/// Element kinematics at the Gauss point (formulary §1).
#[derive(Debug, Clone)]
struct Kinematics {
    length: f64,
    /// d = x2 − x1.
    chord: Vector3<f64>,
    /// Material relative rotation Ψ = log(R1ᵀ R2).
    relative_material: Vector3<f64>,
    /// Spatial relative rotation ψ = R1 Ψ.
    relative_spatial: Vector3<f64>,
    /// Midpoint triad R_m = R1 exp(½ Ψ̂).
    midpoint_rotation: Matrix3<f64>,
}

impl Kinematics {
    fn new(
        x1: &Vector3<f64>,
        x2: &Vector3<f64>,
        r1: &UnitQuaternion<f64>,
        r2: &UnitQuaternion<f64>,
        reference: &ElementReference,
    ) -> Self {
        let relative_material = log_quat(&(r1.inverse() * r2));
        let r1m = r1.to_rotation_matrix().into_inner();
        Kinematics {
            length: reference.length,
            chord: x2 - x1,
            relative_material,
            relative_spatial: r1m * relative_material,
            midpoint_rotation: r1m * exp(&(0.5 * relative_material)),
        }
    }

    /// Γ = R_mᵀ x′ − E1 and K = Ψ / L0.
    fn strains(&self) -> (Vector3<f64>, Vector3<f64>) {
        let tangent = self.chord / self.length;
        let strain = self.midpoint_rotation.transpose() * tangent - Vector3::x();
        (strain, self.relative_material / self.length)
    }
}

/// Midpoint triad R_m and strains (Γ, K) of the objective element for a configuration (formulary §1).
pub fn midpoint_frame_and_strains(
    x1: &Vector3<f64>,
    x2: &Vector3<f64>,
    r1: &UnitQuaternion<f64>,
    r2: &UnitQuaternion<f64>,
    reference: &ElementReference,
) -> (Matrix3<f64>, Vector3<f64>, Vector3<f64>) {
    let kin = Kinematics::new(x1, x2, r1, r2, reference);
    let (strain, curvature) = kin.strains();
    (kin.midpoint_rotation, strain, curvature)
}

/// Everything the solver needs from one element evaluation.
#[derive(Debug, Clone)]
pub struct ElementResponse {
    /// Material resultants [N; M] at the Gauss point (force N, moment N·m).
    pub material_force: Vector3<f64>,
    pub material_moment: Vector3<f64>,
    /// Stored energy Π_e (J).
    pub energy: f64,
    /// Relative rotation |ψ| between the nodes (rad).
    pub relative_rotation: f64,
    /// Internal nodal forces f_int = ∂Π_e/∂[x1, θ1, x2, θ2].
    pub forces: ElementVector,
}

/// τ(ψ) = tan(ψ/4)/ψ and τ′(ψ)/ψ, with series below 1e-2 (formulary §4b).
fn tau_and_derivative(psi: f64) -> (f64, f64) {
    if psi < 1e-2 {
        let p2 = psi * psi;
        (
            0.25 + p2 / 192.0 + p2 * p2 / 7680.0,
            1.0 / 96.0 + p2 / 1920.0,
        )
    } else {
        let tau = (0.25 * psi).tan() / psi;
        let c = (0.25 * psi).cos();
        let dtau = 1.0 / (4.0 * psi * c * c) - tau / psi;
        (tau, dtau / psi)
    }
}

/// q(ψ) = (1/ψ²)(1 − ψ/(2 sin(ψ/2))) and q′(ψ)/ψ, with series below 1e-2 (formulary §4b).
fn q_and_derivative(psi: f64) -> (f64, f64) {
    if psi < 1e-2 {
        let p2 = psi * psi;
        (
            -1.0 / 24.0 - 7.0 * p2 / 5760.0 - 31.0 * p2 * p2 / 967680.0,
            -7.0 / 2880.0 - 31.0 * p2 / 241920.0,
        )
    } else {
        let s = (0.5 * psi).sin();
        let c = (0.5 * psi).cos();
        let q = (1.0 - psi / (2.0 * s)) / (psi * psi);
        let dq = -2.0 * q / psi - (2.0 * s - psi * c) / (4.0 * psi * psi * s * s);
        (q, dq / psi)
    }
}

/// A section's response at the Gauss point to the changes of strain and curvature (Γ − Γ₀, K − K₀): the
/// material force and moment, the stored energy per unit length (J/m) and the tangent
/// ∂(n, m)/∂(Γ − Γ₀, K − K₀) (blocks [C_TT C_TR; C_RT C_RR]).
#[derive(Debug, Clone, Copy)]
pub struct SectionLaw {
    pub force: Vector3<f64>,
    pub moment: Vector3<f64>,
    pub energy: f64,
    pub stiffness: Matrix6<f64>,
}

/// The linear elastic law n = C_T (Γ − Γ₀), m = C_R (K − K₀) (eqs. 29–30).
pub fn elastic_law(
    c_t: &Matrix3<f64>,
    c_r: &Matrix3<f64>,
    strain_change: &Vector3<f64>,
    curvature_change: &Vector3<f64>,
) -> SectionLaw {
    let force = c_t * strain_change;
    let moment = c_r * curvature_change;
    let mut stiffness = Matrix6::zeros();
    stiffness.fixed_view_mut::<3, 3>(0, 0).copy_from(c_t);
    stiffness.fixed_view_mut::<3, 3>(3, 3).copy_from(c_r);
    SectionLaw {
        force,
        moment,
        energy: 0.5 * (strain_change.dot(&force) + curvature_change.dot(&moment)),
        stiffness,
    }
}

/// Evaluates the element of a linear elastic section (C_T, C_R): see [`evaluate_with`].
#[allow(clippy::too_many_arguments)]
pub fn evaluate(
    x1: &Vector3<f64>,
    x2: &Vector3<f64>,
    r1: &UnitQuaternion<f64>,
    r2: &UnitQuaternion<f64>,
    reference: &ElementReference,
    c_t: &Matrix3<f64>,
    c_r: &Matrix3<f64>,
    tangent: Option<&mut ElementMatrix>,
) -> ElementResponse {
    let mut law =
        |strain: &Vector3<f64>, curvature: &Vector3<f64>| elastic_law(c_t, c_r, strain, curvature);
    evaluate_with(x1, x2, r1, r2, reference, &mut law, tangent)
}

/// Evaluates the element: resultants, energy, internal forces and, if `tangent` is given, the
/// consistent tangent K = ∂f_int/∂[x1, θ1, x2, θ2] (material and geometric parts, formulary §4b,
/// "energy-consistent (BG) objective element"), the section's response given by `law` (a yielding
/// section's couples the axial force and the bending moments: its tangent's C_TR block).
pub fn evaluate_with(
    x1: &Vector3<f64>,
    x2: &Vector3<f64>,
    r1: &UnitQuaternion<f64>,
    r2: &UnitQuaternion<f64>,
    reference: &ElementReference,
    law: &mut dyn FnMut(&Vector3<f64>, &Vector3<f64>) -> SectionLaw,
    tangent: Option<&mut ElementMatrix>,
) -> ElementResponse {
    let kin = Kinematics::new(x1, x2, r1, r2, reference);
    let l0 = kin.length;
    let (strain, curvature) = kin.strains();
    let strain_change = strain - reference.strain;
    let curvature_change = curvature - reference.curvature;
    let section = law(&strain_change, &curvature_change);
    let (material_force, material_moment) = (section.force, section.moment);
    let energy = l0 * section.energy;

    let rm = &kin.midpoint_rotation;
    let n = rm * material_force;
    let m = rm * material_moment;
    let psi_vec = kin.relative_spatial;
    let psi = psi_vec.norm();
    let psi_hat = skew(&psi_vec);
    let (tau, dtau_over_psi) = tau_and_derivative(psi);
    let (q, dq_over_psi) = q_and_derivative(psi);
    let identity = Matrix3::identity();
    let q_mat = identity + q * psi_hat * psi_hat;
    // Row (test) factors V_aᵀ: V1ᵀ = ½(I − τψ̂), V2ᵀ = ½(I + τψ̂).
    let v1t = 0.5 * (identity - tau * psi_hat);
    let v2t = 0.5 * (identity + tau * psi_hat);
    let x_prime = kin.chord / l0;
    let a = n.cross(&x_prime);
    let qm = q_mat * m;

    let mut forces = ElementVector::zeros();
    forces.fixed_rows_mut::<3>(0).copy_from(&(-n));
    forces
        .fixed_rows_mut::<3>(3)
        .copy_from(&(-qm + l0 * v1t * a));
    forces.fixed_rows_mut::<3>(6).copy_from(&n);
    forces
        .fixed_rows_mut::<3>(9)
        .copy_from(&(qm + l0 * v2t * a));

    if let Some(k) = tangent {
        // Linearisation chain, each a 3×12 map of [Δx1, Δθ1, Δx2, Δθ2].
        let d_xprime = nodal_difference(0, 1.0 / l0);
        let mut d_theta_m = Block3x12::zeros();
        d_theta_m
            .fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&v1t.transpose());
        d_theta_m
            .fixed_view_mut::<3, 3>(0, 9)
            .copy_from(&v2t.transpose());
        let mut d_kappa = Block3x12::zeros();
        d_kappa
            .fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-q_mat / l0));
        d_kappa
            .fixed_view_mut::<3, 3>(0, 9)
            .copy_from(&(q_mat / l0));
        let mut d_psi = Block3x12::zeros();
        d_psi
            .fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-tangent_right_inv(&psi_vec)));
        d_psi
            .fixed_view_mut::<3, 3>(0, 9)
            .copy_from(&tangent_left_inv(&psi_vec));

        let block = |row: usize, column: usize| {
            rm * section.stiffness.fixed_view::<3, 3>(row, column) * rm.transpose()
        };
        let xprime_hat = skew(&x_prime);
        let n_hat = skew(&n);
        let m_hat = skew(&m);
        // With the strain's change Δγ = Δx′ + x̂′Δθ_m and the curvature's Δκ (spatial):
        // Δn = c_TT Δγ + c_TR Δκ − n̂Δθ_m, Δm = c_RT Δγ + c_RR Δκ − m̂Δθ_m, Δa = Δn × x′ + n × Δx′.
        let d_gamma = d_xprime + xprime_hat * d_theta_m;
        let d_n = block(0, 0) * d_gamma + block(0, 3) * d_kappa - n_hat * d_theta_m;
        let d_m = block(3, 0) * d_gamma + block(3, 3) * d_kappa - m_hat * d_theta_m;
        let d_a = -xprime_hat * d_n + n_hat * d_xprime;
        // Terms from differentiating V_a and Q with respect to ψ.
        let d_tau_term =
            (-tau * skew(&a) + dtau_over_psi * (psi_hat * a) * psi_vec.transpose()) * d_psi;
        let d_q_term = (q
            * (psi_vec * m.transpose() - 2.0 * m * psi_vec.transpose()
                + psi_vec.dot(&m) * identity)
            + dq_over_psi * (psi_hat * psi_hat * m) * psi_vec.transpose())
            * d_psi;

        let q_dm = q_mat * d_m;
        k.fixed_rows_mut::<3>(0).copy_from(&(-d_n));
        k.fixed_rows_mut::<3>(6).copy_from(&d_n);
        k.fixed_rows_mut::<3>(3)
            .copy_from(&(-q_dm + l0 * v1t * d_a - 0.5 * l0 * d_tau_term - d_q_term));
        k.fixed_rows_mut::<3>(9)
            .copy_from(&(q_dm + l0 * v2t * d_a + 0.5 * l0 * d_tau_term + d_q_term));
    }

    ElementResponse {
        material_force,
        material_moment,
        energy,
        relative_rotation: psi,
        forces,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::so3::exp_quat;

    struct Case {
        x1: Vector3<f64>,
        x2: Vector3<f64>,
        r1: UnitQuaternion<f64>,
        r2: UnitQuaternion<f64>,
        reference: ElementReference,
        c_t: Matrix3<f64>,
        c_r: Matrix3<f64>,
    }

    impl Case {
        /// A curved reference, then a deformed state with a large relative rotation (|ψ| ≈ 1.1 rad).
        fn new(psi_scale: f64) -> Self {
            let rx1 = exp_quat(&Vector3::new(0.1, -0.2, 0.3));
            let rx2 = exp_quat(&Vector3::new(0.2, -0.1, 0.5));
            let reference = ElementReference::new(
                &Vector3::new(0.0, 0.0, 0.0),
                &Vector3::new(1.9, 0.3, -0.2),
                &rx1,
                &rx2,
                2.0,
            );
            let r1 = exp_quat(&Vector3::new(0.4, 0.7, -0.3));
            let r2 = exp_quat(&(psi_scale * Vector3::new(0.5, -0.6, 0.7))) * r1;
            Case {
                x1: Vector3::new(0.1, -0.2, 0.05),
                x2: Vector3::new(1.7, 0.9, -0.6),
                r1,
                r2,
                reference,
                c_t: Matrix3::from_diagonal(&Vector3::new(3.0, 1.2, 0.8)),
                c_r: Matrix3::new(2.0, 0.1, 0.0, 0.1, 1.5, 0.2, 0.0, 0.2, 1.1),
            }
        }

        /// The state perturbed along local DOF `dof` by `h` (spatial spin for rotations).
        fn perturbed(
            &self,
            dof: usize,
            h: f64,
        ) -> (
            Vector3<f64>,
            Vector3<f64>,
            UnitQuaternion<f64>,
            UnitQuaternion<f64>,
        ) {
            let (mut x1, mut x2, mut r1, mut r2) = (self.x1, self.x2, self.r1, self.r2);
            let mut e = Vector3::zeros();
            e[dof % 3] = h;
            match dof / 3 {
                0 => x1 += e,
                1 => r1 = exp_quat(&e) * r1,
                2 => x2 += e,
                _ => r2 = exp_quat(&e) * r2,
            }
            (x1, x2, r1, r2)
        }

        fn eval(
            &self,
            state: (
                Vector3<f64>,
                Vector3<f64>,
                UnitQuaternion<f64>,
                UnitQuaternion<f64>,
            ),
            k: Option<&mut ElementMatrix>,
        ) -> ElementResponse {
            evaluate(
                &state.0,
                &state.1,
                &state.2,
                &state.3,
                &self.reference,
                &self.c_t,
                &self.c_r,
                k,
            )
        }
    }

    #[test]
    fn reference_is_stress_free() {
        let case = Case::new(1.0);
        let rx1 = exp_quat(&Vector3::new(0.1, -0.2, 0.3));
        let rx2 = exp_quat(&Vector3::new(0.2, -0.1, 0.5));
        let r = evaluate(
            &Vector3::zeros(),
            &Vector3::new(1.9, 0.3, -0.2),
            &rx1,
            &rx2,
            &case.reference,
            &case.c_t,
            &case.c_r,
            None,
        );
        assert!(r.forces.norm() < 1e-14 && r.energy.abs() < 1e-28);
    }

    #[test]
    fn internal_force_is_the_energy_gradient() {
        for scale in [1e-6, 0.3, 1.0, 2.5] {
            let case = Case::new(scale);
            let f = case.eval(case.perturbed(0, 0.0), None).forces;
            let h = 1e-6;
            let mut worst: f64 = 0.0;
            for dof in 0..12 {
                let ep = case.eval(case.perturbed(dof, h), None).energy;
                let em = case.eval(case.perturbed(dof, -h), None).energy;
                worst = worst.max(((ep - em) / (2.0 * h) - f[dof]).abs());
            }
            assert!(worst < 1e-8 * f.norm().max(1.0), "scale {scale}: {worst:e}");
        }
    }

    #[test]
    fn tangent_matches_finite_differences() {
        for scale in [0.0, 1e-7, 0.3, 1.0, 2.5] {
            let case = Case::new(scale);
            let mut k = ElementMatrix::zeros();
            case.eval(case.perturbed(0, 0.0), Some(&mut k));
            let h = 1e-6;
            let mut fd = ElementMatrix::zeros();
            for dof in 0..12 {
                let fp = case.eval(case.perturbed(dof, h), None).forces;
                let fm = case.eval(case.perturbed(dof, -h), None).forces;
                fd.set_column(dof, &((fp - fm) / (2.0 * h)));
            }
            let err = (k - fd).abs().max();
            assert!(
                err < 1e-7 * k.abs().max(),
                "scale {scale}: {err:e} of {}",
                k.abs().max()
            );
        }
    }

    /// A law that couples the axial force with the bending moments (a yielding section's tangent has the C_TR
    /// block): a quadratic energy of a full symmetric 6×6 C, its gradient and tangent checked by differences.
    #[test]
    fn a_coupled_law_is_differentiated_consistently() {
        let stiffness = Matrix6::from_fn(|i, j| {
            if i == j {
                3.0 + i as f64
            } else {
                0.3 / (1.0 + (i + j) as f64)
            }
        });
        let mut law = |g: &Vector3<f64>, k: &Vector3<f64>| {
            let strains = nalgebra::Vector6::new(g.x, g.y, g.z, k.x, k.y, k.z);
            let resultants = stiffness * strains;
            SectionLaw {
                force: resultants.fixed_rows::<3>(0).into_owned(),
                moment: resultants.fixed_rows::<3>(3).into_owned(),
                energy: 0.5 * strains.dot(&resultants),
                stiffness,
            }
        };
        let case = Case::new(1.0);
        let mut eval = |state: (
            Vector3<f64>,
            Vector3<f64>,
            UnitQuaternion<f64>,
            UnitQuaternion<f64>,
        ),
                        k: Option<&mut ElementMatrix>| {
            evaluate_with(
                &state.0,
                &state.1,
                &state.2,
                &state.3,
                &case.reference,
                &mut law,
                k,
            )
        };
        let mut k = ElementMatrix::zeros();
        let f = eval(case.perturbed(0, 0.0), Some(&mut k)).forces;
        let h = 1e-6;
        let (mut worst_force, mut worst_tangent): (f64, f64) = (0.0, 0.0);
        for dof in 0..12 {
            let plus = eval(case.perturbed(dof, h), None);
            let minus = eval(case.perturbed(dof, -h), None);
            worst_force =
                worst_force.max(((plus.energy - minus.energy) / (2.0 * h) - f[dof]).abs());
            let column = (plus.forces - minus.forces) / (2.0 * h);
            worst_tangent = worst_tangent.max((column - k.column(dof)).abs().max());
        }
        assert!(worst_force < 1e-8 * f.norm(), "{worst_force:e}");
        assert!(worst_tangent < 1e-7 * k.abs().max(), "{worst_tangent:e}");
    }

    #[test]
    fn rigid_motion_leaves_energy_and_forces_objective() {
        let case = Case::new(1.0);
        let base = case.eval(case.perturbed(0, 0.0), None);
        let q = exp_quat(&Vector3::new(-1.3, 0.4, 2.2));
        let shift = Vector3::new(5.0, -3.0, 7.0);
        let moved = evaluate(
            &(q * case.x1 + shift),
            &(q * case.x2 + shift),
            &(q * case.r1),
            &(q * case.r2),
            &case.reference,
            &case.c_t,
            &case.c_r,
            None,
        );
        assert!((moved.energy - base.energy).abs() < 1e-12 * base.energy);
        assert!(
            (moved.material_force - base.material_force).norm()
                < 1e-12 * base.material_force.norm()
        );
        let rotated_force = q * base.forces.fixed_rows::<3>(0).into_owned();
        assert!(
            (moved.forces.fixed_rows::<3>(0) - rotated_force).norm() < 1e-12 * rotated_force.norm()
        );
    }

    #[test]
    fn forces_are_in_global_balance() {
        let case = Case::new(1.0);
        let f = case.eval(case.perturbed(0, 0.0), None).forces;
        let f1 = f.fixed_rows::<3>(0).into_owned();
        let f2 = f.fixed_rows::<3>(6).into_owned();
        let moment =
            f.fixed_rows::<3>(3) + f.fixed_rows::<3>(9) + case.x1.cross(&f1) + case.x2.cross(&f2);
        assert!((f1 + f2).norm() < 1e-13 && moment.norm() < 1e-12);
    }
}
