//! A stiff foundation beam on elastic ground under an eccentric column load:
//! `geo/footing.{geo,toml}` through the real gmsh CLI and the library driver.
//!
//! Reference: the middle-third rule of foundation design, and K. L. Johnson,
//! *Contact Mechanics* (1985), §5.2 (the flat punch, tilted).
//!
//! Goal: the no-tension contact (f_t = 0, friction 0.6, no cohesion) lifts
//! the beam off where an engineer expects, and the contact forces carry
//! exactly the load.
//!
//! ```text
//!                    V (on a 0.2 m plate at x = e)
//!                    |
//!        +-----------v------+        beam: B = 2 m, t = 0.5 m, E = 3e4
//!        |       beam       |
//!   -----+~~~~~~~+==========+-----   base: open (~) / closed (=)
//!        |<B - L>|<-- L --->|        ground: 10 B wide, `depth` deep,
//!             ground                 E = 30, nu = 0.3, sides held in x,
//!                                    bottom held
//! ```
//!
//! What the elastic answer is. The rigid-block no-tension rule (pressure
//! linear in x, a triangle once the far edge lifts: resultant at L/3 from
//! the loaded edge, so L = 3 (B/2 - e) for e > B/6) is the answer of a
//! Winkler subgrade. A deep elastic ground is not one: under a rigid
//! footing on a half-space (frictionless, plane strain) the pressure is
//! `p = V / (pi b) sqrt((b + s) / (b - s))` on a contact of length L = 2b
//! that ends smoothly at the lifted side and is singular at the loaded edge
//! (s from the contact's middle). Its resultant lies b/2 from the middle,
//! L/4 from the loaded edge: L = 4 (B/2 - e), and lift-off starts only at
//! e = B/4 (below that `p = V (1 + 2 e x / a^2) / (pi sqrt(a^2 - x^2))`,
//! a = B/2, positive at both edges). At e = B/4 and B/3 the two rules differ
//! by B/2 - e = 0.5 m and 0.33 m, ten and seven elements at lc = 0.05 m: on
//! the 5 B deep ground of the issue the rigid-block rule does not hold
//! "within one element", and no honest mesh makes it so (one element would
//! have to be B/4). So the rule is tested where the elastic answer is the
//! rule's, on a thin compressible stratum on rock (depth B/20 = 0.1 m, the
//! `depth` parameter of the .geo: a Winkler subgrade), and the deep ground
//! against the half-space answer, which misses the rule by many elements.
//! Both ground models keep full contact at e = B/12.
//!
//! Measured (lc = 0.05 m on the base, quad9, 81 pairs 0.025 m apart, beam
//! 1000 times stiffer than the ground; L = extent of the pairs not open,
//! from the loaded edge):
//!
//! ```text
//!   e      thin stratum (B/20)  3(B/2-e)   deep ground (5B)  min(B, 4(B/2-e))
//!   B/12   2.000 (all closed)   2.000      2.000 (all closed)  2.000
//!   B/5    1.775                1.800      2.000 (all closed)  2.000
//!   B/4    1.500                1.500      1.975               2.000
//!   B/3    1.000                1.000      1.325               1.333
//! ```
//!
//! Every measured length is within half an element (one pair spacing) of
//! its ground's rule; on the deep ground the contact is longer than the
//! rigid-block rule's by 0.475 m and 0.325 m (9.5 and 6.5 elements) at B/4
//! and B/3. Halving lc (0.025) or a beam 1e4 times stiffer moves no length
//! by more than one pair spacing; a beam only 100 times stiffer bends enough
//! to shorten the contact at B/4 by 0.075 m (thin) and 0.05 m (deep).
//! The pressure picture: on both grounds the largest compression is at the
//! loaded edge pair. On the thin stratum it is the triangle (within 8 % of
//! V/L over the middle half of the contact; the half nearer the loaded edge
//! carries 0.742 to 0.747 V against 3/4), on the deep ground the half-space
//! distribution (within 4 %; 0.756, 0.821, 0.816 V against 1/2 + 2e/(pi a)
//! = 0.755 and 1/2 + 1/pi = 0.818). The contact forces balance V and its
//! moment V e to 1e-11 relative (the sum of sigma_n times the pair area, the
//! vertical and horizontal components of the traction, the moment about the
//! base's centre). Each run takes 0.2 to 0.6 s alone (deep ground: 16 700
//! DOFs, 324 on the interface; gmsh is half of it), the file about 3 s. The
//! contact iteration takes 1, 4, 9, 6 iterations on the thin stratum (B/12,
//! B/5, B/4, B/3) and 11, 16, 18, 19 on the deep ground, with no cycles; on
//! the deep ground the state set is settled after about 8 and the rest is
//! the Coulomb shear of the 15 to 27 slipping pairs settling.

mod common;

use common::measure::count;
use common::{read, repo_text, Case};
use subcontact::contact::law::ContactState;
use subcontact::driver::Run;

/// Beam width (fixed in footing.geo).
const B: f64 = 2.0;
/// The column load per metre: 2.5 MPa on the 0.2 m plate (footing.toml).
const V: f64 = 0.5;
/// Element size along the base (footing.toml's `lc`).
const LC: f64 = 0.05;
/// The issue's ground block: 5 B deep (footing.toml's `depth`).
const DEEP: f64 = 10.0;
/// A thin compressible stratum on rock: B / 20 deep.
const THIN: f64 = 0.1;

/// The repository's footing.toml with the eccentricity and the ground's depth set.
fn scene_text(e: f64, depth: f64) -> String {
    let text = repo_text("geo/footing.toml");
    let line = "setnumber = { lc = 0.05, e = 0.6666666666666666, depth = 10.0 }";
    assert!(text.contains(line), "footing.toml has the line {line:?}");
    text.replace(line, &format!("setnumber = {{ lc = {LC:?}, e = {e:?}, depth = {depth:?} }}"))
}

/// One solved footing and what was measured on it.
struct Footing {
    e: f64,
    depth: f64,
    run: Run,
    /// Extent of the pairs not open, from the loaded edge x = B/2.
    length: f64,
    /// (x, vertical force on the ground, pressure) of every pair, by x.
    pairs: Vec<(f64, f64, f64)>,
}

/// Solves the footing at eccentricity e on ground of the given depth and
/// checks what holds for every run: converged, the contact is one interval
/// that ends at the loaded edge, open pairs gap, and the contact forces
/// balance the load and its moment to round-off.
fn solve(case: &Case, name: &str, e: f64, depth: f64) -> Footing {
    let scene = case.write(&format!("{name}.toml"), &scene_text(e, depth));
    let run = case.run(&scene).unwrap_or_else(|err| panic!("{name}: {err:#}"));
    let c = run.contact().expect("a contact run");
    assert!(c.summary.converged && !c.summary.cycled(), "{name}: converged without cycling");
    assert!(run.stats.residuals.interface < 1e-8, "{name}: interface residual {:.2e}", run.stats.residuals.interface);

    // 1. Force and moment balance: the ground (body I, n = +y) takes V down at x = e.
    let (mut fn_sum, mut fx, mut fy, mut m) = (0.0, 0.0, 0.0, 0.0);
    let mut pairs = Vec::new();
    for (p, (pair, r)) in run.model.pairs.iter().zip(&c.pairs).enumerate() {
        let x = run.model.coords[pair.k];
        assert!(x[1].abs() < 1e-12, "pair {p} lies on the base");
        assert!((pair.normal[1] - 1.0).abs() < 1e-12, "pair {p}: n = +y (the ground is body I)");
        let t = [-pair.normal[1], pair.normal[0]];
        let f = [
            (r.sigma_n * pair.normal[0] + r.tau_t * t[0]) * pair.area,
            (r.sigma_n * pair.normal[1] + r.tau_t * t[1]) * pair.area,
        ];
        fn_sum += r.sigma_n * pair.area;
        fx += f[0];
        fy += f[1];
        m += x[0] * f[1];
        pairs.push((x[0], f[1], -r.sigma_n));
    }
    let (en, ex, ey, em) = ((fn_sum + V).abs() / V, fx.abs() / V, (fy + V).abs() / V, (m + V * e).abs() / (V * B));
    assert!(
        en < 1e-8 && ex < 1e-8 && ey < 1e-8 && em < 1e-8,
        "{name}: balance of sum sigma_n A {en:.1e}, x {ex:.1e}, y {ey:.1e}, moment {em:.1e}"
    );

    // 2. The contact: one interval from the loaded edge; open pairs have lifted.
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let state_at = |x: f64| {
        let p = run.model.pairs.iter().position(|q| (run.model.coords[q.k][0] - x).abs() < 1e-9).expect("a pair at x");
        c.states[p]
    };
    let closed: Vec<f64> = pairs.iter().map(|q| q.0).filter(|&x| state_at(x) != ContactState::Open).collect();
    let x_min = closed.first().copied().expect("some pairs are closed");
    assert!((closed.last().copied().expect("closed") - B / 2.0).abs() < 1e-9, "{name}: the loaded edge bears");
    let n_between = pairs.iter().filter(|q| q.0 >= x_min - 1e-9).count();
    assert_eq!(closed.len(), n_between, "{name}: the closed pairs form one interval");
    for (p, pair) in run.model.pairs.iter().enumerate() {
        if c.states[p] == ContactState::Open {
            assert!(c.pairs[p].gap > 0.0, "{name}: open pair at x = {} lifts", run.model.coords[pair.k][0]);
        }
    }
    let length = B / 2.0 - x_min;
    assert_bearing(&run, name, e, length);
    let (slip, open) = (count(c, ContactState::Slip), count(c, ContactState::Open));
    eprintln!(
        "{name}: depth {depth}, e = {e:.4}: L = {length:.4} m; {} pairs ({slip} slip, {open} open), {} iterations, {} cycles broken; balance {en:.1e} / {ey:.1e} / moment {em:.1e}; {} DOFs ({} interface), {:.2} s",
        c.states.len(),
        c.summary.iterations,
        c.summary.cycles_broken,
        run.stats.dofs.total,
        run.stats.dofs.interface,
        run.stats.timings.total
    );
    Footing { e, depth, run, length, pairs }
}

/// The bearing pressure summary of the base (issue 34) says what the
/// engineer found by hand: the load V, acting at x = e (the beam balances
/// V and the contact alone, so to round-off), e about the base's centre,
/// in the middle third when e <= B/6, the length in contact within a pair
/// spacing of the closed pairs' extent (each closed pair counts the length
/// it controls), the largest pressure at the loaded edge, and a design
/// pressure over B/10 between the mean and the singular edge value.
fn assert_bearing(run: &Run, name: &str, e: f64, length: f64) {
    let all = subcontact::output::bearing::of_run(run).expect("a bearing summary");
    assert_eq!(all.len(), 1, "{name}: one group, one face pair");
    let b = &all[0].bearing;
    let ends = b.from_ends();
    eprintln!(
        "  bearing: N {:.6} at x {:.6} (e {:+.6}), in contact {:.4} (closed extent {length:.4}), p max {:.3}, mean {:.3}, over {} {:.3}",
        b.force, b.at[0], b.eccentricity[0], b.contact_area, b.max_pressure, b.mean_pressure, b.window, b.design_pressure
    );
    assert!((b.force - V).abs() < 1e-8 * V, "{name}: N = {}", b.force);
    assert!((b.at[0] - e).abs() < 1e-8 * B && b.at[1].abs() < 1e-12, "{name}: acts at {:?}", b.at);
    // t runs from the loaded edge x = B/2 towards -x
    assert!((b.eccentricity[0] + e).abs() < 1e-8 * B && (ends[0] - (B / 2.0 - e)).abs() < 1e-8 * B, "{name}: {ends:?}");
    assert_eq!(b.in_kern(true), e <= B / 6.0, "{name}: middle third");
    assert!((b.contact_area - length).abs() <= LC / 2.0 + 1e-9, "{name}: contact {}", b.contact_area);
    assert!((b.max_at[0] - B / 2.0).abs() < 1e-9 && (b.window - 0.1 * B).abs() < 1e-12, "{name}: {b:?}");
    assert!(b.mean_pressure < b.design_pressure && b.design_pressure < b.max_pressure, "{name}: {b:?}");
}

impl Footing {
    /// Asserts the contact length is within one element of `want`.
    fn assert_length(&self, want: f64, rule: &str) {
        let d = self.length - want;
        eprintln!(
            "  depth {}, e = {:.4}: L = {:.4}, {rule} = {want:.4}, {:+.4} m ({:+.2} elements)",
            self.depth,
            self.e,
            self.length,
            d,
            d / LC
        );
        assert!(
            d.abs() <= LC + 1e-9,
            "depth {}, e = {}: L = {} against {rule} = {want}: more than one element (lc = {LC}) off",
            self.depth,
            self.e,
            self.length
        );
    }

    /// Every pair closed.
    fn assert_full_contact(&self) {
        let c = self.run.contact().expect("contact");
        for (p, s) in c.states.iter().enumerate() {
            assert_ne!(
                *s,
                ContactState::Open,
                "depth {}, e = {}: pair at x = {} must stay closed",
                self.depth,
                self.e,
                self.run.model.coords[self.run.model.pairs[p].k][0]
            );
        }
    }

    /// The largest compression is at the loaded edge; returns the share of V
    /// carried by the half of the contact (of length `l`) nearer to it.
    fn near_share(&self, l: f64) -> f64 {
        let peak = self.pairs.iter().max_by(|a, b| a.2.total_cmp(&b.2)).expect("pairs");
        assert!(
            (peak.0 - B / 2.0).abs() < 1e-9,
            "depth {}, e = {}: peak pressure {} at x = {}, not at the loaded edge",
            self.depth,
            self.e,
            peak.2,
            peak.0
        );
        let mid = B / 2.0 - l / 2.0;
        let near: f64 = self
            .pairs
            .iter()
            .map(|&(x, f, _)| {
                if (x - mid).abs() < 1e-9 {
                    -0.5 * f
                } else if x > mid {
                    -f
                } else {
                    0.0
                }
            })
            .sum();
        near / V
    }

    /// Max |p - p_ref| over the pairs at least `margin` inside [x0, B/2],
    /// relative to the mean pressure V / (B/2 - x0).
    fn profile_error(&self, x0: f64, margin: f64, p_ref: impl Fn(f64) -> f64) -> f64 {
        let mean = V / (B / 2.0 - x0);
        self.pairs
            .iter()
            .filter(|q| q.0 >= x0 + margin - 1e-9 && q.0 <= B / 2.0 - margin + 1e-9)
            .map(|q| (q.2 - p_ref(q.0)).abs() / mean)
            .fold(0.0, f64::max)
    }
}

/// The no-tension rule's contact length: 3 (B/2 - e), at most B.
fn rigid_block_length(e: f64) -> f64 {
    (3.0 * (B / 2.0 - e)).min(B)
}

/// A rigid footing on an elastic half-space: 4 (B/2 - e), at most B.
fn half_space_length(e: f64) -> f64 {
    (4.0 * (B / 2.0 - e)).min(B)
}

/// The half-space pressure under a rigid footing in contact over [B/2 - l, B/2]
/// with the load at e (l from half_space_length).
fn half_space_pressure(e: f64, x: f64) -> f64 {
    let l = half_space_length(e);
    if l < B {
        let b = l / 2.0;
        let s = x - (B / 2.0 - b);
        V / (std::f64::consts::PI * b) * ((b + s) / (b - s)).sqrt()
    } else {
        let a = B / 2.0;
        V * (1.0 + 2.0 * e * x / (a * a)) / (std::f64::consts::PI * (a * a - x * x).sqrt())
    }
}

/// The share of V the half-space pressure puts on the half of the contact
/// nearer the loaded edge: 1/2 + 2 e / (pi a) in full contact (a = B/2),
/// 1/2 + 1/pi once the far edge has lifted.
fn half_space_share(e: f64) -> f64 {
    0.5 + (2.0 * e / B).min(0.5) * 2.0 / std::f64::consts::PI
}

// ---------------------------------------------------------------------------

/// On a thin compressible stratum (a Winkler subgrade) the contact length
/// is the rigid-block no-tension rule's within one element, and the
/// pressure is its triangle.
#[test]
fn thin_stratum_contact_length_follows_the_no_tension_rule() {
    let case = Case::new("footing-thin");
    case.copy("geo/footing.geo");
    for (name, e) in [("thin_b5", B / 5.0), ("thin_b4", B / 4.0), ("thin_b3", B / 3.0)] {
        let f = solve(&case, name, e, THIN);
        let l = rigid_block_length(e);
        f.assert_length(l, "3 (B/2 - e)");
        let share = f.near_share(l);
        let triangle = |x: f64| (2.0 * V / l * (1.0 - (B / 2.0 - x) / l)).max(0.0);
        let err = f.profile_error(B / 2.0 - l, 0.25 * l, triangle);
        eprintln!("  near half carries {share:.4} V (triangle 0.75); pressure within {:.1} % of V/L of the triangle in the middle half", 100.0 * err);
        assert!((share - 0.75).abs() < 0.03, "{name}: near half carries {share}");
        assert!(err < 0.1, "{name}: {err}");
    }
}

/// On the issue's deep ground (5 B, the committed scene) the contact length
/// is the half-space answer 4 (B/2 - e) within one element, full contact
/// up to B/4, and many elements longer than the rigid-block rule's.
#[test]
fn deep_ground_contact_length_follows_the_rigid_footing_on_a_half_space() {
    let case = Case::new("footing-deep");
    case.copy("geo/footing.geo");
    // the committed scene as it is: e = B/3 on the 5 B ground
    let scene = case.copy("geo/footing.toml");
    assert_eq!(read(&scene), scene_text(B / 3.0, DEEP), "footing.toml is e = B/3 on the deep ground");
    for (name, e) in [("deep_b5", B / 5.0), ("deep_b4", B / 4.0), ("footing", B / 3.0)] {
        let f = solve(&case, name, e, DEEP);
        let l = half_space_length(e);
        f.assert_length(l, "min(B, 4 (B/2 - e))");
        if e < B / 4.0 {
            f.assert_full_contact();
        }
        let share = f.near_share(l);
        let want = half_space_share(e);
        let err = f.profile_error(B / 2.0 - l, 0.25 * l, |x| half_space_pressure(e, x));
        eprintln!("  near half carries {share:.4} V (half-space {want:.4}); pressure within {:.1} % of V/L of the half-space's in the middle half", 100.0 * err);
        assert!((share - want).abs() < 0.03, "{name}: near half carries {share}, half-space {want}");
        assert!(err < 0.1, "{name}: {err}");
        if e >= B / 4.0 {
            let miss = f.length - rigid_block_length(e);
            eprintln!(
                "  the rigid-block rule 3 (B/2 - e) = {:.4} is {miss:.4} m ({:.1} elements) short",
                rigid_block_length(e),
                miss / LC
            );
            assert!(miss > 5.0 * LC, "the deep ground's contact is longer than the rule's by more than five elements");
        }
    }
}

/// Inside the middle third (e = B/12) no pair opens, on either ground.
#[test]
fn full_contact_inside_the_middle_third() {
    let case = Case::new("footing-middle-third");
    case.copy("geo/footing.geo");
    for (name, depth) in [("thin_b12", THIN), ("deep_b12", DEEP)] {
        let f = solve(&case, name, B / 12.0, depth);
        f.assert_full_contact();
        f.assert_length(B, "B");
    }
}

/// geo/footing_layers.{geo,toml} through the real gmsh CLI and the real
/// binary, on a coarser plan (lc 0.4 under the footing, 2 at the ground's
/// edge): a square footing on two layers of prisms extruded from a
/// triangulated plan, the load at (0.6, 0.6) m from its centre. The far
/// corner lifts, the loaded one stays closed, the base carries the load
/// V = 0.9 MN exactly (the footing's underside is flat, its outward normal
/// -z, so each pair's force on it is area (tau - sigma_n e_z)), and meshio
/// reads both VTU files (prism18 bodies, tri6 contact facets).
#[test]
fn square_footing_on_layers_of_prisms_lifts_its_far_corner_and_carries_the_load() {
    let case = Case::new("footing-layers");
    case.copy("geo/footing_layers.geo");
    let text = common::scenes::edited(
        "geo/footing_layers.toml",
        &[("setnumber = { lc = 0.25, e = 0.6 }", "setnumber = { lc = 0.4, lc_far = 2.0, e = 0.6 }")],
    );
    case.write("footing_layers.toml", &text);
    let out = case.cli(&["solve", "footing_layers.toml", "--out", "res", "--quiet"]);
    assert!(out.status.success(), "subcontact solve failed: {}", String::from_utf8_lossy(&out.stderr));
    let res = case.dir.join("res");
    let csv = read(&res.join("contact.csv"));
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| {
        header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("contact.csv has no column {name}"))
    };
    // every column a number but the contact's name (NaN here)
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap_or(f64::NAN)).collect()).collect();
    let at = |x: f64, y: f64| {
        rows.iter()
            .find(|r| (r[col("x")] - x).abs() < 1e-9 && (r[col("y")] - y).abs() < 1e-9)
            .expect("a pair at the corner")
    };
    let (far, loaded) = (at(-1.0, -1.0), at(1.0, 1.0));
    eprintln!(
        "footing on layers: {} pairs; far corner status {} gap {:.4e} m; loaded corner status {} sigma_n {:.3}",
        rows.len(),
        far[col("status")],
        far[col("gap")],
        loaded[col("status")],
        loaded[col("sigma_n")]
    );
    assert_eq!(far[col("status")], 0.0, "the far corner opens");
    assert!(far[col("gap")] > 1e-3, "the far corner lifts: gap {}", far[col("gap")]);
    assert!(loaded[col("status")] > 0.0 && loaded[col("sigma_n")] < 0.0, "the loaded corner stays pressed");
    let resultant: [f64; 3] = std::array::from_fn(|i| {
        let tau = [col("tau_x"), col("tau_y"), col("tau_z")][i];
        rows.iter().map(|r| r[col("area")] * (r[tau] - if i == 2 { r[col("sigma_n")] } else { 0.0 })).sum()
    });
    eprintln!("    contact resultant on the footing {resultant:?} (the load: 0.9 MN down)");
    let v = 10.0 * 0.3 * 0.3;
    assert!(
        resultant[0].abs() < 1e-8 * v && resultant[1].abs() < 1e-8 * v && (resultant[2] - v).abs() < 1e-8 * v,
        "the base carries the load: {resultant:?}"
    );
    // the bearing summary (issue 34): V at the plate's centre (e, e), out
    // of the kern, the far corner open, in summary.json and report.md
    let bearing = &common::json(&res.join("summary.json"))["bearing"][0];
    let at = common::json_vec3(&bearing["at"]);
    let f = bearing["force"].as_f64().expect("force");
    eprintln!("    bearing: N {f:.6} at {at:?}, {} of {} m2 in contact", bearing["contact_area"], bearing["area"]);
    assert!((f - v).abs() < 1e-8 * v, "N = {f}");
    assert!((at[0] - 0.6).abs() < 1e-8 && (at[1] - 0.6).abs() < 1e-8 && at[2].abs() < 1e-12, "acts at {at:?}");
    assert_eq!(bearing["in_kern"], false);
    let area = |k: &str| bearing[k].as_f64().expect("area");
    assert!((area("area") - 4.0).abs() < 1e-9 && area("contact_area") < area("area"), "{bearing}");
    let report = read(&res.join("report.md"));
    assert!(report.contains("## Bearing pressure") && report.contains("### `base`"), "report.md: the bearing table");
    assert!(read(&res.join("bearing.csv")).lines().count() == 2, "bearing.csv: a header and the group");
    // meshio (as ParaView) reads the results: wedge18 cells, tri6 facets and the pairs
    let types = |file: &str| -> String {
        let script =
            "import sys, meshio\nm = meshio.read(sys.argv[1])\nprint(' '.join(sorted({c.type for c in m.cells})))";
        let out = std::process::Command::new("python3")
            .args(["-c", script])
            .arg(res.join(file))
            .output()
            .expect("python3 (make deps)");
        assert!(out.status.success(), "meshio cannot read {file}: {}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout).trim().to_string()
    };
    assert_eq!(types("footing_layers.vtu"), "wedge18");
    // the facets, then a vertex cell per pair (its categorical pair_status)
    assert_eq!(types("footing_layers_contact.vtu"), "triangle6 vertex");
}
