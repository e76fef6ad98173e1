//! Contacts that meet in 3D: the gravity-dam slice of geo/dam3d.toml (three
//! blocks on rock, the joints between the blocks ending on the base).
//!
//! Along the line where a joint ends on the base, the joint cedes its nodes:
//! the two blocks stay joined there and that node pairs with the rock, as
//! in 2D. The scene is run coarse (lc = 6 m in the dam): every load step
//! converges, and the base carries exactly the dam's weight W = rho g V
//! (V = 825 m^2 x 10 m) and, at full reservoir, the water thrust
//! gamma_w H^2 / 2 x 10 m on the upstream face (the reservoir floor loads
//! the rock directly).

mod common;

use common::Case;
use subcontact::contact::law::ContactState;
use subcontact::results::Run;

const RHO_G: f64 = 2.4e-3 * 9.81;
const VOLUME: f64 = (5.0 * 50.0 + 0.5 * 23.0 * 50.0) * 10.0;
const GAMMA_W: f64 = 0.00981;
const H: f64 = 50.0;
const D: f64 = 10.0;

fn dam3d(case: &Case) -> Run {
    case.copy("geo/dam3d.geo");
    let text = common::scenes::edited(
        "geo/dam3d.toml",
        &[("setnumber = { lc = 2.5 }", "setnumber = { lc = 6.0, lc_rock = 25.0 }")],
    );
    case.run(&case.write("dam3d.toml", &text)).unwrap_or_else(|e| panic!("dam3d: {e:#}"))
}

#[test]
fn joints_end_on_the_base_and_the_base_carries_the_weight_and_the_water() {
    let case = Case::new("dam3d");
    let run = dam3d(&case);
    let m = &run.model;
    let contact_of = |name: &str| m.interfaces.iter().position(|i| i.name == name).expect("contact");
    let (base, j12) = (contact_of("base"), contact_of("joint_12"));
    // along the line x = 9, z = 0, where joint_12 ends on the base, every
    // block keeps its copy: each node has a base pair for each of the two
    // blocks and a joint pair between them
    let on_line = |x: [f64; 3]| (x[0] - 9.0).abs() < 1e-9 && x[2].abs() < 1e-9;
    let mut at: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for pair in m.pairs.iter().filter(|pair| on_line(m.coords[pair.k])) {
        at.entry(m.mesh_node[pair.k]).or_default().push(pair.contact);
    }
    assert!(at.len() >= 3, "the junction line has nodes ({})", at.len());
    for contacts in at.values_mut() {
        contacts.sort_unstable();
        let mut want = vec![base, base, j12];
        want.sort_unstable();
        assert_eq!(*contacts, want, "a node where joint_12 ends on the base: two base pairs and one joint pair");
    }
    assert_eq!(m.bodies[m.interfaces[base].body_i].name, "rock");
    assert!(m.pairs.iter().any(|p| p.contact == j12), "joint_12 has pairs of its own");
    let weight = RHO_G * VOLUME;
    for (step, water) in [(0, 0.0), (1, 0.5), (2, 1.0)] {
        let c = run.steps[step].contact.as_ref().expect("contact");
        assert!(c.summary.converged, "step {}: converged", step + 1);
        assert!(c.summary.iterations <= 30, "step {}: {} iterations", step + 1, c.summary.iterations);
        let mut f = [0.0; 3];
        for p in (0..m.pairs.len()).filter(|&p| m.pairs[p].contact == base) {
            let fp = c.force(p); // on the rock (body I)
            for i in 0..3 {
                f[i] += fp[i];
            }
        }
        let thrust = water * 0.5 * GAMMA_W * H * H * D;
        let scale = weight.hypot(thrust);
        let k = c.states.iter().fold([0; 3], |mut k, s| {
            k[s.code() as usize] += 1;
            k
        });
        eprintln!("step {}: {} iterations, {} stick / {} slip / {} open; base force {f:?} (thrust {thrust:.3}, weight {weight:.3})", step + 1, c.summary.iterations, k[2], k[1], k[0]);
        assert!((f[0] - thrust).abs() < 1e-8 * scale, "step {}: horizontal {} against {thrust}", step + 1, f[0]);
        // (across the slice the blocks' own side rollers take a share: no check on f[1])
        assert!((f[2] + weight).abs() < 1e-8 * scale, "step {}: vertical {} against {}", step + 1, f[2], -weight);
    }
    // the heel lifts under the full reservoir, not under self-weight
    let heel = (0..m.pairs.len())
        .filter(|&p| m.pairs[p].contact == base && m.coords[m.pairs[p].k][0].abs() < 1e-9)
        .collect::<Vec<_>>();
    assert!(!heel.is_empty());
    let states = |s: usize| run.steps[s].contact.as_ref().expect("contact").states.clone();
    assert!(heel.iter().all(|&p| states(0)[p] != ContactState::Open), "self-weight keeps the heel closed");
    assert!(heel.iter().all(|&p| states(2)[p] == ContactState::Open), "the full reservoir opens the heel");
}
