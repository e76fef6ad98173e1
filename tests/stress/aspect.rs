//! 3. Aspect ratio up to 1000: the two-block stack of fixed shape with
//!    elements stretched 1:1000 along or across the joint, under uniform
//!    compression, where the exact solution is in every element space (so the
//!    error is round-off, bounded by [`aspect_tols`]); and a slender column of
//!    such elements, reported beside it.

use std::time::Instant;

use subcontact::contact::law::ContactState;
use subcontact::driver::Run;

use crate::common::measure::count;
use crate::stack::{uniform_errors, Stack};
use crate::table::Suite;
use crate::{converged, fmt_e, solve, states_note};

/// or 1 x 10 (tall: across it, dy/dx = AR), so that only the elements'
/// shape changes with AR, not the structure's; `m` scales the divisions.
pub fn aspect_case(s: &mut Suite, kinds: &[&str], ratios: &[f64], m: usize) {
    let left = "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n\n[[supports]]\ngroup = \"left\"\nfix = [\"x\"]\n";
    for &kind in kinds {
        for &ar in ratios {
            for flat in [true, false] {
                if ar == 1.0 && !flat {
                    continue;
                }
                let mut st = Stack::kind(kind);
                let (long, short) = (m * ((10.0 / ar).max(1.0) as usize), m * ((ar / 10.0).max(1.0) as usize));
                if flat {
                    (st.w, st.h, st.nx, st.ny) = (10.0, 1.0, long, short);
                } else {
                    (st.w, st.h, st.nx, st.ny) = (1.0, 10.0, short, long);
                    st.supports = left.into();
                }
                let (dx, dy) = (st.w / st.nx as f64, st.h / st.ny as f64);
                assert!(
                    ((if flat { dx / dy } else { dy / dx }) / ar - 1.0).abs() < 1e-12,
                    "aspect ratio of {kind} {ar}"
                );
                let name = format!("aspect_{kind}_{}_{ar:e}_{}x{}", if flat { "flat" } else { "tall" }, st.nx, st.ny);
                let t = Instant::now();
                let run = solve(&s.case, &name, &st.text(), false);
                let secs = t.elapsed().as_secs_f64();
                aspect_row(
                    s,
                    &run,
                    &st,
                    kind,
                    &format!("AR {} ({})", fmt_e(ar), if flat { "flat" } else { "tall" }),
                    Some(aspect_tols(ar, m)),
                    secs,
                );
            }
        }
    }
}

/// Bounds of the aspect case: round-off grows with the condition of the
/// stiffness, ~ (AR m)^2 for displacements and element stresses (m: the
/// mesh's refinement factor); the contact forces, read off `S d - G`
/// where the terms are ~ AR times the force they leave, one power of AR
/// more. With a = max(AR, 10) and eps = 2.2e-16: 100 eps (a m)^2 and
/// 10 eps a^3 m (at AR 1000, m = 1: 2.2e-8 and 2.2e-6). Measured: at most
/// a fifth of these (`stress.md`).
fn aspect_tols(ar: f64, m: usize) -> (f64, f64) {
    let (a, m) = (ar.max(10.0), m as f64);
    (100.0 * f64::EPSILON * (a * m).powi(2), 10.0 * f64::EPSILON * a.powi(3) * m)
}

#[allow(clippy::too_many_arguments)]
fn aspect_row(s: &mut Suite, run: &Run, st: &Stack, kind: &str, cond: &str, tol: Option<(f64, f64)>, secs: f64) {
    assert_eq!(run.model.bodies[0].cells[0].kind.name(), kind, "element kind of {}", run.scene.name);
    let c = converged(run);
    let all_stick = count(c, ContactState::Stick) == c.states.len();
    let (eu, es, ec) = uniform_errors(run, st, 1.0);
    let inf_unless = |ok: bool, v: f64| if ok { v } else { f64::INFINITY };
    let label = format!("aspect {kind} {}x{}", st.nx, st.ny);
    let res = Some(run.stats.residuals.interface);
    let note = format!(
        "u {eu:.1e}, sigma {es:.1e}; {}; {} x {} blocks; {} DOFs",
        states_note(c),
        st.w,
        st.h,
        run.stats.dofs.total
    );
    let rows = [
        ("uniform compression: nodal u and sigma vs exact", inf_unless(all_stick, eu.max(es)), tol.map(|t| t.0), note),
        (
            "uniform compression: contact sigma_n = -p, tau = 0",
            inf_unless(all_stick, ec),
            tol.map(|t| t.1),
            String::new(),
        ),
    ];
    for (i, (checks, error, t, note)) in rows.into_iter().enumerate() {
        let secs = if i == 0 { secs } else { 0.0 };
        match t {
            Some(t) => s.check(&label, checks, error, t, res, cond, secs, &note),
            None => s.report(&label, checks, error, res, cond, secs, &note),
        }
    }
}

/// A slender column (1 x 2000, held at one corner in x) of AR 1000
/// elements: the structure's slenderness, not the elements', costs digits
/// in the contact forces (read off S d - G): reported.
pub fn column_case(s: &mut Suite, kind: &str) {
    let mut st = Stack::kind(kind);
    (st.w, st.h, st.nx, st.ny) = (1.0, 1000.0, 4, 4);
    let t = Instant::now();
    let run = solve(&s.case, &format!("column_{kind}"), &st.text(), false);
    let secs = t.elapsed().as_secs_f64();
    aspect_row(s, &run, &st, kind, "AR 1e3 (tall), slenderness 2000", None, secs);
}
