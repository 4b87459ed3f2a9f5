//! What can be read off the integrator's current state: the storage function's parts, momenta, section
//! forces, the touchdown, contact forces, the lay summary and the vessel's values. A read-only view: it
//! changes nothing and the step does not depend on it except through the values it returns.
// Indexing cannot go out of bounds here: Node and element indices of the state's own mesh.
#![allow(clippy::indexing_slicing)]
use crate::contact::rollers::RollerContact;
use crate::contact::seabed::SeabedContact;
use crate::contact::touchdown::Touchdown;
use crate::dynamics::ledger::Energy;
use crate::dynamics::nodal::NodalProperties;
use crate::dynamics::state::DynamicState;
use crate::model::Model;
use crate::response::lay_summary::{lay_summary, residual_curvatures, LaySummary, RollerContacts};
use crate::rod::dynamic_element::GaussPoint;
use crate::rod::element::ElementReference;
use crate::rod::fibre_section::FibreSection;
use crate::rod::plastic_state::PlasticState;
use crate::rod::section::Section;
use crate::vessel::coupling::{eta_of, low_frequency_pose, vessel_pose};
use crate::vessel::rigid_body::kinetic_energy;
use crate::vessel::stinger_sections::StingerSections;
use crate::vessel::wave_motion::WaveOffset;
use crate::vessel::VesselAttachment;
use nalgebra::{Matrix3, Vector3, Vector6};

/// The strain energy an element stores at its Gauss point `gauss` over `reference` (J): a yielding wall's fibres'
/// free energy in their plastic state `plastic` (`fibres`: the wall, if it yields), else the elastic
/// [`GaussPoint::energy`] of `section`.
pub fn stored_energy(
    gauss: &GaussPoint,
    reference: &ElementReference,
    section: &Section,
    fibres: Option<&FibreSection>,
    plastic: &[f64],
) -> f64 {
    match fibres {
        Some(fibres) => {
            reference.length
                * fibres.energy(
                    &(gauss.strain - reference.strain),
                    &(gauss.curvature - reference.curvature),
                    plastic,
                )
        }
        None => gauss.energy(reference, &section.c_t(), &section.c_r()),
    }
}

/// A view of a state with what its observables need beside it.
#[derive(Clone, Copy)]
pub struct Observables<'a> {
    pub model: &'a Model,
    pub state: &'a DynamicState,
    /// The lumped inertia of the state's mesh.
    pub nodal: &'a NodalProperties,
    /// Seabed contact after the last step, if the model has a seabed.
    pub contact: Option<&'a SeabedContact>,
    /// Roller contact after the last step, if the vessel has rollers.
    pub rollers: Option<&'a RollerContact>,
    /// The vessel's wave-frequency offset at the state's time, in waves with RAOs.
    pub wave_offset: Option<&'a WaveOffset>,
    /// An articulated stinger's sections, if the vessel has one.
    pub sections: Option<&'a StingerSections>,
    /// The yielding elements' wall fibres, if any wall yields.
    pub plastic: Option<&'a PlasticState>,
}

impl<'a> Observables<'a> {
    /// The pipe's unstretched length (m).
    pub fn length(&self) -> f64 {
        self.model.rod.length()
    }

    /// The low-frequency pose (position of CO, body rotation) of the vessel `attachment` holds the rod by.
    fn vessel_pose(&self, attachment: &VesselAttachment) -> (Vector3<f64>, Matrix3<f64>) {
        let node = attachment.node;
        low_frequency_pose(
            attachment,
            &self.state.configuration.positions[node],
            &self.state.configuration.rotations[node],
            self.wave_offset,
        )
    }

    /// With a vessel: its η (the total motion, low and wave frequency), ν, the thrust τ and the pipe's force χ
    /// of the current state.
    pub fn vessel_values(&self) -> Option<[Vector6<f64>; 4]> {
        let state = &self.state;
        let (attachment, motion) = (self.model.vessel.as_ref()?, state.vessel.as_ref()?);
        let node = attachment.node;
        let (position, body) = vessel_pose(
            attachment,
            &state.configuration.positions[node],
            &state.configuration.rotations[node],
        );
        let eta = eta_of(&position, &body);
        Some([eta, motion.velocity, motion.thrust, motion.pipe_force])
    }

    /// With a vessel: its low-frequency η (the pose the DP controls; η itself without waves).
    pub fn vessel_low_frequency(&self) -> Option<Vector6<f64>> {
        let attachment = self.model.vessel.as_ref()?;
        let (position, body) = self.vessel_pose(attachment);
        Some(eta_of(&position, &body))
    }

    /// Energy of the current state.
    pub fn energy(&self) -> Energy {
        self.energy_with_strain(self.strain_energy())
    }

    /// The rod's stored strain energy (J): a yielding wall's its fibres' free energy.
    fn strain_energy(&self) -> f64 {
        let (rod, state) = (&self.model.rod, &self.state);
        state
            .gauss
            .iter()
            .zip(&rod.elements)
            .enumerate()
            .map(|(e, (g, reference))| {
                stored_energy(
                    g,
                    reference,
                    rod.section(e),
                    self.plastic.and_then(|p| p.fibres(e)),
                    &state.plastic[e],
                )
            })
            .sum()
    }

    /// Energy of the current state whose rod stores the strain energy `strain` (J).
    fn energy_with_strain(&self, strain: f64) -> Energy {
        let state = &self.state;
        let kinetic = (0..self.model.rod.node_count())
            .map(|i| self.nodal.kinetic_energy(state, i))
            .sum::<f64>()
            + (0..self.model.rod.element_count())
                .map(|e| self.nodal.element_kinetic_energy(state, e))
                .sum::<f64>();
        let (vessel_kinetic, vessel_potential) = match (&self.model.vessel, &state.vessel) {
            (Some(attachment), Some(motion)) => {
                let (position, body) = self.vessel_pose(attachment);
                (
                    kinetic_energy(&attachment.vessel, &motion.velocity),
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
            gravity: state.configuration.gravity_potential(self.model),
            vessel_kinetic,
            vessel_potential,
            seabed: self.contact.map_or(0.0, |contact| {
                contact.energy(&state.configuration.positions, &state.slips)
            }),
            rollers: self.rollers.map_or(0.0, |r| r.energy_end),
            stinger: self.stinger_energy(),
        }
    }

    /// The articulated stinger's sections' energy (J; 0 without).
    fn stinger_energy(&self) -> f64 {
        let (Some(sections), Some(attachment)) = (self.sections, &self.model.vessel) else {
            return 0.0;
        };
        let config = &self.state.configuration;
        sections.energy(
            &config.positions[attachment.node],
            &config.rotations[attachment.node],
            &config.hinge_angles,
            &self.state.section_velocities,
        )
    }

    /// Where the pipe leaves the seabed in the current state; `None` without a seabed.
    pub fn touchdown(&self) -> Option<Touchdown> {
        self.contact
            .map(|contact| contact.touchdown(&self.state.configuration.positions))
    }

    /// The seabed's force on each node over the last step (N, in e); `None` without a seabed.
    pub fn seabed_forces(&self) -> Option<&'a [Vector3<f64>]> {
        self.contact.map(|contact| &contact.forces[..])
    }

    /// The lay summary of the current state, whose section forces are `section_forces`; `None` without a
    /// vessel.
    pub fn lay_summary(&self, section_forces: &[Vector6<f64>]) -> Option<LaySummary> {
        let state = &self.state;
        let configuration = &state.configuration;
        let residuals = self.plastic.map(|_| {
            residual_curvatures(
                self.model,
                &configuration.positions,
                &configuration.rotations,
                section_forces,
            )
        });
        lay_summary(
            self.model,
            &state.configuration.positions,
            &state.configuration.rotations,
            &state.configuration.hinge_angles,
            section_forces,
            self.rollers.map(|r| RollerContacts {
                forces: &r.forces,
                elements: &r.nearest_elements,
                offsets: &r.offsets,
            }),
            self.touchdown().as_ref(),
            residuals.as_deref(),
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
        (self.model.rod.section(element).c_t() * strain).x
    }

    /// Each roller's normal force in the current state (N); `None` without rollers.
    pub fn roller_forces(&self) -> Option<&'a [f64]> {
        self.rollers.map(|r| &r.forces[..])
    }

    /// Each roller's force on the pipe (body frame, N) and its contact's offset along it (m; NaN out of
    /// contact) in the current state; `None` without rollers.
    pub fn roller_reactions(&self) -> Option<(&'a [Vector3<f64>], &'a [f64])> {
        self.rollers.map(|r| (&r.reactions[..], &r.offsets[..]))
    }

    /// Linear momentum Σ M_I v_I (kg·m/s), M_I with the added mass by direction.
    pub fn linear_momentum(&self) -> Vector3<f64> {
        (0..self.model.rod.node_count())
            .map(|i| self.nodal.momentum(self.state, i))
            .sum::<Vector3<f64>>()
            + (0..self.model.rod.element_count())
                .map(|e| self.nodal.element_momentum(self.state, e))
                .sum::<Vector3<f64>>()
    }

    /// Angular momentum about the origin Σ (φ_I × M_I v_I + Λ_I J_I W_I) (kg·m²/s).
    pub fn angular_momentum(&self) -> Vector3<f64> {
        let state = &self.state;
        (0..self.model.rod.node_count())
            .map(|i| {
                let spin = state.configuration.rotations[i]
                    * self.nodal.inertia[i].component_mul(&state.body_angular_velocities[i]);
                state.configuration.positions[i].cross(&self.nodal.momentum(state, i)) + spin
            })
            .sum::<Vector3<f64>>()
            + (0..self.model.rod.element_count())
                .map(|e| {
                    let positions = &state.configuration.positions;
                    let middle = 0.5 * (positions[e] + positions[e + 1]);
                    middle.cross(&self.nodal.element_momentum(state, e))
                })
                .sum::<Vector3<f64>>()
    }

    /// Material force and moment [N; M] at the element Gauss points of the current state.
    pub fn section_forces(&self) -> Vec<Vector6<f64>> {
        self.section_forces_and_energy().0
    }

    /// [`Self::section_forces`] and [`Self::energy`] at once: a yielding wall's fibres read once for both.
    pub fn section_forces_and_energy(&self) -> (Vec<Vector6<f64>>, Energy) {
        let rod = &self.model.rod;
        let mut strain_energy = 0.0;
        let forces = self
            .state
            .gauss
            .iter()
            .zip(&rod.elements)
            .enumerate()
            .map(|(e, (g, reference))| {
                let (strain, curvature) = (
                    g.strain - reference.strain,
                    g.curvature - reference.curvature,
                );
                // A yielding wall's from its fibres' state.
                let (n, m) = match self.plastic.and_then(|p| p.fibres(e)) {
                    Some(fibres) => {
                        let (n, m, energy) = fibres.resultants_and_energy(
                            &strain,
                            &curvature,
                            &self.state.plastic[e],
                        );
                        strain_energy += reference.length * energy;
                        (n, m)
                    }
                    None => {
                        let section = rod.section(e);
                        strain_energy += g.energy(reference, &section.c_t(), &section.c_r());
                        (
                            self.state.material_force(self.model, e),
                            section.c_r() * curvature,
                        )
                    }
                };
                Vector6::new(n.x, n.y, n.z, m.x, m.y, m.z)
            })
            .collect();
        (forces, self.energy_with_strain(strain_energy))
    }
}
