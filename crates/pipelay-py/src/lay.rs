//! Python classes Stinger, SLay and JLay: lay equipment on the vessel (body frame b: forward, starboard,
//! down; metres from the vessel's reference point CO).
use crate::convert::{points, vector3};
use crate::errors::{input, to_py};
use numpy::PyArray2;
use pipelay::vessel::articulation::{self, Articulation};
use pipelay::vessel::lay::{self, LayEquipment, Roller, RollerFriction};
use pipelay::vessel::roller_box;
use pyo3::prelude::*;

/// A stinger: `rollers` rollers spread evenly over a circular arc of `radius` and `length` (m), the rollers'
/// top line, starting at `origin` (body frame, m) with the slope `angle` (rad below the horizontal) and
/// running aft while bending down. `roller_radius` (m). `Stinger.from_rollers(positions, axes)` places
/// rollers at given top points instead; `Stinger.articulated(sections, ...)` hinges the arc's sections.
#[pyclass(module = "pipelay", name = "Stinger", frozen)]
#[derive(Clone)]
pub struct Stinger(pub Vec<Roller>, pub Option<Articulation>);

#[pymethods]
impl Stinger {
    #[new]
    #[pyo3(signature = (radius, length, rollers, *, origin=None, angle=0.0, roller_radius=lay::ROLLER_RADIUS, boxes=None))]
    fn new(
        radius: f64,
        length: f64,
        rollers: i64,
        origin: Option<&Bound<'_, PyAny>>,
        angle: f64,
        roller_radius: f64,
        boxes: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let count = usize::try_from(rollers)
            .ok()
            .filter(|&c| (1..=1000).contains(&c))
            .ok_or_else(|| input("rollers", rollers, "must be an integer from 1 to 1000"))?;
        pipelay::error::positive("roller_radius", roller_radius, "m").map_err(to_py)?;
        let origin = origin
            .map(|o| vector3(o, "origin"))
            .transpose()?
            .unwrap_or_else(nalgebra::Vector3::zeros);
        let Some(boxes) = boxes else {
            return lay::stinger_rollers(radius, length, count, origin, angle, roller_radius)
                .map(|rollers| Stinger(rollers, None))
                .map_err(to_py);
        };
        let boxes = boxes
            .try_iter()
            .and_then(|items| {
                items
                    .map(|item| Ok(item?.cast::<RollerBox>()?.get().clone()))
                    .collect::<PyResult<Vec<RollerBox>>>()
            })
            .map_err(|_| input("boxes", "the given value", "must be a list of pl.RollerBox"))?;
        // A box without its own arc length stands at the place of the roller it replaces.
        if boxes.iter().any(|b| b.arc_length.is_none()) && boxes.len() != count {
            return Err(input(
                "boxes",
                format!("{} boxes", boxes.len()),
                &format!(
                    "must hold one box per roller place ({count}), or give each box its arc_length"
                ),
            ));
        }
        // The rollers' places on the arc, the last exactly at its end.
        let place = |k: usize| {
            if count == 1 {
                0.0
            } else {
                (length * k as f64 / (count - 1) as f64).min(length)
            }
        };
        let placed: Vec<_> = boxes
            .iter()
            .enumerate()
            .map(|(k, b)| (b.arc_length.unwrap_or_else(|| place(k)), b.shape))
            .collect();
        roller_box::stinger_boxes(radius, length, origin, angle, roller_radius, &placed)
            .map(|rollers| Stinger(rollers, None))
            .map_err(to_py)
    }

    /// An articulated stinger: the arc of `radius` (m) from `origin` at the slope `angle` (as `Stinger`), its
    /// first `fixed_length` (m) on the vessel, then `sections` (a list of `pl.StingerSection`), each hinged to
    /// the one before (the first to the vessel) about the vessel's lateral axis b2. Its supports are spread as
    /// a `Stinger`'s over the whole length, `rollers` lone rollers or `boxes`; each rides on the section that
    /// carries its place (a support at a hinge on the one before).
    #[staticmethod]
    #[pyo3(signature = (sections, radius, rollers, *, fixed_length=0.0, origin=None, angle=0.0, roller_radius=lay::ROLLER_RADIUS, boxes=None))]
    #[allow(clippy::too_many_arguments)]
    fn articulated(
        sections: &Bound<'_, PyAny>,
        radius: f64,
        rollers: i64,
        fixed_length: f64,
        origin: Option<&Bound<'_, PyAny>>,
        angle: f64,
        roller_radius: f64,
        boxes: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let sections = sections
            .try_iter()
            .and_then(|items| {
                items
                    .map(|item| Ok(item?.cast::<StingerSection>()?.get().0))
                    .collect::<PyResult<Vec<_>>>()
            })
            .map_err(|_| {
                input(
                    "sections",
                    "the given value",
                    "must be a list of pl.StingerSection",
                )
            })?;
        let length = fixed_length + sections.iter().map(|s| s.length).sum::<f64>();
        let Stinger(mut placed, _) =
            Stinger::new(radius, length, rollers, origin, angle, roller_radius, boxes)?;
        let origin = origin
            .map(|o| vector3(o, "origin"))
            .transpose()?
            .unwrap_or_else(nalgebra::Vector3::zeros);
        let articulation =
            Articulation::new(radius, origin, angle, fixed_length, sections).map_err(to_py)?;
        lay::assign_sections(&articulation, &mut placed);
        Ok(Stinger(placed, Some(articulation)))
    }

    /// The hinged sections (a list of `pl.StingerSection`; empty unless articulated).
    #[getter]
    fn sections(&self) -> Vec<StingerSection> {
        self.1
            .as_ref()
            .map(|a| a.sections.iter().copied().map(StingerSection).collect())
            .unwrap_or_default()
    }

    /// Each section's hinge (h, 3), body frame (m), where the sections stand at zero hinge angles.
    #[getter]
    fn hinges<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let hinges = self
            .1
            .as_ref()
            .map(|a| a.chain.hinges.clone())
            .unwrap_or_default();
        crate::convert::points_to_numpy(py, &hinges)
    }

    /// The section each roller rides on (k,), -1 for a roller on the vessel.
    #[getter]
    fn roller_sections(&self) -> Vec<i64> {
        self.0
            .iter()
            .map(|r| r.section.map_or(-1, |j| j as i64))
            .collect()
    }

    /// Rollers at `positions` (k, 3), their top points (where the pipe's bottom rests), with axes `axes`
    /// (k, 3) (default: athwartships, b2), body frame (m).
    #[staticmethod]
    #[pyo3(signature = (positions, axes=None, roller_radius=lay::ROLLER_RADIUS))]
    fn from_rollers(
        positions: &Bound<'_, PyAny>,
        axes: Option<&Bound<'_, PyAny>>,
        roller_radius: f64,
    ) -> PyResult<Self> {
        pipelay::error::positive("roller_radius", roller_radius, "m").map_err(to_py)?;
        let tops = points(positions, "positions")?;
        if tops.is_empty() || tops.len() > 1000 {
            return Err(input(
                "positions",
                format!("{} rollers", tops.len()),
                "must hold 1 to 1000 rows",
            ));
        }
        let axes = match axes {
            Some(a) => points(a, "axes")?,
            None => vec![nalgebra::Vector3::y(); tops.len()],
        };
        if axes.len() != tops.len() {
            return Err(input(
                "axes",
                format!("{} rows", axes.len()),
                &format!("must have one row per roller ({})", tops.len()),
            ));
        }
        lay::rollers_at(&tops, &axes, roller_radius)
            .map(|rollers| Stinger(rollers, None))
            .map_err(to_py)
    }

    /// The rollers' top points (k, 3), body frame (m).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let tops: Vec<_> = self
            .0
            .iter()
            .map(|r| r.centre + r.radius * r.normal)
            .collect();
        crate::convert::points_to_numpy(py, &tops)
    }

    /// Each support's station on the stinger's top line (m, 3), body frame (m): a lone roller's top, a box's
    /// station (where the surfaces of its V meet, or its bottom roller's top).
    #[getter]
    fn stations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let stations: Vec<_> = lay::supports(&self.0).into_iter().map(|s| s.0).collect();
        crate::convert::points_to_numpy(py, &stations)
    }

    /// The support (lone roller or box, 0-based) of each roller (k,).
    #[getter]
    fn supports(&self) -> Vec<usize> {
        self.0.iter().map(|r| r.support).collect()
    }

    /// Each roller's axis (k, 3), unit, body frame.
    #[getter]
    fn axes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let axes: Vec<_> = self.0.iter().map(|r| r.axis).collect();
        crate::convert::points_to_numpy(py, &axes)
    }

    /// Each roller's length (k,) (m; inf for the long cylinders of a stinger of lone rollers).
    #[getter]
    fn lengths(&self) -> Vec<f64> {
        self.0.iter().map(|r| r.length).collect()
    }

    fn __len__(&self) -> usize {
        self.0.len()
    }

    fn __repr__(&self) -> String {
        let supports = self.0.last().map_or(0, |r| r.support + 1);
        let hinged = self.1.as_ref().map_or(String::new(), |a| {
            format!(", {} hinged sections", a.sections.len())
        });
        if supports == self.0.len() {
            format!("Stinger({} rollers{hinged})", self.0.len())
        } else {
            format!(
                "Stinger({supports} boxes, {} rollers{hinged})",
                self.0.len()
            )
        }
    }
}

/// A section of an articulated stinger (`Stinger.articulated`): it carries `length` (m) of the stinger's top
/// line, a rigid body of `mass` (kg) with a constant `buoyancy` (N, upward: its displaced water with its
/// ballast set), hinged at its start with a spring of `hinge_stiffness` (N·m/rad, about the angle 0 where it
/// lies on the stinger's arc; 0: a free hinge) within `hinge_limits` (min ≤ 0 ≤ max, rad; a positive angle
/// turns its aft end down), against drag of area `drag_area` (C_d A, m²), its inertia that of its mass and
/// its `added_mass` (kg, the water it carries along).
#[pyclass(module = "pipelay", name = "StingerSection", frozen)]
#[derive(Clone)]
pub struct StingerSection(pub articulation::StingerSection);

#[pymethods]
impl StingerSection {
    #[new]
    #[pyo3(signature = (length, mass, buoyancy, hinge_stiffness=0.0, hinge_limits=vec![-0.5, 0.5], drag_area=0.0, added_mass=0.0))]
    fn new(
        length: f64,
        mass: f64,
        buoyancy: f64,
        hinge_stiffness: f64,
        hinge_limits: Vec<f64>,
        drag_area: f64,
        added_mass: f64,
    ) -> PyResult<Self> {
        let limits: [f64; 2] = hinge_limits.as_slice().try_into().map_err(|_| {
            input(
                "hinge_limits",
                format!("{} values", hinge_limits.len()),
                "must be [min, max] (rad)",
            )
        })?;
        articulation::StingerSection::new(
            length,
            mass,
            buoyancy,
            hinge_stiffness,
            limits,
            drag_area,
        )
        .and_then(|section| section.with_added_mass(added_mass))
        .map(StingerSection)
        .map_err(to_py)
    }

    /// The length of the stinger's top line it carries (m).
    #[getter]
    fn length(&self) -> f64 {
        self.0.length
    }
    /// Mass (kg).
    #[getter]
    fn mass(&self) -> f64 {
        self.0.mass
    }
    /// Buoyancy (N, upward).
    #[getter]
    fn buoyancy(&self) -> f64 {
        self.0.buoyancy
    }
    /// Hinge stiffness (N·m/rad).
    #[getter]
    fn hinge_stiffness(&self) -> f64 {
        self.0.hinge_stiffness
    }
    /// The hinge's angle limits (min, max) (rad).
    #[getter]
    fn hinge_limits(&self) -> (f64, f64) {
        (self.0.limits[0], self.0.limits[1])
    }
    /// Drag area C_d A (m²).
    #[getter]
    fn drag_area(&self) -> f64 {
        self.0.drag_area
    }
    /// Added mass (kg).
    #[getter]
    fn added_mass(&self) -> f64 {
        self.0.added_mass
    }

    fn __repr__(&self) -> String {
        format!(
            "StingerSection(length={}, mass={}, buoyancy={}, hinge_stiffness={}, hinge_limits=({}, {}))",
            self.0.length,
            self.0.mass,
            self.0.buoyancy,
            self.0.hinge_stiffness,
            self.0.limits[0],
            self.0.limits[1]
        )
    }
}

/// A roller box: rollers of finite length set across the pipe at a place of the stinger. `kind` "v": two
/// rollers rising outward at ±`half_angle` (rad) from the lateral, whose surfaces meet at the stinger's top
/// line (with `bottom`, a bottom roller between them); `sides`: vertical side rollers at the V's upper ends.
/// `kind` "u": a bottom roller between two vertical side rollers. Every roller `roller_length` (m) long.
/// `arc_length` (m along the stinger from its start; None: the place of the roller the box replaces).
/// Its rollers turn freely against `rolling_resistance` (force per normal force, along the pipe) and resist
/// the pipe sliding along them with Coulomb `friction` μ; `locked` rollers (braked) resist with μ in every
/// direction.
#[pyclass(module = "pipelay", name = "RollerBox", frozen)]
#[derive(Clone)]
pub struct RollerBox {
    arc_length: Option<f64>,
    shape: roller_box::RollerBox,
}

#[pymethods]
impl RollerBox {
    #[new]
    #[pyo3(signature = (arc_length=None, kind="v", half_angle=std::f64::consts::FRAC_PI_6, roller_length=1.2, bottom=false, sides=false, friction=0.0, rolling_resistance=0.0, locked=false))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        arc_length: Option<f64>,
        kind: &str,
        half_angle: f64,
        roller_length: f64,
        bottom: bool,
        sides: bool,
        friction: f64,
        rolling_resistance: f64,
        locked: bool,
    ) -> PyResult<Self> {
        let shape = match kind {
            "v" => roller_box::BoxShape::V,
            "u" => roller_box::BoxShape::U,
            other => return Err(input("kind", other, "must be \"v\" or \"u\"")),
        };
        if let Some(s) = arc_length {
            pipelay::error::finite("arc_length", &[s]).map_err(to_py)?;
        }
        let mut shape = roller_box::RollerBox::new(shape, half_angle, roller_length, bottom, sides)
            .map_err(to_py)?;
        shape.friction =
            RollerFriction::new(friction, rolling_resistance, locked).map_err(to_py)?;
        Ok(RollerBox { arc_length, shape })
    }

    /// Where the box stands along the stinger (m), or None: at the place of the roller it replaces.
    #[getter]
    fn arc_length(&self) -> Option<f64> {
        self.arc_length
    }
    /// "v" or "u".
    #[getter]
    fn kind(&self) -> &'static str {
        match self.shape.shape {
            roller_box::BoxShape::V => "v",
            roller_box::BoxShape::U => "u",
        }
    }
    /// The V's rollers' rise from the lateral (rad).
    #[getter]
    fn half_angle(&self) -> f64 {
        self.shape.half_angle
    }
    /// Every roller's length (m).
    #[getter]
    fn roller_length(&self) -> f64 {
        self.shape.roller_length
    }
    #[getter]
    fn bottom(&self) -> bool {
        self.shape.bottom
    }
    #[getter]
    fn sides(&self) -> bool {
        self.shape.sides
    }
    /// Coulomb friction μ of the box's rollers.
    #[getter]
    fn friction(&self) -> f64 {
        self.shape.friction.friction
    }
    /// Rolling resistance f_r of the box's rollers.
    #[getter]
    fn rolling_resistance(&self) -> f64 {
        self.shape.friction.rolling_resistance
    }
    /// Whether the box's rollers are locked.
    #[getter]
    fn locked(&self) -> bool {
        self.shape.friction.locked
    }

    fn __repr__(&self) -> String {
        format!(
            "RollerBox(kind={:?}, half_angle={}, roller_length={}, bottom={}, sides={})",
            self.kind(),
            self.shape.half_angle,
            self.shape.roller_length,
            self.shape.bottom,
            self.shape.sides
        )
    }
}

/// S-lay: the pipe held by the tensioner at `tensioner` (body frame, m) on a horizontal firing line along
/// the vessel's axis, running aft over the stinger's rollers. `friction`: the rolling resistance along the
/// pipe (force per normal force) of the stinger's rollers that have no friction of their own (lone rollers;
/// a `RollerBox` carries its own). `roller_stiffness`: contact stiffness (N/m).
#[pyclass(module = "pipelay", name = "SLay", frozen)]
#[derive(Clone)]
pub struct SLay(pub LayEquipment);

#[pymethods]
impl SLay {
    #[new]
    #[pyo3(signature = (tensioner, stinger=None, friction=0.0, *, roller_stiffness=lay::ROLLER_STIFFNESS))]
    fn new(
        tensioner: &Bound<'_, PyAny>,
        stinger: Option<&Stinger>,
        friction: f64,
        roller_stiffness: f64,
    ) -> PyResult<Self> {
        let resistance = RollerFriction::new(0.0, friction, false)
            .map_err(|_| input("friction", friction, "must be a finite coefficient ≥ 0"))?;
        let tensioner = vector3(tensioner, "tensioner")?;
        let mut rollers = stinger.map(|s| s.0.clone()).unwrap_or_default();
        for roller in rollers
            .iter_mut()
            .filter(|r| r.friction == RollerFriction::default())
        {
            roller.friction = resistance;
        }
        let mut lay = LayEquipment::s_lay(tensioner, rollers, roller_stiffness).map_err(to_py)?;
        lay.articulation = stinger.and_then(|s| s.1.clone());
        Ok(SLay(lay))
    }

    /// The tensioner's position (body frame, m).
    #[getter]
    fn tensioner(&self) -> (f64, f64, f64) {
        let p = self.0.hang_off;
        (p.x, p.y, p.z)
    }

    /// The stinger's rollers (body frame), as a Stinger.
    #[getter]
    fn stinger(&self) -> Stinger {
        Stinger(self.0.rollers.clone(), self.0.articulation.clone())
    }

    fn __repr__(&self) -> String {
        let p = self.0.hang_off;
        format!(
            "SLay(tensioner=({}, {}, {}), {} rollers)",
            p.x,
            p.y,
            p.z,
            self.0.rollers.len()
        )
    }
}

/// J-lay: the pipe held at the tower exit `position` (body frame, m), along the tower, which leans `angle`
/// (rad) from the vertical toward the bow. `guide` (m): a bellmouth at the exit of that bend radius, whose
/// narrowest opening is `guide_opening` (m, default 1 m) across: a line that leaves the exit at an angle (the
/// A&R wire, lowered below the exit) bends over it.
#[pyclass(module = "pipelay", name = "JLay", frozen)]
#[derive(Clone)]
pub struct JLay(pub LayEquipment);

#[pymethods]
impl JLay {
    #[new]
    #[pyo3(signature = (position, angle=0.0, guide=None, guide_opening=1.0))]
    fn new(
        position: &Bound<'_, PyAny>,
        angle: f64,
        guide: Option<f64>,
        guide_opening: f64,
    ) -> PyResult<Self> {
        let position = vector3(position, "position")?;
        let lay = LayEquipment::j_lay(position, angle).map_err(to_py)?;
        match guide {
            Some(radius) => lay.with_guide(radius, guide_opening),
            None => Ok(lay),
        }
        .map(JLay)
        .map_err(to_py)
    }

    /// The guide's bend radius (m), None without a guide.
    #[getter]
    fn guide(&self) -> Option<f64> {
        self.0.rollers.first().filter(|r| r.guide).map(|r| r.radius)
    }

    /// The tower exit's position (body frame, m).
    #[getter]
    fn position(&self) -> (f64, f64, f64) {
        let p = self.0.hang_off;
        (p.x, p.y, p.z)
    }

    fn __repr__(&self) -> String {
        let p = self.0.hang_off;
        format!("JLay(position=({}, {}, {}))", p.x, p.y, p.z)
    }
}

/// The lay equipment of a Python SLay, JLay or ReelLay object.
pub fn equipment(value: &Bound<'_, PyAny>) -> PyResult<LayEquipment> {
    if let Ok(s) = value.cast::<SLay>() {
        return Ok(s.get().0.clone());
    }
    if let Ok(j) = value.cast::<JLay>() {
        return Ok(j.get().0.clone());
    }
    if let Ok(reel) = value.cast::<crate::reeling::ReelLay>() {
        return reel.get().equipment();
    }
    Err(input(
        "lay",
        value.repr().map_or("?".into(), |r| r.to_string()),
        "must be a pl.SLay, a pl.JLay or a pl.ReelLay",
    ))
}
