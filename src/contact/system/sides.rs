//! The interface with springs, factorised in the parts' own DOFs: the
//! sparse interface's preconditioner where every pair deforms.
//!
//! In the mean / relative unknowns `x = [m; r]` ([`super::coords`]) a
//! part's condensed matrix touches the mean and the relative displacement
//! of each of its pairs: its clique is twice its interface DOFs, and a
//! factor of `K + F` over x (F the springs) does about eight times the
//! work of one over the sides' displacements. But every place (a lone
//! pair, a junction, a join) writes its sides' DOFs in its own unknowns
//! alone, `d = T x` with T square there: a lone pair's axis `d_k = m - r/2,
//! d_l = m + r/2`, a junction's copies `d_0 = m, d_j = m + r_j`, a join's
//! parts one mean. So
//!
//! ```text
//! K + F = T^T (S + G) T,   G = T^-T F T^-1,   (K + F)^-1 = T^-1 (S + G)^-1 T^-T
//! ```
//!
//! with S the parts' matrices side by side, each part's clique its own
//! interface DOFs, and G the springs between the sides of each place: the
//! bonded model's pattern with each place's sides apart and sprung. A
//! place is the unknowns its sides' DOFs share, joined by the springs
//! that couple them (a junction's copies held by a support share none).
//! The same preconditioner either way, to round-off (tunnel4sets_stiff:
//! the same 72 GMRES applications); on the 86k tunnel (99,095 DOFs) its
//! factor over x took 31.8 s (351 million values), over the sides 6.0 s
//! with its assembly, peak memory 4.9 -> 2.8 GB.
//!
//! But each part's S is a dense clique over its interface, which nested
//! dissection cannot cut. Where the parts' own stiffness is at hand
//! ([`super::own`]) the factor is of that instead, each part's interior
//! numbered after the sides: its Schur complement onto the sides is
//! `S + G`, so a right-hand side on the sides (zero on the interiors)
//! gives the same answer. 86k tunnel: 60,406 DOFs and 19.5 million entries
//! over S (114 million values in the factor, 5.8 s with its assembly),
//! 96,051 DOFs and 3.0 million entries over the parts' own (63 million,
//! 2.9 s), the same 20 GMRES applications; peak memory 2.5 -> 1.6 GB.

use nalgebra::DMatrix;

use super::coords::{Terms, Var};
use super::own::Own;
use crate::fem::sparse::{SymMatrix, NONE};
use crate::substructure::ordering::Ordering;
use crate::substructure::single_precision::SingleCholesky;

/// One place: its unknowns in x, its sides' DOFs, and `T^-1` there
/// (rows the unknowns, columns the DOFs).
struct Place {
    vars: Vec<usize>,
    dofs: Vec<usize>,
    t_inv: DMatrix<f64>,
}

/// `(K + F)^-1` through the sides' DOFs; see the module header.
pub(super) struct Sides {
    places: Vec<Place>,
    /// Unknowns in x, and sides' DOFs.
    n: usize,
    n_d: usize,
    factor: SingleCholesky,
}

/// A side DOF's unknowns, as a key: the unknowns and their coefficients' bits.
type Key = Vec<(usize, u64)>;

impl Sides {
    /// The factor of `K + F` over the `n` unknowns `index` numbers, from
    /// the parts' matrices `s` (local axes, column-major) and `terms`, and
    /// the springs (small dense row-major matrices at unknowns of x). None
    /// where some place is not square in its unknowns, or the factor fails.
    ///
    /// With `own` (each part's [`Own`], in the order of `parts`) the factor
    /// is of the parts' own stiffness, interiors and sides, with the
    /// springs: the same `(S + G)^-1` on the sides (see [`super::own`]).
    pub fn new(
        parts: &[(&[f64], &[Terms])],
        own: Option<&[Own]>,
        index: impl Fn(Var) -> Option<usize>,
        n: usize,
        springs: &[(Vec<usize>, Vec<f64>)],
        place_of: &[usize],
        (nd, threads): (usize, usize),
    ) -> Option<Sides> {
        let key = |t: &Terms| -> Key {
            (t.vars[..t.n].iter()).filter_map(|&(v, c)| index(v).map(|i| (i, c.to_bits()))).collect()
        };
        // the sides' DOFs: distinct keys (a join's parts share theirs)
        let mut dof_of: std::collections::HashMap<Key, usize> = std::collections::HashMap::new();
        let mut keys: Vec<Key> = Vec::new();
        let part_dofs: Vec<Vec<usize>> = (parts.iter())
            .map(|(_, terms)| {
                (terms.iter())
                    .map(|t| {
                        let k = key(t);
                        if k.is_empty() {
                            return NONE;
                        }
                        *dof_of.entry(k.clone()).or_insert_with(|| {
                            keys.push(k);
                            keys.len() - 1
                        })
                    })
                    .collect()
            })
            .collect();
        let places = places(&keys, place_of, n)?;
        let (g, cliques) = sprung(&places, place_of, springs)?;
        let n_d = keys.len();
        // nested dissection keeps the DOFs of a part's node together
        let mut node_of = vec![usize::MAX; n_d];
        let mut nodes = 0;
        for dofs in &part_dofs {
            for node in dofs.chunks(nd.max(1)) {
                for &d in node {
                    if d != NONE && node_of[d] == usize::MAX {
                        node_of[d] = nodes;
                    }
                }
                nodes += 1;
            }
        }
        let k = match own {
            Some(own) => own_matrix(own, &part_dofs, &g, &mut node_of, nodes),
            None => schur_matrix(parts, &part_dofs, &g, cliques, n_d),
        };
        let factor = SingleCholesky::factor(&k, &node_of, Ordering::choose(k.n, nd), threads).ok()?;
        Some(Sides { places, n, n_d, factor })
    }

    /// `(K + F)^-1 v` over x.
    pub fn solve(&self, v: &[f64]) -> Vec<f64> {
        let mut w = vec![0.0; self.n_d];
        for p in &self.places {
            // w = T^-T v at the place
            for (j, &d) in p.dofs.iter().enumerate() {
                w[d] = p.vars.iter().enumerate().map(|(i, &x)| p.t_inv[(i, j)] * v[x]).sum();
            }
        }
        // (the parts' interiors, where the factor has them, follow the sides)
        w.resize(self.factor.n(), 0.0);
        let z = self.factor.solve(&w);
        let mut x = vec![0.0; self.n];
        for p in &self.places {
            for (i, &xi) in p.vars.iter().enumerate() {
                x[xi] = p.dofs.iter().enumerate().map(|(j, &d)| p.t_inv[(i, j)] * z[d]).sum();
            }
        }
        x
    }
}

/// The parts' S side by side (each a clique over its sides' DOFs) and
/// the springs `g`, over the `n_d` sides' DOFs.
fn schur_matrix(
    parts: &[(&[f64], &[Terms])],
    part_dofs: &[Vec<usize>],
    g: &[(Vec<usize>, Vec<f64>)],
    mut cliques: Vec<Vec<usize>>,
    n_d: usize,
) -> SymMatrix {
    cliques.extend(part_dofs.iter().map(|d| {
        let mut c: Vec<usize> = d.iter().copied().filter(|&x| x != NONE).collect();
        c.sort_unstable();
        c.dedup();
        c
    }));
    let mut k = SymMatrix::from_cliques(n_d, &cliques);
    drop(cliques);
    for ((s, _), dofs) in parts.iter().zip(part_dofs) {
        k.add(dofs, s);
    }
    for (dofs, ke) in g {
        k.add(dofs, ke);
    }
    k
}

/// The parts' own K' side by side, each interior numbered after the sides'
/// DOFs (`node_of` extended with their nodes, numbered from `nodes`), and
/// the springs `g`.
fn own_matrix(
    own: &[Own],
    part_dofs: &[Vec<usize>],
    g: &[(Vec<usize>, Vec<f64>)],
    node_of: &mut Vec<usize>,
    mut nodes: usize,
) -> SymMatrix {
    let mut entries: Vec<(usize, usize, f64)> = Vec::new();
    for (k, dofs) in own.iter().zip(part_dofs) {
        let first = node_of.len();
        let at = |i: u32| {
            let i = i as usize;
            if i < k.ni {
                first + i
            } else {
                dofs[i - k.ni]
            }
        };
        for &(r, c, v) in &k.entries {
            let (r, c) = (at(r), at(c));
            if r != NONE && c != NONE {
                entries.push((r.max(c), r.min(c), v));
            }
        }
        for (i, &node) in k.nodes.iter().enumerate() {
            if i == 0 || k.nodes[i - 1] != node {
                nodes += 1;
            }
            node_of.push(nodes - 1);
        }
    }
    for (dofs, ke) in g {
        let m = dofs.len();
        for a in 0..m {
            for b in 0..m {
                if dofs[a] >= dofs[b] {
                    entries.push((dofs[a], dofs[b], ke[a * m + b]));
                }
            }
        }
    }
    super::sparse::lower_from_entries(node_of.len(), entries)
}

/// The places of the `keys` (each DOF's unknowns): their unknowns, DOFs and
/// `T^-1`; None where a place has not as many DOFs as unknowns, or its T
/// is singular, or an unknown is in no DOF.
fn places(keys: &[Key], place_of: &[usize], n: usize) -> Option<Vec<Place>> {
    let mut at: std::collections::BTreeMap<usize, (Vec<usize>, Vec<usize>)> = std::collections::BTreeMap::new();
    let mut seen = vec![false; n];
    for (d, k) in keys.iter().enumerate() {
        let e = at.entry(place_of[k[0].0]).or_default();
        e.1.push(d);
        for &(x, _) in k {
            if !seen[x] {
                seen[x] = true;
                e.0.push(x);
            }
        }
    }
    if seen.iter().any(|s| !s) {
        return None;
    }
    at.into_values()
        .map(|(vars, dofs)| {
            if vars.len() != dofs.len() {
                return None;
            }
            let t = DMatrix::from_fn(dofs.len(), vars.len(), |a, b| {
                let c = keys[dofs[a]].iter().find(|&&(x, _)| x == vars[b]);
                c.map_or(0.0, |&(_, bits)| f64::from_bits(bits))
            });
            Some(Place { vars, dofs, t_inv: t.try_inverse()? })
        })
        .collect()
}

/// The springs in the sides' DOFs, `G = T^-T F T^-1` per place (row-major
/// at its DOFs), and the places' cliques.
#[allow(clippy::type_complexity)]
fn sprung(
    places: &[Place],
    place_of: &[usize],
    springs: &[(Vec<usize>, Vec<f64>)],
) -> Option<(Vec<(Vec<usize>, Vec<f64>)>, Vec<Vec<usize>>)> {
    let mut which = std::collections::HashMap::new();
    for (q, p) in places.iter().enumerate() {
        which.insert(place_of[p.vars[0]], q);
    }
    let mut f: Vec<Option<DMatrix<f64>>> = vec![None; places.len()];
    for (xs, ke) in springs {
        let q = *which.get(&place_of[xs[0]])?;
        let p = &places[q];
        let m = xs.len();
        let fq = f[q].get_or_insert_with(|| DMatrix::zeros(p.vars.len(), p.vars.len()));
        let pos: Option<Vec<usize>> = xs.iter().map(|x| p.vars.iter().position(|v| v == x)).collect();
        let pos = pos?;
        for a in 0..m {
            for b in 0..m {
                fq[(pos[a], pos[b])] += ke[a * m + b];
            }
        }
    }
    let mut g = Vec::new();
    let mut cliques = Vec::new();
    for (p, fq) in places.iter().zip(f) {
        let Some(fq) = fq else { continue };
        let gq = p.t_inv.transpose() * fq * &p.t_inv;
        let m = p.dofs.len();
        g.push((p.dofs.clone(), (0..m * m).map(|e| gq[(e / m, e % m)]).collect()));
        let mut c = p.dofs.clone();
        c.sort_unstable();
        cliques.push(c);
    }
    Some((g, cliques))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terms(vars: &[(Var, f64)]) -> Terms {
        let mut t = Terms { vars: [(Var::M(0), 0.0); 2], n: vars.len(), constant: 0.0 };
        t.vars[..vars.len()].copy_from_slice(vars);
        t
    }

    /// `(K + F)^-1 v` with K and F given over x, against a dense solve.
    fn check(parts: &[(&[f64], &[Terms])], springs: &[(Vec<usize>, Vec<f64>)], k: DMatrix<f64>, nm: usize) {
        check_with(parts, None, springs, k, nm);
    }

    fn check_with(
        parts: &[(&[f64], &[Terms])],
        own: Option<&[Own]>,
        springs: &[(Vec<usize>, Vec<f64>)],
        k: DMatrix<f64>,
        nm: usize,
    ) {
        let n = k.nrows();
        let index = |v: Var| {
            Some(if let Var::R(i) = v {
                nm + i
            } else if let Var::M(i) = v {
                i
            } else {
                0
            })
        };
        let mut place_of: Vec<usize> = (0..n).collect();
        // one place: the unknowns of this small model all coincide
        place_of.iter_mut().for_each(|p| *p = 0);
        let sides = Sides::new(parts, own, index, n, springs, &place_of, (1, 1)).expect("square places");
        let v: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let x = sides.solve(&v);
        let exact = k.lu().solve(&nalgebra::DVector::from_vec(v)).expect("regular");
        for i in 0..n {
            assert!((x[i] - exact[i]).abs() < 1e-5 * exact.amax(), "{i}: {} against {}", x[i], exact[i]);
        }
    }

    /// A lone pair between two one-DOF parts, `d_k = m - r/2`, `d_l = m +
    /// r/2`, stiffnesses a and b, a spring k on r: `K + F = W^T diag(a, b)
    /// W + k e_r e_r^T`.
    #[test]
    fn a_lone_pair_is_solved_through_its_sides() {
        let (a, b, k) = (3.0, 5.0, 7.0);
        let t0 = [terms(&[(Var::M(0), 1.0), (Var::R(0), -0.5)])];
        let t1 = [terms(&[(Var::M(0), 1.0), (Var::R(0), 0.5)])];
        let parts: [(&[f64], &[Terms]); 2] = [(&[a], &t0), (&[b], &t1)];
        let springs = vec![(vec![1], vec![k])];
        let kx = DMatrix::from_row_slice(2, 2, &[a + b, (b - a) / 2.0, (b - a) / 2.0, (a + b) / 4.0 + k]);
        check(&parts, &springs, kx, 1);
    }

    /// The same pair with an interior DOF in each part, given as the parts'
    /// own stiffness: `[[2, -1], [-1, a + 1/2]]` and `[[4, 2], [2, b + 1]]`
    /// (interior first), whose Schur complements are a and b.
    #[test]
    fn a_lone_pair_is_solved_through_its_parts_own_stiffness() {
        let (a, b, k) = (3.0, 5.0, 7.0);
        let t0 = [terms(&[(Var::M(0), 1.0), (Var::R(0), -0.5)])];
        let t1 = [terms(&[(Var::M(0), 1.0), (Var::R(0), 0.5)])];
        let parts: [(&[f64], &[Terms]); 2] = [(&[a], &t0), (&[b], &t1)];
        let own = [
            Own { ni: 1, nodes: vec![0], entries: vec![(0, 0, 2.0), (1, 0, -1.0), (1, 1, a + 0.5)] },
            Own { ni: 1, nodes: vec![0], entries: vec![(0, 0, 4.0), (1, 0, 2.0), (1, 1, b + 1.0)] },
        ];
        let springs = vec![(vec![1], vec![k])];
        let kx = DMatrix::from_row_slice(2, 2, &[a + b, (b - a) / 2.0, (b - a) / 2.0, (a + b) / 4.0 + k]);
        check_with(&parts, Some(&own), &springs, kx, 1);
    }

    /// Three copies held by a support, `d_j = v + r_j`, no mean: they share
    /// no unknown, and only the junction's springs (a full 3 x 3) join them.
    #[test]
    fn held_copies_joined_by_springs_are_one_place() {
        let s = [[2.0], [3.0], [4.0]];
        let t: Vec<[Terms; 1]> = (0..3).map(|j| [terms(&[(Var::R(j), 1.0)])]).collect();
        let parts: Vec<(&[f64], &[Terms])> = (0..3).map(|j| (&s[j][..], &t[j][..])).collect();
        let kz = [6.0, -1.0, -2.0, -1.0, 5.0, -1.5, -2.0, -1.5, 7.0];
        let springs = vec![(vec![0, 1, 2], kz.to_vec())];
        let kx = DMatrix::from_row_slice(3, 3, &kz)
            + DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![2.0, 3.0, 4.0]));
        check(&parts, &springs, kx, 0);
    }
}
