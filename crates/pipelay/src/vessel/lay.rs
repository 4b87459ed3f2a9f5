//! Lay equipment on the vessel (body frame b: forward, starboard, down): where the pipe is held (the
//! tensioner of an S-lay, the tower exit of a J-lay) and the rollers it runs over.
//!
//! A roller is a vessel-fixed cylinder: an axis line through its centre, a radius. The pipe's outer surface
//! (radius d_o/2) rests on it, a unilateral contact ([`crate::contact::rollers`]). A stinger is a circular arc of
//! rollers: the arc is the rollers' top line (the pipe's bottom when it rests on all of them), starting at
//! `origin` with the slope `angle` below the horizontal, running aft (−b1) and bending down with radius R,
//! whose supports are lone rollers across it or roller boxes ([`crate::vessel::roller_box`], which builds on
//! this module).
use crate::error::{finite, positive, Error, Result};
use crate::rod::reeling::Reeling;
use crate::vessel::articulation::Articulation;
pub use crate::vessel::stinger_arc::stinger_station;
use nalgebra::{Matrix3, Vector3};

/// What a roller's surface resists along the contact ([`crate::contact::roller_friction`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RollerFriction {
    /// Coulomb friction coefficient μ: along the roller for a free-turning one, in every direction for a
    /// locked one.
    pub friction: f64,
    /// A free-turning roller's rolling resistance coefficient f_r (force per normal force), along the pipe.
    pub rolling_resistance: f64,
    /// Whether the roller is braked or locked (it does not turn).
    pub locked: bool,
}

impl RollerFriction {
    /// A checked friction: coefficients finite and ≥ 0.
    pub fn new(friction: f64, rolling_resistance: f64, locked: bool) -> Result<Self> {
        for (name, value) in [
            ("friction", friction),
            ("rolling_resistance", rolling_resistance),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::input(
                    name,
                    value,
                    "must be a finite coefficient ≥ 0",
                ));
            }
        }
        Ok(RollerFriction {
            friction,
            rolling_resistance,
            locked,
        })
    }

    /// Whether the roller resists anything along the contact.
    pub fn is_frictionless(&self) -> bool {
        self.friction == 0.0 && (self.locked || self.rolling_resistance == 0.0)
    }
}

/// A vessel-fixed roller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Roller {
    /// A point of the roller's axis (body frame, m).
    pub centre: Vector3<f64>,
    /// The axis direction (body frame, unit).
    pub axis: Vector3<f64>,
    /// Roller radius (m).
    pub radius: f64,
    /// Roller length along its axis (m; infinite for the long cylinders of a plain stinger), centred on
    /// `centre`, with rounded ends.
    pub length: f64,
    /// The side the pipe rests on: unit, normal to the axis (body frame); for initial guesses and drawings.
    pub normal: Vector3<f64>,
    /// The point of the stinger's top line the roller's support stands at (body frame, m): the roller's top
    /// for a lone roller, the box's station for a roller of a box ([`crate::vessel::roller_box`]).
    pub station: Vector3<f64>,
    /// The index of the roller's support (a lone roller or a box) among the stinger's, from the hold point.
    pub support: usize,
    pub friction: RollerFriction,
    /// The articulated stinger's section the roller rides on ([`crate::vessel::articulation`]); None on the
    /// vessel.
    pub section: Option<usize>,
    /// A roller of a J-lay tower's guide at its exit ([`LayEquipment::with_guide`]), not of a stinger: the
    /// line runs through the guide and bends over it, it does not rest on it.
    pub guide: bool,
}

/// How many rollers make a J-lay tower's guide ([`LayEquipment::with_guide`]).
pub const GUIDE_ROLLERS: usize = 8;

/// Default roller radius (m) and contact stiffness (N/m): a stiff steel roller on its bearing.
pub const ROLLER_RADIUS: f64 = 0.25;
pub const ROLLER_STIFFNESS: f64 = 1e7;

/// How the vessel holds the pipe.
#[derive(Debug, Clone, PartialEq)]
pub struct LayEquipment {
    /// The hold point (tensioner or tower exit) in the body frame (m), relative to CO.
    pub hang_off: Vector3<f64>,
    /// The pipe-end frame in the body frame, R_t^b: t1 is the pipe's tangent leaving the hold toward end B.
    pub end_frame: Matrix3<f64>,
    pub rollers: Vec<Roller>,
    /// Contact stiffness of every roller (N per m of overlap).
    pub roller_stiffness: f64,
    /// The stinger's hinged sections, if it is articulated.
    pub articulation: Option<Articulation>,
    /// A reel-lay's reeling (reel, aligner, straightener) the pipe went through before the ramp: the state
    /// its wall enters the line in ([`crate::rod::reeling::entry_state`]).
    pub reeling: Option<Reeling>,
}

/// Checks a stinger arc of `radius` and `length` (at most half a circle) from `origin` at the slope `angle`,
/// and that `count` supports (at least 1) fit in memory.
pub fn check_arc(
    radius: f64,
    length: f64,
    origin: Vector3<f64>,
    angle: f64,
    count: usize,
) -> Result<()> {
    positive("stinger radius", radius, "m")?;
    positive("stinger length", length, "m")?;
    finite("stinger origin", origin.as_slice())?;
    finite("stinger angle", &[angle])?;
    if count == 0 {
        return Err(Error::input("rollers", 0, "must be at least 1"));
    }
    crate::memory::check(
        "rollers",
        count,
        count as f64 * (std::mem::size_of::<Roller>() as f64 + 100.0),
        "the rollers and their contacts",
    )?;
    if length / radius > std::f64::consts::PI {
        return Err(Error::input(
            "stinger length",
            length,
            format!(
                "must not exceed π·radius = {:.1} m (half a circle)",
                std::f64::consts::PI * radius
            ),
        ));
    }
    Ok(())
}

/// Body-frame top points, axes and outward normals of `count` rollers spread evenly over a stinger arc.
pub fn stinger_rollers(
    radius: f64,
    length: f64,
    count: usize,
    origin: Vector3<f64>,
    angle: f64,
    roller_radius: f64,
) -> Result<Vec<Roller>> {
    check_arc(radius, length, origin, angle, count)?;
    let rollers = (0..count)
        .map(|k| {
            let s = if count == 1 {
                0.0
            } else {
                length * k as f64 / (count - 1) as f64
            };
            let (top, normal, _) = stinger_station(radius, origin, angle, s);
            Roller {
                centre: top - roller_radius * normal,
                axis: Vector3::y(),
                radius: roller_radius,
                length: f64::INFINITY,
                normal,
                station: top,
                support: k,
                friction: RollerFriction::default(),
                section: None,
                guide: false,
            }
        })
        .collect();
    Ok(rollers)
}

/// Each support's station and the stinger's outward normal there (body frame, m and unit), in the supports'
/// order: see [`Roller::station`]. The normal is the mean of its rollers' resting sides (a box's V and side
/// rollers' lateral parts cancel).
pub fn supports(rollers: &[Roller]) -> Vec<(Vector3<f64>, Vector3<f64>)> {
    let mut supports: Vec<(Vector3<f64>, Vector3<f64>)> = Vec::new();
    let mut previous = None;
    for roller in rollers.iter().filter(|r| !r.guide) {
        match supports.last_mut() {
            Some(last) if previous == Some(roller.support) => last.1 += roller.normal,
            _ => supports.push((roller.station, roller.normal)),
        }
        previous = Some(roller.support);
    }
    for support in &mut supports {
        support.1 = support.1.try_normalize(1e-12).unwrap_or(-Vector3::z());
    }
    supports
}

/// Rollers at given top points with given axes (body frame); the pipe rests on their upper side.
pub fn rollers_at(
    tops: &[Vector3<f64>],
    axes: &[Vector3<f64>],
    roller_radius: f64,
) -> Result<Vec<Roller>> {
    tops.iter()
        .zip(axes)
        .enumerate()
        .map(|(support, (top, axis))| {
            finite("roller positions", top.as_slice())?;
            finite("roller axes", axis.as_slice())?;
            let axis = axis.try_normalize(1e-12).ok_or_else(|| {
                Error::input(
                    "roller axes",
                    format!("{axis:?}"),
                    "must be non-zero vectors",
                )
            })?;
            let up = -Vector3::z();
            let normal = (up - up.dot(&axis) * axis)
                .try_normalize(1e-9)
                .ok_or_else(|| {
                    Error::input(
                        "roller axes",
                        format!("{axis:?}"),
                        "must not be vertical (the pipe rests on the roller's upper side)",
                    )
                })?;
            Ok(Roller {
                centre: top - roller_radius * normal,
                axis,
                radius: roller_radius,
                length: f64::INFINITY,
                normal,
                station: *top,
                support,
                friction: RollerFriction::default(),
                section: None,
                guide: false,
            })
        })
        .collect()
}

/// Checks a tower's or a ramp's lean `angle` (rad, from the vertical toward the bow), named `name`.
pub fn check_lean(name: &str, angle: f64) -> Result<()> {
    finite(name, &[angle])?;
    if !(0.0..=std::f64::consts::FRAC_PI_2).contains(&angle) {
        return Err(Error::input(
            name,
            angle,
            "must be between 0 (vertical) and π/2 rad (horizontal)",
        ));
    }
    Ok(())
}

/// Puts each of `rollers` on the section of `articulation` that carries its station.
pub fn assign_sections(articulation: &Articulation, rollers: &mut [Roller]) {
    for roller in rollers {
        roller.section = articulation.section_at(articulation.arc_length_of(&roller.station));
    }
}

impl LayEquipment {
    /// S-lay: the pipe held by the tensioner at `tensioner` on a horizontal firing line along +b1 (its
    /// tangent toward end B points forward), running aft over `rollers`.
    pub fn s_lay(tensioner: Vector3<f64>, rollers: Vec<Roller>, stiffness: f64) -> Result<Self> {
        finite("tensioner", tensioner.as_slice())?;
        positive("roller_stiffness", stiffness, "N/m")?;
        Ok(LayEquipment {
            hang_off: tensioner,
            end_frame: Matrix3::identity(),
            rollers,
            roller_stiffness: stiffness,
            articulation: None,
            reeling: None,
        })
    }

    /// J-lay: the pipe held at the tower exit `position`, its tangent toward end B up the tower, which
    /// leans `angle` (rad) from the vertical toward the bow: t1 = (sin α, 0, −cos α) in b.
    pub fn j_lay(position: Vector3<f64>, angle: f64) -> Result<Self> {
        finite("position", position.as_slice())?;
        check_lean("angle", angle)?;
        let pitch = std::f64::consts::FRAC_PI_2 - angle;
        // Rotation about b2 by `pitch` turns b1 into (cos, 0, −sin) = (sin α, 0, −cos α).
        let (s, c) = pitch.sin_cos();
        let end_frame = Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c);
        Ok(LayEquipment {
            hang_off: position,
            end_frame,
            rollers: Vec::new(),
            roller_stiffness: ROLLER_STIFFNESS,
            articulation: None,
            reeling: None,
        })
    }

    /// This J-lay tower with a guide at its exit: a bellmouth of bend radius `radius` (m) whose narrowest
    /// opening, in the exit's plane, is `opening` (m) across. It is [`GUIDE_ROLLERS`] rollers of that radius in
    /// a ring around the tower's axis, each tangent to the ring and as long as the ring's side, so that a line
    /// leaving the exit at an angle bends over the bellmouth's surface instead of running through the tower.
    pub fn with_guide(mut self, radius: f64, opening: f64) -> Result<Self> {
        positive("guide", radius, "m")?;
        positive("guide_opening", opening, "m")?;
        if self.rollers.iter().any(|r| !r.guide) || self.reeling.is_some() {
            return Err(Error::input(
                "guide",
                radius,
                "is a J-lay tower's: a stinger's rollers already guide the line",
            ));
        }
        let along = self.end_frame.column(0).into_owned();
        let across = self.end_frame.column(1).into_owned();
        let ring = 0.5 * opening + radius;
        let half_angle = std::f64::consts::PI / GUIDE_ROLLERS as f64;
        self.rollers = (0..GUIDE_ROLLERS)
            .map(|k| {
                let angle = 2.0 * half_angle * k as f64;
                let outward = across * angle.cos() + along.cross(&across) * angle.sin();
                Roller {
                    centre: self.hang_off + ring * outward,
                    axis: along.cross(&outward),
                    radius,
                    length: 2.0 * ring * half_angle.tan(),
                    normal: -outward,
                    station: self.hang_off + 0.5 * opening * outward,
                    support: k,
                    friction: RollerFriction::default(),
                    section: None,
                    guide: true,
                }
            })
            .collect();
        Ok(self)
    }

    /// Reel-lay: the pipe, reeled by `reeling`, held at the ramp's exit `position` along the ramp, which
    /// leans `angle` (rad) from the vertical toward the bow, as a J-lay tower ([`Self::j_lay`]).
    pub fn reel_lay(position: Vector3<f64>, angle: f64, reeling: Reeling) -> Result<Self> {
        check_lean("ramp_angle", angle)?;
        Ok(LayEquipment {
            reeling: Some(reeling),
            ..Self::j_lay(position, angle)?
        })
    }

    /// How many hinge angles the stinger has (0 unless articulated).
    pub fn hinge_count(&self) -> usize {
        self.articulation.as_ref().map_or(0, |a| a.sections.len())
    }

    /// The rollers where the hinge `angles` put them (body frame): each section's turned with it.
    pub fn placed_rollers(&self, angles: &[f64]) -> Vec<Roller> {
        let Some(articulation) = &self.articulation else {
            return self.rollers.clone();
        };
        self.rollers
            .iter()
            .map(|roller| match roller.section {
                Some(j) => {
                    let (rotation, translation) = articulation.chain.placement(angles, j);
                    Roller {
                        centre: rotation * roller.centre + translation,
                        axis: rotation * roller.axis,
                        normal: rotation * roller.normal,
                        station: rotation * roller.station + translation,
                        ..*roller
                    }
                }
                None => *roller,
            })
            .collect()
    }

    /// Puts each roller on the articulated stinger's section that carries its station (none without one).
    pub fn assign_sections(&mut self) {
        if let Some(articulation) = &self.articulation {
            assign_sections(articulation, &mut self.rollers);
        }
    }

    /// Length of the roller path from the hold point to the farthest roller (m): how far along the pipe
    /// from its held end the rollers can reach.
    pub fn reach(&self) -> f64 {
        let mut previous = self.hang_off;
        let mut length = 0.0;
        for roller in &self.rollers {
            let top = roller.centre + roller.radius * roller.normal;
            length += (top - previous).norm();
            previous = top;
        }
        length
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stinger_rollers_lie_on_the_arc() {
        let (radius, origin, angle) = (100.0, Vector3::new(-30.0, 0.0, 5.0), 0.05);
        let rollers = stinger_rollers(radius, 60.0, 7, origin, angle, 0.3).unwrap();
        // The arc's centre: origin + R·(inward normal at the start).
        let centre = origin + radius * Vector3::new(angle.sin(), 0.0, angle.cos());
        for roller in &rollers {
            let top = roller.centre + roller.radius * roller.normal;
            assert!(((top - centre).norm() - radius).abs() < 1e-9);
            assert!(((roller.centre - centre).norm() - (radius - 0.3)).abs() < 1e-9);
        }
        let last = rollers[6].centre + 0.3 * rollers[6].normal;
        let arc = 2.0 * radius * (0.5 * (last - origin).norm() / radius).asin();
        assert!((arc - 60.0).abs() < 1e-9);
        assert!(last.x < origin.x && last.z > origin.z);
    }

    #[test]
    fn j_lay_tangent_leans_from_vertical() {
        let lay = LayEquipment::j_lay(Vector3::zeros(), 0.2).unwrap();
        let t1 = lay.end_frame.column(0);
        assert!((t1 - Vector3::new(0.2f64.sin(), 0.0, -0.2f64.cos())).norm() < 1e-12);
        assert!((lay.end_frame.determinant() - 1.0).abs() < 1e-12);
        assert!(LayEquipment::j_lay(Vector3::zeros(), 2.0).is_err());
    }
}
