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
    let mut worst = moving.clone();
    worst.sort_by(|&a, &b| changes[b].cmp(&changes[a]).then(a.cmp(&b)));
    let _ = writeln!(
        s,
        "\n| pair | x | y | z | contact group | changes | states, oldest first |\n|---|---|---|---|---|---|---|"
    );
    for &p in worst.iter().take(MOST_LISTED) {
        let (pair, x) = (&model.pairs[p], model.coords[model.pairs[p].k]);
        let states: Vec<&str> = recent(c).iter().map(|h| h[p].name()).collect();
        let _ = writeln!(
            s,
            "| {p} | {:.4} | {:.4} | {:.4} | {} | {} | {} |",
            x[0],
            x[1],
            x[2],
            model.interfaces[pair.contact].name,
            changes[p],
            states.join(" ")
        );
    }
    if worst.len() > MOST_LISTED {
        let _ = writeln!(s, "| ({} more pairs) | | | | | | |", worst.len() - MOST_LISTED);
    }
    s
}
