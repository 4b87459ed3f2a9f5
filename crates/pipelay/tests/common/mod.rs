//! The 1200 m flooded steel pipe of the validation tests (0.6 m × 15 mm, 800 m of water), straight along e1.
use nalgebra::Vector3;
use pipelay::environment::sea::Sea;
use pipelay::model::Model;
use pipelay::rod::section::Section;
use pipelay::rod::Rod;

/// The flooded pipe with `n` elements in 800 m of water, held by nothing yet.
pub fn flooded_pipe(n: usize) -> Model {
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
    let sea = Sea::new(800.0, 1025.0, None, None).expect("sea");
    Model::new(rod, Some(sea), 9.81).expect("model")
}
