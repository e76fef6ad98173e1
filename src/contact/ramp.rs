//! The initial stage's strength ramp: where the in-situ stress puts joints
//! beyond their strength, the stage is solved first with every joint's
//! strength raised until none is beyond (by the largest in-situ
//! mobilisation `m = |τ| / (c + f σn')`), then brought down to the
//! strength as given in pieces, each from where the last one converged.
//!
//! Halving the stage's load, as [`super::cutting`] does for a load step,
//! cannot help it: the stage's loads are the in-situ stress and gravity
//! together, so every fraction of it puts the same pairs beyond by the
//! same mobilisation (the problem is homogeneous in the load). At k0 =
//! 0.25 the jointed tunnel of tests/initial_stage.rs has every pair of
//! both sets beyond (mobilised 1.060 and 1.019): solved at once, 120-220
//! of its 884 pairs changed state every iteration and the stage did not
//! converge in 400 iterations with 3 cuts. The strength is a homotopy
//! parameter that does reach it: at `m` every pair sticks (2 iterations),
//! and each piece of at most [`STEP`] lets only the pairs nearest their
//! limit slip; the stage converges in 11 iterations (2, 5, 4) to 469
//! stick / 415 slip. This is the continuation that an explicit code's
//! damped relaxation runs implicitly (3DEC, UDEC: the joints reach their
//! limit one after another as the unbalanced force decays), and it picks
//! the solution the path reaches: slip grows from the most mobilised
//! pairs, as a rock mass loaded in situ would slip.
//!
//! A piece that does not converge is halved, as a load step is, down to
//! `max_cuts` times; one that still does not ends the stage unconverged.

use super::cutting::{iterate_cutting, Attempt, Budget};
use super::history::History;
use super::iterate;
use super::options::StateRule;
use super::outcome::{Failed, Outcome};
use super::pair_law::PairLaw;
use super::safety::{reduced, Reduce};
use crate::contact::system::InterfaceProblem;

/// The largest relative change of the strength in one piece of the ramp
/// (the jointed tunnel at k0 = 0.25 from 1.07: in one piece not
/// converged in 60 iterations, in two 11 in all, in four 17, in eight 27;
/// from 1.0707, its 1 % above 1.060, three pieces and 13).
const STEP: f64 = 0.03;

/// How far above the in-situ mobilisation the ramp starts: at it, the
/// most mobilised pairs would be exactly at their limit (the jointed
/// tunnel at k0 = 0.25, started at 1.060 in two pieces: not converged
/// after 70 iterations; at 1.061 or 1.07, 11-12 in all).
const MARGIN: f64 = 0.01;

/// Runs the initial stage from the factors `from` to `to` with the
/// pairs' `laws`, where the in-situ stress mobilises the joints up to
/// `mobilised` (1 or less: the stage is solved as a load step is, by
/// [`iterate_cutting`]). The outcome is the last piece's; its summary
/// counts every piece's iterations and halvings and lists the strength
/// factors the pieces ended at ([`super::Summary::strengths`]). `told`
/// hears each [`Attempt`] as it ends where the stage (or its first solve
/// at the raised strength) is halved as a load step is, or a piece of the
/// ramp is (with the strengths it runs between).
pub fn iterate_stage(
    problem: &InterfaceProblem,
    (laws, mobilised): (&[PairLaw], f64),
    rule: StateRule,
    (from, to): (&[f64], &[f64]),
    h: &mut History,
    budget: Budget,
    told: &mut dyn FnMut(Attempt),
) -> Result<Outcome, Failed> {
    if !(mobilised > 1.0 && mobilised.is_finite()) {
        return iterate_cutting(problem, laws, rule, (from, to), h, budget, told);
    }
    let every = vec![true; laws.len()];
    // the strength at t: top^t times the scene's (t = 1: none beyond, none at its limit)
    let top = mobilised * (1.0 + MARGIN);
    let at = |t: f64| reduced(laws, &every, Reduce::ALL, top.powf(-t));
    let mut outcome = iterate_cutting(problem, &at(1.0), rule, (from, to), h, budget, told)?;
    let (mut iterations, mut cuts) = (outcome.summary.iterations, outcome.summary.cuts);
    let mut strengths = vec![top];
    let n = (top.ln() / STEP.ln_1p()).ceil().max(1.0) as usize;
    // pieces still to solve, the next on top: (start, end, depth) in t
    let mut todo: Vec<(f64, f64, usize)> = if outcome.summary.converged {
        (0..n).rev().map(|k| (1.0 - k as f64 / n as f64, 1.0 - (k + 1) as f64 / n as f64, 0)).collect()
    } else {
        Vec::new()
    };
    while let Some((a, b, depth)) = todo.pop() {
        let saved = (depth < budget.cuts).then(|| h.clone());
        outcome = iterate(problem, &at(b), rule, to, h, budget.iterations).map_err(|mut f| {
            f.iteration += iterations;
            f
        })?;
        iterations += outcome.summary.iterations;
        let converged = outcome.summary.converged;
        let halved = !converged && saved.is_some();
        if depth > 0 || halved {
            let strength = Some((top.powf(a), top.powf(b)));
            told(Attempt { strength, ..Attempt::of(&outcome.summary, (a, b), halved) });
        }
        if converged {
            strengths.push(top.powf(b));
            continue;
        }
        let Some(saved) = saved else { break };
        *h = saved;
        cuts += 1;
        let mid = 0.5 * (a + b);
        todo.push((mid, b, depth + 1));
        todo.push((a, mid, depth + 1));
    }
    outcome.summary.iterations = iterations;
    outcome.summary.cuts = cuts;
    outcome.summary.strengths = strengths;
    Ok(outcome)
}
