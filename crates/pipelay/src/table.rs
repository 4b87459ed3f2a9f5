//! Functions of time: user functions ([`TimeFunction`]) and tables of samples (t_k, y_k), interpolated
//! linearly: drives and pay-out speeds that a run evaluates in Rust, without calling Python at every step.
// Indexing cannot go out of bounds here: a table has at least two rows (checked at construction), segment
// indices stay below the last row, and columns below the width.
#![allow(clippy::indexing_slicing)]
use crate::error::{Error, Result};
use nalgebra::Vector3;
use std::sync::Arc;

/// A user function of time t (s), e.g. a Python callable; its error is a message.
pub type TimeFunction<T> = Arc<dyn Fn(f64) -> std::result::Result<T, String> + Send + Sync>;

/// Samples y_k ∈ ℝ^width at strictly increasing times t_k.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    times: Vec<f64>,
    /// Row k's values at `values[width·k .. width·(k + 1)]`.
    values: Vec<f64>,
    width: usize,
}

impl Table {
    /// A table from rows [t_k, y_k,1 … y_k,width] (flat, row after row). Named `argument` in errors: at least
    /// two rows, finite entries and strictly increasing times.
    pub fn new(argument: &str, rows: &[f64], width: usize) -> Result<Self> {
        let columns = width + 1;
        let count = rows.len() / columns;
        if width == 0 || rows.len() % columns != 0 || count < 2 {
            return Err(Error::input(
                argument,
                format!("{} values", rows.len()),
                format!("must be a table of at least two rows [t, {width} values] (s, …)"),
            ));
        }
        if let Some(bad) = rows.iter().find(|v| !v.is_finite()) {
            return Err(Error::input(argument, bad, "must hold finite numbers"));
        }
        let times: Vec<f64> = rows.iter().step_by(columns).copied().collect();
        if let Some(pair) = times.windows(2).find(|pair| pair[1] <= pair[0]) {
            return Err(Error::input(
                argument,
                format!("times {} then {} s", pair[0], pair[1]),
                "must increase strictly from row to row",
            ));
        }
        let values = rows
            .chunks_exact(columns)
            .flat_map(|row| row.iter().skip(1).copied())
            .collect();
        Ok(Table {
            times,
            values,
            width,
        })
    }

    /// The segment [t_k, t_k+1] holding `time` and the fraction of it at `time`; outside the table, the message
    /// of the error (its caller names the argument and the time).
    fn segment(&self, time: f64) -> std::result::Result<(usize, f64), String> {
        let (first, last) = (self.times[0], self.times[self.times.len() - 1]);
        // A run's time is a sum of steps: it may pass the last sample by round-off.
        let slack = 1e-9 * (last - first);
        if !(first - slack..=last + slack).contains(&time) {
            return Err(format!(
                "must lie within the table's times [{first}, {last}] s"
            ));
        }
        let time = time.clamp(first, last);
        // The last k with t_k ≤ time, kept below the last row so that the segment exists.
        let k = self
            .times
            .partition_point(|&t| t <= time)
            .saturating_sub(1)
            .min(self.times.len() - 2);
        let fraction = (time - self.times[k]) / (self.times[k + 1] - self.times[k]);
        Ok((k, fraction))
    }

    /// Column `column`'s value at `time` and its slope there (that of the segment after a sample).
    pub fn at(&self, column: usize, time: f64) -> std::result::Result<(f64, f64), String> {
        let (k, fraction) = self.segment(time)?;
        let (y0, y1) = (
            self.values[self.width * k + column],
            self.values[self.width * (k + 1) + column],
        );
        // At a sample the sample itself, not a rounded interpolation of it.
        let value = if fraction == 0.0 {
            y0
        } else if fraction == 1.0 {
            y1
        } else {
            y0 + fraction * (y1 - y0)
        };
        Ok((value, (y1 - y0) / (self.times[k + 1] - self.times[k])))
    }

    /// The interpolated scalar (a one-column table) as a function of time.
    pub fn scalar(self) -> TimeFunction<f64> {
        Arc::new(move |time| self.at(0, time).map(|(value, _)| value))
    }

    /// The interpolated vector (a three-column table) and its slope, as functions of time.
    pub fn vector(self) -> (TimeFunction<Vector3<f64>>, TimeFunction<Vector3<f64>>) {
        let table = Arc::new(self);
        let column = |table: Arc<Table>, slope: bool| -> TimeFunction<Vector3<f64>> {
            Arc::new(move |time| {
                let mut out = Vector3::zeros();
                for (i, entry) in out.iter_mut().enumerate() {
                    let (value, rate) = table.at(i, time)?;
                    *entry = if slope { rate } else { value };
                }
                Ok(out)
            })
        };
        (column(table.clone(), false), column(table, true))
    }
}

/// The cell of a periodic grid holding `value`: indices (i₀, i₁) of its ends and the fraction t ∈ [0, 1)
/// of the way from i₀ to i₁. `grid` increases within [0, `period`) and holds at least one point; `value` is
/// taken modulo `period`, and the cell from the last point wraps to the first + period.
pub fn periodic_cell(grid: &[f64], value: f64, period: f64) -> (usize, usize, f64) {
    let n = grid.len();
    let (Some(&first), Some(&last)) = (grid.first(), grid.last()) else {
        return (0, 0, 0.0);
    };
    let value = value.rem_euclid(period);
    let k = grid.partition_point(|x| *x <= value);
    let (i0, i1, lower, upper) = match k {
        0 => (n - 1, 0, last - period, first),
        k if k == n => (n - 1, 0, last, first + period),
        k => (k - 1, k, grid[k - 1], grid[k]),
    };
    let t = if upper > lower {
        (value - lower) / (upper - lower)
    } else {
        0.0
    };
    (i0, i1, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_linearly_and_keeps_the_samples() {
        #[rustfmt::skip]
        let rows = [
            0.0, 1.0, 0.0, 5.0,
            0.5, 3.0, 0.5, 9.0,
            2.5, 2.0, 1.5, 7.0,
        ];
        let table = Table::new("position", &rows, 3).expect("table");
        assert_eq!(table.at(0, 0.25).expect("inside"), (2.0, 4.0));
        assert_eq!(table.at(2, 2.5).expect("sample"), (7.0, -1.0));
        let (position, velocity) = table.vector();
        let p = position(0.1 + 0.2).expect("inside");
        assert!((p - Vector3::new(2.2, 0.3, 7.4)).norm() < 1e-14, "{p}");
        assert_eq!(velocity(0.3).expect("inside"), Vector3::new(4.0, 1.0, 8.0));
    }

    #[test]
    fn bad_tables_and_times_outside_are_refused() {
        let message = |rows: &[f64]| match Table::new("speed", rows, 1) {
            Err(e) => e.to_string(),
            Ok(_) => String::new(),
        };
        assert!(message(&[0.0, 1.0]).contains("at least two rows"));
        assert!(message(&[0.0, 1.0, 0.0, 2.0]).contains("increase strictly"));
        assert!(message(&[0.0, 1.0, 1.0, f64::NAN]).contains("finite"));
        let speed = Table::new("speed", &[0.0, 1.0, 10.0, 2.0], 1)
            .expect("table")
            .scalar();
        assert_eq!(speed(5.0), Ok(1.5));
        // Round-off of a summed time past the end is the end.
        assert_eq!(speed(10.0 + 1e-12), Ok(2.0));
        let outside = speed(10.5).expect_err("outside");
        assert_eq!(outside, "must lie within the table's times [0, 10] s");
    }
}

/// A speed in legs, each ramping linearly from the speed before it to its own over its ramp time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Leg {
    /// When the leg starts (s).
    pub start: f64,
    /// Its speed once ramped (m/s).
    pub speed: f64,
    /// The time the change from the speed before takes (s; 0: a step).
    pub ramp: f64,
}

/// The distance travelled by `time` (s) since the first leg's start, and the speed then, of legs in time
/// order (each lasting until the next starts); before the first, nothing and zero.
pub fn travel(legs: &[Leg], time: f64) -> (f64, f64) {
    let (mut distance, mut speed, mut before) = (0.0, 0.0, 0.0);
    for (k, leg) in legs.iter().enumerate() {
        if time <= leg.start {
            break;
        }
        let end = legs.get(k + 1).map_or(f64::INFINITY, |next| next.start);
        let span = time.min(end) - leg.start;
        let ramp = leg.ramp.min(span);
        // The speed rises linearly from `before` to `leg.speed` over `leg.ramp`, then holds.
        let reached = if leg.ramp > 0.0 {
            before + (leg.speed - before) * (ramp / leg.ramp)
        } else {
            leg.speed
        };
        distance += 0.5 * (before + reached) * ramp + leg.speed * (span - ramp).max(0.0);
        speed = if span > leg.ramp { leg.speed } else { reached };
        before = speed;
    }
    (distance, speed)
}

#[cfg(test)]
mod leg_tests {
    use super::*;

    #[test]
    fn ramped_legs_integrate_their_speed() {
        let legs = [
            Leg {
                start: 0.0,
                speed: 1.0,
                ramp: 10.0,
            },
            Leg {
                start: 20.0,
                speed: 0.0,
                ramp: 0.0,
            },
        ];
        assert_eq!(travel(&legs, -1.0), (0.0, 0.0));
        let (d, v) = travel(&legs, 5.0);
        assert!((d - 1.25).abs() < 1e-12 && (v - 0.5).abs() < 1e-12);
        let (d, v) = travel(&legs, 15.0);
        assert!((d - 10.0).abs() < 1e-12 && v == 1.0);
        let (d, v) = travel(&legs, 30.0);
        assert!((d - 15.0).abs() < 1e-12 && v == 0.0);
        // The speed is the distance's derivative, by central differences.
        for t in [3.0, 12.0, 19.0] {
            let h = 1e-6;
            let rate = (travel(&legs, t + h).0 - travel(&legs, t - h).0) / (2.0 * h);
            assert!((rate - travel(&legs, t).1).abs() < 1e-6);
        }
    }
}
