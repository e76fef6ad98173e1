//! The interface basis: which displacement coefficients the pairs tie, and
//! the area each pair controls.
//!
//! The paper judges a pair by its contact stress `f / A`, with A the area
//! the pair controls, `A_a = ∫ N_a dA`. On linear faces (line2, tri3, quad4)
//! and on line3 and quad9 faces every `A_a` is positive, and a uniform
//! traction t gives `f_a = t A_a`: the lumped stress is exact. On tri6 faces
//! the corner integrals vanish (`∫ N_corner dA = 0`), on quad8 faces they are
//! negative (`-A/12`), and on a line3 face of an axisymmetric model that
//! starts on the axis the corner's `∫ N r dr` vanishes: force / area is 0/0
//! or of the wrong sign there, and the law judges nonsense.
//!
//! So on such faces the interface works in a transformed basis (the basis
//! transformation of Wohlmuth, Popp, Gee & Wall, Comput. Mech. 49 (2012),
//! for dual mortar methods with quadratic elements): along every edge
//! (corners c1, c2, middle node m)
//!
//! ```text
//! Ñ_c = N_c + α (N_m of each edge at c)       u_m = (1 - 2α) ũ_m + α (ũ_c1 + ũ_c2)
//! Ñ_m = (1 - 2α) N_m                          u_c = ũ_c
//! ```
//!
//! i.e. `u = Q ũ` and `Ñ = Q^T N`. The field on the face is the same; only
//! its coefficients change. With α = 1/5 every pair gets a positive area
//! `Ã = Q^T A` (tri6: corners 2/15, middles 1/5 of a flat facet; quad8:
//! corners 1/20, middles 1/5), and a uniform traction gives `f̃ = Q^T f =
//! t Ã` exactly, so the contact patch test holds on every face kind. Both
//! sides of a pair use the same Q, so tying ũ_k = ũ_l ties u_k = u_l: stick,
//! slip and open mean what they did, on the coefficients (a weighted gap, as
//! in mortar methods). Faces whose lumped areas are positive keep the nodal
//! basis, so everything measured on them stays as it was.
//!
//! An edge whose middle node is supported in a direction its corners are
//! not keeps the nodal basis (the support would otherwise constrain a
//! combination of coefficients).

use std::collections::HashMap;

use crate::fem::sparse::NONE;
use crate::mesh::CellKind;
use crate::model::Model;

/// The coefficient of the middle node in the corners' transformed functions.
pub const ALPHA: f64 = 0.2;

/// The transformed edges of all interfaces, by pair and by node.
#[derive(Clone, Debug, Default)]
pub struct FaceBasis {
    /// `[middle pair, corner pair, corner pair]` of every transformed edge
    /// of a face (a junction's copies have one per face they are on).
    pub edges: Vec<[usize; 3]>,
    /// `[middle, corner, corner]` model nodes of every transformed edge of
    /// every side, once per middle node: what transforms a part's
    /// displacement coefficients.
    pub nodes: Vec<[usize; 3]>,
    /// Area each pair controls in this basis (`Q^T A`), positive.
    pub areas: Vec<f64>,
}

impl FaceBasis {
    /// The basis of the model's interfaces: transformed edges on tri6 and
    /// quad8 faces, and on line3 / quad9 faces where a corner controls no
    /// positive area. An edge is transformed on every face and every copy
    /// that has it or on none (the copies of a junction edge are tied
    /// across several faces).
    pub fn new(model: &Model) -> FaceBasis {
        let n = model.pairs.len();
        let nodal: Vec<f64> = model.pairs.iter().map(|p| p.area).collect();
        let at = model.facet_pairs();
        let mean = nodal.iter().map(|a| a.abs()).sum::<f64>() / n.max(1) as f64;
        let nd = model.nd;
        // prescribed components of a node, as a bit set
        let held =
            |node: usize| (0..nd).filter(|&c| model.prescribed[node * nd + c].is_some()).fold(0u8, |m, c| m | (1 << c));
        // every face edge's pair triple, and per middle mesh node: needed, supports allow it
        let mut by_mid: HashMap<usize, [usize; 3]> = HashMap::new();
        let mut decide: HashMap<usize, (bool, bool)> = HashMap::new();
        for (ii, iface) in model.interfaces.iter().enumerate() {
            for (fi, f) in iface.facets.iter().enumerate() {
                let always = matches!(f.kind, CellKind::Tri6 | CellKind::Quad8);
                for e in f.kind.facet_edges().iter().filter(|e| e[0] != usize::MAX) {
                    let [m, c1, c2] = e.map(|i| at[ii][fi][i]);
                    if m == NONE || c1 == NONE || c2 == NONE || by_mid.contains_key(&m) {
                        continue;
                    }
                    let needed = always || nodal[c1] <= 1e-9 * mean || nodal[c2] <= 1e-9 * mean;
                    // a middle node held where its corners are not keeps the nodal basis
                    let supported_ok =
                        [|p: &crate::model::Pair| p.k, |p: &crate::model::Pair| p.l].iter().all(|side| {
                            let hm = held(side(&model.pairs[m]));
                            hm & held(side(&model.pairs[c1])) == hm && hm & held(side(&model.pairs[c2])) == hm
                        });
                    by_mid.insert(m, [m, c1, c2]);
                    let d = decide.entry(model.mesh_node[model.pairs[m].k]).or_insert((false, true));
                    d.0 |= needed;
                    d.1 &= supported_ok;
                }
            }
        }
        let mut edges: Vec<[usize; 3]> = by_mid
            .into_values()
            .filter(|t| decide.get(&model.mesh_node[model.pairs[t[0]].k]).is_some_and(|&(needed, ok)| needed && ok))
            .collect();
        edges.sort_unstable();
        let mut nodes: Vec<[usize; 3]> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for &[m, c1, c2] in &edges {
            let (pm, p1, p2) = (&model.pairs[m], &model.pairs[c1], &model.pairs[c2]);
            for side in [[pm.k, p1.k, p2.k], [pm.l, p1.l, p2.l]] {
                if seen.insert(side[0]) {
                    nodes.push(side);
                }
            }
        }
        let mut basis = FaceBasis { edges, nodes, areas: nodal };
        basis.areas = basis.transpose_apply(&basis.areas);
        basis
    }

    /// The nodal basis everywhere (no transformed edge).
    pub fn nodal(areas: Vec<f64>) -> FaceBasis {
        FaceBasis { edges: Vec::new(), nodes: Vec::new(), areas }
    }

    /// `Q^T v` for a per-pair scalar (areas, or one component of forces).
    pub fn transpose_apply(&self, v: &[f64]) -> Vec<f64> {
        let mut out = v.to_vec();
        for &[m, c1, c2] in &self.edges {
            out[c1] += ALPHA * v[m];
            out[c2] += ALPHA * v[m];
            out[m] = (1.0 - 2.0 * ALPHA) * v[m];
        }
        out
    }

    /// `Q^-T v`: nodal forces from transformed ones (per pair, one component).
    pub fn inverse_transpose_apply(&self, v: &[f64]) -> Vec<f64> {
        let mut out = v.to_vec();
        for &[m, _, _] in &self.edges {
            out[m] = v[m] / (1.0 - 2.0 * ALPHA);
        }
        for &[m, c1, c2] in &self.edges {
            out[c1] -= ALPHA * out[m];
            out[c2] -= ALPHA * out[m];
        }
        out
    }

    /// Whether the basis is nodal everywhere.
    pub fn is_nodal(&self) -> bool {
        self.edges.is_empty()
    }
}

/// The transformation restricted to one part's interface nodes: for each
/// transformed edge whose nodes the part holds, the positions `[middle,
/// corner, corner]` of those nodes in the part's interface list (`position`
/// of a model node).
pub fn part_edges(basis: &FaceBasis, position: impl Fn(usize) -> Option<usize>) -> Vec<[usize; 3]> {
    basis.nodes.iter().filter_map(|e| Some([position(e[0])?, position(e[1])?, position(e[2])?])).collect()
}

/// Prescribed values per unit ramp of every model DOF in the face basis:
/// `ũ = Q^-1 u` along the transformed edges (global components; an edge
/// is transformed only where its middle node's held components are its
/// corners' too, so every value it needs is known).
pub fn prescribed(basis: &FaceBasis, prescribed: &[Option<f64>], nd: usize) -> Vec<Option<f64>> {
    let mut out = prescribed.to_vec();
    for &[m, c1, c2] in &basis.nodes {
        for c in 0..nd {
            if let (Some(vm), Some(v1), Some(v2)) =
                (prescribed[m * nd + c], prescribed[c1 * nd + c], prescribed[c2 * nd + c])
            {
                out[m * nd + c] = Some((vm - ALPHA * (v1 + v2)) / (1.0 - 2.0 * ALPHA));
            }
        }
    }
    out
}

/// `S Q` then `Q^T (S Q)` in place, for a dense column-major `nc x nc`
/// matrix over a part's interface nodes with `nd` components each.
pub fn transform_matrix(s: &mut [f64], nc: usize, nd: usize, edges: &[[usize; 3]]) {
    let a = ALPHA;
    for &[m, c1, c2] in edges {
        for c in 0..nd {
            let (jm, j1, j2) = (m * nd + c, c1 * nd + c, c2 * nd + c);
            for i in 0..nc {
                let v = s[i + jm * nc];
                s[i + j1 * nc] += a * v;
                s[i + j2 * nc] += a * v;
                s[i + jm * nc] = (1.0 - 2.0 * a) * v;
            }
        }
    }
    // the rows column by column, as a load (along a row, a cache line an entry)
    for column in s.chunks_exact_mut(nc.max(1)) {
        transform_load(column, nd, edges);
    }
}

/// `Q^T g` in place for a vector over a part's interface nodes.
pub fn transform_load(g: &mut [f64], nd: usize, edges: &[[usize; 3]]) {
    for &[m, c1, c2] in edges {
        for c in 0..nd {
            let v = g[m * nd + c];
            g[c1 * nd + c] += ALPHA * v;
            g[c2 * nd + c] += ALPHA * v;
            g[m * nd + c] = (1.0 - 2.0 * ALPHA) * v;
        }
    }
}

/// `u = Q ũ` in place for a vector over a part's interface nodes.
pub fn to_nodal(u: &mut [f64], nd: usize, edges: &[[usize; 3]]) {
    for &[m, c1, c2] in edges {
        for c in 0..nd {
            u[m * nd + c] = (1.0 - 2.0 * ALPHA) * u[m * nd + c] + ALPHA * (u[c1 * nd + c] + u[c2 * nd + c]);
        }
    }
}

/// `ũ = Q^-1 u` in place (for prescribed values).
pub fn from_nodal(u: &mut [f64], nd: usize, edges: &[[usize; 3]]) {
    for &[m, c1, c2] in edges {
        for c in 0..nd {
            u[m * nd + c] = (u[m * nd + c] - ALPHA * (u[c1 * nd + c] + u[c2 * nd + c])) / (1.0 - 2.0 * ALPHA);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Q^T S Q computed densely against the in-place transformation.
    #[test]
    fn matrix_transformation_is_q_transpose_s_q() {
        let (nn, nd) = (4, 2);
        let nc = nn * nd;
        let edges = [[3usize, 0, 1], [2, 1, 0]];
        let s: Vec<f64> = (0..nc * nc).map(|k| ((k * 7919) % 23) as f64 - 11.0).collect();
        let mut q = vec![0.0; nc * nc];
        for i in 0..nc {
            q[i + i * nc] = 1.0;
        }
        for &[m, c1, c2] in &edges {
            for c in 0..nd {
                let r = m * nd + c;
                q[r + r * nc] = 1.0 - 2.0 * ALPHA;
                q[r + (c1 * nd + c) * nc] = ALPHA;
                q[r + (c2 * nd + c) * nc] = ALPHA;
            }
        }
        let mut want = vec![0.0; nc * nc];
        for i in 0..nc {
            for j in 0..nc {
                want[i + j * nc] = (0..nc)
                    .flat_map(|a| (0..nc).map(move |b| (a, b)))
                    .map(|(a, b)| q[a + i * nc] * s[a + b * nc] * q[b + j * nc])
                    .sum();
            }
        }
        let mut got = s.clone();
        transform_matrix(&mut got, nc, nd, &edges);
        for k in 0..nc * nc {
            assert!((got[k] - want[k]).abs() < 1e-12, "entry {k}: {} vs {}", got[k], want[k]);
        }
        let mut u: Vec<f64> = (0..nc).map(|k| k as f64 * 0.3 - 1.0).collect();
        let orig = u.clone();
        from_nodal(&mut u, nd, &edges);
        to_nodal(&mut u, nd, &edges);
        for k in 0..nc {
            assert!((u[k] - orig[k]).abs() < 1e-12);
        }
    }

    #[test]
    fn tri6_and_quad8_corners_get_positive_areas() {
        // one flat facet of area 1: nodal lumped areas, then Q^T A
        let tri6 = FaceBasis { edges: vec![[3, 0, 1], [4, 1, 2], [5, 2, 0]], nodes: vec![], areas: vec![] };
        let a = tri6.transpose_apply(&[0.0, 0.0, 0.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0]);
        for c in 0..3 {
            assert!((a[c] - 2.0 / 15.0).abs() < 1e-15);
            assert!((a[3 + c] - 0.2).abs() < 1e-15);
        }
        let quad8 = FaceBasis { edges: vec![[4, 0, 1], [5, 1, 2], [6, 2, 3], [7, 3, 0]], nodes: vec![], areas: vec![] };
        let a = quad8.transpose_apply(&[
            -1.0 / 12.0,
            -1.0 / 12.0,
            -1.0 / 12.0,
            -1.0 / 12.0,
            1.0 / 3.0,
            1.0 / 3.0,
            1.0 / 3.0,
            1.0 / 3.0,
        ]);
        for c in 0..4 {
            assert!((a[c] - 0.05).abs() < 1e-15, "{}", a[c]);
            assert!((a[4 + c] - 0.2).abs() < 1e-15);
        }
        assert!((a.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        let back = quad8.inverse_transpose_apply(&a);
        assert!((back[0] + 1.0 / 12.0).abs() < 1e-15 && (back[4] - 1.0 / 3.0).abs() < 1e-15);
    }
}
