//! What users read off a configuration: section forces, tension, support reactions and energy.
// Indexing cannot go out of bounds here: Node and element indices of the configuration evaluated (the model's mesh).
#![allow(clippy::indexing_slicing)]
use crate::assembly::assembler::Assembler;
use crate::assembly::configuration::Configuration;
use crate::assembly::dofs::NODE_DOFS;
use crate::contact::touchdown::Touchdown;
use crate::model::Model;
use crate::rod::cable;
use crate::rod::element::{elastic_law, evaluate_with};
use crate::rod::plastic_state::PlasticState;
use crate::vessel::coupling::{eta_of, pipe_force_on_vessel, vessel_pose};
use nalgebra::{Vector2, Vector3, Vector6};

/// Derived quantities of a configuration at full load.
#[derive(Debug, Clone)]
pub struct Response {
    /// Material force N and moment M at each element midpoint: [N1, N2, N3, M1, M2, M3].
    pub section_forces: Vec<Vector6<f64>>,
    /// Force and moment the rod exerts on each node's support (or vessel), in e: −(f_int − f_ext) at that node.
    pub nodal_reactions: Vec<Vector6<f64>>,
    /// Strain energy (J).
    pub strain_energy: f64,
    /// Potential of the submerged weight (J), zero at z = 0.
    pub gravity_energy: f64,
    /// With a vessel: its pose η, the holding thrust τ and the pipe's force on it χ (body frame), and its
    /// restoring energy (J).
    pub vessel: Option<VesselResponse>,
    /// With a seabed: its contact.
    pub seabed: Option<SeabedResponse>,
    /// With rollers: their contact.
    pub rollers: Option<RollerResponse>,
    /// Where a segment's wall yields: each element's largest plastic strain over its wall (0 for an elastic
    /// element), and its residual curvature |κ − m/EI| (1/m): the bending curvature it keeps unloaded
    /// elastically; in a lay, with the pipe's history from the hold point ([`plastic_field`]).
    pub plastic: Option<PlasticResponse>,
}

/// The plastic strain and residual curvature of each element (see [`Response::plastic`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticResponse {
    pub plastic_strain: Vec<f64>,
    pub residual_curvature: Vec<f64>,
}

/// Roller contact of a configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct RollerResponse {
    /// Each roller's normal force (N, ≥ 0).
    pub forces: Vec<f64>,
    /// Each roller's force on the pipe, body frame (N), and where its contact lies along it from its centre
    /// (m; NaN out of contact).
    pub reactions: Vec<Vector3<f64>>,
    pub offsets: Vec<f64>,
    /// The element nearest each roller.
    pub elements: Vec<usize>,
    /// Energy stored in the contacts (J).
    pub energy: f64,
}

/// Seabed contact of a configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct SeabedResponse {
    /// The seabed's force on each node (N, in e).
    pub forces: Vec<Vector3<f64>>,
    /// Energy stored in the contact: normal springs and friction's elastic slip (J).
    pub energy: f64,
    pub touchdown: Touchdown,
    /// Elastic friction slip per node (axial, lateral) (m): the state friction starts a simulation from.
    pub slips: Vec<Vector2<f64>>,
}

/// Static quantities of an attached vessel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VesselResponse {
    pub eta: Vector6<f64>,
    pub thrust: Vector6<f64>,
    pub pipe_force: Vector6<f64>,
    pub restoring_energy: f64,
}

/// Each element's largest plastic strain and residual curvature in the configuration `positions`,
/// `rotations` (see [`Response::plastic`]); None where no wall yields. In a lay (a vessel's lay equipment holds
/// the line) from the pipe's steady-lay history: its fibres' state marched from the hold point through the
/// configuration ([`PlasticState::march`]), so that the laid pipe carries the plastic strain and the residual
/// curvature the overbend left; elsewhere from `state`'s starts (the unyielded state without one). In a run,
/// from the run's plastic state `run` (each element's, consistent with the configuration).
pub fn plastic_field(
    model: &Model,
    positions: &[Vector3<f64>],
    rotations: &[nalgebra::UnitQuaternion<f64>],
    state: Option<&PlasticState>,
    run: Option<&[Vec<f64>]>,
) -> Option<PlasticResponse> {
    let mut state = match state {
        Some(state) => state.clone(),
        None => model.plastic_state()?,
    };
    if let Some(run) = run {
        state.start_from(run);
    }
    let lay = model
        .vessel
        .as_ref()
        .filter(|v| v.lay.is_some() && run.is_none())
        .map(|v| v.node);
    if let Some(hold) = lay {
        state.march(&model.rod, positions, rotations, hold);
        // The states each element ends with are the ones the residual curvature is read from.
        state.commit();
    }
    let (plastic_strain, residual_curvature) = model
        .rod
        .elements
        .iter()
        .enumerate()
        .map(|(e, _)| {
            if !state.yields(e) {
                return (0.0, 0.0);
            }
            let (strain, curvature) = model.rod.strain_changes(e, positions, rotations);
            let plastic = state.largest_plastic_strain(e, &strain, &curvature);
            let moment = state
                .law(e, &strain, &curvature, 1.0)
                .map_or_else(Vector3::zeros, |law| law.moment);
            let kept = model.rod.section(e).residual_curvature(&curvature, &moment);
            (plastic, kept)
        })
        .unzip();
    Some(PlasticResponse {
        plastic_strain,
        residual_curvature,
    })
}

impl Response {
    /// Evaluates `config` of `model` at full load.
    pub fn new(model: &Model, config: &Configuration) -> Self {
        Self::with_assembler(model, config, &mut Assembler::new(model))
    }

    /// Same, reusing an assembler built for `model`.
    pub fn with_assembler(
        model: &Model,
        config: &Configuration,
        assembler: &mut Assembler,
    ) -> Self {
        let section_forces: Vec<Vector6<f64>> = model
            .rod
            .elements
            .iter()
            .enumerate()
            .map(|(e, reference)| {
                let section = model.rod.section(e);
                if section.cable {
                    let (x1, x2) = (&config.positions[e], &config.positions[e + 1]);
                    let ea = section.translational_stiffness.x;
                    let tension = cable::evaluate(x1, x2, reference, ea, None).tension;
                    return Vector6::new(tension, 0.0, 0.0, 0.0, 0.0, 0.0);
                }
                let (c_t, c_r) = (section.c_t(), section.c_r());
                let plastic = &mut assembler.plastic;
                let mut law = |strain: &Vector3<f64>, curvature: &Vector3<f64>| {
                    plastic
                        .as_mut()
                        .and_then(|p| p.law(e, strain, curvature, 1.0))
                        .unwrap_or_else(|| elastic_law(&c_t, &c_r, strain, curvature))
                };
                let r = evaluate_with(
                    &config.positions[e],
                    &config.positions[e + 1],
                    &config.rotations[e],
                    &config.rotations[e + 1],
                    reference,
                    &mut law,
                    None,
                );
                Vector6::new(
                    r.material_force.x,
                    r.material_force.y,
                    r.material_force.z,
                    r.material_moment.x,
                    r.material_moment.y,
                    r.material_moment.z,
                )
            })
            .collect();
        let summary = assembler.assemble(model, config, 1.0, false, None);
        let mut nodal_reactions: Vec<Vector6<f64>> = assembler
            .residual
            .chunks_exact(NODE_DOFS)
            .take(model.rod.node_count())
            .map(|r| -Vector6::from_column_slice(r))
            .collect();
        // At a vessel's node the "support" is the vessel: the rod pushes on it with −(vessel's force on the rod).
        if let Some(attachment) = &model.vessel {
            nodal_reactions[attachment.node] = -assembler.vessel_force;
        }
        let vessel = model.vessel.as_ref().map(|attachment| {
            let node = attachment.node;
            let (position, body) =
                vessel_pose(attachment, &config.positions[node], &config.rotations[node]);
            let pipe_force = pipe_force_on_vessel(
                attachment,
                &config.rotations[node],
                &assembler.vessel_force,
                None,
            );
            VesselResponse {
                eta: eta_of(&position, &body),
                thrust: assembler.vessel_thrust,
                pipe_force,
                restoring_energy: attachment.vessel.restoring_energy(
                    &position,
                    &body,
                    attachment.surface,
                ),
            }
        });
        let seabed = assembler.contact.as_ref().map(|contact| SeabedResponse {
            forces: contact.forces.clone(),
            energy: contact.energy_end,
            touchdown: contact.touchdown(&config.positions),
            slips: contact.slip_end.clone(),
        });
        let rollers = assembler.rollers.as_ref().map(|r| RollerResponse {
            forces: r.forces.clone(),
            reactions: r.reactions.clone(),
            offsets: r.offsets.clone(),
            elements: r.nearest_elements.clone(),
            energy: r.energy_end,
        });
        let plastic = assembler.plastic.as_ref().and_then(|state| {
            plastic_field(
                model,
                &config.positions,
                &config.rotations,
                Some(state),
                None,
            )
        });
        Response {
            plastic,
            rollers,
            seabed,
            vessel,
            section_forces,
            nodal_reactions,
            strain_energy: summary.strain_energy,
            gravity_energy: config.gravity_potential(model),
        }
    }
}
