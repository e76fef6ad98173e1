//! Contact between the parts: pairs, frames, the law and the state
//! iteration of the substructure interface method.
//!
//! The iteration (paper §2.3 (6)): start with every pair stuck; solve the
//! interface system; judge every pair; repeat with the new states until a
//! state set repeats. A repeat of the previous set is convergence; a repeat
//! of an older one is a cycle, reported as not converged. Bounded by
//! `max_iterations`.

pub mod frame;
pub mod law;
pub mod rigid;
pub mod system;

use law::{judge, ContactState, PairResult, Strength};
use system::{InterfaceProblem, InterfaceSolution, SolveFailure};

/// How the state iteration ended.
pub struct Outcome {
    pub states: Vec<ContactState>,
    pub solution: InterfaceSolution,
    pub iterations: usize,
    pub converged: bool,
    /// A state set came back after other ones in between.
    pub cycled: bool,
    /// State sets of every iteration (the ones solved with).
    pub history: Vec<Vec<ContactState>>,
    pub cracked: Vec<bool>,
}

/// A failed iteration: the failure and the states it happened with.
pub struct Failed {
    pub failure: SolveFailure,
    pub states: Vec<ContactState>,
    pub iteration: usize,
}

/// Runs the state iteration from `start` states.
pub fn iterate(
    problem: &InterfaceProblem,
    strength: &[Strength],
    start: Vec<ContactState>,
    mut cracked: Vec<bool>,
    max_iterations: usize,
) -> Result<Outcome, Failed> {
    let n = start.len();
    let shear = vec![[0.0; 3]; n];
    let mut states = start;
    let mut history: Vec<Vec<ContactState>> = Vec::new();
    let mut iteration = 0;
    loop {
        iteration += 1;
        let solution = problem
            .solve(&states, &shear)
            .map_err(|failure| Failed { failure, states: states.clone(), iteration })?;
        history.push(states.clone());
        let gap_tol = gap_tolerance(&solution.pairs);
        let next: Vec<ContactState> =
            (0..n).map(|p| judge(states[p], &solution.pairs[p], &strength[p], cracked[p], gap_tol)).collect();
        for p in 0..n {
            if next[p] != ContactState::Stick {
                cracked[p] = true;
            }
        }
        let converged = next == states;
        let cycled = !converged && history.iter().any(|h| *h == next);
        if converged || cycled || iteration >= max_iterations {
            return Ok(Outcome { states, solution, iterations: iteration, converged, cycled, history, cracked });
        }
        states = next;
    }
}

/// Gaps below this count as closed: round-off relative to the largest
/// relative displacement of any pair.
fn gap_tolerance(r: &[PairResult]) -> f64 {
    let scale = r.iter().map(|p| p.gap.abs().max(p.slip)).fold(0.0, f64::max);
    1e-10 * scale
}
