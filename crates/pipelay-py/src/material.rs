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

/// A reel-lay straightener: the curvature (1/m, of the pipe's centreline; negative: against the reel's) its
/// reverse bending gives the pipe. `pl.design_straightener` finds the one that leaves the pipe straight.
#[pyclass(module = "pipelay", name = "Straightener", frozen, from_py_object)]
#[derive(Clone, Copy)]
pub struct Straightener {
    #[pyo3(get)]
    curvature: f64,
}

#[pymethods]
impl Straightener {
    #[new]
    fn new(curvature: f64) -> PyResult<Self> {
        pipelay::error::finite("curvature", &[curvature]).map_err(to_py)?;
        Ok(Straightener { curvature })
    }

    fn __repr__(&self) -> String {
        format!("Straightener(curvature={})", self.curvature)
    }
}

/// Reel-lay's bending of the pipe (SI units): spooled onto a reel whose pipe centreline has `reel_radius`,
/// unspooled straight, bent over the aligner (`aligner_radius`, of the centreline), reverse-bent by the
/// `straightener` (none: not at all) and released. `history(section)` follows a pipe section of a yielding
/// wall through it.
#[pyclass(module = "pipelay", name = "ReelLay", frozen)]
#[derive(Clone, Copy)]
pub struct ReelLay(pipelay::rod::reeling::Reeling);

#[pymethods]
impl ReelLay {
    #[new]
    #[pyo3(signature = (reel_radius, aligner_radius, straightener=None))]
    fn new(
        reel_radius: f64,
        aligner_radius: f64,
        straightener: Option<Straightener>,
    ) -> PyResult<Self> {
        pipelay::rod::reeling::Reeling::new(
            reel_radius,
            aligner_radius,
            straightener.map_or(0.0, |s| s.curvature),
        )
        .map(ReelLay)
        .map_err(to_py)
    }

    /// The history of a pipe `section` (a pipe's wall, `Section.pipe`) through the reeling at the axial strain
    /// `axial_strain`: a dict of curvature (1/m), moment (N·m), strain (the wall's largest) and stage (0 reel,
    /// 1 unspooled, 2 aligner, 3 straightener, 4 released) along it, residual_curvature (1/m, at zero moment
    /// after release) and accumulated_plastic_strain (the largest Σ|Δε_p| over the wall's fibres: the
    /// reeling's share of a strain-based design's plastic strain).
    #[pyo3(signature = (section, axial_strain=0.0))]
    fn history<'py>(
        &self,
        py: Python<'py>,
        section: &crate::structure::Section,
        axial_strain: f64,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let fibres = wall(&section.0)?;
        pipelay::error::finite("axial_strain", &[axial_strain]).map_err(to_py)?;
        let history = py.detach(|| pipelay::rod::reeling::reel(&fibres, &self.0, axial_strain));
        let dict = pyo3::types::PyDict::new(py);
        dict.set_item("curvature", PyArray1::from_vec(py, history.curvature))?;
        dict.set_item("moment", PyArray1::from_vec(py, history.moment))?;
        dict.set_item("strain", PyArray1::from_vec(py, history.strain))?;
        dict.set_item("stage", history.stage)?;
        dict.set_item("residual_curvature", history.residual_curvature)?;
        dict.set_item(
            "accumulated_plastic_strain",
            history.accumulated_plastic_strain,
        )?;
        Ok(dict)
    }

    /// The reel's centreline radius (m).
    #[getter]
    fn reel_radius(&self) -> f64 {
        self.0.reel_radius
    }
    /// The aligner's centreline radius (m).
    #[getter]
    fn aligner_radius(&self) -> f64 {
        self.0.aligner_radius
    }
    /// The straightener.
    #[getter]
    fn straightener(&self) -> Straightener {
        Straightener {
            curvature: self.0.straightener_curvature,
        }
    }
}

/// The straightener that leaves a pipe `section` straight (zero residual curvature) after a reel of
/// `reel_radius` and an aligner of `aligner_radius` (m, of the pipe's centreline), at the axial strain
/// `axial_strain`.
#[pyfunction]
#[pyo3(signature = (section, reel_radius, aligner_radius, axial_strain=0.0))]
pub fn design_straightener(
    py: Python<'_>,
    section: &crate::structure::Section,
    reel_radius: f64,
    aligner_radius: f64,
    axial_strain: f64,
) -> PyResult<Straightener> {
    let fibres = wall(&section.0)?;
    let curvature = py
        .detach(|| {
            pipelay::rod::reeling::design_straightener(
                &fibres,
                reel_radius,
                aligner_radius,
                axial_strain,
            )
        })
        .map_err(to_py)?;
    Ok(Straightener { curvature })
}

/// A section's wall as fibres, or an error naming the section.
fn wall(
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
