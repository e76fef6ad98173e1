//! 1. Stiffness contrast 1 ... 1e6 between two bodies: the compound thick
//!    cylinder (rings a..c and c..b, moduli E1 and E2, bonded by a contact at
//!    r = c that stays stuck, internal pressure p, plane strain) against its
//!    closed form ([`Compound`]: Lamé in each ring, u_r and sigma_r continuous
//!    at r = c); the contact's sign convention on the curved joint; and the
//!    closed form's self-check. The compound scene ([`compound_scene`]) is
//!    also the curved joint of the units and strengths cases.

use std::time::Instant;

use subcontact::analytic::Lame;
use subcontact::contact::law::ContactState;
use subcontact::driver::Run;
use subcontact::scene::Analysis;

use crate::common::measure::{body_nodes, count, diff_to_bonded, max_abs};
use crate::table::Suite;
use crate::{converged, fmt_e, solve, states_note};

/// The compound thick cylinder in plane strain: ring 1 (a <= r <= c; E1,
/// nu1) inside ring 2 (c <= r <= b; E2, nu2), no shrink fit, internal
/// pressure p. In each ring u = A r + B / r, so with L = E/((1+nu)(1-2nu))
/// and M = E/(1+nu):
///
/// ```text
/// sigma_r = L A - M B / r^2     sigma_theta = L A + M B / r^2
/// sigma_z = nu (sigma_r + sigma_theta)
/// sigma_r1(a) = -p,  sigma_r2(b) = 0,  u1(c) = u2(c),  sigma_r1(c) = sigma_r2(c)
/// ```
struct Compound {
    a: f64,
    c: f64,
    b: f64,
    p: f64,
    e: [f64; 2],
    nu: [f64; 2],
    /// A1, B1, A2, B2.
    k: [f64; 4],
}

impl Compound {
    fn new(a: f64, c: f64, b: f64, p: f64, e: [f64; 2], nu: [f64; 2]) -> Compound {
        let l = |i: usize| e[i] / ((1.0 + nu[i]) * (1.0 - 2.0 * nu[i]));
        let m = |i: usize| e[i] / (1.0 + nu[i]);
        // unknowns scaled to stresses (L1 A1, M1 B1, L2 A2, M2 B2), rows
        // equilibrated: the system stays well conditioned at any contrast
        let mut mat = [
            [1.0, -1.0 / (a * a), 0.0, 0.0, -p],
            [0.0, 0.0, 1.0, -1.0 / (b * b), 0.0],
            [c / l(0), 1.0 / (c * m(0)), -c / l(1), -1.0 / (c * m(1)), 0.0],
            [1.0, -1.0 / (c * c), -1.0, 1.0 / (c * c), 0.0],
        ];
        for row in mat.iter_mut() {
            let big = row[..4].iter().fold(0.0f64, |x, v| x.max(v.abs()));
            row.iter_mut().for_each(|v| *v /= big);
        }
        let x = gauss4(&mut mat);
        let k = [x[0] / l(0), x[1] / m(0), x[2] / l(1), x[3] / m(1)];
        Compound { a, c, b, p, e, nu, k }
    }
    fn ring(&self, r: f64) -> usize {
        if r < self.c {
            0
        } else {
            1
        }
    }
    fn u_r(&self, r: f64) -> f64 {
        let i = self.ring(r);
        self.k[2 * i] * r + self.k[2 * i + 1] / r
    }
    /// (sigma_r, sigma_theta, sigma_z) at r (ring by r; at r = c, ring 2).
    fn stress(&self, r: f64) -> (f64, f64, f64) {
        self.stress_in(self.ring(r), r)
    }
    fn stress_in(&self, i: usize, r: f64) -> (f64, f64, f64) {
        let (e, nu) = (self.e[i], self.nu[i]);
        let l = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let m = e / (1.0 + nu);
        let (a, b) = (self.k[2 * i], self.k[2 * i + 1]);
        let sr = l * a - m * b / (r * r);
        let st = l * a + m * b / (r * r);
        (sr, st, nu * (sr + st))
    }
}

/// Solves the 4x4 system [A | rhs] by Gaussian elimination with partial pivoting.
fn gauss4(m: &mut [[f64; 5]; 4]) -> [f64; 4] {
    for col in 0..4 {
        let piv = (col..4).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs())).expect("rows");
        m.swap(col, piv);
        let pivot = m[col];
        for row in m.iter_mut().skip(col + 1) {
            let f = row[col] / pivot[col];
            for (v, p) in row.iter_mut().zip(pivot).skip(col) {
                *v -= f * p;
            }
        }
    }
    let mut x = [0.0; 4];
    for r in (0..4).rev() {
        let s: f64 = (r + 1..4).map(|k| m[r][k] * x[k]).sum();
        x[r] = (m[r][4] - s) / m[r][r];
    }
    x
}

/// Polar components (sigma_r, sigma_theta) of a Cartesian stress at angle theta.
fn polar(s: &[f64; 6], th: f64) -> (f64, f64) {
    let (c, sn) = (th.cos(), th.sin());
    (s[0] * c * c + s[1] * sn * sn + 2.0 * s[3] * c * sn, s[0] * sn * sn + s[1] * c * c - 2.0 * s[3] * c * sn)
}

/// One mesh of the compound cylinder.
#[derive(Clone, Copy)]
pub struct Ring {
    pub kind: &'static str,
    pub order: usize,
    pub quad: bool,
    pub serendipity: bool,
    pub lc: f64,
}

pub const E_SOFT: f64 = 1.0e3;
const NU1: f64 = 0.3;
const NU2: f64 = 0.2;
const PROBE_ANGLE: f64 = std::f64::consts::PI / 8.0;

pub fn compound_scene(m: Ring, e1: f64, e2: f64, contact: &str, outer_first: bool) -> String {
    let (r0, r1) = (3.1, 4.9);
    let (c, s) = (PROBE_ANGLE.cos(), PROBE_ANGLE.sin());
    let inner = "[[bodies]]\ngroup = \"inner_ring\"\nmaterial = \"inner\"\n";
    let outer = "[[bodies]]\ngroup = \"outer_ring\"\nmaterial = \"outer\"\n";
    let bodies = if outer_first { format!("{outer}\n{inner}") } else { format!("{inner}\n{outer}") };
    format!(
        r#"title = "compound cylinder, E2/E1 = {ratio:e}"
mesh = "stress_annulus.geo"
analysis = "plane_strain"

[gmsh]
order = {order}
setnumber = {{ lc = {lc}, quad = {quad}, serendipity = {ser} }}

[materials.inner]
E = {e1:e}
nu = {NU1}

[materials.outer]
E = {e2:e}
nu = {NU2}

{bodies}
[[contacts]]
group = "joint"
{contact}

[[supports]]
group = "symmetry_x0"
fix = ["x"]

[[supports]]
group = "symmetry_y0"
fix = ["y"]

[[loads]]
group = "inner"
pressure = 1.0

[[probes]]
name = "radial"
from = [{fx}, {fy}]
to = [{tx}, {ty}]
points = 10
"#,
        ratio = e2 / e1,
        order = m.order,
        lc = m.lc,
        quad = m.quad as i32,
        ser = m.serendipity as i32,
        fx = r0 * c,
        fy = r0 * s,
        tx = r1 * c,
        ty = r1 * s,
    )
}

/// Errors of a compound cylinder run: (probe stresses / p, nodal u_r /
/// max u_r, contact sigma_n / p, max tau / p).
fn compound_errors(run: &Run, exact: &Compound) -> (f64, f64, f64, f64) {
    let p = exact.p;
    let samples = &run.checks.probes.iter().find(|(n, _)| n == "radial").expect("probe").1;
    let mut es = 0.0f64;
    for smp in samples {
        assert!(smp.found, "probe point {:?} in the model", smp.x);
        let r = smp.x[0].hypot(smp.x[1]);
        let (sr, st) = polar(&smp.stress, PROBE_ANGLE);
        let (er, et, ez) = exact.stress(r);
        es = es.max((sr - er).abs()).max((st - et).abs()).max((smp.stress[2] - ez).abs());
    }
    let umax = max_abs([exact.u_r(exact.a), exact.u_r(exact.c), exact.u_r(exact.b)]);
    let mut eu = 0.0f64;
    for (_, n) in body_nodes(run) {
        let x = run.model.coords[n];
        let r = x[0].hypot(x[1]);
        let ur = exact.u_r(r.clamp(exact.a, exact.b));
        let ex = [ur * x[0] / r, ur * x[1] / r];
        eu = eu.max((run.last().u[2 * n] - ex[0]).abs()).max((run.last().u[2 * n + 1] - ex[1]).abs());
    }
    let c = converged(run);
    let sc = exact.stress(exact.c).0;
    let en = max_abs(c.pairs.iter().map(|r| r.sigma_n - sc));
    let et = max_abs(c.pairs.iter().map(|r| r.tau()));
    (es / p, eu / umax, en / p, et / p)
}

pub const STUCK_JOINT: &str = "friction = 0.8\ncohesion = 1.0e6\ntensile_strength = 1.0e6";

/// `tol`: probe stresses / p, nodal displacements / max u_r, contact / p.
pub fn contrast_case(s: &mut Suite, m: Ring, ratios: &[f64], tol: [f64; 3]) {
    for &ratio in ratios {
        for stiff_outer in [true, false] {
            if ratio == 1.0 && !stiff_outer {
                continue;
            }
            let (e1, e2) = if stiff_outer { (E_SOFT, E_SOFT * ratio) } else { (E_SOFT * ratio, E_SOFT) };
            let name = format!("compound_{}_lc{}_r{:e}_{}", m.kind, m.lc, ratio, if stiff_outer { "o" } else { "i" });
            let t = Instant::now();
            let text = compound_scene(m, e1, e2, STUCK_JOINT, false);
            let run = solve(&s.case, &name, &text, false);
            let bonded = solve(&s.case, &name, &text, true);
            let secs = t.elapsed().as_secs_f64();
            let exact = Compound::new(3.0, 4.0, 5.0, 1.0, [e1, e2], [NU1, NU2]);
            let c = converged(&run);
            let all_stick = count(c, ContactState::Stick) == c.states.len();
            let (es, eu, en, et) = compound_errors(&run, &exact);
            let db = diff_to_bonded(&run, &bonded);
            let cond = format!("E2/E1 = {}", fmt_e(e2 / e1));
            let label = format!("contrast {} {} lc {}", m.kind, cond, m.lc);
            let res = Some(run.stats.residuals.interface);
            let note =
                format!("{} pairs, {}; sigma_r(c) = {:.4} p", c.pairs.len(), states_note(c), exact.stress(exact.c).0);
            s.boolean(&label, "every pair stuck", all_stick, res, &cond, secs, &note);
            s.check(
                &label,
                "stresses at 10 probe points vs closed form (/p)",
                es,
                tol[0],
                res,
                &cond,
                0.0,
                "sigma_r, sigma_theta, sigma_z at r = 3.1 ... 4.9",
            );
            s.check(&label, "nodal displacement vs closed form (/max u_r)", eu, tol[1], res, &cond, 0.0, "");
            s.check(
                &label,
                "contact sigma_n vs sigma_r(c), tau vs 0 (/p)",
                en.max(et),
                tol[2],
                res,
                &cond,
                0.0,
                &format!("sigma_n {en:.2e}, tau {et:.2e}"),
            );
            s.check(
                &label,
                "interface solve vs bonded solve (/max u)",
                db,
                1e-9,
                res,
                &cond,
                0.0,
                "round-off only: the same discrete problem",
            );
        }
    }
}

/// The sign convention on a curved interface: listing the outer ring first
/// (body I = outer ring, n = -e_r) gives the same sigma_n = sigma_r(c).
pub fn contrast_swapped_case(s: &mut Suite, m: Ring) {
    let (e1, e2) = (E_SOFT, E_SOFT * 1e3);
    let t = Instant::now();
    let a = solve(&s.case, "compound_order_a", &compound_scene(m, e1, e2, STUCK_JOINT, false), false);
    let b = solve(&s.case, "compound_order_b", &compound_scene(m, e1, e2, STUCK_JOINT, true), false);
    let secs = t.elapsed().as_secs_f64();
    let exact = Compound::new(3.0, 4.0, 5.0, 1.0, [e1, e2], [NU1, NU2]);
    let (ca, cb) = (converged(&a), converged(&b));
    // normals point out of body I: +e_r with the inner ring first, -e_r
    // with the outer (n . e_r = +-1 up to the arc's parabolic approximation)
    let n_dot_er = |run: &Run| -> Vec<f64> {
        run.model
            .pairs
            .iter()
            .map(|p| {
                let x = run.model.coords[p.k];
                (p.normal[0] * x[0] + p.normal[1] * x[1]) / x[0].hypot(x[1])
            })
            .collect()
    };
    let (na, nb) = (n_dot_er(&a), n_dot_er(&b));
    let dev = na.iter().map(|v| (v - 1.0).abs()).chain(nb.iter().map(|v| (v + 1.0).abs())).fold(0.0f64, f64::max);
    let cond = "E2/E1 = 1e3";
    s.check(
        "sign convention, curved joint",
        "n = +e_r (inner ring is body I) / -e_r (outer ring is body I) at every pair: max |n.e_r -+ 1|",
        dev,
        1e-3,
        Some(a.stats.residuals.interface.max(b.stats.residuals.interface)),
        cond,
        secs,
        "",
    );
    let sc = exact.stress(exact.c).0;
    let ea = max_abs(ca.pairs.iter().map(|r| r.sigma_n - sc));
    let eb = max_abs(cb.pairs.iter().map(|r| r.sigma_n - sc));
    s.check(
        "sign convention, curved joint",
        "sigma_n = sigma_r(c) < 0 with either ring as body I (/p)",
        ea.max(eb),
        5e-3,
        Some(a.stats.residuals.interface.max(b.stats.residuals.interface)),
        cond,
        0.0,
        &format!(
            "sigma_r(c) = {sc:.4} p; mean sigma_n {:.4} / {:.4}",
            ca.pairs.iter().map(|r| r.sigma_n).sum::<f64>() / ca.pairs.len() as f64,
            cb.pairs.iter().map(|r| r.sigma_n).sum::<f64>() / cb.pairs.len() as f64
        ),
    );
}

/// The closed form checks itself: equal rings are Lamé's cylinder.
pub fn compound_closed_form_case(s: &mut Suite) {
    let c = Compound::new(3.0, 4.0, 5.0, 1.0, [2.0e5, 2.0e5], [0.167, 0.167]);
    let l = Lame { a: 3.0, b: 5.0, p: 1.0, e: 2.0e5, nu: 0.167, analysis: Analysis::PlaneStrain };
    let mut e = 0.0f64;
    for i in 0..=20 {
        let r = 3.0 + 0.1 * i as f64;
        let (sr, st, _) = c.stress(r);
        e = e
            .max((sr - l.sigma_r(r)).abs())
            .max((st - l.sigma_theta(r)).abs())
            .max((c.u_r(r) - l.u_r(r)).abs() / l.u_r(3.0));
    }
    // and with contrast: the four conditions hold
    let d = Compound::new(3.0, 4.0, 5.0, 1.0, [1.0e3, 1.0e9], [NU1, NU2]);
    let (s1, _, _) = d.stress_in(0, 4.0);
    let (s2, _, _) = d.stress_in(1, 4.0);
    let u1 = d.k[0] * 4.0 + d.k[1] / 4.0;
    let u2 = d.k[2] * 4.0 + d.k[3] / 4.0;
    let bc =
        (d.stress(3.0).0 + 1.0).abs().max(d.stress(5.0).0.abs()).max((s1 - s2).abs()).max((u1 - u2).abs() / u1.abs());
    s.check(
        "compound closed form",
        "E1 = E2 gives Lamé; E2/E1 = 1e6 meets its 4 conditions",
        e.max(bc),
        1e-11,
        None,
        "E2/E1 = 1, 1e6",
        0.0,
        "self-check of the reference (4x4 solve, scaled)",
    );
}
