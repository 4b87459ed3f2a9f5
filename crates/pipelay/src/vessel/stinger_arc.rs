//! The stinger's arc: its top line (the pipe's bottom where it rests on every support), a circle of radius R
//! in the vessel's plane of symmetry, starting at `origin` with the slope `angle` below the horizontal and
//! running aft while bending down. Lone rollers ([`crate::vessel::lay`]), roller boxes
//! ([`crate::vessel::roller_box`]) and an articulated stinger's hinges ([`crate::vessel::articulation`])
//! stand on it.
use nalgebra::Vector3;

/// The stinger's top line at arc length `s` (m) from its start `origin`, for a stinger of `radius` starting
/// with the slope `angle` (rad below the horizontal): the point, the outward normal (toward the pipe: up and
/// forward of the arc, away from its centre) and the unit tangent (aft and down), body frame.
pub fn stinger_station(
    radius: f64,
    origin: Vector3<f64>,
    angle: f64,
    s: f64,
) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let slope = angle + s / radius;
    // p(s) = origin + R(−(sin φ − sin φ0), 0, −(cos φ − cos φ0)) with φ the slope below the horizontal.
    let top = origin
        + radius
            * Vector3::new(
                -(slope.sin() - angle.sin()),
                0.0,
                -(slope.cos() - angle.cos()),
            );
    let normal = Vector3::new(-slope.sin(), 0.0, -slope.cos());
    let tangent = Vector3::new(-slope.cos(), 0.0, slope.sin());
    (top, normal, tangent)
}
