//! The load–settlement picture, `settlement.svg` (probes and more than one
//! load step): each probe's vertical displacement (2D and axisymmetric uy,
//! 3D uz) against the load factor, one curve per probe, from the same
//! samples as `probes_history.csv`. A probe of several points is drawn at
//! the point that moves most at the last step (named in the legend). The
//! load factor is the one of [`crate::results::About::step_times`]: the factor of the one
//! load that grows at every step, else the ramp k / load_steps.

use super::number::num;
use super::picture::PictureError;
use super::plot::{self, Panel, Series};
use crate::recover::Sample;
use crate::results::Run;

/// The picture's file name.
pub const FILE: &str = "settlement.svg";

/// Width and height of the picture in pixels.
pub const SIZE: (u32, u32) = (640, 420);

/// The probes sampled at every load step: (step, load factor of
/// probes_history.csv, each probe's name and samples).
pub type History = Vec<(usize, f64, Vec<(String, Vec<Sample>)>)>;

/// Every probe at every load step.
pub fn history(run: &Run) -> History {
    (run.steps.iter())
        .map(|step| {
            let probes = (run.about.probes.iter())
                .map(|p| (p.name.clone(), crate::recover::probe(&run.model, &step.u, p)))
                .collect();
            (step.step, step.load_factor, probes)
        })
        .collect()
}

/// The curves: one per probe, the vertical displacement (component `c`)
/// of the point of the probe that moves most at the last step, against
/// `factors` (one per step of `history`).
pub fn curves(history: &History, factors: &[f64], c: usize) -> Vec<Series> {
    let Some((_, _, last)) = history.last() else { return Vec::new() };
    last.iter()
        .enumerate()
        .filter_map(|(k, (name, samples))| {
            let moved = |s: &Sample| if s.found { s.displacement[c].abs() } else { -1.0 };
            let (i, at) = samples.iter().enumerate().max_by(|a, b| moved(a.1).total_cmp(&moved(b.1)))?;
            let label = if samples.len() > 1 {
                let x: Vec<String> = at.x[..c.max(1) + 1].iter().map(|&v| num(v)).collect();
                format!("{name} (point {i} at {})", x.join(", "))
            } else {
                name.clone()
            };
            let points = (history.iter().zip(factors))
                .filter_map(|((_, _, probes), &f)| Some((f, probes.get(k)?.1.get(i)?.displacement[c])))
                .collect();
            Some(Series { label, points })
        })
        .collect()
}

/// The picture of a run with probes and more than one load step.
pub fn svg(run: &Run, history: &History) -> Result<Vec<u8>, PictureError> {
    let c = if run.about.analysis.dim() == 3 { 2 } else { 1 };
    let times = &run.about.step_times;
    let factors: Vec<f64> = history.iter().map(|h| times.get(h.0.wrapping_sub(1)).copied().unwrap_or(h.1)).collect();
    let series = curves(history, &factors, c);
    if series.iter().all(|s| s.points.is_empty()) {
        return Err(PictureError::Empty("no probe has a point in the model".into()));
    }
    draw(&run.about.title, if c == 2 { "uz" } else { "uy" }, &series)
}

/// The SVG of `series` (vertical displacement `comp` against load factor).
pub fn draw(title: &str, comp: &str, series: &[Series]) -> Result<Vec<u8>, PictureError> {
    let title = format!("{title}: load against displacement");
    let y = format!("{comp} (vertical displacement, up +)");
    let panel = Panel { title: &title, x_label: "load factor", y_label: &y, log_x: false, log_y: false, series };
    Ok(plot::svg(&[panel], SIZE.0, SIZE.1)?.into_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(uy: f64) -> Sample {
        Sample { x: [1.0, 2.0, 0.0], displacement: [0.0, uy, 0.0], stress: [0.0; 6], von_mises: 0.0, found: true }
    }

    /// Two probes over three steps: two curves, each at the point that
    /// moves most, with the factors given.
    #[test]
    fn one_curve_per_probe_at_the_point_that_moves_most() {
        let h: History = (1..=3)
            .map(|k| {
                let f = k as f64 / 3.0;
                (k, f, vec![("a".into(), vec![sample(-f), sample(-2.0 * f)]), ("b".into(), vec![sample(0.5 * f)])])
            })
            .collect();
        let s = curves(&h, &[0.1, 0.2, 0.3], 1);
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].points, vec![(0.1, -2.0 / 3.0), (0.2, -4.0 / 3.0), (0.3, -2.0)]);
        assert!(s[0].label.starts_with("a (point 1 at 1, 2"), "{}", s[0].label);
        assert_eq!((s[1].label.as_str(), s[1].points.len()), ("b", 3));
        let svg = String::from_utf8(draw("t", "uy", &s).expect("drawn")).expect("utf8");
        assert!(svg.contains("width=\"640\"") && svg.contains("height=\"420\""));
    }

    /// One step with no displacement: drawn or refused, never a panic.
    #[test]
    fn one_step_without_displacement_does_not_panic() {
        let h: History = vec![(1, 1.0, vec![("a".into(), vec![sample(0.0)])])];
        let s = curves(&h, &[1.0], 1);
        assert_eq!(s[0].points, vec![(1.0, 0.0)]);
        let mut d = crate::output::picture::Drawn::default();
        d.draw(FILE, || draw("t", "uy", &s));
        assert_eq!(d.files.len() + d.skipped.len(), 1);
    }
}
