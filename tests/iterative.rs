//! The iterative interface (`[solver] interface = "iterative"`: no S
//! formed, GMRES applying S through the parts' interior factors) must give
//! the dense interface's answer: the same contact states at every step, and
//! displacements and contact stresses to 1e-8 of their largest values (the
//! GMRES tolerance is 1e-10 of the load).
//!
//! The friction law's linearisation takes a stiffness per pair (the `c`
//! of `ξ = τ + c s`): W's diagonal on the dense interface; here, where W
//! is never formed, the preconditioner's diagonal scaled down to W's on a
//! sample of pairs (src/contact/system/iterative/stiffness.rs). Any `c`
//! has the same answers, not the same path: with the preconditioner's
//! diagonal alone (3.4 times W's on the corpus cavern) the dam's step 2
//! took 8 iterations against the dense interface's 7 and ended 3.5e-9
//! apart in contact stress (9.5e-7 when first measured), and the cavern
//! below did not converge. Scaled, the dam takes 7 and ends 4.1e-9 apart
//! (asserted below 1e-7 after its first step), the cavern 6 as the dense
//! interface does, 4.5e-9 apart (below 1e-7).
//!
//! Cases that reach every kind of interface unknown:
//!
//! - block on block, tet10 (quadratic faces in the transformed basis),
//!   oblique load: stick and slip, the friction law linearised;
//! - the dam slice, three load steps: joints ending on a supported base
//!   (held contact axes), gravity and water, pairs that open;
//! - the corpus cavern, tet10, two oblique sets the tool cuts, a
//!   full-tensor in-situ stress: 154 pairs slipping at rigid joints;
//! - a column cut into 4 substructures, hex8 and hex20 (quad8 faces),
//!   pressed and pushed: bonded joins beside the contact.

mod common;

use common::Case;
use subcontact::contact::InterfaceSolver;
use subcontact::driver::{self, RunOptions};
use subcontact::results::Run;

fn solve(case: &Case, scene: &str, interface: InterfaceSolver, substructures: usize) -> Run {
    let out = case.out(&format!("{}-{interface:?}-k{substructures}", scene.trim_end_matches(".toml")));
    let opts = RunOptions {
        out: Some(out),
        interface: Some(interface),
        substructures: Some(substructures),
        ..Default::default()
    };
    driver::run(&case.dir.join(scene), &opts).unwrap_or_else(|e| panic!("{scene}, {interface:?}: {e:#}"))
}

/// Largest differences of displacements and contact stresses (every step),
/// relative to the largest value of each, and of contact stresses at the
/// first step; the states must be the same.
fn differences(a: &Run, b: &Run) -> (f64, f64, f64) {
    let rel = |x: Vec<(f64, f64)>| {
        let scale = x.iter().fold(0.0f64, |m, (p, _)| m.max(p.abs())).max(f64::MIN_POSITIVE);
        x.iter().fold(0.0f64, |m, (p, q)| m.max((p - q).abs())) / scale
    };
    let u = rel(a.last().u.iter().copied().zip(b.last().u.iter().copied()).collect());
    assert_eq!(a.steps.len(), b.steps.len());
    let mut pairs = Vec::new();
    let mut first = f64::NAN;
    for (sa, sb) in a.steps.iter().zip(&b.steps) {
        let (ca, cb) = (sa.contact.as_ref().expect("contact"), sb.contact.as_ref().expect("contact"));
        assert_eq!(ca.states, cb.states, "the same contact states at step {}", sa.step);
        let step: Vec<(f64, f64)> = ca
            .pairs
            .iter()
            .zip(&cb.pairs)
            .flat_map(|(p, q)| [(p.sigma_n, q.sigma_n), (p.tau_t, q.tau_t), (p.tau_b, q.tau_b)])
            .collect();
        if first.is_nan() {
            first = rel(step.clone());
        }
        pairs.extend(step);
    }
    (u, rel(pairs), first)
}

/// `[first, later]`: the bounds on contact stresses at the first step
/// and after it (displacements: 1e-8).
fn same_answer(case: &Case, scene: &str, dense_k: usize, iterative_k: usize, [bound, later]: [f64; 2]) {
    let dense = solve(case, scene, InterfaceSolver::Dense, dense_k);
    let iterative = solve(case, scene, InterfaceSolver::Iterative, iterative_k);
    assert_eq!(dense.stats.counters.interface_applications, 0);
    assert!(iterative.stats.counters.interface_applications > 0, "{scene}: the iterative run applied no S");
    let (u, t, first) = differences(&dense, &iterative);
    let its: Vec<usize> =
        iterative.steps.iter().filter_map(|s| s.contact.as_ref().map(|c| c.summary.iterations)).collect();
    eprintln!(
        "{scene}: {} interface DOFs, contact iterations {its:?}, {} applications of S: displacements {u:.1e}, contact stresses {t:.1e} ({first:.1e} at step 1)",
        iterative.stats.dofs.interface, iterative.stats.counters.interface_applications
    );
    assert!(u < 1e-8 && first < bound && t < later.max(bound), "{scene}: iterative against dense: displacements differ by {u:.1e}, contact stresses by {t:.1e} ({first:.1e} at step 1)");
}

#[test]
fn block_on_block_tet10_in_partial_slip_solved_iteratively_is_the_dense_answer() {
    let case = Case::new("iterative-blocks");
    let scene = common::scenes::coarse_blocks(&case);
    same_answer(&case, scene, 1, 1, [1e-8; 2]);
}

#[test]
fn the_dam_slice_over_three_load_steps_solved_iteratively_is_the_dense_answer() {
    let case = Case::new("iterative-dam3d");
    case.copy("geo/dam3d.geo");
    case.copy("geo/dam3d.toml");
    same_answer(&case, "dam3d.toml", 1, 1, [1e-8, 1e-7]);
}

/// The corpus cavern (tests/corpus/cavern3d.toml: tet10, two oblique
/// sets, a full-tensor in-situ stress, rigid joints): the dense and the
/// sparse interface end in 6 iterations. With the friction law
/// linearised at the preconditioner's diagonal this one went through 100
/// state sets without converging (the run fell back to joints that
/// deform: 1,863 / 107 / 0 where the rigid joints end 1,815 / 154 / 1);
/// scaled to W's diagonal, it converges in 6, the same states pair by
/// pair.
#[test]
fn the_corpus_cavern_solved_iteratively_is_the_dense_answer() {
    let case = Case::new("iterative-cavern");
    case.copy("tests/corpus/cavern3d.geo");
    case.copy("tests/corpus/cavern3d.toml");
    same_answer(&case, "cavern3d.toml", 1, 1, [1e-7; 2]);
}

#[test]
fn a_column_cut_into_substructures_solved_iteratively_is_the_uncut_dense_answer() {
    let case = Case::new("iterative-column");
    common::scenes::column(&case, "column.toml", &[("lc = 0.0357142857142857", "lc = 0.125")]);
    same_answer(&case, "column.toml", 1, 4, [1e-8; 2]);
    // hex20: serendipity quad8 faces in the transformed contact basis
    common::scenes::column(
        &case,
        "column20.toml",
        &[("order = 1", "order = 2"), ("lc = 0.0357142857142857, hex = 1", "lc = 0.25, hex = 1, serendipity = 1")],
    );
    same_answer(&case, "column20.toml", 1, 4, [1e-8; 2]);
}
