//! What every factorisation of a fixed pattern offers: a numeric factorisation of the pattern's values and
//! solves with it, each of which may find the matrix singular.

/// The numeric factorisation failed (singular matrix), or a solve was asked of a failed one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Singular;

/// An LU of a square matrix whose sparsity pattern was analysed at construction.
pub trait Factorisation {
    /// Numeric factorisation of the matrix with these values (in the pattern's order).
    fn factorise(&mut self, values: &[f64]) -> Result<(), Singular>;
    /// Solves A x = b in place (b → x) with the last factorisation.
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular>;
}
