//! First-order displacement RAOs: the vessel's wave-frequency motion per metre of wave amplitude, per period and
//! relative heading, for the 6 DOF about CO (surge, sway, heave in m/m; roll, pitch, yaw in rad/m; body frame,
//! z down), as amplitude and phase: for the wave elevation a cos(ωt) at CO the motion is |RAO| a cos(ωt + phase).
//!
//! A table is read from CSV text with the columns `period_s, heading_deg` and `<dof>_amp, <dof>_phase` for the
//! six DOF (`#` lines are comments), on a full grid of periods × headings (headings in [0, 360), periodic).
//! The built-in OSV's table (`data/osv_raos.csv`) was computed with Capytaine by `scripts/osv_raos.py`.
//! Values between grid points are interpolated bilinearly on the complex RAO (amplitude e^{i phase}), so that
//! phases wrap correctly.
// Indexing cannot go out of bounds here: grid indices of a table checked to hold at least 2 periods and 1
// heading, clamped or wrapped into it; `values` filled for every grid point.
#![allow(clippy::indexing_slicing)]
use crate::error::{Error, Result};
use nalgebra::Complex;

/// The six DOF's column names.
pub const DOFS: [&str; 6] = ["surge", "sway", "heave", "roll", "pitch", "yaw"];

/// A table of complex RAOs on a grid of periods (s, increasing) and headings (deg, increasing in [0, 360)).
#[derive(Debug, Clone, PartialEq)]
pub struct Raos {
    pub periods: Vec<f64>,
    pub headings: Vec<f64>,
    /// RAO of each DOF at (period, heading), period-major: `values[(p * headings + h) * 6 + dof]`.
    pub values: Vec<Complex<f64>>,
}

/// The OSV's table, shipped with the engine.
const OSV: &str = include_str!("../../data/osv_raos.csv");

impl Raos {
    /// The built-in OSV's RAOs (Capytaine; see `scripts/osv_raos.py`).
    pub fn osv() -> Result<Self> {
        Self::from_csv(OSV, "osv_raos.csv")
    }

    /// A table from CSV text; `source` names it in errors.
    pub fn from_csv(text: &str, source: &str) -> Result<Self> {
        let columns: Vec<String> = DOFS
            .iter()
            .flat_map(|d| [format!("{d}_amp"), format!("{d}_phase")])
            .collect();
        Self::grid_from_csv(text, source, "raos", &columns, |numbers| {
            let mut values = [Complex::new(0.0, 0.0); 6];
            for (dof, value) in values.iter_mut().enumerate() {
                *value = Complex::from_polar(numbers[2 * dof], numbers[2 * dof + 1]);
            }
            values
        })
    }

    /// A table of the same grid from a CSV text whose columns are `period_s`, `heading_deg` and `columns`;
    /// `values` turns a row's numbers (in the order of `columns`) into the 6 values. Errors name `argument`
    /// and `source`.
    pub fn grid_from_csv(
        text: &str,
        source: &str,
        argument: &str,
        columns: &[String],
        values: impl Fn(&[f64]) -> [Complex<f64>; 6],
    ) -> Result<Self> {
        let bad = |what: String| Error::input(argument, source, what);
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim_start().starts_with('#') && !l.trim().is_empty());
        let (_, header) = lines
            .next()
            .ok_or_else(|| bad("must have a header line".into()))?;
        let names: Vec<&str> = header.split(',').map(str::trim).collect();
        let column = |name: &str| {
            names
                .iter()
                .position(|n| *n == name)
                .ok_or_else(|| bad(format!("must have a column {name:?}")))
        };
        let period_column = column("period_s")?;
        let heading_column = column("heading_deg")?;
        let value_columns = columns
            .iter()
            .map(|c| column(c))
            .collect::<Result<Vec<_>>>()?;
        let mut rows: Vec<(f64, f64, [Complex<f64>; 6])> = Vec::new();
        let mut numbers = vec![0.0; value_columns.len()];
        for (index, line) in lines {
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            let number = |c: usize| -> Result<f64> {
                let text = fields.get(c).copied().unwrap_or("");
                match text.parse::<f64>() {
                    Ok(v) if v.is_finite() => Ok(v),
                    _ => Err(bad(format!(
                        "line {}, column {:?}: {text:?} must be a finite number",
                        index + 1,
                        names.get(c).copied().unwrap_or("?")
                    ))),
                }
            };
            for (value, &c) in numbers.iter_mut().zip(&value_columns) {
                *value = number(c)?;
            }
            rows.push((
                number(period_column)?,
                number(heading_column)?,
                values(&numbers),
            ));
        }
        let mut periods: Vec<f64> = rows.iter().map(|r| r.0).collect();
        let mut headings: Vec<f64> = rows.iter().map(|r| r.1).collect();
        for list in [&mut periods, &mut headings] {
            list.sort_by(f64::total_cmp);
            list.dedup();
        }
        if periods.len() < 2 || headings.is_empty() {
            return Err(bad("must hold at least 2 periods and 1 heading".into()));
        }
        if periods[0] <= 0.0 || headings.iter().any(|h| !(0.0..360.0).contains(h)) {
            return Err(bad(
                "periods must be > 0 s and headings in [0, 360) deg".into()
            ));
        }
        let (np, nh) = (periods.len(), headings.len());
        let mut values = vec![None; np * nh * 6];
        for (period, heading, row) in &rows {
            let p = periods.partition_point(|x| x < period);
            let h = headings.partition_point(|x| x < heading);
            for (dof, value) in row.iter().enumerate() {
                values[(p * nh + h) * 6 + dof] = Some(*value);
            }
        }
        let values = values
            .into_iter()
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| {
                bad(format!(
                    "must fill the grid of {np} periods × {nh} headings"
                ))
            })?;
        Ok(Raos {
            periods,
            headings,
            values,
        })
    }

    /// The complex RAOs of the 6 DOF at `period` (s) and relative `heading` (deg, any value: taken modulo
    /// 360), interpolated bilinearly; a period outside the table is an error.
    pub fn at(&self, period: f64, heading: f64) -> Result<[Complex<f64>; 6]> {
        let (first, last) = (self.periods[0], self.periods[self.periods.len() - 1]);
        if !(period.is_finite() && period >= first && period <= last) {
            return Err(Error::input(
                "period",
                format!("{period} s"),
                format!("must lie in the RAO table's periods [{first}, {last}] s"),
            ));
        }
        if !heading.is_finite() {
            return Err(Error::input("heading", heading, "must be finite (deg)"));
        }
        let p = self
            .periods
            .partition_point(|x| *x <= period)
            .clamp(1, self.periods.len() - 1);
        let tp = (period - self.periods[p - 1]) / (self.periods[p] - self.periods[p - 1]);
        let nh = self.headings.len();
        // Headings are periodic: the cell from the last heading wraps to the first + 360.
        let (h0, h1, th) = crate::table::periodic_cell(&self.headings, heading, 360.0);
        let value = |p: usize, h: usize, dof: usize| self.values[(p * nh + h) * 6 + dof];
        let mut out = [Complex::new(0.0, 0.0); 6];
        for (dof, o) in out.iter_mut().enumerate() {
            let low = value(p - 1, h0, dof) * (1.0 - th) + value(p - 1, h1, dof) * th;
            let high = value(p, h0, dof) * (1.0 - th) + value(p, h1, dof) * th;
            *o = low * (1.0 - tp) + high * tp;
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The OSV's table: heave → 1 and pitch → k at long periods in head seas (the vessel follows the wave),
    /// and the beam-sea heave RAO peaks near the heave natural period 2π√((M33 + A33)/G33) ≈ 6.6 s.
    #[test]
    fn osv_table_has_the_long_wave_limits() {
        let raos = Raos::osv().unwrap();
        assert_eq!((raos.periods.len(), raos.headings.len()), (43, 24));
        let long = raos.at(30.0, 180.0).unwrap();
        assert!((long[2].norm() - 1.0).abs() < 0.01, "{}", long[2].norm());
        let k = (std::f64::consts::TAU / 30.0).powi(2) / 9.81;
        assert!((long[4].norm() / k - 1.0).abs() < 0.01);
        let peak = (0..=60)
            .map(|i| 4.0 + 0.1 * i as f64)
            .max_by(|a, b| {
                let heave = |t: f64| raos.at(t, 90.0).unwrap()[2].norm();
                heave(*a).total_cmp(&heave(*b))
            })
            .unwrap();
        assert!((6.0..=7.5).contains(&peak), "{peak}");
        // Headings wrap: 375° is 15°, and between grid points the interpolation is continuous.
        assert_eq!(raos.at(12.0, 375.0).unwrap(), raos.at(12.0, 15.0).unwrap());
        let (a, b) = (raos.at(12.0, 352.5).unwrap(), raos.at(12.0, -7.5).unwrap());
        assert!((a[1] - b[1]).norm() < 1e-12);
    }

    #[test]
    fn bad_tables_and_periods_are_input_errors() {
        let header = "period_s,heading_deg,surge_amp,surge_phase,sway_amp,sway_phase,heave_amp,heave_phase,roll_amp,roll_phase,pitch_amp,pitch_phase,yaw_amp,yaw_phase";
        let row = |t: &str, h: &str, heave: &str| format!("{t},{h},0,0,0,0,{heave},0,0,0,0,0,0,0");
        let good = format!(
            "{header}\n{}\n{}\n",
            row("5", "0", "0.5"),
            row("10", "0", "0.9")
        );
        assert!(Raos::from_csv(&good, "t.csv").is_ok());
        let nan = format!(
            "{header}\n{}\n{}\n",
            row("5", "0", "nan"),
            row("10", "0", "0.9")
        );
        let message = Raos::from_csv(&nan, "t.csv").unwrap_err().to_string();
        assert!(
            message.contains("heave_amp") && message.contains("finite"),
            "{message}"
        );
        let missing = format!(
            "{header}\n{}\n{}\n",
            row("5", "0", "1"),
            row("10", "90", "1")
        );
        assert!(Raos::from_csv(&missing, "t.csv")
            .unwrap_err()
            .to_string()
            .contains("fill the grid"));
        assert!(Raos::from_csv("period_s,heading_deg\n", "t.csv").is_err());
        let raos = Raos::osv().unwrap();
        let message = raos.at(40.0, 0.0).unwrap_err().to_string();
        assert!(
            message.starts_with("period: must lie in the RAO table's periods [3, 30] s"),
            "{message}"
        );
        assert!(raos.at(2.0, 0.0).is_err() && raos.at(f64::NAN, 0.0).is_err());
    }
}
