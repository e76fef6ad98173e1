//! Skipping what a scene does not need, shown by the counters in
//! summary.json (`counters`, `parts`, `dofs`), not by timings:
//!
//! - no contacts: no condensation, one factorisation and solve per part;
//! - a body without contact is never condensed, even beside contacts;
//! - each part is factorised once for all contact iterations and load steps;
//! - stresses are not recovered when `[output] fields` leaves them out, and
//!   interior displacements not at all when nothing needs them;
//! - a 2D scene has two unknowns per node.

mod common;

use common::{read, repo_text, scenes, Case};

fn counters(run: &subcontact::driver::Run) -> &subcontact::driver::Counters {
    &run.stats.counters
}

/// geo/cylinder.* copied into the case, coarsened, with the scene text edited.
fn cylinder(case: &Case, edit: &dyn Fn(String) -> String) -> std::path::PathBuf {
    case.copy("geo/cylinder.geo");
    let text = scenes::edited("geo/cylinder.toml", &[("setnumber = { lc = 0.05 }", "setnumber = { lc = 0.2 }")]);
    case.write("cylinder.toml", &edit(text))
}

#[test]
fn no_contacts_means_no_condensation_and_one_solve() {
    let case = Case::new("skip-bonded");
    let scene = cylinder(&case, &|t| t);
    let run = case.run_with(&scene, true).expect("bonded run");
    assert_eq!(run.stats.dofs.interface, 0);
    assert_eq!(counters(&run).condensed_parts, 0);
    assert_eq!(counters(&run).factorisations, 1, "the two bodies share nodes: one part, one factorisation");
    assert_eq!(counters(&run).interface_solves, 0);
    assert!(run.contact().is_none());
}

#[test]
fn a_body_without_contact_is_not_condensed() {
    // the block-push scene plus a third, separate body with its own support
    let case = Case::new("skip-third-body");
    let geo = repo_text("geo/block_push.geo");
    let geo = geo
        + "\nPoint(20) = {3, 0, 0};\nPoint(21) = {4, 0, 0};\nPoint(22) = {4, 1, 0};\nPoint(23) = {3, 1, 0};\n\
           Line(20) = {20, 21};\nLine(21) = {21, 22};\nLine(22) = {22, 23};\nLine(23) = {23, 20};\n\
           Curve Loop(20) = {20, 21, 22, 23};\nPlane Surface(20) = {20};\nRecombine Surface{20};\n\
           Physical Surface(\"pier\") = {20};\nPhysical Curve(\"pier_bottom\") = {20};\nPhysical Curve(\"pier_top\") = {22};\n";
    case.write("block_push.geo", &geo);
    let toml = repo_text("geo/block_push.toml")
        + "\n[[bodies]]\ngroup = \"pier\"\nmaterial = \"concrete\"\n\n[[supports]]\ngroup = \"pier_bottom\"\nfix = [\"x\", \"y\"]\n\n\
           [[loads]]\ngroup = \"pier_top\"\npressure = 2.0\n";
    let scene = case.write("block_push.toml", &toml);
    let run = case.run(&scene).expect("run");
    assert_eq!(run.stats.parts.total, 3);
    assert_eq!(counters(&run).factorisations, 3);
    assert_eq!(counters(&run).condensed_parts, 2, "only the base and the block have a contact interface");
}

#[test]
fn parts_are_factorised_once_for_all_iterations_and_load_steps() {
    let case = Case::new("skip-steps");
    case.copy("geo/block_push.geo");
    let toml = repo_text("geo/block_push.toml") + "\n[solver]\nload_steps = 3\n";
    let scene = case.write("block_push.toml", &toml);
    let run = case.run(&scene).expect("run");
    let c = counters(&run);
    assert_eq!(run.steps.len(), 3);
    let iterations: usize = run.steps.iter().map(|s| s.contact.as_ref().expect("contact").summary.iterations).sum();
    assert!(iterations > 3, "the friction needs several iterations per step ({iterations})");
    assert_eq!(c.interface_solves, iterations);
    assert_eq!(c.factorisations, 2, "two parts, each factorised once for {iterations} interface solves in 3 steps");
}

#[test]
fn stresses_are_not_recovered_when_not_asked_for() {
    let case = Case::new("skip-fields");
    let only_u = cylinder(&case, &|t| t.replace("[analytic]", "[output]\nfields = [\"displacement\"]\n\n[analytic]"));
    let run = case.run(&only_u).expect("run");
    assert_eq!(counters(&run).stress_recoveries, 0);
    assert!(run.last().stresses.is_empty());
    let vtu = read(&case.out("cylinder").join("cylinder.vtu"));
    assert!(vtu.contains("Name=\"displacement\"") && !vtu.contains("Name=\"stress\"") && !vtu.contains("von_mises"));

    // nothing asked for at all (no fields, no probes, no closed form): no interior recovery
    let case = Case::new("skip-nothing");
    let nothing = cylinder(&case, &|t| {
        let t = t[..t.find("# Table 1").expect("probes")].to_string();
        t + "\n[output]\nfields = []\n"
    });
    let run = case.run(&nothing).expect("run");
    assert_eq!(counters(&run).interior_recoveries, 0);
    assert_eq!(counters(&run).stress_recoveries, 0);
    assert!(run.contact().expect("contact").summary.converged);
}

#[test]
fn plane_scenes_have_two_unknowns_per_node() {
    let case = Case::new("skip-2d");
    let scene = cylinder(&case, &|t| t);
    let run = case.run_with(&scene, true).expect("run");
    assert_eq!(run.model.nd, 2);
    assert_eq!(run.last().u.len(), 2 * run.model.n_nodes());
}
