//! Static equilibrium: Newton–Raphson with adaptive load stepping, optionally started from Irvine's
//! elastic catenary.
//!
//! The path from the stress-free reference has two stages along one parameter s ∈ [0, 2]: first the
//! loads grow (λ = s) with the supports at the reference, so that a hanging line is in tension before
//! its ends move; then the supports move to their prescribed positions and rotations (μ = s − 1).
// Indexing cannot go out of bounds here: Node, element and DOF indices of the mesh being solved.
#![allow(clippy::indexing_slicing)]
use crate::assembly::assembler::Assembler;
use crate::assembly::configuration::Configuration;
use crate::assembly::dofs::NODE_DOFS;
use crate::error::{Error, Result};
use crate::linalg::factorisation::Factorisation;
use crate::model::{Model, SupportTarget};
use crate::response::configuration::Response;
use crate::so3::{exp_quat, quat_from_matrix};
use crate::statics::start::catenary_guess;
use crate::statics::supports::support_increment;
use nalgebra::{Vector2, Vector3};

/// Where Newton starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// The catenary when it applies (both ends held in position, non-zero submerged weight), else the reference.
    Auto,
    /// The stress-free reference, with load stepping.
    Reference,
    /// Irvine's elastic catenary through the two held ends, at full load.
    Catenary,
}

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// Initial number of equal load steps (halved on failure, grown on easy convergence).
    pub initial_steps: usize,
    pub start: Start,
    /// Relative residual tolerance ‖r_free‖ ≤ tol · force scale.
    pub tolerance: f64,
    /// Newton iterations allowed per load step.
    pub max_iterations: usize,
    /// Smallest load step before giving up.
    pub min_step: f64,
    /// Largest nodal rotation increment per Newton iteration (rad); larger corrections are scaled down.
    pub max_rotation_increment: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions {
            initial_steps: 1,
            start: Start::Auto,
            tolerance: 1e-9,
            max_iterations: 30,
            min_step: 1e-6,
            max_rotation_increment: 0.5,
        }
    }
}

/// A converged static solution and how it was reached.
#[derive(Debug, Clone)]
pub struct StaticSolution {
    pub configuration: Configuration,
    /// Total Newton iterations.
    pub iterations: usize,
    /// Accepted load steps (1 when solved at full load directly).
    pub steps: usize,
    /// Final residual norm over the free DOFs.
    pub residual: f64,
    /// Whether Newton started from the elastic catenary.
    pub from_catenary: bool,
    /// Section forces, reactions and energy of the solution.
    pub response: Response,
}

/// Outcome of Newton at one load factor.
enum Newton {
    Converged { iterations: usize, residual: f64 },
    Failed { iterations: usize, residual: f64 },
}

/// A point of the loading path: load factor λ and support motion μ, both in [0, 1].
#[derive(Debug, Clone, Copy, PartialEq)]
struct PathPoint {
    load: f64,
    support: f64,
}

impl PathPoint {
    /// Stage 1 (s ≤ 1): loads; stage 2: support motion.
    fn at(s: f64) -> Self {
        PathPoint {
            load: s.min(1.0),
            support: (s - 1.0).clamp(0.0, 1.0),
        }
    }
}

/// Largest relative rotation between the nodes of one element that Newton may accept (rad): beyond it
/// the element's logarithm is near its branch cut at π and the iterate has jumped to a spurious state.
const MAX_ELEMENT_ROTATION: f64 = 2.5;

/// Newton iteration after which a residual larger than the first one counts as divergence.
const DIVERGENCE_CHECK: usize = 8;

/// Newton at load factor λ. With `support_increment`, the first iteration is the linearised Dirichlet
/// predictor: it moves the supports by their increments and the free DOFs by −K_ff⁻¹(r_f + K_fc Δu_c),
/// so that a support's motion spreads along the rod instead of straining one element.
fn newton(
    model: &Model,
    assembler: &mut Assembler,
    config: &mut Configuration,
    load_factor: f64,
    mut support_increment: Option<&[f64]>,
    options: &StaticOptions,
) -> Newton {
    let mut delta = vec![0.0; assembler.dofs.free];
    let round_off = round_off_floor(model);
    let length_scale = model.rod.length();
    let mut residual = f64::INFINITY;
    let mut first_residual = f64::INFINITY;
    for iteration in 0..=options.max_iterations {
        let summary = assembler.assemble(model, config, load_factor, true, support_increment);
        if summary.max_element_rotation > MAX_ELEMENT_ROTATION {
            break;
        }
        let mut free_norm2 = 0.0;
        let mut fixed_norm2 = 0.0;
        for (r, eq) in assembler.residual.iter().zip(&assembler.dofs.equation) {
            match eq {
                Some(_) => free_norm2 += r * r,
                None => fixed_norm2 += r * r,
            }
        }
        residual = free_norm2.sqrt();
        let scale = summary.external_norm.max(fixed_norm2.sqrt());
        // After the predictor, measure progress from the first true Newton residual.
        if iteration <= 1 {
            first_residual = residual;
        }
        // Divergence: no progress after several iterations means a smaller load step is cheaper.
        let diverging = iteration >= DIVERGENCE_CHECK && residual > first_residual;
        if !residual.is_finite() || diverging {
            return Newton::Failed {
                iterations: iteration,
                residual,
            };
        }
        if support_increment.is_none() && residual <= options.tolerance * scale + round_off {
            return Newton::Converged {
                iterations: iteration,
                residual,
            };
        }
        if iteration == options.max_iterations || assembler.lu.factorise(&assembler.values).is_err()
        {
            break;
        }
        for ((r, c), eq) in assembler
            .residual
            .iter()
            .zip(&assembler.support_coupling)
            .zip(&assembler.dofs.equation)
        {
            if let Some(i) = eq {
                delta[*i] = -(r + c);
            }
        }
        if assembler.lu.solve_in_place(&mut delta).is_err() || delta.iter().any(|d| !d.is_finite())
        {
            break;
        }
        // Scale the whole correction if a node would turn by more than the allowed increment.
        let mut largest_rotation: f64 = 0.0;
        let mut largest_translation: f64 = 0.0;
        for node in 0..model.rod.node_count() {
            let mut spin = Vector3::zeros();
            for k in 0..3 {
                if let Some(i) = assembler.dofs.equation[NODE_DOFS * node + 3 + k] {
                    spin[k] = delta[i];
                }
                if let Some(i) = assembler.dofs.equation[NODE_DOFS * node + k] {
                    largest_translation = largest_translation.max(delta[i].abs());
                }
            }
            largest_rotation = largest_rotation.max(spin.norm());
        }
        let predictor = support_increment.is_some();
        let mut factor = match support_increment.take() {
            Some(increment) => {
                apply_increment(config, increment);
                1.0
            }
            None => (options.max_rotation_increment / largest_rotation).min(1.0),
        };
        // With seabed contact (non-smooth friction, contact switching), backtrack along the correction while
        // the residual grows. Not with rollers: a roller's contact switching raises the residual for an
        // iteration on the way to convergence, and backtracking then stalls.
        let start = (assembler.contact.is_some() && assembler.rollers.is_none() && !predictor)
            .then(|| config.clone());
        for _ in 0..LINE_SEARCH_HALVINGS {
            apply_correction(model, assembler, config, &delta, factor);
            let Some(start) = &start else { break };
            assembler.assemble(model, config, load_factor, false, None);
            let trial = free_norm(assembler);
            let floor = 1e3 * (options.tolerance * scale + round_off);
            if trial.is_finite() && (trial <= residual || trial <= floor) {
                break;
            }
            config.clone_from(start);
            factor *= 0.5;
        }
        // Stagnation at round-off with a residual already small is convergence too.
        if factor == 1.0
            && largest_translation <= 1e-13 * length_scale
            && largest_rotation <= 1e-13
            && residual <= 1e-6 * scale
        {
            return Newton::Converged {
                iterations: iteration + 1,
                residual,
            };
        }
    }
    Newton::Failed {
        iterations: options.max_iterations,
        residual,
    }
}

/// Round-off floor of the residual norm (N): an element's axial force carries an error of about
/// ε·EA·|x|/L0 (positions |x| known to ε relative, differenced over the element length), and n of them add up
/// like a random walk. Never below 1e-13·EA·√n. A vessel's holding springs add theirs.
fn round_off_floor(model: &Model) -> f64 {
    let extent = model.rod.nodes.iter().map(|x| x.norm()).fold(1.0, f64::max);
    let shortest = model
        .rod
        .elements
        .iter()
        .map(|e| e.length)
        .fold(f64::INFINITY, f64::min);
    let per_element = (4.0 * f64::EPSILON * extent / shortest).max(1e-13);
    let vessel = model.vessel.as_ref().map_or(0.0, |attachment| {
        crate::vessel::coupling::static_round_off(attachment, extent)
    });
    per_element
        * model.rod.largest(|s| s.translational_stiffness.max())
        * (model.rod.element_count() as f64).sqrt()
        + vessel
}

/// Backtracking steps of the line search with seabed contact.
const LINE_SEARCH_HALVINGS: usize = 6;

/// Norm of the residual over the free DOFs.
fn free_norm(assembler: &Assembler) -> f64 {
    assembler
        .residual
        .iter()
        .zip(&assembler.dofs.equation)
        .filter(|(_, eq)| eq.is_some())
        .map(|(r, _)| r * r)
        .sum::<f64>()
        .sqrt()
}

/// Moves the free DOFs of `config` by `factor` times the Newton correction `delta`.
fn apply_correction(
    model: &Model,
    assembler: &Assembler,
    config: &mut Configuration,
    delta: &[f64],
    factor: f64,
) {
    for node in 0..model.rod.node_count() {
        let mut spin = Vector3::zeros();
        for k in 0..3 {
            if let Some(i) = assembler.dofs.equation[NODE_DOFS * node + k] {
                config.positions[node][k] += factor * delta[i];
            }
            if let Some(i) = assembler.dofs.equation[NODE_DOFS * node + 3 + k] {
                spin[k] = factor * delta[i];
            }
        }
        if spin != Vector3::zeros() {
            config.rotations[node] = exp_quat(&spin) * config.rotations[node];
        }
    }
}

/// Adds an increment given on all DOFs (positions and spatial spins) to a configuration.
fn apply_increment(config: &mut Configuration, increment: &[f64]) {
    for (node, du) in increment.chunks_exact(NODE_DOFS).enumerate() {
        config.positions[node] += Vector3::new(du[0], du[1], du[2]);
        let spin = Vector3::new(du[3], du[4], du[5]);
        if spin != Vector3::zeros() {
            config.rotations[node] = exp_quat(&spin) * config.rotations[node];
        }
    }
}

/// Smallest factor on the bending stiffness that the continuation from a cable starts at.
const CABLE_BENDING_SCALE: f64 = 1e-8;

/// Where statics' continuation stands: factors on the bending stiffness and on seabed friction.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Homotopy {
    bending: f64,
    friction: f64,
}

impl Homotopy {
    /// The point at parameter t ∈ [0, 2]: first the bending stiffness grows geometrically from a cable's
    /// ([`CABLE_BENDING_SCALE`]) to the pipe's (t ≤ 1), without friction; then friction grows to its value.
    fn at(t: f64, bending_from_cable: bool) -> Self {
        let bending = if bending_from_cable {
            10f64.powf(CABLE_BENDING_SCALE.log10() * (1.0 - t.min(1.0)))
        } else {
            1.0
        };
        Homotopy {
            bending,
            friction: (t - 1.0).clamp(0.0, 1.0),
        }
    }

    fn apply(&self, assembler: &mut Assembler) {
        assembler.bending_scale = self.bending;
        if let Some(contact) = &mut assembler.contact {
            contact.friction_scale = self.friction;
        }
    }
}

/// Statics at full load by continuation from the catenary `guess`: from a cable (bending stiffness scaled
/// down, which the catenary fits) to the pipe, then from a frictionless seabed to the seabed's friction
/// (friction stays relative to statics' start, so the path does not change the answer), in steps that grow on
/// easy convergence and halve on failure. `None` if it stalls.
fn continuation(
    model: &Model,
    assembler: &mut Assembler,
    mut config: Configuration,
    options: &StaticOptions,
) -> Option<StaticSolution> {
    let from_cable = true;
    let end = if assembler.contact.as_ref().is_some_and(|c| c.has_friction()) {
        2.0
    } else {
        1.0
    };
    let mut t = 0.0;
    let mut step: f64 = 0.25;
    let mut iterations = 0;
    let mut steps = 0;
    let mut first = true;
    let outcome = loop {
        let target = if first { 0.0 } else { (t + step).min(end) };
        Homotopy::at(target, from_cable).apply(assembler);
        let mut trial = config.clone();
        match newton(model, assembler, &mut trial, 1.0, None, options) {
            Newton::Converged {
                iterations: its,
                residual,
            } => {
                iterations += its;
                steps += 1;
                config = trial;
                t = target;
                first = false;
                if t >= end {
                    break Some(residual);
                }
                if its <= 6 {
                    step = (2.0 * step).min(0.5);
                }
            }
            Newton::Failed {
                iterations: its, ..
            } => {
                iterations += its;
                step *= 0.5;
                if first || step < 1e-4 {
                    break None;
                }
            }
        }
    };
    Homotopy::at(2.0, false).apply(assembler);
    let residual = outcome?;
    Some(StaticSolution {
        response: Response::with_assembler(model, &config, assembler),
        configuration: config,
        iterations,
        steps,
        residual,
        from_catenary: true,
    })
}

/// Solves for static equilibrium at full load. A vessel found upside down or on its side (its body axis b3
/// more than 60° from the vertical: an equilibrium of the restoring's director form that no vessel floats in)
/// is a failure.
pub fn solve(model: &Model, options: &StaticOptions) -> Result<StaticSolution> {
    // On the engine's threads, where the factorisation and contact run in parallel.
    let solution = crate::linalg::pool::run(
        crate::linalg::pool::worth_it(model.rod.element_count()),
        || solve_unchecked(model, options),
    )?;
    if let Some(attachment) = &model.vessel {
        let node = attachment.node;
        let body = crate::vessel::coupling::body_rotation(
            attachment,
            &solution.configuration.rotations[node],
        );
        let upright = body.column(2).z;
        if upright < 0.5 {
            let angles = crate::vessel::euler::angles_from_rotation(&body);
            return Err(Error::Convergence {
                context: "static solve".into(),
                reached: 1.0,
                iterations: solution.iterations,
                residual: solution.residual,
                reason: format!(
                    "the vessel's equilibrium found is capsized (roll {:.3} rad, pitch {:.3} rad); start from the \
                     catenary (start=\"auto\") or give more load steps",
                    angles.x, angles.y
                ),
            });
        }
    }
    Ok(solution)
}

/// Static equilibrium of `model` found by Newton at full load from `start`, a configuration near it (the state a
/// stage of a lay starts from statics of, [`crate::dynamics::stages`]): supports and point loads at `time` (s),
/// the seabed's friction measured from `start` with its `slips`. Fails (`Error::Convergence`) where Newton
/// does.
pub fn solve_from(
    model: &Model,
    options: &StaticOptions,
    start: Configuration,
    slips: &[Vector2<f64>],
    time: f64,
) -> Result<StaticSolution> {
    let mut assembler = static_assembler(model, time)?;
    assembler.contact_start.clone_from(&start.positions);
    assembler.contact_slips = slips.to_vec();
    let mut config = start;
    match newton(model, &mut assembler, &mut config, 1.0, None, options) {
        Newton::Converged {
            iterations,
            residual,
        } => Ok(StaticSolution {
            response: Response::with_assembler(model, &config, &mut assembler),
            configuration: config,
            iterations,
            steps: 1,
            residual,
            from_catenary: false,
        }),
        Newton::Failed {
            iterations,
            residual,
        } => Err(Error::Convergence {
            context: "static solve".into(),
            reached: time,
            iterations,
            residual,
            reason: format!("Newton did not converge from the configuration at t = {time} s"),
        }),
    }
}

/// An assembler of `model`'s statics with its point loads scaled as at `time` (s).
fn static_assembler(model: &Model, time: f64) -> Result<Assembler> {
    let mut assembler = Assembler::new(model);
    assembler.point_load_scales = model
        .point_loads
        .iter()
        .map(|load| load.scale_at(time))
        .collect::<Result<_>>()?;
    Ok(assembler)
}

fn solve_unchecked(model: &Model, options: &StaticOptions) -> Result<StaticSolution> {
    if options.initial_steps == 0 {
        return Err(Error::input("steps", 0, "must be an integer >= 1"));
    }
    if model.supports.is_empty() && model.vessel.is_none() {
        return Err(Error::input(
            "supports",
            "none",
            "a static solve needs the rod held: clamp, pin or drive an end, or attach a vessel",
        ));
    }
    // Statics is the state at t = 0: supports (drives included) and load scales are taken there.
    let targets = model.support_targets(0.0)?;
    let mut assembler = static_assembler(model, 0.0)?;
    let mut iterations = 0;
    // A vessel holds its end where η puts it, upright at the surface: a target for the catenary guess.
    let mut guess_targets = targets.clone();
    if let Some(attachment) = &model.vessel {
        let mut upright = attachment.eta;
        upright[2] = attachment.surface;
        upright[3] = 0.0;
        upright[4] = 0.0;
        let rotation = crate::vessel::coupling::node_rotation(attachment, &upright);
        let body = rotation * attachment.angle;
        guess_targets.push(SupportTarget {
            node: attachment.node,
            position: crate::vessel::coupling::node_position(
                attachment,
                &upright.fixed_rows::<3>(0).into_owned(),
                &body,
            ),
            rotation: Some(quat_from_matrix(&rotation)),
        });
    }
    let catenary = match options.start {
        Start::Reference => None,
        Start::Auto => catenary_guess(model, &guess_targets),
        Start::Catenary => Some(catenary_guess(model, &guess_targets).ok_or_else(|| {
            Error::input(
                "start",
                "\"catenary\"",
                "needs exactly two supports, at ends A and B, and a non-zero submerged weight",
            )
        })?),
    };
    if let Some(guess) = catenary {
        let mut config = guess.clone();
        match newton(model, &mut assembler, &mut config, 1.0, None, options) {
            Newton::Converged {
                iterations: its,
                residual,
            } => {
                return Ok(StaticSolution {
                    response: Response::with_assembler(model, &config, &mut assembler),
                    configuration: config,
                    iterations: its,
                    steps: 1,
                    residual,
                    from_catenary: true,
                });
            }
            Newton::Failed {
                iterations: its, ..
            } => iterations += its,
        }
        // A stiff pipe far from the catenary, or friction: follow the solution from a cable on a frictionless
        // seabed to the pipe with its friction.
        if let Some(mut solution) = continuation(model, &mut assembler, guess, options) {
            solution.iterations += iterations;
            return Ok(solution);
        }
    }

    let mut config = Configuration::reference(model);
    let mut path = 0.0;
    let mut step = 1.0 / options.initial_steps as f64;
    let mut steps = 0;
    loop {
        let target = (path + step).min(2.0);
        let point = PathPoint::at(target);
        let mut trial = config.clone();
        let increment = support_increment(model, &targets, &trial, point.support);
        assembler.vessel_motion = point.support;
        let moves = increment.iter().any(|&du| du != 0.0);
        let outcome = newton(
            model,
            &mut assembler,
            &mut trial,
            point.load,
            moves.then_some(&increment[..]),
            options,
        );
        match outcome {
            Newton::Converged {
                iterations: its,
                residual,
            } => {
                iterations += its;
                steps += 1;
                assembler.commit_contact(&trial);
                config = trial;
                path = target;
                if path >= 2.0 {
                    return Ok(StaticSolution {
                        response: Response::with_assembler(model, &config, &mut assembler),
                        configuration: config,
                        iterations,
                        steps,
                        residual,
                        from_catenary: false,
                    });
                }
                if its <= 8 {
                    step *= 2.0;
                }
            }
            Newton::Failed {
                iterations: its,
                residual,
            } => {
                iterations += its;
                step *= 0.5;
                if step < options.min_step {
                    let reached = PathPoint::at(path);
                    return Err(Error::Convergence {
                        context: "static solve".into(),
                        reached: reached.load,
                        iterations: its,
                        residual,
                        reason: format!(
                            "load step fell below {:.0e} at load factor {:.6} with the supports moved {:.6} of the way",
                            options.min_step, reached.load, reached.support
                        ),
                    });
                }
            }
        }
    }
}
