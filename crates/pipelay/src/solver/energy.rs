//! The storage function E = E_P + E_V (eq. 24) in its parts.

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
    }
}
