//! How a junction's tied rows share the force they must carry: the
//! least-norm share and the loops' self-equilibrated forces, closed in on
//! the pairs' Coulomb cones where the least-norm share breaks them.

use nalgebra::{DMatrix, DVector};

use super::row::Row;
use crate::contact::system::least_distance::least_norm_point;
use crate::contact::system::relation::Limit;
use crate::fem::vec3::{length, to_one};

/// Singular values below this fraction of the largest are zero: the
/// redundant ties of a loop (the rows are unit vectors of the pairs' frames,
/// so independent ones are O(1)).
pub(super) const RANK_TOLERANCE: f64 = 1e-10;

/// How far inside the pairs' limits a junction's tied forces are chosen
/// when the least-norm ones break one (a fraction of the largest force),
/// how far past a cut counts as breaking it, and how many rounds of cuts
/// close in on the Coulomb cones (see `Split::forces`).
const MARGIN: f64 = 1e-9;
const CUT_TOL: f64 = 1e-12;
const CUT_ROUNDS: usize = 12;

/// How the tied `rows` share the force `g` they must carry
/// (over r): `C_T^T λ = g`. With `ν = λ / sqrt(A)` the least-norm share is
/// `ν0 = pinv(C_T^T D) g`, and every other share is `ν0 + N s` (N the null
/// space of `C_T^T D`: the loops' self-equilibrated forces).
#[derive(Clone, Debug)]
pub(super) struct Split {
    pub(super) rows: Vec<Row>,
    pub(super) d: Vec<f64>,
    pub(super) pinv: DMatrix<f64>,
    pub(super) null: DMatrix<f64>,
}

impl Split {
    /// The split of `rows`, whose rows of C over r are `c_rows`.
    pub(super) fn new(c_rows: &[Vec<f64>], rows: &[Row], areas: &[f64], n_r: usize) -> Split {
        let m_t = rows.len();
        let d: Vec<f64> = rows.iter().map(|&(j, _)| areas[j].max(f64::MIN_POSITIVE).sqrt()).collect();
        // (C_T^T D)^T = D C_T, padded to square: its U spans the range of
        // D C_T and, past the rank, the null space of C_T^T D
        let n = m_t.max(n_r);
        let dc = DMatrix::<f64>::from_fn(m_t, n, |i, c| if c < n_r { c_rows[i][c] * d[i] } else { 0.0 });
        // no rows, no r, or rows that do not decompose (not finite): no
        // share, every force a loop's
        let svd = (m_t > 0 && n_r > 0).then(|| crate::fem::bounded::svd(dc, true, true)).flatten();
        let Some(svd) = svd else {
            return Split { rows: rows.to_vec(), d, pinv: DMatrix::zeros(m_t, n_r), null: DMatrix::identity(m_t, m_t) };
        };
        let (u, v_t) = (svd.u.expect("U"), svd.v_t.expect("V^T"));
        let sv = &svd.singular_values;
        let smax = sv.iter().copied().fold(0.0, f64::max);
        let rank: Vec<usize> =
            (0..sv.len()).filter(|&i| sv[i] > RANK_TOLERANCE * smax.max(f64::MIN_POSITIVE)).collect();
        // pinv(C_T^T D) = pinv((D C_T)^T) = U S^-1 V^T restricted to r's columns
        let pinv =
            DMatrix::<f64>::from_fn(m_t, n_r, |i, c| rank.iter().map(|&k| u[(i, k)] * v_t[(k, c)] / sv[k]).sum());
        let free: Vec<usize> = (0..m_t).filter(|k| !rank.contains(k)).collect();
        let null = DMatrix::<f64>::from_fn(m_t, free.len(), |i, c| u[(i, free[c])]);
        Split { rows: rows.to_vec(), d, pinv, null }
    }

    /// The least-norm share of `g` about the loops' part of `prior`
    /// (what the rows carry in situ: [`Split::loops_of`]), whatever the limits.
    pub(super) fn plain(&self, g: &DVector<f64>, prior: &DVector<f64>) -> DVector<f64> {
        let kept = self.loops_of(prior);
        DVector::from_fn(self.rows.len(), |i, _| self.d[i] * ((self.pinv.row(i) * g)[0] + kept[i]))
    }

    /// The forces of the rows: the least-norm share of `g` (about the
    /// loops' part of `prior`, as [`Split::plain`]), or where that
    /// breaks a pair's limit (tension beyond its strength, shear beyond its
    /// Coulomb bound for a stuck pair), the least-norm share within every
    /// limit, when the loops leave one.
    pub(super) fn forces(&self, g: &DVector<f64>, limits: &[Limit], prior: &DVector<f64>) -> DVector<f64> {
        // the forces brought near 1 (exactly, by a power of two) first: the
        // tolerances of `least_norm_point` add forces to lengths, so that
        // they are the same in every unit of force
        let s = to_one(g.as_slice());
        if s != 1.0 {
            return self.forces(&(g * s), &scaled(limits, s), &(prior * s)) / s;
        }
        let nu0 = &self.pinv * g + self.loops_of(prior);
        let lambda = |s: &DVector<f64>| {
            DVector::from_fn(self.rows.len(), |i, _| self.d[i] * (nu0[i] + (self.null.row(i) * s)[0]))
        };
        // in s: a . D (nu0 + N s) <= b
        let row = |i: usize, c: f64| (self.null.row(i).transpose() * (c * self.d[i]), c * self.d[i] * nu0[i]);
        self.close_in(self.null.ncols(), &lambda, &row, limits)
    }

    /// The loops' part of the share `prior` (over the rows' ν = λ / sqrt(A)):
    /// `N Nᵀ D⁻¹ prior`, what the loops keep of it (zero where `prior` is
    /// empty or the rows have no loop).
    pub(super) fn loops_of(&self, prior: &DVector<f64>) -> DVector<f64> {
        if self.null.ncols() == 0 || prior.len() != self.rows.len() {
            return DVector::zeros(self.rows.len());
        }
        let nu = DVector::from_fn(self.rows.len(), |i, _| prior[i] / self.d[i]);
        &self.null * (self.null.transpose() * nu)
    }

    /// Whether the share `lambda` breaks a limit.
    pub(super) fn breaks(&self, lambda: &DVector<f64>, limits: &[Limit]) -> bool {
        !self.violations(lambda, limits, CUT_TOL).is_empty()
    }

    /// How far the share `lambda` is beyond its limits at most (of its
    /// largest force): 0 where it breaks none ([`Split::breaks`]).
    pub(super) fn beyond(&self, lambda: &DVector<f64>, limits: &[Limit]) -> f64 {
        let scale = lambda.amax().max(f64::MIN_POSITIVE);
        let cuts = self.violations(lambda, limits, CUT_TOL);
        cuts.iter().map(|(a, b)| a.iter().map(|&(i, c)| c * lambda[i]).sum::<f64>() - b).fold(0.0, f64::max) / scale
    }

    /// The share `plain + loops s` of least `|s|` within every limit, where
    /// `plain` breaks one and the columns of `loops` leave one; else
    /// `plain` (forces near 1, as [`Split::forces`] brings them).
    pub(super) fn within(&self, plain: &DVector<f64>, loops: &DMatrix<f64>, limits: &[Limit]) -> DVector<f64> {
        let s = to_one(plain.as_slice());
        if s != 1.0 {
            return self.within(&(plain * s), loops, &scaled(limits, s)) / s;
        }
        let lambda = |s: &DVector<f64>| plain + loops * s;
        let row = |i: usize, c: f64| (loops.row(i).transpose() * c, c * plain[i]);
        self.close_in(loops.ncols(), &lambda, &row, limits)
    }

    /// The share `lambda(s)` of least `|s|` (over `n` loop forces) within
    /// every limit, by cuts `a . lambda(s) <= b`, `row(i, a_i)` giving a
    /// cut's part over s and its constant of row i; `lambda(0)` where it
    /// is within them or none is.
    fn close_in(
        &self,
        n: usize,
        lambda: &dyn Fn(&DVector<f64>) -> DVector<f64>,
        row: &dyn Fn(usize, f64) -> (DVector<f64>, f64),
        limits: &[Limit],
    ) -> DVector<f64> {
        let zero = DVector::zeros(n);
        let plain = lambda(&zero);
        if n == 0 || self.violations(&plain, limits, CUT_TOL).is_empty() {
            return plain;
        }
        // cuts: a row combination of λ with its bound, `a . λ <= b`
        let mut cuts: Vec<(Vec<(usize, f64)>, f64)> = Vec::new();
        let mut s = zero;
        for _ in 0..CUT_ROUNDS {
            let lam = lambda(&s);
            let new = self.violations(&lam, limits, CUT_TOL);
            if new.is_empty() {
                return lam;
            }
            cuts.extend(new);
            let g_rows: Vec<DVector<f64>> =
                cuts.iter().map(|(a, _)| a.iter().fold(DVector::zeros(n), |acc, &(i, c)| acc + row(i, c).0)).collect();
            let h: Vec<f64> = cuts.iter().map(|(a, b)| b - a.iter().map(|&(i, c)| row(i, c).1).sum::<f64>()).collect();
            match least_norm_point(&g_rows, &h) {
                Some(x) => s = x,
                // no share within every limit: the loop cannot carry g so
                None => return plain,
            }
        }
        // the cuts close in on a cone's curved limit from outside: a share
        // that ends within half the margin of them is still inside every limit
        let lam = lambda(&s);
        if self.violations(&lam, limits, MARGIN / 2.0).is_empty() {
            lam
        } else {
            plain
        }
    }

    /// The limits `λ` breaks, as cuts: the tension of every tied normal,
    /// and the Coulomb bound of every stuck pair along its shear's
    /// direction (in 2D, both signs). The cuts stay a hair (1e-9 of the
    /// largest force) inside the limits: a share the loops can choose is
    /// chosen strictly within them, so that judging the pairs by it, with
    /// the law's own `>=`, does not find them on the limit and let go. A
    /// limit is broken when `λ` passes its cut by more than `slack` (of
    /// the largest force).
    pub(super) fn violations(&self, lam: &DVector<f64>, limits: &[Limit], slack: f64) -> Vec<(Vec<(usize, f64)>, f64)> {
        let scale = lam.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
        let (margin, tol) = (MARGIN * scale, slack * scale);
        let mut out = Vec::new();
        let mut j0 = 0;
        while j0 < self.rows.len() {
            let j = self.rows[j0].0;
            let at: Vec<usize> = (j0..self.rows.len()).take_while(|&i| self.rows[i].0 == j).collect();
            j0 += at.len();
            let lim = limits[j];
            let Some(&n) = at.iter().find(|&&i| self.rows[i].1[0] != 0.0) else { continue };
            if lam[n] > lim.tension - margin + tol {
                out.push((vec![(n, 1.0)], lim.tension - margin));
            }
            let t: Vec<usize> = at.iter().copied().filter(|&i| self.rows[i].1[0] == 0.0).collect();
            if t.is_empty() || !lim.cohesion.is_finite() {
                continue;
            }
            // |λ_T| <= c - f λ_n  as  d . λ_T + f λ_n <= c
            let lt = length(&t.iter().map(|&i| lam[i]).collect::<Vec<f64>>());
            let bound = lim.cohesion - lim.friction * lam[n] - margin;
            if lt > bound + tol {
                let c = lim.cohesion - margin;
                if t.len() == 1 {
                    let sign = lam[t[0]].signum();
                    out.push((vec![(t[0], sign), (n, lim.friction)], c));
                } else {
                    let mut a: Vec<(usize, f64)> = t.iter().map(|&i| (i, lam[i] / lt)).collect();
                    a.push((n, lim.friction));
                    out.push((a, c));
                }
            }
        }
        out
    }
}

/// The limits in forces `s` times larger.
fn scaled(limits: &[Limit], s: f64) -> Vec<Limit> {
    limits.iter().map(|l| Limit { tension: l.tension * s, cohesion: l.cohesion * s, friction: l.friction }).collect()
}
