//! LU of a square matrix of any fixed pattern: narrow bands (`BAND_LIMIT`) by the band LU of
//! [`crate::linalg::band_lu`] (in n·kl·(kl + ku) operations), small systems by faer's dense partial-pivoting
//! LU (whose cost there is a fraction of the sparse factorisation's bookkeeping), the rest by faer's sparse
//! LU with its symbolic factorisation computed once. Each numeric factorisation and solve runs without
//! allocating.
// Indexing cannot go out of bounds here: Row and column indices of the pattern the assembler built.
#![allow(clippy::indexing_slicing)]
use crate::linalg::band_lu::BandLu;
use crate::linalg::factorisation::{Factorisation, Singular};
use crate::linalg::pattern::Pattern;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::factor::{
    lu_in_place, lu_in_place_scratch, PartialPivLuParams,
};
use faer::linalg::lu::partial_pivoting::solve::{solve_in_place_scratch, solve_in_place_with_conj};
use faer::perm::PermRef;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Mat, MatMut, Par, Spec};

/// Systems with at most this many unknowns are factorised densely (unless banded).
const DENSE_LIMIT: usize = 150;

/// Systems whose bandwidths kl + ku are at most this are factorised as band matrices: node-ordered unknowns
/// coupled to nodes up to four apart (rollers, [`crate::contact::rollers::COUPLING_REACH`]) have
/// kl = ku = 5·6 − 1.
const BAND_LIMIT: usize = 58;

/// The factorisation behind [`GeneralLu`].
enum Factors {
    Band(BandLu),
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

/// A square sparse matrix of a fixed pattern, and its LU factors.
pub struct GeneralLu {
    pattern: Pattern,
    factors: Factors,
    factor_scratch: MemBuffer,
    solve_scratch: MemBuffer,
    factorised: bool,
}

impl GeneralLu {
    /// Analyses `pattern`. Panics only on an invalid pattern, which is built by the assembler, never by users.
    pub fn new(pattern: Pattern) -> Self {
        let size = pattern.size();
        let params = Spec::<PartialPivLuParams, f64>::default();
        let (lower, upper) = BandLu::bandwidths(&pattern.col_ptr, &pattern.row_idx);
        let (factors, factor_scratch, solve_scratch) = if lower + upper <= BAND_LIMIT {
            (
                Factors::Band(BandLu::new(size, lower, upper)),
                MemBuffer::new(faer::dyn_stack::StackReq::empty()),
                MemBuffer::new(faer::dyn_stack::StackReq::empty()),
            )
        } else if size <= DENSE_LIMIT {
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
            let symbolic_pattern = SymbolicSparseColMatRef::new_checked(
                size,
                size,
                &pattern.col_ptr,
                None,
                &pattern.row_idx,
            );
            // The pattern is square and sorted by construction, and the model's size was checked against the
            // memory (crate::memory) before: faer's only remaining failure would be an index overflow.
            #[allow(clippy::expect_used)]
            let symbolic = factorize_symbolic_lu(symbolic_pattern, Default::default())
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
        GeneralLu {
            pattern,
            factors,
            factor_scratch,
            solve_scratch,
            factorised: false,
        }
    }

    /// The matrix's pattern.
    pub fn pattern(&self) -> &Pattern {
        &self.pattern
    }
}

impl Factorisation for GeneralLu {
    fn factorise(&mut self, values: &[f64]) -> Result<(), Singular> {
        let params = Spec::<PartialPivLuParams, f64>::default();
        let stack = MemStack::new(&mut self.factor_scratch);
        let pattern = &self.pattern;
        let size = pattern.size();
        let ok = match &mut self.factors {
            Factors::Band(band) => band
                .factorise(&pattern.col_ptr, &pattern.row_idx, values)
                .is_ok(),
            Factors::Sparse { symbolic, numeric } => {
                let symbolic_pattern = SymbolicSparseColMatRef::new_checked(
                    size,
                    size,
                    &pattern.col_ptr,
                    None,
                    &pattern.row_idx,
                );
                let matrix = SparseColMatRef::new(symbolic_pattern, values);
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
                for col in 0..size {
                    for k in pattern.col_ptr[col]..pattern.col_ptr[col + 1] {
                        matrix[(pattern.row_idx[k], col)] = values[k];
                    }
                }
                lu_in_place(matrix.as_mut(), perm, perm_inv, Par::Seq, stack, params);
                (0..size).all(|i| {
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

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular> {
        if !self.factorised {
            return Err(Singular);
        }
        let size = self.pattern.size();
        let stack = MemStack::new(&mut self.solve_scratch);
        match &mut self.factors {
            Factors::Band(band) => band.solve_in_place(rhs),
            Factors::Sparse { symbolic, numeric } => {
                LuRef::new_unchecked(symbolic, numeric).solve_in_place_with_conj(
                    Conj::No,
                    MatMut::from_column_major_slice_mut(rhs, size, 1),
                    Par::Seq,
                    stack,
                );
            }
            Factors::Dense {
                matrix,
                perm,
                perm_inv,
            } => {
                let row_perm = PermRef::new_checked(perm, perm_inv, size);
                solve_in_place_with_conj(
                    matrix.as_ref(),
                    matrix.as_ref(),
                    row_perm,
                    Conj::No,
                    MatMut::from_column_major_slice_mut(rhs, size, 1),
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
    use crate::linalg::test_support::sparse_solve_error;

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
            let mut lu = GeneralLu::new(Pattern::new(col_ptr.clone(), row_idx.clone()));
            let error = sparse_solve_error(&mut lu, &col_ptr, &row_idx, &values);
            assert!(error < 1e-13, "size {size}: {error:e}");
        }
    }
}
