//! The free directions of the relative displacements under one set of
//! relations ([`Freedom`]): the lone pairs' free axes, the junctions'
//! null-space blocks and the lone slipping pairs' friction rows.

use super::junction::Tied;

/// The free directions of the relative displacements r under one set of
/// relations: `r = r0 + sum_a y_a col_a`. A lone pair's free axis is a
/// column of one entry; a junction's free directions are the columns of its
/// null space (see [`super::junction`]).
pub struct Freedom {
    /// r where every y is 0: the tied axes' targets, the junctions' r0.
    pub r0: Vec<f64>,
    /// The columns, orthonormal, each over r.
    pub cols: Vec<Vec<(usize, f64)>>,
    /// The column of each lone pair's free r (NONE where tied or in a junction).
    pub pos: Vec<usize>,
    pub junctions: Vec<JunctionBlock>,
    /// The lone slipping pairs' free tangential rows.
    pub slips: Vec<SlipRow>,
    /// What the states add to the right-hand side on the rows of r: the
    /// water in the joints pushing the pairs' sides apart (empty when dry).
    pub pushed: Vec<f64>,
    /// Whether the rows' springs are symmetric (not where a deforming
    /// joint slips: its friction follows its normal spring).
    pub symmetric: bool,
    /// Every pair deforms ([`super::Relation::elastic`]): no axis is tied
    /// in any solve, so the free directions are the same at every one and
    /// only the springs on them change.
    pub deforming: bool,
}

impl Freedom {
    /// Adds [`Freedom::pushed`] to a right-hand side over r.
    pub fn push(&self, b_r: &mut [f64]) {
        for (b, p) in b_r.iter_mut().zip(&self.pushed) {
            *b += p;
        }
    }
}

/// A junction's part of a solve: its columns, and what its slipping pairs
/// add on them (`Z^T k Z`, `Z^T (f + k r0)`; and the lift of their
/// implicit pressures, when they have them).
pub struct JunctionBlock {
    pub cols: std::ops::Range<usize>,
    pub kz: nalgebra::DMatrix<f64>,
    pub fz: nalgebra::DVector<f64>,
    /// The junction's relative displacements (indices into r).
    pub r: Vec<usize>,
    pub lift: Option<Lift>,
    pub tied: Tied,
}

/// What a junction's slipping pairs' implicit pressures add to its rows
/// ([`super::junction::pressure`]): `on_w` times `W r - c` on the junction's r,
/// `on_y` times its own free columns' y (`L` and `L k Z` there; the
/// constant part is in [`JunctionBlock::fz`]).
pub struct Lift {
    pub on_w: nalgebra::DMatrix<f64>,
    pub on_y: nalgebra::DMatrix<f64>,
}

impl JunctionBlock {
    /// The lift's part of the block's rows (one per column) at `w` (`W r -
    /// c`, by r index) and `y` (the free columns' coordinates); None
    /// without a lift.
    pub fn lifted(&self, w: impl Fn(usize) -> f64, y: &[f64]) -> Option<nalgebra::DVector<f64>> {
        let lift = self.lift.as_ref()?;
        let wj = nalgebra::DVector::from_iterator(self.r.len(), self.r.iter().map(|&i| w(i)));
        let yj = nalgebra::DVector::from_column_slice(&y[self.cols.clone()]);
        Some(&lift.on_w * wj + &lift.on_y * yj)
    }
}

/// A lone slipping pair's free tangential row (r index), whose equation is
/// the friction law's (see [`super::relation::Relation`]):
/// `(W r - c)_row + force + coupling (W r - c)_normal + sum_c spring_c r_c = 0`.
pub struct SlipRow {
    pub row: usize,
    pub normal: Option<usize>,
    pub coupling: f64,
    pub springs: Vec<(usize, f64)>,
    pub force: f64,
}
