//! Where statics' Newton starts: the catenary guess. Nodes are placed along Irvine's elastic catenary through
//! the held ends (resting on the seabed where the line lies on it), over the vessel's rollers along their
//! path, with frames turned onto the curve's tangent.
// Indexing cannot go out of bounds here: Node and element indices of the model's own mesh, and path segments.
#![allow(clippy::indexing_slicing)]
use crate::assembly::configuration::Configuration;
use crate::model::{Model, SupportTarget};
use crate::so3::{minimal_rotation, quat_from_matrix};
use crate::statics::catenary::Catenary;
use crate::statics::laid_catenary::LaidCatenary;
use crate::statics::supports::apply_supports;
use nalgebra::Vector3;

/// A curve's position and unit tangent at an unstretched arc length.
type CurveShape = dyn Fn(f64) -> (Vector3<f64>, Vector3<f64>);

/// The catenary initial guess: nodes placed along Irvine's elastic catenary (resting on the seabed from A
/// when A lies on it and the line is long enough, [`LaidCatenary`]) through the two held ends
/// at their reference arc lengths, frames turned by the smallest rotation onto its tangent. A buoyant
/// line (negative submerged weight) is the mirror image, in z, of a heavy one.
pub fn catenary_guess(model: &Model, targets: &[SupportTarget]) -> Option<Configuration> {
    let last = model.rod.element_count();
    let held = |node: usize| targets.iter().find(|s| s.node == node);
    let (a, b) = (held(0)?, held(last)?);
    // A line of segments starts from the catenary of its mean weight and stiffness.
    let weight = model.mean_submerged_weight();
    if targets.len() != 2 || weight == 0.0 {
        return None;
    }
    let mirror = |v: Vector3<f64>| {
        if weight > 0.0 {
            v
        } else {
            Vector3::new(v.x, v.y, -v.z)
        }
    };
    let ea = model.rod.mean(|s| s.translational_stiffness.x);
    let a = mirror(a.position);
    // The line hanging from A to `top` (mirrored) with `length` of pipe: a heavy line whose end A lies on the
    // seabed rests on it up to a touchdown point.
    let hanging = |top: Vector3<f64>, length: f64| -> Option<Box<CurveShape>> {
        let laid = model
            .seabed()
            .filter(|seabed| {
                weight > 0.0 && seabed.bathymetry.penetration(&a).value > -1e-3 * (top - a).norm()
            })
            .and_then(|seabed| LaidCatenary::solve(a, top, length, weight, ea, seabed.friction[0]));
        match laid {
            Some(laid) => Some(Box::new(move |s| (laid.position(s), laid.tangent(s)))),
            None => {
                let catenary = Catenary::solve(a, top, length, weight.abs(), ea).ok()?;
                Some(Box::new(move |s| {
                    (catenary.position(s), catenary.tangent(s))
                }))
            }
        }
    };
    // Over a vessel's rollers the guess follows the roller path from the hold point and leaves it where the
    // hanging line from A meets the path most nearly tangentially.
    let mut path = roller_path(model, b);
    let (length, shape) = if path.len() > 1 {
        let total = model.rod.length();
        let best = (1..path.len())
            .filter_map(|k| {
                let length = total - path[k].0;
                let shape = hanging(mirror(path[k].1), length)?;
                let along = mirror(path[k - 1].1 - path[k].1).normalize();
                let mismatch = (shape(length).1 - along).norm();
                Some((mismatch, k, length, shape))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))?;
        path.truncate(best.1 + 1);
        (best.2, best.3)
    } else {
        let length = model.rod.length();
        (length, hanging(mirror(b.position), length)?)
    };
    let mut config = Configuration::reference(model);
    let mut arc = 0.0;
    for node in 0..=last {
        if node > 0 {
            arc += model.rod.elements[node - 1].length;
        }
        let (position, tangent) = if arc > length && path.len() > 1 {
            along_path(&path, model.rod.length() - arc)
        } else {
            shape(arc.min(length))
        };
        config.positions[node] = mirror(position);
        // Where the guess dips into an uneven seabed, it rests on its surface instead.
        if let Some(seabed) = model.seabed().filter(|_| weight > 0.0) {
            let p = &mut config.positions[node];
            p.z = p.z.min(seabed.bathymetry.elevation(p.x, p.y));
        }
        let frame = config.rotations[node].to_rotation_matrix().into_inner();
        let turn = minimal_rotation(&frame.column(0).into_owned(), &mirror(tangent));
        config.rotations[node] = quat_from_matrix(&(turn * frame));
    }
    apply_supports(model, targets, &mut config, 1.0);
    Some(config)
}

/// The roller path of a vessel holding end B at `held`: (distance from the hold point, point in e) from the
/// hold point over the roller tops raised by the pipe's radius, in the rollers' order; empty without rollers.
fn roller_path(model: &Model, held: &SupportTarget) -> Vec<(f64, Vector3<f64>)> {
    let Some(attachment) = model.vessel.as_ref().filter(|v| !v.rollers().is_empty()) else {
        return Vec::new();
    };
    let Some(rotation) = held.rotation else {
        return Vec::new();
    };
    let body = rotation.to_rotation_matrix().into_inner() * attachment.angle;
    let hang_off = attachment.hang_off();
    let radius = 0.5
        * model
            .rod
            .section(held.node.saturating_sub(1))
            .hydrodynamic_diameter;
    let mut path = vec![(0.0, held.position)];
    // The line's centre over each support: its station raised by the line's radius (a lone roller's top
    // plus that radius; in a V it rests a little higher, and the contact lifts it there).
    for (station, up) in crate::vessel::lay::supports(attachment.rollers()) {
        let top = station + radius * up;
        let point = held.position + body * (top - hang_off);
        let previous = path[path.len() - 1];
        path.push((previous.0 + (point - previous.1).norm(), point));
    }
    path
}

/// Position and tangent (toward the hold point, i.e. toward end B) at distance `s` along a roller path.
fn along_path(path: &[(f64, Vector3<f64>)], s: f64) -> (Vector3<f64>, Vector3<f64>) {
    let k = path
        .windows(2)
        .position(|w| s <= w[1].0)
        .unwrap_or(path.len().saturating_sub(2));
    let (start, end) = (path[k], path[k + 1]);
    let span = (end.0 - start.0).max(f64::MIN_POSITIVE);
    let t = ((s - start.0) / span).clamp(0.0, 1.0);
    (start.1 + t * (end.1 - start.1), (start.1 - end.1) / span)
}
