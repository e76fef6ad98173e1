//! Beside the deformed picture: the colour scale (its limits, the colour
//! maps, the bar with its ticks), the contact states' legend with their
//! counts, and the x, y, z triad of a 3D view.

use plotters::style::text_anchor::{HPos, VPos};

use super::colours::{state_colour, GHOST, INK};
use super::label_numbers::num;
use super::raster::{label, Canvas, Label};
use super::view::View;
use crate::contact::law::ContactState;

/// The left edge of the right-hand panel of the deformed picture: colour
/// bars, then the legend.
pub(super) const PANEL_X: f64 = 990.0;

/// The colour bar's limits `lo..hi` and the field's own range `min..max`.
pub(super) struct Limits {
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) min: f64,
    pub(super) max: f64,
}

impl Limits {
    /// Limits from the nodal values: the field's range, except that a few
    /// outlying nodes (a stress singularity at a corner or a point support)
    /// do not take the whole colour bar ([`robust`]): those nodes take its
    /// end colour, and the bar says how far they go. Signed fields (stress
    /// components) spanning zero get limits symmetric about it, so that grey
    /// is zero; round-off of the other sign (below 1e-3 of the largest
    /// value) is zero.
    pub(super) fn of(signed: bool, values: &[Vec<f32>]) -> Limits {
        let all: Vec<f64> = values.iter().flatten().filter(|v| v.is_finite()).map(|&v| v as f64).collect();
        let Robust { mut lo, mut hi, mut min, mut max } = robust(all);
        let big = min.abs().max(max.abs());
        if min < 0.0 && min > -1e-3 * big {
            min = 0.0;
            lo = lo.max(0.0);
        }
        if max > 0.0 && max < 1e-3 * big {
            max = 0.0;
            hi = hi.min(0.0);
        }
        if signed && lo < 0.0 && hi > 0.0 {
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
    pub(super) fn norm(&self, v: f32) -> f32 {
        ((v as f64 - self.lo) / (self.hi - self.lo)) as f32
    }
}

/// The range a picture scales to, and the values' own.
pub(crate) struct Robust {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) min: f64,
    pub(crate) max: f64,
}

/// The values' range, except where a few of them stand far out (a
/// singular corner of a footing, a point support): with the k = n/200
/// (at least 2, at most n/5) most extreme values at each end set aside, an
/// end stops at the k-th value when the values beyond it lie further out
/// than half the spread of the rest. A bearing diagram of 0..1,100 with a
/// corner of 2,337 scales to 0..1,100, not to the corner.
pub(crate) fn robust(mut all: Vec<f64>) -> Robust {
    if all.is_empty() {
        all.push(0.0);
    }
    let n = all.len();
    all.sort_by(f64::total_cmp);
    let k = (n / 200).max(2).min(n / 5);
    let (min, max, q_lo, q_hi) = (all[0], all[n - 1], all[k], all[n - 1 - k]);
    let spread = q_hi - q_lo;
    let lo = if q_lo - min > 0.5 * spread { q_lo } else { min };
    let hi = if max - q_hi > 0.5 * spread { q_hi } else { max };
    Robust { lo, hi, min, max }
}

/// The colour maps' stops, nine each: for magnitudes viridis,
/// yellow–orange–red and purples; for signed fields cool-to-warm,
/// purple–green and brown–teal.
const VIRIDIS: [[u8; 3]; 9] = [
    [68, 1, 84],
    [71, 44, 122],
    [59, 81, 139],
    [44, 113, 142],
    [33, 145, 140],
    [39, 173, 129],
    [92, 200, 99],
    [170, 220, 50],
    [253, 231, 37],
];

const COOL_WARM: [[u8; 3]; 9] = [
    [59, 76, 192],
    [98, 130, 234],
    [141, 176, 254],
    [184, 208, 249],
    [221, 221, 221],
    [245, 196, 173],
    [244, 154, 123],
    [222, 96, 77],
    [180, 4, 38],
];

const YL_OR_RD: [[u8; 3]; 9] = [
    [255, 255, 204],
    [255, 237, 160],
    [254, 217, 118],
    [254, 178, 76],
    [253, 141, 60],
    [252, 78, 42],
    [227, 26, 28],
    [189, 0, 38],
    [128, 0, 38],
];

const PURPLES: [[u8; 3]; 9] = [
    [252, 251, 253],
    [239, 237, 245],
    [218, 218, 235],
    [188, 189, 220],
    [158, 154, 200],
    [128, 125, 186],
    [106, 81, 163],
    [84, 39, 143],
    [63, 0, 125],
];

const PR_GN: [[u8; 3]; 9] = [
    [118, 42, 131],
    [153, 112, 171],
    [194, 165, 207],
    [231, 212, 232],
    [247, 247, 247],
    [217, 240, 211],
    [166, 219, 160],
    [90, 174, 97],
    [27, 120, 55],
];

const BR_BG: [[u8; 3]; 9] = [
    [140, 81, 10],
    [191, 129, 45],
    [223, 194, 125],
    [246, 232, 195],
    [245, 245, 245],
    [199, 234, 229],
    [128, 205, 193],
    [53, 151, 143],
    [1, 102, 94],
];

/// Colour maps as 256-entry tables: viridis for magnitudes; cool-to-warm
/// (blue compression, grey zero, red tension) for signed fields (stress
/// components), its blue or red half alone when the values have one sign.
pub(super) fn colour_map(signed: bool, lo: f64, hi: f64) -> Vec<[u8; 3]> {
    colour_map_of(0, signed, lo, hi)
}

/// Colour map number `k` of a picture with several colour scales (bodies
/// whose stresses differ by orders of magnitude): 0 as [`colour_map`], 1
/// yellow–orange–red (signed: purple–green), 2 light to dark purple
/// (signed: brown–teal); beyond, as 2.
pub(super) fn colour_map_of(k: usize, signed: bool, lo: f64, hi: f64) -> Vec<[u8; 3]> {
    let (magnitude, diverging) = match k {
        0 => (&VIRIDIS, &COOL_WARM),
        1 => (&YL_OR_RD, &PR_GN),
        _ => (&PURPLES, &BR_BG),
    };
    let (stops, u0, u1) = match signed {
        false => (magnitude, 0.0, 1.0),
        true if lo < 0.0 && hi > 0.0 => (diverging, 0.0, 1.0),
        true if hi <= 0.0 => (diverging, 0.0, 0.5),
        true => (diverging, 0.5, 1.0),
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

/// The colour of a value scaled to the bar (0..1, beyond it the end
/// colours); grey where there is no value.
pub(super) fn lut_colour(lut: &[[u8; 3]], t: f32) -> [u8; 3] {
    if t.is_nan() {
        [150, 150, 150]
    } else {
        let last = lut.len().saturating_sub(1);
        lut.get(((t.clamp(0.0, 1.0) * last as f32 + 0.5) as usize).min(last)).copied().unwrap_or([150, 150, 150])
    }
}

/// What the legend under the colour bars says: the contact states' counts
/// (None without contact), whether the model is drawn in a 3D view (the
/// pairs as dots) and whether the undeformed ghost shows (2D).
pub(super) struct LegendOf {
    pub(super) counts: Option<[usize; 3]>,
    pub(super) solid: bool,
    pub(super) ghost: bool,
}

/// Under the colour bars, from `top`: the contact states with their
/// counts, and the undeformed shape's swatch.
pub(super) fn legend(cv: &mut Canvas, labels: &mut Vec<Label>, of: &LegendOf, top: f64) {
    let x = PANEL_X as f32;
    let mut y = top as f32;
    let text = |labels: &mut Vec<Label>, t: String, x: f32, y: f32, size: f64| {
        labels.push(label(t, (x as f64, y as f64), size, (HPos::Left, VPos::Center)))
    };
    if let Some(counts) = of.counts {
        text(labels, "contact pairs".into(), x, y, 16.0);
        for (s, count) in
            [(ContactState::Stick, counts[2]), (ContactState::Slip, counts[1]), (ContactState::Open, counts[0])]
        {
            y += 26.0;
            if of.solid {
                cv.state_dot([x + 12.0, y], state_colour(s));
            } else {
                cv.segment([x + 2.0, y], [x + 24.0, y], 7.0, [0, 0, 0], 1.0, true);
                cv.segment([x + 2.0, y], [x + 24.0, y], 4.2, state_colour(s), 1.0, true);
            }
            text(labels, format!("{} ({count})", s.name()), x + 36.0, y, 15.0);
        }
        if of.solid {
            y += 22.0;
            text(labels, "(seen through the solid, thinned;".into(), x, y, 12.0);
            y += 16.0;
            text(labels, "every pair in plan_*.png)".into(), x, y, 12.0);
        }
        y += 34.0;
    }
    if of.ghost {
        cv.rect(x as f64 + 2.0, y as f64 - 7.0, x as f64 + 24.0, y as f64 + 7.0, GHOST);
        let frame =
            [[x + 2.0, y - 7.0], [x + 24.0, y - 7.0], [x + 24.0, y + 7.0], [x + 2.0, y + 7.0], [x + 2.0, y - 7.0]];
        cv.polyline(frame.into_iter(), 1.0, [175, 175, 175], 1.0);
        text(labels, "undeformed".into(), x + 36.0, y, 15.0);
    }
}

/// The vertical colour bar with its limits and a few round ticks; an arrow
/// head at an end whose colour also stands for values beyond it, and the
/// field's minimum and maximum under the bar when they are not its ends.
/// `at`: the bar's left edge, top and bottom in pixels; its title goes
/// above it, the last line 52 pixels above, each earlier one 19 higher.
pub(super) fn colour_bar(
    cv: &mut Canvas,
    labels: &mut Vec<Label>,
    lut: &[[u8; 3]],
    lim: &Limits,
    title: &[String],
    at: [f64; 3],
) {
    let (lo, hi) = (lim.lo, lim.hi);
    let (bx0, bx1, by0, by1) = (at[0], at[0] + 26.0, at[1], at[2]);
    for (i, line) in title.iter().enumerate() {
        let y = by0 - 52.0 - 19.0 * (title.len() - 1 - i) as f64;
        labels.push(label(line.clone(), (bx0, y), if i == 0 { 16.0 } else { 14.0 }, (HPos::Left, VPos::Center)));
    }
    for y in by0 as usize..by1 as usize {
        let t = 1.0 - (y as f64 - by0) / (by1 - by0 - 1.0);
        // the bar's top may be a fractional pixel: t a little above 1
        let c = lut_colour(lut, t as f32);
        cv.rect(bx0, y as f64, bx1, y as f64 + 1.0, c);
    }
    let f = |x: f64, y: f64| [x as f32, y as f32];
    let mid = 0.5 * (bx0 + bx1);
    let over = lim.max > hi + 1e-9 * (hi - lo);
    let under = lim.min < lo - 1e-9 * (hi - lo);
    let mut frame = vec![f(bx0, by0)];
    if over {
        cv.triangle([f(bx0, by0), f(bx1, by0), f(mid, by0 - 16.0)], [0.0; 3], &|_| lut_colour(lut, 1.0));
        frame.push(f(mid, by0 - 16.0));
    }
    frame.extend([f(bx1, by0), f(bx1, by1)]);
    if under {
        cv.triangle([f(bx0, by1), f(bx1, by1), f(mid, by1 + 16.0)], [0.0; 3], &|_| lut_colour(lut, 0.0));
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
        labels.push(label(
            format!("up to {}", num(lim.max)),
            (bx1 + 9.0, by0 - 20.0),
            13.0,
            (HPos::Left, VPos::Center),
        ));
    }
    if under {
        labels.push(label(
            format!("down to {}", num(lim.min)),
            (bx1 + 9.0, by1 + 20.0),
            13.0,
            (HPos::Left, VPos::Center),
        ));
    }
    if lim.min > lo + 1e-9 * (hi - lo) || lim.max < hi - 1e-9 * (hi - lo) {
        labels.push(label(
            format!("min {}, max {}", num(lim.min), num(lim.max)),
            (bx0, by1 + 40.0),
            13.0,
            (HPos::Left, VPos::Center),
        ));
    }
}

/// x, y, z arrows in the view of a 3D picture.
pub(super) fn triad(cv: &mut Canvas, labels: &mut Vec<Label>, view: &View) {
    let o = [70.0f32, 730.0];
    for (d, name) in ["x", "y", "z"].iter().enumerate() {
        let mut e = [0.0; 3];
        e[d] = 1.0;
        let (p, _) = view.project(e);
        let tip = [o[0] + 36.0 * p[0] as f32, o[1] - 36.0 * p[1] as f32];
        cv.segment(o, tip, 1.6, INK, 1.0, true);
        labels.push(label(
            *name,
            ((o[0] + 48.0 * p[0] as f32) as f64, (o[1] - 48.0 * p[1] as f32) as f64),
            15.0,
            (HPos::Center, VPos::Center),
        ));
    }
}

/// 1, 2, 2.5 or 5 times a power of ten, at least `raw`.
pub(super) fn nice_step(raw: f64) -> f64 {
    if raw.is_nan() || raw <= 0.0 || raw.is_infinite() {
        return 1.0;
    }
    let p = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0].iter().map(|m| m * p).find(|&s| s >= raw * (1.0 - 1e-12)).unwrap_or(10.0 * p)
}
