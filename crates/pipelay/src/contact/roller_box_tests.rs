//! Closed forms of a frictionless V box on the contact itself: each roller's share of a load, and the lateral
//! load at which the pipe climbs out.
use super::tests::{evaluate_static, held_pipe};
use super::*;
use crate::vessel::lay::LayEquipment;
use crate::vessel::roller_box::{BoxShape, RollerBox};

/// A straight pipe 0.6 m across on a frictionless V box (half-angle θ = 30°, rollers 1.2 m long) standing
/// 5 m from the held end, loaded by F down and L to starboard: the pipe's offset (m, lateral and down)
/// where the rollers balance the load, or where the search for it ends unbalanced, whether they balance
/// it, and each roller's reaction (N) and contact offset (m) there.
fn pipe_in_a_v(load_down: f64, load_lateral: f64) -> (Vector3<f64>, bool, Vec<f64>, Vec<f64>) {
    let theta = std::f64::consts::FRAC_PI_6;
    let roller_box = RollerBox::new(BoxShape::V, theta, 1.2, false, false).unwrap();
    let station = Vector3::new(-5.0, 0.0, 0.0);
    let rollers = roller_box.rollers(station, -Vector3::z(), Vector3::y(), 0.25, 0);
    let lay = LayEquipment::s_lay(Vector3::zeros(), rollers, 1e7).unwrap();
    let mut contact = held_pipe(lay, Vector3::new(-10.0, 0.0, 0.0), Vector3::zeros(), 10);
    let rotations = vec![UnitQuaternion::identity(); 11];
    // The pipe's nodes but the held one moved by (lateral, down); the rollers' total force on it.
    let mut total = |offset: &Vector3<f64>| {
        let positions: Vec<Vector3<f64>> = (0..11)
            .map(|i| {
                let x = Vector3::new(-10.0 + i as f64, 0.0, 0.0);
                if i < 10 {
                    x + offset
                } else {
                    x
                }
            })
            .collect();
        evaluate_static(&mut contact, &positions, &rotations);
        let force: Vector3<f64> = contact.reactions.iter().sum();
        (
            force + Vector3::new(0.0, load_lateral, load_down),
            contact.reactions.clone(),
            contact.offsets.clone(),
        )
    };
    // Damped Newton on the pipe's lateral and vertical offset, the Jacobian by central differences. On a
    // single roller the contact is stiff only along its normal: along the roller the pipe moves with the
    // unbalanced force instead, by up to 2 cm a step.
    let mut offset = Vector3::new(0.0, 0.0, -0.3 / theta.cos());
    for _ in 0..200 {
        let (r, _, _) = total(&offset);
        if r.yz().norm() < 1e-6 * load_down {
            break;
        }
        let h = 1e-7;
        let mut jacobian = nalgebra::Matrix2::zeros();
        for j in 0..2 {
            let mut step = Vector3::zeros();
            step[j + 1] = h;
            let difference = (total(&(offset + step)).0 - total(&(offset - step)).0) / (2.0 * h);
            jacobian.set_column(j, &difference.yz());
        }
        let svd = jacobian.svd(true, true);
        let (u, v_t) = (svd.u.unwrap(), svd.v_t.unwrap());
        let mut delta = nalgebra::Vector2::zeros();
        let mut unbalanced = r.yz();
        for i in 0..2 {
            let (u_i, v_i) = (u.column(i), v_t.row(i).transpose());
            if svd.singular_values[i] > 1e-6 * svd.singular_values.max() {
                delta -= u_i.dot(&r.yz()) / svd.singular_values[i] * v_i;
                unbalanced -= u_i.dot(&r.yz()) * u_i;
            }
        }
        if unbalanced.norm() > 1e-9 * load_down {
            delta += 0.02 * unbalanced.normalize();
        }
        let scale = (0.02 / delta.norm()).min(1.0);
        offset += Vector3::new(0.0, scale * delta.x, scale * delta.y);
    }
    let (r, reactions, offsets) = total(&offset);
    let magnitudes = reactions.iter().map(|f| f.norm()).collect();
    (
        offset,
        r.yz().norm() < 1e-6 * load_down,
        magnitudes,
        offsets,
    )
}

/// Frictionless, symmetric V under a vertical load F: each roller carries F/(2 cos θ), and the pipe rests
/// R tan θ up each roller from its lower end; with a lateral load L both carry F/(2 cos θ) ± L/(2 sin θ).
#[test]
fn v_box_reactions_match_the_closed_form() {
    let (theta, load) = (std::f64::consts::FRAC_PI_6, 50e3);
    let (_, balanced, reactions, offsets) = pipe_in_a_v(load, 0.0);
    assert!(balanced);
    for (reaction, offset) in reactions.iter().zip(&offsets) {
        let expected = load / (2.0 * theta.cos());
        assert!(
            (reaction / expected - 1.0).abs() < 1e-6,
            "{reaction} vs {expected}"
        );
        // R tan θ from the lower end, 0.6 m below the centre, less the overlap's shift along the roller.
        assert!(
            (offset - (0.3 * theta.tan() - 0.6)).abs() < 2e-3,
            "{offset}"
        );
    }
    let lateral = 0.5 * load * theta.tan();
    let (_, balanced, reactions, _) = pipe_in_a_v(load, lateral);
    assert!(balanced);
    let expected = [
        load / (2.0 * theta.cos()) - lateral / (2.0 * theta.sin()),
        load / (2.0 * theta.cos()) + lateral / (2.0 * theta.sin()),
    ];
    for (reaction, expected) in reactions.iter().zip(expected) {
        assert!(
            (reaction / expected - 1.0).abs() < 1e-6,
            "{reaction} vs {expected}"
        );
    }
}

/// The pipe climbs out of the V at a lateral load of F tan θ: at 0.97 F tan θ it rests on both rollers
/// inside the box, the port roller's share F/(2 cos θ) − L/(2 sin θ) small but positive; at 1.03 F tan θ
/// no place in the box balances the load: the port roller unloads and the pipe slides up the starboard
/// roller to its upper end (within 1 mm), where it leaves the box.
#[test]
fn a_pipe_climbs_out_of_the_v_at_f_tan_theta() {
    let (theta, load) = (std::f64::consts::FRAC_PI_6, 50e3);
    let lateral = 0.97 * load * theta.tan();
    let (_, balanced, reactions, offsets) = pipe_in_a_v(load, lateral);
    let port = load / (2.0 * theta.cos()) - lateral / (2.0 * theta.sin());
    assert!(
        balanced && (reactions[0] / port - 1.0).abs() < 1e-6,
        "{reactions:?}"
    );
    assert!(offsets.iter().all(|o| o.abs() < 0.5), "{offsets:?}");
    let (offset, balanced, reactions, offsets) = pipe_in_a_v(load, 1.03 * load * theta.tan());
    assert!(!balanced);
    assert_eq!(reactions[0], 0.0, "{reactions:?}");
    assert!(offsets[1] > 0.599, "{offsets:?}");
    // The pipe's centre has risen with it, to about the V's upper ends (0.6 m above the station).
    assert!(-offset.z > 0.8 && offset.y > 0.85, "{offset}");
}
