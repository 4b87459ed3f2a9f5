//! The DP vessel: a rigid body (eq. 10), its Euler angles, its coupling to the pipe's end, its control, its
//! lay equipment (tensioner and stinger of rollers or roller boxes, or tower), its RAOs and the
//! wave-frequency motion they give, its thrusters and their allocation, the observer of its position, and
//! wind, current and wave drift on its hull.
//!
//! May use: the basics and [`crate::environment`] (the waves that move it).
pub mod allocation;
pub mod articulation;
pub mod capability;
pub mod control;
pub mod coupling;
pub mod euler;
pub mod hull_loads;
pub mod lay;
pub mod observer;
pub mod raos;
pub mod rigid_body;
pub mod roller_box;
pub mod route_path;
pub mod stinger_arc;
pub mod stinger_sections;
pub mod thrusters;
pub mod wave_motion;
pub mod winch;

use control::Pid;

/// A constant environmental force and moment on the vessel (body frame), from `start` (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvironmentForce {
    pub value: nalgebra::Vector6<f64>,
    pub start: f64,
}

impl EnvironmentForce {
    /// A checked force: finite value and start.
    pub fn new(value: nalgebra::Vector6<f64>, start: f64) -> crate::Result<Self> {
        crate::error::finite("value", value.as_slice())?;
        crate::error::finite("start", &[start])?;
        Ok(EnvironmentForce { value, start })
    }
}

/// A vessel holding one end of the rod (eq. 5): the rod's end node is the vessel's reference point CO,
/// and the rod's end frame is R_t^e(L) = R_b^e R_b^tᵀ with the fixed clamp angle R_b^t(β).
#[derive(Debug, Clone, PartialEq)]
pub struct VesselAttachment {
    pub node: usize,
    pub vessel: rigid_body::Vessel,
    /// R_b^t(β): the body frame in the pipe-end frame.
    pub angle: nalgebra::Matrix3<f64>,
    /// Starting pose η = [x, y, z, φ, θ, ψ] in e.
    pub eta: nalgebra::Vector6<f64>,
    pub controller: Option<Pid>,
    pub environment: Vec<EnvironmentForce>,
    /// Elevation of the calm sea surface z_0 = −depth, where restoring vanishes (m).
    pub surface: f64,
    /// Lay equipment: where the pipe is held (body frame) and the rollers it runs over. `None`: the pipe's
    /// end is clamped at CO (the paper's model).
    pub lay: Option<lay::LayEquipment>,
    /// The A&R winch, if any.
    pub winch: Option<winch::Winch>,
    /// Whether wind, current and wave drift act on the hull through the vessel's coefficient tables
    /// ([`hull_loads`]); off, the hull feels only `environment` (the paper's model).
    pub hull_loads: bool,
}

impl VesselAttachment {
    /// The hold point in the body frame, relative to CO (m): the winch's once it holds the line, else the lay
    /// equipment's; zero without either.
    pub fn hang_off(&self) -> nalgebra::Vector3<f64> {
        match (&self.winch, &self.lay) {
            (Some(winch), _) if winch.holds => winch.position,
            (Some(winch), _) if winch.hand_back.is_some() => {
                winch.hand_back.map_or(winch.position, |back| back.hang_off)
            }
            (_, Some(lay)) => lay.hang_off,
            _ => nalgebra::Vector3::zeros(),
        }
    }

    /// The winch, if it holds the line.
    pub fn holding_winch(&self) -> Option<&winch::Winch> {
        self.winch.as_ref().filter(|w| w.holds)
    }

    /// The rollers (empty without lay equipment), an articulated stinger's where its hinges are at φ = 0.
    pub fn rollers(&self) -> &[lay::Roller] {
        self.lay.as_ref().map_or(&[], |lay| &lay.rollers)
    }

    /// The rollers where the hinge `angles` put them (body frame): an articulated stinger's sections turned.
    pub fn placed_rollers(&self, angles: &[f64]) -> std::borrow::Cow<'_, [lay::Roller]> {
        match &self.lay {
            Some(lay) if lay.articulation.is_some() => {
                std::borrow::Cow::Owned(lay.placed_rollers(angles))
            }
            _ => std::borrow::Cow::Borrowed(self.rollers()),
        }
    }
}
