//! LU with partial pivoting of a band matrix (Golub & Van Loan, Matrix Computations, §4.3; LAPACK's dgbtrf
//! layout). A rod's tangent couples each node only to its neighbours: with the unknowns in node order its
//! entries lie within kl = ku ≈ 11 of the diagonal, and the factorisation costs n·kl·(kl + ku) operations,
//! against n³/3 for a dense LU and a supernodal sparse LU's bookkeeping. Row interchanges widen the upper
//! band to kl + ku, which the storage holds.
// Indexing cannot go out of bounds here: band positions (kl + ku + i − j) + j·ld for i − j in [−(kl + ku), kl],
// i and j below the size, and pattern indices of a pattern checked against the bandwidths.
#![allow(clippy::indexing_slicing)]

/// The numeric factorisation met a zero or non-finite pivot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ZeroPivot;

/// A band matrix's LU factors, in column-major band storage.
pub struct BandLu {
    size: usize,
    /// Lower and upper bandwidths of the matrix: a_ij = 0 for i − j > lower or j − i > upper.
    lower: usize,
    upper: usize,
    /// Column j holds rows j − lower − upper … j + lower at (lower + upper + i − j) + j·leading.
    band: Vec<f64>,
    leading: usize,
    /// Row interchanged with row j at step j.
    pivots: Vec<usize>,
}

impl BandLu {
    /// Storage for a `size`×`size` matrix of bandwidths `lower`, `upper`.
    pub fn new(size: usize, lower: usize, upper: usize) -> Self {
        let leading = 2 * lower + upper + 1;
        BandLu {
            size,
            lower,
            upper,
            band: vec![0.0; leading * size],
            leading,
            pivots: vec![0; size],
        }
    }

    /// The bandwidths (lower, upper) of a compressed-column pattern.
    pub fn bandwidths(col_ptr: &[usize], row_idx: &[usize]) -> (usize, usize) {
        let (mut lower, mut upper) = (0, 0);
        for (col, window) in col_ptr.windows(2).enumerate() {
            for &row in &row_idx[window[0]..window[1]] {
                lower = lower.max(row.saturating_sub(col));
                upper = upper.max(col.saturating_sub(row));
            }
        }
        (lower, upper)
    }

    /// Operations of a factorisation, n·kl·(kl + ku), to compare with other methods.
    pub fn cost(size: usize, lower: usize, upper: usize) -> usize {
        size * lower.max(1) * (lower + upper).max(1)
    }

    #[inline]
    fn at(&self, row: usize, col: usize) -> usize {
        self.lower + self.upper + row - col + col * self.leading
    }

    /// Factorises the matrix with compressed-column pattern (`col_ptr`, `row_idx`) within the bandwidths and
    /// `values` in pattern order.
    pub fn factorise(
        &mut self,
        col_ptr: &[usize],
        row_idx: &[usize],
        values: &[f64],
    ) -> Result<(), ZeroPivot> {
        self.band.fill(0.0);
        for col in 0..self.size {
            for k in col_ptr[col]..col_ptr[col + 1] {
                let position = self.at(row_idx[k], col);
                self.band[position] = values[k];
            }
        }
        let n = self.size;
        let reach = self.lower + self.upper;
        // Last column the factorisation has touched so far (row interchanges widen the upper band).
        let mut last = 0;
        for j in 0..n {
            let below = self.lower.min(n - 1 - j);
            // Partial pivoting: the largest entry of column j at or below the diagonal.
            let mut pivot = j;
            let mut largest = self.band[self.at(j, j)].abs();
            for i in j + 1..=j + below {
                let value = self.band[self.at(i, j)].abs();
                if value > largest {
                    largest = value;
                    pivot = i;
                }
            }
            self.pivots[j] = pivot;
            if largest == 0.0 || !largest.is_finite() {
                return Err(ZeroPivot);
            }
            last = last.max((pivot + self.upper).min(n - 1));
            if pivot != j {
                for col in j..=last {
                    let (a, b) = (self.at(j, col), self.at(pivot, col));
                    self.band.swap(a, b);
                }
            }
            let diagonal = self.band[self.at(j, j)];
            for i in j + 1..=j + below {
                let position = self.at(i, j);
                self.band[position] /= diagonal;
            }
            // The trailing update, column by column: rows j + 1 … j + below of column `col` lose
            // multiplier × a_j,col; both runs are contiguous in the band (columns j and col do not overlap).
            let multipliers = self.at(j, j) + 1;
            for col in j + 1..=last.min(j + reach) {
                let top = self.band[self.at(j, col)];
                if top == 0.0 {
                    continue;
                }
                let start = self.at(j + 1, col) - col * self.leading;
                let (left, right) = self.band.split_at_mut(col * self.leading);
                for (entry, multiplier) in right[start..start + below]
                    .iter_mut()
                    .zip(&left[multipliers..multipliers + below])
                {
                    *entry -= multiplier * top;
                }
            }
        }
        Ok(())
    }

    /// Solves A x = b in place (b → x) with the factors.
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        let n = self.size;
        let reach = self.lower + self.upper;
        // L y = P b; column j of L below the diagonal is contiguous in the band.
        for j in 0..n {
            rhs.swap(j, self.pivots[j]);
            let value = rhs[j];
            let below = self.lower.min(n - 1 - j);
            let first = self.at(j, j) + 1;
            for (entry, multiplier) in rhs[j + 1..=j + below]
                .iter_mut()
                .zip(&self.band[first..first + below])
            {
                *entry -= multiplier * value;
            }
        }
        // U x = y, U of upper bandwidth kl + ku; column j of U above the diagonal is contiguous too.
        for j in (0..n).rev() {
            rhs[j] /= self.band[self.at(j, j)];
            let value = rhs[j];
            let top = j - j.min(reach);
            let first = self.at(top, j);
            for (entry, u) in rhs[top..j]
                .iter_mut()
                .zip(&self.band[first..first + (j - top)])
            {
                *entry -= u * value;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::test_support::solve_error;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random band matrix (dense, row-major) and its compressed-column pattern and values.
    fn random_band(
        n: usize,
        lower: usize,
        upper: usize,
        seed: u64,
    ) -> (Vec<f64>, Vec<usize>, Vec<usize>, Vec<f64>) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut dense = vec![0.0; n * n];
        let (mut col_ptr, mut row_idx, mut values) = (vec![0], Vec::new(), Vec::new());
        for j in 0..n {
            for i in j.saturating_sub(upper)..(j + lower + 1).min(n) {
                // Small diagonals, so that pivoting is needed.
                let value = if i == j {
                    1e-3 * rng.random::<f64>()
                } else {
                    rng.random::<f64>() - 0.5
                };
                dense[i * n + j] = value;
                row_idx.push(i);
                values.push(value);
            }
            col_ptr.push(row_idx.len());
        }
        (dense, col_ptr, row_idx, values)
    }

    #[test]
    fn solves_band_systems_that_need_pivoting() {
        for (n, lower, upper, seed) in [(1, 0, 0, 1), (7, 2, 1, 2), (60, 11, 11, 3), (300, 5, 9, 4)]
        {
            let (dense, col_ptr, row_idx, values) = random_band(n, lower, upper, seed);
            assert_eq!(BandLu::bandwidths(&col_ptr, &row_idx), (lower, upper));
            let mut lu = BandLu::new(n, lower, upper);
            lu.factorise(&col_ptr, &row_idx, &values).unwrap();
            let error = solve_error(&dense, n, |b| lu.solve_in_place(b));
            assert!(error < 1e-9, "n = {n}: error {error:e}");
        }
    }

    #[test]
    fn a_singular_matrix_is_refused() {
        let (_, col_ptr, row_idx, mut values) = random_band(10, 2, 2, 5);
        // Column 4 all zero.
        values[col_ptr[4]..col_ptr[5]]
            .iter_mut()
            .for_each(|v| *v = 0.0);
        let mut lu = BandLu::new(10, 2, 2);
        assert_eq!(lu.factorise(&col_ptr, &row_idx, &values), Err(ZeroPivot));
        values[0] = f64::NAN;
        assert!(lu.factorise(&col_ptr, &row_idx, &values).is_err());
    }
}
