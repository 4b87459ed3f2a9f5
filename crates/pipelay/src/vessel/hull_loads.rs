//! Wind, current and wave drift on the hull, from coefficient tables.
//!
//! Wind and current (OCIMF-style): for the flow's velocity relative to the vessel, body frame (u_r, v_r),
//! speed V_r and relative angle γ = atan2(v_r, u_r) (the direction the flow travels, from the bow toward
//! starboard: 0 from astern, 90° to starboard, 180° head-on), the load on DOF j is
//!   F_j = ½ ρ V_r² C_j(γ),
//! C_j the table's dimensional coefficient (the non-dimensional coefficient times its reference area, m² for
//! a force, m³ for a moment), interpolated linearly and periodically in γ.
//!
//! Wave drift (Newman's approximation): for wave components (a_i, ω_i, β_i, θ_i(t)) and the mean drift
//! coefficients D_j(T, β − ψ) (force per amplitude², a period × heading table), the slowly varying force is
//!   F_j(t) = r(t)² Re[ z_j(t) w̄_j(t) ],  z_j = Σ_i a_i √|D_ij| e^{iθ_i},  w_j = Σ_i a_i sgn(D_ij) √|D_ij| e^{iθ_i},
//! the difference-frequency part of the quadratic transfer function taken as T_ik ≈ √(D_i D_k): its mean is
//! Σ_i a_i² D_ij, and a regular wave gives exactly a² D_j. θ_i is the component's phase at the station, as in
//! [`crate::vessel::wave_motion`], and r(t) the sea's build-up.
// Indexing cannot go out of bounds here: tables hold one row per angle, checked when built.
#![allow(clippy::indexing_slicing)]
use super::raos::{Raos, DOFS};
use super::wave_motion::station;
use super::VesselAttachment;
use crate::environment::sea::Sea;
use crate::environment::waves::{ramp_factor, Resolved, WaveField};
use crate::environment::wind::{Wind, AIR_DENSITY};
use crate::error::{Error, Result};
use nalgebra::{Complex, Matrix3, Vector2, Vector3, Vector6};

/// Coefficients C_j(γ) (m², m³) of a flow's load on the hull, by relative angle.
#[derive(Debug, Clone, PartialEq)]
pub struct HullCoefficients {
    /// Relative angles γ (deg, increasing in [0, 360)).
    pub angles: Vec<f64>,
    /// C_j(γ) per angle (surge, sway, heave, roll, pitch, yaw).
    pub values: Vec<Vector6<f64>>,
}

impl HullCoefficients {
    /// A checked table: angles strictly increasing in [0, 360) deg, finite values, one row per angle;
    /// errors name `argument`.
    pub fn new(argument: &str, angles: Vec<f64>, values: Vec<Vector6<f64>>) -> Result<Self> {
        if angles.is_empty() || angles.len() != values.len() {
            return Err(Error::input(
                argument,
                format!("{} angles and {} rows", angles.len(), values.len()),
                "must hold one row of 6 coefficients per angle, at least one",
            ));
        }
        let increasing = angles.windows(2).all(|w| w[0] < w[1]);
        if !increasing || angles.iter().any(|a| !(0.0..360.0).contains(a)) {
            return Err(Error::input(
                argument,
                format!("angles {angles:?}"),
                "must be strictly increasing in [0, 360) deg",
            ));
        }
        for (row, value) in values.iter().enumerate() {
            if value.iter().any(|v| !v.is_finite()) {
                return Err(Error::input(
                    format!("{argument}[{row}]"),
                    format!("{:?}", value.as_slice()),
                    "must hold finite coefficients (m², m³)",
                ));
            }
        }
        Ok(HullCoefficients { angles, values })
    }

    /// A table from CSV text with columns `angle_deg` and surge … yaw (`#` lines are comments).
    pub fn from_csv(argument: &str, text: &str, source: &str) -> Result<Self> {
        let bad = |what: String| Error::input(argument, source, what);
        let mut lines = text
            .lines()
            .filter(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty());
        let header: Vec<&str> = lines
            .next()
            .ok_or_else(|| bad("must have a header line".into()))?
            .split(',')
            .map(str::trim)
            .collect();
        let column = |name: &str| {
            header
                .iter()
                .position(|n| *n == name)
                .ok_or_else(|| bad(format!("must have a column {name:?}")))
        };
        let angle = column("angle_deg")?;
        let dofs = DOFS.iter().map(|d| column(d)).collect::<Result<Vec<_>>>()?;
        let mut angles = Vec::new();
        let mut values = Vec::new();
        for line in lines {
            let fields: Vec<f64> = line
                .split(',')
                .map(|f| f.trim().parse::<f64>().unwrap_or(f64::NAN))
                .collect();
            let field = |c: usize| fields.get(c).copied().unwrap_or(f64::NAN);
            angles.push(field(angle));
            values.push(Vector6::from_fn(|j, _| field(dofs[j])));
        }
        Self::new(argument, angles, values)
    }

    /// C(γ) at relative angle γ (deg, any value: modulo 360), linear between angles, periodic.
    pub fn at(&self, angle: f64) -> Vector6<f64> {
        let (i0, i1, t) = crate::table::periodic_cell(&self.angles, angle, 360.0);
        self.values[i0] * (1.0 - t) + self.values[i1] * t
    }

    /// F = ½ ρ V_r² C(γ) for a flow of velocity `relative` (body frame, relative to the vessel, m/s) and
    /// density ρ (kg/m³).
    pub fn load(&self, density: f64, relative: &Vector2<f64>) -> Vector6<f64> {
        let speed_squared = relative.norm_squared();
        if speed_squared == 0.0 {
            return Vector6::zeros();
        }
        let angle = relative.y.atan2(relative.x).to_degrees();
        0.5 * density * speed_squared * self.at(angle)
    }

    /// The built-in OSV's wind coefficients (`data/osv_wind.csv`, `scripts/osv_hull_coefficients.py`).
    pub fn osv_wind() -> Result<Self> {
        Self::from_csv(
            "wind_coefficients",
            include_str!("../../data/osv_wind.csv"),
            "osv_wind.csv",
        )
    }

    /// The built-in OSV's current coefficients (`data/osv_current.csv`).
    pub fn osv_current() -> Result<Self> {
        Self::from_csv(
            "current_coefficients",
            include_str!("../../data/osv_current.csv"),
            "osv_current.csv",
        )
    }
}

/// Mean wave-drift coefficients D_j(T, β − ψ) (N/m², N·m/m²): a period × heading table of the RAOs' layout
/// (real values), interpolated bilinearly, periodic in heading.
#[derive(Debug, Clone, PartialEq)]
pub struct DriftCoefficients {
    pub table: Raos,
}

impl DriftCoefficients {
    /// A table from CSV text with columns `period_s`, `heading_deg` and surge … yaw.
    pub fn from_csv(text: &str, source: &str) -> Result<Self> {
        let columns: Vec<String> = DOFS.iter().map(|d| d.to_string()).collect();
        let table = Raos::grid_from_csv(text, source, "drift_coefficients", &columns, |n| {
            std::array::from_fn(|j| Complex::new(n[j], 0.0))
        })?;
        Ok(DriftCoefficients { table })
    }

    /// The built-in OSV's drift coefficients (`data/osv_drift.csv`, `scripts/osv_drift.py`, Capytaine).
    pub fn osv() -> Result<Self> {
        Self::from_csv(include_str!("../../data/osv_drift.csv"), "osv_drift.csv")
    }

    /// D_j at a period (s) and relative heading (deg).
    pub fn at(&self, period: f64, heading: f64) -> Result<Vector6<f64>> {
        let values = self.table.at(period, heading)?;
        Ok(Vector6::from_fn(|j, _| values[j].re))
    }
}

/// The slowly varying wave-drift force of a sea on a vessel with drift coefficients.
#[derive(Debug, Clone, PartialEq)]
pub struct DriftForce {
    components: Vec<Resolved>,
    coefficients: DriftCoefficients,
    ramp: f64,
}

impl DriftForce {
    /// The drift force of the sea `field`; its components outside the table's periods carry no drift (a wave
    /// shorter than the table's shortest period drifts the vessel little; longer than its longest, the
    /// vessel follows it). A sea whose peak lies outside the table is an error, as for the RAOs.
    pub fn new(field: &WaveField, coefficients: &DriftCoefficients) -> Result<Self> {
        let periods = &coefficients.table.periods;
        let (first, last) = match (periods.first(), periods.last()) {
            (Some(first), Some(last)) => (*first, *last),
            _ => {
                return Err(Error::input(
                    "drift_coefficients",
                    "an empty table",
                    "must hold periods",
                ))
            }
        };
        let period = |c: &Resolved| std::f64::consts::TAU / c.frequency;
        if let Some(peak) = field
            .components()
            .iter()
            .max_by(|a, b| a.amplitude.total_cmp(&b.amplitude))
        {
            if !(first..=last).contains(&period(peak)) {
                return Err(Error::input(
                    "waves",
                    format!("a peak period of {:.3} s", period(peak)),
                    format!("must lie within the vessel's drift table, [{first}, {last}] s"),
                ));
            }
        }
        Ok(DriftForce {
            components: field
                .components()
                .iter()
                .filter(|c| (first..=last).contains(&period(c)))
                .copied()
                .collect(),
            coefficients: coefficients.clone(),
            ramp: field.ramp(),
        })
    }

    /// F(t) (body frame) of a vessel on station (x_s, y_s, ψ_s) (m, m, rad).
    pub fn force(&self, time: f64, station: &Vector3<f64>) -> Result<Vector6<f64>> {
        let (ramp, _) = ramp_factor(time, self.ramp);
        let mut force = Vector6::zeros();
        if ramp == 0.0 {
            return Ok(force);
        }
        let mut magnitude = [Complex::new(0.0, 0.0); 6];
        let mut signed = [Complex::new(0.0, 0.0); 6];
        for c in &self.components {
            let heading = (c.direction - station.z).to_degrees();
            let d = self
                .coefficients
                .at(std::f64::consts::TAU / c.frequency, heading)?;
            let phase = Complex::from_polar(c.amplitude, -c.angle(station.x, station.y, time));
            for j in 0..6 {
                let root = d[j].abs().sqrt();
                magnitude[j] += phase * root;
                signed[j] += phase * (root * d[j].signum());
            }
        }
        for j in 0..6 {
            force[j] = ramp * ramp * (magnitude[j] * signed[j].conj()).re;
        }
        Ok(force)
    }
}

/// Wind, current and wave drift on the hull, for a vessel attached with `hull_loads`.
#[derive(Debug, Clone)]
pub struct HullEnvironment {
    wind: Option<(Wind, HullCoefficients)>,
    /// The current at the surface: its (e1, e2) velocity (m/s) from its start (s), the coefficients and the
    /// water's density.
    current: Option<(Vector2<f64>, f64, HullCoefficients, f64)>,
    drift: Option<DriftForce>,
}

/// The hull's environment over one step: the flows' velocities (e) and the drift force (body frame) at the
/// step's midpoint.
#[derive(Debug, Clone, Copy, Default)]
pub struct HullValues {
    wind: Vector2<f64>,
    current: Vector2<f64>,
    drift: Vector6<f64>,
}

/// The hull's environment and its values over a step.
#[derive(Debug, Clone, Copy)]
pub struct HullStep<'a> {
    pub environment: &'a HullEnvironment,
    pub values: HullValues,
}

impl HullEnvironment {
    /// The hull's environment in `sea` and its `waves`, if the vessel `attachment` holds feels one.
    pub fn new(
        attachment: &VesselAttachment,
        sea: Option<&Sea>,
        waves: Option<&WaveField>,
    ) -> Result<Option<Self>> {
        if !attachment.hull_loads {
            return Ok(None);
        }
        let vessel = &attachment.vessel;
        let wind = sea
            .and_then(|s| s.wind.clone())
            .zip(vessel.wind_coefficients.clone());
        let current = match (sea, &vessel.current_coefficients) {
            (Some(sea), Some(coefficients)) => sea.current.as_ref().map(|current| {
                let (velocity, _) =
                    current.velocity_and_gradient(-sea.depth, sea.depth, f64::INFINITY);
                (
                    Vector2::new(velocity.x, velocity.y),
                    current.start,
                    coefficients.clone(),
                    sea.density,
                )
            }),
            _ => None,
        };
        let drift = match (waves, &vessel.drift_coefficients) {
            (Some(field), Some(coefficients)) => Some(DriftForce::new(field, coefficients)?),
            _ => None,
        };
        Ok(Some(HullEnvironment {
            wind,
            current,
            drift,
        }))
    }

    /// The environment over the step whose midpoint is `time` (s).
    pub fn at(&self, attachment: &VesselAttachment, time: f64) -> Result<HullValues> {
        let wind = self
            .wind
            .as_ref()
            .map_or_else(Vector2::zeros, |(wind, _)| wind.velocity(time));
        let current = self
            .current
            .as_ref()
            .filter(|(_, start, _, _)| time >= *start)
            .map_or_else(Vector2::zeros, |(velocity, _, _, _)| *velocity);
        let drift = match &self.drift {
            Some(drift) => drift.force(time, &station(attachment, time)?)?,
            None => Vector6::zeros(),
        };
        Ok(HullValues {
            wind,
            current,
            drift,
        })
    }
}

impl HullStep<'_> {
    /// The load on the hull (body frame) of a vessel with body frame `body` moving at ν = `velocity`.
    pub fn load(&self, body: &Matrix3<f64>, velocity: &Vector6<f64>) -> Vector6<f64> {
        let relative = |flow: &Vector2<f64>| {
            let v = body.transpose() * Vector3::new(flow.x, flow.y, 0.0);
            Vector2::new(v.x - velocity[0], v.y - velocity[1])
        };
        let mut load = self.values.drift;
        if let Some((_, coefficients)) = &self.environment.wind {
            load += coefficients.load(AIR_DENSITY, &relative(&self.values.wind));
        }
        if let Some((_, _, coefficients, density)) = &self.environment.current {
            load += coefficients.load(*density, &relative(&self.values.current));
        }
        load
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coefficients_interpolate_periodically_and_scale_with_the_square_of_the_speed() {
        let values = vec![
            Vector6::new(-1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            Vector6::new(0.0, 2.0, 0.0, 0.0, 0.0, 10.0),
            Vector6::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            Vector6::new(0.0, -2.0, 0.0, 0.0, 0.0, -10.0),
        ];
        let table = HullCoefficients::new("wind", vec![0.0, 90.0, 180.0, 270.0], values).unwrap();
        assert_eq!(table.at(45.0)[0], -0.5);
        assert_eq!(table.at(315.0)[1], -1.0);
        assert_eq!(table.at(-45.0), table.at(315.0));
        // A flow to starboard at 10 m/s: ½ρV²C.
        let load = table.load(1.226, &Vector2::new(0.0, 10.0));
        assert!((load[1] - 0.5 * 1.226 * 100.0 * 2.0).abs() < 1e-9);
        let error = HullCoefficients::new(
            "wind_coefficients",
            vec![0.0, 90.0],
            vec![Vector6::repeat(f64::NAN), Vector6::zeros()],
        )
        .unwrap_err()
        .to_string();
        assert!(error.starts_with("wind_coefficients[0]"), "{error}");
    }

    #[test]
    fn a_regular_wave_drifts_the_vessel_by_its_coefficient() {
        let text = "period_s,heading_deg,surge,sway,heave,roll,pitch,yaw\n\
                    5,0,1000,-200,0,0,0,50\n5,180,-3000,0,0,0,0,0\n\
                    15,0,100,-20,0,0,0,5\n15,180,-300,0,0,0,0,0\n";
        let coefficients = DriftCoefficients::from_csv(text, "t.csv").unwrap();
        let waves = crate::environment::waves::Waves::regular(1.5, 10.0, 0.0).unwrap();
        let field = WaveField::new(&waves, 1000.0, 9.81).unwrap();
        let drift = DriftForce::new(&field, &coefficients).unwrap();
        let d = coefficients.at(10.0, 0.0).unwrap();
        for t in [0.0, 3.3, 7.1] {
            let f = drift.force(t, &Vector3::new(10.0, 5.0, 0.0)).unwrap();
            for j in 0..6 {
                assert!(
                    (f[j] - 0.5625 * d[j]).abs() < 1e-9 * (1.0 + d[j].abs()),
                    "{f:?}"
                );
            }
        }
    }
}
