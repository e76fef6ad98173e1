//! The water in the joints on the interface: per pair, the force the water
//! puts on body I at k (its opposite on body II at l), integrated over the
//! pair's facets as a pressure load is (`∫ u N_k n dA`, with thickness or
//! 2 pi r), with the pressure of [`crate::model::water`].
//!
//! The water pushes the two sides of every pair apart whatever its state,
//! so it is a load on the pairs' relative displacements alone: the
//! interface adds it to its right-hand side at each solve, no part is
//! condensed again. The contact force then solved for is the solid-to-solid
//! one, and the law judges the effective normal stress `sigma_n' = sigma_n
//! + u` with no change.
//!
//! Cracks that fill: where a group's water connects to a face (its
//! [`Fill`]), the pairs open in the states being solved that a run of open
//! pairs joins to that face make the crack; it reaches the largest s among
//! them, and the water there is the face's ([`Crack`]). The right-hand side
//! then depends on the states, and the iteration converges on both at once.

use crate::contact::law::ContactState;
use crate::fem::element;
use crate::mesh::Cell;
use crate::model::water::{Crack, Fill, GroupWater};
use crate::model::Model;

/// The water of a model's joints, ready to be integrated at any states.
pub struct Water {
    groups: Vec<Group>,
    n_pairs: usize,
}

/// One group's water, its facets' integration points, and each of its
/// fill pairs' position along the flow.
struct Group {
    water: GroupWater,
    facets: Vec<Facet>,
    s: Vec<f64>,
}

/// A facet's pair at each node (`usize::MAX` where none) and its points.
struct Facet {
    pairs: Vec<usize>,
    points: Vec<Point>,
}

/// An integration point: where it is, `N_a w da measure` of each node, and
/// the outward unit normal of side I.
struct Point {
    x: [f64; 3],
    weights: Vec<f64>,
    normal: [f64; 3],
}

impl Water {
    /// The water of `model`'s joints; None when they are dry.
    pub fn new(model: &Model) -> Option<Water> {
        if model.water.is_empty() {
            return None;
        }
        let at = model.facet_pairs();
        let groups = (model.water.iter())
            .map(|w| {
                let iface = &model.interfaces[w.contact];
                let facets = (iface.facets.iter().zip(&w.signs).zip(&at[w.contact]))
                    .map(|((f, &sign), pairs)| Facet { pairs: pairs.clone(), points: points(model, f, sign) })
                    .collect();
                let s = w
                    .fill
                    .as_ref()
                    .map_or_else(Vec::new, |f| f.pairs.iter().map(|&p| w.s(model.coords[model.pairs[p].k])).collect());
                Group { water: w.clone(), facets, s }
            })
            .collect();
        Some(Water { groups, n_pairs: model.pairs.len() })
    }

    /// The crack of each group under `states` (None where nothing has
    /// filled, or the group has no face to fill from).
    pub fn cracks(&self, states: &[ContactState]) -> Vec<Option<Crack>> {
        self.groups.iter().map(|g| g.water.fill.as_ref().and_then(|f| crack(f, &g.s, states))).collect()
    }

    /// The force of the water on body I at every pair (global axes, nodal
    /// basis; zero on dry pairs) under `states` and the load factors `lambda`.
    pub fn forces(&self, states: &[ContactState], lambda: &[f64]) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; self.n_pairs];
        for (g, crack) in self.groups.iter().zip(self.cracks(states)) {
            let factor = lambda[g.water.case];
            if factor == 0.0 {
                continue;
            }
            for f in &g.facets {
                for q in &f.points {
                    let u = factor * g.water.pressure(q.x, crack);
                    if u == 0.0 {
                        continue;
                    }
                    for (&p, &w) in f.pairs.iter().zip(&q.weights) {
                        if p != usize::MAX {
                            for i in 0..3 {
                                out[p][i] -= u * w * q.normal[i];
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// The water pressure at every pair's node (0 on dry pairs) under
    /// `states` and `lambda`.
    pub fn pressures(&self, model: &Model, states: &[ContactState], lambda: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n_pairs];
        for (g, crack) in self.groups.iter().zip(self.cracks(states)) {
            let factor = lambda[g.water.case];
            for (p, pair) in model.pairs.iter().enumerate().filter(|(_, p)| p.contact == g.water.contact) {
                out[p] = factor * g.water.pressure(model.coords[pair.k], crack);
            }
        }
        out
    }
}

/// The crack of a group whose water fills from `fill`: the open pairs
/// joined to its face by open pairs, reaching the largest s among them.
fn crack(fill: &Fill, s: &[f64], states: &[ContactState]) -> Option<Crack> {
    let open = |i: usize| states[fill.pairs[i]] == ContactState::Open;
    let mut seen = vec![false; fill.pairs.len()];
    let mut stack: Vec<usize> = fill.seeds.iter().copied().filter(|&i| open(i)).collect();
    let mut tip: Option<f64> = None;
    while let Some(i) = stack.pop() {
        if std::mem::replace(&mut seen[i], true) {
            continue;
        }
        tip = Some(tip.map_or(s[i], |t| t.max(s[i])));
        stack.extend(fill.neighbours[i].iter().copied().filter(|&j| !seen[j] && open(j)));
    }
    tip.map(|tip| Crack { tip, level: fill.surface, unit_weight: fill.unit_weight })
}

/// The integration points of facet `f` (side I's nodes; `sign` makes its
/// natural normal outward of side I), as a pressure load integrates it.
fn points(model: &Model, f: &Cell, sign: f64) -> Vec<Point> {
    let xe: Vec<[f64; 3]> = f.nodes.iter().map(|&n| model.coords[n]).collect();
    crate::fem::quadrature::rule(f.kind, 2 * f.kind.order() + 2)
        .iter()
        .map(|q| {
            let (n, unit, da, x) = element::facet_point(f.kind, &xe, q.xi);
            let scale = q.w * da * element::measure(model.analysis, model.thickness, &x);
            Point { x, weights: n.iter().map(|v| v * scale).collect(), normal: unit.map(|c| c * sign) }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Five pairs in a row from the face (pair 0) at s = 0, 1, .., 4: the
    /// crack is the run of open pairs from the face, to its farthest s.
    #[test]
    fn a_crack_runs_from_the_face_through_open_pairs() {
        let fill = Fill {
            surface: 40.0,
            unit_weight: 0.01,
            pairs: vec![10, 11, 12, 13, 14],
            seeds: vec![0],
            neighbours: vec![vec![1], vec![0, 2], vec![1, 3], vec![2, 4], vec![3]],
        };
        let s = [0.0, 1.0, 2.0, 3.0, 4.0];
        let (o, k) = (ContactState::Open, ContactState::Stick);
        let mut states = vec![k; 15];
        assert_eq!(crack(&fill, &s, &states), None, "nothing open");
        states[13] = o;
        assert_eq!(crack(&fill, &s, &states), None, "open, but not joined to the face");
        states[10] = o;
        states[11] = o;
        let c = crack(&fill, &s, &states).expect("a crack from the face");
        assert_eq!((c.tip, c.level, c.unit_weight), (1.0, 40.0, 0.01));
        states[12] = o;
        assert_eq!(crack(&fill, &s, &states).map(|c| c.tip), Some(3.0), "joined up to the open pair at s = 3");
    }
}
