//! Rigid joints that end a load step without converging, solved again as
//! joints that deform (`[solver] rigid_fallback`, on by default).
//!
//! Where rigid joints cross near a free face, the contact law with the
//! rigid ties' share of the crossings' forces can have no state set that
//! keeps it (docs/convergence.md: a corner whose friction wedges it into
//! the other joint with a gain at or above one, Klarbring's examples of
//! non-existence), and no iteration ends there; yet joints made stiffer
//! and stiffer tend to one answer at the same crossings (the 34k tunnel:
//! the same states from 3,600 to 360,000 E / s, forces within 1 / k).
//! Joints with a stiffness have no ties to share and end: the model 3DEC
//! and UDEC always solve. So a run whose rigid joints did not
//! converge is run again, from its mesh, with every contact given
//!
//! ```text
//!     k_n = STIFFER · E / s,   k_s = k_n / 10
//! ```
//!
//! E the softest body's Young's modulus and s the mean block size (the
//! model's bounding box shared among its bodies: `(V / n)^(1/d)`). A rock
//! mass of blocks of size s whose joints have k_n is softer than its rock
//! by `1 / E_m = 1 / E + 1 / (k_n s)`: the joints add a tenth to its
//! compliance, whatever the units and the mesh. The results are those of
//! the joints that deform, and the run says so on the terminal, in
//! report.md and in summary.json (`contact.rigid_fallback`).

use super::messages::ContactError;
use crate::contact::cutting::SHORT_ITERATIONS;
use crate::contact::law::Stiffness;
use crate::contact::Stop;
use crate::error::Error;
use crate::model::Model;
use crate::parallel::{Comm, CommExt};
use crate::results::{Fallback, Run, SafetyRun, StepResult};
use crate::scene::{Scene, StateRule};

/// A rigid step's law residual (of the largest traction) below which
/// the fallback says more iterations may end it rigid.
const CLOSE: f64 = 1e-6;

/// `k_n s / E`: the rock mass is `1 + 1 / STIFFER` times as compliant as
/// its rock.
pub(super) const STIFFER: f64 = 10.0;

/// Whether a run of `scene` falls back when its joints do not converge:
/// rigid joints under the robust rule, and the scene lets it.
pub(super) fn eligible(scene: &Scene) -> bool {
    scene.solver.rigid_fallback && rigid_robust(scene)
}

/// Rigid joints under the robust rule (for which joints that deform are
/// built): where a step that did not converge is advised a stiffness.
pub(super) fn rigid_robust(scene: &Scene) -> bool {
    !scene.contacts.is_empty() && !scene.joints_deform() && scene.solver.rule == StateRule::Robust
}

/// Whether a run of `scene` solves again by augmented Lagrangian rounds
/// the steps its rigid joints' Newton iteration does not end
/// (`[solver] augmented_lagrangian`, rigid joints under the robust rule):
/// what sets `History::penalty` and builds the interface for the rounds.
pub(super) fn takes_rounds(scene: &Scene) -> bool {
    scene.solver.augmented_lagrangian && rigid_robust(scene)
}

/// The stiffness joints that deform take in place of rigid ones:
/// `STIFFER E / s` normal and a tenth of it in shear, with E the softest
/// body's modulus and s the model's mean block size; and those E and s.
pub(super) fn stiffness(scene: &Scene, model: &Model) -> (Stiffness, f64, f64) {
    let e = scene.bodies.iter().map(|b| b.material.e).fold(f64::INFINITY, f64::min);
    let s = block_size(model);
    // rounded as a user would write them back, so that the same values
    // given in the scene give the same answer
    let normal = round(STIFFER * e / s);
    (Stiffness { normal, shear: round(normal / 10.0) }, e, s)
}

/// The model's mean block size: its bounding box's measure (area in 2D)
/// shared among its bodies, to the power one over the dimension. A length
/// of the model, whatever its mesh.
fn block_size(model: &Model) -> f64 {
    let d = model.analysis.dim();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for n in model.bodies.iter().flat_map(|b| &b.cells).flat_map(|c| &c.nodes) {
        for k in 0..d {
            lo[k] = lo[k].min(model.coords[*n][k]);
            hi[k] = hi[k].max(model.coords[*n][k]);
        }
    }
    let measure: f64 = (0..d).map(|k| (hi[k] - lo[k]).max(0.0)).product();
    let s = (measure / model.bodies.len().max(1) as f64).powf(1.0 / d as f64);
    if s.is_finite() && s > 0.0 {
        s
    } else {
        1.0
    }
}

/// Where the load steps' last (`steps`, on rank 0) did not converge, as
/// rank 0 tells every rank: the scene with every contact given the
/// fallback's stiffness, and the record of why (on rank 0); the rigid
/// attempt took `seconds`.
pub(super) fn fall(
    scene: &Scene,
    model: &Model,
    steps: &[StepResult],
    comm: &dyn Comm,
    seconds: f64,
) -> Option<(Scene, Option<Fallback>)> {
    let stop = steps.last().and_then(|s| s.contact.as_ref()).is_some_and(|c| !c.summary.converged);
    if !comm.broadcast(&stop) {
        return None;
    }
    let (stiff, taken) = stiffened(scene, model);
    let short_of = Some(scene.solver.max_iterations).filter(|&n| n > SHORT_ITERATIONS);
    Some((stiff, record(taken, steps.last(), seconds).map(|f| Fallback { short_of, ..f })))
}

/// `scene` with every contact given the fallback's [`stiffness`], and
/// that stiffness with its E and s.
fn stiffened(scene: &Scene, model: &Model) -> (Scene, (Stiffness, f64, f64)) {
    let taken = stiffness(scene, model);
    let mut stiff = scene.clone();
    stiff.give_joints_stiffness(taken.0);
    (stiff, taken)
}

/// Where the rigid attempt stopped with `error` at a state set that
/// holds nothing (a body held by nothing, or free to slide), as rank 0
/// tells every rank: the scene with every contact given the fallback's
/// stiffness, and the record of why (on rank 0); the rigid attempt took
/// `seconds`. An iteration that has not converged passes through state
/// sets the answer does not have: the 3D slope of tests/corpus with half
/// its cohesion reached, at step 3's iteration 481, one that left block
/// 41 held by nothing (a build whose interface solves differed by
/// round-off from this one's; docs/convergence.md), where the step would
/// otherwise have ended unconverged and fallen back. Where the scene
/// itself holds nothing, the joints that deform are refused as well and
/// the run ends with this error ([`super::solve`]).
pub(super) fn fall_unheld(
    scene: &Scene,
    model: &Model,
    error: &Error,
    comm: &dyn Comm,
    seconds: f64,
) -> Option<(Scene, Option<Fallback>)> {
    let stopped = unheld(error);
    if !comm.broadcast(&stopped.is_some()) {
        return None;
    }
    let (stiff, taken) = stiffened(scene, model);
    let record = stopped.map(|(at, said)| Fallback {
        unheld: Some(said),
        rounds: at.rounds.map(|r| r.map(|n| n as usize)),
        ..stopped_at(taken, at.step.unwrap_or(1), at.iteration, seconds)
    });
    Some((stiff, record))
}

/// The record of a rigid attempt stopped at `iterations` of `step` before
/// its step ended (no cut, no law residual), with the stiffness `taken`.
fn stopped_at(taken: (Stiffness, f64, f64), step: usize, iterations: usize, seconds: f64) -> Fallback {
    Fallback {
        stiffness: taken.0,
        modulus: taken.1,
        block_size: taken.2,
        step,
        iterations,
        cuts: 0,
        scaled: false,
        stop: Stop::MaxIterations,
        law_residual: None,
        seconds,
        unheld: None,
        rounds: None,
        held: None,
        short_of: None,
        safety: None,
    }
}

/// Where the rigid joints' safety search (`safety`, on rank 0) stopped
/// at a trial that decided nothing, even retried in smaller steps, as
/// rank 0 tells every rank: the scene with every contact given the
/// fallback's stiffness, and the record of why (on rank 0); the rigid
/// attempt took `seconds`. Near the
/// limit, rigid joints cycle or wander where joints that deform end:
/// the corpus' 3D slope (tests/corpus/slope3d.toml) held at F = 1.3,
/// left 1.2, 1.375 and 1.4 undecided and failed at 1.5 with block 41
/// "held by nothing" at an iterate (760 s); with the fallback's
/// stiffness it holds to F = 3.9, and with ten times that to 3.5 at
/// least (docs/safety.md).
pub(super) fn fall_undecided(
    scene: &Scene,
    model: &Model,
    safety: Option<&SafetyRun>,
    comm: &dyn Comm,
    seconds: f64,
) -> Option<(Scene, Option<Fallback>)> {
    let open = safety.filter(|s| !s.decided && !s.below_one);
    let stop = open.and_then(|s| Some((s.factor?, *s.undecided.last()?)));
    if !comm.broadcast(&stop.is_some()) {
        return None;
    }
    let (stiff, taken) = stiffened(scene, model);
    let record = stop.map(|(holds, trial)| Fallback {
        stop: trial.stop,
        safety: Some((holds, trial)),
        ..stopped_at(taken, scene.solver.load_steps, trial.iterations, seconds)
    });
    Some((stiff, record))
}

/// Where `error` is a contact iteration's that stopped at a state set
/// holding nothing, on joints that carry shear: where, and what it left
/// unheld ("body \"top\" is held by nothing").
pub(super) fn unheld(error: &Error) -> Option<(super::messages::At, String)> {
    let Error::Contact(c) = error else { return None };
    let named = |bodies: &[String]| match bodies {
        [one] => format!("body \"{one}\" is"),
        many => format!("bodies \"{}\" are", many.join("\", \"")),
    };
    match &**c {
        ContactError::NotHeld { at, bodies, .. } => Some((at.clone(), format!("{} held by nothing", named(bodies)))),
        // (joints that carry no shear hold nothing along them, rigid or
        // not: the scene's failure, whatever the path)
        ContactError::Sliding { no_shear: true, .. } => None,
        ContactError::Sliding { at, bodies, .. } if bodies.is_empty() => {
            Some((at.clone(), "bodies slide or rotate freely".to_string()))
        }
        ContactError::Sliding { at, bodies, .. } => {
            Some((at.clone(), format!("{} free to slide or rotate", named(bodies))))
        }
        _ => None,
    }
}

/// Where the joints are rigid under the robust rule, the normal and
/// shear stiffness a step that did not converge (or a safety factor
/// left undecided) is advised to try: those the fallback takes.
pub(super) fn advised(run: &Run) -> Option<[f64; 2]> {
    let k = rigid_robust(&run.scene).then(|| stiffness(&run.scene, &run.model).0)?;
    Some([k.normal, k.shear]).filter(|k| k[0].is_finite())
}

/// What the rigid run's last step did, where it did not converge (None
/// where it did, or it has no contact): the record of the fallback, with
/// the stiffness the run takes instead, its E and s ([`stiffness`]), and
/// the rigid run's `seconds`.
fn record(
    (stiffness, modulus, block_size): (Stiffness, f64, f64),
    last: Option<&StepResult>,
    seconds: f64,
) -> Option<Fallback> {
    let last = last?;
    let c = last.contact.as_ref().filter(|c| !c.summary.converged)?;
    Some(Fallback {
        stiffness,
        modulus,
        block_size,
        step: last.step,
        iterations: c.summary.iterations,
        cuts: c.summary.cuts,
        scaled: c.summary.scaled,
        stop: c.summary.why_not(),
        law_residual: c.worst_law_residual().map(|(_, r)| r),
        seconds,
        unheld: None,
        rounds: c.summary.augmented.map(|r| [r.rounds, r.iterations]),
        held: c.summary.pieces.last().copied(),
        short_of: None,
        safety: None,
    })
}

/// The sentence the run says on the terminal and in report.md: where
/// and how the rigid joints stopped, and the stiffness taken instead.
pub fn said(f: &Fallback) -> String {
    let at = match (f.safety, f.step) {
        (Some((_, trial)), _) => format!("the safety search's trial at F = {:.4}", trial.factor),
        (None, 0) => "the initial equilibrium stage".to_string(),
        (None, k) => format!("load step {k}"),
    };
    let mut how = match &f.unheld {
        Some(what) => format!("the states reached a set in which {what}"),
        None => match f.stop {
            Stop::Cycled => "the states cycled",
            Stop::LawBroken => "the states settled, but their forces broke the contact law",
            Stop::MaxIterations => "the states kept changing",
        }
        .to_string(),
    };
    if let Some((holds, _)) = f.safety {
        how += &format!(", even retried in smaller steps from F = {holds:.4}, the last factor that held");
    }
    let law = f.law_residual.map_or(String::new(), |r| format!(", law residual {r:.2e} of the largest traction"));
    // a rigid iteration stopped this close to the law may end with a few
    // more iterations: the scene's budget, not the rigid law, ran out
    let close = match (f.law_residual, f.short_of) {
        (Some(r), Some(n)) if r < CLOSE => format!("; the rigid joints were close to the law, so more iterations may end them rigid: with [solver] rigid_fallback = false a step takes its max_iterations ({n}), where the fallback gives it {SHORT_ITERATIONS}"),
        (Some(r), None) if r < CLOSE => {
            "; the rigid joints were close to the law, so more [solver] max_iterations may end them rigid".to_string()
        }
        _ => String::new(),
    };
    let theirs = match f.safety {
        Some(_) => "its results, the factor of safety with them, are theirs",
        None => "its results are theirs",
    };
    let rounds = match f.rounds {
        Some([rounds, iterations]) => format!(", {iterations} of them in {rounds} augmented Lagrangian round(s)"),
        None => String::new(),
    };
    // a step whose cut pieces held part of its load: the rigid joints may
    // be at their limit there (the 3D slope with half its cohesion held
    // 0.875 of its step 3, its gravity 0.72)
    let (held, limit) = match f.held {
        Some(x) => (
            format!("; its cut pieces held {x} of its load"),
            format!(" Rigid, the joints held the step's load up to {x} of it and no piece beyond: where rigid joints are at their limit, joints that deform may still stand, so check the margin with a [safety] search."),
        ),
        None => (String::new(), String::new()),
    };
    format!(
        "rigid joints did not converge at {at} ({} iteration(s){}{rounds}, {how}{law}{held}; {:.1} s{close}), so the scene is solved again with joints that deform, and {theirs}: normal_stiffness = {} and shear_stiffness = {} on every contact (k_n = {STIFFER} E / s, E = {} the softest body's modulus, s = {} the mean block size: the joints add a tenth to the rock mass's compliance). Where rigid joints cross near a free face, their ties' share of the forces can leave no state set that keeps the law, although stiff joints have an answer there (docs/convergence.md).{limit} Give the joints your own stiffness, or [solver] rigid_fallback = false to stop with the rigid joints' last iterate",
        f.iterations,
        match (f.cuts, f.scaled) {
            (0, true) => format!(", {}", super::messages::NOT_CUT),
            (0, false) => String::new(),
            (n, _) => format!(" and {n} cut(s)"),
        },
        f.seconds,
        f.stiffness.normal,
        f.stiffness.shear,
        f.modulus,
        round(f.block_size),
    )
}

/// `x` to four significant digits, for a value a user would write back.
fn round(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(3 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

#[cfg(test)]
mod tests {
    use super::super::messages::{At, ContactError};
    use super::{round, said, unheld};
    use crate::contact::law::Stiffness;
    use crate::contact::Stop;
    use crate::error::Error;
    use crate::results::{Fallback, Undecided};
    use crate::scene::StateRule;

    /// A body held by nothing, or free to slide on joints that carry
    /// shear, falls back; joints that carry no shear, a step that did not
    /// converge and any other error do not.
    #[test]
    fn a_state_set_that_holds_nothing_is_told_from_the_scenes_failure() {
        let at = At { step: Some(3), iteration: 481, states: [10, 20, 30], rounds: None };
        let held =
            ContactError::NotHeld { at: at.clone(), bodies: vec!["rock #41".into()], places: vec![None], apex: vec![] };
        let (where_, what) = unheld(&Error::from(held)).expect("held by nothing falls back");
        assert_eq!((where_, what.as_str()), (at.clone(), "body \"rock #41\" is held by nothing"));
        let sliding = |no_shear: bool, bodies: Vec<String>| ContactError::Sliding {
            at: at.clone(),
            places: vec![None; bodies.len()],
            bodies,
            no_shear,
            rule: StateRule::Robust,
            motions: Vec::new(),
        };
        let two = vec!["a".to_string(), "b".to_string()];
        let said = unheld(&Error::from(sliding(false, two.clone()))).map(|u| u.1);
        assert_eq!(said.as_deref(), Some("bodies \"a\", \"b\" are free to slide or rotate"));
        assert!(unheld(&Error::from(sliding(true, two))).is_none(), "frictionless joints are the scene's");
        assert!(unheld(&Error::from(ContactError::BondedNotHeld)).is_none());
    }

    /// A safety search the rigid joints left undecided says which trial,
    /// from which factor, and that the factor is the deforming joints'.
    #[test]
    fn a_fallback_from_the_safety_search_names_its_trial() {
        let trial = Undecided { factor: 1.2, iterations: 11, stop: Stop::MaxIterations };
        let f = Fallback {
            stiffness: Stiffness { normal: 12_110.0, shear: 1_211.0 },
            modulus: 1e4,
            block_size: 8.258,
            step: 2,
            iterations: 11,
            cuts: 0,
            scaled: false,
            stop: Stop::MaxIterations,
            law_residual: None,
            seconds: 170.2,
            unheld: None,
            rounds: None,
            held: None,
            short_of: None,
            safety: Some((1.175, trial)),
        };
        let s = said(&f);
        assert!(s.starts_with("rigid joints did not converge at the safety search's trial at F = 1.2000 (11 iteration(s), the states kept changing, even retried in smaller steps from F = 1.1750, the last factor that held; 170.2 s)"), "{s}");
        assert!(s.contains("its results, the factor of safety with them, are theirs: normal_stiffness = 12110"), "{s}");
        // a trial whose states settled with the law broken says so, not
        // that they kept changing (the 3D slope's F = 1.2, 9 iterations)
        let settled = Undecided { iterations: 9, stop: Stop::LawBroken, ..trial };
        let broken =
            said(&Fallback { iterations: 9, stop: Stop::LawBroken, safety: Some((1.1, settled)), ..f.clone() });
        assert!(broken.contains("at F = 1.2000 (9 iteration(s), the states settled, but their forces broke the contact law, even retried in smaller steps from F = 1.1000"), "{broken}");
        let load = said(&Fallback { safety: None, ..f.clone() });
        assert!(
            load.starts_with(
                "rigid joints did not converge at load step 2 (11 iteration(s), the states kept changing; 170.2 s)"
            ),
            "{load}"
        );
        // augmented Lagrangian rounds that did not end the step either
        // are counted among its iterations, and said
        let unheld = Some("body \"rock #36\" is held by nothing".to_string());
        let rounds = said(&Fallback { iterations: 213, safety: None, unheld, rounds: Some([7, 106]), ..f.clone() });
        assert!(rounds.starts_with("rigid joints did not converge at load step 2 (213 iteration(s), 106 of them in 7 augmented Lagrangian round(s), the states reached a set in which body \"rock #36\" is held by nothing; 170.2 s)"), "{rounds}");
        // a cut step whose pieces held part of its load says how much,
        // and that the rigid joints may be at their limit there
        let cut = said(&Fallback { iterations: 411, cuts: 3, safety: None, held: Some(0.875), ..f.clone() });
        assert!(cut.starts_with("rigid joints did not converge at load step 2 (411 iteration(s) and 3 cut(s), the states kept changing; its cut pieces held 0.875 of its load; 170.2 s)"), "{cut}");
        assert!(cut.contains("(docs/convergence.md). Rigid, the joints held the step's load up to 0.875 of it and no piece beyond: where rigid joints are at their limit, joints that deform may still stand, so check the margin with a [safety] search. Give the joints"), "{cut}");
        assert!(!load.contains("Rigid, the joints held"), "{load}");
        // close to the law: more iterations, which the fallback's 30 held
        // back where the scene asked for more
        let near = Fallback { iterations: 30, safety: None, law_residual: Some(2e-7), ..f.clone() };
        assert!(said(&near).contains("2.00e-7 of the largest traction; 170.2 s; the rigid joints were close to the law, so more [solver] max_iterations may end them rigid)"), "{}", said(&near));
        let held_short = said(&Fallback { short_of: Some(100), ..near });
        assert!(held_short.contains("170.2 s; the rigid joints were close to the law, so more iterations may end them rigid: with [solver] rigid_fallback = false a step takes its max_iterations (100), where the fallback gives it 30)"), "{held_short}");
    }

    #[test]
    fn stiffness_is_rounded_to_four_digits() {
        assert_eq!(round(13_888.888), 13_890.0);
        assert_eq!(round(0.012_345_6), 0.012_35);
        assert_eq!(round(5000.0), 5000.0);
    }
}
