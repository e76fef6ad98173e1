//! Contact between the parts: pairs, frames, the law and the state
//! iteration of the substructure interface method.
//!
//! Each iteration solves the interface system for one set of pair states
//! (stick: tied; slip: tied along the normal, a friction force along the
//! joint; open: free) and judges every pair from the result, until the
//! states and the friction forces no longer change. Two rules
//! (`[solver] rule`):
//!
//! - `robust` (default, [`newton`]): a semismooth Newton method on the
//!   condensed interface in the spirit of the primal-dual active set method
//!   of Hüeber, Stadler & Wohlmuth (SIAM J. Sci. Comput. 30(2), 2008): the
//!   stick/slip/open sets and the friction forces are found together; the
//!   friction force of a slipping pair is linearised in its slip and in its
//!   normal force (slip direction free in the joint plane), so that the
//!   iteration converges superlinearly once the sets settle;
//! - `paper` ([`paper_rule`]): the paper's iteration, every pair judged by eq.
//!   15–17 from its stresses alone; a slipping pair carries the Coulomb
//!   shear of the last iteration along its last slip direction (zero with
//!   `slip = "frictionless"`); cycles are reported, not resolved.
//!
//! Both run one skeleton ([`iteration`]: solve, judge, stop) and commit a
//! converged step in one place ([`history::commit`]). Both keep the paper's law with
//! its extensions: Coulomb with cohesion,
//! tension cut-off, crack memory (a pair that opened or slipped keeps
//! `f_t = 0` and the residual cohesion: from the iteration it did so to the
//! end of its step, and in every step after a converged one), re-closure of
//! open pairs, and states, cracks and slip that carry over from load step
//! to load step (friction is path-dependent). Water in a joint ([`water`])
//! is a load on both faces of its pairs, so the force solved for is the
//! solid-to-solid one and the law judges the effective normal stress.

pub mod augmented;
pub mod basis;
pub mod capacity;
mod cluster;
mod crossing;
pub mod cutting;
pub mod elastic;
pub mod frame;
pub mod history;
mod iteration;
pub mod law;
pub mod mechanism;
pub mod mobility;
pub mod newton;
pub mod options;
mod orbit;
pub mod outcome;
pub mod pair_law;
pub mod paper_rule;
pub mod ramp;
pub mod safety;
pub mod system;
pub mod traction;
pub mod water;

use law::ContactState;
use system::InterfaceProblem;

pub use history::History;
pub use iteration::Limit;
pub use options::{InterfaceSolver, SlipLaw, StateRule, TractionRecovery};
pub use outcome::{Failed, Outcome, Stop, Summary};
pub use pair_law::PairLaw;

/// Runs the state iteration of one load step under the load factors
/// `lambda`, starting from and updating `h`.
pub fn iterate(
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    rule: StateRule,
    lambda: &[f64],
    h: &mut History,
    limit: impl Into<Limit>,
) -> Result<Outcome, Failed> {
    let limit = limit.into();
    let deforms = !h.unloaded.is_empty();
    let mut outcome = match rule {
        StateRule::Robust if deforms => {
            iteration::run(elastic::Elastic::new(problem, laws, h), problem, laws, lambda, h, limit)
        }
        StateRule::Robust => newton_or_rounds(problem, laws, lambda, h, limit),
        StateRule::Paper => iteration::run(paper_rule::Paper::new(problem, laws), problem, laws, lambda, h, limit),
    }?;
    if deforms {
        // a joint that deforms opens from where its normal spring is unloaded
        for (pr, r0) in outcome.solution.pairs.iter_mut().zip(&h.unloaded) {
            pr.gap -= r0[0];
        }
    }
    let before: Vec<bool> = (h.cracked.iter().zip(&h.cracking)).map(|(a, b)| *a || *b).collect();
    outcome.cracked = (before.iter().zip(&outcome.states)).map(|(c, s)| *c || *s != ContactState::Stick).collect();
    Ok(outcome)
}

/// The robust rule on rigid joints: the semismooth Newton iteration, and
/// where it does not end the step and `h` has springs to take
/// (`History::penalty`), the step solved again from where it started (its
/// history and the interface's warm start) by augmented Lagrangian rounds
/// ([`augmented`]). Where the rounds do not end it either, Newton's
/// outcome stands, as without them (cutting and the fallback go on from
/// it); the summary counts both, and says the rounds.
fn newton_or_rounds(
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    lambda: &[f64],
    h: &mut History,
    limit: Limit,
) -> Result<Outcome, Failed> {
    let start = h.penalty.is_some().then(|| (h.clone(), problem.warm_start()));
    let newton = iteration::run(newton::Newton::new(problem, laws, h, lambda), problem, laws, lambda, h, limit);
    let (Some((mut start, warm)), Some(k)) = (start, h.penalty) else { return newton };
    if newton.as_ref().is_ok_and(|o| o.summary.converged) {
        return newton;
    }
    let tried = newton.as_ref().map_or_else(|f| f.iteration, |o| o.summary.iterations);
    // (from where the step started, its interface solves too: not from
    // Newton's last iterate, as a cut piece, `cutting`)
    problem.start_from(&warm);
    let went = match augmented::run(problem, laws, lambda, &mut start, limit.most, k) {
        Ok((mut outcome, went)) => {
            *h = start;
            outcome.summary.iterations += tried;
            outcome.summary.augmented = Some(went);
            return Ok(outcome);
        }
        Err(went) => went,
    };
    match newton {
        Ok(mut outcome) => {
            outcome.summary.iterations += went.iterations;
            outcome.summary.augmented = Some(went);
            Ok(outcome)
        }
        Err(mut failed) => {
            failed.iteration += went.iterations;
            failed.augmented = Some(went);
            Err(failed)
        }
    }
}
