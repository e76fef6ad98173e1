//! The interface reduced to the pairs' relative displacements.
//!
//! The means are shared by the two sides whatever the states, so they are
//! eliminated once (K_mm is the bonded interface system, positive definite
//! whenever the model is held with every contact closed):
//!
//! ```text
//! K_mm = L L^T,   X = L^-1 K_mr,   W = K_rr - X^T X,   u = L^-1 b_m,   c = b_r - X^T u
//! W r - c = -λ                                   (the contact problem in r alone)
//! m = L^-T (u - X r)                             (the means, afterwards)
//! ```
//!
//! W is the stiffness of the relative displacements, every mean left free:
//! each state set then solves only the rows of its free relative
//! displacements, a system of 2 unknowns per slipping pair and 3 per open
//! one, instead of the whole interface. Forming W costs about two dense
//! factorisations of the interface, once; a solve of the contact iteration
//! then costs the factorisation of its free rows.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{solve_lower_triangular_in_place, solve_upper_triangular_in_place};
use faer::{Accum, Mat, MatMut};

use super::coords::Blocks;

/// The contact problem in relative displacements, and what recovers the means.
pub struct Reduced {
    /// `L` with `K_mm = L L^T`.
    l: Mat<f64>,
    /// `X = L^-1 K_mr`.
    x: Mat<f64>,
    /// `W = K_rr - X^T X`.
    pub w: Mat<f64>,
    /// `u = L^-1 b_m` and `c = b_r - X^T u`, per load case and for the
    /// prescribed values at ramp 1.
    u: Vec<Vec<f64>>,
    c: Vec<Vec<f64>>,
    u_fixed: Vec<f64>,
    c_fixed: Vec<f64>,
}

/// The bonded interface (every contact closed) is singular: some part is
/// held by nothing even with every contact stuck.
#[derive(Debug)]
pub struct NotHeld;

fn col(v: &[f64]) -> Mat<f64> {
    Mat::from_fn(v.len(), 1, |i, _| v[i])
}

impl Reduced {
    pub fn new(blocks: Blocks) -> Result<Reduced, NotHeld> {
        let par = faer::get_global_parallelism();
        let Blocks { k_mm, mut k_mr, mut k_rr, b_m, b_r, b_m_fixed, b_r_fixed } = blocks;
        let nm = k_mm.nrows();
        // K_mm = L L^T in place (its lower triangle becomes L): no second copy
        let mut l = k_mm;
        if nm > 0 {
            let mut buf = MemBuffer::new(cholesky_in_place_scratch::<f64>(nm, par, Default::default()));
            cholesky_in_place(l.as_mut(), Default::default(), par, MemStack::new(&mut buf), Default::default())
                .map_err(|_| NotHeld)?;
        }
        if nm > 0 {
            // (the strict upper triangle of `l` still holds K_mm: the
            // triangular solves read only the lower one)
            // X and W column block by column block in the machine's threads:
            // most of the flops of the interface set-up (2 nm^2 nr + nm nr^2
            // against nm^3 / 3 for the Cholesky)
            by_columns(k_mr.as_mut(), |cols, _| solve_lower_triangular_in_place(l.as_ref(), cols, par));
            let x = k_mr.as_ref();
            by_columns(k_rr.as_mut(), |cols, j0| {
                let n = cols.ncols();
                matmul(cols, Accum::Add, x.transpose(), x.subcols(j0, n), -1.0, par)
            });
        }
        let (x, w) = (k_mr, k_rr);
        let reduce = |bm: &[f64], br: &[f64]| -> (Vec<f64>, Vec<f64>) {
            let mut u = col(bm);
            if nm > 0 {
                solve_lower_triangular_in_place(l.as_ref(), u.as_mut(), par);
            }
            let mut c = col(br);
            if nm > 0 {
                matmul(c.as_mut(), Accum::Add, x.transpose(), u.as_ref(), -1.0, par);
            }
            (u.col(0).iter().copied().collect(), c.col(0).iter().copied().collect())
        };
        let (u, c): (Vec<Vec<f64>>, Vec<Vec<f64>>) = b_m.iter().zip(&b_r).map(|(bm, br)| reduce(bm, br)).unzip();
        let (u_fixed, c_fixed) = reduce(&b_m_fixed, &b_r_fixed);
        Ok(Reduced { l, x, w, u, c, u_fixed, c_fixed })
    }

    /// `c` under the load factors `lambda` (case 0 also scales prescribed values).
    pub fn c_at(&self, lambda: &[f64]) -> Vec<f64> {
        combine(&self.c, &self.c_fixed, lambda)
    }

    /// `W r - c`: minus the contact forces.
    pub fn residual(&self, r: &[f64], c: &[f64]) -> Vec<f64> {
        let mut out = col(c);
        matmul(out.as_mut(), Accum::Replace, self.w.as_ref(), col(r).as_ref(), 1.0, faer::get_global_parallelism());
        out.col(0).iter().zip(c).map(|(wr, ci)| wr - ci).collect()
    }

    /// The means `m = L^-T (u - X r)` for the relative displacements `r`.
    pub fn means(&self, r: &[f64], lambda: &[f64]) -> Vec<f64> {
        let par = faer::get_global_parallelism();
        let mut m = col(&combine(&self.u, &self.u_fixed, lambda));
        if self.l.nrows() == 0 {
            return Vec::new();
        }
        matmul(m.as_mut(), Accum::Add, self.x.as_ref(), col(r).as_ref(), -1.0, par);
        solve_upper_triangular_in_place(self.l.transpose(), m.as_mut(), par);
        m.col(0).iter().copied().collect()
    }
}

/// Runs `f(block, first column)` on column blocks of `m`, one per core
/// (faer is built without its rayon feature; the columns are independent).
fn by_columns(m: MatMut<'_, f64>, f: impl Fn(MatMut<'_, f64>, usize) + Sync) {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    if threads <= 1 || m.ncols() < 256 {
        f(m, 0);
        return;
    }
    let chunk = m.ncols().div_ceil(threads);
    std::thread::scope(|scope| {
        let (mut rest, mut start) = (m, 0);
        while rest.ncols() > 0 {
            let w = chunk.min(rest.ncols());
            let (head, tail) = rest.split_at_col_mut(w);
            let (f, first) = (&f, start);
            start += head.ncols();
            scope.spawn(move || f(head, first));
            rest = tail;
        }
    });
}

/// `fixed * ramp + sum lambda_i v_i`: a vector under the load factors
/// `lambda` (case 0's factor, the ramp, also scales the prescribed values).
pub(super) fn combine(v: &[Vec<f64>], fixed: &[f64], lambda: &[f64]) -> Vec<f64> {
    let ramp = lambda.first().copied().unwrap_or(1.0);
    let mut out: Vec<f64> = fixed.iter().map(|x| x * ramp).collect();
    for (vc, &l) in v.iter().zip(lambda) {
        if l != 0.0 {
            for (o, x) in out.iter_mut().zip(vc) {
                *o += l * x;
            }
        }
    }
    out
}
