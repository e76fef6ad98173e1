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

mod common;

use common::Case;
use subcontact::contact::law::ContactState;
use subcontact::output::resultants::strengths;

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
}
