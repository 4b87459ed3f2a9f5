//! Invariants of the energy–momentum integrator: conservation in vacuum, order of accuracy, and the
//! discrete energy balance with drag, damping, gravity, current and a driven support.
use nalgebra::Vector3;
use pipelay::assembly::configuration::Configuration;
use pipelay::dynamics::integrator::{DynamicOptions, Integrator};
use pipelay::dynamics::state::DynamicState;
use pipelay::environment::current::{Current, CurrentProfile};
use pipelay::environment::sea::Sea;
use pipelay::model::Model;
use pipelay::rod::dynamic_element::StressRule;
use pipelay::rod::section::{Section, SectionExtras};
use pipelay::rod::Rod;
use std::sync::Arc;

/// Hat function rising to 1 at t = 2.5 and back to 0 at t = 5.
fn hat(t: f64) -> f64 {
    if t <= 2.5 {
        (t / 2.5).max(0.0)
    } else {
        (2.0 - t / 2.5).max(0.0)
    }
}

/// The free-flying rod of Simo, Tarnow & Doblaré (1995): L = 10 inclined by atan(4/3), EA = GA = 1e4,
/// EI = GJ = 500, ρA = 1, J = (20, 10, 10); tip moments (0, 200, 100)·hat(t) and force (20, 0, 0)·hat(t).
fn flying_rod(elements: usize, dt: f64, rule: StressRule) -> Integrator {
    flying_rod_in(elements, dt, rule, None)
}

/// The same rod, in still water of no weight (gravity 0) with a 4 cm outer diameter and these added-mass
/// coefficients (axial, normal) if `added_mass` is given.
fn flying_rod_in(
    elements: usize,
    dt: f64,
    rule: StressRule,
    added_mass: Option<[f64; 2]>,
) -> Integrator {
    let extras = SectionExtras {
        inertia: [20.0, 10.0, 10.0],
        outer_diameter: added_mass.map_or(0.0, |_| 0.04),
        added_mass: added_mass.unwrap_or_default(),
        ..SectionExtras::default()
    };
    let section = Section::new(1e4, [1e4; 2], 500.0, [500.0; 2], 1.0, extras).expect("section");
    let rod = Rod::straight(
        Vector3::new(6.0, 0.0, 0.0),
        Vector3::new(0.0, 0.0, 8.0),
        elements,
        section,
    )
    .expect("rod");
    let sea = added_mass.map(|_| Sea::new(100.0, 1025.0, None, None).expect("sea"));
    let mut model = Model::new(rod, sea, 0.0).expect("model");
    let scale = Arc::new(|t: f64| Ok(hat(t)));
    model
        .point_load(
            -1,
            Vector3::new(20.0, 0.0, 0.0),
            Vector3::new(0.0, 200.0, 100.0),
            Some(scale),
        )
        .expect("load");
    let state =
        DynamicState::at_rest(&model, Configuration::reference(&model), 0.0).expect("state");
    let options = DynamicOptions {
        time_step: dt,
        stress_rule: rule,
        ..DynamicOptions::default()
    };
    Integrator::new(model, state, options).expect("integrator")
}

/// After the loads stop, energy, linear and angular momentum stay constant to 1e-9 relative over
/// thousands of steps while the rod spins and flexes through large rotations.
#[test]
fn free_flight_conserves_energy_and_momentum() {
    let mut rod = flying_rod(10, 0.05, StressRule::AverageStrain);
    while rod.state().time < 5.0 - 1e-9 {
        rod.step().expect("step");
    }
    let energy = rod.observe().energy().total();
    let linear = rod.observe().linear_momentum();
    let angular = rod.observe().angular_momentum();
    assert!(
        energy > 100.0 && angular.norm() > 100.0,
        "the loads set it moving: E = {energy}, J = {angular}"
    );
    let mut worst_energy: f64 = 0.0;
    let mut worst_momentum: f64 = 0.0;
    let mut largest_rotation: f64 = 0.0;
    for _ in 0..2000 {
        rod.step().expect("step");
        worst_energy = worst_energy.max((rod.observe().energy().total() - energy).abs() / energy);
        worst_momentum = worst_momentum
            .max((rod.observe().linear_momentum() - linear).norm() / linear.norm())
            .max((rod.observe().angular_momentum() - angular).norm() / angular.norm());
        largest_rotation = largest_rotation.max(rod.state().configuration.rotations[10].angle());
    }
    println!("free flight: energy drift {worst_energy:.2e}, momentum drift {worst_momentum:.2e}, tip rotation up to {largest_rotation:.2} rad");
    assert!(
        largest_rotation > 3.0,
        "large rotations: {largest_rotation}"
    );
    assert!(worst_energy < 1e-9, "energy drift {worst_energy:e}");
    assert!(worst_momentum < 1e-9, "momentum drift {worst_momentum:e}");
}

/// The flying rod in still water (no gravity, no drag), with added mass across the pipe only (C_a axial 0,
/// normal 1): its kinetic energy ½vᵀM(t)v depends on each node's axis t, and after the loads stop energy and
/// the linear momentum Σ M(t)v stay constant to round-off while it tumbles. With the axial coefficient equal to
/// the normal one the added mass is isotropic, and the same loads move the rod otherwise.
#[test]
fn free_flight_in_water_conserves_energy_with_added_mass_by_direction() {
    let flight = |added_mass: [f64; 2]| {
        let mut rod = flying_rod_in(10, 0.05, StressRule::AverageStrain, Some(added_mass));
        while rod.state().time < 5.0 - 1e-9 {
            rod.step().expect("step");
        }
        rod
    };
    let mut rod = flight([0.0, 1.0]);
    let energy = rod.observe().energy().total();
    let linear = rod.observe().linear_momentum();
    let (mut worst_energy, mut worst_momentum): (f64, f64) = (0.0, 0.0);
    for _ in 0..1000 {
        rod.step().expect("step");
        worst_energy = worst_energy.max((rod.observe().energy().total() - energy).abs() / energy);
        worst_momentum =
            worst_momentum.max((rod.observe().linear_momentum() - linear).norm() / linear.norm());
    }
    println!("free flight in water: energy drift {worst_energy:.2e}, momentum drift {worst_momentum:.2e}");
    assert!(worst_energy < 1e-9, "energy drift {worst_energy:e}");
    assert!(worst_momentum < 1e-9, "momentum drift {worst_momentum:e}");
    let isotropic = flight([1.0, 1.0]);
    let apart = (isotropic.state().configuration.positions[10]
        - flight([0.0, 1.0]).state().configuration.positions[10])
        .norm();
    assert!(
        apart > 1e-2,
        "the axial coefficient changes the motion: tips {apart} m apart"
    );
}

/// The plain midpoint rule (stresses of the midpoint configuration) conserves momentum but not energy.
#[test]
fn plain_midpoint_rule_does_not_conserve_energy() {
    let mut rod = flying_rod(10, 0.05, StressRule::MidpointConfiguration);
    while rod.state().time < 5.0 - 1e-9 {
        rod.step().expect("step");
    }
    let energy = rod.observe().energy().total();
    let angular = rod.observe().angular_momentum();
    let mut worst_energy: f64 = 0.0;
    let mut worst_momentum: f64 = 0.0;
    for _ in 0..400 {
        match rod.step() {
            Ok(_) => {}
            Err(_) => {
                worst_energy = f64::INFINITY;
                break;
            }
        }
        worst_energy = worst_energy.max((rod.observe().energy().total() - energy).abs() / energy);
        worst_momentum = worst_momentum
            .max((rod.observe().angular_momentum() - angular).norm() / angular.norm());
    }
    println!(
        "plain midpoint: energy error {worst_energy:.2e}, momentum drift {worst_momentum:.2e}"
    );
    assert!(
        worst_energy > 1e-4,
        "midpoint energy error {worst_energy:e}"
    );
    assert!(worst_momentum < 1e-8 || worst_energy.is_infinite());
}

/// Second order in time: errors at t = 3 s fall by four when Δt halves.
#[test]
fn the_scheme_is_second_order_in_time() {
    let tip = |dt: f64| {
        let mut rod = flying_rod(6, dt, StressRule::AverageStrain);
        let steps = (3.0 / dt).round() as usize;
        for _ in 0..steps {
            rod.step().expect("step");
        }
        rod.state().configuration.positions[6]
    };
    let reference = tip(0.05 / 16.0);
    let errors: Vec<f64> = [0.05, 0.025, 0.0125]
        .iter()
        .map(|&dt| (tip(dt) - reference).norm())
        .collect();
    println!("time errors {errors:?}");
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        println!("order {order:.3}");
        assert!((order - 2.0).abs() < 0.15, "order {order} from {errors:?}");
    }
}

/// A pipe in water with gravity, a sheared current, drag, rotational damping, added mass and a driven top:
/// every step satisfies E_{n+1} − E_n = W_supplied − D with D ≥ 0.
#[test]
fn energy_balance_holds_every_step_with_drag_and_a_driven_top() {
    let section = Section::pipe(
        0.3,
        0.02,
        7850.0,
        207e9,
        0.3,
        1025.0,
        [0.1, 1.2],
        [0.0, 1.0],
    )
    .expect("pipe");
    let section = Section {
        rotational_damping: Vector3::new(50.0, 50.0, 50.0),
        ..section
    };
    let rod = Rod::straight(
        Vector3::zeros(),
        Vector3::new(0.0, 0.0, -100.0),
        20,
        section,
    )
    .expect("rod");
    let current = Current::new(
        CurrentProfile::Linear {
            surface: Vector3::new(0.5, -0.8, 0.0),
        },
        0.0,
    )
    .expect("current");
    let sea = Sea::new(120.0, 1025.0, Some(current), None).expect("sea");
    let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
    model.pin("A", None).expect("pin");
    model
        .drive(
            "B",
            Arc::new(|t: f64| {
                Ok(Vector3::new(
                    3.0 * (0.8 * t).sin(),
                    0.0,
                    -100.0 + 0.5 * (1.3 * t).sin(),
                ))
            }),
            Some(Arc::new(|t: f64| {
                Ok(Vector3::new(
                    2.4 * (0.8 * t).cos(),
                    0.0,
                    0.65 * (1.3 * t).cos(),
                ))
            })),
            None,
        )
        .expect("drive");
    let state =
        DynamicState::at_rest(&model, Configuration::reference(&model), 0.0).expect("state");
    let options = DynamicOptions {
        time_step: 0.05,
        ..DynamicOptions::default()
    };
    let mut sim = Integrator::new(model, state, options).expect("integrator");
    let mut previous = (
        sim.observe().energy().total(),
        sim.ledger().supplied_work(),
        sim.ledger().dissipated(),
    );
    let scale = sim.model().submerged_weight(0) * 100.0 * 100.0;
    let mut worst: f64 = 0.0;
    for _ in 0..400 {
        sim.step().expect("step");
        let now = (
            sim.observe().energy().total(),
            sim.ledger().supplied_work(),
            sim.ledger().dissipated(),
        );
        let imbalance = (now.0 - previous.0) - ((now.1 - previous.1) - (now.2 - previous.2));
        assert!(
            now.2 - previous.2 >= 0.0,
            "dissipation must not be negative"
        );
        worst = worst.max(imbalance.abs() / scale);
        previous = now;
    }
    println!(
        "energy balance: worst per-step imbalance {worst:.2e} of wL², supplied {:.4e} J, dissipated {:.4e} J",
        sim.ledger().supplied_work(),
        sim.ledger().dissipated()
    );
    assert!(sim.ledger().dissipated() > 0.0 && sim.ledger().supplied_work().abs() > 0.0);
    assert!(
        worst < 1e-10,
        "worst per-step imbalance {worst:e} of the weight scale"
    );
}
