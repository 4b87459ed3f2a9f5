//! A rod whose wall yields: a cantilever of a thin elastic–perfectly plastic tube bent by an end moment takes the
//! closed-form curvature, keeps the closed-form residual curvature unloaded, and its static tangent is the
//! derivative of its residual.
mod common;

use nalgebra::Vector3;
use pipelay::assembly::assembler::Assembler;
use pipelay::model::Model;
use pipelay::rod::material::Material;
use pipelay::rod::{section::Section, Rod};
use pipelay::statics::newton::{newton, Newton};
use pipelay::statics::solve::{solve, StaticOptions};

const E: f64 = 200e9;
const FY: f64 = 400e6;
const D: f64 = 0.4;
const T: f64 = 0.002;

/// A 10 m cantilever of the thin tube (weightless, in vacuum), clamped at A, with `moment` (N·m) about e2 at B.
fn cantilever(moment: f64) -> Model {
    let mut section =
        Section::pipe(D, T, 7850.0, E, 0.3, 0.0, [0.0, 0.0], [0.0, 0.0]).expect("pipe");
    if let Some(wall) = section.wall.as_mut() {
        wall.material = Some(Material::elastic_perfectly_plastic(E, FY).expect("material"));
    }
    let rod =
        Rod::straight(Vector3::zeros(), Vector3::new(10.0, 0.0, 0.0), 20, section).expect("rod");
    let mut model = Model::new(rod, None, 0.0).expect("model");
    model.clamp("A", None, None).expect("clamp");
    model
        .point_load(-1, Vector3::zeros(), Vector3::new(0.0, moment, 0.0), None)
        .expect("load");
    model
}

/// The thin tube's yield curvature and moment (at the wall's middle) and M/M_y at φ = κ/κ_y.
fn thin_tube() -> (f64, f64, impl Fn(f64) -> f64) {
    let a = 0.5 * (D - T);
    let inertia = std::f64::consts::PI / 64.0 * (D.powi(4) - (D - 2.0 * T).powi(4));
    let kappa_y = FY / (E * a);
    let ratio = |phi: f64| {
        if phi <= 1.0 {
            return phi;
        }
        let beta = (1.0 / phi).asin();
        4.0 / std::f64::consts::PI * (phi * (0.5 * beta - 0.25 * (2.0 * beta).sin()) + beta.cos())
    };
    (kappa_y, E * inertia * kappa_y, ratio)
}

/// Under M = 1.2 M_y the cantilever bends into an arc of the closed form's curvature (tip rotation κL); the
/// largest plastic strain and residual curvature are reported; unloaded, it keeps κ − M/EI.
#[test]
fn a_cantilever_yields_and_keeps_its_residual_curvature() {
    let (kappa_y, moment_y, ratio) = thin_tube();
    let moment = 1.2 * moment_y;
    let model = cantilever(moment);
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let tip = solution.configuration.rotations[20];
    let rotation = pipelay::so3::log_quat(&tip).y;
    let kappa = rotation / 10.0;
    // The closed form's curvature at 1.2 M_y, by bisection.
    let (mut low, mut high) = (1.0, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if ratio(mid) < 1.2 {
            low = mid;
        } else {
            high = mid;
        }
    }
    let expected = 0.5 * (low + high) * kappa_y;
    println!(
        "curvature {:.6} κ_y, closed form {:.6} κ_y",
        kappa / kappa_y,
        expected / kappa_y
    );
    assert!(
        (kappa / expected - 1.0).abs() < 2e-3,
        "{kappa} vs {expected}"
    );
    let plastic = solution
        .response
        .plastic
        .as_ref()
        .expect("plastic response");
    let residual = plastic.residual_curvature[10];
    let expected_residual =
        kappa - moment / (E * std::f64::consts::PI / 64.0 * (D.powi(4) - (D - 2.0 * T).powi(4)));
    assert!(
        (residual - expected_residual).abs() < 1e-6 * expected_residual,
        "{residual} vs {expected_residual}"
    );
    assert!(plastic.plastic_strain[10] > 0.0);

    // Unload in ten steps of the moment from the loaded state, its plastic state committed at each.
    let mut assembler = Assembler::new(&model);
    let mut config = solution.configuration.clone();
    assembler.assemble(&model, &config, 1.0, false, None);
    for step in (0..10).rev() {
        if let Some(state) = assembler.plastic.as_mut() {
            state.commit();
        }
        assembler.point_load_scales[0] = step as f64 / 10.0;
        match newton(
            &model,
            &mut assembler,
            &mut config,
            1.0,
            None,
            &StaticOptions::default(),
        ) {
            Newton::Converged { .. } => {}
            Newton::Failed { residual, .. } => panic!("unloading failed at residual {residual}"),
        }
    }
    let kept = pipelay::so3::log_quat(&config.rotations[20]).y / 10.0;
    println!(
        "kept curvature {:.6} κ_y, expected {:.6} κ_y",
        kept / kappa_y,
        expected_residual / kappa_y
    );
    assert!((kept - expected_residual).abs() < 1e-6 * expected_residual);
}

/// The static tangent of the yielded cantilever equals central differences of its residual.
#[test]
fn the_plastic_static_tangent_is_consistent() {
    let (_, moment_y, _) = thin_tube();
    let model = cantilever(1.15 * moment_y);
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let mut config = solution.configuration.clone();
    // Away from equilibrium, with axial strain and bending about both axes.
    for (k, p) in config.positions.iter_mut().enumerate() {
        p.z += 1e-4 * (0.9 * k as f64).sin();
        p.x += 1e-5 * k as f64;
    }
    let mut assembler = Assembler::new(&model);
    let (worst, largest) = common::tangent_error(&model, &config, &mut assembler, 1e-8);
    println!("worst tangent error {worst:.3e} of {largest:.3e}");
    assert!(worst < 1e-5 * largest, "{worst} of {largest}");
}
