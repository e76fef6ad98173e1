//! What the writers print of the scene ([`About`]), made once from the
//! scene and the model: the header, the `[output]` and `[safety]` options,
//! each contact's law, the factors each load takes at each step and the
//! time of each step, and the warnings (`driver/warnings.rs`).

use super::warnings::warnings;
use crate::model::{ContactGroups, LoadKind, Model};
use crate::results::about::{About, Applied, ContactLaw};
use crate::scene::Scene;

/// The writers' view of `scene`, run on `model`.
pub(crate) fn about(scene: &Scene, model: &Model) -> About {
    let applied = applied(scene);
    About {
        path: scene.path.clone(),
        name: scene.name.clone(),
        title: scene.title.clone(),
        analysis: scene.analysis,
        thickness: scene.thickness,
        output: scene.output.clone(),
        joints: scene.joints.clone(),
        probes: scene.probes.clone(),
        analytic: scene.analytic.clone(),
        safety: scene.safety.clone(),
        contacts: (scene.contacts.iter())
            .map(|c| ContactLaw {
                strength: c.strength,
                slip: c.slip,
                residual_given: c.residual_given,
                stiffness: c.stiffness,
            })
            .collect(),
        loads: scene.loads.iter().map(|l| l.group.clone()).collect(),
        step_times: step_times(&applied, scene.solver.load_steps),
        applied,
        warnings: warnings(scene, model),
    }
}

/// The factors the scene applies at each step, read from the scene as the
/// user wrote it: gravity (when a material has a density) by
/// `[solver] gravity_factors`, each `[[loads]]` entry by its `factors`,
/// prescribed displacements, and everything without factors by the ramp
/// k / load_steps. Loads with the same factors share a column, named by
/// their groups.
fn applied(scene: &Scene) -> Vec<Applied> {
    let n = scene.solver.load_steps;
    let ramp: Vec<f64> = (1..=n).map(|k| k as f64 / n as f64).collect();
    let mut named: Vec<(String, Vec<f64>)> = Vec::new();
    let weighs = scene.gravity.iter().any(|&g| g != 0.0) && scene.materials.values().any(|m| m.density > 0.0);
    if weighs {
        named.push(("gravity".into(), scene.solver.gravity_factors.clone().unwrap_or_else(|| ramp.clone())));
    }
    for l in &scene.loads {
        let name = match l.kind {
            LoadKind::Seismic { kh, kv, .. } => format!("seismic kh = {kh}, kv = {kv}"),
            _ => format!("\"{}\"", l.group),
        };
        named.push((name, l.factors.clone().unwrap_or_else(|| ramp.clone())));
    }
    for c in &scene.contacts {
        let Some(w) = &c.water else { continue };
        let own = w.factors.clone().or_else(|| w.face.as_ref().and_then(|f| scene.loads[f.load].factors.clone()));
        let name = match &c.groups {
            ContactGroups::Shared(g) => g.clone(),
            ContactGroups::Pair(a, b) => format!("{a}|{b}"),
        };
        named.push((format!("water in \"{name}\""), own.unwrap_or_else(|| ramp.clone())));
    }
    if scene.supports.iter().any(|sp| sp.prescribed.iter().flatten().any(|&u| u != 0.0)) {
        named.push(("prescribed u".into(), ramp.clone()));
    }
    let mut columns: Vec<Applied> = Vec::new();
    for (name, factors) in named {
        match columns.iter_mut().find(|c| c.factors == factors) {
            Some(c) => {
                c.name.push_str(", ");
                c.name.push_str(&name);
            }
            None => columns.push(Applied { name, factors }),
        }
    }
    columns
}

/// The time of each of `n` load steps in the `.pvd` collections: its load
/// factor. That is the factor of the one load (or loads sharing factors)
/// that changes from step to step when it grows at every step (a reservoir
/// filled in steps under constant self-weight: 0, 0.5, 1), else the ramp
/// k / load_steps, which always grows (ParaView orders the steps by time).
fn step_times(applied: &[Applied], n: usize) -> Vec<f64> {
    let varying: Vec<&Vec<f64>> =
        applied.iter().map(|c| &c.factors).filter(|f| f.windows(2).any(|w| w[0] != w[1])).collect();
    match varying.as_slice() {
        [one] if one.len() == n && one.windows(2).all(|w| w[1] > w[0]) => one.to_vec(),
        _ => (1..=n).map(|k| k as f64 / n as f64).collect(),
    }
}
