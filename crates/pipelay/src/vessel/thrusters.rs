//! The vessel's thrusters: where each sits, which way it pushes, how much and how fast its thrust and azimuth
//! can change, and the generalised force they deliver together.
//!
//! A thruster at (l_x, l_y) (body frame, from CO) pushing with thrust f along azimuth α (from the bow toward
//! starboard) gives the body-frame force and moment
//!   X = f cos α,  Y = f sin α,  N = l_x f sin α − l_y f cos α            (Fossen 2021, eq. 11.53),
//! a tunnel thruster at α = 90° (positive thrust pushes to starboard), a main propeller at α = 0 (positive
//! thrust pushes ahead), an azimuth thruster along an azimuth it turns. Its thrust answers the command through
//! a first-order lag of time constant T, ḟ = (f_c − f)/T, and both the thrust and the azimuth change no faster
//! than their rate limits.
// Indexing cannot go out of bounds here: thruster lists and their states have one entry per thruster, checked.
#![allow(clippy::indexing_slicing)]
use crate::error::{Error, Result};
use nalgebra::{Vector2, Vector6};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// What a thruster is: it sets the direction it pushes in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ThrusterKind {
    /// A tunnel thruster: pushes athwartships (positive: to starboard), forward or reverse.
    Tunnel,
    /// An azimuth thruster: pushes along an azimuth it turns, forward only.
    Azimuth,
    /// A main propeller: pushes ahead (positive) or astern.
    Main,
}

impl ThrusterKind {
    /// The kind named `name` ("tunnel", "azimuth" or "main").
    pub fn parse(name: &str) -> Result<Self> {
        match name {
            "tunnel" => Ok(ThrusterKind::Tunnel),
            "azimuth" => Ok(ThrusterKind::Azimuth),
            "main" => Ok(ThrusterKind::Main),
            other => Err(Error::input(
                "kind",
                format!("{other:?}"),
                "must be \"tunnel\", \"azimuth\" or \"main\"",
            )),
        }
    }

    /// The kind's name.
    pub fn name(self) -> &'static str {
        match self {
            ThrusterKind::Tunnel => "tunnel",
            ThrusterKind::Azimuth => "azimuth",
            ThrusterKind::Main => "main",
        }
    }
}

/// One thruster.
#[derive(Debug, Clone, PartialEq)]
pub struct Thruster {
    pub kind: ThrusterKind,
    /// (l_x, l_y): where it pushes, body frame from CO (m).
    pub position: Vector2<f64>,
    /// The largest forward thrust (N).
    pub max_thrust: f64,
    /// The largest reverse thrust (N, ≥ 0; zero for an azimuth thruster, which turns instead).
    pub reverse_thrust: f64,
    /// Bound on |ḟ| (N/s); `None`: unbounded.
    pub thrust_rate: Option<f64>,
    /// Bound on |α̇| of an azimuth thruster (rad/s); `None`: unbounded.
    pub azimuth_rate: Option<f64>,
    /// Time constant T of the thrust's first-order response (s; 0: the thrust follows the command at once).
    pub time_constant: f64,
}

/// A thruster's thrust f (N) and azimuth α (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ThrusterState {
    pub thrust: f64,
    pub azimuth: f64,
}

fn check_positive(argument: &str, value: f64, unit: &str, zero: bool) -> Result<()> {
    let ok = value.is_finite() && (value > 0.0 || (zero && value == 0.0));
    if ok {
        return Ok(());
    }
    let allowed = if zero { "≥ 0" } else { "> 0" };
    Err(Error::input(
        argument,
        value,
        format!("must be a finite number {allowed} ({unit})"),
    ))
}

impl Thruster {
    /// A checked thruster; the reverse thrust defaults to the forward one for a tunnel thruster or a main
    /// propeller, and must be absent (or zero) for an azimuth thruster.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        kind: ThrusterKind,
        position: Vector2<f64>,
        max_thrust: f64,
        reverse_thrust: Option<f64>,
        thrust_rate: Option<f64>,
        azimuth_rate: Option<f64>,
        time_constant: f64,
    ) -> Result<Self> {
        crate::error::finite("position", position.as_slice())?;
        check_positive("max_thrust", max_thrust, "N", false)?;
        let reverse_thrust = match (kind, reverse_thrust) {
            (ThrusterKind::Azimuth, Some(reverse)) if reverse != 0.0 => {
                return Err(Error::input(
                    "reverse_thrust",
                    reverse,
                    "must be None for an azimuth thruster (it turns to push the other way)",
                ))
            }
            (ThrusterKind::Azimuth, _) => 0.0,
            (_, Some(reverse)) => {
                check_positive("reverse_thrust", reverse, "N", true)?;
                reverse
            }
            (_, None) => max_thrust,
        };
        if let Some(rate) = thrust_rate {
            check_positive("thrust_rate", rate, "N/s", false)?;
        }
        if let Some(rate) = azimuth_rate {
            check_positive("azimuth_rate", rate, "rad/s", false)?;
            if kind != ThrusterKind::Azimuth {
                return Err(Error::input(
                    "azimuth_rate",
                    rate,
                    "applies to an azimuth thruster only (a tunnel thruster or main propeller does not turn)",
                ));
            }
        }
        check_positive("time_constant", time_constant, "s", true)?;
        Ok(Thruster {
            kind,
            position,
            max_thrust,
            reverse_thrust,
            thrust_rate,
            azimuth_rate,
            time_constant,
        })
    }

    /// The direction a tunnel thruster (90°) or main propeller (0°) pushes; `None` for an azimuth thruster.
    pub fn fixed_azimuth(&self) -> Option<f64> {
        match self.kind {
            ThrusterKind::Tunnel => Some(FRAC_PI_2),
            ThrusterKind::Main => Some(0.0),
            ThrusterKind::Azimuth => None,
        }
    }

    /// Its state at rest: no thrust, pointing where it pushes (an azimuth thruster ahead).
    pub fn at_rest(&self) -> ThrusterState {
        ThrusterState {
            thrust: 0.0,
            azimuth: self.fixed_azimuth().unwrap_or(0.0),
        }
    }

    /// (X, Y, N) per newton of thrust along azimuth α (eq. 11.53).
    pub fn column(&self, azimuth: f64) -> [f64; 3] {
        let (sin, cos) = azimuth.sin_cos();
        [cos, sin, self.position.x * sin - self.position.y * cos]
    }

    /// The state after a step `dt` (s) from `state` toward `command`: the first-order lag, exact for a command
    /// held over the step, then the rate limits and the thrust's bounds; the azimuth turns the short way.
    pub fn respond(
        &self,
        state: &ThrusterState,
        command: &ThrusterState,
        dt: f64,
    ) -> ThrusterState {
        let weight = if self.time_constant > 0.0 {
            1.0 - (-dt / self.time_constant).exp()
        } else {
            1.0
        };
        let mut change = weight * (command.thrust - state.thrust);
        if let Some(rate) = self.thrust_rate {
            change = change.clamp(-rate * dt, rate * dt);
        }
        let thrust = (state.thrust + change).clamp(-self.reverse_thrust, self.max_thrust);
        let azimuth = match self.fixed_azimuth() {
            Some(fixed) => fixed,
            None => {
                let mut turn = wrap(command.azimuth - state.azimuth);
                if let Some(rate) = self.azimuth_rate {
                    turn = turn.clamp(-rate * dt, rate * dt);
                }
                wrap(state.azimuth + turn)
            }
        };
        ThrusterState { thrust, azimuth }
    }
}

/// An angle in (−π, π].
pub fn wrap(angle: f64) -> f64 {
    let a = angle.rem_euclid(TAU);
    if a > PI {
        a - TAU
    } else {
        a
    }
}

/// The body-frame generalised force [X, Y, 0, 0, 0, N] of thrusters in states `states`.
pub fn generalised_force(thrusters: &[Thruster], states: &[ThrusterState]) -> Vector6<f64> {
    let mut tau = Vector6::zeros();
    for (thruster, state) in thrusters.iter().zip(states) {
        let [x, y, n] = thruster.column(state.azimuth);
        tau[0] += state.thrust * x;
        tau[1] += state.thrust * y;
        tau[5] += state.thrust * n;
    }
    tau
}

/// Checks that every thruster lies within the hull's length `length` (m, CO amidships): |l_x| ≤ L/2.
pub fn check_on_hull(thrusters: &[Thruster], length: f64) -> Result<()> {
    check_positive("length", length, "m", false)?;
    for (k, thruster) in thrusters.iter().enumerate() {
        if thruster.position.x.abs() > 0.5 * length {
            return Err(Error::input(
                format!("thrusters[{k}].position"),
                format!("l_x = {} m", thruster.position.x),
                format!(
                    "must lie on the hull: |l_x| ≤ L/2 = {} m from CO amidships",
                    0.5 * length
                ),
            ));
        }
    }
    Ok(())
}

/// The six thrusters of Fossen's MSS supply vessel (`supply.m`; Fossen 2021, Table 11.2): four tunnel
/// thrusters of 200 kN (bow at l_x = 30 and 22 m, stern at −22 and −30 m) and two main propellers of
/// 798.72 kN at (−38.1, ±8) m, symmetric in thrust (K|n|n), with the propeller speed's time constant of 1 s as
/// the thrust's; the model gives no rate limits.
pub fn mss_supply_vessel() -> Vec<Thruster> {
    let tunnel = |x: f64| Thruster {
        kind: ThrusterKind::Tunnel,
        position: Vector2::new(x, 0.0),
        max_thrust: 200e3,
        reverse_thrust: 200e3,
        thrust_rate: None,
        azimuth_rate: None,
        time_constant: 1.0,
    };
    let main = |y: f64| Thruster {
        kind: ThrusterKind::Main,
        position: Vector2::new(-38.1, y),
        max_thrust: 798.72e3,
        reverse_thrust: 798.72e3,
        thrust_rate: None,
        azimuth_rate: None,
        time_constant: 1.0,
    };
    vec![
        tunnel(30.0),
        tunnel(22.0),
        tunnel(-22.0),
        tunnel(-30.0),
        main(8.0),
        main(-8.0),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mss_thrusters_give_its_configuration_matrix() {
        // T_config of supply.m: tunnel column [0, 1, l_x], main column [1, 0, −l_y].
        let thrusters = mss_supply_vessel();
        let expected = [
            [0.0, 1.0, 30.0],
            [0.0, 1.0, 22.0],
            [0.0, 1.0, -22.0],
            [0.0, 1.0, -30.0],
            [1.0, 0.0, -8.0],
            [1.0, 0.0, 8.0],
        ];
        for (thruster, column) in thrusters.iter().zip(expected) {
            let got = thruster.column(thruster.at_rest().azimuth);
            for (g, e) in got.iter().zip(column) {
                assert!((g - e).abs() < 1e-12, "{got:?} vs {column:?}");
            }
        }
    }

    #[test]
    fn a_thruster_answers_with_its_lag_and_within_its_rates() {
        let thruster = Thruster::new(
            ThrusterKind::Azimuth,
            Vector2::new(-35.0, 0.0),
            250e3,
            None,
            Some(50e3),
            Some(0.2),
            2.0,
        )
        .unwrap();
        let start = ThrusterState {
            thrust: 0.0,
            azimuth: 0.0,
        };
        let command = ThrusterState {
            thrust: 10e3,
            azimuth: 3.0,
        };
        // Small command: the lag alone, 1 − e^{−dt/T} of the way.
        let next = thruster.respond(&start, &command, 0.1);
        assert!((next.thrust - 10e3 * (1.0 - (-0.05f64).exp())).abs() < 1e-9);
        assert!((next.azimuth - 0.02).abs() < 1e-12);
        // Large command: the rate limit.
        let big = ThrusterState {
            thrust: 1e9,
            azimuth: -3.0,
        };
        let next = thruster.respond(&start, &big, 0.1);
        assert!((next.thrust - 5e3).abs() < 1e-9);
        assert!((next.azimuth + 0.02).abs() < 1e-12);
    }

    #[test]
    fn bad_thrusters_are_refused_by_name() {
        let p = Vector2::new(0.0, 0.0);
        let error = Thruster::new(ThrusterKind::Tunnel, p, -1.0, None, None, None, 1.0)
            .unwrap_err()
            .to_string();
        assert!(error.contains("max_thrust"), "{error}");
        let error = Thruster::new(ThrusterKind::Azimuth, p, 1.0, Some(1.0), None, None, 1.0)
            .unwrap_err()
            .to_string();
        assert!(error.contains("reverse_thrust"), "{error}");
        let thrusters = mss_supply_vessel();
        let error = check_on_hull(&thrusters, 60.0).unwrap_err().to_string();
        assert!(error.contains("thrusters[4].position"), "{error}");
        assert!(check_on_hull(&thrusters, 83.0).is_ok());
    }
}
