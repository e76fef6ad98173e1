//! The interface in mean / relative coordinates.
//!
//! Per pair and local axis the two sides' DOFs are written as a mean `m`
//! and a relative displacement `r = d'_l - d'_k`, or, where a side is held,
//! as the held value and `r`:
//!
//! ```text
//! d'_k = m - r/2,  d'_l = m + r/2        (neither side held)
//! d'_k = v,        d'_l = v + r          (k held at v; likewise for l)
//! ```
//!
//! i.e. `d' = W [m; r] + w0`. With the parts' condensed matrices in local
//! axes, `S' = T Q^T S Q T^T`, `G' = T Q^T G`, the interface equations
//! `S' d' = G' + f` (contact force λ on body I at k, -λ on body II at l)
//! become
//!
//! ```text
//! [K_mm K_mr] [m]   [b_m]   [ 0]
//! [K_rm K_rr] [r] - [b_r] = [-λ]        K = W^T S' W,  b = W^T (G' - S' w0)
//! ```
//!
//! This file assembles the three blocks and the right-hand sides.

use faer::Mat;

use super::super::basis;
use super::super::frame::Frame;
use crate::fem::sparse::SymMatrix;

/// How one local axis of a pair enters the unknowns: `m` indexes the means,
/// `r` the relative displacements.
#[derive(Clone, Copy, Debug)]
pub enum Axis {
    /// Neither side held: `d'_k = m - r/2`, `d'_l = m + r/2`.
    Free { m: usize, r: usize },
    /// Side k held at `v` (per unit ramp): `d'_k = v`, `d'_l = v + r`.
    HeldK { r: usize, v: f64 },
    /// Side l held at `v`: `d'_l = v`, `d'_k = v - r`.
    HeldL { r: usize, v: f64 },
    /// Both sides held.
    Held { vk: f64, vl: f64 },
    /// A node shared by parts (a bonded join): one mean, no relative displacement.
    Joined { m: usize },
    /// The axis does not exist (the third axis in 2D).
    Absent,
}

/// An unknown: a mean or a relative displacement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Var {
    M(usize),
    R(usize),
}

/// `d'` of one side as `sum c var + const * ramp` (at most two terms).
#[derive(Clone, Debug)]
pub struct Terms {
    pub vars: [(Var, f64); 2],
    pub n: usize,
    pub constant: f64,
}

impl Axis {
    /// The mean of this axis, if it has one.
    pub fn m(self) -> Option<usize> {
        match self {
            Axis::Free { m, .. } | Axis::Joined { m } => Some(m),
            _ => None,
        }
    }

    pub fn r(self) -> Option<usize> {
        match self {
            Axis::Free { r, .. } | Axis::HeldK { r, .. } | Axis::HeldL { r, .. } => Some(r),
            _ => None,
        }
    }

    /// `d'` of side `s` (0 = k, 1 = l).
    pub fn terms(self, s: usize) -> Terms {
        let none = (Var::M(0), 0.0);
        let (vars, n, constant) = match (self, s) {
            (Axis::Free { m, r }, 0) => ([(Var::M(m), 1.0), (Var::R(r), -0.5)], 2, 0.0),
            (Axis::Free { m, r }, _) => ([(Var::M(m), 1.0), (Var::R(r), 0.5)], 2, 0.0),
            (Axis::HeldK { v, .. }, 0) => ([none, none], 0, v),
            (Axis::HeldK { r, v }, _) => ([(Var::R(r), 1.0), none], 1, v),
            (Axis::HeldL { r, v }, 0) => ([(Var::R(r), -1.0), none], 1, v),
            (Axis::HeldL { v, .. }, _) => ([none, none], 0, v),
            (Axis::Held { vk, .. }, 0) => ([none, none], 0, vk),
            (Axis::Held { vl, .. }, _) => ([none, none], 0, vl),
            (Axis::Joined { m }, _) => ([(Var::M(m), 1.0), none], 1, 0.0),
            (Axis::Absent, _) => ([none, none], 0, 0.0),
        };
        Terms { vars, n, constant }
    }
}

/// Numbers the unknowns of one pair's axes from the prescribed local
/// values of its two sides (per unit ramp), counting on from `nm` means and
/// `nr` relative displacements.
pub fn number_pair(fx: &[[Option<f64>; 3]; 2], nd: usize, nm: &mut usize, nr: &mut usize) -> [Axis; 3] {
    std::array::from_fn(|a| {
        if a >= nd {
            return Axis::Absent;
        }
        let mut r = || {
            *nr += 1;
            *nr - 1
        };
        match (fx[0][a], fx[1][a]) {
            (None, None) => {
                *nm += 1;
                Axis::Free { m: *nm - 1, r: r() }
            }
            (Some(v), None) => Axis::HeldK { r: r(), v },
            (None, Some(v)) => Axis::HeldL { r: r(), v },
            (Some(vk), Some(vl)) => Axis::Held { vk, vl },
        }
    })
}

/// `T A T^T` in place for a dense column-major `nc x nc` matrix whose
/// node blocks are rotated by `t[node]`.
pub fn rotate_matrix(s: &mut [f64], nc: usize, nd: usize, t: &[Frame]) {
    let mut tmp = [0.0; 3];
    // (a node's columns swept down together: row by row across all the
    // columns read a cache line per entry)
    for (q, tq) in t.iter().enumerate() {
        for i in 0..nc {
            for a in 0..nd {
                tmp[a] = (0..nd).map(|c| s[i + (q * nd + c) * nc] * tq[a][c]).sum();
            }
            for a in 0..nd {
                s[i + (q * nd + a) * nc] = tmp[a];
            }
        }
    }
    for j in 0..nc {
        for (q, tq) in t.iter().enumerate() {
            for a in 0..nd {
                tmp[a] = (0..nd).map(|c| tq[a][c] * s[q * nd + c + j * nc]).sum();
            }
            for a in 0..nd {
                s[q * nd + a + j * nc] = tmp[a];
            }
        }
    }
}

/// `T g` in place.
pub fn rotate_vector(g: &mut [f64], nd: usize, t: &[Frame]) {
    for (q, tq) in t.iter().enumerate() {
        let v: Vec<f64> = (0..nd).map(|a| (0..nd).map(|c| tq[a][c] * g[q * nd + c]).sum()).collect();
        g[q * nd..q * nd + nd].copy_from_slice(&v);
    }
}

/// The blocks of `K = W^T S' W` and the right-hand sides `b = W^T (G' -
/// S' w0)`: per load case, and for the prescribed values at ramp 1.
pub struct Blocks {
    pub k_mm: Mat<f64>,
    pub k_mr: Mat<f64>,
    pub k_rr: Mat<f64>,
    pub b_m: Vec<Vec<f64>>,
    pub b_r: Vec<Vec<f64>>,
    pub b_m_fixed: Vec<f64>,
    pub b_r_fixed: Vec<f64>,
}

impl Blocks {
    pub fn zeros(nm: usize, nr: usize, cases: usize) -> Blocks {
        Blocks {
            k_mm: Mat::zeros(nm, nm),
            k_mr: Mat::zeros(nm, nr),
            k_rr: Mat::zeros(nr, nr),
            b_m: vec![vec![0.0; nm]; cases],
            b_r: vec![vec![0.0; nr]; cases],
            b_m_fixed: vec![0.0; nm],
            b_r_fixed: vec![0.0; nr],
        }
    }

    /// Adds one part: its Schur complement `s` (column-major, nodal basis,
    /// global axes) and condensed loads `g`, with `terms[u]` the unknowns of
    /// its interface DOF u, `frames` the frame of each of its interface
    /// nodes and `edges` its transformed face edges.
    pub fn add_part(
        &mut self,
        s: &[f64],
        g: &[Vec<f64>],
        nd: usize,
        terms: &[Terms],
        frames: &[Frame],
        edges: &[[usize; 3]],
    ) {
        let (s, g) = localise(s, g, nd, frames, edges);
        for_each_entry(&s, terms, |i, j, x| match (i, j) {
            (Var::M(a), Var::M(b)) => self.k_mm[(a, b)] += x,
            (Var::M(a), Var::R(b)) => self.k_mr[(a, b)] += x,
            (Var::R(a), Var::R(b)) => self.k_rr[(a, b)] += x,
            // the (r, m) entries are the (m, r) ones of the symmetric K
            (Var::R(_), Var::M(_)) => {}
        });
        let add = |bm: &mut [f64], br: &mut [f64], i: Var, x: f64| match i {
            Var::M(a) => bm[a] += x,
            Var::R(a) => br[a] += x,
        };
        for (case, gc) in g.iter().enumerate() {
            for_each_load(gc, terms, |i, x| add(&mut self.b_m[case], &mut self.b_r[case], i, x));
        }
        fixed_load(&s, terms, |i, x| add(&mut self.b_m_fixed, &mut self.b_r_fixed, i, x));
    }
}

/// A part's Schur complement and condensed loads in the interface basis and
/// the pairs' local axes: `T Q^T S Q T^T` and `T Q^T G`.
pub fn localise(
    s: &[f64],
    g: &[Vec<f64>],
    nd: usize,
    frames: &[Frame],
    edges: &[[usize; 3]],
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let nc = frames.len() * nd;
    let mut s = s.to_vec();
    basis::transform_matrix(&mut s, nc, nd, edges);
    rotate_matrix(&mut s, nc, nd, frames);
    let g = g
        .iter()
        .map(|gc| {
            let mut g = gc.clone();
            basis::transform_load(&mut g, nd, edges);
            rotate_vector(&mut g, nd, frames);
            g
        })
        .collect();
    (s, g)
}

/// Calls `f(i, j, x)` for every term of `K = W^T S' W` (both triangles;
/// `s` local, `terms[u]` the unknowns of DOF u).
pub fn for_each_entry(s: &[f64], terms: &[Terms], mut f: impl FnMut(Var, Var, f64)) {
    let nc = terms.len();
    for v in 0..nc {
        let tv = &terms[v];
        for u in 0..nc {
            let suv = s[u + v * nc];
            if suv == 0.0 {
                continue;
            }
            let tu = &terms[u];
            for &(i, ci) in &tu.vars[..tu.n] {
                for &(j, cj) in &tv.vars[..tv.n] {
                    f(i, j, ci * cj * suv);
                }
            }
        }
    }
}

/// Scratch space of [`add_clique`]: one slot per unknown of the matrix.
pub struct CliqueScratch {
    local: Vec<usize>,
    pos: Vec<usize>,
}

impl CliqueScratch {
    pub fn new(n: usize) -> CliqueScratch {
        CliqueScratch { local: vec![usize::MAX; n], pos: vec![usize::MAX; n] }
    }
}

/// Adds one part's `K_p = W^T S' W` (`s` local, `terms[u]` the unknowns of
/// DOF u) to the lower triangle of `k`, whose pattern holds the part's
/// clique: the terms whose unknown `index` maps to an equation; the others
/// are left out.
pub fn add_clique(
    k: &mut SymMatrix,
    s: &[f64],
    terms: &[Terms],
    index: impl Fn(Var) -> Option<usize>,
    scratch: &mut CliqueScratch,
) {
    let mut vars: Vec<usize> = terms.iter().flat_map(|t| t.vars[..t.n].iter().filter_map(|&(x, _)| index(x))).collect();
    vars.sort_unstable();
    vars.dedup();
    let m = vars.len();
    for (a, &v) in vars.iter().enumerate() {
        scratch.local[v] = a;
    }
    let mut kp = vec![0.0; m * m];
    for_each_entry(s, terms, |i, j, x| {
        if let (Some(a), Some(b)) = (index(i), index(j)) {
            kp[scratch.local[a] + scratch.local[b] * m] += x;
        }
    });
    for (b, &col) in vars.iter().enumerate() {
        let (lo, hi) = (k.col_ptr[col], k.col_ptr[col + 1]);
        for p in lo..hi {
            scratch.pos[k.row_idx[p]] = p;
        }
        for (a, &row) in vars.iter().enumerate() {
            if row >= col {
                k.values[scratch.pos[row]] += kp[a + b * m];
            }
        }
    }
    for &v in &vars {
        scratch.local[v] = usize::MAX;
    }
}

/// Calls `f(i, x)` for every term of `W^T g`.
pub fn for_each_load(g: &[f64], terms: &[Terms], mut f: impl FnMut(Var, f64)) {
    for (u, &x) in g.iter().enumerate() {
        let tu = &terms[u];
        for &(i, ci) in &tu.vars[..tu.n] {
            f(i, ci * x);
        }
    }
}

/// Calls `f(i, x)` for every term of `-W^T S' w0`, the load of the
/// prescribed values at ramp 1.
pub fn fixed_load(s: &[f64], terms: &[Terms], f: impl FnMut(Var, f64)) {
    let nc = terms.len();
    let w0: Vec<f64> = terms.iter().map(|t| t.constant).collect();
    if w0.iter().all(|&v| v == 0.0) {
        return;
    }
    let sw: Vec<f64> = (0..nc).map(|u| -(0..nc).map(|v| s[u + v * nc] * w0[v]).sum::<f64>()).collect();
    for_each_load(&sw, terms, f);
}

/// A part's interface displacements (global axes, nodal basis) from the
/// unknowns: `Q T^T (W x + ramp w0)`, with `terms[u]` the unknowns of its
/// interface DOF u, `frames` the frame of each of its interface nodes,
/// `edges` its transformed face edges and `value` the unknowns' values.
pub fn part_displacements(
    terms: &[Terms],
    frames: &[Frame],
    edges: &[[usize; 3]],
    nd: usize,
    ramp: f64,
    value: impl Fn(Var) -> f64,
) -> Vec<f64> {
    let mut d = vec![0.0; terms.len()];
    for (q, f) in frames.iter().enumerate() {
        let mut local = [0.0; 3];
        for (a, l) in local.iter_mut().enumerate().take(nd) {
            let t = &terms[q * nd + a];
            *l = t.constant * ramp + t.vars[..t.n].iter().map(|&(v, c)| c * value(v)).sum::<f64>();
        }
        for c in 0..nd {
            d[q * nd + c] = (0..nd).map(|a| f[a][c] * local[a]).sum();
        }
    }
    basis::to_nodal(&mut d, nd, edges);
    d
}
