//! The deformed picture (PNG, 1200 x 800): the model moved by its
//! magnified displacements and coloured by a field, the undeformed shape as
//! a grey ghost behind it (2D), and the contact states on the interfaces.
//! 3D models are drawn in an oblique view (up against gravity, else y for
//! extrusions thin in z, else z), boundary faces far to near (painter's
//! algorithm), lit from over the viewer's shoulder.

use plotters::style::text_anchor::{HPos, VPos};

use super::legend::{colour_bar, colour_map, legend, lut_colour, triad, Limits};
use super::raster::{encode_png, label, register_font, Canvas};
use super::surface::{centred, edges, fill, mesh_alpha, patches, Patch};
use super::{cross, dot, norm3, num, sig2, state_colour, sub3, Field, Snapshot, GHOST, INK, NO_PAIR};
use crate::fem::material::von_mises;
use crate::fem::Analysis;

pub(super) const W: usize = 1200;
pub(super) const H: usize = 800;
/// Where the model goes: x0, y0, x1, y1 in pixels.
const PLOT: [f64; 4] = [24.0, 84.0, 960.0, 780.0];
/// The right-hand panel: colour bar, then the legend.
pub(super) const PANEL_X: f64 = 990.0;

/// A PNG (1200 x 800) of the model deformed by the magnified displacements
/// and coloured by `field`, with the contact states on the interfaces.
/// `scale` is the displacement magnification; None picks one that makes the
/// largest displacement 5 % of the model's size.
pub fn deformed_png(snap: &Snapshot, field: Field, scale: Option<f64>) -> Result<Vec<u8>, String> {
    let c = deformed_canvas(snap, field, scale)?;
    encode_png(c.w, c.h, &c.rgb)
}

/// Which way is up in a 3D model of this extent: against gravity when there
/// is some; else y, as in the plane pictures, for models thinner in z than
/// across (extrusions of a plane section); else z.
pub(super) fn up_of(extent: [f64; 3], gravity: [f64; 3]) -> [f64; 3] {
    let g = dot(gravity, gravity).sqrt();
    if g > 0.0 {
        gravity.map(|x| -x / g)
    } else if extent[2] < 0.99 * extent[0].min(extent[1]) {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    }
}

/// Oblique view of 3D models: the eye's direction, right and up on screen.
pub(super) struct View {
    eye: [f64; 3],
    pub(super) right: [f64; 3],
    pub(super) up: [f64; 3],
}

impl View {
    /// Which way is up: [`up_of`]. The eye is turned 30 degrees to the
    /// right and raised 25 degrees (20 and 20 for the extrusions seen mostly
    /// from +z, so that their section dominates).
    fn new(extent: [f64; 3], gravity: [f64; 3]) -> View {
        let up = up_of(extent, gravity);
        let (toward, az, el) = if dot(gravity, gravity) > 0.0 {
            // the world axis least along up faces the viewer
            let k = (0..3).min_by(|&a, &b| up[a].abs().total_cmp(&up[b].abs())).unwrap_or(0);
            let mut t = [0.0; 3];
            t[k] = if k == 1 { -1.0 } else { 1.0 };
            (norm3(sub3(t, up.map(|x| x * dot(t, up)))), 30.0f64, 25.0f64)
        } else if up[1] == 1.0 {
            ([0.0, 0.0, 1.0], 20.0, 20.0)
        } else {
            ([0.0, -1.0, 0.0], 30.0, 25.0)
        };
        let right = cross(up, toward);
        let (sa, ca, se, ce) = (az.to_radians().sin(), az.to_radians().cos(), el.to_radians().sin(), el.to_radians().cos());
        let eye: [f64; 3] = std::array::from_fn(|i| ce * (ca * toward[i] + sa * right[i]) + se * up[i]);
        let r: [f64; 3] = std::array::from_fn(|i| ca * right[i] - sa * toward[i]);
        View { eye, right: r, up: cross(eye, r) }
    }
    pub(super) fn project(&self, x: [f64; 3]) -> ([f64; 2], f64) {
        ([dot(x, self.right), dot(x, self.up)], dot(x, self.eye))
    }
}

pub(super) fn deformed_canvas(snap: &Snapshot, field: Field, scale: Option<f64>) -> Result<Canvas, String> {
    register_font();
    let model = snap.model;
    let stresses_ok = snap.stresses.len() == model.bodies.len() || (snap.stresses.is_empty() && field == Field::Displacement);
    if snap.u.len() != model.n_nodes() * model.nd || !stresses_ok {
        return Err("the run's displacements or stresses do not match its model".into());
    }
    let frame = Frame::new(snap, scale)?;
    let values = nodal_values(snap, field);
    let signed = field.component().is_some();
    let lim = Limits::of(signed, &values);
    let lut = colour_map(signed, lim.lo, lim.hi);
    let mut cv = Canvas::new(W, H);
    draw_bodies(&mut cv, snap, &frame, &values, &lim, &lut);
    draw_contacts(&mut cv, snap, &frame);

    let mut labels = Vec::new();
    labels.push(label(snap.title.to_string(), (24.0, 14.0), 24.0, (HPos::Left, VPos::Top)));
    let shape = if frame.mag > 0.0 {
        format!("deformed shape, displacements × {} (largest displacement {})", sig2(frame.mag), num(frame.umax))
    } else {
        "undeformed shape (no displacement)".to_string()
    };
    labels.push(label(format!("{} on the {shape}", field.label(model.analysis)), (24.0, 48.0), 17.0, (HPos::Left, VPos::Top)));
    colour_bar(&mut cv, &mut labels, &lut, &lim, field.label(model.analysis), [PANEL_X, 146.0, 500.0]);
    legend(&mut cv, &mut labels, snap, &frame);
    if let Some(view) = &frame.view {
        triad(&mut cv, &mut labels, view);
    }
    cv.text(&labels)?;
    Ok(cv)
}

/// Where every node lands in the picture, deformed (`sd`) and undeformed
/// (`su`), with its depth in 3D (larger is nearer).
pub(super) struct Frame {
    mag: f64,
    umax: f64,
    /// Pixels per model length.
    px: f64,
    sd: Vec<[f32; 2]>,
    su: Vec<[f32; 2]>,
    depth: Vec<f64>,
    /// The 3D view; None in 2D (x right, y up).
    pub(super) view: Option<View>,
}

impl Frame {
    fn new(snap: &Snapshot, scale: Option<f64>) -> Result<Frame, String> {
        let model = snap.model;
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
            let u = displacement(snap, k);
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
            let (u, x) = (displacement(snap, k), model.coords[k]);
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
    pub(super) fn moved(&self) -> bool {
        self.mag * self.umax * self.px > 1.5
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

/// The bodies: the undeformed ghost (2D), the patches coloured by the field
/// (3D: far faces first, shaded), mesh lines on cells big enough to show
/// them, and the outlines.
fn draw_bodies(cv: &mut Canvas, snap: &Snapshot, frame: &Frame, values: &[Vec<f32>], lim: &Limits, lut: &[[u8; 3]]) {
    let (sd, su) = (&frame.sd, &frame.su);
    let mut patches = patches(snap.model);
    let mesh_alpha = mesh_alpha(&patches, sd);
    let Some(view) = &frame.view else {
        if frame.moved() {
            for p in &patches {
                fill(cv, p, su, &|_| [0.0; 9], &|_| GHOST);
            }
            for p in &patches {
                edges(cv, p, su, &|outline, _| outline.then_some((1.0, [175, 175, 175], 1.0)));
            }
        }
        for p in &patches {
            let v = &values[p.body];
            fill(cv, p, sd, &|p| centred(p, |k| lim.norm(v[k])), &|t| lut_colour(lut, t));
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
    let coords = &snap.model.coords;
    for p in &patches {
        // faces lit from over the viewer's shoulder, either side alike
        let shade = (0.62 + 0.38 * dot(p.normal(coords), light).abs()) as f32;
        let v = &values[p.body];
        fill(cv, p, sd, &|p| centred(p, |k| lim.norm(v[k])), &|t| lut_colour(lut, t).map(|c| (c as f32 * shade) as u8));
        edges(cv, p, sd, &|outline, _| match outline {
            true => Some((1.2, [0, 0, 0], 0.85)),
            false => (mesh_alpha > 0.0).then_some((0.8, [0, 0, 0], mesh_alpha)),
        });
    }
}

/// The contact interfaces by state, over everything: in 2D both sides of
/// every facet as a thick line, each node's half of a segment in its pair's
/// colour; in 3D the pairs as dots (the interfaces are inside the solid).
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

pub(super) fn state_dot(cv: &mut Canvas, at: [f32; 2], c: [u8; 3]) {
    cv.dot(at, 4.6, [0, 0, 0]);
    cv.dot(at, 3.4, c);
}
