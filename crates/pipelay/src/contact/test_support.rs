//! What the contact tests share.
use crate::environment::bathymetry::Bathymetry;

/// A gently sloping, wavy seabed on a 5 × 3 grid around the origin (elevations in m, e3 down).
pub fn wavy_seabed() -> Bathymetry {
    let x: Vec<f64> = (0..5).map(|i| -5.0 + 4.0 * i as f64).collect();
    let y = vec![-5.0, 0.0, 5.0];
    let z = x
        .iter()
        .flat_map(|xi| {
            y.iter()
                .map(move |yj| 0.02 * xi + 0.05 * (0.4 * xi).sin() + 0.01 * yj)
        })
        .collect();
    Bathymetry::grid(x, y, z).expect("grid")
}
