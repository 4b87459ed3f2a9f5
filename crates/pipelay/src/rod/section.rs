//! Cross-section properties: stiffness (eqs. 29–30), mass, inertia (19) and hydrodynamic coefficients.
use crate::error::{finite, non_negative, positive, Result};
use crate::rod::fibre_section::FibreSection;
use crate::rod::material::Material;
use nalgebra::{Matrix3, Vector3};

/// A cross-section, constant along a segment of the line. Axis 1 is the rod axis (t1); 2 and 3 the principal axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// C_T = diag(EA, GA2, GA3) (N).
    pub translational_stiffness: Vector3<f64>,
    /// C_R = diag(GJ, EI2, EI3) (N·m²).
    pub rotational_stiffness: Vector3<f64>,
    /// Mass per unit length, contents included (kg/m).
    pub mass: f64,
    /// Rotational inertia per unit length J_ρ = diag(J1, J2, J3) (kg·m).
    pub inertia: Vector3<f64>,
    /// Outer diameter of the structural tube (the steel's, m): the strain's outer fibre and the design checks
    /// refer to it.
    pub outer_diameter: f64,
    /// Diameter of the outer surface, over any coatings (m): drag, added mass, the default buoyancy area, the
    /// seabed's contact width and the rollers refer to it. The outer diameter for a section without coatings.
    pub hydrodynamic_diameter: f64,
    /// Buoyancy area per unit length (m²).
    pub displaced_area: f64,
    /// Morison drag coefficients (axial, normal).
    pub drag: [f64; 2],
    /// Added-mass coefficients (axial, normal).
    pub added_mass: [f64; 2],
    /// Rotational damping D_R = diag (N·m·s per m).
    pub rotational_damping: Vector3<f64>,
    /// The pipe's wall, for sections built from it ([`Section::pipe`]): what design checks need.
    pub wall: Option<PipeWall>,
    /// A cable's section ([`Section::cable`]): axial stiffness only, its elements bars ([`crate::rod::cable`]).
    pub cable: bool,
    /// A cable's axial internal damping B (N·s): a taut cable's damping force B ε̇ along its chord (MoorDyn's
    /// BA); zero for rods.
    pub axial_damping: f64,
    /// Structural (Kelvin–Voigt) damping of the section's strains; `None`: none.
    pub structural_damping: Option<StructuralDamping>,
    /// A laydown head's section ([`Section::head`]): the surface's diameter at each element's second node, to
    /// which it tapers linearly from `hydrodynamic_diameter` at its first (m; the rollers see the taper);
    /// `None`: a cylinder.
    pub nose_diameter: Option<f64>,
}

/// Structural damping of a section, given as fractions of critical damping ζ (-) at the circular frequency
/// ω₀ = 2π/T₀ of a stated period T₀ (s), as MoorDyn's `BA/-zeta` and OrcaFlex's target damping are given.
///
/// It is Kelvin–Voigt (stiffness-proportional) damping: the section's resultants gain B_T Γ̇ and B_R K̇ with
/// B_T = β_a C_T (the shear strains with the axial ratio) and B_R = diag(β_t GJ, β_b EI2, β_b EI3),
/// β = 2ζ/ω₀ = ζT₀/π (s). A mode of circular frequency ω that strains the section one way is then damped at
/// the ratio βω/2 = ζ ω/ω₀: ζ at the stated period, more at shorter periods (the stiff axial modes), less at
/// longer ones. All its work is dissipated and booked in the energy ledger.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StructuralDamping {
    /// Fraction of critical damping of the axial (and shear) strains at the period (-).
    pub axial: f64,
    /// Fraction of critical damping of the bending curvatures at the period (-).
    pub bending: f64,
    /// Fraction of critical damping of the torsional curvature at the period (-).
    pub torsion: f64,
    /// The period T₀ at which the fractions hold (s).
    pub period: f64,
}

impl StructuralDamping {
    /// Damping of `axial`, `bending` and `torsion` fractions of critical (each finite, ≥ 0) at the period
    /// `period` (s, > 0).
    pub fn new(axial: f64, bending: f64, torsion: f64, period: f64) -> Result<Self> {
        non_negative("axial", axial, "(fraction of critical)")?;
        non_negative("bending", bending, "(fraction of critical)")?;
        non_negative("torsion", torsion, "(fraction of critical)")?;
        positive("period", period, "s")?;
        Ok(StructuralDamping {
            axial,
            bending,
            torsion,
            period,
        })
    }

    /// The stiffness-proportional coefficient β = ζT₀/π (s) of a fraction ζ of critical at the period.
    fn coefficient(&self, fraction: f64) -> f64 {
        fraction * self.period / std::f64::consts::PI
    }

    /// The damping matrices (B_T, B_R) of a section of stiffnesses `c_t`, `c_r` (diagonal): resultants
    /// B_T Γ̇ (N) and B_R K̇ (N·m).
    pub fn matrices(&self, c_t: &Matrix3<f64>, c_r: &Matrix3<f64>) -> (Matrix3<f64>, Matrix3<f64>) {
        let rotational = Vector3::new(
            self.coefficient(self.torsion),
            self.coefficient(self.bending),
            self.coefficient(self.bending),
        );
        (
            self.coefficient(self.axial) * c_t,
            Matrix3::from_diagonal(&rotational) * c_r,
        )
    }
}

/// The wall of a pipe section.
#[derive(Debug, Clone, PartialEq)]
pub struct PipeWall {
    /// Wall thickness (m).
    pub thickness: f64,
    /// Young's modulus (Pa).
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    /// Density of the contents (kg/m³).
    pub contents_density: f64,
    /// The steel's grade (e.g. "X65"), for the design checks; the engine does not read it.
    pub grade: Option<String>,
    /// The steel's stress–strain law beyond yield ([`crate::rod::material`]); None: linear elastic. Its
    /// Young's modulus is the wall's.
    pub material: Option<Material>,
    /// The external coatings, from the steel outwards, and the internal lining.
    pub coatings: Vec<Coating>,
    pub lining: Option<Coating>,
}

/// A layer of a pipe outside its steel wall (a coating: anti-corrosion, concrete weight coat, insulation) or
/// inside it (a lining).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coating {
    /// Layer thickness (m).
    pub thickness: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Young's modulus the layer adds to the axial and bending stiffness (Pa): 0 (the usual choice for
    /// concrete, whose cracked coat carries little) adds none.
    pub youngs_modulus: f64,
}

impl Coating {
    /// A layer of `thickness` (m) and `density` (kg/m³) that adds no stiffness.
    pub fn new(thickness: f64, density: f64) -> Self {
        Coating {
            thickness,
            density,
            youngs_modulus: 0.0,
        }
    }

    /// Refuses a layer that is not a layer: thickness ≤ 0, or a negative or non-finite density or modulus;
    /// the errors name `prefix` + the field.
    pub fn check(&self, prefix: &str) -> Result<()> {
        positive(&format!("{prefix}thickness"), self.thickness, "m")?;
        non_negative(&format!("{prefix}density"), self.density, "kg/m³")?;
        non_negative(
            &format!("{prefix}youngs_modulus"),
            self.youngs_modulus,
            "Pa",
        )?;
        Ok(())
    }
}

/// An annulus between diameters `inner` and `outer` (m): its area A = π/4(D² − d²) and second moment of area
/// I = π/64(D⁴ − d⁴).
fn annulus(inner: f64, outer: f64) -> (f64, f64) {
    let pi = std::f64::consts::PI;
    (
        pi / 4.0 * (outer * outer - inner * inner),
        pi / 64.0 * (outer.powi(4) - inner.powi(4)),
    )
}

/// Hydrodynamic and inertial data of a section that are optional when building one.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionExtras {
    pub inertia: [f64; 3],
    pub outer_diameter: f64,
    pub displaced_area: Option<f64>,
    pub drag: [f64; 2],
    pub added_mass: [f64; 2],
    pub rotational_damping: [f64; 3],
}

impl Default for SectionExtras {
    fn default() -> Self {
        SectionExtras {
            inertia: [0.0; 3],
            outer_diameter: 0.0,
            displaced_area: None,
            drag: [0.0; 2],
            added_mass: [0.0; 2],
            rotational_damping: [0.0; 3],
        }
    }
}

/// Checks the Morison drag and added-mass coefficients (axial, normal): each finite and ≥ 0.
fn check_coefficients(drag: &[f64; 2], added_mass: &[f64; 2]) -> Result<()> {
    for &c in drag {
        non_negative("drag", c, "(dimensionless)")?;
    }
    for &c in added_mass {
        non_negative("added_mass", c, "(dimensionless)")?;
    }
    Ok(())
}

impl Section {
    /// A section from its stiffnesses: `ga` and `ei` per principal axis (2, 3).
    pub fn new(
        ea: f64,
        ga: [f64; 2],
        gj: f64,
        ei: [f64; 2],
        mass: f64,
        extras: SectionExtras,
    ) -> Result<Self> {
        positive("EA", ea, "N")?;
        positive("GA", ga[0], "N")?;
        positive("GA", ga[1], "N")?;
        positive("GJ", gj, "N·m²")?;
        positive("EI", ei[0], "N·m²")?;
        positive("EI", ei[1], "N·m²")?;
        positive("mass", mass, "kg/m")?;
        for &j in &extras.inertia {
            non_negative("inertia", j, "kg·m")?;
        }
        non_negative("outer_diameter", extras.outer_diameter, "m")?;
        let displaced_area = match extras.displaced_area {
            Some(a) => non_negative("displaced_area", a, "m²")?,
            None => std::f64::consts::FRAC_PI_4 * extras.outer_diameter.powi(2),
        };
        check_coefficients(&extras.drag, &extras.added_mass)?;
        for &c in &extras.rotational_damping {
            non_negative("rotational_damping", c, "N·m·s/m")?;
        }
        Ok(Section {
            translational_stiffness: Vector3::new(ea, ga[0], ga[1]),
            rotational_stiffness: Vector3::new(gj, ei[0], ei[1]),
            mass,
            inertia: Vector3::from(extras.inertia),
            outer_diameter: extras.outer_diameter,
            hydrodynamic_diameter: extras.outer_diameter,
            displaced_area,
            drag: extras.drag,
            added_mass: extras.added_mass,
            rotational_damping: Vector3::from(extras.rotational_damping),
            wall: None,
            cable: false,
            axial_damping: 0.0,
            structural_damping: None,
            nose_diameter: None,
        })
    }

    /// A cable (wire rope, chain, umbilical without bending stiffness) of nominal `diameter` (m), `mass`
    /// (kg/m) and axial stiffness `ea` (N): it carries tension only. The buoyancy area is π/4 d², drag and added
    /// mass refer to d.
    pub fn cable(
        diameter: f64,
        mass: f64,
        ea: f64,
        drag: [f64; 2],
        added_mass: [f64; 2],
    ) -> Result<Self> {
        positive("diameter", diameter, "m")?;
        positive("EA", ea, "N")?;
        positive("mass", mass, "kg/m")?;
        check_coefficients(&drag, &added_mass)?;
        Ok(Section {
            translational_stiffness: Vector3::new(ea, 0.0, 0.0),
            rotational_stiffness: Vector3::zeros(),
            mass,
            inertia: Vector3::zeros(),
            outer_diameter: diameter,
            hydrodynamic_diameter: diameter,
            displaced_area: std::f64::consts::FRAC_PI_4 * diameter * diameter,
            drag,
            added_mass,
            rotational_damping: Vector3::zeros(),
            wall: None,
            cable: true,
            axial_damping: 0.0,
            structural_damping: None,
            nose_diameter: None,
        })
    }

    /// A laydown head of `length` (m) as one element of a line whose pipe has the section `pipe`: the pipe's
    /// stiffness (over a few metres the head bends and stretches as little as a rigid body), the head's `mass`
    /// (kg) and displaced `volume` (m³) spread over its length, its surface of `diameter` (m) at the pipe's
    /// end tapering to `nose_diameter` (m) at the wire's padeye, its drag area C_d·A (m²) as a normal drag
    /// coefficient on that diameter and its added-mass coefficient on its volume as the section's (both
    /// ways). Not a pipe wall: design checks skip it.
    #[allow(clippy::too_many_arguments)]
    pub fn head(
        pipe: &Section,
        length: f64,
        diameter: f64,
        nose_diameter: f64,
        mass: f64,
        volume: f64,
        drag_area: f64,
        added_mass: f64,
    ) -> Result<Self> {
        positive("head length", length, "m")?;
        positive("head diameter", diameter, "m")?;
        positive("mass", mass, "kg")?;
        let area = std::f64::consts::FRAC_PI_4 * diameter * diameter;
        let mass_per_length = mass / length;
        let added = added_mass * volume / (area * length);
        Ok(Section {
            translational_stiffness: pipe.translational_stiffness,
            rotational_stiffness: pipe.rotational_stiffness,
            mass: mass_per_length,
            inertia: pipe.inertia * (mass_per_length / pipe.mass.max(f64::MIN_POSITIVE)),
            outer_diameter: pipe.outer_diameter,
            hydrodynamic_diameter: diameter,
            displaced_area: volume / length,
            drag: [0.0, drag_area / (diameter * length)],
            added_mass: [added, added],
            rotational_damping: pipe.rotational_damping,
            wall: None,
            cable: false,
            axial_damping: 0.0,
            structural_damping: None,
            nose_diameter: Some(nose_diameter),
        })
    }

    /// This cable's section with axial internal damping `damping` B (N·s, ≥ 0; force B ε̇ when taut).
    pub fn with_axial_damping(self, damping: f64) -> Result<Self> {
        crate::error::non_negative("damping", damping, "N·s")?;
        Ok(Section {
            axial_damping: damping,
            ..self
        })
    }

    /// This section with structural damping `damping` (a cable's has no bending or torsion to damp: its
    /// axial damping adds β_a EA to its B).
    pub fn with_structural_damping(self, damping: StructuralDamping) -> Result<Self> {
        if self.cable && damping.bending.max(damping.torsion) > 0.0 {
            return Err(crate::error::Error::input(
                "structural_damping.bending, torsion",
                format!("{}, {}", damping.bending, damping.torsion),
                "must be 0 on a cable (it has no bending or torsion to damp)",
            ));
        }
        Ok(Section {
            structural_damping: Some(damping),
            ..self
        })
    }

    /// A cable's axial internal damping B (N·s) with its structural damping's: B + β_a EA; 0 for a rod (its
    /// structural damping acts through [`StructuralDamping::matrices`]).
    pub fn cable_axial_damping(&self) -> f64 {
        if !self.cable {
            return 0.0;
        }
        self.axial_damping
            + self.structural_damping.map_or(0.0, |d| {
                d.coefficient(d.axial) * self.translational_stiffness.x
            })
    }

    /// A thin-or-thick-walled steel-like pipe from its geometry and material.
    ///
    /// A = π/4(D² − d²), I = π/64(D⁴ − d⁴), J = 2I, G = E/(2(1+ν)); shear area factor 1/2 (thin tube).
    /// Mass includes the contents; rotational inertia J_ρ = ρ·diag(J, I, I).
    #[allow(clippy::too_many_arguments)]
    pub fn pipe(
        outer_diameter: f64,
        wall_thickness: f64,
        density: f64,
        youngs_modulus: f64,
        poisson_ratio: f64,
        contents_density: f64,
        drag: [f64; 2],
        added_mass: [f64; 2],
    ) -> Result<Self> {
        Self::coated_pipe(
            outer_diameter,
            wall_thickness,
            density,
            youngs_modulus,
            poisson_ratio,
            contents_density,
            &[],
            None,
            drag,
            added_mass,
        )
    }

    /// A pipe as [`Section::pipe`] with external `coatings` (listed from the steel outwards) and an internal
    /// `lining`. Each layer adds its mass ρA and rotational inertia ρ·diag(J, I, I), and with a Young's modulus
    /// E_c its stiffness E_c A and E_c I (shear and torsion stay the steel's); the contents fill the lining's
    /// bore. The coatings' outer surface is the hydrodynamic diameter D_h, and the buoyancy area π/4 D_h².
    #[allow(clippy::too_many_arguments)]
    pub fn coated_pipe(
        outer_diameter: f64,
        wall_thickness: f64,
        density: f64,
        youngs_modulus: f64,
        poisson_ratio: f64,
        contents_density: f64,
        coatings: &[Coating],
        lining: Option<Coating>,
        drag: [f64; 2],
        added_mass: [f64; 2],
    ) -> Result<Self> {
        positive("outer_diameter", outer_diameter, "m")?;
        positive("wall_thickness", wall_thickness, "m")?;
        if wall_thickness > 0.5 * outer_diameter {
            return Err(crate::error::Error::input(
                "wall_thickness",
                wall_thickness,
                format!("must be <= outer_diameter/2 = {} m", 0.5 * outer_diameter),
            ));
        }
        positive("density", density, "kg/m³")?;
        positive("youngs_modulus", youngs_modulus, "Pa")?;
        finite("poisson_ratio", &[poisson_ratio])?;
        if !(poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(crate::error::Error::input(
                "poisson_ratio",
                poisson_ratio,
                "must lie in (-1, 0.5)",
            ));
        }
        non_negative("contents_density", contents_density, "kg/m³")?;
        for coating in coatings {
            coating.check("coatings ")?;
        }
        if let Some(lining) = &lining {
            lining.check("lining ")?;
        }
        let d_o = outer_diameter;
        let d_i = outer_diameter - 2.0 * wall_thickness;
        let bore = match lining {
            Some(lining) if 2.0 * lining.thickness >= d_i => {
                return Err(crate::error::Error::input(
                    "lining thickness",
                    lining.thickness,
                    format!("must be < the steel's inner radius {} m", 0.5 * d_i),
                ))
            }
            Some(lining) => d_i - 2.0 * lining.thickness,
            None => d_i,
        };
        let pi = std::f64::consts::PI;
        let (area, second_moment) = annulus(d_i, d_o);
        let shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
        let shear_area = 0.5 * area;
        let mut mass = density * area + contents_density * pi / 4.0 * bore * bore;
        let mut inertia = density * second_moment;
        let (mut axial, mut bending) = (youngs_modulus * area, youngs_modulus * second_moment);
        // The layers from the bore outwards: the lining, then the coatings.
        let mut layers = Vec::with_capacity(coatings.len() + 1);
        layers.extend(lining.map(|lining| (bore, d_i, lining)));
        let mut inner = d_o;
        for coating in coatings {
            let outer = inner + 2.0 * coating.thickness;
            layers.push((inner, outer, *coating));
            inner = outer;
        }
        for (inside, outside, layer) in layers {
            let (layer_area, layer_moment) = annulus(inside, outside);
            mass += layer.density * layer_area;
            inertia += layer.density * layer_moment;
            axial += layer.youngs_modulus * layer_area;
            bending += layer.youngs_modulus * layer_moment;
        }
        let extras = SectionExtras {
            inertia: [2.0 * inertia, inertia, inertia],
            outer_diameter: inner,
            displaced_area: None,
            drag,
            added_mass,
            rotational_damping: [0.0; 3],
        };
        let mut section = Section::new(
            axial,
            [shear_modulus * shear_area; 2],
            shear_modulus * 2.0 * second_moment,
            [bending; 2],
            mass,
            extras,
        )?;
        section.outer_diameter = d_o;
        section.wall = Some(PipeWall {
            thickness: wall_thickness,
            youngs_modulus,
            poisson_ratio,
            contents_density,
            grade: None,
            coatings: coatings.to_vec(),
            lining,
            material: None,
        });
        Ok(section)
    }

    /// The pipe's steel wall as fibres of its material ([`crate::rod::fibre_section`]); None for a section
    /// without a wall.
    pub fn fibre_section(&self) -> Option<Result<FibreSection>> {
        let wall = self.wall.as_ref()?;
        let material = match &wall.material {
            Some(material) => material.clone(),
            None => match Material::elastic(wall.youngs_modulus) {
                Ok(material) => material,
                Err(error) => return Some(Err(error)),
            },
        };
        let d = self.outer_diameter;
        let inner = d - 2.0 * wall.thickness;
        let area = std::f64::consts::PI / 4.0 * (d * d - inner * inner);
        let inertia = std::f64::consts::PI / 64.0 * (d.powi(4) - inner.powi(4));
        let e = material.youngs_modulus;
        Some(
            FibreSection::pipe(d, wall.thickness, material).map(|mut fibres| {
                fibres.shear = [
                    self.translational_stiffness.y,
                    self.translational_stiffness.z,
                ];
                fibres.torsion = self.rotational_stiffness.x;
                fibres.extra_axial = (self.translational_stiffness.x - e * area).max(0.0);
                fibres.extra_bending = (self.rotational_stiffness.y - e * inertia).max(0.0);
                fibres
            }),
        )
    }

    /// Whether the section's wall can yield (a pipe with a material beyond elastic).
    pub fn yields(&self) -> bool {
        self.wall
            .as_ref()
            .and_then(|w| w.material.as_ref())
            .is_some_and(|m| !m.is_elastic())
    }

    /// Largest longitudinal strain of a section carrying material force and moment `forces`
    /// ([N1, N2, N3, M1, M2, M3]): axial N1/EA plus bending at the outer fibre, (d_o/2)|(M2/EI2, M3/EI3)|
    /// (linear elastic; the tensile side in bending).
    pub fn strain(&self, forces: &nalgebra::Vector6<f64>) -> f64 {
        let axial = forces[0] / self.translational_stiffness.x;
        if self.cable {
            return axial;
        }
        let curvature = nalgebra::Vector2::new(
            forces[4] / self.rotational_stiffness.y,
            forces[5] / self.rotational_stiffness.z,
        );
        axial + 0.5 * self.outer_diameter * curvature.norm()
    }

    /// The bending curvature a section bent to `curvature` (K − K₀, 1/m) under the moment `moment` (N·m) keeps
    /// when unloaded elastically: its residual curvature |(κ₂ − m₂/EI₂, κ₃ − m₃/EI₃)| (1/m).
    pub fn residual_curvature(&self, curvature: &Vector3<f64>, moment: &Vector3<f64>) -> f64 {
        let bending = self.rotational_stiffness;
        nalgebra::Vector2::new(
            curvature.y - moment.y / bending.y,
            curvature.z - moment.z / bending.z,
        )
        .norm()
    }

    /// C_T as a matrix.
    pub fn c_t(&self) -> Matrix3<f64> {
        Matrix3::from_diagonal(&self.translational_stiffness)
    }

    /// C_R as a matrix.
    pub fn c_r(&self) -> Matrix3<f64> {
        Matrix3::from_diagonal(&self.rotational_stiffness)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Structural damping's matrices: B_T = β_a C_T, B_R = diag(β_t GJ, β_b EI2, β_b EI3) with β = ζT₀/π, so a
    /// one-degree-of-freedom mode k of circular frequency ω = 2π/T₀ is damped at βω/2 = ζ; a cable adds β_a EA
    /// to its B and refuses bending or torsional damping; negative ratios and a zero period are refused.
    #[test]
    fn structural_damping_is_stiffness_proportional_at_the_stated_period() {
        let pipe = Section::pipe(0.6, 0.025, 7850.0, 207e9, 0.3, 0.0, [0.0, 1.0], [0.0, 1.0])
            .expect("pipe");
        let damping = StructuralDamping::new(0.02, 0.05, 0.01, 0.5).expect("damping");
        let (b_t, b_r) = damping.matrices(&pipe.c_t(), &pipe.c_r());
        let beta = |zeta: f64| zeta * 0.5 / PI;
        let (c_t, c_r) = (pipe.c_t(), pipe.c_r());
        for i in 0..3 {
            assert!((b_t[(i, i)] - beta(0.02) * c_t[(i, i)]).abs() <= 1e-12 * b_t[(i, i)]);
        }
        assert!((b_r[(0, 0)] - beta(0.01) * c_r[(0, 0)]).abs() <= 1e-12 * b_r[(0, 0)]);
        assert!((b_r[(1, 1)] - beta(0.05) * c_r[(1, 1)]).abs() <= 1e-12 * b_r[(1, 1)]);
        assert!((b_r[(2, 2)] - beta(0.05) * c_r[(2, 2)]).abs() <= 1e-12 * b_r[(2, 2)]);
        assert_eq!(b_t[(0, 1)], 0.0);
        // The ratio at the stated period: β ω / 2 with ω = 2π/T₀.
        assert!((beta(0.02) * (2.0 * PI / 0.5) / 2.0 - 0.02).abs() < 1e-15);
        let cable = Section::cable(0.09, 40.0, 4e8, [0.0, 1.2], [0.0, 1.0])
            .and_then(|c| c.with_axial_damping(1e3))
            .expect("cable");
        let axial = StructuralDamping::new(0.1, 0.0, 0.0, 0.5).expect("axial");
        let damped = cable
            .clone()
            .with_structural_damping(axial)
            .expect("damped");
        assert!((damped.cable_axial_damping() - (1e3 + 0.1 * 0.5 / PI * 4e8)).abs() < 1e-6);
        assert!(cable.with_structural_damping(damping).is_err());
        assert!(StructuralDamping::new(-0.01, 0.0, 0.0, 1.0).is_err());
        assert!(StructuralDamping::new(0.01, 0.0, 0.0, 0.0).is_err());
        assert!(StructuralDamping::new(f64::NAN, 0.0, 0.0, 1.0).is_err());
        let damped_pipe = pipe.with_structural_damping(damping).expect("damped pipe");
        assert_eq!(damped_pipe.cable_axial_damping(), 0.0);
    }

    /// A 24-inch pipe with 3 mm of 3LPE and 60 mm of concrete, lined and flooded: mass, diameters, buoyancy
    /// area and inertia against the layers summed by hand; the steel alone carries the stiffness.
    #[test]
    fn coatings_and_lining_add_mass_and_diameter_but_no_stiffness() {
        let (d, t) = (0.6096, 0.0206);
        let (pe, concrete) = (Coating::new(0.003, 940.0), Coating::new(0.06, 3040.0));
        let lining = Coating::new(0.005, 1100.0);
        let bare =
            Section::pipe(d, t, 7850.0, 207e9, 0.3, 0.0, [0.0, 1.0], [0.0, 1.0]).expect("pipe");
        let coated = Section::coated_pipe(
            d,
            t,
            7850.0,
            207e9,
            0.3,
            1025.0,
            &[pe, concrete],
            Some(lining),
            [0.0, 1.0],
            [0.0, 1.0],
        )
        .expect("coated pipe");
        let ring = |inner: f64, outer: f64| PI / 4.0 * (outer * outer - inner * inner);
        let moment = |inner: f64, outer: f64| PI / 64.0 * (outer.powi(4) - inner.powi(4));
        let (d_i, d_pe) = (d - 2.0 * t, d + 0.006);
        let (d_h, bore) = (d_pe + 0.12, d - 2.0 * t - 0.01);
        let mass = 7850.0 * ring(d_i, d)
            + 940.0 * ring(d, d_pe)
            + 3040.0 * ring(d_pe, d_h)
            + 1100.0 * ring(bore, d_i)
            + 1025.0 * PI / 4.0 * bore * bore;
        assert!(
            (coated.mass - mass).abs() < 1e-9 * mass,
            "{} vs {mass}",
            coated.mass
        );
        assert_eq!(coated.outer_diameter, d);
        assert!((coated.hydrodynamic_diameter - d_h).abs() < 1e-15);
        assert!((coated.displaced_area - PI / 4.0 * d_h * d_h).abs() < 1e-15);
        let inertia = 7850.0 * moment(d_i, d)
            + 940.0 * moment(d, d_pe)
            + 3040.0 * moment(d_pe, d_h)
            + 1100.0 * moment(bore, d_i);
        assert!((coated.inertia.y - inertia).abs() < 1e-9 * inertia);
        assert!((coated.inertia.x - 2.0 * inertia).abs() < 1e-9 * inertia);
        assert_eq!(coated.translational_stiffness, bare.translational_stiffness);
        assert_eq!(coated.rotational_stiffness, bare.rotational_stiffness);
        let wall = coated.wall.expect("wall");
        assert_eq!((wall.thickness, wall.contents_density), (t, 1025.0));
        assert_eq!(
            (wall.coatings, wall.lining),
            (vec![pe, concrete], Some(lining))
        );
    }

    /// A coating given a Young's modulus adds E_c A and E_c I of its annulus to EA and EI, not to GJ.
    #[test]
    fn a_stiff_coating_adds_its_stiffness() {
        let (d, t) = (0.5, 0.02);
        let stiff = Coating {
            youngs_modulus: 30e9,
            ..Coating::new(0.05, 2400.0)
        };
        let bare = Section::pipe(d, t, 7850.0, 207e9, 0.3, 0.0, [0.0; 2], [0.0; 2]).expect("pipe");
        let coated = Section::coated_pipe(
            d,
            t,
            7850.0,
            207e9,
            0.3,
            0.0,
            &[stiff],
            None,
            [0.0; 2],
            [0.0; 2],
        )
        .expect("pipe");
        let (area, moment) = (
            PI / 4.0 * (0.6_f64.powi(2) - d * d),
            PI / 64.0 * (0.6_f64.powi(4) - d.powi(4)),
        );
        let ea = bare.translational_stiffness.x + 30e9 * area;
        let ei = bare.rotational_stiffness.y + 30e9 * moment;
        assert!((coated.translational_stiffness.x - ea).abs() < 1e-9 * ea);
        assert!((coated.rotational_stiffness.z - ei).abs() < 1e-9 * ei);
        assert_eq!(coated.rotational_stiffness.x, bare.rotational_stiffness.x);
    }

    /// A pipe without layers is the coated pipe without layers, to the bit; bad layers name themselves.
    #[test]
    fn bare_pipes_are_unchanged_and_bad_layers_are_input_errors() {
        let bare = Section::pipe(
            0.6,
            0.015,
            7850.0,
            207e9,
            0.3,
            1025.0,
            [0.0, 1.2],
            [0.0, 1.0],
        )
        .expect("pipe");
        assert_eq!(bare.hydrodynamic_diameter, bare.outer_diameter);
        let coated = |coatings: &[Coating], lining: Option<Coating>| {
            Section::coated_pipe(
                0.6,
                0.015,
                7850.0,
                207e9,
                0.3,
                1025.0,
                coatings,
                lining,
                [0.0, 1.2],
                [0.0, 1.0],
            )
        };
        assert_eq!(coated(&[], None).expect("pipe"), bare);
        for (coatings, lining, named) in [
            (vec![Coating::new(0.0, 3040.0)], None, "coatings thickness"),
            (
                vec![Coating::new(-0.01, 3040.0)],
                None,
                "coatings thickness",
            ),
            (vec![Coating::new(0.05, f64::NAN)], None, "coatings density"),
            (vec![], Some(Coating::new(0.3, 1000.0)), "lining thickness"),
            (vec![], Some(Coating::new(0.0, 1000.0)), "lining thickness"),
        ] {
            let error = coated(&coatings, lining)
                .expect_err("bad layer")
                .to_string();
            assert!(error.starts_with(named), "{error}");
        }
    }
}
