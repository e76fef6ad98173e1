//! The paper's state iteration (`[solver] rule = "paper"`, §2.3 (6)):
//! start with every pair stuck; solve; judge every pair by eq. 15–17 from its
//! stresses alone, every change at once; repeat until the state set
//! repeats. A slipping pair carries the Mohr–Coulomb shear `c - f sigma_n`
//! of the last iteration along its last slip direction (zero with
//! `slip = "frictionless"`, the paper's own slip), so the iteration also runs
//! until that shear has settled. A state set that comes back after others is
//! a cycle: it is reported, not resolved (the robust rule resolves it).
//! Pairs that opened or slipped in a converged step are judged cracked in
//! the steps after it (f_t = 0, the residual cohesion), as are those open
//! or slipping now. Unlike the robust rule, a pair solved open or slipping
//! earlier in this step is not: the paper's iteration passes through sets
//! that open a whole joint on its way (a joint pulled below its f_t opens
//! at the second solve and closes again), and keeping those cracks would
//! leave it open (tests/contact.rs, the intact joint under a pull).

use super::frame::tangential;
use super::history::History;
use super::iteration::{Next, Rule, Verdict};
use super::law::{judge_paper, ContactState, PairResult};
use super::options::SlipLaw;
use super::outcome::{Stop, Summary};
use super::pair_law::{limit, PairLaw};
use super::system::{InterfaceProblem, InterfaceSolution, Relation};
use crate::fem::vec3::{norm, sub};

/// The paper's rule through one load step.
pub(super) struct Paper<'p> {
    problem: &'p InterfaceProblem<'p>,
    laws: &'p [PairLaw],
}

impl<'p> Paper<'p> {
    pub fn new(problem: &'p InterfaceProblem<'p>, laws: &'p [PairLaw]) -> Paper<'p> {
        Paper { problem, laws }
    }

    /// The friction force on body I of a slipping Coulomb pair.
    fn friction(&self, h: &History, p: usize) -> [f64; 3] {
        if h.states[p] != ContactState::Slip || self.laws[p].slip == SlipLaw::Frictionless {
            return [0.0; 3];
        }
        let t = self.laws[p].strength.shear_limit(h.sigma_n[p], paper_cracked(h, p)) * self.problem.area(p);
        [0.0, t * h.dir[p][1], t * h.dir[p][2]]
    }
}

impl Rule for Paper<'_> {
    /// No: the paper's criteria are not the law the residual measures. They
    /// keep f_t for a pair they find slipping, which the law cracks (the
    /// intact joint of tests/contact.rs slips frictionless under a pull of
    /// about 0.1 below its f_t = 0.3: the law's f_t = 0), and judge a
    /// locked junction pair by its forces as tied whatever they are.
    fn answers_to_the_law(&self) -> bool {
        false
    }

    fn relations(&self, h: &History) -> Vec<Relation> {
        (0..self.laws.len())
            .map(|p| {
                Relation::simple(h.states[p], h.offset[p], self.friction(h, p)).within(limit(
                    &self.laws[p],
                    paper_cracked(h, p),
                    self.problem.area(p),
                ))
            })
            .collect()
    }

    fn judge(&mut self, h: &mut History, solution: &InterfaceSolution, summary: &mut Summary) -> Verdict {
        let n = self.laws.len();
        let r = &solution.pairs;
        let scale_u = solution.rel.iter().map(|v| norm(*v)).fold(0.0, f64::max);
        let scale_s = r.iter().map(|p| p.sigma_n.abs().max(p.tau())).fold(0.0, f64::max);
        let tol_u = 1e-10 * scale_u;

        // a junction pair its loop locks is judged by the forces it would carry tied
        let judged = |p: usize| match solution.as_tied[p] {
            Some(f) => {
                let a = self.problem.area(p);
                PairResult { sigma_n: f[0] / a, tau_t: f[1] / a, tau_b: f[2] / a, ..r[p] }
            }
            None => r[p],
        };
        let next: Vec<ContactState> =
            (0..n).map(|p| judge_paper(&judged(p), &self.laws[p].strength, h.cracked[p])).collect();
        if next != h.states && summary.history.contains(&next) {
            summary.stop = Some(Stop::Cycled);
        }

        // carry the new states: friction directions, offsets; and how far
        // the Coulomb shear of slipping pairs still moves
        let mut shear_moved: f64 = 0.0;
        for p in 0..n {
            let (st, nx) = (h.states[p], next[p]);
            let incr = tangential(sub(solution.rel[p], h.rel_start[p]));
            let cr = paper_cracked(h, p);
            let coulomb = st == ContactState::Slip && self.laws[p].slip == SlipLaw::Coulomb;
            let limit = |sigma_n: f64| self.laws[p].strength.shear_limit(sigma_n, cr);
            if nx == ContactState::Slip {
                // entering slip: friction keeps the direction of the stick shear
                let d = if st == ContactState::Stick || norm(incr) <= tol_u {
                    let t = [0.0, r[p].tau_t, r[p].tau_b];
                    if norm(t) > 0.0 {
                        t
                    } else {
                        h.dir[p]
                    }
                } else {
                    incr
                };
                let l = norm(d);
                if l > 0.0 {
                    let new = [0.0, d[1] / l, d[2] / l];
                    if coulomb {
                        shear_moved = shear_moved.max(norm(sub(new, h.dir[p])) * limit(r[p].sigma_n));
                    }
                    h.dir[p] = new;
                }
                if coulomb {
                    shear_moved = shear_moved.max((limit(r[p].sigma_n) - limit(h.sigma_n[p])).abs());
                }
            }
            if nx == ContactState::Stick && st != ContactState::Stick {
                // stuck again: keep the slip of earlier steps; a re-closing
                // pair touches where it is
                h.offset[p] =
                    if st == ContactState::Open { tangential(solution.rel[p]) } else { tangential(h.rel_start[p]) };
            }
            h.sigma_n[p] = r[p].sigma_n;
        }
        let settled = shear_moved <= 1e-12 * scale_s.max(f64::MIN_POSITIVE);
        Verdict { next: Next::States(next), settled, law: 0.0 }
    }
}

/// Whether pair `p` is judged cracked by the paper rule: in a converged
/// step, or open or slipping now (not the robust rule's in-step cracks).
fn paper_cracked(h: &History, p: usize) -> bool {
    h.cracked[p] || h.states[p] != ContactState::Stick
}
