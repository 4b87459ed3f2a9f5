//! Validation of the static solver against analytic solutions (the validation ladder's first rung).
use nalgebra::Vector3;
use pipelay::assembly::assembler::Assembler;
use pipelay::assembly::configuration::Configuration;
use pipelay::environment::current::{Current, CurrentProfile};
use pipelay::environment::sea::Sea;
use pipelay::model::Model;
use pipelay::response::configuration::Response;
use pipelay::rod::attachment::Attachment;
use pipelay::rod::section::{Section, SectionExtras};
use pipelay::rod::Rod;
use pipelay::so3::{exp_quat, log_quat};
use pipelay::statics::catenary::Catenary;
use pipelay::statics::solve::{solve, Start, StaticOptions};
use pipelay::Error;
use std::f64::consts::PI;

mod common;

fn beam_section(ei: f64, ga: f64) -> Section {
    Section::new(1e9, [ga; 2], ei, [ei; 2], 1.0, SectionExtras::default()).expect("valid section")
}

/// A clamped cantilever of length `length` along e1 with `n` elements, no gravity.
fn cantilever(length: f64, n: usize, section: Section) -> Model {
    let rod =
        Rod::straight(Vector3::zeros(), Vector3::new(length, 0.0, 0.0), n, section).expect("rod");
    let mut model = Model::new(rod, None, 0.0).expect("model");
    model.clamp("A", None, None).expect("clamp");
    model
}

fn tip(model: &Model) -> (Vector3<f64>, Vector3<f64>) {
    let solution = solve(model, &StaticOptions::default()).expect("converges");
    let last = model.rod.element_count();
    let config = solution.configuration;
    (config.positions[last], log_quat(&config.rotations[last]))
}

/// Roll-up under an end moment M: the rod bends into an arc of radius EI/M. The discrete nodes lie on a
/// circle of radius R_h = L0 / (2 sin(κL0/2)); against the exact circle the error falls as h².
#[test]
fn end_moment_rolls_the_cantilever_into_a_circle() {
    let (length, ei) = (10.0, 2.0e4);
    let mut errors = Vec::new();
    for n in [10, 20, 40] {
        let mut model = cantilever(length, n, beam_section(ei, 1e9));
        let moment = PI * ei / length; // half circle
        model
            .point_load(-1, Vector3::zeros(), Vector3::new(0.0, 0.0, moment), None)
            .expect("load");
        let (position, rotation) = tip(&model);
        let radius = ei / moment;
        let exact = Vector3::new(0.0, 2.0 * radius, 0.0);
        assert!(
            (rotation - Vector3::new(0.0, 0.0, PI)).norm() < 1e-6
                || (rotation.norm() - PI).abs() < 1e-6
        );
        errors.push((position - exact).norm() / length);
    }
    let order = (errors[1] / errors[2]).log2();
    assert!(errors[2] < 2e-3, "half circle error {errors:?}");
    assert!((order - 2.0).abs() < 0.1, "order {order}");

    // Full circle: the tip comes back to the root, and the tip frame has turned 2π.
    let n = 40;
    let mut model = cantilever(length, n, beam_section(ei, 1e9));
    model
        .point_load(
            -1,
            Vector3::zeros(),
            Vector3::new(0.0, 0.0, 2.0 * PI * ei / length),
            None,
        )
        .expect("load");
    let (position, rotation) = tip(&model);
    assert!(position.norm() < 1e-8 * length, "tip at {position}");
    assert!(rotation.norm() < 1e-8, "tip rotation {rotation}");
}

/// Small tip load: Timoshenko's δ = PL³/(3EI) + PL/(GA). One-point linear elements give PL³/(12EI n²) less (one element: PL³/(4EI)).
#[test]
fn small_tip_load_matches_timoshenko_beam_theory() {
    let (length, ei, ga, load): (f64, f64, f64, f64) = (2.0, 1.0e6, 5.0e6, 1.0);
    let exact = load * length.powi(3) / (3.0 * ei) + load * length / ga;
    let mut errors = Vec::new();
    for n in [4, 8, 16, 32] {
        let mut model = cantilever(length, n, beam_section(ei, ga));
        model
            .point_load(-1, Vector3::new(0.0, load, 0.0), Vector3::zeros(), None)
            .expect("load");
        let deflection = tip(&model).0.y;
        let predicted = exact - load * length.powi(3) / (12.0 * ei * (n * n) as f64);
        assert!(
            (deflection - predicted).abs() < 1e-5 * exact,
            "n {n}: {deflection} vs {predicted}"
        );
        errors.push((deflection - exact).abs() / exact);
    }
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!((order - 2.0).abs() < 0.02, "order {order}");
    }
    assert!(errors[3] < 1e-3);
}

fn hanging_pipe(n: usize, ei: f64, clamped: bool) -> Model {
    let mut model = common::flooded_pipe(n);
    model.rod.sections[0].rotational_stiffness = Vector3::new(ei, ei, ei);
    let top = Vector3::new(850.0, 0.0, -800.0);
    if clamped {
        model.clamp("A", None, None).expect("clamp");
        model.clamp("B", Some(top), None).expect("clamp");
    } else {
        model.pin("A", None).expect("pin");
        model.pin("B", Some(top)).expect("pin");
    }
    model
}

/// A pipe with negligible bending stiffness against Irvine's elastic catenary, from both starts.
#[test]
fn slack_pipe_matches_the_elastic_catenary() {
    let model = hanging_pipe(200, 1.0, false);
    let catenary = Catenary::solve(
        Vector3::zeros(),
        Vector3::new(850.0, 0.0, -800.0),
        1200.0,
        model.submerged_weight(0),
        model.rod.section(0).translational_stiffness.x,
    )
    .expect("catenary");
    for start in [Start::Auto, Start::Reference] {
        let options = StaticOptions {
            start,
            ..StaticOptions::default()
        };
        let solution = solve(&model, &options).expect("converges");
        let response = Response::new(&model, &solution.configuration);
        let top = response.nodal_reactions[200];
        let expected = catenary.force_at_b();
        let error = (top.fixed_rows::<3>(0) - expected).norm() / expected.norm();
        assert!(
            error < 2e-4,
            "{start:?}: top force {top} vs {expected}, error {error:e}"
        );
        let horizontal = (top.x.powi(2) + top.y.powi(2)).sqrt();
        assert!(
            (horizontal - catenary.horizontal_tension()).abs()
                < 2e-4 * catenary.horizontal_tension()
        );
    }
}

/// The 1200 m steel pipe converges from its straight reference, pinned and clamped, and the supports
/// carry exactly its submerged weight.
#[test]
fn steel_pipe_converges_from_the_straight_reference() {
    for clamped in [false, true] {
        for n in [10, 100] {
            let model = hanging_pipe(n, 244.27e6, clamped);
            let options = StaticOptions {
                start: Start::Reference,
                ..StaticOptions::default()
            };
            let solution =
                solve(&model, &options).unwrap_or_else(|e| panic!("n {n} clamped {clamped}: {e}"));
            let response = Response::new(&model, &solution.configuration);
            let weight = model.submerged_weight(0) * 1200.0;
            let carried = response.nodal_reactions[0] + response.nodal_reactions[n];
            assert!(
                (carried.z - weight).abs() < 1e-6 * weight,
                "carried {carried} of {weight}"
            );
            assert!(carried.x.abs() < 1e-6 * weight);
            // The same state from the catenary start.
            let from_catenary = solve(&model, &StaticOptions::default()).expect("converges");
            assert!(from_catenary.from_catenary);
            let gap = from_catenary
                .configuration
                .positions
                .iter()
                .zip(&solution.configuration.positions)
                .map(|(a, b)| (a - b).norm())
                .fold(0.0, f64::max);
            assert!(
                gap < 1e-6,
                "n {n} clamped {clamped}: states differ by {gap} m"
            );
        }
    }
}

/// A clamped pipe of three elements in a sheared current, and a configuration away from its reference.
fn pipe_in_a_sheared_current() -> (Model, Configuration) {
    let section =
        Section::pipe(0.6, 0.015, 7850.0, 207e9, 0.3, 0.0, [0.3, 1.2], [0.0, 1.0]).expect("pipe");
    let rod =
        Rod::straight(Vector3::zeros(), Vector3::new(30.0, 0.0, -20.0), 3, section).expect("rod");
    let current = Current::new(
        CurrentProfile::Linear {
            surface: Vector3::new(0.4, -0.9, 0.0),
        },
        0.0,
    )
    .expect("current");
    let sea = Sea::new(50.0, 1025.0, Some(current), None).expect("sea");
    let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
    model.clamp("A", None, None).expect("clamp");
    let mut config = Configuration::reference(&model);
    for (a, (x, r)) in config
        .positions
        .iter_mut()
        .zip(config.rotations.iter_mut())
        .enumerate()
        .skip(1)
    {
        *x += Vector3::new(0.3 * a as f64, -0.5, 0.2 * (a * a) as f64);
        *r = exp_quat(&Vector3::new(0.2, -0.4 * a as f64, 0.3)) * *r;
    }
    (model, config)
}

/// The assembled tangent (elements, drag in a sheared current) equals finite differences of the
/// assembled residual, for every free DOF.
#[test]
fn assembled_tangent_matches_finite_differences() {
    let (model, config) = pipe_in_a_sheared_current();
    let mut assembler = Assembler::new(&model);
    let (worst, largest) = common::tangent_error(&model, &config, &mut assembler, 1e-6);
    assert!(worst < 1e-6 * largest, "worst {worst:e} of {largest:e}");
}

/// So it does with a clump on the line, whose drag changes with its depth in the sheared current.
#[test]
fn assembled_tangent_with_an_attachment_matches_finite_differences() {
    let (mut model, config) = pipe_in_a_sheared_current();
    // A drag area far beyond any clump's, so that its depth derivative stands out of the elements' stiffness.
    let clump = Attachment::new(17.0, 5e3, 1.5, 2e4, 1.0).expect("clump");
    model.attach(clump).expect("attach");
    let mut assembler = Assembler::new(&model);
    let (worst, largest) = common::tangent_error(&model, &config, &mut assembler, 1e-6);
    assert!(worst < 1e-6 * largest, "worst {worst:e} of {largest:e}");
}

/// A rod that nothing holds has no static equilibrium: the solver says which input is missing.
#[test]
fn unsupported_rod_is_refused() {
    let rod = Rod::straight(
        Vector3::zeros(),
        Vector3::new(10.0, 0.0, 0.0),
        4,
        beam_section(1e4, 1e8),
    )
    .expect("rod");
    let model = Model::new(rod, None, 9.81).expect("model");
    match solve(&model, &StaticOptions::default()) {
        Err(Error::Input { argument, .. }) => assert_eq!(argument, "supports"),
        other => panic!("expected an input error, got {other:?}"),
    }
}

/// A load the supports cannot carry (a pinned–pinned straight rod pushed along its axis far beyond
/// buckling, then sideways) fails as a ConvergenceError with the load factor reached, not a panic.
#[test]
fn impossible_equilibrium_raises_a_convergence_error() {
    let rod = Rod::straight(
        Vector3::zeros(),
        Vector3::new(10.0, 0.0, 0.0),
        4,
        beam_section(1e4, 1e8),
    )
    .expect("rod");
    let mut model = Model::new(rod, None, 0.0).expect("model");
    model.pin("A", None).expect("pin");
    // A moment at a pinned end that nothing resists.
    model
        .point_load(0, Vector3::zeros(), Vector3::new(0.0, 0.0, 1e3), None)
        .expect("load");
    match solve(&model, &StaticOptions::default()) {
        Err(Error::Convergence { reached, .. }) => assert!(reached < 1.0),
        other => panic!("expected a convergence error, got {other:?}"),
    }
}

#[test]
fn bad_input_names_the_argument() {
    let section = beam_section(1e4, 1e8);
    let cases: Vec<(Result<Rod, Error>, &str)> = vec![
        (
            Rod::straight(Vector3::zeros(), Vector3::x(), 0, section.clone()),
            "elements",
        ),
        (
            Rod::new(vec![Vector3::zeros(), Vector3::zeros()], section.clone()),
            "nodes",
        ),
        (
            Rod::new(
                vec![Vector3::zeros(), Vector3::new(f64::NAN, 0.0, 0.0)],
                section.clone(),
            ),
            "nodes",
        ),
    ];
    for (result, argument) in cases {
        match result {
            Err(Error::Input { argument: a, .. }) => assert_eq!(a, argument),
            other => panic!("expected an input error on {argument}, got {other:?}"),
        }
    }
    let bad_sections = [
        (
            Section::new(-1.0, [1.0; 2], 1.0, [1.0; 2], 1.0, SectionExtras::default()),
            "EA",
        ),
        (
            Section::new(
                1.0,
                [1.0; 2],
                1.0,
                [0.0, 1.0],
                1.0,
                SectionExtras::default(),
            ),
            "EI",
        ),
        (
            Section::new(
                1.0,
                [1.0; 2],
                1.0,
                [1.0; 2],
                f64::INFINITY,
                SectionExtras::default(),
            ),
            "mass",
        ),
    ];
    for (result, argument) in bad_sections {
        assert!(matches!(result, Err(Error::Input { argument: a, .. }) if a == argument));
    }
    let rod = Rod::straight(Vector3::zeros(), Vector3::x(), 2, section).expect("rod");
    let mut model = Model::new(rod, None, 9.81).expect("model");
    assert!(
        matches!(model.clamp("C", None, None), Err(Error::Input { argument, .. }) if argument == "end")
    );
    assert!(
        matches!(model.point_load(3, Vector3::zeros(), Vector3::zeros(), None), Err(Error::Input { argument, .. }) if argument == "node")
    );
}

/// A stage's statics from a configuration far from equilibrium (the straight reference along the seabed, the
/// J-lay tower 1 km away and 800 m up): Newton at full load and relaxation from it fail, and the paths of a
/// model's first statics reach the equilibrium the model's own statics find.
#[test]
fn statics_from_far_from_equilibrium_take_the_paths_of_a_first_solve() {
    let mut model = common::flooded_pipe(60);
    model.pin("A", None).expect("pin");
    let tower = pipelay::vessel::lay::LayEquipment::j_lay(Vector3::new(-40.0, 5.0, -10.0), 0.4)
        .expect("tower");
    model
        .attach_vessel(
            "B",
            pipelay::vessel::rigid_body::Vessel::osv(),
            nalgebra::Vector6::new(850.0, 0.0, -800.0, 0.0, 0.0, 0.0),
            Vector3::zeros(),
            None,
            vec![],
            Some(tower),
        )
        .expect("vessel");
    let options = StaticOptions::default();
    let first = solve(&model, &options).expect("statics");
    let far = Configuration::reference(&model);
    let slips = vec![nalgebra::Vector2::zeros(); model.rod.node_count()];
    let plastic = vec![Vec::new(); model.rod.element_count()];
    let again = pipelay::statics::solve::solve_from(&model, &options, far, &slips, &plastic, 0.0)
        .expect("statics from far");
    let apart = first
        .configuration
        .positions
        .iter()
        .zip(&again.configuration.positions)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    println!(
        "from the straight reference: {} iterations, {} relaxations; {apart:.3e} m from the first statics",
        again.iterations, again.relaxations
    );
    assert!(apart < 1e-6, "{apart}");
    // Newton and relaxation from the reference came first, and failed.
    assert!(again.relaxations >= 1 && again.iterations > first.iterations);
}
