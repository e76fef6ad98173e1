//! A contact surface with a crease (issue 17: "a wedge in a V-groove, a
//! block in a corner: a node on the crease honours both faces").
//!
//! tests/geo/vgroove.geo: a wedge fills a groove whose two faces dip 45
//! degrees towards each other and meet at a sharp crease along y; one
//! contact group holds both faces. Under its own weight W = rho g V (V =
//! 1 x 2, rho = 2.5, g = 10: W = 50) the wedge is wedged in: it presses on
//! both faces and its elastic spreading makes part of them slip. The copies
//! of a node on the crease are tied by two pairs at once (one per face),
//! so their forces are a junction's (src/contact/system/junction.rs): the
//! least-norm share within every pair's Coulomb cone, found by least
//! distance programming (system/least_distance.rs).
//!
//! Goals, each asserted, for f in {0.3, 0.6, 0.8}, the rock held at its base
//! and then at its base and ends:
//! - the iteration converges within 30 iterations (it toggled the crease's
//!   pairs for 100 iterations and gave up before the cuts of the cones were
//!   found by LDP);
//! - the faces carry the weight: the force on the rock is (0, 0, -W) to
//!   1e-9 W;
//! - Coulomb's law at every pair: slipping |tau| = f |sigma_n| to 1e-9,
//!   stuck |tau| <= f |sigma_n|; no pair opens.

mod common;

use common::Case;
use subcontact::contact::law::ContactState;

/// The wedge's weight (rho g V).
const W: f64 = 2.5 * 10.0 * 2.0;

fn scene(f: f64, ends: bool) -> String {
    let ends = if ends { "[[supports]]\ngroup = \"ends\"\nfix = [\"x\", \"y\", \"z\"]\n" } else { "" };
    format!(
        "title = \"a wedge in a sharp V-groove\"\nmesh = \"vgroove.geo\"\nanalysis = \"solid\"\ngravity = [0.0, 0.0, -10.0]\n[gmsh]\norder = 1\nsetnumber = {{ lc = 0.4 }}\n\
         [materials.rock]\nE = 1.0e4\nnu = 0.25\ndensity = 2.5\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n[[bodies]]\ngroup = \"wedge\"\nmaterial = \"rock\"\n\
         [[contacts]]\ngroup = \"groove\"\nfriction = {f:?}\n[[supports]]\ngroup = \"bottom\"\nfix = [\"x\", \"y\", \"z\"]\n{ends}"
    )
}

#[test]
fn a_wedge_in_a_sharp_groove_converges_and_every_crease_pair_obeys_coulomb() {
    let case = Case::new("crease-vgroove");
    case.copy("tests/geo/vgroove.geo");
    for ends in [false, true] {
        for f in [0.3, 0.6, 0.8] {
            let name = format!("f{f}_{}", if ends { "ends" } else { "base" });
            let run = case
                .run(&case.write(&format!("{name}.toml"), &scene(f, ends)))
                .unwrap_or_else(|e| panic!("{name}: {e:#}"));
            let c = run.contact().expect("a contact run");
            let n = c.states.len();
            let total: [f64; 3] = std::array::from_fn(|i| (0..n).map(|p| c.force(p)[i]).sum());
            let (mut slip, mut stick) = (0.0f64, 0.0f64);
            for (p, pair) in c.pairs.iter().enumerate() {
                let excess = (pair.tau() - f * pair.sigma_n.abs()) / pair.sigma_n.abs();
                match c.states[p] {
                    ContactState::Slip => slip = slip.max(excess.abs()),
                    ContactState::Stick => stick = stick.max(excess),
                    ContactState::Open => panic!("{name}: pair {p} opens"),
                }
            }
            let count = |s| c.states.iter().filter(|&&x| x == s).count();
            eprintln!(
                "{name}: {n} pairs, {} iterations, {} stick / {} slip; force on the rock {total:?} (W = {W}); Coulomb: slip {slip:.1e}, stick excess {stick:.1e}",
                c.summary.iterations,
                count(ContactState::Stick),
                count(ContactState::Slip)
            );
            assert!(
                c.summary.converged && c.summary.iterations <= 30,
                "{name}: {} iterations, converged {}",
                c.summary.iterations,
                c.summary.converged
            );
            assert!(
                total[0].abs() < 1e-9 * W && total[1].abs() < 1e-9 * W && (total[2] + W).abs() < 1e-9 * W,
                "{name}: the faces carry the weight: {total:?}"
            );
            assert!(slip < 1e-9 && stick < 1e-9, "{name}: Coulomb's law (slip {slip:.1e}, stick {stick:.1e})");
            assert!(count(ContactState::Slip) > 0 && count(ContactState::Stick) > 0, "{name}: partial slip");
        }
    }
}
