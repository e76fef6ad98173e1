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
//! coarser mesh (lc 3, 1,779 pairs, ~5 s each). With W's diagonal the
//! sparse interface followed the dense one's states and forces to 1e-13
//! up to iteration 32, where its solve was loose (residual 3.2e-11); the
//! next, a Newton step from the same states, moved a junction's lagged
//! pressure and two pairs cycled (400 iterations, 3 cuts). Late in a step
//! a settled answer that was not tight is now solved again with its own
//! relations (`contact/iteration.rs`, `TIGHTEN_AFTER`).

mod common;

use common::scenes::tunnel_two_sets;
use common::Case;
use subcontact::contact::InterfaceSolver;
use subcontact::driver::{self, RunOptions};
use subcontact::results::Run;

fn solve(case: &Case, scene: &str, interface: InterfaceSolver, name: &str) -> Run {
    let opts = RunOptions { out: Some(case.out(name)), interface: Some(interface), ..Default::default() };
    driver::run(&case.dir.join(scene), &opts).expect("the tunnel solves")
}

/// The same states pair by pair on the jointed tunnel with two sets,
/// dense and sparse, in about as many iterations, on one mesh of it kept
/// in tests/geo/tunnel3d_joints_2sets.msh: gmsh 4.8 does not mesh this
/// .geo the same twice, and the iterations depend on the mesh (7, 26, 32
/// and 33 dense iterations on four meshes; on a fifth the dense interface
/// did not converge in 400: issue 28). On this one: dense 32, sparse 33
/// when this test was written; 45 and 49 since the cycle breaker stops
/// holding a decided change (2509578); 16 and 46 once a junction's
/// pressures were solved for wherever its feedback's real parts are
/// below 3/4 (`junction/pressure.rs`): the cycle met at iteration 5 was
/// broken there on the dense interface, and held for another Newton step
/// on the sparse one, whose solve was loose (a change of states), so
/// that whether the change was decided was not known. Since a loose
/// verdict of the breaker stands only where each comparison it turns on
/// is clear of the solve's error, and is solved again tightly elsewhere
/// (`newton.rs`, `MARGIN`, `Cycle::Undecided`), the sparse interface
/// takes the dense one's path: 16 and 16 (20 while every such verdict
/// was solved again).
#[test]
fn the_sparse_interface_takes_the_dense_ones_path_on_the_jointed_tunnel() {
    let case = Case::new("interface-paths");
    case.write("tunnel.toml", &tunnel_two_sets(&case));
    let dense = solve(&case, "tunnel.toml", InterfaceSolver::Dense, "dense");
    let sparse = solve(&case, "tunnel.toml", InterfaceSolver::Sparse, "sparse");
    assert_eq!((dense.stats.interface_solver, sparse.stats.interface_solver), ("dense", "sparse"));
    let (d, s) =
        (dense.steps[0].contact.as_ref().expect("contact"), sparse.steps[0].contact.as_ref().expect("contact"));
    assert!(d.summary.converged && s.summary.converged, "both converge");
    let (ds, ss) = (d.summary.iterations, s.summary.iterations);
    eprintln!("{} pairs: dense {ds} iterations, sparse {ss}", d.states.len());
    assert!(d.states.iter().any(|&st| st != subcontact::contact::law::ContactState::Stick), "some pairs slip");
    assert_eq!(s.states, d.states, "the same states pair by pair");
    // (at most one solve again per change the cycle breaker makes: here
    // four, each a single change, and none needed)
    assert!(ds <= 20 && ss <= ds + 4, "dense {ds} iterations, sparse {ss}");
    // the dense interface never solves loosely, so never solves again
    assert_eq!(d.summary.tight_resolves, 0);
    assert!(
        s.summary.tight_resolves <= ss.saturating_sub(ds),
        "sparse {ss} iterations, {} again",
        s.summary.tight_resolves
    );
}
