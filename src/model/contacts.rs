//! Contacts in the model: the split of a shared contact group's nodes (one
//! copy per body beyond the first, so the two sides can move apart), the
//! pairing of two coincident groups by position, and junctions where
//! contacts meet (a node is paired only by the contact it lies inside).
//! Side I of a shared group is the side of the body listed first; pairs are
//! (k on side I, l on side II).

use std::collections::{HashMap, HashSet};

use super::build::{facet_bodies, Builder};
use super::{Body, ContactGroups, Interface, ModelError};
use crate::fem::element;
use crate::mesh::Cell;

/// The model nodes after the contact split, and the pairs and interfaces.
pub(super) struct Split {
    /// Coordinates of every model node: the mesh's, then the copies.
    pub coords: Vec<[f64; 3]>,
    /// Mesh node of every model node.
    pub mesh_node: Vec<usize>,
    /// (body, mesh node) -> model node, for split nodes only.
    pub copy: HashMap<(usize, usize), usize>,
    /// (k, l, contact) of every pair, in model nodes.
    pub pairs: Vec<(usize, usize, usize)>,
    /// One interface per contact, its facets in side I's model nodes.
    pub interfaces: Vec<Interface>,
}

/// Splits and pairs every contact of the description; renumbers the bodies' cells
/// onto their own copies. `nb` lists the bodies of every mesh node, `size`
/// is the mesh's size (the pairing tolerance is 1e-6 of it).
pub(super) fn split(b: &Builder, bodies: &mut [Body], nb: &[Vec<usize>], size: f64) -> Result<Split, ModelError> {
    let (mesh, spec) = (b.mesh, b.spec);
    let sd = spec.analysis.dim();
    let mut coords = mesh.coords.clone();
    let mut mesh_node: Vec<usize> = (0..coords.len()).collect();
    // (body, mesh node) -> model node, for split nodes only
    let mut copy: HashMap<(usize, usize), usize> = HashMap::new();
    let mut raw_pairs: Vec<(usize, usize, usize)> = Vec::new(); // (k, l, contact)
    let mut interfaces = Vec::new();
    // Junctions: a node where contacts meet is paired only by the
    // contact it lies inside, not by those that end there (a vertical
    // joint ending on a dam's base: the two blocks stay joined at that
    // one node, which pairs with the rock).
    let mut ceded: HashSet<(usize, usize)> = HashSet::new();
    {
        let shared: Vec<(usize, &crate::mesh::Group)> = spec
            .contacts
            .iter()
            .enumerate()
            .filter_map(|(ci, c)| match &c.groups {
                ContactGroups::Shared(name) => mesh.group(name).map(|g| (ci, g)),
                ContactGroups::Pair(..) => None,
            })
            .collect();
        let rims: Vec<Rim> = shared.iter().map(|(_, g)| Rim::new(&g.cells)).collect();
        for (a, (ca, _)) in shared.iter().enumerate() {
            for (key, nodes) in &rims[a].rim {
                if (0..shared.len()).any(|o| o != a && rims[o].inside.contains(key)) {
                    ceded.extend(nodes.iter().map(|&n| (*ca, n)));
                }
            }
        }
    }
    for (ci, contact) in spec.contacts.iter().enumerate() {
        match &contact.groups {
            ContactGroups::Shared(name) => {
                let key = format!("{}.group", contact.key);
                let g = b.group(&key, name, &[sd - 1])?;
                let [side_i, side_ii] = contact_sides(b, &key, name, nb, bodies, &g.cells)?;
                for n in g.nodes() {
                    if ceded.contains(&(ci, n)) {
                        continue;
                    }
                    let l = coords.len();
                    coords.push(mesh.coords[n]);
                    mesh_node.push(n);
                    // side II's bodies at this node share one copy
                    for &bii in side_ii.iter().filter(|&&x| nb[n].contains(&x)) {
                        if copy.insert((bii, n), l).is_some() {
                            return Err(b.invalid(
                                key.clone(),
                                format!(
                                    "node at {:?} of body \"{}\" lies inside two contacts: contacts may meet only where one of them ends (a joint ending on a base); crossing contacts are not supported",
                                    mesh.coords[n], bodies[bii].name
                                ),
                            ));
                        }
                    }
                    raw_pairs.push((n, l, ci));
                }
                interfaces.push(Interface { name: name.clone(), body_i: side_i[0], body_ii: side_ii[0], side_i, facets: g.cells.clone() });
            }
            ContactGroups::Pair(na, nb_name) => {
                let ka = format!("{}.groups[0]", contact.key);
                let kb = format!("{}.groups[1]", contact.key);
                let ga = b.group(&ka, na, &[sd - 1])?;
                let gb = b.group(&kb, nb_name, &[sd - 1])?;
                let ba = single_body(b, &ka, na, nb, bodies, &ga.cells)?;
                let bb = single_body(b, &kb, nb_name, nb, bodies, &gb.cells)?;
                if ba == bb {
                    return Err(b.invalid(
                        format!("{}.groups", contact.key),
                        format!(
                            "both \"{na}\" and \"{nb_name}\" bound body \"{}\": a contact between a body and itself is not supported; split the body into two physical groups",
                            bodies[ba].name
                        ),
                    ));
                }
                let (gi, gii, bi, bii) = if ba < bb { (ga, gb, ba, bb) } else { (gb, ga, bb, ba) };
                let pairs = pair_by_position(&mesh.coords, &gi.nodes(), &gii.nodes(), 1e-6 * size)
                    .map_err(|msg| b.invalid(format!("{}.groups", contact.key), format!("pairing the nodes of \"{}\" with those of \"{}\": {msg}", gi.name, gii.name)))?;
                raw_pairs.extend(pairs.into_iter().map(|(k, l)| (k, l, ci)));
                let name = format!("{}|{}", gi.name, gii.name);
                interfaces.push(Interface { name, body_i: bi, body_ii: bii, side_i: vec![bi], facets: gi.cells.clone() });
            }
        }
    }
    for (bi, body) in bodies.iter_mut().enumerate() {
        for c in &mut body.cells {
            for n in &mut c.nodes {
                if let Some(&m) = copy.get(&(bi, *n)) {
                    *n = m;
                }
            }
        }
    }
    // Side I keeps the mesh node unless another contact copied it for
    // that body (a base on the far side of a joint's end): facets and
    // pairs use side I's own node.
    let side_i_node = |side: &[usize], n: usize| side.iter().filter(|&&bd| nb[n].contains(&bd)).find_map(|&bd| copy.get(&(bd, n)).copied()).unwrap_or(n);
    for iface in &mut interfaces {
        for f in &mut iface.facets {
            let owner = facet_bodies(nb, f).into_iter().find(|o| iface.side_i.contains(o));
            for n in &mut f.nodes {
                if let Some(o) = owner {
                    *n = copy.get(&(o, *n)).copied().unwrap_or(*n);
                }
            }
        }
    }
    for (k, _, ci) in &mut raw_pairs {
        *k = side_i_node(&interfaces[*ci].side_i, *k);
    }
    Ok(Split { coords, mesh_node, copy, pairs: raw_pairs, interfaces })
}

/// The bodies on either side of a shared contact group: every facet lies
/// between two bodies, and the bodies split into two sides (a dam's base
/// group has the rock on one side and every block on the other). Side I is
/// the side of the body listed first in `[[bodies]]`.
fn contact_sides(b: &Builder, key: &str, name: &str, nb: &[Vec<usize>], bodies: &[Body], facets: &[Cell]) -> Result<[Vec<usize>; 2], ModelError> {
    let mut edges: Vec<(usize, usize)> = Vec::new();
    for f in facets {
        let owners = facet_bodies(nb, f);
        match owners.as_slice() {
            [x, y] => edges.push((*x.min(y), *x.max(y))),
            [one] => {
                return Err(b.invalid(
                    key.to_string(),
                    format!(
                        "group \"{name}\" touches only body \"{}\" (element {}): a contact needs a body on each side sharing the {} (group = ..), or two coincident groups (groups = [..]); a contact between a body and itself is not supported, split the body into two physical groups",
                        bodies[*one].name,
                        f.tag,
                        if f.kind.dim() == 1 { "curve" } else { "surface" }
                    ),
                ))
            }
            [] => return Err(b.invalid(key.to_string(), format!("element {} of group \"{name}\" touches no body", f.tag))),
            many => {
                return Err(b.invalid(
                    key.to_string(),
                    format!("element {} of group \"{name}\" is shared by more than two bodies ({})", f.tag, many.len()),
                ))
            }
        }
    }
    edges.sort_unstable();
    edges.dedup();
    let Some(first) = edges.iter().map(|e| e.0).min() else {
        return Err(b.invalid(key.to_string(), format!("group \"{name}\" has no elements")));
    };
    // two-colour the bodies the group joins, starting from the first one
    let mut side: HashMap<usize, usize> = HashMap::from([(first, 0)]);
    loop {
        let mut changed = false;
        for &(x, y) in &edges {
            match (side.get(&x).copied(), side.get(&y).copied()) {
                (Some(a), None) => {
                    side.insert(y, 1 - a);
                    changed = true;
                }
                (None, Some(a)) => {
                    side.insert(x, 1 - a);
                    changed = true;
                }
                (Some(a), Some(c)) if a == c => {
                    return Err(b.invalid(
                        key.to_string(),
                        format!(
                            "group \"{name}\" joins bodies that cannot be put on two sides of one interface (\"{}\" and \"{}\" are on the same side): give the contacts their own groups",
                            bodies[x].name, bodies[y].name
                        ),
                    ))
                }
                _ => {}
            }
        }
        if !changed {
            break;
        }
    }
    if edges.iter().any(|(x, _)| !side.contains_key(x)) {
        return Err(b.invalid(key.to_string(), format!("group \"{name}\" is made of pieces between unrelated bodies: give each piece its own contact group")));
    }
    let mut sides = [Vec::new(), Vec::new()];
    for (&body, &sd) in &side {
        sides[sd].push(body);
    }
    sides[0].sort_unstable();
    sides[1].sort_unstable();
    Ok(sides)
}

/// The rim of a contact group and what lies inside it, as keys: on a curve
/// its points `(n, n)`, on a surface its edges `(corner, corner)` ascending.
/// The rim is a curve's two ends, or a surface's edges that only one facet
/// has; inside is every other point or edge. Where contacts meet, a
/// contact whose rim lies inside another (a joint ending on a base) cedes
/// the nodes of that part of its rim: they are paired by the other one.
struct Rim {
    /// Each rim key with its nodes (a surface edge's middle node included).
    rim: Vec<((usize, usize), Vec<usize>)>,
    inside: HashSet<(usize, usize)>,
}

impl Rim {
    fn new(facets: &[Cell]) -> Rim {
        let mut count: HashMap<(usize, usize), (usize, Vec<usize>)> = HashMap::new();
        for f in facets {
            if f.kind.dim() == 1 {
                // a curve: its corners count their facets, its middle nodes are inside
                for &n in &f.nodes[..2] {
                    count.entry((n, n)).or_insert((0, vec![n])).0 += 1;
                }
                for &n in &f.nodes[2..] {
                    count.entry((n, n)).or_insert((0, vec![n])).0 += 2;
                }
                continue;
            }
            for e in f.kind.facet_edges() {
                let (a, b) = (f.nodes[e[1]], f.nodes[e[2]]);
                let mut nodes = vec![a, b];
                if e[0] != usize::MAX {
                    nodes.push(f.nodes[e[0]]);
                }
                count.entry((a.min(b), a.max(b))).or_insert((0, nodes)).0 += 1;
            }
        }
        let mut rim = Vec::new();
        let mut inside = HashSet::new();
        for (key, (n, nodes)) in count {
            if n == 1 {
                rim.push((key, nodes));
            } else {
                inside.insert(key);
            }
        }
        rim.sort_unstable();
        Rim { rim, inside }
    }
}

/// The one body a group (one side of a `groups = [..]` contact) bounds.
fn single_body(b: &Builder, key: &str, name: &str, nb: &[Vec<usize>], bodies: &[Body], facets: &[Cell]) -> Result<usize, ModelError> {
    let mut found = None;
    for f in facets {
        let owners = facet_bodies(nb, f);
        match (owners.as_slice(), found) {
            ([one], None) => found = Some(*one),
            ([one], Some(prev)) if *one == prev => {}
            _ => {
                return Err(b.invalid(
                    key.to_string(),
                    format!(
                        "element {} of group \"{name}\" must bound exactly one body (it bounds {}); with groups = [..] each group is the face of one body",
                        f.tag,
                        if owners.is_empty() { "none".to_string() } else { owners.iter().map(|&o| format!("\"{}\"", bodies[o].name)).collect::<Vec<_>>().join(", ") }
                    ),
                ))
            }
        }
    }
    found.ok_or_else(|| b.invalid(key.to_string(), format!("group \"{name}\" has no elements")))
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
}
