//! Coulomb slip in 3D follows the tangential slip vector, not a fixed axis.
//!
//! Two boxes stacked along y (tests/geo/contact_stack3d.geo), the bottom one
//! clamped at y = 0; the top face of the upper box is pressed down by a
//! prescribed uy = -2e-3 (so it cannot tilt and lift the trailing edge) and
//! moved by (a, 0, b) with a = 1e-2, b = 6e-3 (several times what the boxes
//! take in shear at the friction limit), so the joint slides along a
//! direction that is neither local axis of the pairs' frames. With cohesion 0
//! and friction f = 0.3 the joint slips (corners may stick under their stress
//! concentration); the shear traction of every slipping pair must have
//! magnitude f |sigma_n| and point along the relative slip of the upper box
//! (the friction on the lower box, body I, is dragged along by the upper).

mod common;

use common::measure::count;
use common::scenes::two_blocks;
use common::Case;
use subcontact::contact::frame::frame;
use subcontact::contact::law::ContactState;

#[test]
fn friction_in_3d_follows_the_slip_vector_and_has_the_coulomb_magnitude() {
    let case = Case::new("slide3d");
    case.copy("tests/geo/contact_stack3d.geo");
    let head = r#"title = "a box slid diagonally across another"
mesh = "contact_stack3d.geo"
analysis = "solid"

[gmsh]
order = 2
setnumber = { n = 3, nz = 2, hex = 1 }"#;
    // the base clamped; the top face pressed down and moved diagonally
    let supports = r#"[[supports]]
group = "base"
fix = ["x", "y", "z"]

[[supports]]
group = "top_face"
ux = 1.0e-2
uy = -2.0e-3
uz = 6.0e-3
"#;
    let toml = two_blocks(head, 1000.0, 0.25, "friction = 0.3\ncohesion = 0.0\ntensile_strength = 0.0", supports);
    let run = case.run(&case.write("slide.toml", &toml)).expect("run");
    let c = run.contact().expect("contact");
    assert!(c.summary.converged);
    let nd = run.model.nd;
    let mut worst_mag: f64 = 0.0;
    let mut worst_dir: f64 = 0.0;
    let slipping = count(c, ContactState::Slip);
    assert!(slipping * 10 >= 9 * c.states.len(), "{slipping} of {} pairs slip", c.states.len());
    for (p, pair) in run.model.pairs.iter().enumerate() {
        if c.states[p] != ContactState::Slip {
            continue; // a corner may stick under its stress concentration
        }
        let r = &c.pairs[p];
        assert!(r.sigma_n < 0.0, "pressed");
        worst_mag = worst_mag.max((r.tau() - 0.3 * r.sigma_n.abs()).abs() / (0.3 * r.sigma_n.abs()));
        // the shear traction in global axes, and the relative slip of l
        let f = frame(3, pair.normal, [false; 3]);
        let tau: Vec<f64> = (0..3).map(|i| r.tau_t * f[1][i] + r.tau_b * f[2][i]).collect();
        let rel: Vec<f64> = (0..3).map(|i| run.last().u[pair.l * nd + i] - run.last().u[pair.k * nd + i]).collect();
        let rn = (0..3).map(|i| rel[i] * pair.normal[i]).sum::<f64>();
        let slip: Vec<f64> = (0..3).map(|i| rel[i] - rn * pair.normal[i]).collect();
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let cos = (0..3).map(|i| tau[i] * slip[i]).sum::<f64>() / (norm(&tau) * norm(&slip));
        worst_dir = worst_dir.max(1.0 - cos);
    }
    assert!(worst_mag < 1e-6, "|tau| = f |sigma_n| to {worst_mag:e}");
    assert!(worst_dir < 1e-6, "shear along the slip: 1 - cos = {worst_dir:e}");
    // and the slip is diagonal, not along one axis: both x and z components
    let p = run.model.pairs.len() / 2;
    let pair = &run.model.pairs[p];
    let (dx, dz) = (
        run.last().u[pair.l * nd] - run.last().u[pair.k * nd],
        run.last().u[pair.l * nd + 2] - run.last().u[pair.k * nd + 2],
    );
    assert!(dx.abs() > 1e-5 && dz.abs() > 1e-5, "diagonal slip ({dx:e}, {dz:e})");
}
