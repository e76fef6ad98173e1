//! The interface's unknowns, and how every interface node is written in
//! them: its frame and the terms of each of its local components.
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

use super::coords::{number_pair, Axis, Terms};
use super::junction::{clusters, Junction};
use crate::contact::basis::{self, FaceBasis};
use crate::contact::frame::{aligned_axis, frame, Frame};
use crate::model::Model;

pub const IDENTITY: Frame = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// How one interface node is written: its frame, and per local axis the
/// unknowns of its displacement coefficient (face basis).
#[derive(Clone, Debug)]
pub struct NodeVars {
    pub frame: Frame,
    pub terms: [Terms; 3],
    /// Its share of its means (the coarse space's weight): 1/2 on a lone
    /// pair, 1/q on a junction of q copies, 1/p on a join of p parts.
    pub share: f64,
}

/// Every unknown of the interface.
pub struct Unknowns {
    /// Means: of pairs and junctions (`0..nm_pairs`), then of joins.
    pub nm: usize,
    pub nm_pairs: usize,
    pub nr: usize,
    /// Each pair's frame (rows n, t, b).
    pub frames: Vec<Frame>,
    /// Each lone pair's axes (a junction's pairs: `Absent`).
    pub axes: Vec<[Axis; 3]>,
    pub junctions: Vec<Junction>,
    /// (junction, its pair index) of each pair in one.
    pub in_junction: Vec<Option<(usize, usize)>>,
    /// The unknowns of each join's components, and its node.
    pub joins: Vec<[Axis; 3]>,
    pub join_nodes: Vec<usize>,
    vars: HashMap<usize, NodeVars>,
}

impl Unknowns {
    /// The unknowns of the model's pairs and of the joins `join_nodes`
    /// (nodes shared by parts that are in no pair; `sharing` parts each),
    /// in the face basis `basis`.
    pub fn new(model: &Model, basis: &FaceBasis, join_nodes: &[usize], sharing: &[usize]) -> Unknowns {
        let nd = model.nd;
        let np = model.pairs.len();
        // prescribed values in the face basis
        let held = basis::prescribed(basis, &model.prescribed, nd);
        // frames, and each lone pair's prescribed local values
        let mut frames = Vec::with_capacity(np);
        let mut fixed: Vec<Option<[[Option<f64>; 3]; 2]>> = Vec::with_capacity(np);
        for pair in &model.pairs {
            let mut sup = [false; 3];
            for node in [pair.k, pair.l] {
                for (c, s) in sup.iter_mut().enumerate().take(nd) {
                    *s |= model.prescribed[node * nd + c].is_some();
                }
            }
            let f = frame(nd, pair.normal, sup);
            match local_values(&f, &held, [pair.k, pair.l], nd) {
                Some(fx) => {
                    frames.push(f);
                    fixed.push(Some(fx));
                }
                // supports across the frame: a junction of one pair, in global axes
                None => {
                    frames.push(frame(nd, pair.normal, [false; 3]));
                    fixed.push(None);
                }
            }
        }
        let ends: Vec<(usize, usize)> = model.pairs.iter().map(|p| (p.k, p.l)).collect();
        let groups = clusters(&ends, model.n_nodes(), |p| fixed[p].is_none());
        let mut in_junction = vec![None; np];
        for (j, g) in groups.iter().enumerate() {
            for (i, &p) in g.iter().enumerate() {
                in_junction[p] = Some((j, i));
            }
        }
        let (mut nm, mut nr) = (0, 0);
        let mut axes = vec![[Axis::Absent; 3]; np];
        let mut junctions: Vec<Junction> = Vec::with_capacity(groups.len());
        for p in 0..np {
            match in_junction[p] {
                Some((j, 0)) => {
                    debug_assert_eq!(junctions.len(), j);
                    junctions.push(Junction::new(groups[j].clone(), |q| (ends[q].0, ends[q].1, frames[q]), &held, nd, &mut nm, &mut nr));
                }
                Some(_) => {}
                None => axes[p] = number_pair(fixed[p].as_ref().expect("a lone pair's values"), nd, &mut nm, &mut nr),
            }
        }
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
        let mut vars: HashMap<usize, NodeVars> = HashMap::new();
        for (p, pair) in model.pairs.iter().enumerate() {
            if in_junction[p].is_none() {
                for (side, node) in [pair.k, pair.l].into_iter().enumerate() {
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
        for ((ax, &node), &parts) in joins.iter().zip(join_nodes).zip(sharing) {
            vars.insert(node, NodeVars { frame: IDENTITY, terms: ax.map(|a| a.terms(0)), share: 1.0 / parts as f64 });
        }
        Unknowns { nm, nm_pairs, nr, frames, axes, junctions, in_junction, joins, join_nodes: join_nodes.to_vec(), vars }
    }

    /// How interface node `n` is written (a node of a pair, junction or join).
    pub fn of(&self, n: usize) -> &NodeVars {
        self.vars.get(&n).expect("an interface node is in a pair or shared by parts")
    }
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
