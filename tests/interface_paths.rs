//! The sparse interface takes the dense one's path through the contact
//! states (issue 28: every interface solver reaches the same states as the
//! dense one on the same scene, in about as many iterations).
//!
//! The robust rule's friction Newton turns a slipping pair's slip into a
//! force with the pair's stiffness (`InterfaceProblem::stiffness`, the
//! interface's diagonal at its relative displacements). The dense
//! interface's is W's, the Schur complement on the relative displacements;
//! the sparse one took K_rr's, with the means held, and so took other
//! Newton steps from the same states. On the coarse jointed tet10 tunnel
//! (tests/geo/tunnel3d_joints_coarse.toml: 148 blocks, 7,160 pairs) the
//! two agreed on the states to iteration 20, the law's residual differing
//! from iteration 3 on (0.0454 / 0.0439 of the largest traction, 0.0141 /
//! 0.0284 at iteration 6), and the sparse one cycled around the junction
//! where J1 meets J2 at the wall for 400 iterations and 3 cuts where the
//! dense one converged in 38. With W's diagonal it takes the dense one's 38
//! iterations to the same 7,082 stick / 78 slip.
//!
//! The scene here is that tunnel with two of its sets (J1, J2) and a
//! coarser mesh (lc 3, 1,779 pairs, ~10 s each): the sparse interface took
//! 31 iterations there with K_rr's diagonal, the dense one 32. With W's it
//! followed the dense one's states and forces to 1e-13 up to iteration
//! 32, where its solve was loose (residual 3.2e-11); the next, a Newton
//! step from the same states, moved a junction's lagged pressure and two
//! pairs cycled (400 iterations, 3 cuts), until a settled solve that is
//! not tight was solved again with its own relations
//! (`contact/iteration.rs`).

mod common;

use common::scenes::edited;
use common::Case;
use subcontact::contact::InterfaceSolver;
use subcontact::driver::{self, RunOptions};
use subcontact::results::Run;

fn solve(case: &Case, scene: &str, interface: InterfaceSolver, name: &str) -> Run {
    let opts = RunOptions { out: Some(case.out(name)), interface: Some(interface), ..Default::default() };
    driver::run(&case.dir.join(scene), &opts).expect("the tunnel solves")
}

/// The same states pair by pair on the jointed tunnel with two sets,
/// dense and sparse, on one mesh (gmsh 4.8 does not mesh this .geo the
/// same twice: two meshes of it took 7 and 33 dense iterations). The
/// sparse interface takes more iterations: 99 against the dense one's 33
/// on one such mesh, measured; the bound catches a cycle (400 and cuts
/// before the settled solves were tightened with their own relations),
/// not yet "about as many" (issue 28).
#[test]
fn the_sparse_interface_reaches_the_dense_ones_states_on_the_jointed_tunnel() {
    let case = Case::new("interface-paths");
    case.copy("tests/geo/tunnel3d_joints.geo");
    let text = edited(
        "tests/geo/tunnel3d_joints_coarse.toml",
        &[
            ("setnumber = { lc = 2.0, lc_far = 4.0 }", "setnumber = { lc = 3.0, lc_far = 6.0, sets = 2 }"),
            ("[[contacts]]\ngroup = \"J3\"\nfriction = 0.7002\n\n", ""),
        ],
    );
    case.write("tunnel.toml", &text);
    let dense = solve(&case, "tunnel.toml", InterfaceSolver::Dense, "dense");
    // the sparse solve on the dense one's mesh
    std::fs::copy(case.out("dense").join("mesh/tunnel.msh"), case.dir.join("tunnel.msh")).expect("the mesh");
    let gmsh = text.find("[gmsh]").expect("a [gmsh] table");
    let end = gmsh + text[gmsh..].find("\n\n").expect("its end");
    let on_msh = format!("{}{}", &text[..gmsh], &text[end..]).replace("tunnel3d_joints.geo", "tunnel.msh");
    case.write("tunnel_msh.toml", &on_msh);
    let sparse = solve(&case, "tunnel_msh.toml", InterfaceSolver::Sparse, "sparse");
    assert_eq!((dense.stats.interface_solver, sparse.stats.interface_solver), ("dense", "sparse"));
    let (d, s) =
        (dense.steps[0].contact.as_ref().expect("contact"), sparse.steps[0].contact.as_ref().expect("contact"));
    assert!(d.summary.converged && s.summary.converged, "both converge");
    let (ds, ss) = (d.summary.iterations, s.summary.iterations);
    eprintln!("{} pairs: dense {ds} iterations, sparse {ss}", d.states.len());
    assert!(d.states.iter().any(|&st| st != subcontact::contact::law::ContactState::Stick), "some pairs slip");
    assert_eq!(s.states, d.states, "the same states pair by pair");
    assert!(ss <= 4 * ds, "dense {ds} iterations, sparse {ss}");
}
