//! The state of the rod (and its vessel) at one time: what a step starts from and produces, and what a
//! checkpoint stores.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the integrator's own mesh (rebuilt with it at every pay-out change).
#![allow(clippy::indexing_slicing)]
use crate::assembly::assembler::Assembler;
use crate::assembly::configuration::Configuration;
use crate::error::Result;
use crate::model::Model;
use crate::response::configuration::Response;
use crate::rod::cable::gauss_point as cable_gauss_point;
use crate::rod::dynamic_element::GaussPoint;
use nalgebra::{Vector2, Vector3, Vector6};

/// The state of the rod at one time.
#[derive(Debug, Clone)]
pub struct DynamicState {
    /// Time t (s).
    pub time: f64,
    pub configuration: Configuration,
    /// Nodal velocities v_I (m/s).
    pub velocities: Vec<Vector3<f64>>,
    /// Convected (body-frame) angular velocities W_I (rad/s): Λ̇ = ΛŴ.
    pub body_angular_velocities: Vec<Vector3<f64>>,
    /// Nodal accelerations over the last step, (v_n − v_n−1)/Δt (m/s²; zero at a start), from which the next
    /// step's predictor extrapolates.
    pub accelerations: Vec<Vector3<f64>>,
    /// Gauss-point rotations and strains.
    pub gauss: Vec<GaussPoint>,
    /// The attached vessel's velocity and controller state, if any.
    pub vessel: Option<VesselMotion>,
    /// Elastic seabed-friction slip (axial, lateral) of each node (m); zero without a seabed.
    pub slips: Vec<Vector2<f64>>,
    /// An articulated stinger's hinge rates over the last step, Δφ/Δt (rad/s; zero at a start), from which the
    /// next step's predictor extrapolates.
    pub hinge_rates: Vec<f64>,
    /// Velocity of each of its sections' mass points (m/s, two per section; [`crate::vessel::stinger_sections`]).
    pub section_velocities: Vec<Vector3<f64>>,
    /// Each element's wall fibres' plastic strains ([`crate::rod::plastic_state`]; empty where its wall does
    /// not yield).
    pub plastic: Vec<Vec<f64>>,
    /// The pay-out speed of the last step (m/s; zero at rest): the tensioner's, or the winch's once it holds,
    /// from which the winch's acceleration limit counts.
    pub pay_out_speed: f64,
}

/// Velocity and controller state of an attached vessel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VesselMotion {
    /// ν = [u, v, w, p, q, r] (body frame).
    pub velocity: Vector6<f64>,
    /// ν̇ over the last step, (ν_n − ν_n−1)/Δt (zero at a start), from which the next step's predictor
    /// extrapolates the vessel's node.
    pub acceleration: Vector6<f64>,
    /// ∫η̃ dt of the PID.
    pub integral: Vector6<f64>,
    /// Thrust that holds the vessel until the controller starts (body frame): the static holding thrust of
    /// the starting configuration.
    pub hold_thrust: Vector6<f64>,
    /// Thrust applied over the last step (body frame).
    pub thrust: Vector6<f64>,
    /// The pipe's force and moment on the vessel over the last step, χ (body frame).
    pub pipe_force: Vector6<f64>,
    /// How far the lay-tension loop has moved the set-point along the reference's heading (m).
    pub setpoint_offset: f64,
    /// The lay-tension loop's filtered top tension (N).
    pub filtered_tension: f64,
    /// The passivity observer's ledger of the controller's port ([`crate::dynamics::passivity`]).
    pub passivity: crate::dynamics::passivity::PassivityLedger,
}

/// The storage E₀ (J) a certified controller starts with at `configuration` and `time`: ½η̃ᵀK_pη̃ at the vessel's
/// pose about its reference (zero without a certified controller).
fn starting_storage(model: &Model, configuration: &Configuration, time: f64) -> f64 {
    let Some(attachment) = model.vessel.as_ref() else {
        return 0.0;
    };
    let Some(controller) = attachment
        .controller
        .as_ref()
        .filter(|c| c.passivity.is_some())
    else {
        return 0.0;
    };
    let node = attachment.node;
    let (position, body) = crate::vessel::coupling::vessel_pose(
        attachment,
        &configuration.positions[node],
        &configuration.rotations[node],
    );
    let eta = crate::vessel::coupling::eta_of(&position, &body);
    controller
        .reference
        .at(time)
        .map_or(0.0, |(reference, _)| controller.storage(&eta, &reference))
}

/// The yielding elements' plastic state in `configuration` reached along a monotonic path from `starts` (each
/// element's fibres' state; None: the state at rest, [`Model::plastic_state`]: unyielded, or reeled), as statics
/// reach it; each element's empty where its wall does not yield.
fn plastic_from(
    model: &Model,
    configuration: &Configuration,
    starts: Option<&[Vec<f64>]>,
) -> Vec<Vec<f64>> {
    let elements = model.rod.element_count();
    let Some(mut state) = model.plastic_state() else {
        return vec![Vec::new(); elements];
    };
    if let Some(starts) = starts {
        state.start_from(starts);
    }
    for e in 0..elements {
        if !state.yields(e) {
            continue;
        }
        let (strain, curvature) =
            model
                .rod
                .strain_changes(e, &configuration.positions, &configuration.rotations);
        state.law(e, &strain, &curvature, 1.0);
    }
    state.end
}

impl DynamicState {
    /// The material force n^t = C_T (Γ − Γ₀) at element `element`'s Gauss point (N, section frame); its first
    /// component is the element's axial force.
    pub fn material_force(&self, model: &Model, element: usize) -> Vector3<f64> {
        model.rod.section(element).c_t()
            * (self.gauss[element].strain - model.rod.elements[element].strain)
    }

    /// Element `element`'s axial force (N): a yielding wall's from its fibres' state, else the first component
    /// of [`Self::material_force`].
    pub fn axial_force(&self, model: &Model, element: usize) -> f64 {
        let section = model.rod.section(element);
        let fibres = section
            .yields()
            .then(|| section.fibre_section()?.ok())
            .flatten()
            .filter(|fibres| fibres.state_size() == self.plastic[element].len());
        match fibres {
            Some(fibres) => {
                let (gauss, reference) = (&self.gauss[element], &model.rod.elements[element]);
                fibres
                    .resultants_and_energy(
                        &(gauss.strain - reference.strain),
                        &(gauss.curvature - reference.curvature),
                        &self.plastic[element],
                    )
                    .0
                    .x
            }
            None => self.material_force(model, element).x,
        }
    }

    /// A state at rest in `configuration` at time `time`; driven nodes move with their drive's velocity.
    pub fn at_rest(model: &Model, configuration: Configuration, time: f64) -> Result<Self> {
        Self::at_rest_from(model, configuration, time, None)
    }

    /// [`Self::at_rest`], the yielding walls reached from the plastic states `plastic` (each element's fibres';
    /// a run's, which a stage's statics start from) rather than from rest.
    pub fn at_rest_from(
        model: &Model,
        configuration: Configuration,
        time: f64,
        plastic: Option<&[Vec<f64>]>,
    ) -> Result<Self> {
        let gauss = (0..model.rod.element_count())
            .map(|e| element_gauss_point(model, &configuration, e))
            .collect();
        let mut velocities = vec![Vector3::zeros(); model.rod.node_count()];
        for support in &model.supports {
            velocities[support.node] = support.velocity(time)?;
        }
        let vessel = model.vessel.as_ref().map(|_| {
            let mut assembler = Assembler::new(model);
            if let Some(plastic) = plastic {
                assembler.start_plastic_from(plastic);
            }
            let response = Response::with_assembler(model, &configuration, &mut assembler);
            let top = response
                .section_forces
                .get(
                    model
                        .vessel
                        .as_ref()
                        .map_or(0, |v| v.node.saturating_sub(1)),
                )
                .map_or(0.0, |f| f.x);
            let held = response.vessel;
            let (hold_thrust, pipe_force) = held
                .map_or((Vector6::zeros(), Vector6::zeros()), |v| {
                    (v.thrust, v.pipe_force)
                });
            VesselMotion {
                velocity: Vector6::zeros(),
                acceleration: Vector6::zeros(),
                integral: Vector6::zeros(),
                hold_thrust,
                thrust: hold_thrust,
                pipe_force,
                setpoint_offset: 0.0,
                filtered_tension: top,
                passivity: crate::dynamics::passivity::PassivityLedger {
                    budget: starting_storage(model, &configuration, time),
                    ..Default::default()
                },
            }
        });
        Ok(DynamicState {
            time,
            slips: vec![Vector2::zeros(); model.rod.node_count()],
            body_angular_velocities: vec![Vector3::zeros(); model.rod.node_count()],
            accelerations: vec![Vector3::zeros(); model.rod.node_count()],
            plastic: plastic_from(model, &configuration, plastic),
            hinge_rates: vec![0.0; model.hinge_count()],
            section_velocities: vec![Vector3::zeros(); 2 * model.hinge_count()],
            pay_out_speed: 0.0,
            configuration,
            velocities,
            gauss,
            vessel,
        })
    }

    /// The same state with the seabed friction's elastic slips `slips` (one per node; e.g. those of a static
    /// solution).
    pub fn with_slips(mut self, slips: &[Vector2<f64>]) -> Self {
        if slips.len() == self.slips.len() {
            self.slips.copy_from_slice(slips);
        }
        self
    }

    /// Spatial angular velocities w_I = Λ_I W_I (rad/s).
    pub fn angular_velocities(&self) -> Vec<Vector3<f64>> {
        self.configuration
            .rotations
            .iter()
            .zip(&self.body_angular_velocities)
            .map(|(q, w)| q * w)
            .collect()
    }
}

/// The Gauss point of element `element` of `config`: the objective element's for a rod, the chord's strain
/// for a cable.
pub fn element_gauss_point(model: &Model, config: &Configuration, element: usize) -> GaussPoint {
    let (a, b) = (element, element + 1);
    let reference = &model.rod.elements[element];
    if model.rod.section(element).cable {
        return cable_gauss_point(
            &(config.positions[b] - config.positions[a]),
            reference.length,
        );
    }
    GaussPoint::from_configuration(
        &config.positions[a],
        &config.positions[b],
        &config.rotations[a],
        &config.rotations[b],
        reference,
    )
}
