//! What several integration tests share: the 1200 m flooded steel pipe of the validation tests (0.6 m × 15 mm,
//! 800 m of water, straight along e1), the check of an assembled tangent against finite differences, and a
//! vessel-held model let go without dissipation, and one started from its statics.
#![allow(dead_code)]
use nalgebra::Vector3;
use pipelay::assembly::assembler::Assembler;
use pipelay::assembly::configuration::Configuration;
use pipelay::assembly::dofs::NODE_DOFS;
use pipelay::dynamics::integrator::{DynamicOptions, Integrator};
use pipelay::dynamics::state::DynamicState;
use pipelay::environment::sea::Sea;
use pipelay::model::Model;
use pipelay::rod::section::Section;
use pipelay::rod::Rod;
use pipelay::so3::exp_quat;
use pipelay::statics::solve::{solve, StaticOptions};

/// The flooded 0.6 m × 15 mm steel pipe's section (drag and added mass 1 normal).
pub fn flooded_section() -> Section {
    Section::pipe(
        0.6,
        0.015,
        7850.0,
        207e9,
        0.3,
        1025.0,
        [0.0, 1.0],
        [0.0, 1.0],
    )
    .expect("pipe")
}

/// `config` with global DOF `dof` moved by `step`: a position component, a spatial spin exp(step e_k), or a
/// hinge angle.
pub fn perturbed(config: &Configuration, dof: usize, step: f64) -> Configuration {
    let mut c = config.clone();
    let (node, k) = (dof / NODE_DOFS, dof % NODE_DOFS);
    if node >= c.positions.len() {
        c.hinge_angles[dof - NODE_DOFS * c.positions.len()] += step;
    } else if k < 3 {
        c.positions[node][k] += step;
    } else {
        let mut spin = Vector3::zeros();
        spin[k - 3] = step;
        c.rotations[node] = exp_quat(&spin) * c.rotations[node];
    }
    c
}

/// A vessel-held model from its static state with every dissipation off and the holding thrust let go (the
/// pipe pulls the vessel), stepping by `dt`.
pub fn released_without_dissipation(mut model: Model, dt: f64) -> Integrator {
    model.rod.sections[0].drag = [0.0, 0.0];
    if let Some(attachment) = model.vessel.as_mut() {
        attachment.vessel.damping = nalgebra::Matrix6::zeros();
    }
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let mut state = DynamicState::at_rest(&model, solution.configuration, 0.0).expect("state");
    if let Some(v) = state.vessel.as_mut() {
        v.hold_thrust = nalgebra::Vector6::zeros();
    }
    let options = DynamicOptions {
        time_step: dt,
        ..DynamicOptions::default()
    };
    Integrator::new(model, state, options).expect("integrator")
}

/// The speed of the integrator's fastest node (m/s).
pub fn fastest_node(integrator: &Integrator) -> f64 {
    integrator
        .state()
        .velocities
        .iter()
        .map(|v| v.norm())
        .fold(0.0, f64::max)
}

/// A model's integrator from its static state at rest, stepping by `dt`.
pub fn from_statics(model: Model, dt: f64) -> Integrator {
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let state = DynamicState::at_rest(&model, solution.configuration, 0.0).expect("state");
    let options = DynamicOptions {
        time_step: dt,
        ..DynamicOptions::default()
    };
    Integrator::new(model, state, options).expect("integrator")
}

/// The largest difference between the static tangent that `assembler` assembles at `config` and central
/// differences (step `h`) of its residual over the free DOFs, and the largest tangent entry.
pub fn tangent_error(
    model: &Model,
    config: &Configuration,
    assembler: &mut Assembler,
    h: f64,
) -> (f64, f64) {
    assembler.assemble(model, config, 1.0, true, None);
    let values = assembler.values.clone();
    let dofs = assembler.dofs.clone();
    let perturbed = |dof: usize, step: f64, assembler: &mut Assembler| -> Vec<f64> {
        assembler.assemble(model, &perturbed(config, dof, step), 1.0, false, None);
        assembler.residual.clone()
    };
    let (mut worst, mut largest): (f64, f64) = (0.0, 0.0);
    for (col_dof, col) in dofs.equation.iter().enumerate() {
        let Some(col) = col else { continue };
        let plus = perturbed(col_dof, h, assembler);
        let minus = perturbed(col_dof, -h, assembler);
        for (row_dof, row) in dofs.equation.iter().enumerate() {
            let Some(row) = row else { continue };
            let fd = (plus[row_dof] - minus[row_dof]) / (2.0 * h);
            let analytic = assembler.lu.position(*row, *col).map_or(0.0, |p| values[p]);
            worst = worst.max((fd - analytic).abs());
            largest = largest.max(analytic.abs());
        }
    }
    (worst, largest)
}

/// The flooded pipe with `n` elements in 800 m of water, held by nothing yet.
pub fn flooded_pipe(n: usize) -> Model {
    let section = flooded_section();
    let rod =
        Rod::straight(Vector3::zeros(), Vector3::new(1200.0, 0.0, 0.0), n, section).expect("rod");
    let sea = Sea::new(800.0, 1025.0, None, None).expect("sea");
    Model::new(rod, Some(sea), 9.81).expect("model")
}
