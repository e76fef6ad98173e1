//! Bodies cut into substructures (`[solver] substructures = K`): METIS cuts
//! every part into K pieces joined by bonded joins, and the answer must be
//! the uncut one to 1e-9: the same states, displacements and contact
//! stresses. Two cases:
//!
//! - block on block (geo/blocks3d.geo, tet10), K = 2 and 4: a few joins
//!   beside many contact unknowns, eliminated densely with the pairs' means;
//! - column on column (scripts/scaling/column.toml, coarse hex8 and hex20),
//!   K = 4: the joins (3 cuts per body) outnumber the contact unknowns, so
//!   they are eliminated by the sparse factorisation of contact/system/joins.rs.
//!
//! The load is the scenes' oblique traction: part of each joint slips.

mod common;

use common::Case;
use subcontact::driver::{self, RunOptions};
use subcontact::results::Run;

fn solve(case: &Case, scene: &str, k: usize) -> Run {
    let out = case.out(&format!("{}-k{k}", scene.trim_end_matches(".toml")));
    let opts = RunOptions { out: Some(out), substructures: Some(k), ..Default::default() };
    driver::run(&case.dir.join(scene), &opts).unwrap_or_else(|e| panic!("{scene}, {k} substructures: {e:#}"))
}

/// Largest differences of displacements and contact stresses, relative to
/// the largest value of each.
fn differences(a: &Run, b: &Run) -> (f64, f64) {
    let rel = |x: Vec<(f64, f64)>| {
        let scale = x.iter().fold(0.0f64, |m, (p, _)| m.max(p.abs())).max(f64::MIN_POSITIVE);
        x.iter().fold(0.0f64, |m, (p, q)| m.max((p - q).abs())) / scale
    };
    let u = rel(a.last().u.iter().copied().zip(b.last().u.iter().copied()).collect());
    let (ca, cb) = (a.contact().expect("contact"), b.contact().expect("contact"));
    assert_eq!(ca.states, cb.states, "the same contact states");
    let t = rel(ca
        .pairs
        .iter()
        .zip(&cb.pairs)
        .flat_map(|(p, q)| [(p.sigma_n, q.sigma_n), (p.tau_t, q.tau_t), (p.tau_b, q.tau_b)])
        .collect());
    (u, t)
}

fn same_answer_when_cut(case: &Case, scene: &str, cuts: &[usize]) {
    let whole = solve(case, scene, 1);
    for &k in cuts {
        let cut = solve(case, scene, k);
        assert!(
            cut.stats.parts.total > whole.stats.parts.total,
            "{scene}: {k} substructures cut the parts ({} -> {})",
            whole.stats.parts.total,
            cut.stats.parts.total
        );
        let (u, t) = differences(&whole, &cut);
        eprintln!("{scene}, {k} substructures: {} parts, {} interface DOFs (uncut {}): displacements {u:.1e}, contact stresses {t:.1e}", cut.stats.parts.total, cut.stats.dofs.interface, whole.stats.dofs.interface);
        assert!(
            u < 1e-9 && t < 1e-9,
            "{scene}, {k} substructures: displacements differ by {u:.1e}, contact stresses by {t:.1e}"
        );
    }
}

#[test]
fn block_on_block_cut_into_substructures_gives_the_uncut_answer() {
    let case = Case::new("substructures-blocks");
    let scene = common::scenes::coarse_blocks(&case);
    same_answer_when_cut(&case, scene, &[2, 4]);
}

#[test]
fn a_column_whose_joins_outnumber_its_contact_unknowns_gives_the_uncut_answer() {
    let case = Case::new("substructures-column");
    common::scenes::column(&case, "column.toml", &[("lc = 0.0357142857142857", "lc = 0.125")]);
    same_answer_when_cut(&case, "column.toml", &[4]);
    common::scenes::column(
        &case,
        "column20.toml",
        &[("order = 1", "order = 2"), ("lc = 0.0357142857142857, hex = 1", "lc = 0.25, hex = 1, serendipity = 1")],
    );
    same_answer_when_cut(&case, "column20.toml", &[4]);
}
