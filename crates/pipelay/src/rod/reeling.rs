//! Reel-lay's bending history of a pipe section: spooled onto the reel, unspooled straight, bent over the
//! aligner, reverse-bent by the straightener, and released; its wall's state through it
//! ([`crate::rod::fibre_section`]) and the residual curvature it leaves.
//!
//! The curvatures are those of the pipe's centreline: 1/R on the reel and on the aligner (R the radius of the
//! centreline there), κ_s at the straightener (negative: against the reel's). Released, the section unloads to
//! zero moment; its curvature then is the residual curvature. Each stage's curvature changes monotonically, so
//! the overlay model's return mapping is exact over it, whatever the steps.
// Indexing cannot go out of bounds here: fibre indices of the section's own lists.
#![allow(clippy::indexing_slicing)]
use crate::error::{positive, Error, Result};
use crate::rod::fibre_section::FibreSection;
use nalgebra::Vector3;

/// Points recorded per stage.
const STAGE_POINTS: usize = 40;

/// The reeling path: the reel's and the aligner's centreline radii (m) and the straightener's curvature (1/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reeling {
    pub reel_radius: f64,
    pub aligner_radius: f64,
    pub straightener_curvature: f64,
}

impl Reeling {
    /// A checked path.
    pub fn new(reel_radius: f64, aligner_radius: f64, straightener_curvature: f64) -> Result<Self> {
        positive("reel_radius", reel_radius, "m")?;
        positive("aligner_radius", aligner_radius, "m")?;
        if !straightener_curvature.is_finite() {
            return Err(Error::input(
                "straightener curvature",
                straightener_curvature,
                "must be finite (1/m)",
            ));
        }
        Ok(Reeling {
            reel_radius,
            aligner_radius,
            straightener_curvature,
        })
    }

    /// The stages' end curvatures (1/m): reel, unspooled, aligner, straightener.
    fn stages(&self) -> [f64; 4] {
        [
            1.0 / self.reel_radius,
            0.0,
            1.0 / self.aligner_radius,
            self.straightener_curvature,
        ]
    }
}

/// A section's history through the reeling path.
#[derive(Debug, Clone, PartialEq)]
pub struct ReelingHistory {
    /// Curvature (1/m), bending moment (N·m) and the largest strain over the wall (tension positive) along the
    /// path, the release last; and the stage of each point (0 reel, 1 unspooled, 2 aligner, 3 straightener,
    /// 4 released).
    pub curvature: Vec<f64>,
    pub moment: Vec<f64>,
    pub strain: Vec<f64>,
    pub stage: Vec<usize>,
    /// The curvature left at zero moment (1/m).
    pub residual_curvature: f64,
    /// The largest accumulated plastic strain Σ|Δε_p| over the wall's fibres through the path.
    pub accumulated_plastic_strain: f64,
    /// The wall's fibres' plastic state as it leaves (released).
    pub plastic: Vec<f64>,
}

/// The history of `fibres` along `reeling`, at the axial strain `axial_strain` throughout.
pub fn reel(fibres: &FibreSection, reeling: &Reeling, axial_strain: f64) -> ReelingHistory {
    reel_about(fibres, reeling, axial_strain, 1.0)
}

/// The wall's fibres' plastic state of a pipe leaving a reel-lay ramp, the rod's curvature about its second
/// axis being `sense` (±1) times the reeling's: the state [`reel`] leaves, released, at zero axial strain (the
/// reel's back tension is small against EA). The aligner bends the pipe against the sagbend: seen from the
/// ramp's exit, toward end B, the rod's κ₂ of the aligner is −1/R when the vessel holds end B.
pub fn entry_state(fibres: &FibreSection, reeling: &Reeling, sense: f64) -> Vec<f64> {
    reel_about(fibres, reeling, 0.0, sense).plastic
}

/// [`reel`] with the fibres bent about the section's second axis by `sense` (±1) times the reeling's
/// curvature; the history's curvatures and moments are the reeling's.
fn reel_about(
    fibres: &FibreSection,
    reeling: &Reeling,
    axial_strain: f64,
    sense: f64,
) -> ReelingHistory {
    let mut plastic = vec![0.0; fibres.state_size()];
    let mut end = plastic.clone();
    let mut history = ReelingHistory {
        curvature: vec![0.0],
        moment: vec![0.0],
        strain: vec![axial_strain],
        stage: vec![0],
        residual_curvature: 0.0,
        accumulated_plastic_strain: 0.0,
        plastic: Vec::new(),
    };
    let mut fibre_plastic =
        fibres.fibre_plastic_strains(&Vector3::new(axial_strain, 0.0, 0.0), &plastic);
    let mut accumulated = vec![0.0; fibre_plastic.len()];
    let mut kappa = 0.0;
    let mut record = |kappa: f64, stage: usize, plastic: &mut Vec<f64>, end: &mut Vec<f64>| {
        let strains = Vector3::new(axial_strain, sense * kappa, 0.0);
        let response = fibres.respond(&strains, plastic, end);
        plastic.copy_from_slice(end);
        let now = fibres.fibre_plastic_strains(&strains, plastic);
        for ((sum, before), after) in accumulated.iter_mut().zip(&fibre_plastic).zip(&now) {
            *sum += (after - before).abs();
        }
        fibre_plastic = now;
        history.curvature.push(kappa);
        history.moment.push(sense * response.resultants.y);
        history
            .strain
            .push(axial_strain + 0.5 * fibres.outer_diameter() * kappa.abs());
        history.stage.push(stage);
        response
    };
    for (stage, target) in reeling.stages().into_iter().enumerate() {
        let start = kappa;
        for k in 1..=STAGE_POINTS {
            kappa = start + (target - start) * k as f64 / STAGE_POINTS as f64;
            record(kappa, stage, &mut plastic, &mut end);
        }
    }
    // Release: Newton on the curvature for zero moment from the straightened state (elastic unloading).
    for _ in 0..50 {
        let strains = Vector3::new(axial_strain, sense * kappa, 0.0);
        let mut scratch = plastic.clone();
        let response = fibres.respond(&strains, &plastic, &mut scratch);
        let (moment, stiffness) = (sense * response.resultants.y, response.tangent[(1, 1)]);
        if moment.abs() <= 1e-9 * stiffness.abs() * (1e-6 + kappa.abs()) || stiffness <= 0.0 {
            break;
        }
        kappa -= moment / stiffness;
    }
    record(kappa, 4, &mut plastic, &mut end);
    history.residual_curvature = kappa;
    history.accumulated_plastic_strain = accumulated.iter().copied().fold(0.0, f64::max);
    history.plastic = plastic;
    history
}

/// The straightener's curvature (1/m) that leaves `fibres` straight (zero residual curvature) after the reel of
/// `reel_radius` and the aligner of `aligner_radius` (m), at the axial strain `axial_strain`; by bisection
/// between the aligner's curvature and its opposite twice over.
pub fn design_straightener(
    fibres: &FibreSection,
    reel_radius: f64,
    aligner_radius: f64,
    axial_strain: f64,
) -> Result<f64> {
    let residual = |curvature: f64| -> Result<f64> {
        let reeling = Reeling::new(reel_radius, aligner_radius, curvature)?;
        Ok(reel(fibres, &reeling, axial_strain).residual_curvature)
    };
    let aligner = 1.0 / aligner_radius;
    let (mut low, mut high) = (-2.0 * aligner, aligner);
    let (mut at_low, at_high) = (residual(low)?, residual(high)?);
    if at_low.signum() == at_high.signum() {
        return Err(Error::input(
            "aligner_radius",
            aligner_radius,
            "leaves no straightener setting between the aligner's curvature and twice its opposite that \
             straightens the pipe",
        ));
    }
    for _ in 0..60 {
        let middle = 0.5 * (low + high);
        let at_middle = residual(middle)?;
        if at_middle.signum() == at_low.signum() {
            (low, at_low) = (middle, at_middle);
        } else {
            high = middle;
        }
    }
    Ok(0.5 * (low + high))
}
