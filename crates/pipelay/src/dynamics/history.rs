//! The record of a simulation: states at chosen steps, reactions at the ends, energy and its ledger.
//!
//! A record is made from a [`Snapshot`], a view of one state that the integrator hands over: the history
//! knows nothing of how states are computed.
// Indexing cannot go out of bounds here: Snapshots always hold at least one node's reactions (a rod has at least 2 nodes).
#![allow(clippy::indexing_slicing)]
use crate::contact::touchdown::Touchdown;
use crate::dynamics::ledger::Energy;
use crate::error::Result;
use crate::memory::{reserve, vec_with_capacity};
use crate::response::lay_summary::LaySummary;
use nalgebra::{UnitQuaternion, Vector3, Vector6};

/// What one record holds, borrowed from the state it describes.
#[derive(Debug, Clone)]
pub struct Snapshot<'a> {
    /// Time (s).
    pub time: f64,
    pub positions: &'a [Vector3<f64>],
    pub rotations: &'a [UnitQuaternion<f64>],
    pub velocities: &'a [Vector3<f64>],
    /// Material force and moment at the elements' Gauss points.
    pub section_forces: Vec<Vector6<f64>>,
    /// The segment of each element.
    pub segment_of: &'a [usize],
    /// Force and moment the rod exerts on each node's support (N, N·m).
    pub reactions: &'a [Vector6<f64>],
    pub energy: Energy,
    /// With a vessel: η (total motion), ν, τ and χ.
    pub vessel: Option<[Vector6<f64>; 4]>,
    /// With a vessel: what its station keeping records.
    pub station: Option<StationRecord>,
    /// With a seabed: where the pipe leaves it.
    pub touchdown: Option<Touchdown>,
    /// With rollers: each roller's normal force (N) and its force on the pipe (body frame, N).
    pub roller_forces: Option<&'a [f64]>,
    pub roller_vectors: Option<&'a [Vector3<f64>]>,
    /// An articulated stinger's hinge angles (rad; empty without).
    pub hinge_angles: &'a [f64],
    /// With a vessel: the lay summary.
    pub lay: Option<LaySummary>,
    /// Work supplied and energy dissipated since the integrator started (J).
    pub supplied_work: f64,
    pub dissipated: f64,
    /// The pipe's unstretched length (m).
    pub length: f64,
    /// The pay-out speed of the step that led here (m/s): the tensioner's, or the winch's once it holds.
    pub pay_out_speed: f64,
    /// Energy pay-out brought in since the integrator started (J; part of `supplied_work`).
    pub pay_out_energy: f64,
    /// Energy the yielding walls dissipated since the integrator started (J; part of `dissipated`).
    pub plastic_dissipation: f64,
    /// Newton iterations of the step that led to this state.
    pub iterations: usize,
    /// The most substeps any step since the last record was taken in (1: none split).
    pub substeps: usize,
    /// With a controller that certifies the loop: the passivity observer's ledger.
    pub passivity: Option<crate::dynamics::passivity::PassivityLedger>,
}

/// A vessel's station keeping at one record.
#[derive(Debug, Clone, PartialEq)]
pub struct StationRecord {
    /// The low-frequency pose (what the DP controls).
    pub eta_low_frequency: Vector6<f64>,
    /// The observer's estimate of it, if there is an observer.
    pub eta_estimate: Option<Vector6<f64>>,
    /// The controller's command over the last step (body frame).
    pub tau_commanded: Vector6<f64>,
    /// With allocation: each thruster's thrust (N) and azimuth (rad).
    pub thrust: Vec<f64>,
    pub azimuth: Vec<f64>,
}

/// Time series of a run, stored flat (row-major: time first) for cheap hand-over to arrays.
///
/// With pay-out the number of nodes changes during a run: node series are as wide as the most nodes any
/// record had, and the rows of records with fewer nodes end in NaN.
#[derive(Debug, Clone, Default)]
pub struct History {
    /// Number of nodes n + 1 (the most of any record).
    pub nodes: usize,
    /// Times (s).
    pub time: Vec<f64>,
    /// Node positions, (T, n+1, 3) (m).
    pub positions: Vec<f64>,
    /// Nodal rotations R_t^e, (T, n+1, 3, 3) row-major.
    pub rotations: Vec<f64>,
    /// Node velocities, (T, n+1, 3) (m/s).
    pub velocities: Vec<f64>,
    /// Section forces at element midpoints, (T, n, 6): [N; M] material (N, N·m).
    pub section_forces: Vec<f64>,
    /// The segment of each element, (T, n) (NaN where a record had fewer elements).
    pub segment: Vec<f64>,
    /// Force and moment the rod exerts on the supports at ends A and B, (T, 6) each.
    pub reaction_a: Vec<f64>,
    pub reaction_b: Vec<f64>,
    /// Energy parts (J).
    pub kinetic: Vec<f64>,
    pub strain: Vec<f64>,
    pub gravity: Vec<f64>,
    pub vessel_kinetic: Vec<f64>,
    pub vessel_potential: Vec<f64>,
    /// Energy stored in the seabed contact (J).
    pub seabed: Vec<f64>,
    /// Energy stored in the roller contacts (J).
    pub rollers: Vec<f64>,
    /// An articulated stinger's sections' energy (J): kinetic, weight less buoyancy's potential, hinges'.
    pub stinger: Vec<f64>,
    /// An articulated stinger's hinge angles, (T, h) (rad); empty without.
    pub hinge_angles: Vec<f64>,
    /// Number of hinges h.
    pub hinges_count: usize,
    /// With rollers: each roller's normal force, (T, k) (N), and its force on the pipe in the body frame,
    /// (T, k, 3) (N); empty without (the vectors also in files written before they were recorded).
    pub roller_reactions: Vec<f64>,
    pub roller_vectors: Vec<f64>,
    /// With a vessel: the lay summary of each record, (T, 13) in the order of
    /// [`crate::response::lay_summary::LAY_FIELDS`]; empty without.
    pub lay: Vec<f64>,
    /// Number of rollers k.
    pub rollers_count: usize,
    /// With a seabed: touchdown positions (T, 3), NaN where the pipe does not touch, its arc length from end A
    /// along the reference (T,) and the laid length (T,) (m); empty without a seabed.
    pub touchdown: Vec<f64>,
    pub touchdown_arc_length: Vec<f64>,
    pub laid_length: Vec<f64>,
    /// With a vessel: η (e), ν, thrust τ and the pipe's force χ (body frame), (T, 6) each; empty without.
    pub eta: Vec<f64>,
    pub nu: Vec<f64>,
    pub tau: Vec<f64>,
    pub chi: Vec<f64>,
    /// With a vessel: its low-frequency η and the controller's command τ_c, (T, 6) each; with an observer its
    /// estimate η̂ (T, 6); with allocation each thruster's thrust and azimuth, (T, k); empty otherwise.
    pub eta_low_frequency: Vec<f64>,
    pub tau_commanded: Vec<f64>,
    pub eta_estimate: Vec<f64>,
    pub thrust: Vec<f64>,
    pub azimuth: Vec<f64>,
    /// Number of thrusters k (0 without allocation).
    pub thrusters_count: usize,
    /// Work supplied and energy dissipated since the start of the run (J).
    pub supplied_work: Vec<f64>,
    pub dissipated: Vec<f64>,
    /// Newton iterations of the step that led to each record (0 for the first).
    pub iterations: Vec<usize>,
    /// The most substeps any step since the record before was taken in (1: none split; 1 for the first).
    pub substeps: Vec<usize>,
    /// The pipe's unstretched length at each record (m).
    pub length: Vec<f64>,
    /// The pay-out speed of the step that led to each record (m/s; the winch's once it holds).
    pub pay_out_speed: Vec<f64>,
    /// Energy pay-out brought in since the start of the run (J; part of `supplied_work`).
    pub pay_out_energy: Vec<f64>,
    /// Energy the yielding walls dissipated since the start of the run (J; part of `dissipated`).
    pub plastic_dissipation: Vec<f64>,
    /// With a controller that certifies the loop ([`crate::dynamics::passivity`]), each (T,): the energy it may
    /// still give the vessel, E₀ − W_c (J, ≥ 0 when certified); the controller's work the passivity controller
    /// withheld (J) and the steps it acted in, since the simulation started (a resumed one continues them).
    /// Empty otherwise.
    pub passivity_reserve: Vec<f64>,
    pub passivity_withheld: Vec<f64>,
    pub passivity_steps: Vec<f64>,
    /// Ledger values at the start of the run, so that the record starts from zero.
    supplied_offset: f64,
    dissipated_offset: f64,
    pay_out_offset: f64,
    plastic_offset: f64,
}

impl History {
    /// An empty history whose first record is `first`; its ledger counts from there.
    pub fn starting_at(first: &Snapshot) -> Result<Self> {
        let mut history = History {
            nodes: first.positions.len(),
            supplied_offset: first.supplied_work,
            dissipated_offset: first.dissipated,
            pay_out_offset: first.pay_out_energy,
            plastic_offset: first.plastic_dissipation,
            ..History::default()
        };
        history.record(first)?;
        Ok(history)
    }

    /// Room for `records` more records of the node and element series (the bulk of a record), so that a run
    /// whose length is known does not copy its records as they grow; [`crate::Error::Memory`] if there is no
    /// room.
    pub fn reserve_records(&mut self, records: usize) -> Result<()> {
        let what = "the records of the run (stream them with output=, or record less often)";
        let per_node = records.saturating_mul(self.nodes);
        reserve(&mut self.positions, 3 * per_node, what)?;
        reserve(&mut self.velocities, 3 * per_node, what)?;
        reserve(&mut self.rotations, 9 * per_node, what)?;
        reserve(&mut self.section_forces, 6 * per_node, what)
    }

    /// An empty history of a rod with `nodes` nodes (to be filled field by field, e.g. from a file).
    pub fn empty(nodes: usize) -> Self {
        History {
            nodes,
            ..History::default()
        }
    }

    /// Checks that every series has T records of the right width; names the first field that does not.
    pub fn check(&self) -> std::result::Result<(), String> {
        let t = self.len();
        let n = self.nodes;
        let vessel = !self.eta.is_empty();
        let seabed = !self.touchdown_arc_length.is_empty();
        let six = |series: &Vec<f64>| if series.is_empty() { 0 } else { 6 };
        let k = self.thrusters_count;
        let passivity = usize::from(!self.passivity_reserve.is_empty());
        let fields: [(&str, usize, usize); 43] = [
            (
                "eta_low_frequency",
                self.eta_low_frequency.len(),
                six(&self.eta_low_frequency),
            ),
            (
                "tau_commanded",
                self.tau_commanded.len(),
                six(&self.tau_commanded),
            ),
            (
                "eta_estimate",
                self.eta_estimate.len(),
                six(&self.eta_estimate),
            ),
            ("thrust", self.thrust.len(), k),
            ("azimuth", self.azimuth.len(), k),
            ("segment", self.segment.len(), n.saturating_sub(1)),
            ("length", self.length.len(), 1),
            ("pay_out_speed", self.pay_out_speed.len(), 1),
            ("pay_out_energy", self.pay_out_energy.len(), 1),
            ("plastic_dissipation", self.plastic_dissipation.len(), 1),
            ("seabed_energy", self.seabed.len(), 1),
            ("roller_energy", self.rollers.len(), 1),
            ("stinger_energy", self.stinger.len(), 1),
            ("hinge_angles", self.hinge_angles.len(), self.hinges_count),
            (
                "roller_reactions",
                self.roller_reactions.len(),
                self.rollers_count,
            ),
            (
                "roller_reaction_vectors",
                self.roller_vectors.len(),
                if self.roller_vectors.is_empty() {
                    0
                } else {
                    3 * self.rollers_count
                },
            ),
            (
                "lay summary",
                self.lay.len(),
                if self.lay.is_empty() {
                    0
                } else {
                    crate::response::lay_summary::LAY_FIELDS.len()
                },
            ),
            (
                "touchdown",
                self.touchdown.len(),
                if seabed { 3 } else { 0 },
            ),
            (
                "touchdown_arc_length",
                self.touchdown_arc_length.len(),
                if seabed { 1 } else { 0 },
            ),
            (
                "laid_length",
                self.laid_length.len(),
                if seabed { 1 } else { 0 },
            ),
            ("positions", self.positions.len(), n * 3),
            ("rotations", self.rotations.len(), n * 9),
            ("velocities", self.velocities.len(), n * 3),
            (
                "section_forces",
                self.section_forces.len(),
                n.saturating_sub(1) * 6,
            ),
            ("reaction_A", self.reaction_a.len(), 6),
            ("reaction_B", self.reaction_b.len(), 6),
            ("pipe_kinetic", self.kinetic.len(), 1),
            ("pipe_strain", self.strain.len(), 1),
            ("pipe_gravity", self.gravity.len(), 1),
            ("vessel_kinetic", self.vessel_kinetic.len(), 1),
            ("vessel_potential", self.vessel_potential.len(), 1),
            ("supplied_work", self.supplied_work.len(), 1),
            ("dissipated", self.dissipated.len(), 1),
            ("iterations", self.iterations.len(), 1),
            ("substeps", self.substeps.len(), 1),
            ("passivity_reserve", self.passivity_reserve.len(), passivity),
            (
                "passivity_withheld",
                self.passivity_withheld.len(),
                passivity,
            ),
            ("passivity_steps", self.passivity_steps.len(), passivity),
            ("eta", self.eta.len(), if vessel { 6 } else { 0 }),
            ("nu", self.nu.len(), if vessel { 6 } else { 0 }),
            ("tau", self.tau.len(), if vessel { 6 } else { 0 }),
            ("chi", self.chi.len(), if vessel { 6 } else { 0 }),
            ("time", self.time.len(), 1),
        ];
        match fields.iter().find(|(_, len, width)| *len != t * width) {
            Some((name, len, width)) => {
                Err(format!("{name}: {len} values, expected {t} × {width}"))
            }
            None => Ok(()),
        }
    }

    /// The storage function E of record `i` (J).
    pub fn total_energy(&self, i: usize) -> f64 {
        self.kinetic[i]
            + self.strain[i]
            + self.gravity[i]
            + self.vessel_kinetic[i]
            + self.vessel_potential[i]
            + self.seabed[i]
            + self.rollers[i]
            + self.stinger[i]
    }

    /// Number of records T.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// Whether nothing is recorded.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// Widens the node series to `nodes` nodes, padding earlier rows with NaN.
    fn widen(&mut self, nodes: usize) -> Result<()> {
        let old = self.nodes;
        let records = self.len();
        let pad = |data: &mut Vec<f64>, width_old: usize, width_new: usize| -> Result<()> {
            let mut wide = vec_with_capacity(records * width_new, "the records of the run")?;
            for row in data.chunks_exact(width_old.max(1)).take(records) {
                wide.extend_from_slice(row);
                wide.resize(wide.len() + width_new - width_old, f64::NAN);
            }
            *data = wide;
            Ok(())
        };
        pad(&mut self.positions, 3 * old, 3 * nodes)?;
        pad(&mut self.velocities, 3 * old, 3 * nodes)?;
        pad(&mut self.rotations, 9 * old, 9 * nodes)?;
        let elements = |n: usize| 6 * n.saturating_sub(1);
        pad(&mut self.section_forces, elements(old), elements(nodes))?;
        pad(
            &mut self.segment,
            old.saturating_sub(1),
            nodes.saturating_sub(1),
        )?;
        self.nodes = nodes;
        Ok(())
    }

    /// Appends a record; [`crate::Error::Memory`] (and nothing recorded) if there is no room for it.
    pub fn record(&mut self, snapshot: &Snapshot) -> Result<()> {
        let nodes = snapshot.positions.len();
        if nodes > self.nodes {
            self.widen(nodes)?;
        }
        let what = "the records of the run (stream them with output=, or record less often)";
        reserve(&mut self.positions, 3 * self.nodes, what)?;
        reserve(&mut self.velocities, 3 * self.nodes, what)?;
        reserve(&mut self.rotations, 9 * self.nodes, what)?;
        reserve(&mut self.section_forces, 6 * self.nodes, what)?;
        reserve(&mut self.segment, self.nodes, what)?;
        let missing = self.nodes - nodes;
        for (p, v) in snapshot.positions.iter().zip(snapshot.velocities) {
            self.positions.extend_from_slice(p.as_slice());
            self.velocities.extend_from_slice(v.as_slice());
        }
        for q in snapshot.rotations {
            let m = q.to_rotation_matrix().into_inner();
            for i in 0..3 {
                for j in 0..3 {
                    self.rotations.push(m[(i, j)]);
                }
            }
        }
        for f in &snapshot.section_forces {
            self.section_forces.extend_from_slice(f.as_slice());
        }
        self.segment
            .extend(snapshot.segment_of.iter().map(|&k| k as f64));
        let nan = |data: &mut Vec<f64>, count: usize| data.resize(data.len() + count, f64::NAN);
        nan(&mut self.positions, 3 * missing);
        nan(&mut self.velocities, 3 * missing);
        nan(&mut self.rotations, 9 * missing);
        nan(&mut self.section_forces, 6 * missing);
        nan(&mut self.segment, missing);
        self.time.push(snapshot.time);
        self.length.push(snapshot.length);
        self.pay_out_speed.push(snapshot.pay_out_speed);
        self.pay_out_energy
            .push(snapshot.pay_out_energy - self.pay_out_offset);
        self.plastic_dissipation
            .push(snapshot.plastic_dissipation - self.plastic_offset);
        let reactions = snapshot.reactions;
        self.reaction_a.extend_from_slice(reactions[0].as_slice());
        self.reaction_b
            .extend_from_slice(reactions[reactions.len() - 1].as_slice());
        let energy = &snapshot.energy;
        self.kinetic.push(energy.kinetic);
        self.strain.push(energy.strain);
        self.gravity.push(energy.gravity);
        self.vessel_kinetic.push(energy.vessel_kinetic);
        self.vessel_potential.push(energy.vessel_potential);
        self.seabed.push(energy.seabed);
        self.rollers.push(energy.rollers);
        self.stinger.push(energy.stinger);
        self.hinges_count = snapshot.hinge_angles.len();
        self.hinge_angles.extend_from_slice(snapshot.hinge_angles);
        if let Some(forces) = snapshot.roller_forces {
            self.rollers_count = forces.len();
            self.roller_reactions.extend_from_slice(forces);
        }
        if let Some(vectors) = snapshot.roller_vectors {
            self.roller_vectors
                .extend(vectors.iter().flat_map(|v| [v.x, v.y, v.z]));
        }
        if let Some(lay) = snapshot.lay {
            self.lay.extend_from_slice(&lay.values());
        }
        if let Some(touchdown) = &snapshot.touchdown {
            let (arc, position) = touchdown
                .point
                .unwrap_or((f64::NAN, Vector3::repeat(f64::NAN)));
            self.touchdown.extend_from_slice(position.as_slice());
            self.touchdown_arc_length.push(arc);
            self.laid_length.push(touchdown.laid_length);
        }
        if let Some([eta, nu, tau, chi]) = &snapshot.vessel {
            self.eta.extend_from_slice(eta.as_slice());
            self.nu.extend_from_slice(nu.as_slice());
            self.tau.extend_from_slice(tau.as_slice());
            self.chi.extend_from_slice(chi.as_slice());
        }
        if let Some(station) = &snapshot.station {
            self.eta_low_frequency
                .extend_from_slice(station.eta_low_frequency.as_slice());
            self.tau_commanded
                .extend_from_slice(station.tau_commanded.as_slice());
            if let Some(estimate) = &station.eta_estimate {
                self.eta_estimate.extend_from_slice(estimate.as_slice());
            }
            self.thrusters_count = station.thrust.len();
            self.thrust.extend_from_slice(&station.thrust);
            self.azimuth.extend_from_slice(&station.azimuth);
        }
        self.supplied_work
            .push(snapshot.supplied_work - self.supplied_offset);
        self.dissipated
            .push(snapshot.dissipated - self.dissipated_offset);
        self.iterations.push(snapshot.iterations);
        self.substeps.push(snapshot.substeps);
        if let Some(ledger) = &snapshot.passivity {
            self.passivity_reserve.push(ledger.reserve());
            self.passivity_withheld.push(ledger.withheld);
            self.passivity_steps.push(ledger.steps as f64);
        }
        Ok(())
    }
}
