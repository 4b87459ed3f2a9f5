//! Steps that fail or blow up: a step whose Newton fails is taken in substeps, each an energy–momentum step of
//! its own, so that energy and momentum still balance; a step that converges to a state out of physical bounds
//! is rejected, and where even the smallest substep does, the run stops with a ConvergenceError and its state
//! untouched.
use nalgebra::Vector3;
use pipelay::assembly::configuration::Configuration;
use pipelay::dynamics::acceptance::MAX_SPEED;
use pipelay::dynamics::integrator::{DynamicOptions, Integrator, MAX_HALVINGS};
use pipelay::dynamics::state::DynamicState;
use pipelay::error::Error;
use pipelay::model::Model;
use pipelay::rod::section::{Section, SectionExtras};
use pipelay::rod::Rod;
use std::sync::Arc;

/// The free-flying rod of Simo, Tarnow & Doblaré (1995) (L = 10, EA = GA = 1e4, EI = GJ = 500, ρA = 1) in
/// vacuum, its tip pushed by `force` (N) and turned by `moment` (N·m) for the first 2.5 s.
fn pushed_rod(dt: f64, force: Vector3<f64>, moment: Vector3<f64>) -> Integrator {
    let extras = SectionExtras {
        inertia: [20.0, 10.0, 10.0],
        ..SectionExtras::default()
    };
    let section = Section::new(1e4, [1e4; 2], 500.0, [500.0; 2], 1.0, extras).expect("section");
    let rod = Rod::straight(
        Vector3::new(6.0, 0.0, 0.0),
        Vector3::new(0.0, 0.0, 8.0),
        10,
        section,
    )
    .expect("rod");
    let mut model = Model::new(rod, None, 0.0).expect("model");
    let scale = Arc::new(|t: f64| Ok(if t < 2.5 { 1.0 } else { 0.0 }));
    model
        .point_load(-1, force, moment, Some(scale))
        .expect("load");
    let state =
        DynamicState::at_rest(&model, Configuration::reference(&model), 0.0).expect("state");
    let options = DynamicOptions {
        time_step: dt,
        ..DynamicOptions::default()
    };
    Integrator::new(model, state, options).expect("integrator")
}

/// Simo's rod in steps of 0.5 s (ten times the usual), its tip turned hard: Newton fails in some steps, which are
/// taken in substeps that grow back; over the run the energy equals the work of the tip load to 1e-9 of it, the
/// linear momentum the load's impulse, and the run ends exactly at t = 10 s.
#[test]
fn failed_steps_are_taken_in_substeps_that_keep_the_balance() {
    let force = Vector3::new(20.0, 0.0, 0.0);
    let mut rod = pushed_rod(0.5, force, Vector3::new(0.0, 2000.0, 1000.0));
    let mut split = 0;
    let mut most = 1;
    for _ in 0..20 {
        let report = rod.step().expect("step");
        split += usize::from(report.substeps > 1);
        most = most.max(report.substeps);
    }
    println!("steps split: {split} of 20, most substeps {most}");
    assert!(split >= 1, "some steps need substeps");
    assert!(most < 1 << MAX_HALVINGS, "substeps grow back: {most}");
    assert_eq!(rod.state().time, 10.0);
    let energy = rod.observe().energy().total();
    let supplied = rod.ledger().supplied_work();
    assert!(energy > 100.0, "the loads set it moving: {energy}");
    assert!(
        (energy - supplied).abs() < 1e-9 * supplied,
        "E = {energy}, work supplied {supplied}"
    );
    // The force pushes for exactly 2.5 s (the steps' and substeps' midpoints fall on either side of 2.5).
    let impulse = 2.5 * force;
    let momentum = rod.observe().linear_momentum();
    assert!(
        (momentum - impulse).norm() < 1e-9 * impulse.norm(),
        "momentum {momentum} against the impulse {impulse}"
    );
}

/// A tip force of 1e12 N on a rod of 10 kg: Newton converges, but to a tip moving at ~1e10 m/s, far beyond the
/// axial wave speed MAX_SPEED; every substep down to the floor is rejected, and the step fails with a
/// ConvergenceError that says so, the state still at t = 0, at rest.
#[test]
fn a_step_out_of_physical_bounds_is_rejected() {
    let mut rod = pushed_rod(0.05, Vector3::new(1e12, 0.0, 0.0), Vector3::zeros());
    let Err(Error::Convergence {
        reason, reached, ..
    }) = rod.step()
    else {
        panic!("the step is rejected");
    };
    println!("{reason}");
    assert!(reason.contains("out of physical bounds"), "{reason}");
    assert!(reason.contains(&format!("{MAX_SPEED} m/s")), "{reason}");
    assert!(reason.contains("floor"), "{reason}");
    assert_eq!(reached, 0.0);
    assert_eq!(rod.state().time, 0.0);
    assert!(rod.state().velocities.iter().all(|v| v.norm() == 0.0));
}

/// A run resumed from its state after 6 of the 0.5 s steps (a new integrator from a copy of the state and the
/// ledger, as a checkpoint restores them) takes the same substeps and reaches, bit for bit, the same state as
/// the run that went on.
#[test]
fn a_resumed_run_takes_the_same_substeps_bit_for_bit() {
    let force = Vector3::new(20.0, 0.0, 0.0);
    let moment = Vector3::new(0.0, 2000.0, 1000.0);
    let mut rod = pushed_rod(0.5, force, moment);
    for _ in 0..6 {
        rod.step().expect("step");
    }
    let mut resumed = Integrator::new(
        pushed_rod(0.5, force, moment).model().clone(),
        rod.state().clone(),
        *rod.options(),
    )
    .expect("integrator");
    resumed.restore_ledger(*rod.ledger());
    let mut split = 0;
    for _ in 0..8 {
        let on = rod.step().expect("step");
        let again = resumed.step().expect("step");
        assert_eq!(on.substeps, again.substeps);
        assert_eq!(on.iterations, again.iterations);
        split += usize::from(on.substeps > 1);
    }
    assert!(split >= 1, "the steps compared include split ones");
    assert_eq!(
        rod.state().configuration.positions,
        resumed.state().configuration.positions
    );
    assert_eq!(rod.state().velocities, resumed.state().velocities);
    assert_eq!(rod.ledger(), resumed.ledger());
}
