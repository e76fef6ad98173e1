//! A 3D contact interface cut into the sheets a person reads one by one,
//! each laid flat: planes seen square on, cylinder-like surfaces (a tunnel
//! lining, a shaft) unrolled, other curved surfaces seen along their mean
//! normal. A contact group may hold a whole joint set (many parallel planes
//! between many blocks) or a crease (a wedge in a V-groove), so the facets
//! are sorted into sheets by their geometry alone:
//!
//! 1. facets that share an edge and whose normals differ by less than 35
//!    degrees are one smooth piece (a crease or a crossing joint separates
//!    pieces);
//! 2. a piece whose facet normals all lie within 3 degrees of their mean is
//!    flat; flat pieces with the same normal (up to its sign: body I may lie
//!    on either side) and the same offset `n . x` are one plane, so a joint
//!    plane cut by crossing joints into many faces is one sheet;
//! 3. a piece whose normals are all perpendicular to one axis `a` (the
//!    smallest eigenvector of `sum A n n^T`, its eigenvalue below 3 % of
//!    the sum) is a cylinder: the centre is a least-squares circle (Kasa)
//!    through its nodes projected along `a`, and a point is drawn at `(R
//!    theta, a . x)`, theta the angle about the axis from the crown (up,
//!    projected across the axis) towards `a x up`. A ring is cut at the
//!    invert; an arc in the middle of its largest gap;
//! 4. anything else is seen along its mean normal (or from above when it
//!    has none).
//!
//! Planes come first, by set (normals within 10 degrees) in the order the
//! facets first meet them, and by offset within a set.

use super::label_numbers::num;
use super::surface::{facet_patches, Patch};
use super::view::model_up;
use crate::fem::vec3::{cross, dot, normalized, sub};
use crate::mesh::Cell;
use crate::model::topology::UnionFind;
use crate::model::Model;

/// How a sheet is laid flat.
#[derive(Clone, Debug)]
pub(super) enum Shape {
    /// A plane seen from `e` (unit, towards the viewer): a point x is drawn
    /// at `(r . x, v . x)`. `offset = n . x` on the plane, n its normal
    /// with the largest component positive.
    Plane { e: [f64; 3], r: [f64; 3], v: [f64; 3], n: [f64; 3], offset: f64 },
    /// A cylinder-like surface, unrolled: axis `a` through `centre`, radius
    /// `radius`, angle 0 along `zero` and 90 degrees along `side = a x zero`;
    /// angles run over `[cut, cut + 2 pi)`. `crown`: zero is up (a tunnel),
    /// else a world axis (a shaft). `ring`: a whole turn (no gap).
    Cylinder {
        a: [f64; 3],
        centre: [f64; 3],
        radius: f64,
        zero: [f64; 3],
        side: [f64; 3],
        cut: f64,
        crown: bool,
        ring: bool,
    },
    /// A curved surface seen along `e`, like a plane.
    Curved { e: [f64; 3], r: [f64; 3], v: [f64; 3] },
}

/// A part of one interface laid flat.
#[derive(Clone, Debug)]
pub(super) struct Sheet {
    pub(super) interface: usize,
    /// Indices into the interface's facets.
    pub(super) facets: Vec<usize>,
    pub(super) shape: Shape,
    /// The set of parallel planes it belongs to (planes only; 0 otherwise),
    /// numbered from 0 per interface.
    pub(super) set: usize,
}

/// A sheet laid flat: points in the plane of the picture, each a model
/// node (a node on an unrolled surface's seam has one point on each side),
/// and the facets as patches over the points.
pub(super) struct Flat {
    pub(super) points: Vec<[f64; 2]>,
    pub(super) node: Vec<usize>,
    pub(super) patches: Vec<Patch>,
    /// The drawn box: the nodes' range (an unrolled ring's full turn).
    pub(super) lo: [f64; 2],
    pub(super) hi: [f64; 2],
}

impl Sheet {
    /// The sheet's model nodes, ascending.
    pub(super) fn nodes(&self, model: &Model) -> Vec<usize> {
        let iface = &model.interfaces[self.interface];
        let mut n: Vec<usize> = self.facets.iter().flat_map(|&f| iface.facets[f].nodes.iter().copied()).collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    /// Where a point lands on the flat sheet (an unrolled surface's angle
    /// in `[cut, cut + 2 pi)` times its radius).
    pub(super) fn at(&self, x: [f64; 3]) -> [f64; 2] {
        match &self.shape {
            Shape::Plane { r, v, .. } | Shape::Curved { r, v, .. } => [dot(x, *r), dot(x, *v)],
            Shape::Cylinder { a, radius, cut, .. } => {
                [radius * (cut + (self.angle(x) - cut).rem_euclid(std::f64::consts::TAU)), dot(x, *a)]
            }
        }
    }

    /// The world directions of the flat sheet's x and y at point x: (r, v)
    /// of a plane; along the angle and the axis of an unrolled surface.
    pub(super) fn directions(&self, x: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        match &self.shape {
            Shape::Plane { r, v, .. } | Shape::Curved { r, v, .. } => (*r, *v),
            Shape::Cylinder { a, zero, side, .. } => {
                let t = self.angle(x);
                (std::array::from_fn(|i| t.cos() * side[i] - t.sin() * zero[i]), *a)
            }
        }
    }

    /// The angle of x about a cylinder's axis from its zero, in (-pi, pi]
    /// (0 for other shapes).
    pub(super) fn angle(&self, x: [f64; 3]) -> f64 {
        match &self.shape {
            Shape::Cylinder { centre, zero, side, .. } => {
                let q = sub(x, *centre);
                dot(q, *side).atan2(dot(q, *zero))
            }
            _ => 0.0,
        }
    }

    /// The direction the viewer looks from (planes and curved sheets; an
    /// unrolled one is seen from inside its axis, as None).
    pub(super) fn eye(&self) -> Option<[f64; 3]> {
        match &self.shape {
            Shape::Plane { e, .. } | Shape::Curved { e, .. } => Some(*e),
            Shape::Cylinder { .. } => None,
        }
    }

    /// The sheet laid flat. Facets of an unrolled surface that cross its
    /// seam are drawn on both sides of it (the picture clips them at its
    /// edge); outlines are those of the surface, not of the copies.
    pub(super) fn flat(&self, model: &Model) -> Flat {
        let iface = &model.interfaces[self.interface];
        let cells: Vec<Cell> = self.facets.iter().map(|&f| iface.facets[f].clone()).collect();
        let patches = facet_patches(&cells, &model.coords);
        let mut points: Vec<[f64; 2]> = Vec::new();
        let mut node: Vec<usize> = Vec::new();
        let mut index: std::collections::HashMap<(usize, i8), usize> = std::collections::HashMap::new();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &k in &self.nodes(model) {
            let q = self.at(model.coords[k]);
            for d in 0..2 {
                lo[d] = lo[d].min(q[d]);
                hi[d] = hi[d].max(q[d]);
            }
        }
        // a ring is drawn over its whole turn
        if let Shape::Cylinder { ring: true, cut, radius, .. } = self.shape {
            lo[0] = radius * cut;
            hi[0] = radius * (cut + std::f64::consts::TAU);
        }
        let mut out = Vec::with_capacity(patches.len());
        let tau = std::f64::consts::TAU;
        let mut point = |k: usize, turn: i8, points: &mut Vec<[f64; 2]>, node: &mut Vec<usize>| -> usize {
            *index.entry((k, turn)).or_insert_with(|| {
                let q = self.at(model.coords[k]);
                let width = match &self.shape {
                    Shape::Cylinder { radius, .. } => radius * tau,
                    _ => 0.0,
                };
                points.push([q[0] + turn as f64 * width, q[1]]);
                node.push(k);
                points.len() - 1
            })
        };
        for p in patches {
            let ks = p.nodes().to_vec();
            // turns that bring each node within half a turn of the first
            let turns: Vec<i8> = match &self.shape {
                Shape::Cylinder { radius, .. } => {
                    let x0 = self.at(model.coords[ks[0]])[0];
                    ks.iter().map(|&k| ((x0 - self.at(model.coords[k])[0]) / (radius * tau)).round() as i8).collect()
                }
                _ => vec![0; ks.len()],
            };
            let (tmin, tmax) = (*turns.iter().min().unwrap_or(&0), *turns.iter().max().unwrap_or(&0));
            // one copy as it comes, another a turn back when it crosses the seam
            for shift in std::iter::once(0).chain((tmin != tmax).then_some(-(tmin + tmax))) {
                let mut q = p;
                for (i, &k) in ks.iter().enumerate() {
                    q.nodes[i] = point(k, turns[i] + shift, &mut points, &mut node);
                }
                out.push(q);
            }
        }
        Flat { points, node, patches: out, lo, hi }
    }

    /// How the sheet is named in a title: "z = 2.5", "n . x = 3.2 with n =
    /// (..)" (with dip and dip direction when up is z), "cylinder r = 5.06
    /// about an axis along y", or "curved surface".
    pub(super) fn describe(&self, model: &Model) -> String {
        match &self.shape {
            Shape::Plane { n, offset, .. } => {
                let axis = (0..3).find(|&a| (n[a].abs() - 1.0).abs() < 1e-9);
                let mut s = match axis {
                    Some(a) => format!("the plane {} = {}", ["x", "y", "z"][a], num(offset * n[a].signum())),
                    None => format!("the plane n . x = {} with n = {}", num(*offset), direction(*n, false)),
                };
                let up = model_up(model);
                if up == [0.0, 0.0, 1.0] && axis.is_none() {
                    let (dip, dir) = dip(*n);
                    s += &format!(", dip {dip:.0}°, dip direction {dir:03.0}°");
                }
                s
            }
            Shape::Cylinder { a, radius, .. } => {
                format!("the cylinder r = {} about an axis along {}", num(*radius), direction(*a, false))
            }
            Shape::Curved { e, .. } => format!("a curved surface seen from {}", direction(*e, true)),
        }
    }
}

impl Sheet {
    /// A short name for captions: "z = 2.5", "dip 45°/090°" (z up) or
    /// "n = (..)", "r = 5.06 about y", "curved".
    pub(super) fn short(&self, model: &Model) -> String {
        match &self.shape {
            Shape::Plane { n, offset, .. } => match (0..3).find(|&a| (n[a].abs() - 1.0).abs() < 1e-9) {
                Some(a) => format!("{} = {}", ["x", "y", "z"][a], num(offset * n[a].signum())),
                None if model_up(model) == [0.0, 0.0, 1.0] => {
                    let (d, dir) = dip(*n);
                    format!("dip {d:.0}°/{dir:03.0}°, n . x = {}", num(*offset))
                }
                None => format!("n = {}, n . x = {}", direction(*n, false), num(*offset)),
            },
            Shape::Cylinder { a, radius, .. } => format!("r = {} about {}", num(*radius), direction(*a, false)),
            Shape::Curved { .. } => "curved".to_string(),
        }
    }
}

/// Dip (degrees from horizontal) and dip direction (degrees clockwise from
/// +y, north) of a plane with normal n in a model with z up.
pub(super) fn dip(n: [f64; 3]) -> (f64, f64) {
    let n = if n[2] < 0.0 { n.map(|x| -x) } else { n };
    let dip = n[2].clamp(-1.0, 1.0).acos().to_degrees();
    let dir = if n[0].hypot(n[1]) < 1e-12 { 0.0 } else { n[0].atan2(n[1]).to_degrees().rem_euclid(360.0) };
    (dip, dir)
}

/// A direction's name: "x", "−z" ("+z" with `plus`), or its components.
pub(super) fn direction(d: [f64; 3], plus: bool) -> String {
    match (0..3).find(|&a| (d[a].abs() - 1.0).abs() < 1e-9) {
        Some(a) => format!(
            "{}{}",
            if d[a] < 0.0 {
                "−"
            } else if plus {
                "+"
            } else {
                ""
            },
            ["x", "y", "z"][a]
        ),
        None => format!(
            "({}, {}, {})",
            num((d[0] * 100.0).round() / 100.0),
            num((d[1] * 100.0).round() / 100.0),
            num((d[2] * 100.0).round() / 100.0)
        ),
    }
}

/// A facet's unit normal (from its corners; zero when degenerate), area
/// (of its corners' polygon) and centroid.
fn facet_geometry(f: &Cell, coords: &[[f64; 3]]) -> FacetGeometry {
    let nc = f.kind.n_corners();
    let x: Vec<[f64; 3]> = f.nodes[..nc].iter().map(|&k| coords[k]).collect();
    let c: [f64; 3] = std::array::from_fn(|d| x.iter().map(|p| p[d]).sum::<f64>() / nc as f64);
    let mut m = [0.0; 3];
    for i in 0..nc {
        let w = cross(sub(x[i], c), sub(x[(i + 1) % nc], c));
        for d in 0..3 {
            m[d] += 0.5 * w[d];
        }
    }
    let a = dot(m, m).sqrt();
    (normalized(m), a, c)
}

/// A unit vector within a degree of a world axis, made that axis (a
/// tunnel's axis fitted to a faceted lining reads "y", not "(0, 1, 0)").
fn snap(a: [f64; 3]) -> [f64; 3] {
    match (0..3).find(|&i| a[i].abs() >= 1f64.to_radians().cos()) {
        Some(i) => std::array::from_fn(|j| if j == i { a[i].signum() } else { 0.0 }),
        None => a,
    }
}

/// A unit vector's sign turned so that its largest component is positive.
fn canonical(n: [f64; 3]) -> [f64; 3] {
    let a = (0..3).max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs())).unwrap_or(0);
    if n[a] < 0.0 {
        n.map(|x| -x)
    } else {
        n
    }
}

/// A facet's unit normal, area and centroid.
type FacetGeometry = ([f64; 3], f64, [f64; 3]);

/// The sheets of interface `ii` of a solid model (see the module header).
pub(super) fn sheets(model: &Model, ii: usize) -> Vec<Sheet> {
    let iface = &model.interfaces[ii];
    let geo: Vec<FacetGeometry> = iface.facets.iter().map(|f| facet_geometry(f, &model.coords)).collect();
    if geo.is_empty() {
        return Vec::new();
    }
    // 1. smooth pieces: facets joined across edges that bend less than 35 degrees
    let pieces = smooth_pieces(&iface.facets, &geo);
    let up = model_up(model);
    let extent = {
        let (lo, hi) = super::view::model_box(model);
        (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max).max(f64::MIN_POSITIVE)
    };
    // 2. flat pieces, merged into planes; 3.-4. the others as they are
    let flat_tol = 3f64.to_radians().cos();
    let mut planes: Vec<(Vec<usize>, [f64; 3], f64)> = Vec::new();
    let mut others: Vec<Sheet> = Vec::new();
    for piece in pieces {
        let Some((n, offset)) = flat_plane(&piece, &geo, flat_tol) else {
            others.push(curved(model, ii, piece, &geo, up));
            continue;
        };
        // the same plane: parallel, and offsets within 1e-4 of the model's size
        let same = |pn: [f64; 3], po: f64| {
            dot(pn, n).abs() >= flat_tol && (po - dot(pn, n).signum() * offset).abs() <= 1e-4 * extent
        };
        match planes.iter_mut().find(|(_, pn, po)| same(*pn, *po)) {
            Some(p) => p.0.extend(piece),
            None => planes.push((piece, n, offset)),
        }
    }
    let mut out = plane_sheets(planes, ii, up);
    out.extend(others);
    out
}

/// The facets joined into smooth pieces: across shared edges whose
/// normals differ by less than 35 degrees; pieces and their facets in the
/// order of their first facet.
fn smooth_pieces(facets: &[Cell], geo: &[FacetGeometry]) -> Vec<Vec<usize>> {
    let mut sets = UnionFind::new(geo.len());
    let mut edges: Vec<(usize, usize, usize)> = Vec::new();
    for (i, f) in facets.iter().enumerate() {
        let nc = f.kind.n_corners();
        for c in 0..nc {
            let (a, b) = (f.nodes[c], f.nodes[(c + 1) % nc]);
            edges.push((a.min(b), a.max(b), i));
        }
    }
    edges.sort_unstable();
    let smooth = 35f64.to_radians().cos();
    for w in edges.windows(2) {
        if (w[0].0, w[0].1) == (w[1].0, w[1].1) && dot(geo[w[0].2].0, geo[w[1].2].0).abs() >= smooth {
            sets.join(w[0].2, w[1].2);
        }
    }
    sets.groups()
}

/// The plane of a flat piece, `(n, offset)` with n canonical and offset
/// the area-weighted mean of `n . x`; None when a facet normal leaves the
/// mean normal by more than `flat_tol` (a cosine).
fn flat_plane(piece: &[usize], geo: &[FacetGeometry], flat_tol: f64) -> Option<([f64; 3], f64)> {
    // the area-weighted mean of the normals turned to agree with the largest facet's
    let big = *piece.iter().max_by(|&&a, &&b| geo[a].1.total_cmp(&geo[b].1)).unwrap_or(&piece[0]);
    let refn = geo[big].0;
    let mut m = [0.0; 3];
    for &f in piece {
        let s = if dot(geo[f].0, refn) < 0.0 { -1.0 } else { 1.0 };
        for d in 0..3 {
            m[d] += s * geo[f].1 * geo[f].0[d];
        }
    }
    let mean = normalized(m);
    if !piece.iter().all(|&f| dot(geo[f].0, mean).abs() >= flat_tol) {
        return None;
    }
    let n = canonical(mean);
    let area: f64 = piece.iter().map(|&f| geo[f].1).sum();
    let offset = piece.iter().map(|&f| geo[f].1 * dot(geo[f].2, n)).sum::<f64>() / area.max(f64::MIN_POSITIVE);
    Some((n, offset))
}

/// The planes as sheets: in sets of parallel planes (normals within 10
/// degrees) by first appearance, and by offset within a set.
fn plane_sheets(planes: Vec<(Vec<usize>, [f64; 3], f64)>, ii: usize, up: [f64; 3]) -> Vec<Sheet> {
    let set_tol = 10f64.to_radians().cos();
    let mut sets: Vec<[f64; 3]> = Vec::new();
    let mut out: Vec<Sheet> = planes
        .into_iter()
        .map(|(mut facets, n, offset)| {
            facets.sort_unstable();
            let set = match sets.iter().position(|s| dot(*s, n).abs() >= set_tol) {
                Some(s) => s,
                None => {
                    sets.push(n);
                    sets.len() - 1
                }
            };
            Sheet { interface: ii, facets, shape: plane_shape(n, offset, up), set }
        })
        .collect();
    out.sort_by(|a, b| {
        let off = |s: &Sheet| if let Shape::Plane { offset, .. } = s.shape { offset } else { 0.0 };
        a.set.cmp(&b.set).then(off(a).total_cmp(&off(b))).then(a.facets[0].cmp(&b.facets[0]))
    });
    out
}

/// The view of a plane with normal n: from the side that faces up, with
/// in-plane axes (r, v), `r x v = e`. For planes within 60 degrees of
/// horizontal, r is the world's first horizontal axis projected on the
/// plane; for steeper planes, v is up projected on it.
fn plane_shape(n: [f64; 3], offset: f64, up: [f64; 3]) -> Shape {
    let (e, r, v) = axes(n, up);
    Shape::Plane { e, r, v, n, offset }
}

fn axes(n: [f64; 3], up: [f64; 3]) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let e = if dot(n, up) < -1e-6 { n.map(|x| -x) } else { n };
    let along = |d: [f64; 3]| normalized(sub(d, e.map(|x| x * dot(d, e))));
    if dot(e, up).abs() > 0.5 {
        // the world axis least along up, the first of equals
        let a = (0..3).fold(0, |b, a| if up[a].abs() < up[b].abs() - 1e-12 { a } else { b });
        let mut h = [0.0; 3];
        h[a] = 1.0;
        let r = along(h);
        (e, r, cross(e, r))
    } else {
        let v = along(up);
        (e, cross(v, e), v)
    }
}

/// A piece that is not flat: a cylinder when its normals are all across one
/// axis, else a curved surface seen along its mean normal.
fn curved(model: &Model, ii: usize, piece: Vec<usize>, geo: &[FacetGeometry], up: [f64; 3]) -> Sheet {
    let mut m = nalgebra::Matrix3::<f64>::zeros();
    let mut total = 0.0;
    for &f in &piece {
        let (n, a, _) = geo[f];
        total += a;
        for i in 0..3 {
            for j in 0..3 {
                m[(i, j)] += a * n[i] * n[j];
            }
        }
    }
    let iface = &model.interfaces[ii];
    let mut nodes: Vec<usize> = piece.iter().flat_map(|&f| iface.facets[f].nodes.iter().copied()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    // (normals that do not decompose are no cylinder)
    if let Some(eig) = crate::fem::bounded::symmetric_eigen(m) {
        let imin = eig.eigenvalues.imin();
        if eig.eigenvalues[imin] <= 0.03 * total {
            let a = snap(canonical(normalized([
                eig.eigenvectors[(0, imin)],
                eig.eigenvectors[(1, imin)],
                eig.eigenvectors[(2, imin)],
            ])));
            if let Some(shape) = cylinder(model, &nodes, a, up) {
                return Sheet { interface: ii, facets: piece, shape, set: 0 };
            }
        }
    }
    // the mean of body I's normals, as they are (a dome keeps one side)
    let mut s = [0.0; 3];
    for &f in &piece {
        for d in 0..3 {
            s[d] += geo[f].1 * geo[f].0[d];
        }
    }
    let e = if dot(s, s).sqrt() >= 0.3 * total && total > 0.0 { normalized(s) } else { up };
    let (e, r, v) = axes(e, up);
    Sheet { interface: ii, facets: piece, shape: Shape::Curved { e, r, v }, set: 0 }
}

/// The unrolling of the nodes about axis `a`: the circle through them
/// (least squares) and where the angles start and are cut.
fn cylinder(model: &Model, nodes: &[usize], a: [f64; 3], up: [f64; 3]) -> Option<Shape> {
    // angle 0: up across the axis (a tunnel's crown), else the world axis least along a
    let across = |d: [f64; 3]| sub(d, a.map(|x| x * dot(d, a)));
    let u = across(up);
    let (zero, crown) = if dot(u, u).sqrt() > 0.5 {
        (normalized(u), true)
    } else {
        let k = (0..3).fold(0, |b, k| if a[k].abs() < a[b].abs() - 1e-12 { k } else { b });
        let mut h = [0.0; 3];
        h[k] = 1.0;
        (normalized(across(h)), false)
    };
    let side = cross(a, zero);
    // Kasa's circle: x^2 + y^2 + D x + E y + F = 0 in least squares, about the nodes' mean
    let n = nodes.len() as f64;
    let mean: [f64; 3] = std::array::from_fn(|d| nodes.iter().map(|&k| model.coords[k][d]).sum::<f64>() / n);
    let mut ata = nalgebra::Matrix3::<f64>::zeros();
    let mut atb = nalgebra::Vector3::<f64>::zeros();
    for &k in nodes {
        let q = sub(model.coords[k], mean);
        let (x, y) = (dot(q, zero), dot(q, side));
        let row = nalgebra::Vector3::new(x, y, 1.0);
        ata += row * row.transpose();
        atb -= row * (x * x + y * y);
    }
    let sol = ata.lu().solve(&atb)?;
    let (cx, cy) = (-0.5 * sol[0], -0.5 * sol[1]);
    let centre: [f64; 3] = std::array::from_fn(|d| mean[d] + cx * zero[d] + cy * side[d]);
    let radius = nodes
        .iter()
        .map(|&k| dot(across(sub(model.coords[k], centre)), across(sub(model.coords[k], centre))).sqrt())
        .sum::<f64>()
        / n;
    if !radius.is_finite() || radius <= 0.0 {
        return None;
    }
    // cut a ring at the invert, an arc in the middle of its largest gap
    let mut angles: Vec<f64> = nodes
        .iter()
        .map(|&k| {
            let q = sub(model.coords[k], centre);
            dot(q, side).atan2(dot(q, zero))
        })
        .collect();
    angles.sort_by(|x, y| x.total_cmp(y));
    angles.dedup_by(|x, y| (*x - *y).abs() < 1e-9);
    let tau = std::f64::consts::TAU;
    let gaps: Vec<(f64, f64)> = (0..angles.len())
        .map(|i| {
            let (x, y) = (angles[i], if i + 1 < angles.len() { angles[i + 1] } else { angles[0] + tau });
            (y - x, 0.5 * (x + y))
        })
        .collect();
    let mut sorted: Vec<f64> = gaps.iter().map(|g| g.0).collect();
    sorted.sort_by(|x, y| x.total_cmp(y));
    let typical = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
    let (widest, mid) = gaps.iter().copied().fold((0.0, 0.0), |b, g| if g.0 > b.0 { g } else { b });
    let ring = !(widest > 4.0 * typical.max(1e-9) && widest > 10f64.to_radians());
    let cut = if ring {
        -std::f64::consts::PI
    } else {
        let mid = mid.rem_euclid(tau);
        if mid > 1e-12 {
            mid - tau
        } else {
            0.0
        }
    };
    Some(Shape::Cylinder { a, centre, radius, zero, side, cut, crown, ring })
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::fem::Analysis;
    use crate::mesh::CellKind;
    use crate::model::{Body, Interface, Material};

    /// A model whose only contact is `facets` (quad4) over `coords`, with a
    /// body cell so that the model has a size, z up by gravity.
    pub(in super::super) fn model_of(coords: Vec<[f64; 3]>, quads: Vec<[usize; 4]>) -> Model {
        let n = coords.len();
        let facets: Vec<Cell> = quads
            .iter()
            .enumerate()
            .map(|(i, q)| Cell { kind: CellKind::Quad4, nodes: q.to_vec(), tag: i as u64 + 1 })
            .collect();
        let cell = Cell { kind: CellKind::Tet4, nodes: (0..4.min(n)).collect(), tag: 0 };
        Model {
            analysis: Analysis::Solid,
            nd: 3,
            thickness: 1.0,
            gravity: [0.0, 0.0, -9.81],
            coords,
            bodies: vec![Body {
                name: "a".into(),
                group: 0,
                block: None,
                material: Material { e: 1.0, nu: 0.2, density: 0.0 },
                cells: vec![cell],
                initial: None,
            }],
            loads: Vec::new(),
            nodal_loads: Vec::new(),
            supports: Vec::new(),
            prescribed: vec![None; 3 * n],
            pairs: Vec::new(),
            interfaces: vec![Interface {
                name: "joints".into(),
                body_i: 0,
                body_ii: 0,
                side_i: vec![0],
                sides: vec![[0, 0]; facets.len()],
                facets,
            }],
            mesh_node: (0..n).collect(),
            cases: vec![vec![1.0]],
            load_cases: Vec::new(),
            gravity_case: 0,
            initial_case: 0,
            hold_case: None,
            water: Vec::new(),
            seismic: Vec::new(),
        }
    }

    /// A grid of quads over `[0, 1] x [0, 1]` mapped by `at(s, t)`,
    /// appended to `coords` and `quads`.
    pub(in super::super) fn grid(
        coords: &mut Vec<[f64; 3]>,
        quads: &mut Vec<[usize; 4]>,
        n: [usize; 2],
        at: impl Fn(f64, f64) -> [f64; 3],
    ) {
        let first = coords.len();
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                coords.push(at(i as f64 / n[0] as f64, j as f64 / n[1] as f64));
            }
        }
        let id = |i: usize, j: usize| first + j * (n[0] + 1) + i;
        for j in 0..n[1] {
            for i in 0..n[0] {
                quads.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }

    /// A tunnel lining's outer surface, r = 5 about the y axis, y in [0, 2]:
    /// a full ring or the arc from `a0` to `a1` degrees from the crown
    /// (+z) towards +x.
    pub(in super::super) fn ring(a0: f64, a1: f64, n: usize) -> Model {
        let (mut coords, mut quads) = (Vec::new(), Vec::new());
        grid(&mut coords, &mut quads, [n, 2], |s, t| {
            let th = (a0 + (a1 - a0) * s).to_radians();
            [5.0 * th.sin(), 2.0 * t, 5.0 * th.cos()]
        });
        if a1 - a0 >= 360.0 {
            // close the ring: the last column is the first
            let cols = n + 1;
            for q in quads.iter_mut() {
                for k in q.iter_mut() {
                    if *k % cols == n {
                        *k -= n;
                    }
                }
            }
        }
        model_of(coords, quads)
    }

    #[test]
    fn a_joint_set_gives_one_sheet_per_plane_in_order_of_offset() {
        // three horizontal planes (z = 2, 0, 1), each cut in two faces by a
        // vertical joint at x = 1 (the same group), and that joint
        let (mut coords, mut quads) = (Vec::new(), Vec::new());
        for z in [2.0, 0.0, 1.0] {
            grid(&mut coords, &mut quads, [2, 2], |s, t| [s, 2.0 * t, z]);
            grid(&mut coords, &mut quads, [2, 2], |s, t| [1.0 + s, 2.0 * t, z]);
        }
        grid(&mut coords, &mut quads, [2, 2], |s, t| [1.0, 2.0 * s, 2.0 * t]);
        let m = model_of(coords, quads);
        let sh = sheets(&m, 0);
        assert_eq!(sh.len(), 4, "three horizontal planes and one vertical");
        let offsets: Vec<(usize, f64, usize)> = sh
            .iter()
            .map(|s| match s.shape {
                Shape::Plane { offset, .. } => (s.set, offset, s.facets.len()),
                _ => panic!("planes only"),
            })
            .collect();
        assert_eq!(offsets, [(0, 0.0, 8), (0, 1.0, 8), (0, 2.0, 8), (1, 1.0, 4)]);
        assert_eq!(sh[0].describe(&m), "the plane z = 0");
        assert_eq!(sh[3].describe(&m), "the plane x = 1");
        // seen from above, x to the right and y up
        assert_eq!(sh[2].at([0.3, 0.7, 2.0]), [0.3, 0.7]);
    }

    #[test]
    fn a_v_groove_gives_two_planes_with_their_dip() {
        // faces dipping 45 degrees towards +x and -x, meeting along the y axis
        let (mut coords, mut quads) = (Vec::new(), Vec::new());
        grid(&mut coords, &mut quads, [3, 3], |s, t| [-s, 3.0 * t, s]);
        grid(&mut coords, &mut quads, [3, 3], |s, t| [s, 3.0 * t, s]);
        let m = model_of(coords, quads);
        let sh = sheets(&m, 0);
        assert_eq!(sh.len(), 2);
        assert!(sh.iter().all(|s| matches!(s.shape, Shape::Plane { .. }) && s.facets.len() == 9));
        assert_ne!(sh[0].set, sh[1].set, "not parallel");
        let d = sh[0].describe(&m);
        assert!(d.contains("dip 45°"), "{d}");
    }

    #[test]
    fn a_ring_is_unrolled_from_the_crown_and_cut_at_the_invert() {
        let m = ring(0.0, 360.0, 24);
        let sh = sheets(&m, 0);
        assert_eq!(sh.len(), 1);
        let Shape::Cylinder { a, centre, radius, cut, crown, ring, .. } = sh[0].shape else {
            panic!("a cylinder: {:?}", sh[0].shape)
        };
        assert!(crown && ring && (radius - 5.0).abs() < 1e-9 && a == [0.0, 1.0, 0.0], "{a:?} {radius}");
        assert!(centre[0].abs() < 1e-9 && centre[2].abs() < 1e-9);
        assert!((cut + std::f64::consts::PI).abs() < 1e-12);
        // the crown at 0, the springline at +x at a quarter turn, y along the axis
        let at = |x: [f64; 3]| sh[0].at(x);
        assert!(at([0.0, 0.5, 5.0])[0].abs() < 1e-9 && (at([0.0, 0.5, 5.0])[1] - 0.5).abs() < 1e-12);
        assert!((at([5.0, 0.0, 0.0])[0] - 5.0 * std::f64::consts::FRAC_PI_2).abs() < 1e-9);
        assert!((at([-5.0, 0.0, 0.0])[0] + 5.0 * std::f64::consts::FRAC_PI_2).abs() < 1e-9);
        // the facets across the invert are drawn on both sides
        let flat = sh[0].flat(&m);
        assert_eq!(flat.patches.len(), 48 + 2);
        let half = 5.0 * std::f64::consts::PI;
        assert_eq!([flat.lo[0], flat.hi[0]], [-half, half], "the whole turn, the invert at both ends");
        assert!(
            flat.patches.iter().all(|p| {
                let xs: Vec<f64> = p.nodes().iter().map(|&i| flat.points[i][0]).collect();
                xs.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b)) - xs.iter().fold(f64::INFINITY, |a, &b| a.min(b))
                    < 2.0
            }),
            "no facet stretched across the picture"
        );
    }

    #[test]
    fn an_arc_is_cut_in_its_gap() {
        // a quarter from the crown to the springline, and the lower half
        for (a0, a1, lo, hi) in [(0.0, 90.0, 0.0, 90.0), (90.0, 270.0, 90.0, 270.0), (-60.0, 30.0, -60.0, 30.0)] {
            let m = ring(a0, a1, 12);
            let sh = sheets(&m, 0);
            assert_eq!(sh.len(), 1);
            assert!(matches!(sh[0].shape, Shape::Cylinder { .. }));
            let flat = sh[0].flat(&m);
            let deg = |x: f64| (x / 5.0).to_degrees();
            assert!(
                (deg(flat.lo[0]) - lo).abs() < 1e-6 && (deg(flat.hi[0]) - hi).abs() < 1e-6,
                "{a0}..{a1}: {} .. {}",
                deg(flat.lo[0]),
                deg(flat.hi[0])
            );
            assert_eq!(flat.patches.len(), 24, "no copies");
        }
    }
}
