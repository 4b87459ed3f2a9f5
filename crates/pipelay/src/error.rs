//! Errors of the engine, as types: bad input and failed solves.
use std::fmt;

/// Everything that can go wrong in the engine.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// A user-supplied value is outside what is allowed.
    Input {
        /// The argument (or scenario key) at fault, e.g. `"section.EA"`.
        argument: String,
        /// The offending value, formatted.
        value: String,
        /// What would have been accepted, with units.
        allowed: String,
    },
    /// Newton's method failed to converge.
    Convergence {
        /// Where it failed: "static solve", "time step", ...
        context: String,
        /// Load factor reached (statics) or time (dynamics) when it gave up.
        reached: f64,
        /// Newton iterations of the failed attempt.
        iterations: usize,
        /// Residual norm of the last iterate.
        residual: f64,
        /// What went wrong, e.g. "load step fell below 1e-6".
        reason: String,
    },
    /// Memory for a buffer could not be reserved.
    Memory {
        /// What the buffer is for.
        what: String,
        /// The bytes asked for.
        bytes: f64,
    },
}

impl Error {
    /// Shorthand for [`Error::Input`].
    pub fn input(
        argument: impl Into<String>,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Error::Input {
            argument: argument.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Input {
                argument,
                value,
                allowed,
            } => write!(f, "{argument}: {allowed}, got {value}"),
            Error::Convergence {
                context,
                reached,
                iterations,
                residual,
                reason,
            } => write!(
                f,
                "{context} failed: {reason} (reached {reached:.6}, {iterations} Newton iterations, residual {residual:.3e})"
            ),
            Error::Memory { what, bytes } => write!(
                f,
                "out of memory: could not reserve {} for {what}",
                human(*bytes)
            ),
        }
    }
}

impl std::error::Error for Error {}

/// Bytes in a readable unit.
pub fn human(bytes: f64) -> String {
    let units = ["B", "KB", "MB", "GB", "TB", "PB"];
    let mut value = bytes;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < units.len() {
        value /= 1024.0;
        unit += 1;
    }
    format!("{value:.1} {}", units.get(unit).copied().unwrap_or("B"))
}

/// Result type of the engine.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite and strictly positive.
pub fn positive(argument: &str, value: f64, unit: &str) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::input(
            argument,
            value,
            format!("must be a finite number > 0 {unit}"),
        ))
    }
}

/// Checks that `value` is finite and not negative.
pub fn non_negative(argument: &str, value: f64, unit: &str) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::input(
            argument,
            value,
            format!("must be a finite number >= 0 {unit}"),
        ))
    }
}

/// Checks that every component of `values` is finite.
pub fn finite(argument: &str, values: &[f64]) -> Result<()> {
    match values.iter().find(|v| !v.is_finite()) {
        None => Ok(()),
        Some(v) => Err(Error::input(argument, v, "must be finite (no NaN or inf)")),
    }
}
