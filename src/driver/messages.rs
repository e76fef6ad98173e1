//! The messages of a failed contact iteration: which bodies nothing holds,
//! or which slide freely, at which load step and iteration, and what to do.

use crate::contact::{self, system::SolveFailure};
use crate::model::Model;
use crate::results::state_counts;
use crate::scene::Scene;
use crate::substructure::Part;

/// The one-paragraph message of a failed contact iteration; `parts` are the
/// parts in the interface's order.
pub(super) fn failure_message(model: &Model, parts: &[&Part], scene: &Scene, step: usize, f: contact::Failed) -> String {
    let at = if scene.solver.load_steps > 1 { format!("load step {step}, ") } else { String::new() };
    let counts = state_counts(&f.states);
    match f.failure {
        SolveFailure::NotHeld(ids) => {
            let mut bodies: Vec<usize> = ids.iter().flat_map(|&i| parts[i].bodies.iter().copied()).collect();
            bodies.sort_unstable();
            bodies.dedup();
            let one = bodies.len() == 1;
            format!(
                "{path}: {what} {names} {verb} held by nothing at {at}contact iteration {it} ({stick} stick, {slip} slip, {open} open): {its} contact pairs opened and no support holds {it_them}{apex}. Add a support, or check the loads that pull the contact apart",
                apex = apex_note(scene),
                path = scene.path.display(),
                at = at,
                what = if one { "body" } else { "bodies" },
                names = model.body_names(&bodies),
                verb = if one { "is" } else { "are" },
                it = f.iteration,
                stick = counts[2],
                slip = counts[1],
                open = counts[0],
                its = if one { "its" } else { "their" },
                it_them = if one { "it" } else { "them" },
            )
        }
        SolveFailure::Sliding(ids) => {
            let mut bodies: Vec<usize> = ids.iter().flat_map(|&i| parts[i].bodies.iter().copied()).collect();
            bodies.sort_unstable();
            bodies.dedup();
            format!(
                "{}: the interface system is singular at {at}contact iteration {} ({} stick, {} slip, {} open): {} slides or rotates freely on its contacts — loss of equilibrium: the load along the contact exceeds what friction and cohesion can carry. Reduce the load, or add a support that holds it tangentially, or friction",
                scene.path.display(),
                f.iteration,
                counts[2],
                counts[1],
                counts[0],
                if bodies.is_empty() { "a body".to_string() } else { format!("{} {}", if bodies.len() == 1 { "body" } else { "bodies" }, model.body_names(&bodies)) },
            )
        }
    }
}

/// Where a contact's f_t exceeds the Coulomb apex c / f, the robust rule
/// opens its pairs at c / f already: say so where they let a body go.
fn apex_note(scene: &Scene) -> String {
    let which: Vec<String> = scene
        .contacts
        .iter()
        .enumerate()
        .filter(|(_, c)| c.friction > 0.0 && c.tensile_strength > c.cohesion / c.friction)
        .map(|(i, c)| format!("contacts[{i}] opens at c / f = {} (its tensile_strength {} exceeds that Coulomb apex: no shear strength is left there)", c.cohesion / c.friction, c.tensile_strength))
        .collect();
    if which.is_empty() || scene.solver.rule != crate::contact::StateRule::Robust {
        String::new()
    } else {
        format!(" ({})", which.join("; "))
    }
}
