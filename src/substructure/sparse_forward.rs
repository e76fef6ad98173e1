//! A forward substitution `L^-1 b` for right-hand sides with a few
//! non-zeros, through the supernodes it reaches alone.
//!
//! The sparse interface's W diagonal asks `b^T K_mm^-1 b = |L^-1 P b|^2`
//! of every slipping or open relative displacement, `b = K_mr e_i`, which
//! is non-zero only on the means of the one or two parts that hold it.
//! Row r of `L^-1 b` is non-zero only where r's supernode lies on the path
//! from the supernode of a non-zero of b to its root (the supernodal
//! elimination tree: a supernode's parent holds the first row below its
//! diagonal block), so only those supernodes are substituted, in
//! ascending order (children before parents), as faer's own substitution
//! would, on a vector that holds their rows alone.
//!
//! Columns whose paths meet share a pass: the top separators of nested
//! dissection are on every path and are read once per batch rather than
//! once per column. A batch's columns are best sorted by their lowest
//! supernode ([`Paths::leaf`]), so that the lower parts of their paths
//! overlap too. What it saves against the dense substitution is in
//! docs/blocks.md.

use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::{Accum, MatMut, Par};

/// No supernode (a root's parent, a row not reached).
const NONE: usize = usize::MAX;

/// The supernodal elimination tree of a factor; see the module header.
pub struct Paths {
    /// The supernode of each row (the factor's ordering).
    super_of: Vec<usize>,
    /// Each supernode's parent, [`NONE`] at a root.
    parent: Vec<usize>,
    /// Each supernode's first row.
    begin: Vec<usize>,
}

impl Paths {
    /// The tree of `sn`'s supernodes.
    pub fn new(sn: &SymbolicSupernodalCholesky<usize>) -> Paths {
        let (begin, end) = (sn.supernode_begin(), sn.supernode_end());
        let mut super_of = vec![0; sn.nrows()];
        let parent = (0..sn.n_supernodes())
            .map(|s| {
                super_of[begin[s]..end[s]].fill(s);
                sn.supernode(s).pattern().iter().min().map_or(NONE, |&r| r)
            })
            .collect::<Vec<usize>>();
        let parent = parent.into_iter().map(|r| if r == NONE { NONE } else { super_of[r] }).collect();
        Paths { super_of, parent, begin: begin.to_vec() }
    }

    /// The lowest supernode holding one of `rows` (the factor's ordering),
    /// a key to sort columns by so that a batch's paths overlap.
    pub fn leaf(&self, rows: impl Iterator<Item = usize>) -> usize {
        rows.map(|r| self.super_of[r]).min().unwrap_or(NONE)
    }

    /// The supernodes on the paths from the supernodes of `rows` to their
    /// roots, ascending.
    fn reach(&self, rows: impl Iterator<Item = usize>) -> Vec<usize> {
        let mut seen = vec![false; self.parent.len()];
        let mut reached = Vec::new();
        for r in rows {
            let mut s = self.super_of[r];
            while s != NONE && !seen[s] {
                seen[s] = true;
                reached.push(s);
                s = self.parent[s];
            }
        }
        reached.sort_unstable();
        reached
    }
}

/// `|L^-1 b|^2` of every column of `cols`, each given by its non-zeros
/// (row in the factor's ordering, value), in one pass through the
/// supernodes their paths reach; see the module header.
pub fn energies(l: SupernodalLltRef<'_, usize, f32>, paths: &Paths, cols: &[Vec<(usize, f32)>]) -> Vec<f64> {
    let batch = substitute(l, paths, cols);
    let m = batch.m;
    (0..cols.len()).map(|c| batch.x[c * m..(c + 1) * m].iter().map(|&v| f64::from(v).powi(2)).sum()).collect()
}

/// `L^-1 b` of every column of `cols` (as [`energies`] takes them), each
/// on the supernodes its own path reaches: what products `b_a^T K^-1 b_b`
/// of two columns are formed from ([`Forward::dot`]).
pub fn forward(l: SupernodalLltRef<'_, usize, f32>, paths: &Paths, cols: &[Vec<(usize, f32)>]) -> Vec<Forward> {
    let batch = substitute(l, paths, cols);
    let m = batch.m;
    (cols.iter().enumerate())
        .map(|(c, col)| {
            let x = &batch.x[c * m..(c + 1) * m];
            let (mut nodes, mut values) = (Vec::new(), Vec::new());
            for s in paths.reach(col.iter().map(|&(r, _)| r)) {
                nodes.push((s, values.len()));
                let o = batch.local[s];
                values.extend_from_slice(&x[o..o + l.supernode(s).val().ncols()]);
            }
            Forward { nodes, values }
        })
        .collect()
}

/// One column's `L^-1 b` on the supernodes of its path; see [`forward`].
pub struct Forward {
    /// The supernodes, ascending, and where each one's rows begin in `values`.
    nodes: Vec<(usize, usize)>,
    values: Vec<f32>,
}

impl Forward {
    /// `(L^-1 a)^T (L^-1 b)`, over the supernodes both paths reach (the
    /// top separators at least), summed in double precision.
    pub fn dot(&self, other: &Forward) -> f64 {
        let (mut i, mut j, mut sum) = (0, 0, 0.0);
        while i < self.nodes.len() && j < other.nodes.len() {
            let (a, b) = (self.nodes[i], other.nodes[j]);
            match a.0.cmp(&b.0) {
                std::cmp::Ordering::Less => i += 1,
                std::cmp::Ordering::Greater => j += 1,
                std::cmp::Ordering::Equal => {
                    let end = |f: &Forward, k: usize| f.nodes.get(k + 1).map_or(f.values.len(), |n| n.1);
                    sum += dot(&self.values[a.1..end(self, i)], &other.values[b.1..end(other, j)]);
                    i += 1;
                    j += 1;
                }
            }
        }
        sum
    }

    /// The bytes its values hold.
    pub fn bytes(&self) -> usize {
        4 * self.values.len()
    }
}

/// `a . b` in double precision, in eight lanes.
fn dot(a: &[f32], b: &[f32]) -> f64 {
    let mut lanes = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca.remainder().iter().zip(cb.remainder()).map(|(&x, &y)| f64::from(x) * f64::from(y)).sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            lanes[k] += f64::from(x[k]) * f64::from(y[k]);
        }
    }
    lanes.iter().sum::<f64>() + tail
}

/// A batch's forward substitutions, packed over the supernodes their
/// paths reach: column c's row r at `x[c * m + local[s] + r - begin[s]]`.
struct Batch {
    x: Vec<f32>,
    m: usize,
    local: Vec<usize>,
}

/// [`Batch`] of `cols`.
fn substitute(l: SupernodalLltRef<'_, usize, f32>, paths: &Paths, cols: &[Vec<(usize, f32)>]) -> Batch {
    let k = cols.len();
    let reached = paths.reach(cols.iter().flatten().map(|&(r, _)| r));
    // the reached supernodes' rows, packed in ascending order
    let mut local = vec![NONE; paths.parent.len()];
    let mut m = 0;
    for &s in &reached {
        local[s] = m;
        m += l.supernode(s).val().ncols();
    }
    let at = |r: usize| {
        let s = paths.super_of[r];
        local[s] + r - paths.begin[s]
    };
    let mut x = vec![0.0f32; m * k];
    for (c, col) in cols.iter().enumerate() {
        for &(r, v) in col {
            x[c * m + at(r)] += v;
        }
    }
    let mut tmp = Vec::new();
    for &s in &reached {
        let node = l.supernode(s);
        let (pattern, ls) = (node.pattern(), node.val());
        let (size, o) = (ls.ncols(), at(node.start()));
        let (diag, below) = ls.split_at_row(size);
        let mut xs = MatMut::from_column_major_slice_with_stride_mut(&mut x[o..], size, k, m);
        solve_lower_triangular_in_place(diag, xs.as_mut(), Par::Seq);
        tmp.clear();
        tmp.resize(pattern.len() * k, 0.0f32);
        let t = MatMut::from_column_major_slice_mut(&mut tmp, pattern.len(), k);
        matmul(t, Accum::Replace, below, xs.as_ref(), 1.0f32, Par::Seq);
        let rows: Vec<usize> = pattern.iter().map(|&r| at(r)).collect();
        for (c, tc) in tmp.chunks_exact(pattern.len().max(1)).take(k).enumerate() {
            for (&i, v) in rows.iter().zip(tc) {
                x[c * m + i] -= v;
            }
        }
    }
    Batch { x, m, local }
}
