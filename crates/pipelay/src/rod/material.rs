//! The pipe steel's uniaxial stress–strain law, elastic or elastoplastic with hysteresis.
//!
//! **Backbone.** The monotonic curve σ = f(ε): linear elastic (E); elastic–perfectly plastic (E, f_y);
//! Ramberg–Osgood ε = σ/E + (0.005 − σ_y/E)(σ/σ_y)ⁿ (σ_y the stress at 0.5 % total strain); or a table of
//! (ε, σ) points.
//!
//! **Hysteresis: the overlay model** (Besseling's; Iwan's parallel elements). The curve is taken piecewise
//! linear through breakpoints ε_1 < ε_2 < … with slopes s_1 > s_2 > … ≥ s_∞ ≥ 0 (s_1 = E). The material is a
//! set of elastic–perfectly plastic elements in parallel, all at the fibre's strain: element i of modulus
//! E_i = s_i − s_{i+1} yields at the strain ε_i, at the stress y_i = E_i ε_i; one more of modulus s_∞ never
//! yields. Loaded from rest the sum follows the backbone exactly at its breakpoints; unloaded it retraces
//! each element elastically, so reversals follow Masing's rule (the backbone doubled), and cycles close.
//! Each element's plastic strain ε_p,i is the state. Its free energy ψ = Σ ½E_i(ε − ε_p,i)² + ½s_∞ε², and
//! a strain step dissipates Σ y_i |Δε_p,i| exactly (each element's return onto its yield stress), so the
//! energy ledger of a rod made of it can close to round-off. A Ramberg–Osgood curve is sampled at
//! [`RO_BREAKPOINTS`] strains spaced geometrically from its 0.3·σ_y point to 5 %: its chords stay within
//! 1e-3 σ_y of it for n = 14 (the tests).
// Indexing cannot go out of bounds here: element indices of the law's own lists.
#![allow(clippy::indexing_slicing)]
use crate::error::{finite, positive, Error, Result};

/// Breakpoints a Ramberg–Osgood backbone is sampled at.
pub const RO_BREAKPOINTS: usize = 64;
/// Relative round-off within which an element's trial stress counts as on its yield stress, not beyond.
const YIELD_ROUND_OFF: f64 = 1e-12;
/// Independent partial sums the overlay's passes keep (a vector register's width of them).
const LANES: usize = 4;
/// The largest strain a Ramberg–Osgood backbone is sampled to; beyond, its last slope holds.
const RO_LAST_STRAIN: f64 = 0.05;

/// The uniaxial law of a material.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// How it was given (for reports and reprs).
    pub kind: MaterialKind,
    /// The overlay model's elements: modulus E_i (Pa) and yield strain ε_i, by increasing ε_i; empty for an
    /// elastic material.
    pub elements: Vec<(f64, f64)>,
    /// The modulus that never yields, s_∞ (Pa): E for an elastic material.
    pub hardening: f64,
}

/// How a material's backbone curve was given.
#[derive(Debug, Clone, PartialEq)]
pub enum MaterialKind {
    Elastic,
    ElasticPerfectlyPlastic { yield_stress: f64 },
    RambergOsgood { yield_stress: f64, exponent: f64 },
    Table,
}

impl Material {
    /// A linear elastic material.
    pub fn elastic(youngs_modulus: f64) -> Result<Self> {
        positive("E", youngs_modulus, "Pa")?;
        Ok(Material {
            youngs_modulus,
            kind: MaterialKind::Elastic,
            elements: Vec::new(),
            hardening: youngs_modulus,
        })
    }

    /// Elastic–perfectly plastic: E up to the yield stress f_y (Pa), then flat.
    pub fn elastic_perfectly_plastic(youngs_modulus: f64, yield_stress: f64) -> Result<Self> {
        positive("E", youngs_modulus, "Pa")?;
        positive("yield_stress", yield_stress, "Pa")?;
        Ok(Material {
            youngs_modulus,
            kind: MaterialKind::ElasticPerfectlyPlastic { yield_stress },
            elements: vec![(youngs_modulus, yield_stress / youngs_modulus)],
            hardening: 0.0,
        })
    }

    /// Ramberg–Osgood: ε = σ/E + (0.005 − σ_y/E)(σ/σ_y)ⁿ, σ_y the stress at 0.5 % total strain (Pa), n > 1.
    pub fn ramberg_osgood(youngs_modulus: f64, yield_stress: f64, exponent: f64) -> Result<Self> {
        positive("E", youngs_modulus, "Pa")?;
        positive("yield_stress", yield_stress, "Pa")?;
        if !(exponent.is_finite() && exponent > 1.0) {
            return Err(Error::input("n", exponent, "must be a finite exponent > 1"));
        }
        if yield_stress / youngs_modulus >= 0.005 {
            return Err(Error::input(
                "yield_stress",
                yield_stress,
                format!(
                    "must be below E·0.5 % = {:.4e} Pa (the yield stress is at 0.5 % total strain)",
                    0.005 * youngs_modulus
                ),
            ));
        }
        let strain =
            |stress: f64| ramberg_osgood_strain(youngs_modulus, yield_stress, exponent, stress);
        // Breakpoints: strains from that at 0.3 σ_y geometrically to RO_LAST_STRAIN, each stress by bisection.
        let stress_at = |target: f64| {
            let (mut low, mut high) = (0.0, yield_stress);
            while strain(high) < target {
                high *= 2.0;
            }
            for _ in 0..200 {
                let mid = 0.5 * (low + high);
                if strain(mid) < target {
                    low = mid;
                } else {
                    high = mid;
                }
            }
            0.5 * (low + high)
        };
        let first = strain(0.3 * yield_stress);
        let ratio = (RO_LAST_STRAIN / first).powf(1.0 / (RO_BREAKPOINTS - 1) as f64);
        let points: Vec<(f64, f64)> = (0..RO_BREAKPOINTS)
            .map(|k| {
                let at = first * ratio.powi(k as i32);
                (at, stress_at(at))
            })
            .collect();
        let mut material = Self::from_points(&points, "Ramberg–Osgood")?;
        material.youngs_modulus = youngs_modulus;
        material.kind = MaterialKind::RambergOsgood {
            yield_stress,
            exponent,
        };
        Ok(material)
    }

    /// A table of the backbone's (strain, stress) points (strain increasing from above 0, stress increasing,
    /// slopes decreasing), its first slope E, beyond its last point its last slope.
    pub fn table(strain: &[f64], stress: &[f64]) -> Result<Self> {
        finite("strain", strain)?;
        finite("stress", stress)?;
        if strain.len() != stress.len() || strain.is_empty() {
            return Err(Error::input(
                "stress",
                format!("{} values for {} strains", stress.len(), strain.len()),
                "must hold one stress per strain, at least one point",
            ));
        }
        let points: Vec<(f64, f64)> = strain.iter().copied().zip(stress.iter().copied()).collect();
        positive(
            "stress / strain at the first point (E)",
            points[0].1 / points[0].0,
            "Pa",
        )?;
        Self::from_points(&points, "table")
    }

    /// The overlay model through the backbone's breakpoints `points` (ε, σ), the curve from the origin to the
    /// first (its slope E); beyond the last, its last slope (flat if that is 0).
    fn from_points(points: &[(f64, f64)], what: &str) -> Result<Self> {
        let mut previous = (0.0, 0.0);
        let mut slopes = Vec::with_capacity(points.len());
        for &(strain, stress) in points {
            if !(strain > previous.0 && stress >= previous.1) {
                return Err(Error::input(
                    "strain",
                    format!(
                        "({strain}, {stress}) after ({}, {})",
                        previous.0, previous.1
                    ),
                    format!("must rise: the {what}'s strains increasing, its stresses not falling"),
                ));
            }
            slopes.push((stress - previous.1) / (strain - previous.0));
            previous = (strain, stress);
        }
        if slopes.windows(2).any(|w| w[1] > w[0] * (1.0 + 1e-12)) {
            return Err(Error::input(
                "stress",
                format!("{slopes:?}"),
                format!("must bend down: the {what}'s slopes must not grow along the curve"),
            ));
        }
        // Segment k (ending at point k) has slope s_k; element k yields at ε_k with E_k = s_k − s_{k+1}; the
        // last segment's slope continues beyond the last point and never yields.
        let hardening = slopes[slopes.len() - 1];
        let elements = (0..points.len() - 1)
            .map(|k| (slopes[k] - slopes[k + 1], points[k].0))
            .filter(|(modulus, _)| *modulus > 0.0)
            .collect();
        Ok(Material {
            youngs_modulus: slopes[0],
            kind: MaterialKind::Table,
            elements,
            hardening,
        })
    }

    /// Whether the material never yields.
    pub fn is_elastic(&self) -> bool {
        self.elements.is_empty()
    }

    /// How many plastic strains a fibre of it carries (one per overlay element).
    pub fn state_size(&self) -> usize {
        self.elements.len()
    }

    /// The stress (Pa) and tangent dσ/dε (Pa) at the total strain `strain`, from the elements' plastic strains
    /// `plastic` at the step's start, and their plastic strains after it (written into `plastic_end`):
    /// each element's return onto its yield stress. Also the free energy ψ (J/m³) after it and the energy
    /// dissipated over it (J/m³).
    pub fn respond(&self, strain: f64, plastic: &[f64], plastic_end: &mut [f64]) -> Response {
        let mut stress = self.hardening * strain;
        let mut tangent = self.hardening;
        let mut free_energy = 0.5 * self.hardening * strain * strain;
        let mut dissipated = 0.0;
        for (i, &(modulus, yield_strain)) in self.elements.iter().enumerate() {
            let trial = modulus * (strain - plastic[i]);
            let limit = modulus * yield_strain;
            // An element on its yield stress to round-off (where the last step left it) is taken as elastic:
            // its stress is the limit either way, and the elastic tangent is the one that unloading needs
            // (with the plastic one, Newton's first correction of an unloading overshoots without bound).
            let (element_stress, plastic_strain) = if trial.abs() <= limit * (1.0 + YIELD_ROUND_OFF)
            {
                tangent += modulus;
                (trial.clamp(-limit, limit), plastic[i])
            } else {
                let element_stress = limit.copysign(trial);
                (element_stress, strain - element_stress / modulus)
            };
            dissipated += limit * (plastic_strain - plastic[i]).abs();
            plastic_end[i] = plastic_strain;
            stress += element_stress;
            free_energy += 0.5 * element_stress * element_stress / modulus;
        }
        Response {
            stress,
            tangent,
            free_energy,
            dissipated,
        }
    }

    /// A step along the straight strain path from `start` to `end` (from the elements' plastic strains
    /// `plastic`, which `start` is consistent with; after it into `plastic_end`): the stress averaged over the
    /// path, σ̄ = ∫σ dε/Δε, and ∂σ̄/∂ε_end, the stress and free energy at the end and the energy dissipated.
    /// The average is exact: an element that stays elastic averages linearly; one that yields goes elastically
    /// from its start stress to ±y at ε* and flows beyond, so its path integral is Δψ_i + y_i|Δε_p,i|, and
    /// σ̄Δε = Δψ + D to round-off: the step's work is the free energy's change and the dissipation.
    pub fn respond_over(
        &self,
        start: f64,
        end: f64,
        plastic: &[f64],
        plastic_end: &mut [f64],
    ) -> PathResponse {
        if let Some(response) = self.respond_over_elastically(start, end, plastic, plastic_end) {
            return response;
        }
        let change = end - start;
        let middle = 0.5 * (start + end);
        let mut mean = self.hardening * middle;
        let mut mean_tangent = 0.5 * self.hardening;
        let mut stress = self.hardening * end;
        let mut free_energy = 0.5 * self.hardening * end * end;
        let mut dissipated = 0.0;
        for (i, &(modulus, yield_strain)) in self.elements.iter().enumerate() {
            let limit = modulus * yield_strain;
            let trial = modulus * (end - plastic[i]);
            if trial.abs() <= limit * (1.0 + YIELD_ROUND_OFF) {
                mean += modulus * (middle - plastic[i]);
                mean_tangent += 0.5 * modulus;
                let elastic_strain = bound(end - plastic[i], yield_strain);
                stress += modulus * elastic_strain;
                free_energy += 0.5 * modulus * elastic_strain * elastic_strain;
                plastic_end[i] = plastic[i];
                continue;
            }
            // Elastic from the start stress to s·y at ε* = ε_p + s y/E_i, then flowing to the end.
            let sign = trial.signum();
            let start_stress = bound(modulus * (start - plastic[i]), limit);
            let reached = plastic[i] + sign * yield_strain;
            let flow = end - reached;
            let path_work =
                0.5 * (start_stress + sign * limit) * (reached - start) + sign * limit * flow;
            if change != 0.0 {
                mean += path_work / change;
                mean_tangent += (sign * limit - path_work / change) / change;
            } else {
                mean += sign * limit;
            }
            stress += sign * limit;
            free_energy += 0.5 * limit * yield_strain;
            dissipated += limit * flow.abs();
            plastic_end[i] = end - sign * yield_strain;
        }
        PathResponse {
            mean,
            mean_tangent,
            stress,
            free_energy,
            dissipated,
        }
    }

    /// [`Self::respond_over`] where every element stays elastic over the path (the end within each element's
    /// elastic range ε_p,i ± ε_i; the start is, being consistent with the state), in one pass without branches:
    /// σ̄ = E ε̄ − Σ E_i ε_p,i at the path's middle ε̄, ∂σ̄/∂ε_end = E/2, ψ = ½ s_∞ ε² + Σ ½ E_i (ε − ε_p,i)².
    /// None if an element yields.
    fn respond_over_elastically(
        &self,
        start: f64,
        end: f64,
        plastic: &[f64],
        plastic_end: &mut [f64],
    ) -> Option<PathResponse> {
        let (mut excess, mut modulus_sum, mut plastic_sum, mut energy) = (
            [f64::NEG_INFINITY; LANES],
            [0.0; LANES],
            [0.0; LANES],
            [0.0; LANES],
        );
        in_lanes(
            &self.elements,
            plastic,
            |lane, (modulus, yield_strain), plastic_strain| {
                let elastic_strain = end - plastic_strain;
                excess[lane] =
                    excess[lane].max(elastic_strain.abs() - yield_strain * (1.0 + YIELD_ROUND_OFF));
                modulus_sum[lane] += modulus;
                plastic_sum[lane] += modulus * plastic_strain;
                energy[lane] += modulus * elastic_strain * elastic_strain;
            },
        );
        let elastic = excess.iter().all(|&e| e <= 0.0);
        let (modulus_sum, plastic_sum, energy): (f64, f64, f64) = (
            modulus_sum.iter().sum(),
            plastic_sum.iter().sum(),
            energy.iter().sum(),
        );
        if !elastic {
            return None;
        }
        plastic_end.copy_from_slice(plastic);
        let modulus = self.hardening + modulus_sum;
        Some(PathResponse {
            mean: modulus * 0.5 * (start + end) - plastic_sum,
            mean_tangent: 0.5 * modulus,
            stress: modulus * end - plastic_sum,
            free_energy: 0.5 * (self.hardening * end * end + energy),
            dissipated: 0.0,
        })
    }

    /// The stress (Pa) and free energy (J/m³) at `strain` of a state `plastic` consistent with it (where a
    /// step left it): read, not advanced.
    pub fn stress_and_energy(&self, strain: f64, plastic: &[f64]) -> (f64, f64) {
        let mut stress = self.hardening * strain;
        let mut free_energy = 0.5 * self.hardening * strain * strain;
        let (mut stresses, mut energies) = ([0.0; LANES], [0.0; LANES]);
        in_lanes(
            &self.elements,
            plastic,
            |lane, (modulus, yield_strain), plastic_strain| {
                let elastic_strain = bound(strain - plastic_strain, yield_strain);
                stresses[lane] += modulus * elastic_strain;
                energies[lane] += 0.5 * modulus * elastic_strain * elastic_strain;
            },
        );
        stress += stresses.iter().sum::<f64>();
        free_energy += energies.iter().sum::<f64>();
        (stress, free_energy)
    }

    /// The backbone's stress (Pa) at `strain` from rest (monotonic loading).
    pub fn backbone(&self, strain: f64) -> f64 {
        let rest = vec![0.0; self.state_size()];
        let mut end = rest.clone();
        self.respond(strain, &rest, &mut end).stress
    }
}

/// Calls `add(lane, element, plastic strain)` for each overlay element and its plastic strain, lane k of
/// every [`LANES`] in a row: sums kept per lane are independent, so that a pass vectorises (floating-point sums
/// are not reordered).
fn in_lanes(elements: &[(f64, f64)], plastic: &[f64], mut add: impl FnMut(usize, (f64, f64), f64)) {
    let (chunks, plastic_chunks) = (elements.chunks_exact(LANES), plastic.chunks_exact(LANES));
    let rest = chunks.remainder().iter().zip(plastic_chunks.remainder());
    for (elements, plastic) in chunks.zip(plastic_chunks) {
        for lane in 0..LANES {
            add(lane, elements[lane], plastic[lane]);
        }
    }
    for (&element, &plastic_strain) in rest {
        add(0, element, plastic_strain);
    }
}

/// `value` within ±`limit` (`limit` ≥ 0): `clamp` without its check or NaN rules (comparisons a vector
/// register's min and max do at once), so that the passes vectorise.
fn bound(value: f64, limit: f64) -> f64 {
    let above = if value < -limit { -limit } else { value };
    if above > limit {
        limit
    } else {
        above
    }
}

/// A fibre's response over a step's strain path ([`Material::respond_over`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathResponse {
    /// σ̄ = ∫σ dε/Δε over the path (Pa), and ∂σ̄/∂ε_end.
    pub mean: f64,
    pub mean_tangent: f64,
    /// The stress (Pa) and free energy (J/m³) at the end, and the energy dissipated over the step (J/m³).
    pub stress: f64,
    pub free_energy: f64,
    pub dissipated: f64,
}

/// A fibre's response to a strain step ([`Material::respond`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Response {
    pub stress: f64,
    pub tangent: f64,
    pub free_energy: f64,
    pub dissipated: f64,
}

/// Ramberg–Osgood's total strain at `stress`: σ/E + (0.005 − σ_y/E)(σ/σ_y)ⁿ.
pub fn ramberg_osgood_strain(
    youngs_modulus: f64,
    yield_stress: f64,
    exponent: f64,
    stress: f64,
) -> f64 {
    stress / youngs_modulus
        + (0.005 - yield_stress / youngs_modulus)
            * (stress / yield_stress).abs().powf(exponent)
            * stress.signum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_overlay_model_follows_the_backbone_and_masings_rule() {
        let epp = Material::elastic_perfectly_plastic(200e9, 400e6).unwrap();
        assert_eq!(epp.backbone(1e-3), 200e6);
        assert_eq!(epp.backbone(5e-3), 400e6);
        assert_eq!(epp.backbone(-5e-3), -400e6);
        // A table: at its points exactly, and unloading from ε_r by Δ follows σ_r − 2 f(Δ/2) (Masing).
        let table = Material::table(&[1e-3, 3e-3, 1e-2], &[200e6, 300e6, 350e6]).unwrap();
        let beyond = 350e6 + 50e6 / 7e-3 * 1e-2;
        for (strain, stress) in [(1e-3, 200e6), (3e-3, 300e6), (1e-2, 350e6), (2e-2, beyond)] {
            assert!((table.backbone(strain) - stress).abs() < 1e-3, "{strain}");
        }
        let mut plastic = vec![0.0; table.state_size()];
        let mut end = plastic.clone();
        let reversal = 8e-3;
        let top = table.respond(reversal, &plastic, &mut end).stress;
        plastic.copy_from_slice(&end);
        for delta in [1e-3, 3e-3, 6e-3, 1e-2] {
            let mut scratch = plastic.clone();
            let stress = table
                .respond(reversal - delta, &plastic, &mut scratch)
                .stress;
            let masing = top - 2.0 * table.backbone(0.5 * delta);
            assert!(
                (stress - masing).abs() < 1e-3,
                "{delta}: {stress} vs {masing}"
            );
        }
    }

    #[test]
    fn a_closed_cycle_dissipates_its_loop_area_and_stores_nothing() {
        let steel = Material::ramberg_osgood(207e9, 450e6, 14.0).unwrap();
        let mut plastic = vec![0.0; steel.state_size()];
        let mut end = plastic.clone();
        // Two cycles between ±1 % in small steps: the second's work equals its dissipation.
        let path: Vec<f64> = (0..=800)
            .map(|k| 0.01 * (2.0 * std::f64::consts::PI * k as f64 / 400.0).sin())
            .collect();
        let (mut work, mut dissipated, mut stress_before) = (0.0, 0.0, 0.0);
        let mut free_energy = 0.0;
        let (mut start_free, mut start_work, mut start_dissipated) = (0.0, 0.0, 0.0);
        for (k, pair) in path.windows(2).enumerate() {
            if k == 400 {
                (start_free, start_work, start_dissipated) = (free_energy, work, dissipated);
            }
            let response = steel.respond(pair[1], &plastic, &mut end);
            plastic.copy_from_slice(&end);
            // The stress over a step in which each element either stays elastic or flows is exact with the
            // trapezoid only for linear pieces: the ledger is ψ's change plus the dissipation.
            work += 0.5 * (stress_before + response.stress) * (pair[1] - pair[0]);
            stress_before = response.stress;
            free_energy = response.free_energy;
            dissipated += response.dissipated;
        }
        let cycle_work = work - start_work;
        let cycle_dissipated = dissipated - start_dissipated;
        assert!((free_energy - start_free).abs() < 1e-9 * cycle_dissipated);
        assert!(
            (cycle_work - cycle_dissipated).abs() < 1e-3 * cycle_dissipated,
            "{cycle_work} vs {cycle_dissipated}"
        );
    }

    /// Over any step the path-averaged stress does work equal to the free energy's change and the
    /// dissipation, and its derivative is the differences' (away from a breakpoint).
    #[test]
    fn a_steps_mean_stress_does_its_exact_work() {
        let steel = Material::ramberg_osgood(207e9, 450e6, 14.0).unwrap();
        let mut plastic = vec![0.0; steel.state_size()];
        let mut end = plastic.clone();
        let mut strain = 0.0;
        let mut free = 0.0;
        // Steps large and small, through yield, reversals and back.
        for step in [3e-3, 4e-3, -1e-4, -9e-3, 2e-6, 1.2e-2, -2.5e-2, 1e-9] {
            let response = steel.respond_over(strain, strain + step, &plastic, &mut end);
            let work = response.mean * step;
            let balance = response.free_energy - free + response.dissipated;
            assert!(
                (work - balance).abs()
                    <= 1e-12 * (response.free_energy + response.dissipated + free).max(1.0),
                "step {step}: {work} vs {balance}"
            );
            // ∂σ̄/∂ε_end against central differences.
            let h = 1e-11;
            let mut scratch = end.clone();
            let plus = steel
                .respond_over(strain, strain + step + h, &plastic, &mut scratch)
                .mean;
            let minus = steel
                .respond_over(strain, strain + step - h, &plastic, &mut scratch)
                .mean;
            let difference = (plus - minus) / (2.0 * h);
            assert!(
                (difference - response.mean_tangent).abs() < 1e-4 * 207e9,
                "step {step}: {difference} vs {}",
                response.mean_tangent
            );
            plastic.copy_from_slice(&end);
            strain += step;
            free = response.free_energy;
        }
    }

    #[test]
    fn ramberg_osgood_is_sampled_within_its_stated_error() {
        let (e, sy, n) = (207e9, 450e6, 14.0);
        let steel = Material::ramberg_osgood(e, sy, n).unwrap();
        let mut worst: f64 = 0.0;
        for k in 1..=400 {
            let stress = sy * 1.15 * k as f64 / 400.0;
            let strain = ramberg_osgood_strain(e, sy, n, stress);
            if strain > RO_LAST_STRAIN {
                break;
            }
            worst = worst.max((steel.backbone(strain) - stress).abs() / sy);
        }
        println!("Ramberg–Osgood sampled within {worst:.2e} of σ_y");
        assert!(worst < 1.1e-3, "{worst}");
        assert!(Material::ramberg_osgood(e, 2e9, n).is_err());
        assert!(Material::table(&[1e-3, 2e-3], &[200e6, 500e6]).is_err());
    }
}
