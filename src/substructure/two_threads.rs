//! A supernodal substitution with a single-precision Cholesky factor in two
//! threads. The sparse interface substitutes with the means' factor once
//! per GMRES iteration and streams the whole factor through memory each
//! time; one core reads memory at 34 GB/s on this machine, two at 45 GB/s.
//!
//! The supernodes form a tree (a supernode's parent holds the first row
//! below its diagonal block), and nested dissection makes it wide: below
//! the root separators it splits into subtrees that share no rows. The
//! heaviest subtrees are opened from the roots down until the rest can be
//! dealt to two threads, by work, within 5 % of each other; the opened
//! supernodes are "the top".
//!
//! - Forwards, each thread solves its subtrees on its own copy of the
//!   right-hand side. A subtree writes to its own rows and to the top's,
//!   so the top's rows take the sum of both threads' updates; then the top
//!   is solved.
//! - Backwards, the top first; then each thread its subtrees, which read
//!   the top's rows and write only their own.
//! - A wide supernode of the top (the root separator of a cube's means is
//!   a fifth of the factor) has its rows cut between the threads, which
//!   pass each other a block of 128 answers at a time.
//!
//! Each thread adds the same updates in the same order as a sequential
//! substitution; only the sums over both threads are formed in another
//! order (single-precision round-off, `single_precision.rs`'s unit test).
//!
//! What it saves against faer's one-thread substitution is measured in
//! docs/kernels.md (the means of `make bench-blocks`).

use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{solve_lower_triangular_in_place, solve_upper_triangular_in_place};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::{Accum, MatMut, MatRef, Par};

/// Who substitutes a supernode.
const TOP: u8 = 2;

/// The supernodes dealt to two threads and the top; see the module header.
pub struct Twofold {
    /// Each thread's supernodes, ascending.
    bins: [Vec<usize>; 2],
    /// The top's supernodes, ascending.
    top: Vec<usize>,
    /// Who owns each column: 0, 1 or [`TOP`].
    owner: Vec<u8>,
    /// A supernode of the top with this many values or more has its rows
    /// shared by both threads.
    wide: usize,
}

/// How far the two threads' work may differ, as a share of the larger.
const BALANCE: f64 = 0.05;

/// The largest share of the work the top may take before the split is
/// given up (one thread then does everything). Nested dissection of a
/// cube's means puts a fifth of the factor in the root separator alone
/// (the 512-block cube: 22 %, and 29 % on the top).
const MOST_ON_TOP: f64 = 0.45;

/// Factors smaller than this (values) are substituted by one thread: two
/// threads' start costs more than they share.
const SMALLEST: f64 = 1e6;

/// See [`Twofold::wide`].
const WIDE: usize = 1 << 20;

impl Twofold {
    /// The split of `sn`'s supernodes, or None where its tree does not
    /// split into two nearly equal halves with a small top.
    pub fn new(sn: &SymbolicSupernodalCholesky<usize>) -> Option<Twofold> {
        Twofold::with(sn, WIDE)
    }

    /// [`Twofold::new`] with the top's supernodes of `wide` values or more
    /// shared by both threads.
    pub(super) fn with(sn: &SymbolicSupernodalCholesky<usize>, wide: usize) -> Option<Twofold> {
        let ns = sn.n_supernodes();
        let (begin, end) = (sn.supernode_begin(), sn.supernode_end());
        let mut super_of = vec![0; sn.nrows()];
        for s in 0..ns {
            super_of[begin[s]..end[s]].fill(s);
        }
        let mut children = vec![Vec::new(); ns];
        let mut roots = Vec::new();
        let mut work = vec![0.0; ns];
        for s in 0..ns {
            let pattern = sn.supernode(s).pattern();
            let cols = (end[s] - begin[s]) as f64;
            work[s] = cols * (cols + pattern.len() as f64);
            match pattern.iter().min() {
                Some(&r) => children[super_of[r]].push(s),
                None => roots.push(s),
            }
        }
        // subtree weights: a child comes before its parent
        let mut weight = work.clone();
        for s in 0..ns {
            for &c in &children[s] {
                weight[s] += weight[c];
            }
        }
        let total: f64 = roots.iter().map(|&r| weight[r]).sum();
        if total < SMALLEST {
            return None;
        }
        let (mut frontier, mut top) = (roots, Vec::new());
        let mut on_top = 0.0;
        let bins = loop {
            if frontier.is_empty() {
                return None;
            }
            frontier.sort_by(|a, b| weight[*b].total_cmp(&weight[*a]));
            let (mut bins, mut load) = ([Vec::new(), Vec::new()], [0.0, 0.0]);
            for &s in &frontier {
                let t = usize::from(load[1] < load[0]);
                bins[t].push(s);
                load[t] += weight[s];
            }
            let big = load[0].max(load[1]);
            if big > 0.0 && (load[0] - load[1]).abs() <= BALANCE * big {
                break bins;
            }
            let heaviest = frontier.remove(0);
            on_top += work[heaviest];
            if on_top > MOST_ON_TOP * total {
                return None;
            }
            top.push(heaviest);
            frontier.extend(children[heaviest].iter().copied());
        };
        let mut owner = vec![TOP; sn.nrows()];
        let mut lists: [Vec<usize>; 2] = [Vec::new(), Vec::new()];
        for (t, bin) in bins.iter().enumerate() {
            let mut stack = bin.clone();
            while let Some(s) = stack.pop() {
                owner[begin[s]..end[s]].fill(t as u8);
                lists[t].push(s);
                stack.extend(children[s].iter().copied());
            }
            lists[t].sort_unstable();
        }
        top.sort_unstable();
        Some(Twofold { bins: lists, top, owner, wide })
    }

    /// `L L^T x = b` in place (x in the factor's own ordering).
    pub fn solve(&self, l: SupernodalLltRef<'_, usize, f32>, x: &mut [f32]) {
        let b = x.to_vec();
        let mut copies = [b.clone(), b.clone()];
        std::thread::scope(|scope| {
            for (bin, copy) in self.bins.iter().zip(copies.iter_mut()) {
                scope.spawn(move || forward(l, bin, copy));
            }
        });
        for (c, xc) in x.iter_mut().enumerate() {
            *xc = match self.owner[c] {
                TOP => copies[0][c] + copies[1][c] - b[c],
                t => copies[usize::from(t)][c],
            };
        }
        for &s in &self.top {
            forward_wide(l, s, x, self.wide);
        }
        for &s in self.top.iter().rev() {
            backward_wide(l, s, x, self.wide);
        }
        let mut copies = [x.to_vec(), x.to_vec()];
        std::thread::scope(|scope| {
            for (bin, copy) in self.bins.iter().zip(copies.iter_mut()) {
                scope.spawn(move || backward(l, bin, copy));
            }
        });
        for (c, xc) in x.iter_mut().enumerate() {
            if self.owner[c] != TOP {
                *xc = copies[usize::from(self.owner[c])][c];
            }
        }
    }
}

/// `L x = b` over the supernodes `list` (ascending).
fn forward(l: SupernodalLltRef<'_, usize, f32>, list: &[usize], x: &mut [f32]) {
    let mut tmp = Vec::new();
    for &s in list {
        let node = l.supernode(s);
        let (start, pattern, ls) = (node.start(), node.pattern(), node.val());
        let size = ls.ncols();
        let (diag, below) = ls.split_at_row(size);
        let mut xs = MatMut::from_column_major_slice_mut(&mut x[start..start + size], size, 1);
        solve_lower_triangular_in_place(diag, xs.as_mut(), Par::Seq);
        tmp.clear();
        tmp.resize(pattern.len(), 0.0f32);
        let t = MatMut::from_column_major_slice_mut(&mut tmp, pattern.len(), 1);
        matmul(t, Accum::Replace, below, xs.as_ref(), 1.0f32, Par::Seq);
        for (&r, v) in pattern.iter().zip(&tmp) {
            x[r] -= v;
        }
    }
}

/// `L^T x = b` over the supernodes `list` (ascending; taken descending).
fn backward(l: SupernodalLltRef<'_, usize, f32>, list: &[usize], x: &mut [f32]) {
    let mut tmp = Vec::new();
    for &s in list.iter().rev() {
        let node = l.supernode(s);
        let (start, pattern, ls) = (node.start(), node.pattern(), node.val());
        let size = ls.ncols();
        let (diag, below) = ls.split_at_row(size);
        tmp.clear();
        tmp.extend(pattern.iter().map(|&r| x[r]));
        let t = MatRef::from_column_major_slice(&tmp, pattern.len(), 1);
        let mut xs = MatMut::from_column_major_slice_mut(&mut x[start..start + size], size, 1);
        matmul(xs.as_mut(), Accum::Add, below.transpose(), t, -1.0f32, Par::Seq);
        solve_upper_triangular_in_place(diag.transpose(), xs.as_mut(), Par::Seq);
    }
}

/// Columns per block of a wide supernode.
const BLOCK: usize = 128;

/// Where a wide supernode's rows are cut between the two threads: the
/// first thread takes the rows above `m` (a block boundary), the second the
/// rest, so that both do about the same multiply-adds. The first thread's
/// blocks update rows of both; the second's only its own.
fn cut(nrows: usize, ncols: usize) -> usize {
    let blocks: Vec<usize> = (0..ncols).step_by(BLOCK).collect();
    let work = |m: usize| {
        let (mut a, mut b) = (0.0f64, 0.0f64);
        for &c0 in &blocks {
            let nb = ((c0 + BLOCK).min(ncols) - c0) as f64;
            if c0 < m {
                a += nb * (m - c0) as f64;
                b += nb * (nrows - m) as f64;
            } else {
                b += nb * (nrows - c0) as f64;
            }
        }
        a.max(b)
    };
    blocks.iter().copied().chain([ncols]).min_by(|x, y| work(*x).total_cmp(&work(*y))).unwrap_or(0)
}

/// A supernode of `wide` values or more: its first column, its rows below
/// the diagonal block, its values and the cut of its rows.
struct Wide<'a> {
    start: usize,
    pattern: &'a [usize],
    ls: MatRef<'a, f32>,
    m: usize,
}

impl<'a> Wide<'a> {
    fn of(l: SupernodalLltRef<'a, usize, f32>, s: usize, wide: usize) -> Option<Wide<'a>> {
        let node = l.supernode(s);
        let ls = node.val();
        (ls.nrows() * ls.ncols() >= wide).then(|| Wide {
            start: node.start(),
            pattern: node.pattern(),
            ls,
            m: cut(ls.nrows(), ls.ncols()),
        })
    }
}

/// `forward` on the top's supernode `s`, its rows shared by two threads
/// where it is wide: the first thread solves the blocks above the cut and
/// passes each block's answer to the second, which updates the rows below
/// the cut with it and then solves its own blocks.
fn forward_wide(l: SupernodalLltRef<'_, usize, f32>, s: usize, x: &mut [f32], wide: usize) {
    let Some(Wide { start, pattern, ls, m }) = Wide::of(l, s, wide) else {
        return forward(l, &[s], x);
    };
    let (nrows, ncols) = (ls.nrows(), ls.ncols());
    // z: the supernode's own rows, then (negated) its updates to the rows below
    let mut z: Vec<f32> = x[start..start + ncols].to_vec();
    z.resize(nrows, 0.0);
    let (za, zb) = z.split_at_mut(m);
    let (send, receive) = std::sync::mpsc::channel::<(usize, Vec<f32>)>();
    std::thread::scope(|scope| {
        scope.spawn(move || {
            let mut zb = MatMut::from_column_major_slice_mut(zb, nrows - m, 1);
            for (c0, xk) in receive {
                let xk = MatRef::from_column_major_slice(&xk, xk.len(), 1);
                matmul(zb.as_mut(), Accum::Add, ls.submatrix(m, c0, nrows - m, xk.nrows()), xk, -1.0f32, Par::Seq);
            }
            for c0 in (m..ncols).step_by(BLOCK) {
                let c1 = (c0 + BLOCK).min(ncols);
                let (done, mut rest) = zb.as_mut().split_at_row_mut(c1 - m);
                let mut xk = done.subrows_mut(c0 - m, c1 - c0);
                solve_lower_triangular_in_place(ls.submatrix(c0, c0, c1 - c0, c1 - c0), xk.as_mut(), Par::Seq);
                let n = rest.nrows();
                matmul(rest.as_mut(), Accum::Add, ls.submatrix(c1, c0, n, c1 - c0), xk.as_ref(), -1.0f32, Par::Seq);
            }
        });
        let mut za = MatMut::from_column_major_slice_mut(za, m, 1);
        for c0 in (0..m).step_by(BLOCK) {
            let c1 = c0 + BLOCK.min(m - c0);
            let (done, mut rest) = za.as_mut().split_at_row_mut(c1);
            let mut xk = done.subrows_mut(c0, c1 - c0);
            solve_lower_triangular_in_place(ls.submatrix(c0, c0, c1 - c0, c1 - c0), xk.as_mut(), Par::Seq);
            let copy: Vec<f32> = (0..c1 - c0).map(|i| xk[(i, 0)]).collect();
            send.send((c0, copy)).expect("the second substitution thread");
            let n = rest.nrows();
            matmul(rest.as_mut(), Accum::Add, ls.submatrix(c1, c0, n, c1 - c0), xk.as_ref(), -1.0f32, Par::Seq);
        }
        drop(send);
    });
    x[start..start + ncols].copy_from_slice(&z[..ncols]);
    for (&r, v) in pattern.iter().zip(&z[ncols..]) {
        x[r] += v;
    }
}

/// `backward` on the top's supernode `s`, its rows shared by two threads
/// where it is wide: the second thread solves its own blocks, then sends
/// the first each block's product with the rows below the cut.
fn backward_wide(l: SupernodalLltRef<'_, usize, f32>, s: usize, x: &mut [f32], wide: usize) {
    let Some(Wide { start, pattern, ls, m }) = Wide::of(l, s, wide) else {
        return backward(l, &[s], x);
    };
    let (nrows, ncols) = (ls.nrows(), ls.ncols());
    let mut z: Vec<f32> = x[start..start + ncols].to_vec();
    z.extend(pattern.iter().map(|&r| x[r]));
    let (za, zb) = z.split_at_mut(m);
    let (send, receive) = std::sync::mpsc::channel::<Vec<f32>>();
    let blocks: Vec<usize> = (0..ncols).step_by(BLOCK).collect();
    let (above, below) = blocks.split_at(blocks.partition_point(|&c0| c0 < m));
    std::thread::scope(|scope| {
        scope.spawn(move || {
            let mut zb = MatMut::from_column_major_slice_mut(zb, nrows - m, 1);
            for &c0 in below.iter().rev() {
                let c1 = (c0 + BLOCK).min(ncols);
                let (mut head, rest) = zb.as_mut().split_at_row_mut(c1 - m);
                let n = rest.nrows();
                let mut xk = head.as_mut().subrows_mut(c0 - m, c1 - c0);
                matmul(
                    xk.as_mut(),
                    Accum::Add,
                    ls.submatrix(c1, c0, n, c1 - c0).transpose(),
                    rest.as_ref(),
                    -1.0f32,
                    Par::Seq,
                );
                solve_upper_triangular_in_place(ls.submatrix(c0, c0, c1 - c0, c1 - c0).transpose(), xk, Par::Seq);
            }
            for &c0 in above.iter().rev() {
                let nb = BLOCK.min(m - c0);
                let mut y = vec![0.0f32; nb];
                let out = MatMut::from_column_major_slice_mut(&mut y, nb, 1);
                matmul(
                    out,
                    Accum::Replace,
                    ls.submatrix(m, c0, nrows - m, nb).transpose(),
                    zb.as_ref(),
                    1.0f32,
                    Par::Seq,
                );
                if send.send(y).is_err() {
                    break;
                }
            }
        });
        let mut za = MatMut::from_column_major_slice_mut(za, m, 1);
        for &c0 in above.iter().rev() {
            let c1 = c0 + BLOCK.min(m - c0);
            let (mut head, rest) = za.as_mut().split_at_row_mut(c1);
            let n = rest.nrows();
            let mut xk = head.as_mut().subrows_mut(c0, c1 - c0);
            matmul(
                xk.as_mut(),
                Accum::Add,
                ls.submatrix(c1, c0, n, c1 - c0).transpose(),
                rest.as_ref(),
                -1.0f32,
                Par::Seq,
            );
            let y = receive.recv().expect("the second substitution thread");
            for (i, v) in y.iter().enumerate() {
                xk[(i, 0)] -= v;
            }
            solve_upper_triangular_in_place(ls.submatrix(c0, c0, c1 - c0, c1 - c0).transpose(), xk, Par::Seq);
        }
    });
    x[start..start + ncols].copy_from_slice(&z[..ncols]);
}
