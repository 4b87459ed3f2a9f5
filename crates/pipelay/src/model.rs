//! A model: the rod, the sea, gravity, supports (eqs. 20–21), point loads and attachments.
use crate::environment::sea::Sea;
use crate::environment::waves::WaveField;
use crate::error::{finite, non_negative, Error, Result};
use crate::rod::attachment::{Attachment, Place};
use crate::rod::plastic_state::PlasticState;
use crate::rod::reeling::{entry_state, reel};
use crate::rod::Rod;
use crate::so3::quat_from_matrix;
use crate::table::TimeFunction;
use crate::vessel::control::Pid;
use crate::vessel::winch::{HandBack, Winch};
use crate::vessel::{EnvironmentForce, VesselAttachment};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use std::fmt;

/// Degrees of freedom per node: position (3) and spatial spin (3).
pub const NODE_DOFS: usize = 6;

/// How a node is held.
#[derive(Clone)]
pub enum SupportKind {
    /// Position and rotation prescribed.
    Clamp {
        position: Vector3<f64>,
        rotation: UnitQuaternion<f64>,
    },
    /// Position prescribed, rotation free.
    Pin { position: Vector3<f64> },
    /// Position (and optionally rotation) prescribed as functions of time; `velocity` gives the initial
    /// velocity of the node (default: zero).
    Drive {
        position: TimeFunction<Vector3<f64>>,
        velocity: Option<TimeFunction<Vector3<f64>>>,
        rotation: Option<TimeFunction<Matrix3<f64>>>,
    },
}

impl fmt::Debug for SupportKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SupportKind::Clamp { position, rotation } => {
                write!(f, "Clamp({position:?}, {rotation:?})")
            }
            SupportKind::Pin { position } => write!(f, "Pin({position:?})"),
            SupportKind::Drive { rotation, .. } => {
                write!(f, "Drive(rotation: {})", rotation.is_some())
            }
        }
    }
}

/// A support at a node.
#[derive(Debug, Clone)]
pub struct Support {
    pub node: usize,
    pub kind: SupportKind,
}

/// Where a support holds its node at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportTarget {
    pub node: usize,
    pub position: Vector3<f64>,
    /// The prescribed rotation, `None` where rotation is free.
    pub rotation: Option<UnitQuaternion<f64>>,
}

/// Checks that `r` is a rotation matrix.
fn checked_rotation(argument: &str, r: &Matrix3<f64>) -> Result<UnitQuaternion<f64>> {
    finite(argument, r.as_slice())?;
    let error = (r.transpose() * r - Matrix3::identity()).abs().max();
    if error > 1e-6 || r.determinant() <= 0.0 {
        return Err(Error::input(
            argument,
            format!(
                "a matrix with |RᵀR − I| = {error:.2e}, det = {:.4}",
                r.determinant()
            ),
            "must be a rotation matrix (orthonormal to 1e-6, det = +1)",
        ));
    }
    Ok(quat_from_matrix(r))
}

/// Calls a user function of time and checks that its result is finite.
fn call_vector(
    function: &TimeFunction<Vector3<f64>>,
    argument: &str,
    time: f64,
) -> Result<Vector3<f64>> {
    let value =
        function(time).map_err(|message| Error::input(argument, format!("t = {time}"), message))?;
    finite(argument, value.as_slice())?;
    Ok(value)
}

/// How far (m) a vessel's starting η z may lie from the calm sea surface z = −depth: a few metres of heave
/// with margin (statics put CO on the surface whatever η z says), and never more than half the depth, so that
/// η z = +depth (the sign of e3 mistaken) or a vessel on the seabed is always refused.
pub const SURFACE_TOLERANCE: f64 = 10.0;

/// Checks that a vessel's starting pose η puts CO at the sea surface z = −depth (e3 down) within
/// [`SURFACE_TOLERANCE`] (at most half the depth), and above the seabed under it.
fn check_afloat(eta: &nalgebra::Vector6<f64>, sea: &Sea) -> Result<()> {
    // Metres to the millimetre, without trailing zeros (120, -135.3, not 15.300000000000011).
    let m = |v: f64| {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    let (surface, z) = (-sea.depth, eta[2]);
    let tolerance = SURFACE_TOLERANCE.min(0.5 * sea.depth);
    if (z - surface).abs() > tolerance {
        let side = if z < surface { "above" } else { "below" };
        return Err(Error::input(
            "eta",
            format!("z = {} m, {} m {side} the surface", m(z), m((z - surface).abs())),
            format!(
                "η's z (the vessel's CO, m, e3 pointing down) must be at the sea surface z = −depth = {} m \
                 within {} m: in [{}, {}] m",
                m(surface),
                m(tolerance),
                m(surface - tolerance),
                m(surface + tolerance)
            ),
        ));
    }
    if let Some(seabed) = &sea.seabed {
        let bottom = seabed.bathymetry.elevation(eta[0], eta[1]);
        if z >= bottom {
            return Err(Error::input(
                "eta",
                format!("z = {} m at (x, y) = ({}, {}) m", m(z), m(eta[0]), m(eta[1])),
                format!(
                    "η's z (the vessel's CO, m, e3 pointing down) must be above the seabed, which lies at \
                     z = {} m there",
                    m(bottom)
                ),
            ));
        }
    }
    Ok(())
}

impl Support {
    /// Whether the support holds the node's rotation.
    pub fn holds_rotation(&self) -> bool {
        match &self.kind {
            SupportKind::Clamp { .. } => true,
            SupportKind::Pin { .. } => false,
            SupportKind::Drive { rotation, .. } => rotation.is_some(),
        }
    }

    /// Where the support holds its node at time t (s).
    pub fn target(&self, time: f64) -> Result<SupportTarget> {
        let (position, rotation) = match &self.kind {
            SupportKind::Clamp { position, rotation } => (*position, Some(*rotation)),
            SupportKind::Pin { position } => (*position, None),
            SupportKind::Drive {
                position, rotation, ..
            } => {
                let p = call_vector(position, "drive position", time)?;
                let r = match rotation {
                    Some(f) => {
                        let m = f(time).map_err(|message| {
                            Error::input("drive rotation", format!("t = {time}"), message)
                        })?;
                        Some(checked_rotation("drive rotation", &m)?)
                    }
                    None => None,
                };
                (p, r)
            }
        };
        Ok(SupportTarget {
            node: self.node,
            position,
            rotation,
        })
    }

    /// Velocity of the supported node at time t (m/s): the drive's velocity function, else zero.
    pub fn velocity(&self, time: f64) -> Result<Vector3<f64>> {
        match &self.kind {
            SupportKind::Drive {
                velocity: Some(v), ..
            } => call_vector(v, "drive velocity", time),
            _ => Ok(Vector3::zeros()),
        }
    }
}

/// A fixed-direction (dead) force and moment at a node, optionally scaled by a function of time.
#[derive(Clone)]
pub struct PointLoad {
    pub node: usize,
    pub force: Vector3<f64>,
    pub moment: Vector3<f64>,
    pub scale: Option<TimeFunction<f64>>,
}

impl fmt::Debug for PointLoad {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "PointLoad(node {}, {:?}, {:?}, scaled: {})",
            self.node,
            self.force,
            self.moment,
            self.scale.is_some()
        )
    }
}

impl PointLoad {
    /// The load's scale factor at time t (1 without a scale function).
    pub fn scale_at(&self, time: f64) -> Result<f64> {
        match &self.scale {
            None => Ok(1.0),
            Some(f) => {
                let value = f(time)
                    .map_err(|message| Error::input("scale", format!("t = {time}"), message))?;
                finite("scale", &[value])?;
                Ok(value)
            }
        }
    }
}

/// The whole model.
#[derive(Debug, Clone)]
pub struct Model {
    pub rod: Rod,
    pub sea: Option<Sea>,
    /// Gravitational acceleration g ≥ 0 (m/s²), acting along +e3.
    pub gravity: f64,
    pub supports: Vec<Support>,
    pub point_loads: Vec<PointLoad>,
    /// A vessel holding one end, if any.
    pub vessel: Option<VesselAttachment>,
    /// Pipe paid out (or in) at one end, if any.
    pub pay_out: Option<PayOut>,
    /// The sea's waves resolved for its depth and this gravity, if it has any.
    pub waves: Option<WaveField>,
    /// Bodies attached at points of the line.
    pub attachments: Vec<Attachment>,
}

/// Pay-out speed (m/s of unstretched pipe; negative: pay-in).
#[derive(Clone)]
pub enum PayOutSpeed {
    Constant(f64),
    Function(TimeFunction<f64>),
    /// In stages ([`crate::dynamics::stages`]): legs in time order, each ramping to its speed and holding it
    /// until the next.
    Staged(Vec<crate::table::Leg>),
}

impl fmt::Debug for PayOutSpeed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PayOutSpeed::Constant(v) => write!(f, "Constant({v})"),
            PayOutSpeed::Function(_) => write!(f, "Function"),
            PayOutSpeed::Staged(stages) => write!(f, "Staged({stages:?})"),
        }
    }
}

/// Pipe paid out through a vessel's tensioner or tower, or at a driven end: the end element's unstretched
/// length grows at the pay-out speed; when it passes 1.5 `element_length` it is split, and on pay-in it is
/// joined with its neighbour when it falls below 0.5 `element_length`.
#[derive(Debug, Clone)]
pub struct PayOut {
    /// The end: true for end A (node 0), false for end B (node n).
    pub at_start: bool,
    pub speed: PayOutSpeed,
    /// The length of the elements pay-out adds (m): that of the end element when pay-out was set.
    pub element_length: f64,
    /// The line's length when pay-out was set (m): the length paid out since is the rod's length less it.
    pub initial_length: f64,
    /// The line still on board, in the order it is paid out: each part's length (m) and its section (an index
    /// into the rod's sections). Empty: paid-out pipe continues the end's segment.
    pub feed: Vec<(f64, usize)>,
}

impl PayOut {
    /// The segment of the material `paid` metres along the feed from where the line ended when pay-out was
    /// set; `None` for material of the line as it was then (`paid` < 0) or without a feed. Past the feed's
    /// end, its last part continues.
    pub fn fed_segment(&self, paid: f64) -> Option<usize> {
        if paid < 0.0 {
            return None;
        }
        let mut end = 0.0;
        for &(length, segment) in &self.feed {
            end += length;
            if paid < end {
                return Some(segment);
            }
        }
        self.feed.last().map(|&(_, segment)| segment)
    }

    /// The speed at time t (s), checked finite.
    pub fn speed_at(&self, time: f64) -> Result<f64> {
        let speed = match &self.speed {
            PayOutSpeed::Constant(v) => *v,
            PayOutSpeed::Function(f) => f(time)
                .map_err(|message| Error::input("pay_out speed", format!("t = {time}"), message))?,
            PayOutSpeed::Staged(legs) => crate::table::travel(legs, time).1,
        };
        if !speed.is_finite() {
            return Err(Error::input(
                "pay_out speed",
                format!("{speed} at t = {time} s"),
                "must be a finite speed (m/s)",
            ));
        }
        Ok(speed)
    }
}

impl Model {
    /// A free rod, optionally in a sea.
    pub fn new(rod: Rod, sea: Option<Sea>, gravity: f64) -> Result<Self> {
        non_negative("gravity", gravity, "m/s²")?;
        let elements = rod.element_count();
        crate::memory::check(
            "rod",
            format!("a rod of {elements} elements"),
            elements as f64 * crate::memory::SOLVER_BYTES_PER_ELEMENT,
            "solving it",
        )?;
        if let Some(sea) = &sea {
            let horizontal: Vec<_> = rod.nodes.iter().map(|p| p.xy()).collect();
            sea.check_seabed_below_surface(&horizontal)?;
        }
        let waves = match sea
            .as_ref()
            .and_then(|sea| sea.waves.as_ref().map(|w| (sea, w)))
        {
            Some((sea, waves)) => Some(WaveField::new(waves, sea.depth, gravity)?),
            None => None,
        };
        Ok(Model {
            waves,
            rod,
            sea,
            gravity,
            supports: Vec::new(),
            point_loads: Vec::new(),
            vessel: None,
            pay_out: None,
            attachments: Vec::new(),
        })
    }

    /// The plastic state of the rod's yielding elements at rest (None if none yields): the unyielded pipe, or in
    /// a reel-lay the state its reeling left the wall in, bent in the ramp's plane against the sagbend
    /// ([`crate::rod::reeling::entry_state`]).
    pub fn plastic_state(&self) -> Option<PlasticState> {
        let mut state = PlasticState::new(&self.rod)?;
        let reeled = self.vessel.as_ref().and_then(|attachment| {
            let reeling = attachment.lay.as_ref()?.reeling?;
            Some((reeling, attachment.node))
        });
        if let Some((reeling, hold)) = reeled {
            let sense = if hold == 0 { 1.0 } else { -1.0 };
            state.enter(|fibres| entry_state(fibres, &reeling, sense));
        }
        Some(state)
    }

    /// In a reel-lay, the residual curvature (1/m) the reeling leaves the first yielding segment's pipe with
    /// ([`crate::rod::reeling::reel`]); None elsewhere.
    pub fn reeled_residual_curvature(&self) -> Option<f64> {
        let reeling = self.vessel.as_ref()?.lay.as_ref()?.reeling?;
        let fibres = self
            .rod
            .sections
            .iter()
            .filter(|section| section.yields())
            .find_map(|section| section.fibre_section()?.ok())?;
        Some(reel(&fibres, &reeling, 0.0).residual_curvature)
    }

    /// The node of a rod end: "A" is node 0 (seabed end), "B" node n (top end).
    pub fn end_node(&self, end: &str) -> Result<usize> {
        match end {
            "A" => Ok(0),
            "B" => Ok(self.rod.element_count()),
            other => Err(Error::input(
                "end",
                format!("{other:?}"),
                "must be \"A\" (node 0) or \"B\" (node n)",
            )),
        }
    }

    /// A node index, Python style: negative counts from the end.
    pub fn node_index(&self, node: i64) -> Result<usize> {
        let count = self.rod.node_count() as i64;
        let index = if node < 0 { node + count } else { node };
        if (0..count).contains(&index) {
            Ok(index as usize)
        } else {
            Err(Error::input(
                "node",
                node,
                format!("must be an index in [-{count}, {})", count),
            ))
        }
    }

    /// Holds `node` by `kind`, replacing an earlier support there; an end that carries a vessel is refused.
    fn add_support(&mut self, node: usize, kind: SupportKind) -> Result<()> {
        if self.vessel.as_ref().is_some_and(|v| v.node == node) {
            let end = if node == 0 { "A" } else { "B" };
            return Err(Error::input(
                "end",
                format!("{end:?}"),
                "must not carry a vessel: the vessel holds that end (use the other end)",
            ));
        }
        let paid_out = self.growing_element().is_some_and(|(_, end)| end == node);
        if paid_out && !matches!(kind, SupportKind::Drive { .. }) {
            return Err(Error::input(
                "end",
                format!("{:?}", if node == 0 { "A" } else { "B" }),
                "pays pipe out: it may be driven but not clamped or pinned",
            ));
        }
        self.supports.retain(|s| s.node != node);
        self.supports.push(Support { node, kind });
        Ok(())
    }

    /// Clamps an end: position and rotation held (default: the reference node and frame).
    pub fn clamp(
        &mut self,
        end: &str,
        position: Option<Vector3<f64>>,
        rotation: Option<Matrix3<f64>>,
    ) -> Result<()> {
        let node = self.end_node(end)?;
        let position = self.checked_position(node, position)?;
        let rotation = match rotation {
            None => self.rod.frames.get(node).copied().unwrap_or_default(),
            Some(r) => checked_rotation("rotation", &r)?,
        };
        self.add_support(node, SupportKind::Clamp { position, rotation })
    }

    /// Pins an end: position held (default: the reference node), rotation free.
    pub fn pin(&mut self, end: &str, position: Option<Vector3<f64>>) -> Result<()> {
        let node = self.end_node(end)?;
        let position = self.checked_position(node, position)?;
        self.add_support(node, SupportKind::Pin { position })
    }

    fn checked_position(
        &self,
        node: usize,
        position: Option<Vector3<f64>>,
    ) -> Result<Vector3<f64>> {
        match position {
            None => Ok(self.rod.nodes.get(node).copied().unwrap_or_default()),
            Some(p) => {
                finite("position", p.as_slice())?;
                Ok(p)
            }
        }
    }

    /// Drives an end: position (m) and optionally rotation as functions of time; `velocity` (m/s) gives the
    /// node's initial velocity. Checked at t = 0.
    pub fn drive(
        &mut self,
        end: &str,
        position: TimeFunction<Vector3<f64>>,
        velocity: Option<TimeFunction<Vector3<f64>>>,
        rotation: Option<TimeFunction<Matrix3<f64>>>,
    ) -> Result<()> {
        let node = self.end_node(end)?;
        let support = Support {
            node,
            kind: SupportKind::Drive {
                position,
                velocity,
                rotation,
            },
        };
        support.target(0.0)?;
        support.velocity(0.0)?;
        self.add_support(node, support.kind)
    }

    /// Attaches a vessel to an end (which must not also be supported). `angle` is β, zyx Euler angles of
    /// R_b^t (rad); `eta` the starting pose; the sea gives the surface where restoring vanishes. With `lay`,
    /// the end is held at the lay equipment's hold point in its frame instead (and `angle` must be zero).
    #[allow(clippy::too_many_arguments)]
    pub fn attach_vessel(
        &mut self,
        end: &str,
        vessel: crate::vessel::rigid_body::Vessel,
        eta: nalgebra::Vector6<f64>,
        angle: Vector3<f64>,
        controller: Option<Pid>,
        environment: Vec<EnvironmentForce>,
        lay: Option<crate::vessel::lay::LayEquipment>,
    ) -> Result<()> {
        let node = self.end_node(end)?;
        finite("eta", eta.as_slice())?;
        finite("angle", angle.as_slice())?;
        let Some(sea) = &self.sea else {
            return Err(Error::input(
                "sea",
                "None",
                "a vessel needs a sea (pl.Sea) to float in",
            ));
        };
        if let Some(c) = &controller {
            for (name, m) in [("kp", &c.kp), ("kd", &c.kd), ("ki", &c.ki)] {
                finite(name, m.as_slice())?;
            }
            if let crate::vessel::control::Reference::Route {
                start,
                heading,
                legs,
            } = &c.reference
            {
                finite("route start", start.as_slice())?;
                finite("route heading", &[*heading])?;
                for leg in legs {
                    finite("route speed", &[leg.speed])?;
                    finite("route start_time", &[leg.start])?;
                }
            }
            c.reference.at(0.0)?;
            finite("start", &[c.start])?;
            if let Some(limit) = &c.integral_limit {
                for &l in limit.iter() {
                    crate::error::positive("integral_limit", l, "(units of η·s)")?;
                }
            }
            if let Some(limit) = &c.thrust_limit {
                for &l in limit.iter() {
                    crate::error::positive("thrust_limit", l, "N (surge, sway), N·m (yaw)")?;
                }
            }
        }
        if controller.as_ref().is_some_and(|c| c.allocation) && vessel.thrusters.is_empty() {
            return Err(Error::input(
                "allocation",
                "\"qp\"",
                "needs a vessel with thrusters (pl.Vessel(..., thrusters=...), or pl.Vessel.osv())",
            ));
        }
        for force in &environment {
            finite("environment", force.value.as_slice())?;
            finite("environment start", &[force.start])?;
        }
        if self.supports.iter().any(|s| s.node == node) {
            return Err(Error::input(
                "end",
                format!("{end:?}"),
                "must not be clamped, pinned or driven as well: the vessel holds that end",
            ));
        }
        check_afloat(&eta, sea)?;
        let angle = match &lay {
            Some(_) if angle != Vector3::zeros() => {
                return Err(Error::input(
                    "angle",
                    format!("{:?}", angle.as_slice()),
                    "must be left at zero with lay equipment: the tensioner or tower sets the pipe's angle",
                ))
            }
            Some(lay) => lay.end_frame.transpose(),
            None => crate::vessel::euler::rotation(&angle),
        };
        self.vessel = Some(VesselAttachment {
            node,
            surface: -sea.depth,
            vessel,
            lay,
            angle,
            eta,
            controller,
            environment,
            winch: None,
            hull_loads: false,
        });
        Ok(())
    }

    /// Lets wind, current and wave drift act on the vessel's hull through its coefficient tables; each load
    /// the sea has needs the vessel's table for it.
    pub fn enable_hull_loads(&mut self) -> Result<()> {
        let Some(attachment) = self.vessel.as_mut() else {
            return Err(Error::input(
                "hull_loads",
                "True",
                "needs a vessel (attach_vessel)",
            ));
        };
        let vessel = &attachment.vessel;
        let sea = self.sea.as_ref();
        let needs = [
            (
                sea.is_some_and(|s| s.wind.is_some()),
                vessel.wind_coefficients.is_none(),
                "wind_coefficients",
                "wind",
            ),
            (
                sea.is_some_and(|s| s.current.is_some()),
                vessel.current_coefficients.is_none(),
                "current_coefficients",
                "current",
            ),
            (
                self.waves.is_some(),
                vessel.drift_coefficients.is_none(),
                "drift_coefficients",
                "waves",
            ),
        ];
        for (present, missing, table, load) in needs {
            if present && missing {
                return Err(Error::input(
                    table,
                    "None",
                    format!("must be given for the {load} to act on the hull (hull_loads=True)"),
                ));
            }
        }
        attachment.hull_loads = true;
        Ok(())
    }

    /// Gives the vessel an A&R winch whose wire has the section `wire`. With lay equipment the winch must lie on
    /// the firing line ahead of the hold point ([`Winch::distance_along`]); a line whose top element is a cable
    /// is held by the winch from the start (a recovery starts so).
    pub fn add_winch(
        &mut self,
        mut winch: Winch,
        wire: crate::rod::section::Section,
    ) -> Result<()> {
        if !wire.cable {
            return Err(Error::input(
                "wire",
                "a pipe or rod section",
                "must be a cable: pl.Section.cable(...)",
            ));
        }
        let Some(attachment) = self.vessel.as_ref() else {
            return Err(Error::input(
                "winch",
                "a winch without a vessel",
                "needs attach_vessel first: the winch is on the vessel",
            ));
        };
        let top = self.rod.element_count() - 1;
        let held_top = attachment.node != 0 && self.rod.section(top).cable;
        if let Some(lay) = &attachment.lay {
            let tangent = lay.end_frame.column(0).into_owned();
            winch.distance_along(&lay.hang_off, &tangent)?;
        } else if !held_top {
            return Err(Error::input(
                "winch",
                "a winch on a vessel without lay equipment",
                "needs lay= (pl.SLay or pl.JLay): the winch takes the line over from its tensioner",
            ));
        }
        if let Some(body) = winch.head_body.as_mut() {
            let Some(lay) = attachment.lay.as_ref().filter(|_| !held_top) else {
                return Err(Error::input(
                    "head_length",
                    body.length,
                    "needs the pipe at the line's top, held by lay equipment: the head is fitted to it at the \
                     hand-over",
                ));
            };
            let room = (winch.position - lay.hang_off).norm() - body.length;
            if room < 1.0 {
                return Err(Error::input(
                    "head_length",
                    body.length,
                    format!(
                        "must leave at least 1 m of wire between the head and the winch, {} m from the hold point",
                        room + body.length
                    ),
                ));
            }
            // with_head_body refuses a body without the head's clump.
            let Some(clump) = winch.head else {
                return Err(Error::input(
                    "head_length",
                    body.length,
                    "needs head=pl.Clump(...)",
                ));
            };
            let pipe = self.rod.section(top);
            let head = crate::rod::section::Section::head(
                pipe,
                body.length,
                body.diameter,
                wire.hydrodynamic_diameter,
                clump.mass,
                clump.volume,
                clump.drag_area,
                clump.added_mass,
            )?;
            self.rod.sections.push(head);
            body.section = self.rod.sections.len() - 1;
        }
        self.rod.sections.push(wire);
        winch.wire = self.rod.sections.len() - 1;
        winch.holds = held_top;
        if let Some(attachment) = self.vessel.as_mut() {
            attachment.winch = Some(winch);
        }
        if held_top {
            self.hold_by_winch();
        }
        Ok(())
    }

    /// Makes the winch hold the line, whose top element is now its wire: pay-out continues the wire in
    /// elements of the winch's length, and the laydown head (if any) is fitted where the wire meets the pipe.
    /// Called at the hand-over ([`crate::dynamics::hand_over`]) and when a remeshed rod whose top is the wire
    /// comes back ([`Model::with_rod`]).
    pub fn hold_by_winch(&mut self) {
        let Some(winch) = self.vessel.as_mut().and_then(|v| v.winch.as_mut()) else {
            return;
        };
        winch.holds = true;
        let (element_length, head) = (
            winch.element_length,
            winch.head.filter(|_| winch.head_body.is_none()),
        );
        let rod_length = self.rod.length();
        if let Some(pay_out) = self.pay_out.as_mut() {
            winch.pipe_element_length = pay_out.element_length;
            pay_out.element_length = element_length;
            pay_out.initial_length = rod_length;
            pay_out.feed.clear();
        }
        let joint = self.wire_joint();
        if let (Some(head), Some(joint)) = (head, joint) {
            let arc = self
                .rod
                .arc_lengths()
                .get(joint)
                .copied()
                .unwrap_or_default();
            if !self.attachments.iter().any(|a| a.arc_length == arc) {
                self.attachments.push(Attachment {
                    arc_length: arc,
                    ..head
                });
            }
        }
    }

    /// Makes the tensioner hold the line again after the hand-back `back`, the winch's wire gone from the mesh
    /// ([`crate::dynamics::hand_back`]): the vessel holds the pipe's end with the clamp `back` made, pay-out adds
    /// pipe elements again, and the laydown head is taken off the pipe's end. Called at the hand-back and when a
    /// run is resumed after it.
    pub fn hand_back(&mut self, back: HandBack) {
        let Some(attachment) = self.vessel.as_mut() else {
            return;
        };
        attachment.angle = back.angle;
        let Some(winch) = attachment.winch.as_mut() else {
            return;
        };
        winch.holds = false;
        winch.hand_back = Some(back);
        let head = winch.head;
        let element_length = winch.pipe_element_length;
        let rod_length = self.rod.length();
        if let Some(pay_out) = self.pay_out.as_mut() {
            pay_out.element_length = element_length;
            pay_out.initial_length = rod_length;
        }
        if head.is_some() && winch.head_body.is_none() {
            let tolerance = 1e-9 * rod_length.max(1.0);
            self.attachments
                .retain(|a| (a.arc_length - rod_length).abs() > tolerance);
        }
    }

    /// Whether `element` is the winch's last wire element, next to the pipe's end: pay-in must not join it
    /// into the pipe.
    pub fn is_last_wire_element(&self, element: usize) -> bool {
        self.vessel
            .as_ref()
            .and_then(|v| v.holding_winch())
            .is_some_and(|w| {
                self.rod.segment_of.get(element) == Some(&w.wire)
                    && element
                        .checked_sub(1)
                        .is_some_and(|e| self.rod.segment_of.get(e) != Some(&w.wire))
            })
    }

    /// The node where the winch's wire meets the line below it (the pipe's end, where the head sits): the
    /// first node of the cable run at end B; `None` without a winch or if the whole line is wire.
    pub fn wire_joint(&self) -> Option<usize> {
        let wire = self.vessel.as_ref()?.winch.as_ref()?.wire;
        let count = self.rod.element_count();
        let run = self
            .rod
            .segment_of
            .iter()
            .rev()
            .take_while(|&&k| k == wire || self.rod.sections.get(k).is_some_and(|s| s.cable))
            .count();
        (run > 0 && run < count).then_some(count - run)
    }

    /// Where every support holds its node at time t (s).
    pub fn support_targets(&self, time: f64) -> Result<Vec<SupportTarget>> {
        self.supports.iter().map(|s| s.target(time)).collect()
    }

    /// Adds a fixed-direction force (N) and moment (N·m) at a node, scaled by `scale(t)` if given.
    pub fn point_load(
        &mut self,
        node: i64,
        force: Vector3<f64>,
        moment: Vector3<f64>,
        scale: Option<TimeFunction<f64>>,
    ) -> Result<()> {
        let node = self.node_index(node)?;
        finite("force", force.as_slice())?;
        finite("moment", moment.as_slice())?;
        let load = PointLoad {
            node,
            force,
            moment,
            scale,
        };
        load.scale_at(0.0)?;
        self.point_loads.push(load);
        Ok(())
    }

    /// Attaches `attachment` to the line; returns its index. Its arc length must lie on the line.
    pub fn attach(&mut self, attachment: Attachment) -> Result<usize> {
        let length = self.rod.length();
        if !(0.0..=length * (1.0 + 1e-12)).contains(&attachment.arc_length) {
            return Err(Error::input(
                "arc_length",
                format!("{} m", attachment.arc_length),
                format!("must lie on the line: in [0, {length}] m from end A"),
            ));
        }
        if let Some(pay_out) = &self.pay_out {
            if pay_out.at_start {
                return Err(Error::input(
                    "attach",
                    "an attachment to a line paid out at end A",
                    "attachments are placed from end A: pay out at end B",
                ));
            }
            let place = attachment.place(&self.rod);
            if place.element + 1 == self.rod.element_count() && place.weights[0] < 1.0 {
                return Err(Error::input(
                    "arc_length",
                    format!(
                        "{} m, on the end element pay-out grows",
                        attachment.arc_length
                    ),
                    "must lie on an element that pay-out does not grow (before the last)",
                ));
            }
        }
        self.attachments.push(attachment);
        Ok(self.attachments.len() - 1)
    }

    /// The arc length (m) of an attachment that element `element` carries (not merely at its first node).
    pub fn attachment_on_element(&self, element: usize) -> Option<f64> {
        self.placed_attachments()
            .find(|(_, place)| place.element == element && place.weights[0] < 1.0)
            .map(|(attachment, _)| attachment.arc_length)
    }

    /// Each attachment with its place on the line.
    pub fn placed_attachments(&self) -> impl Iterator<Item = (&Attachment, Place)> + '_ {
        self.attachments.iter().map(|a| (a, a.place(&self.rod)))
    }

    /// What each attachment applies to the line at `positions` moving with `velocities` (zero if `None`) at
    /// `time`: its weight less buoyancy and its drag in the current (N, in e).
    // Indexing cannot go out of bounds here: element indices of the model's own rod, on its node arrays.
    #[allow(clippy::indexing_slicing)]
    pub fn attachment_forces(
        &self,
        positions: &[Vector3<f64>],
        velocities: Option<&[Vector3<f64>]>,
        time: f64,
    ) -> Vec<Vector3<f64>> {
        let density = self.water_density();
        self.placed_attachments()
            .map(|(attachment, place)| {
                let e = place.element;
                let mut force = Vector3::z() * attachment.net_weight(density, self.gravity);
                if let Some(sea) = &self.sea {
                    let point = place.point(&positions[e], &positions[e + 1]);
                    let velocity =
                        velocities.map_or_else(Vector3::zeros, |v| place.point(&v[e], &v[e + 1]));
                    let (current, _) = sea.current_at(point.z, time);
                    force += attachment.drag(density, &(current - velocity));
                }
                force
            })
            .collect()
    }

    /// The sea's density (kg/m³), 0 without a sea.
    pub fn water_density(&self) -> f64 {
        self.sea.as_ref().map_or(0.0, |sea| sea.density)
    }

    /// Pays pipe out at `end` at `speed` (m/s; negative pays in). The end must carry the vessel or be driven:
    /// pipe cannot pass through a clamp or a pin.
    pub fn pay_out(&mut self, end: &str, speed: PayOutSpeed) -> Result<()> {
        let node = self.end_node(end)?;
        if node == 0 && !self.attachments.is_empty() {
            return Err(Error::input(
                "end",
                "\"A\" of a line with attachments",
                "attachments are placed from end A: pay out at end B",
            ));
        }
        if let Some(arc) = self.attachment_on_element(self.rod.element_count() - 1) {
            return Err(Error::input(
                "end",
                format!("\"{end}\", whose end element carries an attachment at {arc} m"),
                "pay-out grows the end element: attach on the elements before it",
            ));
        }
        let held = self
            .supports
            .iter()
            .find(|s| s.node == node)
            .map(|s| &s.kind);
        let by_vessel = self.vessel.as_ref().is_some_and(|v| v.node == node);
        match held {
            Some(SupportKind::Drive { .. }) => {}
            Some(_) => {
                return Err(Error::input(
                    "end",
                    format!("{end:?}, which is clamped or pinned"),
                    "pay-out needs the end the vessel holds or a driven end (pipe cannot pass a clamp or pin)",
                ))
            }
            None if by_vessel => {}
            None => {
                return Err(Error::input(
                    "end",
                    format!("{end:?}, which is free"),
                    "pay-out needs the end the vessel holds or a driven end",
                ))
            }
        }
        let pay_out = PayOut {
            at_start: node == 0,
            speed,
            element_length: self
                .rod
                .elements
                .get(node.saturating_sub(1))
                .map_or(0.0, |e| e.length),
            initial_length: self.rod.length(),
            feed: Vec::new(),
        };
        pay_out.speed_at(0.0)?;
        self.pay_out = Some(pay_out);
        Ok(())
    }

    /// The line still on board for the pay-out set by [`Model::pay_out`]: parts of `length` (m) and section, in
    /// the order they are paid out after the end's segment. Each element pay-out adds takes the section of the
    /// material at its midpoint, so a joint passes the end within half an element of its place.
    pub fn feed_pay_out(&mut self, feed: Vec<(f64, crate::rod::section::Section)>) -> Result<()> {
        if self.pay_out.is_none() {
            return Err(Error::input(
                "feed",
                format!("{} part(s)", feed.len()),
                "needs a pay-out to feed: set pay_out first",
            ));
        }
        let mut parts = Vec::with_capacity(feed.len());
        for (k, (length, section)) in feed.into_iter().enumerate() {
            finite(&format!("feed[{k}] length"), &[length])?;
            if length <= 0.0 {
                return Err(Error::input(
                    format!("feed[{k}] length"),
                    length,
                    "must be > 0 m",
                ));
            }
            self.rod.sections.push(section);
            parts.push((length, self.rod.sections.len() - 1));
        }
        if let Some(pay_out) = self.pay_out.as_mut() {
            pay_out.feed = parts;
        }
        Ok(())
    }

    /// The element that grows with pay-out and its end node, if pipe is paid out.
    pub fn growing_element(&self) -> Option<(usize, usize)> {
        let pay_out = self.pay_out.as_ref()?;
        let n = self.rod.element_count();
        Some(if pay_out.at_start { (0, 0) } else { (n - 1, n) })
    }

    /// Renumbers node references after a node was inserted (`delta` = 1) or removed (`delta` = −1) at index
    /// `at`: every reference to a node at or after `at` moves by `delta`.
    pub fn renumber_nodes(&mut self, at: usize, delta: isize) {
        let shift = |node: &mut usize| {
            if *node >= at {
                *node = node.saturating_add_signed(delta);
            }
        };
        self.supports.iter_mut().for_each(|s| shift(&mut s.node));
        self.point_loads.iter_mut().for_each(|l| shift(&mut l.node));
        if let Some(vessel) = &mut self.vessel {
            shift(&mut vessel.node);
        }
    }

    /// The model with its rod replaced by `rod`, a remeshing of it by pay-out (e.g. read from a checkpoint):
    /// the references to nodes move with the nodes pay-out added or removed.
    pub fn with_rod(&self, rod: Rod) -> Result<Model> {
        let added = rod.node_count() as isize - self.rod.node_count() as isize;
        if added != 0 && self.pay_out.is_none() {
            return Err(Error::input(
                "rod",
                format!("{} nodes", rod.node_count()),
                format!(
                    "must have this model's {} nodes (only pay-out changes the mesh)",
                    self.rod.node_count()
                ),
            ));
        }
        let mut model = self.clone();
        if let Some(pay_out) = &self.pay_out {
            let at = if pay_out.at_start {
                1
            } else {
                self.rod.element_count()
            };
            model.renumber_nodes(at, added);
        }
        model.rod = rod;
        // A rod remeshed after the hand-over has the winch's wire at its top: the winch holds it.
        let top = model.rod.element_count() - 1;
        let wire = model.vessel.as_ref().and_then(|v| v.winch.as_ref());
        if wire.is_some_and(|w| !w.holds && model.rod.segment_of.get(top) == Some(&w.wire)) {
            model.hold_by_winch();
        }
        Ok(model)
    }

    /// Submerged weight per unit reference length of a section (N/m, along +e3): (m − ρ_w A_b) g (text under
    /// eq. 17).
    pub fn submerged_weight_of(&self, section: &crate::rod::section::Section) -> f64 {
        (section.mass - self.water_density() * section.displaced_area) * self.gravity
    }

    /// Submerged weight per unit reference length of element `element` (N/m).
    pub fn submerged_weight(&self, element: usize) -> f64 {
        self.submerged_weight_of(self.rod.section(element))
    }

    /// The length-weighted mean submerged weight of the line (N/m).
    pub fn mean_submerged_weight(&self) -> f64 {
        self.rod.mean(|section| self.submerged_weight_of(section))
    }

    /// Whether node `node` has no rotation of its own: a cable node ([`Rod::is_cable_node`]) that does not
    /// carry the vessel (whose rotation the vessel's node keeps, as the winch holds its wire).
    pub fn is_rotationless(&self, node: usize) -> bool {
        self.rod.is_cable_node(node) && self.vessel.as_ref().is_none_or(|v| v.node != node)
    }

    /// How many hinge angles the model has: the sections of its vessel's articulated stinger (0 without).
    pub fn hinge_count(&self) -> usize {
        self.vessel
            .as_ref()
            .and_then(|v| v.lay.as_ref())
            .map_or(0, |lay| lay.hinge_count())
    }

    /// All DOFs: the nodes' six each, then the hinge angles.
    pub fn dof_count(&self) -> usize {
        self.hinge_dof(self.hinge_count())
    }

    /// The global DOF of hinge `i`'s angle: after the nodes' (see [`crate::assembly::dofs`]).
    pub fn hinge_dof(&self, i: usize) -> usize {
        NODE_DOFS * self.rod.node_count() + i
    }

    /// The seabed, if the model has one.
    pub fn seabed(&self) -> Option<&crate::environment::seabed::Seabed> {
        self.sea.as_ref().and_then(|sea| sea.seabed.as_ref())
    }

    /// Morison drag coefficients k = ½ρ_w C_D D_h (axial, normal) of a section, zero without a sea.
    pub fn drag_coefficients_of(&self, section: &crate::rod::section::Section) -> (f64, f64) {
        let k = 0.5 * self.water_density() * section.hydrodynamic_diameter;
        (k * section.drag[0], k * section.drag[1])
    }

    /// Morison drag coefficients of element `element`.
    pub fn drag_coefficients(&self, element: usize) -> (f64, f64) {
        self.drag_coefficients_of(self.rod.section(element))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::bathymetry::Bathymetry;
    use crate::environment::seabed::Seabed;
    use crate::rod::section::Section;
    use crate::vessel::rigid_body::Vessel;
    use nalgebra::Vector6;

    /// A 200 m pipe in `depth` of water over `seabed`, its end B at the surface.
    fn model(depth: f64, seabed: Option<Seabed>) -> Model {
        let section = Section::pipe(0.3, 0.02, 7850.0, 2.07e11, 0.3, 0.0, [0.0, 1.2], [0.0, 1.0])
            .expect("pipe");
        let rod = Rod::straight(
            Vector3::zeros(),
            Vector3::new(200.0, 0.0, -depth),
            10,
            section,
        )
        .expect("rod");
        let sea = Sea::new(depth, 1025.0, None, seabed).expect("sea");
        Model::new(rod, Some(sea), 9.81).expect("model")
    }

    fn attach(model: &mut Model, z: f64) -> Result<()> {
        attach_at(model, 200.0, z)
    }

    /// The OSV attached at end B with η = (x, 0, z, 0, 0, 0).
    fn attach_at(model: &mut Model, x: f64, z: f64) -> Result<()> {
        let eta = Vector6::new(x, 0.0, z, 0.0, 0.0, 0.0);
        model.attach_vessel(
            "B",
            Vessel::osv(),
            eta,
            Vector3::zeros(),
            None,
            vec![],
            None,
        )
    }

    /// The error's argument and the value it shows.
    fn refused(result: Result<()>) -> (String, String) {
        match result {
            Err(Error::Input {
                argument, value, ..
            }) => (argument, value),
            other => panic!("expected an input error, got {other:?}"),
        }
    }

    #[test]
    fn a_vessel_floats_at_the_surface_within_the_tolerance() {
        let mut m = model(120.0, None);
        // At the surface z = −120 m and within 10 m of it: accepted.
        for z in [-120.0, -110.0, -130.0] {
            attach(&mut m, z).expect("afloat");
        }
        // e3 down mistaken (z = +120, 240 m below the surface), on the seabed (z = 0), 15 m up in the air.
        for (z, shown) in [
            (120.0, "z = 120 m, 240 m below the surface"),
            (0.0, "z = 0 m, 120 m below the surface"),
            (-135.3, "z = -135.3 m, 15.3 m above the surface"),
        ] {
            let mut m = model(120.0, None);
            assert_eq!(refused(attach(&mut m, z)), ("eta".into(), shown.into()));
            assert!(m.vessel.is_none());
        }
        // In 12 m of water the tolerance is half the depth, 6 m: z = +12 and the seabed at z = 0 stay refused.
        let mut shallow = model(12.0, None);
        attach(&mut shallow, -6.5).expect("6 m under the surface");
        assert_eq!(refused(attach(&mut shallow, -5.5)).0, "eta");
        assert_eq!(refused(attach(&mut shallow, 12.0)).0, "eta");
    }

    #[test]
    fn a_vessel_is_refused_below_a_seabed_that_rises_under_it() {
        // A plane seabed rising 1 in 20 toward +x: z = 0 at the origin, −12.5 m at x = 250 m.
        let bathymetry = Bathymetry::plane(0.0, nalgebra::Vector2::new(-0.05, 0.0)).expect("plane");
        let seabed = Seabed::new(2e5, 0.0, [0.5, 0.8], 0.02, bathymetry).expect("seabed");
        let mut m = model(20.0, Some(seabed));
        assert_eq!(
            refused(attach_at(&mut m, 250.0, -12.0)),
            ("eta".into(), "z = -12 m at (x, y) = (250, 0) m".into())
        );
        attach(&mut m, -15.0).expect("above the seabed at x = 200 m, z = −10 m");
    }
}
