//! LU of the global tangent with faer. The pattern and its symbolic factorisation are computed once; each
//! Newton iteration refactorises numerically and solves, without allocating. Small systems (a few
//! elements, e.g. the paper's 10-element pipe) use faer's dense partial-pivoting LU instead, whose cost
//! there is a fraction of the sparse factorisation's bookkeeping.
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::factor::{
    lu_in_place, lu_in_place_scratch, PartialPivLuParams,
};
use faer::linalg::lu::partial_pivoting::solve::{solve_in_place_scratch, solve_in_place_with_conj};
use faer::perm::PermRef;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Mat, MatMut, Par, Spec};

/// Systems with at most this many unknowns are factorised densely.
const DENSE_LIMIT: usize = 150;

/// The factorisation behind [`SparseLu`].
enum Factors {
    Sparse {
        symbolic: Box<SymbolicLu<usize>>,
        numeric: Box<NumericLu<usize, f64>>,
    },
    Dense {
        matrix: Mat<f64>,
        perm: Vec<usize>,
        perm_inv: Vec<usize>,
    },
}

/// A square sparse matrix in compressed-column form with a fixed pattern, and its LU factors.
pub struct SparseLu {
    size: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    factors: Factors,
    factor_scratch: MemBuffer,
    solve_scratch: MemBuffer,
    factorised: bool,
}

/// The numeric factorisation failed (singular matrix).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Singular;

impl SparseLu {
    /// Analyses the pattern (columns `col_ptr`, sorted rows `row_idx`). Panics only on an invalid
    /// pattern, which is built by the assembler, never by users.
    pub fn new(size: usize, col_ptr: Vec<usize>, row_idx: Vec<usize>) -> Self {
        let params = Spec::<PartialPivLuParams, f64>::default();
        let (factors, factor_scratch, solve_scratch) = if size <= DENSE_LIMIT {
            (
                Factors::Dense {
                    matrix: Mat::zeros(size, size),
                    perm: vec![0; size],
                    perm_inv: vec![0; size],
                },
                MemBuffer::new(lu_in_place_scratch::<usize, f64>(
                    size,
                    size,
                    Par::Seq,
                    params,
                )),
                MemBuffer::new(solve_in_place_scratch::<usize, f64>(size, 1, Par::Seq)),
            )
        } else {
            let pattern =
                SymbolicSparseColMatRef::new_checked(size, size, &col_ptr, None, &row_idx);
            let symbolic = factorize_symbolic_lu(pattern, Default::default())
                .expect("symbolic LU of an assembler-built pattern");
            let factor_scratch =
                MemBuffer::new(symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, params));
            let solve_scratch = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
            (
                Factors::Sparse {
                    symbolic: Box::new(symbolic),
                    numeric: Box::new(NumericLu::new()),
                },
                factor_scratch,
                solve_scratch,
            )
        };
        SparseLu {
            size,
            col_ptr,
            row_idx,
            factors,
            factor_scratch,
            solve_scratch,
            factorised: false,
        }
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Position of entry (row, col) in the value array, if it is in the pattern.
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        let start = self.col_ptr[col];
        let rows = &self.row_idx[start..self.col_ptr[col + 1]];
        rows.binary_search(&row).ok().map(|k| start + k)
    }

    /// Numeric factorisation of the matrix with these values (in pattern order).
    pub fn factorise(&mut self, values: &[f64]) -> Result<(), Singular> {
        let params = Spec::<PartialPivLuParams, f64>::default();
        let stack = MemStack::new(&mut self.factor_scratch);
        let ok = match &mut self.factors {
            Factors::Sparse { symbolic, numeric } => {
                let pattern = SymbolicSparseColMatRef::new_checked(
                    self.size,
                    self.size,
                    &self.col_ptr,
                    None,
                    &self.row_idx,
                );
                let matrix = SparseColMatRef::new(pattern, values);
                symbolic
                    .factorize_numeric_lu(numeric, matrix, Par::Seq, stack, params)
                    .is_ok()
            }
            Factors::Dense {
                matrix,
                perm,
                perm_inv,
            } => {
                matrix.fill(0.0);
                for col in 0..self.size {
                    for k in self.col_ptr[col]..self.col_ptr[col + 1] {
                        matrix[(self.row_idx[k], col)] = values[k];
                    }
                }
                lu_in_place(matrix.as_mut(), perm, perm_inv, Par::Seq, stack, params);
                (0..self.size).all(|i| {
                    let pivot = matrix[(i, i)];
                    pivot != 0.0 && pivot.is_finite()
                })
            }
        };
        self.factorised = ok;
        if ok {
            Ok(())
        } else {
            Err(Singular)
        }
    }

    /// Solves A x = b in place (b → x) with the last factorisation.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular> {
        if !self.factorised {
            return Err(Singular);
        }
        let stack = MemStack::new(&mut self.solve_scratch);
        let rhs = MatMut::from_column_major_slice_mut(rhs, self.size, 1);
        match &self.factors {
            Factors::Sparse { symbolic, numeric } => {
                LuRef::new_unchecked(symbolic, numeric).solve_in_place_with_conj(
                    Conj::No,
                    rhs,
                    Par::Seq,
                    stack,
                );
            }
            Factors::Dense {
                matrix,
                perm,
                perm_inv,
            } => {
                let row_perm = PermRef::new_checked(perm, perm_inv, self.size);
                solve_in_place_with_conj(
                    matrix.as_ref(),
                    matrix.as_ref(),
                    row_perm,
                    Conj::No,
                    rhs,
                    Par::Seq,
                    stack,
                );
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tridiagonal non-symmetric system, small (dense path) and large (sparse path), against its solution.
    #[test]
    fn both_paths_solve_a_nonsymmetric_banded_system() {
        for size in [20_usize, 400] {
            let mut col_ptr = vec![0];
            let mut row_idx = Vec::new();
            let mut values = Vec::new();
            for col in 0..size {
                for row in col.saturating_sub(1)..(col + 2).min(size) {
                    row_idx.push(row);
                    values.push(if row == col {
                        4.0
                    } else if row < col {
                        -1.0
                    } else {
                        -0.5
                    });
                }
                col_ptr.push(row_idx.len());
            }
            let exact: Vec<f64> = (0..size).map(|i| (i as f64).sin()).collect();
            let mut rhs = vec![0.0; size];
            for col in 0..size {
                for k in col_ptr[col]..col_ptr[col + 1] {
                    rhs[row_idx[k]] += values[k] * exact[col];
                }
            }
            let mut lu = SparseLu::new(size, col_ptr, row_idx);
            lu.factorise(&values).expect("regular");
            lu.solve_in_place(&mut rhs).expect("solves");
            let error = rhs
                .iter()
                .zip(&exact)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(error < 1e-13, "size {size}: {error:e}");
        }
    }
}
