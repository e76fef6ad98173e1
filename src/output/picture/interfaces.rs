//! The interface plot (SVG): one panel per contact interface (in 3D, per
//! sheet of it: a plane of a joint set, an unrolled lining), the normal
//! stress sigma_n (tension positive) and the shear stress tau against the
//! position along the interface, the contact state as background bands (2D)
//! or marker colours (3D). plotters draws it, in the embedded font.
//!
//! In 2D the position is the arc length along the interface's chain of
//! facets. A 3D sheet is a surface, so one position leaves out the other
//! direction: the plot uses the direction in which the stresses vary
//! ([`Along::of_sheet`]): every direction of the sheet's plane in 5-degree
//! steps (an unrolled surface: its angle or its axis) is scored by how much
//! of the stresses' variance is left within bins of the position along it,
//! and the best one is taken (a world axis, or the angle, when it does
//! within 0.02 as well). A wall's base, pressed harder at the toe than at
//! the heel all along the wall, is plotted across the wall, not along it.
//! When a quarter of the variance or more is left, the panel says so and
//! points to the sheet's plan view, which maps both directions.

use std::collections::HashMap;

use plotters::coord::cartesian::Cartesian2d;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::colours::state_colour;
use super::label_numbers::num;
use super::picture_error::PictureError;
use super::plan::{plan_files, sheet_pairs, sides, PlanFile};
#[cfg(test)]
use super::raster::encode_png;
use super::raster::{register_font, rgb};
use super::sheets::{direction, Shape, Sheet};
use crate::contact::law::ContactState;
use crate::fem::vec3::{dot, sub};
use crate::fem::Analysis;
use crate::model::{Interface, Model};
use crate::results::ContactRun;

/// The most panels an interface plot shows (a joint set of many planes
/// leaves the rest to `joints.png` and the plan views).
const MOST_PANELS: usize = 24;

/// The pairs of one interface in order along it.
pub(super) struct Along {
    /// Runs of pairs (pair index, position s); lines are drawn within a run.
    pub(super) runs: Vec<Vec<(usize, f64)>>,
    /// What s measures, for the axis.
    pub(super) axis: String,
    /// The share of the stresses' variance that the position leaves
    /// unexplained (3D; 0 in 2D).
    pub(super) left: f64,
}

impl Along {
    /// A 3D sheet's pairs against the direction in which their stresses
    /// vary (see the module header).
    pub(super) fn of_sheet(model: &Model, sheet: &Sheet, c: &ContactRun) -> Along {
        let (_, pairs) = sheet_pairs(model, sheet);
        let uv: Vec<[f64; 2]> = pairs.iter().map(|&p| sheet.at(model.coords[model.pairs[p].k])).collect();
        let values: Vec<[f64; 2]> = pairs.iter().map(|&p| [c.pairs[p].sigma_n, c.pairs[p].tau()]).collect();
        let cylinder = matches!(sheet.shape, Shape::Cylinder { .. });
        let angles: Vec<f64> = if cylinder { vec![0.0, 90.0] } else { (0..36).map(|i| 5.0 * i as f64).collect() };
        let s_of = |phi: f64, q: [f64; 2]| phi.to_radians().cos() * q[0] + phi.to_radians().sin() * q[1];
        let score = |phi: f64| -> f64 { unexplained(&uv.iter().map(|&q| s_of(phi, q)).collect::<Vec<_>>(), &values) };
        let scores: Vec<(f64, f64)> = angles.iter().map(|&a| (a, score(a))).collect();
        let best = scores.iter().copied().fold((0.0, f64::INFINITY), |b, x| if x.1 < b.1 { x } else { b });
        // a world axis or the angle when it explains nearly as much
        let plain = |phi: f64| -> bool {
            if cylinder {
                return phi == 0.0;
            }
            let (r, v) = sheet.directions([0.0; 3]);
            let d: [f64; 3] = std::array::from_fn(|i| phi.to_radians().cos() * r[i] + phi.to_radians().sin() * v[i]);
            d.iter().any(|x| (x.abs() - 1.0).abs() < 1e-6)
        };
        let (phi, left) = scores
            .iter()
            .copied()
            .filter(|&(a, sc)| plain(a) && sc <= best.1 + 0.02)
            .fold(best, |b, x| if plain(b.0) && b.1 <= x.1 { b } else { x });
        let (mut pts, axis): (Vec<(usize, f64)>, String) = match &sheet.shape {
            Shape::Cylinder { radius, a, crown, zero, .. } if phi == 0.0 => {
                let from = if *crown { "the crown".to_string() } else { direction(*zero, true) };
                let _ = a;
                (
                    pairs.iter().zip(&uv).map(|(&p, q)| (p, (q[0] / radius).to_degrees())).collect(),
                    format!("angle about the axis from {from} (degrees)"),
                )
            }
            _ => {
                let (r, v) = sheet.directions(uv.first().map_or([0.0; 3], |_| model.coords[model.pairs[pairs[0]].k]));
                let mut d: [f64; 3] =
                    std::array::from_fn(|i| phi.to_radians().cos() * r[i] + phi.to_radians().sin() * v[i]);
                let mut sign = 1.0;
                if d.iter().any(|x| (x + 1.0).abs() < 1e-6) {
                    d = d.map(|x| -x);
                    sign = -1.0;
                }
                let name = if cylinder {
                    format!("position along {}", direction(d, false))
                } else {
                    match (0..3).find(|&i| (d[i] - 1.0).abs() < 1e-6) {
                        Some(i) => ["x", "y", "z"][i].to_string(),
                        None => format!("position along {}", direction(d, false)),
                    }
                };
                (pairs.iter().zip(&uv).map(|(&p, &q)| (p, sign * s_of(phi, q))).collect(), name)
            }
        };
        pts.sort_by(|a, b| a.1.total_cmp(&b.1));
        Along { runs: vec![pts], axis, left: if left.is_finite() { left } else { 0.0 } }
    }
}

/// The share of the variance of `values` (sigma_n and tau together) left
/// within bins of the positions `s` (about the square root of their number,
/// 4 to 40 bins of equal width); 0 when the values do not vary.
fn unexplained(s: &[f64], values: &[[f64; 2]]) -> f64 {
    let n = s.len();
    if n < 2 {
        return 0.0;
    }
    let mean: [f64; 2] = std::array::from_fn(|j| values.iter().map(|v| v[j]).sum::<f64>() / n as f64);
    let total: f64 = values.iter().map(|v| (v[0] - mean[0]).powi(2) + (v[1] - mean[1]).powi(2)).sum();
    let scale = values.iter().map(|v| v[0].abs().max(v[1].abs())).fold(0.0, f64::max);
    if total <= 1e-20 * scale * scale * n as f64 || total == 0.0 {
        return 0.0;
    }
    let (lo, hi) = s.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let bins = ((n as f64).sqrt().round() as usize).clamp(4, 40);
    let width = (hi - lo).max(1e-300) / bins as f64;
    let mut acc = vec![(0usize, [0.0f64; 2], [0.0f64; 2]); bins];
    for (x, v) in s.iter().zip(values) {
        let b = (((x - lo) / width) as usize).min(bins - 1);
        acc[b].0 += 1;
        for j in 0..2 {
            acc[b].1[j] += v[j];
            acc[b].2[j] += v[j] * v[j];
        }
    }
    let within: f64 = acc
        .iter()
        .filter(|a| a.0 > 0)
        .map(|(k, sum, sq)| (0..2).map(|j| sq[j] - sum[j] * sum[j] / *k as f64).sum::<f64>())
        .sum();
    (within / total).clamp(0.0, 1.0)
}

/// Orders an interface's pairs: in 2D by walking its chain of facets from
/// the end nearest the model's lower-left corner (arc length), else by the
/// position along the direction in which the pairs spread most.
pub(super) fn along(model: &Model, ii: usize) -> Along {
    let iface = &model.interfaces[ii];
    let mut pair_of = HashMap::new();
    for (i, p) in model.pairs.iter().enumerate() {
        pair_of.insert(p.k, i);
    }
    if model.analysis != Analysis::Solid {
        if let Some(al) = walk_chains(model, iface, &pair_of) {
            return al;
        }
    }
    let mut nodes: Vec<usize> =
        iface.facets.iter().flat_map(|f| f.nodes.iter().copied()).filter(|k| pair_of.contains_key(k)).collect();
    nodes.sort_unstable();
    nodes.dedup();
    principal(model, &nodes, &pair_of)
}

/// A 2D interface's pairs by arc length, walking its chains of facets
/// from the end nearest the model's lower-left corner; None when the
/// facets branch (a node on more than two links).
fn walk_chains(model: &Model, iface: &Interface, pair_of: &HashMap<usize, usize>) -> Option<Along> {
    let x = |k: usize| model.coords[k];
    let corner = lower_corner(model);
    let dist = |a: [f64; 3], b: [f64; 3]| dot(sub(a, b), sub(a, b)).sqrt();
    // links between consecutive nodes of each facet (corner, mid, corner),
    // in node order: of two ends equally near the corner, the first node
    // starts the walk, the same in every run
    let mut links: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for f in &iface.facets {
        let chain: Vec<usize> =
            if f.nodes.len() == 3 { vec![f.nodes[0], f.nodes[2], f.nodes[1]] } else { f.nodes.clone() };
        for w in chain.windows(2) {
            links.entry(w[0]).or_default().push(w[1]);
            links.entry(w[1]).or_default().push(w[0]);
        }
    }
    if !links.values().all(|v| v.len() <= 2) {
        return None;
    }
    let mut seen = std::collections::HashSet::new();
    let mut runs = Vec::new();
    let mut s = 0.0;
    let mut origin = None;
    loop {
        // open chains start at an end, closed ones anywhere; nearest the corner first
        let left = links.keys().copied().filter(|k| !seen.contains(k));
        let ends: Vec<usize> = left.clone().filter(|k| links[k].len() == 1).collect();
        let pool: Vec<usize> = if ends.is_empty() { left.collect() } else { ends };
        let Some(&start) = pool.iter().min_by(|&&a, &&b| dist(x(a), corner).total_cmp(&dist(x(b), corner))) else {
            break;
        };
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
    Some(Along { runs, axis: format!("distance along the interface from ({}, {})", num(o[0]), num(o[1])), left: 0.0 })
}

/// The lower-left corner of the model's box.
fn lower_corner(model: &Model) -> [f64; 3] {
    let mut lo = [f64::INFINITY; 3];
    for &k in model.bodies.iter().flat_map(|b| &b.cells).flat_map(|c| &c.nodes) {
        for (l, x) in lo.iter_mut().zip(model.coords[k]) {
            *l = l.min(x);
        }
    }
    lo
}

/// The pairs at `nodes` by their position along the principal direction
/// of the nodes' positions.
fn principal(model: &Model, nodes: &[usize], pair_of: &HashMap<usize, usize>) -> Along {
    let x = |k: usize| model.coords[k];
    let n = nodes.len().max(1) as f64;
    let mean: [f64; 3] = std::array::from_fn(|d| nodes.iter().map(|&k| x(k)[d]).sum::<f64>() / n);
    let mut cov = nalgebra::Matrix3::<f64>::zeros();
    for &k in nodes {
        let r = sub(x(k), mean);
        for i in 0..3 {
            for j in 0..3 {
                cov[(i, j)] += r[i] * r[j];
            }
        }
    }
    // (positions that do not decompose are drawn along x)
    let mut dir = crate::fem::bounded::symmetric_eigen(cov).map_or([1.0, 0.0, 0.0], |eig| {
        let imax = eig.eigenvalues.iamax();
        [eig.eigenvectors[(0, imax)], eig.eigenvectors[(1, imax)], eig.eigenvectors[(2, imax)]]
    });
    if dot(dir, [1.0, 1.0, 1.0]) < 0.0 {
        dir = dir.map(|v| -v);
    }
    let mut pts: Vec<(usize, f64)> = nodes.iter().map(|&k| (pair_of[&k], dot(sub(x(k), mean), dir))).collect();
    let smin = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    for p in &mut pts {
        p.1 -= smin;
    }
    pts.sort_by(|a, b| a.1.total_cmp(&b.1));
    Along {
        runs: vec![pts],
        axis: format!("position along the direction ({}, {}, {})", num(dir[0]), num(dir[1]), num(dir[2])),
        left: 0.0,
    }
}

/// An SVG with one panel per interface (per sheet in 3D, at most
/// [`MOST_PANELS`]): the normal stress σn (tension positive) and the shear
/// stress τ against the position along it, the contact state as background
/// bands (2D) or marker colours (3D).
pub fn interface_plot_svg(model: &Model, contact: &ContactRun) -> Result<String, PictureError> {
    let panels = panels(model)?;
    let (w, h) = size(&panels);
    let mut out = String::new();
    interface_plot_on(SVGBackend::with_string(&mut out, (w, h)).into_drawing_area(), model, contact, &panels)?;
    Ok(out)
}

/// The same plot as [`interface_plot_svg`], as a PNG, to look at in tests
/// (plotters' bitmap text spaces letters unevenly, see `raster::Canvas::text`).
#[cfg(test)]
pub(super) fn interface_plot_png(model: &Model, contact: &ContactRun) -> Result<Vec<u8>, PictureError> {
    let panels = panels(model)?;
    let (w, h) = size(&panels);
    let mut buf = vec![255u8; w as usize * h as usize * 3];
    interface_plot_on(BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area(), model, contact, &panels)?;
    encode_png(w as usize, h as usize, &buf)
}

/// What the plot shows: the panels (an interface, and in 3D its sheet) and
/// how many sheets are left out.
struct Panels {
    list: Vec<(usize, Option<PlanFile>)>,
    left_out: usize,
}

fn panels(model: &Model) -> Result<Panels, PictureError> {
    if model.interfaces.is_empty() {
        return Err(PictureError::Empty("the model has no contact interface to plot".into()));
    }
    if model.analysis != Analysis::Solid {
        return Ok(Panels { list: (0..model.interfaces.len()).map(|ii| (ii, None)).collect(), left_out: 0 });
    }
    let mut all = plan_files(model);
    let left_out = all.len().saturating_sub(MOST_PANELS);
    all.truncate(MOST_PANELS);
    Ok(Panels { list: all.into_iter().map(|p| (p.interface, Some(p))).collect(), left_out })
}

fn size(p: &Panels) -> (u32, u32) {
    (1000, 420 * p.list.len().max(1) as u32 + if p.left_out > 0 { 40 } else { 0 })
}

/// What a robust range leaves out, for the caption: "; beyond the scale:
/// down to -2337" (empty when nothing is).
fn beyond(r: &super::legend::Robust) -> String {
    let mut parts = Vec::new();
    if r.min < r.lo {
        parts.push(format!("down to {}", super::label_numbers::num(r.min)));
    }
    if r.max > r.hi {
        parts.push(format!("up to {}", super::label_numbers::num(r.max)));
    }
    if parts.is_empty() {
        String::new()
    } else {
        format!("; beyond the scale (on its edge): {}", parts.join(", "))
    }
}

fn plot_err(e: &dyn std::fmt::Debug) -> PictureError {
    PictureError::Plot(crate::output::plot::PlotError::of(e))
}

fn interface_plot_on<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    model: &Model,
    contact: &ContactRun,
    panels: &Panels,
) -> Result<(), PictureError> {
    register_font();
    root.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let n = panels.list.len();
    let (plots, note) =
        if panels.left_out > 0 { root.split_vertically(420 * n as u32) } else { (root.clone(), root.clone()) };
    for ((ii, plan), area) in panels.list.iter().zip(plots.split_evenly((n, 1)).iter()) {
        interface_panel(area, model, contact, *ii, plan.as_ref())?;
    }
    if panels.left_out > 0 {
        let text = format!(
            "{} more surfaces are not plotted here: joints.png shows every one by state, and each has its plan view.",
            panels.left_out
        );
        note.draw_text(&text, &("sans-serif", 15).into_font().color(&BLACK), (20, 12)).map_err(|e| plot_err(&e))?;
    }
    root.present().map_err(|e| plot_err(&e))
}

/// One panel's data: the pairs in order along the interface, how many are
/// in each state, and the frame the stresses are drawn in.
struct PanelData<'a> {
    c: &'a ContactRun,
    al: Along,
    solid: bool,
    /// Water in the joint: -u is drawn beside sigma_n' (they add up to the total).
    wet: bool,
    /// Pairs open, slipping, sticking (by state code).
    counts: [usize; 3],
    x: (f64, f64),
    y: (f64, f64),
    /// What the robust range leaves out, for the caption.
    beyond: String,
}

impl<'a> PanelData<'a> {
    fn new(model: &Model, c: &'a ContactRun, ii: usize, plan: Option<&PlanFile>) -> PanelData<'a> {
        let solid = model.analysis == Analysis::Solid;
        let al = match plan {
            Some(p) => Along::of_sheet(model, &p.sheet, c),
            None => along(model, ii),
        };
        let mut d =
            PanelData { c, al, solid, wet: false, counts: [0; 3], x: (0.0, 1.0), y: (0.0, 1.0), beyond: String::new() };
        let wet = d.all().any(|&(p, _)| c.water_pressure(p) > 0.0);
        let mut counts = [0usize; 3];
        for &(p, _) in d.all() {
            counts[c.states[p].code() as usize] += 1;
        }
        (d.wet, d.counts) = (wet, counts);
        let smin = d.all().map(|q| q.1).fold(f64::INFINITY, f64::min);
        let smax = d.all().map(|q| q.1).fold(f64::NEG_INFINITY, f64::max);
        let (smin, smax) = if smin <= smax { (smin, smax) } else { (0.0, 1.0) };
        let span = (smax - smin).max(1e-300);
        // a robust range: a singular corner does not set the scale; its
        // points sit on the frame's edge, and the caption says how far they go
        let values: Vec<f64> = d
            .all()
            .flat_map(|&(p, _)| [d.raw_sn(p), d.raw_tau(p), d.raw_minus_u(p)])
            .filter(|v| v.is_finite())
            .collect();
        let range = super::legend::robust(values);
        let (ylo, yhi) = (range.lo.min(0.0), range.hi.max(0.0));
        let pad = 0.08 * (yhi - ylo).max(1e-30);
        d.y = (ylo - pad, yhi + pad);
        d.beyond = beyond(&range);
        d.x = (smin - 0.02 * span, smax + 0.02 * span);
        d
    }

    fn all(&self) -> impl Iterator<Item = &(usize, f64)> + Clone {
        self.al.runs.iter().flatten()
    }

    fn raw_sn(&self, p: usize) -> f64 {
        self.c.pairs[p].sigma_n
    }

    /// In 2D the shear keeps its sign (along the tangent t).
    fn raw_tau(&self, p: usize) -> f64 {
        if self.solid {
            self.c.pairs[p].tau()
        } else {
            self.c.pairs[p].tau_t
        }
    }

    fn raw_minus_u(&self, p: usize) -> f64 {
        -self.c.water_pressure(p)
    }

    /// sigma_n on the frame (clamped to its edge).
    fn sn(&self, p: usize) -> f64 {
        self.raw_sn(p).clamp(self.y.0, self.y.1)
    }

    fn tau(&self, p: usize) -> f64 {
        self.raw_tau(p).clamp(self.y.0, self.y.1)
    }

    fn minus_u(&self, p: usize) -> f64 {
        self.raw_minus_u(p).clamp(self.y.0, self.y.1)
    }

    fn sn_label(&self) -> &'static str {
        if self.wet {
            "σn' (effective, tension > 0)"
        } else {
            "σn (normal, tension > 0)"
        }
    }

    fn colour(&self, p: usize) -> RGBColor {
        rgb(state_colour(self.c.states[p]))
    }
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

const BLUE: RGBColor = RGBColor(31, 90, 180);
const PURPLE: RGBColor = RGBColor(150, 60, 170);
const CYAN: RGBColor = RGBColor(0, 160, 190);

/// One interface's panel: the frame, the state bands (2D), the stresses,
/// the legend.
fn interface_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    model: &Model,
    c: &ContactRun,
    ii: usize,
    plan: Option<&PlanFile>,
) -> Result<(), PictureError> {
    let d = PanelData::new(model, c, ii, plan);
    let mut chart = frame(area, model, &d, ii, plan)?;
    if !d.solid {
        draw_state_bands(&mut chart, &d)?;
    }
    chart.draw_series(LineSeries::new(vec![(d.x.0, 0.0), (d.x.1, 0.0)], BLACK.mix(0.5))).map_err(|e| plot_err(&e))?;
    if d.solid {
        draw_markers(&mut chart, &d)?;
    } else {
        draw_lines(&mut chart, &d)?;
    }
    draw_state_keys(&mut chart, &d)?;
    let place = legend_corner(&d, area.dim_in_pixel().1 as f64);
    chart
        .configure_series_labels()
        .position(place)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", 14))
        .draw()
        .map_err(|e| plot_err(&e))?;
    Ok(())
}

/// The panel's chart: caption (interface, sides, pairs by state), axes.
fn frame<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    model: &Model,
    d: &PanelData,
    ii: usize,
    plan: Option<&PlanFile>,
) -> Result<Chart<'a, DB>, PictureError> {
    let pairs: Vec<usize> = d.all().map(|q| q.0).collect();
    let [bi, bii] = sides(model, &pairs);
    let which = match plan {
        Some(p) if p.of > 1 => format!(" {} of {}, {}", p.index + 1, p.of, p.sheet.short(model)),
        _ => String::new(),
    };
    let counts = d.counts;
    let caption = format!(
        "{}{which}: {} | {}, {} pairs: {} stick, {} slip, {} open{}",
        model.interfaces[ii].name,
        bi.0,
        bii.0,
        counts.iter().sum::<usize>(),
        counts[2],
        counts[1],
        counts[0],
        d.beyond
    );
    let axis = match plan {
        Some(p) if d.al.left >= 0.25 => format!("{}; σn and τ also vary across it: see {}", d.al.axis, p.file),
        _ => d.al.axis.clone(),
    };
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(14)
        .x_label_area_size(46)
        .y_label_area_size(78)
        .build_cartesian_2d(d.x.0..d.x.1, d.y.0..d.y.1)
        .map_err(|e| plot_err(&e))?;
    chart
        .configure_mesh()
        .x_desc(axis.as_str())
        .y_desc("contact stress")
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(|e| plot_err(&e))?;
    Ok(chart)
}

/// 2D: each pair's state over the half-way points to its neighbours.
fn draw_state_bands<DB: DrawingBackend>(chart: &mut Chart<DB>, d: &PanelData) -> Result<(), PictureError> {
    let (ylo, yhi) = d.y;
    let mut bands = Vec::new();
    for r in &d.al.runs {
        for (i, &(p, s)) in r.iter().enumerate() {
            let a = if i == 0 { s } else { 0.5 * (s + r[i - 1].1) };
            let b = if i + 1 == r.len() { s } else { 0.5 * (s + r[i + 1].1) };
            bands.push(Rectangle::new([(a, ylo), (b, yhi)], d.colour(p).mix(0.22).filled()));
        }
    }
    chart.draw_series(bands).map_err(|e| plot_err(&e))?;
    Ok(())
}

/// 3D: markers coloured by state (circles sigma_n, triangles |tau|,
/// crosses -u).
fn draw_markers<DB: DrawingBackend>(chart: &mut Chart<DB>, d: &PanelData) -> Result<(), PictureError> {
    let dots = d.all().map(|&(p, s)| Circle::new((s, d.sn(p)), 4, d.colour(p).filled()));
    chart
        .draw_series(dots)
        .map_err(|e| plot_err(&e))?
        .label(d.sn_label())
        .legend(|(x, y)| Circle::new((x + 9, y), 4, BLACK.filled()));
    let tris = d.all().map(|&(p, s)| TriangleMarker::new((s, d.tau(p)), 5, d.colour(p).stroke_width(2)));
    chart
        .draw_series(tris)
        .map_err(|e| plot_err(&e))?
        .label("τ (shear, magnitude)")
        .legend(|(x, y)| TriangleMarker::new((x + 9, y), 5, BLACK.stroke_width(2)));
    if d.wet {
        let marks = d.all().map(|&(p, s)| Cross::new((s, d.minus_u(p)), 4, CYAN.stroke_width(2)));
        chart
            .draw_series(marks)
            .map_err(|e| plot_err(&e))?
            .label("-u (water pressure)")
            .legend(move |(x, y)| Cross::new((x + 9, y), 4, CYAN.stroke_width(2)));
    }
    Ok(())
}

/// 2D: one line per run for sigma_n, tau and -u.
fn draw_lines<DB: DrawingBackend>(chart: &mut Chart<DB>, d: &PanelData) -> Result<(), PictureError> {
    for (i, r) in d.al.runs.iter().enumerate() {
        let pts: Vec<(f64, f64)> = r.iter().map(|&(p, s)| (s, d.sn(p))).collect();
        let a = chart.draw_series(LineSeries::new(pts.clone(), BLUE.stroke_width(2))).map_err(|e| plot_err(&e))?;
        if i == 0 {
            a.label(d.sn_label())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLUE.stroke_width(2)));
        }
        chart.draw_series(pts.iter().map(|&q| Circle::new(q, 3, BLUE.filled()))).map_err(|e| plot_err(&e))?;
        let pts: Vec<(f64, f64)> = r.iter().map(|&(p, s)| (s, d.tau(p))).collect();
        let a = chart.draw_series(LineSeries::new(pts.clone(), PURPLE.stroke_width(2))).map_err(|e| plot_err(&e))?;
        if i == 0 {
            a.label("τ (shear, along the tangent)")
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], PURPLE.stroke_width(2)));
        }
        chart.draw_series(pts.iter().map(|&q| TriangleMarker::new(q, 4, PURPLE.filled()))).map_err(|e| plot_err(&e))?;
        if d.wet {
            let pts: Vec<(f64, f64)> = r.iter().map(|&(p, s)| (s, d.minus_u(p))).collect();
            let a = chart.draw_series(LineSeries::new(pts, CYAN.stroke_width(2))).map_err(|e| plot_err(&e))?;
            if i == 0 {
                a.label("-u (water pressure)")
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], CYAN.stroke_width(2)));
            }
        }
    }
    Ok(())
}

/// Legend entries for the states present (no series of their own).
fn draw_state_keys<DB: DrawingBackend>(chart: &mut Chart<DB>, d: &PanelData) -> Result<(), PictureError> {
    let counts = d.counts;
    for (s, count) in
        [(ContactState::Stick, counts[2]), (ContactState::Slip, counts[1]), (ContactState::Open, counts[0])]
    {
        if count > 0 {
            let col = rgb(state_colour(s));
            let style = if d.solid { col.filled() } else { col.mix(0.35).filled() };
            chart
                .draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())
                .map_err(|e| plot_err(&e))?
                .label(s.name())
                .legend(move |(x, y)| Rectangle::new([(x + 2, y - 6), (x + 16, y + 6)], style));
        }
    }
    Ok(())
}

/// The legend goes in the corner with the fewest points under it
/// (`height`: the panel's height in pixels).
fn legend_corner(d: &PanelData, height: f64) -> SeriesLabelPosition {
    let (xlo, xhi) = d.x;
    let (ylo, yhi) = d.y;
    let entries = 2 + usize::from(d.wet) + d.counts.iter().filter(|&&c| c > 0).count();
    let (lw, lh) = (0.34, (entries as f64 * 22.0 + 12.0) / (height - 90.0));
    let under = |fx: f64, fy: f64| {
        let (bx, by) = (fx * (1.0 - lw), fy * (1.0 - lh));
        d.all()
            .flat_map(|&(p, s)| [(s, d.sn(p)), (s, d.tau(p))])
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
    corners.into_iter().min_by_key(|&(_, fx, fy)| under(fx, fy)).map(|c| c.0).unwrap_or(SeriesLabelPosition::UpperRight)
}
