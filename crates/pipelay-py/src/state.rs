//! Python class State: one configuration of a model and what follows from it.
use crate::convert::{matrices_to_numpy, points_to_numpy, to_numpy};
use crate::errors::input;
use nalgebra::{Matrix3, Vector2, Vector3, Vector6};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pipelay::assembly::configuration::Configuration;
use pipelay::contact::touchdown::Touchdown;
use pipelay::dynamics::integrator::Integrator;
use pipelay::dynamics::ledger::Energy;
use pipelay::dynamics::state::DynamicState;
use pipelay::model::Model;
use pipelay::response::configuration::Response;
use pipelay::response::lay_summary::{
    element_strains, lay_summary, roller_lines, roller_tops, section_lines, LaySummary,
    RollerContacts, LAY_FIELDS,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Seabed contact of a state.
struct SeabedState {
    forces: Vec<Vector3<f64>>,
    touchdown: Touchdown,
    slips: Vec<Vector2<f64>>,
}

/// A configuration of the model and what follows from it (SI units, frame e).
#[pyclass(module = "pipelay", name = "State", frozen)]
pub struct State {
    configuration: Configuration,
    velocities: Vec<Vector3<f64>>,
    angular_velocities: Vec<Vector3<f64>>,
    section_forces: Vec<Vector6<f64>>,
    reactions: Vec<Vector6<f64>>,
    energy: Energy,
    /// With a vessel: η, ν, τ and χ (6,) each.
    vessel: Option<[Vector6<f64>; 4]>,
    /// The integrator's own state (Gauss points included), when the state comes from a simulation.
    dynamic: Option<DynamicState>,
    /// With a seabed: its force on each node, the touchdown and the friction slips.
    seabed: Option<SeabedState>,
    /// What each attachment applies to the line: weight less buoyancy and drag (N, in e).
    attachment_forces: Vec<Vector3<f64>>,
    /// What lay engineers read: strain per element, roller forces, the lay summary; and the section and sea
    /// that design checks need.
    lay: LayState,
    /// Where a wall yields (statics): each element's largest plastic strain and residual curvature.
    plastic: Option<pipelay::response::configuration::PlasticResponse>,
    /// Time (s): 0 for static states.
    #[pyo3(get)]
    time: f64,
    /// Load factor reached (1.0 for a converged static state, 0.0 for `Model.rest()`).
    #[pyo3(get)]
    load_factor: f64,
    /// Newton iterations spent (static: all load steps; simulation: the last step).
    #[pyo3(get)]
    iterations: usize,
    /// Accepted load steps (static states).
    #[pyo3(get)]
    steps: usize,
}

/// The lay quantities of a state.
struct LayState {
    strain: Vec<f64>,
    roller_forces: Option<Vec<f64>>,
    /// Each roller's force on the pipe (body frame, N) and its contact's offset along it (m; NaN: none).
    roller_vectors: Option<(Vec<Vector3<f64>>, Vec<f64>)>,
    /// The support (lone roller or box) of each roller.
    roller_supports: Vec<usize>,
    summary: Option<LaySummary>,
    /// The sections of the line's segments, and the segment of each element.
    sections: Vec<pipelay::rod::section::Section>,
    segment_of: Vec<usize>,
    /// The rollers' top points in e (m).
    roller_tops: Vec<Vector3<f64>>,
    /// The ends of each roller's top line in e (m).
    roller_lines: Vec<[Vector3<f64>; 2]>,
    /// An articulated stinger's sections: each one's hinge and far end (in e, m).
    section_lines: Vec<[Vector3<f64>; 2]>,
    /// Each node's arc length from end A along the reference (m).
    arc_length: Vec<f64>,
    /// Water depth and density (m, kg/m³), with a sea.
    water: Option<(f64, f64)>,
}

impl LayState {
    /// From a configuration's section forces, its rollers' forces and its lay summary.
    fn new(
        model: &Model,
        configuration: &Configuration,
        section_forces: &[Vector6<f64>],
        roller_forces: Option<&[f64]>,
        roller_vectors: Option<(&[Vector3<f64>], &[f64])>,
        summary: Option<LaySummary>,
    ) -> Self {
        let rod = &model.rod;
        LayState {
            strain: element_strains(
                model,
                &configuration.positions,
                &configuration.rotations,
                section_forces,
            ),
            roller_forces: roller_forces.map(<[f64]>::to_vec),
            roller_vectors: roller_vectors.map(|(v, o)| (v.to_vec(), o.to_vec())),
            roller_supports: model
                .vessel
                .as_ref()
                .map(|a| a.rollers().iter().map(|r| r.support).collect())
                .unwrap_or_default(),
            summary,
            sections: rod.sections.clone(),
            segment_of: rod.segment_of.clone(),
            roller_tops: roller_tops(
                model,
                &configuration.positions,
                &configuration.rotations,
                &configuration.hinge_angles,
            ),
            section_lines: section_lines(
                model,
                &configuration.positions,
                &configuration.rotations,
                &configuration.hinge_angles,
            ),
            roller_lines: roller_lines(
                model,
                &configuration.positions,
                &configuration.rotations,
                &configuration.hinge_angles,
            ),
            arc_length: model.rod.arc_lengths(),
            water: model.sea.as_ref().map(|sea| (sea.depth, sea.density)),
        }
    }
}

/// An articulated stinger's sections' energy at rest in `configuration` (J; 0 without): weight less buoyancy's
/// potential and the hinges'.
fn stinger_energy_at_rest(model: &Model, configuration: &Configuration) -> f64 {
    let Some(attachment) = &model.vessel else {
        return 0.0;
    };
    let count = model.rod.node_count();
    pipelay::vessel::stinger_sections::StingerSections::new(attachment, count, model.gravity)
        .map_or(0.0, |sections| {
            let node = attachment.node;
            sections.energy(
                &configuration.positions[node],
                &configuration.rotations[node],
                &configuration.hinge_angles,
                &vec![Vector3::zeros(); sections.point_count()],
            )
        })
}

impl State {
    /// A static state (at rest).
    pub fn from_static(
        model: &Model,
        configuration: Configuration,
        response: &Response,
        load_factor: f64,
        iterations: usize,
        steps: usize,
    ) -> Self {
        let count = model.rod.node_count();
        let rollers = response.rollers.as_ref().map(|r| RollerContacts {
            forces: &r.forces,
            elements: &r.elements,
            offsets: &r.offsets,
        });
        let summary = lay_summary(
            model,
            &configuration.positions,
            &configuration.rotations,
            &configuration.hinge_angles,
            &response.section_forces,
            rollers,
            response.seabed.as_ref().map(|s| &s.touchdown),
            response.plastic.as_ref().map(|p| &p.residual_curvature[..]),
        );
        let lay = LayState::new(
            model,
            &configuration,
            &response.section_forces,
            rollers.map(|r| r.forces),
            response
                .rollers
                .as_ref()
                .map(|r| (&r.reactions[..], &r.offsets[..])),
            summary,
        );
        let stinger = stinger_energy_at_rest(model, &configuration);
        State {
            lay,
            attachment_forces: model.attachment_forces(&configuration.positions, None, 0.0),
            configuration,
            velocities: vec![Vector3::zeros(); count],
            angular_velocities: vec![Vector3::zeros(); count],
            section_forces: response.section_forces.clone(),
            reactions: response.nodal_reactions.clone(),
            energy: Energy {
                kinetic: 0.0,
                strain: response.strain_energy,
                gravity: response.gravity_energy,
                vessel_kinetic: 0.0,
                vessel_potential: response.vessel.map_or(0.0, |v| v.restoring_energy),
                seabed: response.seabed.as_ref().map_or(0.0, |s| s.energy),
                rollers: response.rollers.as_ref().map_or(0.0, |r| r.energy),
                stinger,
            },
            plastic: response.plastic.clone(),
            seabed: response.seabed.as_ref().map(|s| SeabedState {
                forces: s.forces.clone(),
                touchdown: s.touchdown,
                slips: s.slips.clone(),
            }),
            vessel: response
                .vessel
                .map(|v| [v.eta, Vector6::zeros(), v.thrust, v.pipe_force]),
            dynamic: None,
            time: 0.0,
            load_factor,
            iterations,
            steps,
        }
    }

    /// The current state of a simulation.
    pub fn from_integrator(integrator: &Integrator, iterations: usize) -> Self {
        let state = integrator.state();
        let observables = integrator.observe();
        let section_forces = observables.section_forces();
        let lay = LayState::new(
            integrator.model(),
            &state.configuration,
            &section_forces,
            observables.roller_forces(),
            observables.roller_reactions(),
            observables.lay_summary(&section_forces),
        );
        State {
            lay,
            attachment_forces: integrator.model().attachment_forces(
                &state.configuration.positions,
                Some(&state.velocities),
                state.time,
            ),
            configuration: state.configuration.clone(),
            velocities: state.velocities.clone(),
            angular_velocities: state.angular_velocities(),
            section_forces,
            reactions: integrator.reactions().to_vec(),
            energy: observables.energy(),
            vessel: observables.vessel_values(),
            // A yielding wall's plastic strain and residual curvature from the run's plastic state.
            plastic: pipelay::response::configuration::plastic_field(
                integrator.model(),
                &state.configuration.positions,
                &state.configuration.rotations,
                None,
                Some(&state.plastic),
            ),
            seabed: match (observables.seabed_forces(), observables.touchdown()) {
                (Some(forces), Some(touchdown)) => Some(SeabedState {
                    forces: forces.to_vec(),
                    touchdown,
                    slips: state.slips.clone(),
                }),
                _ => None,
            },
            dynamic: Some(state.clone()),
            time: state.time,
            load_factor: 1.0,
            iterations,
            steps: 0,
        }
    }

    /// The state as the integrator's starting point.
    pub fn dynamic_state(&self, model: &Model) -> pipelay::Result<DynamicState> {
        if self.configuration.positions.len() != model.rod.node_count() {
            return Err(pipelay::Error::input(
                "state",
                format!("a state of {} nodes", self.configuration.positions.len()),
                format!(
                    "must belong to this model ({} nodes)",
                    model.rod.node_count()
                ),
            ));
        }
        match &self.dynamic {
            Some(state) => Ok(state.clone()),
            None => {
                DynamicState::at_rest(model, self.configuration.clone(), self.time).map(|state| {
                    match &self.seabed {
                        Some(seabed) => state.with_slips(&seabed.slips),
                        None => state,
                    }
                })
            }
        }
    }

    fn end_node(&self, end: &str) -> PyResult<usize> {
        match end {
            "A" => Ok(0),
            "B" => Ok(self.configuration.positions.len() - 1),
            other => Err(input(
                "end",
                format!("{other:?}"),
                "must be \"A\" (node 0) or \"B\" (node n)",
            )),
        }
    }
}

/// The energy dictionary of API.md.
fn energy_dict<'py>(py: Python<'py>, energy: &Energy) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("pipe_kinetic", energy.kinetic)?;
    dict.set_item("pipe_strain", energy.strain)?;
    dict.set_item("pipe_gravity", energy.gravity)?;
    dict.set_item("vessel_kinetic", energy.vessel_kinetic)?;
    dict.set_item("vessel_potential", energy.vessel_potential)?;
    dict.set_item("seabed", energy.seabed)?;
    dict.set_item("rollers", energy.rollers)?;
    dict.set_item("stinger", energy.stinger)?;
    dict.set_item("total", energy.total())?;
    Ok(dict)
}

#[pymethods]
impl State {
    /// Node positions (n + 1, 3) (m).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_to_numpy(py, &self.configuration.positions)
    }
    /// Nodal rotations R_t^e (n + 1, 3, 3).
    #[getter]
    fn rotations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let matrices: Vec<Matrix3<f64>> = self
            .configuration
            .rotations
            .iter()
            .map(|q| q.to_rotation_matrix().into_inner())
            .collect();
        matrices_to_numpy(py, &matrices)
    }
    /// Nodal velocities (n + 1, 3) (m/s).
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_to_numpy(py, &self.velocities)
    }
    /// Spatial angular velocities (n + 1, 3) (rad/s).
    #[getter]
    fn angular_velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_to_numpy(py, &self.angular_velocities)
    }
    /// Material-frame force (N) and moment (N·m) at element midpoints (n, 6): [N1, N2, N3, M1, M2, M3].
    #[getter]
    fn section_forces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let rows: Vec<Vec<f64>> = self
            .section_forces
            .iter()
            .map(|f| f.as_slice().to_vec())
            .collect();
        PyArray2::from_vec2(py, &rows).expect("rows of six")
    }
    /// Axial force N1 at element midpoints (n,) (N), positive in tension.
    #[getter]
    fn tension<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let tension: Vec<f64> = self.section_forces.iter().map(|f| f[0]).collect();
        to_numpy(py, &tension)
    }
    /// Force (N) and moment (N·m) (6,) the rod exerts on the support at end "A" or "B", in e; at a vessel's end,
    /// on the vessel (`chi` is the same in the body frame).
    fn reaction<'py>(&self, py: Python<'py>, end: &str) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let node = self.end_node(end)?;
        Ok(to_numpy(py, self.reactions[node].as_slice()))
    }
    /// Vessel pose η = [x, y, z, φ, θ, ψ] (6,) in e (m, rad): None without a vessel.
    #[getter]
    fn eta<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.vessel.as_ref().map(|v| to_numpy(py, v[0].as_slice()))
    }
    /// Vessel velocity ν (6,), body frame (m/s, rad/s): None without a vessel.
    #[getter]
    fn nu<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.vessel.as_ref().map(|v| to_numpy(py, v[1].as_slice()))
    }
    /// Thrust τ (6,), body frame (N, N·m); in statics the holding thrust: None without a vessel.
    #[getter]
    fn tau<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.vessel.as_ref().map(|v| to_numpy(py, v[2].as_slice()))
    }
    /// The pipe's force and moment on the vessel χ (6,), body frame (N, N·m): None without a vessel.
    #[getter]
    fn chi<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.vessel.as_ref().map(|v| to_numpy(py, v[3].as_slice()))
    }
    /// Where the pipe leaves the seabed, seen from end A (a pl.Touchdown), or None: no seabed, or no contact.
    #[getter]
    fn touchdown(&self) -> Option<crate::seabed::Touchdown> {
        let (arc, position) = self.seabed.as_ref()?.touchdown.point?;
        Some(crate::seabed::Touchdown::new(arc, position))
    }
    /// The seabed's force on each node (n + 1, 3) (N, in e): normal, friction and damping; None without a seabed.
    #[getter]
    fn seabed_reaction<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.seabed.as_ref().map(|s| points_to_numpy(py, &s.forces))
    }
    /// What each attachment applies to the line (k, 3) (N, in e): its weight less its buoyancy and its drag
    /// in the current (on its velocity in a simulation's state); (0, 3) without attachments.
    #[getter]
    fn attachment_forces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        if self.attachment_forces.is_empty() {
            return PyArray2::zeros(py, [0, 3], false);
        }
        points_to_numpy(py, &self.attachment_forces)
    }
    /// Reference length of pipe resting on the seabed (m); None without a seabed.
    #[getter]
    fn laid_length(&self) -> Option<f64> {
        self.seabed.as_ref().map(|s| s.touchdown.laid_length)
    }
    /// Largest longitudinal strain in each element (n,): axial plus bending at the outer fibre (−).
    #[getter]
    fn strain<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, &self.lay.strain)
    }
    /// Normal force of each roller (k,) (N, ≥ 0; 0: lifted off); None without rollers.
    #[getter]
    fn roller_reactions<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.lay.roller_forces.as_ref().map(|f| to_numpy(py, f))
    }
    /// Each roller's force on the pipe (k, 3) in the vessel's body frame (forward, starboard, down; N): its
    /// vertical part is −[:, 2], its lateral part [:, 1]; its length is roller_reactions. None without
    /// rollers.
    #[getter]
    fn roller_reaction_vectors<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        let (vectors, _) = self.lay.roller_vectors.as_ref()?;
        Some(crate::convert::points_to_numpy(py, vectors))
    }
    /// Where each roller's contact lies along it (k,): from the roller's centre along its axis (m; NaN out
    /// of contact). None without rollers.
    #[getter]
    fn roller_offsets<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        let (_, offsets) = self.lay.roller_vectors.as_ref()?;
        Some(to_numpy(py, offsets))
    }
    /// The support of each roller (k,): the 0-based index of its lone roller or roller box along the
    /// stinger (for a stinger of lone rollers, 0 … k − 1). Empty without rollers.
    #[getter]
    fn roller_supports(&self) -> Vec<usize> {
        self.lay.roller_supports.clone()
    }
    /// The lay summary (dict; SI units, angles in rad): top_tension (N, at the hold point), departure_angle
    /// (below the horizontal where the pipe leaves the equipment), liftoff_roller (the 0-based index of the
    /// last support in contact, a lone roller or a roller box, as in roller_supports, or None; people read
    /// rollers numbered from 1),
    /// liftoff_arc_length, inflection_arc_length (the steepest point, where the overbend meets the sagbend),
    /// layback (horizontal, hold point to touchdown; NaN without one), touchdown_arc_length, overbend_strain
    /// (largest, hold point to inflection), sagbend_strain and sagbend_moment (largest, inflection to
    /// touchdown), tip_clearance (m, the pipe to the stinger's last support; NaN without rollers),
    /// tip_offset, boxes_left, residual_curvature (1/m, the laid pipe's largest, from its history through the
    /// lay; NaN where no wall yields). None without a vessel.
    fn lay_summary<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(summary) = &self.lay.summary else {
            return Ok(None);
        };
        let dict = PyDict::new(py);
        for (name, value) in LAY_FIELDS.iter().zip(summary.values()) {
            dict.set_item(name, value)?;
        }
        dict.set_item("liftoff_roller", summary.liftoff_roller)?;
        Ok(Some(dict))
    }
    /// The rollers' top points (k, 3) in e (m), where the vessel holds them in this state; None without rollers.
    #[getter]
    fn roller_positions<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.lay
            .roller_forces
            .as_ref()
            .map(|_| points_to_numpy(py, &self.lay.roller_tops))
    }
    /// Each element's largest plastic strain over its steel wall (n,) (0 where elastic): where a section's
    /// material yields (`Section.pipe(..., material=)`); None without one.
    #[getter]
    fn plastic_strain<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.plastic
            .as_ref()
            .map(|p| to_numpy(py, &p.plastic_strain))
    }
    /// Each element's residual curvature (n,) (1/m): the bending curvature it would keep unloaded
    /// elastically, |κ − m/EI|; None without a yielding wall.
    #[getter]
    fn residual_curvature<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.plastic
            .as_ref()
            .map(|p| to_numpy(py, &p.residual_curvature))
    }
    /// An articulated stinger's hinge angles (h,) (rad; positive: a section's aft end turned down from the
    /// stinger's arc). Empty without.
    #[getter]
    fn hinge_angles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, &self.configuration.hinge_angles)
    }
    /// An articulated stinger's sections (h, 2, 3) in e (m): each section's hinge and far end on the
    /// stinger's top line. None unless articulated.
    #[getter]
    fn section_lines<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        if self.lay.section_lines.is_empty() {
            return Ok(None);
        }
        let flat: Vec<f64> = self
            .lay
            .section_lines
            .iter()
            .flat_map(|ends| ends.iter().flat_map(|p| [p.x, p.y, p.z]))
            .collect();
        let count = self.lay.section_lines.len();
        Ok(Some(
            PyArray1::from_vec(py, flat)
                .reshape([count, 2, 3])?
                .into_any(),
        ))
    }
    /// The ends of each roller's top line (k, 2, 3) in e (m): a box's roller's line, its length long, where the
    /// pipe rests on it; a lone (endless) roller's top point twice. None without rollers.
    #[getter]
    fn roller_lines<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        if self.lay.roller_forces.is_none() {
            return Ok(None);
        }
        let flat: Vec<f64> = self
            .lay
            .roller_lines
            .iter()
            .flat_map(|ends| ends.iter().flat_map(|p| [p.x, p.y, p.z]))
            .collect();
        let count = self.lay.roller_lines.len();
        Ok(Some(
            PyArray1::from_vec(py, flat)
                .reshape([count, 2, 3])?
                .into_any(),
        ))
    }
    /// Each node's arc length from end A along the stress-free reference (n + 1,) (m).
    #[getter]
    fn reference_arc_length<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, &self.lay.arc_length)
    }
    /// The model's cross-section: its first segment's (the whole line's for a line of one segment).
    #[getter]
    fn section(&self) -> crate::structure::Section {
        crate::structure::Section(self.lay.sections[0].clone())
    }
    /// The cross-section of each segment of the line, from end A.
    #[getter]
    fn sections(&self) -> Vec<crate::structure::Section> {
        self.lay
            .sections
            .iter()
            .cloned()
            .map(crate::structure::Section)
            .collect()
    }
    /// The segment index of each element (n,).
    #[getter]
    fn segment_of<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let indices: Vec<i64> = self.lay.segment_of.iter().map(|&k| k as i64).collect();
        PyArray1::from_vec(py, indices)
    }
    /// The sea's depth (m), None without a sea.
    #[getter]
    fn water_depth(&self) -> Option<f64> {
        self.lay.water.map(|w| w.0)
    }
    /// The sea's density (kg/m³), None without a sea.
    #[getter]
    fn water_density(&self) -> Option<f64> {
        self.lay.water.map(|w| w.1)
    }
    /// Energy parts (J): pipe_kinetic, pipe_strain, pipe_gravity, vessel_kinetic, vessel_potential, seabed,
    /// rollers, total.
    fn energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        energy_dict(py, &self.energy)
    }

    fn __repr__(&self) -> String {
        format!(
            "State(nodes={}, time={}, load_factor={}, iterations={}, steps={})",
            self.configuration.positions.len(),
            self.time,
            self.load_factor,
            self.iterations,
            self.steps
        )
    }
}
