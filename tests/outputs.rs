//! The result files of real runs (DESIGN.md §4, "Outputs"), read back the way
//! users read them: the VTU files through Python meshio (as ParaView would
//! open them), `contact.csv`, `summary.json` and `report.md` as text. The
//! default cylinder (plane strain, quad9, lc = 0.05, 81 contact pairs, all
//! stuck) is solved once by the real binary and shared by the tests; the
//! paper's 30-hexahedron cylinder checks the 3D files. Besides the promised
//! names, shapes and cell types, the values must agree with each other and
//! with Lamé's closed form: von_mises is von Mises of the stress field, the
//! displacement at every node equals u_r = (1+nu) k/E ((1-2nu) r + b^2/r) with
//! k = p a^2/(b^2-a^2) to 1e-6 relative, and contact.csv carries the same
//! sigma_n, tau, gap and slip as the contact VTU. Finally the mesh cache: a
//! second run reuses the mesh, a changed `setnumber` remeshes.

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use common::{json, read, repo_text, Case};
use serde_json::Value;

/// What meshio reads from a VTU file.
struct Vtu {
    points: Vec<[f64; 3]>,
    /// (meshio cell type, connectivity of each cell)
    cells: Vec<(String, Vec<Vec<usize>>)>,
    point_data: HashMap<String, Vec<Vec<f64>>>,
    /// cell data of all blocks, concatenated
    cell_data: HashMap<String, Vec<f64>>,
}

const MESHIO_DUMP: &str = r#"
import json, sys
try:
    import meshio
except ImportError:
    print("Python package meshio is missing: run `make deps` (or python3 -m pip install meshio)", file=sys.stderr)
    sys.exit(3)
m = meshio.read(sys.argv[1])
def rows(a):
    a = a.tolist()
    return [r if isinstance(r, list) else [r] for r in a]
json.dump({
    "points": m.points.tolist(),
    "cells": [[c.type, c.data.tolist()] for c in m.cells],
    "point_data": {k: rows(v) for k, v in m.point_data.items()},
    "cell_data": {k: [x for block in v for x in block.tolist()] for k, v in m.cell_data.items()},
}, sys.stdout)
"#;

/// Reads a VTU with meshio; fails with a clear message when meshio is missing.
fn meshio(path: &Path) -> Vtu {
    let out = Command::new("python3")
        .arg("-c")
        .arg(MESHIO_DUMP)
        .arg(path)
        .output()
        .expect("python3 must be installed to read the VTU files (make deps)");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() != Some(3), "{}", stderr.trim());
    assert!(out.status.success(), "meshio cannot read {}:\n{stderr}", path.display());
    let v: Value = serde_json::from_slice(&out.stdout).expect("meshio dump is JSON");
    let floats =
        |a: &Value| -> Vec<f64> { a.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect() };
    Vtu {
        points: v["points"].as_array().unwrap().iter().map(|p| floats(p).try_into().expect("3 coordinates")).collect(),
        cells: v["cells"]
            .as_array()
            .unwrap()
            .iter()
            .map(|b| {
                (
                    b[0].as_str().unwrap().to_string(),
                    b[1].as_array().unwrap().iter().map(|c| floats(c).iter().map(|&n| n as usize).collect()).collect(),
                )
            })
            .collect(),
        point_data: v["point_data"]
            .as_object()
            .unwrap()
            .iter()
            .map(|(k, a)| (k.clone(), a.as_array().unwrap().iter().map(floats).collect()))
            .collect(),
        cell_data: v["cell_data"].as_object().unwrap().iter().map(|(k, a)| (k.clone(), floats(a))).collect(),
    }
}

impl Vtu {
    /// Point field `name`, checked to have `n_comp` components at every point.
    fn field(&self, name: &str, n_comp: usize) -> &Vec<Vec<f64>> {
        let f = self
            .point_data
            .get(name)
            .unwrap_or_else(|| panic!("no point data `{name}`; have {:?}", self.point_data.keys().collect::<Vec<_>>()));
        assert_eq!(f.len(), self.points.len(), "`{name}` has a value per point");
        assert!(f.iter().all(|v| v.len() == n_comp), "`{name}` must have {n_comp} components");
        assert!(f.iter().flatten().all(|x| x.is_finite()), "`{name}` has non-finite values");
        f
    }
}

/// One run of a scene through the binary, with its result files read.
struct Results {
    dir: PathBuf,
    stdout: String,
    summary: Value,
    csv: Vec<HashMap<String, f64>>,
    csv_header: String,
}

/// Copies `geo/<stem>.geo` and `.toml` into a case and solves with the binary.
fn solve(case_name: &str, stem: &str) -> Results {
    let case = Case::new(case_name);
    case.copy(&format!("geo/{stem}.geo"));
    case.copy(&format!("geo/{stem}.toml"));
    let out = case.cli(&["solve", &format!("{stem}.toml"), "--out", "out", "--quiet"]);
    assert!(out.status.success(), "solve {stem} failed: {}", String::from_utf8_lossy(&out.stderr));
    let dir = case.dir.join("out");
    let summary = json(&dir.join("summary.json"));
    let text = read(&dir.join("contact.csv"));
    let mut lines = text.lines();
    let csv_header = lines.next().expect("contact.csv header").to_string();
    let names: Vec<&str> = csv_header.split(',').collect();
    // every column a number but the contact's name
    let csv = lines
        .map(|l| {
            (names.iter().zip(l.split(',')))
                .filter(|(k, _)| **k != "contact")
                .map(|(k, v)| (k.to_string(), v.parse::<f64>().unwrap_or_else(|_| panic!("contact.csv: {k} = {v:?}"))))
                .collect()
        })
        .collect();
    Results { dir, stdout: String::from_utf8_lossy(&out.stdout).into_owned(), summary, csv, csv_header }
}

/// The default cylinder, solved once for all tests of this file.
fn cylinder() -> &'static Results {
    static RUN: OnceLock<Results> = OnceLock::new();
    RUN.get_or_init(|| solve("outputs-cylinder", "cylinder"))
}

/// The bodies VTU of the default cylinder, read once.
fn cylinder_vtu() -> &'static Vtu {
    static VTU: OnceLock<Vtu> = OnceLock::new();
    VTU.get_or_init(|| meshio(&cylinder().dir.join("cylinder.vtu")))
}

/// The summary's value at a dotted path, which must exist.
fn at<'a>(v: &'a Value, path: &str) -> &'a Value {
    path.split('.').fold(v, |v, k| v.get(k).unwrap_or_else(|| panic!("summary.json lacks `{path}`")))
}

// Lamé's cylinder of the scene: a = 3, b = 5, p = 0.1, E = 2e5, nu = 0.167, plane strain.
const A: f64 = 3.0;
const B: f64 = 5.0;
const P: f64 = 0.1;
const E: f64 = 2.0e5;
const NU: f64 = 0.167;

fn lame_k() -> f64 {
    P * A * A / (B * B - A * A)
}

/// Plane-strain radial displacement.
fn lame_u_r(r: f64) -> f64 {
    (1.0 + NU) * lame_k() / E * ((1.0 - 2.0 * NU) * r + B * B / r)
}

fn lame_sigma_theta(r: f64) -> f64 {
    lame_k() * (1.0 + B * B / (r * r))
}

fn von_mises(s: &[f64]) -> f64 {
    let (xx, yy, zz, xy, yz, xz) = (s[0], s[1], s[2], s[3], s[4], s[5]);
    (0.5 * ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2)) + 3.0 * (xy * xy + yz * yz + xz * xz)).sqrt()
}

#[test]
fn bodies_vtu_has_displacement_stress_von_mises_body_and_stays_quad9() {
    let r = cylinder();
    let m = cylinder_vtu();
    assert_eq!(m.cells.len(), 1, "one cell block");
    let (kind, cells) = &m.cells[0];
    assert_eq!(kind, "quad9", "order-2 quadrilaterals must stay quad9 (VTK 28)");
    assert_eq!(cells.len() as u64, at(&r.summary, "mesh.elements").as_u64().unwrap());
    m.field("displacement", 3);
    m.field("stress", 6);
    m.field("von_mises", 1);
    let body = &m.cell_data["body"];
    assert_eq!(body.len(), cells.len());
    let n1 = body.iter().filter(|&&b| b == 1.0).count();
    assert!(body.iter().all(|&b| b == 0.0 || b == 1.0), "body ids are 0 and 1");
    assert_eq!(2 * n1, cells.len(), "the 45-degree cut halves the quarter");
    // VTK node order of quad9: corners, then the mid-edge nodes of 0-1, 1-2,
    // 2-3, 3-0, then the centre (the arcs make midpoints inexact by ~1e-4).
    for c in cells {
        let x = |i: usize| m.points[c[i]];
        let mid = |i: usize, j: usize| [(x(i)[0] + x(j)[0]) / 2.0, (x(i)[1] + x(j)[1]) / 2.0];
        let dist = |p: [f64; 3], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
        let h = dist(x(0), [x(2)[0], x(2)[1]]);
        for (k, (i, j)) in [(0, 1), (1, 2), (2, 3), (3, 0)].into_iter().enumerate() {
            assert!(
                dist(x(4 + k), mid(i, j)) < 0.05 * h,
                "quad9 cell {c:?}: node {} is not the midpoint of edge {i}-{j}",
                4 + k
            );
        }
        assert!(dist(x(8), mid(0, 2)) < 0.05 * h, "quad9 cell {c:?}: node 8 is not the centre");
    }
    assert!(m.points.iter().all(|p| p[2] == 0.0), "a plane mesh lies in z = 0");
    assert!(r.stdout.contains("81 stick / 0 slip / 0 open"), "{}", r.stdout);
}

#[test]
fn von_mises_field_is_von_mises_of_the_stress_field() {
    let m = cylinder_vtu();
    let stress = m.field("stress", 6);
    let vm = m.field("von_mises", 1);
    let scale = vm.iter().map(|v| v[0]).fold(0.0, f64::max);
    assert!(scale > 0.0);
    for (i, (s, v)) in stress.iter().zip(vm).enumerate() {
        assert!(
            (von_mises(s) - v[0]).abs() <= 1e-12 * scale,
            "point {i}: von_mises {} but the stress {s:?} gives {}",
            v[0],
            von_mises(s)
        );
    }
    // plane strain: szz = nu (sxx + syy), no out-of-plane shear
    for s in stress {
        assert!((s[2] - NU * (s[0] + s[1])).abs() <= 1e-9 * scale && s[4] == 0.0 && s[5] == 0.0, "{s:?}");
    }
}

#[test]
fn vtu_displacement_equals_the_lame_closed_form_at_every_node() {
    let m = cylinder_vtu();
    let u = m.field("displacement", 3);
    let scale = lame_u_r(A);
    let mut worst: f64 = 0.0;
    for (x, u) in m.points.iter().zip(u) {
        let r = x[0].hypot(x[1]);
        let ur = lame_u_r(r);
        let err = (u[0] - ur * x[0] / r).hypot(u[1] - ur * x[1] / r) + u[2].abs();
        worst = worst.max(err / scale);
    }
    assert!(worst < 1e-6, "displacement differs from Lamé by {worst:.2e} (relative to u_r(a))");
    // nodal stresses, averaged per body: sigma_r and sigma_theta to 0.1 % of p
    let s = m.field("stress", 6);
    let mut worst: f64 = 0.0;
    for (x, s) in m.points.iter().zip(s) {
        let r = x[0].hypot(x[1]);
        let (c, sn) = (x[0] / r, x[1] / r);
        let sr = s[0] * c * c + s[1] * sn * sn + 2.0 * s[3] * sn * c;
        let st = s[0] * sn * sn + s[1] * c * c - 2.0 * s[3] * sn * c;
        let k = lame_k();
        worst = worst.max((sr - k * (1.0 - B * B / (r * r))).abs()).max((st - lame_sigma_theta(r)).abs());
    }
    assert!(worst < 1e-3 * P, "nodal stress differs from Lamé by {worst:.2e} (p = {P})");
}

#[test]
fn contact_csv_has_the_promised_header_and_one_row_per_pair() {
    let r = cylinder();
    // the promised columns first, then the ones added since (area, global
    // shear vector; the pair's normal, its contact group and its two blocks)
    assert_eq!(
        r.csv_header,
        "pair,x,y,z,status,sigma_n,tau_t,tau_b,gap,slip,area,tau_x,tau_y,tau_z,n_x,n_y,n_z,contact,block_i,block_ii,law_residual"
    );
    let text = std::fs::read_to_string(r.dir.join("contact.csv")).expect("contact.csv");
    assert!(text.lines().skip(1).all(|l| l.split(',').nth(17) == Some("A-A")), "every pair is on contact A-A");
    let pairs = at(&r.summary, "contact.pairs").as_u64().unwrap() as usize;
    assert_eq!(pairs, 81, "lc = 0.05 puts 81 nodes on A-A");
    assert_eq!(r.csv.len(), pairs, "one row per pair");
    for (i, row) in r.csv.iter().enumerate() {
        assert_eq!(row["pair"], i as f64);
        let rr = row["x"].hypot(row["y"]);
        assert!(
            (row["x"] - row["y"]).abs() < 1e-9 && (A - 1e-9..=B + 1e-9).contains(&rr),
            "pair {i} is not on the 45-degree cut: {row:?}"
        );
        assert_eq!(row["status"], 2.0, "all pairs stick");
        // the outward normal of body I (the first listed, below the cut): (-1, 1) / sqrt 2
        let h = 0.5f64.sqrt();
        assert!(
            (row["n_x"] + h).abs() < 1e-9 && (row["n_y"] - h).abs() < 1e-9 && row["n_z"] == 0.0,
            "pair {i}: normal {row:?}"
        );
        assert_eq!((row["block_i"], row["block_ii"]), (0.0, 1.0), "pair {i}: body I is the first listed");
        // tension positive: the cut carries sigma_theta > 0
        let th = lame_sigma_theta(rr);
        assert!(
            (row["sigma_n"] - th).abs() < 1e-3 * th,
            "pair {i} at r = {rr}: sigma_n {} vs Lamé {th}",
            row["sigma_n"]
        );
        assert!(
            row["tau_t"].abs() < 1e-6 * th
                && row["tau_b"] == 0.0
                && row["gap"].abs() < 1e-12
                && row["slip"].abs() < 1e-12,
            "{row:?}"
        );
    }
}

#[test]
fn contact_vtu_has_the_promised_fields_and_matches_contact_csv() {
    let r = cylinder();
    let m = meshio(&r.dir.join("cylinder_contact.vtu"));
    assert_eq!(m.cells.len(), 2, "the facets, then a vertex cell per pair");
    assert_eq!(m.cells[0].0, "line3", "the quadratic interface stays quadratic");
    assert_eq!(m.cells[0].1.len(), 40);
    assert_eq!(m.cells[1].0, "vertex");
    assert_eq!(m.cells[1].1.len(), r.csv.len());
    let mut names: Vec<&str> = m.point_data.keys().map(|k| k.as_str()).collect();
    names.sort();
    assert_eq!(names, ["area", "gap", "law_residual", "shear", "sigma_n", "slip", "status", "tau"]);
    let (status, sigma_n, tau, gap, slip) =
        (m.field("status", 1), m.field("sigma_n", 1), m.field("tau", 1), m.field("gap", 1), m.field("slip", 1));
    let law = m.field("law_residual", 1);
    assert_eq!(m.points.len(), r.csv.len(), "one point per pair");
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-11 * (1.0 + a.abs().max(b.abs()));
    for (i, x) in m.points.iter().enumerate() {
        let row = r
            .csv
            .iter()
            .find(|row| {
                (row["x"] - x[0]).abs() < 1e-9 && (row["y"] - x[1]).abs() < 1e-9 && (row["z"] - x[2]).abs() < 1e-9
            })
            .unwrap_or_else(|| panic!("contact VTU point {x:?} is no pair of contact.csv"));
        assert_eq!(status[i][0], row["status"], "status at {x:?}");
        assert!(
            close(sigma_n[i][0], row["sigma_n"]),
            "sigma_n at {x:?}: VTU {} vs CSV {}",
            sigma_n[i][0],
            row["sigma_n"]
        );
        assert!(close(tau[i][0], row["tau_t"].hypot(row["tau_b"])), "tau at {x:?}");
        assert!(close(gap[i][0], row["gap"]) && close(slip[i][0], row["slip"]), "gap/slip at {x:?}");
        // (the CSV keeps 7 digits of the residual)
        let (a, b) = (law[i][0], row["law_residual"]);
        assert!((a - b).abs() <= 1e-6 * a.abs().max(b.abs()), "law_residual at {x:?}: VTU {a:e} vs CSV {b:e}");
    }
}

#[test]
fn summary_json_has_the_promised_keys_with_consistent_values() {
    let r = cylinder();
    let s = &r.summary;
    assert_eq!(at(s, "analysis"), "plane_strain", "the scene's spelling");
    assert_eq!(at(s, "mesh.cached"), &Value::Bool(false), "a fresh case meshes");
    let pairs = at(s, "contact.pairs").as_u64().unwrap();
    // both sides of each pair, 2 DOFs per node
    assert_eq!(at(s, "dofs.interface").as_u64().unwrap(), 2 * 2 * pairs);
    assert!(at(s, "dofs.total").as_u64().unwrap() > at(s, "dofs.interface").as_u64().unwrap());
    let it = at(s, "contact.iterations").as_u64().unwrap();
    assert!((1..=2).contains(&it), "stuck from the start: 1 or 2 iterations, got {it}");
    assert_eq!(at(s, "contact.converged"), &Value::Bool(true));
    let states: Vec<u64> =
        ["stick", "slip", "open"].iter().map(|k| at(s, &format!("contact.states.{k}")).as_u64().unwrap()).collect();
    assert_eq!(states, [pairs, 0, 0]);
    let total = at(s, "timings_s.total").as_f64().unwrap();
    for k in ["mesh", "assemble", "condense", "interface", "recover", "output"] {
        let t = at(s, &format!("timings_s.{k}")).as_f64().unwrap();
        assert!(t >= 0.0 && t <= total, "timings_s.{k} = {t}, total {total}");
    }
    assert!(at(s, "errors.displacement_l2").as_f64().unwrap() < 1e-6);
    assert!(at(s, "errors.stress_l2").as_f64().unwrap() < 1e-3);
    assert!(at(s, "errors.contact_max").as_f64().unwrap() < 1e-3);
    let radial = at(s, "probes.radial").as_array().expect("probes.radial is a list");
    assert_eq!(radial.len(), 5, "points = 5");
    for p in radial {
        assert_eq!(p["found"], Value::Bool(true), "{p}");
        let x: Vec<f64> = p["x"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let u: Vec<f64> = p["displacement"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let rr = x[0].hypot(x[1]);
        assert!((u[0].hypot(u[1]) - lame_u_r(rr)).abs() < 1e-6 * lame_u_r(A), "probe at r = {rr}: {u:?}");
        assert_eq!(p["stress"].as_array().unwrap().len(), 6);
    }
}

#[test]
fn report_md_has_the_scene_the_iterations_the_states_and_the_papers_tables() {
    let r = cylinder();
    let text = read(&r.dir.join("report.md"));
    for needle in [
        "# Thick-walled cylinder, quarter model cut at 45 degrees",
        "cylinder.toml`, analysis plane_strain, mesh",
        "| contact iterations | 1 (converged) |",
        "| states stick / slip / open | 81 / 0 / 0 |",
        "## Table 1",
        "## Table 2",
        "| 3.2 | -8.11 | -8.00 |",
        "19.28",
        "| 5.0 | 11.25 | 10.55 |",
        "## Probe `radial`",
    ] {
        assert!(text.contains(needle), "report.md lacks {needle:?}:\n{text}");
    }
    let table =
        |title: &str| text.split(title).nth(1).unwrap().lines().skip(4).take_while(|l| l.starts_with('|')).count();
    assert_eq!(table("## Table 1"), 5, "Table 1 has the paper's 5 radii");
    assert_eq!(table("## Table 2"), 6, "Table 2 has the paper's 6 radii");
}

#[test]
fn paper_mesh_writes_30_hex8_and_12_contact_pairs() {
    let r = solve("outputs-paper", "cylinder_paper");
    let m = meshio(&r.dir.join("cylinder_paper.vtu"));
    assert_eq!(m.cells.len(), 1);
    assert_eq!(m.cells[0].0, "hexahedron");
    assert_eq!(m.cells[0].1.len(), 30);
    let u = m.field("displacement", 3);
    m.field("stress", 6);
    m.field("von_mises", 1);
    assert!(u.iter().all(|u| u[2].abs() < 1e-12 * lame_u_r(A)), "w = 0 on both z faces of one element layer");
    let c = meshio(&r.dir.join("cylinder_paper_contact.vtu"));
    assert_eq!(c.cells[0].0, "quad");
    assert_eq!(c.cells[0].1.len(), 5, "5 radial facets on A-A");
    assert_eq!((c.cells[1].0.as_str(), c.cells[1].1.len()), ("vertex", 12), "a vertex cell per pair");
    assert_eq!(r.csv.len(), 12, "the paper's 12 contact node pairs");
    assert_eq!(c.points.len(), 12);
    assert_eq!(at(&r.summary, "dofs.interface").as_u64().unwrap(), 2 * 3 * 12);
    assert_eq!(at(&r.summary, "contact.states.stick").as_u64().unwrap(), 12);
    let text = read(&r.dir.join("report.md"));
    assert!(text.contains("## Table 1") && text.contains("## Table 2"), "{text}");
}

#[test]
fn mesh_is_reused_on_a_second_run_and_remade_when_setnumber_changes() {
    let case = Case::new("outputs-cache");
    case.copy("geo/cylinder.geo");
    let base = repo_text("geo/cylinder.toml");
    assert!(base.contains("lc = 0.05"), "geo/cylinder.toml changed: update this test");
    let run = |lc: &str| -> Value {
        case.write("cylinder.toml", &base.replace("lc = 0.05", lc));
        let out = case.cli(&["solve", "cylinder.toml", "--out", "out", "--quiet"]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        json(&case.dir.join("out/summary.json"))
    };
    let msh = case.dir.join("out/mesh/cylinder.msh");
    let first = run("lc = 0.2");
    assert_eq!(at(&first, "mesh.cached"), &Value::Bool(false), "the first run meshes");
    let stamp = std::fs::metadata(&msh).unwrap().modified().unwrap();
    let second = run("lc = 0.2");
    assert_eq!(at(&second, "mesh.cached"), &Value::Bool(true), "the second run reuses the mesh");
    assert_eq!(std::fs::metadata(&msh).unwrap().modified().unwrap(), stamp, "the cached .msh is not rewritten");
    assert_eq!(at(&second, "mesh.nodes"), at(&first, "mesh.nodes"));
    let third = run("lc = 0.25");
    assert_eq!(at(&third, "mesh.cached"), &Value::Bool(false), "a new lc remeshes");
    assert!(
        at(&third, "mesh.nodes").as_u64().unwrap() < at(&first, "mesh.nodes").as_u64().unwrap(),
        "lc = 0.25 is coarser than 0.2"
    );
    let report = read(&case.dir.join("out/report.md"));
    assert!(!report.contains("(cached)"), "report.md of the remeshed run says cached");
}

/// Issue 19: ParaView blends point data `status` between 0, 1 and 2; a
/// vertex cell per pair carries it as cell data `pair_status`, which
/// ParaView colours as categories (-1 on the facets). Read back through
/// meshio for every pair of the default cylinder, against contact.csv.
#[test]
fn contact_vtu_has_a_categorical_status_on_a_vertex_cell_per_pair() {
    let r = cylinder();
    let m = meshio(&r.dir.join("cylinder_contact.vtu"));
    let status = m.cell_data.get("pair_status").expect("cell data pair_status");
    let facets = m.cells[0].1.len();
    assert_eq!(status.len(), facets + r.csv.len());
    assert!(status[..facets].iter().all(|&s| s == -1.0), "-1 on the facets");
    for (cell, &s) in m.cells[1].1.iter().zip(&status[facets..]) {
        let x = m.points[cell[0]];
        let row = r
            .csv
            .iter()
            .find(|row| (row["x"] - x[0]).abs() < 1e-9 && (row["y"] - x[1]).abs() < 1e-9)
            .expect("a pair of contact.csv");
        assert_eq!(s, row["status"], "pair at {x:?}");
    }
    let interface = m.cell_data.get("interface").expect("cell data interface");
    assert!(interface.iter().all(|&i| i == 0.0), "one contact");
}

/// Issue 19 on the 2D dam (self-weight, then the reservoir in two steps):
/// the `.pvd` times are the load factors (the reservoir's 0, 0.5, 1), the
/// load-step table of report.md shows the factors applied per load, its
/// timings are summary.json's, and `check` counts the DOFs the run solved.
#[test]
fn dam_steps_report_their_factors_and_the_report_the_summarys_timings() {
    let case = Case::new("outputs-dam");
    case.copy("geo/dam.geo");
    case.copy("geo/dam.toml");
    let out = case.cli(&["solve", "dam.toml", "--out", "out", "--quiet"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let dir = case.dir.join("out");
    for pvd in ["dam.pvd", "dam_contact.pvd"] {
        let text = read(&dir.join(pvd));
        let times: Vec<&str> = text.split("timestep=\"").skip(1).map(|t| t.split('"').next().unwrap_or("")).collect();
        assert_eq!(times, ["0.0", "0.5", "1.0"], "{pvd}:\n{text}");
    }
    // each step's contact file carries the states as categories
    let m = meshio(&dir.join("dam_contact_step001.vtu"));
    assert!(m.cell_data["pair_status"].contains(&2.0));

    let report = read(&dir.join("report.md"));
    for row in [
        "| step | gravity | \"upstream_face\", \"reservoir_floor\" | iterations | stick / slip / open | converged |",
        "| 1 | 1 | 0 | ",
        "| 2 | 1 | 0.5 | ",
        "| 3 | 1 | 1 | ",
    ] {
        assert!(report.contains(row), "report.md lacks {row:?}:\n{report}");
    }
    assert!(!report.contains("ramp k/N"));
    let summary = json(&dir.join("summary.json"));
    let steps = summary["steps"].as_array().expect("steps");
    assert_eq!(
        steps[1]["case_factors"].as_array().map(|a| a.len()),
        Some(5),
        "ramp, two loads, gravity, initial stress"
    );
    // the timings row of report.md, to its three decimals, is summary.json's
    let t = &summary["timings_s"];
    let want: Vec<String> = ["mesh", "model", "assemble", "condense", "interface", "recover", "output", "total"]
        .iter()
        .map(|k| format!("{:.3}", t[k].as_f64().expect("a timing")))
        .collect();
    let row = format!(
        "| time mesh / model / assemble / condense / interface / recover / output / total (s) | {} |",
        want.join(" / ")
    );
    assert!(report.contains(&row), "report.md lacks {row:?}:\n{report}");
    assert!(t["output"].as_f64().unwrap() > 0.0, "the output stage is timed");

    let check = case.cli(&["check", "dam.toml"]);
    let stdout = String::from_utf8_lossy(&check.stdout);
    assert!(check.status.success(), "{}", String::from_utf8_lossy(&check.stderr));
    let dofs = format!("  {} DOFs ({} interface)", summary["dofs"]["total"], summary["dofs"]["interface"]);
    assert!(stdout.contains(&dofs), "check prints {dofs:?}:\n{stdout}");
}

/// Issue 19: two bodies that share nodes with no contact between them are
/// bonded, and the user hears of it: summary.json `warnings`, report.md,
/// stderr of solve and check. The two blocks of tests/geo/contact_stack.geo
/// without their [[contacts]] entry; with it, `solve --bonded` bonds them
/// on purpose and warns of nothing.
#[test]
fn bodies_bonded_without_a_contact_are_warned_of() {
    let case = Case::new("outputs-bonded");
    case.copy("tests/geo/contact_stack.geo");
    case.write(
        "glued.toml",
        "mesh = \"contact_stack.geo\"\nanalysis = \"plane_stress\"\n[materials.m]\nE = 1000.0\nnu = 0.25\n\
         [[bodies]]\ngroup = \"bottom\"\nmaterial = \"m\"\n[[bodies]]\ngroup = \"top\"\nmaterial = \"m\"\n\
         [[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n[[supports]]\ngroup = \"corner\"\nfix = [\"x\"]\n\
         [[loads]]\ngroup = \"top_face\"\ntraction = [0.0, -1.0]\n",
    );
    let out = case.cli(&["solve", "glued.toml", "--out", "out", "--quiet"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let says = "bodies \"bottom\" and \"top\" share";
    assert!(
        stderr.contains(&format!("warning: glued.toml: {says}")) && stderr.contains("so they are bonded there"),
        "{stderr}"
    );
    let summary = json(&case.dir.join("out/summary.json"));
    let warnings: Vec<&str> =
        summary["warnings"].as_array().expect("warnings").iter().filter_map(|w| w.as_str()).collect();
    assert!(
        warnings.len() == 1 && warnings[0].contains(says) && warnings[0].contains("add a [[contacts]] entry"),
        "{warnings:?}"
    );
    let report = read(&case.dir.join("out/report.md"));
    assert!(report.contains(&format!("**Warning:** glued.toml: {says}")), "{report}");
    let check = case.cli(&["check", "glued.toml"]);
    assert!(String::from_utf8_lossy(&check.stderr).contains(says));

    // `solve --bonded` bonds the scene's contact on purpose: nothing to warn of
    let text = read(&case.dir.join("glued.toml")) + "[[contacts]]\ngroup = \"joint\"\nfriction = 0.5\n";
    case.write("jointed.toml", &text);
    let out = case.cli(&["solve", "jointed.toml", "--out", "bonded", "--quiet", "--bonded"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !stderr.contains("warning"), "no warning of a bond asked for: {stderr}");
    let summary = json(&case.dir.join("bonded/summary.json"));
    assert_eq!(summary["warnings"].as_array().map(|a| a.len()), Some(0), "{}", summary["warnings"]);
}
