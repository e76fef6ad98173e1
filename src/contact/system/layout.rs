//! Where the interface unknowns are, and how every interface node of every
//! part is written in them: its frame and the terms of each of its local
//! components. Built once by [`Layout::new`], in named steps; every
//! interface solver reads its parts through it ([`Layout::terms_of`],
//! [`Layout::frames_of`]).
//!
//! - a lone pair, its supports along its frame: the mean / relative
//!   coordinates of [`super::coords`], in the pair's local axes;
//! - a junction (copies in several pairs, or a pair whose supports do not
//!   lie along its frame): [`super::junction`], in global axes;
//! - a join (a node that parts of one body share, in no pair): one mean
//!   per free component, global axes.
//!
//! Means are numbered pair by pair (a junction's with its first pair), then
//! the joins'; relative displacements pair by pair.

use std::collections::HashMap;

use super::coords::{number_pair, Axis, Terms, Var};
use super::junction::{clusters, Junction};
use crate::contact::basis::{self, FaceBasis};
use crate::contact::frame::IDENTITY;
use crate::contact::frame::{aligned_axis, frame, Frame};
use crate::fem::sparse::NONE;
use crate::model::Model;
use crate::substructure::OperatorRef;

/// How a part's interface nodes are written in the unknowns.
pub(super) struct PartMap {
    /// The frame of each interface node of the part, in the part's order.
    pub frames: Vec<Frame>,
    /// The unknowns of each interface DOF (local axes, face basis).
    pub terms: Vec<Terms>,
    /// Each interface node's share of its means (the coarse space's
    /// weight): 1/2 on a lone pair, 1/q on a junction of q copies, 1/p on a
    /// join of p parts.
    pub shares: Vec<f64>,
    /// Transformed edges, as positions in the part's interface nodes.
    pub edges: Vec<[usize; 3]>,
}

/// How one interface node is written.
#[derive(Clone, Debug)]
struct NodeVars {
    frame: Frame,
    terms: [Terms; 3],
    share: f64,
}

/// The interface's unknowns and where every part's interface nodes are among them.
pub(super) struct Layout {
    pub nd: usize,
    /// Each pair's frame (rows n, t, b).
    pub frames: Vec<Frame>,
    /// Each lone pair's axes (a junction's pairs: `Absent`).
    pub axes: Vec<[Axis; 3]>,
    pub junctions: Vec<Junction>,
    /// (junction, its pair index) of each pair in one.
    pub in_junction: Vec<Option<(usize, usize)>>,
    /// The unknowns of each join's components.
    pub joins: Vec<[Axis; 3]>,
    /// Parts that share each join, and where the join is.
    pub join_parts: Vec<(Vec<usize>, [f64; 3])>,
    pub parts: Vec<PartMap>,
    /// (part, position) of each pair's k and l.
    pub at: Vec<[(usize, usize); 2]>,
    /// Means of the pairs and junctions (the first `nm_pairs` of `nm`), all
    /// means, and relative displacements.
    pub nm_pairs: usize,
    pub nm: usize,
    pub nr: usize,
}

/// Which part holds each interface node first, and which parts share it.
struct Holders {
    where_is: Vec<(usize, usize)>,
    holders: Vec<Vec<usize>>,
}

impl Layout {
    /// The layout of the condensed `parts` (every part of the model, in
    /// order) in the face basis `basis`.
    pub fn new(model: &Model, parts: &[OperatorRef], basis: &FaceBasis) -> Layout {
        let nd = model.nd;
        let Holders { where_is, holders } = holders(model, parts);
        // prescribed values in the face basis
        let held = basis::prescribed(basis, &model.prescribed, nd);
        let (frames, fixed) = frames_and_fixed(model, &held);
        let ends: Vec<(usize, usize)> = model.pairs.iter().map(|p| (p.k, p.l)).collect();
        let groups = clusters(&ends, model.n_nodes(), |p| fixed[p].is_none());
        let mut in_junction = vec![None; ends.len()];
        for (j, g) in groups.iter().enumerate() {
            for (i, &p) in g.iter().enumerate() {
                in_junction[p] = Some((j, i));
            }
        }
        // 1. pairs and junctions, in pair order
        let (mut nm, mut nr) = (0, 0);
        let mut axes = vec![[Axis::Absent; 3]; ends.len()];
        let mut junctions: Vec<Junction> = Vec::with_capacity(groups.len());
        for p in 0..ends.len() {
            match in_junction[p] {
                Some((j, 0)) => {
                    debug_assert_eq!(junctions.len(), j);
                    junctions.push(Junction::new(
                        groups[j].clone(),
                        |q| (ends[q].0, ends[q].1, frames[q]),
                        &held,
                        nd,
                        &mut nm,
                        &mut nr,
                    ));
                }
                Some(_) => {}
                None => axes[p] = number_pair(fixed[p].as_ref().expect("a lone pair's values"), nd, &mut nm, &mut nr),
            }
        }
        let nm_pairs = nm;
        // 2. joins: nodes shared by parts that are in no pair
        let mut paired = vec![false; model.n_nodes()];
        for &(k, l) in &ends {
            paired[k] = true;
            paired[l] = true;
        }
        let join_nodes: Vec<usize> = (0..model.n_nodes()).filter(|&n| !paired[n] && holders[n].len() > 1).collect();
        let joins = join_axes(model, &join_nodes, &mut nm);
        // 3. every interface node written in the unknowns
        let mut vars: HashMap<usize, NodeVars> = HashMap::new();
        for (p, &(k, l)) in ends.iter().enumerate() {
            if in_junction[p].is_none() {
                for (side, node) in [k, l].into_iter().enumerate() {
                    vars.insert(node, NodeVars { frame: frames[p], terms: axes[p].map(|a| a.terms(side)), share: 0.5 });
                }
            }
        }
        for j in &junctions {
            let share = 1.0 / j.copies.len() as f64;
            for (c, &node) in j.copies.iter().enumerate() {
                vars.insert(node, NodeVars { frame: IDENTITY, terms: j.terms[c].clone(), share });
            }
        }
        for (ax, &node) in joins.iter().zip(&join_nodes) {
            vars.insert(
                node,
                NodeVars { frame: IDENTITY, terms: ax.map(|a| a.terms(0)), share: 1.0 / holders[node].len() as f64 },
            );
        }
        let join_parts = join_nodes.iter().map(|&n| (holders[n].clone(), model.coords[n])).collect();
        let at = model.pairs.iter().map(|p| [where_is[p.k], where_is[p.l]]).collect();
        let parts = parts.iter().map(|p| part_map(&p.part.interface, &vars, nd, basis)).collect();
        Layout { nd, frames, axes, junctions, in_junction, joins, join_parts, parts, at, nm_pairs, nm, nr }
    }

    /// The frame of each interface node of a part.
    pub fn frames_of(&self, map: &PartMap) -> Vec<Frame> {
        map.frames.clone()
    }

    /// The unknowns of each of a part's interface DOFs.
    pub fn terms_of(&self, map: &PartMap) -> Vec<Terms> {
        map.terms.clone()
    }

    /// The right-hand side on the relative displacements of forces that
    /// push the two sides of every pair apart: `push[p]` on body I at k
    /// (global axes, interface basis), its opposite on body II at l.
    /// `b = W^T G'` on the rows of r; on the means the two sides cancel.
    pub fn pushed(&self, push: &[[f64; 3]]) -> Vec<f64> {
        let nd = self.nd;
        let mut b = vec![0.0; self.nr];
        for (p, f) in push.iter().enumerate().filter(|(_, f)| **f != [0.0; 3]) {
            for (side, sign) in [(0, 1.0), (1, -1.0)] {
                let (part, pos) = self.at[p][side];
                let map = &self.parts[part];
                let frame = &map.frames[pos];
                for a in 0..nd {
                    let local = sign * (0..3).map(|i| frame[a][i] * f[i]).sum::<f64>();
                    let t = &map.terms[pos * nd + a];
                    for &(var, c) in &t.vars[..t.n] {
                        if let Var::R(i) = var {
                            b[i] += c * local;
                        }
                    }
                }
            }
        }
        b
    }

    /// The unknowns of every lone pair, every junction and every join
    /// node, group by group (the iterative interface's preconditioner blocks).
    pub fn groups(&self) -> Vec<Vec<Var>> {
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
        (self.axes.iter().zip(&self.in_junction))
            .filter(|(_, j)| j.is_none())
            .map(|(ax, _)| vars_of(ax))
            .chain(
                self.junctions
                    .iter()
                    .map(|j| j.m.iter().map(|&m| Var::M(m)).chain(j.r.iter().map(|&r| Var::R(r))).collect()),
            )
            .chain(self.joins.iter().map(vars_of))
            .collect()
    }
}

/// The first part holding each node, and the parts sharing each node.
fn holders(model: &Model, parts: &[OperatorRef]) -> Holders {
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
    Holders { where_is, holders }
}

/// Each pair's frame, and each lone pair's prescribed local values per unit
/// ramp (`held`, in the face basis); None for a pair whose supports do not
/// lie along its frame: it is a junction of one pair, in global axes, with
/// the frame of its normal alone. That is a joint meeting a roller or a
/// symmetry plane obliquely (`frame` turns n onto or off a supported axis
/// only by a few degrees): its gap, its slip and its strength are then the
/// joint's own, and what the rigid limit leaves undecided between the
/// joint and the support is the junction's least-norm share (about the
/// joint's in-situ force, as every junction's: [`super::junction`]) within the
/// joint's Coulomb cone.
#[allow(clippy::type_complexity)]
fn frames_and_fixed(model: &Model, held: &[Option<f64>]) -> (Vec<Frame>, Vec<Option<[[Option<f64>; 3]; 2]>>) {
    let nd = model.nd;
    let mut frames = Vec::with_capacity(model.pairs.len());
    let mut fixed = Vec::with_capacity(model.pairs.len());
    for pair in &model.pairs {
        let mut sup = [false; 3];
        for node in [pair.k, pair.l] {
            for (c, s) in sup.iter_mut().enumerate().take(nd) {
                *s |= model.prescribed[node * nd + c].is_some();
            }
        }
        let f = frame(nd, pair.normal, sup);
        match local_values(&f, held, [pair.k, pair.l], nd) {
            Some(fx) => {
                frames.push(f);
                fixed.push(Some(fx));
            }
            None => {
                frames.push(frame(nd, pair.normal, [false; 3]));
                fixed.push(None);
            }
        }
    }
    (frames, fixed)
}

/// The prescribed local values (per unit ramp) of a pair's two sides in
/// frame `f`, or None when a held global direction is not along one of
/// its axes.
fn local_values(f: &Frame, held: &[Option<f64>], nodes: [usize; 2], nd: usize) -> Option<[[Option<f64>; 3]; 2]> {
    let mut fx = [[None; 3]; 2];
    for (side, node) in nodes.into_iter().enumerate() {
        for c in 0..nd {
            if let Some(v) = held[node * nd + c] {
                let (a, sign) = aligned_axis(f, nd, c)?;
                fx[side][a] = Some(sign * v);
            }
        }
    }
    // a frame that could not follow the supports (NaN) aligns nothing
    f.iter().flatten().all(|x| x.is_finite()).then_some(fx)
}

/// The joins' unknowns: a mean per component (numbered on from `nm`), or
/// the prescribed value.
fn join_axes(model: &Model, join_nodes: &[usize], nm: &mut usize) -> Vec<[Axis; 3]> {
    let nd = model.nd;
    join_nodes
        .iter()
        .map(|&n| {
            std::array::from_fn(|c| match (c < nd, model.prescribed.get(n * nd + c).copied().flatten()) {
                (false, _) => Axis::Absent,
                (true, Some(v)) => Axis::Held { vk: v, vl: v },
                (true, None) => {
                    *nm += 1;
                    Axis::Joined { m: *nm - 1 }
                }
            })
        })
        .collect()
}

/// How a part's interface nodes are written, and its transformed face edges.
fn part_map(interface: &[usize], vars: &HashMap<usize, NodeVars>, nd: usize, basis: &FaceBasis) -> PartMap {
    let of = |n: usize| vars.get(&n).expect("an interface node is in a pair or shared by parts");
    let pos: HashMap<usize, usize> = interface.iter().enumerate().map(|(q, &n)| (n, q)).collect();
    PartMap {
        frames: interface.iter().map(|&n| of(n).frame).collect(),
        terms: interface.iter().flat_map(|&n| of(n).terms[..nd].to_vec()).collect(),
        shares: interface.iter().map(|&n| of(n).share).collect(),
        edges: basis::part_edges(basis, |n| pos.get(&n).copied()),
    }
}
