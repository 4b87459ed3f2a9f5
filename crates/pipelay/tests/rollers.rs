//! Rollers on the vessel: a stinger under an S-lay pipe in statics and dynamics.
mod common;

use nalgebra::{Vector3, Vector6};
use pipelay::assembly::assembler::Assembler;
use pipelay::assembly::dofs::NODE_DOFS;
use pipelay::environment::sea::Sea;
use pipelay::environment::seabed::Seabed;
use pipelay::model::Model;
use pipelay::response::configuration::Response;
use pipelay::rod::{section::Section, Rod};
use pipelay::statics::solve::{solve, StaticOptions};
use pipelay::vessel::lay::{stinger_rollers, LayEquipment};
use pipelay::vessel::rigid_body::Vessel;

/// A 0.6 m × 30 mm steel pipe (empty) in 150 m of water, pinned at A, held by an OSV's tensioner 10 m
/// forward of CO on a firing line 6.3 m above the waterline, over a 100 m-radius, 80 m stinger of 12 rollers
/// starting 40 m aft of CO.
fn s_lay(vessel_x: f64, elements: usize, seabed: Option<Seabed>) -> Model {
    let section =
        Section::pipe(0.6, 0.03, 7850.0, 207e9, 0.3, 0.0, [0.0, 1.0], [0.0, 1.0]).expect("pipe");
    let rod = Rod::straight(
        Vector3::zeros(),
        Vector3::new(700.0, 0.0, 0.0),
        elements,
        section,
    )
    .expect("rod");
    let sea = Sea::new(150.0, 1025.0, None, seabed).expect("sea");
    let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
    model.pin("A", None).expect("pin");
    let rollers = stinger_rollers(100.0, 80.0, 12, Vector3::new(-40.0, 0.0, -6.0), 0.0, 0.25)
        .expect("stinger");
    let lay = LayEquipment::s_lay(Vector3::new(10.0, 0.0, -6.3), rollers, 1e7).expect("lay");
    let eta = Vector6::new(vessel_x, 0.0, -150.0, 0.0, 0.0, 0.0);
    model
        .attach_vessel(
            "B",
            Vessel::osv(),
            eta,
            Vector3::zeros(),
            None,
            vec![],
            Some(lay),
        )
        .expect("vessel");
    model
}

/// The assembled static tangent matches central differences of the residual on every DOF the rollers
/// touch (the pipe's last 30 nodes and the vessel's node), with rollers in contact.
#[test]
fn roller_tangent_matches_differences() {
    let model = s_lay(600.0, 140, None);
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let mut config = solution.configuration.clone();
    // Press the pipe into the stinger unevenly so that several rollers are loaded.
    for k in 110..140 {
        config.positions[k].z += 0.05 * (0.7 * k as f64).sin();
    }
    let mut assembler = Assembler::new(&model);
    assembler.assemble(&model, &config, 1.0, true, None);
    let active = assembler
        .rollers
        .as_ref()
        .expect("rollers")
        .forces
        .iter()
        .filter(|f| **f > 0.0)
        .count();
    assert!(active >= 3, "{active} rollers loaded");
    let values = assembler.values.clone();
    let dofs = assembler.dofs.clone();
    let h = 1e-6;
    let range = NODE_DOFS * 110..NODE_DOFS * 141;
    let mut worst: f64 = 0.0;
    for column in range.clone() {
        let Some(col) = dofs.equation[column] else {
            continue;
        };
        let residuals: Vec<Vec<f64>> = [h, -h]
            .iter()
            .map(|&step| {
                let c = common::perturbed(&config, column, step);
                assembler.assemble(&model, &c, 1.0, false, None);
                assembler.residual.clone()
            })
            .collect();
        for row in range.clone() {
            let Some(r) = dofs.equation[row] else {
                continue;
            };
            let fd = (residuals[0][row] - residuals[1][row]) / (2.0 * h);
            let analytic = assembler.lu.position(r, col).map_or(0.0, |p| values[p]);
            // Relative to the entry, with a floor at the roller stiffness (1e7 N/m).
            worst = worst.max((fd - analytic).abs() / analytic.abs().max(1e7));
        }
    }
    println!("rollers loaded: {active}; worst relative tangent error {worst:.2e}");
    assert!(worst < 1e-4, "{worst:e}");
}

/// Deviation of T + w z + M²/(2EI) from its value at the tensioner, relative to the top tension: just below
/// the stinger and the worst over the last 200 m of pipe (x: vessel position, n: elements).
fn elastica_invariant_error(x: f64, n: usize) -> (f64, f64) {
    let model = s_lay(x, n, None);
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let response = Response::new(&model, &solution.configuration);
    let forces = response.rollers.clone().expect("rollers").forces;
    assert!(
        forces.iter().filter(|f| **f > 0.0).count() >= 5,
        "{forces:?}"
    );
    assert!(forces.iter().all(|f| *f >= 0.0));
    let w = model.submerged_weight(0);
    let ei = model.rod.section(0).rotational_stiffness.y;
    let positions = &solution.configuration.positions;
    let invariant = |e: usize| {
        let f = response.section_forces[e];
        let z = 0.5 * (positions[e].z + positions[e + 1].z);
        f[0] + w * z + (f[4].powi(2) + f[5].powi(2)) / (2.0 * ei)
    };
    // The last 200 m of pipe: 50 m of deck, 80 m of stinger and the free span below it.
    let below = n - 80 * n / 280;
    let tension = response.section_forces[n - 1][0];
    let top = invariant(n - 1);
    let worst = (below..n)
        .map(|e| (invariant(e) - top).abs())
        .fold(0.0, f64::max);
    println!(
        "x = {x}, n = {n}: top tension {tension:.0} N, invariant {top:.0} at the top, {:.0} below the stinger, worst {worst:.0}; rollers {:?}",
        invariant(below),
        forces.iter().map(|f| f.round()).collect::<Vec<_>>()
    );
    ((invariant(below) - top).abs() / tension, worst / tension)
}

/// Frictionless rollers do no work along the pipe: T + w z + M²/(2EI) (effective tension, submerged weight
/// w, e3 down, bending moment M) is a first integral of the elastica between concentrated normal loads and
/// stays continuous across them. From the tensioner, over the stinger's rollers, down the free span: within
/// 0.1 % of the top tension below the stinger and on it (2.5 m elements); the error on the stinger, where
/// each roller's load is shared by the spline's four nodes, shrinks at first order as the mesh is refined
/// (by 2.8 from 2.5 m to 0.625 m elements).
#[test]
fn frictionless_rollers_keep_the_elastica_invariant() {
    let (below, worst) = elastica_invariant_error(560.0, 280);
    assert!(below < 1e-3 && worst < 1e-3, "{below:e} {worst:e}");
    let (below, coarse) = elastica_invariant_error(600.0, 280);
    assert!(below < 1e-3 && coarse < 1e-3, "{below:e} {coarse:e}");
    let (below, fine) = elastica_invariant_error(600.0, 1120);
    assert!(below < 1e-3, "{below:e}");
    assert!(
        coarse > 2.2 * fine,
        "refining 2.5 m → 0.625 m elements: {coarse:e} → {fine:e}"
    );
}

/// With every dissipation off and the vessel let go, pipe, vessel and roller contacts exchange energy while
/// the pipe slides and lifts on the stinger: the total stays constant to 1e-8 of the energies in play.
#[test]
fn rollers_keep_the_energy_balance_exact() {
    // Let go: the pipe pulls the vessel back over its stinger.
    let mut sim = common::released_without_dissipation(s_lay(640.0, 140, None), 0.1);
    let start = sim.observe().energy();
    let scale = start.strain.abs() + start.gravity.abs() + start.vessel_potential.abs();
    let mut worst: f64 = 0.0;
    let mut changes = 0;
    let mut previous: Vec<bool> = sim
        .observe()
        .roller_forces()
        .expect("rollers")
        .iter()
        .map(|f| *f > 0.0)
        .collect();
    for _ in 0..200 {
        sim.step().expect("step");
        worst = worst.max((sim.observe().energy().total() - start.total()).abs() / scale);
        let now: Vec<bool> = sim
            .observe()
            .roller_forces()
            .expect("rollers")
            .iter()
            .map(|f| *f > 0.0)
            .collect();
        changes += now.iter().zip(&previous).filter(|(a, b)| a != b).count();
        previous = now;
    }
    let eta = sim.observe().vessel_values().expect("vessel")[0];
    println!(
        "energy drift {worst:.2e} of {scale:.3e} J; vessel moved {:.2} m; {changes} roller lift-offs or touches; roller energy {:.3e} J",
        eta[0] - 640.0,
        sim.observe().energy().rollers
    );
    assert!((eta[0] - 640.0).abs() > 1.0, "the vessel moves");
    assert!(changes >= 1, "contacts change during the run");
    assert!(worst < 1e-8, "energy drift {worst:e}");
}

/// On a seabed the S-lay finds its touchdown and its stinger contact together.
#[test]
fn s_lay_on_a_seabed_converges() {
    let flat = pipelay::environment::bathymetry::Bathymetry::flat(0.0).expect("flat");
    let seabed = Seabed::new(1e5, 0.0, [0.0, 0.0], 0.01, flat).expect("seabed");
    let model = s_lay(620.0, 140, Some(seabed));
    let solution = solve(&model, &StaticOptions::default());
    if let Err(e) = &solution {
        println!("{e:?}");
    }
    let solution = solution.expect("statics");
    let response = Response::new(&model, &solution.configuration);
    let touchdown = response.seabed.as_ref().expect("seabed").touchdown;
    let forces = response.rollers.clone().expect("rollers").forces;
    println!("touchdown {touchdown:?}; rollers {forces:?}");
    assert!(forces.iter().any(|f| *f > 0.0));
    let laid = touchdown.laid_length;
    assert!(laid > 100.0 && laid < 600.0, "laid length {laid}");
}

/// From a static S-lay the vessel keeps its holding thrust: the pipe barely moves, and Newton converges in a
/// step or two every time (the discrete gradient's correction term must not turn the round-off of the
/// contact energy into force where the pipe hardly moves over the rollers).
#[test]
fn a_held_s_lay_steps_in_few_iterations() {
    let model = s_lay(660.0, 280, None);
    let mut sim = common::from_statics(model, 0.2);
    let mut most = 0;
    for _ in 0..20 {
        most = most.max(sim.step().expect("step").iterations);
    }
    println!("most Newton iterations in a step: {most}");
    assert!(most <= 3, "{most}");
}
