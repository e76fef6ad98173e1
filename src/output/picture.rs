//! Pictures of a run, for a person to look at rather than read: the deformed
//! model coloured by a field, with the contact states drawn on the interfaces
//! (PNG), and the contact stresses along each interface (SVG).
//!
//! The deformed picture is rasterised here into an RGB buffer: every cell
//! (2D) or boundary face (3D: painter's algorithm in an oblique view, up
//! against gravity, else y for extrusions thin in z, else z) is cut into
//! sub-triangles through its mid-edge nodes and filled with the nodal field
//! interpolated linearly (Gouraud); lines are anti-aliased capsules.
//! plotters only writes the text, in the embedded DejaVu Sans, and the `png`
//! crate encodes the image, so no external program is needed.
//!
//! Displacements are magnified by `m = 0.05 L / max|u|` (L the model's
//! largest extent) unless a scale is given; the title states `m`. Colours:
//! viridis for magnitudes, blue (compression) to red (tension) through grey
//! for stress components; stick green, slip orange, open red.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::contact::law::ContactState;
use crate::driver::Run;
use crate::fem::material::von_mises;
use crate::fem::shape::{HEX_EDGES, HEX_FACES, TET_EDGES};
use crate::mesh::CellKind;
use crate::scene::Analysis;

/// The quantity that colours the deformed picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    VonMises,
    /// Magnitude of the displacement.
    Displacement,
    Sxx,
    Syy,
    Szz,
    Sxy,
    Syz,
    Sxz,
}

impl Field {
    pub const ALL: [Field; 8] = [Field::VonMises, Field::Displacement, Field::Sxx, Field::Syy, Field::Szz, Field::Sxy, Field::Syz, Field::Sxz];

    /// Spelling for file names and command lines (`von_mises`, `sxx`, ...).
    pub fn key(self) -> &'static str {
        match self {
            Field::VonMises => "von_mises",
            Field::Displacement => "displacement",
            Field::Sxx => "sxx",
            Field::Syy => "syy",
            Field::Szz => "szz",
            Field::Sxy => "sxy",
            Field::Syz => "syz",
            Field::Sxz => "sxz",
        }
    }

    pub fn parse(s: &str) -> Option<Field> {
        Field::ALL.into_iter().find(|f| f.key() == s)
    }

    /// Name for a reader; axisymmetric models have x = r and y = z (the axis).
    pub fn label(self, analysis: Analysis) -> &'static str {
        let axi = analysis == Analysis::Axisymmetric;
        match self {
            Field::VonMises => "von Mises stress",
            Field::Displacement => "displacement |u|",
            Field::Sxx if axi => "σrr (radial stress)",
            Field::Syy if axi => "σzz (axial stress)",
            Field::Szz if axi => "σθθ (hoop stress)",
            Field::Sxy if axi => "σrz (shear stress)",
            Field::Sxx => "σxx (normal stress)",
            Field::Syy => "σyy (normal stress)",
            Field::Szz => "σzz (normal stress)",
            Field::Sxy => "σxy (shear stress)",
            Field::Syz => "σyz (shear stress)",
            Field::Sxz => "σxz (shear stress)",
        }
    }

    /// Index in the stress vector `[xx, yy, zz, xy, yz, xz]`.
    fn component(self) -> Option<usize> {
        match self {
            Field::VonMises | Field::Displacement => None,
            Field::Sxx => Some(0),
            Field::Syy => Some(1),
            Field::Szz => Some(2),
            Field::Sxy => Some(3),
            Field::Syz => Some(4),
            Field::Sxz => Some(5),
        }
    }
}

/// The file name of the deformed picture of [`pictures`].
pub fn deformed_file(run: &Run) -> String {
    if run.stresses.is_empty() { "deformed_displacement.png" } else { "deformed_von_mises.png" }.to_string()
}

/// The pictures of a run under their file names: the deformed model coloured
/// by von Mises stress, and (with contact) the interface stresses.
pub fn pictures(run: &Run) -> Result<Vec<(String, Vec<u8>)>, String> {
    // von Mises when stresses were recovered, else the displacement magnitude
    let field = if run.stresses.is_empty() { Field::Displacement } else { Field::VonMises };
    let mut out = vec![(deformed_file(run), deformed_png(run, field, None)?)];
    if run.contact.is_some() && !run.model.interfaces.is_empty() {
        out.push(("interfaces.svg".to_string(), interface_plot_svg(run)?.into_bytes()));
    }
    Ok(out)
}

// ---------------------------------------------------------------------------
// The deformed picture
// ---------------------------------------------------------------------------

const W: usize = 1200;
const H: usize = 800;
/// Where the model goes: x0, y0, x1, y1 in pixels.
const PLOT: [f64; 4] = [24.0, 84.0, 960.0, 780.0];
/// The right-hand panel: colour bar, then the legend.
const PANEL_X: f64 = 990.0;

const STICK: [u8; 3] = [20, 170, 60];
const SLIP: [u8; 3] = [255, 140, 0];
const OPEN: [u8; 3] = [225, 20, 30];
const NO_PAIR: [u8; 3] = [120, 120, 120];
const GHOST: [u8; 3] = [228, 228, 228];
const INK: [u8; 3] = [40, 40, 40];

fn state_colour(s: ContactState) -> [u8; 3] {
    match s {
        ContactState::Stick => STICK,
        ContactState::Slip => SLIP,
        ContactState::Open => OPEN,
    }
}

/// A PNG (1200 x 800) of the model deformed by the magnified displacements
/// and coloured by `field`, with the contact states on the interfaces.
/// `scale` is the displacement magnification; None picks one that makes the
/// largest displacement 5 % of the model's size.
pub fn deformed_png(run: &Run, field: Field, scale: Option<f64>) -> Result<Vec<u8>, String> {
    let c = deformed_canvas(run, field, scale)?;
    encode_png(c.w, c.h, &c.rgb)
}

/// Oblique view of 3D models: the eye's direction, right and up on screen.
struct View {
    eye: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
}

impl View {
    /// Which way is up: against gravity when there is some; else y, as in
    /// the plane pictures, for models thinnest in z (extrusions of a plane
    /// section), seen mostly from +z; else z. The eye is turned 30 degrees
    /// to the right and raised 25 degrees (20 and 20 for the extrusions, so
    /// that their section dominates).
    fn new(extent: [f64; 3], gravity: [f64; 3]) -> View {
        let g = dot(gravity, gravity).sqrt();
        let thin_z = extent[2] <= extent[0].min(extent[1]);
        let (up, toward, az, el) = if g > 0.0 {
            let up = gravity.map(|x| -x / g);
            // the world axis least along up faces the viewer
            let k = (0..3).min_by(|&a, &b| up[a].abs().total_cmp(&up[b].abs())).unwrap_or(0);
            let mut t = [0.0; 3];
            t[k] = if k == 1 { -1.0 } else { 1.0 };
            let t = norm3(sub3(t, up.map(|x| x * dot(t, up))));
            (up, t, 30.0f64, 25.0f64)
        } else if thin_z {
            ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], 20.0, 20.0)
        } else {
            ([0.0, 0.0, 1.0], [0.0, -1.0, 0.0], 30.0, 25.0)
        };
        let right = cross(up, toward);
        let (sa, ca, se, ce) = (az.to_radians().sin(), az.to_radians().cos(), el.to_radians().sin(), el.to_radians().cos());
        let eye: [f64; 3] = std::array::from_fn(|i| ce * (ca * toward[i] + sa * right[i]) + se * up[i]);
        let r: [f64; 3] = std::array::from_fn(|i| ca * right[i] - sa * toward[i]);
        View { eye, right: r, up: cross(eye, r) }
    }
    fn project(&self, x: [f64; 3]) -> ([f64; 2], f64) {
        ([dot(x, self.right), dot(x, self.up)], dot(x, self.eye))
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// A cell or face drawn as a surface patch: nodes in gmsh 2D order (Tri3/6,
/// Quad4/8/9: corners, mid-edge nodes, centre).
#[derive(Clone, Copy)]
struct Patch {
    kind: CellKind,
    nodes: [usize; 9],
    body: usize,
    /// Edges to outline (bit i: edge from corner i to corner i + 1).
    outline: u8,
    /// Edges this patch is the first of the body's patches to have.
    first: u8,
}

impl Patch {
    fn nodes(&self) -> &[usize] {
        &self.nodes[..self.kind.n_nodes()]
    }
    /// Unit normal of a 3D face (from its diagonals; zero when degenerate).
    fn normal(&self, coords: &[[f64; 3]]) -> [f64; 3] {
        let x: Vec<[f64; 3]> = self.nodes[..self.kind.n_corners()].iter().map(|&n| coords[n]).collect();
        norm3(cross(sub3(x[2], x[0]), sub3(x[x.len() - 1], x[1])))
    }
    /// Node chain of edge i: corner, mid-edge node (if any), next corner.
    fn edge(&self, i: usize) -> ([usize; 3], usize) {
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
fn sub_triangles(kind: CellKind) -> &'static [[usize; 3]] {
    const QUAD_LIN: [[usize; 3]; 4] = [[0, 1, 8], [1, 2, 8], [2, 3, 8], [3, 0, 8]];
    const QUAD_QUAD: [[usize; 3]; 8] = [[0, 4, 8], [4, 1, 8], [1, 5, 8], [5, 2, 8], [2, 6, 8], [6, 3, 8], [3, 7, 8], [7, 0, 8]];
    match kind {
        CellKind::Tri3 => &[[0, 1, 2]],
        CellKind::Tri6 => &[[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]],
        CellKind::Quad4 => &QUAD_LIN,
        CellKind::Quad8 | CellKind::Quad9 => &QUAD_QUAD,
        _ => &[],
    }
}

/// Values at a patch's nodes and centre (index 8) from values at its nodes.
fn with_centre<T: Copy + Into<f64>>(kind: CellKind, v: &mut [f64; 9], node: impl Fn(usize) -> T) {
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
    let faces = |corners: &[usize], edges: &[[usize; 2]], first_mid: usize, centre: Option<usize>| -> (CellKind, Vec<usize>) {
        let nc = corners.len();
        let mut nodes = corners.to_vec();
        if kind.order() == 2 {
            for i in 0..nc {
                let (a, b) = (corners[i], corners[(i + 1) % nc]);
                let e = edges.iter().position(|e| (e[0] == a && e[1] == b) || (e[0] == b && e[1] == a)).expect("face edge is a cell edge");
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
        CellKind::Tri3 | CellKind::Tri6 | CellKind::Quad4 | CellKind::Quad8 | CellKind::Quad9 => vec![(kind, (0..kind.n_nodes()).collect())],
        CellKind::Tet4 | CellKind::Tet10 => TET_FACES.iter().map(|f| faces(f, &TET_EDGES, 4, None)).collect(),
        CellKind::Hex8 | CellKind::Hex20 | CellKind::Hex27 => HEX_FACES
            .iter()
            .enumerate()
            .map(|(i, f)| faces(f, &HEX_EDGES, 8, (kind == CellKind::Hex27).then_some(20 + i)))
            .collect(),
        _ => Vec::new(),
    }
}

/// The patches to draw: every 2D cell, or the faces of 3D cells not shared by
/// two cells of the same body. `outline` marks edges on a body's boundary
/// (2D) or between faces meeting at more than 30 degrees (3D).
fn patches(run: &Run) -> Vec<Patch> {
    let model = &run.model;
    let solid = model.analysis == Analysis::Solid;
    let mut out = Vec::new();
    for (b, body) in model.bodies.iter().enumerate() {
        let first = out.len();
        let mut keyed: Vec<([usize; 4], Patch)> = Vec::new();
        let mut cache: Vec<(CellKind, LocalPatches)> = Vec::new();
        for cell in &body.cells {
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
            (true, 2) => dot(normal(&patches[edges[i].2 as usize]), normal(&patches[edges[i + 1].2 as usize])).abs() < 30f64.to_radians().cos(),
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

/// The colour bar's limits `lo..hi` and the field's own range `min..max`.
struct Limits {
    lo: f64,
    hi: f64,
    min: f64,
    max: f64,
}

impl Limits {
    /// Limits from the nodal values: the field's range, except that a few
    /// outlying nodes (a stress singularity at a corner or a point support)
    /// do not take the whole colour bar: beyond the 0.5 % and 99.5 %
    /// quantiles by more than half their spread, the bar stops at the
    /// quantile and those nodes take its end colour. Stress components
    /// spanning zero get limits symmetric about it, so that grey is zero;
    /// round-off of the other sign (below 1e-3 of the largest value) is zero.
    fn of(field: Field, values: &[Vec<f32>]) -> Limits {
        let mut all: Vec<f64> = values.iter().flatten().filter(|v| v.is_finite()).map(|&v| v as f64).collect();
        if all.is_empty() {
            all.push(0.0);
        }
        let n = all.len();
        let mut quantile = |q: f64| *all.select_nth_unstable_by(((n - 1) as f64 * q).round() as usize, |a, b| a.total_cmp(b)).1;
        let (mut min, mut max, q_lo, q_hi) = (quantile(0.0), quantile(1.0), quantile(0.005), quantile(0.995));
        let big = min.abs().max(max.abs());
        if min < 0.0 && min > -1e-3 * big {
            min = 0.0;
        }
        if max > 0.0 && max < 1e-3 * big {
            max = 0.0;
        }
        let spread = q_hi - q_lo;
        let mut lo = if q_lo - min > 0.5 * spread { q_lo } else { min };
        let mut hi = if max - q_hi > 0.5 * spread { q_hi } else { max };
        if field.component().is_some() && lo < 0.0 && hi > 0.0 {
            let m = lo.abs().max(hi);
            (lo, hi) = (-m, m);
        }
        if hi - lo <= 1e-12 * hi.abs().max(lo.abs()) {
            let pad = (1e-3 * hi.abs()).max(1e-30);
            (lo, hi) = (lo - pad, hi + pad);
        }
        Limits { lo, hi, min, max }
    }

    /// A value scaled to the bar: 0 at `lo`, 1 at `hi`.
    fn norm(&self, v: f32) -> f32 {
        ((v as f64 - self.lo) / (self.hi - self.lo)) as f32
    }
}

/// Colour maps as 256-entry tables: viridis for magnitudes; cool-to-warm
/// (blue compression, grey zero, red tension) for stress components, its
/// blue or red half alone when the field has one sign.
fn colour_map(field: Field, lo: f64, hi: f64) -> Vec<[u8; 3]> {
    const VIRIDIS: [[u8; 3]; 9] = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 145, 140], [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37]];
    const COOL_WARM: [[u8; 3]; 9] = [[59, 76, 192], [98, 130, 234], [141, 176, 254], [184, 208, 249], [221, 221, 221], [245, 196, 173], [244, 154, 123], [222, 96, 77], [180, 4, 38]];
    let (stops, u0, u1) = match field.component() {
        None => (&VIRIDIS, 0.0, 1.0),
        Some(_) if lo < 0.0 && hi > 0.0 => (&COOL_WARM, 0.0, 1.0),
        Some(_) if hi <= 0.0 => (&COOL_WARM, 0.0, 0.5),
        Some(_) => (&COOL_WARM, 0.5, 1.0),
    };
    (0..256)
        .map(|i| {
            let t = (u0 + (u1 - u0) * i as f64 / 255.0) * 8.0;
            let k = (t as usize).min(7);
            let f = t - k as f64;
            std::array::from_fn(|c| (stops[k][c] as f64 * (1.0 - f) + stops[k + 1][c] as f64 * f).round() as u8)
        })
        .collect()
}

/// Text to write once the raster is done.
struct Label {
    text: String,
    at: (f64, f64),
    size: f64,
    pos: (HPos, VPos),
}

fn label(text: impl Into<String>, at: (f64, f64), size: f64, pos: (HPos, VPos)) -> Label {
    Label { text: text.into(), at, size, pos }
}

fn deformed_canvas(run: &Run, field: Field, scale: Option<f64>) -> Result<Canvas, String> {
    register_font();
    let model = &run.model;
    let stresses_ok = run.stresses.len() == model.bodies.len() || (run.stresses.is_empty() && field == Field::Displacement);
    if run.u.len() != model.n_nodes() * model.nd || !stresses_ok {
        return Err("the run's displacements or stresses do not match its model".into());
    }
    let frame = Frame::new(run, scale)?;
    let values = nodal_values(run, field);
    let lim = Limits::of(field, &values);
    let lut = colour_map(field, lim.lo, lim.hi);
    let mut cv = Canvas::new(W, H);
    draw_bodies(&mut cv, run, &frame, &values, &lim, &lut);
    draw_contacts(&mut cv, run, &frame);

    let mut labels = Vec::new();
    labels.push(label(run.scene.title.clone(), (24.0, 14.0), 24.0, (HPos::Left, VPos::Top)));
    let shape = if frame.mag > 0.0 {
        format!("deformed shape, displacements × {} (largest displacement {})", sig2(frame.mag), num(frame.umax))
    } else {
        "undeformed shape (no displacement)".to_string()
    };
    labels.push(label(format!("{} on the {shape}", field.label(model.analysis)), (24.0, 48.0), 17.0, (HPos::Left, VPos::Top)));
    colour_bar(&mut cv, &mut labels, &lut, &lim, field.label(model.analysis));
    legend(&mut cv, &mut labels, run, &frame);
    if let Some(view) = &frame.view {
        triad(&mut cv, &mut labels, view);
    }
    cv.text(&labels)?;
    Ok(cv)
}

/// Where every node lands in the picture, deformed (`sd`) and undeformed
/// (`su`), with its depth in 3D (larger is nearer).
struct Frame {
    mag: f64,
    umax: f64,
    /// Pixels per model length.
    px: f64,
    sd: Vec<[f32; 2]>,
    su: Vec<[f32; 2]>,
    depth: Vec<f64>,
    /// The 3D view; None in 2D (x right, y up).
    view: Option<View>,
}

impl Frame {
    fn new(run: &Run, scale: Option<f64>) -> Result<Frame, String> {
        let model = &run.model;
        let n = model.n_nodes();
        let mut used = vec![false; n];
        for cell in model.bodies.iter().flat_map(|b| &b.cells) {
            for &k in &cell.nodes {
                used[k] = true;
            }
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        let mut umax: f64 = 0.0;
        for k in (0..n).filter(|&k| used[k]) {
            for d in 0..3 {
                lo[d] = lo[d].min(model.coords[k][d]);
                hi[d] = hi[d].max(model.coords[k][d]);
            }
            let u = displacement(run, k);
            umax = umax.max(dot(u, u).sqrt());
        }
        if lo[0] > hi[0] {
            return Err("the model has no cells to draw".into());
        }
        let extent: [f64; 3] = std::array::from_fn(|d| hi[d] - lo[d]);
        let size = extent.iter().copied().fold(0.0, f64::max);
        let mag = match scale {
            Some(s) => s,
            None if umax > 0.0 && umax.is_finite() => 0.05 * size / umax,
            None => 0.0,
        };
        let view = (model.analysis == Analysis::Solid).then(|| View::new(extent, model.gravity));
        let place = |x: [f64; 3]| -> ([f64; 2], f64) {
            match &view {
                Some(v) => v.project(x),
                None => ([x[0], x[1]], 0.0),
            }
        };
        let mut flat = vec![[[0.0f64; 2]; 2]; n];
        let mut depth = vec![0.0f64; n];
        let (mut plo, mut phi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for k in (0..n).filter(|&k| used[k]) {
            let (u, x) = (displacement(run, k), model.coords[k]);
            let (pd, dd) = place(std::array::from_fn(|d| x[d] + mag * u[d]));
            flat[k] = [pd, place(x).0];
            depth[k] = dd;
            for p in flat[k] {
                for d in 0..2 {
                    plo[d] = plo[d].min(p[d]);
                    phi[d] = phi[d].max(p[d]);
                }
            }
        }
        let [x0, y0, x1, y1] = PLOT;
        let px = ((x1 - x0) / (phi[0] - plo[0])).min((y1 - y0) / (phi[1] - plo[1]));
        let px = if px.is_finite() && px > 0.0 { px } else { 1.0 };
        let (cx, cy) = (0.5 * (plo[0] + phi[0]), 0.5 * (plo[1] + phi[1]));
        let screen = |p: [f64; 2]| -> [f32; 2] { [(0.5 * (x0 + x1) + (p[0] - cx) * px) as f32, (0.5 * (y0 + y1) - (p[1] - cy) * px) as f32] };
        Ok(Frame {
            mag,
            umax,
            px,
            sd: flat.iter().map(|p| screen(p[0])).collect(),
            su: flat.iter().map(|p| screen(p[1])).collect(),
            depth,
            view,
        })
    }

    /// Whether the magnified displacements show (more than a pixel and a half).
    fn moved(&self) -> bool {
        self.mag * self.umax * self.px > 1.5
    }
}

fn displacement(run: &Run, k: usize) -> [f64; 3] {
    let nd = run.model.nd;
    std::array::from_fn(|c| if c < nd { run.u[k * nd + c] } else { 0.0 })
}

/// The field at every node of every body (each body keeps its own averages
/// where bodies share nodes); NaN at nodes not in the body.
fn nodal_values(run: &Run, field: Field) -> Vec<Vec<f32>> {
    if run.stresses.is_empty() {
        // displacement magnitude without recovered stresses
        return run
            .model
            .bodies
            .iter()
            .map(|b| {
                let mut v = vec![f32::NAN; run.model.n_nodes()];
                for k in crate::recover::body_nodes(b) {
                    let u = displacement(run, k);
                    v[k] = dot(u, u).sqrt() as f32;
                }
                v
            })
            .collect();
    }
    run.stresses
        .iter()
        .map(|bs| {
            let mut v = vec![f32::NAN; run.model.n_nodes()];
            for (&k, s) in bs.nodes.iter().zip(&bs.stress) {
                v[k] = match field.component() {
                    Some(c) => s[c],
                    None if field == Field::VonMises => von_mises(s),
                    None => {
                        let u = displacement(run, k);
                        dot(u, u).sqrt()
                    }
                } as f32;
            }
            v
        })
        .collect()
}

/// The bodies: the undeformed ghost (2D), the patches coloured by the field
/// (3D: far faces first, shaded), mesh lines on cells big enough to show
/// them, and the outlines.
fn draw_bodies(cv: &mut Canvas, run: &Run, frame: &Frame, values: &[Vec<f32>], lim: &Limits, lut: &[[u8; 3]]) {
    let (sd, su) = (&frame.sd, &frame.su);
    let mut patches = patches(run);
    // mesh lines fade in from 6 px cells, full from 14 px
    let mesh_alpha = (((typical_edge(&patches, sd) - 6.0) / 8.0).clamp(0.0, 1.0) * 0.45) as f32;
    let edges = |cv: &mut Canvas, p: &Patch, pos: &[[f32; 2]], pick: &dyn Fn(bool, bool) -> Option<(f32, [u8; 3], f32)>| {
        for i in 0..p.kind.n_corners() {
            if let Some((w, c, a)) = pick(p.outline & (1 << i) != 0, p.first & (1 << i) != 0) {
                let (chain, len) = p.edge(i);
                cv.polyline(chain[..len].iter().map(|&k| pos[k]), w, c, a);
            }
        }
    };
    let Some(view) = &frame.view else {
        if frame.moved() {
            for p in &patches {
                cv.patch(p, su, &|_| [0.0; 9], &|_| GHOST);
            }
            for p in &patches {
                edges(cv, p, su, &|outline, _| outline.then_some((1.0, [175, 175, 175], 1.0)));
            }
        }
        for p in &patches {
            let v = &values[p.body];
            cv.patch(p, sd, &|p| centred(p, |k| lim.norm(v[k])), &|t| lut_colour(lut, t));
        }
        // each mesh line once (from the first cell that has it), outlines over them
        for p in &patches {
            edges(cv, p, sd, &|outline, first| (!outline && first && mesh_alpha > 0.0).then_some((0.8, [0, 0, 0], mesh_alpha)));
        }
        for p in &patches {
            edges(cv, p, sd, &|outline, _| outline.then_some((1.3, INK, 1.0)));
        }
        return;
    };
    let key = |p: &Patch| p.nodes().iter().map(|&k| frame.depth[k]).sum::<f64>() / p.kind.n_nodes() as f64;
    patches.sort_by(|a, b| key(a).total_cmp(&key(b)));
    let light = norm3(std::array::from_fn(|i| 0.3 * view.right[i] + 0.5 * view.up[i] + view.eye[i]));
    let coords = &run.model.coords;
    for p in &patches {
        // faces lit from over the viewer's shoulder, either side alike
        let shade = (0.62 + 0.38 * dot(p.normal(coords), light).abs()) as f32;
        let v = &values[p.body];
        cv.patch(p, sd, &|p| centred(p, |k| lim.norm(v[k])), &|t| lut_colour(lut, t).map(|c| (c as f32 * shade) as u8));
        edges(cv, p, sd, &|outline, _| match outline {
            true => Some((1.2, [0, 0, 0], 0.85)),
            false => (mesh_alpha > 0.0).then_some((0.8, [0, 0, 0], mesh_alpha)),
        });
    }
}

fn norm3(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    if l > 0.0 {
        v.map(|x| x / l)
    } else {
        v
    }
}

/// A patch's values at its nodes and centre.
fn centred(p: &Patch, value: impl Fn(usize) -> f32) -> [f64; 9] {
    let mut t = [0.0f64; 9];
    with_centre(p.kind, &mut t, |i| value(p.nodes[i]));
    t
}

/// The colour of a value scaled to the bar (0..1, beyond it the end
/// colours); grey where there is no value.
fn lut_colour(lut: &[[u8; 3]], t: f32) -> [u8; 3] {
    if t.is_nan() {
        [150, 150, 150]
    } else {
        lut[(t.clamp(0.0, 1.0) * 255.0 + 0.5) as usize]
    }
}

/// The contact interfaces by state, over everything: in 2D both sides of
/// every facet as a thick line, each node's half of a segment in its pair's
/// colour; in 3D the pairs as dots (the interfaces are inside the solid).
fn draw_contacts(cv: &mut Canvas, run: &Run, frame: &Frame) {
    let model = &run.model;
    let sd = &frame.sd;
    let states = run.contact.as_ref().map(|c| &c.states[..]);
    let mut pair_of = vec![usize::MAX; model.n_nodes()];
    for (i, p) in model.pairs.iter().enumerate() {
        pair_of[p.k] = i;
    }
    let colour_of = |k: usize| match (states, pair_of[k]) {
        (Some(s), p) if p < s.len() => state_colour(s[p]),
        _ => NO_PAIR,
    };
    if frame.view.is_some() {
        for p in &model.pairs {
            state_dot(cv, sd[p.k], colour_of(p.k));
        }
        return;
    }
    let other = |k: usize| if pair_of[k] == usize::MAX { k } else { model.pairs[pair_of[k]].l };
    for casing in [true, false] {
        for f in model.interfaces.iter().flat_map(|i| &i.facets) {
            let chain: Vec<usize> = if f.nodes.len() == 3 { vec![f.nodes[0], f.nodes[2], f.nodes[1]] } else { f.nodes.clone() };
            for side in [&other as &dyn Fn(usize) -> usize, &|k| k] {
                for w in chain.windows(2) {
                    let (a, b) = (sd[side(w[0])], sd[side(w[1])]);
                    let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
                    if casing {
                        cv.segment(a, b, 7.0, [0, 0, 0], 1.0, true);
                    } else {
                        cv.segment(a, m, 4.2, colour_of(w[0]), 1.0, true);
                        cv.segment(m, b, 4.2, colour_of(w[1]), 1.0, true);
                    }
                }
            }
        }
    }
}

fn state_dot(cv: &mut Canvas, at: [f32; 2], c: [u8; 3]) {
    cv.dot(at, 4.6, [0, 0, 0]);
    cv.dot(at, 3.4, c);
}

/// Under the colour bar: the contact states with their counts, and the
/// undeformed shape's swatch.
fn legend(cv: &mut Canvas, labels: &mut Vec<Label>, run: &Run, frame: &Frame) {
    let x = PANEL_X as f32;
    let mut y = 580.0f32;
    let text = |labels: &mut Vec<Label>, t: String, x: f32, y: f32, size: f64| labels.push(label(t, (x as f64, y as f64), size, (HPos::Left, VPos::Center)));
    if let Some(c) = &run.contact {
        let counts = crate::driver::state_counts(&c.states);
        text(labels, "contact pairs".into(), x, y, 16.0);
        for (s, count) in [(ContactState::Stick, counts[2]), (ContactState::Slip, counts[1]), (ContactState::Open, counts[0])] {
            y += 26.0;
            if frame.view.is_some() {
                state_dot(cv, [x + 12.0, y], state_colour(s));
            } else {
                cv.segment([x + 2.0, y], [x + 24.0, y], 7.0, [0, 0, 0], 1.0, true);
                cv.segment([x + 2.0, y], [x + 24.0, y], 4.2, state_colour(s), 1.0, true);
            }
            text(labels, format!("{} ({count})", s.name()), x + 36.0, y, 15.0);
        }
        if frame.view.is_some() {
            y += 22.0;
            text(labels, "(seen through the solid)".into(), x, y, 12.0);
        }
        y += 34.0;
    }
    if frame.moved() && frame.view.is_none() {
        cv.rect(x as f64 + 2.0, y as f64 - 7.0, x as f64 + 24.0, y as f64 + 7.0, GHOST);
        let frame = [[x + 2.0, y - 7.0], [x + 24.0, y - 7.0], [x + 24.0, y + 7.0], [x + 2.0, y + 7.0], [x + 2.0, y - 7.0]];
        cv.polyline(frame.into_iter(), 1.0, [175, 175, 175], 1.0);
        text(labels, "undeformed".into(), x + 36.0, y, 15.0);
    }
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

/// The vertical colour bar with its limits and a few round ticks; an arrow
/// head at an end whose colour also stands for values beyond it, and the
/// field's minimum and maximum under the bar when they are not its ends.
fn colour_bar(cv: &mut Canvas, labels: &mut Vec<Label>, lut: &[[u8; 3]], lim: &Limits, name: &str) {
    let (lo, hi) = (lim.lo, lim.hi);
    let (bx0, bx1, by0, by1) = (PANEL_X, PANEL_X + 26.0, 146.0, 500.0);
    labels.push(label(name, (PANEL_X, 94.0), 16.0, (HPos::Left, VPos::Center)));
    for y in by0 as usize..by1 as usize {
        let t = 1.0 - (y as f64 - by0) / (by1 - by0 - 1.0);
        let c = lut[(t * 255.0).round() as usize];
        cv.rect(bx0, y as f64, bx1, y as f64 + 1.0, c);
    }
    let f = |x: f64, y: f64| [x as f32, y as f32];
    let mid = 0.5 * (bx0 + bx1);
    let over = lim.max > hi + 1e-9 * (hi - lo);
    let under = lim.min < lo - 1e-9 * (hi - lo);
    let mut frame = vec![f(bx0, by0)];
    if over {
        cv.triangle([f(bx0, by0), f(bx1, by0), f(mid, by0 - 16.0)], [0.0; 3], &|_| lut[255]);
        frame.push(f(mid, by0 - 16.0));
    }
    frame.extend([f(bx1, by0), f(bx1, by1)]);
    if under {
        cv.triangle([f(bx0, by1), f(bx1, by1), f(mid, by1 + 16.0)], [0.0; 3], &|_| lut[0]);
        frame.push(f(mid, by1 + 16.0));
    }
    frame.extend([f(bx0, by1), f(bx0, by0)]);
    cv.polyline(frame.into_iter(), 1.0, INK, 1.0);
    let y_of = |v: f64| by1 - (v - lo) / (hi - lo) * (by1 - by0);
    let mut tick = |v: f64, text: String, size: f64| {
        let y = y_of(v);
        cv.segment([bx1 as f32, y as f32], [bx1 as f32 + 5.0, y as f32], 1.0, INK, 1.0, false);
        labels.push(label(text, (bx1 + 9.0, y), size, (HPos::Left, VPos::Center)));
    };
    tick(hi, num(hi), 15.0);
    tick(lo, num(lo), 15.0);
    let step = nice_step((hi - lo) / 5.0);
    let mut k = (lo / step).ceil() as i64;
    while (k as f64) * step <= hi {
        let v = k as f64 * step;
        if (y_of(v) - y_of(hi)).abs() > 22.0 && (y_of(v) - y_of(lo)).abs() > 22.0 {
            tick(v, num(v), 13.0);
        }
        k += 1;
    }
    if over {
        labels.push(label(format!("up to {}", num(lim.max)), (bx1 + 9.0, by0 - 20.0), 13.0, (HPos::Left, VPos::Center)));
    }
    if under {
        labels.push(label(format!("down to {}", num(lim.min)), (bx1 + 9.0, by1 + 20.0), 13.0, (HPos::Left, VPos::Center)));
    }
    if lim.min > lo + 1e-9 * (hi - lo) || lim.max < hi - 1e-9 * (hi - lo) {
        labels.push(label(format!("min {}, max {}", num(lim.min), num(lim.max)), (PANEL_X, by1 + 40.0), 13.0, (HPos::Left, VPos::Center)));
    }
}

/// x, y, z arrows in the view of a 3D picture.
fn triad(cv: &mut Canvas, labels: &mut Vec<Label>, view: &View) {
    let o = [70.0f32, 730.0];
    for (d, name) in ["x", "y", "z"].iter().enumerate() {
        let mut e = [0.0; 3];
        e[d] = 1.0;
        let (p, _) = view.project(e);
        let tip = [o[0] + 36.0 * p[0] as f32, o[1] - 36.0 * p[1] as f32];
        cv.segment(o, tip, 1.6, INK, 1.0, true);
        labels.push(label(*name, ((o[0] + 48.0 * p[0] as f32) as f64, (o[1] - 48.0 * p[1] as f32) as f64), 15.0, (HPos::Center, VPos::Center)));
    }
}

/// 1, 2, 2.5 or 5 times a power of ten, at least `raw`.
fn nice_step(raw: f64) -> f64 {
    if raw.is_nan() || raw <= 0.0 || raw.is_infinite() {
        return 1.0;
    }
    let p = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0].iter().map(|m| m * p).find(|&s| s >= raw * (1.0 - 1e-12)).unwrap_or(10.0 * p)
}

/// A number with four significant digits, scientific outside [1e-3, 1e5).
fn num(v: f64) -> String {
    if !v.is_finite() {
        return "n/a".into();
    }
    let a = v.abs();
    if a == 0.0 {
        return "0".into();
    }
    if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            return s.trim_end_matches('0').trim_end_matches('.').to_string();
        }
        return s;
    }
    format!("{v:.2e}")
}

/// A magnification with two significant digits.
fn sig2(v: f64) -> String {
    if (1.0..1e4).contains(&v) {
        let p = 10f64.powf(v.log10().floor() - 1.0);
        return format!("{}", (v / p).round() * p);
    }
    if (0.01..1.0).contains(&v) {
        return num((v * 100.0).round() / 100.0);
    }
    format!("{v:.1e}")
}

fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, include_bytes!("../../assets/DejaVuSans.ttf"));
    });
}

// ---------------------------------------------------------------------------
// Raster
// ---------------------------------------------------------------------------

/// An RGB image, row by row from the top.
struct Canvas {
    w: usize,
    h: usize,
    rgb: Vec<u8>,
}

impl Canvas {
    fn new(w: usize, h: usize) -> Canvas {
        Canvas { w, h, rgb: vec![255; w * h * 3] }
    }

    #[inline]
    fn blend(&mut self, x: usize, y: usize, c: [u8; 3], a: f32) {
        let i = (y * self.w + x) * 3;
        for (k, &ck) in c.iter().enumerate() {
            let o = self.rgb[i + k] as f32;
            self.rgb[i + k] = (o + (ck as f32 - o) * a + 0.5) as u8;
        }
    }

    fn rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, c: [u8; 3]) {
        for y in (y0.max(0.0) as usize)..(y1.min(self.h as f64) as usize) {
            for x in (x0.max(0.0) as usize)..(x1.min(self.w as f64) as usize) {
                self.blend(x, y, c, 1.0);
            }
        }
    }

    /// Fills a patch through its sub-triangles; `values` gives the patch's
    /// nodal values (index 8 the centre) and `paint` a colour for a value.
    fn patch(&mut self, p: &Patch, pos: &[[f32; 2]], values: &dyn Fn(&Patch) -> [f64; 9], paint: &dyn Fn(f32) -> [u8; 3]) {
        let mut xy = [[0.0f64; 9]; 2];
        for d in 0..2 {
            with_centre(p.kind, &mut xy[d], |i| pos[p.nodes[i]][d]);
        }
        let t = values(p);
        for tri in sub_triangles(p.kind) {
            let q = tri.map(|i| [xy[0][i] as f32, xy[1][i] as f32]);
            self.triangle(q, tri.map(|i| t[i] as f32), paint);
        }
    }

    /// Fills a triangle, each pixel painted by the linearly interpolated
    /// value. Barycentric weights in f64 about the first vertex, with a
    /// small tolerance, leave no pixel out between triangles sharing an edge.
    fn triangle(&mut self, p: [[f32; 2]; 3], t: [f32; 3], paint: &dyn Fn(f32) -> [u8; 3]) {
        let o = [p[0][0] as f64, p[0][1] as f64];
        let q = p.map(|v| [v[0] as f64 - o[0], v[1] as f64 - o[1]]);
        let area = q[1][0] * q[2][1] - q[1][1] * q[2][0];
        if area.is_nan() || area.abs() <= 1e-12 {
            return;
        }
        let xmin = p.iter().map(|v| v[0]).fold(f32::INFINITY, f32::min).floor().max(0.0) as usize;
        let ymin = p.iter().map(|v| v[1]).fold(f32::INFINITY, f32::min).floor().max(0.0) as usize;
        let xmax = (p.iter().map(|v| v[0]).fold(f32::NEG_INFINITY, f32::max).ceil() as isize).min(self.w as isize - 1);
        let ymax = (p.iter().map(|v| v[1]).fold(f32::NEG_INFINITY, f32::max).ceil() as isize).min(self.h as isize - 1);
        if xmax < 0 || ymax < 0 {
            return;
        }
        let inv = 1.0 / area;
        // weights of vertices 1 and 2 as affine functions of the pixel centre
        let (a1, b1) = (q[2][1] * inv, -q[2][0] * inv);
        let (a2, b2) = (-q[1][1] * inv, q[1][0] * inv);
        let eps = -1e-9;
        let uniform = t[0] == t[1] && t[1] == t[2];
        let flat = paint(t[0]);
        for y in ymin..=ymax as usize {
            let py = y as f64 + 0.5 - o[1];
            for x in xmin..=xmax as usize {
                let px = x as f64 + 0.5 - o[0];
                let w1 = a1 * px + b1 * py;
                let w2 = a2 * px + b2 * py;
                let w0 = 1.0 - w1 - w2;
                if w0 >= eps && w1 >= eps && w2 >= eps {
                    let c = if uniform { flat } else { paint((w0 * t[0] as f64 + w1 * t[1] as f64 + w2 * t[2] as f64) as f32) };
                    let i = (y * self.w + x) * 3;
                    self.rgb[i..i + 3].copy_from_slice(&c);
                }
            }
        }
    }

    /// An anti-aliased line of the given width, round-capped or butt-ended.
    fn segment(&mut self, a: [f32; 2], b: [f32; 2], width: f32, c: [u8; 3], alpha: f32, round: bool) {
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        if !len.is_finite() {
            return;
        }
        // long lines in short pieces keep the scanned boxes small
        let pieces = (len / 12.0).ceil().max(1.0) as usize;
        let r = 0.5 * width;
        for s in 0..pieces {
            let (f0, f1) = (s as f32 / pieces as f32, (s + 1) as f32 / pieces as f32);
            let p = [a[0] + (b[0] - a[0]) * f0, a[1] + (b[1] - a[1]) * f0];
            let q = [a[0] + (b[0] - a[0]) * f1, a[1] + (b[1] - a[1]) * f1];
            let caps = round && (s == 0 || s + 1 == pieces);
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let l2 = dx * dx + dy * dy;
            let xmin = (p[0].min(q[0]) - r - 1.0).floor().max(0.0) as usize;
            let ymin = (p[1].min(q[1]) - r - 1.0).floor().max(0.0) as usize;
            let xmax = ((p[0].max(q[0]) + r + 1.0).ceil() as isize).min(self.w as isize - 1);
            let ymax = ((p[1].max(q[1]) + r + 1.0).ceil() as isize).min(self.h as isize - 1);
            for y in ymin as isize..=ymax {
                for x in xmin as isize..=xmax {
                    let (px, py) = (x as f32 + 0.5 - p[0], y as f32 + 0.5 - p[1]);
                    let t = if l2 > 0.0 { (px * dx + py * dy) / l2 } else { 0.0 };
                    // pieces own [f0, f1); the last also its end
                    if !caps && (!(0.0..=1.0).contains(&t) || (t == 1.0 && s + 1 != pieces)) {
                        continue;
                    }
                    if caps && ((s != 0 && t < 0.0) || (s + 1 != pieces && t >= 1.0)) {
                        continue;
                    }
                    let t = t.clamp(0.0, 1.0);
                    let d = (px - t * dx).hypot(py - t * dy);
                    let cover = (r + 0.5 - d).clamp(0.0, 1.0);
                    if cover > 0.0 {
                        self.blend(x as usize, y as usize, c, alpha * cover);
                    }
                }
            }
        }
    }

    fn polyline(&mut self, pts: impl Iterator<Item = [f32; 2]>, width: f32, c: [u8; 3], alpha: f32) {
        let mut last: Option<[f32; 2]> = None;
        for p in pts {
            if let Some(q) = last {
                self.segment(q, p, width, c, alpha, false);
            }
            last = Some(p);
        }
    }

    fn dot(&mut self, p: [f32; 2], r: f32, c: [u8; 3]) {
        let (x0, x1) = ((p[0] - r - 1.0).floor().max(0.0) as isize, ((p[0] + r + 1.0).ceil() as isize).min(self.w as isize - 1));
        let (y0, y1) = ((p[1] - r - 1.0).floor().max(0.0) as isize, ((p[1] + r + 1.0).ceil() as isize).min(self.h as isize - 1));
        for y in y0..=y1 {
            for x in x0..=x1 {
                let d = (x as f32 + 0.5 - p[0]).hypot(y as f32 + 0.5 - p[1]);
                let cover = (r + 0.5 - d).clamp(0.0, 1.0);
                if cover > 0.0 {
                    self.blend(x as usize, y as usize, c, cover);
                }
            }
        }
    }

    /// Writes the labels with plotters (the embedded font), one glyph at a
    /// time: plotters 0.3.7 draws the glyphs of a string each shifted left
    /// by its whole-pixel left side bearing, which jumbles letter spacing
    /// ("op en") in bitmaps; placing them from the font's own metrics
    /// restores it.
    fn text(&mut self, labels: &[Label]) -> Result<(), String> {
        let (w, h) = (self.w as u32, self.h as u32);
        let metrics = FontMetrics::get().ok_or("the embedded font has no readable metrics")?;
        let root = BitMapBackend::with_buffer(&mut self.rgb, (w, h)).into_drawing_area();
        for l in labels {
            let colour = rgb(INK);
            let style = TextStyle::from(("sans-serif", l.size).into_font()).color(&colour).pos(Pos::new(HPos::Left, l.pos.1));
            let k = l.size / metrics.height;
            let width: f64 = l.text.chars().map(|c| metrics.glyph(c).0 * k).sum();
            let mut pen = match l.pos.0 {
                HPos::Left => l.at.0,
                HPos::Center => l.at.0 - 0.5 * width,
                HPos::Right => l.at.0 - width,
            };
            let mut buf = [0u8; 4];
            for c in l.text.chars() {
                let (advance, lsb) = metrics.glyph(c);
                if !c.is_whitespace() {
                    let x = pen.round() as i32 + (lsb * k).floor() as i32;
                    root.draw_text(c.encode_utf8(&mut buf), &style, (x, l.at.1.round() as i32)).map_err(|e| format!("writing \"{}\" on the picture: {e:?}", l.text))?;
                }
                pen += advance * k;
            }
        }
        root.present().map_err(|e| format!("{e:?}"))?;
        Ok(())
    }
}

/// Horizontal metrics of the embedded font (TrueType `hhea`, `hmtx` and the
/// format-4 `cmap`), in font units.
struct FontMetrics {
    /// Ascender minus descender: the unit ab_glyph scales a size by.
    height: f64,
    /// Advance width and left side bearing of every glyph.
    hmtx: Vec<(f64, f64)>,
    /// cmap format 4 segments: (end, start, delta, range offset, its position).
    segments: Vec<(u16, u16, u16, u16, usize)>,
    cmap: &'static [u8],
}

impl FontMetrics {
    fn get() -> Option<&'static FontMetrics> {
        static METRICS: std::sync::OnceLock<Option<FontMetrics>> = std::sync::OnceLock::new();
        METRICS.get_or_init(|| FontMetrics::parse(include_bytes!("../../assets/DejaVuSans.ttf"))).as_ref()
    }

    fn parse(font: &'static [u8]) -> Option<FontMetrics> {
        let u16_at = |b: &[u8], at: usize| -> Option<u16> { Some(u16::from_be_bytes(b.get(at..at + 2)?.try_into().ok()?)) };
        let u32_at = |b: &[u8], at: usize| -> Option<usize> { Some(u32::from_be_bytes(b.get(at..at + 4)?.try_into().ok()?) as usize) };
        let table = |tag: &[u8; 4]| -> Option<&'static [u8]> {
            let n = u16_at(font, 4)? as usize;
            let r = (0..n).map(|i| 12 + 16 * i).find(|&r| font.get(r..r + 4) == Some(&tag[..]))?;
            font.get(u32_at(font, r + 8)?..u32_at(font, r + 8)? + u32_at(font, r + 12)?)
        };
        let (hhea, hmtx, cmap) = (table(b"hhea")?, table(b"hmtx")?, table(b"cmap")?);
        let height = u16_at(hhea, 4)? as i16 as f64 - u16_at(hhea, 6)? as i16 as f64;
        let n_long = u16_at(hhea, 34)? as usize;
        let mut metrics = Vec::new();
        for g in 0..n_long {
            metrics.push((u16_at(hmtx, 4 * g)? as f64, u16_at(hmtx, 4 * g + 2)? as i16 as f64));
        }
        let last = metrics.last()?.0;
        let mut at = 4 * n_long;
        while let Some(lsb) = u16_at(hmtx, at) {
            metrics.push((last, lsb as i16 as f64));
            at += 2;
        }
        let sub = (0..u16_at(cmap, 2)? as usize).map(|i| 4 + 8 * i).find_map(|r| {
            let (platform, encoding) = (u16_at(cmap, r)?, u16_at(cmap, r + 2)?);
            let off = u32_at(cmap, r + 4)?;
            ((platform == 3 && encoding == 1 || platform == 0) && u16_at(cmap, off)? == 4).then_some(off)
        })?;
        let seg2 = u16_at(cmap, sub + 6)? as usize;
        let mut segments = Vec::new();
        for i in 0..seg2 / 2 {
            let end = u16_at(cmap, sub + 14 + 2 * i)?;
            let start = u16_at(cmap, sub + 16 + seg2 + 2 * i)?;
            let delta = u16_at(cmap, sub + 16 + 2 * seg2 + 2 * i)?;
            let pos = sub + 16 + 3 * seg2 + 2 * i;
            segments.push((end, start, delta, u16_at(cmap, pos)?, pos));
        }
        (height > 0.0).then_some(FontMetrics { height, hmtx: metrics, segments, cmap })
    }

    /// Advance width and left side bearing of the glyph of `c`.
    fn glyph(&self, c: char) -> (f64, f64) {
        let code = c as u32;
        let gid = (code <= 0xFFFF)
            .then(|| {
                let code = code as u16;
                let &(_, start, delta, range, pos) = self.segments.iter().find(|s| s.0 >= code)?;
                if code < start {
                    return None;
                }
                if range == 0 {
                    return Some(code.wrapping_add(delta));
                }
                let at = pos + range as usize + 2 * (code - start) as usize;
                let g = u16::from_be_bytes(self.cmap.get(at..at + 2)?.try_into().ok()?);
                (g != 0).then(|| g.wrapping_add(delta))
            })
            .flatten()
            .unwrap_or(0);
        self.hmtx.get(gid as usize).or(self.hmtx.first()).copied().unwrap_or((0.0, 0.0))
    }
}

// ---------------------------------------------------------------------------
// The interface plot
// ---------------------------------------------------------------------------

/// The pairs of one interface in order along it.
struct Along {
    /// Runs of pairs (pair index, position s); lines are drawn within a run.
    runs: Vec<Vec<(usize, f64)>>,
    /// What s measures, for the axis.
    axis: String,
}

/// Orders an interface's pairs: in 2D by walking its chain of facets from
/// the end nearest the model's lower-left corner (arc length), else by the
/// position along the direction in which the pairs spread most.
fn along(run: &Run, ii: usize) -> Along {
    let model = &run.model;
    let iface = &model.interfaces[ii];
    let mut pair_of = std::collections::HashMap::new();
    for (i, p) in model.pairs.iter().enumerate() {
        pair_of.insert(p.k, i);
    }
    let mut nodes: Vec<usize> = iface.facets.iter().flat_map(|f| f.nodes.iter().copied()).filter(|k| pair_of.contains_key(k)).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let x = |k: usize| model.coords[k];
    let corner = {
        let mut lo = [f64::INFINITY; 3];
        for &k in model.bodies.iter().flat_map(|b| &b.cells).flat_map(|c| &c.nodes) {
            for (l, x) in lo.iter_mut().zip(model.coords[k]) {
                *l = l.min(x);
            }
        }
        lo
    };
    let dist = |a: [f64; 3], b: [f64; 3]| dot(sub3(a, b), sub3(a, b)).sqrt();
    if model.analysis != Analysis::Solid {
        // links between consecutive nodes of each facet (corner, mid, corner)
        let mut links: std::collections::HashMap<usize, Vec<usize>> = std::collections::HashMap::new();
        for f in &iface.facets {
            let chain: Vec<usize> = if f.nodes.len() == 3 { vec![f.nodes[0], f.nodes[2], f.nodes[1]] } else { f.nodes.clone() };
            for w in chain.windows(2) {
                links.entry(w[0]).or_default().push(w[1]);
                links.entry(w[1]).or_default().push(w[0]);
            }
        }
        if links.values().all(|v| v.len() <= 2) {
            let mut seen = std::collections::HashSet::new();
            let mut runs = Vec::new();
            let mut s = 0.0;
            let mut origin = None;
            loop {
                // open chains start at an end, closed ones anywhere; nearest the corner first
                let left = links.keys().copied().filter(|k| !seen.contains(k));
                let ends: Vec<usize> = left.clone().filter(|k| links[k].len() == 1).collect();
                let pool: Vec<usize> = if ends.is_empty() { left.collect() } else { ends };
                let Some(&start) = pool.iter().min_by(|&&a, &&b| dist(x(a), corner).total_cmp(&dist(x(b), corner))) else { break };
                origin.get_or_insert(start);
                let mut run_pairs = Vec::new();
                let (mut prev, mut at) = (usize::MAX, start);
                loop {
                    seen.insert(at);
                    if let Some(&p) = pair_of.get(&at) {
                        run_pairs.push((p, s));
                    }
                    let Some(&next) = links[&at].iter().find(|&&m| m != prev && !seen.contains(&m)) else { break };
                    s += dist(x(at), x(next));
                    (prev, at) = (at, next);
                }
                runs.push(run_pairs);
            }
            let o = origin.map(x).unwrap_or_default();
            return Along { runs, axis: format!("distance along the interface from ({}, {})", num(o[0]), num(o[1])) };
        }
    }
    // the principal direction of the pairs' positions
    let n = nodes.len().max(1) as f64;
    let mean: [f64; 3] = std::array::from_fn(|d| nodes.iter().map(|&k| x(k)[d]).sum::<f64>() / n);
    let mut cov = nalgebra::Matrix3::<f64>::zeros();
    for &k in &nodes {
        let r = sub3(x(k), mean);
        for i in 0..3 {
            for j in 0..3 {
                cov[(i, j)] += r[i] * r[j];
            }
        }
    }
    let eig = nalgebra::SymmetricEigen::new(cov);
    let imax = eig.eigenvalues.iamax();
    let mut dir = [eig.eigenvectors[(0, imax)], eig.eigenvectors[(1, imax)], eig.eigenvectors[(2, imax)]];
    if dot(dir, [1.0, 1.0, 1.0]) < 0.0 {
        dir = dir.map(|v| -v);
    }
    let mut pts: Vec<(usize, f64)> = nodes.iter().map(|&k| (pair_of[&k], dot(sub3(x(k), mean), dir))).collect();
    let smin = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    for p in &mut pts {
        p.1 -= smin;
    }
    pts.sort_by(|a, b| a.1.total_cmp(&b.1));
    Along { runs: vec![pts], axis: format!("position along the direction ({}, {}, {})", num(dir[0]), num(dir[1]), num(dir[2])) }
}

/// An SVG with one panel per interface: the normal stress σn (tension
/// positive) and the shear stress τ against the position along it, the
/// contact state as background bands (2D) or marker colours (3D).
pub fn interface_plot_svg(run: &Run) -> Result<String, String> {
    let (w, h) = interface_plot_size(run)?;
    let mut out = String::new();
    interface_plot_on(SVGBackend::with_string(&mut out, (w, h)).into_drawing_area(), run)?;
    Ok(out)
}

/// The same plot as [`interface_plot_svg`], as a PNG, to look at in tests
/// (plotters' bitmap text spaces letters unevenly, see [`Canvas::text`]).
#[cfg(test)]
fn interface_plot_png(run: &Run) -> Result<Vec<u8>, String> {
    let (w, h) = interface_plot_size(run)?;
    let mut buf = vec![255u8; w as usize * h as usize * 3];
    interface_plot_on(BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area(), run)?;
    encode_png(w as usize, h as usize, &buf)
}

fn interface_plot_size(run: &Run) -> Result<(u32, u32), String> {
    if run.contact.is_none() || run.model.interfaces.is_empty() {
        return Err("the run has no contact interface to plot".into());
    }
    Ok((1000, 420 * run.model.interfaces.len() as u32))
}

fn interface_plot_on<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, run: &Run) -> Result<(), String> {
    register_font();
    root.fill(&WHITE).map_err(|e| format!("{e:?}"))?;
    let n = run.model.interfaces.len();
    for (ii, area) in root.split_evenly((n, 1)).iter().enumerate() {
        interface_panel(area, run, ii)?;
    }
    root.present().map_err(|e| format!("{e:?}"))
}

fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

fn interface_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, run: &Run, ii: usize) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Debug| format!("{e:?}");
    let c = run.contact.as_ref().ok_or("no contact")?;
    let model = &run.model;
    let iface = &model.interfaces[ii];
    let solid = model.analysis == Analysis::Solid;
    let al = along(run, ii);
    let all = || al.runs.iter().flatten();
    let sn = |p: usize| c.pairs[p].sigma_n;
    // in 2D the shear keeps its sign (along the tangent t)
    let tau = |p: usize| if solid { c.pairs[p].tau() } else { c.pairs[p].tau_t };
    let mut counts = [0usize; 3];
    for &(p, _) in all() {
        counts[c.states[p].code() as usize] += 1;
    }
    let smax = all().map(|q| q.1).fold(0.0, f64::max).max(1e-300);
    let (mut ylo, mut yhi) = (0.0f64, 0.0f64);
    for &(p, _) in all() {
        for v in [sn(p), tau(p)].into_iter().filter(|v| v.is_finite()) {
            ylo = ylo.min(v);
            yhi = yhi.max(v);
        }
    }
    let pad = 0.08 * (yhi - ylo).max(1e-30);
    let (ylo, yhi) = (ylo - pad, yhi + pad);
    let (xlo, xhi) = (-0.02 * smax, 1.02 * smax);
    let caption = format!(
        "{}: \"{}\" | \"{}\", {} pairs: {} stick, {} slip, {} open",
        iface.name,
        model.bodies[iface.body_i].name,
        model.bodies[iface.body_ii].name,
        counts.iter().sum::<usize>(),
        counts[2],
        counts[1],
        counts[0]
    );
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(14)
        .x_label_area_size(46)
        .y_label_area_size(78)
        .build_cartesian_2d(xlo..xhi, ylo..yhi)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(al.axis.as_str())
        .y_desc("contact stress")
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(|e| err(&e))?;
    let blue = RGBColor(31, 90, 180);
    let purple = RGBColor(150, 60, 170);
    if !solid {
        // each pair's state over the half-way points to its neighbours
        let mut bands = Vec::new();
        for r in &al.runs {
            for (i, &(p, s)) in r.iter().enumerate() {
                let a = if i == 0 { s } else { 0.5 * (s + r[i - 1].1) };
                let b = if i + 1 == r.len() { s } else { 0.5 * (s + r[i + 1].1) };
                bands.push(Rectangle::new([(a, ylo), (b, yhi)], rgb(state_colour(c.states[p])).mix(0.22).filled()));
            }
        }
        chart.draw_series(bands).map_err(|e| err(&e))?;
    }
    chart.draw_series(LineSeries::new(vec![(xlo, 0.0), (xhi, 0.0)], BLACK.mix(0.5))).map_err(|e| err(&e))?;
    if solid {
        let dots = all().map(|&(p, s)| Circle::new((s, sn(p)), 4, rgb(state_colour(c.states[p])).filled()));
        chart.draw_series(dots).map_err(|e| err(&e))?.label("σn (normal, tension > 0)").legend(|(x, y)| Circle::new((x + 9, y), 4, BLACK.filled()));
        let tris = all().map(|&(p, s)| TriangleMarker::new((s, tau(p)), 5, rgb(state_colour(c.states[p])).stroke_width(2)));
        chart.draw_series(tris).map_err(|e| err(&e))?.label("τ (shear, magnitude)").legend(|(x, y)| TriangleMarker::new((x + 9, y), 5, BLACK.stroke_width(2)));
    } else {
        for (i, r) in al.runs.iter().enumerate() {
            let pts: Vec<(f64, f64)> = r.iter().map(|&(p, s)| (s, sn(p))).collect();
            let a = chart.draw_series(LineSeries::new(pts.clone(), blue.stroke_width(2))).map_err(|e| err(&e))?;
            if i == 0 {
                a.label("σn (normal, tension > 0)").legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], blue.stroke_width(2)));
            }
            chart.draw_series(pts.iter().map(|&q| Circle::new(q, 3, blue.filled()))).map_err(|e| err(&e))?;
            let pts: Vec<(f64, f64)> = r.iter().map(|&(p, s)| (s, tau(p))).collect();
            let a = chart.draw_series(LineSeries::new(pts.clone(), purple.stroke_width(2))).map_err(|e| err(&e))?;
            if i == 0 {
                a.label("τ (shear, along the tangent)").legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], purple.stroke_width(2)));
            }
            chart.draw_series(pts.iter().map(|&q| TriangleMarker::new(q, 4, purple.filled()))).map_err(|e| err(&e))?;
        }
    }
    for (s, count) in [(ContactState::Stick, counts[2]), (ContactState::Slip, counts[1]), (ContactState::Open, counts[0])] {
        if count > 0 {
            let col = rgb(state_colour(s));
            let style = if solid { col.filled() } else { col.mix(0.35).filled() };
            chart
                .draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())
                .map_err(|e| err(&e))?
                .label(s.name())
                .legend(move |(x, y)| Rectangle::new([(x + 2, y - 6), (x + 16, y + 6)], style));
        }
    }
    // the legend goes in the corner with the fewest points under it
    let entries = 2 + counts.iter().filter(|&&c| c > 0).count();
    let (lw, lh) = (0.34, (entries as f64 * 22.0 + 12.0) / (area.dim_in_pixel().1 as f64 - 90.0));
    let under = |fx: f64, fy: f64| {
        let (bx, by) = (fx * (1.0 - lw), fy * (1.0 - lh));
        all()
            .flat_map(|&(p, s)| [(s, sn(p)), (s, tau(p))])
            .map(|(s, v)| ((s - xlo) / (xhi - xlo), (v - ylo) / (yhi - ylo)))
            .filter(|&(x, y)| x >= bx && x <= bx + lw && y >= by && y <= by + lh)
            .count()
    };
    let corners = [
        (SeriesLabelPosition::UpperRight, 1.0, 1.0),
        (SeriesLabelPosition::LowerRight, 1.0, 0.0),
        (SeriesLabelPosition::UpperLeft, 0.0, 1.0),
        (SeriesLabelPosition::LowerLeft, 0.0, 0.0),
        (SeriesLabelPosition::UpperMiddle, 0.5, 1.0),
        (SeriesLabelPosition::LowerMiddle, 0.5, 0.0),
    ];
    let place = corners.into_iter().min_by_key(|&(_, fx, fy)| under(fx, fy)).map(|c| c.0).unwrap_or(SeriesLabelPosition::UpperRight);
    chart
        .configure_series_labels()
        .position(place)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", 14))
        .draw()
        .map_err(|e| err(&e))?;
    Ok(())
}

// ---------------------------------------------------------------------------
// PNG
// ---------------------------------------------------------------------------

/// An 8-bit RGB PNG of `rgb` (rows from the top), each row with the filter
/// the `png` crate's adaptive heuristic picks.
fn encode_png(w: usize, h: usize, rgb: &[u8]) -> Result<Vec<u8>, String> {
    let err = |e: png::EncodingError| format!("encoding the PNG: {e}");
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w as u32, h as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    let mut writer = enc.write_header().map_err(err)?;
    writer.write_image_data(rgb).map_err(err)?;
    writer.finish().map_err(err)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::driver::{self, RunOptions};
    use crate::scene::Scene;
    use std::path::{Path, PathBuf};

    /// Decodes a PNG to (width, height, rgb) with the `png` crate.
    fn decode(bytes: &[u8]) -> (usize, usize, Vec<u8>) {
        let mut reader = png::Decoder::new(bytes).read_info().expect("a PNG header");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("the PNG's pixels");
        assert_eq!((info.color_type, info.bit_depth), (png::ColorType::Rgb, png::BitDepth::Eight));
        buf.truncate(info.buffer_size());
        (info.width as usize, info.height as usize, buf)
    }

    #[test]
    fn png_decodes_to_the_pixels_it_was_given() {
        let (w, h) = (97, 61);
        let mut rgb = vec![255u8; w * h * 3];
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) * 3;
                rgb[i] = if x < 30 { 10 } else { (x * 2) as u8 };
                rgb[i + 1] = ((x * y) % 251) as u8;
                rgb[i + 2] = if y > 40 { ((x * 7919 + y * 104729) % 256) as u8 } else { 200 };
            }
        }
        let bytes = encode_png(w, h, &rgb).expect("PNG");
        let (dw, dh, back) = decode(&bytes);
        assert_eq!((dw, dh), (w, h));
        assert!(back == rgb, "pixels survive the round trip");
    }

    #[test]
    fn numbers_read_well() {
        assert_eq!(num(0.15000000000000002), "0.15");
        assert_eq!(num(-2125.0), "-2125");
        assert_eq!(num(1.2345e-5), "1.23e-5");
        assert_eq!(sig2(23456.0), "2.3e4");
        assert_eq!(sig2(234.5), "230");
        assert_eq!(nice_step(0.037), 0.05);
        assert_eq!(Field::parse("sxy"), Some(Field::Sxy));
    }

    #[test]
    fn font_metrics_give_plotters_string_widths() {
        register_font();
        let m = FontMetrics::get().expect("metrics");
        for text in ["contact pairs", "open (6)", "σθθ (hoop stress) × 2.3e4"] {
            let ours: f64 = text.chars().map(|c| m.glyph(c).0).sum::<f64>() * 40.0 / m.height;
            let (w, _) = ("sans-serif", 40.0).into_font().box_size(text).expect("layout");
            assert!((ours - w as f64).abs() <= 2.0, "{text}: {ours} vs {w}");
        }
    }

    fn out_dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("subcontact_picture_{name}"));
        std::fs::create_dir_all(&d).expect("temp dir");
        d
    }

    /// Where the pictures go for a person to look at.
    fn keep(name: &str, bytes: &[u8]) {
        let d = std::env::temp_dir().join("subcontact_pictures");
        std::fs::create_dir_all(&d).expect("picture dir");
        std::fs::write(d.join(name), bytes).expect("write picture");
    }

    /// Pixels of colour `c` where the model is drawn (not in the legend).
    fn count(cv: &Canvas, c: [u8; 3]) -> usize {
        cv.rgb.chunks_exact(3).enumerate().filter(|(i, p)| (i % cv.w) < PANEL_X as usize - 10 && p == &c).count()
    }

    fn cylinder(lc: f64, order: usize) -> driver::Run {
        let mut scene = Scene::load(Path::new("geo/cylinder.toml")).expect("scene");
        scene.gmsh.setnumber = vec![("lc".into(), lc)];
        scene.gmsh.order = order;
        let opts = RunOptions { out: Some(out_dir(&format!("cylinder_{lc}_{order}"))), skip_output: true, ..Default::default() };
        driver::run_scene(scene, &opts).expect("cylinder run")
    }

    #[test]
    fn cylinder_picture_shows_the_field_and_every_contact_state() {
        let mut run = cylinder(0.25, 2);
        let bytes = deformed_png(&run, Field::VonMises, None).expect("picture");
        let (w, h, _) = decode(&bytes);
        assert_eq!((w, h), (W, H));
        keep("cylinder_von_mises.png", &bytes);
        let cv = deformed_canvas(&run, Field::VonMises, None).expect("canvas");
        // the cut sticks everywhere (the paper's data)
        assert!(count(&cv, STICK) > 300, "stick line drawn: {}", count(&cv, STICK));
        assert_eq!(count(&cv, OPEN) + count(&cv, SLIP), 0);
        keep("cylinder_szz.png", &deformed_png(&run, Field::Szz, None).expect("picture"));
        keep("cylinder_sxy.png", &deformed_png(&run, Field::Sxy, None).expect("picture"));

        // every state, in thirds along the cut
        let c = run.contact.as_mut().expect("contact");
        let n = c.states.len();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| {
            let r = |p: usize| run.model.coords[run.model.pairs[p].k][0];
            r(a).total_cmp(&r(b))
        });
        for (i, &p) in order.iter().enumerate() {
            c.states[p] = [ContactState::Open, ContactState::Slip, ContactState::Stick][3 * i / n];
        }
        let cv = deformed_canvas(&run, Field::Displacement, Some(2.0e3)).expect("canvas");
        for (name, colour) in [("stick", STICK), ("slip", SLIP), ("open", OPEN)] {
            assert!(count(&cv, colour) > 100, "{name}: {} pixels", count(&cv, colour));
        }
        keep("cylinder_states_displacement.png", &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
        let svg = interface_plot_svg(&run).expect("interface plot");
        for want in ["A-A", "stick", "slip", "open", "σn", "distance along the interface from (2.121, 2.121)"] {
            assert!(svg.contains(want), "{want}");
        }
        keep("cylinder_states_interfaces.svg", svg.as_bytes());
        let bytes = interface_plot_png(&run).expect("interface plot");
        assert_eq!(decode(&bytes).0, 1000);
        keep("cylinder_states_interfaces.png", &bytes);
    }

    #[test]
    fn interface_pairs_are_ordered_by_arc_length_from_the_inner_end() {
        let run = cylinder(0.25, 2);
        let al = along(&run, 0);
        assert_eq!(al.runs.len(), 1);
        let r = &al.runs[0];
        assert_eq!(r.len(), run.model.pairs.len());
        for &(p, s) in r {
            let x = run.model.coords[run.model.pairs[p].k];
            let radius = x[0].hypot(x[1]);
            assert!((s - (radius - 3.0)).abs() < 1e-9, "s = {s} at r = {radius}");
        }
        keep("cylinder_interfaces.png", &interface_plot_png(&run).expect("plot"));
    }

    #[test]
    fn paper_mesh_picture_in_3d() {
        let run = driver::run(Path::new("geo/cylinder_paper.toml"), &RunOptions { out: Some(out_dir("paper")), ..Default::default() }).expect("paper run");
        let cv = deformed_canvas(&run, Field::VonMises, None).expect("canvas");
        assert!(count(&cv, STICK) > 50, "stick dots: {}", count(&cv, STICK));
        let bytes = encode_png(cv.w, cv.h, &cv.rgb).expect("PNG");
        assert_eq!(decode(&bytes).0, W);
        keep("paper_von_mises.png", &bytes);
        let svg = interface_plot_svg(&run).expect("plot");
        assert!(svg.contains("12 stick"));
        keep("paper_interfaces.svg", svg.as_bytes());
        keep("paper_interfaces.png", &interface_plot_png(&run).expect("plot"));
    }

    /// Two blocks stacked on a frictional joint (f = 0.8) without cohesion
    /// or tensile strength, the top face pushed down and sideways: the push
    /// tips the top block, so the joint opens at one end, slips in the
    /// middle and sticks where it is pressed hardest. Every 2D kind and
    /// hex20 (the boxes clamped at the base and held in z, the top one held
    /// by the joint); tet4 under a joint too strong to give (pushed, the
    /// unstructured tetrahedra make the contact iteration cycle).
    #[test]
    fn stacked_blocks_pushed_sideways_show_the_states_they_reach() {
        let dir = out_dir("stack");
        for geo in ["contact_stack.geo", "contact_stack3d.geo"] {
            std::fs::copy(format!("tests/geo/{geo}"), dir.join(geo)).expect("copy geo");
        }
        let weak = "friction = 0.8\ncohesion = 0.0\ntensile_strength = 0.0";
        let strong = "friction = 0.5\ncohesion = 100.0\ntensile_strength = 100.0";
        let plane = ("contact_stack.geo", "plane_stress", "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n[[supports]]\ngroup = \"corner\"\nfix = [\"x\"]\n", "[0.5, -1.0]", weak);
        let solid = ("contact_stack3d.geo", "solid", "[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n[[supports]]\ngroup = \"z_faces\"\nfix = [\"z\"]\n", "[0.5, -1.0, 0.0]", weak);
        let cases = [
            ("tri6", 2, "n = 8, quad = 0", plane),
            ("tri3", 1, "n = 10, quad = 0", plane),
            ("quad4", 1, "n = 10, quad = 1", plane),
            ("quad8", 2, "n = 6, quad = 1, serendipity = 1", plane),
            ("hex20", 2, "n = 4, nz = 2, hex = 1, serendipity = 1", solid),
            ("tet4", 1, "n = 6, hex = 0", (solid.0, solid.1, "[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n", "[0.3, -1.0, 0.2]", strong)),
        ];
        for (name, order, set, (geo, analysis, supports, traction, joint)) in cases {
            let toml = format!(
                "title = \"Two blocks, the top one pushed sideways ({name})\"\nmesh = \"{geo}\"\nanalysis = \"{analysis}\"\n\
                 [gmsh]\norder = {order}\nsetnumber = {{ {set} }}\n[materials.m]\nE = 1000.0\nnu = 0.25\n\
                 [[bodies]]\ngroup = \"bottom\"\nmaterial = \"m\"\n[[bodies]]\ngroup = \"top\"\nmaterial = \"m\"\n\
                 [[contacts]]\ngroup = \"joint\"\n{joint}\n\
                 {supports}[[loads]]\ngroup = \"top_face\"\ntraction = {traction}\n"
            );
            let path = dir.join(format!("stack_{name}.toml"));
            std::fs::write(&path, toml).expect("scene");
            let opts = RunOptions { out: Some(dir.join(name)), skip_output: true, ..Default::default() };
            let run = driver::run(&path, &opts).expect("stack run");
            let c = run.contact.as_ref().expect("contact");
            let counts = driver::state_counts(&c.states);
            eprintln!("{name}: {} stick, {} slip, {} open after {} iterations", counts[2], counts[1], counts[0], c.iterations);
            assert!(c.converged, "{name}");
            if joint == weak {
                assert!(counts[0] > 0 && counts[2] > 0, "{name}: the joint opens at one end and sticks at the other: {counts:?}");
            }
            let t = std::time::Instant::now();
            let cv = deformed_canvas(&run, Field::VonMises, None).expect("canvas");
            eprintln!("{name}: rendered in {:.3} s", t.elapsed().as_secs_f64());
            for (state, colour, n) in [("open", OPEN, counts[0]), ("slip", SLIP, counts[1]), ("stick", STICK, counts[2])] {
                assert_eq!(count(&cv, colour) > 0, n > 0, "{name}: {state} drawn exactly when present ({n} pairs)");
            }
            keep(&format!("stack_{name}_von_mises.png"), &encode_png(cv.w, cv.h, &cv.rgb).expect("PNG"));
            keep(&format!("stack_{name}_syy.png"), &deformed_png(&run, Field::Syy, None).expect("picture"));
            keep(&format!("stack_{name}_interfaces.png"), &interface_plot_png(&run).expect("plot"));
            let svg = interface_plot_svg(&run).expect("plot");
            assert!(svg.contains(&format!("{} stick, {} slip, {} open", counts[2], counts[1], counts[0])));
        }
    }

    /// Regression: thin triangles sharing edges left unpainted pixels
    /// between them (white specks over a fine mesh) when the barycentric
    /// weights were taken in f32 about the image origin.
    #[test]
    fn triangles_sharing_edges_leave_no_gaps() {
        let mut cv = Canvas::new(400, 300);
        let n = 60;
        // a jittered grid over [50, 350] x [40, 260], two triangles per square
        let pt = |i: usize, j: usize| -> [f32; 2] {
            let jitter = |k: usize| if i == 0 || j == 0 || i == n || j == n { 0.0 } else { ((k * 7919 % 101) as f32 / 101.0 - 0.5) * 2.0 };
            [50.0 + 300.0 * i as f32 / n as f32 + jitter(i * 31 + j), 40.0 + 220.0 * j as f32 / n as f32 + jitter(j * 17 + i * 3)]
        };
        for i in 0..n {
            for j in 0..n {
                let (a, b, c, d) = (pt(i, j), pt(i + 1, j), pt(i + 1, j + 1), pt(i, j + 1));
                cv.triangle([a, b, c], [0.0; 3], &|_| [0, 0, 0]);
                cv.triangle([a, c, d], [0.0; 3], &|_| [0, 0, 0]);
            }
        }
        let white = (41..259).flat_map(|y| (51..349).map(move |x| (x, y))).filter(|&(x, y)| cv.rgb[(y * 400 + x) * 3] == 255).count();
        assert_eq!(white, 0, "unpainted pixels inside the mesh");
    }

    /// About 1e5 nodes (quad9, lc = 0.022): prints the render time; run with
    /// `cargo test --release --lib picture -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn render_time_of_a_fine_mesh() {
        let run = cylinder(0.022, 2);
        eprintln!("{} nodes, {} cells", run.model.n_nodes(), run.model.bodies.iter().map(|b| b.cells.len()).sum::<usize>());
        for _ in 0..2 {
            let t = std::time::Instant::now();
            let cv = deformed_canvas(&run, Field::VonMises, None).expect("canvas");
            let raster = t.elapsed().as_secs_f64();
            let bytes = encode_png(cv.w, cv.h, &cv.rgb).expect("PNG");
            let total = t.elapsed().as_secs_f64();
            let t = std::time::Instant::now();
            let svg = interface_plot_svg(&run).expect("plot");
            eprintln!("deformed: raster {raster:.3} s, with PNG {total:.3} s ({} kB); interfaces: {:.3} s", bytes.len() / 1024, t.elapsed().as_secs_f64());
            keep("fine_von_mises.png", &bytes);
            keep("fine_interfaces.svg", svg.as_bytes());
        }
    }
}
