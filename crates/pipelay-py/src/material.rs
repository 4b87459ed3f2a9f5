//! Python class Material: the pipe steel's stress–strain law beyond yield, with hysteresis.
use crate::errors::{input, to_py};
use numpy::PyArray1;
use pipelay::rod::material::{self, MaterialKind};
use pyo3::prelude::*;

/// The pipe steel's uniaxial law (SI units): `Material.elastic(E)`, `Material.elastic_perfectly_plastic(E,
/// yield_stress)`, `Material.ramberg_osgood(E, yield_stress, n)` (the yield stress at 0.5 % total strain),
/// `Material.table(strain, stress)` (the monotonic curve's points), `Material.grade("X65")`. Unloading and
/// reloading follow Masing's rule (the overlay model's kinematic hardening), so that cycles close and dissipate.
#[pyclass(module = "pipelay", name = "Material", frozen, from_py_object)]
#[derive(Clone)]
pub struct Material(pub material::Material);

/// Ramberg–Osgood's exponent `Material.grade` takes unless given.
const GRADE_EXPONENT: f64 = 15.0;

#[pymethods]
impl Material {
    /// Linear elastic with Young's modulus `E` (Pa).
    #[staticmethod]
    #[allow(non_snake_case)]
    fn elastic(E: f64) -> PyResult<Self> {
        material::Material::elastic(E).map(Material).map_err(to_py)
    }

    /// Elastic up to `yield_stress` (Pa), then flat: modulus `E` (Pa).
    #[staticmethod]
    #[allow(non_snake_case)]
    fn elastic_perfectly_plastic(E: f64, yield_stress: f64) -> PyResult<Self> {
        material::Material::elastic_perfectly_plastic(E, yield_stress)
            .map(Material)
            .map_err(to_py)
    }

    /// Ramberg–Osgood: ε = σ/E + (0.005 − σ_y/E)(σ/σ_y)ⁿ, `yield_stress` σ_y (Pa) at 0.5 % total strain,
    /// exponent `n` > 1.
    #[staticmethod]
    #[allow(non_snake_case)]
    fn ramberg_osgood(E: f64, yield_stress: f64, n: f64) -> PyResult<Self> {
        material::Material::ramberg_osgood(E, yield_stress, n)
            .map(Material)
            .map_err(to_py)
    }

    /// The monotonic curve through the points (`strain`, `stress`) (strain from above 0, increasing; stress
    /// in Pa, slopes not growing); its first slope is E, and beyond its last point its last slope holds.
    #[staticmethod]
    fn table(strain: Vec<f64>, stress: Vec<f64>) -> PyResult<Self> {
        material::Material::table(&strain, &stress)
            .map(Material)
            .map_err(to_py)
    }

    /// A line pipe grade (a key of `pipelay.analysis.checks.GRADES`, e.g. "X65"): Ramberg–Osgood with its
    /// SMYS at 0.5 % total strain, `E` (Pa) and exponent `n` (15 unless given: a typical fit of seamless
    /// and UOE line pipe; fit your mill's curve where the strain matters).
    #[staticmethod]
    #[pyo3(signature = (name, n=GRADE_EXPONENT, E=207e9))]
    #[allow(non_snake_case)]
    fn grade(py: Python<'_>, name: &str, n: f64, E: f64) -> PyResult<Self> {
        let grades = py.import("pipelay.analysis.checks")?.getattr("GRADES")?;
        let Some(entry) = grades.get_item(name).ok() else {
            let known: Vec<String> = grades
                .try_iter()?
                .map(|g| g?.extract())
                .collect::<PyResult<_>>()?;
            return Err(input(
                "grade",
                format!("{name:?}"),
                &format!("must be one of {}", known.join(", ")),
            ));
        };
        let (smys, _smts): (f64, f64) = entry.extract()?;
        material::Material::ramberg_osgood(E, smys, n)
            .map(Material)
            .map_err(to_py)
    }

    /// Young's modulus E (Pa).
    #[getter]
    fn youngs_modulus(&self) -> f64 {
        self.0.youngs_modulus
    }

    /// "elastic", "elastic_perfectly_plastic", "ramberg_osgood" or "table".
    #[getter]
    fn kind(&self) -> &'static str {
        match self.0.kind {
            MaterialKind::Elastic => "elastic",
            MaterialKind::ElasticPerfectlyPlastic { .. } => "elastic_perfectly_plastic",
            MaterialKind::RambergOsgood { .. } => "ramberg_osgood",
            MaterialKind::Table => "table",
        }
    }

    /// The stresses (Pa) along a path of strains `strain` from rest (history-dependent: unloading follows
    /// Masing's rule).
    fn stress_strain<'py>(&self, py: Python<'py>, strain: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
        let mut plastic = vec![0.0; self.0.state_size()];
        let mut end = plastic.clone();
        let stresses: Vec<f64> = strain
            .iter()
            .map(|&e| {
                let response = self.0.respond(e, &plastic, &mut end);
                plastic.copy_from_slice(&end);
                response.stress
            })
            .collect();
        PyArray1::from_vec(py, stresses)
    }

    fn __repr__(&self) -> String {
        let e = self.0.youngs_modulus;
        match self.0.kind {
            MaterialKind::Elastic => format!("Material.elastic(E={e:e})"),
            MaterialKind::ElasticPerfectlyPlastic { yield_stress } => {
                format!(
                    "Material.elastic_perfectly_plastic(E={e:e}, yield_stress={yield_stress:e})"
                )
            }
            MaterialKind::RambergOsgood {
                yield_stress,
                exponent,
            } => format!(
                "Material.ramberg_osgood(E={e:e}, yield_stress={yield_stress:e}, n={exponent})"
            ),
            MaterialKind::Table => format!(
                "Material.table(E={e:e}, {} elements)",
                self.0.elements.len()
            ),
        }
    }
}

/// The moments along `curvatures` of `section` at `axial_strain` (see `Section.moment_curvature`).
pub fn moment_curvature<'py>(
    py: Python<'py>,
    section: &pipelay::rod::section::Section,
    curvatures: &Bound<'py, PyAny>,
    axial_strain: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let fibres = wall(section)?;
    let curvatures: Vec<f64> = curvatures.extract().map_err(|_| {
        input(
            "curvatures",
            "the given value",
            "must be a sequence of numbers (1/m)",
        )
    })?;
    pipelay::error::finite("curvatures", &curvatures).map_err(to_py)?;
    pipelay::error::finite("axial_strain", &[axial_strain]).map_err(to_py)?;
    let moments = fibres.moment_curvature(&curvatures, axial_strain);
    Ok(PyArray1::from_vec(py, moments))
}

/// A section's wall as fibres, or an error naming the section.
pub fn wall(
    section: &pipelay::rod::section::Section,
) -> PyResult<pipelay::rod::fibre_section::FibreSection> {
    section
        .fibre_section()
        .ok_or_else(|| {
            input(
                "section",
                "a section without a pipe wall",
                "must be a pipe (Section.pipe) to integrate its wall",
            )
        })?
        .map_err(to_py)
}
