//! Static equilibrium: the paths statics tries, in order, and the check of what they converge to.
//!
//! 1. From the catenary guess over the rollers ([`catenary_guess`]): Newton in still water at full stiffness,
//!    then the current brought in by continuation ([`continuation`]);
//! 2. from the same guess as a cable on a frictionless seabed in still water: the pipe's bending stiffness, the
//!    seabed's friction and the current, one after the other;
//! 3. relaxation from the guess at full load ([`relax`]);
//!
//! paths 1–3 with Newton's steps kept from carrying the line through a stinger's rollers
//! ([`crate::statics::newton::roller_step_factor`]), then, where that kept it from sliding far along them,
//! again with the steps free;
//! 4. from the stress-free reference (without a guess, or when all else fails), along one parameter
//!    s ∈ [0, 2]: first the loads grow (λ = s) with the supports at the reference, so that a hanging line is in
//!    tension before its ends move; then the supports move to their prescribed positions and rotations
//!    (μ = s − 1).
//!
//! A path's converged state is accepted only if it is physical ([`physical::check`]): else the next path is
//! tried, and if none gives a physical state the solve fails saying what is wrong and what to change.
// Indexing cannot go out of bounds here: Node, element and DOF indices of the mesh being solved.
#![allow(clippy::indexing_slicing)]
use crate::assembly::assembler::Assembler;
use crate::assembly::configuration::Configuration;
use crate::error::{Error, Result};
use crate::model::{Model, SupportTarget};
use crate::response::configuration::Response;
use crate::so3::quat_from_matrix;
use crate::statics::continuation::{continuation, legs_from_cable, legs_from_still_water};
use crate::statics::newton::{newton, Newton};
use crate::statics::physical::{self, Unphysical};
use crate::statics::relaxation::relax;
use crate::statics::start::catenary_guess;
use crate::statics::supports::support_increment;
use nalgebra::Vector2;

pub use crate::statics::options::{Start, StaticOptions, StaticSolution};

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

/// Solves for static equilibrium at full load: the first physical state of the paths tried in turn (see the
/// module's documentation).
pub fn solve(model: &Model, options: &StaticOptions) -> Result<StaticSolution> {
    // On the engine's threads, where the factorisation and contact run in parallel.
    crate::linalg::pool::run(
        crate::linalg::pool::worth_it(model.rod.element_count()),
        || solve_on_paths(model, options, 0.0, None),
    )
}

/// What the paths tried so far came to: their iterations, and what each one reached.
#[derive(Default)]
struct Attempts {
    iterations: usize,
    /// Each path's name and outcome, in the order tried.
    outcomes: Vec<(String, String)>,
    /// The first unphysical state a path converged to, and its residual.
    unphysical: Option<(Unphysical, f64)>,
    /// The last path's failure, reported as it is when it is the only one.
    failure: Option<Error>,
}

impl Attempts {
    /// The solution of path `path`, if it is physical; else it is noted and `None`.
    fn accept(
        &mut self,
        model: &Model,
        path: &str,
        mut solution: StaticSolution,
    ) -> Option<StaticSolution> {
        self.iterations += solution.iterations;
        match verdict(model, &solution) {
            None => {
                solution.iterations = self.iterations;
                Some(solution)
            }
            Some(unphysical) => {
                self.outcomes.push((
                    path.to_string(),
                    format!("converged to a state that is not physical: {unphysical}"),
                ));
                self.unphysical
                    .get_or_insert((unphysical, solution.residual));
                None
            }
        }
    }

    /// Path `path` failed after `iterations`, as `outcome` says.
    fn failed(&mut self, path: &str, iterations: usize, outcome: String) {
        self.iterations += iterations;
        self.outcomes.push((path.to_string(), outcome));
    }

    /// The error to report when no path gave a physical state: each path's outcome, and what to change (in a
    /// reel-lay, the straightener too).
    fn error(self, model: &Model) -> Error {
        if let (1, Some(failure)) = (self.outcomes.len(), self.failure) {
            return failure;
        }
        let tried: Vec<String> = self
            .outcomes
            .iter()
            .map(|(path, outcome)| format!("{path} {outcome}"))
            .collect();
        let (residual, mut advice) = match self.unphysical {
            Some((unphysical, residual)) => (residual, unphysical.advice().to_string()),
            None => (
                f64::NAN,
                "check that the line can hang between its supports (its length, the vessel's position, the \
                 stinger), or give the reference path more load steps"
                    .to_string(),
            ),
        };
        if let Some(kept) = model.reeled_residual_curvature() {
            advice.push_str(&format!(
                "; the reeled pipe leaves the straightener with a residual curvature of {kept:.3e} 1/m (a radius \
                 of {:.0} m): set the straightener that leaves it straight (pl.design_straightener)",
                1.0 / kept.abs()
            ));
        }
        Error::Convergence {
            context: "static solve".into(),
            reached: if self.unphysical.is_some() { 1.0 } else { 0.0 },
            iterations: self.iterations,
            residual,
            reason: format!(
                "no path reached a physical state: {}; {advice}",
                tried.join("; ")
            ),
        }
    }
}

/// Why a converged solution of `model` is not physical, if it is not ([`physical::check`]).
fn verdict(model: &Model, solution: &StaticSolution) -> Option<Unphysical> {
    let configuration = &solution.configuration;
    let nearest = solution
        .response
        .rollers
        .as_ref()
        .map_or(&[][..], |rollers| &rollers.elements[..]);
    let reactions = solution
        .response
        .rollers
        .as_ref()
        .map_or(&[][..], |rollers| &rollers.reactions[..]);
    physical::check(
        model,
        &configuration.positions,
        &configuration.rotations,
        &configuration.hinge_angles,
        nearest,
    )
    .or_else(|| physical::pushed_down(model, &configuration.hinge_angles, reactions))
}

/// Static equilibrium of `model` found from `start`, a configuration near it (the state a stage of a lay starts
/// from statics of, [`crate::dynamics::stages`]): by Newton at full load, else by relaxation, else (a start far
/// from equilibrium) along the paths of a model's first statics ([`solve`]); supports and point loads at
/// `time` (s), the seabed's friction measured from `start` with its `slips` (from scratch, from the path's
/// start), yielding walls from the plastic states `plastic` (each element's fibres', a run's). Fails
/// (`Error::Convergence`) where all do, or where the state reached is not physical.
pub fn solve_from(
    model: &Model,
    options: &StaticOptions,
    start: Configuration,
    slips: &[Vector2<f64>],
    plastic: &[Vec<f64>],
    time: f64,
) -> Result<StaticSolution> {
    let mut assembler = static_assembler(model, time)?;
    assembler.start_plastic_from(plastic);
    assembler.contact_start.clone_from(&start.positions);
    assembler.contact_slips = slips.to_vec();
    let mut config = start.clone();
    let mut relaxations = 0;
    let mut outcome = newton(model, &mut assembler, &mut config, 1.0, None, options);
    if let Newton::Failed { iterations, .. } = outcome {
        config = start;
        relaxations = 1;
        outcome = match relax(model, &mut assembler, &mut config, 1.0, options) {
            Newton::Converged {
                iterations: its,
                residual,
            } => Newton::Converged {
                iterations: iterations + its,
                residual,
            },
            Newton::Failed {
                iterations: its,
                residual,
            } => Newton::Failed {
                iterations: iterations + its,
                residual,
            },
        };
    }
    match outcome {
        Newton::Converged {
            iterations,
            residual,
        } => {
            let solution = StaticSolution {
                response: Response::with_assembler(model, &config, &mut assembler),
                configuration: config,
                iterations,
                steps: 1,
                residual,
                from_catenary: false,
                relaxations,
            };
            match verdict(model, &solution) {
                None => Ok(solution),
                Some(unphysical) => Err(Error::Convergence {
                    context: "static solve".into(),
                    reached: time,
                    iterations,
                    residual,
                    reason: format!(
                        "the state reached from the configuration at t = {time} s is not physical: {unphysical}; {}",
                        unphysical.advice()
                    ),
                }),
            }
        }
        // Far from equilibrium: the paths a model's first statics take, with the supports and loads at `time`.
        Newton::Failed { iterations, .. } => solve_on_paths(model, options, time, Some(plastic))
            .map(|mut solution| {
                solution.iterations += iterations;
                solution.relaxations += relaxations;
                solution
            })
            .map_err(|error| match error {
                Error::Convergence {
                    iterations: more,
                    residual,
                    reason,
                    ..
                } => Error::Convergence {
                    context: "static solve".into(),
                    reached: time,
                    iterations: iterations + more,
                    residual,
                    reason: format!(
                        "neither Newton nor relaxation converged from the configuration at t = {time} s, and \
                         from scratch: {reason}"
                    ),
                },
                other => other,
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

/// The supports' targets of the catenary guess: the supports at t = 0 and, with a vessel, its end where η puts
/// it, upright at the surface.
fn guess_targets(model: &Model, targets: &[SupportTarget]) -> Vec<SupportTarget> {
    let mut guess_targets = targets.to_vec();
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
    guess_targets
}

/// The paths of the module's documentation, in turn, until one gives a physical state: supports and point loads
/// at `time` (s), yielding walls from the plastic states `plastic` (None: the state at rest).
fn solve_on_paths(
    model: &Model,
    options: &StaticOptions,
    time: f64,
    plastic: Option<&[Vec<f64>]>,
) -> Result<StaticSolution> {
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
    let targets = model.support_targets(time)?;
    let mut assembler = static_assembler(model, time)?;
    if let Some(plastic) = plastic {
        assembler.start_plastic_from(plastic);
    }
    let catenary = match options.start {
        Start::Reference => None,
        Start::Auto => catenary_guess(model, &guess_targets(model, &targets)),
        Start::Catenary => Some(
            catenary_guess(model, &guess_targets(model, &targets)).ok_or_else(|| {
                Error::input(
                    "start",
                    "\"catenary\"",
                    "needs exactly two supports, at ends A and B, and a non-zero submerged weight",
                )
            })?,
        ),
    };
    let mut attempts = Attempts::default();
    if let Some(guess) = &catenary {
        let paths = [
            (
                "Newton from the catenary in still water, then the current,",
                legs_from_still_water(model),
            ),
            (
                "the continuation from a cable (bending, friction, current)",
                legs_from_cable(model, &assembler),
            ),
        ];
        // Newton's steps kept from carrying the line through the rollers first; where that also keeps it from
        // sliding far along them (a strong current across the lay), every path again with the steps free.
        let passes: &[bool] = if assembler.rollers.is_some() {
            &[true, false]
        } else {
            &[true]
        };
        for &limited in passes {
            assembler.limit_roller_steps = limited;
            let free = if limited {
                ""
            } else {
                " (steps on the stinger free)"
            };
            for (path, legs) in &paths {
                let path = format!("{path}{free}");
                match continuation(model, &mut assembler, guess.clone(), legs, options) {
                    Ok(solution) => {
                        if let Some(solution) = attempts.accept(model, &path, solution) {
                            return Ok(solution);
                        }
                    }
                    Err(stall) => attempts.failed(&path, stall.iterations, stall.to_string()),
                }
            }
            let path = format!("relaxation from the catenary{free}");
            let mut config = guess.clone();
            match relax(model, &mut assembler, &mut config, 1.0, options) {
                Newton::Converged {
                    iterations,
                    residual,
                } => {
                    let solution = StaticSolution {
                        response: Response::with_assembler(model, &config, &mut assembler),
                        configuration: config,
                        iterations,
                        steps: 1,
                        residual,
                        from_catenary: true,
                        relaxations: 1,
                    };
                    if let Some(solution) = attempts.accept(model, &path, solution) {
                        return Ok(solution);
                    }
                }
                Newton::Failed {
                    iterations,
                    residual,
                } => attempts.failed(
                    &path,
                    iterations,
                    format!(
                        "did not converge in {iterations} iterations (residual {residual:.3e})"
                    ),
                ),
            }
        }
        assembler.limit_roller_steps = true;
    }
    let path = "the path from the straight reference";
    match from_reference(model, &mut assembler, &targets, options) {
        Ok(solution) => {
            if let Some(solution) = attempts.accept(model, path, solution) {
                return Ok(solution);
            }
        }
        Err(failure) => {
            let outcome = match &failure {
                Error::Convergence { reason, .. } => format!("failed: {reason}"),
                other => format!("failed: {other}"),
            };
            attempts.failed(path, 0, outcome);
            attempts.failure = Some(failure);
        }
    }
    Err(attempts.error(model))
}

/// Statics along the path from the stress-free reference: the loads, then the supports' motion.
fn from_reference(
    model: &Model,
    assembler: &mut Assembler,
    targets: &[SupportTarget],
    options: &StaticOptions,
) -> Result<StaticSolution> {
    let mut config = Configuration::reference(model);
    let mut path = 0.0;
    let mut step = 1.0 / options.initial_steps as f64;
    let mut steps = 0;
    let mut iterations = 0;
    loop {
        let target = (path + step).min(2.0);
        let point = PathPoint::at(target);
        let mut trial = config.clone();
        let increment = support_increment(model, targets, &trial, point.support);
        assembler.vessel_motion = point.support;
        let moves = increment.iter().any(|&du| du != 0.0);
        let outcome = newton(
            model,
            assembler,
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
                        response: Response::with_assembler(model, &config, assembler),
                        configuration: config,
                        iterations,
                        steps,
                        residual,
                        from_catenary: false,
                        relaxations: 0,
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
