//! The two cells of every facet of the shared contact groups (`group =
//! ".."`), and, when a facet does not lie between two cells, the message
//! that says what is wrong with its group: outer faces taken in beside the
//! shared ones, a face of no body or of several, or bodies meshed apart
//! (a group that touches one body, lying against another that does not
//! share its nodes). [`super::contacts`] splits the nodes once every facet
//! has its two cells.

use std::collections::{HashMap, HashSet};

use super::build_input::Builder;
use super::errors::{ModelError, Near};
use super::spec::ContactGroups;
use super::topology::Topology;
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
            [] => return Err(ModelError::ContactOffBodies { key, tag: f.tag, group: name.to_string() }),
            many => return Err(ModelError::FaceOfMany { key, tag: f.tag, group: name.to_string(), count: many.len() }),
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
    let (group, tag, body, dim) = (name.to_string(), f.tag, own.clone(), f.kind.dim());
    if between > 0 {
        return ModelError::OuterFaces { key, group, lone: lone.len(), tag, body, between, dim };
    }
    let near = match against(b, topo, lone) {
        Some((i, dist, other)) => {
            Some(Box::new(Near::Against { tag: lone[i].0.tag, body: b.spec.bodies[other].group.clone(), dist }))
        }
        None => nearest(b, topo, centre(b, f), topo.body[cell])
            .map(|(dist, other)| Box::new(Near::Nearest { body: b.spec.bodies[other].group.clone(), dist })),
    };
    ModelError::OneSided { key, group, body, tag, lone: lone.len(), near, dim }
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
