//! LU of a rod's tangent that is block tridiagonal except in a window of nodes at one end, where a vessel's
//! rollers couple each node to its neighbours up to four nodes away.
//!
//! Ordered as [P; W] (the rest of the rod P, the window W), the system [A B; C D][x; w] = [r; s] couples P
//! and W only through the block between the window's first node and its neighbour: B has at most six
//! nonzero columns and C at most six nonzero rows. Block elimination factorises A by the block-tridiagonal
//! LU of [`crate::linalg::block_lu`], forms Z = A⁻¹B (one solve per nonzero column of B) and the Schur
//! complement D − C Z, which differs from D in one 6×6 block and so keeps D's band, and factorises it by the
//! band LU. A solve is then x̃ = A⁻¹r, w = (D − C Z)⁻¹(s − C x̃), x = x̃ − Z w: the band LU's cost is paid on
//! the window alone, not on the whole rod's widest band.
// Indexing cannot go out of bounds here: Row, column and value indices of the pattern the assembler built.
#![allow(clippy::indexing_slicing)]
use crate::linalg::factorisation::{Factorisation, Singular};
use crate::linalg::general_lu::GeneralLu;
use crate::linalg::partition::{Gather, Partition};
use crate::linalg::pattern::Pattern;
use crate::linalg::rod_lu::RodLu;

/// Fewest unknowns outside the window for which the split pays (below, the whole band LU is as cheap).
const MIN_REST: usize = 60;

/// Most columns of B (one node's unknowns).
const MAX_COUPLING: usize = 6;

/// The factorisation of a rod's tangent split at its roller window (module docs).
pub struct WindowLu {
    /// Each unknown's index in A or in D, and whether it is in the window (D).
    index: Vec<usize>,
    in_window: Vec<bool>,
    /// A's and D's values in the whole pattern.
    rest_gather: Gather,
    window_gather: Gather,
    rest: RodLu,
    rest_values: Vec<f64>,
    window: GeneralLu,
    window_values: Vec<f64>,
    /// D-indices of B's nonzero columns and of C's nonzero rows.
    coupled_columns: Vec<usize>,
    coupled_rows: Vec<usize>,
    /// Value position in D's pattern of (coupled row i, coupled column j), row-major.
    schur_positions: Vec<usize>,
    /// B's entries (position in the whole pattern, row of A, coupled column), C's (position, coupled row,
    /// column of A), and C's values as factorised.
    right: Vec<(usize, usize, usize)>,
    below: Vec<(usize, usize, usize)>,
    below_values: Vec<f64>,
    /// Z = A⁻¹B, column by column.
    solved: Vec<Vec<f64>>,
    rest_work: Vec<f64>,
    window_work: Vec<f64>,
}

impl WindowLu {
    /// The split of the tangent whose unknown i sits at node-major position `slots[i]` (6·node + k,
    /// increasing), of pattern `pattern`; `None` where the entries coupling nodes more than one apart do not
    /// lie in one window at an end of the rod, or the rest is too small to pay.
    pub fn new(slots: &[usize], pattern: &Pattern) -> Option<Self> {
        let (col_ptr, row_idx) = (&pattern.col_ptr, &pattern.row_idx);
        let size = slots.len();
        let node = |i: usize| slots[i] / 6;
        let (mut low, mut high) = (usize::MAX, 0);
        for column in 0..size {
            for &row in &row_idx[col_ptr[column]..col_ptr[column + 1]] {
                let (a, b) = (node(row), node(column));
                if a.abs_diff(b) > 1 {
                    low = low.min(a.min(b));
                    high = high.max(a.max(b));
                }
            }
        }
        if low == usize::MAX || size == 0 || (low != node(0) && high != node(size - 1)) {
            return None;
        }
        let mut partition = Partition::new(col_ptr, row_idx, |i| (low..=high).contains(&node(i)));
        let rest_slots: Vec<usize> = partition.group(false).map(|(i, _)| slots[i]).collect();
        if rest_slots.len() < MIN_REST {
            return None;
        }
        // B's nonzero columns and C's nonzero rows, as D-indices, in order of appearance.
        let index_in = |list: &mut Vec<usize>, item: usize| {
            list.iter().position(|&x| x == item).unwrap_or_else(|| {
                list.push(item);
                list.len() - 1
            })
        };
        let (mut coupled_columns, mut coupled_rows) = (Vec::new(), Vec::new());
        let right: Vec<(usize, usize, usize)> = partition
            .right
            .iter()
            .map(|&(k, row, column)| (k, row, index_in(&mut coupled_columns, column)))
            .collect();
        let below: Vec<(usize, usize, usize)> = partition
            .below
            .iter()
            .map(|&(k, row, column)| (k, index_in(&mut coupled_rows, row), column))
            .collect();
        let [(rest_ptr, rest_rows), (window_ptr, window_rows)] =
            std::mem::take(&mut partition.patterns);
        let [rest_gather, window_gather] = std::mem::take(&mut partition.gathers);
        if coupled_columns.len() > MAX_COUPLING || coupled_rows.len() > MAX_COUPLING {
            return None;
        }
        let (rest_count, window_count) = (rest_ptr.len() - 1, window_ptr.len() - 1);
        let window_values = vec![0.0; window_rows.len()];
        let window = GeneralLu::new(Pattern::new(window_ptr, window_rows));
        // C Z changes D where a coupled row meets a coupled column: D's pattern must hold those entries.
        let mut schur_positions = Vec::with_capacity(coupled_rows.len() * coupled_columns.len());
        for &row in &coupled_rows {
            for &column in &coupled_columns {
                schur_positions.push(window.pattern().position(row, column)?);
            }
        }
        Some(WindowLu {
            rest_values: vec![0.0; rest_rows.len()],
            rest: RodLu::new(&rest_slots, Pattern::new(rest_ptr, rest_rows)),
            window_values,
            window,
            solved: vec![vec![0.0; rest_count]; coupled_columns.len()],
            right,
            below_values: vec![0.0; below.len()],
            below,
            coupled_columns,
            coupled_rows,
            schur_positions,
            index: std::mem::take(&mut partition.index),
            in_window: std::mem::take(&mut partition.second),
            rest_gather,
            window_gather,
            rest_work: vec![0.0; rest_count],
            window_work: vec![0.0; window_count],
        })
    }
}

impl Factorisation for WindowLu {
    /// Factorises the matrix with `values` in the whole pattern's order.
    fn factorise(&mut self, values: &[f64]) -> Result<(), Singular> {
        self.rest_gather.copy(values, &mut self.rest_values);
        self.window_gather.copy(values, &mut self.window_values);
        for (value, &(position, _, _)) in self.below_values.iter_mut().zip(&self.below) {
            *value = values[position];
        }
        self.rest.factorise(&self.rest_values)?;
        for column in &mut self.solved {
            column.iter_mut().for_each(|z| *z = 0.0);
        }
        for &(position, row, j) in &self.right {
            self.solved[j][row] = values[position];
        }
        for column in &mut self.solved {
            self.rest.solve_in_place(column)?;
        }
        // D − C Z, in the coupled rows and columns.
        let columns = self.coupled_columns.len();
        for (&(_, i, column), value) in self.below.iter().zip(&self.below_values) {
            for (j, solved) in self.solved.iter().enumerate() {
                self.window_values[self.schur_positions[i * columns + j]] -= value * solved[column];
            }
        }
        self.window.factorise(&self.window_values)
    }

    /// Solves A x = b in place (b → x) with the last factorisation.
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular> {
        let mut rest_loaded = false;
        for ((&index, &in_window), &value) in self.index.iter().zip(&self.in_window).zip(rhs.iter())
        {
            if in_window {
                self.window_work[index] = value;
            } else {
                self.rest_work[index] = value;
                rest_loaded |= value != 0.0;
            }
        }
        // A⁻¹0 = 0: the bordered system's columns for the vessel load the window alone.
        if rest_loaded {
            self.rest.solve_in_place(&mut self.rest_work)?;
        }
        for (&(_, i, column), value) in self.below.iter().zip(&self.below_values) {
            self.window_work[self.coupled_rows[i]] -= value * self.rest_work[column];
        }
        self.window.solve_in_place(&mut self.window_work)?;
        for (solved, &column) in self.solved.iter().zip(&self.coupled_columns) {
            let w = self.window_work[column];
            for (x, z) in self.rest_work.iter_mut().zip(solved) {
                *x -= z * w;
            }
        }
        for ((&index, &in_window), value) in
            self.index.iter().zip(&self.in_window).zip(rhs.iter_mut())
        {
            *value = if in_window {
                self.window_work[index]
            } else {
                self.rest_work[index]
            };
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::tangent_lu::TangentLu;
    use crate::linalg::test_support::{sparse_matrix, sparse_solve_error};

    /// A rod's pattern over `nodes` nodes of six unknowns, the first node's translations prescribed:
    /// neighbours coupled, nodes `window` coupled up to three apart, and node `vessel` (if any) coupled to
    /// every node of the window. Returns the unknowns' slots, the pattern and its (non-symmetric, diagonally
    /// dominant) values.
    fn rod_pattern(
        nodes: usize,
        window: std::ops::RangeInclusive<usize>,
        vessel: Option<usize>,
    ) -> (Vec<usize>, Vec<usize>, Vec<usize>, Vec<f64>) {
        let slots: Vec<usize> = (3..6 * nodes).collect();
        let coupled = |a: usize, b: usize| {
            let (na, nb) = (slots[a] / 6, slots[b] / 6);
            na.abs_diff(nb) <= 1
                || (window.contains(&na) && window.contains(&nb) && na.abs_diff(nb) <= 3)
                || vessel.is_some_and(|v| {
                    (na == v && window.contains(&nb)) || (nb == v && window.contains(&na))
                })
        };
        let (col_ptr, row_idx, values) = sparse_matrix(slots.len(), coupled, 20.0);
        (slots, col_ptr, row_idx, values)
    }

    /// The split is found where the wide coupling lies in a window at either end of the rod, not in the
    /// middle, and not without one.
    #[test]
    fn the_window_is_found_at_either_end_only() {
        let found = |window, vessel| {
            let (slots, col_ptr, row_idx, _) = rod_pattern(40, window, vessel);
            WindowLu::new(&slots, &Pattern::new(col_ptr, row_idx)).is_some()
        };
        assert!(found(28..=39, None));
        assert!(found(0..=11, None));
        assert!(!found(10..=20, None));
        assert!(!found(39..=39, None));
    }

    /// A rod with its vessel at either end: the bordered factorisation around the window's solves it to
    /// round-off, as the whole-pattern LU does.
    #[test]
    fn a_rod_with_a_roller_window_solves_to_round_off() {
        for (window, vessel) in [(28..=38, 39), (1..=11, 0)] {
            let (slots, col_ptr, row_idx, values) = rod_pattern(40, window, Some(vessel));
            let size = slots.len();
            let border: Vec<usize> = (0..size).filter(|&i| slots[i] / 6 == vessel).collect();
            let interior: Vec<usize> = (0..size).filter(|i| !border.contains(i)).collect();
            let interior_slots: Vec<usize> = interior.iter().map(|&i| slots[i]).collect();
            let (mut inner_ptr, mut inner_rows) = (vec![0], Vec::new());
            for &col in &interior {
                for &row in &row_idx[col_ptr[col]..col_ptr[col + 1]] {
                    if let Some(r) = interior.iter().position(|&i| i == row) {
                        inner_rows.push(r);
                    }
                }
                inner_ptr.push(inner_rows.len());
            }
            assert!(WindowLu::new(&interior_slots, &Pattern::new(inner_ptr, inner_rows)).is_some());
            let pattern = Pattern::new(col_ptr.clone(), row_idx.clone());
            let mut split = TangentLu::for_rod(&slots, pattern.clone(), &border);
            let mut whole = GeneralLu::new(pattern);
            for error in [
                sparse_solve_error(&mut split, &col_ptr, &row_idx, &values),
                sparse_solve_error(&mut whole, &col_ptr, &row_idx, &values),
            ] {
                assert!(error < 1e-12, "vessel at node {vessel}: {error:e}");
            }
        }
    }
}
