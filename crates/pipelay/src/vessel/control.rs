//! The DP controller (eqs. 44–45): PID on η with a bounded integral, thrust in surge, sway and yaw, about a
//! fixed reference, a lay route or a reference given as a function of time.
// Indexing cannot go out of bounds here: 6-vectors of the vessel's degrees of freedom indexed by constants.
#![allow(clippy::indexing_slicing)]
use super::euler;
use super::route_path::RoutePath;
use crate::error::{finite, Error, Result};
use crate::table::{travel, Leg, TimeFunction};
use nalgebra::{Matrix3, Matrix6, Vector2, Vector3, Vector6};

/// The pose η_ref(t) the controller holds or follows, and its rate η̇_ref(t).
#[derive(Clone)]
pub enum Reference {
    /// A fixed pose [x, y, z, φ, θ, ψ] (m, rad).
    Fixed(Vector6<f64>),
    /// A lay route: from `start` (x, y), along `heading` ψ, in legs of speed ([`Leg`], in time order, each
    /// lasting until the next); before the first the route waits at `start`. z, φ, θ zero.
    Route {
        start: Vector2<f64>,
        heading: f64,
        legs: Vec<Leg>,
    },
    /// A lay route through waypoints with arcs at its corners ([`RoutePath`]), travelled in legs of speed from
    /// its start; the heading is the path's, and at its end the route stops. z, φ, θ zero.
    Path { path: RoutePath, legs: Vec<Leg> },
    /// References in pieces: each (its start time (s), the reference from then on), in time order; before the
    /// first piece's start, the first piece (the stages of a lay: a new DP set-point starts a piece).
    Pieces(Vec<(f64, Reference)>),
    /// A function of time, and its rate (else central differences over a millisecond).
    Function {
        pose: TimeFunction<Vector6<f64>>,
        rate: Option<TimeFunction<Vector6<f64>>>,
    },
}

impl std::fmt::Debug for Reference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Reference::Fixed(pose) => write!(f, "Fixed({:?})", pose.as_slice()),
            Reference::Route {
                start,
                heading,
                legs,
            } => write!(
                f,
                "Route(start={:?}, heading={heading}, legs={legs:?})",
                start.as_slice()
            ),
            // All of the path: a checkpoint's fingerprint tells two routes apart by it.
            Reference::Path { path, legs } => write!(f, "Path({path:?}, legs={legs:?})"),
            Reference::Pieces(pieces) => write!(f, "Pieces({pieces:?})"),
            Reference::Function { .. } => write!(f, "Function"),
        }
    }
}

impl PartialEq for Reference {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (Reference::Fixed(a), Reference::Fixed(b)) => a == b,
            (
                Reference::Route {
                    start: a,
                    heading: b,
                    legs: c,
                },
                Reference::Route {
                    start: d,
                    heading: e,
                    legs: g,
                },
            ) => a == d && b == e && c == g,
            (Reference::Path { path: a, legs: b }, Reference::Path { path: c, legs: d }) => {
                a == c && b == d
            }
            (Reference::Pieces(a), Reference::Pieces(b)) => a == b,
            (Reference::Function { pose: a, .. }, Reference::Function { pose: b, .. }) => {
                std::sync::Arc::ptr_eq(a, b)
            }
            _ => false,
        }
    }
}

impl Reference {
    /// η_ref(t) and η̇_ref(t); a function's failure or a non-finite value names `reference` and the time.
    pub fn at(&self, time: f64) -> Result<(Vector6<f64>, Vector6<f64>)> {
        match self {
            Reference::Fixed(pose) => Ok((*pose, Vector6::zeros())),
            Reference::Route {
                start,
                heading,
                legs,
            } => {
                let (sin, cos) = heading.sin_cos();
                let (travelled, speed) = travel(legs, time);
                let pose = Vector6::new(
                    start.x + travelled * cos,
                    start.y + travelled * sin,
                    0.0,
                    0.0,
                    0.0,
                    *heading,
                );
                let rate = Vector6::new(speed * cos, speed * sin, 0.0, 0.0, 0.0, 0.0);
                Ok((pose, rate))
            }
            Reference::Path { path, legs } => {
                let (travelled, speed) = travel(legs, time);
                let at = path.at(travelled);
                // At the path's end the route stops.
                let speed = if travelled < path.length() {
                    speed
                } else {
                    0.0
                };
                let (sin, cos) = at.heading.sin_cos();
                let pose = Vector6::new(at.point.x, at.point.y, 0.0, 0.0, 0.0, at.heading);
                let rate = Vector6::new(
                    speed * cos,
                    speed * sin,
                    0.0,
                    0.0,
                    0.0,
                    speed * at.curvature,
                );
                Ok((pose, rate))
            }
            Reference::Pieces(pieces) => {
                let piece = pieces
                    .iter()
                    .take_while(|(start, _)| *start <= time)
                    .last()
                    .or(pieces.first());
                match piece {
                    Some((_, reference)) => reference.at(time),
                    None => Ok((Vector6::zeros(), Vector6::zeros())),
                }
            }
            Reference::Function { pose, rate } => {
                let call = |function: &TimeFunction<Vector6<f64>>, argument: &str, t: f64| {
                    let value = function(t)
                        .map_err(|message| Error::input(argument, format!("t = {t} s"), message))?;
                    finite(argument, value.as_slice()).map_err(|_| {
                        Error::input(
                            argument,
                            format!("{:?} at t = {t} s", value.as_slice()),
                            "must return finite numbers",
                        )
                    })?;
                    Ok::<_, Error>(value)
                };
                let value = call(pose, "reference", time)?;
                let derivative = match rate {
                    Some(rate) => call(rate, "reference_rate", time)?,
                    None => {
                        let h = 1e-3;
                        (call(pose, "reference", time + h)? - call(pose, "reference", time - h)?)
                            / (2.0 * h)
                    }
                };
                Ok((value, derivative))
            }
        }
    }
}

/// The lay-tension loop around the DP controller: it moves the set-point along the reference's heading
/// to hold the pipe's top tension, ṡ = −k (T_f − T*) (the set-point backs off toward the touchdown while the
/// tension is too high), bounded by `rate_limit`, from `start`. T_f is the top tension through a first-order
/// low-pass filter of time constant `filter` (s): the loop must not feed the pipe's fast axial and contact
/// oscillations back into the set-point, which pumps them up. It acts only through the reference, so the
/// pipe–vessel system stays passive from thrust to velocity whatever the set-point does (the thrust's work
/// is supplied work in the energy ledger).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TensionControl {
    /// Target top tension T* (N).
    pub target: f64,
    /// k (m/s per N of tension error).
    pub gain: f64,
    /// Time the loop starts (s).
    pub start: f64,
    /// Bound on |ṡ| (m/s); `None`: unbounded.
    pub rate_limit: Option<f64>,
    /// Time constant of the tension filter (s).
    pub filter: f64,
}

impl TensionControl {
    /// The filtered tension after a step `dt` (s) from `filtered` with the measured `tension` (N): exact for a
    /// tension held over the step.
    pub fn filtered(&self, filtered: f64, tension: f64, dt: f64) -> f64 {
        let weight = 1.0 - (-dt / self.filter).exp();
        filtered + weight * (tension - filtered)
    }

    /// ṡ for the filtered top tension (N) at time t (s).
    pub fn rate(&self, tension: f64, time: f64) -> f64 {
        if time < self.start {
            return 0.0;
        }
        let rate = -self.gain * (tension - self.target);
        match self.rate_limit {
            Some(limit) => rate.clamp(-limit, limit),
            None => rate,
        }
    }
}

/// The reference moved by `offset` (m) along its own heading, its rate by `offset_rate` (m/s).
pub fn shifted(
    reference: (Vector6<f64>, Vector6<f64>),
    offset: f64,
    offset_rate: f64,
) -> (Vector6<f64>, Vector6<f64>) {
    let (mut pose, mut rate) = reference;
    let (sin, cos) = pose[5].sin_cos();
    pose[0] += offset * cos;
    pose[1] += offset * sin;
    rate[0] += offset_rate * cos;
    rate[1] += offset_rate * sin;
    (pose, rate)
}

/// A PID controller on the vessel's η (eqs. 44–45): τ = −Jᵀ(η)(K_p η̃ + K_d η̃̇ + K_i ∫η̃), η̃ = η − η_ref(t),
/// η̃̇ = J(η)ν − η̇_ref(t), active from `start`; thrust acts in surge, sway and yaw only.
#[derive(Debug, Clone, PartialEq)]
pub struct Pid {
    pub kp: nalgebra::Matrix6<f64>,
    pub kd: nalgebra::Matrix6<f64>,
    pub ki: nalgebra::Matrix6<f64>,
    /// η_ref(t) = [x, y, z, φ, θ, ψ] in e (m, rad).
    pub reference: Reference,
    /// Time the controller starts (s).
    pub start: f64,
    /// Bound on each component of ∫η̃ (keeps the PID passive, §III.B); `None`: unbounded.
    pub integral_limit: Option<nalgebra::Vector6<f64>>,
    /// Bounds on the thrust in surge (N), sway (N) and yaw (N·m); `None`: unbounded.
    pub thrust_limit: Option<Vector3<f64>>,
    /// The lay-tension loop that moves the set-point, if any.
    pub tension: Option<TensionControl>,
    /// Whether τ goes through the thrusters' allocation ([`super::allocation`]) and their dynamics.
    pub allocation: bool,
    /// The observer the controller acts on, if any ([`super::observer`]); `None`: it sees the true
    /// low-frequency pose and velocity.
    pub observer: Option<super::observer::ObserverSettings>,
    /// Bumpless transfer: a controller that starts after t = 0 takes over the static holding thrust in its
    /// integral ([`transfer_integral`]) instead of starting from ∫η̃ = 0 (no effect where K_i = 0).
    pub bumpless: bool,
    /// A command given from outside the engine, in place of the PID's ([`Pid::external`]).
    pub external: Option<ExternalCommand>,
    /// The time-domain passivity observer, and its controller if it certifies the loop
    /// ([`crate::dynamics::passivity`]); None: neither.
    pub passivity: Option<Passivity>,
}

/// What the time-domain passivity observer of the DP loop does ([`crate::dynamics::passivity`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Passivity {
    /// It books the controller's work on the vessel against its storage, and nothing more.
    Observe,
    /// Its passivity controller damps the vessel wherever the controller would give more than its storage.
    Certify,
}

/// A law of the command τ (6,) (body frame: N, N·m) of a controller outside the engine (a controller FMU, a
/// co-simulation master) over the step from t (s) to t + Δt, of t, Δt (s) and the pose η (6,) and velocity ν (6,)
/// the sampled loop sees at t (the observer's estimate, if there is one, else the low-frequency pose and
/// velocity).
pub type CommandLaw = std::sync::Arc<
    dyn Fn(f64, f64, &Vector6<f64>, &Vector6<f64>) -> std::result::Result<Vector6<f64>, String>
        + Send
        + Sync,
>;

/// A controller's command from outside the engine: its law, called once per time step at the step's start, the
/// command held over the step (a zero-order hold, as a DP computer's or a co-simulation's communication step).
#[derive(Clone)]
pub struct ExternalCommand(pub CommandLaw);

impl std::fmt::Debug for ExternalCommand {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ExternalCommand")
    }
}

impl PartialEq for ExternalCommand {
    fn eq(&self, other: &Self) -> bool {
        std::sync::Arc::ptr_eq(&self.0, &other.0)
    }
}

impl ExternalCommand {
    /// The command over the step from `time` to `time` + `dt` (s) for the pose `eta` and velocity `velocity`
    /// seen; a failure or a non-finite value names `controller` and the time.
    pub fn over(
        &self,
        time: f64,
        dt: f64,
        eta: &Vector6<f64>,
        velocity: &Vector6<f64>,
    ) -> Result<Vector6<f64>> {
        let value = (self.0)(time, dt, eta, velocity)
            .map_err(|message| Error::input("controller", format!("t = {time} s"), message))?;
        finite("controller", value.as_slice()).map_err(|_| {
            Error::input(
                "controller",
                format!("τ = {:?} at t = {time} s", value.as_slice()),
                "must command finite thrust (N, N·m)",
            )
        })?;
        Ok(value)
    }
}

/// Checks a gain matrix: finite, symmetric and positive semi-definite (K_p and K_d so, the controller is
/// passive: its storage ½η̃ᵀK_pη̃ ≥ 0 and its damping η̃̇ᵀK_dη̃̇ ≥ 0).
fn check_gain(argument: &str, gain: &Matrix6<f64>) -> Result<()> {
    finite(argument, gain.as_slice())?;
    let scale = gain.abs().max().max(f64::MIN_POSITIVE);
    let asymmetry = (gain - gain.transpose()).abs().max();
    if asymmetry > 1e-9 * scale {
        return Err(Error::input(
            argument,
            format!("a matrix with |K − Kᵀ| = {asymmetry:.3e}"),
            "must be symmetric (a diagonal (6,) or a symmetric (6, 6) gain)",
        ));
    }
    let lowest = gain.symmetric_eigenvalues().min();
    if lowest < -1e-12 * scale {
        return Err(Error::input(
            argument,
            format!("a matrix with eigenvalue {lowest:.6e}"),
            "must be positive semi-definite (no negative gain), so that the controller is passive",
        ));
    }
    Ok(())
}

/// Checks that every component of `limits` is finite and > 0.
fn check_limits(argument: &str, limits: &[f64], unit: &str) -> Result<()> {
    match limits.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        Some(v) => Err(Error::input(
            argument,
            v,
            format!("must hold finite bounds > 0 ({unit})"),
        )),
        None => Ok(()),
    }
}

impl Reference {
    /// A fixed pose, checked finite.
    pub fn fixed(pose: Vector6<f64>) -> Result<Self> {
        finite("reference", pose.as_slice())?;
        Ok(Reference::Fixed(pose))
    }

    /// A route along the path through `waypoints` with arcs of `radius` at its corners ([`RoutePath`]), from
    /// its first waypoint at `start_time` (s) at `speed` (m/s).
    pub fn path(
        waypoints: &[Vector2<f64>],
        radius: f64,
        speed: f64,
        start_time: f64,
    ) -> Result<Self> {
        finite("speed", &[speed])?;
        finite("start_time", &[start_time])?;
        Ok(Reference::Path {
            path: RoutePath::new(waypoints, radius)?,
            legs: vec![Leg {
                start: start_time,
                speed,
                ramp: 0.0,
            }],
        })
    }

    /// A lay route, checked finite.
    pub fn route(start: Vector2<f64>, heading: f64, speed: f64, start_time: f64) -> Result<Self> {
        finite("start", start.as_slice())?;
        for (name, value, unit) in [
            ("heading", heading, "rad"),
            ("speed", speed, "m/s"),
            ("start_time", start_time, "s"),
        ] {
            if !value.is_finite() {
                return Err(Error::input(
                    name,
                    value,
                    format!("must be a finite number ({unit})"),
                ));
            }
        }
        Ok(Reference::Route {
            start,
            heading,
            legs: vec![Leg {
                start: start_time,
                speed,
                ramp: 0.0,
            }],
        })
    }

    /// This reference with the route's speed changed at times: `changes` holds legs in time order, each
    /// replacing the route from its start. A fixed pose becomes a route from it along its heading, waiting
    /// there until the first change; a function of time (or a reference in pieces, which the stages change
    /// piece by piece) cannot take them (`key` names the first change in the error).
    pub fn with_speed_changes(&self, changes: &[Leg], key: &str) -> Result<Self> {
        let changed = |mut legs: Vec<Leg>| {
            for &change in changes {
                legs.retain(|leg| leg.start < change.start);
                legs.push(change);
            }
            legs
        };
        // A route along a path keeps its path.
        if let Reference::Path { path, legs } = self {
            return Ok(Reference::Path {
                path: path.clone(),
                legs: changed(legs.clone()),
            });
        }
        let (start, heading, legs) = match self {
            Reference::Fixed(pose) => (Vector2::new(pose[0], pose[1]), pose[5], Vec::new()),
            Reference::Route {
                start,
                heading,
                legs,
            } => (*start, *heading, legs.clone()),
            Reference::Pieces(_) | Reference::Function { .. } | Reference::Path { .. } => {
                return Err(Error::input(
                    key,
                    "a route speed for a controller whose reference is a function of time",
                    "needs a fixed pose or a pl.Route as the controller's reference",
                ))
            }
        };
        Ok(Reference::Route {
            start,
            heading,
            legs: changed(legs),
        })
    }
}

impl TensionControl {
    /// A checked lay-tension loop.
    pub fn new(
        target: f64,
        gain: f64,
        start: f64,
        rate_limit: Option<f64>,
        filter: f64,
    ) -> Result<Self> {
        crate::error::positive("filter", filter, "s (a time constant)")?;
        if !target.is_finite() {
            return Err(Error::input(
                "target",
                target,
                "must be a finite tension (N)",
            ));
        }
        crate::error::positive("gain", gain, "(m/s per N)")?;
        if !start.is_finite() {
            return Err(Error::input("start", start, "must be a finite time (s)"));
        }
        if let Some(limit) = rate_limit {
            crate::error::positive("rate_limit", limit, "m/s")?;
        }
        Ok(TensionControl {
            target,
            gain,
            start,
            rate_limit,
            filter,
        })
    }
}

impl Pid {
    /// A checked PID: gains finite, symmetric and positive semi-definite, limits finite and > 0, start finite.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        kp: Matrix6<f64>,
        kd: Matrix6<f64>,
        ki: Matrix6<f64>,
        reference: Reference,
        start: f64,
        integral_limit: Option<Vector6<f64>>,
        thrust_limit: Option<Vector3<f64>>,
        tension: Option<TensionControl>,
    ) -> Result<Self> {
        check_gain("kp", &kp)?;
        check_gain("kd", &kd)?;
        check_gain("ki", &ki)?;
        if !start.is_finite() {
            return Err(Error::input("start", start, "must be a finite time (s)"));
        }
        if let Some(limit) = &integral_limit {
            check_limits("integral_limit", limit.as_slice(), "m·s, rad·s")?;
        }
        if let Some(limit) = &thrust_limit {
            check_limits("thrust_limit", limit.as_slice(), "N, N, N·m")?;
        }
        Ok(Pid {
            kp,
            kd,
            ki,
            reference,
            start,
            integral_limit,
            thrust_limit,
            tension,
            allocation: false,
            observer: None,
            bumpless: true,
            external: None,
            passivity: None,
        })
    }

    /// The same controller with the time-domain passivity observer (and controller) `passivity`
    /// ([`crate::dynamics::passivity`]). It books station keeping about a fixed reference (or a controller
    /// from outside, whose reference pipelay does not see): a moving reference supplies work it does not book.
    pub fn with_passivity(mut self, passivity: Option<Passivity>) -> Result<Self> {
        if passivity.is_some()
            && self.external.is_none()
            && !matches!(self.reference, Reference::Fixed(_))
        {
            return Err(Error::input(
                "passivity",
                "an observer with a route or a reference of time",
                "books station keeping about a fixed reference: give the reference as η_ref (6,)",
            ));
        }
        self.passivity = passivity;
        Ok(self)
    }

    /// Whether the passivity controller certifies the loop.
    pub fn certifies(&self) -> bool {
        self.passivity == Some(Passivity::Certify)
    }

    /// The controller's storage ½η̃ᵀK_pη̃ (J) at the pose `eta` about `reference`: what it may give back.
    pub fn storage(&self, eta: &Vector6<f64>, reference: &Vector6<f64>) -> f64 {
        let error = eta_error(eta, reference);
        0.5 * error.dot(&(self.kp * error))
    }

    /// A controller whose command comes from `law` ([`ExternalCommand`]), from `start` (s), within
    /// `thrust_limit` (as [`Pid::new`]'s): a sampled loop (with allocation and an observer, if given) whose PID
    /// is replaced by the law; statics hold the vessel by the holding thrust, which the command is until the
    /// law's first answer.
    pub fn external(
        law: CommandLaw,
        start: f64,
        thrust_limit: Option<Vector3<f64>>,
    ) -> Result<Self> {
        let mut controller = Pid::new(
            Matrix6::zeros(),
            Matrix6::zeros(),
            Matrix6::zeros(),
            Reference::Fixed(Vector6::zeros()),
            start,
            None,
            thrust_limit,
            None,
        )?;
        controller.external = Some(ExternalCommand(law));
        Ok(controller)
    }

    /// Whether statics hold the vessel by this controller (it acts from t ≤ 0 and is a PID), else by the
    /// holding thrust.
    pub fn holds_in_statics(&self) -> bool {
        self.start <= 0.0 && self.external.is_none()
    }

    /// The same controller with bumpless transfer on or off ([`Pid::bumpless`]).
    pub fn with_bumpless(mut self, bumpless: bool) -> Self {
        self.bumpless = bumpless;
        self
    }

    /// Whether the controller takes over the holding thrust at the start of the step from `time` to
    /// `time` + `dt` (s): with bumpless transfer, when it starts after t = 0 (statics hold the vessel by
    /// thrust; a controller on at t ≤ 0 is already in the static solve) and `time` ≤ start < `time` + `dt`,
    /// the one step of the run that holds its start. The controller acts from the first step whose
    /// midpoint reaches its start, this one or the next, so it never acts before its integral is set.
    pub fn takes_over(&self, time: f64, dt: f64) -> bool {
        self.bumpless && self.start > 0.0 && time <= self.start && self.start < time + dt
    }

    /// The same controller with its command allocated to the thrusters (`allocation`) and acting on an
    /// observer's estimate (`observer`).
    pub fn with_station_keeping(
        mut self,
        allocation: bool,
        observer: Option<super::observer::ObserverSettings>,
    ) -> Self {
        self.allocation = allocation;
        self.observer = observer;
        self
    }

    /// Whether the controller runs as a sampled loop, once per step on the state at the step's start: with
    /// allocation or an observer. Otherwise its τ is implicit in the step (at the midpoint), which keeps the
    /// closed loop passive step by step.
    pub fn is_sampled(&self) -> bool {
        self.allocation || self.observer.is_some() || self.external.is_some()
    }
}

/// η − η_ref with angles wrapped.
pub fn eta_error(eta: &Vector6<f64>, reference: &Vector6<f64>) -> Vector6<f64> {
    let mut e = eta - reference;
    for k in 3..6 {
        e[k] = super::thrusters::wrap(e[k]);
    }
    e
}

/// Keeps thrust to surge, sway and yaw, within the limits.
pub fn thrust_only(mut tau: Vector6<f64>, limit: Option<&Vector3<f64>>) -> Vector6<f64> {
    tau[2] = 0.0;
    tau[3] = 0.0;
    tau[4] = 0.0;
    if let Some(limit) = limit {
        for (k, l) in [(0, limit.x), (1, limit.y), (5, limit.z)] {
            tau[k] = tau[k].clamp(-l, l);
        }
    }
    tau
}

/// τ = −Jᵀ(η)(K_p η̃ + K_d η̃̇ + K_i z) (body frame), thrust in surge, sway, yaw within the limits, about the
/// reference pose and rate `reference` = (η_ref, η̇_ref).
pub fn pid_thrust(
    controller: &Pid,
    eta: &Vector6<f64>,
    velocity: &Vector6<f64>,
    integral: &Vector6<f64>,
    reference: &(Vector6<f64>, Vector6<f64>),
) -> Vector6<f64> {
    let error = eta_error(eta, &reference.0);
    let jacobian = euler::jacobian(eta).unwrap_or_else(Matrix6::identity);
    let rate = jacobian * velocity - reference.1;
    let tau_pid = controller.kp * error + controller.kd * rate + controller.ki * integral;
    thrust_only(
        -jacobian.transpose() * tau_pid,
        controller.thrust_limit.as_ref(),
    )
}

/// The integral state z₀ with which the controller takes over the holding thrust τ_h (body frame) at pose η
/// (bumpless transfer): at η̃ = 0 and η̃̇ = 0 its thrust −Jᵀ(η) K_i z₀ is τ_h in surge, sway and yaw, so the
/// thrust is continuous at its start when the vessel is at its reference, and the proportional and derivative
/// parts act on the error alone (a set-point step at the start is answered as without the transfer).
///
/// With S selecting surge, sway and yaw and B = −S Jᵀ(η) K_i (3×6), z₀ is the least-squares solution of
/// B z = S τ_h of least norm, z₀ = Bᵀ (B Bᵀ)⁺ S τ_h (the pseudo-inverse of the symmetric 3×3 B Bᵀ from its
/// eigenvalues): exact in the directions K_i reaches, zero where K_i = 0; then within `integral_limit`. The
/// thrust's work stays supplied work in the energy ledger, whatever z₀ is.
pub fn transfer_integral(
    controller: &Pid,
    eta: &Vector6<f64>,
    hold_thrust: &Vector6<f64>,
) -> Vector6<f64> {
    let jacobian = euler::jacobian(eta).unwrap_or_else(Matrix6::identity);
    let full = -jacobian.transpose() * controller.ki;
    let rows = [0, 1, 5];
    let b = nalgebra::SMatrix::<f64, 3, 6>::from_fn(|i, j| full[(rows[i], j)]);
    let target = Vector3::from_fn(|i, _| hold_thrust[rows[i]]);
    let normal = b * b.transpose();
    let scale = normal.abs().max();
    if scale == 0.0 {
        return Vector6::zeros();
    }
    let eigen = normal.symmetric_eigen();
    let inverse_values = eigen.eigenvalues.map(|value| {
        if value > 1e-12 * scale {
            1.0 / value
        } else {
            0.0
        }
    });
    let pseudo_inverse = eigen.eigenvectors
        * Matrix3::from_diagonal(&inverse_values)
        * eigen.eigenvectors.transpose();
    clamp_integral(controller, &(b.transpose() * pseudo_inverse * target))
}

/// ∫η̃ within the controller's bound.
pub fn clamp_integral(controller: &Pid, integral: &Vector6<f64>) -> Vector6<f64> {
    match &controller.integral_limit {
        Some(limit) => integral.zip_map(limit, |z, l| z.clamp(-l, l)),
        None => *integral,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An external controller is sampled, lets statics hold the vessel by thrust, passes its law's τ through,
    /// and names `controller` and the time for a law that fails or commands a non-finite thrust.
    #[test]
    fn an_external_command_is_its_laws_answer_or_an_error_naming_the_controller() {
        let law: CommandLaw = std::sync::Arc::new(|time, dt, eta, velocity| {
            if time > 1.0 {
                return Err("the DP computer is down".into());
            }
            let yaw = if time == 0.5 { f64::NAN } else { 0.0 };
            Ok(Vector6::new(eta[0] + dt, velocity[1], 0.0, 0.0, 0.0, yaw))
        });
        let controller = Pid::external(law, 0.0, None).unwrap();
        assert!(controller.is_sampled() && !controller.holds_in_statics());
        let external = controller.external.as_ref().unwrap();
        let (eta, velocity) = (Vector6::repeat(2.0), Vector6::repeat(3.0));
        let tau = external.over(0.0, 0.5, &eta, &velocity).unwrap();
        assert_eq!(tau, Vector6::new(2.5, 3.0, 0.0, 0.0, 0.0, 0.0));
        let non_finite = external
            .over(0.5, 0.5, &eta, &velocity)
            .unwrap_err()
            .to_string();
        assert!(
            non_finite.contains("controller") && non_finite.contains("finite"),
            "{non_finite}"
        );
        let failed = external
            .over(2.0, 0.5, &eta, &velocity)
            .unwrap_err()
            .to_string();
        assert!(
            failed.contains("controller") && failed.contains("t = 2 s"),
            "{failed}"
        );
        assert!(failed.contains("the DP computer is down"), "{failed}");
        let pid = Pid::new(
            Matrix6::identity(),
            Matrix6::identity(),
            Matrix6::zeros(),
            Reference::Fixed(Vector6::zeros()),
            0.0,
            None,
            None,
            None,
        )
        .unwrap();
        assert!(pid.holds_in_statics() && !pid.is_sampled());
    }

    #[test]
    fn a_route_waits_for_its_start_then_moves_at_its_speed() {
        let route = Reference::route(Vector2::new(100.0, -5.0), 0.5, 2.0, 10.0).unwrap();
        let (before, rate_before) = route.at(4.0).unwrap();
        assert_eq!(before, Vector6::new(100.0, -5.0, 0.0, 0.0, 0.0, 0.5));
        assert_eq!(rate_before, Vector6::zeros());
        let (after, rate) = route.at(25.0).unwrap();
        let travelled = Vector2::new(after.x - 100.0, after.y + 5.0);
        assert!((travelled.norm() - 30.0).abs() < 1e-12);
        assert!((travelled.y.atan2(travelled.x) - 0.5).abs() < 1e-12);
        assert!((rate.fixed_rows::<2>(0).norm() - 2.0).abs() < 1e-12);
    }

    /// Two routes of one length but other corners differ, in their description too (a checkpoint's
    /// fingerprint is a digest of it).
    #[test]
    fn routes_of_one_length_are_told_apart() {
        let corner = |turn: f64| {
            let points = [
                Vector2::new(0.0, 0.0),
                Vector2::new(100.0, 0.0),
                Vector2::new(100.0, turn),
            ];
            Reference::path(&points, 30.0, 1.0, 0.0).unwrap()
        };
        let (left, right) = (corner(100.0), corner(-100.0));
        assert_ne!(left, right);
        assert_ne!(format!("{left:?}"), format!("{right:?}"));
        assert_eq!(format!("{left:?}"), format!("{:?}", corner(100.0)));
    }

    #[test]
    fn a_route_in_legs_travels_each_at_its_speed() {
        let route = Reference::route(Vector2::zeros(), 0.0, 1.0, 0.0)
            .unwrap()
            .with_speed_changes(
                &[
                    Leg {
                        start: 10.0,
                        speed: 0.0,
                        ramp: 0.0,
                    },
                    Leg {
                        start: 20.0,
                        speed: 3.0,
                        ramp: 0.0,
                    },
                ],
                "stages[1].route_speed",
            )
            .unwrap();
        // 10 m in the first leg, none in the second, 3 m/s after 20 s.
        let (pose, rate) = route.at(15.0).unwrap();
        assert!((pose.x - 10.0).abs() < 1e-12 && rate.x == 0.0);
        let (pose, rate) = route.at(25.0).unwrap();
        assert!((pose.x - 25.0).abs() < 1e-12 && rate.x == 3.0);
        let fixed = Reference::Fixed(Vector6::new(5.0, 1.0, 0.0, 0.0, 0.0, 0.0));
        let leg = Leg {
            start: 2.0,
            speed: 1.0,
            ramp: 0.0,
        };
        let moving = fixed.with_speed_changes(&[leg], "k").unwrap();
        assert!((moving.at(4.0).unwrap().0.x - 7.0).abs() < 1e-12);
    }

    /// A PID with K_i on surge, sway and yaw, its reference at the pose `eta`.
    fn pid_at(eta: Vector6<f64>, ki: Vector6<f64>, start: f64) -> Pid {
        Pid::new(
            Matrix6::from_diagonal(&Vector6::new(2e5, 2e5, 0.0, 0.0, 0.0, 1e7)),
            Matrix6::from_diagonal(&Vector6::new(4e6, 4e6, 0.0, 0.0, 0.0, 1e8)),
            Matrix6::from_diagonal(&ki),
            Reference::Fixed(eta),
            start,
            None,
            None,
            None,
        )
        .unwrap()
    }

    /// Bumpless transfer: at the reference and at rest, the PID's thrust with the transferred integral is the
    /// holding thrust it takes over, to round-off, at a heading, roll and pitch where Jᵀ mixes the axes;
    /// without K_i there is nothing to transfer (z₀ = 0), and with K_i on surge alone only surge is taken
    /// over at ψ = 0; the integral bound caps z₀.
    #[test]
    fn the_thrust_is_continuous_at_the_controllers_start() {
        let eta = Vector6::new(660.0, -3.0, -150.0, 0.02, -0.03, 0.7);
        let hold = Vector6::new(866.6e3, -41.0e3, 0.0, 0.0, 0.0, 3.2e6);
        let pid = pid_at(eta, Vector6::new(1e3, 2e3, 0.0, 0.0, 0.0, 5e4), 5.0);
        let integral = transfer_integral(&pid, &eta, &hold);
        let reference = (eta, Vector6::zeros());
        let thrust = pid_thrust(&pid, &eta, &Vector6::zeros(), &integral, &reference);
        assert!(
            (thrust - hold).norm() < 1e-9 * hold.norm(),
            "{thrust:?} against {hold:?}"
        );
        assert!(integral[2] == 0.0 && integral[3] == 0.0 && integral[4] == 0.0);

        let pd = pid_at(eta, Vector6::zeros(), 5.0);
        assert_eq!(transfer_integral(&pd, &eta, &hold), Vector6::zeros());

        let level = Vector6::new(660.0, 0.0, -150.0, 0.0, 0.0, 0.0);
        let surge = pid_at(level, Vector6::new(1e3, 0.0, 0.0, 0.0, 0.0, 0.0), 5.0);
        let z = transfer_integral(&surge, &level, &hold);
        // τ_x = −K_i,x z_x at ψ = 0.
        assert!(
            (z[0] + 866.6).abs() < 1e-9 && z.rows(1, 5).norm() == 0.0,
            "{z:?}"
        );

        let mut bounded = surge.clone();
        bounded.integral_limit = Some(Vector6::repeat(100.0));
        assert_eq!(transfer_integral(&bounded, &level, &hold)[0], -100.0);
    }

    /// The transfer happens in exactly one step of a run, the one that holds the start, also when the
    /// times are sums of a step that is not a binary fraction (0.2 s: 25 steps make 5.000000000000001 s);
    /// only for a controller that starts after t = 0 and has bumpless transfer on.
    #[test]
    fn the_controller_takes_over_in_one_step() {
        let eta = Vector6::zeros();
        for (start, dt, expected) in [(30.0, 0.25, 30.0), (5.0, 0.2, 4.8), (5.1, 0.2, 5.0)] {
            let pid = pid_at(eta, Vector6::repeat(1.0), start);
            let mut time = 0.0;
            let mut over = Vec::new();
            for _ in 0..300 {
                if pid.takes_over(time, dt) {
                    over.push(time);
                }
                time += dt;
            }
            assert_eq!(over.len(), 1, "start {start}: {over:?}");
            assert!((over[0] - expected).abs() < 1e-9, "start {start}: {over:?}");
        }
        let pid = pid_at(eta, Vector6::repeat(1.0), 30.0);
        assert!(!pid.with_bumpless(false).takes_over(30.0, 0.25));
        assert!(!pid_at(eta, Vector6::repeat(1.0), 0.0).takes_over(0.0, 0.25));
    }

    #[test]
    fn a_reference_function_that_fails_names_itself_and_the_time() {
        let pose: TimeFunction<Vector6<f64>> = std::sync::Arc::new(|t| {
            if t < 1.0 {
                Ok(Vector6::repeat(t))
            } else {
                Ok(Vector6::repeat(f64::NAN))
            }
        });
        let reference = Reference::Function { pose, rate: None };
        let (value, rate) = reference.at(0.5).unwrap();
        assert!((value[0] - 0.5).abs() < 1e-15 && (rate[0] - 1.0).abs() < 1e-9);
        let message = reference.at(2.0).unwrap_err().to_string();
        assert!(
            message.contains("reference") && message.contains("t = 2"),
            "{message}"
        );
    }
}
