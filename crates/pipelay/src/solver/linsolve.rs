//! LU of the global tangent. The pattern is analysed once; each Newton iteration refactorises numerically
//! and solves, without allocating. A rod's tangent, its unknowns in node order, is block tridiagonal (each
//! node couples to its neighbours): [`crate::solver::block_lu`] factorises it in fixed-size 6×6 blocks, and
//! where a diagonal block would need pivoting across blocks, the band LU of [`crate::solver::band_lu`] (in
//! n·kl·(kl + ku) operations) takes over. Other narrow bands ([`BAND_LIMIT`]) go to the band LU directly. Otherwise faer's sparse LU (symbolic factorisation computed once), or for
//! small systems faer's dense partial-pivoting LU, whose cost there is a fraction of the sparse
//! factorisation's bookkeeping.
//!
//! **Border.** A vessel's rollers couple its node to every node within their reach. A sparse LU analysed
//! on AᵀA (as faer's is) sees those few dense rows as a dense block and fills hundreds of columns. Given the
//! border unknowns (at most six, the vessel node's), the system [A B; C D][x; z] = [r; s] is solved by block
//! elimination instead: A (the rod with the border held) by the LU of [`crate::solver::window_lu`] (the
//! rollers' wider coupling lies in a window of nodes next to the vessel) or else by the band or sparse LU,
//! X = A⁻¹B once per factorisation, the Schur complement D − C X (at most 6×6) densely, then
//! x = A⁻¹r − X z. Cost stays linear in the unknowns.
// Indexing cannot go out of bounds here: Row and column indices of the pattern the solver built.
#![allow(clippy::indexing_slicing)]
use crate::solver::band_lu::BandLu;
use crate::solver::block_lu::BlockTridiagonalLu;
use crate::solver::window_lu::WindowLu;
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

/// Systems whose bandwidths kl + ku are at most this are factorised as band matrices.
const BAND_LIMIT: usize = 48;

/// The largest |entry| of `values`, NaNs skipped (0 for none). Eight running maxima, each a comparison
/// rather than `f64::max` (whose NaN rule costs three more instructions per entry), so that the loop
/// vectorises instead of waiting on one maximum's dependency chain.
pub fn largest_magnitude(values: &[f64]) -> f64 {
    fn keep_larger(largest: &mut f64, value: f64) {
        if value.abs() > *largest {
            *largest = value.abs();
        }
    }
    let mut lanes = [0.0_f64; 8];
    let chunks = values.chunks_exact(lanes.len());
    let mut largest = 0.0_f64;
    for &value in chunks.remainder() {
        keep_larger(&mut largest, value);
    }
    for chunk in chunks {
        for (lane, &value) in lanes.iter_mut().zip(chunk) {
            keep_larger(lane, value);
        }
    }
    for lane in lanes {
        keep_larger(&mut largest, lane);
    }
    largest
}

/// The factorisation behind [`SparseLu`].
enum Factors {
    /// Block tridiagonal, with the band LU (allocated at its first use) for blocks that need pivoting.
    Block {
        blocks: Box<BlockTridiagonalLu>,
        band: Option<BandLu>,
        banded: bool,
    },
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

/// A square sparse matrix in compressed-column form with a fixed pattern, and its LU factors.
pub struct SparseLu {
    /// With border unknowns: the block elimination around the interior's factorisation.
    border: Option<Box<Border>>,
    /// A rod whose wide coupling lies in a window at one end: the block elimination around it.
    window: Option<Box<WindowLu>>,
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
    /// The tangent of a rod whose unknown i sits at node-major position `slots[i]` (6·node + k, increasing):
    /// block tridiagonal where the pattern is, split at a window of wider coupling at one end of the rod
    /// where it has one ([`WindowLu`]). Unknowns `border` (sorted, at most six) that couple densely to the rest
    /// are factorised by block elimination around the LU of the others (module docs). The values stay in the
    /// whole pattern's order.
    pub fn for_rod(
        slots: &[usize],
        col_ptr: Vec<usize>,
        row_idx: Vec<usize>,
        border: &[usize],
    ) -> Self {
        let size = slots.len();
        if border.is_empty() || border.len() > BORDER_MAX || border.len() >= size {
            if let Some(blocks) = BlockTridiagonalLu::new(slots, &col_ptr, &row_idx) {
                let mut lu = Self::keeping_positions(col_ptr, row_idx);
                lu.factors = Factors::Block {
                    blocks: Box::new(blocks),
                    band: None,
                    banded: false,
                };
                return lu;
            }
            if let Some(window) = WindowLu::new(slots, &col_ptr, &row_idx) {
                let mut lu = Self::keeping_positions(col_ptr, row_idx);
                lu.window = Some(Box::new(window));
                return lu;
            }
            return Self::new(size, col_ptr, row_idx);
        }
        let border = Border::new(slots, &col_ptr, &row_idx, border);
        let mut lu = Self::keeping_positions(col_ptr, row_idx);
        lu.border = Some(Box::new(border));
        lu
    }

    /// An LU that keeps the whole pattern only for positions, its factorisation to be set by the caller (no
    /// analysis of the pattern for the general LU).
    fn keeping_positions(col_ptr: Vec<usize>, row_idx: Vec<usize>) -> Self {
        let mut lu = Self::new(0, vec![0], Vec::new());
        lu.size = col_ptr.len() - 1;
        lu.col_ptr = col_ptr;
        lu.row_idx = row_idx;
        lu
    }

    /// Analyses the pattern (columns `col_ptr`, sorted rows `row_idx`). Panics only on an invalid
    /// pattern, which is built by the assembler, never by users.
    pub fn new(size: usize, col_ptr: Vec<usize>, row_idx: Vec<usize>) -> Self {
        let params = Spec::<PartialPivLuParams, f64>::default();
        let (lower, upper) = BandLu::bandwidths(&col_ptr, &row_idx);
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
            let pattern =
                SymbolicSparseColMatRef::new_checked(size, size, &col_ptr, None, &row_idx);
            // The pattern is square and sorted by construction, and the model's size was checked against the
            // memory (crate::memory) before: faer's only remaining failure would be an index overflow.
            #[allow(clippy::expect_used)]
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
            border: None,
            window: None,
            size,
            col_ptr,
            row_idx,
            factors,
            factor_scratch,
            solve_scratch,
            factorised: false,
        }
    }

    /// Whether the factorisation is the block-tridiagonal one, whose cost is about an assembly's.
    pub fn is_block_tridiagonal(&self) -> bool {
        self.border.is_none()
            && self.window.is_none()
            && matches!(self.factors, Factors::Block { .. })
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
        if let Some(border) = self.border.as_mut() {
            let ok = border.factorise(values).is_ok();
            self.factorised = ok;
            return if ok { Ok(()) } else { Err(Singular) };
        }
        if let Some(window) = self.window.as_mut() {
            let ok = window.factorise(values).is_ok();
            self.factorised = ok;
            return if ok { Ok(()) } else { Err(Singular) };
        }
        let params = Spec::<PartialPivLuParams, f64>::default();
        let stack = MemStack::new(&mut self.factor_scratch);
        let ok = match &mut self.factors {
            Factors::Block {
                blocks,
                band,
                banded,
            } => {
                *banded = blocks.factorise(values).is_err();
                !*banded || {
                    let band = band.get_or_insert_with(|| {
                        let (lower, upper) = BandLu::bandwidths(&self.col_ptr, &self.row_idx);
                        BandLu::new(self.size, lower, upper)
                    });
                    band.factorise(&self.col_ptr, &self.row_idx, values).is_ok()
                }
            }
            Factors::Band(band) => band.factorise(&self.col_ptr, &self.row_idx, values).is_ok(),
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
        if let Some(border) = self.border.as_mut() {
            return border.solve_in_place(rhs);
        }
        if let Some(window) = self.window.as_mut() {
            return window.solve_in_place(rhs);
        }
        let stack = MemStack::new(&mut self.solve_scratch);
        match &mut self.factors {
            Factors::Block {
                band: Some(band),
                banded: true,
                ..
            } => band.solve_in_place(rhs),
            Factors::Block { blocks, .. } => blocks.solve_in_place(rhs),
            Factors::Band(band) => band.solve_in_place(rhs),
            Factors::Sparse { symbolic, numeric } => {
                LuRef::new_unchecked(symbolic, numeric).solve_in_place_with_conj(
                    Conj::No,
                    MatMut::from_column_major_slice_mut(rhs, self.size, 1),
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
                    MatMut::from_column_major_slice_mut(rhs, self.size, 1),
                    Par::Seq,
                    stack,
                );
            }
        }
        Ok(())
    }
}

/// Most border unknowns (one node's).
const BORDER_MAX: usize = 6;

/// Copies part of a pattern's values into a smaller pattern's, as runs of consecutive positions that land on
/// consecutive positions (a column of the part is one run), instead of one decision per value.
#[derive(Debug, Default)]
pub struct Gather {
    /// (first source position, first destination position, length).
    runs: Vec<(usize, usize, usize)>,
}

impl Gather {
    /// Value `source` of the whole pattern goes to position `destination` of the part.
    pub fn push(&mut self, source: usize, destination: usize) {
        match self.runs.last_mut() {
            Some(run) if run.0 + run.2 == source && run.1 + run.2 == destination => run.2 += 1,
            _ => self.runs.push((source, destination, 1)),
        }
    }

    /// Copies the part's values from `values` into `part`.
    pub fn copy(&self, values: &[f64], part: &mut [f64]) {
        for &(source, destination, length) in &self.runs {
            part[destination..destination + length]
                .copy_from_slice(&values[source..source + length]);
        }
    }
}

/// A square pattern's unknowns in two groups, the first (A) and the second (D), for block elimination of
/// [A B; C D]: each group's own pattern with the runs that copy its values out of the whole pattern's, and
/// the entries that couple the groups.
pub struct Partition {
    /// Each unknown's index within its group, and whether that is the second.
    pub index: Vec<usize>,
    pub second: Vec<bool>,
    /// A's and D's patterns (columns, rows) and values.
    pub patterns: [(Vec<usize>, Vec<usize>); 2],
    pub gathers: [Gather; 2],
    /// B's entries (first row, second column) and C's (second row, first column): (position in the whole
    /// pattern, row, column), each index within its group.
    pub right: Vec<(usize, usize, usize)>,
    pub below: Vec<(usize, usize, usize)>,
}

impl Partition {
    /// The pattern of columns `col_ptr` and sorted rows `row_idx` split by `in_second(unknown)`.
    pub fn new(col_ptr: &[usize], row_idx: &[usize], in_second: impl Fn(usize) -> bool) -> Self {
        let size = col_ptr.len() - 1;
        let second: Vec<bool> = (0..size).map(in_second).collect();
        let mut counts = [0, 0];
        let index = second
            .iter()
            .map(|&group| {
                let count = &mut counts[usize::from(group)];
                *count += 1;
                *count - 1
            })
            .collect::<Vec<_>>();
        let mut patterns = [(vec![0], Vec::new()), (vec![0], Vec::new())];
        let mut gathers = [Gather::default(), Gather::default()];
        let (mut right, mut below) = (Vec::new(), Vec::new());
        for col in 0..size {
            let range = col_ptr[col]..col_ptr[col + 1];
            for (k, &row) in range.clone().zip(&row_idx[range]) {
                let entry = (k, index[row], index[col]);
                match (second[row], second[col]) {
                    (false, true) => right.push(entry),
                    (true, false) => below.push(entry),
                    (group, _) => {
                        let (gather, pattern) = (
                            &mut gathers[usize::from(group)],
                            &mut patterns[usize::from(group)],
                        );
                        gather.push(k, pattern.1.len());
                        pattern.1.push(index[row]);
                    }
                }
            }
            let pattern = &mut patterns[usize::from(second[col])];
            pattern.0.push(pattern.1.len());
        }
        Partition {
            index,
            second,
            patterns,
            gathers,
            right,
            below,
        }
    }

    /// The unknowns of group `second` (false: the first) in order, each with its index within the group.
    pub fn group(&self, second: bool) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.index.len())
            .filter(move |&i| self.second[i] == second)
            .map(|i| (i, self.index[i]))
    }
}

/// The block elimination of a bordered system (module docs).
struct Border {
    /// Border unknowns.
    unknowns: Vec<usize>,
    /// The interior (A) and the border (D) of the whole pattern (each unknown's index in its own), and where
    /// B and C go.
    partition: Partition,
    corner_values: Vec<f64>,
    interior: SparseLu,
    interior_values: Vec<f64>,
    /// B and X = A⁻¹B, column by column (interior × border), and C row by row (border × interior).
    right: Vec<Vec<f64>>,
    solved: Vec<Vec<f64>>,
    below: Vec<Vec<f64>>,
    corner: nalgebra::Matrix6<f64>,
    /// LU of the Schur complement D − C X (padded with the identity to 6×6).
    schur: Option<nalgebra::LU<f64, nalgebra::Const<6>, nalgebra::Const<6>>>,
    work: Vec<f64>,
}

impl Border {
    /// The system of unknowns at node-major positions `slots` (see [`SparseLu::for_rod`]).
    fn new(slots: &[usize], col_ptr: &[usize], row_idx: &[usize], border: &[usize]) -> Self {
        let mut partition = Partition::new(col_ptr, row_idx, |i| border.contains(&i));
        let interior_slots: Vec<usize> = partition.group(false).map(|(i, _)| slots[i]).collect();
        let count = interior_slots.len();
        // The interior's pattern moves to its LU; the corner's stays for the copy into the 6×6 block.
        let (inner_ptr, inner_rows) = std::mem::take(&mut partition.patterns[0]);
        Border {
            unknowns: border.to_vec(),
            interior_values: vec![0.0; inner_rows.len()],
            interior: SparseLu::for_rod(&interior_slots, inner_ptr, inner_rows, &[]),
            corner_values: vec![0.0; partition.patterns[1].1.len()],
            partition,
            right: vec![vec![0.0; count]; border.len()],
            solved: vec![vec![0.0; count]; border.len()],
            below: vec![vec![0.0; count]; border.len()],
            corner: nalgebra::Matrix6::identity(),
            schur: None,
            work: vec![0.0; count],
        }
    }

    fn factorise(&mut self, values: &[f64]) -> Result<(), Singular> {
        let m = self.unknowns.len();
        for column in self.right.iter_mut().chain(self.below.iter_mut()) {
            column.iter_mut().for_each(|v| *v = 0.0);
        }
        self.corner = nalgebra::Matrix6::identity();
        for r in 0..m {
            for c in 0..m {
                self.corner[(r, c)] = 0.0;
            }
        }
        let partition = &self.partition;
        partition.gathers[0].copy(values, &mut self.interior_values);
        partition.gathers[1].copy(values, &mut self.corner_values);
        for &(position, i, c) in &partition.right {
            self.right[c][i] = values[position];
        }
        for &(position, r, i) in &partition.below {
            self.below[r][i] = values[position];
        }
        let (corner_ptr, corner_rows) = &partition.patterns[1];
        for c in 0..m {
            let range = corner_ptr[c]..corner_ptr[c + 1];
            for (&r, &value) in corner_rows[range.clone()]
                .iter()
                .zip(&self.corner_values[range])
            {
                self.corner[(r, c)] = value;
            }
        }
        self.interior.factorise(&self.interior_values)?;
        let mut schur = self.corner;
        for c in 0..m {
            self.solved[c].copy_from_slice(&self.right[c]);
            self.interior.solve_in_place(&mut self.solved[c])?;
            for r in 0..m {
                let product: f64 = self.below[r]
                    .iter()
                    .zip(&self.solved[c])
                    .map(|(a, b)| a * b)
                    .sum();
                schur[(r, c)] -= product;
            }
        }
        let lu = schur.lu();
        if !lu.is_invertible() || !schur.iter().all(|v| v.is_finite()) {
            self.schur = None;
            return Err(Singular);
        }
        self.schur = Some(lu);
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular> {
        let Some(schur) = &self.schur else {
            return Err(Singular);
        };
        for (i, slot) in self.partition.group(false) {
            self.work[slot] = rhs[i];
        }
        self.interior.solve_in_place(&mut self.work)?;
        let m = self.unknowns.len();
        let mut reduced = nalgebra::Vector6::zeros();
        for r in 0..m {
            let product: f64 = self.below[r]
                .iter()
                .zip(&self.work)
                .map(|(a, b)| a * b)
                .sum();
            reduced[r] = rhs[self.unknowns[r]] - product;
        }
        let z = schur.solve(&reduced).ok_or(Singular)?;
        for (i, slot) in self.partition.group(false) {
            let correction: f64 = (0..m).map(|c| self.solved[c][slot] * z[c]).sum();
            rhs[i] = self.work[slot] - correction;
        }
        for (r, &i) in self.unknowns.iter().enumerate() {
            rhs[i] = z[r];
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::test_support::{sparse_matrix, sparse_solve_error};

    /// The largest |entry| wherever it sits (in the eight lanes or the remainder), of either sign, with NaNs
    /// skipped, against a plain fold.
    #[test]
    fn largest_magnitude_is_the_plain_maximum_with_nans_skipped() {
        for length in [0_usize, 1, 7, 8, 9, 23, 64, 101] {
            for at in 0..length {
                let mut values: Vec<f64> = (0..length).map(|i| (i as f64 * 0.7).sin()).collect();
                values[at] = if at % 2 == 0 { -3.5 } else { 3.5 };
                values[(at + 1) % length] = f64::NAN;
                let plain = values
                    .iter()
                    .filter(|v| !v.is_nan())
                    .fold(0.0_f64, |m, v| m.max(v.abs()));
                assert_eq!(
                    largest_magnitude(&values),
                    plain,
                    "length {length}, at {at}"
                );
            }
        }
        assert_eq!(largest_magnitude(&[]), 0.0);
    }

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
        for mut lu in [
            SparseLu::for_rod(
                &(0..size).collect::<Vec<_>>(),
                col_ptr.clone(),
                row_idx.clone(),
                &border,
            ),
            SparseLu::new(size, col_ptr.clone(), row_idx.clone()),
        ] {
            let error = sparse_solve_error(&mut lu, &col_ptr, &row_idx, &values);
            assert!(error < 1e-12, "{error:e}");
        }
    }

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
            let mut lu = SparseLu::new(size, col_ptr.clone(), row_idx.clone());
            let error = sparse_solve_error(&mut lu, &col_ptr, &row_idx, &values);
            assert!(error < 1e-13, "size {size}: {error:e}");
        }
    }
}
