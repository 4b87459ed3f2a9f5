//! LU of a block-tridiagonal matrix of B×B blocks: the rod's tangent with its unknowns in node order, where
//! each node couples only to its two neighbours (Golub & Van Loan, Matrix Computations, §4.5.1, block
//! tridiagonal LU), eliminated from both ends towards the middle node m (a "twisted" factorisation, whose two
//! halves run in parallel). With A_i,i−1 = L_i, A_ii = D_i, A_i,i+1 = U_i:
//!
//!   from the top, i < m:     S_0 = D_0,          S_i = D_i − L_i X_i−1,   X_i = S_i⁻¹U_i;
//!   from the bottom, i > m:  T_n−1 = D_n−1,      T_i = D_i − U_i Y_i+1,   Y_i = T_i⁻¹L_i;
//!   the middle:              M = D_m − L_m X_m−1 − U_m Y_m+1,
//!
//! each S_i, T_i and M factorised by LU with partial pivoting inside the block. Then A x = b by
//! y_i = S_i⁻¹(b_i − L_i y_i−1) (i < m), z_i = T_i⁻¹(b_i − U_i z_i+1) (i > m),
//! x_m = M⁻¹(b_m − L_m y_m−1 − U_m z_m+1), and outwards x_i = y_i − X_i x_i+1, x_i = z_i − Y_i x_i−1. With
//! B = 6 (a rod's node: three positions, three rotations) it costs about 500 multiply–adds per node in
//! fixed-size loops, against 6·kl·(kl + ku) ≈ 1450 for the band LU with kl = ku = 11; with B = 3 (a line of
//! cable nodes, positions only) about an eighth of that ([`NodeBlocks`] picks B from the unknowns).
//!
//! Pivoting stays within the diagonal blocks. That is stable for the block diagonally dominant or positive
//! definite tangents of dynamics (mass over Δt²) and of stable statics; a block whose pivot falls below
//! `PIVOT_FLOOR` of its size is reported, and the caller factorises with full band pivoting instead.
//!
//! Prescribed DOFs are not unknowns: their rows and columns are padded with the identity, so that every node
//! has a full B×B block.
// Indexing cannot go out of bounds here: node indices below the node count, entries below B² and B, and
// block positions computed at construction from the pattern they scatter.
#![allow(clippy::indexing_slicing)]
use crate::linalg::largest::largest_magnitude;
use crate::linalg::pool;

/// Nodes from which the two halves are eliminated and substituted in parallel (the arithmetic is the same
/// below it, one half after the other). Smaller rods run on one thread anyway ([`pool::worth_it`]); from
/// there the halves pay: driven line at n = 150, 0.273 → 0.222 ms per step against halves from 256 nodes.
const PARALLEL_NODES: usize = 128;

/// Smallest pivot accepted, relative to the largest entry of its block.
const PIVOT_FLOOR: f64 = 1e-13;

/// Degrees of freedom of a node in the unknowns' node-major numbering (6·node + k).
const NODE_SLOTS: usize = 6;

/// A B×B block, column-major: entry (row, column) at `[column][row]`.
type Block<const B: usize> = [[f64; B]; B];

/// A pivot of a diagonal block was zero, non-finite or below `PIVOT_FLOOR` of the block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SmallPivot;

/// Pattern values that land contiguously in one block: `length` values from pattern position `source` to
/// entry `entry` (B·column + row) of block `block`.
#[derive(Debug, Clone, Copy)]
struct Run {
    source: u32,
    block: u32,
    entry: u8,
    length: u8,
}

/// The block-tridiagonal LU in the block size its unknowns need: 6×6 where a node has rotations among its
/// unknowns, 3×3 where no node has (a line of cable elements).
pub enum NodeBlocks {
    Rotations(BlockTridiagonalLu<6>),
    Positions(BlockTridiagonalLu<3>),
}

impl NodeBlocks {
    /// As [`BlockTridiagonalLu::new`], in 3×3 blocks where every unknown is a position (k < 3).
    pub fn new(slots: &[usize], col_ptr: &[usize], row_idx: &[usize]) -> Option<Self> {
        if BlockTridiagonalLu::<3>::fits(slots) {
            BlockTridiagonalLu::new(slots, col_ptr, row_idx).map(NodeBlocks::Positions)
        } else {
            BlockTridiagonalLu::new(slots, col_ptr, row_idx).map(NodeBlocks::Rotations)
        }
    }

    /// Factorises the matrix with `values` in pattern order.
    pub fn factorise(&mut self, values: &[f64]) -> Result<(), SmallPivot> {
        match self {
            NodeBlocks::Rotations(lu) => lu.factorise(values),
            NodeBlocks::Positions(lu) => lu.factorise(values),
        }
    }

    /// Solves A x = b in place (b → x, unknowns only) with the factors.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        match self {
            NodeBlocks::Rotations(lu) => lu.solve_in_place(rhs),
            NodeBlocks::Positions(lu) => lu.solve_in_place(rhs),
        }
    }
}

/// The LU factors of a block-tridiagonal matrix of B×B blocks (module docs).
pub struct BlockTridiagonalLu<const B: usize> {
    nodes: usize,
    /// Node-major position (6·node + k, k < B) of each unknown.
    slots: Vec<usize>,
    /// Where the pattern's values go, column by column.
    runs: Vec<Run>,
    /// Block entries no value lands on (block, entry, value): the identity of prescribed DOFs, zeros.
    constants: Vec<(u32, u8, f64)>,
    /// Blocks ordered [D | L | U], each by node: D_i, then the LU factors of S_i, T_i or M in place (unit
    /// lower triangle below the diagonal); L_i = A_i,i−1, then Y_i = T_i⁻¹L_i (row-major) below the middle;
    /// U_i = A_i,i+1, then X_i = S_i⁻¹U_i (row-major) above it.
    blocks: Vec<Block<B>>,
    /// Row interchanged with row k at step k of block i's LU.
    pivots: Vec<[u8; B]>,
    /// The padded right-hand side of a solve, node by node.
    work: Vec<[f64; B]>,
}

impl<const B: usize> BlockTridiagonalLu<B> {
    /// Whether every unknown's DOF (slot 6·node + k) has k < B, so that its node's unknowns fit a B×B block.
    pub fn fits(slots: &[usize]) -> bool {
        slots.iter().all(|&slot| slot % NODE_SLOTS < B)
    }

    /// For a matrix whose unknown i sits at node-major position `slots[i]` (6·node + k, increasing, k < B),
    /// with compressed-column pattern (`col_ptr`, `row_idx`) of sorted rows: `None` unless every entry couples
    /// a node to itself or to a neighbour.
    pub fn new(slots: &[usize], col_ptr: &[usize], row_idx: &[usize]) -> Option<Self> {
        let nodes = slots.last().map_or(0, |&last| last / NODE_SLOTS + 1);
        if nodes == 0
            || row_idx.len() > u32::MAX as usize
            || 3 * nodes > u32::MAX as usize
            || !Self::fits(slots)
        {
            return None;
        }
        let mut runs: Vec<Run> = Vec::new();
        let mut covered = vec![[[false; B]; B]; 3 * nodes];
        for (col, window) in col_ptr.windows(2).enumerate() {
            let (c, column_node) = (slots[col] % NODE_SLOTS, slots[col] / NODE_SLOTS);
            for (position, &row) in (window[0]..window[1]).zip(&row_idx[window[0]..window[1]]) {
                let (r, row_node) = (slots[row] % NODE_SLOTS, slots[row] / NODE_SLOTS);
                // Block (row_node, column_node) is D, L (one below) or U (one above), kept at row_node.
                let kind = match row_node as isize - column_node as isize {
                    0 => 0,
                    1 => 1,
                    -1 => 2,
                    _ => return None,
                };
                let (block, entry) = (kind * nodes + row_node, B * c + r);
                covered[block][c][r] = true;
                match runs.last_mut() {
                    Some(run)
                        if run.block as usize == block
                            && (run.entry + run.length) as usize == entry
                            && (run.source as usize + run.length as usize) == position =>
                    {
                        run.length += 1;
                    }
                    _ => runs.push(Run {
                        source: position as u32,
                        block: block as u32,
                        entry: entry as u8,
                        length: 1,
                    }),
                }
            }
        }
        let mut unknown = vec![false; NODE_SLOTS * nodes];
        slots.iter().for_each(|&s| unknown[s] = true);
        let mut constants = Vec::new();
        for (block, columns) in covered.iter().enumerate() {
            for (c, rows) in columns.iter().enumerate() {
                for (r, _) in rows.iter().enumerate().filter(|(_, &covered)| !covered) {
                    let padded_diagonal =
                        block < nodes && r == c && !unknown[NODE_SLOTS * block + r];
                    let value = if padded_diagonal { 1.0 } else { 0.0 };
                    constants.push((block as u32, (B * c + r) as u8, value));
                }
            }
        }
        Some(BlockTridiagonalLu {
            nodes,
            slots: slots.to_vec(),
            runs,
            constants,
            blocks: vec![[[0.0; B]; B]; 3 * nodes],
            pivots: vec![[0; B]; nodes],
            work: vec![[0.0; B]; nodes],
        })
    }

    /// Factorises the matrix with `values` in pattern order.
    pub fn factorise(&mut self, values: &[f64]) -> Result<(), SmallPivot> {
        let n = self.nodes;
        for run in &self.runs {
            let (source, entry) = (run.source as usize, run.entry as usize);
            let length = run.length as usize;
            let block = self.blocks[run.block as usize].as_flattened_mut();
            // A block's whole column (the common run) as a fixed-size copy: a call to memcpy per run of B
            // values cost more than the copy.
            match (
                <&mut [f64; B]>::try_from(&mut block[entry..entry + length]),
                <&[f64; B]>::try_from(&values[source..source + length]),
            ) {
                (Ok(column), Ok(column_values)) => *column = *column_values,
                _ => block[entry..entry + length].copy_from_slice(&values[source..source + length]),
            }
        }
        for &(block, entry, value) in &self.constants {
            let entry = entry as usize;
            self.blocks[block as usize][entry / B][entry % B] = value;
        }
        let middle = n / 2;
        let (diagonal, rest) = self.blocks.split_at_mut(n);
        let (lower, upper) = rest.split_at_mut(n);
        let (diagonal_top, diagonal_rest) = diagonal.split_at_mut(middle);
        let (diagonal_middle, diagonal_bottom) = diagonal_rest.split_at_mut(1);
        let (lower_top, lower_rest) = lower.split_at_mut(middle);
        let (lower_middle, lower_bottom) = lower_rest.split_at_mut(1);
        let (upper_top, upper_rest) = upper.split_at_mut(middle);
        let (upper_middle, upper_bottom) = upper_rest.split_at_mut(1);
        let (pivots_top, pivots_rest) = self.pivots.split_at_mut(middle);
        let (pivots_middle, pivots_bottom) = pivots_rest.split_at_mut(1);
        let (top, bottom) = pool::join(
            n >= PARALLEL_NODES,
            || eliminate(diagonal_top, lower_top, upper_top, pivots_top, Sweep::Down),
            || {
                eliminate(
                    diagonal_bottom,
                    upper_bottom,
                    lower_bottom,
                    pivots_bottom,
                    Sweep::Up,
                )
            },
        );
        top?;
        bottom?;
        // M = D_m − L_m X_m−1 − U_m Y_m+1.
        let block = &mut diagonal_middle[0];
        if let Some(x) = upper_top.last() {
            subtract_product(block, &lower_middle[0], x);
        }
        if let Some(y) = lower_bottom.first() {
            subtract_product(block, &upper_middle[0], y);
        }
        factorise_block(block, &mut pivots_middle[0])
    }

    /// Solves A x = b in place (b → x, unknowns only) with the factors.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let n = self.nodes;
        self.work.iter_mut().for_each(|w| *w = [0.0; B]);
        for (&slot, &value) in self.slots.iter().zip(rhs.iter()) {
            self.work[slot / NODE_SLOTS][slot % NODE_SLOTS] = value;
        }
        let middle = n / 2;
        let (diagonal, rest) = self.blocks.split_at(n);
        let (lower, upper) = rest.split_at(n);
        let (work_top, work_rest) = self.work.split_at_mut(middle);
        let (work_middle, work_bottom) = work_rest.split_at_mut(1);
        let (pivots_top, pivots_rest) = self.pivots.split_at(middle);
        let (pivots_middle, pivots_bottom) = pivots_rest.split_at(1);
        let bottom = middle + 1..n;
        let parallel = n >= PARALLEL_NODES;
        pool::join(
            parallel,
            || {
                let top = ..middle;
                substitute(
                    &diagonal[top],
                    &lower[top],
                    pivots_top,
                    work_top,
                    Sweep::Down,
                );
            },
            || {
                let (diagonal, upper) = (&diagonal[bottom.clone()], &upper[bottom.clone()]);
                substitute(diagonal, upper, pivots_bottom, work_bottom, Sweep::Up);
            },
        );
        let x = &mut work_middle[0];
        if let Some(y) = work_top.last() {
            subtract_product_vector(x, &lower[middle], y);
        }
        if let Some(z) = work_bottom.first() {
            subtract_product_vector(x, &upper[middle], z);
        }
        solve_block(&diagonal[middle], &pivots_middle[0], x);
        let x = *x;
        pool::join(
            parallel,
            || back_substitute(&upper[..middle], work_top, &x, Sweep::Down),
            || back_substitute(&lower[bottom.clone()], work_bottom, &x, Sweep::Up),
        );
        for (&slot, value) in self.slots.iter().zip(rhs.iter_mut()) {
            *value = self.work[slot / NODE_SLOTS][slot % NODE_SLOTS];
        }
    }
}

/// Which way an elimination runs over its half: from the first node down to the middle (its blocks in
/// order), or from the last node up to it (in reverse).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Sweep {
    Down,
    Up,
}

impl Sweep {
    /// The half's nodes in elimination order, as indices into its slices of `count`.
    fn order(self, count: usize) -> impl Iterator<Item = (usize, Option<usize>)> {
        (0..count).map(move |k| match self {
            Sweep::Down => (k, k.checked_sub(1)),
            Sweep::Up => (count - 1 - k, (k > 0).then_some(count - k)),
        })
    }
}

/// Eliminates one half: for each node i in order, with `behind` its coupling to the node eliminated before
/// it and `ahead` its coupling towards the middle, S_i = D_i − behind_i Z_prev, then Z_i = S_i⁻¹ ahead_i
/// (row-major, in place of `ahead`).
fn eliminate<const B: usize>(
    diagonal: &mut [Block<B>],
    behind: &mut [Block<B>],
    ahead: &mut [Block<B>],
    pivots: &mut [[u8; B]],
    sweep: Sweep,
) -> Result<(), SmallPivot> {
    for (i, previous) in sweep.order(diagonal.len()) {
        if let Some(p) = previous {
            subtract_product(&mut diagonal[i], &behind[i], &ahead[p]);
        }
        factorise_block(&mut diagonal[i], &mut pivots[i])?;
        transpose(&mut ahead[i]);
        solve_block_rows(&diagonal[i], &pivots[i], &mut ahead[i]);
    }
    Ok(())
}

/// Forward substitution over one half: w_i ← S_i⁻¹(w_i − behind_i w_prev).
fn substitute<const B: usize>(
    diagonal: &[Block<B>],
    behind: &[Block<B>],
    pivots: &[[u8; B]],
    work: &mut [[f64; B]],
    sweep: Sweep,
) {
    for (i, previous) in sweep.order(diagonal.len()) {
        if let Some(p) = previous {
            let before = work[p];
            subtract_product_vector(&mut work[i], &behind[i], &before);
        }
        solve_block(&diagonal[i], &pivots[i], &mut work[i]);
    }
}

/// Back substitution over one half, outwards from the middle's solution x_m: x_i = w_i − Z_i x_next.
fn back_substitute<const B: usize>(
    solved: &[Block<B>],
    work: &mut [[f64; B]],
    middle: &[f64; B],
    sweep: Sweep,
) {
    let count = work.len();
    for k in 0..count {
        let (i, next) = match sweep {
            Sweep::Down => (count - 1 - k, count - k),
            Sweep::Up => (k, k.wrapping_sub(1)),
        };
        let toward = if next < count { work[next] } else { *middle };
        subtract_row_major_product_vector(&mut work[i], &solved[i], &toward);
    }
}

/// LU with partial pivoting of a B×B block in place: P S = L U with unit L stored below the diagonal and
/// the reciprocals of U's diagonal on it (whole rows interchanged, as LAPACK's getrf).
fn factorise_block<const B: usize>(
    a: &mut Block<B>,
    pivots: &mut [u8; B],
) -> Result<(), SmallPivot> {
    // The column steps below are written out for the two block sizes there are.
    const { assert!(B == 3 || B == 6) };
    // A NaN is skipped by the largest entry but fails the pivot test (or, off the pivots, reaches the solution).
    let floor = PIVOT_FLOOR * largest_magnitude(a.as_flattened());
    // Column by column in place, one step per column with its bounds known at compile time (unrolled, free
    // of bounds checks), and no copy in or out.
    pivots[0] = eliminate_column::<0, B>(a, floor)?;
    pivots[1] = eliminate_column::<1, B>(a, floor)?;
    pivots[2] = eliminate_column::<2, B>(a, floor)?;
    if B > 3 {
        pivots[3] = eliminate_column::<3, B>(a, floor)?;
        pivots[4] = eliminate_column::<4, B>(a, floor)?;
        pivots[5] = eliminate_column::<5, B>(a, floor)?;
    }
    Ok(())
}

/// Step `K` of [`factorise_block`]: picks the largest pivot of column `K` at or below the diagonal (it must
/// exceed `floor`), interchanges its row with row `K` in every column, stores the multipliers below the
/// pivot and the pivot's reciprocal on it, and updates the columns to the right. Returns the pivot's row.
#[inline(always)]
fn eliminate_column<const K: usize, const B: usize>(
    a: &mut Block<B>,
    floor: f64,
) -> Result<u8, SmallPivot> {
    let mut pivot = K;
    let mut largest = a[K][K].abs();
    for (row, value) in a[K].iter().enumerate().skip(K + 1) {
        if value.abs() > largest {
            largest = value.abs();
            pivot = row;
        }
    }
    if !(largest > floor && largest.is_finite()) {
        return Err(SmallPivot);
    }
    if pivot != K {
        for column in a.iter_mut() {
            column.swap(K, pivot);
        }
    }
    let inverse = 1.0 / a[K][K];
    a[K][K] = inverse;
    a[K].iter_mut()
        .skip(K + 1)
        .for_each(|multiplier| *multiplier *= inverse);
    let multipliers = a[K];
    for column in a.iter_mut().skip(K + 1) {
        let top = column[K];
        for row in K + 1..B {
            column[row] -= multipliers[row] * top;
        }
    }
    Ok(pivot as u8)
}

/// Solves S x = b in place with the factors of [`factorise_block`].
fn solve_block<const B: usize>(factors: &Block<B>, pivots: &[u8; B], x: &mut [f64; B]) {
    for (k, &pivot) in pivots.iter().enumerate() {
        x.swap(k, pivot as usize);
    }
    for k in 0..B {
        let value = x[k];
        for i in k + 1..B {
            x[i] -= factors[k][i] * value;
        }
    }
    for k in (0..B).rev() {
        x[k] *= factors[k][k];
        let value = x[k];
        for i in 0..k {
            x[i] -= factors[k][i] * value;
        }
    }
}

/// Transposes a block in place (column-major ↔ row-major).
#[allow(clippy::needless_range_loop)] // entries (i, j) and (j, i) of one array
fn transpose<const B: usize>(b: &mut Block<B>) {
    for j in 0..B {
        for i in j + 1..B {
            let below = b[j][i];
            b[j][i] = b[i][j];
            b[i][j] = below;
        }
    }
}

/// B ← S⁻¹B for B row-major (row r at `[r]`), with the factors of [`factorise_block`]: the row operations of
/// the substitutions act on whole rows.
fn solve_block_rows<const B: usize>(factors: &Block<B>, pivots: &[u8; B], rows: &mut Block<B>) {
    for (k, &pivot) in pivots.iter().enumerate() {
        rows.swap(k, pivot as usize);
    }
    for k in 0..B {
        let pivot_row = rows[k];
        for i in k + 1..B {
            let multiplier = factors[k][i];
            for (entry, top) in rows[i].iter_mut().zip(&pivot_row) {
                *entry -= multiplier * top;
            }
        }
    }
    for k in (0..B).rev() {
        let reciprocal = factors[k][k];
        rows[k].iter_mut().for_each(|entry| *entry *= reciprocal);
        let pivot_row = rows[k];
        for i in 0..k {
            let multiplier = factors[k][i];
            for (entry, top) in rows[i].iter_mut().zip(&pivot_row) {
                *entry -= multiplier * top;
            }
        }
    }
}

/// S ← S − L X with X row-major.
fn subtract_product<const B: usize>(s: &mut Block<B>, l: &Block<B>, x: &Block<B>) {
    for (j, column) in s.iter_mut().enumerate() {
        for (k, l_column) in l.iter().enumerate() {
            let factor = x[k][j];
            for (entry, l_entry) in column.iter_mut().zip(l_column) {
                *entry -= l_entry * factor;
            }
        }
    }
}

/// y ← y − X v with X row-major.
fn subtract_row_major_product_vector<const B: usize>(y: &mut [f64; B], x: &Block<B>, v: &[f64; B]) {
    for (entry, row) in y.iter_mut().zip(x) {
        *entry -= row.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
    }
}

/// y ← y − L v.
fn subtract_product_vector<const B: usize>(y: &mut [f64; B], l: &Block<B>, v: &[f64; B]) {
    for (column, &factor) in l.iter().zip(v) {
        for (entry, l_entry) in y.iter_mut().zip(column) {
            *entry -= l_entry * factor;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::test_support::solve_error;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random block-tridiagonal system over `nodes` nodes of `per_node` DOFs each (6·node + k, k <
    /// `per_node`) with the DOFs in `fixed` removed: its unknowns' slots, compressed-column pattern and values,
    /// and the dense matrix (row-major over the unknowns).
    #[allow(clippy::type_complexity)]
    fn random_system(
        nodes: usize,
        per_node: usize,
        fixed: &[usize],
        seed: u64,
    ) -> (Vec<usize>, Vec<usize>, Vec<usize>, Vec<f64>, Vec<f64>) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let slots: Vec<usize> = (0..6 * nodes)
            .filter(|s| s % 6 < per_node && !fixed.contains(s))
            .collect();
        let n = slots.len();
        let mut dense = vec![0.0; n * n];
        let (mut col_ptr, mut row_idx, mut values) = (vec![0], Vec::new(), Vec::new());
        for (j, &cj) in slots.iter().enumerate() {
            for (i, &ri) in slots.iter().enumerate() {
                if (ri / 6).abs_diff(cj / 6) <= 1 {
                    // Diagonal blocks dominant, but with small diagonal entries inside them (pivoting needed).
                    let value = match (ri / 6 == cj / 6, ri == cj) {
                        (_, true) => 1e-3 * rng.random::<f64>(),
                        (true, false) => 4.0 * (rng.random::<f64>() - 0.5),
                        _ => 0.2 * (rng.random::<f64>() - 0.5),
                    };
                    dense[i * n + j] = value;
                    row_idx.push(i);
                    values.push(value);
                }
            }
            col_ptr.push(row_idx.len());
        }
        (slots, col_ptr, row_idx, values, dense)
    }

    /// `lu` factorised with `values` and its solution's error against the dense matrix of `n` unknowns, on the
    /// pool, so that the halves run in parallel where there are enough nodes.
    fn factorised_solve_error(lu: &mut NodeBlocks, values: &[f64], dense: &[f64], n: usize) -> f64 {
        pool::run(true, || {
            lu.factorise(values).expect("regular");
            solve_error(dense, n, |b| lu.solve_in_place(b))
        })
    }

    #[test]
    fn solves_block_tridiagonal_systems_with_prescribed_dofs() {
        for (nodes, fixed, seed) in [
            (1, vec![], 1),
            (2, vec![0, 1, 2], 2),
            (3, vec![15, 16, 17], 6),
            (40, vec![0, 1, 2, 237, 238, 239], 3),
            (25, vec![3, 4, 5, 60], 4),
            (PARALLEL_NODES + 3, vec![0, 1, 2, 5], 7),
        ] {
            let (slots, col_ptr, row_idx, values, dense) = random_system(nodes, 6, &fixed, seed);
            let n = slots.len();
            let mut lu = NodeBlocks::new(&slots, &col_ptr, &row_idx).expect("tridiagonal");
            assert!(matches!(lu, NodeBlocks::Rotations(_)));
            let error = factorised_solve_error(&mut lu, &values, &dense, n);
            assert!(error < 1e-10, "{nodes} nodes: error {error:e}");
        }
    }

    #[test]
    fn solves_systems_of_position_nodes_in_three_by_three_blocks() {
        for (nodes, fixed, seed) in [
            (1, vec![], 11),
            (2, vec![0, 1, 2], 12),
            (40, vec![0, 1, 2, 236], 13),
            (PARALLEL_NODES + 3, vec![0, 1, 2, 7], 14),
        ] {
            let (slots, col_ptr, row_idx, values, dense) = random_system(nodes, 3, &fixed, seed);
            let n = slots.len();
            let mut lu = NodeBlocks::new(&slots, &col_ptr, &row_idx).expect("tridiagonal");
            assert!(matches!(lu, NodeBlocks::Positions(_)));
            let error = factorised_solve_error(&mut lu, &values, &dense, n);
            assert!(error < 1e-10, "{nodes} nodes: error {error:e}");
            // The same system in 6×6 blocks (the rotations padded with the identity): the same solution.
            let mut six =
                BlockTridiagonalLu::<6>::new(&slots, &col_ptr, &row_idx).expect("tridiagonal");
            six.factorise(&values).expect("regular");
            let error = solve_error(&dense, n, |b| six.solve_in_place(b));
            assert!(
                error < 1e-10,
                "{nodes} nodes in 6×6 blocks: error {error:e}"
            );
        }
        // A rotation among the unknowns does not fit 3×3 blocks.
        let (slots, col_ptr, row_idx, _, _) = random_system(3, 4, &[], 15);
        assert!(BlockTridiagonalLu::<3>::new(&slots, &col_ptr, &row_idx).is_none());
    }

    #[test]
    fn wider_patterns_and_singular_blocks_are_refused() {
        let (slots, col_ptr, row_idx, mut values, _) = random_system(6, 6, &[], 5);
        // A coupling between nodes 0 and 2.
        let mut wide_rows = row_idx.clone();
        wide_rows[0] = 12;
        assert!(NodeBlocks::new(&slots, &col_ptr, &wide_rows).is_none());
        let mut lu = NodeBlocks::new(&slots, &col_ptr, &row_idx).expect("tridiagonal");
        // Column 7 (node 1) all zero: S_1 is singular.
        values[col_ptr[7]..col_ptr[8]]
            .iter_mut()
            .for_each(|v| *v = 0.0);
        assert_eq!(lu.factorise(&values), Err(SmallPivot));
        values[0] = f64::NAN;
        assert_eq!(lu.factorise(&values), Err(SmallPivot));
    }
}
