//! A pair that has parted (opened, closed and opened again in a step)
//! closes again without cohesion (issue 28, the law's tension cut-off:
//! `src/contact/law.rs`).
//!
//! tests/corpus/slope2d_c020.toml (a 2D rock cut, bedding c = 0.02, cross
//! set f = 0.7, c = 0.05 = its residual cohesion, gravity in four steps):
//! in step 4 the cross-set pair of the crest wedge at the east roller,
//! (69.17, 29.25), is stuck at sigma_n = +9.4e-5 MPa (a little tension:
//! f_t = 0) under a shear of 7.1e-3 MPa, far below its cohesion. Open, it
//! carries nothing and the wedge overlaps it by 1.7e-7 m: under the law
//! where it closed with its residual cohesion, stuck again, it had no
//! state that held (412 iterations and 3 cuts, not converged). Once it
//! has parted it closes without cohesion and slips on its friction alone:
//!
//! ```text
//!   |tau| = f (-sigma_n)          (c A + f p before: c lost with the opening)
//! ```
//!
//! and the step converges (6 iterations). Every pair solved open in the
//! step's iterates that ends closed (here each has parted) carries at most
//! f p, and at least one (the wedge's) slips on it.

mod common;

use common::Case;
use subcontact::contact::law::ContactState;
use subcontact::output::resultants::strengths;

#[test]
fn the_crest_wedge_pair_that_opened_slips_on_its_friction_alone() {
    let case = Case::new("opened-cohesion");
    case.copy("tests/corpus/slope2d.geo");
    let run = case.run(&case.copy("tests/corpus/slope2d_c020.toml")).unwrap_or_else(|e| panic!("c020: {e:#}"));
    let c = run.contact().expect("contact");
    assert!(c.summary.converged, "the last step converges");
    assert!(c.summary.iterations <= 30, "in {} iterations", c.summary.iterations);
    let strength = strengths(&run);
    let scale = c.pairs.iter().map(|r| r.sigma_n.hypot(r.tau())).fold(0.0, f64::max);
    let sets = &c.summary.history;
    let opened: Vec<usize> = (0..c.states.len())
        .filter(|&p| sets[1..].iter().any(|s| s[p] == ContactState::Open) && c.states[p] != ContactState::Open)
        .collect();
    assert!(!opened.is_empty(), "a pair opened in the step and closed again");
    let mut on_the_bound = 0;
    for &p in &opened {
        let (r, s) = (&c.pairs[p], &strength[run.model.pairs[p].contact]);
        assert!(s.residual_cohesion > 0.0, "pair {p}: a joint that keeps cohesion once slipping");
        let bound = -s.friction * r.sigma_n;
        assert!(r.sigma_n <= 1e-9 * scale, "pair {p}: no tension once opened ({})", r.sigma_n);
        assert!(r.tau() <= bound + 1e-9 * scale, "pair {p}: tau {} beyond f p = {bound}", r.tau());
        if c.states[p] == ContactState::Slip {
            assert!((r.tau() - bound).abs() <= 1e-9 * scale, "pair {p} slips at tau {} = f p {bound}", r.tau());
            on_the_bound += 1;
        }
    }
    assert!(on_the_bound >= 1, "the wedge's pair slips on friction alone: {opened:?}");
}
