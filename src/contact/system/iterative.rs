//! The interface system without S: the unknowns `x = [m; r]` of
//! [`super::coords`], `K x` applied part by part through each part's
//! interior factor ([`crate::substructure::interior`]),
//!
//! ```text
//! K x = sum_p W_p^T T_p Q_p^T  S_p  Q_p T_p^T W_p x       (S_p x = K_cc x - K_ci K_ii^-1 K_ic x)
//! ```
//!
//! and each set of pair relations solved by GMRES ([`super::gmres`]) in the
//! means and the free relative displacements, the tied ones moved to the
//! right-hand side. Nothing of size nc^2 exists: memory is the parts'
//! interior factors plus a few vectors per GMRES iteration, and a contact
//! iteration costs a number of sparse sweeps instead of a dense
//! factorisation. Each solve starts from the last one's answer. A solve
//! whose state set differs from the last one's only decides the next
//! states, so it stops at [`LOOSE_TOLERANCE`] (early in a step: late ones
//! are solved as [`Accuracy::Tight`]); the contact iteration
//! accepts only a solve at [`TOLERANCE`], made once the states repeat
//! (blocks3d_tet10: 345 applications of S in 9 contact iterations instead
//! of 581 in 8, the answer within 1.4e-10 of the dense interface's). While
//! the states repeat but the friction has not settled, each solve is a
//! Newton step on the friction, solved to [`STEP_FRACTION`] of the law's
//! residual ([`tolerance`]); the solve after the friction settles is the
//! tight one.
//!
//! The preconditioner has two levels. The fine one is block Jacobi: per
//! pair (its means and relative displacements) and per join node, the
//! diagonal blocks of the parts' K_cc in the same coordinates (the face
//! basis of quadratic faces left out), with the friction law's
//! linearisation on the pair's slipping rows. Alone, its iteration count
//! grows with the number of pieces in a row (a column cut into 8 slices
//! bends through 7 joins). The coarse level is the parts' rigid motions
//! (6 per part in 3D) on the interface means, weighted by the number of
//! parts sharing each node, as balancing Neumann-Neumann and FETI coarse
//! spaces are: `Φ`, orthonormalised, with `K Φ` applied once, in one
//! batch of columns; each solve then factorises `Φ^T J Φ` (J the system
//! with the solve's relations) and preconditions by
//!
//! ```text
//! c = (Φ^T J Φ)^-1 Φ^T v,     z = Φ c + D^-1 (v - J Φ c)
//! ```
//!
//! Φ holds means only, which are unknowns under every relation, so `J Φ`
//! comes from the stored `K Φ` without applying S again.

mod stiffness;

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use faer::linalg::solvers::Solve;
use faer::Mat;

use super::coords;
use super::coords::{for_each_load, Terms, Var};
use super::freedom::Freedom;
use super::gmres;
use super::layout::Layout;
use super::reduce::combine;
use super::solver::{Accuracy, Answer, Solver, WarmStart};
use super::threads::in_runs;
use crate::contact::basis;
use crate::contact::frame::Frame;
use crate::contact::law::ContactState;
use crate::contact::mobility::PartModes;
use crate::fem::rigid::n_modes;
use crate::fem::vec3::length;
use crate::model::Model;
use crate::substructure::interior::SharedSolve;
use crate::substructure::{OperatorRef, SchurRef};

/// Relative tolerance of each interface solve, against the load.
pub const TOLERANCE: f64 = 1e-10;
/// The tolerance of a solve whose state set differs from the last one's:
/// its answer only decides the next states (the contact iteration then
/// solves the same states again at [`TOLERANCE`] before accepting it).
pub const LOOSE_TOLERANCE: f64 = 1e-6;
/// A Newton step under held states ([`Accuracy::Step`]) is solved to this
/// fraction of the law's residual: the step's error is then a thousandth
/// of what it corrects, and Newton's rate is kept.
pub const STEP_FRACTION: f64 = 1e-3;
/// A solve that did not reach its tolerance is still used where its
/// residual is below this fraction of the load (the answer inexact);
/// above it the system is taken as singular (a body sliding freely), and
/// GMRES gives up once its rate cannot bring it there
/// ([`gmres::Target::enough`]).
pub const USABLE: f64 = 1e-6;
const RESTART: usize = 200;
const MAX_ITERATIONS: usize = 5_000;

/// A solve's tolerance on its residual (a force), `scale` the size of its
/// load: [`LOOSE_TOLERANCE`] of it where the states changed (`loose`), the
/// [`STEP_FRACTION`] of the law's residual for a Newton step under held
/// states (within the loose and the tight tolerance), [`TOLERANCE`] of it
/// for the answer; and whether that is looser than the answer's.
pub(super) fn tolerance(loose: bool, accuracy: Accuracy, scale: f64) -> (f64, bool) {
    let tight = TOLERANCE * scale;
    let tol = match (loose, accuracy) {
        (_, Accuracy::Tight) => tight,
        (true, _) => LOOSE_TOLERANCE * scale,
        (false, Accuracy::Step(law)) => (STEP_FRACTION * law).clamp(tight, LOOSE_TOLERANCE * scale),
        (false, Accuracy::Answer) => tight,
    };
    (tol, tol > tight)
}

/// What GMRES aims at: `tol`, and the [`USABLE`] fraction of the load
/// `scale`, above which its answer is of no use.
pub(super) fn target(tol: f64, scale: f64) -> gmres::Target {
    gmres::Target { tol, enough: USABLE * scale }
}

/// The state set of the last solve, which tells whether a solve may stop
/// at [`LOOSE_TOLERANCE`] (the sparse interface keeps one too).
#[derive(Default)]
pub(super) struct LastStates(Mutex<Option<Vec<ContactState>>>);

impl LastStates {
    /// The state set of the last solve.
    pub(super) fn get(&self) -> Option<Vec<ContactState>> {
        self.0.lock().ok().and_then(|l| l.clone())
    }

    /// Takes `states` as the last solve's.
    pub(super) fn set(&self, states: Option<Vec<ContactState>>) {
        if let Ok(mut last) = self.0.lock() {
            *last = states;
        }
    }

    /// Loose while the states change; the same states as last time (or
    /// none to judge: bonded joins alone) are solved tightly.
    pub(super) fn loose(&self, states: &[ContactState]) -> bool {
        match self.0.lock() {
            Ok(mut last) => {
                let same = last.as_deref() == Some(states);
                *last = Some(states.to_vec());
                !same && !states.is_empty()
            }
            Err(_) => false,
        }
    }
}

/// What a [`WarmStart`] keeps of an iterative solver: its last answer
/// (shared with the solver, not copied: 4 vectors of the interface's size
/// on the sparse interface) and the state set of its last solve.
struct Resume<T> {
    answer: Option<Arc<T>>,
    states: Option<Vec<ContactState>>,
}

/// A solver's last answer (`last`) and the state set of its last solve,
/// kept as a [`WarmStart`].
pub(super) fn keep_start<T: Send + Sync + 'static>(last: &Mutex<Option<Arc<T>>>, states: &LastStates) -> WarmStart {
    let answer = last.lock().ok().and_then(|l| l.clone());
    WarmStart(Some(Arc::new(Resume { answer, states: states.get() })))
}

/// Gives back what [`keep_start`] kept of a solver of the same kind (any
/// other start is passed over).
pub(super) fn give_start<T: Send + Sync + 'static>(
    start: &WarmStart,
    last: &Mutex<Option<Arc<T>>>,
    states: &LastStates,
) {
    let Some(kept) = start.0.as_ref().and_then(|s| s.downcast_ref::<Resume<T>>()) else {
        return;
    };
    if let Ok(mut l) = last.lock() {
        *l = kept.answer.clone();
    }
    states.set(kept.states.clone());
}

/// Where a part's S is applied.
pub enum Source {
    /// On this rank, through this factor.
    Local(SharedSolve),
    /// On the part's own MPI rank: part number `i`, through [`Remote`].
    Remote(usize),
}

/// The parts of other MPI ranks: their S applied where their factors are.
/// `send` gives each remote part its columns and returns at once; `receive`
/// waits for `S d` of every part sent, in any order. Every call of one is
/// followed by one of the other.
pub trait Remote {
    fn send(&self, work: Vec<(usize, Vec<f64>)>, k: usize);
    fn receive(&self) -> Vec<(usize, Vec<f64>)>;
}

/// A part as the interface sees it.
pub struct AppliedPart {
    pub source: Source,
    /// The diagonal blocks of its K_cc (row-major nd x nd per interface node).
    pub diag: Vec<f64>,
    /// The unknowns of each interface DOF, in local axes and the face basis.
    pub terms: Vec<Terms>,
    /// Frame of each interface node.
    pub frames: Vec<Frame>,
    /// Transformed face edges.
    pub edges: Vec<[usize; 3]>,
    /// Condensed loads, one per case (global axes, nodal basis).
    pub g: Vec<Vec<f64>>,
}

/// A slipping pair's free tangential row `i`, whose equation is the friction
/// law's (see [`Relation`](super::Relation)):
/// `(K x - b)_i + force + coupling (K x - b)_n + sum_c spring_c x_c = 0`.
struct SlipRow {
    row: usize,
    normal: Option<usize>,
    coupling: f64,
    springs: Vec<(usize, f64)>,
    force: f64,
}

/// `J x` from `K x` (`full`): each slipping row takes in its normal row
/// and its springs.
fn slip_rows_of(slip_rows: &[SlipRow], full: &mut [f64], x: &[f64]) {
    for s in slip_rows {
        let mut v = full[s.row];
        if let Some(rn) = s.normal {
            v += s.coupling * full[rn];
        }
        v += s.springs.iter().map(|&(c, k)| k * x[c]).sum::<f64>();
        full[s.row] = v;
    }
}

/// The unknowns of one solve, every mean then the free columns of `fr`,
/// against the full `[m; r]`.
struct Columns<'f> {
    /// The means, and every unknown (means and relative displacements).
    nm: usize,
    n: usize,
    fr: &'f Freedom,
}

impl Columns<'_> {
    /// `[m; r0-free r]` over every unknown from the solve's unknowns `v`
    /// (the relative part `sum_a v_a col_a`).
    fn expand(&self, v: &[f64]) -> Vec<f64> {
        let nm = self.nm;
        let mut full = vec![0.0; self.n];
        full[..nm].copy_from_slice(&v[..nm]);
        for (a, col) in self.fr.cols.iter().enumerate() {
            for &(i, zi) in col {
                full[nm + i] += zi * v[nm + a];
            }
        }
        full
    }

    /// The solve's unknowns' share of `full`: the means, and each free
    /// column's projection.
    fn restrict(&self, full: &[f64]) -> Vec<f64> {
        let nm = self.nm;
        let mut v = full[..nm].to_vec();
        v.extend(self.fr.cols.iter().map(|col| col.iter().map(|&(i, zi)| zi * full[nm + i]).sum::<f64>()));
        v
    }

    /// Adds the junctions' springs on the solve's unknowns `v` to `out`,
    /// and their implicit pressures' lift at `full` (`K x - b` or `K dx`
    /// over every unknown).
    fn springs(&self, out: &mut [f64], v: &[f64], full: &[f64]) {
        let nm = self.nm;
        for jb in &self.fr.junctions {
            let lifted = jb.lifted(|i| full[nm + i], &v[nm..]);
            for (a, fa) in jb.cols.clone().enumerate() {
                out[nm + fa] += jb.cols.clone().enumerate().map(|(c, fc)| jb.kz[(a, c)] * v[nm + fc]).sum::<f64>()
                    + lifted.as_ref().map_or(0.0, |l| l[a]);
            }
        }
    }
}

/// The coarse level of one solve: `Φ` and `J Φ` on its unknowns, and
/// `Φ^T J Φ` factorised.
struct Coarse {
    phi: Mat<f64>,
    j_phi: Mat<f64>,
    lu: faer::linalg::solvers::PartialPivLu<f64>,
}

impl Coarse {
    /// `c = (Φ^T J Φ)^-1 Φ^T v`: the residual `v - J Φ c` left for the
    /// fine level, and the coarse correction `Φ c`.
    fn correct(&self, v: &[f64]) -> (Vec<f64>, Mat<f64>) {
        let vm = Mat::<f64>::from_fn(v.len(), 1, |i, _| v[i]);
        let c = self.lu.solve(self.phi.transpose() * &vm);
        let jc = &self.j_phi * &c;
        let y = &self.phi * &c;
        ((0..v.len()).map(|i| v[i] - jc[(i, 0)]).collect(), y)
    }
}

/// Which block of the preconditioner an unknown is in, and where.
#[derive(Clone, Copy)]
struct Place {
    block: usize,
    at: usize,
}

/// The interface system, applied; see the module header.
pub struct Iterative<'a> {
    nd: usize,
    nm: usize,
    nr: usize,
    parts: Vec<AppliedPart>,
    remote: Option<&'a dyn Remote>,
    /// Right-hand sides over `[m; r]` per case, and of the prescribed values at ramp 1.
    b: Vec<Vec<f64>>,
    b_fixed: Vec<f64>,
    /// Diagonal blocks (row-major) and the unknowns of each.
    blocks: Vec<(Vec<usize>, Vec<f64>)>,
    place: Vec<Place>,
    threads: usize,
    /// The coarse space: `Φ` (orthonormal columns over `[m; r]`, zero on
    /// r) and `K Φ`.
    phi: Vec<Vec<f64>>,
    k_phi: Vec<Vec<f64>>,
    /// The state set of the last solve.
    last_states: LastStates,
    /// The last solution, where the next solve starts.
    last: Mutex<Option<Arc<Vec<f64>>>>,
    /// GMRES iterations of every solve so far.
    iterations: Mutex<Vec<usize>>,
    /// The factor from the preconditioner's diagonal to the stiffness the
    /// friction law is linearised with, once measured ([`stiffness`]).
    alpha: Mutex<Option<f64>>,
}

impl<'a> Iterative<'a> {
    /// The iterative interface of the `parts` laid out by `layout`: the
    /// parts condensed for it (their S applied here through `solve`, or on
    /// their own rank through `remote`), the preconditioner's groups (each
    /// pair and join node) and the coarse space of the parts' rigid motions
    /// `rigid`.
    pub(super) fn build(
        model: &Model,
        layout: &Layout,
        parts: &[OperatorRef],
        rigid: &[PartModes],
        remote: Option<&'a dyn Remote>,
        threads: usize,
    ) -> Iterative<'a> {
        let applied = (parts.iter().enumerate().zip(&layout.parts))
            .filter_map(|((i, p), map)| {
                let SchurRef::Applied { diag, solve } = p.s else { return None };
                (p.nc > 0).then(|| AppliedPart {
                    source: solve.map_or(Source::Remote(i), |s| Source::Local(s.clone())),
                    diag: diag.to_vec(),
                    terms: layout.terms_of(map),
                    frames: layout.frames_of(map),
                    edges: map.edges.clone(),
                    g: p.g.to_vec(),
                })
            })
            .collect();
        let coarse = coarse_space(model, layout, parts, rigid);
        Iterative::new(model.nd, layout.nm, layout.nr, applied, layout.groups(), coarse, remote, threads)
    }

    /// Sets up the right-hand sides (one application of S per part, for
    /// the prescribed values) and the preconditioner's blocks; `groups`
    /// lists the unknowns of each pair and join node.
    /// `coarse`: the coarse space's columns over `[m; r]` (nonzero on means only).
    /// `remote` applies the parts of other MPI ranks; `threads` apply this
    /// rank's parts side by side.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        nd: usize,
        nm: usize,
        nr: usize,
        parts: Vec<AppliedPart>,
        groups: Vec<Vec<Var>>,
        coarse: Vec<Vec<f64>>,
        remote: Option<&'a dyn Remote>,
        threads: usize,
    ) -> Iterative<'a> {
        let n = nm + nr;
        // 1. the right-hand sides, one application of S per part
        let b = loads(&parts, nm, n);
        let mut it = Iterative {
            nd,
            nm,
            nr,
            parts,
            remote,
            b,
            b_fixed: vec![0.0; n],
            blocks: Vec::new(),
            place: vec![Place { block: usize::MAX, at: 0 }; n],
            threads,
            phi: orthonormal(coarse),
            k_phi: Vec::new(),
            last_states: LastStates::default(),
            last: Mutex::new(None),
            iterations: Mutex::new(Vec::new()),
            alpha: Mutex::new(None),
        };
        // 2. -K w0: the prescribed values at ramp 1
        if it.parts.iter().any(|p| p.terms.iter().any(|t| t.constant != 0.0)) {
            let kw0 = it.apply_with(&vec![0.0; n], 1.0);
            it.b_fixed = kw0.iter().map(|v| -v).collect();
        }
        // 3. K Φ, once
        if !it.phi.is_empty() {
            let cols: Vec<&[f64]> = it.phi.iter().map(|c| c.as_slice()).collect();
            it.k_phi = it.apply_many(&cols, 0.0);
        }
        // 4. the preconditioner's blocks
        for (bi, vars) in groups.iter().enumerate() {
            let members: Vec<usize> = vars.iter().map(|&v| index(v, nm)).collect();
            for (at, &u) in members.iter().enumerate() {
                it.place[u] = Place { block: bi, at };
            }
            let k = members.len();
            it.blocks.push((members, vec![0.0; k * k]));
        }
        it.fill_blocks();
        it
    }

    /// Adds every part's diagonal blocks `F D F^T`, turned into the
    /// unknowns by its terms, into the preconditioner's blocks.
    fn fill_blocks(&mut self) {
        let nd = self.nd;
        for part in &self.parts {
            for (q, f) in part.frames.iter().enumerate() {
                let d = &part.diag[q * nd * nd..(q + 1) * nd * nd];
                // F D F^T
                let mut local = [[0.0; 3]; 3];
                for a in 0..nd {
                    for c in 0..nd {
                        local[a][c] =
                            (0..nd).map(|i| f[a][i] * (0..nd).map(|j| d[i * nd + j] * f[c][j]).sum::<f64>()).sum();
                    }
                }
                for a in 0..nd {
                    let ta = &part.terms[q * nd + a];
                    for c in 0..nd {
                        let tc = &part.terms[q * nd + c];
                        for &(vi, ci) in &ta.vars[..ta.n] {
                            for &(vj, cj) in &tc.vars[..tc.n] {
                                let (pi, pj) = (self.place[index(vi, self.nm)], self.place[index(vj, self.nm)]);
                                if pi.block == pj.block && pi.block != usize::MAX {
                                    let (members, m) = &mut self.blocks[pi.block];
                                    let k = members.len();
                                    m[pi.at * k + pj.at] += ci * cj * local[a][c];
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    /// The position of the unknown `v` in `[m; r]`.
    fn unknown(&self, v: Var) -> usize {
        index(v, self.nm)
    }

    /// `K x`.
    fn apply(&self, x: &[f64]) -> Vec<f64> {
        self.apply_with(x, 0.0)
    }

    /// `K (x + ramp w0)`.
    fn apply_with(&self, x: &[f64], ramp: f64) -> Vec<f64> {
        self.apply_many(&[x], ramp).pop().expect("one column")
    }

    /// `K (x + ramp w0)` for every column `x` of `xs`, each part's S
    /// applied to all of them at once; the parts side by side in the
    /// machine's threads.
    fn apply_many(&self, xs: &[&[f64]], ramp: f64) -> Vec<Vec<f64>> {
        let n = self.nm + self.nr;
        let (nm, nd, k) = (self.nm, self.nd, xs.len());
        let columns = |part: &AppliedPart| -> Vec<f64> {
            xs.iter().flat_map(|x| part.displacements_of(x, ramp, nm, nd)).collect()
        };
        // `K` of S d, column by column
        let gather = |part: &AppliedPart, sd: &[f64]| -> Vec<Vec<f64>> {
            let nc = part.terms.len();
            (0..k)
                .map(|c| {
                    let y = part.to_unknowns(sd[c * nc..(c + 1) * nc].to_vec());
                    let mut out = vec![0.0; n];
                    for_each_load(&y, &part.terms, |v, val| match v {
                        Var::M(i) => out[i] += val,
                        Var::R(i) => out[nm + i] += val,
                    });
                    out
                })
                .collect()
        };
        // the other ranks' parts work while this rank does its own
        let remote_parts: Vec<(usize, usize)> =
            (self.parts.iter().enumerate()).filter_map(|(at, p)| p.remote().map(|i| (i, at))).collect();
        if let (Some(remote), false) = (self.remote, remote_parts.is_empty()) {
            remote.send(remote_parts.iter().map(|&(i, at)| (i, columns(&self.parts[at]))).collect(), k);
        }
        let local: Vec<(&AppliedPart, &SharedSolve)> =
            (self.parts.iter()).filter_map(|p| p.local().map(|solve| (p, solve))).collect();
        // each thread sums its parts' contributions
        let sum = |ps: &[(&AppliedPart, &SharedSolve)]| -> Vec<Vec<f64>> {
            let mut acc = vec![vec![0.0; n]; k];
            for (part, solve) in ps {
                add_columns(&mut acc, gather(part, &solve.apply(&columns(part), k)));
            }
            acc
        };
        // the parts in one run per thread
        let mut partials = in_runs(&local, self.threads, sum).into_iter();
        let mut out = partials.next().unwrap_or_else(|| vec![vec![0.0; n]; k]);
        for p in partials {
            add_columns(&mut out, p);
        }
        if let (Some(remote), false) = (self.remote, remote_parts.is_empty()) {
            for (i, sd) in remote.receive() {
                let at = remote_parts.iter().find(|r| r.0 == i).expect("a part that was sent").1;
                add_columns(&mut out, gather(&self.parts[at], &sd));
            }
        }
        out
    }

    /// Solves one set of relations, given by the free directions `fr` of
    /// the relative displacements, under the load factors `lambda`; `None`
    /// when GMRES does not get below [`USABLE`] (a singular system: a body
    /// sliding freely). The unknowns are every mean, then the free columns.
    fn solve_gmres(&self, fr: &Freedom, states: &[ContactState], lambda: &[f64], accuracy: Accuracy) -> Option<Answer> {
        let cols = Columns { nm: self.nm, n: self.nm + self.nr, fr };
        let mut b = combine(&self.b, &self.b_fixed, lambda);
        fr.push(&mut b[self.nm..]);
        let loose = self.last_states.loose(states) && accuracy.may_be_loose();
        let slip_rows: Vec<SlipRow> = (fr.slips.iter())
            .map(|s| SlipRow {
                row: self.nm + s.row,
                normal: s.normal.map(|r| self.nm + r),
                coupling: s.coupling,
                springs: s.springs.iter().map(|&(c, k)| (self.nm + c, k)).collect(),
                force: s.force,
            })
            .collect();
        let (x0, y0) = self.start(fr, |v| cols.restrict(v));
        let rhs = self.start_residual(&cols, &slip_rows, &b, &x0, &y0);
        let j = |v: &[f64]| -> Vec<f64> {
            let dx = cols.expand(v);
            let mut full = self.apply(&dx);
            slip_rows_of(&slip_rows, &mut full, &dx);
            let mut out = cols.restrict(&full);
            cols.springs(&mut out, v, &full);
            out
        };
        let precondition = self.preconditioner(fr);
        let coarse = self.coarse(self.nm + fr.cols.len(), &slip_rows, |v| cols.restrict(v));
        let m = |v: &[f64]| -> Vec<f64> {
            let (r1, y) = match &coarse {
                Some(c) => {
                    let (r1, y) = c.correct(v);
                    (r1, Some(y))
                }
                None => (v.to_vec(), None),
            };
            let mut out = precondition(&r1);
            if let Some(y) = y {
                for (i, z) in out.iter_mut().enumerate() {
                    *z += y[(i, 0)];
                }
            }
            out
        };
        let scale = length(&b).max(length(&rhs)).max(f64::MIN_POSITIVE);
        let (tolerance, looser) = tolerance(loose, accuracy, scale);
        let (dx, conv) = gmres::solve(j, m, &rhs, target(tolerance, scale), RESTART, MAX_ITERATIONS);
        if let Ok(mut its) = self.iterations.lock() {
            its.push(conv.iterations + 2); // and the applications for e0 and the forces
        }
        let residual = conv.residual / scale;
        if !conv.converged && !(residual <= USABLE) {
            return None;
        }
        Some(self.answer(x0, &cols.expand(&dx), &b, (residual, conv.residual), (loose, looser && !loose)))
    }

    /// The right-hand side of GMRES: minus the residual of the solve's
    /// equations at its start `x0` (`y0`: the free columns' coordinates
    /// there), with the slipping rows' forces and the junctions' springs.
    fn start_residual(&self, cols: &Columns, slip_rows: &[SlipRow], b: &[f64], x0: &[f64], y0: &[f64]) -> Vec<f64> {
        let mut e0 = self.apply(x0);
        for (e, bi) in e0.iter_mut().zip(b) {
            *e -= bi;
        }
        slip_rows_of(slip_rows, &mut e0, x0);
        for s in slip_rows {
            e0[s.row] += s.force;
        }
        let full = e0;
        let mut e0 = cols.restrict(&full);
        cols.springs(&mut e0, y0, &full);
        let nm = self.nm;
        for jb in &cols.fr.junctions {
            for (a, fa) in jb.cols.clone().enumerate() {
                e0[nm + fa] += jb.fz[a];
            }
        }
        e0.iter().map(|v| -v).collect()
    }

    /// The answer `x = x0 + dx` (`dx` over every unknown), remembered as
    /// the next solve's start, with `K x - b` on the relative rows.
    fn answer(
        &self,
        x0: Vec<f64>,
        dx: &[f64],
        b: &[f64],
        (residual, accuracy): (f64, f64),
        (loose, inexact): (bool, bool),
    ) -> Answer {
        let (nm, nr) = (self.nm, self.nr);
        let mut x = x0;
        for (xi, d) in x.iter_mut().zip(dx) {
            *xi += d;
        }
        let kx = self.apply(&x);
        let residual_r = (0..nr).map(|r| kx[nm + r] - b[nm + r]).collect();
        let (m, r) = (x[..nm].to_vec(), x[nm..].to_vec());
        if let Ok(mut last) = self.last.lock() {
            *last = Some(Arc::new(x));
        }
        Answer { m, r, residual_r, residual, accuracy, loose, inexact }
    }

    /// Where GMRES starts: the last answer, its relative displacements
    /// moved onto `r0 + span(cols)`; and the free columns' coordinates there.
    fn start(&self, fr: &Freedom, restrict: impl Fn(&[f64]) -> Vec<f64>) -> (Vec<f64>, Vec<f64>) {
        let (nm, nr) = (self.nm, self.nr);
        let n = nm + nr;
        let last = self
            .last
            .lock()
            .ok()
            .and_then(|l| l.clone())
            .filter(|l| l.len() == n)
            .map_or_else(|| vec![0.0; n], |l| l.to_vec());
        let mut shifted = vec![0.0; n];
        for i in 0..nr {
            shifted[nm + i] = last[nm + i] - fr.r0[i];
        }
        let y0 = restrict(&shifted);
        let mut x0 = last;
        x0[nm..].copy_from_slice(&fr.r0);
        for (a, col) in fr.cols.iter().enumerate() {
            for &(i, zi) in col {
                x0[nm + i] += zi * y0[nm + a];
            }
        }
        (x0, y0)
    }

    /// The coarse level on the `nu` unknowns (Φ is zero on r: its rows are
    /// the means'): Φ and J Φ, Φ^T J Φ factorised (none without a coarse space).
    fn coarse(&self, nu: usize, slip_rows: &[SlipRow], restrict: impl Fn(&[f64]) -> Vec<f64>) -> Option<Coarse> {
        if self.phi.is_empty() {
            return None;
        }
        let nm = self.nm;
        let phi = Mat::<f64>::from_fn(nu, self.phi.len(), |i, c| if i < nm { self.phi[c][i] } else { 0.0 });
        let cols: Vec<Vec<f64>> = (self.k_phi.iter().zip(&self.phi))
            .map(|(kp, p)| {
                let mut full = kp.clone();
                slip_rows_of(slip_rows, &mut full, p);
                restrict(&full)
            })
            .collect();
        let j_phi = Mat::<f64>::from_fn(nu, cols.len(), |i, c| cols[c][i]);
        let lu = (phi.transpose() * &j_phi).partial_piv_lu();
        Some(Coarse { phi, j_phi, lu })
    }

    /// `M^-1` on the unknowns of a solve (every mean, then the free columns
    /// `fr.cols`): each block `P^T B P` over the unknowns it touches, with
    /// the slipping rows as in [`Self::solve_gmres`] and the junctions'
    /// springs, factorised once per solve.
    fn preconditioner(&self, fr: &Freedom) -> impl Fn(&[f64]) -> Vec<f64> + '_ {
        // 1. the unknowns each block touches
        let touching = self.touching(fr);
        // 2. what couples them beyond the blocks: slipping rows, junctions
        let couplings = Couplings::of(fr, self.nm);
        // 3. each block over its unknowns, factorised
        let factors: Vec<BlockFactor> = (self.blocks.iter().zip(&touching))
            .map(|((members, m), us)| couplings.factor((members, m), us, fr))
            .collect();
        // 4. M^-1: the blocks solved, a non-finite value left as it came
        move |v: &[f64]| {
            let mut out = v.to_vec();
            for (unknowns, lu) in &factors {
                let Some(lu) = lu else { continue };
                let rhs = Mat::<f64>::from_fn(unknowns.len(), 1, |i, _| v[unknowns[i]]);
                let z = lu.solve(&rhs);
                for (i, &u) in unknowns.iter().enumerate() {
                    let zi = z[(i, 0)];
                    out[u] = if zi.is_finite() { zi } else { v[u] };
                }
            }
            out
        }
    }

    /// The unknowns of each block, with their entries over its members:
    /// the means in it, and the free columns whose first row is in it.
    fn touching(&self, fr: &Freedom) -> Vec<Vec<Entries>> {
        let nm = self.nm;
        let mut touching: Vec<Vec<Entries>> = vec![Vec::new(); self.blocks.len()];
        for i in 0..nm {
            let p = self.place[i];
            if p.block != usize::MAX {
                touching[p.block].push((i, vec![(p.at, 1.0)]));
            }
        }
        for (a, col) in fr.cols.iter().enumerate() {
            let p = self.place[nm + col[0].0];
            touching[p.block].push((nm + a, col.iter().map(|&(i, zi)| (self.place[nm + i].at, zi)).collect()));
        }
        touching
    }
}

/// A block's unknowns and the LU factors of the block over them (None
/// when it touches none).
type BlockFactor = (Vec<usize>, Option<faer::linalg::solvers::PartialPivLu<f64>>);

/// What couples a solve's unknowns beyond the parts' blocks, by unknown:
/// the unknown of each row that is a column alone, the slipping rows, and
/// the junctions' columns (junction, column in it).
struct Couplings<'f> {
    nm: usize,
    unknown_of_row: HashMap<usize, usize>,
    slip_of: HashMap<usize, &'f super::SlipRow>,
    junction_of: HashMap<usize, (usize, usize)>,
}

impl<'f> Couplings<'f> {
    fn of(fr: &'f Freedom, nm: usize) -> Couplings<'f> {
        let unknown_of_row = (fr.cols.iter().enumerate())
            .filter_map(|(a, col)| match col.as_slice() {
                [(i, _)] => Some((*i, nm + a)),
                _ => None,
            })
            .collect();
        let slip_of = fr.slips.iter().map(|s| (nm + fr.pos[s.row], s)).collect();
        let mut junction_of = HashMap::new();
        for (bi, jb) in fr.junctions.iter().enumerate() {
            for (a, fa) in jb.cols.clone().enumerate() {
                junction_of.insert(nm + fa, (bi, a));
            }
        }
        Couplings { nm, unknown_of_row, slip_of, junction_of }
    }

    /// Block `(members, m)` as `P^T B P` over the unknowns `us` it
    /// touches, with the slipping rows' coupling and springs and the
    /// junctions' stiffness added, factorised.
    fn factor(&self, (members, m): (&[usize], &[f64]), us: &[Entries], fr: &Freedom) -> BlockFactor {
        let k = members.len();
        // B P: the block times each unknown's entries
        let bp: Vec<Vec<f64>> = us
            .iter()
            .map(|(_, e)| (0..k).map(|row| e.iter().map(|&(at, z)| m[row * k + at] * z).sum()).collect())
            .collect();
        let mut local =
            Mat::<f64>::from_fn(us.len(), us.len(), |i, j| us[i].1.iter().map(|&(at, z)| z * bp[j][at]).sum());
        for (li, (u, _)) in us.iter().enumerate() {
            if let Some(s) = self.slip_of.get(u) {
                if let Some(pn) = s.normal.and_then(|rn| members.iter().position(|&x| x == self.nm + rn)) {
                    for (lj, bpj) in bp.iter().enumerate() {
                        local[(li, lj)] += s.coupling * bpj[pn];
                    }
                }
                for &(c, sp) in &s.springs {
                    let uc = self.unknown_of_row.get(&c);
                    if let Some(lj) = us.iter().position(|(v, _)| Some(v) == uc) {
                        local[(li, lj)] += sp;
                    }
                }
            }
            if let Some(&(bi, a)) = self.junction_of.get(u) {
                for (lj, (v, _)) in us.iter().enumerate() {
                    if let Some(&(bj, c)) = self.junction_of.get(v) {
                        if bi == bj {
                            local[(li, lj)] += fr.junctions[bi].kz[(a, c)];
                        }
                    }
                }
            }
        }
        let unknowns: Vec<usize> = us.iter().map(|(u, _)| *u).collect();
        let lu = (!unknowns.is_empty()).then(|| local.partial_piv_lu());
        (unknowns, lu)
    }
}

impl Solver for Iterative<'_> {
    fn solve(&self, fr: &Freedom, states: &[ContactState], lambda: &[f64], accuracy: Accuracy) -> Option<Answer> {
        self.solve_gmres(fr, states, lambda, accuracy)
    }

    /// The stiffness the friction law is linearised with at relative
    /// displacement `r`: the preconditioner's diagonal scaled down to W's
    /// ([`stiffness`]).
    fn diagonal(&self, r: usize) -> f64 {
        self.pair_stiffness(&[r])[0]
    }

    fn prepare_diagonal(&self, rs: &[usize]) {
        self.pair_stiffness(rs);
    }

    fn counts(&self) -> Vec<usize> {
        self.iterations.lock().map(|v| v.clone()).unwrap_or_default()
    }

    fn warm_start(&self) -> WarmStart {
        keep_start(&self.last, &self.last_states)
    }

    fn start_from(&self, start: &WarmStart) {
        give_start(start, &self.last, &self.last_states);
    }
}

/// The right-hand side of each load case over `[m; r]` (`n` unknowns, the
/// first `nm` means): every part's `g` turned into the unknowns.
fn loads(parts: &[AppliedPart], nm: usize, n: usize) -> Vec<Vec<f64>> {
    let cases = parts.iter().map(|p| p.g.len()).max().unwrap_or(1);
    let mut b = vec![vec![0.0; n]; cases];
    for part in parts {
        for (case, g) in part.g.iter().enumerate() {
            let y = part.to_unknowns(g.clone());
            for_each_load(&y, &part.terms, |v, x| b[case][index(v, nm)] += x);
        }
    }
    b
}

/// The position of an unknown in `[m; r]`, the first `nm` means.
fn index(v: Var, nm: usize) -> usize {
    match v {
        Var::M(i) => i,
        Var::R(i) => nm + i,
    }
}

/// The coarse space: each applied part's rigid motions on the means,
/// shared between the interface nodes that have them (half each on a lone
/// pair, evenly at a junction or a join), one column per part and motion
/// over `[m; r]`.
fn coarse_space(model: &Model, layout: &Layout, parts: &[OperatorRef], rigid: &[PartModes]) -> Vec<Vec<f64>> {
    let (nd, n) = (model.nd, layout.nm + layout.nr);
    let mut coarse = Vec::new();
    for ((p, map), modes) in parts.iter().zip(&layout.parts).zip(rigid) {
        if !(matches!(p.s, SchurRef::Applied { .. }) && p.nc > 0) {
            continue;
        }
        for k in 0..n_modes(model.analysis) {
            let mut col = vec![0.0; n];
            for (q, &node) in p.part.interface.iter().enumerate() {
                for a in 0..nd {
                    let t = &map.terms[q * nd + a];
                    for &(v, coef) in &t.vars[..t.n] {
                        if let Var::M(i) = v {
                            col[i] += coef * map.shares[q] * modes.modes.along(model.coords[node], map.frames[q][a])[k];
                        }
                    }
                }
            }
            coarse.push(col);
        }
    }
    coarse
}

/// An unknown of a block and its entries over the block's members.
type Entries = (usize, Vec<(usize, f64)>);

impl AppliedPart {
    /// Its number, where it is on another rank (which applies it).
    fn remote(&self) -> Option<usize> {
        match self.source {
            Source::Remote(i) => Some(i),
            Source::Local(_) => None,
        }
    }

    /// Its interior factor, where it is on this rank.
    fn local(&self) -> Option<&SharedSolve> {
        match &self.source {
            Source::Local(solve) => Some(solve),
            Source::Remote(_) => None,
        }
    }

    /// The part's interface displacements (global axes, nodal basis) for
    /// the unknowns `x` and the prescribed values at `ramp`.
    fn displacements_of(&self, x: &[f64], ramp: f64, nm: usize, nd: usize) -> Vec<f64> {
        coords::part_displacements(&self.terms, &self.frames, &self.edges, nd, ramp, |v| match v {
            Var::M(i) => x[i],
            Var::R(i) => x[nm + i],
        })
    }

    /// A force on the part's interface (global axes, nodal basis) in the
    /// face basis and local axes: `T Q^T y`.
    fn to_unknowns(&self, mut y: Vec<f64>) -> Vec<f64> {
        let nd = self.terms.len() / self.frames.len().max(1);
        basis::transform_load(&mut y, nd, &self.edges);
        coords::rotate_vector(&mut y, nd, &self.frames);
        y
    }
}

/// The columns of `cols`, orthonormalised by modified Gram-Schmidt (twice,
/// for orthogonality to round-off); a column that depends on the earlier
/// ones (to 1e-8 of its length) is dropped.
fn orthonormal(cols: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let mut out: Vec<Vec<f64>> = Vec::with_capacity(cols.len());
    for mut c in cols {
        let before = c.iter().map(|x| x * x).sum::<f64>().sqrt();
        if before == 0.0 {
            continue;
        }
        for _ in 0..2 {
            for q in &out {
                let d: f64 = q.iter().zip(&c).map(|(a, b)| a * b).sum();
                for (x, qi) in c.iter_mut().zip(q) {
                    *x -= d * qi;
                }
            }
        }
        let after = c.iter().map(|x| x * x).sum::<f64>().sqrt();
        if after > 1e-8 * before {
            out.push(c.iter().map(|x| x / after).collect());
        }
    }
    out
}

/// `acc[c] += cols[c]` for every column.
fn add_columns(acc: &mut [Vec<f64>], cols: Vec<Vec<f64>>) {
    for (a, y) in acc.iter_mut().zip(cols) {
        for (o, v) in a.iter_mut().zip(y) {
            *o += v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{tolerance, Accuracy, LOOSE_TOLERANCE, TOLERANCE};

    /// A change of states is solved loosely, unless the iteration asks
    /// for it tight (late in a step); a Newton step to a fraction of the
    /// law's residual, within the loose and the tight tolerance.
    #[test]
    fn a_solve_is_loose_only_where_the_states_changed_and_it_may_be() {
        let scale = 2.0;
        let tight = (TOLERANCE * scale, false);
        assert_eq!(tolerance(true, Accuracy::Answer, scale), (LOOSE_TOLERANCE * scale, true));
        assert_eq!(tolerance(true, Accuracy::Tight, scale), tight);
        assert_eq!(tolerance(false, Accuracy::Tight, scale), tight);
        assert_eq!(tolerance(false, Accuracy::Answer, scale), tight);
        assert_eq!(tolerance(false, Accuracy::Step(1.0), scale), (LOOSE_TOLERANCE * scale, true));
        assert_eq!(tolerance(false, Accuracy::Step(0.0), scale), tight);
        assert!(!Accuracy::Tight.may_be_loose() && Accuracy::Answer.may_be_loose());
    }
}
