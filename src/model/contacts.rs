//! Contacts in the model: the node split along contact facets, the blocks,
//! and the pairs, which follow the facets.
//!
//! A contact group (`group = ".."`) is a set of facets, each between two
//! cells: of two bodies, or of one body that the group's facets cut into
//! blocks (a rock mass cut by a joint set). Every node of such a facet gets
//! one model node per fan of cells around it ([`super::topology`]): the
//! first fan keeps the mesh node, the others get copies. Where joints cross,
//! every block keeps its own copy: four at a point in 2D, four along a line
//! and eight at a point in 3D.
//!
//! Pairs follow the facets: a facet between cells a (side I) and b (side
//! II) pairs, at each of its nodes, a's copy k with b's copy l. One node can
//! so take part in several pairs (a copy at a crossing pairs with each
//! block it faces), and the pairs around a junction form closed loops;
//! [`crate::contact::system`] solves them. The facets of one pair are those
//! of its contact between the same two copies, split where their normals
//! turn by more than [`CREASE_ANGLE`] degrees: a node on a crease (a wedge in
//! a V-groove) gets one pair per face, each with its face's normal and area.
//! Where one copy faces several blocks across a smooth contact (a lining
//! that joints end on), its pairs take its surface's normal (normals.rs).
//!
//! Side I, written once: between two bodies, side I is the body listed
//! first in `[[bodies]]`; between two blocks of one body, it is the block on
//! the low side: the pair's normal n (outward of side I, summed over the
//! facets the two blocks share in this contact) points along +x, +y or +z,
//! whichever of the three it is closest to. A horizontal joint has the block
//! below it on side I and n = +z. The normal goes into contact.csv.
//!
//! With `groups = [a, b]` the two sides have their own nodes, which are
//! paired by position; side I is the body (block) listed first.

use std::collections::{HashMap, HashSet};

use super::build_input::Builder;
use super::errors::{Bounded, ModelError, Unpaired};
use super::facet_cells::two_cells;
use super::pairs::Interface;
use super::spec::ContactGroups;
use super::topology::{corner_key, FaceKey, Topology};
use crate::fem::{element, shape};
use crate::mesh::Cell;

/// Facets of one pair whose normals differ by more than this many degrees
/// are on two faces of a crease: the node gets one pair per face. A curved
/// joint meshed with at least 9 facets per right angle stays one pair per
/// node (gmsh's own feature angle for surface classification is 40 too).
pub const CREASE_ANGLE: f64 = 40.0;

/// One facet's part in a pair: the facet (index in its interface's
/// `facets`) and the position of the pair's node in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Share {
    pub facet: usize,
    pub node: usize,
}

/// A pair before its normal and area: k on side I, l on side II, its
/// contact and the facets it takes its normal and area from.
pub(super) struct RawPair {
    pub k: usize,
    pub l: usize,
    pub contact: usize,
    pub shares: Vec<Share>,
}

/// The model nodes after the split, the blocks, the pairs and the interfaces.
pub(super) struct Split {
    /// Coordinates of every model node: the mesh's, then the copies.
    pub coords: Vec<[f64; 3]>,
    /// Mesh node of every model node.
    pub mesh_node: Vec<usize>,
    /// Every cell of the topology, in model nodes.
    pub cells: Vec<Cell>,
    /// The block of every cell: blocks numbered in order of their first
    /// cell, so in the order of the bodies.
    pub block: Vec<usize>,
    pub pairs: Vec<RawPair>,
    /// One interface per contact, its facets in side I's model nodes, sides as blocks.
    pub interfaces: Vec<Interface>,
    /// Per interface, the sign that makes each facet's natural normal outward for side I.
    pub signs: Vec<Vec<f64>>,
}

/// Splits every contact of the description, numbers the blocks and makes
/// the pairs, in the steps below. `size` is the mesh's size (the pairing
/// tolerance of `groups = [..]` is 1e-6 of it).
pub(super) fn split(b: &Builder, topo: &Topology, size: f64) -> Result<Split, ModelError> {
    // 1. The facets of shared contact groups cut the bodies.
    let cuts = cuts(b)?;
    // 2. The two cells of every facet.
    let cells_of = two_cells(b, topo, &cuts.shared)?;
    // 3. Blocks, and one model node per fan at every node of a cut.
    let block = topo.blocks(&cuts.cut);
    let copies = copy_nodes(b, topo, &cuts);
    // 4. Side I of every facet.
    let sides = Sides::new(b, topo, &cuts.shared, &cells_of, &block);
    // 5. Interfaces and the facets' shares of pairs (k, l) at each node.
    let mut shares = Shares::default();
    let mut interfaces: Vec<Interface> = Vec::with_capacity(b.spec.contacts.len());
    let mut signs: Vec<Vec<f64>> = Vec::with_capacity(b.spec.contacts.len());
    for (ci, c) in b.spec.contacts.iter().enumerate() {
        let (iface, sg) = match &c.groups {
            ContactGroups::Shared(name) => sides.shared_interface(ci, name, &copies, &mut shares),
            ContactGroups::Pair(na, nb) => sides.paired_interface(ci, (na, nb), size, &copies, &mut shares)?,
        };
        interfaces.push(iface);
        signs.push(sg);
    }
    // 6. Pairs: the shares of each (contact, k, l), split at creases.
    let pairs = shares.pairs(&copies.mesh_node);
    let Copies { coords, mesh_node, cells } = copies;
    Ok(Split { coords, mesh_node, cells, block, pairs, interfaces, signs })
}

/// The facets of the shared contact groups, each once: what cuts the bodies.
struct Cuts<'a> {
    /// The corners of every facet (its key) -> its index in `shared`.
    cut: HashMap<FaceKey, usize>,
    /// Every facet with its contact (index in the description's contacts).
    shared: Vec<(usize, &'a Cell)>,
}

/// The facets of every `group = ".."` contact, each once: what cuts the
/// bodies into blocks. A facet in two contacts is an error naming both.
fn cuts<'a>(b: &Builder<'a>) -> Result<Cuts<'a>, ModelError> {
    let sd = b.spec.analysis.dim();
    let mut cut: HashMap<FaceKey, usize> = HashMap::new();
    let mut shared: Vec<(usize, &Cell)> = Vec::new();
    for (ci, c) in b.spec.contacts.iter().enumerate() {
        let ContactGroups::Shared(name) = &c.groups else { continue };
        let key = format!("{}.group", c.key);
        let g = b.group(&key, name, &[sd - 1])?;
        for f in &g.cells {
            let fk = corner_key(f);
            match cut.get(&fk) {
                Some(&other) if shared[other].0 == ci => continue,
                Some(&other) => {
                    let (oc, of) = shared[other];
                    return Err(ModelError::FaceInTwoContacts {
                        key,
                        tag: f.tag,
                        group: name.clone(),
                        other_tag: of.tag,
                        other: oc,
                    });
                }
                None => {
                    cut.insert(fk, shared.len());
                    shared.push((ci, f));
                }
            }
        }
    }
    Ok(Cuts { cut, shared })
}

/// The model nodes after the split and the cells in them.
struct Copies {
    /// The mesh's nodes, then the copies.
    coords: Vec<[f64; 3]>,
    /// Mesh node of every model node.
    mesh_node: Vec<usize>,
    /// Every cell of the topology, in model nodes.
    cells: Vec<Cell>,
}

/// One model node per fan at every node of a cut, contact by contact: the
/// first fan keeps the mesh node, every other fan's cells get a new copy,
/// so that the sides of a contact can move apart.
fn copy_nodes(b: &Builder, topo: &Topology, cuts: &Cuts) -> Copies {
    let mesh = b.mesh;
    let mut coords = mesh.coords.clone();
    let mut mesh_node: Vec<usize> = (0..coords.len()).collect();
    let mut cells: Vec<Cell> = topo.cells.iter().map(|c| (*c).clone()).collect();
    let mut done: HashSet<usize> = HashSet::new();
    for ci in 0..b.spec.contacts.len() {
        let mut nodes: Vec<usize> =
            cuts.shared.iter().filter(|s| s.0 == ci).flat_map(|s| s.1.nodes.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        for n in nodes {
            if !done.insert(n) {
                continue;
            }
            for fan in topo.fans(n, &cuts.cut).iter().skip(1) {
                let m = coords.len();
                coords.push(mesh.coords[n]);
                mesh_node.push(n);
                for &c in fan {
                    for x in cells[c].nodes.iter_mut().filter(|x| **x == n) {
                        *x = m;
                    }
                }
            }
        }
    }
    Copies { coords, mesh_node, cells }
}

/// What the interfaces are built from: the shared facets with their two
/// cells and the blocks, and what decides side I of each facet.
struct Sides<'a> {
    b: &'a Builder<'a>,
    topo: &'a Topology<'a>,
    shared: &'a [(usize, &'a Cell)],
    cells_of: &'a [[usize; 2]],
    block: &'a [usize],
    /// Within a body, by (contact, lower block, higher block): the normals
    /// the two blocks share in the contact, outward of the lower block and
    /// weighted by area, and that area.
    between: HashMap<(usize, usize, usize), ([f64; 3], f64)>,
}

impl<'a> Sides<'a> {
    /// The sides of the shared facets, with the normals every two blocks
    /// of one body share in a contact summed: they decide side I between
    /// blocks.
    fn new(
        b: &'a Builder<'a>,
        topo: &'a Topology<'a>,
        shared: &'a [(usize, &'a Cell)],
        cells_of: &'a [[usize; 2]],
        block: &'a [usize],
    ) -> Sides<'a> {
        let mut sides = Sides { b, topo, shared, cells_of, block, between: HashMap::new() };
        for (i, &(ci, f)) in shared.iter().enumerate() {
            let [x, y] = cells_of[i];
            if topo.body[x] == topo.body[y] && block[x] != block[y] {
                let low = if block[x] < block[y] { x } else { y };
                let (n, da) = sides.normal_of(f, low);
                let e = sides
                    .between
                    .entry((ci, block[x].min(block[y]), block[x].max(block[y])))
                    .or_insert(([0.0; 3], 0.0));
                for d in 0..3 {
                    e.0[d] += n[d] * da;
                }
                e.1 += da;
            }
        }
        sides
    }

    /// Facet f's unit normal at its centre, outward of cell c, and its area
    /// element there (mesh coordinates).
    fn normal_of(&self, f: &Cell, c: usize) -> ([f64; 3], f64) {
        let (coords, topo) = (&self.b.mesh.coords, self.topo);
        let fc: Vec<[f64; 3]> = f.nodes.iter().map(|&n| coords[n]).collect();
        let cc: Vec<[f64; 3]> = topo.cells[c].nodes.iter().map(|&n| coords[n]).collect();
        let sign = element::outward_sign(f.kind, &fc, topo.cells[c].kind, &cc);
        let (_, n, da, _) = element::facet_point(f.kind, &fc, shape::reference_centre(f.kind));
        ([sign * n[0], sign * n[1], sign * n[2]], da)
    }

    /// The cells of shared facet i as [side I, side II]: the body listed
    /// first, or between blocks of one body the low side (module header).
    fn side_i(&self, i: usize) -> [usize; 2] {
        let (topo, block) = (self.topo, self.block);
        let (ci, f) = self.shared[i];
        let [x, y] = self.cells_of[i];
        if topo.body[x] != topo.body[y] {
            return if topo.body[x] < topo.body[y] { [x, y] } else { [y, x] };
        }
        let (low, high) = if block[x] <= block[y] { (x, y) } else { (y, x) };
        let n = match self.between.get(&(ci, block[low], block[high])) {
            Some(&(n, area)) if element::norm(n) > 1e-6 * area => n,
            // one block on both sides (a joint that ends inside it), or two
            // blocks whose shared facets close around: this facet's own normal
            _ => self.normal_of(f, low).0,
        };
        if points_up(n) {
            [low, high]
        } else {
            [high, low]
        }
    }

    /// Contact `ci` with `group = name`: its interface (the facets in side
    /// I's model nodes) and the signs of its facets; adds each facet's
    /// shares of the pairs at its nodes whose two sides have their own copy.
    fn shared_interface(&self, ci: usize, name: &str, copies: &Copies, shares: &mut Shares) -> (Interface, Vec<f64>) {
        let (topo, cells) = (self.topo, &copies.cells);
        let (mut facets, mut sides, mut sg) = (Vec::new(), Vec::new(), Vec::new());
        for (i, &(fci, f)) in self.shared.iter().enumerate() {
            if fci != ci {
                continue;
            }
            let [ca, cb] = self.side_i(i);
            let (n, _) = self.normal_of(f, ca);
            let fid = facets.len();
            let mut fi = f.clone();
            for (j, x) in fi.nodes.iter_mut().enumerate() {
                let (k, l) = (topo.node_in(cells, ca, f.nodes[j]), topo.node_in(cells, cb, f.nodes[j]));
                *x = k;
                if k != l {
                    shares.add((ci, k, l), Share { facet: fid, node: j }, n);
                }
            }
            facets.push(fi);
            sides.push([self.block[ca], self.block[cb]]);
            sg.push(facet_sign(&copies.coords, &facets[fid], &cells[ca]));
        }
        (interface(name.to_string(), facets, sides), sg)
    }

    /// Contact `ci` with `groups = [a, b]`: its interface and the signs of
    /// its facets, side I the block listed first; adds the shares of the
    /// pairs of nodes at one position. An error when a group is not the
    /// face of one block, both are of the same block, or the nodes do not
    /// pair.
    fn paired_interface(
        &self,
        ci: usize,
        (na, nb): (&str, &str),
        size: f64,
        copies: &Copies,
        shares: &mut Shares,
    ) -> Result<(Interface, Vec<f64>), ModelError> {
        let (b, topo, block) = (self.b, self.topo, self.block);
        let (c, sd) = (&b.spec.contacts[ci], b.spec.analysis.dim());
        let ka = format!("{}.groups[0]", c.key);
        let kb = format!("{}.groups[1]", c.key);
        let ga = b.group(&ka, na, &[sd - 1])?;
        let gb = b.group(&kb, nb, &[sd - 1])?;
        let sa = one_side(b, topo, block, &ka, na, &ga.cells)?;
        let sb = one_side(b, topo, block, &kb, nb, &gb.cells)?;
        if block[sa[0]] == block[sb[0]] {
            return Err(ModelError::SelfContact {
                key: format!("{}.groups", c.key),
                a: na.to_string(),
                b: nb.to_string(),
                bound: describe_cell(b, topo, block, sa[0]),
            });
        }
        let ((gi, ci_cells), (gii, cii_cells)) =
            if block[sa[0]] < block[sb[0]] { ((ga, sa), (gb, sb)) } else { ((gb, sb), (ga, sa)) };
        let (map_i, map_ii) = (
            side_map(topo, &copies.cells, &gi.cells, &ci_cells),
            side_map(topo, &copies.cells, &gii.cells, &cii_cells),
        );
        let pairs = pair_by_position(&b.mesh.coords, &gi.nodes(), &gii.nodes(), 1e-6 * size).map_err(|why| {
            ModelError::Unpaired {
                key: format!("{}.groups", c.key),
                a: gi.name.clone(),
                b: gii.name.clone(),
                why: Box::new(why),
            }
        })?;
        let partner: HashMap<usize, usize> = pairs.into_iter().collect();
        let (mut facets, mut sides, mut sg) = (Vec::new(), Vec::new(), Vec::new());
        for (f, &ca) in gi.cells.iter().zip(&ci_cells) {
            let fid = facets.len();
            let (n, _) = self.normal_of(f, ca);
            let mut fi = f.clone();
            for (j, x) in fi.nodes.iter_mut().enumerate() {
                let m = f.nodes[j];
                *x = map_i[&m];
                shares.add((ci, map_i[&m], map_ii[&partner[&m]]), Share { facet: fid, node: j }, n);
            }
            sg.push(facet_sign(&copies.coords, &fi, &copies.cells[ca]));
            facets.push(fi);
            sides.push([block[ca], block[cii_cells[0]]]);
        }
        Ok((interface(format!("{}|{}", gi.name, gii.name), facets, sides), sg))
    }
}

/// Each mesh node of a `groups = [..]` side's facets in the model node of
/// its own cell (`owners`, one per facet): the side's copy of the node.
fn side_map(topo: &Topology, cells: &[Cell], facets: &[Cell], owners: &[usize]) -> HashMap<usize, usize> {
    let mut map = HashMap::new();
    for (f, &c) in facets.iter().zip(owners) {
        for &n in &f.nodes {
            map.entry(n).or_insert_with(|| topo.node_in(cells, c, n));
        }
    }
    map
}

/// The interface of a contact from its facets and their (body I, body II):
/// the bodies of its first facet and every body on side I, ascending.
fn interface(name: String, facets: Vec<Cell>, sides: Vec<[usize; 2]>) -> Interface {
    let body_i = sides.first().map_or(0, |s| s[0]);
    let body_ii = sides.first().map_or(0, |s| s[1]);
    let mut side_i: Vec<usize> = sides.iter().map(|s| s[0]).collect();
    side_i.sort_unstable();
    side_i.dedup();
    Interface { name, body_i, body_ii, side_i, facets, sides }
}

/// The facets' shares of the pairs, by (contact, k, l) in the order they
/// first appear, each share with its facet's normal outward of side I.
#[derive(Default)]
struct Shares {
    list: Vec<(PairKey, Vec<ShareNormal>)>,
    at: HashMap<PairKey, usize>,
}

/// (contact, k, l): the pair a share belongs to, before creases split it.
type PairKey = (usize, usize, usize);

/// A share with its facet's normal outward of side I.
type ShareNormal = (Share, [f64; 3]);

impl Shares {
    /// Adds a facet's share (with its normal n) to the pair (contact, k, l).
    fn add(&mut self, key: PairKey, share: Share, n: [f64; 3]) {
        let at = *self.at.entry(key).or_insert_with(|| {
            self.list.push((key, Vec::new()));
            self.list.len() - 1
        });
        self.list[at].1.push((share, n));
    }

    /// The pairs, ordered by contact and mesh node: the shares of each
    /// (contact, k, l), split where their facets' normals turn by more than
    /// [`CREASE_ANGLE`], one pair per face.
    fn pairs(mut self, mesh_node: &[usize]) -> Vec<RawPair> {
        self.list.sort_by_key(|((ci, k, l), _)| (*ci, mesh_node[*k], *k, *l));
        let cos_crease = CREASE_ANGLE.to_radians().cos();
        let mut pairs = Vec::new();
        for ((ci, k, l), list) in self.list {
            let mut faces: Vec<([f64; 3], Vec<Share>)> = Vec::new();
            for (share, n) in list {
                match faces.iter_mut().find(|(sum, _)| element::dot(*sum, n) >= cos_crease * element::norm(*sum)) {
                    Some((sum, members)) => {
                        for d in 0..3 {
                            sum[d] += n[d];
                        }
                        members.push(share);
                    }
                    None => faces.push((n, vec![share])),
                }
            }
            pairs.extend(faces.into_iter().map(|(_, shares)| RawPair { k, l, contact: ci, shares }));
        }
        pairs
    }
}

/// Whether the normal n points along +x, +y or +z, whichever of the three
/// axes it is closest to (ties to the first).
fn points_up(n: [f64; 3]) -> bool {
    let d = (0..3).fold(0, |best, d| if n[d].abs() > n[best].abs() { d } else { best });
    n[d] > 0.0
}

/// The sign making `facet`'s natural normal outward for `cell` (model nodes).
pub(super) fn facet_sign(coords: &[[f64; 3]], facet: &Cell, cell: &Cell) -> f64 {
    let fc: Vec<[f64; 3]> = facet.nodes.iter().map(|&n| coords[n]).collect();
    let cc: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| coords[n]).collect();
    element::outward_sign(facet.kind, &fc, cell.kind, &cc)
}

/// The body a cell lies in, or its block when the body is cut into blocks.
fn describe_cell(b: &Builder, topo: &Topology, block: &[usize], c: usize) -> Box<Bounded> {
    let body = topo.body[c];
    let name = b.spec.bodies[body].group.clone();
    let of_body: Vec<usize> = (0..block.len()).filter(|&x| topo.body[x] == body).collect();
    let first = of_body.iter().map(|&x| block[x]).min().unwrap_or(0);
    if of_body.iter().all(|&x| block[x] == first) {
        return Box::new(Bounded::Body { name });
    }
    let nodes: Vec<usize> =
        of_body.iter().filter(|&&x| block[x] == block[c]).flat_map(|&x| topo.cells[x].nodes.iter().copied()).collect();
    let centre: [f64; 3] =
        std::array::from_fn(|d| nodes.iter().map(|&n| b.mesh.coords[n][d]).sum::<f64>() / nodes.len().max(1) as f64);
    Box::new(Bounded::Block { number: block[c] - first + 1, body: name, centre })
}

/// The one cell each facet of a `groups = [..]` side bounds; all in one block.
fn one_side(
    b: &Builder,
    topo: &Topology,
    block: &[usize],
    key: &str,
    name: &str,
    facets: &[Cell],
) -> Result<Vec<usize>, ModelError> {
    let mut out = Vec::with_capacity(facets.len());
    for f in facets {
        let cells = topo.bounding(f);
        match cells.as_slice() {
            [one] => {
                if let Some(&first) = out.first() {
                    if block[first] != block[*one] {
                        return Err(ModelError::SideOfTwo {
                            key: key.to_string(),
                            group: name.to_string(),
                            first: describe_cell(b, topo, block, first),
                            second: describe_cell(b, topo, block, *one),
                        });
                    }
                }
                out.push(*one);
            }
            [] => return Err(ModelError::SideOffBodies { key: key.to_string(), tag: f.tag, group: name.to_string() }),
            [x, y, ..] => {
                return Err(ModelError::SideBetween {
                    key: key.to_string(),
                    tag: f.tag,
                    group: name.to_string(),
                    first: describe_cell(b, topo, block, *x),
                    second: describe_cell(b, topo, block, *y),
                })
            }
        }
    }
    Ok(out)
}

/// Pairs every node of `a` with the one node of `b` within `tol`; error when
/// a node has no partner or several.
fn pair_by_position(coords: &[[f64; 3]], a: &[usize], b: &[usize], tol: f64) -> Result<Vec<(usize, usize)>, Unpaired> {
    // Sort b by x and search a window: robust for large offsets because only
    // differences of nearby coordinates are compared.
    let mut sorted: Vec<usize> = b.to_vec();
    sorted.sort_by(|&p, &q| coords[p][0].total_cmp(&coords[q][0]));
    let xs: Vec<f64> = sorted.iter().map(|&n| coords[n][0]).collect();
    let mut pairs = Vec::with_capacity(a.len());
    let mut used = vec![false; sorted.len()];
    let mut lonely = Vec::new();
    for &k in a {
        let x = coords[k];
        let lo = xs.partition_point(|&v| v < x[0] - tol);
        let hits: Vec<usize> = (lo..sorted.len())
            .take_while(|&j| xs[j] <= x[0] + tol)
            .filter(|&j| element::norm(element::sub(coords[sorted[j]], x)) <= tol)
            .collect();
        match hits.as_slice() {
            [j] => {
                used[*j] = true;
                pairs.push((k, sorted[*j]));
            }
            [] => lonely.push(x),
            _ => return Err(Unpaired::Duplicate { at: x, partners: hits.len(), tol }),
        }
    }
    lonely.extend(sorted.iter().zip(&used).filter(|(_, &u)| !u).map(|(&n, _)| coords[n]));
    if !lonely.is_empty() {
        return Err(Unpaired::Lonely { lonely, tol });
    }
    Ok(pairs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairing_by_position_is_robust_far_from_origin() {
        let base = [5.0e5, 4.2e6, 0.0];
        let mut coords = Vec::new();
        for i in 0..5 {
            coords.push([base[0] + i as f64 * 0.1, base[1] + 0.3 * i as f64, 0.0]);
        }
        for i in (0..5).rev() {
            // the same points, with round-off
            coords.push([base[0] + i as f64 * 0.1 + 1e-9, base[1] + 0.3 * i as f64 - 1e-9, 0.0]);
        }
        let pairs = pair_by_position(&coords, &[0, 1, 2, 3, 4], &[5, 6, 7, 8, 9], 1e-6 * 2.0).unwrap();
        assert_eq!(pairs, vec![(0, 9), (1, 8), (2, 7), (3, 6), (4, 5)]);
        coords[5][0] += 0.05;
        let err = pair_by_position(&coords, &[0, 1, 2, 3, 4], &[5, 6, 7, 8, 9], 1e-6 * 2.0).unwrap_err();
        assert!(matches!(err, Unpaired::Lonely { .. }) && err.to_string().contains("no partner"), "{err}");
    }

    #[test]
    fn side_i_is_the_low_side() {
        assert!(points_up([0.0, 0.0, 1.0]));
        assert!(!points_up([0.1, 0.0, -1.0]));
        assert!(points_up([0.7, -0.69, 0.0]));
        assert!(!points_up([-0.7, 0.69, 0.0]));
    }
}
