//! The pipe of `benches/seabed_cost.py` (1600 m flooded 0.6 m × 15 mm steel pipe, about 400 m of it on an
//! elastic seabed with friction, top driven in surge, Δt = 0.05 s) in Rust alone: for instruction counts of
//! the dynamics with seabed contact without Python, e.g.
//!
//!     cargo build --release -p pipelay --example seabed_line
//!     valgrind --tool=callgrind ./target/release/examples/seabed_line 2000 40
//!
//! Arguments: elements (default 1000), steps (default 40) and `0` to leave the seabed out. Prints the wall time
//! per step and the Newton iterations.
use nalgebra::Vector3;
use pipelay::dynamics::integrator::{DynamicOptions, Integrator};
use pipelay::dynamics::state::DynamicState;
use pipelay::environment::bathymetry::Bathymetry;
use pipelay::environment::sea::Sea;
use pipelay::environment::seabed::Seabed;
use pipelay::model::Model;
use pipelay::rod::section::Section;
use pipelay::rod::Rod;
use pipelay::statics::solve::{solve, StaticOptions};
use std::sync::Arc;
fn main() {
    let argument = |i: usize, default: usize| {
        std::env::args()
            .nth(i)
            .and_then(|s| s.parse().ok())
            .unwrap_or(default)
    };
    let (n, steps, with_seabed) = (argument(1, 1000), argument(2, 40), argument(3, 1) != 0);
    let section = Section::pipe(
        0.6,
        0.015,
        7850.0,
        207e9,
        0.3,
        1025.0,
        [0.0, 1.2],
        [0.0, 1.0],
    )
    .unwrap();
    let rod = Rod::straight(Vector3::zeros(), Vector3::new(1600.0, 0.0, 0.0), n, section).unwrap();
    let seabed = with_seabed
        .then(|| Seabed::new(1e5, 0.0, [0.5, 0.8], 0.01, Bathymetry::flat(0.0).unwrap()).unwrap());
    let sea = Sea::new(800.0, 1025.0, None, seabed).unwrap();
    let mut model = Model::new(rod, Some(sea), 9.81).unwrap();
    model.pin("A", None).unwrap();
    let omega = 2.0 * std::f64::consts::PI / 10.0;
    let position =
        move |t: f64| Vector3::new(1200.0 + 2.5 * (1.0 - (omega * t).cos()), 0.0, -800.0);
    let velocity = move |t: f64| Vector3::new(2.5 * omega * (omega * t).sin(), 0.0, 0.0);
    model
        .drive(
            "B",
            Arc::new(move |t| Ok(position(t))),
            Some(Arc::new(move |t| Ok(velocity(t)))),
            None,
        )
        .unwrap();
    let solution = solve(&model, &StaticOptions::default()).unwrap();
    let state = DynamicState::at_rest(&model, solution.configuration, 0.0).unwrap();
    let options = DynamicOptions {
        time_step: 0.05,
        ..DynamicOptions::default()
    };
    let mut sim = Integrator::new(model, state, options).unwrap();
    let t = std::time::Instant::now();
    // On the engine's threads, as a run from Python.
    let its: usize = pipelay::linalg::pool::run(true, || {
        (0..steps).map(|_| sim.step().unwrap().iterations).sum()
    });
    println!(
        "n {n}, seabed {with_seabed}: {:.3} ms/step, {its} iterations",
        t.elapsed().as_secs_f64() * 1e3 / steps as f64
    );
}
