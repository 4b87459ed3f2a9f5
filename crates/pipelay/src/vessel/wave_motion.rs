//! The vessel's first-order (wave-frequency) motion from its displacement RAOs, superposed on the simulated
//! low-frequency motion (as OrcaFlex does with "displacement RAOs + calculated" vessel motion).
//!
//! For wave components (a_i, ω_i, β_i, φ_i, k_i) and a vessel on station at (x_s, y_s) with heading ψ_s, DOF j
//! of the motion about CO (body frame) is
//!   ξ_j(t) = r(t) Σ_i a_i |R_j| cos(ω_i t − k_i(x_s cos β_i + y_s sin β_i) − φ_i + arg R_j),
//! R_j = R_j(2π/ω_i, β_i − ψ_s) the table's RAO (the phase refers to the elevation at CO) and r(t) the sea's
//! build-up. It moves the vessel's low-frequency pose (x_C, Λ_B) rigidly about CO:
//!   x = x_C + u, Λ = Q Λ_B, u = R(ψ_s)(ξ_1, ξ_2, ξ_3), Q = exp(R(ψ_s)(ξ_4, ξ_5, ξ_6)).
//!
//! Phases and headings are taken at the station (the DP reference, or the starting pose without a
//! controller), not at the instantaneous low-frequency position, so that the motion is a function of time
//! alone; the phase error is k times the vessel's distance from its station (0.05 rad per metre at 9 s).
//! Components shorter than the table's shortest period do not move the vessel (a ship filters them); a
//! component longer than its longest period is an error, and so is a sea whose peak lies outside the table.
use super::raos::Raos;
use super::VesselAttachment;
use crate::environment::waves::{ramp_factor, Resolved, WaveField};
use crate::error::{Error, Result};
use crate::so3::exp;
use nalgebra::{Complex, Matrix3, Vector3, Vector6};

/// The wave-frequency displacement of the vessel at one time: CO's translation u and the rotation Q (in e),
/// from the motion ξ about CO (station frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveOffset {
    pub translation: Vector3<f64>,
    pub rotation: Matrix3<f64>,
}

/// A sea's components that move the vessel, with its RAO table.
#[derive(Debug, Clone, PartialEq)]
pub struct WaveMotion {
    components: Vec<Resolved>,
    raos: Raos,
    ramp: f64,
}

impl WaveMotion {
    /// The motion of a vessel with RAOs `raos` in the sea `field`.
    pub fn new(field: &WaveField, raos: &Raos) -> Result<Self> {
        let (first, last) = match (raos.periods.first(), raos.periods.last()) {
            (Some(first), Some(last)) => (*first, *last),
            _ => return Err(Error::input("raos", "an empty table", "must hold periods")),
        };
        let period = |c: &Resolved| std::f64::consts::TAU / c.frequency;
        let outside = |what: &str, c: &Resolved| {
            Error::input(
                "waves",
                format!("{what} of {:.3} s", period(c)),
                format!("must lie within the vessel's RAO table, [{first}, {last}] s"),
            )
        };
        let components = field.components();
        if let Some(peak) = components
            .iter()
            .max_by(|a, b| a.amplitude.total_cmp(&b.amplitude))
        {
            if !(first..=last).contains(&period(peak)) {
                return Err(outside("a peak period", peak));
            }
        }
        if let Some(long) = components.iter().find(|c| period(c) > last) {
            return Err(outside("a component period", long));
        }
        Ok(WaveMotion {
            components: components
                .iter()
                .filter(|c| period(c) >= first)
                .copied()
                .collect(),
            raos: raos.clone(),
            ramp: field.ramp(),
        })
    }

    /// The displacement at time t (s) of a vessel whose station is `station` = (x_s, y_s, ψ_s) (m, m, rad).
    pub fn offset(&self, time: f64, station: &Vector3<f64>) -> Result<WaveOffset> {
        let (ramp, _) = ramp_factor(time, self.ramp);
        let mut motion = Vector6::zeros();
        if ramp > 0.0 {
            for c in &self.components {
                let heading = (c.direction - station.z).to_degrees();
                let rao = self.raos.at(std::f64::consts::TAU / c.frequency, heading)?;
                // The elevation a cos θ_i = Re(a e^{−iθ_i}), θ_i = k·x_s − ωt + φ: the RAO's phase adds to −θ_i.
                let elevation =
                    Complex::from_polar(ramp * c.amplitude, -c.angle(station.x, station.y, time));
                for (xi, r) in motion.iter_mut().zip(rao) {
                    *xi += (r * elevation).re;
                }
            }
        }
        let heading = crate::vessel::euler::rotation(&Vector3::new(0.0, 0.0, station.z));
        Ok(WaveOffset {
            translation: heading * motion.fixed_rows::<3>(0),
            rotation: exp(&(heading * motion.fixed_rows::<3>(3))),
        })
    }
}

/// Where the vessel keeps station at time t: (x, y, ψ) of its controller's reference, or of its starting pose
/// without a controller or with one outside pipelay (whose reference pipelay does not know).
pub fn station(attachment: &VesselAttachment, time: f64) -> Result<Vector3<f64>> {
    let pose = match &attachment.controller {
        Some(controller) if controller.external.is_none() => controller.reference.at(time)?.0,
        _ => attachment.eta,
    };
    Ok(Vector3::new(pose.x, pose.y, pose.b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::waves::Waves;

    /// In a long head sea the OSV heaves with the surface (z down: heave = −η) and pitches with its slope.
    #[test]
    fn long_waves_move_the_vessel_with_the_surface() {
        let waves = Waves::regular(2.0, 28.0, std::f64::consts::PI).unwrap();
        let field = WaveField::new(&waves, 1000.0, 9.81).unwrap();
        let motion = WaveMotion::new(&field, &Raos::osv().unwrap()).unwrap();
        let station = Vector3::new(30.0, -5.0, 0.0);
        for i in 0..20 {
            let t = 1.4 * i as f64;
            let offset = motion.offset(t, &station).unwrap();
            let eta = field.elevation(station.x, station.y, t);
            assert!(
                (offset.translation.z + eta).abs() < 0.02,
                "{t}: {offset:?} vs {eta}"
            );
            assert!(offset.translation.y.abs() < 1e-3 && offset.rotation[(2, 1)].abs() < 1e-4);
        }
    }

    #[test]
    fn seas_outside_the_table_are_input_errors() {
        let raos = Raos::osv().unwrap();
        // 0.5 m high: a 2 s wave of 1 m would break (L/7 = 0.89 m).
        for period in [2.0, 35.0] {
            let field =
                WaveField::new(&Waves::regular(0.5, period, 0.0).unwrap(), 500.0, 9.81).unwrap();
            let message = WaveMotion::new(&field, &raos).unwrap_err().to_string();
            assert!(message.starts_with("waves: "), "{message}");
            assert!(message.contains("[3, 30] s"), "{message}");
        }
        // A JONSWAP sea at Tp 9 s has components over [0.5, 4]ω_p, periods 2.25–18 s: the 2/7 of them
        // shorter than 3 s do not move the vessel.
        let sea = Waves::jonswap(2.5, 9.0, 3.3, 0.0, None, 1, 700).unwrap();
        let field = WaveField::new(&sea, 500.0, 9.81).unwrap();
        let motion = WaveMotion::new(&field, &raos).unwrap();
        assert_eq!(motion.components.len(), 500);
    }
}
