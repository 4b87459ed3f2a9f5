//! Cross-section properties: stiffness (eqs. 29–30), mass, inertia (19) and hydrodynamic coefficients.
use crate::error::{finite, non_negative, positive, Result};
use nalgebra::{Matrix3, Vector3};

/// A rod's cross-section, constant along the rod. Axis 1 is the rod axis (t1); 2 and 3 the principal axes.
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
    /// Outer diameter, to which drag and added mass refer (m).
    pub outer_diameter: f64,
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
}

/// The wall of a pipe section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PipeWall {
    /// Wall thickness (m).
    pub thickness: f64,
    /// Young's modulus (Pa).
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    /// Density of the contents (kg/m³).
    pub contents_density: f64,
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
        for &c in &extras.drag {
            non_negative("drag", c, "(dimensionless)")?;
        }
        for &c in &extras.added_mass {
            non_negative("added_mass", c, "(dimensionless)")?;
        }
        for &c in &extras.rotational_damping {
            non_negative("rotational_damping", c, "N·m·s/m")?;
        }
        Ok(Section {
            translational_stiffness: Vector3::new(ea, ga[0], ga[1]),
            rotational_stiffness: Vector3::new(gj, ei[0], ei[1]),
            mass,
            inertia: Vector3::from(extras.inertia),
            outer_diameter: extras.outer_diameter,
            displaced_area,
            drag: extras.drag,
            added_mass: extras.added_mass,
            rotational_damping: Vector3::from(extras.rotational_damping),
            wall: None,
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
        let d_o = outer_diameter;
        let d_i = outer_diameter - 2.0 * wall_thickness;
        let pi = std::f64::consts::PI;
        let area = pi / 4.0 * (d_o * d_o - d_i * d_i);
        let second_moment = pi / 64.0 * (d_o.powi(4) - d_i.powi(4));
        let shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
        let shear_area = 0.5 * area;
        let mass = density * area + contents_density * pi / 4.0 * d_i * d_i;
        let extras = SectionExtras {
            inertia: [
                density * 2.0 * second_moment,
                density * second_moment,
                density * second_moment,
            ],
            outer_diameter: d_o,
            displaced_area: None,
            drag,
            added_mass,
            rotational_damping: [0.0; 3],
        };
        let mut section = Section::new(
            youngs_modulus * area,
            [shear_modulus * shear_area; 2],
            shear_modulus * 2.0 * second_moment,
            [youngs_modulus * second_moment; 2],
            mass,
            extras,
        )?;
        section.wall = Some(PipeWall {
            thickness: wall_thickness,
            youngs_modulus,
            poisson_ratio,
            contents_density,
        });
        Ok(section)
    }

    /// Largest longitudinal strain of a section carrying material force and moment `forces`
    /// ([N1, N2, N3, M1, M2, M3]): axial N1/EA plus bending at the outer fibre, (d_o/2)|(M2/EI2, M3/EI3)|
    /// (linear elastic; the tensile side in bending).
    pub fn strain(&self, forces: &nalgebra::Vector6<f64>) -> f64 {
        let axial = forces[0] / self.translational_stiffness.x;
        let curvature = nalgebra::Vector2::new(
            forces[4] / self.rotational_stiffness.y,
            forces[5] / self.rotational_stiffness.z,
        );
        axial + 0.5 * self.outer_diameter * curvature.norm()
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
