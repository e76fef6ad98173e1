//! The supports' reactions and every body's balance in summary.json
//! (`reactions`) and report.md ("Reactions and balance"), from
//! [`crate::recover::reactions`].

use std::fmt::Write;

use super::number::{clean, num};
use crate::results::Run;

/// summary.json's `reactions` (None without supports).
pub fn summary(run: &Run) -> Option<serde_json::Value> {
    run.checks.reactions.as_ref().and_then(|r| serde_json::to_value(r).ok())
}

/// A vector in the analysis's components, `(x, y)` or `(x, y, z)`, with
/// round-off beside `scale` shown as 0.
pub(super) fn vector(v: [f64; 3], dim: usize, scale: f64) -> String {
    format!("({})", v[..dim].iter().map(|&x| num(clean(x, scale))).collect::<Vec<_>>().join(", "))
}

/// A moment: its z component in 2D, the vector in 3D.
pub(super) fn moment(m: [f64; 3], dim: usize, scale: f64) -> String {
    if dim == 2 {
        num(clean(m[2], scale))
    } else {
        vector(m, 3, scale)
    }
}

/// The largest component of the vectors.
fn largest<'a>(vs: impl Iterator<Item = &'a [f64; 3]>) -> f64 {
    vs.flat_map(|v| v.iter()).fold(0.0, |a: f64, &b| a.max(b.abs()))
}

/// report.md's section (empty without supports).
pub fn report(run: &Run) -> String {
    let Some(r) = &run.checks.reactions else { return String::new() };
    let dim = run.about.analysis.dim();
    let mut s = String::from("\n## Reactions and balance\n\n");
    let about = if dim == 2 { "its moment (counterclockwise positive)" } else { "its moment" };
    let _ = writeln!(
        s,
        "The force each support applies to the model (global axes; totals over the thickness in a plane analysis) and {about} about the centroid of the nodes it holds{}.\n",
        if run.steps.len() > 1 { ", at the last load step" } else { "" }
    );
    let _ = writeln!(s, "| support | DOFs held | force | moment | about |\n|---|---|---|---|---|");
    let size = run.model.coords.iter().flat_map(|x| x.iter()).fold(0.0, |a: f64, &b| a.max(b.abs()));
    let forces = largest(r.supports.iter().map(|sp| &sp.force).chain(r.bodies.iter().map(|b| &b.applied)));
    let moments = largest(r.supports.iter().map(|sp| &sp.moment));
    for sp in &r.supports {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} |",
            sp.group,
            sp.dofs,
            vector(sp.force, dim, forces),
            moment(sp.moment, dim, moments.max(forces * size)),
            vector(sp.about, dim, size)
        );
    }
    let _ = writeln!(
        s,
        "\nEach body's balance: the loads on it (weight, loads), the contact forces on it and the supports' reactions on it, which add up to zero.\n"
    );
    let _ = writeln!(s, "| body | loads | contacts | supports | remainder |\n|---|---|---|---|---|");
    for b in &r.bodies {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} |",
            b.group,
            vector(b.applied, dim, forces),
            vector(b.contact, dim, forces),
            vector(b.supports, dim, forces),
            vector(b.remainder, dim, 0.0)
        );
    }
    let _ = writeln!(
        s,
        "\nAt the free DOFs of the supported nodes the nodal forces balance to {:.1e} of the largest force there.",
        r.free_residual
    );
    s
}
