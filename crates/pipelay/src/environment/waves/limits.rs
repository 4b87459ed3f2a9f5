//! The bounds of linear wave theory a sea state must keep: DNV-RP-C205's steepness limit on a sea state, and
//! breaking (Miche's steepness limit and the depth-limited height).
use super::{Resolved, Waves};
use crate::error::{Error, Result};

/// DNV-RP-C205's limit on a sea state's steepness S_p = 2πH_s/(g T_p²) (§3.5.5.4): 1/15 for T_p ≤ 8 s, 1/25
/// for T_p ≥ 15 s, linear in between.
pub fn steepness_limit(tp: f64) -> f64 {
    let t = ((tp - 8.0) / 7.0).clamp(0.0, 1.0);
    (1.0 - t) / 15.0 + t / 25.0
}

/// Refuses a sea state steeper than DNV-RP-C205's limit: linear wave theory does not describe it.
pub(super) fn check_steepness(hs: f64, tp: f64) -> Result<()> {
    let g = 9.81;
    let steepness = std::f64::consts::TAU * hs / (g * tp * tp);
    let limit = steepness_limit(tp);
    if steepness > limit {
        return Err(Error::input(
            "hs",
            format!("{hs} m at tp = {tp} s (steepness S_p = 2πH_s/(gT_p²) = {steepness:.4})"),
            format!(
                "must keep the sea within DNV-RP-C205's steepness limit S_p ≤ {limit:.4} (1/15 for T_p ≤ 8 s, \
                 1/25 from 15 s): H_s ≤ {:.3} m at this T_p",
                limit * g * tp * tp / std::f64::consts::TAU
            ),
        ));
    }
    Ok(())
}

/// The breaking index: a wave breaks in water of depth h when its height exceeds 0.78 h (McCowan).
const BREAKING_INDEX: f64 = 0.78;

/// Refuses waves beyond breaking in `depth` (m): a regular wave steeper than Miche's limit
/// H ≤ (L/7) tanh(kh) (H/L ≤ 1/7 in deep water) or higher than the depth-limited 0.78 h, and a sea state whose
/// significant height exceeds 0.78 h.
pub(super) fn check_breaking(waves: &Waves, components: &[Resolved], depth: f64) -> Result<()> {
    let depth_limit = BREAKING_INDEX * depth;
    if let [regular] = components {
        let height = 2.0 * regular.amplitude;
        let length = std::f64::consts::TAU / regular.number;
        let miche = length / 7.0 * (regular.number * depth).tanh();
        let period = std::f64::consts::TAU / regular.frequency;
        if height > miche.min(depth_limit) {
            return Err(Error::input(
                "waves",
                format!("a regular wave of height {height} m and period {period} s in {depth} m of water"),
                format!(
                    "must not break: H ≤ min((L/7)·tanh(kh), 0.78 h) = {:.3} m (Miche's steepness limit, \
                     H/L ≤ 1/7 in deep water, and the depth-limited height; L = {length:.1} m)",
                    miche.min(depth_limit)
                ),
            ));
        }
        return Ok(());
    }
    let hs = waves.significant_height();
    if hs > depth_limit {
        return Err(Error::input(
            "waves",
            format!("a sea of significant height {hs:.3} m in {depth} m of water"),
            format!("must not break: H_s ≤ 0.78 h = {depth_limit:.3} m (the depth-limited height)"),
        ));
    }
    Ok(())
}
