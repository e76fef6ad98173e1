//! K_mm, the means' block of the sparse interface ([`super::sparse`]),
//! factorised through the parts' own stiffness rather than their S.
//!
//! With every relative displacement zero the pairs are bonded, and the
//! parts' own stiffness ([`super::own`]: interior and interface, the
//! interface in the pairs' local axes) side by side over the means and
//! the parts' interiors is the bonded model:
//!
//! ```text
//! K_b = [ K_ii      K_im ]      K_mm = K_mm,b - K_mi K_ii^-1 K_im
//!       [ K_mi   K_mm,b  ]      so  K_mm^-1 v = [K_b^-1 [v; 0]]_m
//! ```
//!
//! (the means' block of the inverse is the inverse of the Schur complement
//! onto them). A solve through K_mm's factor is one through K_b's, the
//! right-hand side zero on the interiors. K_mm itself is a dense clique
//! of means per part, which nested dissection cannot cut, while K_b keeps
//! the mesh's sparsity: on the 86k tunnel (148 blocks, 26,583 means)
//! K_mm's lower triangle held 16.4 million entries and its factor 72.8
//! million values, K_b (62,228 unknowns) 2.4 million and 34.5 million:
//! the interface's setup 4.0 -> 2.0 s, a substitution 28 -> 17 ms (the
//! same states and iterations, forces within 4e-12 MPa).

use super::coords::{Terms, Var};
use super::own::Own;
use crate::fem::sparse::SymMatrix;

/// K_b over `[m; the interiors]` (the means first, then each
/// part's interior in the order of `own`), from each part's `own`
/// stiffness and the `terms` of its interface DOFs; and a node id per
/// unknown for nested dissection (the means' from `mean_node`, a node's
/// interior DOFs one id).
pub(super) fn bonded(own: &[Own], terms: &[&[Terms]], mean_node: &[usize]) -> (SymMatrix, Vec<usize>) {
    let mut node_of: Vec<usize> = mean_node.to_vec();
    let mut nodes = mean_node.iter().max().map_or(0, |&n| n + 1);
    let mut entries: Vec<(usize, usize, f64)> = Vec::new();
    // the means of an interface DOF with its coefficient there
    let means = |t: &Terms| -> Vec<(usize, f64)> {
        (t.vars[..t.n].iter())
            .filter_map(|&(v, c)| match v {
                Var::M(i) => Some((i, c)),
                Var::R(_) => None,
            })
            .collect()
    };
    for (k, terms) in own.iter().zip(terms) {
        let first = node_of.len();
        let unknowns: Vec<Vec<(usize, f64)>> = terms.iter().map(means).collect();
        let at = |i: u32| -> Vec<(usize, f64)> {
            let i = i as usize;
            if i < k.ni {
                vec![(first + i, 1.0)]
            } else {
                unknowns[i - k.ni].clone()
            }
        };
        for &(r, c, v) in &k.entries {
            let (rows, cols) = (at(r), at(c));
            for &(a, ca) in &rows {
                for &(b, cb) in &cols {
                    // an entry off K's diagonal stands for its mirror too,
                    // which lands on the same place where both DOFs have
                    // the same unknown; one on it reaches (a, b) and (b, a)
                    let times = match (r == c, a.cmp(&b)) {
                        (true, std::cmp::Ordering::Less) => continue,
                        (false, std::cmp::Ordering::Equal) => 2.0,
                        _ => 1.0,
                    };
                    entries.push((a.max(b), a.min(b), times * ca * cb * v));
                }
            }
        }
        for (i, &node) in k.nodes.iter().enumerate() {
            if i == 0 || k.nodes[i - 1] != node {
                nodes += 1;
            }
            node_of.push(nodes - 1);
        }
    }
    (super::sparse::lower_from_entries(node_of.len(), entries), node_of)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terms(vars: &[(Var, f64)]) -> Terms {
        let mut t = Terms { vars: [(Var::M(0), 0.0); 2], n: vars.len(), constant: 0.0 };
        t.vars[..vars.len()].copy_from_slice(vars);
        t
    }

    /// K_b is `sum_p E_p^T K'_p E_p`, E_p taking the means and the part's
    /// interior to its DOFs (a relative displacement is zero, a held DOF
    /// has no unknown): checked entry by entry against that product formed
    /// densely, on parts that put two of their DOFs on one mean (both sides
    /// of a pair in one part) and hold one.
    #[test]
    fn the_bonded_matrix_is_the_parts_own_stiffness_on_the_means() {
        // two parts of 2 interior + 3 interface DOFs, an SPD K' each
        let own_matrix = |seed: f64| -> Vec<(u32, u32, f64)> {
            let mut e = Vec::new();
            for c in 0..5u32 {
                for r in c..5u32 {
                    let v = if r == c { 6.0 + seed * f64::from(r) } else { (seed * f64::from(3 * r + c)).sin() };
                    e.push((r, c, v));
                }
            }
            e
        };
        let own = vec![
            Own { ni: 2, nodes: vec![7, 7], entries: own_matrix(0.3) },
            Own { ni: 2, nodes: vec![8, 9], entries: own_matrix(0.7) },
        ];
        let a = [
            terms(&[(Var::M(0), 1.0), (Var::R(0), -0.5)]),
            terms(&[(Var::M(1), 1.0), (Var::R(1), -0.5)]),
            terms(&[(Var::M(1), 1.0), (Var::R(1), 0.5)]),
        ];
        let b = [terms(&[(Var::M(0), 1.0), (Var::R(0), 0.5)]), terms(&[(Var::R(2), 1.0)]), terms(&[(Var::M(2), 2.0)])];
        let (k, node_of) = bonded(&own, &[&a, &b], &[0, 0, 1]);
        // unknowns: 3 means, then each part's two interiors
        assert_eq!(k.n, 7);
        assert_eq!(node_of, vec![0, 0, 1, 2, 2, 3, 4]);
        let mut want = nalgebra::DMatrix::<f64>::zeros(7, 7);
        for (p, (o, t)) in own.iter().zip([&a[..], &b[..]]).enumerate() {
            let mut kp = nalgebra::DMatrix::<f64>::zeros(5, 5);
            for &(r, c, v) in &o.entries {
                kp[(r as usize, c as usize)] = v;
                kp[(c as usize, r as usize)] = v;
            }
            let mut e = nalgebra::DMatrix::<f64>::zeros(5, 7);
            e[(0, 3 + 2 * p)] = 1.0;
            e[(1, 4 + 2 * p)] = 1.0;
            for (u, tu) in t.iter().enumerate() {
                for &(v, c) in &tu.vars[..tu.n] {
                    if let Var::M(i) = v {
                        e[(2 + u, i)] += c;
                    }
                }
            }
            want += e.transpose() * kp * e;
        }
        for c in 0..7 {
            for r in c..7 {
                let got = k.get(r, c);
                assert!((got - want[(r, c)]).abs() < 1e-12, "({r}, {c}): {got} against {}", want[(r, c)]);
            }
        }
    }
}
