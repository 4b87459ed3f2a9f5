//! Statics by continuation: from a state where Newton converges, one factor of the model at a time grows to its
//! value in steps that grow on easy convergence and halve on failure ([`Leg`]).
use crate::assembly::assembler::Assembler;
use crate::assembly::configuration::Configuration;
use crate::model::Model;
use crate::response::configuration::Response;
use crate::statics::newton::{newton, Newton};
use crate::statics::options::{StaticOptions, StaticSolution};

/// Smallest factor on the bending stiffness that the continuation from a cable starts at.
const CABLE_BENDING_SCALE: f64 = 1e-8;

/// A leg of statics' continuation: one factor grows from its start to 1 while the others hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Leg {
    /// The bending stiffness, geometrically from a cable's ([`CABLE_BENDING_SCALE`]) to the pipe's.
    Bending,
    /// The seabed's friction, from a frictionless seabed.
    Friction,
    /// The current's drag, from still water: the loads out of the pipe's plane come last.
    Current,
}

/// Where statics' continuation stands: factors on the bending stiffness, seabed friction and the current's drag.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Homotopy {
    bending: f64,
    friction: f64,
    current: f64,
}

impl Homotopy {
    /// The point at parameter t ∈ [0, legs.len()]: leg k's factor grows over t ∈ [k, k + 1]; a factor whose leg
    /// is not in `legs` is 1 throughout.
    fn at(t: f64, legs: &[Leg]) -> Self {
        let mut point = Homotopy {
            bending: 1.0,
            friction: 1.0,
            current: 1.0,
        };
        for (k, leg) in legs.iter().enumerate() {
            let progress = (t - k as f64).clamp(0.0, 1.0);
            match leg {
                Leg::Bending => {
                    point.bending = 10f64.powf(CABLE_BENDING_SCALE.log10() * (1.0 - progress))
                }
                Leg::Friction => point.friction = progress,
                Leg::Current => point.current = progress,
            }
        }
        point
    }

    fn apply(&self, assembler: &mut Assembler) {
        assembler.bending_scale = self.bending;
        assembler.current_scale = self.current;
        if let Some(contact) = &mut assembler.contact {
            contact.friction_scale = self.friction;
        }
    }
}

/// The legs `model` needs from a cable, in order: to the pipe, then to the seabed's friction (if it has any), then
/// to the current (if there is one).
pub fn legs_from_cable(model: &Model, assembler: &Assembler) -> Vec<Leg> {
    let mut legs = vec![Leg::Bending];
    if assembler.contact.as_ref().is_some_and(|c| c.has_friction()) {
        legs.push(Leg::Friction);
    }
    legs.extend(legs_from_still_water(model));
    legs
}

/// The leg from still water to the current, if `model` has one.
pub fn legs_from_still_water(model: &Model) -> Vec<Leg> {
    if model.sea.as_ref().is_some_and(|sea| sea.current.is_some()) {
        vec![Leg::Current]
    } else {
        Vec::new()
    }
}

impl std::fmt::Display for Leg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Leg::Bending => "the bending stiffness",
            Leg::Friction => "the seabed's friction",
            Leg::Current => "the current",
        })
    }
}

/// Where a continuation stalled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stall {
    /// Newton's and relaxation's iterations spent.
    pub iterations: usize,
    /// The leg it stalled on and how far that leg's factor had come (0 to 1); `None` at the legs' start.
    pub at: Option<(Leg, f64)>,
    /// The residual of the last attempt (N, N·m mixed).
    pub residual: f64,
}

impl std::fmt::Display for Stall {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.at {
            None => write!(
                f,
                "did not converge at its start (residual {:.3e})",
                self.residual
            ),
            Some((leg, progress)) => write!(
                f,
                "stalled with {leg} {:.1} % of the way in (residual {:.3e})",
                100.0 * progress,
                self.residual
            ),
        }
    }
}

/// Smallest continuation step before giving up.
const MIN_STEP: f64 = 1e-4;

/// Statics at full load by continuation from `config` along `legs` (Newton at full load when there are none):
/// first Newton at the legs' start, then each leg's factor in steps that grow on easy convergence and halve on
/// failure. From a cable (bending stiffness scaled down, which the catenary fits) to the pipe; from a
/// frictionless seabed to the seabed's friction (friction stays relative to statics' start, so the path does not
/// change the answer); from still water to the current. (Relaxing to a point Newton misses, from the last one
/// reached, rescued none of the robustness campaign's 1000 cases and cost up to 1.7 s in five: statics relax
/// only as a path of their own.)
pub fn continuation(
    model: &Model,
    assembler: &mut Assembler,
    mut config: Configuration,
    legs: &[Leg],
    options: &StaticOptions,
) -> std::result::Result<StaticSolution, Stall> {
    let end = legs.len() as f64;
    let mut t = 0.0;
    let mut step: f64 = 0.25;
    let mut iterations = 0;
    let mut steps = 0;
    let mut first = true;
    let mut last_residual = f64::NAN;
    let outcome = loop {
        let target = if first { 0.0 } else { (t + step).min(end) };
        Homotopy::at(target, legs).apply(assembler);
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
                iterations: its,
                residual,
            } => {
                iterations += its;
                last_residual = residual;
                step *= 0.5;
                if first || step < MIN_STEP {
                    break None;
                }
            }
        }
    };
    Homotopy::at(end, legs).apply(assembler);
    let Some(residual) = outcome else {
        // The leg and its factor where the last point reached stands (t = k + progress on leg k).
        let k = t.floor() as usize;
        let at = if first {
            None
        } else {
            legs.get(k.min(legs.len().saturating_sub(1)))
                .map(|leg| (*leg, t - k.min(legs.len().saturating_sub(1)) as f64))
        };
        return Err(Stall {
            iterations,
            at,
            residual: last_residual,
        });
    };
    Ok(StaticSolution {
        response: Response::with_assembler(model, &config, assembler),
        configuration: config,
        iterations,
        steps,
        residual,
        from_catenary: true,
        relaxations: 0,
    })
}
