//! The plan view of a 3D contact surface (PNG, one per interface): the
//! interface's facets (body I's side, quadratic facets through their
//! mid-edge nodes) flattened onto the interface's mean plane and seen from
//! the side that faces up, so that a horizontal joint is seen from above
//! with x to the right and y up. Two panels:
//!
//! - (a) the contact state as regions. Each state's indicator (1 at the
//!   pairs in that state, 0 at the others) is interpolated linearly over
//!   the facets' sub-triangles and every pixel takes the state whose
//!   indicator is largest there, so stick, slip and open zones meet half-way
//!   between pairs in different states. Arrows on slipping pairs, thinned to
//!   an even spacing: the shear on body I, `tau_t t + tau_b b` in the pair's
//!   frame (n, t, b) ([`ContactRun::shear`]), which is the direction body II
//!   slips relative to body I.
//! - (b) sigma_n interpolated over the facets, with its colour bar.
//!
//! The plane: its normal is the pairs' mean normal `m = sum_p A_p n_p` (n_p
//! body I's outward normal, A_p the pair's area), turned to face up (`e . up
//! >= 0`, up as in the deformed picture: against gravity, else y for
//! extrusions thin in z, else z); the view is along it when `|m|` is
//! at least 0.3 `sum_p A_p` (otherwise the surface is too curved to have a
//! mean plane and it is seen from above). The in-plane axes (r, v), with
//! `r x v = e`: for planes within 60 degrees of horizontal, r is the world's
//! first horizontal axis projected on the plane; for steeper planes, v is up
//! projected on the plane. A point x is drawn at (r . x, v . x), so the axes
//! read global coordinates when r and v are world axes.

use plotters::style::text_anchor::{HPos, VPos};

use super::deformed::up_of;
use super::legend::{colour_bar, colour_map, lut_colour, nice_step, Limits};
use super::raster::{encode_png, label, register_font, Canvas, Label};
use super::surface::{centred, edges, facet_patches, fill, mesh_alpha, pieces, Patch};
use super::{cross, dot, norm3, num, state_colour, sub3, INK, NO_PAIR};
use crate::contact::law::ContactState;
use crate::fem::Analysis;
use crate::model::Model;
use crate::results::ContactRun;

/// The plan views of a solid model's contact interfaces (none for plane or
/// axisymmetric models): the interface's index and the file name,
/// `plan_<interface>.png` with the characters of the name that do not belong
/// in a file name replaced by `_`.
pub fn plan_files(model: &Model) -> Vec<(usize, String)> {
    if model.analysis != Analysis::Solid {
        return Vec::new();
    }
    let mut files: Vec<String> = Vec::new();
    for (ii, iface) in model.interfaces.iter().enumerate() {
        let stem: String = iface.name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect();
        let mut f = format!("plan_{stem}.png");
        if files.contains(&f) {
            f = format!("plan_{stem}_{}.png", ii + 1);
        }
        files.push(f);
    }
    files.into_iter().enumerate().collect()
}

/// Every plan view of [`plan_files`], under its file name.
pub fn plan_pngs(title: &str, model: &Model, contact: &ContactRun) -> Result<Vec<(String, Vec<u8>)>, String> {
    plan_files(model).into_iter().map(|(ii, f)| Ok((f, plan_png(title, model, contact, ii)?))).collect()
}

/// The plan view of interface `ii`.
pub fn plan_png(title: &str, model: &Model, contact: &ContactRun, ii: usize) -> Result<Vec<u8>, String> {
    let (cv, _) = plan_canvas(title, model, contact, ii)?;
    encode_png(cv.w, cv.h, &cv.rgb)
}

/// The view: e towards the viewer, r to the right, v up; `up` the world's.
struct Plane {
    e: [f64; 3],
    r: [f64; 3],
    v: [f64; 3],
    up: [f64; 3],
}

impl Plane {
    fn new(model: &Model, pairs: &[usize]) -> Plane {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &k in model.bodies.iter().flat_map(|b| &b.cells).flat_map(|c| &c.nodes) {
            for d in 0..3 {
                lo[d] = lo[d].min(model.coords[k][d]);
                hi[d] = hi[d].max(model.coords[k][d]);
            }
        }
        let up = up_of(std::array::from_fn(|d| hi[d] - lo[d]), model.gravity);
        let m = mean_normal(model, pairs);
        let total: f64 = pairs.iter().map(|&p| model.pairs[p].area).sum();
        let mut e = if dot(m, m).sqrt() >= 0.3 * total && total > 0.0 { norm3(m) } else { up };
        if dot(e, up) < -1e-6 {
            e = e.map(|x| -x);
        }
        let along = |d: [f64; 3]| norm3(sub3(d, e.map(|x| x * dot(d, e))));
        if dot(e, up).abs() > 0.5 {
            // the world axis least along up, the first of equals
            let a = (0..3).fold(0, |b, a| if up[a].abs() < up[b].abs() - 1e-12 { a } else { b });
            let mut h = [0.0; 3];
            h[a] = 1.0;
            let r = along(h);
            Plane { e, r, v: cross(e, r), up }
        } else {
            let v = along(up);
            Plane { e, r: cross(v, e), v, up }
        }
    }

    fn at(&self, x: [f64; 3]) -> [f64; 2] {
        [dot(x, self.r), dot(x, self.v)]
    }
}

/// A direction's name: "x", "−z" ("+z" with `plus`), or its components.
fn direction(d: [f64; 3], plus: bool) -> String {
    match (0..3).find(|&a| (d[a].abs() - 1.0).abs() < 1e-9) {
        Some(a) => format!("{}{}", if d[a] < 0.0 { "−" } else if plus { "+" } else { "" }, ["x", "y", "z"][a]),
        None => format!("({}, {}, {})", num((d[0] * 100.0).round() / 100.0), num((d[1] * 100.0).round() / 100.0), num((d[2] * 100.0).round() / 100.0)),
    }
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
            return Layout { w: 1600, h: 800, boxes: [[80.0, 130.0, 640.0, 690.0], [890.0, 130.0, 1450.0, 690.0]], column: [665.0, 1472.0] };
        }
        let (bw, bh) = ((iw + 28.0).max(560.0).round(), (iw * ey / ex + 28.0).max(240.0).round());
        let b2 = 130.0 + bh + 100.0;
        let column = 80.0 + bw + 25.0;
        Layout { w: ((column + 175.0) as usize).max(1200), h: (b2 + bh + 110.0) as usize, boxes: [[80.0, 130.0, 80.0 + bw, 130.0 + bh], [80.0, b2, 80.0 + bw, b2 + bh]], column: [column, column] }
    }
}

/// Plan coordinates to pixels in one box: equal scales, the data centred.
struct Fit {
    px: f64,
    centre: [f64; 2],
    at: [f64; 2],
}

impl Fit {
    fn new(lo: [f64; 2], hi: [f64; 2], b: [f64; 4]) -> Fit {
        let pad = 14.0;
        let px = ((b[2] - b[0] - 2.0 * pad) / (hi[0] - lo[0])).min((b[3] - b[1] - 2.0 * pad) / (hi[1] - lo[1]));
        let px = if px.is_finite() && px > 0.0 { px } else { 1.0 };
        Fit { px, centre: [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])], at: [0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3])] }
    }
    fn screen(&self, q: [f64; 2]) -> [f32; 2] {
        [(self.at[0] + (q[0] - self.centre[0]) * self.px) as f32, (self.at[1] - (q[1] - self.centre[1]) * self.px) as f32]
    }
}

/// The plan view of interface `ii` and its two panels' boxes (state, sigma_n).
pub(super) fn plan_canvas(title: &str, model: &Model, contact: &ContactRun, ii: usize) -> Result<(Canvas, [[f64; 4]; 2]), String> {
    register_font();
    let iface = model.interfaces.get(ii).ok_or("no such contact interface")?;
    if [contact.states.len(), contact.pairs.len(), contact.frames.len()].iter().any(|&n| n != model.pairs.len()) {
        return Err("the contact results do not match the model's pairs".into());
    }
    let mut patches = facet_patches(&iface.facets, &model.coords);
    let mut nodes: Vec<usize> = patches.iter().flat_map(|p| p.nodes().to_vec()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    // the pair at each facet node: this contact's where contacts meet
    let mut pair_of = vec![usize::MAX; model.n_nodes()];
    for (p, pair) in model.pairs.iter().enumerate() {
        if nodes.binary_search(&pair.k).is_ok() && (pair_of[pair.k] == usize::MAX || pair.contact == ii) {
            pair_of[pair.k] = p;
        }
    }
    let pairs: Vec<usize> = nodes.iter().map(|&k| pair_of[k]).filter(|&p| p != usize::MAX).collect();
    if nodes.is_empty() {
        return Err(format!("contact \"{}\" has no facets to draw", iface.name));
    }
    let plane = Plane::new(model, &pairs);
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for &k in &nodes {
        let q = plane.at(model.coords[k]);
        for d in 0..2 {
            lo[d] = lo[d].min(q[d]);
            hi[d] = hi[d].max(q[d]);
        }
    }
    let layout = Layout::new([hi[0] - lo[0], hi[1] - lo[1]]);
    let mut cv = Canvas::new(layout.w, layout.h);
    let mut labels = Vec::new();
    // far facets first, where a curved surface folds over itself in plan
    let depth = |p: &Patch| p.nodes().iter().map(|&k| dot(model.coords[k], plane.e)).sum::<f64>() / p.kind.n_nodes() as f64;
    patches.sort_by(|a, b| depth(a).total_cmp(&depth(b)));
    let fits = layout.boxes.map(|b| Fit::new(lo, hi, b));
    let positions = |fit: &Fit| -> Vec<[f32; 2]> {
        let mut pos = vec![[0.0f32; 2]; model.n_nodes()];
        for &k in &nodes {
            pos[k] = fit.screen(plane.at(model.coords[k]));
        }
        pos
    };
    let pos = [positions(&fits[0]), positions(&fits[1])];
    let alpha = mesh_alpha(&patches, &pos[0]);
    let lines = |cv: &mut Canvas, pos: &[[f32; 2]]| {
        for p in &patches {
            edges(cv, p, pos, &|outline, first| (!outline && first && alpha > 0.0).then_some((0.8, [0, 0, 0], 0.6 * alpha)));
        }
        for p in &patches {
            edges(cv, p, pos, &|outline, _| outline.then_some((1.3, INK, 1.0)));
        }
    };

    // (a) the states as regions, the slip directions
    let code = |k: usize| match pair_of[k] {
        usize::MAX => 3,
        p => contact.states[p].code() as usize,
    };
    let colours = [state_colour(ContactState::Open), state_colour(ContactState::Slip), state_colour(ContactState::Stick), NO_PAIR];
    for p in &patches {
        let ind: [[f64; 9]; 4] = std::array::from_fn(|s| centred(p, |k| if code(k) == s { 1.0 } else { 0.0 }));
        for (q, tri) in pieces(p, &pos[0]) {
            cv.triangle_weighted(q, &|w| {
                let level = |s: usize| w[0] * ind[s][tri[0]] + w[1] * ind[s][tri[1]] + w[2] * ind[s][tri[2]];
                colours[(0..4).fold(0, |b, s| if level(s) > level(b) { s } else { b })]
            });
        }
    }
    lines(&mut cv, &pos[0]);
    let area_px: f64 = patches.iter().flat_map(|p| pieces(p, &pos[0])).map(|(q, _)| 0.5 * ((q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0])).abs() as f64).sum();
    let arrows = slip_arrows(&mut cv, model, contact, &plane, &pairs, &fits[0], area_px);
    let mut counts = [0usize; 3];
    for &p in &pairs {
        counts[contact.states[p].code() as usize] += 1;
    }
    let unpaired = nodes.iter().any(|&k| pair_of[k] == usize::MAX);
    state_legend(&mut cv, &mut labels, layout.column[0], layout.boxes[0][1], counts, unpaired, arrows > 0);

    // (b) sigma_n
    let sigma: Vec<f32> = pair_of.iter().map(|&p| if p == usize::MAX { f32::NAN } else { contact.pairs[p].sigma_n as f32 }).collect();
    let lim = Limits::of(true, &[pairs.iter().map(|&p| contact.pairs[p].sigma_n as f32).collect()]);
    let lut = colour_map(true, lim.lo, lim.hi);
    for p in &patches {
        fill(&mut cv, p, &pos[1], &|p| centred(p, |k| lim.norm(sigma[k])), &|t| lut_colour(&lut, t));
    }
    lines(&mut cv, &pos[1]);
    let b = layout.boxes[1];
    colour_bar(&mut cv, &mut labels, &lut, &lim, "σn", [layout.column[1], b[1] + 52.0, b[3] - 44.0]);

    // frames, axes, headings
    let names = [direction(plane.r, false), direction(plane.v, false)];
    for fit in &fits {
        axes(&mut cv, &mut labels, fit, lo, hi, &names);
    }
    let heading = |b: [f64; 4], text: &str| label(text, (b[0], b[1] - 22.0), 17.0, (HPos::Left, VPos::Center));
    labels.push(heading(layout.boxes[0], "(a) contact state: where it sticks, slips and opens"));
    labels.push(heading(layout.boxes[1], "(b) σn, contact normal stress (tension > 0)"));
    let [bi, bii] = sides(model, ii, &pairs);
    let viewer = if dot(plane.e, mean_normal(model, &pairs)) >= 0.0 { &bii } else { &bi };
    let above = if dot(plane.e, plane.up) > 0.9 { ", above" } else { "" };
    labels.push(label(title, (24.0, 14.0), 24.0, (HPos::Left, VPos::Top)));
    labels.push(label(
        format!("plan view of contact \"{}\" between {} and {} ({} pairs), seen from {}{above} (the side of {})", iface.name, bi.0, bii.0, pairs.len(), direction(plane.e, true), viewer.0),
        (24.0, 50.0),
        17.0,
        (HPos::Left, VPos::Top),
    ));
    let note = match (counts[1], arrows) {
        (0, _) => "No pair slips.".to_string(),
        (_, 0) => "The slipping pairs carry no shear (frictionless slip): no slip directions to draw.".to_string(),
        _ => format!("Arrows: the direction in which {} {} relative to {} (the shear on {}), on slipping pairs.", bii.0, if bii.1 > 1 { "slip" } else { "slips" }, bi.0, bi.0),
    };
    labels.push(label(note, (24.0, layout.h as f64 - 18.0), 14.0, (HPos::Left, VPos::Center)));
    cv.text(&labels)?;
    Ok((cv, layout.boxes))
}

/// The bodies on each side of interface `ii` as `"a", "b" and "c"`, with
/// their number: side I as the model lists it, side II the bodies that
/// hold the pairs' second nodes.
fn sides(model: &Model, ii: usize, pairs: &[usize]) -> [(String, usize); 2] {
    let iface = &model.interfaces[ii];
    let mut second = vec![false; model.n_nodes()];
    for &p in pairs {
        second[model.pairs[p].l] = true;
    }
    let mut side_ii: Vec<usize> = (0..model.bodies.len()).filter(|&b| model.bodies[b].cells.iter().any(|c| c.nodes.iter().any(|&k| second[k]))).collect();
    if side_ii.is_empty() {
        side_ii.push(iface.body_ii);
    }
    let names = |bodies: &[usize]| -> (String, usize) {
        let q: Vec<String> = bodies.iter().map(|&b| format!("\"{}\"", model.bodies[b].name)).collect();
        let text = match q.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
            _ => q.concat(),
        };
        (text, bodies.len())
    };
    [names(&iface.side_i), names(&side_ii)]
}

/// The unnormalised mean outward normal of body I over the pairs.
fn mean_normal(model: &Model, pairs: &[usize]) -> [f64; 3] {
    let mut m = [0.0; 3];
    for &p in pairs {
        for (mi, ni) in m.iter_mut().zip(model.pairs[p].normal) {
            *mi += model.pairs[p].area * ni;
        }
    }
    m
}

/// Arrows along the shear of slipping pairs, no two closer than the
/// pairs' spacing or 30 px: the pairs taken row by row from the top, each
/// kept when no kept one is that near. Returns how many were drawn.
fn slip_arrows(cv: &mut Canvas, model: &Model, contact: &ContactRun, plane: &Plane, pairs: &[usize], fit: &Fit, area_px: f64) -> usize {
    let gap = (area_px / pairs.len().max(1) as f64).sqrt().max(30.0) as f32;
    let at = |p: usize| fit.screen(plane.at(model.coords[model.pairs[p].k]));
    let mut slipping: Vec<(usize, [f32; 2])> = pairs.iter().filter(|&&p| contact.states[p] == ContactState::Slip).map(|&p| (p, at(p))).collect();
    slipping.sort_by(|a, b| (a.1[1].round(), a.1[0]).partial_cmp(&(b.1[1].round(), b.1[0])).unwrap_or(std::cmp::Ordering::Equal));
    // kept sites in cells of the gap's size: a near one is in the 3 x 3 around
    let mut kept: std::collections::HashMap<(i64, i64), Vec<[f32; 2]>> = std::collections::HashMap::new();
    let cell = |q: [f32; 2]| ((q[0] / gap).floor() as i64, (q[1] / gap).floor() as i64);
    let half = 0.36 * gap;
    let mut drawn = 0;
    for (p, q) in slipping {
        let (i, j) = cell(q);
        let near = (i - 1..=i + 1).flat_map(|a| (j - 1..=j + 1).map(move |b| (a, b))).any(|c| kept.get(&c).is_some_and(|v| v.iter().any(|o| (o[0] - q[0]).hypot(o[1] - q[1]) < gap)));
        if near {
            continue;
        }
        let t = contact.shear(p);
        let d = [dot(t, plane.r) as f32, -dot(t, plane.v) as f32];
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
fn state_legend(cv: &mut Canvas, labels: &mut Vec<Label>, x: f64, top: f64, counts: [usize; 3], unpaired: bool, arrows: bool) {
    let mut y = top + 10.0;
    labels.push(label("contact pairs", (x, y), 16.0, (HPos::Left, VPos::Center)));
    let mut entries: Vec<([u8; 3], String)> =
        [(ContactState::Stick, counts[2]), (ContactState::Slip, counts[1]), (ContactState::Open, counts[0])].iter().map(|&(s, n)| (state_colour(s), format!("{} ({n})", s.name()))).collect();
    if unpaired {
        // facet nodes that are no pair's first node (where contacts meet)
        entries.push((NO_PAIR, "no pair here".into()));
    }
    for (colour, text) in entries {
        y += 28.0;
        cv.rect(x + 1.0, y - 8.0, x + 25.0, y + 8.0, colour);
        cv.polyline([[x + 1.0, y - 8.0], [x + 25.0, y - 8.0], [x + 25.0, y + 8.0], [x + 1.0, y + 8.0], [x + 1.0, y - 8.0]].map(|p| [p[0] as f32, p[1] as f32]).into_iter(), 1.0, INK, 1.0);
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
/// edges, the axes' directions named.
fn axes(cv: &mut Canvas, labels: &mut Vec<Label>, fit: &Fit, lo: [f64; 2], hi: [f64; 2], names: &[String; 2]) {
    let (a, b) = (fit.screen(lo), fit.screen(hi));
    let (x0, x1, y0, y1) = (a[0] - 10.0, b[0] + 10.0, b[1] - 10.0, a[1] + 10.0);
    cv.polyline([[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]].into_iter(), 1.0, [160, 160, 160], 1.0);
    for d in 0..2 {
        let step = nice_step((hi[d] - lo[d]) / 5.0);
        let mut k = (lo[d] / step - 1e-9).ceil() as i64;
        while (k as f64) * step <= hi[d] + 1e-9 * step {
            let v = k as f64 * step;
            let mut q = lo;
            q[d] = v;
            let s = fit.screen(q);
            if d == 0 {
                cv.segment([s[0], y1], [s[0], y1 + 5.0], 1.0, INK, 1.0, false);
                labels.push(label(num(v), (s[0] as f64, y1 as f64 + 8.0), 13.0, (HPos::Center, VPos::Top)));
            } else {
                cv.segment([x0 - 5.0, s[1]], [x0, s[1]], 1.0, INK, 1.0, false);
                labels.push(label(num(v), (x0 as f64 - 8.0, s[1] as f64), 13.0, (HPos::Right, VPos::Center)));
            }
            k += 1;
        }
    }
    labels.push(label(names[0].clone(), (0.5 * (x0 + x1) as f64, y1 as f64 + 28.0), 15.0, (HPos::Center, VPos::Top)));
    labels.push(label(names[1].clone(), (x0 as f64 - 8.0, y0 as f64 - 4.0), 15.0, (HPos::Right, VPos::Bottom)));
}
