//! Pay-out and pay-in: the energy ledger closes through growth and mesh changes, the energy pay-out brings in
//! is the tensioner's work on the pipe it lets out, the length is exact, and pay-in undoes pay-out.
mod common;
use nalgebra::Vector3;
use pipelay::dynamics::integrator::Integrator;
use pipelay::model::{Model, PayOutSpeed};
use pipelay::rod::section::Section;
use pipelay::rod::Rod;
use std::sync::Arc;

/// Smoothstep 3s² − 2s³ of s = t / ramp clipped to [0, 1].
fn smoothstep(t: f64, ramp: f64) -> f64 {
    let s = (t / ramp).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

/// A 100 m steel pipe (0.3 m × 20 mm) in vacuum, 20 elements, hanging from end B at the origin, which is driven
/// sideways by `sway` (m) over time; pay-out at B at `speed`(t).
fn hanging(sway: f64, speed: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Integrator {
    let section =
        Section::pipe(0.3, 0.02, 7850.0, 207e9, 0.3, 0.0, [0.0; 2], [0.0; 2]).expect("section");
    let rod =
        Rod::straight(Vector3::new(0.0, 0.0, 100.0), Vector3::zeros(), 20, section).expect("rod");
    let mut model = Model::new(rod, None, 9.81).expect("model");
    let position =
        Arc::new(move |t: f64| Ok(Vector3::new(sway * (1.0 - (0.5 * t).cos()), 0.0, 0.0)));
    let velocity = Arc::new(move |t: f64| Ok(Vector3::new(0.5 * sway * (0.5 * t).sin(), 0.0, 0.0)));
    model
        .drive("B", position, Some(velocity), None)
        .expect("drive");
    model
        .pay_out("B", PayOutSpeed::Function(Arc::new(move |t| Ok(speed(t)))))
        .expect("pay-out");
    common::from_statics(model, 0.02)
}

/// Without dissipation, E − E0 = work of the drive + energy pay-out brought in, to 1e-9 of E, through growth
/// and five splits while the top sways; the energy pay-out brings in is the tensioner's work −∫T·v dt on the
/// pipe it lets out plus the kinetic energy the new pipe carries (to 1 %), and the length grows by ∫v dt.
#[test]
fn energy_ledger_closes_through_pay_out() {
    let speed = |t: f64| 1.0 * smoothstep(t, 5.0);
    let mut sim = hanging(2.0, speed);
    let e0 = sim.observe().energy().total();
    let mass = 7850.0 * std::f64::consts::PI * (0.3 - 0.02) * 0.02;
    let (mut worst, mut flux) = (0.0_f64, 0.0);
    let dt = sim.options().time_step;
    let nodes0 = sim.model().rod.node_count();
    for _ in 0..1500 {
        let t = sim.state().time;
        let end = sim.model().rod.element_count();
        let v_end = sim.state().velocities[end];
        sim.step().expect("step");
        let reaction = sim.reactions()[sim.model().rod.element_count()];
        let tension = Vector3::new(reaction[0], reaction[1], reaction[2]).norm();
        let v_mid = speed(t + 0.5 * dt);
        let v_top = 0.5 * (v_end + sim.state().velocities[sim.model().rod.element_count()]);
        flux += dt * v_mid * (-tension + 0.5 * mass * v_top.norm_squared());
        let balance = sim.observe().energy().total() - e0 - sim.ledger().supplied_work()
            + sim.ledger().dissipated();
        worst = worst.max(balance.abs());
    }
    let scale = sim.observe().energy().total().abs().max(e0.abs());
    let paid = 30.0 - 2.5; // ∫ smoothstep over 30 s with a 5 s ramp
    println!(
        "balance {worst:.3e} of {scale:.3e} J; pay-out energy {:.6e} J, −∫Tv + ½mv² {flux:.6e} J; \
         length {:.12} m; nodes {} → {}",
        sim.ledger().pay_out_energy(),
        sim.observe().length(),
        nodes0,
        sim.model().rod.node_count()
    );
    assert!(worst < 1e-9 * scale, "{worst:e}");
    assert!((sim.ledger().pay_out_energy() - flux).abs() < 0.01 * flux.abs());
    assert!((sim.observe().length() - 100.0 - paid).abs() < 1e-3);
    assert_eq!(sim.model().rod.node_count(), nodes0 + 5);
    assert!(sim.state().configuration.positions.len() == sim.model().rod.node_count());
}

/// Paying out 12 m and paying the same back in restores the mesh and the length to round-off, and the ledger
/// still closes through the joins.
#[test]
fn pay_in_undoes_pay_out() {
    // +1 m/s for 12 s, then −1 m/s for 12 s, each with smooth 3 s ramps at both ends.
    let pulse = |t: f64| smoothstep(t, 3.0) - smoothstep(t - 9.0, 3.0);
    let speed = move |t: f64| pulse(t) - pulse(t - 12.0);
    let mut sim = hanging(0.0, speed);
    let e0 = sim.observe().energy().total();
    let nodes0 = sim.model().rod.node_count();
    let mut most = nodes0;
    let mut worst = 0.0_f64;
    for _ in 0..1500 {
        sim.step().expect("step");
        most = most.max(sim.model().rod.node_count());
        let balance = sim.observe().energy().total() - e0 - sim.ledger().supplied_work()
            + sim.ledger().dissipated();
        worst = worst.max(balance.abs());
    }
    println!(
        "nodes {nodes0} → {most} → {}; length {:.15} m; balance {worst:.3e} J",
        sim.model().rod.node_count(),
        sim.observe().length()
    );
    assert_eq!(most, nodes0 + 2);
    assert_eq!(sim.model().rod.node_count(), nodes0);
    assert!((sim.observe().length() - 100.0).abs() < 1e-9);
    assert!(worst < 1e-9 * e0.abs());
}
