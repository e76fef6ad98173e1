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
    reported_within_the_cracked_bound(&run, &cracked);
}

/// The faces and blocks the outputs report (faces.csv, report.md,
/// blocks.csv): every pair in `cracked` (and every one open or slipping at
/// the end) is cracked in the contact run, and each face's mobilised
/// friction is its pairs' largest, with the residual cohesion on those.
fn reported_within_the_cracked_bound(run: &Run, cracked: &[usize]) {
    let c = run.contact().expect("contact");
    let strength = strengths(run);
    let body = run.model.body_of_node();
    let mut want: std::collections::BTreeMap<(usize, [usize; 2]), f64> = Default::default();
    let mut stuck_cracked = 0;
    for (p, pair) in run.model.pairs.iter().enumerate() {
        let was = cracked.binary_search(&p).is_ok() || c.states[p] != ContactState::Stick;
        assert_eq!(c.is_cracked(p), was, "pair {p}: the run's crack is the iteration's");
        let (r, s) = (&c.pairs[p], &strength[pair.contact]);
        let cohesion = if was { s.residual_cohesion } else { s.cohesion };
        let limit = cohesion - s.friction * r.sigma_n;
        let m = match c.states[p] {
            ContactState::Stick if limit > 0.0 => r.tau() / limit,
            _ => 1.0,
        };
        stuck_cracked += usize::from(was && c.states[p] == ContactState::Stick);
        let w = want.entry((pair.contact, [body[pair.k], body[pair.l]])).or_insert(0.0);
        *w = w.max(m);
    }
    assert!(stuck_cracked >= 1, "stuck pairs that cracked in the step: {stuck_cracked}");
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
