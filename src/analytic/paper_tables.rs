//! The paper's Tables 1 and 2 for Lamé's cylinder (DESIGN.md §3), the check
//! of `[analytic] kind = "lame_cylinder"`: the stresses along a radius at the
//! paper's radii (Table 1, from the probes) and the contact normal stress on
//! the 45-degree cut (Table 2, interpolated between the pairs), theory
//! against each run, and for the paper's own cylinder (a = 3, b = 5, p = 0.1)
//! the paper's numbers beside them. `subcontact paper` prints them for the
//! paper's mesh and the default one side by side. Numbers only:
//! `output::closed_form` writes the tables.

use super::lame::Lame;
use super::solution::Solution;
use crate::fem::Analysis;
use crate::model::Model;

/// The paper's Table 1 (r, sigma_r, sigma_theta; units 1e-2 MPa) and Table 2
/// (r, contact sigma_n), theory and the paper's numerical values (DESIGN.md §3).
pub const TABLE1_R: [f64; 5] = [3.2, 3.6, 4.0, 4.4, 4.8];
pub const TABLE1_SR_PAPER: [f64; 5] = [-8.00, -5.13, -3.10, -1.59, -0.40];
pub const TABLE1_ST_PAPER: [f64; 5] = [19.28, 16.40, 14.46, 12.90, 11.65];
pub const TABLE2_R: [f64; 6] = [3.0, 3.4, 3.8, 4.2, 4.6, 5.0];
pub const TABLE2_PAPER: [f64; 6] = [21.02, 17.53, 15.14, 13.40, 12.10, 10.55];

/// Polar (sigma_r, sigma_theta) of a stress about the z axis (plane, solid)
/// or of an axisymmetric stress.
pub fn polar(analysis: Analysis, x: [f64; 3], s: &[f64; 6]) -> (f64, f64) {
    if analysis == Analysis::Axisymmetric {
        return (s[0], s[2]);
    }
    let r = x[0].hypot(x[1]);
    let (c, sn) = (x[0] / r, x[1] / r);
    (s[0] * c * c + s[1] * sn * sn + 2.0 * s[3] * sn * c, s[0] * sn * sn + s[1] * c * c - 2.0 * s[3] * sn * c)
}

/// Contact sigma_n at radius r, interpolated linearly between the pairs
/// (None without contact, or off the pairs' span).
pub fn contact_sigma_n_at(sol: &Solution, r: f64) -> Option<f64> {
    let pairs = sol.pairs?;
    let mut pts: Vec<(f64, f64)> = sol
        .model
        .pairs
        .iter()
        .zip(pairs)
        .map(|(p, res)| {
            let x = sol.model.coords[p.k];
            (x[0].hypot(x[1]), res.sigma_n)
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    // several pairs at one radius (3D: through the thickness) are averaged
    let mut merged: Vec<(f64, f64, f64)> = Vec::new();
    for (rr, s) in pts {
        match merged.last_mut() {
            Some(m) if (m.0 - rr).abs() < 1e-9 * rr.abs().max(1.0) => {
                m.1 += s;
                m.2 += 1.0;
            }
            _ => merged.push((rr, s, 1.0)),
        }
    }
    let pts: Vec<(f64, f64)> = merged.into_iter().map(|(r, s, n)| (r, s / n)).collect();
    let tol = 1e-9 * r.abs().max(1.0);
    let i = pts.iter().position(|p| p.0 >= r - tol)?;
    if (pts[i].0 - r).abs() <= tol {
        return Some(pts[i].1);
    }
    if i == 0 {
        return None;
    }
    let (a, b) = (pts[i - 1], pts[i]);
    Some(a.1 + (b.1 - a.1) * (r - a.0) / (b.0 - a.0))
}

/// Stresses at the Table 1 radii from the first probe point there: (sigma_r, sigma_theta).
pub fn table1_values(sol: &Solution) -> Vec<Option<(f64, f64)>> {
    TABLE1_R
        .iter()
        .map(|&r| {
            sol.probed
                .iter()
                .find(|(x, _)| (x[0].hypot(x[1]) - r).abs() < 1e-6 * r)
                .map(|(x, s)| polar(sol.model.analysis, *x, s))
        })
        .collect()
}

/// One run's values for the paper's tables: (sigma_r, sigma_theta) at the
/// Table 1 radii, and the contact sigma_n at the Table 2 radii (None
/// without contact); None where the run has no value at a radius.
#[derive(Clone, Debug, PartialEq)]
pub struct Tables {
    pub table1: Vec<Option<(f64, f64)>>,
    pub table2: Option<Vec<Option<f64>>>,
}

/// The values of one run for both tables.
pub fn tables(sol: &Solution) -> Tables {
    let table2 = sol.pairs.map(|_| TABLE2_R.iter().map(|&r| contact_sigma_n_at(sol, r)).collect());
    Tables { table1: table1_values(sol), table2 }
}

/// Whether `l` is the paper's cylinder (a = 3, b = 5, p = 0.1), whose
/// tables get the paper's own values beside this run's.
pub fn is_paper_cylinder(l: &Lame) -> bool {
    l.a == 3.0 && l.b == 5.0 && (l.p - 0.1).abs() < 1e-12
}

/// The check of Lamé's cylinder: the cylinder, this run's tables, whether
/// the paper's values go beside them ([`is_paper_cylinder`]) and whether
/// the bodies' materials differ (see [`fn@super::exact`]).
#[derive(Clone, Debug)]
pub struct CylinderCheck {
    pub lame: Lame,
    pub tables: Tables,
    pub with_paper: bool,
    pub materials_differ: bool,
}

/// The tables of one run, for report.md.
pub(super) fn check(lame: Lame, sol: &Solution) -> CylinderCheck {
    let with_paper = is_paper_cylinder(&lame);
    CylinderCheck { lame, tables: tables(sol), with_paper, materials_differ: materials_differ(sol.model) }
}

/// Whether the bodies of a model have different elastic constants (E, nu).
pub fn materials_differ(model: &Model) -> bool {
    model.bodies.windows(2).any(|w| w[0].material.e != w[1].material.e || w[0].material.nu != w[1].material.nu)
}
