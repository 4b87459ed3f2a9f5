//! The smooth switch used wherever something starts or fades in without a jolt (contact damping, the sea's
//! build-up).

/// 3s² − 2s³ on [0, 1] (0 below, 1 above) and its derivative: C¹, with zero slope at both ends.
pub fn smoothstep(s: f64) -> (f64, f64) {
    if s >= 1.0 {
        (1.0, 0.0)
    } else if s <= 0.0 {
        (0.0, 0.0)
    } else {
        (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s))
    }
}
