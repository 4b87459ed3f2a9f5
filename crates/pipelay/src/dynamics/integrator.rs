//! Time integration of the rod and its vessel: the energy–momentum conserving scheme of Simo, Tarnow & Doblaré (1995)
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
//! Added mass acts by direction ([`crate::dynamics::nodal`]): the nodal mass depends on the node's axis, and
//! the step balances the kinetic energy's dependence on it exactly ([`crate::dynamics::rod_step`]).
//!
//! The integrator owns the model, the state and the step's work space, and advances them: a step predicts
//! the increments ([`crate::dynamics::step_residual`]), solves for them by Newton's method
//! ([`crate::dynamics::newton`]), commits them here and books their work in the [`Ledger`]; pay-out grows
//! the end element and changes the mesh ([`crate::dynamics::pay_out`]). What users read off a state is
//! [`Observables`].
// Indexing cannot go out of bounds here: Node, element and DOF indices of the integrator's own mesh (rebuilt with it at every pay-out change).
#![allow(clippy::indexing_slicing)]
use crate::assembly::assembler::Assembler;
use crate::assembly::dofs::NODE_DOFS;
use crate::contact::rule::ContactRule;
use crate::contact::seabed::SeabedContact;
use crate::dynamics::hand_back;
use crate::dynamics::hand_over;
use crate::dynamics::history::{History, Snapshot, StationRecord};
use crate::dynamics::ledger::{Ledger, StepWork};
use crate::dynamics::nodal::{node_start, NodalProperties};
use crate::dynamics::observables::Observables;
use crate::dynamics::passivity;
use crate::dynamics::pay_out::Growth;
use crate::dynamics::remesh;
use crate::dynamics::rod_step::{rod_constants, ElementWork, NodeStart, RodConstants};
use crate::dynamics::stages::Stages;
use crate::dynamics::state::DynamicState;
use crate::dynamics::station_keeping::StationKeeping;
use crate::dynamics::vessel_waves::VesselWaves;
use crate::environment::waves::Kinematics;
use crate::error::{positive, Error, Result};
use crate::linalg::pool::{self, SERIAL_RUN};
use crate::model::Model;
use crate::response::configuration::Response;
use crate::rod::dynamic_element::{GaussPoint, StressRule};
use crate::so3::cayley_quaternion;
use crate::vessel::control::{clamp_integral, shifted, transfer_integral};
use crate::vessel::coupling::{
    eta_of, low_frequency_pose, pipe_force_on_vessel, vessel_pose, VesselContribution,
};
use crate::vessel::hull_loads::{HullEnvironment, HullValues};
use crate::vessel::stinger_sections::SectionWork;
use crate::vessel::wave_motion::station;
use nalgebra::{Vector3, Vector6};

/// How many times a step may be halved when Newton fails in it or its state is rejected: the substeps' floor is
/// Δt / 2^MAX_HALVINGS.
pub const MAX_HALVINGS: u32 = 10;
/// Substeps of one size that succeed in a row before the next is tried at twice the size.
pub const GROW_AFTER: usize = 2;

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
    /// High-frequency damping ξ ≥ 0 of the line's strains ([`crate::rod::dynamic_element::with_damping`]):
    /// 0 conserves energy; ξ damps a mode of circular frequency ω at the ratio ξωΔt/2, all its work dissipated.
    pub high_frequency_damping: f64,
}

impl Default for DynamicOptions {
    fn default() -> Self {
        DynamicOptions {
            time_step: 0.05,
            tolerance: 1e-10,
            max_iterations: 25,
            stress_rule: StressRule::AverageStrain,
            high_frequency_damping: 0.0,
        }
    }
}

/// What one step took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepReport {
    pub iterations: usize,
    /// Tangents factorised.
    pub factorisations: usize,
    /// Final residual norm over the free DOFs.
    pub residual: f64,
    /// The residual at the predictor relative to the force scale (the largest of the step's substeps).
    pub predictor_residual: f64,
    /// The substeps the step was taken in (1: the step as a whole).
    pub substeps: usize,
}

/// Advances a model in time.
pub struct Integrator {
    pub(super) model: Model,
    pub(super) options: DynamicOptions,
    pub(super) assembler: Assembler,
    pub(super) state: DynamicState,
    pub(super) nodal: NodalProperties,
    /// Each node's inertia and damping at the current step's start.
    pub(super) node_start: Vec<NodeStart>,
    /// The waves' kinematics at each element's midpoint in the current step (at the predictor), as far as
    /// computed.
    pub(super) wave_kinematics: Vec<Kinematics>,
    /// Unknowns of the current step on all DOFs: [Δφ_I, θ_I].
    pub(super) increments: Vec<f64>,
    /// An articulated stinger's sections in the last assembly: their energy, points' velocities and drag work.
    pub(super) section_work: SectionWork,
    /// Newton correction on the free DOFs.
    pub(super) correction: Vec<f64>,
    /// Σ|terms| per DOF, the scale of the residual.
    pub(super) magnitude: Vec<f64>,
    pub(super) next_gauss: Vec<GaussPoint>,
    /// The yielding elements' plastic strains at the current step's end.
    pub(super) next_plastic: Vec<Vec<f64>>,
    /// Elements and nodes the rod's assembly takes in one run (see [`crate::dynamics::rod_step`]).
    pub(super) serial_run: usize,
    /// Each element's and each node's energy terms in the last assembly (J).
    pub(super) element_work: Vec<ElementWork>,
    pub(super) node_dissipation: Vec<f64>,
    pub(super) work: StepWork,
    pub(super) ledger: Ledger,
    /// Force and moment the rod exerts on each node's support at the last step (N, N·m).
    pub(super) reactions: Vec<Vector6<f64>>,
    /// Round-off floor of the residual norm (N): internal forces carry errors of about 1e-16·EA per element,
    /// a vessel's restoring about 1e-16·G.
    pub(super) round_off: f64,
    /// The vessel's part of the last assembly.
    pub(super) vessel_step: Option<VesselContribution>,
    /// The rod's force on the vessel node in the last assembly (spatial).
    pub(super) rod_force_at_vessel: Vector6<f64>,
    /// The controller's reference pose and rate at the current step's midpoint.
    pub(super) reference_mid: (Vector6<f64>, Vector6<f64>),
    /// The lay-tension loop's set-point offset and filtered tension at the end of the current step (m, N).
    pub(super) offset_next: f64,
    pub(super) filtered_next: f64,
    /// Seabed contact, if the model has a seabed.
    pub(super) contact: Option<SeabedContact>,
    /// Each segment's constants for the rod's terms (the sections do not change over a run).
    pub(super) segment_constants: RodConstants,
    /// With pay-out: the growing element in the current step.
    pub(super) growth: Option<Growth>,
    /// In waves, with a vessel that has RAOs: its wave-frequency motion.
    pub(super) vessel_waves: Option<VesselWaves>,
    /// Wind, current and wave drift on the hull, and their values over the current step.
    pub(super) hull: Option<HullEnvironment>,
    pub(super) hull_values: HullValues,
    /// A sampled DP loop (allocation, observer), and the thrust it holds over the current step.
    pub(super) station_keeping: Option<StationKeeping>,
    pub(super) applied_thrust: Option<Vector6<f64>>,
    /// The passivity controller's scale of the controller's thrust in the step being solved (1: not acting),
    /// and the controller's work the step's first solution, at full thrust, did (J).
    pub(super) passivity_scale: f64,
    passivity_full_work: f64,
    /// The stages of the run, if it has any (applied to the model by [`Stages::apply`]).
    pub(super) stages: Option<Stages>,
    /// The axial force the winch's wire took on at the hand-over (N), once it happened in this run.
    pub(super) handed_over: Option<f64>,
    /// When the tensioner took the line back from the winch (s).
    pub(super) handed_back: Option<f64>,
    /// The most substeps any step since the last record was taken in.
    substeps_since_record: usize,
}

/// An assembler for `state` at rest, with the reactions of its configuration (static ones for a static state,
/// friction from the state's slips, yielding walls in the state's plastic state: an overlay evaluated at the
/// strains its state was reached at does not flow) and its seabed contact: what a run starts from.
fn assembler_at_rest(
    model: &Model,
    state: &DynamicState,
) -> (Assembler, Vec<Vector6<f64>>, Option<SeabedContact>) {
    let mut assembler = Assembler::new(model);
    assembler.start_plastic_from(&state.plastic);
    assembler
        .contact_start
        .clone_from(&state.configuration.positions);
    assembler.contact_slips.clone_from(&state.slips);
    let reactions =
        Response::with_assembler(model, &state.configuration, &mut assembler).nodal_reactions;
    let contact = assembler.contact.take();
    (assembler, reactions, contact)
}

/// The vessel's low-frequency pose η in `configuration`, its wave-frequency offset at the step's start (in
/// `waves`) taken off.
fn low_frequency_eta(
    attachment: &crate::vessel::VesselAttachment,
    configuration: &crate::assembly::configuration::Configuration,
    waves: Option<&VesselWaves>,
) -> Vector6<f64> {
    let node = attachment.node;
    let (position, body) = low_frequency_pose(
        attachment,
        &configuration.positions[node],
        &configuration.rotations[node],
        waves.map(|w| &w.now),
    );
    eta_of(&position, &body)
}

/// Round-off floor of the residual norm (N): internal forces carry errors of about 1e-16·EA per element, a
/// vessel's restoring about 1e-16·G.
fn round_off(model: &Model) -> f64 {
    1e-13
        * (model.rod.largest(|s| s.translational_stiffness.max())
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
        if state.plastic.len() != model.rod.element_count() {
            return Err(Error::input(
                "state",
                format!("{} elements' plastic states", state.plastic.len()),
                format!("must hold one per element ({})", model.rod.element_count()),
            ));
        }
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
        let (assembler, reactions, contact) = assembler_at_rest(&model, &state);
        let nodal = NodalProperties::new(&model);
        let round_off = round_off(&model);
        let vessel_waves = VesselWaves::new(&model, state.time)?;
        let hull = match &model.vessel {
            Some(attachment) => {
                HullEnvironment::new(attachment, model.sea.as_ref(), model.waves.as_ref())?
            }
            None => None,
        };
        let station_keeping = match (&model.vessel, &state.vessel) {
            (Some(attachment), Some(motion)) => {
                let node = attachment.node;
                let (position, body) = crate::vessel::coupling::low_frequency_pose(
                    attachment,
                    &state.configuration.positions[node],
                    &state.configuration.rotations[node],
                    vessel_waves.as_ref().map(|w| &w.now),
                );
                StationKeeping::new(
                    &model,
                    &eta_of(&position, &body),
                    &motion.velocity,
                    &motion.hold_thrust,
                )?
            }
            _ => None,
        };
        Ok(Integrator {
            segment_constants: rod_constants(&model),
            vessel_waves,
            hull,
            hull_values: HullValues::default(),
            station_keeping,
            applied_thrust: None,
            passivity_scale: 1.0,
            passivity_full_work: 0.0,
            contact,
            round_off,
            increments: vec![0.0; model.dof_count()],
            correction: vec![0.0; assembler.dofs.free],
            magnitude: vec![0.0; model.dof_count()],
            section_work: SectionWork::default(),
            next_gauss: state.gauss.clone(),
            next_plastic: state.plastic.clone(),
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
            ledger: Ledger::default(),
            reactions,
            vessel_step: None,
            rod_force_at_vessel: Vector6::zeros(),
            reference_mid: (Vector6::zeros(), Vector6::zeros()),
            offset_next: 0.0,
            filtered_next: 0.0,
            growth: None,
            stages: None,
            handed_over: None,
            handed_back: None,
            substeps_since_record: 1,
        })
    }

    /// Runs through `stages`, already applied to this integrator's model ([`Stages::apply`]: before the
    /// integrator is made, and for a restored run before its checkpoint's rod replaces the model's).
    pub fn set_applied_stages(&mut self, stages: Stages) {
        self.stages = Some(stages);
    }

    /// The stages, if the run has any.
    pub fn stages(&self) -> Option<&Stages> {
        self.stages.as_ref()
    }

    /// The axial force the wire took on at the hand-over (N), if it happened in this run.
    pub fn handed_over(&self) -> Option<f64> {
        self.handed_over
    }

    /// When the tensioner took the line back from the winch in this run (s), if it did.
    pub fn handed_back(&self) -> Option<f64> {
        self.handed_back
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

    /// Work supplied and energy dissipated since the start.
    pub fn ledger(&self) -> &Ledger {
        &self.ledger
    }

    /// Restores the ledger, e.g. from a checkpoint.
    pub fn restore_ledger(&mut self, ledger: Ledger) {
        self.ledger = ledger;
    }

    /// Force and moment the rod exerted on each node's support over the last step, in e: the step's mean
    /// (impulse / Δt), a second-order value at the step's midpoint t_n + Δt/2.
    pub fn reactions(&self) -> &[Vector6<f64>] {
        &self.reactions
    }

    /// What can be read off the current state.
    pub fn observe(&self) -> Observables<'_> {
        Observables {
            model: &self.model,
            state: &self.state,
            nodal: &self.nodal,
            contact: self.contact.as_ref(),
            rollers: self.assembler.rollers.as_ref(),
            sections: self.assembler.sections.as_ref(),
            plastic: self.assembler.plastic.as_ref(),
            wave_offset: self.vessel_waves.as_ref().map(|w| &w.now),
        }
    }

    /// The current state as a record, reached after `iterations` Newton iterations, where the steps since the
    /// last record were taken in at most `substeps` substeps each.
    pub fn snapshot(&self, iterations: usize, substeps: usize) -> Snapshot<'_> {
        let state = &self.state;
        let observables = self.observe();
        let (section_forces, energy) = observables.section_forces_and_energy();
        Snapshot {
            time: state.time,
            positions: &state.configuration.positions,
            rotations: &state.configuration.rotations,
            velocities: &state.velocities,
            lay: observables.lay_summary(&section_forces),
            section_forces,
            segment_of: &self.model.rod.segment_of,
            reactions: &self.reactions,
            energy,
            vessel: observables.vessel_values(),
            station: self.station_record(&observables),
            touchdown: observables.touchdown(),
            roller_forces: observables.roller_forces(),
            roller_vectors: observables.roller_reactions().map(|(vectors, _)| vectors),
            hinge_angles: &state.configuration.hinge_angles,
            supplied_work: self.ledger.supplied_work(),
            dissipated: self.ledger.dissipated(),
            length: observables.length(),
            pay_out_speed: state.pay_out_speed,
            pay_out_energy: self.ledger.pay_out_energy(),
            plastic_dissipation: self.ledger.plastic_dissipated(),
            iterations,
            substeps,
            passivity: self
                .model
                .vessel
                .as_ref()
                .and_then(|v| v.controller.as_ref())
                .filter(|c| c.passivity.is_some())
                .and(self.state.vessel.as_ref())
                .map(|motion| motion.passivity),
        }
    }

    /// What the vessel's station keeping records at the current state.
    fn station_record(&self, observables: &Observables<'_>) -> Option<StationRecord> {
        let eta_low_frequency = observables.vessel_low_frequency()?;
        let thrust = self
            .state
            .vessel
            .as_ref()
            .map_or_else(Vector6::zeros, |m| m.thrust);
        let Some(station_keeping) = &self.station_keeping else {
            return Some(StationRecord {
                eta_low_frequency,
                eta_estimate: None,
                tau_commanded: thrust,
                thrust: Vec::new(),
                azimuth: Vec::new(),
            });
        };
        Some(StationRecord {
            eta_low_frequency,
            eta_estimate: station_keeping.estimate().map(|(eta, _)| eta),
            tau_commanded: station_keeping.tau_commanded,
            thrust: station_keeping.thrusters.iter().map(|s| s.thrust).collect(),
            azimuth: station_keeping
                .thrusters
                .iter()
                .map(|s| s.azimuth)
                .collect(),
        })
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
                self.substeps_since_record = self.substeps_since_record.max(report.substeps);
                if *counter % record_every.max(1) == 0 {
                    history
                        .record(&self.snapshot(report.iterations, self.substeps_since_record))?;
                    self.substeps_since_record = 1;
                }
            }
            Ok(())
        })
    }

    /// Whether the model is large enough for the engine's threads.
    pub(super) fn parallel(&self) -> bool {
        pool::worth_it(self.model.rod.element_count())
    }

    /// Advances one time step Δt, in substeps where Newton fails or a step is rejected ([`Self::substeps`]).
    pub fn step(&mut self) -> Result<StepReport> {
        if self
            .stages
            .as_ref()
            .is_some_and(|stages| stages.hand_over_due(&self.model, self.state.time))
        {
            self.hand_over()?;
        }
        if self.stages.is_some() && hand_back::due(&self.model, &self.state)? {
            self.hand_back();
        }
        if let Some(stages) = &self.stages {
            let remaining = hand_back::remaining(&self.model, &self.state);
            stages.check_handed_back(&self.model, self.state.time, remaining)?;
        }
        if let Some(stage) = self
            .stages
            .as_ref()
            .and_then(|stages| stages.statics_due(self.state.time))
        {
            self.restart_from_statics(stage)?;
        }
        self.command_station_keeping()?;
        pool::run(self.parallel(), || self.substeps(self.options.time_step))
    }

    /// An external controller's command for the step from now, if it has started by the step's midpoint.
    fn command_station_keeping(&mut self) -> Result<()> {
        let (Some(attachment), Some(motion), Some(station_keeping)) = (
            &self.model.vessel,
            &self.state.vessel,
            &mut self.station_keeping,
        ) else {
            return Ok(());
        };
        let time = self.state.time;
        let Some(controller) = attachment
            .controller
            .as_ref()
            .filter(|c| time + 0.5 * self.options.time_step >= c.start)
        else {
            return Ok(());
        };
        let eta = low_frequency_eta(
            attachment,
            &self.state.configuration,
            self.vessel_waves.as_ref(),
        );
        station_keeping.command(
            controller,
            time,
            self.options.time_step,
            &eta,
            &motion.velocity,
        )
    }

    /// Starts stage `stage` from statics of the configuration as it is: the vessel held where it is (its surge,
    /// sway and yaw by the holding thrust), the line in equilibrium from Newton at full load from the current
    /// configuration, yielding walls from the run's plastic state, all at rest. The change of energy is booked
    /// as work supplied: the analysis, not the physics, put the system there.
    fn restart_from_statics(&mut self, stage: usize) -> Result<()> {
        let before = self.observe().energy().total();
        let time = self.state.time;
        if let Some(attachment) = self.model.vessel.as_mut() {
            let node = attachment.node;
            let configuration = &self.state.configuration;
            let (position, body) = crate::vessel::coupling::vessel_pose(
                attachment,
                &configuration.positions[node],
                &configuration.rotations[node],
            );
            attachment.eta = crate::vessel::coupling::eta_of(&position, &body);
        }
        let solution = crate::statics::solve::solve_from(
            &self.model,
            &crate::statics::solve::StaticOptions::default(),
            self.state.configuration.clone(),
            &self.state.slips,
            &self.state.plastic,
            time,
        )
        .map_err(|error| match error {
            Error::Convergence {
                iterations,
                residual,
                reason,
                ..
            } => Error::Convergence {
                context: format!("statics at the start of stage {stage}"),
                reached: time,
                iterations,
                residual,
                reason,
            },
            other => other,
        })?;
        let slips = solution
            .response
            .seabed
            .as_ref()
            .map(|seabed| seabed.slips.clone());
        let mut state = DynamicState::at_rest_from(
            &self.model,
            solution.configuration,
            time,
            Some(&self.state.plastic),
        )?;
        if let Some(slips) = slips {
            state = state.with_slips(&slips);
        }
        // The mesh is as it was: as a new integrator's, the contacts and reactions of the configuration at rest.
        (self.assembler, self.reactions, self.contact) = assembler_at_rest(&self.model, &state);
        self.next_gauss.clone_from(&state.gauss);
        self.state = state;
        let after = self.observe().energy().total();
        self.ledger.book_step(after - before, 0.0);
        Ok(())
    }

    /// Hands the line over to the winch ([`hand_over`]) and books the energy its wire and head bring in.
    fn hand_over(&mut self) -> Result<()> {
        let before = self.observe().energy().total();
        let force = hand_over::hand_over(&mut self.model, &mut self.state, &mut self.reactions)?;
        self.rebuild();
        let after = self.observe().energy().total();
        self.ledger.book_pay_out(after - before);
        self.handed_over = Some(force);
        Ok(())
    }

    /// Hands the line back to the tensioner ([`hand_back`]), rests the pay-out until the next stage the
    /// tensioner holds, and books the energy the wire and head take away.
    fn hand_back(&mut self) {
        let before = self.observe().energy().total();
        let Some(back) =
            hand_back::hand_back(&mut self.model, &mut self.state, &mut self.reactions)
        else {
            return;
        };
        if let Some(stages) = &self.stages {
            stages.rest_after_hand_back(&mut self.model, back.time);
        }
        self.rebuild();
        let after = self.observe().energy().total();
        self.ledger.book_pay_out(after - before);
        self.handed_back = Some(back.time);
    }

    /// The step of size `dt`, in substeps where it must be: a substep whose Newton fails or whose state is
    /// rejected ([`Integrator::accept_step`]) is tried again at half its size, down to the floor
    /// Δt / 2^[`MAX_HALVINGS`]; after [`GROW_AFTER`] successes in a row the size doubles again (where the
    /// time reached is a multiple of the doubled size, so that the substeps tile the step). Each substep is an
    /// energy–momentum step with its own ledger entries, and the decisions depend on the state alone, so a
    /// resumed run takes the same substeps.
    fn substeps(&mut self, dt: f64) -> Result<StepReport> {
        let start = self.state.time;
        let whole: u64 = 1 << MAX_HALVINGS;
        let (mut done, mut size, mut successes) = (0u64, whole, 0usize);
        let mut total = StepReport {
            iterations: 0,
            factorisations: 0,
            residual: 0.0,
            predictor_residual: 0.0,
            substeps: 0,
        };
        while done < whole {
            let h = dt * size as f64 / whole as f64;
            match self.try_step(h) {
                Ok(report) => {
                    total.iterations += report.iterations;
                    total.factorisations += report.factorisations;
                    total.residual = report.residual;
                    total.predictor_residual =
                        total.predictor_residual.max(report.predictor_residual);
                    total.substeps += 1;
                    done += size;
                    successes += 1;
                    if successes >= GROW_AFTER && size < whole && done % (2 * size) == 0 {
                        size *= 2;
                        successes = 0;
                    }
                }
                Err(Error::Convergence {
                    iterations,
                    residual,
                    reason,
                    ..
                }) if size == 1 => {
                    return Err(Error::Convergence {
                        context: "time step".into(),
                        reached: self.state.time,
                        iterations,
                        residual,
                        reason: format!(
                            "{reason}; the step from t = {start:.6} s was split down to its floor Δt/{whole} = \
                             {:.3e} s: reduce dt, soften the contacts (roller or seabed stiffness) or ease \
                             the loads",
                            dt / whole as f64
                        ),
                    });
                }
                Err(Error::Convergence { .. }) => {
                    size /= 2;
                    successes = 0;
                }
                Err(other) => return Err(other),
            }
        }
        if total.substeps > 1 {
            // The substeps' times summed may differ from the step's in the last bit.
            self.state.time = start + dt;
        }
        Ok(total)
    }

    /// One step of size `dt`; the state is untouched if Newton fails or the step is rejected.
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
                            tension.filtered(filtered, self.observe().top_tension(), dt),
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
        self.take_over(dt);
        self.decide_station_keeping(time_mid, dt)?;
        self.growth = None;
        let grown = match Growth::start(&mut self.model, &mut self.nodal, &self.state, dt)? {
            Some((growth, brought_in)) => {
                self.growth = Some(growth);
                brought_in
            }
            None => 0.0,
        };
        self.node_start.clear();
        self.node_start.extend(
            (0..self.model.rod.node_count()).map(|node| node_start(&self.nodal, &self.state, node)),
        );
        self.predict(&targets, dt);
        self.wave_kinematics.clear();
        self.passivity_scale = 1.0;
        let mut outcome = self
            .newton(&scales, time_mid, dt)
            .and_then(|report| self.accept_step(dt, &report).map(|()| report));
        self.passivity_full_work = self.vessel_step.as_ref().map_or(0.0, |s| s.controller_work);
        // The passivity controller: where the step would give the vessel more than the controller's reserve,
        // it is solved again with the controller's thrust scaled down until it fits (cut, at the last).
        for solve in 0..=passivity::MAX_SOLVES {
            let Some(scale) = outcome.as_ref().ok().and_then(|_| self.passivity_needed()) else {
                break;
            };
            self.passivity_scale = if solve == passivity::MAX_SOLVES {
                0.0
            } else {
                scale
            };
            outcome = self
                .newton(&scales, time_mid, dt)
                .and_then(|report| self.accept_step(dt, &report).map(|()| report));
        }
        if outcome.is_err() {
            if let Some(growth) = self.growth.take() {
                growth.undo(&mut self.model, &mut self.nodal);
            }
        }
        let report = outcome?;
        // A winch that renders or holds a tension ran at the speed its law gives at the solved chord.
        let predicted = self.growth.and_then(|growth| {
            growth.winch?;
            let e = growth.element;
            let chord_next = self.state.configuration.positions[e + 1]
                - self.state.configuration.positions[e]
                + Vector3::from_column_slice(&self.increments[NODE_DOFS * (e + 1)..][..3])
                - Vector3::from_column_slice(&self.increments[NODE_DOFS * e..][..3]);
            let predicted = self.model.rod.elements[e].length;
            if let Some(growth) = self.growth.as_mut() {
                growth.solve_length(&mut self.model, chord_next.norm(), dt);
            }
            Some(predicted)
        });
        let stored = self.growth.map_or(0.0, |growth| {
            growth.strain_energy(
                &self.model,
                &self.state,
                &self.next_gauss,
                self.assembler.plastic.as_ref(),
                &self.next_plastic,
                self.element_work[growth.element].plastic,
            )
        });
        self.commit(dt);
        let settled = match (self.growth, predicted) {
            (Some(growth), Some(predicted)) => {
                growth.settle(&mut self.model, &mut self.nodal, &self.state, predicted)
            }
            _ => 0.0,
        };
        if let Some(growth) = self.growth {
            self.state.pay_out_speed = growth.speed;
        }
        self.ledger.book_pay_out(grown + stored + settled);
        self.remesh();
        Ok(report)
    }

    /// The thrust scale to solve the step just solved again with, if the controller certifies the loop and the
    /// step gives the vessel more than its reserve ([`passivity::PassivityLedger::next_scale`]).
    fn passivity_needed(&self) -> Option<f64> {
        let attachment = self.model.vessel.as_ref()?;
        attachment.controller.as_ref().filter(|c| c.certifies())?;
        let (motion, step) = (self.state.vessel.as_ref()?, self.vessel_step.as_ref()?);
        let ledger = &motion.passivity;
        (self.passivity_scale > 0.0 && !ledger.fits(step.controller_work))
            .then(|| ledger.next_scale(self.passivity_scale, step.controller_work))
    }

    /// Bumpless transfer: in the step that holds the controller's start
    /// ([`crate::vessel::control::Pid::takes_over`]), its integral takes over the holding thrust at the
    /// vessel's low-frequency pose at the step's start ([`transfer_integral`]): τ(start) = τ_h at η̃ = 0,
    /// η̃̇ = 0.
    fn take_over(&mut self, dt: f64) {
        let (Some(attachment), Some(motion)) = (&self.model.vessel, &mut self.state.vessel) else {
            return;
        };
        let Some(controller) = attachment
            .controller
            .as_ref()
            .filter(|c| c.takes_over(self.state.time, dt))
        else {
            return;
        };
        let eta = low_frequency_eta(
            attachment,
            &self.state.configuration,
            self.vessel_waves.as_ref(),
        );
        motion.integral = transfer_integral(controller, &eta, &motion.hold_thrust);
    }

    /// The hull's environment over the step and, for a sampled controller that has started, the thrust it
    /// holds over the step, decided from the state at the step's start.
    fn decide_station_keeping(&mut self, time_mid: f64, dt: f64) -> Result<()> {
        self.applied_thrust = None;
        let (Some(attachment), Some(motion)) = (&self.model.vessel, &self.state.vessel) else {
            return Ok(());
        };
        if let Some(hull) = &self.hull {
            self.hull_values = hull.at(attachment, time_mid)?;
        }
        let controller = attachment
            .controller
            .as_ref()
            .filter(|c| time_mid >= c.start);
        if let (Some(station_keeping), Some(controller)) = (&mut self.station_keeping, controller) {
            let node = attachment.node;
            let configuration = &self.state.configuration;
            let (position, body) = vessel_pose(
                attachment,
                &configuration.positions[node],
                &configuration.rotations[node],
            );
            let low_frequency =
                low_frequency_eta(attachment, configuration, self.vessel_waves.as_ref());
            self.applied_thrust = Some(station_keeping.decide(
                attachment,
                controller,
                &eta_of(&position, &body),
                &low_frequency,
                &motion.velocity,
                &motion.integral,
                &self.reference_mid,
                dt,
            )?);
        }
        Ok(())
    }

    /// With pay-out: splits or joins the end element when its length calls for it, rebuilds what depends on
    /// the mesh and books the energy change of the new mesh (a split keeps it to round-off and the
    /// discretisation's O(h²)).
    fn remesh(&mut self) {
        let Some(growth) = self.growth else {
            return;
        };
        let before = self.observe().energy().total();
        if remesh::remesh(
            &mut self.model,
            &mut self.state,
            &mut self.reactions,
            growth.speed,
        )
        .is_none()
        {
            return;
        }
        self.rebuild();
        let after = self.observe().energy().total();
        self.ledger.book_pay_out(after - before);
    }

    /// Rebuilds what depends on the mesh after it changed (a split or join, or elements appended at or taken off
    /// end B). The rollers keep their friction slips; their forces, nearest elements and energy are evaluated
    /// afresh on the new mesh (below).
    fn rebuild(&mut self) {
        let rollers = self.assembler.rollers.take();
        let mut assembler = Assembler::new(&self.model);
        if let (Some(new), Some(old)) = (&mut assembler.rollers, rollers) {
            new.carry_slips(&old);
        }
        self.contact = assembler.contact.take();
        self.assembler = assembler;
        self.nodal = NodalProperties::new(&self.model);
        let count = self.model.rod.node_count();
        self.increments = vec![0.0; self.model.dof_count()];
        self.magnitude = vec![0.0; self.model.dof_count()];
        self.correction = vec![0.0; self.assembler.dofs.free];
        self.next_gauss.clone_from(&self.state.gauss);
        // Elements appended at end B (an A&R wire) do not yield.
        self.state.plastic.resize(count - 1, Vec::new());
        self.next_plastic.clone_from(&self.state.plastic);
        self.element_work = vec![ElementWork::default(); count - 1];
        self.node_dissipation = vec![0.0; count];
        self.round_off = round_off(&self.model);
        // A node inserted or taken off changes the spline the rollers see, so their energy (and forces) are
        // those of the new mesh at the current state (a step of zero increments), for the ledger to book the
        // change.
        self.assembler.add_rollers(
            ContactRule::EnergyMomentum {
                time_step: self.options.time_step,
                damping: 0.0,
            },
            &self.state.configuration,
            Some(&self.increments),
            None,
            false,
        );
        self.assembler.clear(false);
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
        // The step's end states become the state; the next evaluation overwrites every yielding element's end.
        std::mem::swap(&mut self.state.plastic, &mut self.next_plastic);
        for (i, rate) in self.state.hinge_rates.iter_mut().enumerate() {
            let change = self.increments[self.model.hinge_dof(i)];
            self.state.configuration.hinge_angles[i] += change;
            *rate = change / dt;
        }
        let points = self.state.section_velocities.len();
        self.state
            .section_velocities
            .copy_from_slice(&self.section_work.velocities[..points]);
        if let Some(contact) = &self.contact {
            self.state.slips.copy_from_slice(contact.slips());
        }
        if let Some(rollers) = &mut self.assembler.rollers {
            rollers.commit_slips();
        }
        if let (Some(attachment), Some(motion), Some(step)) = (
            &self.model.vessel,
            &mut self.state.vessel,
            &self.vessel_step,
        ) {
            let time_mid = self.state.time + 0.5 * dt;
            motion.acceleration = (step.velocity_next - motion.velocity) / dt;
            motion.velocity = step.velocity_next;
            motion.thrust = step.thrust;
            if attachment
                .controller
                .as_ref()
                .is_some_and(|c| c.passivity.is_some())
            {
                motion.passivity.book(
                    step.controller_work,
                    self.passivity_scale,
                    self.passivity_full_work,
                );
            }
            motion.setpoint_offset = self.offset_next;
            motion.filtered_tension = self.filtered_next;
            // The rod's force on the vessel, −(vessel's force on the rod), is the vessel end's reaction.
            self.reactions[attachment.node] = -self.rod_force_at_vessel;
            let sampled = self
                .station_keeping
                .as_mut()
                .filter(|_| self.applied_thrust.is_some())
                .and_then(|station_keeping| station_keeping.accept(dt));
            if let Some(integral) = sampled {
                motion.integral = integral;
            } else if let Some(controller) = attachment
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
        self.ledger
            .book_step(self.work.supplied + support_work, self.work.dissipated);
        self.ledger.book_plastic(self.work.plastic);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::configuration::Configuration;
    use crate::environment::current::{Current, CurrentProfile};
    use crate::environment::sea::Sea;
    use crate::rod::attachment::Attachment;
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

    /// The largest relative difference between the assembled tangent of `sim`'s next step and central
    /// differences of its assembled residual, column by column, at an iterate away from the predictor.
    fn tangent_error(sim: &mut Integrator) -> f64 {
        tangent_error_with_step(sim, 1e-5)
    }

    /// [`tangent_error`] with the differences' step `h` (a yielding wall's stresses have kinks where its fibres
    /// yield: a step small enough not to straddle one).
    fn tangent_error_with_step(sim: &mut Integrator, h: f64) -> f64 {
        let (dt, time_mid) = at_predictor(sim);
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
        worst
    }

    /// A cantilever whose wall yields (the thin tube, elastic–perfectly plastic) under a sudden end moment of
    /// 1.2 M_y about one axis and 0.3 M_y about the other: once it has yielded, the step's tangent (the fibres'
    /// path-averaged stresses' derivative) equals central differences of the residual.
    #[test]
    fn step_tangent_of_a_yielding_wall_matches_differences_of_the_residual() {
        use crate::rod::material::Material;
        let (d, t, e, fy) = (0.4, 0.002, 200e9, 400e6);
        let mut section = Section::pipe(d, t, 7850.0, e, 0.3, 0.0, [0.0, 0.0], [0.0, 0.0]).unwrap();
        if let Some(wall) = section.wall.as_mut() {
            wall.material = Some(Material::elastic_perfectly_plastic(e, fy).unwrap());
        }
        let rod =
            Rod::straight(Vector3::zeros(), Vector3::new(10.0, 0.0, 0.0), 10, section).unwrap();
        let mut model = Model::new(rod, None, 0.0).unwrap();
        model.clamp("A", None, None).unwrap();
        let inertia = std::f64::consts::PI / 64.0 * (d.powi(4) - (d - 2.0 * t).powi(4));
        let moment_y = e * inertia * fy / (e * 0.5 * (d - t));
        model
            .point_load(
                -1,
                Vector3::zeros(),
                Vector3::new(0.0, 1.2 * moment_y, 0.3 * moment_y),
                None,
            )
            .unwrap();
        let state = DynamicState::at_rest(&model, Configuration::reference(&model), 0.0).unwrap();
        let options = DynamicOptions {
            time_step: 0.01,
            ..DynamicOptions::default()
        };
        let mut sim = Integrator::new(model, state, options).unwrap();
        for _ in 0..30 {
            sim.step().unwrap();
        }
        assert!(
            sim.ledger().dissipated() > 0.0,
            "the wall must have yielded"
        );
        // Kinks where fibres yield spoil the larger steps, round-off the smaller: the best of three.
        let worst = [1e-6, 1e-7, 1e-8]
            .into_iter()
            .map(|h| {
                let mut copy =
                    Integrator::new(sim.model.clone(), sim.state.clone(), sim.options).unwrap();
                let error = tangent_error_with_step(&mut copy, h);
                println!("h {h:e}: worst relative error {error:.2e}");
                error
            })
            .fold(f64::INFINITY, f64::min);
        assert!(worst < 1e-4, "{worst:e}");
    }

    /// With an articulated stinger in a current, the step's tangent over the hinge angles (the rollers on the
    /// sections, their inertia, drag and springs) equals central differences of the residual.
    #[test]
    fn step_tangent_with_hinged_sections_matches_differences_of_the_residual() {
        let model = crate::vessel::stinger_sections::tests::articulated_s_lay();
        let solution = crate::statics::solve::solve(&model, &Default::default()).expect("statics");
        let state = DynamicState::at_rest(&model, solution.configuration, 0.0).expect("state");
        let options = DynamicOptions {
            time_step: 0.1,
            ..DynamicOptions::default()
        };
        let mut sim = Integrator::new(model, state, options).expect("integrator");
        for _ in 0..5 {
            sim.step().expect("step");
        }
        let worst = tangent_error(&mut sim);
        println!("worst relative error {worst:.2e}");
        assert!(worst < 1e-4, "{worst:e}");
    }

    /// The assembled tangent of a step (elements, inertia with added mass by direction, damping, drag in a
    /// sheared current) equals central differences of the assembled residual.
    #[test]
    fn step_tangent_matches_differences_of_the_residual() {
        let worst = tangent_error(&mut moving_pipe(20));
        assert!(worst < 1e-4, "worst relative error {worst:e}");
    }

    /// So it does with a clump on the line, its drag in the sheared current included.
    #[test]
    fn step_tangent_with_an_attachment_matches_differences_of_the_residual() {
        let mut sim = moving_pipe(0);
        let clump = Attachment::new(37.0, 2e3, 0.5, 3.0, 1.0).expect("clump");
        sim.model.attach(clump).expect("attach");
        sim.nodal = NodalProperties::new(&sim.model);
        for _ in 0..20 {
            sim.step().expect("step");
        }
        let worst = tangent_error(&mut sim);
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
