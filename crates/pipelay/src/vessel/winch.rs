//! The abandonment and recovery (A&R) winch: a vessel-fixed point (body frame) where its wire enters the
//! firing line, on the line through the hold point along the pipe's tangent (ahead of the tensioner in an
//! S-lay, up the tower in a J-lay). While the tensioner holds the pipe the winch waits; at the hand-over its
//! wire, from the pipe's end to the winch, takes the load ([`crate::dynamics::hand_over`]) and from then on the
//! vessel holds the line's end at the winch, which pays the wire out or hauls it in.
//!
//! The winch's drive ([`Drive`]) runs at a commanded speed, or holds a set tension (constant-tension mode),
//! within its speed and acceleration limits, and renders where the wire's tension reaches its rating. The
//! speed over a step is then a function of the wire's tension at the step's end ([`WinchLaw`]), which the time
//! step solves with the line ([`crate::rod::cable::step`]).
use crate::error::{finite, positive, Error, Result};
use crate::rod::attachment::Attachment;
use nalgebra::{Matrix3, Vector3};

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
    /// The laydown head fitted to the pipe's end at the hand-over (its arc length is set then): a point body,
    /// or its mass, volume, drag and added mass when it has a `head_body`.
    pub head: Option<Attachment>,
    /// The head as a body of length and diameter: an element of the line between the pipe's end and the wire.
    pub head_body: Option<HeadBody>,
    /// Whether the winch holds the line (after the hand-over, or from the start for a line whose top is wire).
    pub holds: bool,
    pub drive: Drive,
    /// From each start time (s), the tension the winch holds in constant-tension mode (N), `None` for the
    /// commanded speed; set by the stages, in order of time. Empty: commanded speed throughout.
    pub modes: Vec<(f64, Option<f64>)>,
    /// The length of the pipe elements pay-out added before the hand-over (m), which pay-out adds again after
    /// the hand-back.
    pub pipe_element_length: f64,
    /// Where and when the tensioner took the pipe back, once it has ([`crate::dynamics::hand_back`]).
    pub hand_back: Option<HandBack>,
}

/// A laydown head with a length and a diameter: one element of the line from the pipe's end to the wire's
/// padeye ([`crate::rod::section::Section::head`]), its surface tapering from its diameter to the wire's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadBody {
    /// Length (m).
    pub length: f64,
    /// Diameter at the pipe's end (m).
    pub diameter: f64,
    /// Its section: an index into the rod's sections (set by [`crate::model::Model::add_winch`]).
    pub section: usize,
}

/// The hand-back of the line from the winch to the tensioner: its time and the clamp it made, where the pipe's
/// end was then.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HandBack {
    /// Time (s).
    pub time: f64,
    /// The hold point: the pipe's end in the body frame, relative to CO (m).
    pub hang_off: Vector3<f64>,
    /// R_b^t: the body frame in the pipe's end frame then (the clamp's angle).
    pub angle: Matrix3<f64>,
}

/// The winch's drive: how fast it can pay out or haul in, how fast it can change speed, and the tension band
/// of its constant-tension mode and of its rendering at the rating.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drive {
    /// The largest speed either way (m/s).
    pub speed_limit: f64,
    /// The largest change of speed (m/s²).
    pub acceleration_limit: f64,
    /// The tension band (N): in constant-tension mode the winch stands while the tension is within the set
    /// tension ± band, and runs at full speed 2·band away from it; at the rating it renders from
    /// rating − band, at full speed at the rating.
    pub tension_band: f64,
}

impl Default for Drive {
    /// 1 m/s, 0.5 m/s², 50 kN.
    fn default() -> Self {
        Drive {
            speed_limit: 1.0,
            acceleration_limit: 0.5,
            tension_band: 5e4,
        }
    }
}

impl Drive {
    /// Checks the drive's values: each positive and finite.
    pub fn checked(self) -> Result<Self> {
        positive("speed_limit", self.speed_limit, "m/s")?;
        positive("acceleration_limit", self.acceleration_limit, "m/s²")?;
        positive("tension_band", self.tension_band, "N")?;
        Ok(self)
    }
}

/// What the winch does over one step: its speed v (m/s, positive paying out) as a function of the wire's
/// tension T at the winch at the step's end.
///
/// - Commanded speed v_c: v = v_c + max(v_max − v_c, 0)·s, s = clamp((T − T_r + b)/b, 0, 1) with the rating
///   T_r and the band b (without a rating, s = 0): the winch renders from T_r − b, at full speed at T_r.
/// - Constant tension T_s: v = v_max·clamp(sign(e)·max(|e| − b, 0)/b, −1, 1), e = T − T_s: it stands within the
///   band, renders above it and hauls below it.
///
/// Either way v is then held within [v_prev − aΔt, v_prev + aΔt] (the acceleration limit a) and [−v_max, v_max]
/// (a commanded speed beyond v_max is refused where the stages are set). v(T) does not decrease with T, so
/// the wire's unstretched length over the step, L = L_n + Δt v(T(l, L)), has one solution for each chord l.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WinchLaw {
    /// The commanded speed (m/s), or `None` in constant-tension mode.
    pub commanded: Option<f64>,
    /// The set tension in constant-tension mode, or the rating the winch renders at (N).
    pub tension: Option<f64>,
    pub band: f64,
    pub speed_limit: f64,
    /// The speeds the acceleration limit allows over the step (m/s).
    pub lowest: f64,
    pub highest: f64,
}

impl WinchLaw {
    /// The law of `winch` over a step of `dt` (s) from `time` (s), commanded `commanded` (m/s, the stages'
    /// speed at the step's midpoint) after the speed `previous` (m/s) of the step before.
    pub fn of(winch: &Winch, time: f64, dt: f64, commanded: f64, previous: f64) -> Self {
        let drive = winch.drive;
        let set = winch.set_tension_at(time);
        let change = drive.acceleration_limit * dt;
        WinchLaw {
            commanded: set.is_none().then_some(commanded),
            tension: set.or(winch.tension_limit),
            band: drive.tension_band,
            speed_limit: drive.speed_limit,
            lowest: (previous - change).max(-drive.speed_limit),
            highest: (previous + change).min(drive.speed_limit),
        }
    }

    /// The speed v(T) (m/s) and dv/dT at the wire's tension `tension` (N).
    pub fn speed(&self, tension: f64) -> (f64, f64) {
        let (v, slope) = match (self.commanded, self.tension) {
            (Some(commanded), None) => (commanded, 0.0),
            (Some(commanded), Some(rating)) => {
                let room = (self.speed_limit - commanded).max(0.0);
                let s = (tension - rating + self.band) / self.band;
                if s <= 0.0 {
                    (commanded, 0.0)
                } else if s >= 1.0 {
                    (commanded + room, 0.0)
                } else {
                    (commanded + room * s, room / self.band)
                }
            }
            (None, set) => {
                let error = tension - set.unwrap_or(tension);
                let x = (error.abs() - self.band) / self.band;
                if x <= 0.0 {
                    (0.0, 0.0)
                } else if x >= 1.0 {
                    (self.speed_limit.copysign(error), 0.0)
                } else {
                    (
                        self.speed_limit.copysign(error) * x,
                        self.speed_limit / self.band,
                    )
                }
            }
        };
        if v < self.lowest {
            (self.lowest, 0.0)
        } else if v > self.highest {
            (self.highest, 0.0)
        } else {
            (v, slope)
        }
    }

    /// Whether the speed depends on the tension (otherwise it is the lowest of [commanded, bounds]).
    pub fn renders(&self) -> bool {
        self.tension.is_some()
    }

    /// The wire's unstretched length L (m) at the step's end for the chord `chord` (m) of its top element, of
    /// axial stiffness `ea` (N) and unstretched length `length_start` (m) at the step's start, and dL/dl:
    /// the root of F(L) = L − L_n − Δt v(EA max(l/L − 1, 0)), increasing in L, by Newton's method kept in its
    /// bracket [L_n + Δt v_low, L_n + Δt v_high]. dL/dl = Δt v′ EA/L / (1 + Δt v′ EA l/L²).
    pub fn length(&self, ea: f64, length_start: f64, dt: f64, chord: f64) -> (f64, f64) {
        let tension = |length: f64| ea * (chord / length - 1.0).max(0.0);
        let residual = |length: f64| {
            let (v, slope) = self.speed(tension(length));
            let taut = chord > length;
            let d_tension = if taut {
                -ea * chord / (length * length)
            } else {
                0.0
            };
            (
                length - length_start - dt * v,
                1.0 - dt * slope * d_tension,
                slope,
            )
        };
        let (mut low, mut high) = (
            length_start + dt * self.lowest,
            length_start + dt * self.highest,
        );
        let mut length = length_start + dt * self.speed(tension(length_start)).0;
        let mut slope = 0.0;
        for _ in 0..100 {
            let (f, df, v_slope) = residual(length);
            slope = v_slope;
            if f.abs() <= 1e-15 * length_start.abs().max(1.0) {
                break;
            }
            if f > 0.0 {
                high = length;
            } else {
                low = length;
            }
            let next = length - f / df;
            length = if next > low && next < high {
                next
            } else {
                0.5 * (low + high)
            };
            if high - low <= 1e-15 * length_start.abs().max(1.0) {
                break;
            }
        }
        let taut = chord > length;
        let derivative = if taut && slope > 0.0 {
            let k = dt * slope * ea;
            (k / length) / (1.0 + k * chord / (length * length))
        } else {
            0.0
        };
        (length, derivative)
    }
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
            drive: Drive::default(),
            modes: Vec::new(),
            pipe_element_length: element_length,
            hand_back: None,
            head_body: None,
        })
    }

    /// The winch with a head of `length` and `diameter` (m, both positive) fitted at the hand-over as a body.
    pub fn with_head_body(self, length: f64, diameter: f64) -> Result<Self> {
        positive("head_length", length, "m")?;
        positive("head_diameter", diameter, "m")?;
        if self.head.is_none() {
            return Err(Error::input(
                "head_length",
                length,
                "needs head=pl.Clump(...): the head's mass, volume, drag area and added mass",
            ));
        }
        Ok(Winch {
            head_body: Some(HeadBody {
                length,
                diameter,
                section: 0,
            }),
            ..self
        })
    }

    /// The head body's length (m), zero for a point head.
    pub fn head_length(&self) -> f64 {
        self.head_body.map_or(0.0, |body| body.length)
    }

    /// The unstretched length of the wire from the hold point `hang_off` (body frame), or from a head body's
    /// nose there, to the winch under the
    /// tension `tension` (N) of a wire of axial stiffness `ea` (N): hauled in to it, the pipe's end is back at
    /// the hold point, and the tensioner takes the pipe back.
    pub fn hand_back_length(&self, hang_off: &Vector3<f64>, tension: f64, ea: f64) -> f64 {
        ((self.position - hang_off).norm() - self.head_length()) / (1.0 + tension.max(0.0) / ea)
    }

    /// The tension the winch holds at `time` (s) in constant-tension mode, `None` at its commanded speed.
    pub fn set_tension_at(&self, time: f64) -> Option<f64> {
        self.modes
            .iter()
            .rev()
            .find(|(start, _)| time >= *start)
            .and_then(|&(_, set)| set)
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
