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

use super::builder::Builder;
use super::topology::{corner_key, FaceKey, Topology};
use super::{ContactGroups, Interface, ModelError};
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
/// the pairs. `size` is the mesh's size (the pairing tolerance of
/// `groups = [..]` is 1e-6 of it).
pub(super) fn split(b: &Builder, topo: &Topology, size: f64) -> Result<Split, ModelError> {
    let (mesh, spec) = (b.mesh, b.spec);
    let sd = spec.analysis.dim();

    // 1. The facets of shared contact groups cut the bodies.
    let mut cut: HashMap<FaceKey, usize> = HashMap::new();
    let mut shared: Vec<(usize, &Cell)> = Vec::new();
    for (ci, c) in spec.contacts.iter().enumerate() {
        let ContactGroups::Shared(name) = &c.groups else { continue };
        let key = format!("{}.group", c.key);
        let g = b.group(&key, name, &[sd - 1])?;
        for f in &g.cells {
            let fk = corner_key(f);
            match cut.get(&fk) {
                Some(&other) if shared[other].0 == ci => continue,
                Some(&other) => {
                    let (oc, of) = shared[other];
                    return Err(b.invalid(
                        key,
                        format!(
                            "element {} of group \"{name}\" is also element {} of contacts[{oc}]'s group: a face can be in one contact only; remove it from one of the two Physical groups",
                            f.tag, of.tag
                        ),
                    ));
                }
                None => {
                    cut.insert(fk, shared.len());
                    shared.push((ci, f));
                }
            }
        }
    }

    // 2. The two cells of every facet.
    let cells_of = two_cells(b, topo, &shared)?;

    // 3. Blocks, and one model node per fan at every node of a cut.
    let block = topo.blocks(&cut);
    let mut coords = mesh.coords.clone();
    let mut mesh_node: Vec<usize> = (0..coords.len()).collect();
    let mut cells: Vec<Cell> = topo.cells.iter().map(|c| (*c).clone()).collect();
    let mut done: HashSet<usize> = HashSet::new();
    for ci in 0..spec.contacts.len() {
        let mut nodes: Vec<usize> = shared.iter().filter(|s| s.0 == ci).flat_map(|s| s.1.nodes.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        for n in nodes {
            if !done.insert(n) {
                continue;
            }
            for fan in topo.fans(n, &cut).iter().skip(1) {
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
    let node_in = |c: usize, n: usize| -> usize {
        let at = topo.cells[c].nodes.iter().position(|&x| x == n).expect("the node is in the cell");
        cells[c].nodes[at]
    };

    // 4. Side I of every facet.
    let normal_of = |f: &Cell, c: usize| -> ([f64; 3], f64) {
        let fc: Vec<[f64; 3]> = f.nodes.iter().map(|&n| mesh.coords[n]).collect();
        let cc: Vec<[f64; 3]> = topo.cells[c].nodes.iter().map(|&n| mesh.coords[n]).collect();
        let sign = element::outward_sign(f.kind, &fc, topo.cells[c].kind, &cc);
        let (_, n, da, _) = element::facet_point(f.kind, &fc, shape::reference_centre(f.kind));
        ([sign * n[0], sign * n[1], sign * n[2]], da)
    };
    // within a body: the normals the two blocks share in a contact, outward of the lower block
    let mut between: HashMap<(usize, usize, usize), ([f64; 3], f64)> = HashMap::new();
    for (i, &(ci, f)) in shared.iter().enumerate() {
        let [x, y] = cells_of[i];
        if topo.body[x] == topo.body[y] && block[x] != block[y] {
            let low = if block[x] < block[y] { x } else { y };
            let (n, da) = normal_of(f, low);
            let e = between.entry((ci, block[x].min(block[y]), block[x].max(block[y]))).or_insert(([0.0; 3], 0.0));
            for d in 0..3 {
                e.0[d] += n[d] * da;
            }
            e.1 += da;
        }
    }
    let side_i = |i: usize| -> [usize; 2] {
        let (ci, f) = shared[i];
        let [x, y] = cells_of[i];
        if topo.body[x] != topo.body[y] {
            return if topo.body[x] < topo.body[y] { [x, y] } else { [y, x] };
        }
        let (low, high) = if block[x] <= block[y] { (x, y) } else { (y, x) };
        let n = match between.get(&(ci, block[low], block[high])) {
            Some(&(n, area)) if element::norm(n) > 1e-6 * area => n,
            // one block on both sides (a joint that ends inside it), or two
            // blocks whose shared facets close around: this facet's own normal
            _ => normal_of(f, low).0,
        };
        if points_up(n) {
            [low, high]
        } else {
            [high, low]
        }
    };

    // 5. Interfaces and the facets' shares of pairs (k, l) at each node.
    let mut interfaces: Vec<Interface> = Vec::with_capacity(spec.contacts.len());
    let mut signs: Vec<Vec<f64>> = Vec::with_capacity(spec.contacts.len());
    let mut shares: Vec<((usize, usize, usize), Vec<(Share, [f64; 3])>)> = Vec::new();
    let mut share_of: HashMap<(usize, usize, usize), usize> = HashMap::new();
    let mut add_share = |key: (usize, usize, usize), share: Share, n: [f64; 3]| {
        let at = *share_of.entry(key).or_insert_with(|| {
            shares.push((key, Vec::new()));
            shares.len() - 1
        });
        shares[at].1.push((share, n));
    };
    for (ci, c) in spec.contacts.iter().enumerate() {
        let mut iface = Interface { name: String::new(), body_i: 0, body_ii: 0, side_i: Vec::new(), facets: Vec::new(), sides: Vec::new() };
        let mut sg = Vec::new();
        match &c.groups {
            ContactGroups::Shared(name) => {
                iface.name = name.clone();
                for (i, &(fci, f)) in shared.iter().enumerate() {
                    if fci != ci {
                        continue;
                    }
                    let [ca, cb] = side_i(i);
                    let (n, _) = normal_of(f, ca);
                    let fid = iface.facets.len();
                    let mut fi = f.clone();
                    for (j, x) in fi.nodes.iter_mut().enumerate() {
                        let (k, l) = (node_in(ca, f.nodes[j]), node_in(cb, f.nodes[j]));
                        *x = k;
                        if k != l {
                            add_share((ci, k, l), Share { facet: fid, node: j }, n);
                        }
                    }
                    iface.facets.push(fi);
                    iface.sides.push([block[ca], block[cb]]);
                    sg.push(facet_sign(&coords, &iface.facets[fid], &cells[ca]));
                }
            }
            ContactGroups::Pair(na, nb) => {
                let ka = format!("{}.groups[0]", c.key);
                let kb = format!("{}.groups[1]", c.key);
                let ga = b.group(&ka, na, &[sd - 1])?;
                let gb = b.group(&kb, nb, &[sd - 1])?;
                let sa = one_side(b, topo, &block, &ka, na, &ga.cells)?;
                let sb = one_side(b, topo, &block, &kb, nb, &gb.cells)?;
                if block[sa[0]] == block[sb[0]] {
                    return Err(b.invalid(
                        format!("{}.groups", c.key),
                        format!(
                            "both \"{na}\" and \"{nb}\" bound {}: a contact between a body and itself is not supported; split the body into two physical groups",
                            describe_cell(b, topo, &block, sa[0])
                        ),
                    ));
                }
                let ((gi, ci_cells), (gii, cii_cells)) = if block[sa[0]] < block[sb[0]] { ((ga, sa), (gb, sb)) } else { ((gb, sb), (ga, sa)) };
                // each side's mesh nodes in its own cells' model nodes
                let side_map = |facets: &[Cell], owners: &[usize]| -> HashMap<usize, usize> {
                    let mut map = HashMap::new();
                    for (f, &c) in facets.iter().zip(owners) {
                        for &n in &f.nodes {
                            map.entry(n).or_insert_with(|| node_in(c, n));
                        }
                    }
                    map
                };
                let (map_i, map_ii) = (side_map(&gi.cells, &ci_cells), side_map(&gii.cells, &cii_cells));
                let pairs = pair_by_position(&mesh.coords, &gi.nodes(), &gii.nodes(), 1e-6 * size)
                    .map_err(|msg| b.invalid(format!("{}.groups", c.key), format!("pairing the nodes of \"{}\" with those of \"{}\": {msg}", gi.name, gii.name)))?;
                let partner: HashMap<usize, usize> = pairs.into_iter().collect();
                iface.name = format!("{}|{}", gi.name, gii.name);
                for (f, &ca) in gi.cells.iter().zip(&ci_cells) {
                    let fid = iface.facets.len();
                    let (n, _) = normal_of(f, ca);
                    let mut fi = f.clone();
                    for (j, x) in fi.nodes.iter_mut().enumerate() {
                        let m = f.nodes[j];
                        *x = map_i[&m];
                        add_share((ci, map_i[&m], map_ii[&partner[&m]]), Share { facet: fid, node: j }, n);
                    }
                    sg.push(facet_sign(&coords, &fi, &cells[ca]));
                    iface.facets.push(fi);
                    iface.sides.push([block[ca], block[cii_cells[0]]]);
                }
            }
        }
        iface.body_i = iface.sides.first().map_or(0, |s| s[0]);
        iface.body_ii = iface.sides.first().map_or(0, |s| s[1]);
        iface.side_i = iface.sides.iter().map(|s| s[0]).collect();
        iface.side_i.sort_unstable();
        iface.side_i.dedup();
        interfaces.push(iface);
        signs.push(sg);
    }

    // 6. Pairs: the shares of each (contact, k, l), split at creases.
    shares.sort_by_key(|((ci, k, l), _)| (*ci, mesh_node[*k], *k, *l));
    let cos_crease = CREASE_ANGLE.to_radians().cos();
    let mut pairs = Vec::new();
    for ((ci, k, l), list) in shares {
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
    Ok(Split { coords, mesh_node, cells, block, pairs, interfaces, signs })
}

/// Whether the normal n points along +x, +y or +z, whichever of the three
/// axes it is closest to (ties to the first).
fn points_up(n: [f64; 3]) -> bool {
    let d = (0..3).fold(0, |best, d| if n[d].abs() > n[best].abs() { d } else { best });
    n[d] > 0.0
}

/// The sign making `facet`'s natural normal outward for `cell` (model nodes).
fn facet_sign(coords: &[[f64; 3]], facet: &Cell, cell: &Cell) -> f64 {
    let fc: Vec<[f64; 3]> = facet.nodes.iter().map(|&n| coords[n]).collect();
    let cc: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| coords[n]).collect();
    element::outward_sign(facet.kind, &fc, cell.kind, &cc)
}

/// The group name of contact `ci` (shared groups).
fn group_name(spec: &super::ModelSpec, ci: usize) -> &str {
    match &spec.contacts[ci].groups {
        ContactGroups::Shared(n) => n,
        ContactGroups::Pair(a, _) => a,
    }
}

/// "body "rock"", or "block 3 of body "rock" (centre at (x, y, z))" when
/// the body is cut into blocks.
fn describe_cell(b: &Builder, topo: &Topology, block: &[usize], c: usize) -> String {
    let body = topo.body[c];
    let name = &b.spec.bodies[body].group;
    let of_body: Vec<usize> = (0..block.len()).filter(|&x| topo.body[x] == body).collect();
    let first = of_body.iter().map(|&x| block[x]).min().unwrap_or(0);
    if of_body.iter().all(|&x| block[x] == first) {
        return format!("body \"{name}\"");
    }
    let nodes: Vec<usize> = of_body.iter().filter(|&&x| block[x] == block[c]).flat_map(|&x| topo.cells[x].nodes.iter().copied()).collect();
    let centre: [f64; 3] = std::array::from_fn(|d| nodes.iter().map(|&n| b.mesh.coords[n][d]).sum::<f64>() / nodes.len().max(1) as f64);
    format!("block {} of body \"{name}\" (centre at ({:.4}, {:.4}, {:.4}))", block[c] - first + 1, centre[0], centre[1], centre[2])
}

/// The two cells of every facet of the shared contact groups (`shared`:
/// each facet with its contact); a facet that bounds one cell, none or
/// more than two is an error naming its group.
fn two_cells(b: &Builder, topo: &Topology, shared: &[(usize, &Cell)]) -> Result<Vec<[usize; 2]>, ModelError> {
    let spec = b.spec;
    let mut cells_of: Vec<[usize; 2]> = Vec::with_capacity(shared.len());
    // facets that bound one cell, with their contact and cell: read as a
    // whole (below) to say what is wrong with their group
    let mut lone: Vec<(usize, &Cell, usize)> = Vec::new();
    for &(ci, f) in shared {
        let key = format!("{}.group", spec.contacts[ci].key);
        let name = group_name(spec, ci);
        match topo.bounding(f).as_slice() {
            [x, y] => cells_of.push([*x, *y]),
            [one] => {
                lone.push((ci, f, *one));
                cells_of.push([*one, *one]);
            }
            [] => return Err(b.invalid(key, format!("element {} of group \"{name}\" touches no body: it is not a face of any element of the [[bodies]] groups", f.tag))),
            many => return Err(b.invalid(key, format!("element {} of group \"{name}\" is a face of {} elements; a face separates two", f.tag, many.len()))),
        }
    }
    if let Some(&(ci, ..)) = lone.first() {
        let of_group: Vec<(&Cell, usize)> = lone.iter().filter(|l| l.0 == ci).map(|l| (l.1, l.2)).collect();
        let between = shared.iter().zip(&cells_of).filter(|((c, _), [x, y])| *c == ci && x != y).count();
        return Err(touches_one(b, topo, ci, &of_group, between));
    }
    Ok(cells_of)
}

/// The message for a contact group (`contacts[ci]`) with facets that bound
/// one cell each (`lone`, with their cells; `between`: its facets between
/// two cells). Beside facets between two bodies they are outer faces the
/// group takes in. A group of lone facets alone names the body nearest
/// any of them, and when that body lies against one without sharing its
/// nodes, says how to make the mesh conformal.
fn touches_one(b: &Builder, topo: &Topology, ci: usize, lone: &[(&Cell, usize)], between: usize) -> ModelError {
    let key = format!("{}.group", b.spec.contacts[ci].key);
    let name = group_name(b.spec, ci);
    let (f, cell) = lone[0];
    let own = &b.spec.bodies[topo.body[cell]].group;
    let surface = if f.kind.dim() == 1 { "curve" } else { "surface" };
    if between > 0 {
        return b.invalid(
            key,
            format!(
                "group \"{name}\" takes in {} element(s) that touch only one body (element {} of body \"{own}\" the first) besides the {between} between two bodies: a contact is the {surface} the bodies share. Leave its outer faces out of the Physical group",
                lone.len(),
                f.tag
            ),
        );
    }
    let hint = match against(b, topo, lone) {
        Some((i, dist, other)) => format!(
            "; its element {} lies against body \"{}\" ({dist:.3e} away), which does not share its nodes: the two were meshed apart. Make the mesh conformal (OpenCASCADE: BooleanFragments{{ Volume{{..}}; Delete; }}{{ Volume{{..}}; Delete; }}, or Coherence), or give each side its own group and pair them with groups = [..]",
            lone[i].0.tag,
            b.spec.bodies[other].group
        ),
        None => match nearest(b, topo, centre(b, f), topo.body[cell]) {
            Some((dist, other)) => format!("; the nearest other body is \"{}\", {dist:.3e} away", b.spec.bodies[other].group),
            None => String::new(),
        },
    };
    b.invalid(
        key,
        format!(
            "group \"{name}\" touches only body \"{own}\" (element {}{}){hint}. A contact needs a body on each side sharing the {surface} (group = ..), or two coincident groups (groups = [..])",
            f.tag,
            if lone.len() > 1 { format!(" and {} more", lone.len() - 1) } else { String::new() }
        ),
    )
}

/// The centre of a facet's corners.
fn centre(b: &Builder, f: &Cell) -> [f64; 3] {
    let nc = f.kind.n_corners();
    std::array::from_fn(|d| f.nodes[..nc].iter().map(|&n| b.mesh.coords[n][d]).sum::<f64>() / nc as f64)
}

/// The nearest node of a body other than `body` to `x`: (distance, body).
fn nearest(b: &Builder, topo: &Topology, x: [f64; 3], body: usize) -> Option<(f64, usize)> {
    (topo.cells.iter().zip(&topo.body))
        .filter(|(_, &cb)| cb != body)
        .flat_map(|(c, &cb)| c.nodes.iter().map(move |&n| (element::norm(element::sub(b.mesh.coords[n], x)), cb)))
        .min_by(|a, c| a.0.total_cmp(&c.0))
}

/// Of the lone facets, the one another body's nodes come nearest to
/// (within twice the facet's size, relative to it): (its index, the
/// distance, that body). Other bodies' nodes are hashed on a grid of the
/// largest facet's size, so that every facet looks at its neighbourhood.
fn against(b: &Builder, topo: &Topology, lone: &[(&Cell, usize)]) -> Option<(usize, f64, usize)> {
    let coords = &b.mesh.coords;
    let at: Vec<([f64; 3], f64)> = (lone.iter())
        .map(|(f, _)| {
            let c = centre(b, f);
            (c, f.nodes[..f.kind.n_corners()].iter().map(|&n| element::norm(element::sub(coords[n], c))).fold(0.0, f64::max))
        })
        .collect();
    let h = at.iter().map(|a| a.1).fold(0.0, f64::max);
    if h <= 0.0 {
        return None;
    }
    let cell_of = |x: [f64; 3]| x.map(|v| (v / h).floor() as i64);
    let bodies: HashSet<usize> = lone.iter().map(|&(_, c)| topo.body[c]).collect();
    let mut grid: HashMap<[i64; 3], Vec<(usize, usize)>> = HashMap::new();
    for (c, &cb) in topo.cells.iter().zip(&topo.body) {
        if bodies.len() == 1 && bodies.contains(&cb) {
            continue;
        }
        for &n in &c.nodes {
            grid.entry(cell_of(coords[n])).or_default().push((n, cb));
        }
    }
    let mut best: Option<(f64, usize, f64, usize)> = None;
    for (i, (&(_, cell), &(x, size))) in lone.iter().zip(&at).enumerate() {
        let own = topo.body[cell];
        let g = cell_of(x);
        for d in 0..125 {
            let key = [g[0] + d % 5 - 2, g[1] + d / 5 % 5 - 2, g[2] + d / 25 - 2];
            for &(n, cb) in grid.get(&key).map_or(&[][..], |v| &v[..]) {
                let dist = element::norm(element::sub(coords[n], x));
                if cb != own && dist < 2.0 * size && best.is_none_or(|bb| dist / size < bb.0) {
                    best = Some((dist / size, i, dist, cb));
                }
            }
        }
    }
    best.map(|(_, i, dist, cb)| (i, dist, cb))
}

/// The one cell each facet of a `groups = [..]` side bounds; all in one block.
fn one_side(b: &Builder, topo: &Topology, block: &[usize], key: &str, name: &str, facets: &[Cell]) -> Result<Vec<usize>, ModelError> {
    let mut out = Vec::with_capacity(facets.len());
    for f in facets {
        let cells = topo.bounding(f);
        match cells.as_slice() {
            [one] => {
                if let Some(&first) = out.first() {
                    if block[first] != block[*one] {
                        return Err(b.invalid(
                            key.to_string(),
                            format!(
                                "group \"{name}\" bounds {} and {}: with groups = [..] each group is the face of one body (or block)",
                                describe_cell(b, topo, block, first),
                                describe_cell(b, topo, block, *one)
                            ),
                        ));
                    }
                }
                out.push(*one);
            }
            [] => return Err(b.invalid(key.to_string(), format!("element {} of group \"{name}\" is not a face of any element of the [[bodies]] groups", f.tag))),
            [x, y, ..] => {
                return Err(b.invalid(
                    key.to_string(),
                    format!(
                        "element {} of group \"{name}\" lies between {} and {}, which share its nodes: with groups = [..] each group is the face of one body. For a surface the two bodies share, use group = \"{name}\" instead",
                        f.tag,
                        describe_cell(b, topo, block, *x),
                        describe_cell(b, topo, block, *y)
                    ),
                ))
            }
        }
    }
    Ok(out)
}

/// Pairs every node of `a` with the one node of `b` within `tol`; error when
/// a node has no partner or several.
fn pair_by_position(coords: &[[f64; 3]], a: &[usize], b: &[usize], tol: f64) -> Result<Vec<(usize, usize)>, String> {
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
            _ => return Err(format!("node at {:?} has {} partners within {:.1e}: the mesh has duplicate nodes", x, hits.len(), tol)),
        }
    }
    lonely.extend(sorted.iter().zip(&used).filter(|(_, &u)| !u).map(|(&n, _)| coords[n]));
    if !lonely.is_empty() {
        let first: Vec<String> = lonely.iter().take(5).map(|p| format!("({:.6}, {:.6}, {:.6})", p[0], p[1], p[2])).collect();
        return Err(format!(
            "{} node(s) find no partner on the other side within {:.1e}, first at {}: the two groups must have coincident nodes (same mesh divisions on both curves/surfaces)",
            lonely.len(),
            tol,
            first.join(", ")
        ));
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
        assert!(err.contains("no partner"), "{err}");
    }

    #[test]
    fn side_i_is_the_low_side() {
        assert!(points_up([0.0, 0.0, 1.0]));
        assert!(!points_up([0.1, 0.0, -1.0]));
        assert!(points_up([0.7, -0.69, 0.0]));
        assert!(!points_up([-0.7, 0.69, 0.0]));
    }
}
