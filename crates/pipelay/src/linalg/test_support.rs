//! What the linear solvers' tests share.
// Indexing cannot go out of bounds here: a dense n×n matrix and n-vectors.
#![allow(clippy::indexing_slicing)]
use crate::linalg::factorisation::Factorisation;

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

/// A sparse non-symmetric matrix of `size` unknowns with entries where `coupled(row, column)`: `diagonal` +
/// (row mod 7) on the diagonal, 0.3 sin(31 row + 17 column) off it. Returns its columns, rows and values.
pub fn sparse_matrix(
    size: usize,
    coupled: impl Fn(usize, usize) -> bool,
    diagonal: f64,
) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
    let (mut col_ptr, mut row_idx, mut values) = (vec![0], Vec::new(), Vec::new());
    for col in 0..size {
        for row in (0..size).filter(|&row| coupled(row, col)) {
            row_idx.push(row);
            values.push(if row == col {
                diagonal + (row % 7) as f64
            } else {
                0.3 * ((row * 31 + col * 17) as f64).sin()
            });
        }
        col_ptr.push(row_idx.len());
    }
    (col_ptr, row_idx, values)
}

/// The largest error of `lu` (factorised here) on A x = b for the sparse A of columns `col_ptr`, rows
/// `row_idx` and `values`, and a fixed smooth x.
pub fn sparse_solve_error(
    lu: &mut impl Factorisation,
    col_ptr: &[usize],
    row_idx: &[usize],
    values: &[f64],
) -> f64 {
    let n = col_ptr.len() - 1;
    let x: Vec<f64> = (0..n).map(|i| (0.1 * i as f64).cos()).collect();
    let mut b = vec![0.0; n];
    for (col, &x_col) in x.iter().enumerate() {
        for k in col_ptr[col]..col_ptr[col + 1] {
            b[row_idx[k]] += values[k] * x_col;
        }
    }
    lu.factorise(values).expect("regular");
    lu.solve_in_place(&mut b).expect("solves");
    b.iter()
        .zip(&x)
        .map(|(a, e)| (a - e).abs())
        .fold(0.0, f64::max)
}
