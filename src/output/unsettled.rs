//! Where a contact iteration that did not converge kept changing: each
//! pair's state changes over the last [`WINDOW`] iterations (the `changes`
//! column of contact.csv and field of the contact VTU), the pairs that
//! changed counted per contact group and per pair of blocks, and the most
//! restless pairs with where they are and the states they went through
//! (report.md). A converged run has none of it.

use std::collections::BTreeMap;
use std::fmt::Write;

use crate::contact::law::ContactState;
use crate::model::Model;
use crate::results::ContactRun;

/// The iterations looked back on.
pub const WINDOW: usize = 10;
/// The pairs report.md lists one by one.
const MOST_LISTED: usize = 20;

/// Each pair's state changes over the last [`WINDOW`] iterations of `c`
/// (None when the iteration converged).
pub fn changes(c: &ContactRun) -> Option<Vec<usize>> {
    if c.summary.converged {
        return None;
    }
    let last = recent(c);
    Some((0..c.states.len()).map(|p| last.windows(2).filter(|w| w[0][p] != w[1][p]).count()).collect())
}

/// The state sets of the last [`WINDOW`] iterations, oldest first.
fn recent(c: &ContactRun) -> &[Vec<ContactState>] {
    let h = &c.summary.history;
    &h[h.len().saturating_sub(WINDOW)..]
}

/// The pairs of a run that did not converge that slip against their
/// friction at its last iteration (see [`AGAINST`]); 0 for a converged one.
pub fn slipping_back(c: &ContactRun) -> usize {
    if c.summary.converged {
        return 0;
    }
    (0..c.states.len()).filter(|&p| at_the_end(c, p).2 == SLIPS_BACK).count()
}

/// Pair `p`'s shear and law residual at the last iteration of `c`, and
/// how it breaks the law ([`breach`]).
fn at_the_end(c: &ContactRun, p: usize) -> (f64, f64, &'static str) {
    let r = &c.pairs[p];
    let tau = r.tau_t.hypot(r.tau_b);
    let residual = c.law_residual.get(p).copied().unwrap_or(0.0);
    (tau, residual, breach(c.states[p], r.sigma_n, tau, residual))
}

/// report.md's section on where the iteration did not settle (empty when
/// it converged).
pub fn report(model: &Model, c: &ContactRun) -> String {
    let Some(changes) = changes(c) else { return String::new() };
    let mut s = String::new();
    let moving: Vec<usize> = (0..changes.len()).filter(|&p| changes[p] > 0).collect();
    let looked = recent(c).len();
    let _ = writeln!(s, "\n## Where the iteration did not settle\n");
    if moving.is_empty() {
        let _ = writeln!(s, "No pair changed state in the last {looked} iteration(s): the states held while the slipping pairs' friction had not settled to the law (contact.csv, the contact VTU: `changes` = 0 everywhere).");
        return s;
    }
    let _ = writeln!(s, "{} of {} pairs changed state in the last {looked} iteration(s) (contact.csv and the contact VTU: `changes`, the number of changes).\n", moving.len(), changes.len());
    let body = model.body_of_node();
    let mut groups: BTreeMap<&str, usize> = BTreeMap::new();
    let mut blocks: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for &p in &moving {
        let pair = &model.pairs[p];
        *groups.entry(&model.interfaces[pair.contact].name).or_default() += 1;
        let (a, b) = (body[pair.k], body[pair.l]);
        *blocks.entry((a.min(b), a.max(b))).or_default() += 1;
    }
    let _ = writeln!(s, "| contact group | pairs that changed |\n|---|---|");
    for (g, n) in &groups {
        let _ = writeln!(s, "| {g} | {n} |");
    }
    let mut by_blocks: Vec<((usize, usize), usize)> = blocks.into_iter().collect();
    by_blocks.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let _ = writeln!(s, "\n| blocks | pairs that changed |\n|---|---|");
    for ((a, b), n) in by_blocks.iter().take(MOST_LISTED) {
        let _ = writeln!(s, "| {} – {} | {n} |", model.body_names(&[*a]), model.body_names(&[*b]));
    }
    if by_blocks.len() > MOST_LISTED {
        let _ = writeln!(s, "| ({} more block pairs) | |", by_blocks.len() - MOST_LISTED);
    }
    blocks_held(&mut s, model, &body, &moving);
    let mut worst = moving.clone();
    worst.sort_by(|&a, &b| changes[b].cmp(&changes[a]).then(a.cmp(&b)));
    let _ = writeln!(
        s,
        "\n| pair | x | y | z | contact group | changes | states, oldest first | sigma_n | tau | law residual | at the last iteration |\n|---|---|---|---|---|---|---|---|---|---|---|"
    );
    let mut against = false;
    for &p in worst.iter().take(MOST_LISTED) {
        let (pair, x) = (&model.pairs[p], model.coords[model.pairs[p].k]);
        let states: Vec<&str> = recent(c).iter().map(|h| h[p].name()).collect();
        let (tau, residual, how) = at_the_end(c, p);
        against |= how == SLIPS_BACK;
        let _ = writeln!(
            s,
            "| {p} | {:.4} | {:.4} | {:.4} | {} | {} | {} | {:.4} | {tau:.4} | {residual:.3e} | {how} |",
            x[0],
            x[1],
            x[2],
            model.interfaces[pair.contact].name,
            changes[p],
            states.join(" "),
            c.pairs[p].sigma_n,
        );
    }
    if worst.len() > MOST_LISTED {
        let _ = writeln!(s, "| ({} more pairs) | | | | | | | | | | |", worst.len() - MOST_LISTED);
    }
    let _ = writeln!(s, "\nStresses and the law residual in stress units, at the last iteration.");
    if against {
        let _ = writeln!(s, "\n{AGAINST}");
    }
    s
}

/// report.md's table of the blocks whose faces hold the pairs that
/// changed (of `body`, each node's): the pairs each holds, its volume
/// and the supports it touches, with the axes they hold. A small block
/// on a roller is held in the roller's plane by its joints alone: the
/// 34k tunnel's cycle is a 1.9 m^3 wedge against its end roller, which
/// converges with the ends clamped (docs/convergence.md).
fn blocks_held(s: &mut String, model: &Model, body: &[usize], moving: &[usize]) {
    let mut held: BTreeMap<usize, usize> = BTreeMap::new();
    for &p in moving {
        let pair = &model.pairs[p];
        let (a, b) = (body[pair.k], body[pair.l]);
        *held.entry(a).or_default() += 1;
        if b != a {
            *held.entry(b).or_default() += 1;
        }
    }
    // each block's supports: group -> the axes held at one of its nodes
    let mut on: BTreeMap<usize, BTreeMap<&str, [bool; 3]>> = BTreeMap::new();
    for support in &model.supports {
        for &dof in &support.dofs {
            let b = body[dof / model.nd];
            if held.contains_key(&b) {
                on.entry(b).or_default().entry(&support.group).or_default()[dof % model.nd] = true;
            }
        }
    }
    let mut ranked: Vec<(usize, usize)> = held.into_iter().collect();
    ranked.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let _ =
        writeln!(s, "\n| block | pairs that changed on its faces | volume | supports it touches |\n|---|---|---|---|");
    for &(b, n) in ranked.iter().take(MOST_LISTED) {
        let supports: Vec<String> = on.get(&b).map_or_else(Vec::new, |groups| {
            groups
                .iter()
                .map(|(g, axes)| {
                    let held: Vec<&str> = ["x", "y", "z"].into_iter().zip(axes).filter(|x| *x.1).map(|x| x.0).collect();
                    format!("\"{g}\" ({})", held.join(", "))
                })
                .collect()
        });
        let supports = if supports.is_empty() { "none".to_string() } else { supports.join(", ") };
        let volume = super::blocks::volume(model, b);
        let _ = writeln!(s, "| {} | {n} | {volume:.4} | {supports} |", model.body_names(&[b]));
    }
    if ranked.len() > MOST_LISTED {
        let _ = writeln!(s, "| ({} more blocks) | | | |", ranked.len() - MOST_LISTED);
    }
}

/// What the table's last column means by a slip against its friction.
const AGAINST: &str = "A pair that *slips against its friction* (its law residual about twice its shear) was beyond its bound stuck, and let slip it was pushed back by its own friction: its slip presses it harder into the faces round it (a wedge, as where two joints cross at or near a free face). Neither of its states meets the law while the pairs round it keep theirs; where that was measured, more iterations did not end it (docs/convergence.md, the 34k tunnel's crossings).";

/// The last column for a slip against its friction.
const SLIPS_BACK: &str = "slips against its friction";

/// A slipping pair's law residual from this share of its shear up is a
/// slip against its friction: at its bound `|λ_T - b e|` is `2 b` for a
/// slip e straight back, `sqrt(2) b` for one across.
const AGAINST_SHARE: f64 = 1.5;

/// A law residual below this share of the pair's traction is round-off.
const ROUND_OFF: f64 = 1e-9;

/// How a pair in `state`, with stresses `sigma_n` and shear `tau` and law
/// `residual`, breaks the law (see [`crate::contact::law::law_residual`]).
fn breach(state: ContactState, sigma_n: f64, tau: f64, residual: f64) -> &'static str {
    match state {
        _ if residual <= ROUND_OFF * sigma_n.hypot(tau) => "meets the law",
        ContactState::Stick => "stuck beyond its bound",
        ContactState::Slip if tau > 0.0 && residual >= AGAINST_SHARE * tau => SLIPS_BACK,
        ContactState::Slip => "friction off its bound or its slip",
        ContactState::Open => "open, carrying force or overlapping",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slip_straight_back_is_against_its_friction_and_one_across_is_not() {
        // friction 0.7 at sigma_n = -1: the bound b = 0.7
        let (sn, b): (f64, f64) = (-1.0, 0.7);
        // at its bound, slipping back (|λ_T - b e| = 2 b) and across (sqrt 2 b)
        assert_eq!(breach(ContactState::Slip, sn, b, 2.0 * b), SLIPS_BACK);
        assert_eq!(breach(ContactState::Slip, sn, b, 2f64.sqrt() * b), "friction off its bound or its slip");
        assert_eq!(breach(ContactState::Stick, sn, 1.99 * b, 0.99 * b), "stuck beyond its bound");
        // round-off is no breach (pair 2079 of the 34k tunnel: 7.8e-15 MPa)
        assert_eq!(breach(ContactState::Slip, sn, b, 7.8e-15), "meets the law");
        assert_eq!(breach(ContactState::Slip, sn, b, 1e-6), "friction off its bound or its slip");
        assert_eq!(breach(ContactState::Open, 0.0, 0.0, 0.3), "open, carrying force or overlapping");
    }
}
