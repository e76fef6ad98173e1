//! 2. Near incompressibility, nu = 0.45, 0.49, 0.499 (against 0.3), on
//!    Lamé's cylinder: the linear quadrilateral and hexahedron take their
//!    dilatation at the element mean (B-bar, `fem::element`) and keep their
//!    displacement accuracy, asserted; so do the quadratic kinds (quad9,
//!    quad8, tri6), asserted; tri3 has no remedy and locks, reported. The
//!    stresses degrade as lambda/mu for the quadratic kinds (their pressure
//!    error), reported for all.

use std::time::Instant;

use crate::common::scenes::lame_cylinder;
use crate::solve;
use crate::table::Suite;

/// How a kind behaves as nu -> 1/2.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    /// Quadratic: does not lock (displacement asserted).
    Quadratic,
    /// Linear with B-bar: does not lock (displacement and its growth asserted).
    BBar,
    /// Linear without a remedy: locks (reported).
    Locks,
}

/// (kind, geo, order, setnumber extras, behaviour): quad4 and quad9 on
/// geo/cylinder.geo (as lame.rs), tri3 / quad8 / tri6 on
/// tests/geo/stress_annulus.geo, hex8 on tests/geo/lame_slice.geo (solid,
/// w = 0 on both faces: plane strain).
const LOCK_KINDS: &[(&str, &str, usize, &str, Kind)] = &[
    ("quad4", "cylinder.geo", 1, "", Kind::BBar),
    ("hex8", "lame_slice.geo", 1, "", Kind::BBar),
    ("tri3", "stress_annulus.geo", 1, ", quad = 0", Kind::Locks),
    ("quad9", "cylinder.geo", 2, "", Kind::Quadratic),
    ("quad8", "stress_annulus.geo", 2, ", quad = 1, serendipity = 1", Kind::Quadratic),
    ("tri6", "stress_annulus.geo", 2, ", quad = 0", Kind::Quadratic),
];

/// B-bar kinds: the displacement error at nu = 0.499 (B-bar) is at most
/// this multiple of the one at nu = 0.3 (plain B; before B-bar quad4's
/// grew x128).
const B_BAR_GROWTH: f64 = 2.0;

fn lame_scene(geo: &str, order: usize, lc: f64, extra: &str, nu: f64) -> String {
    let gmsh = format!("order = {order}\nsetnumber = {{ lc = {lc}{extra} }}");
    let title = format!("Lame cylinder, nu = {nu}");
    match geo {
        "lame_slice.geo" => lame_cylinder(
            &title,
            geo,
            "solid",
            &gmsh,
            nu,
            &["body"],
            &[("x0", "[\"x\"]"), ("y0", "[\"y\"]"), ("z0", "[\"z\"]"), ("z1", "[\"z\"]")],
        ),
        _ => {
            let bodies = if geo == "cylinder.geo" { ["body_1", "body_2"] } else { ["inner_ring", "outer_ring"] };
            lame_cylinder(
                &title,
                geo,
                "plane_strain",
                &gmsh,
                nu,
                &bodies,
                &[("symmetry_x0", "[\"x\"]"), ("symmetry_y0", "[\"y\"]")],
            )
        }
    }
}

/// The locking study at element size `lc` for `kinds`; `tol_u` bounds the
/// displacement L2 error of the kinds that do not lock.
pub fn locking_case(s: &mut Suite, lc: f64, kinds: &[&str], tol_u: f64) {
    let nus = [0.3, 0.45, 0.49, 0.499];
    for &(kind, geo, order, extra, behaviour) in LOCK_KINDS.iter().filter(|k| kinds.contains(&k.0)) {
        let mut eu = Vec::new();
        let mut es = Vec::new();
        for &nu in &nus {
            let name = format!("lame_{kind}_lc{lc}_nu{nu}");
            let t = Instant::now();
            let run = solve(&s.case, &name, &lame_scene(geo, order, lc, extra, nu), false);
            let secs = t.elapsed().as_secs_f64();
            assert_eq!(run.model.bodies[0].cells[0].kind.name(), kind, "element kind of {name}");
            let e = run.checks.errors.as_ref().expect("[analytic] errors");
            let cond = format!("nu = {nu}, lambda/mu = {:.0}", 2.0 * nu / (1.0 - 2.0 * nu));
            let label = format!("locking {kind} lc {lc}");
            let cells: usize = run.model.bodies.iter().map(|b| b.cells.len()).sum();
            let note = format!("{cells} cells, {} DOFs; stress_l2 {:.2e}", run.stats.dofs.total, e.stress_l2);
            match behaviour {
                Kind::Quadratic => {
                    s.check(
                        &label,
                        "displacement L2 error vs Lamé",
                        e.displacement_l2,
                        tol_u,
                        None,
                        &cond,
                        secs,
                        &note,
                    );
                    s.report(
                        &label,
                        "stress L2 error vs Lamé (pressure error ~ lambda: reported)",
                        e.stress_l2,
                        None,
                        &cond,
                        0.0,
                        "",
                    );
                }
                Kind::BBar if nu < subcontact::fem::element::B_BAR_FROM_NU => {
                    s.report(
                        &label,
                        "displacement L2 error vs Lamé (plain B below nu = 0.4)",
                        e.displacement_l2,
                        None,
                        &cond,
                        secs,
                        &note,
                    );
                }
                Kind::BBar => {
                    s.check(
                        &label,
                        "displacement L2 error vs Lamé (B-bar)",
                        e.displacement_l2,
                        tol_u,
                        None,
                        &cond,
                        secs,
                        &note,
                    );
                    s.report(
                        &label,
                        "stress L2 error vs Lamé (B-bar: element-constant pressure)",
                        e.stress_l2,
                        None,
                        &cond,
                        0.0,
                        "",
                    );
                }
                Kind::Locks => s.report(
                    &label,
                    "displacement L2 error vs Lamé (locks: no remedy implemented)",
                    e.displacement_l2,
                    None,
                    &cond,
                    secs,
                    &note,
                ),
            }
            eu.push(e.displacement_l2);
            es.push(e.stress_l2);
        }
        let label = format!("locking {kind} lc {lc}");
        let trend = format!(
            "u {}; stress {}",
            eu.iter().map(|v| format!("{v:.2e}")).collect::<Vec<_>>().join(" -> "),
            es.iter().map(|v| format!("{v:.2e}")).collect::<Vec<_>>().join(" -> ")
        );
        let growth = eu[3] / eu[0];
        match behaviour {
            Kind::Quadratic => s.report(
                &label,
                "displacement error growth nu 0.3 -> 0.499",
                growth,
                None,
                "nu 0.3 -> 0.499",
                0.0,
                &trend,
            ),
            Kind::BBar => s.check(
                &label,
                "displacement error growth nu 0.3 -> 0.499 (B-bar)",
                growth,
                B_BAR_GROWTH,
                None,
                "nu 0.3 -> 0.499",
                0.0,
                &trend,
            ),
            Kind::Locks => s.report(
                &label,
                "displacement error growth nu 0.3 -> 0.499 (locking trend)",
                growth,
                None,
                "nu 0.3 -> 0.499",
                0.0,
                &trend,
            ),
        }
    }
}
