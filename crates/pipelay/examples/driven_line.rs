//! The driven hanging line of `benches/moordyn_race.py` (250 m wire rope, top driven in surge and heave, Δt =
//! 25/320 s) in Rust alone: for instruction counts of the dynamics without Python, e.g.
//!
//!     cargo build --release -p pipelay --example driven_line
//!     valgrind --tool=callgrind ./target/release/examples/driven_line 1000 30
//!
//! Arguments: elements (default 100) and steps (default 320). Prints the wall time per step and the Newton
//! iterations; run with 0 steps to count the statics alone.
use nalgebra::Vector3;
use pipelay::dynamics::integrator::{DynamicOptions, Integrator};
use pipelay::dynamics::state::DynamicState;
use pipelay::environment::sea::Sea;
use pipelay::model::Model;
use pipelay::rod::section::{Section, SectionExtras};
use pipelay::rod::Rod;
use pipelay::statics::solve::{solve, StaticOptions};
use std::sync::Arc;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let steps: usize = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(320);
    let (d, m) = (0.09, 40.0);
    let extras = SectionExtras {
        inertia: [m * d * d / 4.0, m * d * d / 8.0, m * d * d / 8.0],
        outer_diameter: d,
        drag: [0.0, 1.2],
        added_mass: [1.0, 1.0],
        ..SectionExtras::default()
    };
    let section = Section::new(4e8, [4e8; 2], 10.0, [10.0; 2], m, extras).unwrap();
    let rod = Rod::straight(Vector3::zeros(), Vector3::new(250.0, 0.0, 0.0), n, section).unwrap();
    let sea = Sea::new(200.0, 1025.0, None, None).unwrap();
    let mut model = Model::new(rod, Some(sea), 9.81).unwrap();
    model.pin("A", None).unwrap();
    let pos = |t: f64| {
        let s = (t / 10.0).clamp(0.0, 1.0);
        let r = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
        let w = 2.0 * std::f64::consts::PI / 10.0;
        Vector3::new(
            150.0 + 8.0 * r * (w * t).sin(),
            0.0,
            -190.0 + 2.0 * r * (w * t + 1.0).sin(),
        )
    };
    model
        .drive("B", Arc::new(move |t| Ok(pos(t))), None, None)
        .unwrap();
    let solution = solve(&model, &StaticOptions::default()).unwrap();
    let state = DynamicState::at_rest(&model, solution.configuration, 0.0).unwrap();
    let mut sim = Integrator::new(
        model,
        state,
        DynamicOptions {
            time_step: 25.0 / 320.0,
            ..DynamicOptions::default()
        },
    )
    .unwrap();
    let t = std::time::Instant::now();
    // On the engine's threads, as a run from Python.
    let its: usize = pipelay::linalg::pool::run(true, || {
        (0..steps).map(|_| sim.step().unwrap().iterations).sum()
    });
    println!(
        "n {n}: {:.3} ms/step, {its} iterations",
        t.elapsed().as_secs_f64() * 1e3 / steps as f64
    );
}
