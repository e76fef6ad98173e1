//! Consistent recovery of contact tractions: on each interface, the
//! traction field `t = sum_a N_a t_a` whose consistent nodal forces equal the
//! pair forces, `M t = f` with the interface mass matrix
//! `M_ab = ∫ N_a N_b dA` over body I's facets (thickness or 2 pi r included,
//! as for every other integral). The lumped recovery of the paper (eq. 14) is
//! `t_a = f_a / sum_b M_ab`; both agree in the interior of a uniform field,
//! but only the consistent one is exact at the ends of an interface for a
//! traction the facets' shape functions contain (e.g. linear along linear
//! elements).

use super::basis::FaceBasis;
use crate::fem::element::{facet_point, measure};
use crate::fem::quadrature;
use crate::fem::sparse::{Cholesky, FactorError, SymMatrix, NONE};
use crate::model::Model;

/// The factorised interface mass matrix of all pairs.
pub struct ConsistentTraction {
    chol: Cholesky,
    n: usize,
}

impl ConsistentTraction {
    pub fn new(model: &Model) -> Result<ConsistentTraction, FactorError> {
        let n = model.pairs.len();
        // the pair of every facet node (a junction's copy has one per face)
        let at = model.facet_pairs();
        let facets: Vec<(&crate::mesh::Cell, &[usize])> = model
            .interfaces
            .iter()
            .zip(&at)
            .flat_map(|(i, a)| i.facets.iter().zip(a.iter().map(|v| v.as_slice())))
            .collect();
        let paired: Vec<Vec<usize>> =
            facets.iter().map(|(_, p)| p.iter().copied().filter(|&x| x != NONE).collect()).collect();
        let identity: Vec<usize> = (0..n).collect();
        let mut m = SymMatrix::pattern(n, 1, &identity, paired.iter().map(|p| p.as_slice()));
        let mut me = Vec::new();
        for (f, pairs) in &facets {
            let nn = f.nodes.len();
            let xe: Vec<[f64; 3]> = f.nodes.iter().map(|&k| model.coords[k]).collect();
            me.clear();
            me.resize(nn * nn, 0.0);
            for q in quadrature::rule(f.kind, 2 * f.kind.order() + 2) {
                let (nf, _, da, x) = facet_point(f.kind, &xe, q.xi);
                let w = q.w * da * measure(model.analysis, model.thickness, &x);
                for a in 0..nn {
                    for b in 0..nn {
                        me[a * nn + b] += w * nf[a] * nf[b];
                    }
                }
            }
            m.add(pairs, &me);
        }
        Ok(ConsistentTraction { chol: Cholesky::factor(&m)?, n })
    }

    /// Tractions per pair from forces per pair (each of `nd` local
    /// components) in the interface basis `basis` (nodal forces are
    /// `Q^-T` of them).
    pub fn recover(&self, forces: &[[f64; 3]], basis: &FaceBasis) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; self.n];
        for c in 0..3 {
            let b: Vec<f64> = forces.iter().map(|f| f[c]).collect();
            let mut b = basis.inverse_transpose_apply(&b);
            if b.iter().all(|&v| v == 0.0) {
                continue;
            }
            self.chol.solve(&mut b);
            for (o, v) in out.iter_mut().zip(b) {
                o[c] = v;
            }
        }
        out
    }
}
