//! The interface system: the condensed parts in the pairs' local frames
//! and in mean / relative coordinates ([`coords`], laid out once by
//! [`layout`]), solved for one set of pair relations by an interface
//! [`Solver`]: [`dense`] (S formed, reduced once to the relative
//! displacements, [`reduce`]; the bonded joins of substructures first, by a
//! sparse factorisation, when they outnumber the contact unknowns:
//! [`joins`]) or [`iterative`] (S applied through the parts' interior
//! factors, GMRES). A new way of solving the interface is one more
//! implementation of [`Solver`] and one variant of [`InterfaceKind`].
//!
//! Where joints cross, copies of one node are in several pairs whose ties
//! close loops: those pairs are solved as junctions ([`junction`]), on the
//! null space of their tied rows, their tied forces the least-norm ones
//! within every pair's limit.
//!
//! A set of contact states is a choice, per pair axis, between a known
//! relative displacement `r` (tied: stick on every axis, slip on the normal)
//! and a known relation for the contact force λ (open: λ = 0; slip: the
//! friction law's force, possibly linearised in the pair's slip and normal
//! force). With `W r - c = -λ` (reduce.rs) each state set solves only the
//! rows of its free relative displacements. A joint that deforms
//! ([`Relation::elastic`]) is tied on no axis: closed, its force is a
//! spring's on every axis, a row of the same kind as a slipping pair's. A supported axis of a pair is a
//! prescribed `d'`; its force is read on the unsupported side, and is zero
//! where both are supported (the supports carry it).
//!
//! A right-hand side that depends on the states, the water in the joints
//! pushing every pair's sides apart ([`super::water`]), is added at each
//! solve on the rows of r ([`Freedom::pushed`], [`Layout::pushed`]): no
//! part is condensed again.
//!
//! Before solving, the parts nothing holds are found from the relations'
//! geometry ([`super::mobility`]): every tied axis holds, and so does a
//! slipping pair across its slip where the robust rule's linearised
//! friction has a spring (its force turns as the pair moves across it: a
//! wedge slipping along a V-groove while its friction still holds it
//! partly across the groove is not free to slide). A pair that holds
//! along its normal alone on a curved contact holds only what its facets'
//! normals agree on: a lining whose interface carries no shear turns in
//! its round hole, however its facets' lengths tilt the pairs' normals
//! (see [`super::mobility`]); what moves is named ([`Free::motions`]).

pub mod coords;
pub mod dense;
pub mod freedom;
pub mod gmres;
pub mod iterative;
pub mod joins;
pub mod junction;
pub mod kind;
mod layout;
mod least_distance;
mod means_whole;
mod own;
pub mod reduce;
pub mod relation;
mod sides;
pub mod solver;
pub mod sparse;
mod threads;
mod w_columns;
mod w_entries;

use coords::{Axis, Var};
pub use freedom::{Freedom, JunctionBlock, Lift, SlipRow};
use iterative::Remote;
pub use junction::Room;
pub use kind::{InterfaceKind, ITERATIVE_FROM};
use layout::Layout;
pub use relation::{Limit, Relation};
pub use solver::{Accuracy, Answer, Solver, Split, Springs, WarmStart};
use threads::in_threads;

use super::basis::FaceBasis;
use super::frame::{Frame, IDENTITY};
use super::law::{ContactState, PairResult};
use super::mobility::{free_parts, pair_ties, Free, PartModes, Tie};
use super::water::Water;
use crate::model::{Model, ModelError};
use crate::substructure::OperatorRef;

/// A slipping pair's friction spring holds it across its slip (in the
/// check for bodies that slide freely) from this share of the pair's own
/// stiffness ([`InterfaceProblem::stiffness`]) on.
const SPRING_HOLDS: f64 = 1e-6;

/// The interface problem, set up once; solved for any set of relations.
pub struct InterfaceProblem<'a> {
    layout: Layout,
    basis: FaceBasis,
    solver: Box<dyn Solver + 'a>,
    /// Rigid motions of each part, and the position of each pair and the
    /// spread of its facets' normals, to tell which parts nothing holds.
    rigid: Vec<PartModes>,
    positions: Vec<[f64; 3]>,
    spreads: Vec<f64>,
    /// The load factors of the last solve: a new load (step) lets the
    /// junctions solve for their pressures again (see
    /// [`junction::Junction::new_load`]).
    load: std::sync::Mutex<Vec<f64>>,
    /// The states of the last solve: a junction takes its slipping pairs'
    /// pressures through a least-norm share's tangent only in a solve
    /// that holds them (see [`junction::Junction::tie_held`]).
    states: std::sync::Mutex<Vec<ContactState>>,
    /// Threads for the work of a solve outside the solver: the junctions'
    /// ties and forces, the checks of what holds the parts.
    threads: usize,
    /// The water in the joints: a right-hand side that depends on the states.
    water: Option<Water>,
    /// Seconds of the solves' work outside the solver ([`Split::checks`],
    /// [`Split::relations`], [`Split::forces`]).
    around: std::sync::Mutex<Split>,
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
    /// [`Answer::accuracy`]: what the forces are resolved to.
    pub accuracy: f64,
    /// Solved to the iterative interface's loose tolerance (its state set
    /// differed from the last solve's): good for judging the states, not
    /// as the answer.
    pub loose: bool,
    /// Solved as a Newton step on the friction ([`Accuracy::Step`]): its
    /// forces judge the states and the friction, but it is not the answer.
    pub inexact: bool,
    /// A junction pair with axes its loop's ties lock (see
    /// [`junction::Junction::forces`]): its force as if those were tied,
    /// which tells whether it would stick (the robust rule then judges a
    /// slipping one by its own force, `forces`: what is reported).
    pub as_tied: Vec<Option<[f64; 3]>>,
    /// The size of the water's force on each pair (empty when dry): what
    /// a force it balances is resolved to.
    pub water: Vec<f64>,
    /// The junctions whose locked slipping pairs' pressures reached no
    /// fixed point (see [`junction::Junction::locked_off`]): their pairs,
    /// and how far the pressures written are from those their forces
    /// carry (force units).
    pub locked_off: Vec<(Vec<usize>, f64)>,
}

/// Why an interface solve failed.
#[derive(Clone, Debug, PartialEq)]
pub enum SolveFailure {
    /// These parts are held by nothing.
    NotHeld(Free),
    /// These parts slide (or rotate) freely on slipping pairs, in these
    /// motions: nothing holds them tangentially (empty when the cause is
    /// not found).
    Sliding(Free),
}

impl<'a> InterfaceProblem<'a> {
    /// The interface of the condensed `parts` (every part of the model, in
    /// order), solved the `kind`'s way; `remote` applies the S of parts
    /// condensed for the iterative interface on other MPI ranks, `threads`
    /// this rank's ones; `springs` where its solves put springs on every
    /// pair ([`Springs`]).
    pub fn new(
        model: &Model,
        parts: &[OperatorRef],
        remote: Option<&'a dyn Remote>,
        (threads, springs): (usize, Springs),
        kind: InterfaceKind,
    ) -> Result<InterfaceProblem<'a>, ModelError> {
        let basis = FaceBasis::new(model);
        let layout = Layout::new(model, parts, &basis);
        let rigid: Vec<PartModes> = parts.iter().map(|p| PartModes::new(model, &p.part.nodes(model))).collect();
        let positions = model.pairs.iter().map(|p| model.coords[p.k]).collect();
        let spreads = model.normal_spreads();
        let not_held = |_| crate::model::quality::why_not_held(model);
        let solver = kind.build(model, &layout, parts, &rigid, remote, (threads, springs)).map_err(not_held)?;
        Ok(InterfaceProblem {
            layout,
            basis,
            solver,
            rigid,
            positions,
            spreads,
            load: Default::default(),
            states: Default::default(),
            threads,
            water: None,
            around: Default::default(),
        })
    }

    /// Each pair's frame, rows n, t, b (global components).
    pub fn frames(&self) -> &[Frame] {
        &self.layout.frames
    }

    /// The basis the interface's forces are in (nodal, or the face basis of quadratic faces).
    pub fn basis(&self) -> &FaceBasis {
        &self.basis
    }

    /// Applications of the parts' S by every solve so far; empty when S
    /// was formed.
    pub fn applications(&self) -> Vec<usize> {
        self.solver.counts()
    }

    /// Where the solves' time went, when the solver times its stages (the
    /// sparse interface).
    pub fn split(&self) -> Option<Split> {
        let around = self.around.lock().map(|a| a.clone()).unwrap_or_default();
        self.solver.split().map(|s| Split {
            checks: around.checks,
            relations: around.relations,
            forces: around.forces,
            ..s
        })
    }

    /// Where the next solve would start ([`WarmStart`]).
    pub fn warm_start(&self) -> WarmStart {
        self.solver.warm_start()
    }

    /// Starts the next solve where `start` (taken from this problem) says.
    pub fn start_from(&self, start: &WarmStart) {
        self.solver.start_from(start);
    }

    /// Adds seconds of work outside the solver to [`InterfaceProblem::split`].
    fn add_around(&self, add: impl FnOnce(&mut Split)) {
        if let Ok(mut around) = self.around.lock() {
            add(&mut around);
        }
    }

    /// The area pair `p` controls (in the interface basis), > 0.
    pub fn area(&self, p: usize) -> f64 {
        self.basis.areas[p]
    }

    /// Displacement components per node: 2 in plane and axisymmetric
    /// analyses, 3 in solids.
    pub fn nd(&self) -> usize {
        self.layout.nd
    }

    /// The rigid motions of every part, with its supports.
    pub fn part_modes(&self) -> &[PartModes] {
        &self.rigid
    }

    /// Where each pair is (its node on side k).
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// The rows of the check for parts that slide freely under the
    /// relations `rel` (a slipping pair holding along its normal and its
    /// friction springs): what [`InterfaceProblem::solve`] refuses a set by.
    pub fn sliding_ties(&self, rel: &[Relation]) -> Vec<Tie> {
        self.holds().all_ties(rel, SlipHolds::Spring, &self.slip_stiffness(rel))
    }

    /// The parts of pair `p`'s two sides (k, l).
    pub fn parts_of(&self, p: usize) -> [usize; 2] {
        let [(pk, _), (pl, _)] = self.layout.at[p];
        [pk, pl]
    }

    /// Number of pairs.
    pub fn n_pairs(&self) -> usize {
        self.layout.axes.len()
    }

    /// Whether both sides of pair `p` are held by supports along all its
    /// axes: its relative displacement is prescribed, the supports carry
    /// its forces, and it can neither open nor slip.
    pub fn held(&self, p: usize) -> bool {
        let nd = self.layout.nd;
        match self.layout.in_junction[p] {
            Some((j, i)) => self.layout.junctions[j].rows[i][..nd].iter().all(|row| row.iter().all(|&x| x == 0.0)),
            None => self.layout.axes[p][..nd].iter().all(|a| matches!(a, Axis::Held { .. })),
        }
    }

    /// A stiffness of pair `p`'s relative displacement (the mean diagonal
    /// of W over its axes): the scale that turns a slip into a force. A
    /// junction pair's axis is a row of its junction's r: the diagonal's
    /// quadratic form on it. The sparse interface forms W's diagonal only
    /// where it is asked for (a substitution through its means' factor per
    /// relative displacement): ask only where the value is read, and
    /// [`InterfaceProblem::prepare_stiffness`] of the pairs a solve newly
    /// needs first, so that they are formed together.
    pub fn stiffness(&self, p: usize) -> f64 {
        let d: Vec<f64> = match self.layout.in_junction[p] {
            Some(_) => (self.junction_rows(p).iter())
                .map(|row| row.iter().map(|&(x, r)| x * x * self.solver.diagonal(r)).sum::<f64>())
                .filter(|&v| v > 0.0)
                .collect(),
            None => self.layout.axes[p].iter().filter_map(|a| a.r()).map(|r| self.solver.diagonal(r)).collect(),
        };
        if d.is_empty() {
            1.0
        } else {
            d.iter().sum::<f64>() / d.len() as f64
        }
    }

    /// Forms the [`InterfaceProblem::stiffness`] of every pair of `pairs`
    /// that lacks it, together (one pass through the sparse interface's
    /// means' factor for all their relative displacements).
    pub fn prepare_stiffness(&self, pairs: impl Iterator<Item = usize>) {
        let mut rs = Vec::new();
        for p in pairs {
            match self.layout.in_junction[p] {
                Some(_) => rs.extend(self.junction_rows(p).iter().flatten().map(|&(_, r)| r)),
                None => rs.extend(self.layout.axes[p].iter().filter_map(|a| a.r())),
            }
        }
        self.solver.prepare_diagonal(&rs);
    }

    /// A junction pair's axes as rows of its junction's r: (coefficient,
    /// relative displacement) where the coefficient is not zero.
    fn junction_rows(&self, p: usize) -> Vec<Vec<(f64, usize)>> {
        let Some((j, i)) = self.layout.in_junction[p] else { return Vec::new() };
        let jn = &self.layout.junctions[j];
        (0..self.layout.nd)
            .map(|a| jn.rows[i][a].iter().zip(&jn.r).filter(|(&x, _)| x != 0.0).map(|(&x, &r)| (x, r)).collect())
            .collect()
    }

    /// The line each pair can slip along under `states`, in its local
    /// axes, where a junction's ties leave its shear one free direction
    /// (see [`junction::Junction::slip_lines`]); None elsewhere.
    pub fn slip_lines(&self, states: &[ContactState]) -> Vec<Option<[f64; 3]>> {
        let mut lines = vec![None; states.len()];
        for jn in &self.layout.junctions {
            for (&p, line) in jn.pairs.iter().zip(jn.slip_lines(states)) {
                lines[p] = line;
            }
        }
        lines
    }

    /// The crossings of two joints: the junctions of four pairs, two on
    /// each joint's plane ([`junction::Junction::twin`]).
    pub fn crossings(&self) -> impl Iterator<Item = &junction::Junction> {
        self.layout.junctions.iter().filter(|jn| jn.twin(0).is_some())
    }

    /// The free directions of the relative displacements under `rel`.
    fn freedom(&self, rel: &[Relation], ramp: f64, held: bool) -> Freedom {
        let (nd, layout) = (self.layout.nd, &self.layout);
        let mut r0 = vec![0.0; layout.nr];
        let mut cols: Vec<Vec<(usize, f64)>> = Vec::new();
        let mut pos = vec![crate::fem::sparse::NONE; layout.nr];
        for (p, rl) in rel.iter().enumerate() {
            if layout.in_junction[p].is_some() {
                continue;
            }
            for a in 0..nd {
                if let Some(ri) = layout.axes[p][a].r() {
                    if rl.free_axis(a) {
                        pos[ri] = cols.len();
                        cols.push(vec![(ri, 1.0)]);
                    } else {
                        r0[ri] = rl.target[a];
                    }
                }
            }
        }
        let areas = &self.basis.areas;
        let blocks = in_threads(&layout.junctions, self.threads, |jn| {
            let tied = jn.tie_held(rel, ramp, held, |p| areas[p]);
            // the slipping pairs' springs and forces on the free directions
            let kz = tied.z.transpose() * &tied.k * &tied.z;
            let at_r0 = &tied.f + &tied.k * &tied.r0;
            let mut fz = tied.z.transpose() * &at_r0;
            let lift = tied.pressure.as_ref().map(|pr| {
                // L = Z^T R M A; its constant part L (f + k r0)
                let on_w = tied.z.transpose() * &pr.r * &pr.ma;
                fz += &on_w * &at_r0 + tied.z.transpose() * (&pr.r * &pr.base);
                Lift { on_y: &on_w * &tied.k * &tied.z, on_w }
            });
            (tied, kz, fz, lift)
        });
        let mut junctions = Vec::with_capacity(layout.junctions.len());
        for (jn, (tied, kz, fz, lift)) in layout.junctions.iter().zip(blocks) {
            for (x, &ri) in jn.r.iter().enumerate() {
                r0[ri] = tied.r0[x];
            }
            let first = cols.len();
            for c in 0..tied.z.ncols() {
                cols.push(jn.r.iter().enumerate().map(|(x, &ri)| (ri, tied.z[(x, c)])).collect());
            }
            junctions.push(JunctionBlock { cols: first..cols.len(), kz, fz, r: jn.r.clone(), lift, tied });
        }
        // the lone slipping pairs' rows, and the closed deforming joints'
        let mut slips = Vec::new();
        for (p, rl) in rel.iter().enumerate() {
            if layout.in_junction[p].is_some() {
                continue;
            }
            if rl.elastic {
                slips.extend(spring_rows(&layout.axes[p], rl, nd, ramp));
                continue;
            }
            if rl.state != ContactState::Slip {
                continue;
            }
            let ax = &layout.axes[p];
            for a in 1..nd {
                let Some(ra) = ax[a].r() else { continue };
                let springs =
                    (1..nd).filter_map(|c| ax[c].r().map(|rc| (rc, rl.spring[a][c]))).filter(|s| s.1 != 0.0).collect();
                slips.push(SlipRow {
                    row: ra,
                    normal: ax[0].r(),
                    coupling: rl.coupling[a],
                    springs,
                    force: rl.force[a],
                });
            }
        }
        let symmetric = !rel.iter().any(|rl| rl.elastic && rl.state == ContactState::Slip);
        let deforming = !rel.is_empty() && rel.iter().all(|rl| rl.elastic);
        Freedom { r0, cols, pos, junctions, slips, pushed: Vec::new(), symmetric, deforming }
    }

    /// Solves the interface system for the relations `rel` of every pair
    /// under the load factors `lambda` (case 0 also scales prescribed values),
    /// the forces to `accuracy`.
    pub fn solve(
        &self,
        rel: &[Relation],
        lambda: &[f64],
        accuracy: Accuracy,
    ) -> Result<InterfaceSolution, SolveFailure> {
        let states: Vec<ContactState> = rel.iter().map(|r| r.state).collect();
        // A part nothing holds makes the system singular only up to
        // round-off: decide it from the relations and the supports first
        // (as `diagnose` would, without looking for sliding parts).
        let t = std::time::Instant::now();
        let (not_held, sliding) = self.holding(rel);
        self.add_around(|a| a.checks += t.elapsed().as_secs_f64());
        if !not_held.is_empty() {
            return Err(SolveFailure::NotHeld(not_held));
        }
        if !sliding.is_empty() {
            return Err(SolveFailure::Sliding(sliding));
        }
        if let Ok(mut load) = self.load.lock() {
            if load.as_slice() != lambda {
                self.layout.junctions.iter().for_each(junction::Junction::new_load);
                *load = lambda.to_vec();
            }
        }
        let t = std::time::Instant::now();
        let held = match self.states.lock() {
            Ok(mut last) => {
                let held = *last == states;
                last.clone_from(&states);
                held
            }
            Err(_) => false,
        };
        let mut freedom = self.freedom(rel, lambda[0], held);
        self.add_around(|a| a.relations += t.elapsed().as_secs_f64());
        let mut water_forces = Vec::new();
        if let Some(water) = &self.water {
            let push = water.forces(&states, lambda);
            water_forces = push.iter().map(|f| crate::fem::vec3::norm(*f)).collect();
            freedom.pushed = self.pushed(&push);
        }
        let answer = self.solver.solve(&freedom, &states, lambda, accuracy).ok_or_else(|| self.diagnose(rel))?;
        let t = std::time::Instant::now();
        let (forces, rels, as_tied) = self.forces(rel, &answer, &freedom, lambda[0]);
        let pairs = (0..rel.len())
            .map(|p| {
                let area = self.basis.areas[p];
                let (f, r) = (forces[p], rels[p]);
                PairResult {
                    sigma_n: f[0] / area,
                    tau_t: f[1] / area,
                    tau_b: f[2] / area,
                    gap: r[0],
                    slip: r[1].hypot(r[2]),
                }
            })
            .collect();
        let d_c = self.displacements(&answer, lambda[0]);
        self.add_around(|a| a.forces += t.elapsed().as_secs_f64());
        Ok(InterfaceSolution {
            pairs,
            forces,
            rel: rels,
            d_c,
            residual: answer.residual,
            accuracy: answer.accuracy,
            loose: answer.loose,
            inexact: answer.inexact,
            as_tied,
            water: water_forces,
            locked_off: (self.layout.junctions.iter())
                .filter(|jn| jn.locked_off() > 0.0)
                .map(|jn| (jn.pairs.clone(), jn.locked_off()))
                .collect(),
        })
    }

    /// [`Layout::pushed`] of forces on body I per pair in the nodal basis
    /// (global axes), taken into the interface basis first.
    fn pushed(&self, push: &[[f64; 3]]) -> Vec<f64> {
        let push = if self.basis.is_nodal() {
            push.to_vec()
        } else {
            let comps: Vec<Vec<f64>> =
                (0..3).map(|i| self.basis.transpose_apply(&push.iter().map(|f| f[i]).collect::<Vec<_>>())).collect();
            (0..push.len()).map(|p| [comps[0][p], comps[1][p], comps[2][p]]).collect()
        };
        self.layout.pushed(&push)
    }

    /// The water in the joints, when they have some.
    pub fn water(&self) -> Option<&Water> {
        self.water.as_ref()
    }

    /// The interface with the water of its joints, which every solve adds
    /// to its right-hand side at the states it solves for.
    pub fn with_water(mut self, water: Option<Water>) -> Self {
        self.water = water;
        self
    }

    /// The contact forces, `-(W r - c)`, and the relative displacements of
    /// every pair; a free axis carries what its relation prescribes (an
    /// open pair exactly zero, not round-off). A junction's pairs share
    /// what its ties carry, the least-norm way within their limits, and
    /// the forces its locked pairs would carry tied (`as_tied`).
    #[allow(clippy::type_complexity)]
    fn forces(
        &self,
        rel: &[Relation],
        answer: &Answer,
        fr: &Freedom,
        ramp: f64,
    ) -> (Vec<[f64; 3]>, Vec<[f64; 3]>, Vec<Option<[f64; 3]>>) {
        let nd = self.layout.nd;
        let (r, wr_c) = (&answer.r, &answer.residual_r);
        let mut forces = vec![[0.0; 3]; rel.len()];
        let mut rels = vec![[0.0; 3]; rel.len()];
        let mut as_tied = vec![None; rel.len()];
        for (p, ax) in self.layout.axes.iter().enumerate() {
            if self.layout.in_junction[p].is_some() {
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
            if rel[p].elastic {
                forces[p] = rel[p].spring_force(rels[p]);
            } else if rel[p].state == ContactState::Slip {
                let pn = -forces[p][0];
                let rl = &rel[p];
                for a in 1..nd {
                    if ax[a].r().is_some() {
                        forces[p][a] = rl.force[a]
                            + rl.coupling[a] * pn
                            + (1..nd).map(|c| rl.spring[a][c] * rels[p][c]).sum::<f64>();
                    }
                }
            }
        }
        let with_blocks: Vec<_> = self.layout.junctions.iter().zip(&fr.junctions).collect();
        let shares = in_threads(&with_blocks, self.threads, |(jn, block)| {
            let rj = nalgebra::DVector::from_iterator(jn.r.len(), jn.r.iter().map(|&i| r[i]));
            let g = nalgebra::DVector::from_iterator(jn.r.len(), jn.r.iter().map(|&i| -wr_c[i]));
            jn.forces(&block.tied, rel, &rj, &g, ramp)
        });
        for ((jn, _), share) in with_blocks.iter().zip(shares) {
            for (&p, (f, x, t)) in jn.pairs.iter().zip(share) {
                forces[p] = f;
                rels[p] = x;
                as_tied[p] = t;
            }
        }
        (forces, rels, as_tied)
    }

    /// The interface displacements of every part, global axes, nodal basis.
    fn displacements(&self, answer: &Answer, ramp: f64) -> Vec<Vec<f64>> {
        let nd = self.layout.nd;
        (self.layout.parts.iter())
            .map(|map| {
                coords::part_displacements(&map.terms, &map.frames, &map.edges, nd, ramp, |v| match v {
                    Var::M(i) => answer.m[i],
                    Var::R(i) => answer.r[i],
                })
            })
            .collect()
    }

    /// Parts that a rigid motion moves which the supports and the pairs tied
    /// by the relations `rel` do not stop, a slipping pair holding as
    /// `slip` says.
    fn free(&self, rel: &[Relation], slip: SlipHolds) -> Free {
        let stiffness = match slip {
            SlipHolds::Spring => self.slip_stiffness(rel),
            _ => Vec::new(),
        };
        self.holds().free(rel, slip, &stiffness)
    }

    /// `free` with everything a slipping pair holds, and with its springs
    /// (the parts nothing holds, then those the slipping pairs let slide),
    /// side by side.
    fn holding(&self, rel: &[Relation]) -> (Free, Free) {
        let (holds, stiffness) = (self.holds(), self.slip_stiffness(rel));
        if self.threads < 2 {
            return (holds.free(rel, SlipHolds::Everything, &[]), holds.free(rel, SlipHolds::Spring, &stiffness));
        }
        std::thread::scope(|scope| {
            let sliding = scope.spawn(|| holds.free(rel, SlipHolds::Spring, &stiffness));
            let not_held = holds.free(rel, SlipHolds::Everything, &[]);
            (not_held, sliding.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
        })
    }

    /// [`InterfaceProblem::stiffness`] of each slipping pair (0 elsewhere).
    fn slip_stiffness(&self, rel: &[Relation]) -> Vec<f64> {
        rel.iter()
            .enumerate()
            .map(|(p, rl)| match rl.state {
                // a joint that deforms: its own springs (W's diagonal would
                // cost the sparse interface its means' factor)
                ContactState::Slip if rl.elastic => rl.spring.iter().flatten().fold(0.0, |a: f64, b| a.max(b.abs())),
                ContactState::Slip => self.stiffness(p),
                _ => 0.0,
            })
            .collect()
    }

    fn holds(&self) -> Holds<'_> {
        Holds { layout: &self.layout, rigid: &self.rigid, positions: &self.positions, spreads: &self.spreads }
    }

    /// Why the interface system is singular: parts held by nothing once
    /// their open pairs let go, or else a part sliding on slipping pairs.
    fn diagnose(&self, rel: &[Relation]) -> SolveFailure {
        let free = self.free(rel, SlipHolds::Everything);
        if free.is_empty() {
            // the solve found what the springs' directions did not: name
            // the parts that nothing but friction holds along their slip
            SolveFailure::Sliding(self.free(rel, SlipHolds::Normal))
        } else {
            SolveFailure::NotHeld(free)
        }
    }
}

/// What [`InterfaceProblem::free`] reads: the layout, the parts' rigid
/// motions, the pairs' positions and normals' spreads (apart from the
/// solver, which need not be shared between threads).
struct Holds<'p> {
    layout: &'p Layout,
    rigid: &'p [PartModes],
    positions: &'p [[f64; 3]],
    spreads: &'p [f64],
}

impl Holds<'_> {
    /// The parts a rigid motion moves which the supports and the pairs
    /// tied as `slip` says leave free (`stiffness`: each slipping pair's,
    /// read only for [`SlipHolds::Spring`]).
    fn free(&self, rel: &[Relation], slip: SlipHolds, stiffness: &[f64]) -> Free {
        free_parts(self.rigid, self.all_ties(rel, slip, stiffness).into_iter())
    }

    /// The ties of every pair as `slip` says, and those of the joins of
    /// parts of one body: the rows of [`Holds::free`]'s check.
    fn all_ties(&self, rel: &[Relation], slip: SlipHolds, stiffness: &[f64]) -> Vec<Tie> {
        let (nd, layout) = (self.layout.nd, self.layout);
        let ties = rel.iter().enumerate().flat_map(|(p, rl)| {
            let frame = &layout.frames[p];
            let dirs: Vec<[f64; 3]> = match rl.state {
                ContactState::Stick => frame[..nd].to_vec(),
                ContactState::Slip => match slip {
                    SlipHolds::Everything => frame[..nd].to_vec(),
                    SlipHolds::Spring => std::iter::once(frame[0])
                        .chain(spring_range(&rl.spring, frame, nd, SPRING_HOLDS * stiffness[p]))
                        .collect(),
                    SlipHolds::Normal => vec![frame[0]],
                },
                ContactState::Open => Vec::new(),
            };
            let [(pk, _), (pl, _)] = layout.at[p];
            self.ties([pk, pl], p, &dirs)
        });
        // parts of one body cut into substructures are always tied at their joins
        let joined = layout.join_parts.iter().flat_map(|(ps, x)| {
            ps[1..].iter().flat_map(move |&q| (0..nd).map(move |a| Tie::exact([ps[0], q], *x, IDENTITY[a])))
        });
        ties.chain(joined).collect()
    }

    /// The ties of pair `p` (between `parts`) along `dirs` (its normal
    /// first, when it holds): [`pair_ties`], with its facets' spread.
    fn ties(&self, parts: [usize; 2], p: usize, dirs: &[[f64; 3]]) -> Vec<Tie> {
        pair_ties(parts, self.positions[p], &self.layout.frames[p], self.layout.nd, dirs, self.spreads[p])
    }
}

/// What a slipping pair holds in the check for parts that move freely.
#[derive(Clone, Copy)]
enum SlipHolds {
    /// Everything, as if stuck: then only open pairs release anything.
    Everything,
    /// Its normal, and across its slip where its relation has a friction
    /// spring there (the robust rule's linearised Coulomb law,
    /// [`Relation::spring`]): a wedge whose every pair slips down its
    /// groove is held along the groove by friction.
    Spring,
    /// Its normal only (a fixed friction force holds nothing).
    Normal,
}

/// The rows of a closed joint that deforms (`rl` elastic; none where it
/// is open): on each of its axes with an r, `(W r - c)_a + force_a +
/// sum_c spring_ac r_c = 0`, an axis both sides' supports hold (at
/// `ramp`) a known r in the force.
fn spring_rows(axes: &[Axis], rl: &Relation, nd: usize, ramp: f64) -> Vec<SlipRow> {
    if rl.state == ContactState::Open {
        return Vec::new();
    }
    let held = |c: usize| match axes[c] {
        Axis::Held { vk, vl } => (vl - vk) * ramp,
        _ => 0.0,
    };
    (0..nd)
        .filter_map(|a| {
            let row = axes[a].r()?;
            let springs = (0..nd).filter_map(|c| axes[c].r().map(|rc| (rc, rl.spring[a][c]))).filter(|s| s.1 != 0.0);
            let force = rl.force[a] + (0..nd).map(|c| rl.spring[a][c] * held(c)).sum::<f64>();
            Some(SlipRow { row, normal: None, coupling: 0.0, springs: springs.collect(), force })
        })
        .collect()
}

/// The global directions in which a slipping pair's friction spring (local
/// t, b rows and columns of `spring`) holds it: its rows as unit vectors,
/// those whose stiffness is below `floor` left out (none without a spring).
fn spring_range(spring: &[[f64; 3]; 3], frame: &Frame, nd: usize, floor: f64) -> Vec<[f64; 3]> {
    (1..nd)
        .filter_map(|a| {
            // the frame's rows are orthonormal: |dir| is the row's stiffness
            let dir: [f64; 3] = std::array::from_fn(|i| (1..nd).map(|c| spring[a][c] * frame[c][i]).sum::<f64>());
            let len = crate::fem::vec3::norm(dir);
            (len > 0.0 && len >= floor).then(|| dir.map(|x| x / len))
        })
        .collect()
}
