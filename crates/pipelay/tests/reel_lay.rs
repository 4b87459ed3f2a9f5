//! Reel-lay: the pipe enters the water from the ramp in the state its reeling (reel, aligner, straightener)
//! left its wall in, and the suspended span bends it elastically from there. With the straightener set short
//! of the design the laid pipe keeps the reeling's residual curvature, bent against the sagbend; with the
//! designed one it lies straight; without one the pipe cannot hang and statics say why; a run from the
//! reel-lay's statics starts at rest.
mod common;

use nalgebra::{Vector3, Vector6};
use pipelay::environment::sea::Sea;
use pipelay::model::Model;
use pipelay::response::configuration::Response;
use pipelay::rod::material::Material;
use pipelay::rod::reeling::{design_straightener, reel, Reeling};
use pipelay::rod::{section::Section, Rod};
use pipelay::statics::solve::{solve, StaticOptions};
use pipelay::vessel::lay::LayEquipment;
use pipelay::vessel::rigid_body::Vessel;

const E: f64 = 207e9;
const FY: f64 = 450e6;
const REEL: f64 = 8.0;
const ALIGNER: f64 = 9.0;

/// A 12.75 in × 15.9 mm pipe of elastic–perfectly plastic steel (450 MPa), empty.
fn section() -> Section {
    let mut section =
        Section::pipe(0.3238, 0.0159, 7850.0, E, 0.3, 0.0, [0.0, 1.0], [0.0, 1.0]).expect("pipe");
    if let Some(wall) = section.wall.as_mut() {
        wall.material = Some(Material::elastic_perfectly_plastic(E, FY).expect("material"));
    }
    section
}

/// 600 m of the pipe from a pin on the seabed of 300 m of water to a reel-lay ramp 10° from the vertical.
fn reel_lay(straightener: f64) -> (Model, Reeling) {
    let rod = Rod::straight(
        Vector3::zeros(),
        Vector3::new(600.0, 0.0, 0.0),
        120,
        section(),
    )
    .expect("rod");
    let sea = Sea::new(300.0, 1025.0, None, None).expect("sea");
    let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
    model.pin("A", None).expect("pin");
    let reeling = Reeling::new(REEL, ALIGNER, straightener).expect("reeling");
    let ramp = LayEquipment::reel_lay(Vector3::new(-30.0, 0.0, 5.0), 10f64.to_radians(), reeling)
        .expect("ramp");
    model
        .attach_vessel(
            "B",
            Vessel::osv(),
            Vector6::new(420.0, 0.0, -300.0, 0.0, 0.0, 0.0),
            Vector3::zeros(),
            None,
            vec![],
            Some(ramp),
        )
        .expect("vessel");
    (model, reeling)
}

/// The pipe's bending stiffness EI (N·m²).
fn bending_stiffness() -> f64 {
    section().rotational_stiffness.y
}

/// The straightener's setting (1/m) that leaves the pipe straight.
fn designed_straightener() -> f64 {
    let fibres = section().fibre_section().expect("wall").expect("fibres");
    design_straightener(&fibres, REEL, ALIGNER, 0.0).expect("design")
}

#[test]
fn a_straightener_short_of_the_design_leaves_the_laid_pipe_the_reeling_residual_curvature() {
    let (model, reeling) = reel_lay(0.99 * designed_straightener());
    let fibres = section().fibre_section().expect("wall").expect("fibres");
    let entering = reel(&fibres, &reeling, 0.0);
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let config = &solution.configuration;
    let response = Response::new(&model, config);
    let plastic = response.plastic.as_ref().expect("plastic response");
    let residual = entering.residual_curvature.abs();
    let worst = plastic
        .residual_curvature
        .iter()
        .map(|k| (k / residual - 1.0).abs())
        .fold(0.0, f64::max);
    println!(
        "reeled residual curvature {:.6e} 1/m; along the laid line within {worst:.2e} of it",
        entering.residual_curvature
    );
    assert!(residual > 1e-4, "the setting leaves {residual} 1/m");
    assert!(worst < 1e-3, "{worst}");
    // The reeled pipe's moment-free curvature about the rod's second axis, against the sagbend's.
    let mut state = model.plastic_state().expect("state");
    let middle = 60;
    let moment = state
        .law(middle, &Vector3::zeros(), &Vector3::zeros(), 1.0)
        .expect("law")
        .moment;
    let kept = -moment.y / bending_stiffness();
    let (_, sagbend) = model
        .rod
        .strain_changes(middle, &config.positions, &config.rotations);
    println!(
        "moment-free curvature κ₂ {kept:.4e} 1/m, sagbend's κ₂ {:.4e} 1/m",
        sagbend.y
    );
    assert!((kept.abs() / residual - 1.0).abs() < 1e-3);
    assert!(kept * sagbend.y < 0.0, "{kept} vs {}", sagbend.y);
}

#[test]
fn with_the_designed_straightener_the_laid_pipe_lies_straight() {
    let straightener = designed_straightener();
    let (model, _) = reel_lay(straightener);
    let (unstraightened, _) = reel_lay(0.99 * straightener);
    let kept = |model: &Model| {
        let solution = solve(model, &StaticOptions::default()).expect("statics");
        let response = Response::new(model, &solution.configuration);
        let plastic = response.plastic.expect("plastic response");
        let largest = plastic
            .residual_curvature
            .iter()
            .copied()
            .fold(0.0, f64::max);
        let strain = plastic.plastic_strain.iter().copied().fold(0.0, f64::max);
        (largest, strain, solution.configuration.positions)
    };
    let (straight, strain, shape) = kept(&model);
    let (bent, _, bent_shape) = kept(&unstraightened);
    let moved = shape
        .iter()
        .zip(&bent_shape)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    println!(
        "straightener {straightener:.6e} 1/m: residual curvature {straight:.3e} 1/m (without it {bent:.3e}), \
         plastic strain {strain:.4e}; the line lies up to {moved:.3} m from the one at 99 % of the setting"
    );
    assert!(straight < 1e-3 * bent, "{straight} vs {bent}");
    assert!(strain > 1e-3, "the reeling's plastic strain {strain}");
}

#[test]
fn a_run_from_the_reel_lay_statics_starts_at_rest() {
    let (model, _) = reel_lay(0.99 * designed_straightener());
    let mut integrator = common::from_statics(model, 0.1);
    for _ in 0..10 {
        integrator.step().expect("step");
    }
    let fastest = common::fastest_node(&integrator);
    println!("after 1 s the fastest node moves at {fastest:.3e} m/s");
    assert!(fastest < 1e-4, "{fastest}");
}

#[test]
fn without_a_straightener_the_pipe_cannot_hang_and_statics_say_why() {
    let (model, reeling) = reel_lay(0.0);
    let fibres = section().fibre_section().expect("wall").expect("fibres");
    let kept = reel(&fibres, &reeling, 0.0).residual_curvature;
    let error = solve(&model, &StaticOptions::default()).expect_err("a coiling pipe");
    let message = error.to_string();
    println!("residual curvature {kept:.4e} 1/m: {message}");
    assert!(kept > 1e-2, "{kept}");
    assert!(message.contains("design_straightener"), "{message}");
    assert!(message.contains(&format!("{kept:.3e}")), "{message}");
}
