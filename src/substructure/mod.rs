//! Substructures: the bodies of a model grouped into parts (bodies joined by
//! shared nodes move as one), each assembled and factorised once, and
//! condensed onto its contact interface.
//!
//! With the part's DOFs split into interior `i` and interface `c`,
//!
//! ```text
//! [K_ii K_ic] [d_i]   [F_i      ]
//! [K_ci K_cc] [d_c] = [F_c + f_c]       S = K_cc - K_ci K_ii^-1 K_ic
//!                                        G = F_c  - K_ci K_ii^-1 F_i
//! S d_c = G + f_c                        d_i = K_ii^-1 (F_i - K_ic d_c)
//! ```
//!
//! Interface DOFs are all components of the nodes in contact pairs, in
//! global axes, supported or not: supports of interface nodes are applied in
//! the interface system. A part without contact has no interface and is
//! solved directly.

pub mod assembly;

use crate::fem::sparse::{Cholesky, FactorError, SymMatrix, NONE};
use crate::model::{Model, ModelError};

/// Bodies that share nodes, and the part's contact nodes.
#[derive(Clone, Debug)]
pub struct Part {
    pub bodies: Vec<usize>,
    /// Model nodes of this part that are in contact pairs, ascending.
    pub interface: Vec<usize>,
}

/// Groups bodies into parts by shared model nodes.
pub fn parts(model: &Model) -> Vec<Part> {
    let nb = model.bodies.len();
    let mut parent: Vec<usize> = (0..nb).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let mut owner = vec![NONE; model.n_nodes()];
    for (b, body) in model.bodies.iter().enumerate() {
        for c in &body.cells {
            for &n in &c.nodes {
                if owner[n] == NONE {
                    owner[n] = b;
                } else {
                    let (x, y) = (root(&mut parent, owner[n]), root(&mut parent, b));
                    parent[x.max(y)] = x.min(y);
                }
            }
        }
    }
    let mut in_pair = vec![false; model.n_nodes()];
    for p in &model.pairs {
        in_pair[p.k] = true;
        in_pair[p.l] = true;
    }
    let mut parts: Vec<Part> = Vec::new();
    let mut part_of_root = vec![NONE; nb];
    for b in 0..nb {
        let r = root(&mut parent, b);
        if part_of_root[r] == NONE {
            part_of_root[r] = parts.len();
            parts.push(Part { bodies: Vec::new(), interface: Vec::new() });
        }
        parts[part_of_root[r]].bodies.push(b);
    }
    for (n, &used) in in_pair.iter().enumerate() {
        if used && owner[n] != NONE {
            let r = root(&mut parent, owner[n]);
            parts[part_of_root[r]].interface.push(n);
        }
    }
    parts
}

/// A factorised part, condensed onto its interface when it has one.
pub struct Condensed {
    pub part: Part,
    /// Interior equation of each model DOF, or NONE.
    pub dof_of: Vec<usize>,
    pub ni: usize,
    /// Number of interface DOFs (`interface.len() * nd`).
    pub nc: usize,
    chol: Cholesky,
    /// K_ci as rows: for interface DOF r, its (interior equation, value) entries.
    k_ci: Vec<Vec<(usize, f64)>>,
    /// K_ii^-1 F_i: the interior displacements when the interface is held fixed.
    d_i0: Vec<f64>,
    /// Schur complement, column-major nc x nc.
    pub s: Vec<f64>,
    /// Condensed load.
    pub g: Vec<f64>,
    /// Seconds spent assembling (the rest of `condense` is factorising and condensing).
    pub assemble_s: f64,
}

/// Why a part could not be solved.
pub fn not_held(model: &Model, part: &Part, e: FactorError) -> ModelError {
    let names = model.body_names(&part.bodies);
    let msg = match e {
        FactorError::NotPositiveDefinite => format!(
            "{} {} not held: the stiffness matrix is singular. Add a support (or more supports: every rigid-body motion must be stopped) or a contact that stays closed",
            if part.bodies.len() == 1 { "body" } else { "bodies" },
            names
        ),
        FactorError::Resource(r) => format!("bodies {names}: {r}"),
    };
    ModelError::Invalid { scene: String::from("model"), key: String::from("supports"), msg }
}

/// Number the interior free DOFs (0..ni) and the interface DOFs (ni..ni+nc).
fn numbering(model: &Model, part: &Part) -> (Vec<usize>, usize, usize) {
    let nd = model.nd;
    let mut dof_of = vec![NONE; model.n_nodes() * nd];
    let mut is_iface = vec![false; model.n_nodes()];
    for &n in &part.interface {
        is_iface[n] = true;
    }
    let mut seen = vec![false; model.n_nodes()];
    let mut ni = 0;
    for &b in &part.bodies {
        for c in &model.bodies[b].cells {
            for &n in &c.nodes {
                if seen[n] || is_iface[n] {
                    continue;
                }
                seen[n] = true;
                for comp in 0..nd {
                    if model.prescribed[n * nd + comp].is_none() {
                        dof_of[n * nd + comp] = ni;
                        ni += 1;
                    }
                }
            }
        }
    }
    let mut next = ni;
    for &n in &part.interface {
        for comp in 0..nd {
            dof_of[n * nd + comp] = next;
            next += 1;
        }
    }
    (dof_of, ni, next - ni)
}

/// Assembles, factorises and condenses a part.
pub fn condense(model: &Model, part: Part) -> Result<Condensed, ModelError> {
    let t = std::time::Instant::now();
    let (mut dof_of, ni, nc) = numbering(model, &part);
    let a = assembly::assemble(model, &part.bodies, &dof_of, ni + nc)?;
    let assemble_s = t.elapsed().as_secs_f64();
    // split the lower triangle into K_ii (leading block), K_ci and K_cc
    let k = &a.k;
    let mut col_ptr = Vec::with_capacity(ni + 1);
    let mut row_idx = Vec::new();
    let mut values = Vec::new();
    let mut k_ci: Vec<Vec<(usize, f64)>> = vec![Vec::new(); nc];
    col_ptr.push(0);
    for col in 0..ni {
        for p in k.col_ptr[col]..k.col_ptr[col + 1] {
            let r = k.row_idx[p];
            if r < ni {
                row_idx.push(r);
                values.push(k.values[p]);
            } else {
                k_ci[r - ni].push((col, k.values[p]));
            }
        }
        col_ptr.push(row_idx.len());
    }
    let mut s = vec![0.0; nc * nc];
    for col in ni..ni + nc {
        for p in k.col_ptr[col]..k.col_ptr[col + 1] {
            let (r, c) = (k.row_idx[p] - ni, col - ni);
            s[r + c * nc] = k.values[p];
            s[c + r * nc] = k.values[p];
        }
    }
    let k_ii = SymMatrix { n: ni, col_ptr, row_idx, values };
    let chol = Cholesky::factor(&k_ii).map_err(|e| not_held(model, &part, e))?;
    let mut g = a.f[ni..].to_vec();
    // G = F_c - K_ci K_ii^-1 F_i
    let mut d_i0 = a.f[..ni].to_vec();
    chol.solve(&mut d_i0);
    for r in 0..nc {
        g[r] -= k_ci[r].iter().map(|&(c, v)| v * d_i0[c]).sum::<f64>();
    }
    // S = K_cc - K_ci K_ii^-1 K_ic, a chunk of right-hand sides at a time
    let chunk = (25_000_000 / ni.max(1)).clamp(1, 100);
    let mut w = Vec::new();
    let mut j0 = 0;
    while j0 < nc {
        let m = chunk.min(nc - j0);
        w.clear();
        w.resize(ni * m, 0.0);
        for j in 0..m {
            for &(c, v) in &k_ci[j0 + j] {
                w[c + j * ni] = v;
            }
        }
        chol.solve_many(&mut w, m);
        for j in 0..m {
            let col = &w[j * ni..(j + 1) * ni];
            for r in 0..nc {
                let v: f64 = k_ci[r].iter().map(|&(c, v)| v * col[c]).sum();
                s[r + (j0 + j) * nc] -= v;
            }
        }
        j0 += m;
    }
    // symmetrise the round-off
    for c in 0..nc {
        for r in c + 1..nc {
            let v = 0.5 * (s[r + c * nc] + s[c + r * nc]);
            s[r + c * nc] = v;
            s[c + r * nc] = v;
        }
    }
    for d in dof_of.iter_mut() {
        if *d != NONE && *d >= ni {
            *d = NONE;
        }
    }
    Ok(Condensed { part, dof_of, ni, nc, chol, k_ci, d_i0, s, g, assemble_s })
}

impl Condensed {
    /// Interior displacements from the interface displacements `d_c`, written
    /// into the model-wide displacement vector `u` (node-major, nd per node),
    /// together with `d_c` itself and the prescribed values.
    pub fn recover(&self, model: &Model, d_c: &[f64], u: &mut [f64]) {
        let nd = model.nd;
        // d_i = K_ii^-1 F_i - K_ii^-1 K_ic d_c; no solve at all without interface
        let mut d_i = self.d_i0.clone();
        if d_c.iter().any(|&v| v != 0.0) {
            let mut w = vec![0.0; self.ni];
            for (r, row) in self.k_ci.iter().enumerate() {
                for &(c, v) in row {
                    w[c] += v * d_c[r];
                }
            }
            self.chol.solve(&mut w);
            for (a, b) in d_i.iter_mut().zip(&w) {
                *a -= b;
            }
        }
        for (i, &d) in self.dof_of.iter().enumerate() {
            if d != NONE {
                u[i] = d_i[d];
            } else if let Some(v) = model.prescribed[i] {
                u[i] = v;
            }
        }
        for (q, &n) in self.part.interface.iter().enumerate() {
            for c in 0..nd {
                u[n * nd + c] = d_c[q * nd + c];
            }
        }
    }
}
