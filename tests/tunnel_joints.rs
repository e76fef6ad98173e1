//! A tunnel in jointed rock (geo/tunnel_joints.toml, issue 17): a bare
//! circular opening in rock cut by three joint sets into blocks, under a
//! geostatic in-situ stress, the rock's weight and the overburden on top.
//!
//! ```text
//!        overburden p = rho g (50 - W) on top
//!   +-------------------------------+  y = W
//!   |---/-------/-------/-------/---|  a bedding plane y = y_k above the
//!   |  /     .-/--.    /       /    |  crown carries, on the blocks below
//!   |-/-----/-(   )---/-------/-----|  it, the weight of the rock above
//!   |/     /   `-'   /       /      |  and the overburden:
//!   |-----/-------- /-------/-------|    F_y = -(rho g V_above + p 2W)
//!   +-------------------------------+  y = -W; rollers on the sides
//! ```
//!
//! (below the invert V_above lacks the opening). The side rollers carry
//! no vertical force, so this holds exactly whatever the joints do.
//!
//! Run on the scene's box (W = 15 m, the opening R = 3 m, the joints from
//! its [[joint_sets]]) with a coarser mesh at the opening (lc = 1). (On a
//! 10 m box the traces cut slivers off its corners, 0.02 m thick, and the
//! contact iteration does not converge.) Goals, each asserted:
//! - the contact iteration converges;
//! - faces.csv: each of four bedding planes that cross the whole box
//!   (y = +-4.5, +-7.5) carries the weight above it and the overburden,
//!   F_y to 1e-8 (V_above from the mesh's own cells, so the curved opening
//!   counts as meshed); F_x there is what the side rollers leave;
//! - the rock mass loosens around the opening: the bedding plane just
//!   above the crown slips over it, some joints open, and report.md lists
//!   the most mobilised block faces.

mod common;

use common::Case;
use subcontact::contact::law::ContactState;
use subcontact::fem::element;

const RHO_G: f64 = 2.7e-3 * 9.81;
const W: f64 = 15.0;
const R: f64 = 3.0;

#[test]
fn bedding_planes_carry_the_rock_above_and_the_crown_loosens() {
    let case = Case::new("tunnel-joints");
    case.copy("geo/tunnel_joints.geo");
    let p_top = RHO_G * (50.0 - W);
    let text = common::scenes::edited(
        "geo/tunnel_joints.toml",
        &[
            ("setnumber = { lc = 0.6, lc_far = 2.0 }", "setnumber = { lc = 1.0, lc_far = 2.0 }"),
            ("pressure = 0.92704", &format!("pressure = {p_top}")),
        ],
    );
    let run = case.run(&case.write("tunnel_joints.toml", &text)).unwrap_or_else(|e| panic!("tunnel_joints: {e:#}"));
    let c = run.contact().expect("contact");
    assert!(c.summary.converged, "the contact iteration converges");
    let m = &run.model;

    // the volume (per unit thickness) of every block, from its own cells
    let volume: Vec<f64> = (m.bodies.iter())
        .map(|b| {
            b.cells
                .iter()
                .map(|cell| {
                    let x: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| m.coords[n]).collect();
                    let mut fe = vec![0.0; 2 * x.len()];
                    element::body_force(m.analysis, cell.kind, &x, [0.0, 1.0, 0.0], m.thickness, &mut fe)
                        .expect("a valid cell");
                    fe.iter().skip(1).step_by(2).sum::<f64>()
                })
                .sum()
        })
        .collect();
    let total: f64 = volume.iter().sum();
    let hole = (2.0 * W).powi(2) - total;
    eprintln!(
        "{} blocks, rock {total:.6} m^2, opening {hole:.6} m^2 (pi R^2 = {:.6})",
        m.bodies.len(),
        std::f64::consts::PI * R * R
    );
    assert!((hole / (std::f64::consts::PI * R * R) - 1.0).abs() < 1e-3, "the meshed opening is the circle");

    // every bedding plane across the whole box carries the rock above it
    let rows = common::csv_rows(&case.out("tunnel_joints").join("faces.csv"));
    let num = common::csv_num;
    for y in [7.5, 4.5, -4.5, -7.5] {
        let on: Vec<_> = rows.iter().filter(|r| r["contact"] == "bedding" && (num(r, "y") - y).abs() < 1e-9).collect();
        let fy: f64 = on.iter().map(|r| num(r, "f_y")).sum();
        let width: f64 = on.iter().map(|r| num(r, "area")).sum();
        let above: f64 =
            (0..m.bodies.len()).filter(|&b| m.bodies[b].block.expect("a block").centre[1] > y).map(|b| volume[b]).sum();
        let want = -(RHO_G * above + p_top * 2.0 * W);
        eprintln!(
            "bedding y = {y}: {} face pairs over {width:.6} m carry F_y = {fy:.10} against {want:.10} ({:.1e})",
            on.len(),
            ((fy - want) / want).abs()
        );
        assert!((width - 2.0 * W).abs() < 1e-9, "the plane y = {y} crosses the whole box");
        assert!(((fy - want) / want).abs() < 1e-8, "the plane y = {y} carries {fy}, not {want}");
    }

    // the rock loosens around the opening
    let k = common::measure::count;
    eprintln!(
        "{} pairs: {} stick, {} slip, {} open",
        c.states.len(),
        k(c, ContactState::Stick),
        k(c, ContactState::Slip),
        k(c, ContactState::Open)
    );
    assert!(k(c, ContactState::Open) > 0, "some joints open");
    let bedding = m.interfaces.iter().position(|i| i.name == "bedding").expect("bedding");
    let crown_slips = (0..m.pairs.len()).any(|p| {
        let x = m.coords[m.pairs[p].k];
        m.pairs[p].contact == bedding
            && (x[1] - 4.5).abs() < 1e-9
            && x[0].abs() < R
            && c.states[p] == ContactState::Slip
    });
    assert!(crown_slips, "the bedding plane above the crown slips over it");
    // report.md ranks the faces that matter: slivers and faces held by
    // supports at every pair are left out (faces.csv, column `ranked`)
    let ranked = rows.iter().filter(|r| r["ranked"] == "yes").count();
    let slivers = rows.iter().filter(|r| r["ranked"] == "sliver").count();
    eprintln!("{ranked} of {} face pairs ranked, {slivers} slivers", rows.len());
    assert!(ranked > 20 && ranked < rows.len(), "some faces are left out, not all");
    let report = common::read(&case.out("tunnel_joints").join("report.md"));
    assert!(
        report.contains(&format!("The 20 most mobilised of {ranked} block face pairs")),
        "report.md lists the most mobilised face pairs that matter"
    );
    assert!(report.contains(&format!("Left out: {slivers} sliver(s)")), "report.md says what it left out");
}
