//! Sparse LU of the global tangent with faer: the pattern and its symbolic factorisation are
//! computed once; each Newton iteration refactorises numerically and solves, without allocating.
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::factor::PartialPivLuParams;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Spec};

/// A square sparse matrix in compressed-column form with a fixed pattern, and its LU factors.
pub struct SparseLu {
    size: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
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
        let pattern = SymbolicSparseColMatRef::new_checked(size, size, &col_ptr, None, &row_idx);
        let symbolic = factorize_symbolic_lu(pattern, Default::default())
            .expect("symbolic LU of an assembler-built pattern");
        let factor_scratch = MemBuffer::new(symbolic.factorize_numeric_lu_scratch::<f64>(
            Par::Seq,
            Spec::<PartialPivLuParams, f64>::default(),
        ));
        let solve_scratch = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        SparseLu {
            size,
            col_ptr,
            row_idx,
            symbolic,
            numeric: NumericLu::new(),
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
        let pattern = SymbolicSparseColMatRef::new_checked(
            self.size,
            self.size,
            &self.col_ptr,
            None,
            &self.row_idx,
        );
        let matrix = SparseColMatRef::new(pattern, values);
        let stack = MemStack::new(&mut self.factor_scratch);
        let result = self.symbolic.factorize_numeric_lu(
            &mut self.numeric,
            matrix,
            Par::Seq,
            stack,
            Spec::<PartialPivLuParams, f64>::default(),
        );
        self.factorised = result.is_ok();
        result.map(|_| ()).map_err(|_| Singular)
    }

    /// Solves A x = b in place (b → x) with the last factorisation.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular> {
        if !self.factorised {
            return Err(Singular);
        }
        let lu = faer::sparse::linalg::lu::LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let rhs = MatMut::from_column_major_slice_mut(rhs, self.size, 1);
        lu.solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut self.solve_scratch),
        );
        Ok(())
    }
}
