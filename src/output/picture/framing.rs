//! What the deformed picture frames: a box that the model is cut to
//! ([`Cut`]). By default the structure: the bodies at least [`STIFFER`]
//! times stiffer than the softest body (a lining in rock, a beam or footing
//! on soil), their box grown by half its size on every side, when that is
//! less than half the model's size; else the box of the contacts grown so
//! (the joints around a bare opening); else the whole model. A tunnel
//! lining in jointed rock is framed on the lining, not on the joints that
//! fill the box. The scene may name a box or bodies instead (`[output]
//! frame`, [`Region`]).

use super::cutaway::Cut;
use super::label_numbers::num;
use crate::model::Model;
use crate::results::about::Region;

/// The box the picture is cut to (None: the whole model) and what the
/// picture says about it.
pub(super) struct Focus {
    pub(super) cut: Option<Cut>,
    pub(super) note: Option<String>,
}

/// How much the contacts' box grows on every side, as a fraction of its
/// largest extent, and how small the grown box must be against the
/// model's largest extent to be framed instead of the whole model.
const MARGIN: f64 = 0.5;
const SMALLER_THAN: f64 = 0.5;

/// How much stiffer than the softest body a body must be to be the
/// structure the picture frames.
const STIFFER: f64 = 10.0;

/// The box the deformed picture is cut to (see the module header).
pub(super) fn focus(model: &Model, region: Option<&Region>) -> Focus {
    let dim = if model.analysis == crate::fem::Analysis::Solid { 3 } else { 2 };
    let whole = || Focus { cut: None, note: None };
    let (lo, hi) = super::view::model_box(model);
    let size = (0..dim).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let (bx, why) = match region {
        Some(Region::Box { from, to }) => ((*from, *to), "[output] frame".to_string()),
        Some(Region::Bodies(names)) => {
            let ids: Vec<usize> = names.iter().filter_map(|n| model.bodies.iter().position(|b| &b.name == n)).collect();
            let Some(b) = node_box(
                model,
                ids.iter().flat_map(|&b| model.bodies[b].cells.iter().flat_map(|c| c.nodes.iter().copied())),
            ) else {
                return whole();
            };
            let names: Vec<String> = ids.iter().map(|&b| format!("\"{}\"", model.bodies[b].name)).collect();
            (grow(b, 0.25, dim), format!("{} ([output] frame)", names.join(", ")))
        }
        None => {
            let small = |b: ([f64; 3], [f64; 3])| {
                let grown = grow(b, MARGIN, dim);
                let clipped: Vec<f64> = (0..dim).map(|d| grown.1[d].min(hi[d]) - grown.0[d].max(lo[d])).collect();
                (clipped.iter().copied().fold(0.0, f64::max) < SMALLER_THAN * size && size > 0.0).then_some(grown)
            };
            let structure = structure(model);
            let structure_box = node_box(model, structure.iter().flat_map(|&b| body_nodes(model, b)));
            let contacts = node_box(
                model,
                model.interfaces.iter().flat_map(|i| i.facets.iter().flat_map(|f| f.nodes.iter().copied())),
            );
            if let Some(grown) = structure_box.and_then(small) {
                let mut names: Vec<String> =
                    structure.iter().map(|&b| format!("\"{}\"", model.bodies[b].name)).collect();
                names.dedup();
                (grown, format!("the structure {} ([output] frame chooses another region)", names.join(", ")))
            } else if let Some(grown) = contacts.and_then(small) {
                (grown, "the contacts ([output] frame chooses another region)".to_string())
            } else {
                return whole();
            }
        }
    };
    // the box within the model's: a side beyond the model cuts nothing
    let bx: ([f64; 3], [f64; 3]) =
        (std::array::from_fn(|d| bx.0[d].max(lo[d])), std::array::from_fn(|d| bx.1[d].min(hi[d])));
    if (0..dim).any(|d| bx.0[d] >= bx.1[d]) {
        return Focus { cut: None, note: Some(format!("{why} lies outside the model: the whole model is drawn")) };
    }
    if (0..dim).all(|d| bx.0[d] <= lo[d] && bx.1[d] >= hi[d]) {
        return whole();
    }
    // round-off (a box that starts at 0 computed as -1e-15) reads as 0
    let tidy = |v: f64| num(if v.abs() < 1e-9 * size { 0.0 } else { v });
    let range: Vec<String> =
        (0..dim).map(|d| format!("{} {} .. {}", ["x", "y", "z"][d], tidy(bx.0[d]), tidy(bx.1[d]))).collect();
    Focus {
        cut: Some(Cut { lo: bx.0, hi: bx.1, dim }),
        note: Some(format!("Framed on {why}: cut to {}.", range.join(", "))),
    }
}

/// The bodies at least [`STIFFER`] times stiffer than the softest (none
/// when all are alike).
fn structure(model: &Model) -> Vec<usize> {
    let soft = model.bodies.iter().map(|b| b.material.e).fold(f64::INFINITY, f64::min);
    (0..model.bodies.len()).filter(|&b| model.bodies[b].material.e >= STIFFER * soft).collect()
}

fn body_nodes(model: &Model, b: usize) -> impl Iterator<Item = usize> + '_ {
    model.bodies[b].cells.iter().flat_map(|c| c.nodes.iter().copied())
}

/// The box of some nodes (None without any).
fn node_box(model: &Model, nodes: impl Iterator<Item = usize>) -> Option<([f64; 3], [f64; 3])> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for k in nodes {
        for d in 0..3 {
            lo[d] = lo[d].min(model.coords[k][d]);
            hi[d] = hi[d].max(model.coords[k][d]);
        }
    }
    (lo[0] <= hi[0]).then_some((lo, hi))
}

/// A box grown on every side by `f` times its largest extent (in the
/// model's `dim` directions).
fn grow(b: ([f64; 3], [f64; 3]), f: f64, dim: usize) -> ([f64; 3], [f64; 3]) {
    let m = f * (0..dim).map(|d| b.1[d] - b.0[d]).fold(0.0, f64::max);
    (std::array::from_fn(|d| b.0[d] - m), std::array::from_fn(|d| b.1[d] + m))
}
