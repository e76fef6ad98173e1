//! Where the interface unknowns are: which pair or join each interface node
//! of each part is, the pairs' frames, the prescribed local values, and the
//! numbering of the means and relative displacements ([`super::coords`]).
//! Built once by [`Layout::new`], in named steps; every interface solver
//! reads its parts through it ([`Layout::terms_of`], [`Layout::frames_of`]).

use std::collections::HashMap;

use super::coords::{self, Axis, Terms, Var};
use super::IDENTITY;
use crate::contact::basis::{self, FaceBasis};
use crate::contact::frame::{aligned_axis, frame, Frame};
use crate::fem::sparse::NONE;
use crate::model::{Model, ModelError};
use crate::substructure::OperatorRef;

/// Where a part's interface nodes sit among the pairs.
pub(super) struct PartMap {
    /// What each interface node of the part is, in the part's order.
    pub nodes: Vec<Slot>,
    /// Transformed edges, as positions in `nodes`.
    pub edges: Vec<[usize; 3]>,
}

/// An interface node of a part: one side of a contact pair, or a node the
/// part shares with other parts of the same body (a bonded join, where a
/// body is cut into substructures): always tied, its displacement (global
/// axes) is a mean of the interface.
#[derive(Clone, Copy, Debug)]
pub(super) enum Slot {
    Pair { pair: usize, side: usize },
    Join(usize),
}

/// The interface's unknowns and where every part's interface nodes are among them.
pub(super) struct Layout {
    pub nd: usize,
    pub frames: Vec<Frame>,
    /// The unknowns of each pair's local axes.
    pub axes: Vec<[Axis; 3]>,
    /// The unknowns of each join's components.
    pub joins: Vec<[Axis; 3]>,
    /// Parts that share each join, and where the join is.
    pub join_parts: Vec<(Vec<usize>, [f64; 3])>,
    pub parts: Vec<PartMap>,
    /// (part, position) of each pair's k and l.
    pub at: Vec<[(usize, usize); 2]>,
    /// Means of the pairs (the first `nm_pairs` of `nm`), all means, and
    /// relative displacements.
    pub nm_pairs: usize,
    pub nm: usize,
    pub nr: usize,
}

/// Which part holds each interface node first, which parts share it, and
/// what it is.
struct Slots {
    where_is: Vec<(usize, usize)>,
    holders: Vec<Vec<usize>>,
    role: Vec<Option<Slot>>,
    join_nodes: Vec<usize>,
}

impl Layout {
    /// The layout of the condensed `parts` (every part of the model, in
    /// order) in the face basis `basis`.
    pub fn new(model: &Model, parts: &[OperatorRef], basis: &FaceBasis) -> Result<Layout, ModelError> {
        let nd = model.nd;
        let slots = slots(model, parts);
        let (frames, mut fixed) = frames_and_fixed(model)?;
        fixed_in_face_basis(basis, &mut fixed, nd);
        let (axes, nm_pairs, nr) = coords::number(&fixed, nd);
        let (joins, nm) = join_axes(model, &slots.join_nodes, nm_pairs);
        let join_parts = slots.join_nodes.iter().map(|&n| (slots.holders[n].clone(), model.coords[n])).collect();
        let at = model.pairs.iter().map(|p| [slots.where_is[p.k], slots.where_is[p.l]]).collect();
        let parts = parts.iter().map(|p| part_map(p, &slots.role, basis)).collect();
        Ok(Layout { nd, frames, axes, joins, join_parts, parts, at, nm_pairs, nm, nr })
    }

    /// The unknowns and side of an interface node, and its frame.
    pub fn slot(&self, slot: Slot) -> (&[Axis; 3], usize, Frame) {
        match slot {
            Slot::Pair { pair, side } => (&self.axes[pair], side, self.frames[pair]),
            Slot::Join(j) => (&self.joins[j], 0, IDENTITY),
        }
    }

    /// The frame of each interface node of a part.
    pub fn frames_of(&self, map: &PartMap) -> Vec<Frame> {
        map.nodes.iter().map(|&slot| self.slot(slot).2).collect()
    }

    /// The unknowns of each of a part's `nc` interface DOFs.
    pub fn terms_of(&self, nc: usize, map: &PartMap) -> Vec<Terms> {
        let nd = self.nd;
        (0..nc)
            .map(|u| {
                let (axes, side, _) = self.slot(map.nodes[u / nd]);
                axes[u % nd].terms(side)
            })
            .collect()
    }

    /// The unknowns of every pair and of every join node, group by group.
    pub fn groups(&self) -> Vec<Vec<Var>> {
        (self.axes.iter().chain(&self.joins))
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
            .collect()
    }
}

/// The first part holding each node; the parts sharing each node; each
/// interface node's role: a pair's side, or a join when several parts
/// share a node that is in no pair.
fn slots(model: &Model, parts: &[OperatorRef]) -> Slots {
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
    Slots { where_is, holders, role, join_nodes }
}

/// Each pair's frame, and the prescribed local values of each side (nodal
/// basis); a support across the frame is refused.
#[allow(clippy::type_complexity)]
fn frames_and_fixed(model: &Model) -> Result<(Vec<Frame>, Vec<[[Option<f64>; 3]; 2]>), ModelError> {
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
    Ok((frames, fixed))
}

/// The prescribed values in the face basis (per side, local axis).
fn fixed_in_face_basis(basis: &FaceBasis, fixed: &mut [[[Option<f64>; 3]; 2]], nd: usize) {
    if basis.is_nodal() {
        return;
    }
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

/// The joins' unknowns: a mean per component (numbered from `nm`), or the
/// prescribed value; and the number of means with them.
fn join_axes(model: &Model, join_nodes: &[usize], mut nm: usize) -> (Vec<[Axis; 3]>, usize) {
    let nd = model.nd;
    let joins = join_nodes
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
    (joins, nm)
}

/// What each interface node of a part is, and its transformed face edges.
fn part_map(p: &OperatorRef, role: &[Option<Slot>], basis: &FaceBasis) -> PartMap {
    let nodes: Vec<Slot> = p.part.interface.iter().map(|&n| role[n].expect("an interface node is in a pair or shared by parts")).collect();
    let mut pos: HashMap<(usize, usize), usize> = HashMap::new();
    for (q, slot) in nodes.iter().enumerate() {
        if let Slot::Pair { pair, side } = *slot {
            pos.insert((pair, side), q);
        }
    }
    let edges = basis::part_edges(basis, |pair| [pos.get(&(pair, 0)).copied(), pos.get(&(pair, 1)).copied()]);
    PartMap { nodes, edges }
}
