//! The surfaces the pictures fill: every 2D cell, or the boundary faces of
//! 3D cells (the deformed picture), or a contact interface's facets (the
//! plan view), as patches in gmsh's 2D node order, with the edges to
//! outline, cut into sub-triangles through their mid-edge nodes and filled
//! with the nodal field interpolated linearly (Gouraud).

use super::raster::Canvas;
use crate::fem::shape::{HEX_EDGES, HEX_FACES, TET_EDGES};
use crate::fem::vec3::{cross, dot, normalized, sub};
use crate::fem::Analysis;
use crate::mesh::{Cell, CellKind};
use crate::model::Model;

/// A cell or face drawn as a surface patch: nodes in gmsh 2D order (Tri3/6,
/// Quad4/8/9: corners, mid-edge nodes, centre).
#[derive(Clone, Copy)]
pub(super) struct Patch {
    pub(super) kind: CellKind,
    pub(super) nodes: [usize; 9],
    pub(super) body: usize,
    /// Edges to outline (bit i: edge from corner i to corner i + 1).
    pub(super) outline: u8,
    /// Edges this patch is the first of the body's patches to have.
    pub(super) first: u8,
}

impl Patch {
    pub(super) fn nodes(&self) -> &[usize] {
        &self.nodes[..self.kind.n_nodes()]
    }
    /// Unit normal of a 3D face (from its diagonals; zero when degenerate).
    pub(super) fn normal(&self, coords: &[[f64; 3]]) -> [f64; 3] {
        let x: Vec<[f64; 3]> = self.nodes[..self.kind.n_corners()].iter().map(|&n| coords[n]).collect();
        normalized(cross(sub(x[2], x[0]), sub(x[x.len() - 1], x[1])))
    }
    /// Node chain of edge i: corner, mid-edge node (if any), next corner.
    pub(super) fn edge(&self, i: usize) -> ([usize; 3], usize) {
        let nc = self.kind.n_corners();
        let (a, b) = (self.nodes[i], self.nodes[(i + 1) % nc]);
        if self.kind.order() == 2 {
            ([a, self.nodes[nc + i], b], 3)
        } else {
            ([a, b, b], 2)
        }
    }
}

/// Sub-triangles of a patch over its nodes plus a centre at index 8 (Quad).
pub(super) fn sub_triangles(kind: CellKind) -> &'static [[usize; 3]] {
    const QUAD_LIN: [[usize; 3]; 4] = [[0, 1, 8], [1, 2, 8], [2, 3, 8], [3, 0, 8]];
    const QUAD_QUAD: [[usize; 3]; 8] =
        [[0, 4, 8], [4, 1, 8], [1, 5, 8], [5, 2, 8], [2, 6, 8], [6, 3, 8], [3, 7, 8], [7, 0, 8]];
    match kind {
        CellKind::Tri3 => &[[0, 1, 2]],
        CellKind::Tri6 => &[[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]],
        CellKind::Quad4 => &QUAD_LIN,
        CellKind::Quad8 | CellKind::Quad9 => &QUAD_QUAD,
        _ => &[],
    }
}

/// Values at a patch's nodes and centre (index 8) from values at its nodes.
pub(super) fn with_centre<T: Copy + Into<f64>>(kind: CellKind, v: &mut [f64; 9], node: impl Fn(usize) -> T) {
    for (i, x) in v.iter_mut().enumerate().take(kind.n_nodes()) {
        *x = node(i).into();
    }
    match kind {
        CellKind::Quad4 => v[8] = 0.25 * (v[0] + v[1] + v[2] + v[3]),
        // the serendipity functions at the centre
        CellKind::Quad8 => v[8] = -0.25 * (v[0] + v[1] + v[2] + v[3]) + 0.5 * (v[4] + v[5] + v[6] + v[7]),
        _ => {}
    }
}

const TET_FACES: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

/// Patch kinds and cell-local node numbers.
type LocalPatches = Vec<(CellKind, Vec<usize>)>;

/// The surface patches of a 2D cell (itself) or a 3D cell (its faces), in
/// cell-local node numbers.
fn local_patches(kind: CellKind) -> LocalPatches {
    let faces =
        |corners: &[usize], edges: &[[usize; 2]], first_mid: usize, centre: Option<usize>| -> (CellKind, Vec<usize>) {
            let nc = corners.len();
            let mut nodes = corners.to_vec();
            if kind.order() == 2 {
                for i in 0..nc {
                    let (a, b) = (corners[i], corners[(i + 1) % nc]);
                    let e = edges
                        .iter()
                        .position(|e| (e[0] == a && e[1] == b) || (e[0] == b && e[1] == a))
                        .expect("face edge is a cell edge");
                    nodes.push(first_mid + e);
                }
            }
            nodes.extend(centre);
            let k = match (nc, nodes.len()) {
                (3, 3) => CellKind::Tri3,
                (3, _) => CellKind::Tri6,
                (4, 4) => CellKind::Quad4,
                (4, 8) => CellKind::Quad8,
                _ => CellKind::Quad9,
            };
            (k, nodes)
        };
    match kind {
        CellKind::Tri3 | CellKind::Tri6 | CellKind::Quad4 | CellKind::Quad8 | CellKind::Quad9 => {
            vec![(kind, (0..kind.n_nodes()).collect())]
        }
        CellKind::Tet4 | CellKind::Tet10 => TET_FACES.iter().map(|f| faces(f, &TET_EDGES, 4, None)).collect(),
        CellKind::Hex8 | CellKind::Hex20 | CellKind::Hex27 => HEX_FACES
            .iter()
            .enumerate()
            .map(|(i, f)| faces(f, &HEX_EDGES, 8, (kind == CellKind::Hex27).then_some(20 + i)))
            .collect(),
        // prisms and pyramids: their faces as fem::shape lists them
        _ if kind.dim() == 3 => crate::fem::shape::faces(kind).into_iter().map(|f| (f.kind, f.nodes)).collect(),
        _ => Vec::new(),
    }
}

/// The patches to draw: every 2D cell, or the faces of 3D cells not shared by
/// two cells of the same body; only the cells `keep` marks (per body, per
/// cell), or all. `outline` marks edges on a body's boundary (2D) or
/// between faces meeting at more than 30 degrees (3D).
pub(super) fn patches(model: &Model, keep: Option<&[Vec<bool>]>) -> Vec<Patch> {
    let solid = model.analysis == Analysis::Solid;
    let mut out = Vec::new();
    for (b, body) in model.bodies.iter().enumerate() {
        let first = out.len();
        let mut keyed: Vec<([usize; 4], Patch)> = Vec::new();
        let mut cache: Vec<(CellKind, LocalPatches)> = Vec::new();
        for (ci, cell) in body.cells.iter().enumerate() {
            if keep.is_some_and(|k| !k[b][ci]) {
                continue;
            }
            if !cache.iter().any(|(k, _)| *k == cell.kind) {
                cache.push((cell.kind, local_patches(cell.kind)));
            }
            let local = &cache.iter().find(|(k, _)| *k == cell.kind).expect("cached").1;
            for (kind, nodes) in local {
                let mut p = Patch { kind: *kind, nodes: [0; 9], body: b, outline: 0, first: 0 };
                for (i, &l) in nodes.iter().enumerate() {
                    p.nodes[i] = cell.nodes[l];
                }
                if solid {
                    let mut key = [usize::MAX; 4];
                    key[..kind.n_corners()].copy_from_slice(&p.nodes[..kind.n_corners()]);
                    key.sort_unstable();
                    keyed.push((key, p));
                } else {
                    out.push(p);
                }
            }
        }
        if solid {
            keyed.sort_unstable_by_key(|k| k.0);
            let mut i = 0;
            while i < keyed.len() {
                let j = (i..keyed.len()).find(|&j| keyed[j].0 != keyed[i].0).unwrap_or(keyed.len());
                if j - i == 1 {
                    out.push(keyed[i].1);
                }
                i = j;
            }
        }
        mark_outlines(&mut out[first..], &model.coords, solid);
    }
    out
}

/// The facets of a contact interface (2D cells in gmsh order) as patches,
/// `outline` marking the interface's boundary.
pub(super) fn facet_patches(facets: &[Cell], coords: &[[f64; 3]]) -> Vec<Patch> {
    let mut out: Vec<Patch> = facets
        .iter()
        .filter(|f| !sub_triangles(f.kind).is_empty())
        .map(|f| {
            let mut p = Patch { kind: f.kind, nodes: [0; 9], body: 0, outline: 0, first: 0 };
            p.nodes[..f.nodes.len()].copy_from_slice(&f.nodes);
            p
        })
        .collect();
    mark_outlines(&mut out, coords, false);
    out
}

/// Sets the `outline` and `first` bits of the patches of one body.
fn mark_outlines(patches: &mut [Patch], coords: &[[f64; 3]], solid: bool) {
    let mut edges: Vec<(usize, usize, u32, u8)> = Vec::new();
    for (pi, p) in patches.iter().enumerate() {
        let nc = p.kind.n_corners();
        for i in 0..nc {
            let (a, b) = (p.nodes[i], p.nodes[(i + 1) % nc]);
            edges.push((a.min(b), a.max(b), pi as u32, i as u8));
        }
    }
    edges.sort_unstable();
    let normal = |p: &Patch| p.normal(coords);
    let mut i = 0;
    while i < edges.len() {
        let j = (i..edges.len()).find(|&j| (edges[j].0, edges[j].1) != (edges[i].0, edges[i].1)).unwrap_or(edges.len());
        let sharp = match (solid, j - i) {
            (_, 1) => true,
            (true, 2) => {
                dot(normal(&patches[edges[i].2 as usize]), normal(&patches[edges[i + 1].2 as usize])).abs()
                    < 30f64.to_radians().cos()
            }
            _ => false,
        };
        if sharp {
            for e in &edges[i..j] {
                patches[e.2 as usize].outline |= 1 << e.3;
            }
        }
        patches[edges[i].2 as usize].first |= 1 << edges[i].3;
        i = j;
    }
}

/// A patch's values at its nodes and centre.
pub(super) fn centred(p: &Patch, value: impl Fn(usize) -> f32) -> [f64; 9] {
    let mut t = [0.0f64; 9];
    with_centre(p.kind, &mut t, |i| value(p.nodes[i]));
    t
}

/// Median screen length of the patches' corner-to-corner edges.
fn typical_edge(patches: &[Patch], sd: &[[f32; 2]]) -> f64 {
    let step = (patches.len() / 4000).max(1);
    let mut l: Vec<f32> = patches
        .iter()
        .step_by(step)
        .flat_map(|p| {
            let nc = p.kind.n_corners();
            (0..nc).map(move |i| {
                let (a, b) = (sd[p.nodes[i]], sd[p.nodes[(i + 1) % nc]]);
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
        })
        .collect();
    if l.is_empty() {
        return 0.0;
    }
    let mid = l.len() / 2;
    *l.select_nth_unstable_by(mid, |a, b| a.total_cmp(b)).1 as f64
}

/// Opacity of the mesh lines over patches at these positions: they fade in
/// from 6 px cells and are full (0.45) from 14 px.
pub(super) fn mesh_alpha(patches: &[Patch], pos: &[[f32; 2]]) -> f32 {
    (((typical_edge(patches, pos) - 6.0) / 8.0).clamp(0.0, 1.0) * 0.45) as f32
}

/// Strokes a patch's edges (through their mid-edge nodes): `pick(outline,
/// first)` gives an edge's width, colour and opacity, or None to leave it.
pub(super) fn edges(
    cv: &mut Canvas,
    p: &Patch,
    pos: &[[f32; 2]],
    pick: &dyn Fn(bool, bool) -> Option<(f32, [u8; 3], f32)>,
) {
    for i in 0..p.kind.n_corners() {
        if let Some((w, c, a)) = pick(p.outline & (1 << i) != 0, p.first & (1 << i) != 0) {
            let (chain, len) = p.edge(i);
            cv.polyline(chain[..len].iter().map(|&k| pos[k]), w, c, a);
        }
    }
}

/// The sub-triangles of a patch on the screen, each with its vertices'
/// indices in the patch (8 the centre of a quadrilateral).
pub(super) fn pieces(p: &Patch, pos: &[[f32; 2]]) -> impl Iterator<Item = ([[f32; 2]; 3], [usize; 3])> {
    let mut xy = [[0.0f64; 9]; 2];
    for d in 0..2 {
        with_centre(p.kind, &mut xy[d], |i| pos[p.nodes[i]][d]);
    }
    sub_triangles(p.kind).iter().map(move |tri| (tri.map(|i| [xy[0][i] as f32, xy[1][i] as f32]), *tri))
}

/// Fills a patch through its sub-triangles; `values` gives the patch's
/// nodal values (index 8 the centre) and `paint` a colour for a value.
pub(super) fn fill(
    cv: &mut Canvas,
    p: &Patch,
    pos: &[[f32; 2]],
    values: &dyn Fn(&Patch) -> [f64; 9],
    paint: &dyn Fn(f32) -> [u8; 3],
) {
    let t = values(p);
    for (q, tri) in pieces(p, pos) {
        cv.triangle(q, tri.map(|i| t[i] as f32), paint);
    }
}
