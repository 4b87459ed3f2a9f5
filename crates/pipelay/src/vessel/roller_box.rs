//! Roller boxes: the supports of a real stinger, each a few rollers of finite length set across the pipe.
//!
//! A box stands at a station P of the stinger's top line, in the plane normal to the stinger's tangent t
//! there; l is the lateral direction (starboard, in that plane) and u the stinger's outward normal (up).
//! - **V**: two rollers rising outward at ±θ from the lateral: axis a = cos θ (±l) + sin θ u, resting side
//!   n = ∓sin θ l + cos θ u. Their surfaces meet at P (without a bottom roller), so a pipe of radius R rests
//!   with its centre R/cos θ above P, touching each roller R tan θ up from its lower end, and each roller
//!   carries F/(2 cos θ) of a vertical load F. A lateral load beyond F tan θ lifts the pipe off the lower
//!   roller: it climbs the other and, past its upper end, out of the box.
//! - **bottom**: a roller along l whose top is P, between the lower ends of the V's rollers (or of a U's
//!   sides), which then start at P ± (L/2) l.
//! - **sides**: vertical rollers (axis u) whose inner surfaces rise from the upper ends of the V's rollers
//!   (of the bottom roller's ends, in a U).
//! - **U**: a bottom roller and two sides.
//!
//! The rollers are listed V port, V starboard, bottom, side port, side starboard (those the box has).
use crate::error::{positive, Error, Result};
use crate::vessel::lay::{check_arc, stinger_station, Roller, RollerFriction};
use nalgebra::Vector3;

/// The shape of a box's rollers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoxShape {
    /// Two rollers in a V, with an optional bottom roller and optional side rollers.
    V,
    /// A bottom roller between two vertical side rollers.
    U,
}

/// A roller box (all lengths in m, angles in rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerBox {
    pub shape: BoxShape,
    /// θ: each V roller's rise from the lateral (0 < θ < π/2).
    pub half_angle: f64,
    /// L: every roller's length.
    pub roller_length: f64,
    pub bottom: bool,
    pub sides: bool,
    /// What every roller of the box resists along the contact.
    pub friction: RollerFriction,
}

impl RollerBox {
    /// A checked box.
    pub fn new(
        shape: BoxShape,
        half_angle: f64,
        roller_length: f64,
        bottom: bool,
        sides: bool,
    ) -> Result<Self> {
        positive("roller_length", roller_length, "m")?;
        if shape == BoxShape::V && !(half_angle > 0.0 && half_angle < 0.5 * std::f64::consts::PI) {
            return Err(Error::input(
                "half_angle",
                half_angle,
                "must lie between 0 and π/2 rad (a V's rollers rise from the lateral by it)",
            ));
        }
        Ok(RollerBox {
            shape,
            half_angle,
            roller_length,
            bottom: bottom || shape == BoxShape::U,
            sides: sides || shape == BoxShape::U,
            friction: RollerFriction::default(),
        })
    }

    /// The box's rollers (radius `roller_radius`) at the station `station` of the stinger's top line, where
    /// the stinger's outward normal is `up` and the lateral direction (starboard) is `lateral`, both unit
    /// and normal to each other; `support` is the box's index among the stinger's supports.
    pub fn rollers(
        &self,
        station: Vector3<f64>,
        up: Vector3<f64>,
        lateral: Vector3<f64>,
        roller_radius: f64,
        support: usize,
    ) -> Vec<Roller> {
        let (length, r) = (self.roller_length, roller_radius);
        let roller =
            |surface_start: Vector3<f64>, axis: Vector3<f64>, normal: Vector3<f64>| Roller {
                centre: surface_start - r * normal + 0.5 * length * axis,
                axis,
                radius: r,
                length,
                normal,
                station,
                support,
                friction: self.friction,
                section: None,
                guide: false,
            };
        // Where the rising rollers (the V's, or a U's sides) start: at P, or at the bottom roller's ends.
        let foot = |side: f64| {
            if self.bottom {
                station + side * 0.5 * length * lateral
            } else {
                station
            }
        };
        let mut rollers = Vec::with_capacity(5);
        let mut tops = [station; 2];
        if self.shape == BoxShape::V {
            let (sin, cos) = self.half_angle.sin_cos();
            for (top, side) in tops.iter_mut().zip([-1.0, 1.0]) {
                let axis = cos * side * lateral + sin * up;
                let normal = -sin * side * lateral + cos * up;
                rollers.push(roller(foot(side), axis, normal));
                *top = foot(side) + length * axis;
            }
        } else {
            tops = [foot(-1.0), foot(1.0)];
        }
        if self.bottom {
            rollers.push(roller(station - 0.5 * length * lateral, lateral, up));
        }
        if self.sides {
            for (top, side) in tops.into_iter().zip([-1.0, 1.0]) {
                rollers.push(roller(top, up, -side * lateral));
            }
        }
        rollers
    }
}

/// The rollers of a stinger of roller boxes: each box at its arc length (m) along a stinger arc (as
/// [`stinger_rollers`]), in the plane normal to the arc there, its rollers of radius `roller_radius` (m).
pub fn stinger_boxes(
    radius: f64,
    length: f64,
    origin: Vector3<f64>,
    angle: f64,
    roller_radius: f64,
    boxes: &[(f64, RollerBox)],
) -> Result<Vec<Roller>> {
    check_arc(radius, length, origin, angle, boxes.len().max(1))?;
    let mut rollers = Vec::with_capacity(5 * boxes.len());
    for (support, (arc_length, roller_box)) in boxes.iter().enumerate() {
        check_arc_length(*arc_length, length)?;
        let (station, up, _) = stinger_station(radius, origin, angle, *arc_length);
        rollers.extend(roller_box.rollers(station, up, Vector3::y(), roller_radius, support));
    }
    Ok(rollers)
}

/// Checks a box's place on the stinger: `arc_length` within [0, `length`] (m).
pub fn check_arc_length(arc_length: f64, length: f64) -> Result<()> {
    if !(0.0..=length).contains(&arc_length) {
        return Err(Error::input(
            "arc_length",
            arc_length,
            format!("must lie on the stinger, between 0 and its length {length} m"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pipe of radius R resting in a V of half-angle θ touches each roller's surface with its centre
    /// R/cos θ above the station: the rollers' axes lie R + r from that centre.
    #[test]
    fn a_pipe_rests_in_the_v_at_its_closed_form_height() {
        let (theta, radius, r) = (0.5_f64, 0.3, 0.2);
        let up = -Vector3::z();
        let lateral = Vector3::y();
        let station = Vector3::new(-10.0, 0.0, 3.0);
        let v = RollerBox::new(BoxShape::V, theta, 1.2, false, true).unwrap();
        let rollers = v.rollers(station, up, lateral, r, 4);
        assert_eq!(rollers.len(), 4);
        let centre = station + radius / theta.cos() * up;
        for roller in &rollers[..2] {
            let offset = centre - roller.centre;
            let across = offset - roller.axis.dot(&offset) * roller.axis;
            assert!((across.norm() - (radius + r)).abs() < 1e-12);
            assert!(across.dot(&roller.normal) > 0.0);
            // The contact lies R tan θ up from the roller's lower end.
            let along = roller.axis.dot(&offset) + 0.6;
            assert!((along - radius * theta.tan()).abs() < 1e-12, "{along}");
            assert_eq!((roller.support, roller.station), (4, station));
        }
        // The side rollers stand at the V's upper ends, vertical, facing in.
        for (side, roller) in [-1.0, 1.0].into_iter().zip(&rollers[2..]) {
            assert_eq!(roller.axis, up);
            assert!((roller.normal + side * lateral).norm() < 1e-15);
            let inner = roller.centre + r * roller.normal - 0.6 * up;
            let v_top = station + 1.2 * (theta.cos() * side * lateral + theta.sin() * up);
            assert!((inner - v_top).norm() < 1e-12);
        }
        assert!(RollerBox::new(BoxShape::V, 1.6, 1.2, false, false).is_err());
        assert!(RollerBox::new(BoxShape::V, 0.5, 0.0, false, false).is_err());
    }
}
