//! Statics out of the pipe's plane: a current across the lay, the paths statics takes there, and the check that
//! refuses a converged state no lay spread holds.
mod common;

use nalgebra::{Matrix6, UnitQuaternion, Vector3, Vector6};
use pipelay::assembly::assembler::Assembler;
use pipelay::assembly::configuration::Configuration;
use pipelay::dynamics::integrator::{DynamicOptions, Integrator};
use pipelay::dynamics::state::DynamicState;
use pipelay::environment::bathymetry::Bathymetry;
use pipelay::environment::current::{Current, CurrentProfile};
use pipelay::environment::sea::Sea;
use pipelay::environment::seabed::Seabed;
use pipelay::error::Error;
use pipelay::model::Model;
use pipelay::response::configuration::Response;
use pipelay::rod::{section::Section, Rod};
use pipelay::statics::newton::Newton;
use pipelay::statics::physical::{check, Unphysical};
use pipelay::statics::relaxation::relax;
use pipelay::statics::solve::{solve, Start, StaticOptions, StaticSolution};
use pipelay::vessel::control::{Pid, Reference};
use pipelay::vessel::lay::{stinger_rollers, LayEquipment};
use pipelay::vessel::rigid_body::Vessel;

/// A sea of `depth` with a seabed of soft clay (`friction` along and across) and a uniform current `current`
/// (m/s, in e).
fn sea(depth: f64, current: Option<Vector3<f64>>, friction: f64) -> Sea {
    let bathymetry = Bathymetry::plane(0.0, nalgebra::Vector2::zeros()).expect("plane");
    let seabed = Seabed::new(1e5, 0.0, [friction; 2], 0.02, bathymetry).expect("seabed");
    let current = current.map(|u| Current::new(CurrentProfile::Uniform(u), 0.0).expect("current"));
    Sea::new(depth, 1025.0, current, Some(seabed)).expect("sea")
}

/// The 0.6 m × 30 mm empty steel pipe of the S-lay example over a 200 m-radius, 100 m stinger of 15 rollers, in
/// 150 m of water, the vessel at x = 660 m held by its holding thrust.
fn s_lay(current: Option<Vector3<f64>>) -> Model {
    let section =
        Section::pipe(0.6, 0.03, 7850.0, 207e9, 0.3, 0.0, [0.0, 1.0], [0.0, 1.0]).expect("pipe");
    let rod = Rod::straight(
        Vector3::zeros(),
        Vector3::new(700.0, 0.0, 0.0),
        280,
        section,
    )
    .expect("rod");
    let mut model = Model::new(rod, Some(sea(150.0, current, 0.5)), 9.81).expect("model");
    model.pin("A", None).expect("pin");
    let rollers = stinger_rollers(200.0, 100.0, 15, Vector3::new(-40.0, 0.0, -6.0), 0.0, 0.25)
        .expect("stinger");
    let lay = LayEquipment::s_lay(Vector3::new(10.0, 0.0, -6.3), rollers, 1e7).expect("lay");
    let eta = Vector6::new(660.0, 0.0, -150.0, 0.0, 0.0, 0.0);
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

/// The 0.6 m × 25 mm empty pipe of the J-lay examples in 800 m of water from a tower leaning 0.2 rad, the vessel
/// at x = 880 m, held by `controller` (its holding thrust without one), on a seabed with `friction`.
fn j_lay(current: Option<Vector3<f64>>, controller: Option<Pid>, friction: f64) -> Model {
    let section =
        Section::pipe(0.6, 0.025, 7850.0, 207e9, 0.3, 0.0, [0.0, 1.0], [0.0, 1.0]).expect("pipe");
    let rod = Rod::straight(
        Vector3::zeros(),
        Vector3::new(1400.0, 0.0, 0.0),
        140,
        section,
    )
    .expect("rod");
    let mut model = Model::new(rod, Some(sea(800.0, current, friction)), 9.81).expect("model");
    model.pin("A", None).expect("pin");
    let tower = LayEquipment::j_lay(Vector3::new(0.0, 0.0, -10.0), 0.2).expect("tower");
    let eta = Vector6::new(880.0, 0.0, -800.0, 0.0, 0.0, 0.0);
    model
        .attach_vessel(
            "B",
            Vessel::osv(),
            eta,
            Vector3::zeros(),
            controller,
            vec![],
            Some(tower),
        )
        .expect("vessel");
    model
}

fn top_tension(model: &Model, config: &Configuration) -> f64 {
    Response::new(model, config)
        .section_forces
        .last()
        .expect("elements")[0]
}

/// The cause of statics failing with any current across the lay: the continuation from a cable scaled the
/// torsional stiffness with the bending one, so the pipe's twist was free and a load out of its plane sent
/// Newton's correction turning by thousands of radians. A current of 5 cm/s across a J-lay now solves, to the
/// in-plane state up to the drag's small sideways push (0.8 N/m against a tension of 600 kN).
#[test]
fn a_faint_current_across_a_j_lay_leaves_the_in_plane_state() {
    let calm = j_lay(None, None, 0.5);
    let across = j_lay(Some(Vector3::new(0.0, 0.05, 0.0)), None, 0.5);
    let options = StaticOptions::default();
    let still = solve(&calm, &options).expect("calm statics");
    let faint = solve(&across, &options).expect("statics with a faint cross current");
    let (t0, t1) = (
        top_tension(&calm, &still.configuration),
        top_tension(&across, &faint.configuration),
    );
    assert!((t1 - t0).abs() < 1e-4 * t0, "top tension {t1} against {t0}");
    let sideways = faint
        .configuration
        .positions
        .iter()
        .map(|x| x.y.abs())
        .fold(0.0, f64::max);
    // A taut string's sag under the drag q = 0.77 N/m over the suspended kilometre at its mean tension (about
    // 350 kN, from 118 kN at the touchdown to 643 kN at the top): q L²/(8T) ≈ 0.27 m.
    assert!(
        sideways > 0.1 && sideways < 0.5,
        "largest sideways offset {sideways} m"
    );
}

/// The other cause, behind the message "load step fell below 1e-6 at load factor 0": on the path from the straight
/// reference, a controller that holds the vessel in statics pulled it toward its reference from the start, with
/// the supports still at the reference (hundreds of metres away, ~1e8 N). Its reference now moves with the
/// path's target, and the path from the reference reaches the catenary's state (on a frictionless seabed: the
/// friction mobilised along a path depends on it).
#[test]
fn the_path_from_the_reference_holds_the_vessel_with_its_controller() {
    let pid = Pid::new(
        Matrix6::from_diagonal(&Vector6::new(2e5, 2e5, 0.0, 0.0, 0.0, 1e7)),
        Matrix6::from_diagonal(&Vector6::new(4e6, 4e6, 0.0, 0.0, 0.0, 1e8)),
        Matrix6::zeros(),
        Reference::fixed(Vector6::new(880.0, 0.0, -800.0, 0.0, 0.0, 0.0)).expect("reference"),
        0.0,
        None,
        None,
        None,
    )
    .expect("pid");
    let model = j_lay(None, Some(pid), 0.0);
    let from_catenary = solve(&model, &StaticOptions::default()).expect("from the catenary");
    let options = StaticOptions {
        start: Start::Reference,
        ..StaticOptions::default()
    };
    let from_reference = solve(&model, &options).expect("from the reference");
    let apart = from_catenary
        .configuration
        .positions
        .iter()
        .zip(&from_reference.configuration.positions)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(apart < 1e-4, "the two paths' states are {apart} m apart");
}

/// An S-lay in a 0.5 m/s current across the lay from t = 0 solves; started from its static state, the
/// energy–momentum step in the same current leaves the line at rest (the static residual is the dynamic one at
/// rest), and the line is pushed downstream.
#[test]
fn an_s_lay_in_a_current_across_the_lay_is_at_rest_in_dynamics() {
    let model = s_lay(Some(Vector3::new(0.0, 0.5, 0.0)));
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let positions = &solution.configuration.positions;
    let downstream = positions
        .iter()
        .map(|x| x.y)
        .fold(f64::NEG_INFINITY, f64::max);
    let upstream = positions.iter().map(|x| x.y).fold(f64::INFINITY, f64::min);
    assert!(
        downstream > 1.0 && upstream > -0.01,
        "sideways {upstream} … {downstream} m"
    );
    let slips = solution.response.seabed.as_ref().map(|s| s.slips.clone());
    let mut state = DynamicState::at_rest(&model, solution.configuration, 0.0).expect("state");
    if let Some(slips) = slips {
        state = state.with_slips(&slips);
    }
    let options = DynamicOptions {
        time_step: 0.1,
        ..DynamicOptions::default()
    };
    let mut integrator = Integrator::new(model, state, options).expect("integrator");
    for _ in 0..20 {
        integrator.step().expect("step");
    }
    let fastest = common::fastest_node(&integrator);
    assert!(fastest < 1e-3, "fastest node after 2 s: {fastest} m/s");
}

/// Relaxation (pseudo-transient continuation) from the calm line's state reaches the state Newton reaches in a
/// current across the line's plane.
#[test]
fn relaxation_reaches_newtons_state() {
    let hanging = |current: f64| {
        let mut model = common::flooded_pipe(60);
        let flow = Current::new(
            CurrentProfile::Uniform(Vector3::new(0.0, current, 0.0)),
            0.0,
        )
        .expect("current");
        model.sea = Some(Sea::new(800.0, 1025.0, Some(flow), None).expect("sea"));
        model.pin("A", None).expect("pin");
        model
            .pin("B", Some(Vector3::new(900.0, 0.0, -700.0)))
            .expect("pin");
        model
    };
    let model = hanging(0.6);
    let newton = solve(&model, &StaticOptions::default()).expect("Newton");
    let mut config = solve(&hanging(0.0), &StaticOptions::default())
        .expect("calm")
        .configuration;
    let mut assembler = Assembler::new(&model);
    let iterations = match relax(
        &model,
        &mut assembler,
        &mut config,
        1.0,
        &StaticOptions::default(),
    ) {
        Newton::Converged { iterations, .. } => iterations,
        Newton::Failed { residual, .. } => panic!("relaxation stalled at residual {residual}"),
    };
    let apart = config
        .positions
        .iter()
        .zip(&newton.configuration.positions)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max);
    let sideways = config.positions.iter().map(|x| x.y).fold(0.0, f64::max);
    assert!(
        sideways > 10.0,
        "the current moved the line {sideways} m sideways"
    );
    assert!(apart < 1e-6, "relaxed and Newton's states {apart} m apart");
    assert!(iterations < 100, "{iterations} iterations");
}

/// Each roller's nearest element in a solution of an S-lay.
fn nearest_elements(solution: &StaticSolution) -> Vec<usize> {
    let rollers = solution.response.rollers.as_ref().expect("rollers");
    rollers.elements.clone()
}

/// What the physical check says of a solution of an S-lay.
fn verdict(model: &Model, solution: &StaticSolution) -> Option<Unphysical> {
    let config = &solution.configuration;
    check(
        model,
        &config.positions,
        &config.rotations,
        &[],
        &nearest_elements(solution),
    )
}

/// The check of a converged state: the S-lay's state is physical; the same with a stretch of pipe dropped under
/// the stinger, or a node pushed through a roller, or the vessel turned over, is not, and says where.
#[test]
fn the_check_refuses_a_pipe_under_or_through_the_stinger_and_a_capsized_vessel() {
    let model = s_lay(None);
    let solution = solve(&model, &StaticOptions::default()).expect("statics");
    let nearest = nearest_elements(&solution);
    let config = &solution.configuration;
    assert_eq!(verdict(&model, &solution), None);

    let roller = 6;
    let element = nearest[roller];
    let mut under = config.clone();
    under.positions[element].z += 5.0;
    match check(&model, &under.positions, &under.rotations, &[], &nearest) {
        Some(Unphysical::UnderStinger { node, depth, .. }) => {
            assert_eq!(node, element);
            assert!(depth > 4.0 && depth < 6.0, "depth {depth}");
        }
        other => panic!("expected the pipe under the stinger, got {other:?}"),
    }

    let mut through = config.clone();
    for node in element - 2..=element + 3 {
        through.positions[node].z += 0.7;
    }
    match check(
        &model,
        &through.positions,
        &through.rotations,
        &[],
        &nearest,
    ) {
        Some(Unphysical::ThroughRoller { roller: k, overlap }) => {
            assert_eq!(k, roller + 1);
            assert!(overlap > 0.55, "overlap {overlap}");
        }
        other => panic!(
            "expected the pipe through roller {}, got {other:?}",
            roller + 1
        ),
    }

    let mut capsized = config.clone();
    let last = capsized.rotations.len() - 1;
    capsized.rotations[last] =
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 2.5) * capsized.rotations[last];
    assert!(matches!(
        check(
            &model,
            &capsized.positions,
            &capsized.rotations,
            &[],
            &nearest
        ),
        Some(Unphysical::Capsized { .. })
    ));
}

/// With the vessel far too close to the touchdown for the stinger, every path converges to the pipe curled back
/// under the stinger: the solve fails, saying so and what to change, instead of returning it.
#[test]
fn a_pipe_curled_under_the_stinger_is_refused() {
    let mut model = s_lay(None);
    if let Some(attachment) = model.vessel.as_mut() {
        attachment.eta[0] = 560.0;
    }
    match solve(&model, &StaticOptions::default()) {
        Err(Error::Convergence { reason, .. }) => {
            assert!(
                reason.contains("under the stinger") || reason.contains("through roller"),
                "{reason}"
            );
            assert!(reason.contains("move the vessel forward"), "{reason}");
        }
        Ok(solution) => assert_eq!(
            verdict(&model, &solution),
            None,
            "a state returned must be physical"
        ),
        Err(other) => panic!("unexpected error {other}"),
    }
}
