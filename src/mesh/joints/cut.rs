//! The cut itself, in gmsh's model (module header of `joints` for the
//! steps): lay every joint's patches, fragment, sort the pieces, rebuild
//! the physical groups, size the new points, mesh and write.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use crate::mesh::cell_kind::CellKind;

use super::api::{ApiError, DimTag, PhysicalGroup as Group, Session};
use super::curved;
use super::cut_report::{BlockReport, CutReport, JointReport, NearMiss, PlaneReport};
use super::geometry::{self, Patch};
use super::job::{trim, CutJob, JointSpec, MeshArgs, Placement};
use super::joint_error::JointError;
use super::sizes::Sizes;
use super::slivers;

type R<T> = Result<T, JointError>;

/// A joint's planes as laid: the report of each plane, its patches and
/// the planes that pass close to a corner.
struct Laid {
    planes: Vec<PlaneReport>,
    patches: Vec<Piece>,
    near: Vec<NearMiss>,
}

/// A patch of a joint, or a face of its contact group, and its plane
/// (index in the joint's planes).
#[derive(Clone, Copy)]
struct Piece {
    plane: usize,
    entity: DimTag,
}

pub(super) fn run(s: &Session, args: &MeshArgs, job: &CutJob, out: &Path) -> R<CutReport> {
    let geo = args.geo;
    let g = |e: ApiError| JointError::Gmsh { geo: geo.to_path_buf(), detail: e.to_string() };
    let dim = args.dim as i32;
    s.open(geo).map_err(g)?;
    logged(s, geo)?;
    if s.occ_entities(dim).map_err(g)?.is_empty() {
        return Err(JointError::NotOcc { geo: geo.to_path_buf() });
    }
    let groups = s.physical_groups().map_err(g)?;
    for j in &job.joints {
        if groups.iter().any(|grp| grp.name == j.name) {
            return Err(JointError::NameTaken { key: j.key.clone(), name: j.name.clone(), geo: geo.to_path_buf() });
        }
    }
    let bodies = job.joints.iter().map(|j| body_entities(j, &groups, dim, geo)).collect::<R<Vec<_>>>()?;
    let sizes = measure(s, dim).map_err(g)?;
    let all = s.entities(dim).map_err(g)?;
    let old_points = points(s).map_err(g)?;
    let laid =
        job.joints.iter().zip(&bodies).map(|(j, b)| lay(s, j, b, &all, &sizes, (dim, geo))).collect::<R<Vec<_>>>()?;

    // every volume (surface) and every entity a user's group names, cut by every patch
    let mut objects: Vec<DimTag> = all.clone();
    let mut lower: Vec<DimTag> =
        groups.iter().filter(|grp| grp.dim < dim).flat_map(|grp| grp.tags.iter().map(|&t| (grp.dim, t))).collect();
    lower.sort_unstable();
    lower.dedup();
    objects.extend(lower);
    let tools: Vec<DimTag> = laid.iter().flat_map(|l| l.patches.iter().map(|p| p.entity)).collect();
    let before = objects.iter().map(|&o| s.bounding_box(o)).collect::<Result<Vec<_>, _>>().map_err(g)?;
    // (without joints, nothing is cut: the model's own blocks are reported)
    let map = if tools.is_empty() {
        objects.iter().map(|&o| vec![o]).collect()
    } else {
        s.fragment(&objects, &tools).map_err(g)?.1
    };
    s.synchronize().map_err(g)?;
    let mut children: HashMap<DimTag, Vec<DimTag>> = objects.iter().chain(&tools).copied().zip(map).collect();
    within(s, &objects, &before, &mut children).map_err(g)?;
    unchanged(s, &objects, &before, &mut children).map_err(g)?;

    let mut kept = sort_pieces(s, dim, &objects, &laid, &children).map_err(g)?;
    for (j, (l, k)) in job.joints.iter().zip(laid.iter().zip(&kept)) {
        if k.is_empty() {
            return Err(nothing(j, &format!("its {} plane(s) inside the bounding box of its bodies miss the bodies themselves (they pass through openings or outside); change offset, spacing or extent", l.planes.len())));
        }
    }
    let merged = if job.merge_slivers { merge(s, dim, &sizes, &mut kept).map_err(g)? } else { 0 };
    let blocks = s.entities(dim).map_err(g)?;
    if blocks.len() > job.max_blocks {
        return Err(JointError::TooManyBlocks { count: blocks.len(), max: job.max_blocks });
    }
    if let Some(group) = regroup(s, dim, &groups, &children, job, &kept).map_err(g)?.into_iter().next() {
        return Err(JointError::LostGroup { geo: geo.to_path_buf(), group });
    }
    size_new_points(s, &old_points, &sizes).map_err(g)?;

    if job.structured {
        s.structured().map_err(g)?;
    }
    let straightened = generate(s, dim, args.order).map_err(g)?;
    logged(s, geo)?;
    s.set_option("Mesh.MshFileVersion", 4.1).map_err(g)?;
    s.set_option("Mesh.Binary", 1.0).map_err(g)?;
    s.write(out).map_err(g)?;
    logged(s, geo)?;
    let mut made = report(s, (dim, &sizes), job, laid, &kept, &blocks).map_err(g)?;
    made.merged = merged;
    made.straightened = straightened;
    Ok(made)
}

/// Meshes the model at `order`. gmsh's own high-order optimisation is
/// off (it depends on memory addresses: module header of [`curved`]);
/// where the .geo asked for it, the folded or distorted quadratic elements
/// are made straight instead. Returns how many.
fn generate(s: &Session, dim: i32, order: usize) -> Result<usize, ApiError> {
    let optimise = s.option("Mesh.HighOrderOptimize")?;
    s.set_option("Mesh.HighOrderOptimize", 0.0)?;
    s.set_option("Mesh.ElementOrder", order as f64)?;
    s.generate(dim)?;
    if order < 2 || optimise == 0.0 {
        return Ok(0);
    }
    let threshold = s.option("Mesh.HighOrderThresholdMin")?;
    let (tags, xyz) = s.nodes()?;
    let mut coords: HashMap<usize, [f64; 3]> = tags.into_iter().zip(xyz).collect();
    let kind = if dim == 3 { CellKind::Tet10 } else { CellKind::Tri6 };
    let elements = s.element_nodes(kind.gmsh_code())?;
    let (done, moved) = curved::straighten(kind, &elements, &mut coords, threshold);
    for t in moved {
        s.set_node(t, coords[&t])?;
    }
    Ok(done.elements)
}

/// [`slivers::merge`] on the joints' pieces.
fn merge(s: &Session, dim: i32, sizes: &Sizes, kept: &mut [Vec<Piece>]) -> Result<usize, ApiError> {
    let mut faces: Vec<Vec<DimTag>> = kept.iter().map(|k| k.iter().map(|p| p.entity).collect()).collect();
    let n = slivers::merge(s, dim, sizes, &mut faces)?;
    for (k, f) in kept.iter_mut().zip(&faces) {
        k.retain(|p| f.contains(&p.entity));
    }
    Ok(n)
}

/// A piece of an object meets the object's old bounding box: gmsh 4.8
/// can map an object the fragment left as it was to an entity that took
/// its tag elsewhere (measured: the bottom face of a slab under a block
/// mass cut by three sets, `tests/corpus/blocks3d.geo`, mapped to a piece
/// of a joint in the rock, so its support held the rock and left the slab
/// free). Pieces whose boxes miss it by more than a thousandth of its size
/// are dropped (OpenCASCADE's boxes of curved pieces may be loose, never
/// apart), and an object left with none is found by its box ([`unchanged`]).
fn within(
    s: &Session,
    objects: &[DimTag],
    before: &[geometry::Bbox],
    children: &mut HashMap<DimTag, Vec<DimTag>>,
) -> Result<(), ApiError> {
    for (o, b) in objects.iter().zip(before) {
        let Some(pieces) = children.get_mut(o) else { continue };
        let size = (0..3).map(|i| (b[i + 3] - b[i]).powi(2)).sum::<f64>().sqrt();
        let tol = 1e-3 * size + 1e-9 * b.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let mut meeting = Vec::with_capacity(pieces.len());
        for &c in pieces.iter() {
            let x = s.bounding_box(c)?;
            if (0..3).all(|i| x[i] <= b[i + 3] + tol && x[i + 3] >= b[i] - tol) {
                meeting.push(c);
            }
        }
        *pieces = meeting;
    }
    Ok(())
}

/// gmsh 4.8 maps an object the fragment left as it was (a side of a
/// rectangle no joint reaches) to nothing, and may have renumbered it
/// (measured: the four sides and corners of a rectangle cut by an inner
/// crack): such an object is the entity of its dimension with its bounding
/// box (among several, the one with its old tag, else the first).
fn unchanged(
    s: &Session,
    objects: &[DimTag],
    before: &[geometry::Bbox],
    children: &mut HashMap<DimTag, Vec<DimTag>>,
) -> Result<(), ApiError> {
    let mut boxes: HashMap<i32, Vec<(DimTag, geometry::Bbox)>> = HashMap::new();
    for (o, b) in objects.iter().zip(before) {
        if children.get(o).is_some_and(|k| !k.is_empty()) {
            continue;
        }
        let (d, _) = *o;
        let all = match boxes.entry(d) {
            std::collections::hash_map::Entry::Occupied(e) => e.into_mut(),
            std::collections::hash_map::Entry::Vacant(v) => v.insert(
                s.entities(d)?
                    .into_iter()
                    .map(|e| Ok((e, s.bounding_box(e)?)))
                    .collect::<Result<Vec<_>, ApiError>>()?,
            ),
        };
        let scale = b.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let same: Vec<DimTag> = all
            .iter()
            .filter(|(_, x)| x.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-9 * scale))
            .map(|&(e, _)| e)
            .collect();
        let pick = match same.as_slice() {
            [] => None,
            [one] => Some(*one),
            several => several.iter().copied().find(|e| e == o).or(several.first().copied()),
        };
        children.insert(*o, pick.into_iter().collect());
    }
    Ok(())
}

/// Any `Error` gmsh logged so far is a failure (gmsh may carry on after one).
fn logged(s: &Session, geo: &Path) -> R<()> {
    let errors = s.errors();
    if errors.is_empty() {
        Ok(())
    } else {
        Err(JointError::Gmsh { geo: geo.to_path_buf(), detail: errors.join("; ") })
    }
}

fn nothing(j: &JointSpec, why: &str) -> JointError {
    JointError::CutsNothing {
        key: j.key.clone(),
        name: j.name.clone(),
        label: j.orientation.label(),
        why: why.to_string(),
    }
}

/// The volumes (surfaces in 2D) of the joint's body groups.
fn body_entities(j: &JointSpec, groups: &[Group], dim: i32, geo: &Path) -> R<Vec<DimTag>> {
    let mut out = Vec::new();
    for b in &j.bodies {
        let Some(grp) = groups.iter().find(|grp| grp.dim == dim && &grp.name == b) else {
            return Err(JointError::NoBody {
                key: j.key.clone(),
                geo: geo.to_path_buf(),
                what: if dim == 3 { "volume" } else { "surface" },
                group: b.clone(),
            });
        };
        out.extend(grp.tags.iter().map(|&t| (dim, t)));
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

/// The sizes the uncut model's boundary mesh has (linear, then cleared).
fn measure(s: &Session, dim: i32) -> Result<Sizes, ApiError> {
    let order = s.option("Mesh.ElementOrder")?;
    s.set_option("Mesh.ElementOrder", 1.0)?;
    s.generate(dim - 1)?;
    let (tags, coords) = s.nodes()?;
    let index: HashMap<usize, usize> = tags.iter().enumerate().map(|(i, &t)| (t, i)).collect();
    let mut groups = Vec::new();
    let kinds: &[(i32, usize)] = if dim == 3 { &[(2, 3), (3, 4)] } else { &[(1, 2)] };
    for &(kind, per) in kinds {
        let nodes: Vec<usize> = s.element_nodes(kind)?.iter().filter_map(|t| index.get(t).copied()).collect();
        groups.push((per, nodes));
    }
    s.clear_mesh()?;
    s.set_option("Mesh.ElementOrder", order)?;
    Ok(Sizes::measure(&coords, &groups))
}

/// Every geometric point and where it is.
fn points(s: &Session) -> Result<HashMap<i32, [f64; 3]>, ApiError> {
    s.entities(0)?.into_iter().map(|(_, t)| Ok((t, s.point(t)?))).collect()
}

/// The union of the entities' bounding boxes.
fn bounding_box(s: &Session, ents: &[DimTag]) -> Result<geometry::Bbox, ApiError> {
    let mut b = [f64::INFINITY, f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
    for &e in ents {
        let x = s.bounding_box(e)?;
        for d in 0..3 {
            b[d] = b[d].min(x[d]);
            b[d + 3] = b[d + 3].max(x[d + 3]);
        }
    }
    Ok(b)
}

/// The frame a joint's planes are laid in: its bodies' box (flat in z in
/// 2D), the geometric tolerance, the plane normal and the range of n . x
/// over the box.
struct Frame {
    b: geometry::Bbox,
    d: usize,
    tol: f64,
    n: [f64; 3],
    range: (f64, f64),
}

/// Lays a joint's patches in gmsh: its planes (snapped where asked), each
/// covered or tiled with finite joints, clipped to `extent` and to its
/// bodies when it does not cut every body.
fn lay(
    s: &Session,
    j: &JointSpec,
    bodies: &[DimTag],
    all: &[DimTag],
    sizes: &Sizes,
    (dim, geo): (i32, &Path),
) -> R<Laid> {
    let g = |e: ApiError| JointError::Gmsh { geo: geo.to_path_buf(), detail: e.to_string() };
    // 1. the frame: box, tolerance, normal, range of n . x
    let f = frame(s, j, bodies, dim as usize).map_err(g)?;
    // 2. the planes' offsets inside the bodies
    let planes = plane_offsets(j, &f)?;
    // 3. the corners a plane may snap to, and the centre of a tiling
    let mut corners: Vec<[f64; 3]> = Vec::new();
    for (pd, p) in s.boundary(bodies, true).map_err(g)? {
        if pd == 0 {
            corners.push(s.point(p).map_err(g)?);
        }
    }
    let centre = tiling_centre(j, &f);
    // 4. each plane: snap, cut into patches, clip
    let mut laid = Laid { planes: Vec::new(), patches: Vec::new(), near: Vec::new() };
    for (k, v) in planes {
        let (v, snapped) = snap(j, &f, (k, v), &corners, sizes, &mut laid.near);
        let made = place(s, j, &patches(j, &f, v, centre), (dim, bodies, all)).map_err(g)?;
        let i = laid.planes.len();
        laid.patches.extend(made.into_iter().map(|entity| Piece { plane: i, entity }));
        laid.planes.push(PlaneReport { k, offset: v, area: 0.0, snapped });
    }
    Ok(laid)
}

/// The frame of a joint over its bodies.
fn frame(s: &Session, j: &JointSpec, bodies: &[DimTag], d: usize) -> Result<Frame, ApiError> {
    let mut b = bounding_box(s, bodies)?;
    if d == 2 {
        // OpenCASCADE's boxes are a little larger than the shape: a 2D
        // model lies in z = 0, and so must the traces
        (b[2], b[5]) = (0.0, 0.0);
    }
    let diag =
        ((b[3] - b[0]).powi(2) + (b[4] - b[1]).powi(2) + if d == 3 { (b[5] - b[2]).powi(2) } else { 0.0 }).sqrt();
    let n = j.orientation.normal();
    let range = geometry::range_over(n, &b, d);
    Ok(Frame { b, d, tol: 1e-6 * diag, n, range })
}

/// The offsets (and set indices) of a joint's planes that lie inside its
/// bodies; none is an error naming the joint and what to change.
fn plane_offsets(j: &JointSpec, f: &Frame) -> R<Vec<(Option<i64>, f64)>> {
    let (n, (lo, hi), tol) = (f.n, f.range, f.tol);
    let planes: Vec<(Option<i64>, f64)> = match j.placement {
        Placement::Set { spacing, offset } => {
            geometry::offsets(offset, spacing, (lo, hi), tol).into_iter().map(|(k, v)| (Some(k), v)).collect()
        }
        Placement::Single { point } => {
            let v = geometry::dot(n, point);
            if v > lo + tol && v < hi - tol {
                vec![(None, v)]
            } else {
                vec![]
            }
        }
    };
    if planes.is_empty() {
        let why = match j.placement {
            Placement::Set { spacing, offset } => format!("no plane n . x = {} + k {} lies inside its bodies, where n . x runs from {} to {} (n = [{}]); change offset or spacing", trim(offset), trim(spacing), trim(lo), trim(hi), n.map(trim).join(", ")),
            Placement::Single { point } => format!("its plane through [{}] misses the bounding box of its bodies, where n . x runs from {} to {} against {} at the point; move the point", point.map(trim).join(", "), trim(lo), trim(hi), trim(geometry::dot(n, point))),
        };
        return Err(nothing(j, &why));
    }
    Ok(planes)
}

/// The centre finite joints are tiled about: the persistence's, else the
/// single plane's point, else the middle of the box.
fn tiling_centre(j: &JointSpec, f: &Frame) -> [f64; 3] {
    let b = &f.b;
    j.persistence.as_ref().and_then(|p| p.centre).unwrap_or(match j.placement {
        Placement::Single { point } => point,
        Placement::Set { .. } => {
            [(b[0] + b[3]) / 2.0, (b[1] + b[4]) / 2.0, if f.d == 3 { (b[2] + b[5]) / 2.0 } else { 0.0 }]
        }
    })
}

/// Snaps plane `(k, v)` onto the nearest corner within `j.snap`; a corner
/// closer than a quarter of the local mesh size that is not snapped to is
/// noted in `near`. Returns the offset and the snap, if any.
fn snap(
    j: &JointSpec,
    f: &Frame,
    (k, v): (Option<i64>, f64),
    corners: &[[f64; 3]],
    sizes: &Sizes,
    near: &mut Vec<NearMiss>,
) -> (f64, Option<([f64; 3], f64)>) {
    let Some((c, dist)) = geometry::nearest(f.n, v, corners) else { return (v, None) };
    if dist > f.tol && dist < j.snap {
        return (geometry::dot(f.n, c), Some((c, dist)));
    }
    if dist > f.tol {
        let size = sizes.at(c).unwrap_or(f64::INFINITY);
        if dist < size / 4.0 {
            near.push(NearMiss {
                key: j.key.clone(),
                name: j.name.clone(),
                k,
                offset: v,
                corner: c,
                distance: dist,
                size,
            });
        }
    }
    (v, None)
}

/// The patches of the plane n . x = v: one covering the box, or finite
/// joints (one at a single plane's point, a tiling on a set's planes).
fn patches(j: &JointSpec, f: &Frame, v: f64, centre: [f64; 3]) -> Vec<Patch> {
    let (n, d) = (f.n, f.d);
    match &j.persistence {
        None => vec![geometry::covering(n, v, &f.b, d)],
        Some(p) => match j.placement {
            Placement::Single { .. } => vec![geometry::one(geometry::project(n, v, centre), n, p.size, p.shape, d)],
            Placement::Set { .. } => {
                let tiling = geometry::Tiling { size: p.size, gap: p.gap, shape: p.shape, centre };
                geometry::finite(n, v, &tiling, &f.b, d)
            }
        },
    }
}

/// Adds the patches to gmsh, clipped to the joint's `extent` and, when
/// the joint does not cut every body, to its bodies.
fn place(
    s: &Session,
    j: &JointSpec,
    patches: &[Patch],
    (dim, bodies, all): (i32, &[DimTag], &[DimTag]),
) -> Result<Vec<DimTag>, ApiError> {
    let mut made = patches.iter().map(|p| add_patch(s, p)).collect::<Result<Vec<DimTag>, ApiError>>()?;
    if let Some((from, to)) = j.extent {
        let bx = s.add_box(dim, from, to)?;
        made = s.intersect(&made, &[bx], true)?;
    }
    if bodies.len() < all.len() && !made.is_empty() {
        made = s.intersect(&made, bodies, false)?;
    }
    Ok(made)
}

fn add_patch(s: &Session, p: &Patch) -> Result<DimTag, ApiError> {
    Ok(match p {
        Patch::Polygon(c) => (2, s.add_polygon(c)?),
        Patch::Disc { centre, radius, normal } => (2, s.add_disc(*centre, *radius, *normal)?),
        Patch::Segment(a, b) => {
            let (p, q) = (s.add_point(*a)?, s.add_point(*b)?);
            (1, s.add_line(p, q)?)
        }
    })
}

/// The pieces of every joint that lie between two blocks or inside one, a
/// piece in two joints going to the first; pieces outside every body are
/// removed from the model.
fn sort_pieces(
    s: &Session,
    dim: i32,
    objects: &[DimTag],
    laid: &[Laid],
    children: &HashMap<DimTag, Vec<DimTag>>,
) -> Result<Vec<Vec<Piece>>, ApiError> {
    let mut embedded: HashSet<i32> = HashSet::new();
    for (_, v) in s.entities(dim)? {
        embedded.extend(s.embedded(dim, v)?.into_iter().filter(|&(d, _)| d == dim - 1).map(|(_, t)| t));
    }
    let of_objects: HashSet<DimTag> = objects.iter().flat_map(|o| children[o].iter().copied()).collect();
    let mut taken: HashSet<i32> = HashSet::new();
    let mut dangling: Vec<DimTag> = Vec::new();
    let mut kept = Vec::with_capacity(laid.len());
    for l in laid {
        let mut mine = Vec::new();
        for patch in &l.patches {
            for &(cd, c) in &children[&patch.entity] {
                if cd != dim - 1 || taken.contains(&c) || dangling.contains(&(cd, c)) {
                    continue;
                }
                let up = s.upward(cd, c)?;
                if up.len() >= 2 || embedded.contains(&c) {
                    taken.insert(c);
                    mine.push(Piece { plane: patch.plane, entity: (cd, c) });
                } else if up.is_empty() && !of_objects.contains(&(cd, c)) {
                    dangling.push((cd, c));
                }
            }
        }
        kept.push(mine);
    }
    if !dangling.is_empty() {
        s.remove(&dangling, true)?;
        s.synchronize()?;
    }
    Ok(kept)
}

/// The user's groups on the pieces of what they named, with their own
/// tags, and one group per joint on its pieces; returns the user's groups
/// that found no piece (none should).
fn regroup(
    s: &Session,
    dim: i32,
    groups: &[Group],
    children: &HashMap<DimTag, Vec<DimTag>>,
    job: &CutJob,
    kept: &[Vec<Piece>],
) -> Result<Vec<String>, ApiError> {
    s.remove_physical_groups()?;
    let mut lost = Vec::new();
    for grp in groups {
        let d = grp.dim;
        let mut tags: Vec<i32> = grp
            .tags
            .iter()
            .flat_map(|&e| children.get(&(d, e)).into_iter().flatten())
            .filter(|&&(cd, _)| cd == d)
            .map(|&(_, c)| c)
            .collect();
        tags.sort_unstable();
        tags.dedup();
        if tags.is_empty() && !grp.tags.is_empty() {
            lost.push(grp.name.clone());
        }
        s.add_physical_group(d, &tags, grp.tag, &grp.name)?;
    }
    for (j, k) in job.joints.iter().zip(kept) {
        let mut tags: Vec<i32> = k.iter().map(|p| p.entity.1).collect();
        tags.sort_unstable();
        s.add_physical_group(dim - 1, &tags, -1, &j.name)?;
    }
    Ok(lost)
}

/// Each point the cut made takes the size measured at the nearest node of
/// the uncut boundary mesh.
fn size_new_points(s: &Session, old: &HashMap<i32, [f64; 3]>, sizes: &Sizes) -> Result<(), ApiError> {
    for (_, p) in s.entities(0)? {
        let x = s.point(p)?;
        if old.get(&p).is_some_and(|o| (0..3).all(|d| (o[d] - x[d]).abs() <= 1e-12 * (1.0 + x[d].abs()))) {
            continue;
        }
        if let Some(size) = sizes.at(x) {
            s.set_size(&[p], size)?;
        }
    }
    Ok(())
}

/// What the cut made: the planes with their areas, the blocks.
fn report(
    s: &Session,
    (dim, sizes): (i32, &Sizes),
    job: &CutJob,
    laid: Vec<Laid>,
    kept: &[Vec<Piece>],
    blocks: &[DimTag],
) -> Result<CutReport, ApiError> {
    let mut out = CutReport::default();
    for ((j, mut l), k) in job.joints.iter().zip(laid).zip(kept) {
        for p in k {
            l.planes[p.plane].area += s.mass(p.entity)?;
        }
        out.near_misses.append(&mut l.near);
        out.joints.push(JointReport {
            key: j.key.clone(),
            name: j.name.clone(),
            label: j.orientation.label(),
            normal: j.orientation.normal(),
            planes: l.planes,
            faces: k.len(),
        });
    }
    let body_of: HashMap<i32, String> = s
        .physical_groups()?
        .into_iter()
        .filter(|grp| grp.dim == dim)
        .flat_map(|grp| grp.tags.into_iter().map(move |t| (t, grp.name.clone())))
        .collect();
    for &b in blocks {
        let (_, tag) = b;
        let volume = s.mass(b)?;
        let centre = s.centre(b)?;
        out.blocks.push(BlockReport {
            body: body_of.get(&tag).cloned().unwrap_or_default(),
            volume,
            thickness: slivers::thickness(s, dim, b)?,
            centre,
            size: sizes.at(centre).unwrap_or(f64::INFINITY),
        });
    }
    Ok(out)
}
