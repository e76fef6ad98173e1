//! The recovered result of a search's outcome: interiors and stresses of
//! the state that holds, every rank taking part.

use super::super::condense::Parts;
use super::super::ranks::Ranks;
use super::super::steps::{LoadSteps, Step};
use crate::contact::Outcome;
use crate::error::Result;
use crate::recover;
use crate::results::StepResult;

/// The recovered result of an outcome on rank 0 (`step` its load step, 0
/// for the search's hold), every rank taking part; None elsewhere.
pub(super) fn recovered(
    step: &Step,
    parts: &Parts,
    ranks: &Ranks,
    o: Option<(usize, Vec<f64>, Outcome)>,
    done: &mut LoadSteps,
) -> Result<Option<StepResult>> {
    let (need_stress, need_u) = step.needs();
    // only rank 0 holds the interface problem (and an outcome)
    let (k, lambda, answer) = match o {
        Some((k, lambda, o)) => {
            let problem = step.problem.expect("rank 0's search has an interface");
            let answer = step.contact_run(problem, o, &lambda);
            (k, lambda, Some(answer))
        }
        None => (0, Vec::new(), None),
    };
    let (contact, d_c) = answer.unzip();
    let u = ranks.recover(step.model, &step.plan.parts, &parts.mine, d_c.map(Ok), &lambda, need_u)?;
    let Some((c, mut u)) = contact.zip(u) else { return Ok(None) };
    done.counters.interior_recoveries += usize::from(need_u) * step.plan.parts.len();
    done.counters.stress_recoveries += usize::from(need_stress);
    let stresses = if need_stress { recover::nodal_stresses(step.model, &u) } else { Vec::new() };
    if need_u {
        super::super::steps::reset(&mut u, done.stage.as_ref());
    }
    let k = if k > 0 { k } else { step.scene.solver.load_steps };
    let load_factor = lambda.first().copied().unwrap_or(1.0);
    Ok(Some(StepResult { step: k, load_factor, case_factors: lambda, u, stresses, contact: Some(c) }))
}
