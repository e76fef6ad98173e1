//! The paper's state iteration (`[solver] rule = "paper"`, §2.3 (6)):
//! start with every pair stuck; solve; judge every pair by eq. 15–17 from its
//! stresses alone, every change at once; repeat until the state set
//! repeats. A slipping pair carries the Mohr–Coulomb shear `c - f sigma_n`
//! of the last iteration along its last slip direction (zero with
//! `slip = "frictionless"`, the paper's own slip), so the iteration also runs
//! until that shear has settled. A state set that comes back after others is
//! a cycle: it is reported, not resolved (the robust rule resolves it).

use super::law::{judge_paper, ContactState};
use super::system::{InterfaceProblem, Relation};
use super::{cracked, tangential, Failed, History, Outcome, PairLaw};
use super::options::SlipLaw;
use crate::fem::vec3::{norm, sub};

/// The friction force on body I of every slipping Coulomb pair.
fn friction(problem: &InterfaceProblem, laws: &[PairLaw], h: &History, p: usize) -> [f64; 3] {
    if h.states[p] != ContactState::Slip || laws[p].slip == SlipLaw::Frictionless {
        return [0.0; 3];
    }
    let t = laws[p].strength.shear_limit(h.sigma_n[p], cracked(h, p)) * problem.area(p);
    [0.0, t * h.dir[p][1], t * h.dir[p][2]]
}

pub fn iterate(problem: &InterfaceProblem, laws: &[PairLaw], lambda: &[f64], h: &mut History, max_iterations: usize) -> Result<Outcome, Failed> {
    let n = laws.len();
    let mut history: Vec<Vec<ContactState>> = Vec::new();
    let mut iteration = 0;
    loop {
        iteration += 1;
        let relations: Vec<Relation> = (0..n).map(|p| Relation::simple(h.states[p], h.offset[p], friction(problem, laws, h, p))).collect();
        let solution = problem.solve(&relations, lambda).map_err(|failure| Failed { failure, states: h.states.clone(), iteration })?;
        history.push(h.states.clone());
        let r = &solution.pairs;
        let scale_u = solution.rel.iter().map(|v| norm(*v)).fold(0.0, f64::max);
        let scale_s = r.iter().map(|p| p.sigma_n.abs().max(p.tau())).fold(0.0, f64::max);
        let tol_u = 1e-10 * scale_u;

        let next: Vec<ContactState> = (0..n).map(|p| judge_paper(&r[p], &laws[p].strength)).collect();
        let changed = next != h.states;
        let cycled = changed && history.iter().any(|old| *old == next);

        // carry the new states: friction directions, offsets; and how far
        // the Coulomb shear of slipping pairs still moves
        let mut shear_moved: f64 = 0.0;
        for p in 0..n {
            let (st, nx) = (h.states[p], next[p]);
            let incr = tangential(sub(solution.rel[p], h.rel_start[p]));
            let cr = cracked(h, p);
            let limit = |sigma_n: f64| laws[p].strength.shear_limit(sigma_n, cr);
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
                    if st == ContactState::Slip && laws[p].slip == SlipLaw::Coulomb {
                        shear_moved = shear_moved.max(norm(sub(new, h.dir[p])) * limit(r[p].sigma_n));
                    }
                    h.dir[p] = new;
                }
                if st == ContactState::Slip && laws[p].slip == SlipLaw::Coulomb {
                    shear_moved = shear_moved.max((limit(r[p].sigma_n) - limit(h.sigma_n[p])).abs());
                }
            }
            if nx == ContactState::Stick && st != ContactState::Stick {
                // stuck again: keep the slip of earlier steps; a re-closing
                // pair touches where it is
                h.offset[p] = if st == ContactState::Open { tangential(solution.rel[p]) } else { tangential(h.rel_start[p]) };
            }
            h.sigma_n[p] = r[p].sigma_n;
        }
        let settled = shear_moved <= 1e-12 * scale_s.max(f64::MIN_POSITIVE);
        // (a loose interface solve is never the answer: the next, with the
        // same states, is solved tightly)
        let converged = !changed && settled && !solution.loose;
        if converged || cycled || iteration >= max_iterations {
            if converged {
                h.rel_start = solution.rel.clone();
                h.force = solution.forces.clone();
            }
            let states = h.states.clone();
            h.states = next;
            return Ok(Outcome { states, solution, iterations: iteration, converged, cycled, cycles_broken: 0, apex_openings: 0, history });
        }
        h.states = next;
    }
}
