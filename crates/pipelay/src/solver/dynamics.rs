//! Time integration of the rod: the energy–momentum conserving scheme of Simo, Tarnow & Doblaré (1995)
//! with Simo & Wong's midpoint rule in the Lie algebra for the nodal rotations (formulary
//! `numerics/rod-dynamics.md` §1–§5).
//!
//! Unknowns of a step: nodal displacement increments Δφ_I and Cayley rotation increments θ_I
//! (Λ_{n+1} = cay(θ)Λ_n). Velocities follow the midpoint rule v_{n+1} = 2Δφ/Δt − v_n and
//! W_{n+1} = 2Λ_nᵀθ/Δt − W_n; inertia is lumped at the nodes and balanced in spatial momentum. Loads
//! enter at the step midpoint and are work-conjugate to (Δφ, θ), so each converged step satisfies
//! E_{n+1} − E_n = supplied work − dissipation exactly, with
//! - supplied: point loads, driven supports, the current's share of the drag (Δt F·U);
//! - dissipated: drag on the relative velocity (Δt ℓ(k_a|u_t|³ + k_n|u_n|³) ≥ 0) and rotational damping
//!   (θ·c θ/Δt ≥ 0).
//!
//! Added mass is isotropic here: C_a,normal ρ_w π/4 d_o² added to the translational mass per length in
//! every direction (keeps the mass constant and the scheme exactly energy–momentum; over-estimates the
//! axial added mass of a pipe).
// Indexing cannot go out of bounds here: Node, element and DOF indices of the integrator's own mesh (rebuilt with it at every pay-out change).
#![allow(clippy::indexing_slicing)]
use crate::environment::waves::Kinematics;
use crate::error::{positive, Error, Result};
use crate::model::Model;
use crate::rod::dynamic_element::{GaussPoint, StressRule};
use crate::rod::element::ElementReference;
use crate::so3::{cayley, cayley_parameter, cayley_quaternion, cayley_tangent};
use crate::solver::assembly::{Assembler, Configuration, NODE_DOFS};
use crate::solver::contact::{
    ContactRule, NodeStep, SeabedContact, Touchdown, PARALLEL_NODES as PARALLEL_CONTACT_NODES,
};
pub use crate::solver::energy::Energy;
use crate::solver::history::{History, Snapshot};
use crate::solver::pay_out::{self, MeshChange};
use crate::solver::pool;
use crate::solver::rod_step::{
    ElementOutputs, ElementWork, NodeStart, RodConstants, RodStep, SERIAL_RUN,
};
use crate::vessel::control::{clamp_integral, shifted};
use crate::vessel::coupling::{
    low_frequency_pose, pipe_force_on_vessel, DynamicVessel, VesselContribution,
};
use crate::vessel::wave_motion::{station, WaveMotion, WaveOffset};
use nalgebra::{Matrix3, Vector2, Vector3, Vector6};
use rayon::prelude::*;

/// Largest residual ratio at which a Newton iteration keeps an earlier iterate's factorisation (simplified
/// Newton); a slower fall refreshes the tangent.
const SIMPLIFIED_RATE: f64 = 0.1;

/// Largest relative residual (residual over the force scale) at an iterate whose block-tridiagonal
/// factorisation later iterations may reuse. Over a correction the forces, hence the tangent, change by about
/// that relative amount, which is the contraction a simplified iteration then achieves: on the driven hanging
/// line at n = 1000 the predictor's relative residual is 0.1–0.4 and the simplified correction after it cut
/// the residual by only 0.3–0.4 (0.01: 2.9 ms per step; 1: 4.0 ms). Where the factorisation is the bordered
/// or sparse one (rollers), several times an assembly's cost, a simplified correction is always tried first:
/// the S-lay example at n = 1000 takes 7.5 ms per step so, 11.1 ms with 0.01.
const REUSE_BELOW: f64 = 0.01;

/// Fraction of the tolerance below which a converged iterate needs no polishing correction.
const POLISHED_BELOW: f64 = 1e-2;

/// How many times a step may be halved when Newton fails in it.
pub const MAX_HALVINGS: usize = 4;

/// Settings of the integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicOptions {
    /// Time step Δt (s).
    pub time_step: f64,
    /// Relative residual tolerance of Newton's method.
    pub tolerance: f64,
    /// Newton iterations allowed per step.
    pub max_iterations: usize,
    /// Stress evaluation: average strain (energy–momentum) or midpoint configuration (plain midpoint).
    pub stress_rule: StressRule,
}

impl Default for DynamicOptions {
    fn default() -> Self {
        DynamicOptions {
            time_step: 0.05,
            tolerance: 1e-10,
            max_iterations: 25,
            stress_rule: StressRule::AverageStrain,
        }
    }
}

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
}

/// Velocity and controller state of an attached vessel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VesselMotion {
    /// ν = [u, v, w, p, q, r] (body frame).
    pub velocity: Vector6<f64>,
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
}

impl DynamicState {
    /// A state at rest in `configuration` at time `time`; driven nodes move with their drive's velocity.
    pub fn at_rest(model: &Model, configuration: Configuration, time: f64) -> Result<Self> {
        let gauss = model
            .rod
            .elements
            .iter()
            .enumerate()
            .map(|(e, reference)| {
                GaussPoint::from_configuration(
                    &configuration.positions[e],
                    &configuration.positions[e + 1],
                    &configuration.rotations[e],
                    &configuration.rotations[e + 1],
                    reference,
                )
            })
            .collect();
        let mut velocities = vec![Vector3::zeros(); model.rod.node_count()];
        for support in &model.supports {
            velocities[support.node] = support.velocity(time)?;
        }
        let vessel = model.vessel.as_ref().map(|_| {
            let response = crate::solver::response::Response::new(model, &configuration);
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
                integral: Vector6::zeros(),
                hold_thrust,
                thrust: hold_thrust,
                pipe_force,
                setpoint_offset: 0.0,
                filtered_tension: top,
            }
        });
        Ok(DynamicState {
            time,
            slips: vec![Vector2::zeros(); model.rod.node_count()],
            body_angular_velocities: vec![Vector3::zeros(); model.rod.node_count()],
            accelerations: vec![Vector3::zeros(); model.rod.node_count()],
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

/// What one step took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepReport {
    pub iterations: usize,
    /// Final residual norm over the free DOFs.
    pub residual: f64,
}

/// Work and dissipation of the last step's loads (J).
#[derive(Debug, Clone, Copy, Default)]
struct StepWork {
    supplied: f64,
    dissipated: f64,
}

/// Nodal (lumped) inertia and damping of the rod.
#[derive(Debug, Clone)]
struct NodalProperties {
    /// Translational mass, added mass included (kg).
    mass: Vec<f64>,
    /// Rotational inertia about the material axes (kg·m²).
    inertia: Vec<Vector3<f64>>,
    /// Rotational damping about the material axes (N·m·s).
    damping: Vec<Vector3<f64>>,
}

/// What node `node`'s inertia and damping terms need from the step's start.
fn node_start(nodal: &NodalProperties, state: &DynamicState, node: usize) -> NodeStart {
    let rotation = state.configuration.rotations[node]
        .to_rotation_matrix()
        .into_inner();
    let spatial = |d: &Vector3<f64>| rotation * Matrix3::from_diagonal(d) * rotation.transpose();
    NodeStart {
        inertia: spatial(&nodal.inertia[node]),
        momentum: rotation
            * nodal.inertia[node].component_mul(&state.body_angular_velocities[node]),
        damping: spatial(&nodal.damping[node]),
    }
}

/// The element that grows with pay-out in the current step.
#[derive(Debug, Clone, Copy)]
struct Growth {
    element: usize,
    /// Its reference length at the step's start (m); the model holds the length at the step's end.
    length_start: f64,
    /// Work of its internal forces over the step (J).
    internal_work: f64,
    /// The pay-out speed over the step (m/s).
    speed: f64,
}

impl NodalProperties {
    /// Added mass per unit length (kg/m).
    fn added_mass(model: &Model) -> f64 {
        let section = &model.rod.section;
        model.sea.as_ref().map_or(0.0, |sea| {
            section.added_mass[1]
                * sea.density
                * std::f64::consts::FRAC_PI_4
                * section.outer_diameter.powi(2)
        })
    }

    /// Recomputes the lumps of `node` from the lengths of its elements.
    fn recompute(&mut self, model: &Model, node: usize) {
        let section = &model.rod.section;
        let elements = &model.rod.elements;
        let tributary = 0.5
            * (node.checked_sub(1).map_or(0.0, |e| elements[e].length)
                + elements.get(node).map_or(0.0, |e| e.length));
        self.mass[node] = tributary * (section.mass + Self::added_mass(model));
        self.inertia[node] = tributary * section.inertia;
        self.damping[node] = tributary * section.rotational_damping;
    }

    fn new(model: &Model) -> Self {
        let section = &model.rod.section;
        let added = Self::added_mass(model);
        let count = model.rod.node_count();
        let mut props = NodalProperties {
            mass: vec![0.0; count],
            inertia: vec![Vector3::zeros(); count],
            damping: vec![Vector3::zeros(); count],
        };
        for (e, reference) in model.rod.elements.iter().enumerate() {
            let half = 0.5 * reference.length;
            for node in [e, e + 1] {
                props.mass[node] += half * (section.mass + added);
                props.inertia[node] += half * section.inertia;
                props.damping[node] += half * section.rotational_damping;
            }
        }
        props
    }
}

/// The vessel's wave-frequency motion and its offsets at the state's time and at the current step's end.
#[derive(Debug, Clone)]
struct VesselWaves {
    motion: WaveMotion,
    now: WaveOffset,
    next: WaveOffset,
}

impl VesselWaves {
    /// The motion of the vessel of `model` in its sea, if both exist and the vessel has RAOs, at time t.
    fn new(model: &Model, time: f64) -> Result<Option<Self>> {
        let (Some(field), Some(attachment)) = (&model.waves, &model.vessel) else {
            return Ok(None);
        };
        let Some(raos) = &attachment.vessel.raos else {
            return Ok(None);
        };
        let motion = WaveMotion::new(field, raos)?;
        let now = motion.offset(time, &station(attachment, time)?)?;
        Ok(Some(VesselWaves {
            motion,
            now,
            next: now,
        }))
    }
}

/// Advances a model in time.
pub struct Integrator {
    model: Model,
    options: DynamicOptions,
    assembler: Assembler,
    state: DynamicState,
    nodal: NodalProperties,
    /// Each node's inertia and damping at the current step's start.
    node_start: Vec<NodeStart>,
    /// The waves' kinematics at each element's midpoint in the current step (at the predictor), as far as
    /// computed.
    wave_kinematics: Vec<Kinematics>,
    /// Unknowns of the current step on all DOFs: [Δφ_I, θ_I].
    increments: Vec<f64>,
    /// Newton correction on the free DOFs.
    correction: Vec<f64>,
    /// Σ|terms| per DOF, the scale of the residual.
    magnitude: Vec<f64>,
    next_gauss: Vec<GaussPoint>,
    /// Elements and nodes the rod's assembly takes in one run (see [`crate::solver::rod_step`]).
    serial_run: usize,
    /// Each element's and each node's energy terms in the last assembly (J).
    element_work: Vec<ElementWork>,
    node_dissipation: Vec<f64>,
    work: StepWork,
    supplied_work: f64,
    dissipated: f64,
    /// Force and moment the rod exerts on each node's support at the last step (N, N·m).
    reactions: Vec<Vector6<f64>>,
    /// Round-off floor of the residual norm (N): internal forces carry errors of about 1e-16·EA per element,
    /// a vessel's restoring about 1e-16·G.
    round_off: f64,
    /// The vessel's part of the last assembly.
    vessel_step: Option<VesselContribution>,
    /// The rod's force on the vessel node in the last assembly (spatial).
    rod_force_at_vessel: Vector6<f64>,
    /// The controller's reference pose and rate at the current step's midpoint.
    reference_mid: (Vector6<f64>, Vector6<f64>),
    /// The lay-tension loop's set-point offset and filtered tension at the end of the current step (m, N).
    offset_next: f64,
    filtered_next: f64,
    /// Seabed contact, if the model has a seabed.
    contact: Option<SeabedContact>,
    /// With pay-out: the growing element in the current step.
    growth: Option<Growth>,
    /// In waves, with a vessel that has RAOs: its wave-frequency motion.
    vessel_waves: Option<VesselWaves>,
    /// Energy pay-out has brought in since the start (J): the work of the tensioner on the pipe it holds plus
    /// the energy of the pipe it adds, and the energy change of mesh changes.
    pay_out_energy: f64,
}

/// Round-off floor of the residual norm (N): internal forces carry errors of about 1e-16·EA per element, a
/// vessel's restoring about 1e-16·G.
fn round_off(model: &Model) -> f64 {
    1e-13
        * (model.rod.section.translational_stiffness.max()
            * (model.rod.element_count() as f64).sqrt()
            + model
                .vessel
                .as_ref()
                .map_or(0.0, |v| v.vessel.restoring.abs().max()))
}

impl Integrator {
    /// An integrator starting from `state`.
    pub fn new(model: Model, state: DynamicState, options: DynamicOptions) -> Result<Self> {
        positive("dt", options.time_step, "s")?;
        let count = model.rod.node_count();
        if state.configuration.positions.len() != count
            || state.gauss.len() != model.rod.element_count()
        {
            return Err(Error::input(
                "state",
                format!("a state of {} nodes", state.configuration.positions.len()),
                format!("must belong to this model ({count} nodes)"),
            ));
        }
        if state.accelerations.len() != count {
            return Err(Error::input(
                "state",
                format!("{} accelerations", state.accelerations.len()),
                format!("must hold one per node ({count})"),
            ));
        }
        if state.slips.len() != count {
            return Err(Error::input(
                "state",
                format!("{} friction slips", state.slips.len()),
                format!("must hold one per node ({count})"),
            ));
        }
        let mut assembler = Assembler::new(&model);
        // Before the first step: the reactions of the starting configuration at rest (static ones for a
        // static state, friction from the state's slips), from the integrator's own assembler.
        assembler
            .contact_start
            .clone_from(&state.configuration.positions);
        assembler.contact_slips.clone_from(&state.slips);
        let reactions = crate::solver::response::Response::with_assembler(
            &model,
            &state.configuration,
            &mut assembler,
        )
        .nodal_reactions;
        let nodal = NodalProperties::new(&model);
        let round_off = round_off(&model);
        let contact = assembler.contact.take();
        let vessel_waves = VesselWaves::new(&model, state.time)?;
        Ok(Integrator {
            vessel_waves,
            contact,
            round_off,
            increments: vec![0.0; NODE_DOFS * count],
            correction: vec![0.0; assembler.dofs.free],
            magnitude: vec![0.0; NODE_DOFS * count],
            next_gauss: state.gauss.clone(),
            serial_run: SERIAL_RUN,
            element_work: vec![ElementWork::default(); count - 1],
            node_dissipation: vec![0.0; count],
            assembler,
            nodal,
            node_start: vec![NodeStart::default(); count],
            wave_kinematics: Vec::new(),
            model,
            options,
            state,
            work: StepWork::default(),
            supplied_work: 0.0,
            dissipated: 0.0,
            reactions,
            vessel_step: None,
            rod_force_at_vessel: Vector6::zeros(),
            reference_mid: (Vector6::zeros(), Vector6::zeros()),
            offset_next: 0.0,
            filtered_next: 0.0,
            growth: None,
            pay_out_energy: 0.0,
        })
    }

    /// Energy pay-out has brought in since the start (J); counted in [`Self::supplied_work`].
    pub fn pay_out_energy(&self) -> f64 {
        self.pay_out_energy
    }

    /// The pipe's unstretched length (m).
    pub fn length(&self) -> f64 {
        self.model.rod.length()
    }

    /// The current state.
    pub fn state(&self) -> &DynamicState {
        &self.state
    }

    /// The settings.
    pub fn options(&self) -> &DynamicOptions {
        &self.options
    }

    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Work supplied since the start (J): point loads, driven supports, the current's share of the drag, and
    /// the energy pay-out brought in.
    pub fn supplied_work(&self) -> f64 {
        self.supplied_work
    }

    /// Restores the ledger (J), e.g. from a checkpoint: work supplied, energy dissipated, and the part of the
    /// supplied work that pay-out brought in.
    pub fn restore_ledger(&mut self, supplied_work: f64, dissipated: f64, pay_out_energy: f64) {
        self.supplied_work = supplied_work;
        self.dissipated = dissipated;
        self.pay_out_energy = pay_out_energy;
    }

    /// Energy dissipated since the start (J): drag on the relative velocity and rotational damping.
    pub fn dissipated(&self) -> f64 {
        self.dissipated
    }

    /// Force and moment the rod exerted on each node's support over the last step, in e: the step's mean
    /// (impulse / Δt), a second-order value at the step's midpoint t_n + Δt/2.
    pub fn reactions(&self) -> &[Vector6<f64>] {
        &self.reactions
    }

    /// With a vessel: its η, ν, the thrust τ and the pipe's force χ of the current state.
    pub fn vessel_values(&self) -> Option<[Vector6<f64>; 4]> {
        let state = &self.state;
        let (attachment, motion) = (self.model.vessel.as_ref()?, state.vessel.as_ref()?);
        let node = attachment.node;
        let (position, body) = low_frequency_pose(
            attachment,
            &state.configuration.positions[node],
            &state.configuration.rotations[node],
            self.vessel_waves.as_ref().map(|w| &w.now),
        );
        let eta = crate::vessel::coupling::eta_of(&position, &body);
        Some([eta, motion.velocity, motion.thrust, motion.pipe_force])
    }

    /// The current state as a record, reached after `iterations` Newton iterations.
    pub fn snapshot(&self, iterations: usize) -> Snapshot<'_> {
        let state = &self.state;
        let section_forces = self.section_forces();
        Snapshot {
            time: state.time,
            positions: &state.configuration.positions,
            rotations: &state.configuration.rotations,
            velocities: &state.velocities,
            lay: self.lay_summary(&section_forces),
            section_forces,
            reactions: &self.reactions,
            energy: self.energy(),
            vessel: self.vessel_values(),
            touchdown: self.touchdown(),
            roller_forces: self.roller_forces(),
            supplied_work: self.supplied_work,
            dissipated: self.dissipated,
            length: self.length(),
            pay_out_energy: self.pay_out_energy,
            iterations,
        }
    }

    /// Energy of the current state.
    pub fn energy(&self) -> Energy {
        let section = &self.model.rod.section;
        let (c_t, c_r) = (section.c_t(), section.c_r());
        let state = &self.state;
        let kinetic = (0..self.model.rod.node_count())
            .map(|i| {
                let w = state.body_angular_velocities[i];
                0.5 * self.nodal.mass[i] * state.velocities[i].norm_squared()
                    + 0.5 * w.dot(&self.nodal.inertia[i].component_mul(&w))
            })
            .sum();
        let strain = state
            .gauss
            .iter()
            .zip(&self.model.rod.elements)
            .map(|(g, reference)| g.energy(reference, &c_t, &c_r))
            .sum();
        let (vessel_kinetic, vessel_potential) = match (&self.model.vessel, &state.vessel) {
            (Some(attachment), Some(motion)) => {
                let node = attachment.node;
                let (position, body) = low_frequency_pose(
                    attachment,
                    &state.configuration.positions[node],
                    &state.configuration.rotations[node],
                    self.vessel_waves.as_ref().map(|w| &w.now),
                );
                (
                    crate::vessel::rigid_body::kinetic_energy(&attachment.vessel, &motion.velocity),
                    attachment
                        .vessel
                        .restoring_energy(&position, &body, attachment.surface),
                )
            }
            _ => (0.0, 0.0),
        };
        Energy {
            kinetic,
            strain,
            gravity: Assembler::gravity_potential(&self.model, &state.configuration),
            vessel_kinetic,
            vessel_potential,
            seabed: self.contact.as_ref().map_or(0.0, |contact| {
                contact.energy(&state.configuration.positions, &state.slips)
            }),
            rollers: self
                .assembler
                .rollers
                .as_ref()
                .map_or(0.0, |r| r.energy_end),
        }
    }

    /// Where the pipe leaves the seabed in the current state; `None` without a seabed.
    pub fn touchdown(&self) -> Option<Touchdown> {
        self.contact
            .as_ref()
            .map(|contact| contact.touchdown(&self.state.configuration.positions))
    }

    /// The seabed's force on each node over the last step (N, in e); `None` without a seabed.
    pub fn seabed_forces(&self) -> Option<&[Vector3<f64>]> {
        self.contact.as_ref().map(|contact| &contact.forces[..])
    }

    /// The lay summary of the current state, whose section forces are `section_forces`; `None` without a
    /// vessel.
    pub fn lay_summary(
        &self,
        section_forces: &[Vector6<f64>],
    ) -> Option<crate::solver::lay_summary::LaySummary> {
        let state = &self.state;
        crate::solver::lay_summary::lay_summary(
            &self.model,
            &state.configuration.positions,
            &state.configuration.rotations,
            section_forces,
            self.assembler
                .rollers
                .as_ref()
                .map(|r| (&r.forces[..], &r.nearest_elements[..])),
            self.touchdown().as_ref(),
        )
    }

    /// Effective tension of the element at the vessel (N); 0 without a vessel.
    pub fn top_tension(&self) -> f64 {
        let Some(attachment) = &self.model.vessel else {
            return 0.0;
        };
        let element = attachment.node.saturating_sub(1);
        let reference = &self.model.rod.elements[element];
        let strain = self.state.gauss[element].strain - reference.strain;
        (self.model.rod.section.c_t() * strain).x
    }

    /// Each roller's normal force in the current state (N); `None` without rollers.
    pub fn roller_forces(&self) -> Option<&[f64]> {
        self.assembler.rollers.as_ref().map(|r| &r.forces[..])
    }

    /// Linear momentum Σ M_I v_I (kg·m/s).
    pub fn linear_momentum(&self) -> Vector3<f64> {
        self.state
            .velocities
            .iter()
            .zip(&self.nodal.mass)
            .map(|(v, m)| v * *m)
            .sum()
    }

    /// Angular momentum about the origin Σ (φ_I × M_I v_I + Λ_I J_I W_I) (kg·m²/s).
    pub fn angular_momentum(&self) -> Vector3<f64> {
        let state = &self.state;
        (0..self.model.rod.node_count())
            .map(|i| {
                let spin = state.configuration.rotations[i]
                    * self.nodal.inertia[i].component_mul(&state.body_angular_velocities[i]);
                state.configuration.positions[i].cross(&(state.velocities[i] * self.nodal.mass[i]))
                    + spin
            })
            .sum()
    }

    /// Material force and moment [N; M] at the element Gauss points of the current state.
    pub fn section_forces(&self) -> Vec<Vector6<f64>> {
        let section = &self.model.rod.section;
        self.state
            .gauss
            .iter()
            .zip(&self.model.rod.elements)
            .map(|(g, reference)| {
                let n = section.c_t() * (g.strain - reference.strain);
                let m = section.c_r() * (g.curvature - reference.curvature);
                Vector6::new(n.x, n.y, n.z, m.x, m.y, m.z)
            })
            .collect()
    }

    /// Advances `steps` time steps, recording into `history` every `record_every` steps.
    pub fn advance(
        &mut self,
        steps: usize,
        record_every: usize,
        history: &mut History,
        counter: &mut usize,
    ) -> Result<()> {
        pool::run(self.parallel(), || {
            for _ in 0..steps {
                let report = self.step()?;
                *counter += 1;
                if *counter % record_every.max(1) == 0 {
                    history.record(&self.snapshot(report.iterations))?;
                }
            }
            Ok(())
        })
    }

    /// Whether the model is large enough for the engine's threads.
    fn parallel(&self) -> bool {
        pool::worth_it(self.model.rod.element_count())
    }

    /// Advances one time step Δt. Where Newton fails, the step is split into two halves, up to
    /// [`MAX_HALVINGS`] times; each sub-step keeps the exact energy balance.
    pub fn step(&mut self) -> Result<StepReport> {
        pool::run(self.parallel(), || self.substep(self.options.time_step, 0))
    }

    fn substep(&mut self, dt: f64, depth: usize) -> Result<StepReport> {
        match self.try_step(dt) {
            Err(Error::Convergence { .. }) if depth < MAX_HALVINGS => {
                let first = self.substep(0.5 * dt, depth + 1)?;
                let second = self.substep(0.5 * dt, depth + 1)?;
                Ok(StepReport {
                    iterations: first.iterations + second.iterations,
                    residual: second.residual,
                })
            }
            other => other,
        }
    }

    /// One step of size `dt`; the state is untouched if Newton fails.
    fn try_step(&mut self, dt: f64) -> Result<StepReport> {
        let time_next = self.state.time + dt;
        let time_mid = self.state.time + 0.5 * dt;
        let targets = self.model.support_targets(time_next)?;
        let scales = self
            .model
            .point_loads
            .iter()
            .map(|load| load.scale_at(time_mid))
            .collect::<Result<Vec<f64>>>()?;
        if let Some(controller) = self
            .model
            .vessel
            .as_ref()
            .and_then(|v| v.controller.as_ref())
        {
            let reference = controller.reference.at(time_mid)?;
            // The lay-tension loop moves the set-point by the top tension measured at the step's start.
            let (offset, filtered) = self
                .state
                .vessel
                .as_ref()
                .map_or((0.0, 0.0), |v| (v.setpoint_offset, v.filtered_tension));
            let (rate, filtered_next) =
                controller
                    .tension
                    .as_ref()
                    .map_or((0.0, filtered), |tension| {
                        (
                            tension.rate(filtered, self.state.time),
                            tension.filtered(filtered, self.top_tension(), dt),
                        )
                    });
            self.offset_next = offset + rate * dt;
            self.filtered_next = filtered_next;
            self.reference_mid = shifted(reference, offset + 0.5 * rate * dt, rate);
        }
        if let (Some(waves), Some(attachment)) = (&mut self.vessel_waves, &self.model.vessel) {
            waves.next = waves
                .motion
                .offset(time_next, &station(attachment, time_next)?)?;
        }
        let grown = self.start_growth(dt)?;
        self.node_start.clear();
        self.node_start.extend(
            (0..self.model.rod.node_count()).map(|node| node_start(&self.nodal, &self.state, node)),
        );
        self.predict(&targets, dt);
        self.wave_kinematics.clear();
        let outcome = self.newton(&scales, time_mid, dt);
        if outcome.is_err() {
            self.undo_growth();
        }
        let report = outcome?;
        let elastic = self.growth.map_or(0.0, |growth| {
            let section = &self.model.rod.section;
            let (c_t, c_r) = (section.c_t(), section.c_r());
            let reference = self.model.rod.elements[growth.element];
            let start = ElementReference {
                length: growth.length_start,
                ..reference
            };
            self.next_gauss[growth.element].energy(&reference, &c_t, &c_r)
                - self.state.gauss[growth.element].energy(&start, &c_t, &c_r)
                - growth.internal_work
        });
        self.commit(dt);
        self.book_pay_out(grown + elastic);
        self.remesh();
        Ok(report)
    }

    /// Books energy that pay-out brought in (J).
    fn book_pay_out(&mut self, energy: f64) {
        self.pay_out_energy += energy;
        self.supplied_work += energy;
    }

    /// With pay-out: sets the end element's length to its value at the step's end (the speed at the step's
    /// midpoint times Δt added) and its nodes' lumps to match. Returns the energy the change of mass brings in
    /// at the step's start (kinetic, and the potential of the submerged weight).
    fn start_growth(&mut self, dt: f64) -> Result<f64> {
        self.growth = None;
        let (Some(pay_out), Some((element, _))) =
            (&self.model.pay_out, self.model.growing_element())
        else {
            return Ok(0.0);
        };
        let time = self.state.time;
        let speed = pay_out.speed_at(time + 0.5 * dt)?;
        let length_start = self.model.rod.elements[element].length;
        let length_next = length_start + speed * dt;
        if length_next < 0.05 * pay_out.element_length {
            let reason = if self.model.rod.element_count() == 1 {
                "pay-in has reached the last element: the pipe cannot be paid in further"
            } else {
                "pays in more than half an element in one step: |speed|·dt must stay below 0.45 element_length"
            };
            return Err(Error::input(
                "pay_out speed",
                format!("{speed} m/s at t = {time} s"),
                reason,
            ));
        }
        let before = self.element_lump_energy(element);
        self.model.rod.elements[element].length = length_next;
        self.nodal.recompute(&self.model, element);
        self.nodal.recompute(&self.model, element + 1);
        self.growth = Some(Growth {
            element,
            length_start,
            internal_work: 0.0,
            speed,
        });
        Ok(self.element_lump_energy(element) - before)
    }

    /// Restores the end element's length and lumps after a failed step.
    fn undo_growth(&mut self) {
        if let Some(growth) = self.growth.take() {
            self.model.rod.elements[growth.element].length = growth.length_start;
            self.nodal.recompute(&self.model, growth.element);
            self.nodal.recompute(&self.model, growth.element + 1);
        }
    }

    /// Kinetic energy of an element's two nodes and the potential of its submerged weight (J).
    fn element_lump_energy(&self, element: usize) -> f64 {
        let state = &self.state;
        let kinetic = |i: usize| {
            let w = state.body_angular_velocities[i];
            0.5 * self.nodal.mass[i] * state.velocities[i].norm_squared()
                + 0.5 * w.dot(&self.nodal.inertia[i].component_mul(&w))
        };
        let positions = &state.configuration.positions;
        kinetic(element) + kinetic(element + 1)
            - 0.5
                * self.model.rod.elements[element].length
                * self.model.submerged_weight()
                * (positions[element].z + positions[element + 1].z)
    }

    /// With pay-out: splits or joins the end element when its length calls for it, rebuilds what depends on
    /// the mesh and books the energy change of the new mesh (a split keeps it to round-off and the
    /// discretisation's O(h²)).
    fn remesh(&mut self) {
        let Some(growth) = self.growth else {
            return;
        };
        let before = self.energy().total();
        let Some(change) = pay_out::remesh(
            &mut self.model,
            &mut self.state,
            &mut self.reactions,
            growth.speed,
        ) else {
            return;
        };
        let rollers = self.assembler.rollers.take();
        let mut assembler = Assembler::new(&self.model);
        if let (Some(new), Some(old)) = (&mut assembler.rollers, rollers) {
            new.energy_end = old.energy_end;
            new.forces = old.forces;
            new.nearest_elements = old
                .nearest_elements
                .iter()
                .map(|&e| match change {
                    MeshChange::Inserted(node) if e + 1 >= node => e + 1,
                    MeshChange::Removed(node) if e + 1 >= node => e.saturating_sub(1),
                    _ => e,
                })
                .collect();
        }
        self.contact = assembler.contact.take();
        self.assembler = assembler;
        self.nodal = NodalProperties::new(&self.model);
        let count = self.model.rod.node_count();
        self.increments = vec![0.0; NODE_DOFS * count];
        self.magnitude = vec![0.0; NODE_DOFS * count];
        self.correction = vec![0.0; self.assembler.dofs.free];
        self.next_gauss.clone_from(&self.state.gauss);
        self.element_work = vec![ElementWork::default(); count - 1];
        self.node_dissipation = vec![0.0; count];
        self.round_off = round_off(&self.model);
        let after = self.energy().total();
        self.book_pay_out(after - before);
    }

    /// Norms of the residual and of the per-DOF force magnitudes over the free DOFs.
    fn residual_norms(&self) -> (f64, f64) {
        let mut free2 = 0.0;
        let mut scale2 = 0.0;
        for &dof in &self.assembler.dofs.free_dofs {
            free2 += self.assembler.residual[dof].powi(2);
            scale2 += self.magnitude[dof].powi(2);
        }
        (free2.sqrt(), scale2.sqrt())
    }

    /// Newton's method on the step's increments, to the residual tolerance. The tangent is assembled and
    /// factorised at the predictor; later iterates reuse the last factors (a simplified Newton step costs a
    /// residual and a solve) while the residual falls by [`SIMPLIFIED_RATE`] or faster per iteration, and
    /// the tangent is refreshed at the iterate where it does not, or, for a block-tridiagonal factorisation,
    /// where the residual at the factorised iterate exceeded [`REUSE_BELOW`]. A converged iterate above
    /// [`POLISHED_BELOW`] of the tolerance gets one more correction. Everything depends on the step's start
    /// alone, so a resumed run repeats the same iterations.
    fn newton(&mut self, scales: &[f64], time_mid: f64, dt: f64) -> Result<StepReport> {
        let mut residual = f64::INFINITY;
        let mut converged = false;
        let mut iterations = 0;
        // Whether this iterate's tangent is to be assembled and factorised; the residual of the last correction;
        // whether a polishing correction was made.
        let mut fresh = true;
        let mut last = f64::INFINITY;
        let mut polished = false;
        // The relative residual at the iterate whose tangent is factorised.
        let mut factorised_at = f64::INFINITY;
        for iteration in 0..=self.options.max_iterations {
            iterations = iteration;
            self.assemble(scales, time_mid, dt, fresh)?;
            let (norm, scale) = self.residual_norms();
            residual = norm;
            if !residual.is_finite() {
                break;
            }
            if residual <= self.options.tolerance * scale + self.round_off
                || (iteration > 0 && residual == 0.0)
            {
                // An iterate just below the tolerance is corrected once more with the factors at hand (a
                // residual and a solve), so that energy and momentum balance to round-off, as when full
                // Newton from the constant-velocity predictor overshot the tolerance quadratically.
                if residual <= POLISHED_BELOW * self.options.tolerance * scale
                    || polished
                    || residual == 0.0
                    || iteration == self.options.max_iterations
                {
                    converged = true;
                    break;
                }
                polished = true;
            }
            if iteration == self.options.max_iterations {
                break;
            }
            if !fresh && residual > SIMPLIFIED_RATE * last {
                self.assemble(scales, time_mid, dt, true)?;
                fresh = true;
            }
            if fresh {
                self.assembler.shift_rotations();
                if self.assembler.lu.factorise(&self.assembler.values).is_err() {
                    break;
                }
                factorised_at = residual / scale;
            }
            last = residual;
            // The forces, hence the tangent, change over this correction by about the relative residual at
            // the factorised iterate: the contraction a simplified iteration would achieve.
            fresh = self.assembler.lu.is_block_tridiagonal() && factorised_at > REUSE_BELOW;
            for (correction, &dof) in self
                .correction
                .iter_mut()
                .zip(&self.assembler.dofs.free_dofs)
            {
                *correction = -self.assembler.residual[dof];
            }
            if self
                .assembler
                .lu
                .solve_in_place(&mut self.correction)
                .is_err()
            {
                break;
            }
            let mut correction2 = 0.0;
            let mut size2 = 0.0;
            for (correction, &dof) in self.correction.iter().zip(&self.assembler.dofs.free_dofs) {
                self.increments[dof] += correction;
                correction2 += correction.powi(2);
                size2 += self.increments[dof].powi(2);
            }
            // A correction at round-off of the increments: the residual cannot fall further.
            if correction2 <= 1e-30 * size2 && residual <= 1e3 * self.options.tolerance * scale {
                self.assemble(scales, time_mid, dt, false)?;
                converged = true;
                iterations += 1;
                break;
            }
        }
        if !converged {
            return Err(Error::Convergence {
                context: "time step".into(),
                reached: self.state.time,
                iterations,
                residual,
                reason: format!(
                    "Newton did not converge in the step from t = {:.6} s",
                    self.state.time
                ),
            });
        }
        Ok(StepReport {
            iterations,
            residual,
        })
    }

    /// Predictor: for free nodes, the last step's acceleration held, Δφ = v_n Δt + ½ a Δt² (the scheme's
    /// Δφ = ½(v_n + v_n+1)Δt with v_n+1 = v_n + aΔt), and constant angular velocity; prescribed increments
    /// for supported DOFs. A stiff line's residual at the predictor is dominated by the axial strain of its
    /// error, O(Δt³) with the acceleration against O(Δt²) without.
    fn predict(&mut self, targets: &[crate::model::SupportTarget], dt: f64) {
        let state = &self.state;
        for node in 0..self.model.rod.node_count() {
            let dphi = (state.velocities[node] + 0.5 * dt * state.accelerations[node]) * dt;
            let theta =
                state.configuration.rotations[node] * state.body_angular_velocities[node] * dt;
            let base = NODE_DOFS * node;
            self.increments[base..base + 3].copy_from_slice(dphi.as_slice());
            self.increments[base + 3..base + 6].copy_from_slice(theta.as_slice());
        }
        for target in targets {
            let base = NODE_DOFS * target.node;
            let dphi = target.position - state.configuration.positions[target.node];
            self.increments[base..base + 3].copy_from_slice(dphi.as_slice());
            if let Some(rotation) = target.rotation {
                let theta = cayley_parameter(
                    &(rotation * state.configuration.rotations[target.node].inverse()),
                );
                self.increments[base + 3..base + 6].copy_from_slice(theta.as_slice());
            }
        }
    }

    /// The waves' kinematics at each element's midpoint at the current increments (the predictor's), once per
    /// step.
    fn ensure_wave_kinematics(&mut self, time_mid: f64) {
        let Some(waves) = &self.model.waves else {
            return;
        };
        if self.model.sea.is_none() || !self.wave_kinematics.is_empty() {
            return;
        }
        let positions = &self.state.configuration.positions;
        let increments = &self.increments;
        let midpoint = |e: usize| {
            let moved = |node: usize| {
                Vector3::from_column_slice(&increments[NODE_DOFS * node..NODE_DOFS * node + 3])
            };
            0.5 * (positions[e] + positions[e + 1]) + 0.25 * (moved(e) + moved(e + 1))
        };
        let elements = self.model.rod.element_count();
        let kinematics = |e: usize| waves.kinematics(&midpoint(e), time_mid);
        if self.parallel() {
            pool::run(true, || {
                (0..elements)
                    .into_par_iter()
                    .map(kinematics)
                    .collect_into_vec(&mut self.wave_kinematics);
            });
        } else {
            self.wave_kinematics.extend((0..elements).map(kinematics));
        }
    }

    /// Residual (all DOFs), per-DOF magnitude, the step's work and, with `with_tangent`, the tangent (free
    /// DOFs), at the current increments.
    fn assemble(
        &mut self,
        scales: &[f64],
        time_mid: f64,
        dt: f64,
        with_tangent: bool,
    ) -> Result<()> {
        self.assembler.clear(with_tangent);
        self.magnitude.iter_mut().for_each(|m| *m = 0.0);
        let mut work = StepWork::default();
        self.ensure_wave_kinematics(time_mid);
        let model = &self.model;
        let state = &self.state;
        let rod = RodStep {
            model,
            constants: RodConstants::of(model),
            positions: &state.configuration.positions,
            velocities: &state.velocities,
            gauss: &state.gauss,
            mass: &self.nodal.mass,
            node_start: &self.node_start,
            increments: &self.increments,
            waves: &self.wave_kinematics,
            growth: self.growth.map(|g| (g.element, g.length_start)),
            stress_rule: self.options.stress_rule,
            serial_run: self.serial_run,
            dt,
            time_mid,
        };
        let mut sink = self.assembler.rod_sink(&mut self.magnitude, with_tangent);
        let outputs = ElementOutputs {
            next_gauss: &mut self.next_gauss,
            work: &mut self.element_work,
        };
        rod.add_elements(&mut sink, outputs, with_tangent);
        rod.add_nodes(&mut sink, &mut self.node_dissipation, with_tangent);
        for element in &self.element_work {
            work.supplied += element.supplied;
            work.dissipated += element.dissipated;
        }
        work.dissipated += self.node_dissipation.iter().sum::<f64>();
        if let Some(growth) = self.growth.as_mut() {
            growth.internal_work = self.element_work[growth.element].internal;
        }
        if let Some(mut contact) = self.contact.take() {
            let increments = &self.increments;
            contact
                .nodes
                .par_iter_mut()
                .with_min_len(PARALLEL_CONTACT_NODES)
                .enumerate()
                .for_each(|(node, step)| {
                    let base = NODE_DOFS * node;
                    let half_theta =
                        0.5 * Vector3::from_column_slice(&increments[base + 3..base + 6]);
                    let rotation_mid = cayley(&half_theta)
                        * state.configuration.rotations[node].to_rotation_matrix();
                    *step = NodeStep {
                        start: state.configuration.positions[node],
                        displacement: Vector3::from_column_slice(&increments[base..base + 3]),
                        axis: rotation_mid.column(0).into_owned(),
                        axis_map: 0.5 * cayley_tangent(&half_theta),
                    };
                });
            let rule = ContactRule::EnergyMomentum { time_step: dt };
            self.assembler
                .add_contact(&mut contact, rule, &state.slips, with_tangent);
            for (node, force) in contact.forces.iter().enumerate() {
                for k in 0..3 {
                    self.magnitude[NODE_DOFS * node + k] += force[k].abs();
                }
            }
            work.dissipated += contact.dissipated;
            self.contact = Some(contact);
        }
        self.assembler.add_rollers(
            ContactRule::EnergyMomentum { time_step: dt },
            &state.configuration,
            Some(&self.increments),
            Some(&mut self.magnitude),
            with_tangent,
        );
        for (load, scale) in model.point_loads.iter().zip(scales) {
            let base = NODE_DOFS * load.node;
            let force = load.force * *scale;
            let moment = load.moment * *scale;
            for i in 0..3 {
                self.assembler.residual[base + i] -= force[i];
                self.assembler.residual[base + 3 + i] -= moment[i];
                self.magnitude[base + i] += force[i].abs();
                self.magnitude[base + 3 + i] += moment[i].abs();
            }
            let dphi = Vector3::from_column_slice(&self.increments[base..base + 3]);
            let theta = Vector3::from_column_slice(&self.increments[base + 3..base + 6]);
            work.supplied += force.dot(&dphi) + moment.dot(&theta);
        }
        self.vessel_step = None;
        if let (Some(attachment), Some(motion)) = (&model.vessel, &state.vessel) {
            let node = attachment.node;
            let base = NODE_DOFS * node;
            let increment = Vector6::from_column_slice(&self.increments[base..base + 6]);
            let vessel = DynamicVessel {
                attachment,
                velocity: motion.velocity,
                integral: motion.integral,
                hold_thrust: motion.hold_thrust,
                reference: self.reference_mid,
                waves: self.vessel_waves.as_ref().map(|w| (w.now, w.next)),
            };
            let contribution = vessel.contribution(
                &state.configuration.positions[node],
                &state.configuration.rotations[node],
                &increment,
                dt,
                time_mid,
                with_tangent,
            );
            self.rod_force_at_vessel =
                Vector6::from_column_slice(&self.assembler.residual[base..base + 6]);
            for i in 0..NODE_DOFS {
                self.assembler.residual[base + i] += contribution.residual[i];
                self.magnitude[base + i] += contribution.magnitude[i];
            }
            if with_tangent {
                self.assembler.add_node_matrix(node, &contribution.tangent);
            }
            work.supplied += contribution.supplied;
            work.dissipated += contribution.dissipated;
            self.vessel_step = Some(contribution);
        }
        self.work = work;
        Ok(())
    }

    /// Accepts the converged increments: positions, rotations, velocities, Gauss points, reactions, ledger.
    fn commit(&mut self, dt: f64) {
        let mut support_work = 0.0;
        for node in 0..self.model.rod.node_count() {
            let base = NODE_DOFS * node;
            let dphi = Vector3::from_column_slice(&self.increments[base..base + 3]);
            let theta = Vector3::from_column_slice(&self.increments[base + 3..base + 6]);
            let residual = Vector6::from_column_slice(&self.assembler.residual[base..base + 6]);
            // At a supported DOF the residual is the force of the support on the rod; its work is supplied.
            for k in 0..NODE_DOFS {
                if self.assembler.dofs.equation[base + k].is_none() {
                    support_work += residual[k] * self.increments[base + k];
                }
            }
            self.reactions[node] = -residual;
            let state = &mut self.state;
            let rotation_n = state.configuration.rotations[node];
            state.configuration.positions[node] += dphi;
            let velocity = 2.0 * dphi / dt - state.velocities[node];
            state.accelerations[node] = (velocity - state.velocities[node]) / dt;
            state.velocities[node] = velocity;
            state.body_angular_velocities[node] =
                2.0 * (rotation_n.inverse() * theta) / dt - state.body_angular_velocities[node];
            state.configuration.rotations[node] = cayley_quaternion(&theta) * rotation_n;
        }
        self.state.gauss.copy_from_slice(&self.next_gauss);
        if let Some(contact) = &self.contact {
            self.state.slips.copy_from_slice(contact.slips());
        }
        if let (Some(attachment), Some(motion), Some(step)) = (
            &self.model.vessel,
            &mut self.state.vessel,
            &self.vessel_step,
        ) {
            let time_mid = self.state.time + 0.5 * dt;
            motion.velocity = step.velocity_next;
            motion.thrust = step.thrust;
            motion.setpoint_offset = self.offset_next;
            motion.filtered_tension = self.filtered_next;
            // The rod's force on the vessel, −(vessel's force on the rod), is the vessel end's reaction.
            self.reactions[attachment.node] = -self.rod_force_at_vessel;
            if let Some(controller) = attachment
                .controller
                .as_ref()
                .filter(|c| time_mid >= c.start)
            {
                motion.integral =
                    clamp_integral(controller, &(motion.integral + dt * step.error_mid));
            }
            // χ: the pipe's force on the vessel, −(rod's force on the node), in the body frame about CO.
            motion.pipe_force = pipe_force_on_vessel(
                attachment,
                &self.state.configuration.rotations[attachment.node],
                &self.rod_force_at_vessel,
                self.vessel_waves.as_ref().map(|w| &w.next),
            );
        }
        if let Some(waves) = &mut self.vessel_waves {
            waves.now = waves.next;
        }
        self.state.time += dt;
        self.supplied_work += self.work.supplied + support_work;
        self.dissipated += self.work.dissipated;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::current::{Current, CurrentProfile};
    use crate::environment::sea::Sea;
    use crate::rod::section::Section;
    use crate::rod::Rod;
    use std::sync::Arc;

    /// A steel pipe hanging in a sheared current with drag, rotational damping and a top driven in surge and
    /// heave, after `steps` steps of 0.05 s.
    fn moving_pipe(steps: usize) -> Integrator {
        moving_pipe_of(8, steps)
    }

    /// The moving pipe with `elements` elements, `steps` steps after its start.
    fn moving_pipe_of(elements: usize, steps: usize) -> Integrator {
        let section = Section::pipe(
            0.3,
            0.02,
            7850.0,
            207e9,
            0.3,
            1025.0,
            [0.1, 1.2],
            [0.0, 1.0],
        )
        .expect("pipe");
        let section = Section {
            rotational_damping: Vector3::new(50.0, 50.0, 50.0),
            ..section
        };
        let rod = Rod::straight(
            Vector3::zeros(),
            Vector3::new(0.0, 0.0, -100.0),
            elements,
            section,
        )
        .expect("rod");
        let current = Current::new(
            CurrentProfile::Linear {
                surface: Vector3::new(0.5, -0.8, 0.0),
            },
            0.0,
        )
        .expect("current");
        let sea = Sea::new(120.0, 1025.0, Some(current), None).expect("sea");
        let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
        model.pin("A", None).expect("pin");
        model
            .drive(
                "B",
                Arc::new(|t: f64| Ok(Vector3::new(3.0 * (0.8 * t).sin(), 0.0, -100.0))),
                None,
                None,
            )
            .expect("drive");
        let state =
            DynamicState::at_rest(&model, Configuration::reference(&model), 0.0).expect("state");
        let mut sim = Integrator::new(model, state, DynamicOptions::default()).expect("integrator");
        for _ in 0..steps {
            sim.step().expect("step");
        }
        sim
    }

    /// Sets up the next step of `sim` at its predictor; returns Δt and the step's mid-time.
    fn at_predictor(sim: &mut Integrator) -> (f64, f64) {
        let dt = sim.options.time_step;
        let time_mid = sim.state.time + 0.5 * dt;
        let targets = sim
            .model
            .support_targets(sim.state.time + dt)
            .expect("targets");
        sim.node_start = (0..sim.model.rod.node_count())
            .map(|node| node_start(&sim.nodal, &sim.state, node))
            .collect();
        sim.predict(&targets, dt);
        (dt, time_mid)
    }

    /// The assembled tangent of a step (elements, inertia, damping, drag in a sheared current) equals central
    /// differences of the assembled residual, column by column, at an iterate away from the predictor.
    #[test]
    fn step_tangent_matches_differences_of_the_residual() {
        let mut sim = moving_pipe(20);
        let (dt, time_mid) = at_predictor(&mut sim);
        for (dof, increment) in sim.increments.iter_mut().enumerate() {
            if sim.assembler.dofs.equation[dof].is_some() {
                *increment += 1e-3 * (dof as f64).sin();
            }
        }
        sim.assemble(&[], time_mid, dt, true).expect("assembly");
        let tangent = sim.assembler.values.clone();
        let mut worst: f64 = 0.0;
        for column in 0..sim.increments.len() {
            let Some(col) = sim.assembler.dofs.equation[column] else {
                continue;
            };
            let h = 1e-5;
            let mut residual_at = |step: f64| {
                sim.increments[column] += step;
                sim.assemble(&[], time_mid, dt, false).expect("assembly");
                sim.increments[column] -= step;
                sim.assembler.residual.clone()
            };
            let (plus, minus) = (residual_at(h), residual_at(-h));
            for (row, eq) in sim.assembler.dofs.equation.iter().enumerate() {
                let Some(r) = *eq else { continue };
                let difference = (plus[row] - minus[row]) / (2.0 * h);
                let entry = sim
                    .assembler
                    .lu
                    .position(r, col)
                    .map_or(0.0, |p| tangent[p]);
                // Central differences err by O(h²) relatively and by round-off of the residual (≈ 1e5 N) over h.
                worst = worst.max((difference - entry).abs() / (entry.abs() + 1e3));
            }
        }
        assert!(worst < 1e-4, "worst relative error {worst:e}");
    }

    /// However the rod's assembly is split between threads (runs of 1, 5 and 64 elements against one run),
    /// its residual, magnitudes, tangent and work come out the same to the bit.
    #[test]
    fn parallel_assembly_is_the_serial_one_bit_for_bit() {
        let mut sim = moving_pipe_of(301, 2);
        let (dt, time_mid) = at_predictor(&mut sim);
        let mut assemble = |run: usize| {
            sim.serial_run = run;
            pool::run(true, || sim.assemble(&[], time_mid, dt, true)).expect("assembly");
            (
                sim.assembler.residual.clone(),
                sim.magnitude.clone(),
                sim.assembler.values.clone(),
                [sim.work.supplied, sim.work.dissipated],
            )
        };
        let serial = assemble(usize::MAX);
        for run in [1, 5, SERIAL_RUN] {
            assert!(assemble(run) == serial, "runs of {run}");
        }
    }
}
