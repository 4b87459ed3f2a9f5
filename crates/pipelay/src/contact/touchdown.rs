//! The touchdown: where the pipe leaves the seabed for good, seen from end A.
// Indexing cannot go out of bounds here: node indices of penetrations one longer than the element lengths.
#![allow(clippy::indexing_slicing)]
use nalgebra::Vector3;

/// The touchdown of a configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Touchdown {
    /// Arc length along the reference from end A (m) and position (m) of the last point in contact.
    pub point: Option<(f64, Vector3<f64>)>,
    /// Reference length of pipe in contact with the seabed (m).
    pub laid_length: f64,
}

/// Where the pipe leaves the seabed for good, seen from end A: the last point with penetration ≥ 0, found on
/// the penetration interpolated linearly along each element. Returns its element, the fraction ξ along it,
/// and the reference length in contact.
pub fn touchdown(penetrations: &[f64], lengths: &[f64]) -> (Option<(usize, f64)>, f64) {
    let mut laid = 0.0;
    let mut last = None;
    for (e, length) in lengths.iter().enumerate() {
        let (d1, d2) = (penetrations[e], penetrations[e + 1]);
        let fraction = if d1 >= 0.0 && d2 >= 0.0 {
            last = Some((e, 1.0));
            1.0
        } else if d1 > 0.0 {
            let xi = d1 / (d1 - d2);
            last = Some((e, xi));
            xi
        } else if d2 > 0.0 {
            last = Some((e, 1.0));
            d2 / (d2 - d1)
        } else {
            0.0
        };
        laid += fraction * length;
    }
    (last, laid)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn touchdown_is_the_last_zero_of_the_interpolated_penetration() {
        let lengths = [2.0, 2.0, 2.0];
        let (td, laid) = touchdown(&[0.1, 0.1, 0.05, -0.15], &lengths);
        assert_eq!(td, Some((2, 0.25)));
        assert!((laid - 4.5).abs() < 1e-12);
        assert_eq!(touchdown(&[-0.1, -0.2, -0.3, -0.1], &lengths), (None, 0.0));
    }
}
