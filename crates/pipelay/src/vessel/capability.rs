//! DP capability (a static balance, as DNV-ST-0111 level 1 does it): for an environment coming from a
//! heading relative to the bow, the largest wind speed at which the thrusters, allocated without rate limits,
//! balance the mean wind, a co-linear current and the mean wave drift of a co-linear sea, plus the pipe's load.
//!
//! The sea follows the wind as on the Beaufort scale, on which DNV-ST-0111 level 1 builds its environments:
//! H_s is the WMO scale's probable wave height at the upper wind speed of each Beaufort number (linear
//! between them, 14 m beyond force 12), T_p = 4.2 √H_s (within DNV-RP-C205's range for JONSWAP seas,
//! 3.6 √H_s ≤ T_p ≤ 5 √H_s), a JONSWAP spectrum of γ = 3.3; its mean drift is Σ_i a_i² D(T_i, γ_rel). The
//! current is a fixed speed, co-linear.
// Indexing cannot go out of bounds here: 6-vectors of the vessel's DOFs.
#![allow(clippy::indexing_slicing)]
use super::allocation::allocate;
use super::rigid_body::Vessel;
use crate::environment::waves::{WaveField, Waves};
use crate::environment::wind::AIR_DENSITY;
use crate::error::{Error, Result};
use nalgebra::{Vector2, Vector6};
use std::f64::consts::PI;

/// Sea water density for the current (kg/m³).
const WATER_DENSITY: f64 = 1025.0;
/// Wave components of the sea whose mean drift is summed.
const SEA_COMPONENTS: usize = 200;
/// The bisection's tolerance on the wind speed (m/s).
const SPEED_TOLERANCE: f64 = 1e-3;

/// Upper wind speeds of Beaufort numbers 0–11 (m/s, 10 m above the sea) and the WMO scale's probable wave
/// heights at them (m); force 12 (over 32.6 m/s) has 14 m, reached here linearly at 36.7 m/s and held.
const BEAUFORT_SPEEDS: [f64; 13] = [
    0.2, 1.5, 3.3, 5.4, 7.9, 10.7, 13.8, 17.1, 20.7, 24.4, 28.4, 32.6, 36.7,
];
const BEAUFORT_HEIGHTS: [f64; 13] = [
    0.0, 0.1, 0.2, 0.6, 1.0, 2.0, 3.0, 4.0, 5.5, 7.0, 9.0, 11.5, 14.0,
];

/// H_s (m) and T_p (s) of the sea that goes with a wind speed V (m/s).
pub fn sea_of_wind(speed: f64) -> (f64, f64) {
    let k = BEAUFORT_SPEEDS.partition_point(|v| *v <= speed);
    let hs = match k {
        0 => 0.0,
        k if k == BEAUFORT_SPEEDS.len() => BEAUFORT_HEIGHTS[k - 1],
        k => {
            let t =
                (speed - BEAUFORT_SPEEDS[k - 1]) / (BEAUFORT_SPEEDS[k] - BEAUFORT_SPEEDS[k - 1]);
            BEAUFORT_HEIGHTS[k - 1] + t * (BEAUFORT_HEIGHTS[k] - BEAUFORT_HEIGHTS[k - 1])
        }
    };
    (hs, 4.2 * hs.sqrt())
}

/// The mean environmental load (body frame) of a wind of speed `speed` (m/s) and the current `current` (m/s)
/// and sea that go with it, all coming from `heading` (rad, relative to the bow, 0 head-on, π/2 from
/// starboard), on a vessel at rest. A load the vessel has no table for is left out.
pub fn environment_load(
    vessel: &Vessel,
    speed: f64,
    heading: f64,
    current: f64,
) -> Result<Vector6<f64>> {
    if !(speed.is_finite() && speed >= 0.0) {
        return Err(Error::input(
            "wind_speed",
            speed,
            "must be a finite speed ≥ 0 (m/s)",
        ));
    }
    crate::error::finite("heading", &[heading])?;
    if !(current.is_finite() && current >= 0.0) {
        return Err(Error::input(
            "current",
            current,
            "must be a finite speed ≥ 0 (m/s)",
        ));
    }
    // The direction the environment travels, relative to the bow.
    let travel = heading + PI;
    let direction = Vector2::new(travel.cos(), travel.sin());
    let mut load = Vector6::zeros();
    if let Some(wind) = &vessel.wind_coefficients {
        load += wind.load(AIR_DENSITY, &(speed * direction));
    }
    if let Some(coefficients) = &vessel.current_coefficients {
        load += coefficients.load(WATER_DENSITY, &(current * direction));
    }
    let (hs, tp) = sea_of_wind(speed);
    // Components outside the drift table's periods drift the vessel little (short) or move it whole (long).
    if let (Some(drift), true) = (&vessel.drift_coefficients, hs > 0.0) {
        let periods = &drift.table.periods;
        let (first, last) = (periods[0], periods[periods.len() - 1]);
        let waves = Waves::jonswap(
            hs,
            tp.clamp(first, last),
            3.3,
            travel,
            None,
            1,
            SEA_COMPONENTS,
        )?;
        let field = WaveField::new(&waves, 1000.0, 9.81)?;
        for c in field.components() {
            let period = std::f64::consts::TAU / c.frequency;
            if (first..=last).contains(&period) {
                load += c.amplitude * c.amplitude * drift.at(period, travel.to_degrees())?;
            }
        }
    }
    Ok(load)
}

/// Whether the vessel's thrusters hold the load `load` (body frame): the allocation of −load is delivered.
pub fn holds(vessel: &Vessel, load: &Vector6<f64>) -> Result<bool> {
    Ok(!allocate(&vessel.thrusters, &(-load), None)?.saturated)
}

/// The largest wind speed (m/s, up to `max_wind`) held at each heading (rad, environment from, relative to
/// the bow) with the pipe's load `pipe_load` (body frame) and the current `current` (m/s); 0 where even
/// calm cannot be held.
pub fn capability(
    vessel: &Vessel,
    headings: &[f64],
    pipe_load: &Vector6<f64>,
    current: f64,
    max_wind: f64,
) -> Result<Vec<f64>> {
    if vessel.thrusters.is_empty() {
        return Err(Error::input(
            "vessel",
            "a vessel without thrusters",
            "needs thrusters for a capability analysis",
        ));
    }
    crate::error::finite("pipe_load", pipe_load.as_slice())?;
    crate::error::finite("headings", headings)?;
    crate::error::positive("max_wind", max_wind, "m/s")?;
    let mut speeds = Vec::with_capacity(headings.len());
    for &heading in headings {
        let held = |speed: f64| -> Result<bool> {
            holds(
                vessel,
                &(environment_load(vessel, speed, heading, current)? + pipe_load),
            )
        };
        let speed = if !held(0.0)? {
            0.0
        } else if held(max_wind)? {
            max_wind
        } else {
            let (mut low, mut high) = (0.0, max_wind);
            while high - low > SPEED_TOLERANCE {
                let middle = 0.5 * (low + high);
                if held(middle)? {
                    low = middle;
                } else {
                    high = middle;
                }
            }
            low
        };
        speeds.push(speed);
    }
    Ok(speeds)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Beam wind on the OSV: at the envelope's speed the thrusters are at their limit in sway or yaw; a
    /// pipe pulling aft shrinks the envelope.
    #[test]
    fn the_envelope_is_where_the_thrust_runs_out() {
        let vessel = Vessel::osv();
        let heading = 0.5 * PI;
        let speeds = capability(&vessel, &[heading], &Vector6::zeros(), 0.75, 60.0).unwrap();
        let speed = speeds[0];
        assert!(speed > 5.0 && speed < 60.0, "{speed}");
        let load = |v: f64| environment_load(&vessel, v, heading, 0.75).unwrap();
        assert!(holds(&vessel, &load(0.99 * speed)).unwrap());
        assert!(!holds(&vessel, &load(1.01 * speed)).unwrap());
        let pipe = Vector6::new(-300e3, 0.0, 0.0, 0.0, 0.0, 0.0);
        let loaded = capability(&vessel, &[heading], &pipe, 0.75, 60.0).unwrap();
        assert!(
            loaded[0] <= speed + SPEED_TOLERANCE,
            "{loaded:?} vs {speed}"
        );
    }
}
