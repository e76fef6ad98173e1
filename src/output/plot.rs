//! Line plots drawn in Rust (plotters, SVG), with the DejaVu Sans font built
//! into the binary so no system font or external program is needed.

use plotters::prelude::*;

/// One line of a plot.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// A panel: title, axis labels, log scales, its lines.
pub struct Panel<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub log_x: bool,
    pub log_y: bool,
    pub series: &'a [Series],
}

const COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(23, 190, 207),
];

fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            include_bytes!("../../assets/DejaVuSans.ttf"),
        );
    });
}

fn range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let v: Vec<f64> = values.filter(|v| v.is_finite() && (!log || *v > 0.0)).collect();
    if v.is_empty() {
        return if log { (0.1, 10.0) } else { (0.0, 1.0) };
    }
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if log {
        (lo / 1.5, hi * 1.5)
    } else {
        let pad = 0.05 * (hi - lo).max(hi.abs().max(1e-300) * 1e-3);
        (lo - pad, hi + pad)
    }
}

/// Why plotters could not draw a plot: its error, as plotters describes it
/// (its error type is generic over the drawing backend).
#[derive(Debug, thiserror::Error)]
#[error("{detail}")]
pub struct PlotError {
    pub detail: String,
}

impl PlotError {
    /// The error of a plotters call.
    pub fn of(e: &dyn std::fmt::Debug) -> PlotError {
        PlotError { detail: format!("{e:?}") }
    }
}

fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, plotters::coord::Shift>, p: &Panel) -> Result<(), PlotError> {
    let all = || p.series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = range(all().map(|q| q.0), p.log_x);
    let (y0, y1) = range(all().map(|q| q.1), p.log_y);
    let mut b = ChartBuilder::on(area);
    b.caption(p.title, ("sans-serif", 18)).margin(12).x_label_area_size(42).y_label_area_size(70);
    let err = PlotError::of;
    macro_rules! lines {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(p.x_label)
                .y_desc(p.y_label)
                .label_style(("sans-serif", 12))
                .draw()
                .map_err(|e| err(&e))?;
            for (i, s) in p.series.iter().enumerate() {
                let c = COLOURS[i % COLOURS.len()];
                let pts: Vec<(f64, f64)> =
                    s.points.iter().copied().filter(|q| q.0.is_finite() && q.1.is_finite()).collect();
                chart
                    .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
                    .map_err(|e| err(&e))?
                    .label(s.label.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
                chart.draw_series(pts.iter().map(|&q| Circle::new(q, 3, c.filled()))).map_err(|e| err(&e))?;
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 12))
                .draw()
                .map_err(|e| err(&e))?;
        }};
    }
    match (p.log_x, p.log_y) {
        (true, true) => {
            lines!(b.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale()).map_err(|e| err(&e))?)
        }
        (true, false) => lines!(b.build_cartesian_2d((x0..x1).log_scale(), y0..y1).map_err(|e| err(&e))?),
        (false, true) => lines!(b.build_cartesian_2d(x0..x1, (y0..y1).log_scale()).map_err(|e| err(&e))?),
        (false, false) => lines!(b.build_cartesian_2d(x0..x1, y0..y1).map_err(|e| err(&e))?),
    }
    Ok(())
}

/// An SVG with the panels side by side.
pub fn svg(panels: &[Panel], width_each: u32, height: u32) -> Result<String, PlotError> {
    register_font();
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (width_each * panels.len() as u32, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| PlotError::of(&e))?;
        let areas = root.split_evenly((1, panels.len()));
        for (a, p) in areas.iter().zip(panels) {
            draw_panel(a, p)?;
        }
        root.present().map_err(|e| PlotError::of(&e))?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_has_the_lines_and_labels() {
        let s = [Series { label: "order 1".into(), points: vec![(0.1, 1e-2), (1.0, 1e-4)] }];
        let p = Panel {
            title: "error against time",
            x_label: "time (s)",
            y_label: "error",
            log_x: true,
            log_y: true,
            series: &s,
        };
        let svg = svg(&[p], 400, 300).expect("plot");
        assert!(svg.starts_with("<svg"));
        assert!(svg.contains("order 1") && svg.contains("error against time"));
        assert!(svg.contains("<polyline") || svg.contains("<path"));
    }
}
