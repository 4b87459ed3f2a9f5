//! LU of the global tangent. The pattern is analysed once; each Newton iteration refactorises numerically
//! and solves, without allocating. The factorisation is chosen by the pattern's shape:
//! - a rod's tangent, its unknowns in node order, is block tridiagonal (each node couples to its
//!   neighbours): [`RodLu`];
//! - a vessel's rollers couple a window of nodes next to the vessel up to four nodes apart: block
//!   elimination around that window ([`WindowLu`]);
//! - they also couple the vessel's node to every node within their reach: block elimination around those
//!   border unknowns ([`BorderLu`]), whose interior is one of the two above;
//! - any other pattern: [`GeneralLu`] (band, dense or sparse LU).
use crate::linalg::border_lu::{BorderLu, BORDER_MAX};
use crate::linalg::factorisation::{Factorisation, Singular};
use crate::linalg::general_lu::GeneralLu;
use crate::linalg::pattern::Pattern;
use crate::linalg::rod_lu::RodLu;
use crate::linalg::window_lu::WindowLu;

/// A factorisation without border unknowns.
enum Unbordered {
    Rod(RodLu),
    /// The whole pattern is kept for positions; the window's LU holds the parts.
    Window {
        pattern: Pattern,
        lu: Box<WindowLu>,
    },
}

impl Unbordered {
    /// Block tridiagonal where the pattern is, split at a window of wider coupling at one end of the rod where
    /// it has one, general otherwise.
    fn new(slots: &[usize], pattern: Pattern) -> Self {
        match RodLu::block(slots, pattern) {
            Ok(rod) => Unbordered::Rod(rod),
            Err(pattern) => match WindowLu::new(slots, &pattern) {
                Some(lu) => Unbordered::Window {
                    pattern,
                    lu: Box::new(lu),
                },
                None => Unbordered::Rod(RodLu::General(GeneralLu::new(pattern))),
            },
        }
    }

    fn pattern(&self) -> &Pattern {
        match self {
            Unbordered::Rod(lu) => lu.pattern(),
            Unbordered::Window { pattern, .. } => pattern,
        }
    }
}

impl Factorisation for Unbordered {
    fn factorise(&mut self, values: &[f64]) -> Result<(), Singular> {
        match self {
            Unbordered::Rod(lu) => lu.factorise(values),
            Unbordered::Window { lu, .. } => lu.factorise(values),
        }
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular> {
        match self {
            Unbordered::Rod(lu) => lu.solve_in_place(rhs),
            Unbordered::Window { lu, .. } => lu.solve_in_place(rhs),
        }
    }
}

enum Factors {
    Unbordered(Unbordered),
    /// The whole pattern is kept for positions; the border's LU holds the parts.
    Bordered {
        pattern: Pattern,
        lu: Box<BorderLu<Unbordered>>,
    },
}

/// The LU of a rod's tangent (module docs).
pub struct TangentLu {
    factors: Factors,
    factorised: bool,
}

impl TangentLu {
    /// The tangent of a rod whose unknown i sits at node-major position `slots[i]` (6·node + k, increasing),
    /// of pattern `pattern`. Unknowns `border` (sorted, at most six) that couple densely to the rest are
    /// factorised by block elimination around the LU of the others. The values stay in the whole pattern's
    /// order.
    pub fn for_rod(slots: &[usize], pattern: Pattern, border: &[usize]) -> Self {
        let factors =
            if border.is_empty() || border.len() > BORDER_MAX || border.len() >= slots.len() {
                Factors::Unbordered(Unbordered::new(slots, pattern))
            } else {
                let lu = BorderLu::new(slots, &pattern, border, Unbordered::new);
                Factors::Bordered {
                    pattern,
                    lu: Box::new(lu),
                }
            };
        TangentLu {
            factors,
            factorised: false,
        }
    }

    fn pattern(&self) -> &Pattern {
        match &self.factors {
            Factors::Unbordered(lu) => lu.pattern(),
            Factors::Bordered { pattern, .. } => pattern,
        }
    }

    /// Whether the factorisation is the block-tridiagonal one, whose cost is about an assembly's.
    pub fn is_block_tridiagonal(&self) -> bool {
        matches!(&self.factors, Factors::Unbordered(Unbordered::Rod(lu)) if lu.is_block_tridiagonal())
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.pattern().nnz()
    }

    /// Position of entry (row, col) in the value array, if it is in the pattern.
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        self.pattern().position(row, col)
    }
}

impl Factorisation for TangentLu {
    fn factorise(&mut self, values: &[f64]) -> Result<(), Singular> {
        let outcome = match &mut self.factors {
            Factors::Unbordered(lu) => lu.factorise(values),
            Factors::Bordered { lu, .. } => lu.factorise(values),
        };
        self.factorised = outcome.is_ok();
        outcome
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular> {
        if !self.factorised {
            return Err(Singular);
        }
        match &mut self.factors {
            Factors::Unbordered(lu) => lu.solve_in_place(rhs),
            Factors::Bordered { lu, .. } => lu.solve_in_place(rhs),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::test_support::{sparse_matrix, sparse_solve_error};

    /// An arrowhead system (tridiagonal, with its last three unknowns coupled to every tenth one), solved by
    /// block elimination around those three, against its solution; the same with the plain LU.
    #[test]
    fn a_bordered_system_solves_by_block_elimination() {
        let size = 300_usize;
        let border = [size - 3, size - 2, size - 1];
        let coupled = |a: usize, b: usize| {
            a.abs_diff(b) <= 1
                || (border.contains(&a) && (b % 10 == 0 || border.contains(&b)))
                || (border.contains(&b) && a % 10 == 0)
        };
        let (col_ptr, row_idx, values) = sparse_matrix(size, coupled, 6.0);
        let pattern = Pattern::new(col_ptr.clone(), row_idx.clone());
        let slots: Vec<usize> = (0..size).collect();
        let mut bordered = TangentLu::for_rod(&slots, pattern.clone(), &border);
        let mut plain = GeneralLu::new(pattern);
        for error in [
            sparse_solve_error(&mut bordered, &col_ptr, &row_idx, &values),
            sparse_solve_error(&mut plain, &col_ptr, &row_idx, &values),
        ] {
            assert!(error < 1e-12, "{error:e}");
        }
    }
}
