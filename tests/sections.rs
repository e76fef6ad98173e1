//! Section forces (`[[sections]]`) against statics and closed forms.
//!
//! References: the statics of a determinate beam (any mechanics text);
//! M. Hetényi, *Beams on Elastic Foundation* (1946), the free beam on a
//! Winkler foundation under a point load; Einstein & Schwartz (1979), the
//! lined circular tunnel (`src/analytic/tunnel.rs`, reused here).
//!
//! Goal: the normal force, shear and moment a cut reports balance the
//! loads on one side to round-off (so on a determinate beam they are the
//! statics' exactly, 2D and 3D, at cuts on element edges and through
//! elements); a beam on a thin elastic layer has Hetényi's moments within
//! 2 %; a tunnel lining's thrust and moment come out of a scene without
//! `[analytic]` within Einstein & Schwartz's own accuracy; a lining in rock
//! cut by a joint (which no closed form describes) reports forces that
//! balance the contact forces on the lining between two cuts to round-off
//! and agree with the hoop stress integrated through the lining.
//!
//! ```text
//!   beam2d / beam3d           beam_on_layer                tunnel (quarter)
//!        F                          P                        rock, joint at 45 deg
//!   +----v-----------+     +--------v--------+ beam            .  /
//!   |  |  |  |  |    |     +=================+ frictionless   lining
//!   o--+--+--+--+----o     |     layer       | k = E_s / h    |/ cuts at 22.5, 67.5
//!   cuts at stations       +-----------------+ held           +----
//! ```
//!
//! Parameters: beams as tests/point_loads.rs (L = 4, h = 0.4, F at a = 1);
//! the beam on the layer L = 20, d = 0.5, E = 3e4, nu = 0 on h = 0.1 of
//! E_s = 3, nu = 0 (k = 30, lambda = 0.394, lambda L = 7.9), P = 1; the
//! tunnel of geo/tunnel.toml.

mod common;

use common::{csv_num, csv_rows, json, json_vec3, repo_text, Case};
use serde_json::Value;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// The stations of section `name` in summary.json.
fn stations<'a>(summary: &'a Value, name: &str) -> &'a Vec<Value> {
    let secs = summary["sections"].as_array().expect("summary.json sections");
    let s = secs.iter().find(|s| s["name"] == name).unwrap_or_else(|| panic!("no section {name}"));
    s["stations"].as_array().expect("stations")
}

/// The reaction force of support `group`.
fn reaction(summary: &Value, group: &str) -> [f64; 3] {
    let s = summary["reactions"]["supports"].as_array().expect("reactions");
    json_vec3(&s.iter().find(|r| r["group"] == group).expect("support")["force"])
}

/// The force and moment about `at` on the part behind a cut (x < x0) of a
/// determinate beam from the forces on it (position, force): minus theirs.
fn statics(behind: &[([f64; 3], [f64; 3])], at: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let (mut f, mut m) = ([0.0; 3], [0.0; 3]);
    for &(x, p) in behind {
        let r = [x[0] - at[0], x[1] - at[1], x[2] - at[2]];
        let rm = cross(r, p);
        for i in 0..3 {
            f[i] -= p[i];
            m[i] -= rm[i];
        }
    }
    (f, m)
}

/// Every station's force and moment equal the statics of the part behind
/// it (`forces`: position and force, loads and the supports' reactions),
/// to 1e-9 of `scale` (force) and `scale` times `span` (moment). A force on
/// the cut counts half to each side where the cut has material on both,
/// and belongs to the section on an end face (at the beam's start: the
/// part behind it is the support's side). Returns the stations checked.
fn assert_statics(s: &Value, name: &str, forces: &[([f64; 3], [f64; 3])], scale: f64, span: f64) -> usize {
    let mut checked = 0;
    for st in stations(s, name) {
        let at = json_vec3(&st["at"]);
        let on_cut = if st["sides"] == "both" {
            0.5
        } else if at[0] < 0.5 * span {
            1.0
        } else {
            0.0
        };
        // the cut is normal to x: what lies behind it is x < at.x
        let behind: Vec<([f64; 3], [f64; 3])> = forces
            .iter()
            .filter_map(|&(x, p)| {
                let w = if (x[0] - at[0]).abs() <= 1e-9 { on_cut } else { f64::from(x[0] < at[0]) };
                (w > 0.0).then(|| (x, p.map(|v| v * w)))
            })
            .collect();
        let (f, m) = statics(&behind, at);
        let (got_f, got_m) = (json_vec3(&st["force"]), json_vec3(&st["moment"]));
        for i in 0..3 {
            assert!((got_f[i] - f[i]).abs() < 1e-9 * scale, "{name} at {at:?}: force {got_f:?}, statics {f:?}");
            assert!((got_m[i] - m[i]).abs() < 1e-9 * scale * span, "{name} at {at:?}: moment {got_m:?}, statics {m:?}");
        }
        checked += 1;
    }
    checked
}

/// A beam scene (as in tests/point_loads.rs) with sections.
fn beam_scene(dim: usize, extra: &str) -> String {
    let (mesh, analysis, supports, load) = if dim == 2 {
        (
            "beam2d.geo",
            "plane_strain",
            "[[supports]]\ngroup = \"pin\"\nfix = [\"x\", \"y\"]\n\n[[supports]]\ngroup = \"roller\"\nfix = [\"y\"]\n",
            "[[loads]]\ngroup = \"load\"\nforce = [3.0, -10.0]\n",
        )
    } else {
        (
            "beam3d.geo",
            "solid",
            "[[supports]]\ngroup = \"A\"\nfix = [\"x\", \"y\", \"z\"]\n\n[[supports]]\ngroup = \"B\"\nfix = [\"x\", \"z\"]\n\n[[supports]]\ngroup = \"C\"\nfix = [\"z\"]\n",
            "[[loads]]\ngroup = \"load\"\nforce = [0.0, 2.0, -10.0]\n",
        )
    };
    format!(
        "title = \"beam\"\nmesh = \"{mesh}\"\nanalysis = \"{analysis}\"\n\n[gmsh]\norder = 2\n\n[materials.m]\nE = 1000.0\nnu = 0.25\n\n[[bodies]]\ngroup = \"beam\"\nmaterial = \"m\"\n\n{supports}\n{load}\n{extra}"
    )
}

/// 2D: a simply supported beam, a point force (3, -10) at (1, 0.4): the
/// beam cut at 41 stations (on element edges, one through the load point)
/// and one line through the middle of an element carry the statics of the
/// part behind each cut, to 1e-9.
#[test]
fn cuts_of_a_determinate_beam_carry_its_statics_in_2d() {
    let case = Case::new("sections-statics-2d");
    case.copy("tests/geo/beam2d.geo");
    let extra = "[[sections]]\nname = \"beam\"\nbeam = \"beam\"\nstations = 41\n\n[[sections]]\nname = \"x2.25\"\nfrom = [2.25, 0.0]\nto = [2.25, 0.4]\n";
    let scene = case.write("beam.toml", &beam_scene(2, extra));
    case.run(&scene).unwrap_or_else(|e| panic!("{e:#}"));
    let s = json(&case.out("beam").join("summary.json"));
    let (pin, roller) = (reaction(&s, "pin"), reaction(&s, "roller"));
    let forces = [([0.0, 0.0, 0.0], pin), ([1.0, 0.4, 0.0], [3.0, -10.0, 0.0]), ([4.0, 0.0, 0.0], roller)];
    assert_eq!(assert_statics(&s, "beam", &forces, 10.0, 4.0), 41);
    assert_eq!(assert_statics(&s, "x2.25", &forces, 10.0, 4.0), 1);
    // in the beam's own terms: N = -3 then 0, V = R_pin then -R_roller, M = R x
    for st in stations(&s, "beam") {
        let x = json_vec3(&st["at"])[0];
        let (n, v, m) = (st["N"].as_f64().unwrap(), st["V"].as_f64().unwrap(), st["M"].as_f64().unwrap());
        if (x - 1.0).abs() < 1e-9 {
            // the load's node counts half to each side
            assert!((v - 0.5 * (pin[1] - roller[1])).abs() < 1e-9 * 10.0 && (n + 0.5 * pin[0]).abs() < 1e-9 * 10.0);
            continue;
        }
        let m_exact = if x <= 1.0 { pin[1] * x - pin[0] * 0.2 } else { roller[1] * (4.0 - x) };
        assert!((m - m_exact).abs() < 1e-9 * 40.0, "M at x = {x}: {m} vs {m_exact}");
        if x > 0.0 && x < 4.0 {
            let (n_exact, v_exact) = if x < 1.0 { (-pin[0], pin[1]) } else { (0.0, -roller[1]) };
            assert!((n - n_exact).abs() < 1e-9 * 10.0 && (v - v_exact).abs() < 1e-9 * 10.0, "x = {x}: N {n}, V {v}");
        }
    }
    // the files a person reads
    let rows = csv_rows(&case.out("beam").join("sections.csv"));
    assert_eq!(rows.len(), 42);
    assert!((csv_num(&rows[20], "M") - stations(&s, "beam")[20]["M"].as_f64().unwrap()).abs() < 1e-12);
    let report = common::read(&case.out("beam").join("report.md"));
    assert!(report.contains("## Section forces") && report.contains("section_beam.svg"), "{report}");
    assert!(case.out("beam").join("section_beam.svg").is_file());
}

/// 3D: the beam on three point supports under (0, 2, -10) at (1, 0.2,
/// 0.4): plane cuts and 21 stations carry the six resultants of the
/// statics of the part behind each, torsion and lateral bending included.
#[test]
fn cuts_of_a_determinate_beam_carry_its_statics_in_3d() {
    let case = Case::new("sections-statics-3d");
    case.copy("tests/geo/beam3d.geo");
    let extra = "[[sections]]\nname = \"beam\"\nbeam = \"beam\"\nstations = 21\n\n[[sections]]\nname = \"x2.9\"\npoint = [2.9, 0.0, 0.0]\nnormal = [1.0, 0.0, 0.0]\n";
    let scene = case.write("beam.toml", &beam_scene(3, extra));
    case.run(&scene).unwrap_or_else(|e| panic!("{e:#}"));
    let s = json(&case.out("beam").join("summary.json"));
    let forces = [
        ([0.0, 0.0, 0.0], reaction(&s, "A")),
        ([0.0, 0.4, 0.0], reaction(&s, "B")),
        ([1.0, 0.2, 0.4], [0.0, 2.0, -10.0]),
        ([4.0, 0.0, 0.0], reaction(&s, "C")),
    ];
    assert_eq!(assert_statics(&s, "beam", &forces, 10.0, 4.0), 21);
    assert_eq!(assert_statics(&s, "x2.9", &forces, 10.0, 4.0), 1);
    // the moment about e3 = n x up (sagging positive) just behind the load: R x
    let st = &stations(&s, "beam")[4];
    let (x, rz) = (json_vec3(&st["at"])[0], reaction(&s, "A")[2] + reaction(&s, "B")[2]);
    assert!((st["M3"].as_f64().unwrap() - rz * x).abs() < 1e-9 * 40.0, "M3 at {x}: {}", st["M3"]);
}

/// Hetényi's free beam of length L on a Winkler foundation k under a point
/// load P at its middle: the bending moment at distance x from the load,
/// from the solution w = sum c_j f_j of EI w'''' + k w = 0 on [0, L/2]
/// (f_j = e^{±λx} cos/sin λx) with w'(0) = 0, -EI w'''(0) = -P/2 and
/// w''(L/2) = w'''(L/2) = 0 (free end); M = -EI w''.
struct Hetenyi {
    lambda: f64,
    ei: f64,
    c: [f64; 4],
}

impl Hetenyi {
    fn new(ei: f64, k: f64, l: f64, p: f64) -> Hetenyi {
        let lambda = (k / (4.0 * ei)).powf(0.25);
        let mut h = Hetenyi { lambda, ei, c: [0.0; 4] };
        let rows = [(0.0, 1, 0.0), (0.0, 3, p / (2.0 * ei)), (l / 2.0, 2, 0.0), (l / 2.0, 3, 0.0)];
        let mut a = [[0.0; 5]; 4];
        for (i, &(x, order, rhs)) in rows.iter().enumerate() {
            for j in 0..4 {
                a[i][j] = h.basis(j, x, order);
            }
            a[i][4] = rhs;
        }
        // Gaussian elimination with partial pivoting
        for col in 0..4 {
            let piv = (col..4).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs())).unwrap();
            a.swap(col, piv);
            for r in 0..4 {
                if r != col {
                    let f = a[r][col] / a[col][col];
                    for k in col..5 {
                        a[r][k] -= f * a[col][k];
                    }
                }
            }
        }
        h.c = std::array::from_fn(|j| a[j][4] / a[j][j]);
        h
    }

    /// d^order/dx^order of basis function j at x: Re or Im of
    /// (s λ)^order e^{s λ x}, s = ±1 + i.
    fn basis(&self, j: usize, x: f64, order: u32) -> f64 {
        let s = if j < 2 { (1.0, 1.0) } else { (-1.0, 1.0) };
        let (mut re, mut im) = (1.0, 0.0);
        for _ in 0..order {
            let (a, b) = (s.0 * self.lambda, s.1 * self.lambda);
            (re, im) = (re * a - im * b, re * b + im * a);
        }
        let e = (s.0 * self.lambda * x).exp();
        let (cs, sn) = ((self.lambda * x).cos(), (self.lambda * x).sin());
        let (vr, vi) = (e * (re * cs - im * sn), e * (re * sn + im * cs));
        if j.is_multiple_of(2) {
            vr
        } else {
            vi
        }
    }

    fn moment(&self, x: f64) -> f64 {
        -self.ei * (0..4).map(|j| self.c[j] * self.basis(j, x.abs(), 2)).sum::<f64>()
    }
}

/// A continuum beam on a thin layer (Winkler: k = E_s / h for nu = 0)
/// through a frictionless contact, cut at 81 stations; a uniform pressure
/// of 0.05 on the beam keeps the contact closed where Hetényi's beam would
/// pull on its foundation (on a free beam it only settles it evenly, no
/// moment):
/// the moments within 2 % of Hetényi's largest, and the closed form's own
/// checks (the infinite beam's P / (4 lambda) nearly, shear -P/2 at the load).
#[test]
fn beam_on_a_thin_layer_has_hetenyis_moments() {
    let case = Case::new("sections-hetenyi");
    case.copy("tests/geo/beam_on_layer.geo");
    let (l, d, e, es, h, p): (f64, f64, f64, f64, f64, f64) = (20.0, 0.5, 3.0e4, 3.0, 0.1, 1.0);
    let scene = format!(
        r#"title = "Beam on an elastic layer (Hetényi)"
mesh = "beam_on_layer.geo"
analysis = "plane_strain"

[gmsh]
order = 2

[materials.beam]
E = {e:?}
nu = 0.0

[materials.layer]
E = {es:?}
nu = 0.0

[[bodies]]
group = "beam"
material = "beam"

[[bodies]]
group = "layer"
material = "layer"

[[contacts]]
group = "base"

[[supports]]
group = "bottom"
fix = ["x", "y"]

[[supports]]
group = "load"
fix = ["x"]

[[loads]]
group = "load"
force = [0.0, -{p:?}]

[[loads]]
group = "top"
pressure = 0.05

[[sections]]
name = "beam"
beam = "beam"
stations = 81
"#
    );
    let path = case.write("layer.toml", &scene);
    case.run(&path).unwrap_or_else(|e| panic!("{e:#}"));
    let s = json(&case.out("layer").join("summary.json"));
    let het = Hetenyi::new(e * d.powi(3) / 12.0, es / h, l, p);
    let scale = het.moment(0.0);
    assert!((scale - p / (4.0 * het.lambda)).abs() < 0.01 * scale, "M(0) {scale} vs the infinite beam's");
    let mut worst: f64 = 0.0;
    for st in stations(&s, "beam") {
        let x = json_vec3(&st["at"])[0];
        let m = st["M"].as_f64().expect("M");
        worst = worst.max((m - het.moment(x)).abs() / scale);
    }
    assert!(worst < 0.02, "largest moment error {:.4} of max M {scale:.5}", worst);
    eprintln!("beam on a layer: largest moment error {:.3} % of M(0) = {scale:.5}", 100.0 * worst);
}

/// geo/tunnel.toml (and its full-slip twin) without `[analytic]`, with the
/// lining cut as a ring at 13 angles: thrust and moment against
/// Einstein & Schwartz built from the scene's own numbers.
#[test]
fn lining_thrust_and_moment_without_analytic_match_einstein_schwartz() {
    use subcontact::analytic::{LinedTunnel, TunnelBody, TunnelSlip};
    let case = Case::new("sections-tunnel");
    case.copy("geo/tunnel.geo");
    for (name, slip) in [("tunnel", TunnelSlip::None), ("tunnel_slip", TunnelSlip::Full)] {
        let text = repo_text(&format!("geo/{name}.toml"));
        let cut = text.find("[analytic]").expect("the shipped scene's [analytic]");
        let scene = format!("{}[[sections]]\nname = \"lining\"\nring = \"lining\"\nstations = 13\n", &text[..cut]);
        let path = case.write(&format!("{name}.toml"), &scene);
        case.run(&path).unwrap_or_else(|e| panic!("{e:#}"));
        let s = json(&case.out(name).join("summary.json"));
        let tu = LinedTunnel {
            radius: 5.0,
            thickness: 0.125,
            p: 0.6,
            k: 0.5,
            slip,
            lining: TunnelBody { group: "lining".into(), e: 25000.0, nu: 0.15 },
            ground: TunnelBody { group: "rock".into(), e: 48.0, nu: 0.34 },
            szz0: -0.306,
        };
        let (t0, t2, m2) = tu.modes();
        let (t_scale, m_scale) = (t0.abs() + t2.abs(), tu.uniform_moment().abs() + m2.abs());
        let (mut t_err, mut m_err): (f64, f64) = (0.0, 0.0);
        let st = stations(&s, "lining");
        assert_eq!(st.len(), 13);
        for row in st {
            let theta = row["position"].as_f64().unwrap().to_radians();
            let thrust = -row["N"].as_f64().unwrap();
            t_err = t_err.max((thrust - tu.thrust(theta)).abs() / t_scale);
            m_err = m_err.max((row["M"].as_f64().unwrap() - tu.moment(theta)).abs() / m_scale);
        }
        eprintln!("{name}: thrust {:.2} %, moment {:.2} % of their largest values", 100.0 * t_err, 100.0 * m_err);
        // the thin ring's thrust is ambiguous by O(t/R): the ground presses
        // on r = R + t/2, the ring is R (src/analytic/tunnel.rs): +2.1 %
        assert!(t_err < 0.025, "{name}: thrust {t_err}");
        assert!(m_err < 0.02, "{name}: moment {m_err}");
    }
}

/// The tunnel with its rock cut by a joint at 45 degrees that ends on the
/// lining (the closed form cannot describe it): the lining between the
/// cuts at 22.5 and 67.5 degrees (on element edges) balances the contact
/// forces on it to round-off, and the ring's thrust and moment agree with
/// the hoop stress integrated through the lining.
#[test]
fn lining_in_jointed_rock_reports_forces_that_balance_its_contacts() {
    let case = Case::new("sections-jointed");
    let geo = repo_text("geo/tunnel.geo");
    case.write("tunnel.geo", &format!("{geo}\nPhysical Curve(\"joint\") = {{9}};\n"));
    let text = repo_text("geo/tunnel.toml");
    let cut = text.find("[analytic]").expect("[analytic]");
    let scene = format!(
        "{}[[contacts]]\ngroup = \"joint\"\nfriction = 0.2\n\n[[sections]]\nname = \"lining\"\nring = \"lining\"\nstations = 5\n",
        &text[..cut]
    );
    let path = case.write("jointed.toml", &scene);
    let run = case.run(&path).unwrap_or_else(|e| panic!("{e:#}"));
    let c = run.contact().expect("contacts");
    assert!(c.summary.converged);
    let slipping = c.states.iter().filter(|s| s.code() == 1).count();
    assert!(slipping > 0, "the joint slips somewhere");
    let s = json(&case.out("jointed").join("summary.json"));
    let st = stations(&s, "lining");
    let halves: Vec<f64> = st.iter().map(|r| (2.0 * r["position"].as_f64().unwrap()).round()).collect();
    assert_eq!(halves, vec![0.0, 45.0, 90.0, 135.0, 180.0], "the cuts every 22.5 degrees");
    let (a, b) = (&st[1], &st[3]);
    // contact forces on the lining (body I) from 22.5 to 67.5 degrees, half on the cuts
    let mut sum = [0.0; 3];
    let mut moment = [0.0; 3];
    let at_a = json_vec3(&a["at"]);
    for row in csv_rows(&case.out("jointed").join("contact.csv")) {
        if row["contact"] != "interface" {
            continue;
        }
        let x = [csv_num(&row, "x"), csv_num(&row, "y"), 0.0];
        let th = x[1].atan2(x[0]).to_degrees();
        let w = if (th - 22.5).abs() < 1e-6 || (th - 67.5).abs() < 1e-6 {
            0.5
        } else if th > 22.5 && th < 67.5 {
            1.0
        } else {
            continue;
        };
        let (sn, area) = (csv_num(&row, "sigma_n"), csv_num(&row, "area"));
        let f: [f64; 3] = std::array::from_fn(|i| {
            let k = ["x", "y", "z"][i];
            w * area * (sn * csv_num(&row, &format!("n_{k}")) + csv_num(&row, &format!("tau_{k}")))
        });
        let m = cross([x[0] - at_a[0], x[1] - at_a[1], 0.0], f);
        for i in 0..3 {
            sum[i] += f[i];
            moment[i] += m[i];
        }
    }
    // on the part between the cuts: -F(22.5) (it lies ahead of that cut), +F(67.5), and the contacts
    let (fa, fb) = (json_vec3(&a["force"]), json_vec3(&b["force"]));
    let (ma, mb) = (json_vec3(&a["moment"]), json_vec3(&b["moment"]));
    let at_b = json_vec3(&b["at"]);
    let shift = cross([at_b[0] - at_a[0], at_b[1] - at_a[1], 0.0], fb);
    let scale = fa.iter().map(|v| v.abs()).fold(0.0, f64::max);
    // to the contact iteration's own accuracy: the lining's nodes balance
    // their pairs' forces to 2e-10 (contact.csv's 13 digits add 1e-12)
    for i in 0..2 {
        let r = -fa[i] + fb[i] + sum[i];
        assert!(r.abs() < 1e-8 * scale, "force balance {i}: {r:e} of {scale}");
    }
    let r = -ma[2] + mb[2] + shift[2] + moment[2];
    assert!(r.abs() < 1e-8 * scale * 5.0, "moment balance: {r:e}");
    eprintln!(
        "jointed lining: balance between the cuts {:.1e} (force), {r:.1e} (moment) of {scale:.3}",
        (-fa[0] + fb[0] + sum[0]).abs().max((-fa[1] + fb[1] + sum[1]).abs())
    );
    // against the hoop stress through the lining, at the same angles
    let body = run.model.bodies.iter().position(|b| b.name == "lining").expect("lining");
    let thetas: Vec<f64> = st.iter().map(|r| r["position"].as_f64().unwrap().to_radians()).collect();
    let hoop = subcontact::analytic::lining::section_forces(&run.model, &run.last().u, body, 4.9375, 5.0625, &thetas);
    let (t_scale, m_scale) = st.iter().fold((0.0f64, 0.0f64), |(t, m), r| {
        (t.max(r["N"].as_f64().unwrap().abs()), m.max(r["M"].as_f64().unwrap().abs()))
    });
    for (r, h) in st.iter().zip(&hoop) {
        let h = h.expect("the ray meets the lining");
        let (n, m) = (r["N"].as_f64().unwrap(), r["M"].as_f64().unwrap());
        assert!((-n - h.thrust).abs() < 0.005 * t_scale, "thrust at {}: {} vs {}", r["position"], -n, h.thrust);
        assert!((m - h.moment).abs() < 0.02 * m_scale, "moment at {}: {m} vs {}", r["position"], h.moment);
    }
}

/// A section that cannot be cut says what to do, before anything is solved.
#[test]
fn sections_that_cannot_be_cut_are_refused_with_what_to_do() {
    use common::cli::{says, solve_fails};
    let case = Case::new("sections-refused");
    case.copy("tests/geo/beam2d.geo");
    case.copy("tests/geo/beam3d.geo");
    let refused = |name: &str, dim: usize, section: &str, needles: &[&str]| {
        case.write(&format!("{name}.toml"), &beam_scene(dim, &format!("[[sections]]\n{section}")));
        let msg = solve_fails(&case, &format!("{name}.toml"), &format!("results/{name}"));
        says(&msg, needles);
    };
    refused(
        "two_ways",
        2,
        "name = \"a\"\nbeam = \"beam\"\nfrom = [1.0, 0.0]\nto = [1.0, 1.0]\n",
        &["sections[0]", "one way to cut"],
    );
    refused("unknown_body", 2, "name = \"a\"\nbeam = \"girder\"\n", &["sections[0].beam", "\"girder\"", "\"beam\""]);
    refused(
        "line_in_3d",
        3,
        "name = \"a\"\nfrom = [1.0, 0.0, 0.0]\nto = [1.0, 1.0, 0.0]\n",
        &["sections[0]", "point = [x, y, z]"],
    );
    refused("ring_axis_3d", 3, "name = \"a\"\nring = \"beam\"\n", &["sections[0].axis", "axis = [ax, ay, az]"]);
    refused("one_station", 2, "name = \"a\"\nbeam = \"beam\"\nstations = 1\n", &["sections[0].stations", "at least 2"]);
    refused("no_name", 2, "beam = \"beam\"\n", &["sections[0].name"]);
}
