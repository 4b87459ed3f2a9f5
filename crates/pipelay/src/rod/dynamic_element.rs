//! One energy–momentum time step of the element (Simo, Tarnow & Doblaré 1995), formulary
//! `numerics/rod-dynamics.md` §1–§2 with our axis t1 = E1.
//!
//! The rotation Λ and the strains live at the Gauss point and are updated by the Cayley map of the
//! interpolated nodal increments θ_g = ½(θ1 + θ2): Λ_{n+1} = cay(θ_g)Λ_n. With Λ̄ = ½(Λ_n + Λ_{n+1}):
//! ΔΓ = Λ̄ᵀ(Δφ′ − θ_g × φ′_{n+½}) and ΔK = cof(Λ̄)ᵀθ′ exactly, so the average-of-strains resultants
//! N = C_T(Γ̄ − Γ0), M = C_R(K̄ − K0), pushed forward as n = Λ̄N, m = cof(Λ̄)M, do work equal to the
//! change of stored energy: the scheme conserves energy, and (being a weak form tested with rigid motions)
//! linear and angular momentum.
// Indexing cannot go out of bounds here: Fixed-size 12-vectors and 3-vectors indexed by constants.
#![allow(clippy::indexing_slicing)]
use super::element::{midpoint_frame_and_strains, ElementMatrix, ElementReference, ElementVector};
use crate::so3::{cayley, cayley_tangent, skew};
use nalgebra::{Matrix3, Matrix6, UnitQuaternion, Vector3};
use std::ops::AddAssign;

/// Stored state of an element's Gauss point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussPoint {
    /// Λ at the Gauss point.
    pub rotation: Matrix3<f64>,
    /// Γ = Λᵀφ′ − E1.
    pub strain: Vector3<f64>,
    /// K (updated incrementally).
    pub curvature: Vector3<f64>,
}

impl GaussPoint {
    /// The Gauss point of a configuration, from the objective (static) element: Λ = R_m, Γ, K.
    pub fn from_configuration(
        x1: &Vector3<f64>,
        x2: &Vector3<f64>,
        r1: &UnitQuaternion<f64>,
        r2: &UnitQuaternion<f64>,
        reference: &ElementReference,
    ) -> Self {
        let (rotation, strain, curvature) = midpoint_frame_and_strains(x1, x2, r1, r2, reference);
        GaussPoint {
            rotation,
            strain,
            curvature,
        }
    }

    /// Stored energy ½L0[(Γ−Γ0)·C_T(Γ−Γ0) + (K−K0)·C_R(K−K0)] (J).
    pub fn energy(
        &self,
        reference: &ElementReference,
        c_t: &Matrix3<f64>,
        c_r: &Matrix3<f64>,
    ) -> f64 {
        let g = self.strain - reference.strain;
        let k = self.curvature - reference.curvature;
        0.5 * reference.length * (g.dot(&(c_t * g)) + k.dot(&(c_r * k)))
    }
}

/// How the stresses of a step are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StressRule {
    /// Average of the strains at n and n+1 (energy–momentum conserving).
    AverageStrain,
    /// Strains of the midpoint configuration (a plain midpoint rule: conserves momentum, not energy).
    MidpointConfiguration,
}

/// A section's law over a time step: the algorithmic resultants N̄, M̄ (material frame) whose work over the
/// step, N̄·ΔΓ + M̄·ΔK, is the stored energy's change and the dissipation, their derivative with respect to the
/// end's strain and curvature (Γ_{n+1}, K_{n+1}; blocks [TT TR; RT RR]), the stored energy per unit length at
/// the end (J/m) and the energy dissipated per unit length over the step (J/m).
#[derive(Debug, Clone, Copy)]
pub struct StepLaw {
    pub force: Vector3<f64>,
    pub moment: Vector3<f64>,
    pub derivative: Matrix6<f64>,
    pub energy_end: f64,
    pub dissipated: f64,
}

/// What a step's section law is given: the changes of strain and curvature (from the reference's) at the
/// step's start and end, and the stress rule's algorithmic ones.
#[derive(Debug, Clone, Copy)]
pub struct StepStrains {
    pub start: (Vector3<f64>, Vector3<f64>),
    pub end: (Vector3<f64>, Vector3<f64>),
    pub algorithmic: (Vector3<f64>, Vector3<f64>),
}

/// The linear elastic law over a step: N̄ = C_T(Γ_alg − Γ₀), M̄ = C_R(K_alg − K₀), their derivative by the
/// end's strains ½C (exact for the average-strain rule; the midpoint rule reuses it).
pub fn elastic_step_law(c_t: &Matrix3<f64>, c_r: &Matrix3<f64>, strains: &StepStrains) -> StepLaw {
    let (g, k) = strains.algorithmic;
    let (g_end, k_end) = strains.end;
    let mut derivative = Matrix6::zeros();
    derivative
        .fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(0.5 * c_t));
    derivative
        .fixed_view_mut::<3, 3>(3, 3)
        .copy_from(&(0.5 * c_r));
    StepLaw {
        force: c_t * g,
        moment: c_r * k,
        derivative,
        energy_end: 0.5 * (g_end.dot(&(c_t * g_end)) + k_end.dot(&(c_r * k_end))),
        dissipated: 0.0,
    }
}

/// The law `law` with damping of the step's strain changes added: N̄ + D_T ΔΓ and M̄ + D_R ΔK, with ΔΓ, ΔK
/// the step's changes of strain and curvature and D_T, D_R symmetric and positive semi-definite. Its work over
/// the step, ΔΓ·D_T ΔΓ + ΔK·D_R ΔK per unit length (≥ 0), is added to the law's dissipation, so the energy
/// identity holds exactly. Two dampings take this form ([`damping_matrices`]):
/// - high-frequency damping ξ: D = ξC, a stiffness-proportional damping whose coefficient scales with the
///   step, β = ξΔt: a mode of circular frequency ω is damped at the ratio ξωΔt/2, so modes the step cannot
///   resolve (ωΔt ≫ 1: the stiff axial modes of short elements, contact impacts) are overdamped while those it
///   resolves keep most of their energy;
/// - structural (Kelvin–Voigt) damping B Γ̇ ([`crate::rod::section::StructuralDamping`]): D = B/Δt, the
///   strain rate over the step ΔΓ/Δt.
///
/// Returns the law and the damping's dissipation per unit length (J/m).
pub fn with_damping(
    law: StepLaw,
    strains: &StepStrains,
    d_t: &Matrix3<f64>,
    d_r: &Matrix3<f64>,
) -> (StepLaw, f64) {
    let strain = strains.end.0 - strains.start.0;
    let curvature = strains.end.1 - strains.start.1;
    let (force, moment) = (d_t * strain, d_r * curvature);
    let dissipated = force.dot(&strain) + moment.dot(&curvature);
    let mut derivative = law.derivative;
    derivative.fixed_view_mut::<3, 3>(0, 0).add_assign(d_t);
    derivative.fixed_view_mut::<3, 3>(3, 3).add_assign(d_r);
    (
        StepLaw {
            force: law.force + force,
            moment: law.moment + moment,
            derivative,
            dissipated: law.dissipated + dissipated,
            ..law
        },
        dissipated,
    )
}

/// The damping matrices (D_T, D_R) of [`with_damping`] over a step `dt` (s): high-frequency damping ξ on the
/// stiffnesses C_T, C_R and, if any, structural damping matrices B_T, B_R (N·s, N·m²·s): D = ξC + B/Δt.
pub fn damping_matrices(
    high_frequency: f64,
    c_t: &Matrix3<f64>,
    c_r: &Matrix3<f64>,
    structural: Option<&(Matrix3<f64>, Matrix3<f64>)>,
    dt: f64,
) -> (Matrix3<f64>, Matrix3<f64>) {
    let (d_t, d_r) = (high_frequency * c_t, high_frequency * c_r);
    match structural {
        Some((b_t, b_r)) => (d_t + b_t / dt, d_r + b_r / dt),
        None => (d_t, d_r),
    }
}

/// One element's contribution to a time step.
#[derive(Debug, Clone)]
pub struct ElementStep {
    /// Algorithmic internal nodal forces [f_x1, m_1, f_x2, m_2] (work-conjugate to [Δφ1, θ1, Δφ2, θ2]).
    pub forces: ElementVector,
    /// The Gauss point at n+1.
    pub next: GaussPoint,
}

/// Internal forces of one step and, if asked, their tangent with respect to [Δφ1, θ1, Δφ2, θ2].
/// `chord` is φ2 − φ1 at step n; `increments` the unknowns [Δφ1, θ1, Δφ2, θ2].
///
/// `length_start` is the element's reference length L_n at step n, `reference.length` the length L_{n+1} at
/// n+1 (they differ only for the element that grows with pay-out). Γ_{n+1} = Λ_{n+1}ᵀφ′_{n+1} − E1 with
/// φ′ = chord/L_{n+1}, K_{n+1}L_{n+1} = K_nL_n + cof(Λ̄)ᵀ(θ2 − θ1): each level's strain is its own, so the
/// averaged stress sees no jump when L changes. The forces then do the work
/// L_{n+1}[N̄·(Γ_{n+1} − Γ̃_n) + M̄·(K_{n+1} − K̃_n)] with Γ̃_n, K̃_n the step-n strains at length L_{n+1};
/// the rest of the change of stored energy is the energy pay-out brings in.
#[allow(clippy::too_many_arguments)]
pub fn step(
    chord: &Vector3<f64>,
    increments: &ElementVector,
    gauss: &GaussPoint,
    length_start: f64,
    reference: &ElementReference,
    c_t: &Matrix3<f64>,
    c_r: &Matrix3<f64>,
    rule: StressRule,
    tangent: Option<&mut ElementMatrix>,
) -> ElementStep {
    let mut law = |strains: &StepStrains| elastic_step_law(c_t, c_r, strains);
    step_with(
        chord,
        increments,
        gauss,
        length_start,
        reference,
        rule,
        &mut law,
        tangent,
    )
}

/// [`step`] with the section's law over the step given by `law` (a yielding wall's: its resultants averaged
/// over its fibres' strain paths, coupling the axial force with the bending moments).
#[allow(clippy::too_many_arguments)]
pub fn step_with(
    chord: &Vector3<f64>,
    increments: &ElementVector,
    gauss: &GaussPoint,
    length_start: f64,
    reference: &ElementReference,
    rule: StressRule,
    law: &mut dyn FnMut(&StepStrains) -> StepLaw,
    tangent: Option<&mut ElementMatrix>,
) -> ElementStep {
    let l0 = reference.length;
    // K̃_n: the step-n relative rotation K_nL_n spread over the length L_{n+1}.
    let curvature_start = gauss.curvature * (length_start / l0);
    let identity = Matrix3::identity();
    let dphi1 = increments.fixed_rows::<3>(0).into_owned();
    let theta1 = increments.fixed_rows::<3>(3).into_owned();
    let dphi2 = increments.fixed_rows::<3>(6).into_owned();
    let theta2 = increments.fixed_rows::<3>(9).into_owned();
    let theta_g = 0.5 * (theta1 + theta2);
    let theta_prime = (theta2 - theta1) / l0;
    let q = cayley(&theta_g);
    let rotation_next = q * gauss.rotation;
    // Λ̄ = ½(I + Q)Λ_n = (I − ½θ̂_g)⁻¹Λ_n, so Λ̄⁻¹ = Λ_nᵀ(I − ½θ̂_g) and det Λ̄ = 1/(1 + |θ_g|²/4).
    let half_theta_hat = 0.5 * skew(&theta_g);
    let mean_inverse = gauss.rotation.transpose() * (identity - half_theta_hat);
    let mean = 0.5 * (gauss.rotation + rotation_next);
    let det = 1.0 / (1.0 + 0.25 * theta_g.norm_squared());
    let cofactor = det * mean_inverse.transpose();
    let tangent_n = chord / l0;
    let tangent_next = tangent_n + (dphi2 - dphi1) / l0;
    let tangent_mid = 0.5 * (tangent_n + tangent_next);
    let strain_next = rotation_next.transpose() * tangent_next - Vector3::x();
    let curvature_next = curvature_start + cofactor.transpose() * theta_prime;
    let (strain_alg, curvature_alg) = match rule {
        StressRule::AverageStrain => (
            0.5 * (gauss.strain + strain_next),
            0.5 * (gauss.curvature + curvature_next),
        ),
        StressRule::MidpointConfiguration => {
            let rotation_mid = cayley(&(0.5 * theta_g)) * gauss.rotation;
            (
                rotation_mid.transpose() * tangent_mid - Vector3::x(),
                curvature_start + 0.5 * cofactor.transpose() * theta_prime,
            )
        }
    };
    let section = law(&StepStrains {
        start: (
            gauss.strain - reference.strain,
            curvature_start - reference.curvature,
        ),
        end: (
            strain_next - reference.strain,
            curvature_next - reference.curvature,
        ),
        algorithmic: (
            strain_alg - reference.strain,
            curvature_alg - reference.curvature,
        ),
    });
    let (material_force, material_moment) = (section.force, section.moment);
    let n = mean * material_force;
    let m = cofactor * material_moment;
    let lever = 0.5 * l0 * n.cross(&tangent_mid);
    let mut forces = ElementVector::zeros();
    forces.fixed_rows_mut::<3>(0).copy_from(&(-n));
    forces.fixed_rows_mut::<3>(3).copy_from(&(-m + lever));
    forces.fixed_rows_mut::<3>(6).copy_from(&n);
    forces.fixed_rows_mut::<3>(9).copy_from(&(m + lever));

    if let Some(k) = tangent {
        // Linearisation (exact for the average-strain rule; the midpoint rule reuses it), in 3×3 blocks by
        // [Δφ1, θ1, Δφ2, θ2]: dφ′ = (dΔφ2 − dΔφ1)/L0, dθ′ = (dθ2 − dθ1)/L0, and the Gauss point's spin
        // w = T_c(dθ1 + dθ2)/2 with dΛ_{n+1} = ŵΛ_{n+1}, so both nodal rotations enter through t_c = ½T_c.
        let inverse_length = 1.0 / l0;
        let t_c = 0.5 * cayley_tangent(&theta_g);
        let rotation_next_t = rotation_next.transpose();
        // d(trace Λ̄⁻¹dΛ̄) = ½ c(Λ_{n+1}Λ̄⁻¹)·w with c(B) = (B23−B32, B31−B13, B12−B21).
        let b = rotation_next * mean_inverse;
        let trace_row = 0.5
            * Vector3::new(
                b[(1, 2)] - b[(2, 1)],
                b[(2, 0)] - b[(0, 2)],
                b[(0, 1)] - b[(1, 0)],
            );
        // d(cof(Λ̄)ᵀu) = det[(Λ̄⁻¹u)(½c)ᵀ + ½Λ̄⁻¹(Λ_{n+1}Λ̄⁻¹u)^] w.
        let a_inv_u = mean_inverse * theta_prime;
        let cofactor_t_derivative = det
            * (a_inv_u * trace_row.transpose()
                + 0.5 * mean_inverse * skew(&(rotation_next * a_inv_u)));
        // d(cof(Λ̄)v) = det[(Λ̄⁻ᵀv)(½c)ᵀ − ½Λ̄⁻ᵀΛ_{n+1}ᵀ(Λ̄⁻ᵀv)^] w.
        let a_inv_t_v = mean_inverse.transpose() * material_moment;
        let cofactor_derivative = det
            * (a_inv_t_v * trace_row.transpose()
                - 0.5 * mean_inverse.transpose() * rotation_next_t * skew(&a_inv_t_v));
        // dΓ_{n+1} = Λ_{n+1}ᵀ(dφ′ + φ̂′_{n+1} w); dK_{n+1} = cof(Λ̄)ᵀdθ′ + d(cof(Λ̄)ᵀ)θ′.
        let strain_by_rotation = rotation_next_t * skew(&tangent_next) * t_c;
        let curvature_by_spin = cofactor_t_derivative * t_c;
        let curvature_by_theta2 = curvature_by_spin + cofactor.transpose() * inverse_length;
        let curvature_by_theta1 = curvature_by_spin - cofactor.transpose() * inverse_length;
        // With D = ∂(N̄, M̄)/∂(Γ_{n+1}, K_{n+1}) (½C elastically):
        // dn = −(½Λ_{n+1}N̄)^ w + Λ̄(D_TT dΓ + D_TR dK), dm = d(cof(Λ̄))M̄ + cof(Λ̄)(D_RT dΓ + D_RR dK);
        // by Δφ1 the negative of by Δφ2.
        let block = |row: usize, column: usize| {
            section
                .derivative
                .fixed_view::<3, 3>(row, column)
                .into_owned()
        };
        let strain_by_phi2 = rotation_next_t * inverse_length;
        let n_by_phi2 = mean * block(0, 0) * strain_by_phi2;
        let m_by_phi2 = cofactor * block(3, 0) * strain_by_phi2;
        let n_spin = -skew(&(0.5 * rotation_next * material_force)) * t_c;
        let n_by_theta = |curvature_by_theta: &Matrix3<f64>| {
            n_spin + mean * (block(0, 0) * strain_by_rotation + block(0, 3) * curvature_by_theta)
        };
        let m_by_spin = cofactor_derivative * t_c;
        let m_by_theta = |curvature_by_theta: &Matrix3<f64>| {
            m_by_spin
                + cofactor * (block(3, 0) * strain_by_rotation + block(3, 3) * curvature_by_theta)
        };
        let (n_by_theta1, n_by_theta2) = (
            n_by_theta(&curvature_by_theta1),
            n_by_theta(&curvature_by_theta2),
        );
        let (m_by_theta1, m_by_theta2) = (
            m_by_theta(&curvature_by_theta1),
            m_by_theta(&curvature_by_theta2),
        );
        // d lever = ½L0(−t̂_mid dn + ½n̂ dφ′).
        let tangent_mid_hat = skew(&tangent_mid);
        let lever_by_phi2 = -0.5 * l0 * tangent_mid_hat * n_by_phi2 + 0.25 * skew(&n);
        let lever_by_theta1 = -0.5 * l0 * tangent_mid_hat * n_by_theta1;
        let lever_by_theta2 = -0.5 * l0 * tangent_mid_hat * n_by_theta2;
        let d_n = [-n_by_phi2, n_by_theta1, n_by_phi2, n_by_theta2];
        let d_m = [-m_by_phi2, m_by_theta1, m_by_phi2, m_by_theta2];
        let d_lever = [
            -lever_by_phi2,
            lever_by_theta1,
            lever_by_phi2,
            lever_by_theta2,
        ];
        for column in 0..4 {
            let (dn, dm, dl) = (d_n[column], d_m[column], d_lever[column]);
            for (row, block) in [-dn, dl - dm, dn, dm + dl].iter().enumerate() {
                k.fixed_view_mut::<3, 3>(3 * row, 3 * column)
                    .copy_from(block);
            }
        }
    }

    ElementStep {
        forces,
        next: GaussPoint {
            rotation: rotation_next,
            strain: strain_next,
            curvature: curvature_next,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::so3::exp_quat;

    fn case() -> (
        Vector3<f64>,
        GaussPoint,
        ElementReference,
        Matrix3<f64>,
        Matrix3<f64>,
    ) {
        let reference = ElementReference::new(
            &Vector3::zeros(),
            &Vector3::new(2.0, 0.1, 0.0),
            &exp_quat(&Vector3::new(0.0, 0.0, 0.05)),
            &exp_quat(&Vector3::new(0.1, 0.0, 0.05)),
            2.0,
        );
        let chord = Vector3::new(1.2, 1.5, -0.4);
        let rotation = exp_quat(&Vector3::new(0.3, -0.5, 0.9))
            .to_rotation_matrix()
            .into_inner();
        // The stored strain is that of the stored rotation and the current chord, as in the integrator.
        let gauss = GaussPoint {
            rotation,
            strain: rotation.transpose() * chord / 2.0 - Vector3::x(),
            curvature: Vector3::new(0.2, -0.1, 0.3),
        };
        let c_t = Matrix3::from_diagonal(&Vector3::new(5.0, 2.0, 1.5));
        let c_r = Matrix3::new(2.0, 0.1, 0.0, 0.1, 1.5, 0.2, 0.0, 0.2, 1.1);
        (chord, gauss, reference, c_t, c_r)
    }

    fn increments(scale: f64) -> ElementVector {
        ElementVector::from_column_slice(&[
            0.1, -0.2, 0.05, 0.3, -0.2, 0.4, -0.1, 0.15, 0.2, -0.5, 0.6, 0.1,
        ]) * scale
    }

    /// `step` on the test case, the element's length the same at both time levels.
    fn fixed_length(
        u: &ElementVector,
        rule: StressRule,
        k: Option<&mut ElementMatrix>,
    ) -> ElementStep {
        let (chord, gauss, reference, c_t, c_r) = case();
        step(
            &chord,
            u,
            &gauss,
            reference.length,
            &reference,
            &c_t,
            &c_r,
            rule,
            k,
        )
    }

    #[test]
    fn tangent_matches_finite_differences() {
        let run = fixed_length;
        for scale in [0.0, 0.5, 2.0] {
            let u = increments(scale);
            let mut k = ElementMatrix::zeros();
            run(&u, StressRule::AverageStrain, Some(&mut k));
            let h = 1e-6;
            let mut worst: f64 = 0.0;
            for j in 0..12 {
                let mut up = u;
                up[j] += h;
                let mut um = u;
                um[j] -= h;
                let fp = run(&up, StressRule::AverageStrain, None).forces;
                let fm = run(&um, StressRule::AverageStrain, None).forces;
                worst = worst.max(((fp - fm) / (2.0 * h) - k.column(j)).abs().max());
            }
            assert!(worst < 1e-7 * k.abs().max(), "scale {scale}: {worst:e}");
        }
    }

    /// A wall that yields: the step's tangent is the differences' of its forces, and their work over the step
    /// is the change of stored (free) energy plus the dissipation, exactly.
    #[test]
    fn a_yielding_walls_step_is_consistent_and_its_work_exact() {
        use crate::rod::fibre_section::FibreSection;
        use crate::rod::material::Material;
        let (chord, gauss, reference, _, _) = case();
        let mut fibres = FibreSection::pipe(
            0.4,
            0.02,
            Material::ramberg_osgood(207e9, 450e6, 14.0).unwrap(),
        )
        .unwrap();
        (fibres.shear, fibres.torsion) = ([1e9, 1e9], 5e7);
        // A plastic state from a bend and a stretch beforehand, consistent with the step's start.
        let start = (
            gauss.strain - reference.strain,
            gauss.curvature - reference.curvature,
        );
        let mut plastic = vec![0.0; fibres.state_size()];
        let mut scratch = plastic.clone();
        let earlier = (start.0 * 0.7 + Vector3::new(0.004, 0.0, 0.0), start.1 * 1.3);
        fibres.law(&earlier.0, &earlier.1, &plastic.clone(), &mut plastic);
        fibres.law(&start.0, &start.1, &plastic.clone(), &mut scratch);
        plastic.copy_from_slice(&scratch);
        let energy_start = fibres.energy(&start.0, &start.1, &plastic);
        let run = |u: &ElementVector, k: Option<&mut ElementMatrix>| {
            let mut end = plastic.clone();
            let mut recorded = (0.0, 0.0);
            let mut law = |strains: &StepStrains| {
                let law = fibres.step_law(&strains.start, &strains.end, &plastic, &mut end);
                recorded = (law.energy_end, law.dissipated);
                law
            };
            let step = step_with(
                &chord,
                u,
                &gauss,
                reference.length,
                &reference,
                StressRule::AverageStrain,
                &mut law,
                k,
            );
            (step, recorded)
        };
        for scale in [0.01, 0.05] {
            let u = increments(scale);
            let mut k = ElementMatrix::zeros();
            let (s, (energy_end, dissipated)) = run(&u, Some(&mut k));
            let work = s.forces.dot(&u);
            let balance =
                reference.length * (energy_end + dissipated) - reference.length * energy_start;
            assert!(dissipated > 0.0, "the step must yield");
            assert!(
                (work - balance).abs() < 1e-10 * balance.abs(),
                "{work} vs {balance}"
            );
            let h = 1e-9;
            let mut worst: f64 = 0.0;
            for j in 0..12 {
                let (mut up, mut um) = (u, u);
                up[j] += h;
                um[j] -= h;
                let column = (run(&up, None).0.forces - run(&um, None).0.forces) / (2.0 * h);
                worst = worst.max((column - k.column(j)).abs().max());
            }
            assert!(
                worst < 1e-5 * k.abs().max(),
                "scale {scale}: {worst:e} of {}",
                k.abs().max()
            );
        }
    }

    /// The work of the algorithmic forces over the step equals the change of stored energy.
    #[test]
    fn work_equals_the_change_of_stored_energy() {
        let (_, gauss, reference, c_t, c_r) = case();
        let run = fixed_length;
        for scale in [0.1, 1.0, 3.0] {
            let u = increments(scale);
            let s = run(&u, StressRule::AverageStrain, None);
            let work = s.forces.dot(&u);
            let change =
                s.next.energy(&reference, &c_t, &c_r) - gauss.energy(&reference, &c_t, &c_r);
            assert!(
                (work - change).abs() < 1e-13 * change.abs().max(1.0),
                "{work} vs {change}"
            );
            let mid = run(&u, StressRule::MidpointConfiguration, None);
            if scale >= 1.0 {
                assert!((mid.forces.dot(&u) - change).abs() > 1e-6 * change.abs());
            }
        }
    }

    /// With high-frequency damping ξ: the work of the forces is the change of stored energy plus the damping's
    /// dissipation L ξ(ΔΓ·C_T ΔΓ + ΔK·C_R ΔK) ≥ 0, and the tangent matches central differences.
    #[test]
    fn strain_rate_damping_dissipates_its_work_with_a_consistent_tangent() {
        let (chord, gauss, reference, c_t, c_r) = case();
        // High-frequency damping ξ = 0.3 and structural damping (2 %, 5 %, 1 % at 0.5 s) over a 0.1 s step.
        let structural = crate::rod::section::StructuralDamping::new(0.02, 0.05, 0.01, 0.5)
            .expect("damping")
            .matrices(&c_t, &c_r);
        let (d_t, d_r) = damping_matrices(0.3, &c_t, &c_r, Some(&structural), 0.1);
        for scale in [0.1, 1.0, 3.0] {
            let u = increments(scale);
            let mut dissipated = 0.0;
            let run = |u: &ElementVector, k: Option<&mut ElementMatrix>, dissipated: &mut f64| {
                let mut law = |strains: &StepStrains| {
                    let elastic = elastic_step_law(&c_t, &c_r, strains);
                    let (law, damped) = with_damping(elastic, strains, &d_t, &d_r);
                    *dissipated = reference.length * damped;
                    law
                };
                let rule = StressRule::AverageStrain;
                step_with(
                    &chord,
                    u,
                    &gauss,
                    reference.length,
                    &reference,
                    rule,
                    &mut law,
                    k,
                )
            };
            let mut k = ElementMatrix::zeros();
            let s = run(&u, Some(&mut k), &mut dissipated);
            let change =
                s.next.energy(&reference, &c_t, &c_r) - gauss.energy(&reference, &c_t, &c_r);
            let work = s.forces.dot(&u);
            assert!(dissipated > 0.0);
            assert!(
                (work - change - dissipated).abs() < 1e-12 * (change.abs() + dissipated),
                "{work} vs {change} + {dissipated}"
            );
            let g = s.next.strain - gauss.strain;
            let c = s.next.curvature - gauss.curvature;
            let expected = reference.length * (g.dot(&(d_t * g)) + c.dot(&(d_r * c)));
            assert!((dissipated - expected).abs() < 1e-12 * expected);
            let h = 1e-6;
            let mut worst: f64 = 0.0;
            for j in 0..12 {
                let (mut up, mut um) = (u, u);
                up[j] += h;
                um[j] -= h;
                let mut scratch = 0.0;
                let column = (run(&up, None, &mut scratch).forces
                    - run(&um, None, &mut scratch).forces)
                    / (2.0 * h);
                worst = worst.max((column - k.column(j)).abs().max());
            }
            assert!(worst < 1e-6 * k.abs().max(), "scale {scale}: {worst:e}");
        }
    }

    /// A growing element (L_n → L_{n+1}): the tangent still matches finite differences, and the work of the
    /// forces is L_{n+1}[N̄·(Γ_{n+1} − Γ̃_n) + M̄·(K_{n+1} − K̃_n)] with the step-n strains at length L_{n+1}.
    #[test]
    fn growing_element_tangent_and_work() {
        let (chord, gauss, reference, c_t, c_r) = case();
        let length_start = 0.93 * reference.length;
        // The stored strain is that of the step-n chord at the step-n length.
        let gauss = GaussPoint {
            strain: gauss.rotation.transpose() * chord / length_start - Vector3::x(),
            ..gauss
        };
        let run = |u: &ElementVector, k: Option<&mut ElementMatrix>| {
            let rule = StressRule::AverageStrain;
            step(
                &chord,
                u,
                &gauss,
                length_start,
                &reference,
                &c_t,
                &c_r,
                rule,
                k,
            )
        };
        let u = increments(1.0);
        let mut k = ElementMatrix::zeros();
        let s = run(&u, Some(&mut k));
        let h = 1e-6;
        let mut worst: f64 = 0.0;
        for j in 0..12 {
            let (mut up, mut um) = (u, u);
            up[j] += h;
            um[j] -= h;
            let column = (run(&up, None).forces - run(&um, None).forces) / (2.0 * h);
            worst = worst.max((column - k.column(j)).abs().max());
        }
        assert!(worst < 1e-7 * k.abs().max(), "{worst:e}");
        let l = reference.length;
        let strain_start = gauss.rotation.transpose() * chord / l - Vector3::x();
        let curvature_start = gauss.curvature * (length_start / l);
        let force = c_t * (0.5 * (gauss.strain + s.next.strain) - reference.strain);
        let moment = c_r * (0.5 * (gauss.curvature + s.next.curvature) - reference.curvature);
        let expected = l
            * (force.dot(&(s.next.strain - strain_start))
                + moment.dot(&(s.next.curvature - curvature_start)));
        let work = s.forces.dot(&u);
        assert!(
            (work - expected).abs() < 1e-12 * expected.abs(),
            "{work} vs {expected}"
        );
    }

    /// Steady pay-out: an element that moves rigidly while its chord grows with its length keeps its strains,
    /// and its forces are those of the unchanged strains (no jump from the growth).
    #[test]
    fn steady_growth_keeps_the_strains() {
        let (chord, gauss, reference, c_t, c_r) = case();
        let length_start = 0.9 * reference.length;
        let gauss = GaussPoint {
            strain: gauss.rotation.transpose() * chord / length_start - Vector3::x(),
            ..gauss
        };
        let translation = Vector3::new(0.3, -0.1, 0.2);
        let mut u = ElementVector::zeros();
        u.fixed_rows_mut::<3>(0).copy_from(&translation);
        let growth = chord * (reference.length / length_start - 1.0);
        u.fixed_rows_mut::<3>(6).copy_from(&(translation + growth));
        let s = step(
            &chord,
            &u,
            &gauss,
            length_start,
            &reference,
            &c_t,
            &c_r,
            StressRule::AverageStrain,
            None,
        );
        assert!((s.next.strain - gauss.strain).norm() < 1e-14);
        // K L is kept (the nodes do not rotate relative to each other): K_{n+1} = K_n L_n / L_{n+1}.
        let curvature = gauss.curvature * (length_start / reference.length);
        assert!((s.next.curvature - curvature).norm() < 1e-14);
        let axial = (gauss.rotation * (c_t * (gauss.strain - reference.strain))).norm();
        let f2 = s.forces.fixed_rows::<3>(6).into_owned();
        assert!(
            (f2.norm() - axial).abs() < 1e-9 * axial,
            "{} vs {axial}",
            f2.norm()
        );
    }

    /// Rigid increments (the same translation, or a rotation c about the origin) do no internal work
    /// and the internal forces carry no net force or moment.
    #[test]
    fn internal_forces_are_balanced() {
        let (chord, ..) = case();
        let run = fixed_length;
        let u = increments(1.0);
        let s = run(&u, StressRule::AverageStrain, None);
        let f1 = s.forces.fixed_rows::<3>(0).into_owned();
        let f2 = s.forces.fixed_rows::<3>(6).into_owned();
        // Moment arms at the mid-step positions φ_{n+½}; node 1 at the origin at step n.
        let x1 = 0.5 * u.fixed_rows::<3>(0).into_owned();
        let x2 = chord + 0.5 * u.fixed_rows::<3>(6).into_owned();
        let moment = s.forces.fixed_rows::<3>(3)
            + s.forces.fixed_rows::<3>(9)
            + x1.cross(&f1)
            + x2.cross(&f2);
        assert!(
            (f1 + f2).norm() < 1e-14 && moment.norm() < 1e-13,
            "{moment}"
        );
    }
}
