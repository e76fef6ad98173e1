//! The gravity dam (geo/dam.*): three concrete blocks separated by vertical
//! joints on a massless rock foundation; self-weight in step 1, the
//! reservoir filled in steps 2 and 3 (hydrostatic pressure on the upstream
//! face and the reservoir floor). The base carries no tension (f_t = 0).
//!
//! Checks:
//! - equilibrium: the forces the dam puts on the rock through the base
//!   pairs equal its self-weight plus the water thrust on its upstream face,
//!   `(gamma_w H^2 / 2, -rho g A)`, to 1e-8 at every step;
//! - the heel (upstream end of the base) is closed under self-weight and
//!   opens under the full reservoir, the open stretch starting at the heel;
//! - the result does not depend on the order of the blocks in the scene.
//!
//! Geometry (m): H = 50, crest 5, base B = 28, joints at x = 9 and 18; the
//! dam's cross-section is the polygon (0,0) (28,0) (5,50) (0,50), area 825.

mod common;

use common::measure::{force_on_body_i, max_abs};
use common::{repo_text, Case};
use subcontact::contact::law::ContactState;
use subcontact::driver::Run;

const AREA: f64 = 825.0;
const RHO_G: f64 = 2.4e-3 * 9.81;
const GAMMA_W: f64 = 0.00981;
const H: f64 = 50.0;

fn dam(case: &Case, bodies_order: Option<&[&str]>) -> Run {
    case.copy("geo/dam.geo");
    let mut text = repo_text("geo/dam.toml");
    if let Some(order) = bodies_order {
        let start = text.find("[[bodies]]").expect("bodies");
        let end = text.find("[[contacts]]").expect("contacts");
        let block = |g: &str| {
            format!("[[bodies]]\ngroup = \"{g}\"\nmaterial = \"{}\"\n\n", if g == "rock" { "rock" } else { "concrete" })
        };
        let bodies: String = order.iter().map(|g| block(g)).collect();
        text = format!("{}{}{}", &text[..start], bodies, &text[end..]);
    }
    let scene = case.write("dam.toml", &text);
    case.run(&scene).expect("the dam solves")
}

/// Pairs of the base contact (contact 0) with their x position.
fn base_pairs(run: &Run) -> Vec<usize> {
    let mut v: Vec<usize> = (0..run.model.pairs.len()).filter(|&p| run.model.pairs[p].contact == 0).collect();
    v.sort_by(|&a, &b| run.model.coords[run.model.pairs[a].k][0].total_cmp(&run.model.coords[run.model.pairs[b].k][0]));
    v
}

/// The force the dam puts on the rock through the base at a step.
fn force_on_rock(run: &Run, step: usize) -> [f64; 2] {
    let c = run.steps[step].contact.as_ref().expect("contact");
    let rock_is_i = run.model.bodies[run.model.interfaces[0].body_i].name == "rock";
    // the force on body I; on the rock it is that or its opposite
    let f = force_on_body_i(run, c, |p| run.model.pairs[p].contact == 0);
    if rock_is_i {
        f
    } else {
        [-f[0], -f[1]]
    }
}

#[test]
fn base_forces_balance_self_weight_and_water_thrust_at_every_step() {
    let case = Case::new("dam-equilibrium");
    let run = dam(&case, None);
    assert_eq!(run.steps.len(), 3);
    let weight = RHO_G * AREA;
    for (step, water) in [(0, 0.0), (1, 0.5), (2, 1.0)] {
        let f = force_on_rock(&run, step);
        let thrust = water * 0.5 * GAMMA_W * H * H;
        let scale = weight.hypot(thrust);
        assert!((f[0] - thrust).abs() < 1e-8 * scale, "step {}: horizontal {} against {}", step + 1, f[0], thrust);
        assert!((f[1] + weight).abs() < 1e-8 * scale, "step {}: vertical {} against {}", step + 1, f[1], -weight);
        assert!(run.steps[step].contact.as_ref().expect("contact").summary.converged);
    }
}

#[test]
fn heel_is_closed_under_self_weight_and_opens_under_the_full_reservoir() {
    let case = Case::new("dam-heel");
    let run = dam(&case, None);
    let base = base_pairs(&run);
    let heel = base[0];
    assert!(run.model.coords[run.model.pairs[heel].k][0].abs() < 1e-9, "the first base pair is at the heel");
    let states = |step: usize| run.steps[step].contact.as_ref().expect("contact").states.clone();
    assert!(base.iter().all(|&p| states(0)[p] != ContactState::Open), "self-weight alone keeps the whole base closed");
    let full = states(2);
    assert_eq!(full[heel], ContactState::Open, "the heel opens under the full reservoir");
    // the open stretch starts at the heel and is one piece
    let open: Vec<bool> = base.iter().map(|&p| full[p] == ContactState::Open).collect();
    let first_closed = open.iter().position(|o| !o).expect("the toe stays closed");
    assert!(first_closed >= 2, "more than the heel pair opens");
    assert!(open[first_closed..].iter().all(|o| !o), "the open part of the base is one stretch from the heel");
    let c = run.steps[2].contact.as_ref().expect("contact");
    let scale = max_abs(base.iter().map(|&p| c.pairs[p].sigma_n));
    for &p in &base[..first_closed] {
        assert!(c.pairs[p].gap > 0.0, "open pairs gap");
        assert!(
            c.pairs[p].sigma_n.abs() < 1e-9 * scale && c.pairs[p].tau().abs() < 1e-9 * scale,
            "open pairs carry nothing"
        );
    }
}

#[test]
fn the_answer_does_not_depend_on_the_order_of_the_blocks() {
    let a = dam(&Case::new("dam-order-a"), None);
    let b = dam(&Case::new("dam-order-b"), Some(&["block_3", "block_1", "rock", "block_2"]));
    // each base pair by its position and the block it joins to the rock
    // (where a joint meets the base, each of its two blocks has its pair)
    let keyed = |run: &Run| -> Vec<(f64, String, usize)> {
        let body = run.model.body_of_node();
        let mut v: Vec<(f64, String, usize)> = base_pairs(run)
            .into_iter()
            .map(|p| {
                let pair = &run.model.pairs[p];
                let block = [pair.k, pair.l]
                    .iter()
                    .map(|&n| &run.model.bodies[body[n]].name)
                    .find(|n| *n != "rock")
                    .expect("a block")
                    .clone();
                (run.model.coords[pair.k][0], block, p)
            })
            .collect();
        v.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        v
    };
    let (pa, pb) = (keyed(&a), keyed(&b));
    assert_eq!(pa.len(), pb.len());
    assert!(pa.windows(2).any(|w| w[0].0 == w[1].0), "a joint's end has a base pair for each of its two blocks");
    let (ca, cb) = (a.contact().expect("contact"), b.contact().expect("contact"));
    let scale = max_abs(pa.iter().map(|&(_, _, p)| ca.pairs[p].sigma_n));
    for ((xa, ba, p), (xb, bb, q)) in pa.iter().zip(&pb) {
        let (p, q) = (*p, *q);
        let xa = [*xa];
        assert!((xa[0] - xb).abs() < 1e-9 && ba == bb, "same pair positions");
        assert_eq!(ca.states[p], cb.states[q], "state at x = {}", xa[0]);
        assert!((ca.pairs[p].sigma_n - cb.pairs[q].sigma_n).abs() < 1e-9 * scale, "sigma_n at x = {}", xa[0]);
        assert!((ca.pairs[p].tau_t - cb.pairs[q].tau_t).abs() < 1e-9 * scale, "tau at x = {}", xa[0]);
    }
}
