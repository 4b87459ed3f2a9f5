//! Seabed contact through the whole engine: the assembled static tangent against finite differences, and
//! statics that find the touchdown.
use nalgebra::{Vector2, Vector3};
use pipelay::assembly::assembler::Assembler;
use pipelay::assembly::configuration::Configuration;
use pipelay::environment::bathymetry::Bathymetry;
use pipelay::environment::sea::Sea;
use pipelay::environment::seabed::Seabed;
use pipelay::model::Model;
use pipelay::rod::Rod;
use pipelay::so3::exp_quat;

mod common;

fn wavy_grid() -> Bathymetry {
    let x: Vec<f64> = (0..8).map(|i| -10.0 + 8.0 * i as f64).collect();
    let y = vec![-10.0, 0.0, 10.0];
    let z = x
        .iter()
        .flat_map(|xi| {
            y.iter()
                .map(move |yj| 0.01 * xi + 0.2 * (0.3 * xi).sin() + 0.02 * yj)
        })
        .collect();
    Bathymetry::grid(x, y, z).expect("grid")
}

/// The assembled static tangent of a pipe lying partly in a wavy seabed with friction (from a start state
/// with elastic slips, some nodes sticking, some sliding) equals central differences of the residual.
#[test]
fn assembled_tangent_with_seabed_matches_finite_differences() {
    for bathymetry in [
        Bathymetry::plane(0.0, Vector2::new(0.02, 0.01)).expect("plane"),
        wavy_grid(),
    ] {
        let section = common::flooded_section();
        let rod =
            Rod::straight(Vector3::zeros(), Vector3::new(40.0, 0.0, 0.0), 5, section).expect("rod");
        let seabed = Seabed::new(1e5, 0.0, [0.6, 0.4], 0.02, bathymetry).expect("seabed");
        let sea = Sea::new(50.0, 1025.0, None, Some(seabed)).expect("sea");
        let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
        model.pin("A", None).expect("pin");
        let mut config = Configuration::reference(&model);
        for (a, (x, r)) in config
            .positions
            .iter_mut()
            .zip(config.rotations.iter_mut())
            .enumerate()
            .skip(1)
        {
            let s = a as f64;
            *x += Vector3::new(0.004 * s, -0.003 * s * s, 0.03 - 0.012 * s * s);
            *r = exp_quat(&Vector3::new(0.02 * s, -0.05, 0.03 * s)) * *r;
        }
        let mut assembler = Assembler::new(&model);
        assembler.contact_slips = (0..6)
            .map(|a| Vector2::new(0.01 * ((a % 3) as f64 - 1.0), 0.004 * (a as f64 - 2.5)))
            .collect();
        let (worst, largest) = common::tangent_error(&model, &config, &mut assembler, 1e-7);
        assert!(worst < 1e-6 * largest, "worst {worst:e} of {largest:e}");
    }
}
