//! The recovered result of a search's outcome: interiors and stresses of
//! the state that holds, every rank taking part; and the initial stage
//! replayed before a search below 1.

use super::super::condense::Parts;
use super::super::ranks::Ranks;
use super::super::steps::{LoadSteps, Step};
use crate::contact::Outcome;
use crate::error::Result;
use crate::recover;
use crate::results::{state_counts, InitialStage, StepResult};

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

/// The initial stage from its replayed outcome on rank 0 (its load factors
/// and outcome), its displacements recovered whatever the output needs
/// (every step's are taken off by them), every rank taking part; None
/// elsewhere.
pub(super) fn stage(
    step: &Step,
    parts: &Parts,
    ranks: &Ranks,
    o: Option<(Vec<f64>, Outcome)>,
    done: &mut LoadSteps,
) -> Result<Option<InitialStage>> {
    let (lambda, answer) = match o {
        Some((lambda, o)) => {
            let problem = step.problem.expect("rank 0's search has an interface");
            let answer = step.contact_run(problem, o, &lambda);
            (lambda, Some(answer))
        }
        None => (Vec::new(), None),
    };
    let (contact, d_c) = answer.unzip();
    let u = ranks.recover(step.model, &step.plan.parts, &parts.mine, d_c.map(Ok), &lambda, true)?;
    let Some((c, u)) = contact.zip(u) else { return Ok(None) };
    done.counters.interior_recoveries += step.plan.parts.len();
    Ok(Some(super::super::steps::initial_stage(step.model, &c.summary, state_counts(&c.states), lambda, u)))
}
