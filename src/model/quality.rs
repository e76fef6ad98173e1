//! The mesh's cells and nodes checked beyond what the integration points
//! see: a cell folded between them, a sliver, and nodes that coincide
//! inside one body group.
//!
//! - **Folded** ([`folded`], an error): the Jacobian determinant must be
//!   positive over the whole cell, not only at the integration points. A
//!   quadratic tet10 whose corner nodes are swapped keeps det J > 0 at its
//!   four points while it is negative over part of the cell. det J is
//!   checked at every node of the cell (moved 1/1000 of the way to the
//!   centre, where a pyramid's apex is singular) and at its centre. Two
//!   corners at one point (an edge collapsed, det J zero there but
//!   positive 1/1000 inside) are refused first, naming the corners.
//! - **Slivers** ([`slivers`], a warning): the scaled Jacobian of the
//!   cell's corners (the linear cell), `q = det J / Π |∂x/∂ξ_j|`, is 1 for
//!   a right-angled corner and 0 for a flat one; below [`SLIVER`] the cell
//!   is nearly flat (a tetrahedron with a node 1e-9 off its neighbours'
//!   plane has q ~ 1e-8; a box stretched 1:1000 has q = 1).
//! - **Coincident nodes** ([`coincident`], a warning): two mesh nodes at
//!   the same place in the cells of one body group and in no contact pair
//!   leave the group cut there (volumes that were not fused). Where that
//!   leaves a block that nothing holds, [`lying_on`] finds what it lies on
//!   for the message that refuses it.

use std::collections::HashMap;

use super::errors::ModelError;
use super::mechanical::Model;
use crate::fem::element;
use crate::fem::shape::{self, linear_sibling, reference_centre, reference_nodes};

/// Below this scaled Jacobian a cell is a sliver.
pub const SLIVER: f64 = 1e-6;

/// The first cell (body order) whose Jacobian determinant is not positive
/// at one of its nodes or its centre; a body of several cells that are
/// all inverted at their centres is named as mirrored instead (a surface
/// whose curve loop runs clockwise: every cell's nodes do).
pub fn folded(model: &Model) -> Result<(), ModelError> {
    for body in &model.bodies {
        if let Some(e) = mirrored(model, body) {
            return Err(e);
        }
        for cell in &body.cells {
            let xs: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| model.coords[n]).collect();
            if let Some((a, b)) = collapsed(cell.kind, &xs) {
                let (body, tag, kind, at) = (body.label(), cell.tag, cell.kind.name().to_string(), xs[a]);
                return Err(ModelError::Collapsed { body, tag, kind, corners: (a + 1, b + 1), at });
            }
            let c = reference_centre(cell.kind);
            let inward = |xi: &[f64; 3]| -> [f64; 3] { std::array::from_fn(|d| xi[d] + 1e-3 * (c[d] - xi[d])) };
            let at = reference_nodes(cell.kind).iter().map(inward).chain([c]).enumerate();
            for (i, xi) in at {
                if let Err(e) = element::point(cell.kind, &xs, xi) {
                    let node = (i < cell.nodes.len()).then_some(i + 1);
                    return Err(ModelError::Folded {
                        body: body.label(),
                        tag: cell.tag,
                        kind: cell.kind.name().to_string(),
                        node,
                        det_j: e.det_j,
                    });
                }
            }
        }
    }
    Ok(())
}

/// Every cell of a body of several inverted at its centre (det J < 0):
/// the body's mesh is mirrored, not one cell folded.
fn mirrored(model: &Model, body: &super::body::Body) -> Option<ModelError> {
    let inverted = |cell: &crate::mesh::Cell| {
        let xs: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| model.coords[n]).collect();
        element::point(cell.kind, &xs, reference_centre(cell.kind)).is_err_and(|e| e.det_j < 0.0)
    };
    let first = body.cells.first()?;
    (body.cells.len() > 1 && body.cells.iter().all(inverted)).then(|| ModelError::Mirrored {
        body: body.label(),
        cells: body.cells.len(),
        dim: first.kind.dim(),
    })
}

/// Two corners (0-based, gmsh order) of a cell at the same point, within
/// 1e-12 of the cell's size: an edge collapsed (a quadrangle made a
/// triangle, a hexahedron a prism), where det J is zero but the folded
/// check, 1/1000 inside the corner, sees it positive.
fn collapsed(kind: crate::mesh::CellKind, xs: &[[f64; 3]]) -> Option<(usize, usize)> {
    let corners = &xs[..linear_sibling(kind).n_nodes().min(xs.len())];
    let size = (0..3)
        .map(|d| {
            let (lo, hi) =
                corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| (l.min(x[d]), h.max(x[d])));
            hi - lo
        })
        .fold(0.0, f64::max);
    (0..corners.len())
        .flat_map(|a| (a + 1..corners.len()).map(move |b| (a, b)))
        .find(|&(a, b)| element::norm(element::sub(corners[a], corners[b])) <= 1e-12 * size)
}

/// The least scaled Jacobian over the corners of a cell's linear sibling.
pub fn corner_quality(model: &Model, cell: &crate::mesh::Cell) -> f64 {
    let lin = linear_sibling(cell.kind);
    let nn = lin.n_nodes();
    let dim = lin.dim();
    let (mut n, mut dn) = (vec![0.0; nn], vec![[0.0; 3]; nn]);
    let c = reference_centre(lin);
    let mut worst = f64::INFINITY;
    for xi in reference_nodes(lin) {
        let xi: [f64; 3] = std::array::from_fn(|d| xi[d] + 1e-3 * (c[d] - xi[d]));
        shape::eval(lin, xi, &mut n, &mut dn);
        let o = model.coords[cell.nodes[0]];
        let mut cols = [[0.0; 3]; 3];
        for (&node, g) in cell.nodes.iter().zip(&dn) {
            let r = element::sub(model.coords[node], o);
            for j in 0..dim {
                for i in 0..3 {
                    cols[j][i] += r[i] * g[j];
                }
            }
        }
        let det = if dim == 2 {
            cols[0][0] * cols[1][1] - cols[0][1] * cols[1][0]
        } else {
            element::dot(cols[0], element::cross(cols[1], cols[2]))
        };
        let lengths: f64 = (0..dim).map(|j| element::norm(cols[j])).product();
        worst = worst.min(if lengths > 0.0 { det / lengths } else { 0.0 });
    }
    worst
}

/// Slivers: (body label, gmsh element tag, quality) of every cell below
/// [`SLIVER`], worst first.
pub fn slivers(model: &Model) -> Vec<(String, u64, f64)> {
    let mut out: Vec<(String, u64, f64)> = Vec::new();
    for body in &model.bodies {
        for cell in &body.cells {
            let q = corner_quality(model, cell);
            if q < SLIVER {
                out.push((body.label(), cell.tag, q));
            }
        }
    }
    out.sort_by(|a, b| a.2.total_cmp(&b.2));
    out
}

/// The error of a singular bonded interface, with what may leave bodies
/// free: the bodies (blocks) no support touches, and body groups whose
/// volumes are not fused.
pub fn why_not_held(model: &Model) -> ModelError {
    let nd = model.nd;
    let unsupported: Vec<String> = (model.bodies.iter())
        .filter(|b| {
            !b.cells.iter().flat_map(|c| &c.nodes).any(|&n| (0..nd).any(|c| model.prescribed[n * nd + c].is_some()))
        })
        .map(|b| b.label())
        .collect();
    ModelError::InterfaceNotHeld { unsupported, unfused: coincident(model) }
}

/// Nodes at one place in one body group: (group name, how many nodes have
/// a twin, the first place).
pub fn coincident(model: &Model) -> Vec<(String, usize, [f64; 3])> {
    let paired: std::collections::HashSet<(usize, usize)> =
        model.pairs.iter().map(|p| (p.k.min(p.l), p.k.max(p.l))).collect();
    let mut out = Vec::new();
    let groups = model.bodies.iter().map(|b| b.group).max().map_or(0, |g| g + 1);
    for g in 0..groups {
        let mut nodes: Vec<usize> = model
            .bodies
            .iter()
            .filter(|b| b.group == g)
            .flat_map(|b| b.cells.iter().flat_map(|c| c.nodes.iter().copied()))
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        let bins = Bins::new(&model.coords, &nodes);
        let mut twins = 0;
        let mut first: Option<[f64; 3]> = None;
        for &a in &nodes {
            let twin = bins
                .on(model.coords[a])
                .any(|b| b != a && model.mesh_node[a] != model.mesh_node[b] && !paired.contains(&(a.min(b), a.max(b))));
            if twin {
                twins += 1;
                first.get_or_insert(model.coords[a]);
            }
        }
        if let (Some(x), Some(body)) = (first, model.bodies.iter().find(|b| b.group == g)) {
            out.push((body.name.clone(), twins, x));
        }
    }
    out
}

/// The nodes `these` that lie on nodes of `others` (within 1e-12 of the
/// model's size; the two lists share no node): how many, and the first
/// such node with the node of `others` it lies on.
pub fn lying_on(coords: &[[f64; 3]], these: &[usize], others: &[usize]) -> Option<(usize, usize, usize)> {
    let bins = Bins::new(coords, others);
    let mut on = these.iter().filter_map(|&a| bins.on(coords[a]).next().map(|b| (a, b)));
    let (a, b) = on.next()?;
    Some((1 + on.count(), a, b))
}

/// Nodes binned by place, to find the nodes at a place: bins of the
/// tolerance's size, a node within it of a place is in that place's bin or
/// a neighbour's.
struct Bins<'a> {
    coords: &'a [[f64; 3]],
    tol: f64,
    bins: HashMap<[i64; 3], Vec<usize>>,
}

impl<'a> Bins<'a> {
    /// `nodes` binned, the tolerance 1e-12 of the largest coordinate.
    fn new(coords: &'a [[f64; 3]], nodes: &[usize]) -> Bins<'a> {
        let size = coords.iter().flat_map(|x| x.iter()).fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
        let mut bins = Bins { coords, tol: 1e-12 * size, bins: HashMap::new() };
        for &n in nodes {
            bins.bins.entry(bins.key(coords[n])).or_default().push(n);
        }
        bins
    }

    fn key(&self, x: [f64; 3]) -> [i64; 3] {
        std::array::from_fn(|d| (x[d] / self.tol.max(f64::MIN_POSITIVE)).floor() as i64)
    }

    /// The binned nodes within the tolerance of `x` (every component).
    fn on(&self, x: [f64; 3]) -> impl Iterator<Item = usize> + '_ {
        let k = self.key(x);
        (0..27)
            .flat_map(move |i| {
                self.bins.get(&[k[0] + i % 3 - 1, k[1] + (i / 3) % 3 - 1, k[2] + i / 9 - 1]).into_iter().flatten()
            })
            .copied()
            .filter(move |&b| (0..3).all(|d| (self.coords[b][d] - x[d]).abs() <= self.tol))
    }
}
