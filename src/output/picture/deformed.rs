//! The deformed picture (PNG, 1200 x 800): the model moved by its
//! magnified displacements and coloured by a field, the undeformed shape as
//! a grey ghost behind it (2D), and the contact states on the interfaces.
//! 3D models are drawn in an oblique view ([`View`]), boundary faces far to
//! near (painter's algorithm), lit from over the viewer's shoulder.
//!
//! The picture frames the contacts, or the region the scene names
//! ([`super::framing`]); the magnification and the colours come from what
//! is drawn. Bodies whose stresses differ by more than a factor of 5 (a
//! concrete lining in soft rock) get a colour scale each, with its own
//! colour map and bar ([`scales`]), so that the stiff body does not leave
//! the soft one a single colour; within a scale, a few outlying nodes do
//! not take the whole bar ([`Limits::of`]).

use plotters::style::text_anchor::{HPos, VPos};

use super::colours::{state_colour, GHOST, INK, NO_PAIR};
use super::cutaway::{Cut, Place, Vertex};
use super::field::Field;
use super::framing::{focus, Focus};
use super::label_numbers::{num, sig2};
use super::legend::{colour_bar, colour_map_of, legend, lut_colour, triad, LegendOf, Limits, PANEL_X};
use super::picture_error::PictureError;
use super::raster::{encode_png, label, register_font, Canvas};
use super::snapshot::Snapshot;
use super::surface::{centred, edges, fill, mesh_alpha, patches, sub_triangles, with_centre, Patch};
use super::view::View;
use crate::fem::material::von_mises;
use crate::fem::vec3::{dot, normalized};
use crate::fem::Analysis;
use crate::model::Model;

pub(super) const W: usize = 1200;
pub(super) const H: usize = 800;
/// Where the model goes: x0, y0, x1, y1 in pixels.
const PLOT: [f64; 4] = [24.0, 96.0, 960.0, 780.0];

/// A PNG (1200 x 800) of the model deformed by the magnified displacements
/// and coloured by `field`, with the contact states on the interfaces.
/// `scale` is the displacement magnification; None picks one that makes the
/// largest displacement 5 % of the drawn region's size.
pub fn deformed_png(snap: &Snapshot, field: Field, scale: Option<f64>) -> Result<Vec<u8>, PictureError> {
    let c = deformed_canvas(snap, field, scale)?;
    encode_png(c.w, c.h, &c.rgb)
}

/// A PNG of blocks moved by a mechanism's rigid motion (`snap.u`, whose
/// size means nothing), coloured by it: the largest motion drawn
/// [`MECHANISM_SHARE`] of the drawn region's size, so that a toppling
/// block's heel visibly leaves its joint.
pub fn mechanism_png(snap: &Snapshot) -> Result<Vec<u8>, PictureError> {
    let c = canvas(snap, Field::Displacement, Magnify::Share(MECHANISM_SHARE))?;
    encode_png(c.w, c.h, &c.rgb)
}

/// The share of the drawn region's size that the largest displacement is
/// drawn: of a solution (elastic, small: 5 %, the shape still read) and of
/// a mechanism (rigid: 10 %, the joints it opens seen in 3D, where a 5 %
/// turn of a toppling block lifts its heel by ~1 % of the picture).
const SOLUTION_SHARE: f64 = 0.05;
const MECHANISM_SHARE: f64 = 0.10;

/// How displacements are magnified.
#[derive(Clone, Copy)]
enum Magnify {
    /// By this factor.
    Times(f64),
    /// The largest to this share of the drawn region's size.
    Share(f64),
}

pub(super) fn deformed_canvas(snap: &Snapshot, field: Field, scale: Option<f64>) -> Result<Canvas, PictureError> {
    canvas(snap, field, scale.map_or(Magnify::Share(SOLUTION_SHARE), Magnify::Times))
}

fn canvas(snap: &Snapshot, field: Field, scale: Magnify) -> Result<Canvas, PictureError> {
    register_font();
    let model = snap.model;
    let stresses_ok =
        snap.stresses.len() == model.bodies.len() || (snap.stresses.is_empty() && field == Field::Displacement);
    if snap.u.len() != model.n_nodes() * model.nd || !stresses_ok {
        return Err(PictureError::Mismatch { what: "displacements or stresses" });
    }
    let focus = focus(model, snap.region);
    let frame = Frame::new(snap, &focus, scale)?;
    let values = nodal_values(snap, field);
    // the colours come from what is drawn
    let mut shown = values.clone();
    for v in shown.iter_mut() {
        for (k, x) in v.iter_mut().enumerate() {
            if !frame.drawn(k) {
                *x = f32::NAN;
            }
        }
    }
    let group: Vec<usize> = model.bodies.iter().map(|b| b.group).collect();
    let scales = scales(field, &shown, &group, snap.one_scale);
    let mut cv = Canvas::new(W, H);
    draw_bodies(&mut cv, snap, &frame, &values, &scales);
    draw_contacts(&mut cv, snap, &frame);

    let mut labels = Vec::new();
    labels.push(label(snap.title.to_string(), (24.0, 14.0), 24.0, (HPos::Left, VPos::Top)));
    let shape = if frame.mag > 0.0 {
        format!("deformed shape, displacements × {} (largest displacement {})", sig2(frame.mag), num(frame.umax))
    } else {
        "undeformed shape (no displacement)".to_string()
    };
    labels.push(label(
        format!("{} on the {shape}", field.label(model.analysis)),
        (24.0, 48.0),
        17.0,
        (HPos::Left, VPos::Top),
    ));
    if let Some(note) = &focus.note {
        labels.push(label(note.clone(), (24.0, 72.0), 14.0, (HPos::Left, VPos::Top)));
    }
    // the bars one under the other, each with its bodies when there are several
    let n = scales.len().max(1) as f64;
    let slot = 460.0 / n;
    for (i, s) in scales.iter().enumerate() {
        let mut title = vec![field.label(model.analysis).to_string()];
        if scales.len() > 1 {
            title.push(format!("in {}", super::plan::body_list(model, &s.bodies, 3).0));
        }
        let (top, bottom) = if scales.len() == 1 {
            (146.0, 500.0)
        } else {
            (100.0 + i as f64 * slot + 70.0, 100.0 + (i + 1) as f64 * slot - 50.0)
        };
        colour_bar(&mut cv, &mut labels, &s.lut, &s.lim, &title, [PANEL_X, top, bottom]);
    }
    let of = LegendOf {
        counts: snap.contact.map(|c| crate::results::state_counts(&c.states)),
        solid: frame.view.is_some(),
        ghost: frame.moved() && frame.view.is_none(),
    };
    legend(&mut cv, &mut labels, &of, 580.0);
    if let Some(view) = &frame.view {
        triad(&mut cv, &mut labels, view);
    }
    cv.text(&labels)?;
    Ok(cv)
}

/// One colour scale: the bodies it colours, its limits and colour map.
pub(super) struct Scale {
    pub(super) bodies: Vec<usize>,
    pub(super) lim: Limits,
    pub(super) lut: Vec<[u8; 3]>,
}

/// How far apart (a factor) two bodies' stresses must be to get a colour
/// scale each, and the most scales a picture shows.
const APART: f64 = 5.0;
const MOST_SCALES: usize = 3;

/// The colour scales of a picture: one for every drawn body, except that
/// for stresses, body groups (`group[b]`: the `[[bodies]]` entry of model
/// body b; the blocks of one entry always share a scale) whose typical
/// magnitudes (the 99.5 % quantile of |value|) differ by more than
/// [`APART`] get a scale each, largest first, at most [`MOST_SCALES`] (the
/// smallest ones share the last). The displacement is continuous across
/// bodies and keeps one scale, and so does every field with `one`
/// (`[output] colour_scale = "one"`).
pub(super) fn scales(field: Field, values: &[Vec<f32>], group: &[usize], one: bool) -> Vec<Scale> {
    let signed = field.component().is_some();
    let drawn: Vec<usize> = (0..values.len()).filter(|&b| values[b].iter().any(|v| v.is_finite())).collect();
    let mut ids: Vec<usize> = drawn.iter().map(|&b| group.get(b).copied().unwrap_or(b)).collect();
    ids.sort_unstable();
    ids.dedup();
    let mut groups: Vec<Vec<usize>> = Vec::new();
    if field == Field::Displacement || ids.len() < 2 || one {
        groups.push(drawn);
    } else {
        let members = |g: usize| drawn.iter().copied().filter(move |&b| group.get(b).copied().unwrap_or(b) == g);
        let typical = |g: usize| -> f64 {
            let mut a: Vec<f32> =
                members(g).flat_map(|b| values[b].iter()).filter(|v| v.is_finite()).map(|v| v.abs()).collect();
            let n = a.len();
            let i = ((n - 1) as f64 * 0.995).round() as usize;
            *a.select_nth_unstable_by(i, |x, y| x.total_cmp(y)).1 as f64
        };
        let mut by: Vec<(usize, f64)> = ids.iter().map(|&g| (g, typical(g))).collect();
        by.sort_by(|x, y| y.1.total_cmp(&x.1).then(x.0.cmp(&y.0)));
        let mut top = f64::NAN;
        for (g, t) in by {
            if groups.is_empty() || (t * APART < top && groups.len() < MOST_SCALES) {
                groups.push(Vec::new());
                top = t;
            }
            if let Some(last) = groups.last_mut() {
                last.extend(members(g));
            }
        }
        for g in &mut groups {
            g.sort_unstable();
        }
    }
    groups
        .into_iter()
        .enumerate()
        .map(|(k, bodies)| {
            let vals: Vec<Vec<f32>> = bodies.iter().map(|&b| values[b].clone()).collect();
            let lim = Limits::of(signed, &vals);
            let lut = colour_map_of(k, signed, lim.lo, lim.hi);
            Scale { bodies, lim, lut }
        })
        .collect()
}

/// Where every node lands in the picture, deformed (`sd`) and undeformed
/// (`su`), with its depth in 3D (larger is nearer).
pub(super) struct Frame {
    mag: f64,
    umax: f64,
    /// Pixels per model length, and the model point at the picture's centre.
    px: f64,
    centre: [f64; 2],
    sd: Vec<[f32; 2]>,
    su: Vec<[f32; 2]>,
    depth: Vec<f64>,
    /// Whether each node is drawn (a node of a cell, inside the cut).
    used: Vec<bool>,
    /// The box the model is cut to.
    cut: Option<Cut>,
    /// The 3D view; None in 2D (x right, y up).
    pub(super) view: Option<View>,
}

/// Whether each node is drawn: a node of a cell, inside the cut if any.
fn drawn(model: &Model, focus: &Focus) -> Vec<bool> {
    let mut used = vec![false; model.n_nodes()];
    for &k in model.bodies.iter().flat_map(|b| &b.cells).flat_map(|c| &c.nodes) {
        used[k] = focus.cut.is_none_or(|c| c.contains(model.coords[k]));
    }
    used
}

/// The box of the drawn nodes and their largest displacement.
fn drawn_box(snap: &Snapshot, used: &[bool]) -> ([f64; 3], [f64; 3], f64) {
    let coords = &snap.model.coords;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let mut umax: f64 = 0.0;
    for k in (0..used.len()).filter(|&k| used[k]) {
        for d in 0..3 {
            lo[d] = lo[d].min(coords[k][d]);
            hi[d] = hi[d].max(coords[k][d]);
        }
        let u = displacement(snap, k);
        umax = umax.max(dot(u, u).sqrt());
    }
    (lo, hi, umax)
}

/// The corners of a cut, at `lo` in the directions it does not cut.
fn cut_corners(c: &Cut, lo: [f64; 3]) -> Vec<[f64; 3]> {
    (0..8)
        .map(|m| {
            std::array::from_fn(|d| {
                if d < c.dim {
                    if m >> d & 1 == 0 {
                        c.lo[d]
                    } else {
                        c.hi[d]
                    }
                } else {
                    lo[d]
                }
            })
        })
        .collect()
}

impl Frame {
    fn new(snap: &Snapshot, focus: &Focus, scale: Magnify) -> Result<Frame, PictureError> {
        let model = snap.model;
        let n = model.n_nodes();
        // 1. the nodes drawn, their box and the largest displacement
        let used = drawn(model, focus);
        let (mut lo, mut hi, umax) = drawn_box(snap, &used);
        // 2. a cut's corners frame the picture too (a box round a hole)
        let corners = focus.cut.as_ref().map_or_else(Vec::new, |c| cut_corners(c, lo));
        for x in &corners {
            for d in 0..3 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        if lo[0] > hi[0] {
            return Err(PictureError::Empty("the model has no cells to draw".into()));
        }
        // 3. the magnification of the displacements
        let extent: [f64; 3] = std::array::from_fn(|d| hi[d] - lo[d]);
        let size = extent.iter().copied().fold(0.0, f64::max);
        let mag = match scale {
            Magnify::Times(s) => s,
            Magnify::Share(share) if umax > 0.0 && umax.is_finite() => share * size / umax,
            Magnify::Share(_) => 0.0,
        };
        // 4. the view of the whole model, so that a framed picture keeps its orientation
        let (mlo, mhi) = super::view::model_box(model);
        let view = (model.analysis == Analysis::Solid)
            .then(|| View::new(std::array::from_fn(|d| mhi[d] - mlo[d]), model.gravity));
        let mut frame = Frame {
            mag,
            umax,
            px: 1.0,
            centre: [0.0; 2],
            sd: Vec::new(),
            su: Vec::new(),
            depth: vec![0.0; n],
            used,
            cut: focus.cut,
            view,
        };
        // 5. every node placed, and the picture fitted to the drawn ones
        frame.fit(snap, &corners);
        Ok(frame)
    }

    /// Places every node deformed and undeformed, and fits the drawn nodes
    /// and the cut's corners to the plot area.
    fn fit(&mut self, snap: &Snapshot, corners: &[[f64; 3]]) {
        let (model, mag) = (snap.model, self.mag);
        let n = model.n_nodes();
        let mut flat = vec![[[0.0f64; 2]; 2]; n];
        let (mut plo, mut phi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let mut widen = |p: [f64; 2]| {
            for d in 0..2 {
                plo[d] = plo[d].min(p[d]);
                phi[d] = phi[d].max(p[d]);
            }
        };
        for k in 0..n {
            let (u, x) = (displacement(snap, k), model.coords[k]);
            let (pd, dd) = self.place(std::array::from_fn(|d| x[d] + mag * u[d]));
            flat[k] = [pd, self.place(x).0];
            self.depth[k] = dd;
            if self.used[k] {
                widen(pd);
                widen(flat[k][1]);
            }
        }
        for x in corners {
            widen(self.place(*x).0);
        }
        let [x0, y0, x1, y1] = PLOT;
        let px = ((x1 - x0) / (phi[0] - plo[0])).min((y1 - y0) / (phi[1] - plo[1]));
        self.px = if px.is_finite() && px > 0.0 { px } else { 1.0 };
        self.centre = [0.5 * (plo[0] + phi[0]), 0.5 * (plo[1] + phi[1])];
        self.sd = flat.iter().map(|p| self.screen(p[0])).collect();
        self.su = flat.iter().map(|p| self.screen(p[1])).collect();
    }

    /// A model point on the picture's plane, and its depth.
    fn place(&self, x: [f64; 3]) -> ([f64; 2], f64) {
        match &self.view {
            Some(v) => v.project(x),
            None => ([x[0], x[1]], 0.0),
        }
    }

    /// A point of the picture's plane in pixels.
    fn screen(&self, p: [f64; 2]) -> [f32; 2] {
        let [x0, y0, x1, y1] = PLOT;
        [
            (0.5 * (x0 + x1) + (p[0] - self.centre[0]) * self.px) as f32,
            (0.5 * (y0 + y1) - (p[1] - self.centre[1]) * self.px) as f32,
        ]
    }

    /// Where a clipped piece's vertex lands, deformed or not, and its depth.
    fn vertex(&self, v: &Vertex, deformed: bool) -> ([f32; 2], f64) {
        let m = if deformed { self.mag } else { 0.0 };
        let (p, depth) = self.place(std::array::from_fn(|d| v.x[d] + m * v.u[d]));
        (self.screen(p), depth)
    }

    /// Whether the magnified displacements show (more than a pixel and a half).
    pub(super) fn moved(&self) -> bool {
        self.mag * self.umax * self.px > 1.5
    }

    /// Whether node k is drawn (a node of a cell, inside the cut).
    fn drawn(&self, k: usize) -> bool {
        self.used[k]
    }
}

fn displacement(snap: &Snapshot, k: usize) -> [f64; 3] {
    let nd = snap.model.nd;
    std::array::from_fn(|c| if c < nd { snap.u[k * nd + c] } else { 0.0 })
}

/// The field at every node of every body (each body keeps its own averages
/// where bodies share nodes); NaN at nodes not in the body.
fn nodal_values(snap: &Snapshot, field: Field) -> Vec<Vec<f32>> {
    if snap.stresses.is_empty() {
        // displacement magnitude without recovered stresses
        return snap
            .model
            .bodies
            .iter()
            .map(|b| {
                let mut v = vec![f32::NAN; snap.model.n_nodes()];
                for k in crate::recover::body_nodes(b) {
                    let u = displacement(snap, k);
                    v[k] = dot(u, u).sqrt() as f32;
                }
                v
            })
            .collect();
    }
    snap.stresses
        .iter()
        .map(|bs| {
            let mut v = vec![f32::NAN; snap.model.n_nodes()];
            for (&k, s) in bs.nodes.iter().zip(&bs.stress) {
                v[k] = match field.component() {
                    Some(c) => s[c],
                    None if field == Field::VonMises => von_mises(s),
                    None => {
                        let u = displacement(snap, k);
                        dot(u, u).sqrt()
                    }
                } as f32;
            }
            v
        })
        .collect()
}

/// A patch's sub-triangles as vertices in the model (position,
/// displacement, field), for clipping to the cut.
fn patch_triangles(p: &Patch, vert: &dyn Fn(usize) -> Vertex) -> Vec<Vec<Vertex>> {
    let n = p.kind.n_nodes();
    let mut comps = [[0.0f64; 9]; 7];
    for (c, row) in comps.iter_mut().enumerate() {
        with_centre(p.kind, row, |i| {
            let v = vert(p.nodes[i]);
            match c {
                0..=2 => v.x[c],
                3..=5 => v.u[c - 3],
                _ => v.v as f64,
            }
        });
    }
    let at = |i: usize| -> Vertex {
        if i < n {
            return vert(p.nodes[i]);
        }
        Vertex {
            x: std::array::from_fn(|d| comps[d][i]),
            u: std::array::from_fn(|d| comps[3 + d][i]),
            v: comps[6][i] as f32,
        }
    };
    sub_triangles(p.kind).iter().map(|t| t.iter().map(|&i| at(i)).collect()).collect()
}

/// A clipped polygon filled on the screen (a fan from its first vertex),
/// each pixel coloured from the field interpolated linearly.
fn fill_polygon(
    cv: &mut Canvas,
    frame: &Frame,
    poly: &[Vertex],
    deformed: bool,
    paint: &dyn Fn(f32) -> [u8; 3],
    norm: &dyn Fn(f32) -> f32,
) {
    let pts: Vec<[f32; 2]> = poly.iter().map(|v| frame.vertex(v, deformed).0).collect();
    for i in 1..poly.len().saturating_sub(1) {
        cv.triangle([pts[0], pts[i], pts[i + 1]], [norm(poly[0].v), norm(poly[i].v), norm(poly[i + 1].v)], paint);
    }
}

/// The bodies: the undeformed ghost (2D), the patches coloured by the field
/// on their body's scale (3D: far faces first, shaded, and the sections of
/// a cut), mesh lines on cells big enough to show them, and the outlines.
/// Patches across a cut are clipped to it (without their mesh lines).
fn draw_bodies(cv: &mut Canvas, snap: &Snapshot, frame: &Frame, values: &[Vec<f32>], scales: &[Scale]) {
    let model = snap.model;
    let coords = &model.coords;
    let all = patches(model, None);
    let place = |p: &Patch| frame.cut.map_or(Place::Inside, |c| c.classify(p, coords));
    let patches: Vec<Patch> = all.iter().copied().filter(|p| place(p) == Place::Inside).collect();
    let across: Vec<Patch> = all.iter().copied().filter(|p| place(p) == Place::Across).collect();
    let paint = Paint::new(model.bodies.len(), values, scales);
    let clipped = clipped_pieces(snap, frame, &across, values);
    match &frame.view {
        None => draw_plane(cv, frame, &patches, &clipped, &paint),
        Some(view) => draw_far_to_near(cv, snap, frame, view, patches, &clipped, &paint),
    }
}

/// A piece of a patch across the cut: its body, its polygon, its normal.
type Clipped = (usize, Vec<Vertex>, [f64; 3]);

/// How a body's values are coloured: the scale each body is on.
struct Paint<'a> {
    values: &'a [Vec<f32>],
    scales: &'a [Scale],
    scale_of: Vec<usize>,
}

impl<'a> Paint<'a> {
    fn new(bodies: usize, values: &'a [Vec<f32>], scales: &'a [Scale]) -> Paint<'a> {
        let mut scale_of = vec![0; bodies];
        for (i, s) in scales.iter().enumerate() {
            for &b in &s.bodies {
                scale_of[b] = i;
            }
        }
        Paint { values, scales, scale_of }
    }

    fn colour(&self, body: usize, t: f32) -> [u8; 3] {
        lut_colour(&self.scales[self.scale_of[body]].lut, t)
    }

    fn norm(&self, body: usize, v: f32) -> f32 {
        self.scales.get(self.scale_of[body]).map_or(f32::NAN, |s| s.lim.norm(v))
    }
}

/// The pieces of the patches `across` the frame's cut (none without one).
fn clipped_pieces(snap: &Snapshot, frame: &Frame, across: &[Patch], values: &[Vec<f32>]) -> Vec<Clipped> {
    let coords = &snap.model.coords;
    let vert = |body: usize| move |k: usize| Vertex { x: coords[k], u: displacement(snap, k), v: values[body][k] };
    match frame.cut {
        Some(cut) => across
            .iter()
            .flat_map(|p| {
                let normal = p.normal(coords);
                let body = p.body;
                patch_triangles(p, &vert(body)).into_iter().map(move |t| (body, cut.clip(t), normal))
            })
            .filter(|(_, poly, _)| !poly.is_empty())
            .collect(),
        None => Vec::new(),
    }
}

/// 2D: the undeformed ghost (when the shape moved), the bodies coloured,
/// the mesh lines and outlines over them.
fn draw_plane(cv: &mut Canvas, frame: &Frame, patches: &[Patch], clipped: &[Clipped], paint: &Paint) {
    let (sd, su) = (&frame.sd, &frame.su);
    let mesh_alpha = mesh_alpha(patches, sd);
    if frame.moved() {
        for p in patches {
            fill(cv, p, su, &|_| [0.0; 9], &|_| GHOST);
        }
        for (_, poly, _) in clipped {
            fill_polygon(cv, frame, poly, false, &|_| GHOST, &|_| 0.0);
        }
        for p in patches {
            edges(cv, p, su, &|outline, _| outline.then_some((1.0, [175, 175, 175], 1.0)));
        }
    }
    for p in patches {
        let v = &paint.values[p.body];
        fill(cv, p, sd, &|p| centred(p, |k| paint.norm(p.body, v[k])), &|t| paint.colour(p.body, t));
    }
    for (b, poly, _) in clipped {
        fill_polygon(cv, frame, poly, true, &|t| paint.colour(*b, t), &|v| paint.norm(*b, v));
    }
    // each mesh line once (from the first cell that has it), outlines over them
    for p in patches {
        edges(cv, p, sd, &|outline, first| {
            (!outline && first && mesh_alpha > 0.0).then_some((0.8, [0, 0, 0], mesh_alpha))
        });
    }
    for p in patches {
        edges(cv, p, sd, &|outline, _| outline.then_some((1.3, INK, 1.0)));
    }
}

/// A piece of a 3D picture, drawn in depth order.
enum Piece<'a> {
    Whole(&'a Patch),
    Cut(&'a Clipped),
}

/// 3D: whole patches, clipped pieces and sections far to near, shaded.
fn draw_far_to_near(
    cv: &mut Canvas,
    snap: &Snapshot,
    frame: &Frame,
    view: &View,
    mut patches: Vec<Patch>,
    clipped: &[Clipped],
    paint: &Paint,
) {
    let (model, coords, sd) = (snap.model, &snap.model.coords, &frame.sd);
    let mesh_alpha = mesh_alpha(&patches, sd);
    let sections = match frame.cut {
        Some(cut) => cut.sections(model, &|k| displacement(snap, k), &|b, k| paint.values[b][k]),
        None => Vec::new(),
    };
    let depth_of = |piece: &Piece| -> f64 {
        match piece {
            Piece::Whole(p) => p.nodes().iter().map(|&k| frame.depth[k]).sum::<f64>() / p.kind.n_nodes() as f64,
            Piece::Cut((_, poly, _)) => poly.iter().map(|v| frame.vertex(v, true).1).sum::<f64>() / poly.len() as f64,
        }
    };
    patches.sort_by(|a, b| depth_of(&Piece::Whole(a)).total_cmp(&depth_of(&Piece::Whole(b))));
    let mut order: Vec<(f64, Piece)> = patches
        .iter()
        .map(Piece::Whole)
        .chain(clipped.iter().chain(&sections).map(Piece::Cut))
        .map(|p| (depth_of(&p), p))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    let light = normalized(std::array::from_fn(|i| 0.3 * view.right[i] + 0.5 * view.up[i] + view.eye[i]));
    for (_, piece) in &order {
        match piece {
            Piece::Whole(p) => {
                // faces lit from over the viewer's shoulder, either side alike
                let shade = (0.62 + 0.38 * dot(p.normal(coords), light).abs()) as f32;
                let v = &paint.values[p.body];
                fill(cv, p, sd, &|p| centred(p, |k| paint.norm(p.body, v[k])), &|t| {
                    paint.colour(p.body, t).map(|c| (c as f32 * shade) as u8)
                });
                edges(cv, p, sd, &|outline, _| match outline {
                    true => Some((1.2, [0, 0, 0], 0.85)),
                    false => (mesh_alpha > 0.0).then_some((0.8, [0, 0, 0], mesh_alpha)),
                });
            }
            Piece::Cut((b, poly, normal)) => {
                let shade = (0.62 + 0.38 * dot(*normal, light).abs()) as f32;
                let colour = |t: f32| paint.colour(*b, t).map(|c| (c as f32 * shade) as u8);
                fill_polygon(cv, frame, poly, true, &colour, &|v| paint.norm(*b, v));
            }
        }
    }
}

/// The least distance between two contact dots of a 3D picture, pixels.
const SPACING: f32 = 12.0;

/// The contact interfaces by state, over everything: in 2D both sides of
/// every facet as a thick line, each node's half of a segment in its pair's
/// colour; in 3D the pairs as dots (the interfaces are inside the solid),
/// thinned to [`SPACING`] (the plan views show every pair). Only what lies
/// in the drawn region.
fn draw_contacts(cv: &mut Canvas, snap: &Snapshot, frame: &Frame) {
    let model = snap.model;
    let sd = &frame.sd;
    let states = snap.contact.map(|c| &c.states[..]);
    let mut pair_of = vec![usize::MAX; model.n_nodes()];
    for (i, p) in model.pairs.iter().enumerate() {
        pair_of[p.k] = i;
    }
    let colour_of = |k: usize| match (states, pair_of[k]) {
        (Some(s), p) if p < s.len() => state_colour(s[p]),
        _ => NO_PAIR,
    };
    if frame.view.is_some() {
        // no two dots closer than SPACING, so that the field shows between them
        let mut kept: std::collections::HashMap<(i32, i32), Vec<[f32; 2]>> = std::collections::HashMap::new();
        for p in model.pairs.iter().filter(|p| frame.drawn(p.k)) {
            let q = sd[p.k];
            let cell = ((q[0] / SPACING).floor() as i32, (q[1] / SPACING).floor() as i32);
            let near = (cell.0 - 1..=cell.0 + 1)
                .flat_map(|a| (cell.1 - 1..=cell.1 + 1).map(move |b| (a, b)))
                .any(|c| kept.get(&c).is_some_and(|v| v.iter().any(|o| (o[0] - q[0]).hypot(o[1] - q[1]) < SPACING)));
            if !near {
                cv.state_dot(q, colour_of(p.k));
                kept.entry(cell).or_default().push(q);
            }
        }
        return;
    }
    let other = |k: usize| if pair_of[k] == usize::MAX { k } else { model.pairs[pair_of[k]].l };
    for casing in [true, false] {
        for f in model.interfaces.iter().flat_map(|i| &i.facets) {
            let chain: Vec<usize> =
                if f.nodes.len() == 3 { vec![f.nodes[0], f.nodes[2], f.nodes[1]] } else { f.nodes.clone() };
            if !chain.iter().all(|&k| frame.drawn(k) && frame.drawn(other(k))) {
                continue;
            }
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
