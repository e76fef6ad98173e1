//! The two cells of every facet of the shared contact groups (`group =
//! ".."`), and, when a facet does not lie between two cells, the message
//! that says what is wrong with its group: outer faces taken in beside the
//! shared ones, a face of no body or of several, or bodies meshed apart
//! (a group that touches one body, lying against another that does not
//! share its nodes). [`super::contacts`] splits the nodes once every facet
//! has its two cells.

use std::collections::{HashMap, HashSet};

use super::build_input::Builder;
use super::topology::Topology;
use super::{ContactGroups, ModelError};
use crate::fem::element;
use crate::mesh::Cell;

/// The two cells of every facet of the shared contact groups (`shared`:
/// each facet with its contact); a facet that bounds one cell, none or
/// more than two is an error naming its group.
pub(super) fn two_cells(
    b: &Builder,
    topo: &Topology,
    shared: &[(usize, &Cell)],
) -> Result<Vec<[usize; 2]>, ModelError> {
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
            (
                c,
                f.nodes[..f.kind.n_corners()]
                    .iter()
                    .map(|&n| element::norm(element::sub(coords[n], c)))
                    .fold(0.0, f64::max),
            )
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

/// The group name of contact `ci` (shared groups).
fn group_name(spec: &super::ModelSpec, ci: usize) -> &str {
    match &spec.contacts[ci].groups {
        ContactGroups::Shared(n) => n,
        ContactGroups::Pair(a, _) => a,
    }
}
