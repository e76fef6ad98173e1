//! The share of a junction's tied forces near the last solve, where its
//! loops carried part of them: the derivative of [`Split::forces`] with the
//! limits the share met held as equalities.
//!
//! Where the least-norm share of the force `g` the tied rows carry breaks
//! a limit (a stuck pair's Coulomb cone, a tied normal's tension), the
//! share is the least-norm one within the limits, `λ = D (ν0 + N s)` with s
//! the least-norm point of the cuts (`ν0 = pinv g`). With the cuts the
//! share meets held (their normals `a` at the share: the cone's tangent
//! plane), `G s = h - B g` (`G = A D N`, `B = A D pinv`), and
//!
//! ```text
//! λ ≈ J g + λ0,   J = D (pinv - N G^+ B),   λ0 = λ - J g
//! ```
//!
//! A slipping pair's pressure `-λ_n` is then solved for with r through J
//! ([`super::pressure`]), as the least-norm share's is, instead of taken
//! from the last solve: with the states held, the friction of a junction's
//! slipping pairs whose pressure its loops share with a stuck pair at its
//! bound settled tenfold per contact iteration, or not at all, and the
//! contact iteration changed states on unsettled forces (the 34k-DOF
//! tunnel of docs/convergence.md cycled for 300 iterations).

use nalgebra::{DMatrix, DVector};

use super::row::Row;
use super::split::Split;
use crate::contact::system::relation::Limit;

/// A limit is met by a share within this fraction of its largest force
/// (the cuts keep the share 1e-9 inside them, to 1e-12).
const MET: f64 = 1e-8;

/// The share near the last solve of one set of tied rows: `λ ≈ j g + offset`.
#[derive(Clone, Debug)]
pub(super) struct Tangent {
    pub rows: Vec<Row>,
    pub j: DMatrix<f64>,
    pub offset: DVector<f64>,
    /// The least-norm share's ([`Tangent::plain`]).
    pub plain: bool,
}

impl Tangent {
    /// The least-norm share's (no limit met): its rows of `split`'s pinv,
    /// offset by the loops' part of `prior`.
    pub(super) fn plain(split: &Split, prior: &DVector<f64>) -> Tangent {
        let n_r = split.pinv.ncols();
        let j = DMatrix::<f64>::from_fn(split.rows.len(), n_r, |i, c| split.d[i] * split.pinv[(i, c)]);
        let kept = split.loops_of(prior);
        let offset = DVector::from_fn(split.rows.len(), |i, _| split.d[i] * kept[i]);
        Tangent { rows: split.rows.clone(), j, offset, plain: true }
    }

    /// The share's derivative at `g`, where `split` shared it as `lambda`
    /// within `limits`; None where no limit is met (the least-norm share,
    /// whose pressures [`super::pressure::Pressure`] takes by itself).
    pub(super) fn at(split: &Split, g: &DVector<f64>, lambda: &DVector<f64>, limits: &[Limit]) -> Option<Tangent> {
        let cuts = split.violations(lambda, limits, -MET);
        if cuts.is_empty() || split.null.ncols() == 0 {
            return None;
        }
        let (n_null, n_r) = (split.null.ncols(), split.pinv.ncols());
        let mut gm = DMatrix::<f64>::zeros(cuts.len(), n_null);
        let mut bm = DMatrix::<f64>::zeros(cuts.len(), n_r);
        for (k, (a, _)) in cuts.iter().enumerate() {
            for &(i, c) in a {
                let w = c * split.d[i];
                let (gn, bp) = (split.null.row(i) * w, split.pinv.row(i) * w);
                let mut g_k = gm.row_mut(k);
                g_k += gn;
                let mut b_k = bm.row_mut(k);
                b_k += bp;
            }
        }
        let eps = 1e-10 * gm.amax().max(f64::MIN_POSITIVE);
        let gp = gm.pseudo_inverse(eps).ok()?;
        let inner = &split.pinv - &split.null * gp * bm;
        let j = DMatrix::<f64>::from_fn(split.rows.len(), n_r, |i, c| split.d[i] * inner[(i, c)]);
        let offset = lambda - &j * g;
        Some(Tangent { rows: split.rows.clone(), j, offset, plain: false })
    }
}
