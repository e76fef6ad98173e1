//! Crack memory within a load step (issue 28): a pair that slipped or
//! opened in an iteration of the step keeps `f_t = 0` and its residual
//! cohesion to the step's end, whatever the iteration judges it after.
//!
//! geo/tunnel_joints.toml as it is (one step; bedding f = 0.4, c = 0;
//! two cross-joint sets f = 0.85, c = 0.1, residual cohesion 0): the
//! pairs solved slipping or open in an iteration after the first (the
//! state sets of `Summary::history`) have cracked in the step, and every
//! one of them that ends closed carries at most its cracked Coulomb bound
//! `f p` (p the pressure). Before, a pair that had slipped and was judged
//! stuck again got its peak cohesion back: pair 1079 of joints_a ended
//! stuck at tau = 0.1002, four times its cracked bound 0.0234 (and under
//! its peak bound 0.1246).
//!
//! The outputs judge strength by the same cracks (`ContactRun::cracked`,
//! from the iteration): a face's or block's mobilised friction is its
//! pairs' largest `|tau| / (c - f sigma_n)` with the residual cohesion on
//! every pair that cracked in the step, so no stuck pair reports more
//! than 1. Before, the writers took the cracks from the earlier steps'
//! end states alone and judged such a pair against its peak strength.

mod common;

use common::Case;
use subcontact::contact::law::ContactState;
use subcontact::output::resultants::{self, strengths};
use subcontact::results::Run;

#[test]
fn a_pair_that_slipped_in_the_step_ends_it_within_its_cracked_strength() {
    let case = Case::new("crack-memory");
    case.copy("geo/tunnel_joints.geo");
    let run = case.run(&case.copy("geo/tunnel_joints.toml")).unwrap_or_else(|e| panic!("tunnel_joints: {e:#}"));
    let c = run.contact().expect("contact");
    assert!(c.summary.converged, "the contact iteration converges");
    let sets = &c.summary.history;
    assert!(sets.len() >= 3, "an iteration beyond the first two: {} iterations", sets.len());
    let strength = strengths(&run);
    let n = c.states.len();
    let cracked: Vec<usize> = (0..n).filter(|&p| sets[1..].iter().any(|s| s[p] != ContactState::Stick)).collect();
    // pairs that cracked on the way and ended stuck: the crack did not heal
    let healed: Vec<usize> = cracked.iter().copied().filter(|&p| c.states[p] == ContactState::Stick).collect();
    let cohesive: Vec<usize> =
        cracked.iter().copied().filter(|&p| strength[run.model.pairs[p].contact].cohesion > 0.0).collect();
    assert!(cohesive.len() >= 10, "cohesive pairs that cracked in the step: {}", cohesive.len());
    let scale = c.pairs.iter().map(|r| r.tau()).fold(0.0, f64::max);
    for &p in &cracked {
        let (r, s) = (&c.pairs[p], &strength[run.model.pairs[p].contact]);
        if c.states[p] == ContactState::Open {
            continue;
        }
        assert!(r.sigma_n <= 1e-9 * scale, "pair {p}: a cracked pair carries no tension ({})", r.sigma_n);
        let bound = s.residual_cohesion - s.friction * r.sigma_n;
        assert!(
            r.tau() <= bound + 1e-9 * scale,
            "pair {p} ({:?}, {} stuck of {} cracked): tau {} beyond its cracked bound {bound} (peak {})",
            c.states[p],
            healed.len(),
            cracked.len(),
            r.tau(),
            s.shear_limit(r.sigma_n, false),
        );
    }
    // the outputs' cracks are the iteration's, pair by pair (one step:
    // cracked on the way, or open or slipping at the end)
    for p in 0..n {
        let was = cracked.binary_search(&p).is_ok() || c.states[p] != ContactState::Stick;
        assert_eq!(c.is_cracked(p), was, "pair {p}: the run's crack is the iteration's");
    }
    assert!(!healed.is_empty(), "stuck pairs that cracked in the step: none");
    faces_within_the_cracked_bound(&run);
}

/// geo/dam3d_joints.toml at lc = 6 m (self-weight, then the reservoir at
/// half and full): in the last step, contraction-joint pairs (f = 0.75,
/// c = 0.1, f_t = 0.05, residual cohesion 0) that were stuck at the end
/// of the earlier steps slip on the way and end stuck. Their mobilised
/// friction is `|tau| / (-f sigma_n)` (0.61 to 0.94 on five pairs), not
/// `|tau| / (c - f sigma_n)` (0.20 to 0.47) as the outputs had it when they
/// took cracks from the earlier steps' end states.
#[test]
fn pairs_cracked_in_the_last_step_are_reported_against_their_cracked_bound() {
    let case = Case::new("crack-memory-dam3d");
    case.copy("geo/dam3d_joints.geo");
    let text = common::scenes::edited(
        "geo/dam3d_joints.toml",
        &[("setnumber = { lc = 4.0 }", "setnumber = { lc = 6.0, lc_rock = 25.0 }")],
    );
    let run = case.run(&case.write("dam3d_joints.toml", &text)).unwrap_or_else(|e| panic!("dam3d_joints: {e:#}"));
    let c = run.contact().expect("contact");
    assert!(c.summary.converged, "the last step converges");
    let strength = strengths(&run);
    let earlier = &run.steps[..run.steps.len() - 1];
    let stuck_before = |p: usize| earlier.iter().filter_map(|s| s.contact.as_ref()).all(|e| !e.is_cracked(p));
    let mut fresh = 0;
    for (p, pair) in run.model.pairs.iter().enumerate() {
        let (r, s) = (&c.pairs[p], &strength[pair.contact]);
        if c.states[p] != ContactState::Stick || !c.is_cracked(p) || !stuck_before(p) || s.cohesion == 0.0 {
            continue;
        }
        fresh += 1;
        let moved = c.summary.history[1..].iter().any(|set| set[p] != ContactState::Stick);
        assert!(moved, "pair {p}: cracked in the step, so solved slipping or open in it");
        let reported = resultants::mobilised(c.states[p], r, s, c.is_cracked(p));
        let cracked = r.tau() / (s.residual_cohesion - s.friction * r.sigma_n);
        let peak = r.tau() / (s.cohesion - s.friction * r.sigma_n);
        assert!((reported - cracked).abs() <= 1e-12, "pair {p}: mobilised {reported}, cracked bound gives {cracked}");
        assert!(reported <= 1.0 + 1e-9 && reported > 1.5 * peak, "pair {p}: {reported} (peak bound {peak})");
    }
    assert!(fresh >= 3, "cohesive pairs cracked in the last step that end stuck: {fresh}");
    faces_within_the_cracked_bound(&run);
}

/// The faces and blocks the outputs report (faces.csv, report.md,
/// blocks.csv) for the run's last step: each face's mobilised friction is
/// its pairs' largest `|tau| / (c - f sigma_n)`, with the residual
/// cohesion on the pairs the iteration cracked (1 where a pair slips or
/// opens), and none is above 1.
fn faces_within_the_cracked_bound(run: &Run) {
    let c = run.contact().expect("contact");
    let strength = strengths(run);
    let body = run.model.body_of_node();
    let mut want: std::collections::BTreeMap<(usize, [usize; 2]), f64> = Default::default();
    for (p, pair) in run.model.pairs.iter().enumerate() {
        let (r, s) = (&c.pairs[p], &strength[pair.contact]);
        let cohesion = if c.is_cracked(p) { s.residual_cohesion } else { s.cohesion };
        let limit = cohesion - s.friction * r.sigma_n;
        let m = match c.states[p] {
            ContactState::Stick if limit > 0.0 => r.tau() / limit,
            _ => 1.0,
        };
        let w = want.entry((pair.contact, [body[pair.k], body[pair.l]])).or_insert(0.0);
        *w = w.max(m);
    }
    let faces = resultants::of_run(run).expect("resultants").faces;
    assert_eq!(faces.len(), want.len());
    for f in &faces {
        let (got, w) = (f.resultant.mobilised, want[&(f.contact, f.blocks)]);
        assert!(got <= 1.0 + 1e-9, "face {:?} of contact {}: mobilised {got} above 1", f.blocks, f.contact);
        assert!((got - w).abs() <= 1e-12 * w.max(1.0), "face {:?}: mobilised {got}, cracked bound gives {w}", f.blocks);
    }
    let blocks = subcontact::output::blocks::of_run(run).expect("blocks");
    assert!(blocks.iter().all(|b| b.mobilised <= 1.0 + 1e-9), "a block mobilised above 1");
}
