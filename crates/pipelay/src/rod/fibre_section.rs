//! A pipe wall as fibres: its axial force and bending moments, and their tangent, from the steel's law
//! ([`crate::rod::material`]) under combined tension and bending, with the fibres' plastic state.
//!
//! **Kinematics.** A fibre at (y, z) in the section frame (axes 2, 3) strains ε = ε₀ + z κ₂ − y κ₃ with the
//! axial strain ε₀ and the curvatures κ₂, κ₃ (so that elastically m₂ = EI κ₂, m₃ = EI κ₃). The resultants
//! N = ∫σ dA, m₂ = ∫σ z dA, m₃ = −∫σ y dA; their tangent ∂(N, m₂, m₃)/∂(ε₀, κ₂, κ₃) = ∫E_t g gᵀ dA with
//! g = (1, z, −y) and E_t each fibre's algorithmic tangent. Shear and torsion stay elastic.
//!
//! **Quadrature.** [`AROUND`] fibres around the wall (the midpoint rule in θ) on each of [`THROUGH`]
//! Gauss–Legendre radii through it (weight r dr). The elastic resultants are exact (the integrands are
//! trigonometric of degree 2 and cubic in r); a yielding wall's error comes from the kinks where fibres yield,
//! O(1/AROUND²): the thin elastic–perfectly plastic tube's moment is within 4e-4 of the closed forms at 5 κ_y
//! and at 100 κ_y (the tests).
// Indexing cannot go out of bounds here: fibre and state indices of the section's own lists.
#![allow(clippy::indexing_slicing)]
use crate::error::{positive, Error, Result};
use crate::rod::dynamic_element::{elastic_step_law, StepLaw, StepStrains};
use crate::rod::element::{elastic_law, SectionLaw};
use crate::rod::material::Material;
use nalgebra::{Matrix3, Matrix6, Vector3};

/// Fibres around the wall, and Gauss–Legendre radii through it.
pub const AROUND: usize = 64;
pub const THROUGH: usize = 2;

/// One fibre: its place in the section frame (m) and its area (m²).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Fibre {
    y: f64,
    z: f64,
    area: f64,
}

/// The fibres of a pipe's steel wall and its material.
#[derive(Debug, Clone, PartialEq)]
pub struct FibreSection {
    fibres: Vec<Fibre>,
    /// The wall's outer diameter (m).
    outer_diameter: f64,
    pub material: Material,
    /// What the rest of the section adds, elastically: the shear stiffnesses GA₂, GA₃ (N), the torsional GJ
    /// (N·m²), and the coatings' axial EA and bending EI (N, N·m²) beyond the wall's.
    pub shear: [f64; 2],
    pub torsion: f64,
    pub extra_axial: f64,
    pub extra_bending: f64,
}

/// A section's response to (ε₀, κ₂, κ₃) from a plastic state ([`FibreSection::respond`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionResponse {
    /// (N, m₂, m₃) (N, N·m, N·m).
    pub resultants: Vector3<f64>,
    /// ∂(N, m₂, m₃)/∂(ε₀, κ₂, κ₃).
    pub tangent: Matrix3<f64>,
    /// Free energy per unit length (J/m) after the step, and the energy dissipated per unit length over it.
    pub free_energy: f64,
    pub dissipated: f64,
}

impl FibreSection {
    /// The wall of a pipe of `outer_diameter` and `thickness` (m) of `material`.
    pub fn pipe(outer_diameter: f64, thickness: f64, material: Material) -> Result<Self> {
        positive("outer_diameter", outer_diameter, "m")?;
        positive("wall_thickness", thickness, "m")?;
        if 2.0 * thickness > outer_diameter {
            return Err(Error::input(
                "wall_thickness",
                thickness,
                format!("must be at most half the outer diameter {outer_diameter} m"),
            ));
        }
        let (outer, inner) = (0.5 * outer_diameter, 0.5 * outer_diameter - thickness);
        // Two-point Gauss–Legendre on [inner, outer], weight r dr (the area element r dr dθ).
        let (middle, half) = (0.5 * (outer + inner), 0.5 * (outer - inner));
        let offset = half / 3f64.sqrt();
        let radii = [middle - offset, middle + offset];
        let step = 2.0 * std::f64::consts::PI / AROUND as f64;
        let mut fibres = Vec::with_capacity(AROUND * THROUGH);
        for r in radii {
            for j in 0..AROUND {
                let theta = (j as f64 + 0.5) * step;
                fibres.push(Fibre {
                    y: r * theta.cos(),
                    z: r * theta.sin(),
                    area: half * r * step,
                });
            }
        }
        Ok(FibreSection {
            fibres,
            outer_diameter,
            material,
            shear: [0.0; 2],
            torsion: 0.0,
            extra_axial: 0.0,
            extra_bending: 0.0,
        })
    }

    /// The rest of the section beside the wall's axial force and bending, elastic: C_T = diag(EA_extra, GA₂,
    /// GA₃), C_R = diag(GJ, EI_extra, EI_extra) (the coatings' axial and bending stiffness, shear, torsion).
    fn rest(&self) -> (Matrix3<f64>, Matrix3<f64>) {
        (
            Matrix3::from_diagonal(&Vector3::new(
                self.extra_axial,
                self.shear[0],
                self.shear[1],
            )),
            Matrix3::from_diagonal(&Vector3::new(
                self.torsion,
                self.extra_bending,
                self.extra_bending,
            )),
        )
    }

    /// The whole section's law at the changes of strain and curvature (Γ − Γ₀, K − K₀): the wall's axial force
    /// and bending moments from its fibres, added to the rest's elastic law ([`Self::rest`]); from the plastic
    /// state `plastic`, the state after it into `plastic_end`. Also the energy dissipated per unit length.
    pub fn law(
        &self,
        strain: &Vector3<f64>,
        curvature: &Vector3<f64>,
        plastic: &[f64],
        plastic_end: &mut [f64],
    ) -> (SectionLaw, f64) {
        let wall = self.respond(
            &Vector3::new(strain.x, curvature.y, curvature.z),
            plastic,
            plastic_end,
        );
        let (c_t, c_r) = self.rest();
        let mut law = elastic_law(&c_t, &c_r, strain, curvature);
        add_wall(
            &mut law.force,
            &mut law.moment,
            &mut law.stiffness,
            &wall.resultants,
            &wall.tangent,
        );
        law.energy += wall.free_energy;
        (law, wall.dissipated)
    }

    /// A time step's section law from the changes of strain and curvature at the step's start (`start`:
    /// (Γ − Γ₀, K − K₀)) to its end (`end`), from the plastic state `plastic` (consistent with the start),
    /// the state after it into `plastic_end`: the wall's resultants averaged over each fibre's straight strain
    /// path ([`Material::respond_over`]) added to the rest's elastic step law over the average strain
    /// ([`elastic_step_law`]), their derivative with respect to the end's (Γ, K), the free energy per unit
    /// length at the end and the energy dissipated per unit length. Its work over the step, N̄·ΔΓ + M̄·ΔK, is
    /// the free energy's change and the dissipation.
    pub fn step_law(
        &self,
        start: &(Vector3<f64>, Vector3<f64>),
        end: &(Vector3<f64>, Vector3<f64>),
        plastic: &[f64],
        plastic_end: &mut [f64],
    ) -> StepLaw {
        let size = self.material.state_size();
        let wall_start = Vector3::new(start.0.x, start.1.y, start.1.z);
        let wall_end = Vector3::new(end.0.x, end.1.y, end.1.z);
        let mut resultants = Vector3::zeros();
        let mut derivative = Matrix3::zeros();
        let mut free_energy = 0.0;
        let mut dissipated = 0.0;
        for (k, fibre) in self.fibres.iter().enumerate() {
            let g = Vector3::new(1.0, fibre.z, -fibre.y);
            let state = k * size..(k + 1) * size;
            let response = self.material.respond_over(
                g.dot(&wall_start),
                g.dot(&wall_end),
                &plastic[state.clone()],
                &mut plastic_end[state],
            );
            resultants += fibre.area * response.mean * g;
            derivative += (fibre.area * response.mean_tangent) * g * g.transpose();
            free_energy += fibre.area * response.free_energy;
            dissipated += fibre.area * response.dissipated;
        }
        let (c_t, c_r) = self.rest();
        let average = (0.5 * (start.0 + end.0), 0.5 * (start.1 + end.1));
        let strains = StepStrains {
            start: *start,
            end: *end,
            algorithmic: average,
        };
        let mut law = elastic_step_law(&c_t, &c_r, &strains);
        add_wall(
            &mut law.force,
            &mut law.moment,
            &mut law.derivative,
            &resultants,
            &derivative,
        );
        law.energy_end += free_energy;
        law.dissipated = dissipated;
        law
    }

    /// The section's material force and moment, and stored energy per unit length (J/m), at the changes of
    /// strain and curvature (Γ − Γ₀, K − K₀) and the plastic state `plastic` consistent with them (where a step
    /// left it): read, not advanced.
    pub fn resultants_and_energy(
        &self,
        strain: &Vector3<f64>,
        curvature: &Vector3<f64>,
        plastic: &[f64],
    ) -> (Vector3<f64>, Vector3<f64>, f64) {
        let size = self.material.state_size();
        let wall = Vector3::new(strain.x, curvature.y, curvature.z);
        let mut resultants = Vector3::zeros();
        let mut energy = 0.0;
        for (k, fibre) in self.fibres.iter().enumerate() {
            let g = Vector3::new(1.0, fibre.z, -fibre.y);
            let (stress, free_energy) = self
                .material
                .stress_and_energy(g.dot(&wall), &plastic[k * size..(k + 1) * size]);
            resultants += fibre.area * stress * g;
            energy += fibre.area * free_energy;
        }
        let (c_t, c_r) = self.rest();
        let rest = elastic_law(&c_t, &c_r, strain, curvature);
        let force = rest.force + Vector3::new(resultants.x, 0.0, 0.0);
        let moment = rest.moment + Vector3::new(0.0, resultants.y, resultants.z);
        (force, moment, rest.energy + energy)
    }

    /// The section's stored energy per unit length (J/m) at the changes of strain and curvature and the plastic
    /// state `plastic` consistent with them ([`Self::resultants_and_energy`]).
    pub fn energy(&self, strain: &Vector3<f64>, curvature: &Vector3<f64>, plastic: &[f64]) -> f64 {
        self.resultants_and_energy(strain, curvature, plastic).2
    }

    /// The wall's outer diameter (m): twice its outermost fibre's radius over the quadrature's place.
    pub fn outer_diameter(&self) -> f64 {
        self.outer_diameter
    }

    /// Each fibre's plastic strain ε − σ/E at the strains (ε₀, κ₂, κ₃) and the consistent state `plastic`.
    pub fn fibre_plastic_strains(&self, strains: &Vector3<f64>, plastic: &[f64]) -> Vec<f64> {
        let size = self.material.state_size();
        self.fibres
            .iter()
            .enumerate()
            .map(|(k, fibre)| {
                let strain = Vector3::new(1.0, fibre.z, -fibre.y).dot(strains);
                let (stress, _) = self
                    .material
                    .stress_and_energy(strain, &plastic[k * size..(k + 1) * size]);
                strain - stress / self.material.youngs_modulus
            })
            .collect()
    }

    /// The largest plastic strain |ε − σ/E| over the wall's fibres at the strains (ε₀, κ₂, κ₃) and the plastic
    /// state `plastic` (read, not advanced).
    pub fn largest_plastic_strain(&self, strains: &Vector3<f64>, plastic: &[f64]) -> f64 {
        self.fibre_plastic_strains(strains, plastic)
            .iter()
            .map(|p| p.abs())
            .fold(0.0, f64::max)
    }

    /// How many plastic strains the section's state holds.
    pub fn state_size(&self) -> usize {
        self.fibres.len() * self.material.state_size()
    }

    /// The resultants and their tangent at the strains (ε₀, κ₂, κ₃), from the plastic state `plastic` at the
    /// step's start; the state after the step goes to `plastic_end`.
    pub fn respond(
        &self,
        strains: &Vector3<f64>,
        plastic: &[f64],
        plastic_end: &mut [f64],
    ) -> SectionResponse {
        let size = self.material.state_size();
        let mut response = SectionResponse {
            resultants: Vector3::zeros(),
            tangent: Matrix3::zeros(),
            free_energy: 0.0,
            dissipated: 0.0,
        };
        for (k, fibre) in self.fibres.iter().enumerate() {
            let g = Vector3::new(1.0, fibre.z, -fibre.y);
            let strain = g.dot(strains);
            let state = k * size..(k + 1) * size;
            let fibre_response =
                self.material
                    .respond(strain, &plastic[state.clone()], &mut plastic_end[state]);
            response.resultants += fibre.area * fibre_response.stress * g;
            response.tangent += (fibre.area * fibre_response.tangent) * g * g.transpose();
            response.free_energy += fibre.area * fibre_response.free_energy;
            response.dissipated += fibre.area * fibre_response.dissipated;
        }
        response
    }

    /// The bending moments m₂ (N·m) along a path of curvatures κ₂ (1/m) at the axial strain `axial_strain`,
    /// from rest: history-dependent, so that unloading shows the hysteresis.
    pub fn moment_curvature(&self, curvatures: &[f64], axial_strain: f64) -> Vec<f64> {
        let mut plastic = vec![0.0; self.state_size()];
        let mut end = plastic.clone();
        curvatures
            .iter()
            .map(|&kappa| {
                let response =
                    self.respond(&Vector3::new(axial_strain, kappa, 0.0), &plastic, &mut end);
                plastic.copy_from_slice(&end);
                response.resultants.y
            })
            .collect()
    }
}

/// Adds the wall's resultants (N, m₂, m₃) and their tangent by (ε₀, κ₂, κ₃) to a section law's force, moment
/// and 6×6 stiffness: (ε₀, κ₂, κ₃) are the 0th, 4th and 5th of (Γ, K).
fn add_wall(
    force: &mut Vector3<f64>,
    moment: &mut Vector3<f64>,
    stiffness: &mut Matrix6<f64>,
    resultants: &Vector3<f64>,
    tangent: &Matrix3<f64>,
) {
    force.x += resultants.x;
    moment.y += resultants.y;
    moment.z += resultants.z;
    let places = [0, 4, 5];
    for (i, &row) in places.iter().enumerate() {
        for (j, &column) in places.iter().enumerate() {
            stiffness[(row, column)] += tangent[(i, j)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A thin tube: D = 0.4 m, t = 2 mm, E = 200 GPa, f_y = 400 MPa; its yield curvature and moment as the
    /// thin-tube theory takes them, at the wall's middle a = (D − t)/2: κ_y = f_y/(E a), M_y = EI κ_y; and
    /// its plastic moment.
    fn thin_tube() -> (FibreSection, f64, f64, f64) {
        let (d, t, e, fy) = (0.4, 0.002, 200e9, 400e6);
        let tube =
            FibreSection::pipe(d, t, Material::elastic_perfectly_plastic(e, fy).unwrap()).unwrap();
        let inertia = std::f64::consts::PI / 64.0 * (d.powi(4) - (d - 2.0 * t).powi(4));
        let kappa_y = fy / (e * 0.5 * (d - t));
        let moment_y = e * inertia * kappa_y;
        (tube, kappa_y, moment_y, fy * (d - t).powi(2) * t)
    }

    #[test]
    fn an_elastic_section_is_integrated_exactly() {
        let (d, t, e) = (0.6, 0.03, 207e9);
        let section = FibreSection::pipe(d, t, Material::elastic(e).unwrap()).unwrap();
        let area = std::f64::consts::PI / 4.0 * (d * d - (d - 2.0 * t).powi(2));
        let inertia = std::f64::consts::PI / 64.0 * (d.powi(4) - (d - 2.0 * t).powi(4));
        let response = section.respond(&Vector3::new(1e-4, 2e-3, -1e-3), &[], &mut []);
        let expected = Vector3::new(e * area * 1e-4, e * inertia * 2e-3, -e * inertia * 1e-3);
        assert!((response.resultants - expected).norm() < 1e-12 * expected.norm());
        assert!(
            (response.tangent
                - Matrix3::from_diagonal(&Vector3::new(e * area, e * inertia, e * inertia)))
            .norm()
                < 1e-9 * e * area
        );
    }

    /// The thin tube's closed forms: M/M_y = (4/π)[φ(β/2 − sin 2β/4) + cos β], sin β = 1/φ, = 1.2647 at
    /// φ = 5; M → M_p = f_y (D − t)² t; unloading from 5 κ_y leaves 5 − 1.2647 = 3.7353 κ_y.
    #[test]
    fn a_thin_tube_yields_as_the_closed_form() {
        let (tube, kappa_y, moment_y, moment_p) = thin_tube();
        let ratio = |phi: f64| {
            let beta = (1.0 / phi).asin();
            4.0 / std::f64::consts::PI
                * (phi * (0.5 * beta - 0.25 * (2.0 * beta).sin()) + beta.cos())
        };
        assert!((ratio(5.0) - 1.2647).abs() < 1e-4);
        let path: Vec<f64> = (0..=100)
            .map(|k| 5.0 * kappa_y * k as f64 / 100.0)
            .collect();
        let moments = tube.moment_curvature(&path, 0.0);
        let at_five = moments[100] / moment_y;
        println!(
            "M/M_y at 5 κ_y: {at_five:.6} (closed form {:.6})",
            ratio(5.0)
        );
        assert!((at_five - ratio(5.0)).abs() < 1e-3 * ratio(5.0));
        // Far beyond yield the moment tends to the plastic moment (the quadrature's error of 4e-4 aside).
        let far = tube.moment_curvature(&[0.0, 10.0 * kappa_y, 100.0 * kappa_y], 0.0);
        println!("M/M_p at 100 κ_y: {:.6}", far[2] / moment_p);
        assert!(
            (far[2] / moment_p - 1.0).abs() < 1e-3,
            "{} vs {moment_p}",
            far[2]
        );
        assert!(far[1] < far[2]);
        // Unloading to zero moment, elastically with EI: the residual curvature.
        let mut unload = path.clone();
        unload.extend((1..=200).map(|k| 5.0 * kappa_y - 2.0 * kappa_y * k as f64 / 200.0));
        let moments = tube.moment_curvature(&unload, 0.0);
        let zero = (101..unload.len())
            .find(|&i| moments[i] <= 0.0)
            .expect("the moment crosses zero");
        let (a, b) = (zero - 1, zero);
        let residual = unload[a] + (unload[b] - unload[a]) * moments[a] / (moments[a] - moments[b]);
        println!("residual curvature {:.6} κ_y", residual / kappa_y);
        assert!((residual / kappa_y - (5.0 - at_five)).abs() < 1e-9 * 5.0);
        assert!((residual / kappa_y - 3.7353).abs() < 4e-3);
    }

    /// A cycle of bending stores nothing and dissipates the area of its moment–curvature loop.
    #[test]
    fn a_bending_cycle_dissipates_its_loop_area() {
        let (tube, kappa_y, _, _) = thin_tube();
        let steps = 2000;
        let path: Vec<f64> = (0..=2 * steps)
            .map(|k| 3.0 * kappa_y * (2.0 * std::f64::consts::PI * k as f64 / steps as f64).sin())
            .collect();
        let mut plastic = vec![0.0; tube.state_size()];
        let mut end = plastic.clone();
        let (mut area, mut dissipated, mut previous) = (0.0, 0.0, 0.0);
        let mut free = Vec::new();
        for (k, pair) in path.windows(2).enumerate() {
            let response = tube.respond(&Vector3::new(0.0, pair[1], 0.0), &plastic, &mut end);
            plastic.copy_from_slice(&end);
            if k >= steps {
                area += 0.5 * (previous + response.resultants.y) * (pair[1] - pair[0]);
                dissipated += response.dissipated;
            }
            previous = response.resultants.y;
            free.push(response.free_energy);
        }
        println!("loop area {area:.6e} J/m, dissipated {dissipated:.6e} J/m");
        assert!((free[2 * steps - 1] - free[steps - 1]).abs() < 1e-9 * dissipated);
        assert!((area - dissipated).abs() < 2e-3 * dissipated);
    }
}
