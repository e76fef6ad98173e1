//! 4. Map coordinates: the stack moved to x ~ 5e5, y ~ 4.2e6 and rotated
//!    30 degrees (load rotated; the base clamped, which a rotation leaves
//!    valid) gives the answer of the model at the origin, rotated. Asserted on
//!    the origin's mesh moved exactly by the test ([`transform_msh`]: the
//!    solver's share), reported for gmsh meshing the moved .geo. The
//!    comparison of two runs node by node and pair by pair ([`compare_moved`])
//!    serves the units and strengths cases too.
//!
//! What keeps the 1e-8 at fine meshes far from the origin: the element
//! kernels (`fem::element::point`, `facet_point`, `fem::shape::locate`)
//! difference coordinates relative to each cell's first node, so a
//! Jacobian keeps the digits of the cell's size, not of 4.2e6.

use std::collections::HashMap;
use std::time::Instant;

use subcontact::contact::law::ContactState;
use subcontact::driver::Run;

use crate::common::cli::gmsh;
use crate::common::measure::{body_nodes, count, max_abs};
use crate::common::{read, Case};
use crate::stack::{map_stack, traction_line, Stack, MAP_TRACTION};
use crate::table::Suite;
use crate::{converged, nodal_stress, solve, states_note};

/// Compares run `b` (the model moved by (x0, y0) and rotated by angle)
/// with run `a` (at the origin, unrotated): displacements and nodal
/// stresses rotated back, contact sigma_n, tau_t and states per pair, all
/// relative to the largest value of `a`. Returns (u, sigma, contact, states equal).
pub fn compare_moved(a: &Run, b: &Run, x0: f64, y0: f64, angle_deg: f64, scale_b: f64) -> (f64, f64, f64, bool) {
    let th = angle_deg.to_radians();
    let (c, sn) = if angle_deg == 0.0 { (1.0, 0.0) } else { (th.cos(), th.sin()) };
    let key = |x: [f64; 3], moved: bool| -> [i64; 2] {
        let (lx, ly) = if moved {
            let (dx, dy) = (x[0] - x0, x[1] - y0);
            (c * dx + sn * dy, -sn * dx + c * dy)
        } else {
            (x[0], x[1])
        };
        [(lx * 1e5).round() as i64, (ly * 1e5).round() as i64]
    };
    let sa = nodal_stress(a);
    let sb = nodal_stress(b);
    // (body, position) -> (displacement, nodal stress) of the reference
    type ByPosition = HashMap<(usize, [i64; 2]), ([f64; 2], [f64; 6])>;
    let mut ua: ByPosition = HashMap::new();
    for (body, n) in body_nodes(a) {
        ua.insert((body, key(a.model.coords[n], false)), ([a.last().u[2 * n], a.last().u[2 * n + 1]], sa[&(body, n)]));
    }
    let umax = max_abs(a.last().u.iter().copied());
    let smax = max_abs(sa.values().flat_map(|s| s.iter().copied()));
    let (mut du, mut ds) = (0.0f64, 0.0f64);
    let nb = body_nodes(b);
    assert_eq!(nb.len(), ua.len(), "the same nodes");
    for (body, n) in nb {
        let (u, s) = ua
            .get(&(body, key(b.model.coords[n], true)))
            .unwrap_or_else(|| panic!("node {:?} of the moved model has no match", b.model.coords[n]));
        let (gx, gy) = (b.last().u[2 * n], b.last().u[2 * n + 1]);
        let ul = [c * gx + sn * gy, -sn * gx + c * gy];
        du = du.max((ul[0] - u[0]).abs()).max((ul[1] - u[1]).abs());
        let g = sb[&(body, n)].map(|v| v / scale_b);
        let loc = [
            c * c * g[0] + sn * sn * g[1] + 2.0 * c * sn * g[3],
            sn * sn * g[0] + c * c * g[1] - 2.0 * c * sn * g[3],
            g[2],
            -c * sn * g[0] + c * sn * g[1] + (c * c - sn * sn) * g[3],
        ];
        for (i, comp) in [0usize, 1, 2, 3].iter().enumerate() {
            ds = ds.max((loc[i] - s[*comp]).abs());
        }
    }
    let (ca, cb) = (converged(a), converged(b));
    let mut pa: HashMap<[i64; 2], usize> = HashMap::new();
    for (i, p) in a.model.pairs.iter().enumerate() {
        pa.insert(key(a.model.coords[p.k], false), i);
    }
    let cmax = max_abs(ca.pairs.iter().flat_map(|r| [r.sigma_n, r.tau_t]));
    let mut dc = 0.0f64;
    let mut same_states = ca.states.len() == cb.states.len();
    for (j, p) in b.model.pairs.iter().enumerate() {
        let i = pa[&key(b.model.coords[p.k], true)];
        dc = dc
            .max((ca.pairs[i].sigma_n - cb.pairs[j].sigma_n / scale_b).abs())
            .max((ca.pairs[i].tau_t - cb.pairs[j].tau_t / scale_b).abs());
        same_states &= ca.states[i] == cb.states[j];
    }
    (du / umax, ds / smax, dc / cmax, same_states)
}

/// Meshes stress_stack.geo with the gmsh CLI into an ASCII MSH 4.1 file of
/// the case (the driver's own meshes are binary); returns its text.
fn gmsh_ascii(case: &Case, st: &Stack, msh: &str) -> String {
    let mut args: Vec<String> = vec!["stress_stack.geo".into(), "-2".into(), "-order".into(), st.order.to_string()];
    for (k, v) in st.setnumber() {
        args.extend(["-setnumber".into(), k.to_string(), format!("{v:?}")]);
    }
    args.extend(["-format".into(), "msh41".into(), "-o".into(), msh.into()]);
    gmsh(case, &args);
    read(&case.dir.join(msh))
}

/// Applies a map of the plane to an ASCII MSH 4.1 text: every node (x, y),
/// each point entity, and each entity's bounding box (the box of its moved
/// corners). Everything else is copied. Coordinates are written in the
/// shortest form that reads back to the same double.
fn transform_msh(text: &str, f: &dyn Fn([f64; 2]) -> [f64; 2]) -> String {
    let mut out = String::with_capacity(text.len() + text.len() / 4);
    let lines: Vec<&str> = text.lines().collect();
    let num = |t: &str| -> f64 { t.parse().unwrap_or_else(|_| panic!("a number in the mesh: {t}")) };
    let mut i = 0;
    let push = |out: &mut String, l: &str| {
        out.push_str(l);
        out.push('\n');
    };
    while i < lines.len() {
        let line = lines[i];
        push(&mut out, line);
        i += 1;
        if line == "$Entities" {
            let counts: Vec<usize> = lines[i].split_whitespace().map(|t| t.parse().expect("entity counts")).collect();
            push(&mut out, lines[i]);
            i += 1;
            for (dim, &n) in counts.iter().enumerate() {
                for _ in 0..n {
                    let mut t: Vec<String> = lines[i].split_whitespace().map(String::from).collect();
                    if dim == 0 {
                        let p = f([num(&t[1]), num(&t[2])]);
                        t[1] = format!("{}", p[0]);
                        t[2] = format!("{}", p[1]);
                    } else {
                        let (x0, y0, x1, y1) = (num(&t[1]), num(&t[2]), num(&t[4]), num(&t[5]));
                        let c: Vec<[f64; 2]> = [[x0, y0], [x1, y0], [x0, y1], [x1, y1]].iter().map(|&p| f(p)).collect();
                        t[1] = format!("{}", c.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min));
                        t[2] = format!("{}", c.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min));
                        t[4] = format!("{}", c.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max));
                        t[5] = format!("{}", c.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max));
                    }
                    push(&mut out, &t.join(" "));
                    i += 1;
                }
            }
        } else if line == "$Nodes" {
            let head: Vec<usize> = lines[i].split_whitespace().map(|t| t.parse().expect("node header")).collect();
            push(&mut out, lines[i]);
            i += 1;
            for _ in 0..head[0] {
                let b: Vec<usize> =
                    lines[i].split_whitespace().map(|t| t.parse().expect("node block header")).collect();
                push(&mut out, lines[i]);
                i += 1;
                let n = b[3];
                for _ in 0..n {
                    push(&mut out, lines[i]);
                    i += 1;
                }
                for _ in 0..n {
                    let mut t: Vec<String> = lines[i].split_whitespace().map(String::from).collect();
                    let p = f([num(&t[0]), num(&t[1])]);
                    t[0] = format!("{}", p[0]);
                    t[1] = format!("{}", p[1]);
                    push(&mut out, &t.join(" "));
                    i += 1;
                }
            }
        }
    }
    out
}

/// Largest distance from a node of `b`, mapped back by `back`, to the
/// nearest node of `a` (how far the moved mesh is from the moved model).
fn mesh_deviation(a: &Run, b: &Run, back: &dyn Fn([f64; 2]) -> [f64; 2]) -> f64 {
    let mut grid: HashMap<[i64; 2], Vec<[f64; 2]>> = HashMap::new();
    for x in &a.model.coords {
        grid.entry([(x[0] * 10.0).floor() as i64, (x[1] * 10.0).floor() as i64]).or_default().push([x[0], x[1]]);
    }
    let mut dev = 0.0f64;
    for x in &b.model.coords {
        let l = back([x[0], x[1]]);
        let (gx, gy) = ((l[0] * 10.0).floor() as i64, (l[1] * 10.0).floor() as i64);
        let mut best = f64::INFINITY;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for p in grid.get(&[gx + dx, gy + dy]).map(|v| v.as_slice()).unwrap_or(&[]) {
                    best = best.min((p[0] - l[0]).hypot(p[1] - l[1]));
                }
            }
        }
        dev = dev.max(best);
    }
    dev
}

/// The moves of the map case: (what, x0, y0, angle in degrees).
const MOVES: [(&str, f64, f64, f64); 3] = [
    ("shifted", 5.0e5, 4.2e6, 0.0),
    ("rotated 30 deg", 0.0, 0.0, 30.0),
    ("shifted + rotated 30 deg", 5.0e5, 4.2e6, 30.0),
];

/// Map coordinates. The solver's part: the mesh of the model at the origin
/// moved exactly (each node x' = x0 + R x rounded once to a double, the
/// best a map coordinate can be stored) gives the answer rotated. The
/// mesher's part, reported: gmsh meshing the moved .geo itself.
pub fn map_case(s: &mut Suite, kind: &str, nx: usize, ny: usize) {
    let t = Instant::now();
    let mut base = map_stack(kind, nx, ny);
    base.load = traction_line(MAP_TRACTION, 0.0, 1.0);
    let tag = format!("map_{kind}_{nx}x{ny}");
    let text0 = gmsh_ascii(&s.case, &base, &format!("{tag}_origin.msh"));
    let a = solve(&s.case, &format!("{tag}_origin"), &base.text_msh(&format!("{tag}_origin.msh")), false);
    let t_a = t.elapsed().as_secs_f64();
    let ca = converged(&a);
    assert!(
        count(ca, ContactState::Open) > 0 && count(ca, ContactState::Stick) > 0,
        "the reference opens part of the joint: {}",
        states_note(ca)
    );
    for (what, x0, y0, angle) in MOVES {
        let th = angle.to_radians();
        let (c, sn) = if angle == 0.0 { (1.0, 0.0) } else { (th.cos(), th.sin()) };
        let fwd = move |p: [f64; 2]| [x0 + (c * p[0] - sn * p[1]), y0 + (sn * p[0] + c * p[1])];
        let back = move |p: [f64; 2]| {
            let (dx, dy) = (p[0] - x0, p[1] - y0);
            [c * dx + sn * dy, -sn * dx + c * dy]
        };
        let mut m = base.clone();
        m.load = traction_line(MAP_TRACTION, angle, 1.0);
        let cond = format!("origin ({x0:.1e}, {y0:.1e}), {angle} deg; |x| / w = {:.0e}", x0.hypot(y0).max(20.0) / 20.0);
        let label = format!("map coordinates {kind} {nx}x{ny}");
        let mtag = what.replace([' ', '+'], "");

        // the solver: the same mesh, moved
        let t = Instant::now();
        let msh = format!("{tag}_{mtag}.msh");
        s.case.write(&msh, &transform_msh(&text0, &fwd));
        let b = solve(&s.case, &format!("{tag}_{mtag}"), &m.text_msh(&msh), false);
        let secs = t.elapsed().as_secs_f64() + t_a;
        let dev = mesh_deviation(&a, &b, &back);
        let (du, ds, dc, same) = compare_moved(&a, &b, x0, y0, angle, 1.0);
        s.check(
            &label,
            &format!("{what}, mesh moved exactly: max of u (rotated back), nodal sigma, contact sigma_n/tau_t differences; same states"),
            if same { du.max(ds).max(dc) } else { f64::INFINITY },
            1e-8,
            Some(a.stats.residuals.interface.max(b.stats.residuals.interface)),
            &cond,
            secs,
            &format!("u {du:.1e}, sigma {ds:.1e}, contact {dc:.1e}; nodes {dev:.1e} m off the moved model; {}", states_note(converged(&b))),
        );

        // the mesher: gmsh meshes the moved .geo
        let t = Instant::now();
        let mut g = m.clone();
        g.x0 = x0;
        g.y0 = y0;
        g.angle = angle;
        let b = solve(&s.case, &format!("{tag}_{mtag}_gmsh"), &g.text(), false);
        let secs = t.elapsed().as_secs_f64();
        let dev = mesh_deviation(&a, &b, &back);
        let (du, ds, dc, same) = compare_moved(&a, &b, x0, y0, angle, 1.0);
        s.report(
            &label,
            &format!("{what}, meshed by gmsh at the moved place: the same differences"),
            if same { du.max(ds).max(dc) } else { f64::INFINITY },
            Some(b.stats.residuals.interface),
            &cond,
            secs,
            &format!("u {du:.1e}, sigma {ds:.1e}, contact {dc:.1e}; gmsh put the nodes up to {dev:.1e} m off the moved model ({:.0e} of an element)", dev / (20.0 / nx as f64)),
        );
    }
}
