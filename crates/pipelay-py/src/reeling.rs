//! Python classes ReelLay and Straightener, and design_straightener: reel-lay's bending of a pipe section.
use crate::errors::to_py;
use crate::material::wall;
use numpy::PyArray1;
use pyo3::prelude::*;

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

/// A reel-lay vessel's lay equipment (SI units): the pipe spooled onto a reel whose pipe centreline has
/// `reel_radius`, unspooled straight, bent over the aligner (`aligner_radius`, of the centreline),
/// reverse-bent by the `straightener` (none: back to straight only) and released, then held at the ramp's
/// exit `position` (body frame, m) along the ramp, which leans `ramp_angle` (rad) from the vertical toward
/// the bow, like a J-lay tower. `history(section)` follows a pipe section of a yielding wall through the
/// reeling; `Model.attach_vessel(..., lay=...)` hangs the pipe from the ramp, its wall in the state the
/// reeling left.
#[pyclass(module = "pipelay", name = "ReelLay", frozen)]
#[derive(Clone, Copy)]
pub struct ReelLay {
    reeling: pipelay::rod::reeling::Reeling,
    position: Option<nalgebra::Vector3<f64>>,
    ramp_angle: f64,
}

impl ReelLay {
    /// The reel-lay of lay equipment that has a reeling; its ramp's angle from its end frame's tangent
    /// t1 = (sin α, 0, −cos α).
    pub fn of(lay: &pipelay::vessel::lay::LayEquipment) -> Option<Self> {
        let tangent = lay.end_frame.column(0);
        Some(ReelLay {
            reeling: lay.reeling?,
            position: Some(lay.hang_off),
            ramp_angle: tangent.x.atan2(-tangent.z),
        })
    }

    /// The lay equipment: the ramp holding the reeled pipe.
    pub fn equipment(&self) -> PyResult<pipelay::vessel::lay::LayEquipment> {
        let position = self.position.ok_or_else(|| {
            crate::errors::input(
                "lay",
                "ReelLay(position=None)",
                "must give position=(x, y, z), the ramp's exit (body frame, m), to hold the pipe",
            )
        })?;
        pipelay::vessel::lay::LayEquipment::reel_lay(position, self.ramp_angle, self.reeling)
            .map_err(to_py)
    }
}

#[pymethods]
impl ReelLay {
    #[new]
    #[pyo3(signature = (reel_radius, aligner_radius, straightener=None, position=None, ramp_angle=0.0))]
    fn new(
        reel_radius: f64,
        aligner_radius: f64,
        straightener: Option<Straightener>,
        position: Option<&Bound<'_, PyAny>>,
        ramp_angle: f64,
    ) -> PyResult<Self> {
        let reeling = pipelay::rod::reeling::Reeling::new(
            reel_radius,
            aligner_radius,
            straightener.map_or(0.0, |s| s.curvature),
        )
        .map_err(to_py)?;
        let position = position
            .map(|p| crate::convert::vector3(p, "position"))
            .transpose()?;
        let lay = ReelLay {
            reeling,
            position,
            ramp_angle,
        };
        pipelay::vessel::lay::check_lean("ramp_angle", ramp_angle).map_err(to_py)?;
        Ok(lay)
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
        let history =
            py.detach(|| pipelay::rod::reeling::reel(&fibres, &self.reeling, axial_strain));
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
        self.reeling.reel_radius
    }
    /// The aligner's centreline radius (m).
    #[getter]
    fn aligner_radius(&self) -> f64 {
        self.reeling.aligner_radius
    }
    /// The straightener.
    #[getter]
    fn straightener(&self) -> Straightener {
        Straightener {
            curvature: self.reeling.straightener_curvature,
        }
    }
    /// The ramp's exit (body frame, m), None if not given.
    #[getter]
    fn position(&self) -> Option<(f64, f64, f64)> {
        self.position.map(|p| (p.x, p.y, p.z))
    }
    /// The ramp's lean from the vertical toward the bow (rad).
    #[getter]
    fn ramp_angle(&self) -> f64 {
        self.ramp_angle
    }

    fn __repr__(&self) -> String {
        format!(
            "ReelLay(reel_radius={}, aligner_radius={}, straightener=Straightener(curvature={}), \
             position={:?}, ramp_angle={})",
            self.reeling.reel_radius,
            self.reeling.aligner_radius,
            self.reeling.straightener_curvature,
            self.position.map(|p| (p.x, p.y, p.z)),
            self.ramp_angle
        )
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
