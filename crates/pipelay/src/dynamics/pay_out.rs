//! Pay-out and pay-in within a time step: the end element grows (or shrinks) with the pay-out speed, its
//! nodes' lumps follow, and the energy this brings in is measured for the ledger. When the element's length
//! calls for it the integrator changes the mesh ([`crate::dynamics::remesh`]) after the step.
// Indexing cannot go out of bounds here: the growing element and its two nodes, of the model's own mesh.
#![allow(clippy::indexing_slicing)]
use crate::dynamics::hand_back;
use crate::dynamics::nodal::NodalProperties;
use crate::dynamics::observables::stored_energy;
use crate::dynamics::stages::DEFAULT_RAMP;
use crate::dynamics::state::DynamicState;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::rod::dynamic_element::GaussPoint;
use crate::rod::element::ElementReference;
use crate::rod::plastic_state::PlasticState;
use crate::vessel::winch::WinchLaw;

/// The element that grows with pay-out in the current step.
#[derive(Debug, Clone, Copy)]
pub struct Growth {
    pub element: usize,
    /// Its reference length at the step's start (m); the model holds the length at the step's end.
    pub length_start: f64,
    /// Work of its internal forces over the step (J).
    pub internal_work: f64,
    /// The pay-out speed over the step (m/s); with a winch whose speed depends on the wire's tension, the
    /// predicted one until the step is solved ([`Growth::settle`]).
    pub speed: f64,
    /// The winch's law over the step, if its speed depends on its wire's tension.
    pub winch: Option<WinchLaw>,
}

impl Growth {
    /// With pay-out: sets the end element's length in `model` to its value at the step's end (the speed at
    /// the step's midpoint times Δt added) and its nodes' lumps in `nodal` to match. Returns the growth and the
    /// energy the change of mass brings in at the step's start `state` (kinetic, and the potential of the
    /// submerged weight); `None` without pay-out.
    pub fn start(
        model: &mut Model,
        nodal: &mut NodalProperties,
        state: &DynamicState,
        dt: f64,
    ) -> Result<Option<(Growth, f64)>> {
        let (Some(pay_out), Some((element, _))) = (&model.pay_out, model.growing_element()) else {
            return Ok(None);
        };
        let time = state.time;
        let mut commanded = pay_out.speed_at(time + 0.5 * dt)?;
        // Hauling its wire in to the hold point, the winch slows down to stop there for the hand-back, over the
        // time a stage's change of speed takes (within its acceleration limit).
        if let (Some(remaining), Some(winch)) = (
            hand_back::remaining(model, state),
            model.vessel.as_ref().and_then(|v| v.holding_winch()),
        ) {
            let deceleration = winch
                .drive
                .acceleration_limit
                .min(commanded.abs() / DEFAULT_RAMP);
            commanded = commanded.max(hand_back::approach_speed(remaining, deceleration, dt));
        }
        // A holding winch runs within its drive's limits: its speed over the step follows its law, of the
        // wire's tension at the step's end where it renders or holds a tension; predicted here from the
        // step before.
        let winch = model
            .vessel
            .as_ref()
            .and_then(|v| v.holding_winch())
            .map(|w| WinchLaw::of(w, time + 0.5 * dt, dt, commanded, state.pay_out_speed));
        let tension =
            model.rod.section(element).translational_stiffness.x * state.gauss[element].strain.x;
        let speed = winch.map_or(commanded, |law| law.speed(tension).0);
        let winch = winch.filter(WinchLaw::renders);
        let length_start = model.rod.elements[element].length;
        let length_next = length_start + speed * dt;
        // The shortest the step may leave the element.
        let shortest = length_start + winch.map_or(speed, |law| law.lowest.min(speed)) * dt;
        if shortest < 0.05 * pay_out.element_length {
            let reason = if model.is_last_wire_element(element) {
                "the winch hauls its wire in past the pipe's end: the tensioner takes the pipe back at the hold \
                 point, which a winch in constant-tension mode or a line without lay equipment does not reach"
            } else if model.rod.element_count() == 1 {
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
        // Attachments are placed from end A, so pay-out at end B leaves them on their material; pay-in must
        // not reach one.
        if let Some(arc) = model.attachment_on_element(element) {
            return Err(Error::input(
                "pay_out speed",
                format!("{speed} m/s at t = {time} s"),
                format!("pay-in has reached the attachment at {arc} m from end A: it cannot pass the end"),
            ));
        }
        let before = element_lump_energy(model, nodal, state, element);
        model.rod.elements[element].length = length_next;
        nodal.recompute(model, element);
        nodal.recompute(model, element + 1);
        let growth = Growth {
            element,
            length_start,
            internal_work: 0.0,
            speed,
            winch,
        };
        let brought_in = element_lump_energy(model, nodal, state, element) - before;
        Ok(Some((growth, brought_in)))
    }

    /// After a converged step whose winch renders or holds a tension: the wire's unstretched length at the
    /// step's end from its law at the chord `chord_next` (m) of the step's end, and the speed it ran at. Sets
    /// the length in `model`; the lumps, still those of the predicted length, follow in [`Growth::settle`].
    pub fn solve_length(&mut self, model: &mut Model, chord_next: f64, dt: f64) {
        let Some(law) = self.winch else {
            return;
        };
        let ea = model.rod.section(self.element).translational_stiffness.x;
        let (length, _) = law.length(ea, self.length_start, dt, chord_next);
        model.rod.elements[self.element].length = length;
        self.speed = (length - self.length_start) / dt;
    }

    /// After the step was committed to `state`: the lumps of the growing element's nodes follow its length
    /// (they took the predicted length over the step). Returns the energy the change brings in at `state`
    /// (J): the lumps' kinetic energy and the potential of the submerged weight of the predicted length
    /// `predicted` (m) before, of the solved length after.
    pub fn settle(
        &self,
        model: &mut Model,
        nodal: &mut NodalProperties,
        state: &DynamicState,
        predicted: f64,
    ) -> f64 {
        let e = self.element;
        let solved = model.rod.elements[e].length;
        model.rod.elements[e].length = predicted;
        let before = element_lump_energy(model, nodal, state, e);
        model.rod.elements[e].length = solved;
        nodal.recompute(model, e);
        nodal.recompute(model, e + 1);
        element_lump_energy(model, nodal, state, e) - before
    }

    /// Restores the end element's length and lumps after a failed step.
    pub fn undo(&self, model: &mut Model, nodal: &mut NodalProperties) {
        model.rod.elements[self.element].length = self.length_start;
        nodal.recompute(model, self.element);
        nodal.recompute(model, self.element + 1);
    }

    /// After a converged step from `state` to the Gauss points `next_gauss` (and a yielding wall's plastic
    /// states `next_plastic`, `plastic` its wall's fibres): the growing element's stored-energy change and the
    /// dissipation `dissipated` it booked, less the work of its internal forces over the step, the energy its
    /// change of reference length brought in (J).
    pub fn strain_energy(
        &self,
        model: &Model,
        state: &DynamicState,
        next_gauss: &[GaussPoint],
        plastic: Option<&PlasticState>,
        next_plastic: &[Vec<f64>],
        dissipated: f64,
    ) -> f64 {
        let e = self.element;
        let section = model.rod.section(e);
        let fibres = plastic.and_then(|p| p.fibres(e));
        let reference = model.rod.elements[e];
        let start = ElementReference {
            length: self.length_start,
            ..reference
        };
        stored_energy(
            &next_gauss[e],
            &reference,
            section,
            fibres,
            &next_plastic[e],
        ) - stored_energy(&state.gauss[e], &start, section, fibres, &state.plastic[e])
            + dissipated
            - self.internal_work
    }
}

/// Kinetic energy of an element's two nodes and the potential of its submerged weight (J).
fn element_lump_energy(
    model: &Model,
    nodal: &NodalProperties,
    state: &DynamicState,
    element: usize,
) -> f64 {
    let positions = &state.configuration.positions;
    nodal.kinetic_energy(state, element)
        + nodal.kinetic_energy(state, element + 1)
        + nodal.element_kinetic_energy(state, element)
        - 0.5
            * model.rod.elements[element].length
            * model.submerged_weight(element)
            * (positions[element].z + positions[element + 1].z)
}
