//! What the linear solvers' tests share.
// Indexing cannot go out of bounds here: a dense n×n matrix and n-vectors.
#![allow(clippy::indexing_slicing)]

/// The largest error of `solve` on A x = b for the dense row-major n×n matrix A and a fixed smooth x.
pub fn solve_error(dense: &[f64], n: usize, solve: impl FnOnce(&mut [f64])) -> f64 {
    let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin() + 0.5).collect();
    let mut b: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|j| dense[i * n + j] * x[j]).sum())
        .collect();
    solve(&mut b);
    b.iter()
        .zip(&x)
        .map(|(a, e)| (a - e).abs())
        .fold(0.0, f64::max)
}
