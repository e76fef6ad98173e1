//! What the tests measure on a solved run: convergence rates, largest
//! values, how many pairs are in a state, how far an interface solve is from
//! the monolithic (bonded) one, and the force the contact pairs put on body I.
//! The contact traction of a pair is `sigma_n n + tau_t t` on body I (tension
//! positive; in 2D `t` is `n` turned +90 degrees), times the pair's area.

use std::collections::HashSet;

use subcontact::contact::law::ContactState;
use subcontact::driver::{ContactRun, Run};

/// Least-squares slope of log(y) against log(x).
pub fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// The largest absolute value (0 for none).
pub fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
    v.into_iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// How many pairs of a contact result are in state `s`.
pub fn count(c: &ContactRun, s: ContactState) -> usize {
    c.states.iter().filter(|&&x| x == s).count()
}

/// Max |u_contact - u_bonded| over every model node of the contact run (each
/// split copy against its mesh node in the bonded run), relative to the
/// largest bonded displacement component.
pub fn diff_to_bonded(contact: &Run, bonded: &Run) -> f64 {
    let nd = contact.model.nd;
    assert_eq!(bonded.model.nd, nd);
    assert!(bonded.model.pairs.is_empty(), "the bonded run has no pairs");
    let scale = max_abs(bonded.last().u.iter().copied());
    assert!(scale > 0.0, "the bonded solution moves");
    let mut worst = 0.0f64;
    for m in 0..contact.model.n_nodes() {
        let b = contact.model.mesh_node[m];
        assert_eq!(contact.model.coords[m], bonded.model.coords[b], "node {m} sits at its mesh node");
        for c in 0..nd {
            worst = worst.max((contact.last().u[m * nd + c] - bonded.last().u[b * nd + c]).abs());
        }
    }
    worst / scale
}

/// Nodes used by each body's cells: (body, model node), each once per body,
/// in the order the cells use them.
pub fn body_nodes(run: &Run) -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    for (b, body) in run.model.bodies.iter().enumerate() {
        let mut seen = HashSet::new();
        for c in &body.cells {
            for &n in &c.nodes {
                if seen.insert(n) {
                    v.push((b, n));
                }
            }
        }
    }
    v
}

/// 2D tangent of a pair: the normal turned +90 degrees about z.
pub fn tangent(n: [f64; 3]) -> [f64; 2] {
    [-n[1], n[0]]
}

/// Contact force on body I summed over the pairs `which` (by pair index),
/// global (x, y).
pub fn force_on_body_i(run: &Run, c: &ContactRun, which: impl Fn(usize) -> bool) -> [f64; 2] {
    let mut f = [0.0; 2];
    for (p, (pair, r)) in run.model.pairs.iter().zip(&c.pairs).enumerate() {
        if which(p) {
            let t = tangent(pair.normal);
            for i in 0..2 {
                f[i] += (r.sigma_n * pair.normal[i] + r.tau_t * t[i]) * pair.area;
            }
        }
    }
    f
}
