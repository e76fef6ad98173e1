//! The interface system: the condensed parts in the pairs' local frames,
//! assembled according to the contact states and solved densely.
//!
//! Per part, `S' = T S T^T`, `G' = T G` (T block-diagonal, one pair frame per
//! interface node). For each pair and local axis, the two nodes share one
//! unknown where the state ties them (stick: all axes; slip: the normal only;
//! open: none), so the equal and opposite contact forces cancel and
//! `K_c d_c = R_c` holds no unknown force. After the solve, the contact force
//! on body I is `f = S'_I d' - G'_I` at k (eq. 13), the stresses `f / A` (eq. 14).
//! On a local axis where k is supported that force includes the support
//! reaction, so it is read as `-(S'_II d' - G'_II)` at l instead, and taken as
//! zero (all carried by the supports) where both nodes are supported.

use faer::{Mat, Side};

use super::frame::{aligned_axis, frame, Frame};
use super::law::{ContactState, PairResult};
use super::rigid::{free_parts, RigidModes, Tie};
use crate::fem::sparse::NONE;
use crate::model::{Model, ModelError};
use crate::substructure::Condensed;

/// One part's condensed matrices in local coordinates.
struct LocalPart {
    /// Frame of each interface node.
    t: Vec<Frame>,
    nc: usize,
    s: Vec<f64>,
    /// Condensed loads in local axes, one per load case.
    g: Vec<Vec<f64>>,
}

/// What the interface system is solved for besides the states.
pub struct Loading<'a> {
    /// Load factor of each load case (case 0 also scales prescribed values).
    pub lambda: &'a [f64],
    /// Known tangential force on body I at each pair (local axes; equal and
    /// opposite on body II), applied where the tangential axes are not tied.
    pub shear: &'a [[f64; 3]],
    /// Relative displacement `d'_l - d'_k` kept on each tied axis (slip
    /// accumulated before the pair stuck again; the normal entry is 0).
    pub offset: &'a [[f64; 3]],
}

/// The interface problem, set up once; solved for any set of states.
pub struct InterfaceProblem {
    nd: usize,
    pub frames: Vec<Frame>,
    /// (part, position in that part's interface) of each pair's k and l.
    at: Vec<[(usize, usize); 2]>,
    /// Prescribed local values of each pair's k and l, per local axis.
    fixed: Vec<[[Option<f64>; 3]; 2]>,
    parts: Vec<LocalPart>,
    areas: Vec<f64>,
    /// Rigid motions of each part and the position of each pair, to tell
    /// which parts nothing holds.
    rigid: Vec<RigidModes>,
    positions: Vec<[f64; 3]>,
}

/// Result of one interface solve.
pub struct InterfaceSolution {
    pub pairs: Vec<PairResult>,
    /// Contact force on body I at each pair, local axes (n, t, b).
    pub forces: Vec<[f64; 3]>,
    /// Relative displacement `d'_l - d'_k` at each pair, local axes.
    pub rel: Vec<[f64; 3]>,
    /// Global interface displacements of each part (order of its interface nodes).
    pub d_c: Vec<Vec<f64>>,
    /// Relative residual of the dense interface solve.
    pub residual: f64,
}

/// Why an interface solve failed.
pub enum SolveFailure {
    /// These bodies are held by nothing.
    NotHeld(Vec<usize>),
    /// These bodies slide (or rotate) freely on slipping pairs: nothing holds
    /// them tangentially (empty when the cause is not found).
    Singular(Vec<usize>),
}

impl InterfaceProblem {
    pub fn new(model: &Model, parts: &[Condensed]) -> Result<InterfaceProblem, ModelError> {
        let nd = model.nd;
        let mut where_is = vec![(NONE, NONE); model.n_nodes()];
        for (pi, p) in parts.iter().enumerate() {
            for (q, &n) in p.part.interface.iter().enumerate() {
                where_is[n] = (pi, q);
            }
        }
        let mut frames = Vec::with_capacity(model.pairs.len());
        let mut at = Vec::with_capacity(model.pairs.len());
        let mut fixed = Vec::with_capacity(model.pairs.len());
        let mut node_frame: Vec<Option<Frame>> = vec![None; model.n_nodes()];
        for pair in &model.pairs {
            let mut sup = [false; 3];
            for node in [pair.k, pair.l] {
                for c in 0..nd {
                    sup[c] |= model.prescribed[node * nd + c].is_some();
                }
            }
            let f = frame(nd, pair.normal, sup);
            let mut fx = [[None; 3]; 2];
            for (side, node) in [pair.k, pair.l].into_iter().enumerate() {
                for c in 0..nd {
                    if let Some(v) = model.prescribed[node * nd + c] {
                        let (a, sign) = aligned_axis(&f, nd, c).ok_or_else(|| ModelError::Invalid {
                            scene: "model".into(),
                            key: "supports".into(),
                            msg: format!(
                                "the contact node at {:?} is supported in direction {} which is not along its contact frame (normal {:?}): support it along the contact normal or tangent",
                                model.coords[node],
                                ["x", "y", "z"][c],
                                pair.normal
                            ),
                        })?;
                        fx[side][a] = Some(sign * v);
                    }
                }
                node_frame[node] = Some(f);
            }
            frames.push(f);
            at.push([where_is[pair.k], where_is[pair.l]]);
            fixed.push(fx);
        }
        let local = parts
            .iter()
            .map(|p| {
                let nc = p.nc;
                let nodes = p.part.interface.clone();
                let t: Vec<Frame> = nodes.iter().map(|&n| node_frame[n].unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])).collect();
                // S T^T: column block r becomes S[:, r] T_r^T
                let mut st = vec![0.0; nc * nc];
                for (r, tr) in t.iter().enumerate() {
                    for a in 0..nd {
                        for i in 0..nc {
                            st[i + (r * nd + a) * nc] = (0..nd).map(|c| p.s[i + (r * nd + c) * nc] * tr[a][c]).sum();
                        }
                    }
                }
                let mut s = vec![0.0; nc * nc];
                for (q, tq) in t.iter().enumerate() {
                    for a in 0..nd {
                        for j in 0..nc {
                            s[q * nd + a + j * nc] = (0..nd).map(|c| tq[a][c] * st[q * nd + c + j * nc]).sum();
                        }
                    }
                }
                let g = p
                    .g
                    .iter()
                    .map(|gc| {
                        let mut g = vec![0.0; nc];
                        for (q, tq) in t.iter().enumerate() {
                            for a in 0..nd {
                                g[q * nd + a] = (0..nd).map(|c| tq[a][c] * gc[q * nd + c]).sum();
                            }
                        }
                        g
                    })
                    .collect();
                LocalPart { t, nc, s, g }
            })
            .collect();
        let areas = model.pairs.iter().map(|p| p.area).collect();
        let rigid = parts.iter().map(|p| RigidModes::new(model, &p.part.bodies)).collect();
        let positions = model.pairs.iter().map(|p| model.coords[p.k]).collect();
        Ok(InterfaceProblem { nd, frames, at, fixed, parts: local, areas, rigid, positions })
    }

    /// The area pair `p` controls.
    pub fn area(&self, p: usize) -> f64 {
        self.areas[p]
    }

    /// Solves the interface system for the given states and loading.
    pub fn solve(&self, states: &[ContactState], loading: &Loading) -> Result<InterfaceSolution, SolveFailure> {
        let nd = self.nd;
        let ramp = loading.lambda[0];
        // A part nothing holds makes K_c singular only up to round-off (its
        // S has rigid-body modes of size eps * |S|), so the factorisation
        // may well succeed and return huge displacements: decide it from the
        // states and the supports, before any arithmetic.
        if let failure @ SolveFailure::NotHeld(_) = self.diagnose(states) {
            return Err(failure);
        }
        let sliding = self.free(states, false);
        if !sliding.is_empty() {
            return Err(SolveFailure::Singular(sliding));
        }
        // slot of each (part, interface dof): unknown index or fixed value
        // an unknown plus an offset, or a fixed value
        #[derive(Clone, Copy)]
        enum Slot {
            Free(usize, f64),
            Fixed(f64),
        }
        let mut slots: Vec<Vec<Slot>> = self.parts.iter().map(|p| vec![Slot::Fixed(0.0); p.nc]).collect();
        let mut m = 0;
        let mut new_slot = |fixed: Option<f64>| match fixed {
            Some(v) => Slot::Fixed(v * ramp),
            None => {
                m += 1;
                Slot::Free(m - 1, 0.0)
            }
        };
        for (p, st) in states.iter().enumerate() {
            let [(pk, qk), (pl, ql)] = self.at[p];
            for a in 0..nd {
                let shared = match st {
                    ContactState::Stick => true,
                    ContactState::Slip => a == 0,
                    ContactState::Open => false,
                };
                let fx = self.fixed[p];
                if shared {
                    let s = new_slot(fx[0][a].or(fx[1][a]));
                    slots[pk][qk * nd + a] = s;
                    slots[pl][ql * nd + a] = match s {
                        Slot::Free(i, _) => Slot::Free(i, loading.offset[p][a]),
                        fixed => fixed,
                    };
                } else {
                    slots[pk][qk * nd + a] = new_slot(fx[0][a]);
                    slots[pl][ql * nd + a] = new_slot(fx[1][a]);
                }
            }
        }
        let mut k = Mat::<f64>::zeros(m, m);
        let mut r = Mat::<f64>::zeros(m, 1);
        let g_loc: Vec<Vec<f64>> = self
            .parts
            .iter()
            .map(|lp| {
                let mut g = vec![0.0; lp.nc];
                for (gc, &l) in lp.g.iter().zip(loading.lambda) {
                    if l != 0.0 {
                        for (o, v) in g.iter_mut().zip(gc) {
                            *o += l * v;
                        }
                    }
                }
                g
            })
            .collect();
        for (pi, lp) in self.parts.iter().enumerate() {
            let sl = &slots[pi];
            for j in 0..lp.nc {
                // the known part of d_j moves to the right-hand side
                let known = match sl[j] {
                    Slot::Free(jj, off) => {
                        r[(jj, 0)] += g_loc[pi][j];
                        for i in 0..lp.nc {
                            if let Slot::Free(ii, _) = sl[i] {
                                k[(ii, jj)] += lp.s[i + j * lp.nc];
                            }
                        }
                        off
                    }
                    Slot::Fixed(v) => v,
                };
                if known != 0.0 {
                    for i in 0..lp.nc {
                        if let Slot::Free(ii, _) = sl[i] {
                            r[(ii, 0)] -= lp.s[i + j * lp.nc] * known;
                        }
                    }
                }
            }
        }
        for (p, st) in states.iter().enumerate() {
            if *st == ContactState::Stick {
                continue;
            }
            let [(pk, qk), (pl, ql)] = self.at[p];
            for a in 1..nd {
                if let Slot::Free(i, _) = slots[pk][qk * nd + a] {
                    r[(i, 0)] += loading.shear[p][a];
                }
                if let Slot::Free(i, _) = slots[pl][ql * nd + a] {
                    r[(i, 0)] -= loading.shear[p][a];
                }
            }
        }
        let z = if m == 0 {
            Mat::<f64>::zeros(0, 1)
        } else {
            let llt = match k.llt(Side::Lower) {
                Ok(l) => l,
                Err(_) => return Err(self.diagnose(states)),
            };
            use faer::linalg::solvers::Solve;
            llt.solve(&r)
        };
        if z.col(0).iter().any(|v| !v.is_finite()) {
            return Err(self.diagnose(states));
        }
        let residual = if m == 0 {
            0.0
        } else {
            let res = &k * &z - &r;
            res.norm_l2() / r.norm_l2().max(f64::MIN_POSITIVE)
        };
        // Singular up to round-off (a body sliding freely on slipping pairs)
        // lets the factorisation pass: its residual is O(1), not O(eps).
        if residual > 1e-6 {
            return Err(self.diagnose(states));
        }
        // local displacements and forces per part
        let mut d_loc: Vec<Vec<f64>> = Vec::with_capacity(self.parts.len());
        let mut f_loc: Vec<Vec<f64>> = Vec::with_capacity(self.parts.len());
        for (pi, lp) in self.parts.iter().enumerate() {
            let d: Vec<f64> = slots[pi]
                .iter()
                .map(|s| match *s {
                    Slot::Free(i, off) => z[(i, 0)] + off,
                    Slot::Fixed(v) => v,
                })
                .collect();
            let f: Vec<f64> = (0..lp.nc).map(|i| (0..lp.nc).map(|j| lp.s[i + j * lp.nc] * d[j]).sum::<f64>() - g_loc[pi][i]).collect();
            d_loc.push(d);
            f_loc.push(f);
        }
        let mut forces = Vec::with_capacity(states.len());
        let mut rels = Vec::with_capacity(states.len());
        let pairs = (0..states.len())
            .map(|p| {
                let [(pk, qk), (pl, ql)] = self.at[p];
                let fk = &f_loc[pk][qk * nd..qk * nd + nd];
                let fl = &f_loc[pl][ql * nd..ql * nd + nd];
                let dk = &d_loc[pk][qk * nd..qk * nd + nd];
                let dl = &d_loc[pl][ql * nd..ql * nd + nd];
                let a = self.areas[p];
                let mut rel = [0.0; 3];
                for i in 0..nd {
                    rel[i] = dl[i] - dk[i];
                }
                // On a supported local axis the node's force is contact plus
                // support reaction: read the contact force on the side that is
                // not supported, and where both are, the support carries it all.
                let fx = self.fixed[p];
                let force = |ax: usize| match (fx[0][ax], fx[1][ax]) {
                    (None, _) => fk[ax],
                    (Some(_), None) => -fl[ax],
                    (Some(_), Some(_)) => 0.0,
                };
                let mut f = [0.0; 3];
                for (ax, v) in f.iter_mut().enumerate().take(nd) {
                    *v = force(ax);
                }
                forces.push(f);
                rels.push(rel);
                PairResult {
                    sigma_n: f[0] / a,
                    tau_t: f[1] / a,
                    tau_b: f[2] / a,
                    gap: rel[0],
                    slip: rel[1].hypot(rel[2]),
                }
            })
            .collect();
        // back to global axes
        let d_c = self
            .parts
            .iter()
            .zip(&d_loc)
            .map(|(lp, d)| {
                let mut g = vec![0.0; lp.nc];
                for (q, t) in lp.t.iter().enumerate() {
                    for c in 0..nd {
                        g[q * nd + c] = (0..nd).map(|a| t[a][c] * d[q * nd + a]).sum();
                    }
                }
                g
            })
            .collect();
        Ok(InterfaceSolution { pairs, forces, rel: rels, d_c, residual })
    }

    /// Parts that a rigid motion moves which the supports and the pairs tied
    /// by `states` do not stop; `slip_holds`: count slipping pairs as stuck
    /// (then only open pairs release anything).
    fn free(&self, states: &[ContactState], slip_holds: bool) -> Vec<usize> {
        let nd = self.nd;
        let ties = states.iter().enumerate().flat_map(|(p, st)| {
            let axes = match st {
                ContactState::Stick => nd,
                ContactState::Slip if slip_holds => nd,
                ContactState::Slip => 1,
                ContactState::Open => 0,
            };
            let [(pk, _), (pl, _)] = self.at[p];
            (0..axes).map(move |a| Tie { parts: [pk, pl], x: self.positions[p], dir: self.frames[p][a] })
        });
        free_parts(&self.rigid, ties)
    }

    /// Why the interface system is singular: parts held by nothing once
    /// their open pairs let go, or else a part sliding on slipping pairs.
    fn diagnose(&self, states: &[ContactState]) -> SolveFailure {
        let free = self.free(states, true);
        if free.is_empty() {
            SolveFailure::Singular(self.free(states, false))
        } else {
            SolveFailure::NotHeld(free)
        }
    }
}
