//! The interface system: the condensed parts in the pairs' local frames
//! and in mean / relative coordinates ([`coords`]), reduced once to the
//! relative displacements ([`reduce`]; the bonded joins of substructures
//! first, by a sparse factorisation, when they outnumber the contact
//! unknowns: [`joins`]), and solved for one set of pair relations.
//!
//! A set of contact states is a choice, per pair axis, between a known
//! relative displacement `r` (tied: stick on every axis, slip on the normal)
//! and a known relation for the contact force λ (open: λ = 0; slip: the
//! friction law's force, possibly linearised in the pair's slip and normal
//! force). With `W r - c = -λ` (reduce.rs) each state set solves only the
//! rows of its free relative displacements. A supported axis of a pair is a
//! prescribed `d'`; its force is read on the unsupported side, and is zero
//! where both are supported (the supports carry it).

pub mod coords;
pub mod gmres;
pub mod iterative;
pub mod joins;
pub mod reduce;

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use coords::{Axis, Blocks, Var};
use iterative::{AppliedPart, Iterative, Remote, Source};
use joins::{JoinElimination, SparseBlocks};
use reduce::Reduced;

use super::basis::{self, FaceBasis};
use super::frame::{aligned_axis, frame, Frame};
use super::law::{ContactState, PairResult};
use super::rigid::{free_parts, PartModes, Tie};
use crate::fem::rigid::n_modes;
use crate::fem::sparse::NONE;
use crate::model::{Model, ModelError};
use crate::substructure::{Condensation, OperatorRef};

/// Where a part's interface nodes sit among the pairs.
struct PartMap {
    /// What each interface node of the part is, in the part's order.
    nodes: Vec<Slot>,
    /// Transformed edges, as positions in `nodes`.
    edges: Vec<[usize; 3]>,
}

/// An interface node of a part: one side of a contact pair, or a node the
/// part shares with other parts of the same body (a bonded join, where a
/// body is cut into substructures): always tied, its displacement (global
/// axes) is a mean of the interface.
#[derive(Clone, Copy, Debug)]
enum Slot {
    Pair { pair: usize, side: usize },
    Join(usize),
}

/// Interface DOFs summed over the parts (a joint counted once per side)
/// from which `[solver] interface = "auto"` solves the interface
/// iteratively (the `--help` of `InterfaceSolver::Auto` says the number
/// too). Measured (docs/bench3d.md, 2 threads): below it the dense
/// interface is 1.2-2.4 times faster (6,534 interface DOFs: 8.0 s against
/// 18.6 s; 11,790: 32.1 s against 39.3 s, but 4.1 GB against 1.5 GB); at
/// 24,426 the iterative one takes 229 s and 15.5 GB against 552 s and 21.9
/// GB; a column cut into 4 pieces (41,550 summed) 98 s and 4.7 GB against
/// 115 s and 16.5 GB, into 8 pieces (94,905) 94 s and 3.2 GB where the
/// dense interface ran out of 24 GB.
pub const ITERATIVE_FROM: usize = 20_000;

const IDENTITY: Frame = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// What a pair's unknowns are asked to satisfy in one solve.
#[derive(Clone, Copy, Debug)]
pub struct Relation {
    pub state: ContactState,
    /// `r` on tied axes: stick ties all axes, slip the normal one (its
    /// target is 0: the pair touches).
    pub target: [f64; 3],
    /// On free tangential axes of slipping pairs, the force on body I is
    /// `force + coupling * p + spring * r` (local t, b components; p = -λ_n
    /// the normal pressure force), so that a Newton step can linearise the
    /// Coulomb law; zero for the paper's fixed friction force.
    pub force: [f64; 3],
    pub coupling: [f64; 3],
    pub spring: [[f64; 3]; 3],
}

impl Relation {
    /// Stuck at `target`, open, or slipping with a known tangential force.
    pub fn simple(state: ContactState, target: [f64; 3], force: [f64; 3]) -> Relation {
        Relation { state, target, force, coupling: [0.0; 3], spring: [[0.0; 3]; 3] }
    }

    fn free_axis(&self, a: usize) -> bool {
        match self.state {
            ContactState::Stick => false,
            ContactState::Slip => a > 0,
            ContactState::Open => true,
        }
    }
}

/// The interface problem, set up once; solved for any set of relations.
pub struct InterfaceProblem<'a> {
    nd: usize,
    pub frames: Vec<Frame>,
    pub basis: FaceBasis,
    axes: Vec<[Axis; 3]>,
    /// The unknowns of each join's components.
    joins: Vec<[Axis; 3]>,
    /// Parts that share each join, and where the join is.
    join_parts: Vec<(Vec<usize>, [f64; 3])>,
    /// How the system is solved.
    solver: Solver<'a>,
    parts: Vec<PartMap>,
    /// Rigid motions of each part and the position of each pair, to tell
    /// which parts nothing holds.
    rigid: Vec<PartModes>,
    positions: Vec<[f64; 3]>,
    /// (part, position) of each pair's k and l.
    at: Vec<[(usize, usize); 2]>,
}

/// The interface system, dense or applied.
enum Solver<'a> {
    /// Reduced to the relative displacements (reduce.rs); the join means,
    /// when they were eliminated sparsely (joins.rs).
    Dense { reduced: Reduced, joined: Option<JoinElimination> },
    /// Applied through the parts' factors and solved by GMRES (iterative.rs).
    Iterative(Iterative<'a>),
}

/// Result of one interface solve.
pub struct InterfaceSolution {
    pub pairs: Vec<PairResult>,
    /// Contact force on body I at each pair, local axes (n, t, b), in the
    /// interface basis.
    pub forces: Vec<[f64; 3]>,
    /// Relative displacement `d'_l - d'_k` at each pair, local axes.
    pub rel: Vec<[f64; 3]>,
    /// Global nodal interface displacements of each part (order of its interface nodes).
    pub d_c: Vec<Vec<f64>>,
    /// Relative residual of the interface solve.
    pub residual: f64,
    /// Solved to the iterative interface's loose tolerance (its state set
    /// differed from the last solve's): good for judging the states, not
    /// as the answer.
    pub loose: bool,
}

/// Why an interface solve failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SolveFailure {
    /// These bodies are held by nothing.
    NotHeld(Vec<usize>),
    /// These bodies slide (or rotate) freely on slipping pairs: nothing holds
    /// them tangentially (empty when the cause is not found).
    Singular(Vec<usize>),
}

impl<'a> InterfaceProblem<'a> {
    /// The interface of the condensed `parts` (every part of the model, in
    /// order); `remote` applies the S of parts condensed for the iterative
    /// interface on other MPI ranks, `threads` this rank's ones.
    pub fn new(model: &Model, parts: &[OperatorRef], remote: Option<&'a dyn Remote>, threads: usize) -> Result<InterfaceProblem<'a>, ModelError> {
        let nd = model.nd;
        let np = model.pairs.len();
        let basis = FaceBasis::new(model);
        // the first part holding each node; the parts sharing each other node
        let mut where_is = vec![(NONE, NONE); model.n_nodes()];
        let mut holders: Vec<Vec<usize>> = vec![Vec::new(); model.n_nodes()];
        for (pi, p) in parts.iter().enumerate() {
            for (q, &n) in p.part.interface.iter().enumerate() {
                if where_is[n].0 == NONE {
                    where_is[n] = (pi, q);
                }
                holders[n].push(pi);
            }
        }
        let mut role = vec![None; model.n_nodes()];
        for (pair, p) in model.pairs.iter().enumerate() {
            role[p.k] = Some(Slot::Pair { pair, side: 0 });
            role[p.l] = Some(Slot::Pair { pair, side: 1 });
        }
        let mut join_nodes = Vec::new();
        for n in 0..model.n_nodes() {
            if role[n].is_none() && holders[n].len() > 1 {
                role[n] = Some(Slot::Join(join_nodes.len()));
                join_nodes.push(n);
            }
        }
        // frames, and the prescribed local values of each side (nodal basis)
        let mut frames = Vec::with_capacity(np);
        let mut fixed: Vec<[[Option<f64>; 3]; 2]> = Vec::with_capacity(np);
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
                            scene: model.scene.clone(),
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
            }
            frames.push(f);
            fixed.push(fx);
        }
        // prescribed values in the face basis (per side, local axis)
        if !basis.is_nodal() {
            for side in 0..2 {
                for a in 0..nd {
                    let v: Vec<f64> = fixed.iter().map(|fx| fx[side][a].unwrap_or(0.0)).collect();
                    let mut t = v.clone();
                    for &[m, c1, c2] in &basis.edges {
                        t[m] = (v[m] - basis::ALPHA * (v[c1] + v[c2])) / (1.0 - 2.0 * basis::ALPHA);
                    }
                    for (p, fx) in fixed.iter_mut().enumerate() {
                        if fx[side][a].is_some() {
                            fx[side][a] = Some(t[p]);
                        }
                    }
                }
            }
        }
        // unknowns, and the parts' interface nodes among them
        let (axes, mut nm, nr) = coords::number(&fixed, nd);
        let nm_pairs = nm;
        // joins: a mean per component, or the prescribed value
        let joins: Vec<[Axis; 3]> = join_nodes
            .iter()
            .map(|&n| {
                std::array::from_fn(|c| match (c < nd, model.prescribed.get(n * nd + c).copied().flatten()) {
                    (false, _) => Axis::Absent,
                    (true, Some(v)) => Axis::Held { vk: v, vl: v },
                    (true, None) => {
                        nm += 1;
                        Axis::Joined { m: nm - 1 }
                    }
                })
            })
            .collect();
        let join_parts: Vec<(Vec<usize>, [f64; 3])> = join_nodes.iter().map(|&n| (holders[n].clone(), model.coords[n])).collect();
        let at: Vec<[(usize, usize); 2]> = model.pairs.iter().map(|p| [where_is[p.k], where_is[p.l]]).collect();
        let maps: Vec<PartMap> = parts
            .iter()
            .map(|p| {
                let nodes: Vec<Slot> = p.part.interface.iter().map(|&n| role[n].expect("an interface node is in a pair or shared by parts")).collect();
                let mut pos: std::collections::HashMap<(usize, usize), usize> = std::collections::HashMap::new();
                for (q, slot) in nodes.iter().enumerate() {
                    if let Slot::Pair { pair, side } = *slot {
                        pos.insert((pair, side), q);
                    }
                }
                let edges = basis::part_edges(&basis, |pair| [pos.get(&(pair, 0)).copied(), pos.get(&(pair, 1)).copied()]);
                PartMap { nodes, edges }
            })
            .collect();
        let cases = parts.iter().map(|p| p.g.len()).max().unwrap_or(1);
        let frames_of = |map: &PartMap| -> Vec<Frame> {
            map.nodes
                .iter()
                .map(|slot| match *slot {
                    Slot::Pair { pair, .. } => frames[pair],
                    Slot::Join(_) => IDENTITY,
                })
                .collect()
        };
        let terms_of = |nc: usize, map: &PartMap| -> Vec<coords::Terms> {
            (0..nc)
                .map(|u| match map.nodes[u / nd] {
                    Slot::Pair { pair, side } => axes[pair][u % nd].terms(side),
                    Slot::Join(j) => joins[j][u % nd].terms(0),
                })
                .collect()
        };
        let not_held = || ModelError::Invalid {
            scene: model.scene.clone(),
            key: "supports".into(),
            msg: "the bodies are not held even with every contact stuck (the bonded interface system is singular): add a support".into(),
        };
        let nj = nm - nm_pairs;
        let rigid: Vec<PartModes> = parts.iter().map(|p| PartModes::new(model, &p.part.nodes(model))).collect();
        let positions = model.pairs.iter().map(|p| model.coords[p.k]).collect();
        let is_applied = |p: &OperatorRef| p.how == Condensation::Applied && p.nc > 0;
        if parts.iter().any(is_applied) {
            let applied = (parts.iter().enumerate().zip(&maps))
                .filter(|((_, p), _)| is_applied(p))
                .map(|((i, p), map)| {
                    let source = match p.applied {
                        Some(solve) => Source::Local(solve.clone()),
                        None => Source::Remote(i),
                    };
                    AppliedPart { source, diag: p.diag.to_vec(), terms: terms_of(p.nc, map), frames: frames_of(map), edges: map.edges.clone(), g: p.g.to_vec() }
                })
                .collect();
            let groups = axes
                .iter()
                .chain(&joins)
                .map(|ax| {
                    let mut vars = Vec::new();
                    for a in ax {
                        match *a {
                            Axis::Free { m, r } => vars.extend([Var::M(m), Var::R(r)]),
                            Axis::HeldK { r, .. } | Axis::HeldL { r, .. } => vars.push(Var::R(r)),
                            Axis::Joined { m } => vars.push(Var::M(m)),
                            Axis::Held { .. } | Axis::Absent => {}
                        }
                    }
                    vars
                })
                .collect();
            // the coarse space: each part's rigid motions on the means,
            // shared between the parts that hold a node
            let mut coarse = Vec::new();
            for ((p, map), modes) in parts.iter().zip(&maps).zip(&rigid) {
                if !is_applied(p) {
                    continue;
                }
                for k in 0..n_modes(model.analysis) {
                    let mut col = vec![0.0; nm + nr];
                    for (&node, slot) in p.part.interface.iter().zip(&map.nodes) {
                        // a mean is shared by the two sides of a pair, or by the parts at a join
                        let (node_axes, frame, w) = match *slot {
                            Slot::Join(j) => (&joins[j], IDENTITY, 1.0 / join_parts[j].0.len() as f64),
                            Slot::Pair { pair, .. } => (&axes[pair], frames[pair], 0.5),
                        };
                        for (a, axis) in node_axes.iter().enumerate().take(nd) {
                            if let Axis::Free { m, .. } | Axis::Joined { m } = *axis {
                                col[m] += w * modes.modes.along(model.coords[node], frame[a])[k];
                            }
                        }
                    }
                    coarse.push(col);
                }
            }
            let solver = Solver::Iterative(Iterative::new(nd, nm, nr, applied, groups, coarse, remote, threads));
            return Ok(InterfaceProblem { nd, frames, basis, axes, joins, join_parts, solver, parts: maps, rigid, positions, at });
        }
        let (blocks, joined) = if joins::worth_it(nj, nm_pairs, nr) {
            let cliques: Vec<Vec<coords::Terms>> = parts.iter().zip(&maps).map(|(p, map)| terms_of(p.nc, map)).collect();
            let mut node_of = vec![0; nj];
            for (j, axes) in joins.iter().enumerate() {
                for a in axes {
                    if let Axis::Joined { m } = *a {
                        node_of[m - nm_pairs] = j;
                    }
                }
            }
            let mut sparse = SparseBlocks::new(nm_pairs, nj, nr, cases, &cliques, node_of);
            for ((part, map), terms) in parts.iter().zip(&maps).zip(&cliques) {
                if part.nc > 0 {
                    let (s, g) = coords::localise(part.s, part.g, nd, &frames_of(map), &map.edges);
                    sparse.add_part(&s, &g, terms);
                }
            }
            let (blocks, joined) = sparse.condense().map_err(|_| not_held())?;
            (blocks, Some(joined))
        } else {
            let mut blocks = Blocks::zeros(nm, nr, cases);
            for (part, map) in parts.iter().zip(&maps) {
                if part.nc > 0 {
                    blocks.add_part(part.s, part.g, nd, &terms_of(part.nc, map), &frames_of(map), &map.edges);
                }
            }
            (blocks, None)
        };
        let reduced = Reduced::new(blocks).map_err(|_| not_held())?;
        let solver = Solver::Dense { reduced, joined };
        Ok(InterfaceProblem { nd, frames, basis, axes, joins, join_parts, solver, parts: maps, rigid, positions, at })
    }

    /// GMRES iterations (applications of the parts' S) of every solve so
    /// far; empty for the dense interface.
    pub fn applications(&self) -> Vec<usize> {
        match &self.solver {
            Solver::Dense { .. } => Vec::new(),
            Solver::Iterative(it) => it.iterations.lock().map(|v| v.clone()).unwrap_or_default(),
        }
    }

    /// The area pair `p` controls (in the interface basis), > 0.
    pub fn area(&self, p: usize) -> f64 {
        self.basis.areas[p]
    }

    /// Number of pairs.
    pub fn n_pairs(&self) -> usize {
        self.axes.len()
    }

    /// A stiffness of pair `p`'s relative displacement (the mean diagonal
    /// of W over its axes): the scale that turns a slip into a force.
    pub fn stiffness(&self, p: usize) -> f64 {
        let d: Vec<f64> = self
            .axes[p]
            .iter()
            .filter_map(|a| a.r())
            .map(|r| match &self.solver {
                Solver::Dense { reduced, .. } => reduced.w[(r, r)],
                Solver::Iterative(it) => it.diagonal_r(r),
            })
            .collect();
        if d.is_empty() {
            1.0
        } else {
            d.iter().sum::<f64>() / d.len() as f64
        }
    }

    /// Solves the interface system for the relations `rel` of every pair
    /// under the load factors `lambda` (case 0 also scales prescribed values).
    pub fn solve(&self, rel: &[Relation], lambda: &[f64]) -> Result<InterfaceSolution, SolveFailure> {
        let nd = self.nd;
        let ramp = lambda[0];
        let states: Vec<ContactState> = rel.iter().map(|r| r.state).collect();
        // A part nothing holds makes the system singular only up to
        // round-off: decide it from the states and the supports first.
        if let failure @ SolveFailure::NotHeld(_) = self.diagnose(&states) {
            return Err(failure);
        }
        let sliding = self.free(&states, false);
        if !sliding.is_empty() {
            return Err(SolveFailure::Singular(sliding));
        }
        let (r, wr_c, m, residual, loose) = match &self.solver {
            Solver::Dense { reduced, joined } => {
                let (r, wr_c, m, residual) = self.solve_dense(reduced, joined.as_ref(), rel, lambda, &states)?;
                (r, wr_c, m, residual, false)
            }
            Solver::Iterative(it) => {
                let a = it.solve(&self.axes, rel, lambda).ok_or_else(|| self.diagnose(&states))?;
                (a.r, a.residual_r, a.m, a.residual, a.loose)
            }
        };
        // the contact forces: -(W r - c); a free axis carries what its
        // relation prescribes (an open pair exactly zero, not round-off)
        let mut forces = vec![[0.0; 3]; rel.len()];
        let mut rels = vec![[0.0; 3]; rel.len()];
        for (p, ax) in self.axes.iter().enumerate() {
            for a in 0..nd {
                match ax[a] {
                    Axis::Held { vk, vl } => rels[p][a] = (vl - vk) * ramp,
                    Axis::Absent => {}
                    axis => {
                        let ri = axis.r().expect("an axis with r");
                        rels[p][a] = r[ri];
                        if !rel[p].free_axis(a) || rel[p].state == ContactState::Slip {
                            forces[p][a] = -wr_c[ri];
                        }
                    }
                }
            }
            if rel[p].state == ContactState::Slip {
                let pn = -forces[p][0];
                let rl = &rel[p];
                for a in 1..nd {
                    if self.axes[p][a].r().is_some() {
                        forces[p][a] = rl.force[a] + rl.coupling[a] * pn + (1..nd).map(|c| rl.spring[a][c] * rels[p][c]).sum::<f64>();
                    }
                }
            }
        }
        let pairs = (0..rel.len())
            .map(|p| {
                let area = self.basis.areas[p];
                let (f, r) = (forces[p], rels[p]);
                PairResult { sigma_n: f[0] / area, tau_t: f[1] / area, tau_b: f[2] / area, gap: r[0], slip: r[1].hypot(r[2]) }
            })
            .collect();
        // interface displacements of every part, global axes, nodal basis
        let d_c = self
            .parts
            .iter()
            .map(|map| {
                let (mut terms, mut frames) = (Vec::with_capacity(map.nodes.len() * nd), Vec::with_capacity(map.nodes.len()));
                for slot in &map.nodes {
                    let (axes, side, f) = match *slot {
                        Slot::Pair { pair, side } => (&self.axes[pair], side, self.frames[pair]),
                        Slot::Join(j) => (&self.joins[j], 0, IDENTITY),
                    };
                    terms.extend((0..nd).map(|a| axes[a].terms(side)));
                    frames.push(f);
                }
                coords::part_displacements(&terms, &frames, &map.edges, nd, ramp, |v| match v {
                    Var::M(i) => m[i],
                    Var::R(i) => r[i],
                })
            })
            .collect();
        Ok(InterfaceSolution { pairs, forces, rel: rels, d_c, residual, loose })
    }

    /// The relative displacements, `W r - c`, the means and the residual
    /// of the dense solve of `rel`.
    #[allow(clippy::type_complexity)]
    fn solve_dense(&self, reduced: &Reduced, joined: Option<&JoinElimination>, rel: &[Relation], lambda: &[f64], states: &[ContactState]) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>, f64), SolveFailure> {
        let nd = self.nd;
        let w = &reduced.w;
        let nr = w.nrows();
        let c = reduced.c_at(lambda);
        // free relative displacements, and the known values of tied ones
        let mut r = vec![0.0; nr];
        let mut free = vec![true; nr];
        for (p, rl) in rel.iter().enumerate() {
            for a in 0..nd {
                if let Some(ri) = self.axes[p][a].r() {
                    if !rl.free_axis(a) {
                        free[ri] = false;
                        r[ri] = rl.target[a];
                    }
                }
            }
        }
        let fidx: Vec<usize> = (0..nr).filter(|&i| free[i]).collect();
        let mut pos = vec![NONE; nr];
        for (f, &i) in fidx.iter().enumerate() {
            pos[i] = f;
        }
        let nf = fidx.len();
        // c - W r_T: the known part of every row
        let mut known = c.clone();
        for j in (0..nr).filter(|&j| !free[j] && r[j] != 0.0) {
            let rj = r[j];
            for (i, v) in known.iter_mut().enumerate() {
                *v -= w[(i, j)] * rj;
            }
        }
        let mut wf = Mat::<f64>::zeros(nf, nf);
        for (fj, &j) in fidx.iter().enumerate() {
            for (fi, &i) in fidx.iter().enumerate() {
                wf[(fi, fj)] = w[(i, j)];
            }
        }
        let mut rhs = Mat::<f64>::zeros(nf, 1);
        for (fi, &i) in fidx.iter().enumerate() {
            rhs[(fi, 0)] = known[i];
        }
        // slipping pairs: the friction force on their free tangential rows,
        // (W r - c)_t + force + coupling (W r - c)_n + spring r = 0
        let mut symmetric = true;
        for (p, rl) in rel.iter().enumerate() {
            if rl.state != ContactState::Slip {
                continue;
            }
            let rn = self.axes[p][0].r();
            for a in 1..nd {
                let Some(ra) = self.axes[p][a].r() else { continue };
                let i = pos[ra];
                rhs[(i, 0)] -= rl.force[a];
                if let (Some(rn), true) = (rn, rl.coupling[a] != 0.0) {
                    symmetric = false;
                    let ca = rl.coupling[a];
                    for (fj, &j) in fidx.iter().enumerate() {
                        wf[(i, fj)] += ca * w[(rn, j)];
                    }
                    rhs[(i, 0)] += ca * known[rn];
                }
                for cax in 1..nd {
                    if rl.spring[a][cax] == 0.0 {
                        continue;
                    }
                    if let Some(rc) = self.axes[p][cax].r() {
                        wf[(i, pos[rc])] += rl.spring[a][cax];
                        if rl.spring[a][cax] != rl.spring[cax][a] {
                            symmetric = false;
                        }
                    }
                }
            }
        }
        let z = if nf == 0 {
            Mat::<f64>::zeros(0, 1)
        } else if symmetric {
            match wf.llt(Side::Lower) {
                Ok(l) => l.solve(&rhs),
                Err(_) => return Err(self.diagnose(states)),
            }
        } else {
            wf.partial_piv_lu().solve(&rhs)
        };
        if z.col(0).iter().any(|v| !v.is_finite()) {
            return Err(self.diagnose(states));
        }
        let residual = if nf == 0 {
            0.0
        } else {
            let res = &wf * &z - &rhs;
            res.norm_l2() / rhs.norm_l2().max(f64::MIN_POSITIVE)
        };
        // Singular up to round-off (a body sliding freely on slipping pairs)
        // lets the factorisation pass: its residual is O(1), not O(eps).
        if residual > 1e-6 {
            return Err(self.diagnose(states));
        }
        for (f, &i) in fidx.iter().enumerate() {
            r[i] = z[(f, 0)];
        }
        let wr_c = reduced.residual(&r, &c);
        let mut m = reduced.means(&r, lambda);
        if let Some(joined) = joined {
            let m_j = joined.means(&m, &r, lambda);
            m.extend(m_j);
        }
        Ok((r, wr_c, m, residual))
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
        // parts of one body cut into substructures are always tied at their joins
        let joined = self.join_parts.iter().flat_map(|(ps, x)| {
            ps[1..].iter().flat_map(move |&q| (0..nd).map(move |a| Tie { parts: [ps[0], q], x: *x, dir: IDENTITY[a] }))
        });
        free_parts(&self.rigid, ties.chain(joined))
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
