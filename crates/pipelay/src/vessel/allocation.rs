//! Thrust allocation: the thrusters' thrusts and azimuths that deliver a commanded τ = (X, Y, N), as a convex
//! quadratic program solved by Clarabel (an interior-point conic solver):
//!
//!   min ½ Σ_i |f_i|² + ½ ρ |s|²   subject to   B u − s = τ,
//!   −f̄_i⁻ ≤ f_i ≤ f̄_i (tunnel, main),  |(f_xi, f_yi)| ≤ f̄_i (azimuth),
//!
//! u the unknown thrusts: one per fixed-direction thruster, the force components (f_x, f_y) of each azimuth
//! thruster (so the azimuth is free and the problem convex; Johansen & Fossen 2013), and s the slack, the part
//! of τ the thrusters cannot deliver, penalised by ρ = 10⁶ in units scaled by the largest thruster: a τ within
//! the thrusters' capacity is delivered to 1e-6 of it, and then exactly by the same problem with the slack
//! held at zero. With the state of the last step and its length, a step's
//! allocation also keeps each thrust within its rate of the last (|f_i − f_i⁻| ≤ ḟ̄ Δt; for an azimuth
//! thruster |f_i| ≤ |f_i⁻| + ḟ̄ Δt) and each azimuth within its rate of the last (the force in the sector
//! α⁻ ± α̇̄ Δt, two half-planes, when that sector is narrower than a half turn); the azimuth it commands is
//! where the same problem without rate limits points the thruster, so that a thruster turns round when the
//! command calls for it (its thrust meanwhile within its sector).
// Indexing cannot go out of bounds here: per-thruster arrays have one entry per thruster, built alongside.
#![allow(clippy::indexing_slicing)]
use super::thrusters::{Thruster, ThrusterKind, ThrusterState};
use crate::error::{Error, Result};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, NonnegativeConeT, SecondOrderConeT, SolverStatus,
    SupportedConeT, ZeroConeT,
};
use nalgebra::Vector6;
use std::f64::consts::FRAC_PI_2;

/// The slack's weight against the thrusts' (both scaled by the largest thruster).
const SLACK_WEIGHT: f64 = 1e6;

/// One allocation: each thruster's commanded thrust (N) and azimuth (rad), and the τ they deliver.
#[derive(Debug, Clone, PartialEq)]
pub struct Allocation {
    pub thrust: Vec<f64>,
    pub azimuth: Vec<f64>,
    /// [X, 0 … , N] the thrusts deliver (body frame, N and N·m; heave, roll and pitch zero); for a step's
    /// allocation, along the azimuths within their rates.
    pub tau: Vector6<f64>,
    /// True when the thrusters cannot deliver the command (its shortfall exceeds 1e-4 of their capacity).
    pub saturated: bool,
}

impl Allocation {
    /// The thrusters' commanded states.
    pub fn states(&self) -> Vec<ThrusterState> {
        self.thrust
            .iter()
            .zip(&self.azimuth)
            .map(|(&thrust, &azimuth)| ThrusterState { thrust, azimuth })
            .collect()
    }
}

/// The last step's thruster states and the step's length (s): the rate limits' reference.
pub struct Previous<'a> {
    pub states: &'a [ThrusterState],
    pub dt: f64,
}

/// The solver's iteration limit for a second try when the first (Clarabel's default, 200) ran out.
const LONGER_ITERATIONS: u32 = 5000;

/// The rows of one inequality A u ≤ b, as triplets.
#[derive(Default)]
struct Rows {
    rows: Vec<usize>,
    columns: Vec<usize>,
    values: Vec<f64>,
    bounds: Vec<f64>,
}

impl Rows {
    /// Appends the row Σ coefficients[k].1 u[coefficients[k].0] ≤ bound.
    fn push(&mut self, coefficients: &[(usize, f64)], bound: f64) {
        let row = self.bounds.len();
        for &(column, value) in coefficients {
            self.rows.push(row);
            self.columns.push(column);
            self.values.push(value);
        }
        self.bounds.push(bound);
    }
}

/// Allocates τ (body frame; its X, Y and N are allocated) to `thrusters`, within the rates of `previous` if
/// given. An empty list, or a solver that fails, is an error.
pub fn allocate(
    thrusters: &[Thruster],
    tau: &Vector6<f64>,
    previous: Option<&Previous<'_>>,
) -> Result<Allocation> {
    if thrusters.is_empty() {
        return Err(Error::input(
            "thrusters",
            "none",
            "thrust allocation needs at least one thruster",
        ));
    }
    crate::error::finite("tau", tau.as_slice())?;
    let tau = &within_reach(thrusters, tau);
    let mut allocation = within_rates(thrusters, tau, previous)?;
    // An azimuth thruster turns toward where the allocation without rate limits wants it: within its sector
    // alone it could never turn round to push the other way.
    // (Only azimuth thrusters turn: without them the problem without rate limits has nothing to add.)
    let turning = thrusters.iter().any(|t| t.fixed_azimuth().is_none());
    if let Some(previous) = previous.filter(|_| turning) {
        let wanted = within_rates(thrusters, tau, None)?;
        for (k, thruster) in thrusters.iter().enumerate() {
            if thruster.fixed_azimuth().is_none() {
                let idle = wanted.thrust[k] < 1e-9 * thruster.max_thrust;
                allocation.azimuth[k] = if idle {
                    previous.states[k].azimuth
                } else {
                    wanted.azimuth[k]
                };
            }
        }
    }
    Ok(allocation)
}

/// τ scaled down, its direction kept, to at most ten times what the thrusters can deliver together (forces by
/// their summed capacity, moments by it times the longest arm): beyond that it saturates them all the same,
/// and the QP's scaling would lose its precision.
fn within_reach(thrusters: &[Thruster], tau: &Vector6<f64>) -> Vector6<f64> {
    let capacity: f64 = thrusters.iter().map(|t| t.max_thrust).sum();
    let arm = thrusters
        .iter()
        .map(|t| t.position.norm())
        .fold(1.0, f64::max);
    let size = (tau[0].abs().max(tau[1].abs()) / capacity).max(tau[5].abs() / (capacity * arm));
    if size > REACH {
        tau * (REACH / size)
    } else {
        *tau
    }
}

/// How far beyond the thrusters' summed capacity a command is taken as it is ([`within_reach`]).
const REACH: f64 = 10.0;

/// The allocation within the rates of `previous` (if given): the penalised problem, then the exact one if
/// the command is within reach.
fn within_rates(
    thrusters: &[Thruster],
    tau: &Vector6<f64>,
    previous: Option<&Previous<'_>>,
) -> Result<Allocation> {
    let penalised = solve(thrusters, tau, previous, false)?;
    if !penalised.saturated {
        // Within capacity: the slack to zero, so that τ is delivered to the solver's tolerance.
        if let Ok(exact) = solve(thrusters, tau, previous, true) {
            return Ok(exact);
        }
    }
    Ok(penalised)
}

/// The QP's solution; `exact`: with the slack held at zero (B u = τ), which fails when τ is beyond reach.
fn solve(
    thrusters: &[Thruster],
    tau: &Vector6<f64>,
    previous: Option<&Previous<'_>>,
    exact: bool,
) -> Result<Allocation> {
    // Scales: forces by the largest thruster, moments by it times the longest arm.
    let force_scale = thrusters.iter().map(|t| t.max_thrust).fold(0.0, f64::max);
    let arm = thrusters
        .iter()
        .map(|t| t.position.norm())
        .fold(1.0, f64::max);
    let target = [
        tau[0] / force_scale,
        tau[1] / force_scale,
        tau[5] / (force_scale * arm),
    ];
    // Unknowns: each thruster's one or two, then the three slacks.
    let mut first = Vec::with_capacity(thrusters.len());
    let mut unknowns = 0;
    for thruster in thrusters {
        first.push(unknowns);
        unknowns += if thruster.kind == ThrusterKind::Azimuth {
            2
        } else {
            1
        };
    }
    let slack = unknowns;
    let n = unknowns + 3;
    // Equalities B u − s = τ (scaled).
    let mut equalities = Rows::default();
    for (row, value) in target.iter().enumerate() {
        let mut coefficients = Vec::with_capacity(2 * thrusters.len() + 1);
        for (thruster, &column) in thrusters.iter().zip(&first) {
            let (x, y) = (thruster.position.x / arm, thruster.position.y / arm);
            match thruster.fixed_azimuth() {
                Some(azimuth) => {
                    let b = thruster.column(azimuth);
                    let scaled = [b[0], b[1], b[2] / arm];
                    coefficients.push((column, scaled[row]));
                }
                None => {
                    let (bx, by) = [(1.0, 0.0), (0.0, 1.0), (-y, x)][row];
                    coefficients.push((column, bx));
                    coefficients.push((column + 1, by));
                }
            }
        }
        coefficients.push((slack + row, -1.0));
        equalities.push(&coefficients, *value);
    }
    if exact {
        for row in 0..3 {
            equalities.push(&[(slack + row, 1.0)], 0.0);
        }
    }
    // Inequalities: thrust bounds and rates, azimuth sectors.
    let mut inequalities = Rows::default();
    let mut cones = Vec::new();
    let mut radii = Vec::new();
    for (k, (thruster, &column)) in thrusters.iter().zip(&first).enumerate() {
        let last = previous.map(|p| (p.states[k], p.dt));
        let rate_step = |rate: Option<f64>| rate.zip(last).map(|(r, (_, dt))| r * dt);
        match thruster.fixed_azimuth() {
            Some(_) => {
                let mut upper = thruster.max_thrust / force_scale;
                let mut lower = -thruster.reverse_thrust / force_scale;
                if let (Some(step), Some((state, _))) = (rate_step(thruster.thrust_rate), last) {
                    upper = upper.min((state.thrust + step) / force_scale);
                    lower = lower.max((state.thrust - step) / force_scale);
                }
                // A last thrust outside the bounds (a changed thruster) leaves the bounds themselves.
                if lower > upper {
                    lower = -thruster.reverse_thrust / force_scale;
                    upper = thruster.max_thrust / force_scale;
                }
                inequalities.push(&[(column, 1.0)], upper);
                inequalities.push(&[(column, -1.0)], -lower);
            }
            None => {
                let mut radius = thruster.max_thrust;
                if let (Some(step), Some((state, _))) = (rate_step(thruster.thrust_rate), last) {
                    radius = radius.min(state.thrust.abs() + step);
                }
                radii.push((column, radius / force_scale));
                if let (Some(turn), Some((state, _))) = (rate_step(thruster.azimuth_rate), last) {
                    if turn < FRAC_PI_2 {
                        // f to the left of the ray α⁻ − δ and to the right of α⁻ + δ.
                        let (s1, c1) = (state.azimuth - turn).sin_cos();
                        let (s2, c2) = (state.azimuth + turn).sin_cos();
                        inequalities.push(&[(column, s1), (column + 1, -c1)], 0.0);
                        inequalities.push(&[(column, -s2), (column + 1, c2)], 0.0);
                    }
                }
            }
        }
    }
    // Stack: zero cone (3), nonnegative cone, one second-order cone (3) per azimuth thruster.
    let mut rows = equalities.rows;
    let mut columns = equalities.columns;
    let mut values = equalities.values;
    let mut bounds = equalities.bounds;
    cones.push(ZeroConeT(bounds.len()));
    let offset = bounds.len();
    rows.extend(inequalities.rows.iter().map(|r| r + offset));
    columns.extend(inequalities.columns);
    values.extend(inequalities.values);
    bounds.extend(inequalities.bounds);
    if offset < bounds.len() {
        cones.push(NonnegativeConeT(bounds.len() - offset));
    }
    for (column, radius) in radii {
        // s = b − A u = (radius, f_x, f_y) in the second-order cone.
        let row = bounds.len();
        bounds.extend([radius, 0.0, 0.0]);
        rows.extend([row + 1, row + 2]);
        columns.extend([column, column + 1]);
        values.extend([-1.0, -1.0]);
        cones.push(SecondOrderConeT(3));
    }
    let a = CscMatrix::new_from_triplets(bounds.len(), n, rows, columns, values);
    let diagonal: Vec<f64> = (0..n)
        .map(|j| if j < slack { 1.0 } else { SLACK_WEIGHT })
        .collect();
    let p = CscMatrix::new_from_triplets(n, n, (0..n).collect(), (0..n).collect(), diagonal);
    let q = vec![0.0; n];
    let cones: Vec<SupportedConeT<f64>> = cones;
    let run = |max_iter: u32| {
        let settings = DefaultSettings {
            verbose: false,
            max_iter,
            ..DefaultSettings::default()
        };
        let mut solver =
            DefaultSolver::new(&p, &q, &a, &bounds, &cones, settings).map_err(|e| {
                Error::input(
                    "thrusters",
                    format!("{e:?}"),
                    "must give a well-posed allocation problem",
                )
            })?;
        solver.solve();
        Ok::<_, Error>(solver)
    };
    let mut solver = run(DefaultSettings::<f64>::default().max_iter)?;
    if matches!(solver.solution.status, SolverStatus::MaxIterations) {
        // Thrusters of very unequal sizes pushed far beyond them converge slowly: give it longer.
        solver = run(LONGER_ITERATIONS)?;
    }
    let status = solver.solution.status;
    if !matches!(status, SolverStatus::Solved | SolverStatus::AlmostSolved) {
        return Err(Error::Convergence {
            context: "thrust allocation (Clarabel)".into(),
            reached: 0.0,
            iterations: solver.solution.iterations as usize,
            residual: solver.solution.r_prim,
            reason: format!("the solver ended {status:?}"),
        });
    }
    let u = &solver.solution.x;
    let mut thrust = Vec::with_capacity(thrusters.len());
    let mut azimuth = Vec::with_capacity(thrusters.len());
    for (k, (thruster, &column)) in thrusters.iter().zip(&first).enumerate() {
        match thruster.fixed_azimuth() {
            Some(fixed) => {
                thrust.push(u[column] * force_scale);
                azimuth.push(fixed);
            }
            None => {
                let (fx, fy) = (u[column] * force_scale, u[column + 1] * force_scale);
                let magnitude = fx.hypot(fy);
                thrust.push(magnitude);
                // A thruster left idle keeps its azimuth.
                let idle = magnitude < 1e-9 * force_scale;
                let last = previous.map_or(0.0, |p| p.states[k].azimuth);
                azimuth.push(if idle { last } else { fy.atan2(fx) });
            }
        }
    }
    let states: Vec<ThrusterState> = thrust
        .iter()
        .zip(&azimuth)
        .map(|(&thrust, &azimuth)| ThrusterState { thrust, azimuth })
        .collect();
    let delivered = super::thrusters::generalised_force(thrusters, &states);
    let shortfall = ((delivered[0] - tau[0]) / force_scale)
        .hypot((delivered[1] - tau[1]) / force_scale)
        .hypot((delivered[5] - tau[5]) / (force_scale * arm));
    Ok(Allocation {
        thrust,
        azimuth,
        tau: delivered,
        saturated: shortfall > 1e-4,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vessel::thrusters::mss_supply_vessel;
    use nalgebra::Vector2;

    fn azimuths() -> Vec<Thruster> {
        let mut thrusters = mss_supply_vessel();
        thrusters.truncate(2);
        for y in [7.0, -7.0] {
            thrusters.push(
                Thruster::new(
                    ThrusterKind::Azimuth,
                    Vector2::new(-35.0, y),
                    400e3,
                    None,
                    Some(50e3),
                    Some(0.2),
                    2.0,
                )
                .unwrap(),
            );
        }
        thrusters
    }

    /// The fuzzing's case: two tunnels 456 times apart in size, pushed at five times their capacity; the
    /// solver's first run stops at its iteration limit (the slack's weight against a 1 kN thruster).
    #[test]
    fn a_command_beyond_very_unequal_thrusters_saturates_them() {
        let tunnel = |x: f64, y: f64, max: f64| {
            Thruster::new(
                ThrusterKind::Tunnel,
                Vector2::new(x, y),
                max,
                None,
                None,
                None,
                1.0,
            )
            .unwrap()
        };
        let thrusters = [tunnel(8.5, 1.75, 456_631.187_5), tunnel(0.0, 0.0, 1000.0)];
        let tau = Vector6::new(0.0, 2_333_673.687_5, 0.0, 0.0, 0.0, 0.0);
        let allocation = allocate(&thrusters, &tau, None).unwrap();
        assert!(allocation.saturated);
        assert!(
            (allocation.thrust[0] - 456_631.187_5).abs() < 1e-3 * 456_631.187_5,
            "{:?}",
            allocation.thrust
        );
        assert!(
            allocation.thrust[1].abs() <= 1000.0 * (1.0 + 1e-6),
            "{:?}",
            allocation.thrust
        );
    }

    #[test]
    fn a_feasible_command_is_delivered() {
        for thrusters in [mss_supply_vessel(), azimuths()] {
            let tau = Vector6::new(300e3, -150e3, 0.0, 0.0, 0.0, 2e6);
            let allocation = allocate(&thrusters, &tau, None).unwrap();
            let error = (allocation.tau - tau).abs().max();
            assert!(error < 1e-6 * 300e3, "{error} {:?}", allocation.tau);
            assert!(!allocation.saturated);
        }
    }

    #[test]
    fn minimum_norm_split_between_equal_tunnels() {
        // Pure sway on the MSS vessel: least squares of B u = τ splits it as the pseudo-inverse does.
        let thrusters = mss_supply_vessel();
        let tau = Vector6::new(0.0, 100e3, 0.0, 0.0, 0.0, 0.0);
        let allocation = allocate(&thrusters, &tau, None).unwrap();
        for k in 0..4 {
            assert!(
                (allocation.thrust[k] - 25e3).abs() < 1.0,
                "{:?}",
                allocation.thrust
            );
        }
    }

    #[test]
    fn an_infeasible_command_saturates_and_rates_hold() {
        let thrusters = mss_supply_vessel();
        let tau = Vector6::new(0.0, 2e6, 0.0, 0.0, 0.0, 0.0);
        let allocation = allocate(&thrusters, &tau, None).unwrap();
        assert!(allocation.saturated);
        for k in 0..4 {
            assert!((allocation.thrust[k] - 200e3).abs() < 1.0);
        }
        let thrusters = azimuths();
        let start: Vec<ThrusterState> = thrusters.iter().map(Thruster::at_rest).collect();
        let previous = Previous {
            states: &start,
            dt: 0.5,
        };
        let tau = Vector6::new(-500e3, 0.0, 0.0, 0.0, 0.0, 0.0);
        let allocation = allocate(&thrusters, &tau, Some(&previous)).unwrap();
        for k in 2..4 {
            assert!(allocation.thrust[k] <= 25e3 * (1.0 + 1e-6));
            // The command points where the thruster is wanted; it turns there at its rate.
            let next = thrusters[k].respond(&start[k], &allocation.states()[k], 0.5);
            assert!(next.azimuth.abs() <= 0.1 * (1.0 + 1e-9));
        }
    }
}
