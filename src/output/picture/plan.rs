//! The plan view of a 3D contact surface (PNG, one per sheet of each
//! interface, [`super::sheets`]): planes seen square on from the side that
//! faces up, so that a horizontal joint is seen from above with x to the
//! right and y up; cylinder-like surfaces (a tunnel lining) unrolled, the
//! angle about the axis from the crown across and the position along the
//! axis up, with the crown, springlines and invert marked. A contact group
//! on several planes (a joint set) gets one plan per plane. Two panels:
//!
//! - (a) the contact state as regions. Each state's indicator (1 at the
//!   pairs in that state, 0 at the others) is interpolated linearly over
//!   the facets' sub-triangles and every pixel takes the state whose
//!   indicator is largest there, so stick, slip and open zones meet half-way
//!   between pairs in different states. Arrows on slipping pairs, thinned to
//!   an even spacing: the shear on body I, `tau_t t + tau_b b` in the pair's
//!   frame (n, t, b) ([`ContactRun::shear`]), which is the direction body II
//!   slips relative to body I, drawn along the sheet's directions at the
//!   pair.
//! - (b) sigma_n interpolated over the facets, with its colour bar.
//!
//! A point of a plane is drawn at `(r . x, v . x)`, so the axes read global
//! coordinates when r and v are world axes.

use plotters::style::text_anchor::{HPos, VPos};

use super::colours::{state_colour, INK, NO_PAIR};
use super::label_numbers::num;
use super::legend::{colour_bar, colour_map, lut_colour, nice_step, Limits};
use super::picture_error::PictureError;
use super::raster::{encode_png, label, register_font, Canvas, Label};
use super::sheets::{direction, sheets, Flat, Shape, Sheet};
use super::surface::{centred, edges, fill, mesh_alpha, pieces, Patch};
use crate::contact::law::ContactState;
use crate::fem::vec3::dot;
use crate::fem::Analysis;
use crate::model::Model;
use crate::results::ContactRun;

/// One plan view: a sheet of an interface and its file name.
pub struct PlanFile {
    /// `plan_<interface>.png`, or `plan_<interface>_<k>.png` for the k-th
    /// of several sheets (k from 1), the characters of the name that do not
    /// belong in a file name replaced by `_`.
    pub file: String,
    pub interface: usize,
    /// The sheet's place among the interface's sheets (from 0) and their number.
    pub index: usize,
    pub of: usize,
    pub(super) sheet: Sheet,
}

impl PlanFile {
    /// What the sheet is: "the plane z = 2.5", "the cylinder r = 5 about an
    /// axis along y", ...
    pub fn describe(&self, model: &Model) -> String {
        self.sheet.describe(model)
    }
}

/// The plan views of a solid model's contact interfaces (none for plane or
/// axisymmetric models), interface by interface, sheet by sheet.
pub fn plan_files(model: &Model) -> Vec<PlanFile> {
    if model.analysis != Analysis::Solid {
        return Vec::new();
    }
    let mut files: Vec<PlanFile> = Vec::new();
    for (ii, iface) in model.interfaces.iter().enumerate() {
        let stem: String = iface
            .name
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' })
            .collect();
        let all = sheets(model, ii);
        let of = all.len();
        for (index, sheet) in all.into_iter().enumerate() {
            let mut f = if of == 1 { format!("plan_{stem}.png") } else { format!("plan_{stem}_{}.png", index + 1) };
            if files.iter().any(|p| p.file == f) {
                f = format!("plan_{stem}_{}_{}.png", ii + 1, index + 1);
            }
            files.push(PlanFile { file: f, interface: ii, index, of, sheet });
        }
    }
    files
}

/// Every plan view of [`plan_files`], under its file name.
pub fn plan_pngs(title: &str, model: &Model, contact: &ContactRun) -> Result<Vec<(String, Vec<u8>)>, PictureError> {
    plan_files(model).into_iter().map(|p| Ok((p.file.clone(), plan_png(title, model, contact, &p)?))).collect()
}

/// The plan view of one sheet.
pub fn plan_png(title: &str, model: &Model, contact: &ContactRun, plan: &PlanFile) -> Result<Vec<u8>, PictureError> {
    let (cv, _) = plan_canvas(title, model, contact, plan)?;
    encode_png(cv.w, cv.h, &cv.rgb)
}

/// Where the panels go: the canvas size, each panel's box (x0, y0, x1, y1)
/// and the x of the column beside it (legend, colour bar).
struct Layout {
    w: usize,
    h: usize,
    boxes: [[f64; 4]; 2],
    column: [f64; 2],
}

impl Layout {
    /// Side by side in 560 px squares, or one above the other, sized to the
    /// interface, for interfaces much wider than tall (when that draws them
    /// at least 1.25 times larger).
    fn new(extent: [f64; 2]) -> Layout {
        let (ex, ey) = (extent[0].max(1e-300), extent[1].max(1e-300));
        let side = (532.0 / ex).min(532.0 / ey);
        let iw = (392.0 * ex / ey).min(1332.0);
        if iw / ex <= 1.25 * side {
            return Layout {
                w: 1600,
                h: 800,
                boxes: [[80.0, 130.0, 640.0, 690.0], [890.0, 130.0, 1450.0, 690.0]],
                column: [665.0, 1472.0],
            };
        }
        let (bw, bh) = ((iw + 28.0).max(560.0).round(), (iw * ey / ex + 28.0).max(240.0).round());
        let b2 = 130.0 + bh + 100.0;
        let column = 80.0 + bw + 25.0;
        Layout {
            w: ((column + 175.0) as usize).max(1200),
            h: (b2 + bh + 110.0) as usize,
            boxes: [[80.0, 130.0, 80.0 + bw, 130.0 + bh], [80.0, b2, 80.0 + bw, b2 + bh]],
            column: [column, column],
        }
    }
}

/// Flat coordinates to pixels in one box: equal scales, the data centred.
pub(super) struct Fit {
    px: f64,
    centre: [f64; 2],
    at: [f64; 2],
}

impl Fit {
    pub(super) fn new(lo: [f64; 2], hi: [f64; 2], b: [f64; 4], pad: f64) -> Fit {
        let px = ((b[2] - b[0] - 2.0 * pad) / (hi[0] - lo[0])).min((b[3] - b[1] - 2.0 * pad) / (hi[1] - lo[1]));
        let px = if px.is_finite() && px > 0.0 { px } else { 1.0 };
        Fit {
            px,
            centre: [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])],
            at: [0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3])],
        }
    }
    pub(super) fn screen(&self, q: [f64; 2]) -> [f32; 2] {
        [
            (self.at[0] + (q[0] - self.centre[0]) * self.px) as f32,
            (self.at[1] - (q[1] - self.centre[1]) * self.px) as f32,
        ]
    }
}

/// The pair at each node of a sheet, and the sheet's pairs. Where pairs
/// share a node (contacts that meet, joints that cross) it is this
/// interface's pair, and on a plane the one whose normal is most along the
/// plane's.
pub(super) fn sheet_pairs(model: &Model, sheet: &Sheet) -> (Vec<usize>, Vec<usize>) {
    let nodes = sheet.nodes(model);
    let normal = match &sheet.shape {
        Shape::Plane { n, .. } => Some(*n),
        _ => None,
    };
    let rank = |p: usize| -> (bool, f64) {
        let pair = &model.pairs[p];
        (pair.contact == sheet.interface, normal.map_or(0.0, |n| dot(n, pair.normal).abs()))
    };
    let mut pair_of = vec![usize::MAX; model.n_nodes()];
    for (p, pair) in model.pairs.iter().enumerate() {
        if nodes.binary_search(&pair.k).is_ok() && (pair_of[pair.k] == usize::MAX || rank(p) > rank(pair_of[pair.k])) {
            pair_of[pair.k] = p;
        }
    }
    let pairs = nodes.iter().map(|&k| pair_of[k]).filter(|&p| p != usize::MAX).collect();
    (pair_of, pairs)
}

/// The contact states as regions over the flat patches at `pos` (a point's
/// state `code(point)`: 0 open, 1 slip, 2 stick, 3 no pair).
pub(super) fn paint_states(cv: &mut Canvas, patches: &[Patch], pos: &[[f32; 2]], code: &dyn Fn(usize) -> usize) {
    let colours = [
        state_colour(ContactState::Open),
        state_colour(ContactState::Slip),
        state_colour(ContactState::Stick),
        NO_PAIR,
    ];
    for p in patches {
        let ind: [[f64; 9]; 4] = std::array::from_fn(|s| centred(p, |k| if code(k) == s { 1.0 } else { 0.0 }));
        for (q, tri) in pieces(p, pos) {
            cv.triangle_weighted(q, &|w| {
                let level = |s: usize| w[0] * ind[s][tri[0]] + w[1] * ind[s][tri[1]] + w[2] * ind[s][tri[2]];
                colours[(0..4).fold(0, |b, s| if level(s) > level(b) { s } else { b })]
            });
        }
    }
}

/// The plan view of one sheet and its two panels' boxes (state, sigma_n).
pub(super) fn plan_canvas(
    title: &str,
    model: &Model,
    contact: &ContactRun,
    plan: &PlanFile,
) -> Result<(Canvas, [[f64; 4]; 2]), PictureError> {
    register_font();
    let sheet = &plan.sheet;
    let iface = model.interfaces.get(sheet.interface).ok_or(PictureError::Mismatch { what: "contact interfaces" })?;
    if [contact.states.len(), contact.pairs.len(), contact.frames.len()].iter().any(|&n| n != model.pairs.len()) {
        return Err(PictureError::Mismatch { what: "contact results" });
    }
    let (pair_of, pairs) = sheet_pairs(model, sheet);
    let Flat { points, node, mut patches, lo, hi } = sheet.flat(model);
    if points.is_empty() {
        return Err(PictureError::Empty(format!("contact \"{}\" has no facets to draw", iface.name)));
    }
    let layout = Layout::new([hi[0] - lo[0], hi[1] - lo[1]]);
    let mut cv = Canvas::new(layout.w, layout.h);
    let mut labels = Vec::new();
    // far facets first, where a curved surface folds over itself in plan
    if let Some(e) = sheet.eye() {
        let depth =
            |p: &Patch| p.nodes().iter().map(|&i| dot(model.coords[node[i]], e)).sum::<f64>() / p.kind.n_nodes() as f64;
        patches.sort_by(|a, b| depth(a).total_cmp(&depth(b)));
    }
    let fits = layout.boxes.map(|b| Fit::new(lo, hi, b, 14.0));
    let pos: [Vec<[f32; 2]>; 2] = std::array::from_fn(|i| points.iter().map(|&q| fits[i].screen(q)).collect());
    // the data's own box: an unrolled ring's copies across the seam stop there
    let clips = fits.each_ref().map(|f| {
        let (a, b) = (f.screen(lo), f.screen(hi));
        [a[0] as f64 - 0.5, b[1] as f64 - 0.5, b[0] as f64 + 1.5, a[1] as f64 + 1.5]
    });
    let alpha = mesh_alpha(&patches, &pos[0]);

    // (a) the states as regions, the slip directions
    let code = |i: usize| match pair_of[node[i]] {
        usize::MAX => 3,
        p => contact.states[p].code() as usize,
    };
    cv.clip(Some(clips[0]));
    paint_states(&mut cv, &patches, &pos[0], &code);
    mesh_lines(&mut cv, &patches, &pos[0], alpha);
    cv.clip(None);
    let arrows = slip_arrows(&mut cv, model, contact, sheet, &pairs, &fits[0], pixel_area(&patches, &pos[0]));
    let mut counts = [0usize; 3];
    for &p in &pairs {
        counts[contact.states[p].code() as usize] += 1;
    }
    let unpaired = node.iter().any(|&k| pair_of[k] == usize::MAX);
    state_legend(&mut cv, &mut labels, layout.column[0], layout.boxes[0][1], counts, unpaired, arrows > 0);

    // (b) sigma_n
    let (sigma, lim) = sigma_n_at(contact, &node, &pair_of, &pairs);
    let lut = colour_map(true, lim.lo, lim.hi);
    cv.clip(Some(clips[1]));
    for p in &patches {
        fill(&mut cv, p, &pos[1], &|p| centred(p, |i| lim.norm(sigma[i])), &|t| lut_colour(&lut, t));
    }
    mesh_lines(&mut cv, &patches, &pos[1], alpha);
    cv.clip(None);
    let b = layout.boxes[1];
    colour_bar(&mut cv, &mut labels, &lut, &lim, &["σn".to_string()], [layout.column[1], b[1] + 52.0, b[3] - 44.0]);

    // frames, axes, headings
    for fit in &fits {
        axes(&mut cv, &mut labels, fit, lo, hi, sheet);
    }
    let heading = |b: [f64; 4], text: &str| label(text, (b[0], b[1] - 22.0), 17.0, (HPos::Left, VPos::Center));
    labels.push(heading(layout.boxes[0], "(a) contact state: where it sticks, slips and opens"));
    labels.push(heading(layout.boxes[1], "(b) σn, contact normal stress (tension > 0)"));
    labels.push(label(title, (24.0, 14.0), 24.0, (HPos::Left, VPos::Top)));
    labels.push(label(subtitle(model, plan, &pairs), (24.0, 50.0), 17.0, (HPos::Left, VPos::Top)));
    let note = slip_note(model, &pairs, counts[1], arrows);
    labels.push(label(note, (24.0, layout.h as f64 - 18.0), 14.0, (HPos::Left, VPos::Center)));
    cv.text(&labels)?;
    Ok((cv, layout.boxes))
}

/// The line under the title: what is seen, between which bodies, from where.
fn subtitle(model: &Model, plan: &PlanFile, pairs: &[usize]) -> String {
    let sheet = &plan.sheet;
    let iface = &model.interfaces[sheet.interface];
    let [bi, bii] = sides(model, pairs);
    let what = match plan.of {
        1 => String::new(),
        n => format!(", {} ({} of {n})", plan.describe(model), plan.index + 1),
    };
    let seen = match &sheet.shape {
        Shape::Cylinder { a, .. } => format!("about its axis ({}), seen from outside", direction(*a, true)),
        _ => {
            let e = sheet.eye().unwrap_or([0.0, 0.0, 1.0]);
            let up = super::view::model_up(model);
            let above = if dot(e, up) > 0.9 { ", above" } else { "" };
            format!("seen from {}{above} (the side of {})", direction(e, true), viewer_side(model, pairs, e))
        }
    };
    let view = if matches!(sheet.shape, Shape::Cylinder { .. }) { "unrolled view" } else { "plan view" };
    format!("{view} of contact \"{}\"{what} between {} and {} ({} pairs), {seen}", iface.name, bi.0, bii.0, pairs.len())
}

/// The note under the panels: which way the slip arrows point, or why
/// there are none.
fn slip_note(model: &Model, pairs: &[usize], slipping: usize, arrows: usize) -> String {
    let [bi, bii] = sides(model, pairs);
    match (slipping, arrows) {
        (0, _) => "No pair slips.".to_string(),
        (_, 0) => "The slipping pairs carry no shear (frictionless slip): no slip directions to draw.".to_string(),
        _ => format!(
            "Arrows: the direction in which {} {} relative to {} (the shear on {}), on slipping pairs.",
            bii.0,
            if bii.1 > 1 { "slip" } else { "slips" },
            bi.0,
            bi.0
        ),
    }
}

/// The mesh's lines over a panel: the facets' edges faintly (`alpha`),
/// then the outlines.
fn mesh_lines(cv: &mut Canvas, patches: &[Patch], pos: &[[f32; 2]], alpha: f32) {
    for p in patches {
        edges(cv, p, pos, &|outline, first| {
            (!outline && first && alpha > 0.0).then_some((0.8, [0, 0, 0], 0.6 * alpha))
        });
    }
    for p in patches {
        edges(cv, p, pos, &|outline, _| outline.then_some((1.3, INK, 1.0)));
    }
}

/// The area the patches cover on screen, in pixels.
fn pixel_area(patches: &[Patch], pos: &[[f32; 2]]) -> f64 {
    patches
        .iter()
        .flat_map(|p| pieces(p, pos))
        .map(|(q, _)| {
            0.5 * ((q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0])).abs() as f64
        })
        .sum()
}

/// sigma_n at each flat point (NaN where no pair is) and its colour range.
fn sigma_n_at(contact: &ContactRun, node: &[usize], pair_of: &[usize], pairs: &[usize]) -> (Vec<f32>, Limits) {
    let sigma: Vec<f32> = node
        .iter()
        .map(|&k| match pair_of[k] {
            usize::MAX => f32::NAN,
            p => contact.pairs[p].sigma_n as f32,
        })
        .collect();
    let lim = Limits::of(true, &[pairs.iter().map(|&p| contact.pairs[p].sigma_n as f32).collect()]);
    (sigma, lim)
}

/// Body names as `"a", "b" and "c"`, at most `most` of them and how many
/// more, with their number.
pub(super) fn body_list(model: &Model, bodies: &[usize], most: usize) -> (String, usize) {
    let mut q: Vec<String> = bodies.iter().take(most).map(|&b| format!("\"{}\"", model.bodies[b].name)).collect();
    if bodies.len() > most {
        q.push(format!("{} more", bodies.len() - most));
    }
    let text = match q.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => q.concat(),
    };
    (text, bodies.len())
}

/// The bodies of each side of the pairs: side I those that hold the pairs'
/// first nodes, side II their second nodes.
pub(super) fn sides(model: &Model, pairs: &[usize]) -> [(String, usize); 2] {
    let holders = |pick: &dyn Fn(usize) -> usize| -> Vec<usize> {
        let mut mine = vec![false; model.n_nodes()];
        for &p in pairs {
            mine[pick(p)] = true;
        }
        (0..model.bodies.len())
            .filter(|&b| model.bodies[b].cells.iter().any(|c| c.nodes.iter().any(|&k| mine[k])))
            .collect()
    };
    [body_list(model, &holders(&|p| model.pairs[p].k), 4), body_list(model, &holders(&|p| model.pairs[p].l), 4)]
}

/// The bodies on the viewer's side: of each pair, the body its normal
/// (body I's outward one) points to when it points at the viewer.
fn viewer_side(model: &Model, pairs: &[usize], e: [f64; 3]) -> String {
    let mut mine = vec![false; model.n_nodes()];
    for &p in pairs {
        let pr = &model.pairs[p];
        mine[if dot(pr.normal, e) >= 0.0 { pr.l } else { pr.k }] = true;
    }
    let bodies: Vec<usize> = (0..model.bodies.len())
        .filter(|&b| model.bodies[b].cells.iter().any(|c| c.nodes.iter().any(|&k| mine[k])))
        .collect();
    body_list(model, &bodies, 4).0
}

/// Arrows along the shear of slipping pairs, no two closer than the
/// pairs' spacing or 30 px: the pairs taken row by row from the top, each
/// kept when no kept one is that near. Returns how many were drawn.
fn slip_arrows(
    cv: &mut Canvas,
    model: &Model,
    contact: &ContactRun,
    sheet: &Sheet,
    pairs: &[usize],
    fit: &Fit,
    area_px: f64,
) -> usize {
    let gap = (area_px / pairs.len().max(1) as f64).sqrt().max(30.0) as f32;
    let at = |p: usize| fit.screen(sheet.at(model.coords[model.pairs[p].k]));
    let mut slipping: Vec<(usize, [f32; 2])> =
        pairs.iter().filter(|&&p| contact.states[p] == ContactState::Slip).map(|&p| (p, at(p))).collect();
    slipping.sort_by(|a, b| {
        (a.1[1].round(), a.1[0]).partial_cmp(&(b.1[1].round(), b.1[0])).unwrap_or(std::cmp::Ordering::Equal)
    });
    // kept sites in cells of the gap's size: a near one is in the 3 x 3 around
    let mut kept: std::collections::HashMap<(i64, i64), Vec<[f32; 2]>> = std::collections::HashMap::new();
    let cell = |q: [f32; 2]| ((q[0] / gap).floor() as i64, (q[1] / gap).floor() as i64);
    let half = 0.36 * gap;
    let mut drawn = 0;
    for (p, q) in slipping {
        let (i, j) = cell(q);
        let near = (i - 1..=i + 1)
            .flat_map(|a| (j - 1..=j + 1).map(move |b| (a, b)))
            .any(|c| kept.get(&c).is_some_and(|v| v.iter().any(|o| (o[0] - q[0]).hypot(o[1] - q[1]) < gap)));
        if near {
            continue;
        }
        let t = contact.shear(p);
        let (r, v) = sheet.directions(model.coords[model.pairs[p].k]);
        let d = [dot(t, r) as f32, -dot(t, v) as f32];
        let len = d[0].hypot(d[1]);
        if !(len > 1e-9 * dot(t, t).sqrt() as f32) || !len.is_finite() {
            continue;
        }
        let d = [d[0] / len, d[1] / len];
        arrow(cv, [q[0] - half * d[0], q[1] - half * d[1]], [q[0] + half * d[0], q[1] + half * d[1]]);
        kept.entry((i, j)).or_default().push(q);
        drawn += 1;
    }
    drawn
}

/// A dark arrow from `a` to `b` with a light halo.
fn arrow(cv: &mut Canvas, a: [f32; 2], b: [f32; 2]) {
    let len = (b[0] - a[0]).hypot(b[1] - a[1]).max(1e-6);
    let d = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    let head = (0.42 * len).clamp(5.0, 8.0);
    let base = [b[0] - head * d[0], b[1] - head * d[1]];
    let side = [-d[1] * 0.5 * head, d[0] * 0.5 * head];
    let tri = [b, [base[0] + side[0], base[1] + side[1]], [base[0] - side[0], base[1] - side[1]]];
    cv.segment(a, base, 4.0, [255, 255, 255], 0.75, true);
    cv.polyline([tri[1], tri[0], tri[2]].into_iter(), 3.0, [255, 255, 255], 0.75);
    cv.segment(a, base, 1.6, INK, 1.0, true);
    cv.triangle(tri, [0.0; 3], &|_| INK);
}

/// The states with their counts on this interface, facet nodes without a
/// pair here, and the arrow's meaning.
fn state_legend(
    cv: &mut Canvas,
    labels: &mut Vec<Label>,
    x: f64,
    top: f64,
    counts: [usize; 3],
    unpaired: bool,
    arrows: bool,
) {
    let mut y = top + 10.0;
    labels.push(label("contact pairs", (x, y), 16.0, (HPos::Left, VPos::Center)));
    let mut entries: Vec<([u8; 3], String)> =
        [(ContactState::Stick, counts[2]), (ContactState::Slip, counts[1]), (ContactState::Open, counts[0])]
            .iter()
            .map(|&(s, n)| (state_colour(s), format!("{} ({n})", s.name())))
            .collect();
    if unpaired {
        // facet nodes that are no pair's first node (where contacts meet)
        entries.push((NO_PAIR, "no pair here".into()));
    }
    for (colour, text) in entries {
        y += 28.0;
        cv.rect(x + 1.0, y - 8.0, x + 25.0, y + 8.0, colour);
        cv.polyline(
            [[x + 1.0, y - 8.0], [x + 25.0, y - 8.0], [x + 25.0, y + 8.0], [x + 1.0, y + 8.0], [x + 1.0, y - 8.0]]
                .map(|p| [p[0] as f32, p[1] as f32])
                .into_iter(),
            1.0,
            INK,
            1.0,
        );
        labels.push(label(text, (x + 34.0, y), 15.0, (HPos::Left, VPos::Center)));
    }
    if arrows {
        y += 30.0;
        cv.rect(x + 1.0, y - 10.0, x + 25.0, y + 10.0, state_colour(ContactState::Slip));
        arrow(cv, [x as f32 + 3.0, y as f32], [x as f32 + 23.0, y as f32]);
        labels.push(label("slip direction", (x + 34.0, y), 15.0, (HPos::Left, VPos::Center)));
    }
}

/// A light frame round the data with round ticks on its bottom and left
/// edges, the axes' directions named; an unrolled surface's angle in
/// degrees from its zero, with the crown, springlines and invert named.
fn axes(cv: &mut Canvas, labels: &mut Vec<Label>, fit: &Fit, lo: [f64; 2], hi: [f64; 2], sheet: &Sheet) {
    let (a, b) = (fit.screen(lo), fit.screen(hi));
    let (x0, x1, y0, y1) = (a[0] - 10.0, b[0] + 10.0, b[1] - 10.0, a[1] + 10.0);
    cv.polyline([[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]].into_iter(), 1.0, [160, 160, 160], 1.0);
    let mut tick_x = |cv: &mut Canvas, v: f64, text: String, name: Option<String>| {
        let mut q = lo;
        q[0] = v;
        let s = fit.screen(q);
        cv.segment([s[0], y1], [s[0], y1 + 5.0], 1.0, INK, 1.0, false);
        labels.push(label(text, (s[0] as f64, y1 as f64 + 8.0), 13.0, (HPos::Center, VPos::Top)));
        if let Some(n) = name {
            cv.segment([s[0], y0], [s[0], y1], 1.0, [120, 120, 120], 0.5, false);
            labels.push(label(n, (s[0] as f64, y1 as f64 + 25.0), 13.0, (HPos::Center, VPos::Top)));
        }
    };
    let (names, v_name) = match &sheet.shape {
        Shape::Cylinder { a, radius, zero, side, crown, .. } => {
            for (deg, name) in angle_ticks(lo[0] / radius, hi[0] / radius, (x1 - x0) as f64, *crown, *zero, *side) {
                tick_x(cv, deg.to_radians() * radius, format!("{}°", num(deg)), name);
            }
            let from = if *crown { "the crown".to_string() } else { direction(*zero, true) };
            (
                format!("angle about the axis from {from} towards {} (degrees)", direction(*side, true)),
                format!("along {}", direction(*a, false)),
            )
        }
        Shape::Plane { r, v, .. } | Shape::Curved { r, v, .. } => {
            let step = nice_step((hi[0] - lo[0]) / 5.0);
            let mut k = (lo[0] / step - 1e-9).ceil() as i64;
            while (k as f64) * step <= hi[0] + 1e-9 * step {
                tick_x(cv, k as f64 * step, num(k as f64 * step), None);
                k += 1;
            }
            (direction(*r, false), direction(*v, false))
        }
    };
    let step = nice_step((hi[1] - lo[1]) / 5.0);
    let mut k = (lo[1] / step - 1e-9).ceil() as i64;
    while (k as f64) * step <= hi[1] + 1e-9 * step {
        let v = k as f64 * step;
        let mut q = lo;
        q[1] = v;
        let s = fit.screen(q);
        cv.segment([x0 - 5.0, s[1]], [x0, s[1]], 1.0, INK, 1.0, false);
        labels.push(label(num(v), (x0 as f64 - 8.0, s[1] as f64), 13.0, (HPos::Right, VPos::Center)));
        k += 1;
    }
    let below = if matches!(sheet.shape, Shape::Cylinder { .. }) { 44.0 } else { 28.0 };
    labels.push(label(names, (0.5 * (x0 + x1) as f64, y1 as f64 + below), 15.0, (HPos::Center, VPos::Top)));
    labels.push(label(v_name, (x0 as f64 - 8.0, y0 as f64 - 4.0), 15.0, (HPos::Right, VPos::Bottom)));
}

/// Ticks of an unrolled surface's angle axis over `[t0, t1]` (radians) on
/// `width` pixels: every 15, 30, 45 or 90 degrees, at least 48 px apart;
/// the quarter turns named (a tunnel's crown 0, springlines ±90, invert
/// 180; a shaft's directions).
pub(super) fn angle_ticks(
    t0: f64,
    t1: f64,
    width: f64,
    crown: bool,
    zero: [f64; 3],
    side: [f64; 3],
) -> Vec<(f64, Option<String>)> {
    let (d0, d1) = (t0.to_degrees(), t1.to_degrees());
    let span = (d1 - d0).max(1e-9);
    let step = [15.0, 30.0, 45.0, 90.0].into_iter().find(|s| width * s / span >= 48.0).unwrap_or(90.0);
    let mut out = Vec::new();
    let mut k = (d0 / step - 1e-6).ceil() as i64;
    while k as f64 * step <= d1 + 1e-6 {
        let deg = k as f64 * step;
        let quarter = (deg / 90.0).round();
        let name = ((deg - 90.0 * quarter).abs() < 1e-6).then(|| {
            let q = (quarter as i64).rem_euclid(4) as usize;
            let (c, s) = ([1.0, 0.0, -1.0, 0.0][q], [0.0, 1.0, 0.0, -1.0][q]);
            let towards = direction(std::array::from_fn(|i| c * zero[i] + s * side[i]), true);
            match (crown, q) {
                (true, 0) => "crown".to_string(),
                (true, 2) => "invert".to_string(),
                (true, _) => format!("springline ({towards})"),
                (false, _) => towards,
            }
        });
        out.push((deg, name));
        k += 1;
    }
    out
}
