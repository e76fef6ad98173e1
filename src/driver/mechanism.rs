//! The mechanism of a loss of equilibrium: which blocks move and how
//! ([`crate::contact::mechanism`]), from the pairs' states when it was
//! lost. Each failing block's rigid motions ([`PartModes`], with its
//! supports) are tied where its pairs hold (a stuck pair in every
//! direction, a slipping one along its normal only, with the slack of its
//! facets' normals on a curved contact as in the solver's own check, an
//! open one not at all) and where it shares nodes with another block;
//! blocks that did not fail hold what is tied to them. The motion nothing stops, driven by the
//! blocks' own loads at the failing trial's load factors
//! ([`free_motion`]), is named block by block.

use crate::contact::frame::frame;
use crate::contact::law::ContactState;
use crate::contact::mechanism::{classify, Closed, Mechanism};
use crate::contact::mobility::{free_motion, pair_ties, PartModes, Tie};
use crate::fem::sparse::NONE;
use crate::fem::vec3::unit;
use crate::model::Model;
use crate::recover::body_nodes;
use crate::substructure::assembly::assemble;

/// A block outside the mechanism (held).
const HELD: usize = usize::MAX;

/// The mechanism of the blocks `blocks` (model bodies) failing with the
/// pair states `states` under the load factors `lambda`; None when no
/// block is named or nothing is free (the solver's check and this one
/// disagree).
pub(super) fn of(model: &Model, blocks: &[usize], states: &[ContactState], lambda: &[f64]) -> Option<Mechanism> {
    if blocks.is_empty() || states.len() != model.pairs.len() {
        return None;
    }
    let index = |b: usize| blocks.iter().position(|&x| x == b).unwrap_or(HELD);
    let nodes: Vec<Vec<usize>> = blocks.iter().map(|&b| body_nodes(&model.bodies[b])).collect();
    let parts: Vec<PartModes> = nodes.iter().map(|n| PartModes::new(model, n)).collect();
    let ties = ties(model, blocks, states, &index);
    let loads: Vec<[f64; 6]> =
        blocks.iter().zip(&parts).map(|(&b, p)| load_on_modes(model, b, p, lambda)).collect::<Option<_>>()?;
    let group: Vec<usize> = (0..blocks.len()).collect();
    let motions = free_motion(&parts, &ties, &group, &loads)?;
    let gravity = model.gravity.map(|g| g * lambda.get(model.gravity_case).copied().unwrap_or(1.0));
    let body_of = model.body_of_node();
    let mut named = Vec::new();
    let mut sizes = Vec::new();
    for (i, (&b, a)) in blocks.iter().zip(&motions).enumerate() {
        let modes = &parts[i].modes;
        let closed = closed_pairs(model, states, &body_of, b);
        named.push(classify(b, modes.center(), modes.scale(), modes.velocity(a), &closed, gravity));
        sizes.push(modes.scale());
    }
    Mechanism::new(named, &sizes)
}

/// The ties of the failing blocks: their pairs by state, as the solver's
/// check of free parts ties them ([`pair_ties`]: a slipping pair on a
/// curved contact holds along its normal with its facets' slack), and the
/// nodes they share with other blocks (every direction).
fn ties(model: &Model, blocks: &[usize], states: &[ContactState], index: &dyn Fn(usize) -> usize) -> Vec<Tie> {
    let nd = model.nd;
    let spreads = model.normal_spreads();
    let body_of = model.body_of_node();
    let axes: Vec<[f64; 3]> = (0..nd).map(unit).collect();
    let mut ties = Vec::new();
    for (p, pair) in model.pairs.iter().enumerate() {
        let (i, j) = (index(body_of[pair.k]), index(body_of[pair.l]));
        if i == HELD && j == HELD {
            continue;
        }
        let frame = frame(nd, pair.normal, [false; 3]);
        let dirs = match states[p] {
            ContactState::Stick => &frame[..nd],
            ContactState::Slip => &frame[..1],
            ContactState::Open => &[],
        };
        ties.extend(pair_ties([i, j], model.coords[pair.k], &frame, nd, dirs, spreads[p]));
    }
    // nodes a failing block shares with another block
    let mut first = vec![usize::MAX; model.n_nodes()];
    for (b, body) in model.bodies.iter().enumerate() {
        for &n in &body_nodes(body) {
            match first[n] {
                usize::MAX => first[n] = b,
                a if a != b && (blocks.contains(&a) || blocks.contains(&b)) => {
                    ties.extend(axes.iter().map(|&dir| Tie::exact([index(a), index(b)], model.coords[n], dir)))
                }
                _ => {}
            }
        }
    }
    ties
}

/// The work the loads on block `b` at the load factors `lambda` do in
/// each of its rigid modes (its body forces and the loads on its faces,
/// each load case at its factor).
fn load_on_modes(model: &Model, b: usize, part: &PartModes, lambda: &[f64]) -> Option<[f64; 6]> {
    let nd = model.nd;
    let nodes = body_nodes(&model.bodies[b]);
    let mut dof_of = vec![NONE; model.n_nodes() * nd];
    for (i, &n) in nodes.iter().enumerate() {
        (0..nd).for_each(|c| dof_of[n * nd + c] = i * nd + c);
    }
    let cells: Vec<(usize, usize)> = (0..model.bodies[b].cells.len()).map(|c| (b, c)).collect();
    let assembled = assemble(model, &cells, &dof_of, nodes.len() * nd).ok()?;
    let mut g = [0.0; 6];
    for (i, &n) in nodes.iter().enumerate() {
        let mut force = [0.0; 3];
        for (case, f) in assembled.f.iter().enumerate() {
            let l = lambda.get(case).copied().unwrap_or(0.0);
            (0..nd).for_each(|c| force[c] += l * f[i * nd + c]);
        }
        let r = part.modes.along(model.coords[n], force);
        g.iter_mut().zip(r).for_each(|(a, b)| *a += b);
    }
    Some(g)
}

/// The pairs of block `b` that stay closed, with its outward normal.
fn closed_pairs(model: &Model, states: &[ContactState], body_of: &[usize], b: usize) -> Vec<Closed> {
    (model.pairs.iter().zip(states))
        .filter(|(_, &s)| s != ContactState::Open)
        .filter_map(|(p, _)| {
            let sign = if body_of[p.k] == b {
                1.0
            } else if body_of[p.l] == b {
                -1.0
            } else {
                return None;
            };
            Some(Closed { x: model.coords[p.k], normal: p.normal.map(|v| sign * v), area: p.area, contact: p.contact })
        })
        .collect()
}
