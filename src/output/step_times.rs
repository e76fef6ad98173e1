//! The load factor at each step the output writes against: the factor of
//! the one load that grows at every step, else the ramp k / load_steps.

use super::report;

/// The time of each load step in the `.pvd` collections: its load factor.
/// That is the factor of the one load (or loads sharing factors) that
/// changes from step to step when it grows at every step (a reservoir
/// filled in steps under constant self-weight: 0, 0.5, 1), else the ramp
/// k / load_steps, which always grows (ParaView orders the steps by time).
pub fn step_times(scene: &crate::scene::Scene) -> Vec<f64> {
    let n = scene.solver.load_steps;
    let varying: Vec<Vec<f64>> =
        report::applied(scene).into_iter().map(|c| c.factors).filter(|f| f.windows(2).any(|w| w[0] != w[1])).collect();
    match varying.as_slice() {
        [one] if one.len() == n && one.windows(2).all(|w| w[1] > w[0]) => one.clone(),
        _ => (1..=n).map(|k| k as f64 / n as f64).collect(),
    }
}
