//! Statics' fallback where Newton's continuation stalls: pseudo-transient continuation (Kelley & Keyes 1998),
//! the implicit form of dynamic relaxation.
//!
//! Each iteration solves (K + σM)Δu = −r, M the line's lumped mass: a backward-Euler step of size Δτ = σ^−½ of the
//! line's motion from rest, the velocity dropped after every step (the damping that brings dynamic relaxation to
//! rest). Where Newton's correction would swing a soft mode (a laid pipe pivoting about its anchor, a slack
//! span) far past the solution, σM holds each node's move to about |r|/(σm). The pseudo-time step grows as the
//! residual falls (switched evolution relaxation: σ_{k+1} = σ_k (|r_k|/|r_{k−1}|)², at least halved on a step
//! that lowers the residual), so that the iteration turns into Newton's, and converges quadratically, near the
//! solution. A step that raises the residual tenfold is taken back and retried with σ sixteen times larger.
// Indexing cannot go out of bounds here: node and element indices of the model's own mesh.
#![allow(clippy::indexing_slicing)]
use crate::assembly::assembler::Assembler;
use crate::assembly::configuration::Configuration;
use crate::assembly::dofs::NODE_DOFS;
use crate::linalg::factorisation::Factorisation;
use crate::model::Model;
use crate::statics::newton::{
    apply_correction, free_norm, largest_increments, residual_norms, roller_step_factor,
    round_off_floor, Newton,
};
use crate::statics::options::StaticOptions;
use nalgebra::Matrix6;

/// Iterations the relaxation may take.
pub const MAX_RELAXATION_ITERATIONS: usize = 400;

/// How far the first pseudo-time step may move the node with the largest residual per mass, in element lengths.
const FIRST_MOVE: f64 = 0.1;

/// Residual growth beyond which a step is taken back.
const REJECTED_GROWTH: f64 = 10.0;

/// The lumped mass of each node as a 6×6 diagonal block: the line's mass and its added mass across (kg) on the
/// translations, and on the rotations the inertia of the node's share of the elements about their middles,
/// m ℓ³/12 + J_ρ ℓ (kg·m²). A vessel's node carries only the line's: the vessel, stiff on its restoring and
/// holding springs, settles within each step instead of over the many its own mass would take.
fn nodal_masses(model: &Model) -> Vec<Matrix6<f64>> {
    let mut masses = vec![Matrix6::zeros(); model.rod.node_count()];
    let density = model.water_density();
    for (e, element) in model.rod.elements.iter().enumerate() {
        let section = model.rod.section(e);
        let per_length = section.mass + density * section.displaced_area * section.added_mass[1];
        let length = element.length;
        let translation = 0.5 * per_length * length;
        let rotation = 0.5 * (per_length * length.powi(3) / 12.0 + section.inertia.max() * length);
        for node in [e, e + 1] {
            for k in 0..3 {
                masses[node][(k, k)] += translation;
                masses[node][(3 + k, 3 + k)] += rotation;
            }
        }
    }
    masses
}

/// The factor on σ after a step that took the residual's norm by `ratio`: switched evolution relaxation, (ratio)²
/// within [1/100, 100], and at most 1/2 where the residual fell, so that the pseudo-time step keeps growing while
/// the residual falls slowly.
fn shift_factor(ratio: f64) -> f64 {
    let factor = ratio.powi(2).clamp(0.01, 100.0);
    if ratio < 1.0 {
        factor.min(0.5)
    } else {
        factor
    }
}

/// Relaxes `config` to equilibrium at load factor `load_factor` by pseudo-transient continuation.
pub fn relax(
    model: &Model,
    assembler: &mut Assembler,
    config: &mut Configuration,
    load_factor: f64,
    options: &StaticOptions,
) -> Newton {
    let masses = nodal_masses(model);
    let round_off = round_off_floor(model);
    let shortest = model.rod.shortest_element();
    let mut delta = vec![0.0; assembler.dofs.free];
    // σ and the residual it was last updated at (`None` after a step taken back: σ stands).
    let mut sigma: Option<(f64, Option<f64>)> = None;
    let mut residual = f64::INFINITY;
    for iteration in 0..MAX_RELAXATION_ITERATIONS {
        assembler.assemble(model, config, load_factor, true, None);
        let (free, scale) = residual_norms(assembler);
        residual = free;
        if !residual.is_finite() {
            break;
        }
        if residual <= options.tolerance * scale + round_off {
            return Newton::Converged {
                iterations: iteration,
                residual,
            };
        }
        // σ: first from the largest residual per mass over the translations, then by the residual's fall.
        let shift = match sigma {
            None => {
                let mut largest: f64 = 0.0;
                for (dof, eq) in assembler.dofs.equation.iter().enumerate() {
                    let (node, k) = (dof / NODE_DOFS, dof % NODE_DOFS);
                    // (The hinge angles after the nodes carry no mass here.)
                    if eq.is_some() && k < 3 && masses.get(node).is_some_and(|m| m[(k, k)] > 0.0) {
                        largest = largest.max(assembler.residual[dof].abs() / masses[node][(k, k)]);
                    }
                }
                largest / (FIRST_MOVE * shortest)
            }
            Some((sigma, Some(previous))) => sigma * shift_factor(residual / previous),
            Some((sigma, None)) => sigma,
        };
        sigma = Some((shift, Some(residual)));
        for (node, mass) in masses.iter().enumerate() {
            assembler.add_node_matrix(node, &(mass * shift));
        }
        if assembler.lu.factorise(&assembler.values).is_err() {
            break;
        }
        for (r, eq) in assembler.residual.iter().zip(&assembler.dofs.equation) {
            if let Some(i) = eq {
                delta[*i] = -r;
            }
        }
        if assembler.lu.solve_in_place(&mut delta).is_err() || delta.iter().any(|d| !d.is_finite())
        {
            break;
        }
        let (largest_rotation, _) = largest_increments(model, assembler, &delta);
        let factor = (options.max_rotation_increment / largest_rotation)
            .min(1.0)
            .min(roller_step_factor(model, assembler, config, &delta));
        let start = config.clone();
        apply_correction(model, assembler, config, &delta, factor);
        assembler.assemble(model, config, load_factor, false, None);
        let trial = free_norm(assembler);
        if !trial.is_finite() || trial > REJECTED_GROWTH * residual {
            config.clone_from(&start);
            sigma = Some((16.0 * shift, None));
        }
    }
    Newton::Failed {
        iterations: MAX_RELAXATION_ITERATIONS,
        residual,
    }
}
