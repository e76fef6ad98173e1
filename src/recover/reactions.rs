//! Reactions of a solved load step: every support group's force and its
//! moment about the group's centroid, and every body group's balance —
//! the loads on it, the contact forces on it and the supports' reactions
//! on it, which add up to zero ([`super::forces`] for how a reaction is
//! found). The balance's remainder, and the largest force left at the free
//! DOFs of the cells around the supports, say how well that holds.

use super::forces::{applied_per_body, node_forces, pair_forces};
use crate::fem::vec3::{cross, sub};
use crate::model::Model;
use crate::results::{BodyBalance, Reactions, StepResult, SupportReaction};

/// Every support group's reaction and every body group's balance at `step`.
pub fn reactions(model: &Model, step: &StepResult, body_groups: &[String]) -> Reactions {
    let nd = model.nd;
    let mut wanted = vec![false; model.n_nodes()];
    for s in &model.supports {
        s.dofs.iter().for_each(|&d| wanted[d / nd] = true);
    }
    let forces = node_forces(model, step, &wanted);
    let body_of = model.body_of_node();
    let mut on_body = vec![[0.0; 3]; model.bodies.len()];
    let mut supports = Vec::new();
    for s in &model.supports {
        let mut nodes: Vec<usize> = s.dofs.iter().map(|d| d / nd).collect();
        nodes.dedup();
        let about = centroid(model, &nodes);
        let (mut force, mut moment) = ([0.0; 3], [0.0; 3]);
        let mut at_node = [0.0; 3];
        for (i, &d) in s.dofs.iter().enumerate() {
            let (n, c) = (d / nd, d % nd);
            let r = forces.reaction(n)[c];
            force[c] += r;
            at_node[c] = r;
            on_body[body_of[n]][c] += r;
            // the node's last held DOF: its moment
            if s.dofs.get(i + 1).is_none_or(|e| e / nd != n) {
                let m = cross(sub(model.coords[n], about), at_node);
                (0..3).for_each(|k| moment[k] += m[k]);
                at_node = [0.0; 3];
            }
        }
        supports.push(SupportReaction { group: s.group.clone(), dofs: s.dofs.len(), force, moment, about });
    }
    let bodies = balances(model, step, body_groups, &on_body);
    Reactions { supports, bodies, free_residual: free_residual(model, &forces, &wanted) }
}

/// The mean position of `nodes` (the origin without any).
fn centroid(model: &Model, nodes: &[usize]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for &n in nodes {
        (0..3).for_each(|i| c[i] += model.coords[n][i] / nodes.len() as f64);
    }
    c
}

/// Each body group's loads, contact forces and support reactions
/// (`supports`: per model body).
fn balances(model: &Model, step: &StepResult, groups: &[String], supports: &[[f64; 3]]) -> Vec<BodyBalance> {
    let applied = applied_per_body(model, step);
    let body_of = model.body_of_node();
    let mut contact = vec![[0.0; 3]; model.bodies.len()];
    if let Some(c) = &step.contact {
        for (pair, f) in model.pairs.iter().zip(pair_forces(model, c)) {
            (0..3).for_each(|i| {
                contact[body_of[pair.k]][i] += f[i];
                contact[body_of[pair.l]][i] -= f[i];
            });
        }
    }
    let zero = [0.0; 3];
    let mut out: Vec<BodyBalance> = groups
        .iter()
        .map(|g| BodyBalance { group: g.clone(), applied: zero, contact: zero, supports: zero, remainder: zero })
        .collect();
    for (b, body) in model.bodies.iter().enumerate() {
        let Some(o) = out.get_mut(body.group) else { continue };
        for i in 0..3 {
            o.applied[i] += applied[b][i];
            o.contact[i] += contact[b][i];
            o.supports[i] += supports[b][i];
        }
    }
    for o in &mut out {
        o.remainder = std::array::from_fn(|i| o.applied[i] + o.contact[i] + o.supports[i]);
    }
    out
}

/// The largest |reaction| at a free DOF of the `wanted` nodes over the
/// largest internal force there.
fn free_residual(model: &Model, forces: &super::forces::NodeForces, wanted: &[bool]) -> f64 {
    let nd = model.nd;
    let (mut worst, mut scale): (f64, f64) = (0.0, 0.0);
    for (n, _) in wanted.iter().enumerate().filter(|(_, &w)| w) {
        let r = forces.reaction(n);
        for c in 0..nd {
            scale = scale.max(forces.internal[n][c].abs()).max(forces.applied[n][c].abs());
            if model.prescribed[n * nd + c].is_none() {
                worst = worst.max(r[c].abs());
            }
        }
    }
    if scale > 0.0 {
        worst / scale
    } else {
        0.0
    }
}
