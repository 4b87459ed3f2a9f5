//! Memory: sizes users set are checked against the memory they need before anything is allocated, and large
//! buffers are reserved fallibly, so that too large a model is an error, never an abort of the process.
use crate::error::{human, Error, Result};
use std::fmt;

/// Bytes the rod's reference takes per element: node, frame and element data (measured: 0.16 KB).
pub const ROD_BYTES_PER_ELEMENT: f64 = 200.0;

/// Bytes solving takes per element: the sparse pattern, its LU factors, the assembler's and integrator's
/// vectors (measured: 6–8 KB per element for statics and a time step, n = 1e3 to 4e5).
pub const SOLVER_BYTES_PER_ELEMENT: f64 = 10_000.0;

/// Bytes one record of a run takes per node: position, rotation, velocity and an element's section forces.
pub const RECORD_BYTES_PER_NODE: f64 = 8.0 * (3.0 + 9.0 + 3.0 + 6.0);

/// Memory this machine can still give (bytes): `MemAvailable` + free swap from /proc/meminfo; `None` where
/// unknown (then nothing is refused in advance, and allocation failures still become errors).
pub fn available() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let field = |name: &str| -> Option<f64> {
        let line = text.lines().find(|l| l.starts_with(name))?;
        let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kib * 1024.0)
    };
    Some(field("MemAvailable:")? + field("SwapFree:").unwrap_or(0.0))
}

/// Refuses `value` of `argument` if what it asks for, `bytes` (for `what`), exceeds the available memory.
pub fn check(argument: &str, value: impl fmt::Display, bytes: f64, what: &str) -> Result<()> {
    match available() {
        Some(free) if bytes > free || bytes.is_nan() => Err(Error::input(
            argument,
            value,
            format!(
                "would need {} for {what}, more than the {} this machine has available",
                human(bytes),
                human(free)
            ),
        )),
        _ => Ok(()),
    }
}

/// An empty vector with room for `count` items, or [`Error::Memory`] naming `what`.
pub fn vec_with_capacity<T>(count: usize, what: &str) -> Result<Vec<T>> {
    let mut v = Vec::new();
    reserve(&mut v, count, what)?;
    Ok(v)
}

/// Reserves room for `additional` more items in `v`, or [`Error::Memory`] naming `what`.
pub fn reserve<T>(v: &mut Vec<T>, additional: usize, what: &str) -> Result<()> {
    v.try_reserve(additional).map_err(|_| Error::Memory {
        what: what.to_string(),
        bytes: (additional as f64) * std::mem::size_of::<T>() as f64,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn too_much_is_refused_and_says_how_much() {
        if available().is_none() {
            return;
        }
        let error = check("elements", 1_000_000_000_u64, 1e16, "the rod").unwrap_err();
        let message = error.to_string();
        assert!(
            message.starts_with("elements: would need 8.9 PB for the rod"),
            "{message}"
        );
        assert!(check("elements", 10, 1e3, "the rod").is_ok());
    }

    #[test]
    fn a_failed_reservation_is_an_error() {
        let error = vec_with_capacity::<f64>(usize::MAX / 4, "test buffer").unwrap_err();
        assert!(matches!(error, Error::Memory { .. }), "{error}");
    }
}
