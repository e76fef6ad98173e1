//! A pair's normal where a copy of a node is in several pairs: the normal
//! of the copy's surface there, not of the facets one pair happens to hold.
//!
//! Pairs follow the facets ([`super::contacts`]), so where joints end on a
//! smooth contact (a tunnel lining, a curved fault) the lining's one copy of
//! the node pairs with the copy of each rock block it faces, and each pair
//! holds only the facets on its block's side. On a curved surface meshed in
//! facets, their normals differ by about the facet angle: two normal ties
//! in two directions on one copy hold it tangentially, where the smooth
//! surface holds nothing (a frictionless lining then cannot rotate in its
//! hole, and a rigid motion nothing holds is solved as if held).
//!
//! So where the pairs of one contact at a node that face within
//! [`CREASE_ANGLE`] of each other form a star, one copy in all of them and
//! every other copy in one, each takes its normal summed over the facets of
//! all of them (turned outward of its side I): the normal of the hub's
//! surface, as a lone pair's normal is:
//!
//! ```text
//!   rock A  |  rock B        copy L of the lining pairs with A and with B;
//!  ---------+---------       alone, L|A's normal is n_A, L|B's is n_B;
//!   n_A  \  L  /  n_B        both are now n_A + n_B (summed over their
//!    lining (curved)         facets' areas): the lining's normal at L
//! ```
//!
//! Anything else keeps the normal of its own facets: a lone pair, pairs of
//! two contacts (two joint sets crossing at 30 degrees: each pair keeps its
//! own joint's normal), pairs across a crease, and pairs that close a loop
//! (two joints of one group crossing: no copy is the smooth side there).
//! On a flat contact the sum changes nothing.
//!
//! [`Model::normal_spreads`]: how far a pair's facets' normals turn from
//! its normal, the angle within which the smooth surface they stand for
//! may face (zero on a flat contact; about the facet angle on a curve).

use std::collections::HashMap;

use super::contacts::CREASE_ANGLE;
use super::mechanical::Model;
use crate::fem::element::{self, dot, norm};
use crate::fem::shape;
use crate::fem::vec3::cross;

/// A spread below this many radians is round-off on a flat facet: none.
const FLAT: f64 = 1e-9;

/// The unit normal of every pair from `sums`, each pair's normal summed
/// over its own facets (outward of its side I, weighted by area), its
/// copies `copies` (k on side I, l on side II), its contact, and the mesh
/// node of every model node.
pub(super) fn smooth_normals(
    copies: &[[usize; 2]],
    contacts: &[usize],
    sums: &[[f64; 3]],
    mesh_node: &[usize],
) -> Vec<[f64; 3]> {
    let mut at: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (p, c) in copies.iter().enumerate() {
        at.entry((contacts[p], mesh_node[c[0]])).or_default().push(p);
    }
    let cos_crease = CREASE_ANGLE.to_radians().cos();
    (0..copies.len())
        .map(|p| {
            let k = copies[p][0];
            // the pairs of this contact at the node facing within the
            // crease angle of p (either way)
            let near: Vec<usize> = (at[&(contacts[p], mesh_node[k])].iter().copied())
                .filter(|&q| dot(sums[q], sums[p]).abs() >= cos_crease * norm(sums[q]) * norm(sums[p]))
                .collect();
            let mut n = sums[p];
            if let Some(hub) = hub(&near, copies) {
                for &q in near.iter().filter(|&&q| q != p) {
                    // the hub on the same side of both pairs, or on the other
                    let sign = if (copies[q][0] == hub) == (k == hub) { 1.0 } else { -1.0 };
                    for (a, b) in n.iter_mut().zip(sums[q]) {
                        *a += sign * b;
                    }
                }
            }
            let len = norm(n);
            if len > 0.0 {
                n.map(|x| x / len)
            } else {
                [0.0; 3]
            }
        })
        .collect()
}

/// The copy every pair of `pairs` (two or more) has, when every other
/// copy is in one of them only: the smooth side they all face.
fn hub(pairs: &[usize], copies: &[[usize; 2]]) -> Option<usize> {
    let first = copies[*pairs.first()?];
    if pairs.len() < 2 {
        return None;
    }
    let hub = first.into_iter().find(|c| pairs.iter().all(|&q| copies[q].contains(c)))?;
    let mut others: Vec<usize> = pairs.iter().map(|&q| copies[q][usize::from(copies[q][0] == hub)]).collect();
    let n = others.len();
    others.sort_unstable();
    others.dedup();
    (others.len() == n && !others.contains(&hub)).then_some(hub)
}

impl Model {
    /// For every pair, the largest angle (radians) between its normal and
    /// the normals of its facets at their nodes; 0 on flat facets.
    pub fn normal_spreads(&self) -> Vec<f64> {
        (self.pairs.iter())
            .map(|p| {
                let spread = (p.shares.iter())
                    .flat_map(|&(f, _)| {
                        let facet = &self.interfaces[p.contact].facets[f];
                        let fc: Vec<[f64; 3]> = facet.nodes.iter().map(|&n| self.coords[n]).collect();
                        (shape::reference_nodes(facet.kind).iter()).map(move |&xi| {
                            let (_, n, _, _) = element::facet_point(facet.kind, &fc, xi);
                            norm(cross(n, p.normal)).atan2(dot(n, p.normal).abs())
                        })
                    })
                    .fold(0.0, f64::max);
                if spread > FLAT {
                    spread
                } else {
                    0.0
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(deg: f64) -> [f64; 3] {
        let a = deg.to_radians();
        [a.cos(), a.sin(), 0.0]
    }

    fn angle(n: [f64; 3]) -> f64 {
        n[1].atan2(n[0]).to_degrees()
    }

    #[test]
    fn a_lining_copy_facing_two_blocks_takes_its_surface_normal() {
        // copy 0 of the lining (side I) pairs with rock copies 1 and 2 at a
        // node at 30 degrees on a circle; each pair's facet turned by half
        // a 5-degree facet angle, the second facet twice as long
        let mesh_node = [7, 7, 7];
        let copies = [[0, 1], [0, 2]];
        let sums = [at(27.5), at(32.5).map(|x| 2.0 * x)];
        let n = smooth_normals(&copies, &[0, 0], &sums, &mesh_node);
        let both = angle([at(27.5)[0] + 2.0 * at(32.5)[0], at(27.5)[1] + 2.0 * at(32.5)[1], 0.0]);
        for m in &n {
            assert!((angle(*m) - both).abs() < 1e-12, "{} against {both}", angle(*m));
            assert!((norm(*m) - 1.0).abs() < 1e-15);
        }
        // the lining on side II: the rock's normals point inwards, the same surface
        let copies = [[1, 0], [2, 0]];
        let sums = [at(207.5), at(212.5).map(|x| 2.0 * x)];
        let n = smooth_normals(&copies, &[0, 0], &sums, &mesh_node);
        assert!((angle(n[0]) - angle(n[1])).abs() < 1e-12 && (angle(n[0]) - (both - 180.0)).abs() < 1e-12);
        // the shared copy on side I of one pair and side II of the other
        let copies = [[0, 1], [2, 0]];
        let sums = [at(27.5), at(212.5).map(|x| 2.0 * x)];
        let n = smooth_normals(&copies, &[0, 0], &sums, &mesh_node);
        assert!((angle(n[0]) - both).abs() < 1e-12 && (angle(n[1]) - (both - 180.0)).abs() < 1e-12);
    }

    #[test]
    fn crossings_creases_and_other_nodes_keep_their_own_facets() {
        // four blocks around a crossing: 0|1 and 2|3 across x, 0|2 and 1|3 across y
        let copies = [[0, 1], [2, 3], [0, 2], [1, 3]];
        let sums = [at(0.0), at(0.0), at(90.0), at(90.0)];
        let n = smooth_normals(&copies, &[0; 4], &sums, &[5, 5, 5, 5]);
        assert_eq!(n, sums.to_vec());
        // a copy on a crease (two faces 80 degrees apart) keeps both faces
        let n = smooth_normals(&[[0, 1], [0, 1]], &[0, 0], &[at(-40.0), at(40.0)], &[5, 5]);
        assert!((angle(n[0]) + 40.0).abs() < 1e-12 && (angle(n[1]) - 40.0).abs() < 1e-12);
        // a curved joint crossed by another: its two pairs share no copy
        let n = smooth_normals(&[[0, 2], [1, 3]], &[0, 0], &[at(85.0), at(95.0)], &[5, 5, 5, 5]);
        assert!((angle(n[0]) - 85.0).abs() < 1e-12 && (angle(n[1]) - 95.0).abs() < 1e-12);
        // joints along 0 and 30 degrees crossing: copies 0 and 2 in the
        // 30-degree sectors, 1 and 3 in the 150-degree ones, each of which
        // faces both joints 30 degrees apart; in two contacts, or in one (a
        // loop), each pair keeps its joint's normal
        let copies = [[1, 0], [1, 2], [3, 2], [3, 0]];
        let sums = [at(-60.0), at(-90.0), at(120.0), at(90.0)];
        for contacts in [[1, 0, 1, 0], [0; 4]] {
            let n = smooth_normals(&copies, &contacts, &sums, &[5; 4]);
            for (m, s) in n.iter().zip(&sums) {
                assert!((angle(*m) - angle(*s)).abs() < 1e-12, "{contacts:?}: {} against {}", angle(*m), angle(*s));
            }
        }
        // in one contact without its loop (a joint ending on a bend of
        // another): copy 1 is the hub
        let n = smooth_normals(&copies[..2], &[0, 0], &sums[..2], &[5; 4]);
        assert!((angle(n[0]) + 75.0).abs() < 1e-12 && (angle(n[1]) + 75.0).abs() < 1e-12);
    }
}
