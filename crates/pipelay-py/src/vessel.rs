//! Python classes Vessel, PID and Force.
use crate::convert::{array, float_matrix6, to_numpy};
use crate::errors::{input, to_py};
use crate::raos::Raos;
use crate::station_keeping::{Allocation, DriftCoefficients, HullCoefficients, Observer, Thruster};
use nalgebra::{Matrix6, Vector3, Vector6};
use numpy::{PyArray1, PyArray2};
use pipelay::vessel::control::{Passivity, Pid, Reference, TensionControl};
use pipelay::vessel::EnvironmentForce;
use pyo3::prelude::*;

/// A DP vessel (eq. 10): M = M_RB + M_A, linear damping D and restoring G (6×6, about CO, surge…yaw);
/// C(ν) follows from M_RB and M_A (Fossen's m2c form).
#[pyclass(module = "pipelay", name = "Vessel", frozen)]
#[derive(Clone)]
pub struct Vessel(pub pipelay::vessel::rigid_body::Vessel);

fn matrix_to_numpy<'py>(py: Python<'py>, m: &Matrix6<f64>) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<Vec<f64>> = (0..6)
        .map(|i| (0..6).map(|j| m[(i, j)]).collect())
        .collect();
    PyArray2::from_vec2(py, &rows).expect("6×6")
}

#[pymethods]
impl Vessel {
    #[new]
    #[pyo3(signature = (M, D, G, *, M_RB=None, quadratic_damping=None, raos=None, length=None, thrusters=None, wind_coefficients=None, current_coefficients=None, drift_coefficients=None))]
    #[allow(non_snake_case, clippy::too_many_arguments)]
    fn new(
        M: &Bound<'_, PyAny>,
        D: &Bound<'_, PyAny>,
        G: &Bound<'_, PyAny>,
        M_RB: Option<&Bound<'_, PyAny>>,
        quadratic_damping: Option<&Bound<'_, PyAny>>,
        raos: Option<&Raos>,
        length: Option<f64>,
        thrusters: Option<&Bound<'_, PyAny>>,
        wind_coefficients: Option<&HullCoefficients>,
        current_coefficients: Option<&HullCoefficients>,
        drift_coefficients: Option<&DriftCoefficients>,
    ) -> PyResult<Self> {
        let mass = float_matrix6(M, "M")?;
        let damping = float_matrix6(D, "D")?;
        let restoring = float_matrix6(G, "G")?;
        let rigid = M_RB.map(|m| float_matrix6(m, "M_RB")).transpose()?;
        let quadratic = quadratic_damping
            .map(|m| float_matrix6(m, "quadratic_damping"))
            .transpose()?;
        let vessel =
            pipelay::vessel::rigid_body::Vessel::new(mass, damping, restoring, rigid, quadratic)
                .map_err(to_py)?
                .with_raos(raos.map(|r| r.0.clone()))
                .with_hull_coefficients(
                    wind_coefficients.map(|c| c.0.clone()),
                    current_coefficients.map(|c| c.0.clone()),
                    drift_coefficients.map(|c| c.0.clone()),
                );
        let mut list = Vec::new();
        if let Some(items) = thrusters {
            let iterator = items.try_iter().map_err(|_| {
                input(
                    "thrusters",
                    items.repr().map_or("?".into(), |r| r.to_string()),
                    "must be a sequence of pl.Thruster (a list, even of one)",
                )
            })?;
            for (k, item) in iterator.enumerate() {
                let item = item?;
                let thruster = item.cast::<Thruster>().map_err(|_| {
                    input(
                        &format!("thrusters[{k}]"),
                        item.repr().map_or("?".into(), |r| r.to_string()),
                        "must be a pl.Thruster",
                    )
                })?;
                list.push(thruster.get().0.clone());
            }
        }
        let thrusters = list;
        if let Some(length) = length {
            if !(length.is_finite() && length > 0.0) {
                return Err(input("length", length, "must be a finite length > 0 (m)"));
            }
        }
        vessel
            .with_thrusters(thrusters, length)
            .map(Vessel)
            .map_err(to_py)
    }

    /// Its thrusters.
    #[getter]
    fn thrusters(&self) -> Vec<Thruster> {
        self.0.thrusters.iter().cloned().map(Thruster).collect()
    }
    /// Overall length (m), if given.
    #[getter]
    fn length(&self) -> Option<f64> {
        self.0.length
    }
    /// Wind coefficients of the hull, if any.
    #[getter]
    fn wind_coefficients(&self) -> Option<HullCoefficients> {
        self.0.wind_coefficients.clone().map(HullCoefficients)
    }
    /// Current coefficients of the hull, if any.
    #[getter]
    fn current_coefficients(&self) -> Option<HullCoefficients> {
        self.0.current_coefficients.clone().map(HullCoefficients)
    }
    /// Mean wave-drift coefficients, if any.
    #[getter]
    fn drift_coefficients(&self) -> Option<DriftCoefficients> {
        self.0.drift_coefficients.clone().map(DriftCoefficients)
    }
    /// One allocation of a commanded τ (6,) (body frame) to the thrusters, without rate limits.
    fn allocate(&self, tau: &Bound<'_, PyAny>) -> PyResult<Allocation> {
        let tau = Vector6::from(array::<6>(tau, "tau")?);
        pipelay::vessel::allocation::allocate(&self.0.thrusters, &tau, None)
            .map(Allocation)
            .map_err(to_py)
    }

    /// The 83 m offshore supply vessel of Fossen's MSS toolbox (osv.m; 6-DOF, about CO), with the RAOs of
    /// its hull computed by Capytaine, or `raos`, the six thrusters of the MSS supply vessel, its length and
    /// its wind, current and wave-drift tables.
    #[staticmethod]
    #[pyo3(signature = (raos=None))]
    fn osv(raos: Option<&Raos>) -> Self {
        let vessel = pipelay::vessel::rigid_body::Vessel::osv();
        match raos {
            Some(raos) => Vessel(vessel.with_raos(Some(raos.0.clone()))),
            None => Vessel(vessel),
        }
    }

    /// First-order displacement RAOs, if the vessel has them (its wave-frequency motion in waves).
    #[getter]
    fn raos(&self) -> Option<Raos> {
        self.0.raos.clone().map(Raos)
    }

    /// M = M_RB + M_A (6, 6) (kg, kg·m, kg·m²).
    #[getter(M)]
    fn mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        matrix_to_numpy(py, &self.0.mass())
    }
    /// Rigid-body mass M_RB (6, 6).
    #[getter(M_RB)]
    fn rigid_body_mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        matrix_to_numpy(py, &self.0.rigid_body_mass)
    }
    /// Added mass M_A (6, 6).
    #[getter(M_A)]
    fn added_mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        matrix_to_numpy(py, &self.0.added_mass)
    }
    /// Linear damping D (6, 6).
    #[getter(D)]
    fn damping<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        matrix_to_numpy(py, &self.0.damping)
    }
    /// Restoring G (6, 6).
    #[getter(G)]
    fn restoring<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        matrix_to_numpy(py, &self.0.restoring)
    }
    /// C(ν) = C_RB(ν) + C_A(ν) (6, 6) for ν (6,).
    fn coriolis<'py>(
        &self,
        py: Python<'py>,
        nu: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let nu = Vector6::from(array::<6>(nu, "nu")?);
        Ok(matrix_to_numpy(py, &self.0.coriolis(&nu)))
    }
}

/// Gains: (6,) for a diagonal matrix or (6, 6).
fn gains(value: &Bound<'_, PyAny>, argument: &str) -> PyResult<Matrix6<f64>> {
    if let Ok(diagonal) = array::<6>(value, argument) {
        return Ok(Matrix6::from_diagonal(&Vector6::from(diagonal)));
    }
    float_matrix6(value, argument).map_err(|_| {
        input(
            argument,
            value.repr().map_or("?".into(), |r| r.to_string()),
            "must have shape (6,) or (6, 6)",
        )
    })
}

/// The lay-tension loop around the DP controller: it moves the set-point along the reference's heading at
/// ṡ = −gain·(T_f − target) (m/s; T_f the pipe's top tension, N, through a first-order low-pass filter of time
/// constant `filter`, s) from `start` (s), |ṡ| ≤ `rate_limit` (m/s).
#[pyclass(module = "pipelay", name = "TensionControl", frozen)]
#[derive(Clone)]
pub struct PyTensionControl(pub TensionControl);

#[pymethods]
impl PyTensionControl {
    #[new]
    #[pyo3(signature = (target, gain, start=0.0, rate_limit=None, filter=20.0))]
    fn new(
        target: f64,
        gain: f64,
        start: f64,
        rate_limit: Option<f64>,
        filter: f64,
    ) -> PyResult<Self> {
        TensionControl::new(target, gain, start, rate_limit, filter)
            .map(PyTensionControl)
            .map_err(to_py)
    }
    #[getter]
    fn target(&self) -> f64 {
        self.0.target
    }
}

/// A reference's pose and rate as arrays.
type PoseAndRate<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

fn pose_and_rate<'py>(
    py: Python<'py>,
    reference: &Reference,
    t: f64,
) -> PyResult<PoseAndRate<'py>> {
    let (pose, rate) = reference.at(t).map_err(to_py)?;
    Ok((to_numpy(py, pose.as_slice()), to_numpy(py, rate.as_slice())))
}

/// A lay route for a DP reference: from `start` (x, y) (m) at `start_time` (s), along `heading` ψ (rad) at
/// `speed` (m/s); the reference's z, roll and pitch are zero and its heading is ψ.
#[pyclass(module = "pipelay", name = "Route", frozen)]
#[derive(Clone)]
pub struct PyRoute(pub Reference);

#[pymethods]
impl PyRoute {
    #[new]
    #[pyo3(signature = (start, heading=0.0, speed=0.0, start_time=0.0))]
    fn new(start: &Bound<'_, PyAny>, heading: f64, speed: f64, start_time: f64) -> PyResult<Self> {
        let start = nalgebra::Vector2::from(array::<2>(start, "start")?);
        Reference::route(start, heading, speed, start_time)
            .map(PyRoute)
            .map_err(to_py)
    }

    /// A route through `waypoints` (k, 2) (x, y in e, m), its corners cut by circular arcs of `radius` (m)
    /// tangent to both legs, travelled from the first waypoint at `start_time` (s) at `speed` (m/s), the
    /// heading along the path; it stops at the last waypoint.
    #[staticmethod]
    #[pyo3(signature = (waypoints, radius=0.0, speed=0.0, start_time=0.0))]
    fn legs(
        waypoints: &Bound<'_, PyAny>,
        radius: f64,
        speed: f64,
        start_time: f64,
    ) -> PyResult<Self> {
        let points = crate::convert::points2(waypoints, "waypoints")?;
        Reference::path(&points, radius, speed, start_time)
            .map(PyRoute)
            .map_err(to_py)
    }

    fn at<'py>(&self, py: Python<'py>, t: f64) -> PyResult<PoseAndRate<'py>> {
        pose_and_rate(py, &self.0, t)
    }
}

/// Whether `allocation` asks for the thrust allocation: "qp" or None.
fn allocation_of(allocation: Option<&str>) -> PyResult<bool> {
    match allocation {
        None => Ok(false),
        Some("qp") => Ok(true),
        Some(other) => Err(input(
            "allocation",
            format!("{other:?}"),
            "must be \"qp\" (thrust allocation by quadratic programming) or None (τ acts directly)",
        )),
    }
}

/// The time-domain passivity observer `passivity` asks for: "observe", "certify" or None.
fn passivity_of(passivity: Option<&str>) -> PyResult<Option<Passivity>> {
    match passivity {
        None => Ok(None),
        Some("observe") => Ok(Some(Passivity::Observe)),
        Some("certify") => Ok(Some(Passivity::Certify)),
        Some(other) => Err(input(
            "passivity",
            format!("{other:?}"),
            "must be \"certify\" (the passivity controller certifies the loop), \"observe\" (its observer \
             books the controller's work, nothing more) or None",
        )),
    }
}

/// A PID controller on η (eqs. 44–45): τ = −Jᵀ(η)(K_p η̃ + K_d η̃̇ + K_i ∫η̃), η̃ = η − η_ref(t),
/// η̃̇ = J(η)ν − η̇_ref(t), from `start` (s). PD when ki is None. `reference`: η_ref (6,), a pl.Route, or a
/// callable of t returning (6,) (with `reference_rate`, a callable returning η̇_ref, or central differences
/// over 1 ms). `tension`: a pl.TensionControl moving the set-point to hold the top tension.
/// `integral_limit` (6,) bounds ∫η̃; `thrust_limit` (3,) bounds the thrust in surge (N), sway (N)
/// and yaw (N·m). `allocation="qp"`: the command goes to the vessel's thrusters through a QP each step;
/// `observer` (a pl.Observer): the controller acts on its estimate. `bumpless`: a controller that starts
/// after t = 0 takes over the static holding thrust τ_h in its integral (K_i z₀ = −J⁻ᵀ τ_h where K_i reaches),
/// so that the thrust is continuous at its start; False: ∫η̃ starts at 0 (the paper's PID). `passivity="certify"`:
/// the time-domain passivity observer and controller keep the controller's work on the vessel within its
/// storage at the start, every step; "observe": the observer books it, nothing more (a fixed reference only).
#[pyclass(module = "pipelay", name = "PID", frozen)]
#[derive(Clone)]
pub struct PyPid(pub Pid);

#[pymethods]
impl PyPid {
    #[new]
    #[pyo3(signature = (kp, kd, ki=None, reference=None, start=0.0, integral_limit=None, thrust_limit=None, reference_rate=None, tension=None, allocation=None, observer=None, bumpless=true, passivity=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        kp: &Bound<'_, PyAny>,
        kd: &Bound<'_, PyAny>,
        ki: Option<&Bound<'_, PyAny>>,
        reference: Option<&Bound<'_, PyAny>>,
        start: f64,
        integral_limit: Option<&Bound<'_, PyAny>>,
        thrust_limit: Option<&Bound<'_, PyAny>>,
        reference_rate: Option<&Bound<'_, PyAny>>,
        tension: Option<&PyTensionControl>,
        allocation: Option<&str>,
        observer: Option<&Observer>,
        bumpless: bool,
        passivity: Option<&str>,
    ) -> PyResult<Self> {
        let allocation = allocation_of(allocation)?;
        let certify = passivity_of(passivity)?;
        let Some(reference) = reference else {
            return Err(input(
                "reference",
                "None",
                "must be η_ref (6,): [x, y, z, φ, θ, ψ] (m, rad), a pl.Route or a callable of t",
            ));
        };
        let reference = if let Ok(route) = reference.cast::<PyRoute>() {
            route.get().0.clone()
        } else if reference.is_callable() {
            Reference::Function {
                pose: crate::callables::vector6_function(reference, "reference")?,
                rate: reference_rate
                    .map(|r| crate::callables::vector6_function(r, "reference_rate"))
                    .transpose()?,
            }
        } else {
            Reference::fixed(Vector6::from(array::<6>(reference, "reference")?)).map_err(to_py)?
        };
        if reference_rate.is_some() && !matches!(reference, Reference::Function { .. }) {
            return Err(input(
                "reference_rate",
                "a callable",
                "belongs to a reference given as a callable of t",
            ));
        }
        Pid::new(
            gains(kp, "kp")?,
            gains(kd, "kd")?,
            ki.map(|k| gains(k, "ki"))
                .transpose()?
                .unwrap_or_else(Matrix6::zeros),
            reference,
            start,
            integral_limit
                .map(|l| array::<6>(l, "integral_limit").map(Vector6::from))
                .transpose()?,
            thrust_limit
                .map(|l| array::<3>(l, "thrust_limit").map(Vector3::from))
                .transpose()?,
            tension.map(|t| t.0),
        )
        .and_then(|pid| {
            pid.with_station_keeping(allocation, observer.map(|o| o.0.clone()))
                .with_bumpless(bumpless)
                .with_passivity(certify)
        })
        .map(PyPid)
        .map_err(to_py)
    }

    /// A controller whose command comes from outside pipelay: `law(t, dt, eta, nu)` returns τ (6,) over the
    /// step from t to t + dt (s) (body frame: N, N·m; surge, sway and yaw are kept, within `thrust_limit` (3,))
    /// from the pose η (6,) and velocity ν (6,) the loop sees at t (the `observer`'s estimate, if given, else
    /// the low-frequency pose and velocity), called once per time step at its start from `start` (s);
    /// `allocation="qp"` sends it to the thrusters. Statics hold the vessel by the holding thrust, which is
    /// the command until the law's first. `pl.Controller.fmu` makes the law of a controller FMU.
    #[staticmethod]
    #[pyo3(signature = (law, start=0.0, thrust_limit=None, allocation=None, observer=None, passivity=None))]
    fn external(
        law: &Bound<'_, PyAny>,
        start: f64,
        thrust_limit: Option<&Bound<'_, PyAny>>,
        allocation: Option<&str>,
        observer: Option<&Observer>,
        passivity: Option<&str>,
    ) -> PyResult<Self> {
        let allocation = allocation_of(allocation)?;
        let certify = passivity_of(passivity)?;
        let thrust_limit = thrust_limit
            .map(|l| array::<3>(l, "thrust_limit").map(Vector3::from))
            .transpose()?;
        Pid::external(
            crate::callables::command_law(law, "law")?,
            start,
            thrust_limit,
        )
        .map_err(to_py)?
        .with_station_keeping(allocation, observer.map(|o| o.0.clone()))
        .with_passivity(certify)
        .map(PyPid)
        .map_err(to_py)
    }

    /// Whether the command comes from outside pipelay (`PID.external`).
    #[getter]
    fn is_external(&self) -> bool {
        self.0.external.is_some()
    }
    /// "certify" if the time-domain passivity controller certifies the loop, "observe" if its observer only
    /// books the controller's work, else None.
    #[getter]
    fn passivity(&self) -> Option<&'static str> {
        self.0.passivity.map(|p| match p {
            Passivity::Observe => "observe",
            Passivity::Certify => "certify",
        })
    }

    #[getter]
    fn reference<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (pose, _) = self.0.reference.at(0.0).map_err(to_py)?;
        Ok(to_numpy(py, pose.as_slice()))
    }
    /// η_ref and η̇_ref (6,) each at time `t` (s).
    fn reference_at<'py>(&self, py: Python<'py>, t: f64) -> PyResult<PoseAndRate<'py>> {
        pose_and_rate(py, &self.0.reference, t)
    }
    /// Start time (s).
    #[getter]
    fn start(&self) -> f64 {
        self.0.start
    }
    /// Whether the controller takes over the holding thrust in its integral at its start.
    #[getter]
    fn bumpless(&self) -> bool {
        self.0.bumpless
    }
}

/// A constant environmental force and moment (6,) on the vessel, body frame (N, N·m), from `start` (s).
#[pyclass(module = "pipelay", name = "Force", frozen)]
#[derive(Clone)]
pub struct PyForce(pub EnvironmentForce);

#[pymethods]
impl PyForce {
    #[new]
    #[pyo3(signature = (value, start=0.0))]
    fn new(value: &Bound<'_, PyAny>, start: f64) -> PyResult<Self> {
        EnvironmentForce::new(Vector6::from(array::<6>(value, "value")?), start)
            .map(PyForce)
            .map_err(to_py)
    }
    /// The force and moment (6,).
    #[getter]
    fn value<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        to_numpy(py, self.0.value.as_slice())
    }
    /// Start time (s).
    #[getter]
    fn start(&self) -> f64 {
        self.0.start
    }
}
