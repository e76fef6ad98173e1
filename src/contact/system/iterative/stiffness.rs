//! The stiffness a slipping pair's friction law is linearised with
//! ([`Solver::diagonal`](super::Solver::diagonal)): the scale `c` that
//! turns its slip into a force in `ξ = τ + c s` and in the spring that
//! holds its slip across its direction. Any positive `c` has the same
//! answers, but not the same path to them. The dense and the sparse
//! interface take W's diagonal, the interface's stiffness at that
//! relative displacement with every mean free. S is never formed here,
//! and the preconditioner's blocks (the parts' K_cc, without the
//! quadratic faces' basis) are stiffer than W by more than they need be:
//! on the corpus cavern in tet10 (tests/corpus/cavern3d.toml) 3.4 times
//! W's diagonal at the median slipping pair (1.9 to 5.7), and its rigid
//! joints, which the dense and the sparse interface end in 6 iterations,
//! went through 100 state sets without converging on this interface.
//!
//! So `c` is the preconditioner's diagonal times one factor α, measured
//! once per run on a sample of [`SAMPLE`] pairs among the first asked
//! for: each one's block of `K` (its means and relative displacements)
//! applied exactly, through the parts that hold it, and its own means
//! eliminated,
//!
//! ```text
//! c_r = K_rr - K_rm K_mm^-1 K_mr        (m: the pair's means)
//! ```
//!
//! (within 4 % of W's diagonal at the cavern's median pair), and α the
//! largest `c_r` over the preconditioner's diagonal: `c` comes down to
//! W's at the sampled pair where the two are nearest and stays above it
//! at the other sampled pairs, as the preconditioner's diagonal was at
//! every pair. Measured
//! (`--interface iterative`, rigid joints): the cavern converges in 6,
//! the dense interface's states pair by pair; the four-set tunnel of the
//! corpus in 29 where it took 22 (the dense interface 23), the same
//! states. With α the median instead, `c` below W at half the pairs, the
//! cavern took 10 and the tunnel did not converge in 100; with every
//! pair's own `c_r`, an interface application per pair and axis, the
//! 458 slipping pairs of the regression suite's hex block on block took
//! 66 s where they take 17; the sample costs six columns a pair, once.

use std::collections::{BTreeSet, HashMap};

use nalgebra::{DMatrix, DVector};

use super::Iterative;
use crate::contact::system::coords::{self, for_each_load};

/// Pairs whose `c_r` is formed to measure α (module header).
const SAMPLE: usize = 8;

impl Iterative<'_> {
    /// `c` at each relative displacement of `rs`: the preconditioner's
    /// diagonal times α, which the first call that can measures on pairs
    /// of its `rs` (module header; 1 until then).
    pub(super) fn pair_stiffness(&self, rs: &[usize]) -> Vec<f64> {
        let mut alpha = self.alpha.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if alpha.is_none() && !rs.is_empty() {
            *alpha = self.measure_alpha(rs);
        }
        let a = alpha.unwrap_or(1.0);
        rs.iter().map(|&r| a * self.block_diagonal(self.nm + r)).collect()
    }

    /// α: the largest `c_r` over the preconditioner's diagonal, on the
    /// blocks of at most [`SAMPLE`] pairs spread over `rs`'s; none where
    /// no `c_r` could be formed.
    fn measure_alpha(&self, rs: &[usize]) -> Option<f64> {
        let all: Vec<usize> =
            rs.iter().map(|&r| self.place[self.nm + r].block).collect::<BTreeSet<_>>().into_iter().collect();
        let step = all.len().div_ceil(SAMPLE).max(1);
        let blocks: BTreeSet<usize> = all.into_iter().step_by(step).collect();
        let k = self.block_entries(&blocks);
        (blocks.iter())
            .flat_map(|&b| self.eliminate_means(b, &k))
            .map(|(r, c)| c / self.block_diagonal(self.nm + r))
            .filter(|x| x.is_finite() && *x > 0.0)
            .reduce(f64::max)
    }

    /// The preconditioner's diagonal at unknown `u`.
    pub(super) fn block_diagonal(&self, u: usize) -> f64 {
        let p = self.place[u];
        let (members, m) = &self.blocks[p.block];
        m[p.at * members.len() + p.at]
    }

    /// `c_r` of every relative displacement of block `b`, from its entries
    /// `k` ((row, column) of K over `[m; r]`); none where its means cannot
    /// be eliminated.
    fn eliminate_means(&self, b: usize, k: &HashMap<(usize, usize), f64>) -> Vec<(usize, f64)> {
        let members = &self.blocks[b].0;
        let entry = |i: usize, j: usize| k.get(&(i, j)).copied().unwrap_or(0.0);
        let means: Vec<usize> = members.iter().copied().filter(|&u| u < self.nm).collect();
        let k_mm = DMatrix::from_fn(means.len(), means.len(), |i, j| entry(means[i], means[j]));
        let lu = (!means.is_empty()).then(|| k_mm.lu());
        (members.iter().copied().filter(|&u| u >= self.nm))
            .filter_map(|u| {
                let k_rr = entry(u, u);
                let lowered = match &lu {
                    None => 0.0,
                    Some(lu) => {
                        let k_mr = DVector::from_iterator(means.len(), means.iter().map(|&m| entry(m, u)));
                        lu.solve(&k_mr).map(|x| x.dot(&k_mr))?
                    }
                };
                let c = k_rr - lowered;
                (c.is_finite() && c > 1e-6 * k_rr).then_some((u - self.nm, c))
            })
            .collect()
    }

    /// K's entries between the members of each block of `blocks`: every
    /// member's unit column applied through the parts that hold it.
    fn block_entries(&self, blocks: &BTreeSet<usize>) -> HashMap<(usize, usize), f64> {
        let block_of: HashMap<usize, usize> =
            blocks.iter().flat_map(|&b| self.blocks[b].0.iter().map(move |&u| (u, b))).collect();
        // each part's unknowns among them, its unit columns and S of them
        let columns: Vec<(usize, Vec<usize>)> =
            (0..self.parts.len()).map(|at| (at, self.held(at, &block_of))).filter(|(_, us)| !us.is_empty()).collect();
        let k = columns.iter().map(|(_, us)| us.len()).max().unwrap_or(0);
        let units = |at: usize, us: &[usize]| -> Vec<f64> {
            let mut d: Vec<f64> = us.iter().flat_map(|&u| self.unit_displacements(at, u)).collect();
            d.resize(self.parts[at].terms.len() * k, 0.0);
            d
        };
        let remote: Vec<(usize, usize, &[usize])> =
            (columns.iter()).filter_map(|(at, us)| self.parts[*at].remote().map(|i| (i, *at, us.as_slice()))).collect();
        if let (Some(r), false) = (self.remote, remote.is_empty()) {
            r.send(remote.iter().map(|&(i, at, us)| (i, units(at, us))).collect(), k);
        }
        let mut out = HashMap::new();
        for (at, us) in &columns {
            if let Some(solve) = self.parts[*at].local() {
                let sd = solve.apply(&units(*at, us), k);
                self.gather_entries(*at, us, &sd, &block_of, &mut out);
            }
        }
        if let (Some(r), false) = (self.remote, remote.is_empty()) {
            for (i, sd) in r.receive() {
                let &(_, at, us) = remote.iter().find(|x| x.0 == i).expect("a part that was sent");
                self.gather_entries(at, us, &sd, &block_of, &mut out);
            }
        }
        out
    }

    /// The unknowns of `block_of` that part `at`'s interface holds, in order.
    fn held(&self, at: usize, block_of: &HashMap<usize, usize>) -> Vec<usize> {
        let us: BTreeSet<usize> = (self.parts[at].terms.iter())
            .flat_map(|t| t.vars[..t.n].iter().map(|&(v, _)| self.unknown(v)))
            .filter(|u| block_of.contains_key(u))
            .collect();
        us.into_iter().collect()
    }

    /// Part `at`'s interface displacements (global axes, nodal basis) of
    /// unknown `u` at one, the others at zero.
    fn unit_displacements(&self, at: usize, u: usize) -> Vec<f64> {
        let part = &self.parts[at];
        coords::part_displacements(&part.terms, &part.frames, &part.edges, self.nd, 0.0, |v| {
            f64::from(u8::from(self.unknown(v) == u))
        })
    }

    /// Adds to `out` the entries of `K e_u` (part `at`'s share, `sd` its
    /// S of the unit columns of `us`) in the rows of `u`'s own block.
    fn gather_entries(
        &self,
        at: usize,
        us: &[usize],
        sd: &[f64],
        block_of: &HashMap<usize, usize>,
        out: &mut HashMap<(usize, usize), f64>,
    ) {
        let part = &self.parts[at];
        let nc = part.terms.len();
        for (c, &u) in us.iter().enumerate() {
            let y = part.to_unknowns(sd[c * nc..(c + 1) * nc].to_vec());
            for_each_load(&y, &part.terms, |v, val| {
                let i = self.unknown(v);
                if block_of.get(&i) == block_of.get(&u) {
                    *out.entry((i, u)).or_insert(0.0) += val;
                }
            });
        }
    }
}
