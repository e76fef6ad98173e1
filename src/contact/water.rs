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
//! them, and the water there is the face's ([`Crack`]). A crack runs in one
//! sheet of the group (a smooth piece, which a crease ends): each sheet
//! that meets the face has its own, and its water is on its own facets
//! only, so a dam base's heel crack is not lengthened by the sides of its
//! foundation's steps opening. The right-hand side then depends on the
//! states, and the iteration converges on both at once.

use crate::contact::law::ContactState;
use crate::fem::element;
use crate::mesh::Cell;
use crate::model::water::{Crack, Fill, GroupWater, Sheet};
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

    /// The crack of each sheet of each group under `states` (None where
    /// nothing has filled; no sheets where the group has no face to fill
    /// from).
    pub fn cracks(&self, states: &[ContactState]) -> Vec<Vec<Option<Crack>>> {
        (self.groups.iter())
            .map(|g| {
                g.water
                    .fill
                    .as_ref()
                    .map_or_else(Vec::new, |f| f.sheets.iter().map(|sh| crack(f, sh, &g.s, states)).collect())
            })
            .collect()
    }

    /// The force of the water on body I at every pair (global axes, nodal
    /// basis; zero on dry pairs) under `states` and the load factors `lambda`.
    pub fn forces(&self, states: &[ContactState], lambda: &[f64]) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; self.n_pairs];
        for (g, cracks) in self.groups.iter().zip(self.cracks(states)) {
            let factor = lambda[g.water.case];
            if factor == 0.0 {
                continue;
            }
            for (i, f) in g.facets.iter().enumerate() {
                let crack = sheet_crack(&g.water, &cracks, i);
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
        for (g, cracks) in self.groups.iter().zip(self.cracks(states)) {
            let factor = lambda[g.water.case];
            for (p, pair) in model.pairs.iter().enumerate().filter(|(_, p)| p.contact == g.water.contact) {
                out[p] = factor * g.water.pressure(model.coords[pair.k], None);
            }
            if cracks.iter().all(Option::is_none) {
                continue;
            }
            // a pair on a crease takes the water of the wetter of its sheets
            for (i, f) in g.facets.iter().enumerate() {
                let crack = sheet_crack(&g.water, &cracks, i);
                for &p in f.pairs.iter().filter(|&&p| p != usize::MAX) {
                    out[p] = out[p].max(factor * g.water.pressure(model.coords[model.pairs[p].k], crack));
                }
            }
        }
        out
    }
}

/// The crack of the sheet of a group's facet `i` (None for a group whose
/// cracks do not fill).
fn sheet_crack(water: &GroupWater, cracks: &[Option<Crack>], i: usize) -> Option<Crack> {
    water.fill.as_ref().and_then(|f| cracks[f.facet_sheet[i]])
}

/// The crack of a sheet of a group whose water fills from `fill`: the
/// open pairs joined to its face by open pairs of the sheet, reaching the
/// largest s among them (`s`: of every pair of the group).
fn crack(fill: &Fill, sheet: &Sheet, s: &[f64], states: &[ContactState]) -> Option<Crack> {
    let open = |i: usize| states[fill.pairs[sheet.pairs[i]]] == ContactState::Open;
    let mut seen = vec![false; sheet.pairs.len()];
    let mut stack: Vec<usize> = sheet.seeds.iter().copied().filter(|&i| open(i)).collect();
    let mut tip: Option<f64> = None;
    while let Some(i) = stack.pop() {
        if std::mem::replace(&mut seen[i], true) {
            continue;
        }
        let si = s[sheet.pairs[i]];
        tip = Some(tip.map_or(si, |t| t.max(si)));
        stack.extend(sheet.neighbours[i].iter().copied().filter(|&j| !seen[j] && open(j)));
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

    /// A group of two sheets meeting at a crease, both on the face: five
    /// pairs in a row from the face (pair 0) at s = 0, 1, .., 4 in sheet 0,
    /// two (s = 0, 3) in sheet 1. A crack runs from the face through the
    /// open pairs of its own sheet, to its farthest s.
    #[test]
    fn a_crack_runs_from_the_face_through_open_pairs_of_its_sheet() {
        let sheet =
            |pairs: Vec<usize>, neighbours| Sheet { pairs, seeds: vec![0], neighbours, normal: [0.0, 0.0, 1.0] };
        let fill = Fill {
            surface: 40.0,
            unit_weight: 0.01,
            pairs: vec![10, 11, 12, 13, 14, 15, 16],
            facet_sheet: vec![0, 0, 0, 0, 1],
            sheets: vec![
                sheet(vec![0, 1, 2, 3, 4], vec![vec![1], vec![0, 2], vec![1, 3], vec![2, 4], vec![3]]),
                sheet(vec![5, 6], vec![vec![1], vec![0]]),
            ],
        };
        let s = [0.0, 1.0, 2.0, 3.0, 4.0, 0.0, 3.0];
        let tips = |states: &[ContactState]| -> Vec<Option<f64>> {
            fill.sheets.iter().map(|sh| crack(&fill, sh, &s, states).map(|c| c.tip)).collect()
        };
        let (o, k) = (ContactState::Open, ContactState::Stick);
        let mut states = vec![k; 17];
        assert_eq!(tips(&states), [None, None], "nothing open");
        states[13] = o;
        assert_eq!(tips(&states), [None, None], "open, but not joined to the face");
        states[10] = o;
        states[11] = o;
        let c = crack(&fill, &fill.sheets[0], &s, &states).expect("a crack from the face");
        assert_eq!((c.tip, c.level, c.unit_weight), (1.0, 40.0, 0.01));
        states[12] = o;
        assert_eq!(tips(&states), [Some(3.0), None], "joined up to the open pair at s = 3");
        states[15] = o;
        states[16] = o;
        assert_eq!(tips(&states), [Some(3.0), Some(3.0)], "each sheet its own crack");
        states[11] = k;
        assert_eq!(tips(&states), [Some(0.0), Some(3.0)], "the other sheet's crack does not lengthen this one");
    }
}
