//! The abandonment and recovery (A&R) winch: a vessel-fixed point (body frame) where its wire enters the
//! firing line, on the line through the hold point along the pipe's tangent (ahead of the tensioner in an
//! S-lay, up the tower in a J-lay). While the tensioner holds the pipe the winch waits; at the hand-over its
//! wire, from the pipe's end to the winch, takes the load ([`crate::dynamics::hand_over`]) and from then on the
//! vessel holds the line's end at the winch, which pays the wire out or hauls it in.
use crate::error::{finite, positive, Error, Result};
use crate::rod::attachment::Attachment;
use nalgebra::Vector3;

/// An A&R winch on the vessel.
#[derive(Debug, Clone, PartialEq)]
pub struct Winch {
    /// Where the wire enters the firing line (body frame, relative to CO, m).
    pub position: Vector3<f64>,
    /// The largest wire tension the winch is rated for (N); `None`: unlimited.
    pub tension_limit: Option<f64>,
    /// The wire's section: an index into the rod's sections.
    pub wire: usize,
    /// Length of the wire elements pay-out adds (m).
    pub element_length: f64,
    /// The laydown head fitted to the pipe's end at the hand-over (its arc length is set then).
    pub head: Option<Attachment>,
    /// Whether the winch holds the line (after the hand-over, or from the start for a line whose top is wire).
    pub holds: bool,
}

impl Winch {
    /// Checks a winch's values (its wire section is added by [`crate::model::Model::add_winch`]).
    pub fn checked(
        position: Vector3<f64>,
        tension_limit: Option<f64>,
        element_length: f64,
        head: Option<Attachment>,
    ) -> Result<Self> {
        finite("winch position", position.as_slice())?;
        if let Some(limit) = tension_limit {
            positive("tension_limit", limit, "N")?;
        }
        positive("element_length", element_length, "m")?;
        Ok(Winch {
            position,
            tension_limit,
            wire: 0,
            element_length,
            head,
            holds: false,
        })
    }

    /// Its distance ahead of the hold point `hang_off` along the firing line `tangent` (body frame, unit),
    /// checked: the winch must lie on that line, ahead of the hold point.
    pub fn distance_along(&self, hang_off: &Vector3<f64>, tangent: &Vector3<f64>) -> Result<f64> {
        let offset = self.position - hang_off;
        let distance = offset.dot(tangent);
        let across = (offset - distance * tangent).norm();
        if distance <= 0.0 || across > 1e-6 * distance.max(1.0) {
            return Err(Error::input(
                "winch position",
                format!("{:?} (body frame)", self.position.as_slice()),
                format!(
                    "must lie on the firing line ahead of the hold point {:?}: hold point + d·{:?}, d > 0 \
                     (its wire runs down the firing line to the pipe's end)",
                    hang_off.as_slice(),
                    tangent.as_slice()
                ),
            ));
        }
        Ok(distance)
    }
}
