//! LU of a rod's tangent whose nodes couple only to their neighbours: the block-tridiagonal LU of
//! [`crate::linalg::block_lu`] in fixed-size blocks (6×6, or 3×3 for a line of cable nodes), and where a
//! diagonal block would need pivoting across blocks, the band LU of [`crate::linalg::band_lu`] (allocated at
//! its first use) instead. A pattern that is not block tridiagonal goes to the [`GeneralLu`].
use crate::linalg::band_lu::BandLu;
use crate::linalg::block_lu::NodeBlocks;
use crate::linalg::factorisation::{Factorisation, Singular};
use crate::linalg::general_lu::GeneralLu;
use crate::linalg::pattern::Pattern;

/// The factorisation of a rod's tangent without wider coupling (module docs).
pub enum RodLu {
    /// Block tridiagonal, with the band LU for blocks that need pivoting.
    Block {
        pattern: Pattern,
        blocks: Box<NodeBlocks>,
        band: Option<BandLu>,
        /// Whether the last factorisation is the band LU's.
        banded: bool,
        factorised: bool,
    },
    General(GeneralLu),
}

impl RodLu {
    /// The tangent whose unknown i sits at node-major position `slots[i]` (6·node + k, increasing), of
    /// pattern `pattern`.
    pub fn new(slots: &[usize], pattern: Pattern) -> Self {
        Self::block(slots, pattern)
            .unwrap_or_else(|pattern| RodLu::General(GeneralLu::new(pattern)))
    }

    /// The block-tridiagonal LU of that tangent, or its pattern back where it is not block tridiagonal.
    pub fn block(slots: &[usize], pattern: Pattern) -> Result<Self, Pattern> {
        match NodeBlocks::new(slots, &pattern.col_ptr, &pattern.row_idx) {
            Some(blocks) => Ok(RodLu::Block {
                pattern,
                blocks: Box::new(blocks),
                band: None,
                banded: false,
                factorised: false,
            }),
            None => Err(pattern),
        }
    }

    /// The matrix's pattern.
    pub fn pattern(&self) -> &Pattern {
        match self {
            RodLu::Block { pattern, .. } => pattern,
            RodLu::General(lu) => lu.pattern(),
        }
    }

    /// Whether the factorisation is the block-tridiagonal one, whose cost is about an assembly's.
    pub fn is_block_tridiagonal(&self) -> bool {
        matches!(self, RodLu::Block { .. })
    }
}

impl Factorisation for RodLu {
    fn factorise(&mut self, values: &[f64]) -> Result<(), Singular> {
        match self {
            RodLu::Block {
                pattern,
                blocks,
                band,
                banded,
                factorised,
            } => {
                *banded = blocks.factorise(values).is_err();
                let ok = !*banded || {
                    let band = band.get_or_insert_with(|| {
                        let (lower, upper) = BandLu::bandwidths(&pattern.col_ptr, &pattern.row_idx);
                        BandLu::new(pattern.size(), lower, upper)
                    });
                    band.factorise(&pattern.col_ptr, &pattern.row_idx, values)
                        .is_ok()
                };
                *factorised = ok;
                if ok {
                    Ok(())
                } else {
                    Err(Singular)
                }
            }
            RodLu::General(lu) => lu.factorise(values),
        }
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), Singular> {
        match self {
            RodLu::Block {
                factorised: false, ..
            } => Err(Singular),
            RodLu::Block {
                band: Some(band),
                banded: true,
                ..
            } => {
                band.solve_in_place(rhs);
                Ok(())
            }
            RodLu::Block { blocks, .. } => {
                blocks.solve_in_place(rhs);
                Ok(())
            }
            RodLu::General(lu) => lu.solve_in_place(rhs),
        }
    }
}
