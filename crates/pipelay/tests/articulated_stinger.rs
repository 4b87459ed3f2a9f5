//! An articulated stinger: hinged sections under an S-lay pipe, in statics (closed-form hinge angle, moment
//! balance, tangent) and in time (the energy ledger with the sections moving).
mod common;

use nalgebra::{Rotation3, Unit, Vector3, Vector6};
use pipelay::assembly::assembler::Assembler;
use pipelay::environment::sea::Sea;
use pipelay::model::Model;
use pipelay::rod::{section::Section, Rod};
use pipelay::statics::solve::{solve, StaticOptions};
use pipelay::vessel::articulation::{Articulation, StingerSection};
use pipelay::vessel::lay::{stinger_rollers, LayEquipment};
use pipelay::vessel::rigid_body::Vessel;

/// The S-lay of `tests/rollers.rs` (a 0.6 m × 30 mm pipe in 150 m of water, a 100 m-radius, 80 m stinger of 12
/// rollers 40 m aft of CO) with the stinger's last 50 m in `sections` hinged sections.
fn articulated(vessel_x: f64, sections: &[StingerSection]) -> Model {
    let section =
        Section::pipe(0.6, 0.03, 7850.0, 207e9, 0.3, 0.0, [0.0, 1.0], [0.0, 1.0]).expect("pipe");
    let rod = Rod::straight(
        Vector3::zeros(),
        Vector3::new(700.0, 0.0, 0.0),
        140,
        section,
    )
    .expect("rod");
    let sea = Sea::new(150.0, 1025.0, None, None).expect("sea");
    let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
    model.pin("A", None).expect("pin");
    let (radius, origin, angle) = (100.0, Vector3::new(-40.0, 0.0, -6.0), 0.0);
    let rollers = stinger_rollers(radius, 80.0, 12, origin, angle, 0.25).expect("stinger");
    let fixed = 80.0 - sections.iter().map(|s| s.length).sum::<f64>();
    let articulation =
        Articulation::new(radius, origin, angle, fixed, sections.to_vec()).expect("sections");
    let mut lay = LayEquipment::s_lay(Vector3::new(10.0, 0.0, -6.3), rollers, 1e7).expect("lay");
    lay.articulation = Some(articulation);
    lay.assign_sections();
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

fn section(length: f64, mass: f64, buoyancy: f64, stiffness: f64) -> StingerSection {
    StingerSection::new(length, mass, buoyancy, stiffness, [-0.5, 0.5], 0.0).expect("section")
}

/// One hinged section the pipe has left, under its own weight less buoyancy W at its chord's middle a from
/// the hinge: k φ = W a cos(α + φ), α the chord's slope below the horizontal at φ = 0 (with the vessel's
/// trim), to 1e-6.
#[test]
fn a_section_under_its_weight_takes_its_closed_form_angle() {
    let (k, mass, buoyancy) = (2e7, 4e4, 1e5);
    let model = articulated(600.0, &[section(20.0, mass, buoyancy, k)]);
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let config = &solution.configuration;
    let phi = config.hinge_angles[0];
    let attachment = model.vessel.as_ref().expect("vessel");
    let articulation = attachment
        .lay
        .as_ref()
        .and_then(|l| l.articulation.as_ref())
        .expect("art");
    let response = pipelay::response::configuration::Response::new(&model, config);
    let forces = response.rollers.expect("rollers").forces;
    let lay = attachment.lay.as_ref().expect("lay");
    let on_section: f64 = lay
        .rollers
        .iter()
        .zip(&forces)
        .filter(|(r, _)| r.section == Some(0))
        .map(|(_, f)| f)
        .sum();
    assert_eq!(on_section, 0.0, "the pipe must have left the section");
    // The chord's middle from the hinge in the world frame at φ = 0: Λ_B (c − h) (z down).
    let body =
        pipelay::vessel::coupling::body_rotation(attachment, &config.rotations[attachment.node]);
    let hinge = articulation.chain.hinges[0];
    let middle = 0.5 * (hinge + articulation.ends[0]);
    let weight = mass * 9.81 - buoyancy;
    let lever = |phi: f64| {
        let turn = Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::y()), phi);
        let arm = body * (turn * (middle - hinge));
        // The moment of a downward (+z) force W about the hinge, about the body's lateral axis.
        (body * Vector3::y()).dot(&arm.cross(&(Vector3::z() * weight)))
    };
    // k φ = moment: bisection.
    let (mut low, mut high) = (-0.5, 0.5);
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if k * mid - lever(mid) > 0.0 {
            high = mid;
        } else {
            low = mid;
        }
    }
    let expected = 0.5 * (low + high);
    println!("hinge angle {phi:.9} rad, closed form {expected:.9} rad");
    assert!(phi > 0.01, "the section hangs down: {phi}");
    assert!(
        (phi - expected).abs() < 1e-6 * expected.abs(),
        "{phi} vs {expected}"
    );
}

/// The assembled static tangent matches central differences of the residual on the nodes the rollers touch,
/// the vessel's node and the hinge angles, with the pipe resting on both sections.
#[test]
fn hinged_roller_tangent_matches_differences() {
    let model = articulated(
        600.0,
        &[section(25.0, 3e4, 2e5, 1e8), section(25.0, 3e4, 2e5, 1e8)],
    );
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let mut config = solution.configuration.clone();
    for k in 110..140 {
        config.positions[k].z += 0.05 * (0.7 * k as f64).sin();
    }
    config.hinge_angles = vec![0.01, -0.02];
    let mut assembler = Assembler::new(&model);
    assembler.assemble(&model, &config, 1.0, true, None);
    let values = assembler.values.clone();
    let dofs = assembler.dofs.clone();
    let nodes = model.rod.node_count();
    let dofs_of_interest: Vec<usize> = (6 * 110..6 * nodes)
        .chain(6 * nodes..6 * nodes + 2)
        .collect();
    let mut worst: f64 = 0.0;
    for &column in &dofs_of_interest {
        let Some(col) = dofs.equation[column] else {
            continue;
        };
        let h = if column >= 6 * nodes { 1e-8 } else { 1e-6 };
        let residuals: Vec<Vec<f64>> = [h, -h]
            .iter()
            .map(|&step| {
                let c = common::perturbed(&config, column, step);
                assembler.assemble(&model, &c, 1.0, false, None);
                assembler.residual.clone()
            })
            .collect();
        for &row in &dofs_of_interest {
            let Some(r) = dofs.equation[row] else {
                continue;
            };
            let fd = (residuals[0][row] - residuals[1][row]) / (2.0 * h);
            let analytic = assembler.lu.position(r, col).map_or(0.0, |p| values[p]);
            worst = worst.max((fd - analytic).abs() / analytic.abs().max(1e7));
        }
    }
    println!("worst relative tangent error {worst:.2e}");
    assert!(worst < 1e-4, "{worst:e}");
}

/// Released from statics without dissipation, the pipe pulls the vessel and the free-swinging sections move:
/// the storage function (the sections' kinetic, potential and hinge energy included) is conserved.
#[test]
fn the_ledger_is_exact_with_the_sections_moving() {
    let model = articulated(
        600.0,
        &[section(25.0, 3e4, 2e5, 1e6), section(25.0, 3e4, 2e5, 1e6)],
    );
    let mut sim = common::released_without_dissipation(model, 0.1);
    let start = sim.observe().energy();
    let angles_start = sim.state().configuration.hinge_angles.clone();
    let mut moved: f64 = 0.0;
    for _ in 0..100 {
        sim.step().expect("step");
        for (a, b) in sim
            .state()
            .configuration
            .hinge_angles
            .iter()
            .zip(&angles_start)
        {
            moved = moved.max((a - b).abs());
        }
    }
    let end = sim.observe().energy();
    let ledger = sim.ledger();
    let change = end.total() - start.total();
    let balance = change - (ledger.supplied_work() - ledger.dissipated());
    println!(
        "hinges moved up to {moved:.3e} rad; stinger energy {:.6e} → {:.6e} J; ΔE {change:.6e} J, \
         balance {balance:.3e} J",
        start.stinger, end.stinger
    );
    assert!(moved > 1e-4, "the sections must move: {moved}");
    assert!((end.stinger - start.stinger).abs() > 1.0);
    assert!(
        balance.abs() < 1e-7 * end.total().abs().max(1.0),
        "{balance}"
    );
}
