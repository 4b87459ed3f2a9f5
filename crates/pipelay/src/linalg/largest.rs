//! The largest entry of a matrix's values, the scale against which pivots and shifts are judged.

/// The largest |entry| of `values`, NaNs skipped (0 for none). Eight running maxima, each a comparison
/// rather than `f64::max` (whose NaN rule costs three more instructions per entry), so that the loop
/// vectorises instead of waiting on one maximum's dependency chain.
pub fn largest_magnitude(values: &[f64]) -> f64 {
    fn keep_larger(largest: &mut f64, value: f64) {
        if value.abs() > *largest {
            *largest = value.abs();
        }
    }
    let mut lanes = [0.0_f64; 8];
    let chunks = values.chunks_exact(lanes.len());
    let mut largest = 0.0_f64;
    for &value in chunks.remainder() {
        keep_larger(&mut largest, value);
    }
    for chunk in chunks {
        for (lane, &value) in lanes.iter_mut().zip(chunk) {
            keep_larger(lane, value);
        }
    }
    for lane in lanes {
        keep_larger(&mut largest, lane);
    }
    largest
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest |entry| wherever it sits (in the eight lanes or the remainder), of either sign, with NaNs
    /// skipped, against a plain fold.
    #[test]
    fn largest_magnitude_is_the_plain_maximum_with_nans_skipped() {
        for length in [0_usize, 1, 7, 8, 9, 23, 64, 101] {
            for at in 0..length {
                let mut values: Vec<f64> = (0..length).map(|i| (i as f64 * 0.7).sin()).collect();
                values[at] = if at % 2 == 0 { -3.5 } else { 3.5 };
                values[(at + 1) % length] = f64::NAN;
                let plain = values
                    .iter()
                    .filter(|v| !v.is_nan())
                    .fold(0.0_f64, |m, v| m.max(v.abs()));
                assert_eq!(
                    largest_magnitude(&values),
                    plain,
                    "length {length}, at {at}"
                );
            }
        }
        assert_eq!(largest_magnitude(&[]), 0.0);
    }
}
