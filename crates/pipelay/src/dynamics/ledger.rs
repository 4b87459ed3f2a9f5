//! The energy ledger: the storage function E = E_P + E_V (eq. 24) in its parts, and the work supplied and
//! the energy dissipated since a run started, so that E(t) − E(0) = supplied − dissipated is checked per step.

/// Energy of the pipe and the vessel (J).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energy {
    pub kinetic: f64,
    pub strain: f64,
    /// Potential of the submerged weight, zero at z = 0.
    pub gravity: f64,
    /// Vessel kinetic energy ½νᵀMν.
    pub vessel_kinetic: f64,
    /// Vessel restoring potential ½qᵀG q.
    pub vessel_potential: f64,
    /// Energy stored in the seabed contact: normal springs and friction's elastic slip.
    pub seabed: f64,
    /// Energy stored in the roller contacts.
    pub rollers: f64,
    /// An articulated stinger's sections: kinetic, weight less buoyancy's potential and the hinges'.
    pub stinger: f64,
}

impl Energy {
    /// The storage function E = E_P + E_V (eq. 24).
    pub fn total(&self) -> f64 {
        self.kinetic
            + self.strain
            + self.gravity
            + self.vessel_kinetic
            + self.vessel_potential
            + self.seabed
            + self.rollers
            + self.stinger
    }
}

/// Work and dissipation of the last step's loads (J), and the plastic part of the dissipation.
#[derive(Debug, Clone, Copy, Default)]
pub struct StepWork {
    pub supplied: f64,
    pub dissipated: f64,
    pub plastic: f64,
}

/// Work supplied and energy dissipated since the start of a run (J).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Ledger {
    supplied_work: f64,
    dissipated: f64,
    pay_out_energy: f64,
    plastic_dissipated: f64,
}

impl Ledger {
    /// A ledger with these totals (J), e.g. restored from a checkpoint: work supplied, energy dissipated, and
    /// the part of the supplied work that pay-out brought in.
    pub fn new(supplied_work: f64, dissipated: f64, pay_out_energy: f64) -> Self {
        Ledger {
            supplied_work,
            dissipated,
            pay_out_energy,
            plastic_dissipated: 0.0,
        }
    }

    /// The ledger with `plastic` (J) of its dissipation the yielding walls' (restored from a checkpoint).
    pub fn with_plastic_dissipated(mut self, plastic: f64) -> Self {
        self.plastic_dissipated = plastic;
        self
    }

    /// The energy the yielding walls dissipated since the start (J; counted in [`Self::dissipated`]).
    pub fn plastic_dissipated(&self) -> f64 {
        self.plastic_dissipated
    }

    /// Books the plastic part `plastic` (J) of a step's dissipation, already booked with the step.
    pub fn book_plastic(&mut self, plastic: f64) {
        self.plastic_dissipated += plastic;
    }

    /// Work supplied since the start (J): point loads, driven supports, the current's share of the drag, the
    /// vessel's thrust and environment, and the energy pay-out brought in.
    pub fn supplied_work(&self) -> f64 {
        self.supplied_work
    }

    /// Energy dissipated since the start (J): drag on the relative velocity, rotational damping, seabed
    /// damping and friction, vessel damping.
    pub fn dissipated(&self) -> f64 {
        self.dissipated
    }

    /// Energy pay-out has brought in since the start (J; counted in [`Self::supplied_work`]): the work of the
    /// tensioner on the pipe it holds plus the energy of the pipe it adds, and the energy change of mesh
    /// changes.
    pub fn pay_out_energy(&self) -> f64 {
        self.pay_out_energy
    }

    /// Books a step's work `supplied` and dissipation `dissipated` (J).
    pub fn book_step(&mut self, supplied: f64, dissipated: f64) {
        self.supplied_work += supplied;
        self.dissipated += dissipated;
    }

    /// Books energy that pay-out brought in (J).
    pub fn book_pay_out(&mut self, energy: f64) {
        self.pay_out_energy += energy;
        self.supplied_work += energy;
    }
}
