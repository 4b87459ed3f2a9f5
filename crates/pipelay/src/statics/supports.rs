//! The supports along statics' path: at support motion μ ∈ [0, 1] each prescribed node stands a fraction μ of
//! the way from its reference to its target, in position and (geodesically) in rotation.
// Indexing cannot go out of bounds here: supported nodes of the model's own mesh.
#![allow(clippy::indexing_slicing)]
use crate::assembly::configuration::Configuration;
use crate::assembly::dofs::NODE_DOFS;
use crate::model::{Model, SupportTarget};
use crate::so3::{exp_quat, log_quat};

/// Sets the prescribed DOFs to their values at support motion μ: x = X + μ(p − X), R = exp(μ log(R_p R_Xᵀ)) R_X.
pub fn apply_supports(
    model: &Model,
    targets: &[SupportTarget],
    config: &mut Configuration,
    load_factor: f64,
) {
    for support in targets {
        let node = support.node;
        let reference = model.rod.nodes[node];
        config.positions[node] = reference + (support.position - reference) * load_factor;
        if let Some(target) = support.rotation {
            let frame = model.rod.frames[node];
            let rotation = log_quat(&(target * frame.inverse()));
            config.rotations[node] = exp_quat(&(rotation * load_factor)) * frame;
        }
    }
}

/// Increments that take the supports of `config` to their values at support motion μ (all DOFs, zero where free).
pub fn support_increment(
    model: &Model,
    targets: &[SupportTarget],
    config: &Configuration,
    support_motion: f64,
) -> Vec<f64> {
    let mut target = config.clone();
    apply_supports(model, targets, &mut target, support_motion);
    let mut increment = vec![0.0; NODE_DOFS * model.rod.node_count()];
    for support in targets {
        let node = support.node;
        let du = &mut increment[NODE_DOFS * node..NODE_DOFS * (node + 1)];
        du[..3].copy_from_slice((target.positions[node] - config.positions[node]).as_slice());
        if support.rotation.is_some() {
            let spin = log_quat(&(target.rotations[node] * config.rotations[node].inverse()));
            du[3..].copy_from_slice(spin.as_slice());
        }
    }
    increment
}
