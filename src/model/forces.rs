//! Force loads (`force`, `moment` and `point` of a `[[loads]]` entry):
//! a force F and a moment M acting at the point p, spread onto the nodes
//! of what they load — the nodes of a physical point group, the facets of
//! a boundary curve (2D) or surface (3D), or the cells of a body group —
//! so that the nodal forces carry exactly that resultant.
//!
//! Over the loaded measure w (one per node of a point group; area of the
//! facets or volume of the cells, times the thickness in plane analyses),
//! with W = ∫ dw, the centroid c and, with r = x - c, the inertia
//! J = ∫ (|r|² I - r rᵀ) dw, the load per unit of w is the rigid-body
//! field
//!
//! ```text
//! q(x) = F / W + ω × (x - c),      J ω = M + (p - c) × F
//! ```
//!
//! (Abaqus's distributing coupling, with uniform weights): ∫ q dw = F since
//! ∫ r dw = 0, and ∫ r × q dw = J ω is the moment about c, so F and M at p.
//! The nodal forces are `f_a = ∫ N_a q dw`, integrated with the facet's or
//! cell's shape functions (consistent: a quadratic facet's corners and
//! mid-side nodes get what its shape functions give them). In 2D ω turns
//! about z and J is `∫ |r|² dw`; a single point carries no moment, nor (in
//! 3D) a group of points on one line about that line: both are refused.

use super::body::Body;
use super::boundary::NodalLoad;
use super::build::{placed, placed_facets};
use super::build_input::Builder;
use super::contacts::Split;
use super::errors::ModelError;
use super::spec::{ForceLoad, LoadKind};
use super::topology::Topology;
use crate::fem::element::{self, measure};
use crate::fem::quadrature;
use crate::fem::vec3::{cross, dot, sub};
use crate::mesh::Group;

/// Every force load of the description spread onto the model's nodes, each
/// node with a cell that has it; `of_load`: the load case of every load.
pub(super) fn nodal_loads(
    b: &Builder,
    topo: &Topology,
    split: &Split,
    bodies: &[Body],
    of_load: &[usize],
) -> Result<Vec<NodalLoad>, ModelError> {
    let placed = placed(&split.block, bodies.len());
    let mut out = Vec::new();
    for (load, &case) in b.spec.loads.iter().zip(of_load) {
        let LoadKind::Force(force) = &load.kind else { continue };
        let key = format!("{}.group", load.key);
        let sd = b.spec.analysis.dim();
        let g = b.group(&key, &load.group, &[0, sd - 1, sd])?;
        let spots = match g.dim {
            0 => point_spots(b, topo, split, &key, g)?,
            d if d == sd => body_spots(b, split, bodies, &key, g)?,
            _ => facet_spots(b, topo, split, bodies, &key, g)?,
        };
        let spread = spread(&spots, force, sd == 2).map_err(|e| {
            let (key, group) = (format!("{}.moment", load.key), g.name.clone());
            match e {
                SpreadError::Empty => ModelError::NoExtent { key, group, dim: g.dim },
                SpreadError::NoLever if g.dim == 0 && spots.len() == 1 => ModelError::MomentOnPoint { key },
                SpreadError::NoLever => ModelError::MomentOnLine { key, group },
            }
        })?;
        // the cell each node is assembled with
        let mut cell_of: std::collections::HashMap<usize, (usize, usize)> = Default::default();
        for (c, cell) in split.cells.iter().enumerate() {
            for &n in &cell.nodes {
                cell_of.entry(n).or_insert(placed[c]);
            }
        }
        for (node, f) in spread {
            let (body, element) = cell_of[&node];
            out.push(NodalLoad { node, force: f, case, body, element });
        }
    }
    Ok(out)
}

/// The nodes of a point group, weight 1 each; a point on a contact (where
/// each body has its own copy of the node) or on no body is an error.
fn point_spots(b: &Builder, topo: &Topology, split: &Split, key: &str, g: &Group) -> Result<Vec<Spot>, ModelError> {
    let mut spots = Vec::new();
    for n in g.nodes() {
        let copies: Vec<usize> = (0..split.mesh_node.len()).filter(|&m| split.mesh_node[m] == n).collect();
        if topo.at(n).is_empty() {
            return Err(ModelError::PointOffBodies {
                key: key.to_string(),
                group: g.name.clone(),
                at: b.mesh.coords[n],
            });
        }
        if copies.len() != 1 {
            return Err(ModelError::PointOnContact {
                key: key.to_string(),
                group: g.name.clone(),
                at: b.mesh.coords[n],
            });
        }
        spots.push(Spot { w: 1.0, x: split.coords[copies[0]], nodes: vec![(copies[0], 1.0)] });
    }
    Ok(spots)
}

/// The quadrature points of a boundary group's facets, weights `w da`
/// (times the thickness or 2 pi r as every integral).
fn facet_spots(
    b: &Builder,
    topo: &Topology,
    split: &Split,
    bodies: &[Body],
    key: &str,
    g: &Group,
) -> Result<Vec<Spot>, ModelError> {
    let (analysis, thickness) = (b.spec.analysis, b.spec.thickness);
    let mut spots = Vec::new();
    for (cell, _, _, _) in placed_facets(topo, split, bodies, key, g, false)? {
        let xe: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| split.coords[n]).collect();
        for q in quadrature::rule(cell.kind, 2 * cell.kind.order() + 1) {
            let (n, _, da, x) = element::facet_point(cell.kind, &xe, q.xi);
            let nodes = cell.nodes.iter().copied().zip(n).collect();
            spots.push(Spot { w: q.w * da * measure(analysis, thickness, &x), x, nodes });
        }
    }
    Ok(spots)
}

/// The quadrature points of the cells of the body group `g` (a `[[bodies]]`
/// entry), weights `w det J` (times the thickness).
fn body_spots(b: &Builder, split: &Split, bodies: &[Body], key: &str, g: &Group) -> Result<Vec<Spot>, ModelError> {
    let (analysis, thickness) = (b.spec.analysis, b.spec.thickness);
    let mine: Vec<&Body> = bodies.iter().filter(|body| body.name == g.name).collect();
    if mine.is_empty() {
        return Err(ModelError::ForceOffBodies { key: key.to_string(), group: g.name.clone(), dim: g.dim });
    }
    let mut spots = Vec::new();
    for cell in mine.iter().flat_map(|body| &body.cells) {
        let xe: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| split.coords[n]).collect();
        for q in quadrature::rule(cell.kind, 2 * cell.kind.order() + 1) {
            let Ok(p) = element::point(cell.kind, &xe, q.xi) else { continue };
            let w = q.w * p.det_j * measure(analysis, thickness, &p.x);
            spots.push(Spot { w, x: p.x, nodes: cell.nodes.iter().copied().zip(p.n).collect() });
        }
    }
    Ok(spots)
}

/// A point of the loaded measure: its weight, position, and the model
/// nodes with their shape values there.
#[derive(Clone, Debug)]
pub(super) struct Spot {
    pub w: f64,
    pub x: [f64; 3],
    pub nodes: Vec<(usize, f64)>,
}

/// Why a force load cannot be spread.
#[derive(Debug, PartialEq)]
pub(super) enum SpreadError {
    /// The measure is zero (no spots, or all of zero weight).
    Empty,
    /// The moment has a component the spots cannot carry (a single point;
    /// points on a line, about that line).
    NoLever,
}

/// The nodal forces (summed per node, in order of first appearance) that
/// carry `load` over `spots`; `plane`: a 2D analysis (ω about z only).
pub(super) fn spread(spots: &[Spot], load: &ForceLoad, plane: bool) -> Result<Vec<(usize, [f64; 3])>, SpreadError> {
    let total: f64 = spots.iter().map(|s| s.w).sum();
    if spots.is_empty() || total <= 0.0 {
        return Err(SpreadError::Empty);
    }
    // the centroid, relative to the first spot (map coordinates stay exact)
    let o = spots[0].x;
    let mut c = [0.0; 3];
    for s in spots {
        let r = sub(s.x, o);
        (0..3).for_each(|i| c[i] += s.w * r[i] / total);
    }
    let c = [o[0] + c[0], o[1] + c[1], o[2] + c[2]];
    let p = load.point.unwrap_or(c);
    let m = cross(sub(p, c), load.force);
    let m: [f64; 3] = std::array::from_fn(|i| load.moment[i] + m[i]);
    let omega = rotation(spots, c, m, plane)?;
    let mut out: Vec<(usize, [f64; 3])> = Vec::new();
    let mut at: std::collections::HashMap<usize, usize> = Default::default();
    for s in spots {
        let turn = cross(omega, sub(s.x, c));
        let q: [f64; 3] = std::array::from_fn(|i| load.force[i] / total + turn[i]);
        for &(node, n) in &s.nodes {
            let k = *at.entry(node).or_insert_with(|| {
                out.push((node, [0.0; 3]));
                out.len() - 1
            });
            (0..3).for_each(|i| out[k].1[i] += s.w * n * q[i]);
        }
    }
    Ok(out)
}

/// ω with J ω = m about the centroid c; an error when m needs a rotation
/// the spots cannot carry.
fn rotation(spots: &[Spot], c: [f64; 3], m: [f64; 3], plane: bool) -> Result<[f64; 3], SpreadError> {
    let mut j = [[0.0; 3]; 3];
    let mut size: f64 = 0.0;
    for s in spots {
        let r = sub(s.x, c);
        let rr = dot(r, r);
        size = size.max(rr);
        for a in 0..3 {
            for b in 0..3 {
                j[a][b] += s.w * (if a == b { rr } else { 0.0 } - r[a] * r[b]);
            }
        }
    }
    let scale = m.iter().map(|v| v.abs()).fold(0.0, f64::max);
    if scale == 0.0 {
        return Ok([0.0; 3]);
    }
    let total: f64 = spots.iter().map(|s| s.w).sum();
    // a lever below 1e-12 of the group's size is none
    let tiny = 1e-24 * total * size;
    if plane {
        return if j[2][2] > tiny { Ok([0.0, 0.0, m[2] / j[2][2]]) } else { Err(SpreadError::NoLever) };
    }
    solve_sym3(j, m, tiny)
}

/// x with J x = m for a symmetric positive semi-definite J, through its
/// eigenvectors (Jacobi rotations): components of m along a direction of
/// J's null space (eigenvalue <= tiny) are an error.
fn solve_sym3(mut a: [[f64; 3]; 3], m: [f64; 3], tiny: f64) -> Result<[f64; 3], SpreadError> {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        if off <= 1e-15 * (a[0][0].abs() + a[1][1].abs() + a[2][2].abs()) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = 0.5 * (a[q][q] - a[p][p]) / a[p][q];
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let (cs, sn) = (1.0 / (t * t + 1.0).sqrt(), t / (t * t + 1.0).sqrt());
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = cs * akp - sn * akq;
                a[k][q] = sn * akp + cs * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = cs * apk - sn * aqk;
                a[q][k] = sn * apk + cs * aqk;
            }
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = cs * vp - sn * vq;
                row[q] = sn * vp + cs * vq;
            }
        }
    }
    let scale = m.iter().map(|x| x.abs()).fold(0.0, f64::max);
    let mut x = [0.0; 3];
    for e in 0..3 {
        let dir = [v[0][e], v[1][e], v[2][e]];
        let along = dot(dir, m);
        if a[e][e] <= tiny {
            if along.abs() > 1e-9 * scale {
                return Err(SpreadError::NoLever);
            }
            continue;
        }
        (0..3).for_each(|i| x[i] += dir[i] * along / a[e][e]);
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(w: f64, x: [f64; 3], node: usize) -> Spot {
        Spot { w, x, nodes: vec![(node, 1.0)] }
    }

    fn resultant(f: &[(usize, [f64; 3])], xs: &[[f64; 3]], about: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let mut force = [0.0; 3];
        let mut moment = [0.0; 3];
        for &(n, v) in f {
            let m = cross(sub(xs[n], about), v);
            (0..3).for_each(|i| {
                force[i] += v[i];
                moment[i] += m[i];
            });
        }
        (force, moment)
    }

    /// Three unequal points in 3D, a force off their centroid and a
    /// moment: the nodal forces sum to F, and their moment about p is M.
    #[test]
    fn nodal_forces_carry_the_force_and_moment_at_the_point() {
        let xs = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.5, 1.5, 0.3], [1.0, 1.0, -2.0]];
        let spots: Vec<Spot> = xs.iter().enumerate().map(|(i, &x)| spot(1.0 + i as f64, x, i)).collect();
        let load = ForceLoad { force: [1.0, -2.0, 3.0], moment: [0.5, 0.25, -1.0], point: Some([3.0, 1.0, 1.0]) };
        let f = spread(&spots, &load, false).expect("spread");
        let (force, moment) = resultant(&f, &xs, [3.0, 1.0, 1.0]);
        for i in 0..3 {
            assert!((force[i] - load.force[i]).abs() < 1e-13, "{force:?}");
            assert!((moment[i] - load.moment[i]).abs() < 1e-12, "{moment:?}");
        }
    }

    /// 2D: a moment about z on two points; a single point refuses a moment
    /// but takes a force; collinear points in 3D refuse a moment about
    /// their line and take one across it.
    #[test]
    fn what_cannot_carry_a_moment_is_refused() {
        let two = [spot(1.0, [0.0, 0.0, 0.0], 0), spot(1.0, [2.0, 0.0, 0.0], 1)];
        let load = ForceLoad { force: [0.0, -1.0, 0.0], moment: [0.0, 0.0, 4.0], point: None };
        let f = spread(&two, &load, true).expect("spread");
        // M = 4 about the middle: +-2 on arms of 1, plus half the force each
        assert!((f[0].1[1] - (-0.5 - 2.0)).abs() < 1e-14 && (f[1].1[1] - (-0.5 + 2.0)).abs() < 1e-14, "{f:?}");
        let one = [spot(1.0, [1.0, 1.0, 0.0], 0)];
        assert_eq!(spread(&one, &load, true), Err(SpreadError::NoLever));
        let push = ForceLoad { moment: [0.0; 3], ..load };
        assert_eq!(spread(&one, &push, true).expect("a point force"), vec![(0, [0.0, -1.0, 0.0])]);
        let about_line = ForceLoad { moment: [1.0, 0.0, 0.0], ..push };
        assert_eq!(spread(&two, &about_line, false), Err(SpreadError::NoLever));
        let across = ForceLoad { moment: [0.0, 0.0, 4.0], ..push };
        let f = spread(&two, &across, false).expect("across the line");
        let (_, m) = resultant(&f, &[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], [1.0, 0.0, 0.0]);
        assert!((m[2] - 4.0).abs() < 1e-14 && m[0].abs() < 1e-14, "{m:?}");
        assert_eq!(spread(&[], &push, true), Err(SpreadError::Empty));
    }
}
