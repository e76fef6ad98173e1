//! The forces at one cut ([`super::Plane`]): the kernel of section forces.
//!
//! The cells the cut passes through are split by it at their edges: with
//! the cut's cells on one side, the nodes shared by cells behind and cells
//! ahead form an edge cut, and the force and moment on the part behind
//! from the part ahead are
//!
//! ```text
//! F = - Σ_cells Σ_a φ_a r_a        M = - Σ_cells Σ_a φ_a (x_a - c) × r_a
//! ```
//!
//! with φ = 1 on the nodes of cells behind only, 1/2 on the shared nodes,
//! 0 ahead (the virtual work of moving the part behind rigidly). A cell
//! whose nodes all have one weight adds nothing (its forces sum to zero and
//! have no moment), and Σ_cells r_a is the load at node a, so F and M
//! balance the loads behind the edge cut (half of those on it) to
//! round-off. A cut through cells lies between two edge cuts, one with the
//! cells it passes through ahead, one with them behind: its N, V and M are
//! interpolated between theirs by position (angle round a ring), exact for
//! forces varying linearly along the member. A cut along cell edges is its
//! own edge cut.
//!
//! Where material lies on one side only (a cut along an end face) the
//! nodes on the cut carry the section: F = ∓ Σ r_a over them (− with the
//! body ahead); on a symmetry plane (those nodes held along n alone) only
//! their components along n, the rest being shared with the mirror half.

use super::station::{Sides, Station};
use crate::fem::vec3::{cross, dot, sub};
use crate::model::Model;
use crate::recover::forces::cell_internal;

/// One cut: origin, axes, which cells it considers (a half-plane window
/// on their centres: `(x - o)·dir` within `lo..=hi`), whether it is a
/// ring's ray from `o` (positions round it by angle, the reference point
/// by radius), and where it lies along the section.
pub(super) struct Plane {
    pub(super) o: [f64; 3],
    pub(super) frame: [[f64; 3]; 3],
    pub(super) window: Option<([f64; 3], f64, f64)>,
    pub(super) ring: bool,
    pub(super) position: f64,
}

/// A cell the cut meets: (body, cell, the least and largest distance of
/// its nodes from the cut).
type Crossed = (usize, usize, f64, f64);

/// An edge cut's position along the member (distance, or angle round a
/// ring) and its resultants in its own axes: N, V, V3, T, M2, M.
struct Edge {
    position: f64,
    local: [f64; 6],
}

/// The forces at one cut, None where it meets no cell.
pub(super) fn station(model: &Model, u: &[f64], cells: &[(usize, usize)], p: &Plane) -> Option<Station> {
    let (crossed, w) = crossed(model, cells, p);
    if crossed.is_empty() || w <= 0.0 {
        return None;
    }
    let (at, depth) = reference(model, p, &crossed);
    // material behind the cut and ahead of it (one side only: an end face)
    let behind = crossed.iter().any(|&(_, _, lo, _)| lo < -1e-6 * w);
    let ahead = crossed.iter().any(|&(_, _, _, hi)| hi > 1e-6 * w);
    let position = p.position;
    if !(behind && ahead) {
        let (force, moment, sides) = one_sided(model, u, p, at, &crossed, behind, w);
        return Some(Station { position, at, frame: p.frame, force, moment, depth, sides });
    }
    let through: Vec<(usize, usize)> =
        (crossed.iter()).filter(|c| c.2 < -1e-6 * w && c.3 > 1e-6 * w).map(|c| (c.0, c.1)).collect();
    let near: Vec<(usize, usize, f64)> = cells
        .iter()
        .filter_map(|&(b, c)| {
            let xs = coords(model, b, c);
            let (lo, hi, s) = extent(p, &xs);
            (lo < w * (1.0 + 1e-6) && hi > -w * (1.0 + 1e-6) && in_window(p, &xs)).then_some((b, c, s))
        })
        .collect();
    let local = match edge_cut(model, u, p, at, &near, &through, false) {
        Some(a) if !through.is_empty() => {
            let b = edge_cut(model, u, p, at, &near, &through, true)?;
            let t = if (b.position - a.position).abs() > 0.0 { -a.position / (b.position - a.position) } else { 0.5 };
            std::array::from_fn(|i| (1.0 - t) * a.local[i] + t * b.local[i])
        }
        Some(a) => a.local,
        None => return None,
    };
    let [n, e2, e3] = p.frame;
    let force = std::array::from_fn(|i| local[0] * n[i] - local[1] * e2[i] - local[2] * e3[i]);
    let moment = std::array::from_fn(|i| local[3] * n[i] + local[4] * e2[i] + local[5] * e3[i]);
    Some(Station { position, at, frame: p.frame, force, moment, depth, sides: Sides::Both })
}

fn coords(model: &Model, b: usize, c: usize) -> Vec<[f64; 3]> {
    model.bodies[b].cells[c].nodes.iter().map(|&k| model.coords[k]).collect()
}

/// The least and largest distance of points from the cut, and their mean's.
fn extent(p: &Plane, xs: &[[f64; 3]]) -> (f64, f64, f64) {
    let n = p.frame[0];
    let (lo, hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
        let s = dot(sub(x, p.o), n);
        (lo.min(s), hi.max(s))
    });
    (lo, hi, dot(sub(centre(xs), p.o), n))
}

/// Whether the cell's centre lies in the cut's window.
fn in_window(p: &Plane, xs: &[[f64; 3]]) -> bool {
    p.window.is_none_or(|(dir, lo, hi)| {
        let t = dot(sub(centre(xs), p.o), dir);
        t >= lo && t <= hi
    })
}

/// The cells the cut meets (in its window), and its width: their largest
/// extent across it. A cell whose face lies on the cut meets it (the
/// nodes' distances within 1e-6 of its extent: gmsh's nodes on a circle
/// sit 1e-10 off it).
fn crossed(model: &Model, cells: &[(usize, usize)], p: &Plane) -> (Vec<Crossed>, f64) {
    let mut out = Vec::new();
    let mut w: f64 = 0.0;
    for &(b, c) in cells {
        let xs = coords(model, b, c);
        let (lo, hi, _) = extent(p, &xs);
        let tol = 1e-6 * (hi - lo);
        if lo <= tol && hi >= -tol && in_window(p, &xs) {
            out.push((b, c, lo, hi));
            w = w.max(hi - lo);
        }
    }
    (out, w)
}

/// The edge cut with the cells the cut passes through (`through`) behind
/// it or ahead of it, the others by the side of their centre (`near`: the
/// cells within one width of the cut, with their centre's distance).
fn edge_cut(
    model: &Model,
    u: &[f64],
    p: &Plane,
    at: [f64; 3],
    near: &[(usize, usize, f64)],
    through: &[(usize, usize)],
    through_behind: bool,
) -> Option<Edge> {
    use std::collections::HashMap;
    let behind = |b: usize, c: usize, s: f64| if through.contains(&(b, c)) { through_behind } else { s < 0.0 };
    // each node: (in a cell behind, in a cell ahead)
    let mut sides: HashMap<usize, (bool, bool)> = HashMap::new();
    for &(b, c, s) in near {
        let back = behind(b, c, s);
        for &k in &model.bodies[b].cells[c].nodes {
            let e = sides.entry(k).or_default();
            if back {
                e.0 = true;
            } else {
                e.1 = true;
            }
        }
    }
    let shared: Vec<usize> = sides.iter().filter(|(_, &(b, a))| b && a).map(|(&k, _)| k).collect();
    if shared.is_empty() {
        return None;
    }
    let (position, frame, at) = edge_frame(model, p, at, &shared);
    let weight = |k: usize| match sides[&k] {
        (true, true) => 0.5,
        (true, false) => 1.0,
        _ => 0.0,
    };
    let (mut force, mut moment) = ([0.0; 3], [0.0; 3]);
    for &(b, c, _) in near {
        let cell = &model.bodies[b].cells[c];
        let phis: Vec<f64> = cell.nodes.iter().map(|&k| weight(k)).collect();
        if phis.iter().all(|&f| f == phis[0]) {
            continue;
        }
        add_forces(model, u, (b, c), &phis, at, None, &mut force, &mut moment);
    }
    let [n, e2, e3] = frame;
    let local = [dot(force, n), -dot(force, e2), -dot(force, e3), dot(moment, n), dot(moment, e2), dot(moment, e3)];
    Some(Edge { position, local })
}

/// Adds `-φ_a r_a` and its moment about `at` over the cell's nodes; with
/// `along`, only the components of r_a along it.
#[allow(clippy::too_many_arguments)] // the sums it adds to are the caller's
fn add_forces(
    model: &Model,
    u: &[f64],
    (b, c): (usize, usize),
    phis: &[f64],
    at: [f64; 3],
    along: Option<[f64; 3]>,
    force: &mut [f64; 3],
    moment: &mut [f64; 3],
) {
    let body = &model.bodies[b];
    let cell = &body.cells[c];
    let r = cell_internal(model, body, cell, u);
    let nd = model.nd;
    for (a, (&k, &phi)) in cell.nodes.iter().zip(phis).enumerate() {
        if phi == 0.0 {
            continue;
        }
        let mut ra: [f64; 3] = std::array::from_fn(|i| if i < nd { r[a * nd + i] } else { 0.0 });
        if let Some(n) = along {
            let f = dot(ra, n);
            ra = n.map(|v| v * f);
        }
        let m = cross(sub(model.coords[k], at), ra);
        for i in 0..3 {
            force[i] -= phi * ra[i];
            moment[i] -= phi * m[i];
        }
    }
}

/// An edge cut's position (the mean distance of its nodes from the cut;
/// round a ring, their mean angle from it), its axes and its reference
/// point (the cut's, moved there along the member or turned round the ring).
fn edge_frame(model: &Model, p: &Plane, at: [f64; 3], nodes: &[usize]) -> (f64, [[f64; 3]; 3], [f64; 3]) {
    let [n, e2, e3] = p.frame;
    let mean = |f: &dyn Fn([f64; 3]) -> f64| nodes.iter().map(|&k| f(sub(model.coords[k], p.o))).sum::<f64>();
    let count = nodes.len() as f64;
    if !p.ring {
        let s = mean(&|r| dot(r, n)) / count;
        return (s, p.frame, std::array::from_fn(|i| at[i] + s * n[i]));
    }
    // round the ring: e_r = -e2, n = e3 x e_r; turned by the mean angle
    let angle = mean(&|r| dot(r, n).atan2(-dot(r, e2))) / count;
    let (cs, sn) = (angle.cos(), angle.sin());
    let e_r: [f64; 3] = std::array::from_fn(|i| -cs * e2[i] + sn * n[i]);
    let n2: [f64; 3] = std::array::from_fn(|i| cs * n[i] + sn * e2[i]);
    let r = sub(at, p.o);
    let (radius, axial) = (-dot(r, e2), dot(r, e3));
    let at2 = std::array::from_fn(|i| p.o[i] + radius * e_r[i] + axial * e3[i]);
    (angle, [n2, e_r.map(|v| -v), e3], at2)
}

/// A cut with material on one side only: the forces of its own nodes
/// (`behind`: the material is behind it), along n alone on a symmetry plane.
fn one_sided(
    model: &Model,
    u: &[f64],
    p: &Plane,
    at: [f64; 3],
    crossed: &[Crossed],
    behind: bool,
    w: f64,
) -> ([f64; 3], [f64; 3], Sides) {
    let n = p.frame[0];
    let sign = if behind { -1.0 } else { 1.0 };
    let weights: Vec<(usize, usize, Vec<f64>)> = crossed
        .iter()
        .map(|&(b, c, _, _)| {
            let xs = coords(model, b, c);
            let phis = xs.iter().map(|&x| sign * f64::from(dot(sub(x, p.o), n).abs() <= 1e-6 * w)).collect();
            (b, c, phis)
        })
        .collect();
    let symmetry = symmetric(model, &weights, n);
    let (mut force, mut moment) = ([0.0; 3], [0.0; 3]);
    for (b, c, phis) in &weights {
        if phis.iter().any(|&f| f != 0.0) {
            let along = symmetry.then_some(n);
            add_forces(model, u, (*b, *c), phis, at, along, &mut force, &mut moment);
        }
    }
    (force, moment, if symmetry { Sides::Symmetry } else { Sides::End })
}

/// Whether a one-sided cut is a symmetry plane: every node on it (weight
/// not 0) is held along the global axis of n and free across it.
fn symmetric(model: &Model, band: &[(usize, usize, Vec<f64>)], n: [f64; 3]) -> bool {
    let nd = model.nd;
    let Some(along) = (0..nd).find(|&c| n[c].abs() > 1.0 - 1e-9) else { return false };
    let mut any = false;
    for (b, c, phis) in band {
        for (&k, &phi) in model.bodies[*b].cells[*c].nodes.iter().zip(phis) {
            if phi == 0.0 {
                continue;
            }
            any = true;
            let held = |c: usize| model.prescribed[k * nd + c].is_some();
            if !held(along) || (0..nd).any(|c| c != along && held(c)) {
                return false;
            }
        }
    }
    any
}

/// The mean of points.
fn centre(xs: &[[f64; 3]]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for x in xs {
        (0..3).for_each(|i| c[i] += x[i] / xs.len() as f64);
    }
    c
}

/// Where the cut's moments are taken, and its depth: the middle of the
/// cut's extent across the member (along e2, and e3 in 3D; a ring: by
/// radius on the cut's ray), where the straight lines between the crossed
/// cells' corners pass through the cut (a ring's radius interpolated
/// between corners of one radius is that radius).
fn reference(model: &Model, p: &Plane, crossed: &[Crossed]) -> ([f64; 3], f64) {
    let [n, e2, e3] = p.frame;
    let gauge = |x: [f64; 3]| -> [f64; 2] {
        let r = sub(x, p.o);
        let a = if p.ring {
            let along = dot(r, e3);
            let rr: [f64; 3] = std::array::from_fn(|i| r[i] - along * e3[i]);
            -dot(rr, rr).sqrt()
        } else {
            dot(r, e2)
        };
        [a, dot(r, e3)]
    };
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for &(b, c, clo, chi) in crossed {
        let cell = &model.bodies[b].cells[c];
        let xs: Vec<[f64; 3]> = cell.nodes[..cell.kind.n_corners()].iter().map(|&k| model.coords[k]).collect();
        let tol = 1e-6 * (chi - clo);
        let s: Vec<f64> = xs.iter().map(|&x| dot(sub(x, p.o), n)).collect();
        for i in 0..xs.len() {
            for j in i..xs.len() {
                let (gi, gj) = (gauge(xs[i]), gauge(xs[j]));
                let g = if s[i].abs() <= tol {
                    gi
                } else if s[j].abs() <= tol || (s[i] < 0.0) == (s[j] < 0.0) {
                    continue;
                } else {
                    let t = s[i] / (s[i] - s[j]);
                    [gi[0] + t * (gj[0] - gi[0]), gi[1] + t * (gj[1] - gi[1])]
                };
                lo = [lo[0].min(g[0]), lo[1].min(g[1])];
                hi = [hi[0].max(g[0]), hi[1].max(g[1])];
            }
        }
    }
    let (m2, m3) = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]));
    let m3 = if model.analysis.dim() == 2 || !m3.is_finite() { 0.0 } else { m3 };
    let m2 = if m2.is_finite() { m2 } else { 0.0 };
    (std::array::from_fn(|i| p.o[i] + m2 * e2[i] + m3 * e3[i]), (hi[0] - lo[0]).max(0.0))
}
