//! Newton's method on statics' residual at one point of a path: the correction limited to a largest nodal
//! rotation, a backtracking line search with seabed contact, and the tests of convergence, divergence and
//! stagnation at round-off.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the mesh being solved.
#![allow(clippy::indexing_slicing)]
use crate::assembly::assembler::Assembler;
use crate::assembly::configuration::Configuration;
use crate::assembly::dofs::NODE_DOFS;
use crate::linalg::factorisation::Factorisation;
use crate::model::Model;
use crate::so3::exp_quat;
use crate::statics::options::StaticOptions;
use nalgebra::Vector3;

/// Outcome of Newton at one load factor.
pub enum Newton {
    Converged { iterations: usize, residual: f64 },
    Failed { iterations: usize, residual: f64 },
}

/// Largest relative rotation between the nodes of one element that Newton may accept (rad): beyond it
/// the element's logarithm is near its branch cut at π and the iterate has jumped to a spurious state.
const MAX_ELEMENT_ROTATION: f64 = 2.5;

/// Newton iteration after which a residual larger than the first one counts as divergence.
const DIVERGENCE_CHECK: usize = 8;

/// Newton at load factor λ. With `support_increment`, the first iteration is the linearised Dirichlet
/// predictor: it moves the supports by their increments and the free DOFs by −K_ff⁻¹(r_f + K_fc Δu_c),
/// so that a support's motion spreads along the rod instead of straining one element.
pub fn newton(
    model: &Model,
    assembler: &mut Assembler,
    config: &mut Configuration,
    load_factor: f64,
    mut support_increment: Option<&[f64]>,
    options: &StaticOptions,
) -> Newton {
    let mut delta = vec![0.0; assembler.dofs.free];
    let round_off = round_off_floor(model);
    let length_scale = model.rod.length();
    let mut residual = f64::INFINITY;
    let mut first_residual = f64::INFINITY;
    for iteration in 0..=options.max_iterations {
        let summary = assembler.assemble(model, config, load_factor, true, support_increment);
        if summary.max_element_rotation > MAX_ELEMENT_ROTATION {
            break;
        }
        let (free, reactions) = residual_norms(assembler);
        residual = free;
        let scale = summary.external_norm.max(reactions);
        // After the predictor, measure progress from the first true Newton residual.
        if iteration <= 1 {
            first_residual = residual;
        }
        // Divergence: no progress after several iterations means a smaller load step is cheaper.
        let diverging = iteration >= DIVERGENCE_CHECK && residual > first_residual;
        if !residual.is_finite() || diverging {
            return Newton::Failed {
                iterations: iteration,
                residual,
            };
        }
        if support_increment.is_none() && residual <= options.tolerance * scale + round_off {
            return Newton::Converged {
                iterations: iteration,
                residual,
            };
        }
        if iteration == options.max_iterations || assembler.lu.factorise(&assembler.values).is_err()
        {
            break;
        }
        for ((r, c), eq) in assembler
            .residual
            .iter()
            .zip(&assembler.support_coupling)
            .zip(&assembler.dofs.equation)
        {
            if let Some(i) = eq {
                delta[*i] = -(r + c);
            }
        }
        if assembler.lu.solve_in_place(&mut delta).is_err() || delta.iter().any(|d| !d.is_finite())
        {
            break;
        }
        // Scale the whole correction if a node would turn by more than the allowed increment.
        let (largest_rotation, largest_translation) = largest_increments(model, assembler, &delta);
        let predictor = support_increment.is_some();
        let mut factor = match support_increment.take() {
            Some(increment) => {
                apply_increment(config, increment);
                1.0
            }
            None => (options.max_rotation_increment / largest_rotation)
                .min(1.0)
                .min(roller_step_factor(model, assembler, config, &delta)),
        };
        // With seabed contact (non-smooth friction, contact switching), backtrack along the correction while the
        // residual grows more than LINE_SEARCH_GROWTH-fold. Not with rollers: a roller's contact switching raises
        // the residual for an iteration on the way to convergence, and backtracking then stalls. Nor for a
        // moderate growth: a laid pipe pivoting sideways about its anchor (a current across the lay) stretches,
        // to second order, under Newton's linear correction, and the next correction takes the stretch back;
        // halving each such step made Newton crawl.
        let start = (assembler.contact.is_some() && assembler.rollers.is_none() && !predictor)
            .then(|| config.clone());
        for _ in 0..LINE_SEARCH_HALVINGS {
            apply_correction(model, assembler, config, &delta, factor);
            let Some(start) = &start else { break };
            assembler.assemble(model, config, load_factor, false, None);
            let trial = free_norm(assembler);
            let floor = 1e3 * (options.tolerance * scale + round_off);
            if trial.is_finite() && (trial <= LINE_SEARCH_GROWTH * residual || trial <= floor) {
                break;
            }
            config.clone_from(start);
            factor *= 0.5;
        }
        // Stagnation at round-off with a residual already small is convergence too.
        if factor == 1.0
            && largest_translation <= 1e-13 * length_scale
            && largest_rotation <= 1e-13
            && residual <= 1e-6 * scale
        {
            return Newton::Converged {
                iterations: iteration + 1,
                residual,
            };
        }
    }
    Newton::Failed {
        iterations: options.max_iterations,
        residual,
    }
}

/// Round-off floor of the residual norm (N): an element's axial force carries an error of about
/// ε·EA·|x|/L0 (positions |x| known to ε relative, differenced over the element length), and n of them add up
/// like a random walk. Never below 1e-13·EA·√n. A vessel's holding springs add theirs.
pub fn round_off_floor(model: &Model) -> f64 {
    let extent = model.rod.nodes.iter().map(|x| x.norm()).fold(1.0, f64::max);
    let shortest = model.rod.shortest_element();
    let per_element = (4.0 * f64::EPSILON * extent / shortest).max(1e-13);
    let vessel = model.vessel.as_ref().map_or(0.0, |attachment| {
        crate::vessel::coupling::static_round_off(attachment, extent)
    });
    per_element
        * model.rod.largest(|s| s.translational_stiffness.max())
        * (model.rod.element_count() as f64).sqrt()
        + vessel
}

/// The residual's norm over the free DOFs and over the prescribed ones (the reactions' scale) (N, N·m mixed).
pub fn residual_norms(assembler: &Assembler) -> (f64, f64) {
    let mut free_norm2 = 0.0;
    let mut fixed_norm2 = 0.0;
    for (r, eq) in assembler.residual.iter().zip(&assembler.dofs.equation) {
        match eq {
            Some(_) => free_norm2 += r * r,
            None => fixed_norm2 += r * r,
        }
    }
    (free_norm2.sqrt(), fixed_norm2.sqrt())
}

/// The largest nodal rotation or hinge angle (rad) and translation (m) of a correction `delta` on the free DOFs.
pub fn largest_increments(model: &Model, assembler: &Assembler, delta: &[f64]) -> (f64, f64) {
    let mut largest_rotation: f64 = 0.0;
    let mut largest_translation: f64 = 0.0;
    for node in 0..model.rod.node_count() {
        let mut spin = Vector3::zeros();
        for k in 0..3 {
            if let Some(i) = assembler.dofs.equation[NODE_DOFS * node + 3 + k] {
                spin[k] = delta[i];
            }
            if let Some(i) = assembler.dofs.equation[NODE_DOFS * node + k] {
                largest_translation = largest_translation.max(delta[i].abs());
            }
        }
        largest_rotation = largest_rotation.max(spin.norm());
    }
    for i in 0..model.hinge_count() {
        if let Some(eq) = assembler.dofs.equation[model.hinge_dof(i)] {
            largest_rotation = largest_rotation.max(delta[eq].abs());
        }
    }
    (largest_rotation, largest_translation)
}

/// The factor that keeps a correction `delta` from moving any node near the rollers down toward them, relative
/// to the vessel's node and in the vessel's body frame, by more than the rollers' reach (a roller's radius and
/// the line's half diameter): the contact sees a line only within twice that on the rollers' far side, and a
/// correction that carries a node further can pass it through the stinger (a quarter of that on roller boxes).
/// 1 without rollers, or where `assembler.limit_roller_steps` is off.
pub fn roller_step_factor(
    model: &Model,
    assembler: &Assembler,
    config: &Configuration,
    delta: &[f64],
) -> f64 {
    let (Some(rollers), Some(attachment), true) = (
        &assembler.rollers,
        &model.vessel,
        assembler.limit_roller_steps,
    ) else {
        return 1.0;
    };
    let reach = attachment
        .rollers()
        .iter()
        .map(|r| r.radius)
        .fold(f64::INFINITY, f64::min)
        + 0.5
            * (0..model.rod.element_count())
                .map(|e| model.rod.section(e).hydrodynamic_diameter)
                .fold(f64::INFINITY, f64::min);
    // A box's rollers end: beyond an end the contact pushes away from it whichever side the line is on, so a
    // step that carries a node between the lower ends of a V wedges it there. Steps on boxes are held to a
    // quarter of the reach.
    let boxes = attachment.rollers().iter().any(|r| r.length.is_finite());
    let reach = if boxes { 0.25 * reach } else { reach };
    let moved = |node: usize| {
        Vector3::from_fn(|k, _| {
            assembler.dofs.equation[NODE_DOFS * node + k].map_or(0.0, |i| delta[i])
        })
    };
    let vessel_node = attachment.node;
    let body = crate::vessel::coupling::body_rotation(attachment, &config.rotations[vessel_node]);
    let vessel_move = moved(vessel_node);
    let deepest = rollers
        .nodes()
        .map(|node| (body.transpose() * (moved(node) - vessel_move)).z)
        .fold(0.0, f64::max);
    if deepest > reach {
        reach / deepest
    } else {
        1.0
    }
}

/// Growth of the residual's norm beyond which the line search with seabed contact takes a correction back.
const LINE_SEARCH_GROWTH: f64 = 10.0;

/// Backtracking steps of the line search with seabed contact.
const LINE_SEARCH_HALVINGS: usize = 6;

/// Norm of the residual over the free DOFs.
pub fn free_norm(assembler: &Assembler) -> f64 {
    assembler
        .residual
        .iter()
        .zip(&assembler.dofs.equation)
        .filter(|(_, eq)| eq.is_some())
        .map(|(r, _)| r * r)
        .sum::<f64>()
        .sqrt()
}

/// Moves the free DOFs of `config` (its hinge angles too) by `factor` times the Newton correction `delta`.
pub fn apply_correction(
    model: &Model,
    assembler: &Assembler,
    config: &mut Configuration,
    delta: &[f64],
    factor: f64,
) {
    for node in 0..model.rod.node_count() {
        let mut spin = Vector3::zeros();
        for k in 0..3 {
            if let Some(i) = assembler.dofs.equation[NODE_DOFS * node + k] {
                config.positions[node][k] += factor * delta[i];
            }
            if let Some(i) = assembler.dofs.equation[NODE_DOFS * node + 3 + k] {
                spin[k] = factor * delta[i];
            }
        }
        if spin != Vector3::zeros() {
            config.rotations[node] = exp_quat(&spin) * config.rotations[node];
        }
    }
    for (i, angle) in config.hinge_angles.iter_mut().enumerate() {
        if let Some(eq) = assembler.dofs.equation[model.hinge_dof(i)] {
            *angle += factor * delta[eq];
        }
    }
}

/// Adds an increment given on all DOFs (positions and spatial spins) to a configuration.
pub fn apply_increment(config: &mut Configuration, increment: &[f64]) {
    for (node, du) in increment.chunks_exact(NODE_DOFS).enumerate() {
        config.positions[node] += Vector3::new(du[0], du[1], du[2]);
        let spin = Vector3::new(du[3], du[4], du[5]);
        if spin != Vector3::zeros() {
            config.rotations[node] = exp_quat(&spin) * config.rotations[node];
        }
    }
}
