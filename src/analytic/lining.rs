//! Thrust and bending moment of a tunnel lining from its finite element
//! stresses, and their comparison with Einstein & Schwartz's closed form
//! ([`super::LinedTunnel`]): the check of `[analytic] kind = "lined_tunnel"`
//! (numbers; `output::closed_form` writes them as a section of report.md
//! and the `lining` entry of summary.json).
//!
//! A lining is a ring-shaped body between radii ri and ro about the origin.
//! On the radial line at angle theta (from +x, the springline, towards +y)
//! the hoop stress sigma_tt is integrated through the thickness by
//! Gauss–Legendre in r:
//!
//! ```text
//! T(theta) = - ∫ sigma_tt dr                  thrust, compression positive
//! M(theta) =   ∫ sigma_tt (r - rm) dr         rm = (ri + ro)/2
//! ```
//!
//! both per unit length of tunnel. M is positive where the outer fibre is in
//! tension (the lining's curvature increases): the sign of the closed form.
//! The stresses are totals (initial stress included), evaluated directly in
//! the lining's elements at each point (averaged where it lies on an edge
//! shared by several).

use super::exact::Exact;
use super::solution::Solution;
use super::tunnel::LinedTunnel;
use crate::fem::element;
use crate::fem::material::{d_matrix, full_stress};
use crate::fem::{quadrature, shape};
use crate::model::Model;

/// Gauss points across the whole thickness (over several elements, whose
/// stresses jump slightly at their edges): 16 points change T and M by
/// less than 1e-4 of their largest values on the shipped tunnel scenes.
pub const THICKNESS_POINTS: usize = 8;

/// Angles of the report's table: every 7.5 degrees the lining covers.
pub const STEP_DEG: f64 = 7.5;

/// Thrust and moment at one angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Section {
    /// Radians from +x.
    pub theta: f64,
    pub thrust: f64,
    pub moment: f64,
    /// Displacement of the middle surface.
    pub displacement: [f64; 3],
}

/// Displacement and total stress `[xx, yy, zz, xy, yz, xz]` of body `body`
/// at x, averaged over its cells containing x; None outside the body.
fn sample_body(model: &Model, u: &[f64], body: usize, x: [f64; 3]) -> Option<([f64; 3], [f64; 6])> {
    let b = &model.bodies[body];
    let d = d_matrix(model.analysis, b.material.e, b.material.nu);
    let nd = model.nd;
    let mut sum = [0.0; 6];
    let mut disp = [0.0; 3];
    let mut hits = 0.0;
    for cell in &b.cells {
        let xe: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| model.coords[n]).collect();
        let inside_box = (0..2).all(|c| {
            let lo = xe.iter().map(|p| p[c]).fold(f64::INFINITY, f64::min);
            let hi = xe.iter().map(|p| p[c]).fold(f64::NEG_INFINITY, f64::max);
            let pad = 0.05 * (hi - lo);
            x[c] >= lo - pad && x[c] <= hi + pad
        });
        if !inside_box {
            continue;
        }
        let Some(xi) = shape::locate(cell.kind, &xe, x) else { continue };
        let Ok(p) = element::point(cell.kind, &xe, xi) else { continue };
        let ue: Vec<f64> = cell.nodes.iter().flat_map(|&n| (0..nd).map(move |c| u[n * nd + c])).collect();
        let mean = element::mean_dilatation(model.analysis, cell.kind, b.material.nu, &xe, &ue);
        let mut s = full_stress(
            model.analysis,
            b.material.e,
            b.material.nu,
            &d,
            &element::strain(model.analysis, &p, &ue, mean),
        );
        let s0 = b.initial_at(p.x, model.analysis, model.gravity);
        for c in 0..6 {
            s[c] += s0[c];
            sum[c] += s[c];
        }
        for c in 0..nd {
            disp[c] += (0..cell.kind.n_nodes()).map(|a| p.n[a] * ue[a * nd + c]).sum::<f64>();
        }
        hits += 1.0;
    }
    (hits > 0.0).then(|| (disp.map(|v| v / hits), sum.map(|v| v / hits)))
}

/// Thrust and moment of the ring `body` (radii ri..ro about the origin) at
/// each angle; None where the radial line leaves the body.
pub fn section_forces(model: &Model, u: &[f64], body: usize, ri: f64, ro: f64, thetas: &[f64]) -> Vec<Option<Section>> {
    let gl = quadrature::gauss_legendre(THICKNESS_POINTS);
    let (half, rm) = (0.5 * (ro - ri), 0.5 * (ri + ro));
    thetas
        .iter()
        .map(|&theta| {
            let (c, s) = (theta.cos(), theta.sin());
            let (mut thrust, mut moment) = (0.0, 0.0);
            let (displacement, _) = sample_body(model, u, body, [rm * c, rm * s, 0.0])?;
            for &(z, w) in &gl {
                let r = rm + half * z;
                let (_, st) = sample_body(model, u, body, [r * c, r * s, 0.0])?;
                let hoop = st[0] * s * s + st[1] * c * c - 2.0 * st[3] * s * c;
                thrust -= w * half * hoop;
                moment += w * half * hoop * (r - rm);
            }
            Some(Section { theta, thrust, moment, displacement })
        })
        .collect()
}

/// One row of the comparison.
#[derive(Clone, Copy, Debug)]
pub struct Row {
    pub theta_deg: f64,
    pub thrust: f64,
    pub thrust_theory: f64,
    pub moment: f64,
    pub moment_theory: f64,
    /// |u_FE - u| of the middle surface.
    pub displacement_error: f64,
    /// |u| of the middle surface in the closed form's field.
    pub displacement_theory: f64,
}

/// This run's lining against the closed form.
#[derive(Clone, Debug)]
pub struct Comparison {
    pub rows: Vec<Row>,
    /// max |T| and max |M| of the closed form over all angles: the error scales.
    pub thrust_scale: f64,
    pub moment_scale: f64,
    /// max |T_FE - T| / thrust_scale and max |M_FE - M| / moment_scale over the rows.
    pub thrust_error: f64,
    pub moment_error: f64,
    /// max |M_FE - M2 cos 2theta| / |M2|: against the published moment
    /// formula alone, without the ring's uniform moment M0.
    pub published_moment_error: f64,
    /// max |u_FE - u| / max |u| of the middle surface over the rows (u: the
    /// thin ring's motion in the closed form's field).
    pub displacement_error: f64,
}

/// The comparison, when the lining body covers some of the table's angles.
pub fn compare(tunnel: &LinedTunnel, sol: &Solution) -> Option<Comparison> {
    let body = sol.model.bodies.iter().position(|b| b.name == tunnel.lining.group)?;
    let (ri, ro) = tunnel.lining_radii();
    let n = (360.0 / STEP_DEG).round() as usize;
    let thetas: Vec<f64> = (0..n).map(|i| (i as f64 * STEP_DEG).to_radians()).collect();
    let rows: Vec<Row> = section_forces(sol.model, sol.u, body, ri, ro, &thetas)
        .into_iter()
        .flatten()
        .map(|s| {
            let x = [tunnel.radius * s.theta.cos(), tunnel.radius * s.theta.sin(), 0.0];
            let ue = tunnel.displacement(x);
            Row {
                theta_deg: s.theta.to_degrees(),
                thrust: s.thrust,
                thrust_theory: tunnel.thrust(s.theta),
                moment: s.moment,
                moment_theory: tunnel.moment(s.theta),
                displacement_error: (0..3).map(|c| (s.displacement[c] - ue[c]).powi(2)).sum::<f64>().sqrt(),
                displacement_theory: ue.iter().map(|v| v * v).sum::<f64>().sqrt(),
            }
        })
        .collect();
    if rows.is_empty() {
        return None;
    }
    let (t0, t2, m2) = tunnel.modes();
    let thrust_scale = t0.abs() + t2.abs();
    let moment_scale = tunnel.uniform_moment().abs() + m2.abs();
    let worst =
        |f: &dyn Fn(&Row) -> f64, scale: f64| rows.iter().map(f).fold(0.0, f64::max) / scale.max(f64::MIN_POSITIVE);
    let thrust_error = worst(&|r: &Row| (r.thrust - r.thrust_theory).abs(), thrust_scale);
    let moment_error = worst(&|r: &Row| (r.moment - r.moment_theory).abs(), moment_scale);
    let published_moment_error =
        worst(&|r: &Row| (r.moment - tunnel.moment_published(r.theta_deg.to_radians())).abs(), m2.abs());
    let u_scale = rows.iter().map(|r| r.displacement_theory).fold(0.0, f64::max);
    let displacement_error = worst(&|r: &Row| r.displacement_error, u_scale);
    Some(Comparison {
        rows,
        thrust_scale,
        moment_scale,
        thrust_error,
        moment_error,
        published_moment_error,
        displacement_error,
    })
}

/// The check of a lined tunnel: the closed form, this run's lining against
/// it (None when the lining covers none of the angles) and how far the
/// model reaches from the tunnel's centre ([`reach`]).
#[derive(Clone, Debug)]
pub struct TunnelCheck {
    pub tunnel: LinedTunnel,
    pub comparison: Option<Comparison>,
    pub reach: f64,
}

/// The check: the comparison, and the model's reach for the caveat on it.
pub(super) fn check(tunnel: &LinedTunnel, sol: &Solution) -> TunnelCheck {
    TunnelCheck { tunnel: tunnel.clone(), comparison: compare(tunnel, sol), reach: reach(sol.model) }
}

/// How far the model reaches from the tunnel's centre (the origin): the
/// smaller of its largest |x| and |y|, where the closed form's plane is
/// infinite.
pub fn reach(model: &Model) -> f64 {
    let (mut x, mut y) = (0.0f64, 0.0f64);
    for c in &model.coords {
        x = x.max(c[0].abs());
        y = y.max(c[1].abs());
    }
    x.min(y)
}
