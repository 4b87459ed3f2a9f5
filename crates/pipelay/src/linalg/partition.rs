//! A pattern's unknowns split in two groups for block elimination, and the copies of each group's values out
//! of the whole pattern's.
// Indexing cannot go out of bounds here: positions and indices of the pattern being split.
#![allow(clippy::indexing_slicing)]

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
