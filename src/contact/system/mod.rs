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
mod dense;
pub mod gmres;
pub mod iterative;
pub mod joins;
pub mod junction;
pub mod reduce;
pub mod unknowns;


use coords::{Axis, Blocks, Terms, Var};
use iterative::{AppliedPart, Iterative, Remote, Source};
use joins::{JoinElimination, SparseBlocks};
use junction::Tied;
use reduce::Reduced;
use unknowns::{Unknowns, IDENTITY};

use super::basis::{self, FaceBasis};
use super::frame::Frame;
use super::law::{ContactState, PairResult};
use super::rigid::{self, free_parts, RigidModes, Tie};
use crate::fem::sparse::NONE;
use crate::model::{Model, ModelError};
use crate::substructure::{Condensation, OperatorRef};

/// How a part's interface nodes are written in the unknowns.
struct PartMap {
    /// The frame of each interface node of the part, in the part's order.
    frames: Vec<Frame>,
    /// The unknowns of each interface DOF (local axes, face basis).
    terms: Vec<Terms>,
    /// Transformed edges, as positions in the part's interface nodes.
    edges: Vec<[usize; 3]>,
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
    /// The normal pressure force p the relation was linearised at: a pair
    /// at a junction, whose normal force is known only after the solve,
    /// takes `force + coupling * pressure` (see [`junction`]).
    pub pressure: f64,
    /// What the pair can carry, for a junction choosing its tied forces.
    pub limit: Limit,
}

/// What a pair can carry in force, `λ_n <= tension` and `|λ_T| <= cohesion
/// - friction λ_n` (λ on body I, tension positive; cohesion and tension are
/// strengths times the pair's area): where a junction's tied forces are not
/// unique, it takes the least-norm ones within these (see [`junction`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    pub tension: f64,
    pub cohesion: f64,
    pub friction: f64,
}

impl Limit {
    /// No limit.
    pub const NONE: Limit = Limit { tension: f64::INFINITY, cohesion: f64::INFINITY, friction: 0.0 };
}

impl Relation {
    /// Stuck at `target`, open, or slipping with a known tangential force.
    pub fn simple(state: ContactState, target: [f64; 3], force: [f64; 3]) -> Relation {
        Relation { state, target, force, coupling: [0.0; 3], spring: [[0.0; 3]; 3], pressure: 0.0, limit: Limit::NONE }
    }

    /// The same relation with what the pair can carry.
    pub fn within(self, limit: Limit) -> Relation {
        Relation { limit, ..self }
    }

    pub fn free_axis(&self, a: usize) -> bool {
        match self.state {
            ContactState::Stick => false,
            ContactState::Slip => a > 0,
            ContactState::Open => true,
        }
    }
}

/// The free directions of the relative displacements r under one set of
/// relations: `r = r0 + sum_a y_a col_a`. A lone pair's free axis is a
/// column of one entry; a junction's free directions are the columns of its
/// null space (see [`junction`]).
pub struct Freedom {
    /// r where every y is 0: the tied axes' targets, the junctions' r0.
    pub r0: Vec<f64>,
    /// The columns, orthonormal, each over r.
    pub cols: Vec<Vec<(usize, f64)>>,
    /// The column of each lone pair's free r (NONE where tied or in a junction).
    pub pos: Vec<usize>,
    pub junctions: Vec<JunctionBlock>,
    /// The lone slipping pairs' free tangential rows.
    pub slips: Vec<SlipRow>,
}

/// A junction's part of a solve: its columns, and what its slipping pairs
/// add on them (`Z^T k Z`, `Z^T (f + k r0)`).
pub struct JunctionBlock {
    pub cols: std::ops::Range<usize>,
    pub kz: nalgebra::DMatrix<f64>,
    pub fz: nalgebra::DVector<f64>,
    pub tied: Tied,
}

/// A lone slipping pair's free tangential row (r index), whose equation is
/// the friction law's (see [`Relation`]):
/// `(W r - c)_row + force + coupling (W r - c)_normal + sum_c spring_c r_c = 0`.
pub struct SlipRow {
    pub row: usize,
    pub normal: Option<usize>,
    pub coupling: f64,
    pub springs: Vec<(usize, f64)>,
    pub force: f64,
}

/// The interface problem, set up once; solved for any set of relations.
pub struct InterfaceProblem<'a> {
    nd: usize,
    pub frames: Vec<Frame>,
    pub basis: FaceBasis,
    /// The unknowns: lone pairs' axes, junctions, joins.
    unknowns: Unknowns,
    /// Parts that share each join, and where the join is.
    join_parts: Vec<(Vec<usize>, [f64; 3])>,
    /// How the system is solved.
    solver: Solver<'a>,
    parts: Vec<PartMap>,
    /// Rigid motions of each part and the position of each pair, to tell
    /// which parts nothing holds.
    rigid: Vec<RigidModes>,
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
    /// A junction pair with axes its loop's ties lock (see
    /// [`junction::Junction::forces`]): its force as if those were tied,
    /// which is what it is judged by.
    pub as_tied: Vec<Option<[f64; 3]>>,
}

/// Why an interface solve failed.
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
        let mut paired = vec![false; model.n_nodes()];
        for p in &model.pairs {
            paired[p.k] = true;
            paired[p.l] = true;
        }
        let join_nodes: Vec<usize> = (0..model.n_nodes()).filter(|&n| !paired[n] && holders[n].len() > 1).collect();
        let sharing: Vec<usize> = join_nodes.iter().map(|&n| holders[n].len()).collect();
        let unknowns = Unknowns::new(model, &basis, &join_nodes, &sharing);
        let (nm, nm_pairs, nr) = (unknowns.nm, unknowns.nm_pairs, unknowns.nr);
        let frames = unknowns.frames.clone();
        let join_parts: Vec<(Vec<usize>, [f64; 3])> = join_nodes.iter().map(|&n| (holders[n].clone(), model.coords[n])).collect();
        let at: Vec<[(usize, usize); 2]> = model.pairs.iter().map(|p| [where_is[p.k], where_is[p.l]]).collect();
        let maps: Vec<PartMap> = parts
            .iter()
            .map(|p| {
                let nodes = &p.part.interface;
                let pos: std::collections::HashMap<usize, usize> = nodes.iter().enumerate().map(|(q, &n)| (n, q)).collect();
                let frames = nodes.iter().map(|&n| unknowns.of(n).frame).collect();
                let terms = nodes.iter().flat_map(|&n| unknowns.of(n).terms[..nd].to_vec()).collect();
                let edges = basis::part_edges(&basis, |n| pos.get(&n).copied());
                PartMap { frames, terms, edges }
            })
            .collect();
        let cases = parts.iter().map(|p| p.g.len()).max().unwrap_or(1);
        let not_held = || ModelError::Invalid {
            scene: model.scene.clone(),
            key: "supports".into(),
            msg: "the bodies are not held even with every contact stuck (the bonded interface system is singular): add a support".into(),
        };
        let nj = nm - nm_pairs;
        let rigid: Vec<RigidModes> = parts.iter().map(|p| RigidModes::new(model, &p.part.nodes(model))).collect();
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
                    AppliedPart { source, diag: p.diag.to_vec(), terms: map.terms.clone(), frames: map.frames.clone(), edges: map.edges.clone(), g: p.g.to_vec() }
                })
                .collect();
            // the preconditioner's blocks: per lone pair, junction and join node
            let vars_of = |ax: &[Axis; 3]| -> Vec<Var> {
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
            };
            let groups = (unknowns.axes.iter().zip(&unknowns.in_junction))
                .filter(|(_, j)| j.is_none())
                .map(|(ax, _)| vars_of(ax))
                .chain(unknowns.junctions.iter().map(|j| j.m.iter().map(|&m| Var::M(m)).chain(j.r.iter().map(|&r| Var::R(r))).collect()))
                .chain(unknowns.joins.iter().map(vars_of))
                .collect();
            // the coarse space: each part's rigid motions on the means,
            // shared between the nodes that have them
            let mut coarse = Vec::new();
            for ((p, map), modes) in parts.iter().zip(&maps).zip(&rigid) {
                if !is_applied(p) {
                    continue;
                }
                for k in 0..rigid::n_modes(model.analysis) {
                    let mut col = vec![0.0; nm + nr];
                    for (q, &node) in p.part.interface.iter().enumerate() {
                        let w = unknowns.of(node).share;
                        for a in 0..nd {
                            let t = &map.terms[q * nd + a];
                            for &(v, coef) in &t.vars[..t.n] {
                                if let Var::M(i) = v {
                                    col[i] += coef * w * modes.along(model.coords[node], map.frames[q][a])[k];
                                }
                            }
                        }
                    }
                    coarse.push(col);
                }
            }
            let solver = Solver::Iterative(Iterative::new(nd, nm, nr, applied, groups, coarse, remote, threads));
            return Ok(InterfaceProblem { nd, frames, basis, unknowns, join_parts, solver, parts: maps, rigid, positions, at });
        }
        let (blocks, joined) = if joins::worth_it(nj, nm_pairs, nr) {
            let cliques: Vec<Vec<Terms>> = maps.iter().map(|map| map.terms.clone()).collect();
            let mut node_of = vec![0; nj];
            for (j, axes) in unknowns.joins.iter().enumerate() {
                for a in axes {
                    if let Axis::Joined { m } = *a {
                        node_of[m - nm_pairs] = j;
                    }
                }
            }
            let mut sparse = SparseBlocks::new(nm_pairs, nj, nr, cases, &cliques, node_of);
            for ((part, map), terms) in parts.iter().zip(&maps).zip(&cliques) {
                if part.nc > 0 {
                    let (s, g) = coords::localise(part.s, part.g, nd, &map.frames, &map.edges);
                    sparse.add_part(&s, &g, terms);
                }
            }
            let (blocks, joined) = sparse.condense().map_err(|_| not_held())?;
            (blocks, Some(joined))
        } else {
            let mut blocks = Blocks::zeros(nm, nr, cases);
            for (part, map) in parts.iter().zip(&maps) {
                if part.nc > 0 {
                    blocks.add_part(part.s, part.g, nd, &map.terms, &map.frames, &map.edges);
                }
            }
            (blocks, None)
        };
        let reduced = Reduced::new(blocks).map_err(|_| not_held())?;
        let solver = Solver::Dense { reduced, joined };
        Ok(InterfaceProblem { nd, frames, basis, unknowns, join_parts, solver, parts: maps, rigid, positions, at })
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
        self.unknowns.axes.len()
    }

    /// A stiffness of pair `p`'s relative displacement (the mean diagonal
    /// of W over its axes): the scale that turns a slip into a force.
    pub fn stiffness(&self, p: usize) -> f64 {
        let diag = |r: usize| match &self.solver {
            Solver::Dense { reduced, .. } => reduced.w[(r, r)],
            Solver::Iterative(it) => it.diagonal_r(r),
        };
        let d: Vec<f64> = match self.unknowns.in_junction[p] {
            // a junction pair's axis is a row of its junction's r: rowᵀ W row
            // (the iterative interface: its diagonal only)
            Some((j, i)) => {
                let jn = &self.unknowns.junctions[j];
                (0..self.nd)
                    .map(|a| {
                        let row = &jn.rows[i][a];
                        match &self.solver {
                            Solver::Dense { reduced, .. } => (0..row.len())
                                .flat_map(|x| (0..row.len()).map(move |y| (x, y)))
                                .map(|(x, y)| row[x] * row[y] * reduced.w[(jn.r[x], jn.r[y])])
                                .sum(),
                            Solver::Iterative(_) => (0..row.len()).map(|x| row[x] * row[x] * diag(jn.r[x])).sum(),
                        }
                    })
                    .filter(|&v: &f64| v > 0.0)
                    .collect()
            }
            None => self.unknowns.axes[p].iter().filter_map(|a| a.r()).map(diag).collect(),
        };
        if d.is_empty() {
            1.0
        } else {
            d.iter().sum::<f64>() / d.len() as f64
        }
    }

    /// The free directions of the relative displacements under `rel`.
    fn freedom(&self, rel: &[Relation], ramp: f64) -> Freedom {
        let nd = self.nd;
        let u = &self.unknowns;
        let mut r0 = vec![0.0; u.nr];
        let mut cols: Vec<Vec<(usize, f64)>> = Vec::new();
        let mut pos = vec![NONE; u.nr];
        for (p, rl) in rel.iter().enumerate() {
            if u.in_junction[p].is_some() {
                continue;
            }
            for a in 0..nd {
                if let Some(ri) = u.axes[p][a].r() {
                    if rl.free_axis(a) {
                        pos[ri] = cols.len();
                        cols.push(vec![(ri, 1.0)]);
                    } else {
                        r0[ri] = rl.target[a];
                    }
                }
            }
        }
        let mut junctions = Vec::with_capacity(u.junctions.len());
        for jn in &u.junctions {
            let tied = jn.tie(rel, ramp, |p| self.basis.areas[p]);
            for (x, &ri) in jn.r.iter().enumerate() {
                r0[ri] = tied.r0[x];
            }
            let first = cols.len();
            for c in 0..tied.z.ncols() {
                cols.push(jn.r.iter().enumerate().map(|(x, &ri)| (ri, tied.z[(x, c)])).collect());
            }
            // the slipping pairs' springs and forces on the free directions
            let kz = tied.z.transpose() * &tied.k * &tied.z;
            let fz = tied.z.transpose() * (&tied.f + &tied.k * &tied.r0);
            junctions.push(JunctionBlock { cols: first..cols.len(), kz, fz, tied });
        }
        // the lone slipping pairs' rows
        let mut slips = Vec::new();
        for (p, rl) in rel.iter().enumerate() {
            if rl.state != ContactState::Slip || u.in_junction[p].is_some() {
                continue;
            }
            let ax = &u.axes[p];
            for a in 1..nd {
                let Some(ra) = ax[a].r() else { continue };
                let springs = (1..nd).filter_map(|c| ax[c].r().map(|rc| (rc, rl.spring[a][c]))).filter(|s| s.1 != 0.0).collect();
                slips.push(SlipRow { row: ra, normal: ax[0].r(), coupling: rl.coupling[a], springs, force: rl.force[a] });
            }
        }
        Freedom { r0, cols, pos, junctions, slips }
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
        let freedom = self.freedom(rel, ramp);
        let (r, wr_c, m, residual, loose) = match &self.solver {
            Solver::Dense { reduced, joined } => {
                let (r, wr_c, m, residual) = dense::solve(reduced, joined.as_ref(), &freedom, lambda).ok_or_else(|| self.diagnose(&states))?;
                (r, wr_c, m, residual, false)
            }
            Solver::Iterative(it) => {
                let a = it.solve(&freedom, &states, lambda).ok_or_else(|| self.diagnose(&states))?;
                (a.r, a.residual_r, a.m, a.residual, a.loose)
            }
        };
        // the contact forces: -(W r - c); a free axis carries what its
        // relation prescribes (an open pair exactly zero, not round-off)
        let mut forces = vec![[0.0; 3]; rel.len()];
        let mut rels = vec![[0.0; 3]; rel.len()];
        for (p, ax) in self.unknowns.axes.iter().enumerate() {
            if self.unknowns.in_junction[p].is_some() {
                continue;
            }
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
                    if ax[a].r().is_some() {
                        forces[p][a] = rl.force[a] + rl.coupling[a] * pn + (1..nd).map(|c| rl.spring[a][c] * rels[p][c]).sum::<f64>();
                    }
                }
            }
        }
        // a junction's pairs: the least-norm split of what its ties carry
        let mut as_tied = vec![None; rel.len()];
        for (jn, block) in self.unknowns.junctions.iter().zip(&freedom.junctions) {
            let rj = nalgebra::DVector::from_iterator(jn.r.len(), jn.r.iter().map(|&i| r[i]));
            let g = nalgebra::DVector::from_iterator(jn.r.len(), jn.r.iter().map(|&i| -wr_c[i]));
            for (&p, (f, x, t)) in jn.pairs.iter().zip(jn.forces(&block.tied, rel, &rj, &g, ramp)) {
                forces[p] = f;
                rels[p] = x;
                as_tied[p] = t;
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
                coords::part_displacements(&map.terms, &map.frames, &map.edges, nd, ramp, |v| match v {
                    Var::M(i) => m[i],
                    Var::R(i) => r[i],
                })
            })
            .collect();
        Ok(InterfaceSolution { pairs, forces, rel: rels, d_c, residual, loose, as_tied })
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
