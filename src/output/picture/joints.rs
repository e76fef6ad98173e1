//! Every contact surface of a 3D model by state, in one picture
//! (`joints.png`): a tile per sheet ([`super::sheets`]: a plane of a joint
//! set, a crease's face, an unrolled lining), laid flat as in its plan view
//! and painted stick, slip or open as there, all at one scale so that the
//! tiles compare. What a rock engineer scans first in a model of many
//! joints: which planes open and where, before opening each plan.

use plotters::style::text_anchor::{HPos, VPos};

use super::colours::{state_colour, INK};
use super::picture_error::PictureError;
use super::plan::{paint_states, sheet_pairs, Fit, PlanFile};
use super::raster::{encode_png, label, register_font, Canvas, Label};
use super::sheets::{Flat, Shape};
use super::surface::edges;
use crate::contact::law::ContactState;
use crate::model::Model;
use crate::results::ContactRun;

/// The overview's file name when the model has more than one sheet (with
/// one, its plan view says it all).
pub fn joints_file(plans: &[PlanFile]) -> Option<&'static str> {
    (plans.len() > 1).then_some("joints.png")
}

/// Canvas width, the most height, the largest side of a tile, the margin
/// round the tiles, the space between tiles and the room above each for
/// its heading, and the top of the first row.
const WIDTH: f64 = 1600.0;
const MOST_HEIGHT: f64 = 2400.0;
const MOST_SIDE: f64 = 400.0;
const MARGIN: f64 = 40.0;
const GAP: f64 = 28.0;
const HEADING: f64 = 44.0;
const TOP: f64 = 130.0;

/// Tiles of these sizes (model units) at `px` pixels per unit, packed in
/// rows left to right: each tile's top-left corner, and the height used.
fn pack(sizes: &[[f64; 2]], px: f64) -> (Vec<[f64; 2]>, f64) {
    let (mut x, mut y, mut row) = (MARGIN, TOP, 0.0f64);
    let mut at = Vec::with_capacity(sizes.len());
    for s in sizes {
        let (w, h) = ((s[0] * px).max(24.0), (s[1] * px).max(24.0) + HEADING);
        if x > MARGIN && x + w > WIDTH - MARGIN {
            (x, y, row) = (MARGIN, y + row + GAP, 0.0);
        }
        at.push([x, y + HEADING]);
        x += w.max(210.0) + GAP;
        row = row.max(h);
    }
    (at, y + row)
}

/// The overview of every sheet of `plans` by state.
pub fn joints_png(
    title: &str,
    model: &Model,
    contact: &ContactRun,
    plans: &[PlanFile],
) -> Result<Vec<u8>, PictureError> {
    register_font();
    if contact.states.len() != model.pairs.len() {
        return Err(PictureError::Mismatch { what: "contact results" });
    }
    // 1. every sheet laid flat, and the one scale of the tiles
    let flats: Vec<_> = plans.iter().map(|p| p.sheet.flat(model)).collect();
    let sizes: Vec<[f64; 2]> =
        flats.iter().map(|f| [(f.hi[0] - f.lo[0]).max(1e-300), (f.hi[1] - f.lo[1]).max(1e-300)]).collect();
    let px = scale(&sizes);
    let (corners, used) = pack(&sizes, px);
    // 2. a canvas as wide as the tiles and the legend need
    let right = corners.iter().zip(&sizes).map(|(c, s)| c[0] + (s[0] * px).max(210.0)).fold(900.0, f64::max);
    let mut cv = Canvas::new((right + MARGIN).min(WIDTH).round() as usize, (used + 40.0).round() as usize);
    // 3. the tiles, counting the states
    let mut labels = Vec::new();
    let mut totals = [0usize; 3];
    for ((plan, flat), at) in plans.iter().zip(&flats).zip(&corners) {
        let counts = tile(&mut cv, &mut labels, (model, contact), (plan, flat), *at, px);
        for s in 0..3 {
            totals[s] += counts[s];
        }
    }
    // 4. the headings and the legend
    legend(&mut cv, &mut labels, title, plans.len(), totals);
    cv.text(&labels)?;
    encode_png(cv.w, cv.h, &cv.rgb)
}

/// The largest scale (pixels per model unit) whose rows of tiles fit the
/// height, no tile over MOST_SIDE.
fn scale(sizes: &[[f64; 2]]) -> f64 {
    let biggest = sizes.iter().map(|s| s[0].max(s[1])).fold(0.0, f64::max);
    let widest = sizes.iter().map(|s| s[0]).fold(0.0, f64::max);
    let (mut lo, mut hi) = (0.0, (MOST_SIDE / biggest).min((WIDTH - 2.0 * MARGIN) / widest));
    if pack(sizes, hi).1 > MOST_HEIGHT {
        for _ in 0..50 {
            let mid = 0.5 * (lo + hi);
            if pack(sizes, mid).1 > MOST_HEIGHT {
                hi = mid
            } else {
                lo = mid
            }
        }
        hi = lo;
    }
    hi
}

/// One sheet's tile with its top-left corner at `at`: painted by state,
/// outlined, and headed by its file, its counts and its interface. Returns
/// the sheet's open, slip and stick counts.
fn tile(
    cv: &mut Canvas,
    labels: &mut Vec<Label>,
    (model, contact): (&Model, &ContactRun),
    (plan, flat): (&PlanFile, &Flat),
    at: [f64; 2],
    px: f64,
) -> [usize; 3] {
    let (x0, y0) = (at[0], at[1]);
    let (w, h) = ((flat.hi[0] - flat.lo[0]) * px, (flat.hi[1] - flat.lo[1]) * px);
    let fit = Fit::new(flat.lo, flat.hi, [x0, y0, x0 + w.max(1.0), y0 + h.max(1.0)], 0.0);
    let pos: Vec<[f32; 2]> = flat.points.iter().map(|&q| fit.screen(q)).collect();
    let (pair_of, pairs) = sheet_pairs(model, &plan.sheet);
    let code = |j: usize| match pair_of[flat.node[j]] {
        usize::MAX => 3,
        p => contact.states[p].code() as usize,
    };
    let (a, z) = (fit.screen(flat.lo), fit.screen(flat.hi));
    cv.clip(Some([a[0] as f64 - 0.5, z[1] as f64 - 0.5, z[0] as f64 + 1.5, a[1] as f64 + 1.5]));
    paint_states(cv, &flat.patches, &pos, &code);
    for p in &flat.patches {
        edges(cv, p, &pos, &|outline, _| outline.then_some((1.0, INK, 1.0)));
    }
    cv.clip(None);
    let mut counts = [0usize; 3];
    for &p in &pairs {
        counts[contact.states[p].code() as usize] += 1;
    }
    let iface = &model.interfaces[plan.interface].name;
    let what = if matches!(plan.sheet.shape, Shape::Cylinder { .. }) { " (unrolled)" } else { "" };
    labels.push(label(
        format!("{}{what}: {} / {} / {}", plan.file, counts[2], counts[1], counts[0]),
        (x0, y0 - 30.0),
        13.0,
        (HPos::Left, VPos::Center),
    ));
    labels.push(label(
        format!("\"{iface}\": {}", plan.sheet.short(model)),
        (x0, y0 - 12.0),
        12.0,
        (HPos::Left, VPos::Center),
    ));
    counts
}

/// The title, the line under it and the legend: the states with the
/// model's totals, and what the numbers are.
fn legend(cv: &mut Canvas, labels: &mut Vec<Label>, title: &str, sheets: usize, totals: [usize; 3]) {
    labels.push(label(title, (24.0, 14.0), 24.0, (HPos::Left, VPos::Top)));
    labels.push(label(
        format!("every contact surface by state: {sheets} sheets (planes and unrolled surfaces), each laid flat as in its plan view, all at one scale"),
        (24.0, 50.0),
        17.0,
        (HPos::Left, VPos::Top),
    ));
    let mut x = 24.0;
    for (s, n) in [(ContactState::Stick, totals[2]), (ContactState::Slip, totals[1]), (ContactState::Open, totals[0])] {
        cv.rect(x, 84.0, x + 22.0, 100.0, state_colour(s));
        labels.push(label(format!("{} ({n})", s.name()), (x + 30.0, 92.0), 14.0, (HPos::Left, VPos::Center)));
        x += 160.0;
    }
    labels.push(label(
        "after each file name: stick / slip / open pairs",
        (x + 20.0, 92.0),
        13.0,
        (HPos::Left, VPos::Center),
    ));
}
