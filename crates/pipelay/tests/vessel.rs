//! The vessel on the pipe: statics with holding thrust, free decay, energy of the coupled system.
use nalgebra::{Vector3, Vector6};
use pipelay::hydro::Sea;
use pipelay::model::Model;
use pipelay::response::Response;
use pipelay::rod::Rod;
use pipelay::section::Section;
use pipelay::statics::{solve, StaticOptions};
use pipelay::vessel::Vessel;

fn pipe_with_vessel(n: usize) -> Model {
    let section = Section::pipe(
        0.6,
        0.015,
        7850.0,
        207e9,
        0.3,
        1025.0,
        [0.0, 1.0],
        [0.0, 1.0],
    )
    .expect("pipe");
    let rod =
        Rod::straight(Vector3::zeros(), Vector3::new(1200.0, 0.0, 0.0), n, section).expect("rod");
    let sea = Sea::new(800.0, 1025.0, None).expect("sea");
    let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
    model.pin("A", None).expect("pin");
    model
        .attach_vessel(
            "B",
            Vessel::osv(),
            Vector6::new(850.0, 0.0, -800.0, 0.0, 0.0, 0.0),
            Vector3::zeros(),
            None,
            vec![],
        )
        .expect("vessel");
    model
}

/// Heave, roll and pitch settle against the restoring; the holding thrust balances the pipe's horizontal pull;
/// the vessel's vertical equilibrium G33 Δz + G35 θ equals the pipe's vertical pull.
#[test]
fn static_vessel_holds_the_pipe() {
    let model = pipe_with_vessel(50);
    let solution = solve(&model, &StaticOptions::default()).expect("converges");
    let response = Response::new(&model, &solution.configuration);
    let vessel = response.vessel.expect("vessel response");
    println!(
        "eta {:?}\nthrust {:?}\npipe force {:?}",
        vessel.eta.as_slice(),
        vessel.thrust.as_slice(),
        vessel.pipe_force.as_slice()
    );
    assert!(
        (vessel.eta[0] - 850.0).abs() < 1e-4
            && vessel.eta[1].abs() < 1e-4
            && vessel.eta[5].abs() < 1e-8
    );
    // In e, the horizontal thrust balances the pipe's horizontal pull (restoring is vertical).
    let body = pipelay::euler::rotation(&vessel.eta.fixed_rows::<3>(3).into_owned());
    let thrust = body * vessel.thrust.fixed_rows::<3>(0);
    let pipe = body * vessel.pipe_force.fixed_rows::<3>(0);
    assert!(
        (thrust.x + pipe.x).abs() < 1e-6 * pipe.norm()
            && (thrust.y + pipe.y).abs() < 1e-6 * pipe.norm()
    );
    // Vertical: the restoring G33 Δz + G35 sin θ (director form, about the surface z = −800) carries the pipe's
    // downward pull and the vertical part of the tilted thrust.
    let g = Vessel::osv().restoring;
    let restoring = g[(2, 2)] * (vessel.eta[2] + 800.0) + g[(2, 4)] * vessel.eta[4].sin();
    assert!(
        (restoring - (pipe.z + thrust.z)).abs() < 1e-6 * pipe.z,
        "{restoring} vs {}",
        pipe.z + thrust.z
    );
    assert!(
        vessel.pipe_force[0] < 0.0 && vessel.pipe_force[2] > 0.0,
        "the pipe pulls back and down"
    );
}
