//! Python classes for what a model is built from: Section, Rod, Current, Sea.
use crate::convert::{array, points, points_to_numpy, scalar_or_array, vector, vector3};
use crate::errors::{input, to_py};
use numpy::{PyArray1, PyArray2};
use pipelay::environment::current::{self, CurrentProfile};
use pipelay::environment::sea;
use pipelay::rod::section::{self, SectionExtras};
use pyo3::prelude::*;

/// Sea water's density (kg/m³) and gravity (m/s²) of `Section.submerged_weight`.
const SEA_WATER_DENSITY: f64 = 1025.0;
const GRAVITY: f64 = 9.81;

/// A layer outside a pipe's steel wall (a coating) or inside it (a lining): thickness (m), density (kg/m³)
/// and the Young's modulus (Pa) it adds to the axial and bending stiffness (default 0: none, as usual for
/// concrete).
#[pyclass(module = "pipelay", name = "Coating", frozen, from_py_object)]
#[derive(Clone, Copy)]
pub struct Coating(pub section::Coating);

#[pymethods]
impl Coating {
    #[new]
    #[pyo3(signature = (thickness, density, youngs_modulus=0.0))]
    fn new(thickness: f64, density: f64, youngs_modulus: f64) -> PyResult<Self> {
        let layer = section::Coating {
            thickness,
            density,
            youngs_modulus,
        };
        layer.check("").map_err(to_py)?;
        Ok(Coating(layer))
    }
    /// Thickness (m).
    #[getter]
    fn thickness(&self) -> f64 {
        self.0.thickness
    }
    /// Density (kg/m³).
    #[getter]
    fn density(&self) -> f64 {
        self.0.density
    }
    /// Young's modulus added to the stiffness (Pa; 0: none).
    #[getter]
    fn youngs_modulus(&self) -> f64 {
        self.0.youngs_modulus
    }
    fn __repr__(&self) -> String {
        format!(
            "Coating(thickness={}, density={}, youngs_modulus={})",
            self.0.thickness, self.0.density, self.0.youngs_modulus
        )
    }
}

/// A body to attach at a point of the line (`Model.attach`): a clump weight, a buoyancy module, an in-line
/// structure or a laydown head: mass in air (kg), displaced volume (m³), drag area C_d·A (m²) and added-mass
/// coefficient on the displaced volume.
#[pyclass(module = "pipelay", name = "Clump", frozen)]
#[derive(Clone, Copy)]
pub struct Clump(pub pipelay::rod::attachment::Attachment);

#[pymethods]
impl Clump {
    #[new]
    #[pyo3(signature = (mass, volume=0.0, drag_area=0.0, added_mass=1.0))]
    fn new(mass: f64, volume: f64, drag_area: f64, added_mass: f64) -> PyResult<Self> {
        pipelay::rod::attachment::Attachment::new(0.0, mass, volume, drag_area, added_mass)
            .map(Clump)
            .map_err(to_py)
    }
    /// Mass in air (kg).
    #[getter]
    fn mass(&self) -> f64 {
        self.0.mass
    }
    /// Displaced volume (m³).
    #[getter]
    fn volume(&self) -> f64 {
        self.0.volume
    }
    /// Drag area C_d·A (m²).
    #[getter]
    fn drag_area(&self) -> f64 {
        self.0.drag_area
    }
    /// Added-mass coefficient on the displaced volume.
    #[getter]
    fn added_mass(&self) -> f64 {
        self.0.added_mass
    }
    fn __repr__(&self) -> String {
        format!(
            "Clump(mass={}, volume={}, drag_area={}, added_mass={})",
            self.0.mass, self.0.volume, self.0.drag_area, self.0.added_mass
        )
    }
}

/// Refuses a steel grade that the design checks do not know (`pipelay.analysis.checks.GRADES`).
fn check_grade(py: Python<'_>, grade: &str) -> PyResult<()> {
    let grades = py.import("pipelay.analysis.checks")?.getattr("GRADES")?;
    if grades.contains(grade)? {
        return Ok(());
    }
    let known: Vec<String> = grades
        .try_iter()?
        .map(|g| g?.extract())
        .collect::<PyResult<_>>()?;
    Err(input(
        "grade",
        format!("{grade:?}"),
        &format!("must be one of {}", known.join(", ")),
    ))
}

/// Cross-section properties (SI units). GA, EI: one number (both principal axes) or a pair (axis 2, axis 3).
#[pyclass(module = "pipelay", name = "Section", frozen, from_py_object)]
#[derive(Clone)]
pub struct Section(pub section::Section);

/// A pair of coefficients (axial, normal) named `name`, or `default` where not given.
fn coefficients(
    value: Option<&Bound<'_, PyAny>>,
    name: &str,
    default: [f64; 2],
) -> PyResult<[f64; 2]> {
    Ok(value
        .map(|v| array::<2>(v, name))
        .transpose()?
        .unwrap_or(default))
}

#[pymethods]
impl Section {
    #[new]
    #[pyo3(signature = (EA, GA, GJ, EI, mass, inertia=None, outer_diameter=0.0, displaced_area=None, drag=None, added_mass=None, rotational_damping=None))]
    #[allow(non_snake_case, clippy::too_many_arguments)]
    fn new(
        EA: f64,
        GA: &Bound<'_, PyAny>,
        GJ: f64,
        EI: &Bound<'_, PyAny>,
        mass: f64,
        inertia: Option<&Bound<'_, PyAny>>,
        outer_diameter: f64,
        displaced_area: Option<f64>,
        drag: Option<&Bound<'_, PyAny>>,
        added_mass: Option<&Bound<'_, PyAny>>,
        rotational_damping: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let extras = SectionExtras {
            inertia: inertia
                .map(|v| array::<3>(v, "inertia"))
                .transpose()?
                .unwrap_or([0.0; 3]),
            outer_diameter,
            displaced_area,
            drag: drag
                .map(|v| array::<2>(v, "drag"))
                .transpose()?
                .unwrap_or([0.0; 2]),
            added_mass: added_mass
                .map(|v| array::<2>(v, "added_mass"))
                .transpose()?
                .unwrap_or([0.0; 2]),
            rotational_damping: rotational_damping
                .map(|v| scalar_or_array::<3>(v, "rotational_damping"))
                .transpose()?
                .unwrap_or([0.0; 3]),
        };
        let ga = scalar_or_array::<2>(GA, "GA")?;
        let ei = scalar_or_array::<2>(EI, "EI")?;
        section::Section::new(EA, ga, GJ, ei, mass, extras)
            .map(Section)
            .map_err(to_py)
    }

    /// A pipe from its geometry (m) and material: density (kg/m³), Young's modulus (Pa), Poisson's ratio,
    /// contents density (kg/m³, adds to the mass), Morison drag and added-mass coefficients (axial, normal),
    /// the steel's grade (for the design checks), external coatings (from the steel outwards) and a lining.
    #[staticmethod]
    #[pyo3(signature = (outer_diameter, wall_thickness, density=7850.0, youngs_modulus=207e9, poisson_ratio=0.3, contents_density=0.0, drag=None, added_mass=None, *, grade=None, coatings=None, lining=None, material=None))]
    #[allow(clippy::too_many_arguments)]
    fn pipe(
        py: Python<'_>,
        outer_diameter: f64,
        wall_thickness: f64,
        density: f64,
        youngs_modulus: f64,
        poisson_ratio: f64,
        contents_density: f64,
        drag: Option<&Bound<'_, PyAny>>,
        added_mass: Option<&Bound<'_, PyAny>>,
        grade: Option<String>,
        coatings: Option<Vec<Coating>>,
        lining: Option<Coating>,
        material: Option<crate::material::Material>,
    ) -> PyResult<Self> {
        // With a material, its Young's modulus is the wall's.
        let youngs_modulus = material
            .as_ref()
            .map_or(youngs_modulus, |m| m.0.youngs_modulus);
        let drag = coefficients(drag, "drag", [0.0, 1.0])?;
        let added_mass = coefficients(added_mass, "added_mass", [0.0, 1.0])?;
        if let Some(grade) = &grade {
            check_grade(py, grade)?;
        }
        let coatings: Vec<section::Coating> =
            coatings.unwrap_or_default().iter().map(|c| c.0).collect();
        let mut pipe = section::Section::coated_pipe(
            outer_diameter,
            wall_thickness,
            density,
            youngs_modulus,
            poisson_ratio,
            contents_density,
            &coatings,
            lining.map(|l| l.0),
            drag,
            added_mass,
        )
        .map_err(to_py)?;
        if let Some(wall) = pipe.wall.as_mut() {
            wall.grade = grade;
            wall.material = material.map(|m| m.0);
        }
        Ok(Section(pipe))
    }

    /// The bending moments m₂ (N·m) of a pipe's steel wall along a path of curvatures κ₂ (1/m) from rest, at
    /// the axial strain `axial_strain`: integrated over the wall's fibres of its material (history-dependent:
    /// unloading shows the hysteresis). Linear (EI κ) for an elastic wall.
    #[pyo3(signature = (curvatures, axial_strain=0.0))]
    fn moment_curvature<'py>(
        &self,
        py: Python<'py>,
        curvatures: &Bound<'py, PyAny>,
        axial_strain: f64,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        crate::material::moment_curvature(py, &self.0, curvatures, axial_strain)
    }

    /// The steel's stress–strain law beyond yield (a Material), or None: linear elastic.
    #[getter]
    fn material(&self) -> Option<crate::material::Material> {
        self.0
            .wall
            .as_ref()
            .and_then(|w| w.material.clone())
            .map(crate::material::Material)
    }

    /// A cable (wire rope, chain) of nominal `diameter` (m), `mass` (kg/m, in air) and axial stiffness `EA`
    /// (N): tension only, no bending or torsional stiffness; its nodes have no rotation. Buoyancy area π/4 d²;
    /// drag and added-mass coefficients (axial, normal) refer to d. `damping` B (N·s, MoorDyn's BA): the
    /// axial internal damping of a taut cable, force B·ε̇ (it damps the stiff axial modes a time step cannot
    /// resolve; all its work is dissipated).
    #[staticmethod]
    #[pyo3(signature = (diameter, mass, EA, drag=None, added_mass=None, damping=0.0))]
    #[allow(non_snake_case)]
    fn cable(
        diameter: f64,
        mass: f64,
        EA: f64,
        drag: Option<&Bound<'_, PyAny>>,
        added_mass: Option<&Bound<'_, PyAny>>,
        damping: f64,
    ) -> PyResult<Self> {
        let drag = coefficients(drag, "drag", [0.0, 1.2])?;
        let added_mass = coefficients(added_mass, "added_mass", [0.0, 1.0])?;
        section::Section::cable(diameter, mass, EA, drag, added_mass)
            .and_then(|section| section.with_axial_damping(damping))
            .map(Section)
            .map_err(to_py)
    }

    /// A cable's axial internal damping B (N·s): the damping force B·ε̇ of a taut cable, its structural
    /// damping's β·EA included; 0 for rods.
    #[getter]
    fn damping(&self) -> f64 {
        self.0.cable_axial_damping()
    }

    /// This section with structural (Kelvin–Voigt) damping: `axial`, `bending` and `torsion` fractions of
    /// critical damping (-, ≥ 0) at the period `period` (s, > 0), the way MoorDyn's BA/-zeta and OrcaFlex's
    /// target damping are given. The resultants gain β C times the strain rates, β = ζ·period/π (shear with
    /// the axial ratio), so a mode of period T is damped at ζ·period/T: the stated ratio at the period, more
    /// for shorter ones. Its work is dissipated (in `Results.dissipated`). A cable takes only `axial`, which
    /// adds β·EA to its `damping`.
    #[pyo3(signature = (period, axial=0.0, bending=0.0, torsion=0.0))]
    fn with_structural_damping(
        &self,
        period: f64,
        axial: f64,
        bending: f64,
        torsion: f64,
    ) -> PyResult<Self> {
        section::StructuralDamping::new(axial, bending, torsion, period)
            .and_then(|damping| self.0.clone().with_structural_damping(damping))
            .map(Section)
            .map_err(to_py)
    }

    /// The structural damping (axial, bending, torsion fractions of critical (-), period (s)), or None.
    #[getter]
    fn structural_damping(&self) -> Option<(f64, f64, f64, f64)> {
        self.0
            .structural_damping
            .map(|d| (d.axial, d.bending, d.torsion, d.period))
    }

    /// Whether this is a cable's section (`Section.cable`): axial stiffness only.
    #[getter]
    fn is_cable(&self) -> bool {
        self.0.cable
    }

    /// Diameter over the coatings (m): drag, added mass, buoyancy, seabed contact and rollers refer to it;
    /// `outer_diameter` for a section without coatings.
    #[getter]
    fn hydrodynamic_diameter(&self) -> f64 {
        self.0.hydrodynamic_diameter
    }
    /// Submerged weight per unit length (N/m) in sea water of 1025 kg/m³ under g = 9.81 m/s²: (mass −
    /// 1025·displaced_area)·g, contents included.
    #[getter]
    fn submerged_weight(&self) -> f64 {
        (self.0.mass - SEA_WATER_DENSITY * self.0.displaced_area) * GRAVITY
    }
    /// The steel's grade of a section built by Section.pipe with one (e.g. "X65"); None otherwise.
    #[getter]
    fn grade(&self) -> Option<String> {
        self.0.wall.as_ref().and_then(|w| w.grade.clone())
    }
    /// The external coatings of a section built by Section.pipe, from the steel outwards.
    #[getter]
    fn coatings(&self) -> Vec<Coating> {
        self.0.wall.as_ref().map_or_else(Vec::new, |w| {
            w.coatings.iter().copied().map(Coating).collect()
        })
    }
    /// The internal lining of a section built by Section.pipe; None without one.
    #[getter]
    fn lining(&self) -> Option<Coating> {
        self.0.wall.as_ref().and_then(|w| w.lining).map(Coating)
    }

    /// Axial stiffness EA (N).
    #[getter(EA)]
    fn ea(&self) -> f64 {
        self.0.translational_stiffness.x
    }
    /// Shear stiffnesses (GA2, GA3) (N).
    #[getter(GA)]
    fn ga(&self) -> (f64, f64) {
        (
            self.0.translational_stiffness.y,
            self.0.translational_stiffness.z,
        )
    }
    /// Torsional stiffness GJ (N·m²).
    #[getter(GJ)]
    fn gj(&self) -> f64 {
        self.0.rotational_stiffness.x
    }
    /// Bending stiffnesses (EI2, EI3) (N·m²).
    #[getter(EI)]
    fn ei(&self) -> (f64, f64) {
        (self.0.rotational_stiffness.y, self.0.rotational_stiffness.z)
    }
    /// Mass per unit length, contents included (kg/m).
    #[getter]
    fn mass(&self) -> f64 {
        self.0.mass
    }
    /// Rotational inertia per unit length (J1, J2, J3) (kg·m).
    #[getter]
    fn inertia(&self) -> (f64, f64, f64) {
        (self.0.inertia.x, self.0.inertia.y, self.0.inertia.z)
    }
    /// Wall thickness (m) of a section built by Section.pipe; None otherwise.
    #[getter]
    fn wall_thickness(&self) -> Option<f64> {
        self.0.wall.as_ref().map(|w| w.thickness)
    }
    /// Young's modulus (Pa) of a section built by Section.pipe; None otherwise.
    #[getter]
    fn youngs_modulus(&self) -> Option<f64> {
        self.0.wall.as_ref().map(|w| w.youngs_modulus)
    }
    /// Poisson's ratio of a section built by Section.pipe; None otherwise.
    #[getter]
    fn poisson_ratio(&self) -> Option<f64> {
        self.0.wall.as_ref().map(|w| w.poisson_ratio)
    }
    /// Density of the contents (kg/m³) of a section built by Section.pipe; None otherwise.
    #[getter]
    fn contents_density(&self) -> Option<f64> {
        self.0.wall.as_ref().map(|w| w.contents_density)
    }
    /// Outer diameter (m): the steel's for a Section.pipe (coatings not included).
    #[getter]
    fn outer_diameter(&self) -> f64 {
        self.0.outer_diameter
    }
    /// Buoyancy area per unit length (m²).
    #[getter]
    fn displaced_area(&self) -> f64 {
        self.0.displaced_area
    }
    /// Morison drag coefficients (axial, normal).
    #[getter]
    fn drag(&self) -> (f64, f64) {
        (self.0.drag[0], self.0.drag[1])
    }
    /// Added-mass coefficients (axial, normal).
    #[getter]
    fn added_mass(&self) -> (f64, f64) {
        (self.0.added_mass[0], self.0.added_mass[1])
    }
    /// Rotational damping (N·m·s per m) about t1, t2, t3.
    #[getter]
    fn rotational_damping(&self) -> (f64, f64, f64) {
        let d = self.0.rotational_damping;
        (d.x, d.y, d.z)
    }

    fn __repr__(&self) -> String {
        let s = &self.0;
        if s.cable {
            return format!(
                "Section.cable(diameter={}, mass={:.4}, EA={:.4e})",
                s.outer_diameter, s.mass, s.translational_stiffness.x
            );
        }
        format!(
            "Section(EA={:.4e}, GA={:?}, GJ={:.4e}, EI={:?}, mass={:.4})",
            s.translational_stiffness.x,
            (s.translational_stiffness.y, s.translational_stiffness.z),
            s.rotational_stiffness.x,
            (s.rotational_stiffness.y, s.rotational_stiffness.z),
            s.mass
        )
    }
}

/// One segment of a line: its unstretched `length` (m), its `section` and its number of `elements`.
#[pyclass(module = "pipelay", name = "Segment", frozen, from_py_object)]
#[derive(Clone)]
pub struct Segment(pub pipelay::rod::Segment);

#[pymethods]
impl Segment {
    #[new]
    #[pyo3(signature = (length, section, elements))]
    fn new(length: f64, section: &Section, elements: i64) -> PyResult<Self> {
        // A Python int below 1 (negative ones included) is refused before it becomes a count.
        if elements < 1 {
            return Err(crate::errors::input(
                "elements",
                elements,
                "must be an integer >= 1",
            ));
        }
        let segment = pipelay::rod::Segment {
            length,
            section: section.0.clone(),
            elements: elements as usize,
        };
        segment.check("").map_err(to_py)?;
        Ok(Segment(segment))
    }
    /// Unstretched length (m).
    #[getter]
    fn length(&self) -> f64 {
        self.0.length
    }
    /// The segment's cross-section.
    #[getter]
    fn section(&self) -> Section {
        Section(self.0.section.clone())
    }
    /// Number of elements.
    #[getter]
    fn elements(&self) -> usize {
        self.0.elements
    }
    fn __repr__(&self) -> String {
        format!(
            "Segment(length={} m, elements={}, cable={})",
            self.0.length, self.0.elements, self.0.section.cable
        )
    }
}

/// A rod in its stress-free reference configuration: nodes (n + 1, 3) in m and a section.
#[pyclass(module = "pipelay", name = "Rod", frozen)]
#[derive(Clone)]
pub struct Rod(pub pipelay::rod::Rod);

#[pymethods]
impl Rod {
    #[new]
    fn new(nodes: &Bound<'_, PyAny>, section: &Section) -> PyResult<Self> {
        let nodes = points(nodes, "nodes")?;
        pipelay::rod::Rod::new(nodes, section.0.clone())
            .map(Rod)
            .map_err(to_py)
    }

    /// A straight rod of `elements` equal elements from `start` to `end` (m).
    #[staticmethod]
    fn straight(
        start: &Bound<'_, PyAny>,
        end: &Bound<'_, PyAny>,
        elements: i64,
        section: &Section,
    ) -> PyResult<Self> {
        let start = vector3(start, "start")?;
        let end = vector3(end, "end")?;
        if elements < 1 {
            return Err(crate::errors::input(
                "elements",
                elements,
                "must be an integer >= 1",
            ));
        }
        pipelay::rod::Rod::straight(start, end, elements as usize, section.0.clone())
            .map(Rod)
            .map_err(to_py)
    }

    /// Reference node positions (n + 1, 3) (m).
    #[getter]
    fn nodes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_to_numpy(py, &self.0.nodes)
    }
    /// Number of elements n.
    #[getter]
    fn elements(&self) -> usize {
        self.0.element_count()
    }
    /// Total reference length (m).
    #[getter]
    fn length(&self) -> f64 {
        self.0.length()
    }
    /// A straight line of consecutive `segments` (a list of `Segment`) from `start` (m) along `direction`,
    /// continuous at the joints.
    #[staticmethod]
    fn segments(
        start: &Bound<'_, PyAny>,
        direction: &Bound<'_, PyAny>,
        segments: Vec<Segment>,
    ) -> PyResult<Self> {
        let start = vector3(start, "start")?;
        let direction = vector3(direction, "direction")?;
        let segments: Vec<pipelay::rod::Segment> = segments.into_iter().map(|s| s.0).collect();
        pipelay::rod::Rod::segments(start, direction, &segments)
            .map(Rod)
            .map_err(to_py)
    }

    /// The cross-section of the first segment (of the whole rod for a rod of one segment).
    #[getter]
    fn section(&self) -> Section {
        Section(self.0.section(0).clone())
    }
    /// The cross-section of each segment, from end A.
    #[getter]
    fn sections(&self) -> Vec<Section> {
        self.0.sections.iter().cloned().map(Section).collect()
    }
    /// The segment index of each element (n,).
    #[getter]
    fn segment_of<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let indices: Vec<i64> = self.0.segment_of.iter().map(|&k| k as i64).collect();
        PyArray1::from_vec(py, indices)
    }

    fn __repr__(&self) -> String {
        format!(
            "Rod(elements={}, length={:.6} m)",
            self.0.element_count(),
            self.0.length()
        )
    }
}

/// A steady current; build it with `Current.uniform`, `Current.linear` or `Current.profile`.
#[pyclass(module = "pipelay", name = "Current", frozen)]
#[derive(Clone)]
pub struct Current(pub current::Current);

#[pymethods]
impl Current {
    /// The same velocity (3,) (m/s, in e) at every depth, from time `start` (s).
    #[staticmethod]
    #[pyo3(signature = (velocity, start=0.0))]
    fn uniform(velocity: &Bound<'_, PyAny>, start: f64) -> PyResult<Self> {
        let v = vector3(velocity, "velocity")?;
        current::Current::new(CurrentProfile::Uniform(v), start)
            .map(Current)
            .map_err(to_py)
    }

    /// Linear shear: `surface_velocity` (3,) (m/s) at the surface, zero at the seabed end's depth.
    #[staticmethod]
    #[pyo3(signature = (surface_velocity, start=0.0))]
    fn linear(surface_velocity: &Bound<'_, PyAny>, start: f64) -> PyResult<Self> {
        let surface = vector3(surface_velocity, "surface_velocity")?;
        current::Current::new(CurrentProfile::Linear { surface }, start)
            .map(Current)
            .map_err(to_py)
    }

    /// A table: `depths` (k,) below the surface (m, increasing) and `velocities` (k, 3) (m/s), interpolated linearly.
    #[staticmethod]
    #[pyo3(signature = (depths, velocities, start=0.0))]
    fn profile(
        depths: &Bound<'_, PyAny>,
        velocities: &Bound<'_, PyAny>,
        start: f64,
    ) -> PyResult<Self> {
        let depths = vector(depths, "depths")?;
        let velocities = points(velocities, "velocities")?;
        current::Current::new(CurrentProfile::Table { depths, velocities }, start)
            .map(Current)
            .map_err(to_py)
    }

    /// Velocity (3,) (m/s) at elevation z (m, e3 down) in a sea of the given depth, at time t (s).
    fn velocity(&self, z: f64, depth: f64, t: f64) -> (f64, f64, f64) {
        let v = self.0.velocity_and_gradient(z, depth, t).0;
        (v.x, v.y, v.z)
    }

    /// Start time (s).
    #[getter]
    fn start(&self) -> f64 {
        self.0.start
    }
}

/// Water: depth (m; the surface is z = −depth), density (kg/m³), an optional current, an optional seabed
/// (without one the pipe passes through the bottom) and optional waves.
#[pyclass(module = "pipelay", name = "Sea", frozen)]
#[derive(Clone)]
pub struct Sea(pub sea::Sea);

#[pymethods]
impl Sea {
    #[new]
    #[pyo3(signature = (depth, density=1025.0, current=None, seabed=None, waves=None, wind=None))]
    fn new(
        depth: f64,
        density: f64,
        current: Option<&Current>,
        seabed: Option<&crate::seabed::Seabed>,
        waves: Option<&crate::waves::Waves>,
        wind: Option<&crate::station_keeping::Wind>,
    ) -> PyResult<Self> {
        let sea = sea::Sea::new(
            depth,
            density,
            current.map(|c| c.0.clone()),
            seabed.map(|s| s.0.clone()),
        )
        .map_err(to_py)?;
        let sea = match wind {
            Some(w) => sea.with_wind(w.0.clone()),
            None => sea,
        };
        Ok(Sea(match waves {
            Some(w) => sea.with_waves(w.sea_state.clone()),
            None => sea,
        }))
    }
    /// The sea state, if any, resolved for this depth.
    #[getter]
    fn waves(&self) -> Option<crate::waves::Waves> {
        self.0.waves.clone().map(|sea_state| crate::waves::Waves {
            sea_state,
            depth: Some(self.0.depth),
        })
    }
    /// The wind, if any.
    #[getter]
    fn wind(&self) -> Option<crate::station_keeping::Wind> {
        self.0.wind.clone().map(crate::station_keeping::Wind)
    }
    /// Water depth (m).
    #[getter]
    fn depth(&self) -> f64 {
        self.0.depth
    }
    /// Water density (kg/m³).
    #[getter]
    fn density(&self) -> f64 {
        self.0.density
    }
    /// The current, if any.
    #[getter]
    fn current(&self) -> Option<Current> {
        self.0.current.clone().map(Current)
    }
    /// The seabed, if any.
    #[getter]
    fn seabed(&self) -> Option<crate::seabed::Seabed> {
        self.0.seabed.clone().map(crate::seabed::Seabed)
    }
}
