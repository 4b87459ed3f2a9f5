//! A square matrix's sparsity pattern in compressed-column form: column pointers and sorted row indices.
// Indexing cannot go out of bounds here: columns below the size of a pattern built by the assembler.
#![allow(clippy::indexing_slicing)]

/// The pattern of a square sparse matrix: column j's rows are `row_idx[col_ptr[j]..col_ptr[j + 1]]`, sorted.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pattern {
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
}

impl Pattern {
    /// The pattern of columns `col_ptr` and sorted rows `row_idx`.
    pub fn new(col_ptr: Vec<usize>, row_idx: Vec<usize>) -> Self {
        Pattern { col_ptr, row_idx }
    }

    /// Number of unknowns (columns).
    pub fn size(&self) -> usize {
        self.col_ptr.len() - 1
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
}
