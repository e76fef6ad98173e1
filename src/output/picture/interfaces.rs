//! The interface plot (SVG): one panel per contact interface, the normal
//! stress sigma_n (tension positive) and the shear stress tau against the
//! position along the interface, the contact state as background bands (2D)
//! or marker colours (3D). plotters draws it, in the embedded font.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::raster::{register_font, rgb};
use super::{dot, num, state_colour, sub3};
use crate::contact::law::ContactState;
use crate::model::Model;
use crate::results::ContactRun;
use crate::fem::Analysis;
#[cfg(test)]
use super::raster::encode_png;

/// The pairs of one interface in order along it.
pub(super) struct Along {
    /// Runs of pairs (pair index, position s); lines are drawn within a run.
    pub(super) runs: Vec<Vec<(usize, f64)>>,
    /// What s measures, for the axis.
    pub(super) axis: String,
}

/// Orders an interface's pairs: in 2D by walking its chain of facets from
/// the end nearest the model's lower-left corner (arc length), else by the
/// position along the direction in which the pairs spread most.
pub(super) fn along(model: &Model, ii: usize) -> Along {
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
        // links between consecutive nodes of each facet (corner, mid, corner),
        // in node order: of two ends equally near the corner, the first node
        // starts the walk, the same in every run
        let mut links: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
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
pub fn interface_plot_svg(model: &Model, contact: &ContactRun) -> Result<String, String> {
    let (w, h) = interface_plot_size(model)?;
    let mut out = String::new();
    interface_plot_on(SVGBackend::with_string(&mut out, (w, h)).into_drawing_area(), model, contact)?;
    Ok(out)
}

/// The same plot as [`interface_plot_svg`], as a PNG, to look at in tests
/// (plotters' bitmap text spaces letters unevenly, see `raster::Canvas::text`).
#[cfg(test)]
pub(super) fn interface_plot_png(model: &Model, contact: &ContactRun) -> Result<Vec<u8>, String> {
    let (w, h) = interface_plot_size(model)?;
    let mut buf = vec![255u8; w as usize * h as usize * 3];
    interface_plot_on(BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area(), model, contact)?;
    encode_png(w as usize, h as usize, &buf)
}

fn interface_plot_size(model: &Model) -> Result<(u32, u32), String> {
    if model.interfaces.is_empty() {
        return Err("the model has no contact interface to plot".into());
    }
    Ok((1000, 420 * model.interfaces.len() as u32))
}

fn interface_plot_on<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, model: &Model, contact: &ContactRun) -> Result<(), String> {
    register_font();
    root.fill(&WHITE).map_err(|e| format!("{e:?}"))?;
    let n = model.interfaces.len();
    for (ii, area) in root.split_evenly((n, 1)).iter().enumerate() {
        interface_panel(area, model, contact, ii)?;
    }
    root.present().map_err(|e| format!("{e:?}"))
}

fn interface_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, model: &Model, c: &ContactRun, ii: usize) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Debug| format!("{e:?}");
    let iface = &model.interfaces[ii];
    let solid = model.analysis == Analysis::Solid;
    let al = along(model, ii);
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
