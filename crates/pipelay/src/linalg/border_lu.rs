//! Block elimination of a bordered system. A vessel's rollers couple its node to every node within their
//! reach. A sparse LU analysed on AᵀA (as faer's is) sees those few dense rows as a dense block and fills
//! hundreds of columns. Given the border unknowns (the vessel node's six, and an articulated stinger's
//! hinge angles, whose sections carry rollers too), the system
//! [A B; C D][x; z] = [r; s] is solved by block elimination instead: A (the rod with the border held) by the
//! interior's own factorisation, X = A⁻¹B once per factorisation, the Schur complement D − C X (at most
//! [`BORDER_MAX`] square) densely, then x = A⁻¹r − X z. Cost stays linear in the unknowns.
// Indexing cannot go out of bounds here: Row and column indices of the pattern the assembler built.
#![allow(clippy::indexing_slicing)]
use crate::linalg::factorisation::{Factorisation, Singular};
use crate::linalg::partition::Partition;
use crate::linalg::pattern::Pattern;

/// Most border unknowns: one node's and an articulated stinger's hinges.
pub const BORDER_MAX: usize = 6 + crate::vessel::articulation::MAX_SECTIONS;

/// The block elimination of a bordered system around the factorisation `I` of its interior (module docs).
pub struct BorderLu<I> {
    /// Border unknowns.
    unknowns: Vec<usize>,
    /// The interior (A) and the border (D) of the whole pattern (each unknown's index in its own), and where
    /// B and C go.
    partition: Partition,
    corner_values: Vec<f64>,
    interior: I,
    interior_values: Vec<f64>,
    /// B and X = A⁻¹B, column by column (interior × border), and C row by row (border × interior).
    right: Vec<Vec<f64>>,
    solved: Vec<Vec<f64>>,
    below: Vec<Vec<f64>>,
    corner: nalgebra::DMatrix<f64>,
    /// LU of the Schur complement D − C X.
    schur: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    reduced: nalgebra::DVector<f64>,
    work: Vec<f64>,
}

impl<I: Factorisation> BorderLu<I> {
    /// The system of unknowns at node-major positions `slots` (6·node + k, increasing), of pattern `pattern`,
    /// whose unknowns `border` (sorted, at most [`BORDER_MAX`]) couple densely to the rest; the interior is
    /// factorised by what `interior` makes of its unknowns' slots and pattern.
    pub fn new(
        slots: &[usize],
        pattern: &Pattern,
        border: &[usize],
        interior: impl FnOnce(&[usize], Pattern) -> I,
    ) -> Self {
        let (col_ptr, row_idx) = (&pattern.col_ptr, &pattern.row_idx);
        let mut partition = Partition::new(col_ptr, row_idx, |i| border.contains(&i));
        let interior_slots: Vec<usize> = partition.group(false).map(|(i, _)| slots[i]).collect();
        let count = interior_slots.len();
        // The interior's pattern moves to its LU; the corner's stays for the copy into the 6×6 block.
        let (inner_ptr, inner_rows) = std::mem::take(&mut partition.patterns[0]);
        BorderLu {
            unknowns: border.to_vec(),
            interior_values: vec![0.0; inner_rows.len()],
            interior: interior(&interior_slots, Pattern::new(inner_ptr, inner_rows)),
            corner_values: vec![0.0; partition.patterns[1].1.len()],
            partition,
            right: vec![vec![0.0; count]; border.len()],
            solved: vec![vec![0.0; count]; border.len()],
            below: vec![vec![0.0; count]; border.len()],
            corner: nalgebra::DMatrix::zeros(border.len(), border.len()),
            reduced: nalgebra::DVector::zeros(border.len()),
            schur: None,
            work: vec![0.0; count],
        }
    }
}

impl<I: Factorisation> Factorisation for BorderLu<I> {
    fn factorise(&mut self, values: &[f64]) -> Result<(), Singular> {
        let m = self.unknowns.len();
        for column in self.right.iter_mut().chain(self.below.iter_mut()) {
            column.iter_mut().for_each(|v| *v = 0.0);
        }
        self.corner.fill(0.0);
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
        let mut schur = self.corner.clone();
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
        let finite = schur.iter().all(|v| v.is_finite());
        let lu = schur.lu();
        if !lu.is_invertible() || !finite {
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
        let reduced = &mut self.reduced;
        for r in 0..m {
            let product: f64 = self.below[r]
                .iter()
                .zip(&self.work)
                .map(|(a, b)| a * b)
                .sum();
            reduced[r] = rhs[self.unknowns[r]] - product;
        }
        let z = schur.solve(reduced).ok_or(Singular)?;
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
