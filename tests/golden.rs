//! Golden summaries: a handful of the repository's fast scenes solved by
//! the real binary, and what their summary.json and contact.csv say
//! compared with tests/golden/<case>.json: the interface solver, the DOFs,
//! the pairs and every step's contact states exactly, every step's
//! iteration count within a range, and the key forces and stresses (the
//! contact groups' forces, the supports' reactions, the peak contact
//! pressure, shear, gap and slip) within a relative tolerance of their
//! size. A refactor that must not change answers is checked by
//! `cargo test --release --test golden`.
//!
//! A change that moves answers on purpose writes the files again with
//! `GOLDEN_UPDATE=1 cargo test --release --test golden` (iteration ranges
//! are then the count ± 1); the commit says why, and the diff of
//! tests/golden/ shows what moved.

mod common;

use common::{csv_num, csv_rows, json, repo_root, Case};
use serde_json::{json, Map, Value};
use std::path::Path;

/// Relative tolerance of the values, of each vector's norm.
const RTOL: f64 = 1e-6;

/// Values below this fraction of a scene's largest golden value are its
/// round-off: they are compared on that scale, not their own.
const ROUND_OFF: f64 = 1e-9;

/// Solves `scene` (a repository path) with `args`, and checks (or writes,
/// with GOLDEN_UPDATE=1) tests/golden/<name>.json.
fn golden(name: &str, scene: &str, args: &[&str]) {
    let case = Case::new(&format!("golden-{name}"));
    let out = case.dir.join("out");
    let scene_path = repo_root().join(scene);
    let mut cli = vec!["solve", scene_path.to_str().expect("utf-8 path"), "--quiet", "--out"];
    cli.push(out.to_str().expect("utf-8 path"));
    cli.extend_from_slice(args);
    let o = case.cli(&cli);
    // an unconverged run (the paper's rule cycling) is pinned too: it fails
    // but writes its last iteration, converged = false
    let wrote = out.join("summary.json").exists();
    assert!(o.status.success() || wrote, "{name}: {}", String::from_utf8_lossy(&o.stderr));
    let got = record(scene, args, &out);
    let file = repo_root().join("tests/golden").join(format!("{name}.json"));
    if std::env::var_os("GOLDEN_UPDATE").is_some() {
        let text = serde_json::to_string_pretty(&got).expect("json") + "\n";
        std::fs::write(&file, text).expect("write the golden file");
        return;
    }
    assert!(file.exists(), "{name}: no {} (GOLDEN_UPDATE=1 writes it)", file.display());
    compare(name, &json(&file), &got);
}

/// What a run is checked by.
fn record(scene: &str, args: &[&str], out: &Path) -> Value {
    let s = json(&out.join("summary.json"));
    let steps = s["steps"].as_array().expect("steps");
    let iterations: Vec<Value> = (steps.iter().map(|st| st["contact"]["iterations"].as_i64().unwrap_or(0)))
        .map(|n| json!([(n - 1).max(0), n + 1]))
        .collect();
    let mut values = Map::new();
    for g in s["contact"]["groups"].as_array().into_iter().flatten() {
        let name = g["name"].as_str().unwrap_or("?");
        values.insert(format!("group {name} force"), g["force"].clone());
        values.insert(format!("group {name} mobilised_max"), json!([g["mobilised_max"]]));
    }
    for r in s["reactions"]["supports"].as_array().into_iter().flatten() {
        let name = r["group"].as_str().unwrap_or("?");
        values.insert(format!("support {name} force"), r["force"].clone());
        values.insert(format!("support {name} moment"), r["moment"].clone());
    }
    peaks(&out.join("contact.csv"), &mut values);
    json!({
        "scene": scene,
        "args": args,
        "exact": {
            "interface_solver": s["interface_solver"],
            "dofs": s["dofs"],
            "pairs": s["contact"]["pairs"],
            "converged": s["contact"]["converged"],
            "states": steps.iter().map(|st| st["contact"]["states"].clone()).collect::<Vec<_>>(),
        },
        "iterations": iterations,
        "values": values,
    })
}

/// The peak contact pressure (most negative sigma_n), shear, gap and slip
/// of the last step's pairs.
fn peaks(csv: &Path, values: &mut Map<String, Value>) {
    if !csv.exists() {
        return;
    }
    let rows = csv_rows(csv);
    let peak =
        |f: &dyn Fn(&std::collections::HashMap<String, String>) -> f64| rows.iter().map(f).fold(0.0f64, f64::max);
    values.insert("peak pressure".into(), json!([peak(&|r| -csv_num(r, "sigma_n"))]));
    values.insert("peak shear".into(), json!([peak(&|r| csv_num(r, "tau_t").hypot(csv_num(r, "tau_b")))]));
    values.insert("peak gap".into(), json!([peak(&|r| csv_num(r, "gap").abs())]));
    values.insert("peak slip".into(), json!([peak(&|r| csv_num(r, "slip").abs())]));
}

/// Fails naming every difference of `got` from the golden `want`.
fn compare(name: &str, want: &Value, got: &Value) {
    let mut wrong = Vec::new();
    if want["exact"] != got["exact"] {
        wrong.push(format!("exact: want {}, got {}", want["exact"], got["exact"]));
    }
    let got_its: Vec<i64> =
        (got["iterations"].as_array().into_iter().flatten()).map(|r| r[1].as_i64().unwrap_or(0) - 1).collect();
    let ranges = want["iterations"].as_array().cloned().unwrap_or_default();
    let inside = ranges.len() == got_its.len()
        && ranges.iter().zip(&got_its).all(|(r, n)| r[0].as_i64() <= Some(*n) && Some(*n) <= r[1].as_i64());
    if !inside {
        wrong.push(format!("iterations {got_its:?} outside {}", want["iterations"]));
    }
    let (want_v, got_v) = (want["values"].as_object(), got["values"].as_object());
    let keys: Vec<&String> = want_v.into_iter().chain(got_v).flat_map(|m| m.keys()).collect();
    // a value that is round-off of the scene's largest (a support that
    // carries nothing: 1e-13 of 393 MN) is compared against that
    let largest = keys.iter().flat_map(|k| nums(&want["values"][*k])).fold(0.0f64, |m, x| m.max(x.abs()));
    for key in keys {
        let (a, b) = (nums(&want["values"][key]), nums(&got["values"][key]));
        let size = a.iter().chain(&b).fold(ROUND_OFF * largest, |m, x| m.max(x.abs()));
        let far = a.len() != b.len() || a.iter().zip(&b).any(|(x, y)| (x - y).abs() > RTOL * size);
        if far {
            wrong.push(format!("{key}: want {a:?}, got {b:?}"));
        }
    }
    wrong.dedup();
    assert!(wrong.is_empty(), "{name} differs from tests/golden/{name}.json:\n  {}", wrong.join("\n  "));
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array().into_iter().flatten().filter_map(Value::as_f64).collect()
}

#[test]
fn footing() {
    golden("footing", "geo/footing.toml", &[]);
}

#[test]
fn footing_bonded() {
    golden("footing_bonded", "geo/footing.toml", &["--bonded"]);
}

#[test]
fn dam() {
    golden("dam", "geo/dam.toml", &[]);
}

#[test]
fn block_push() {
    golden("block_push", "geo/block_push.toml", &[]);
}

#[test]
fn block_push_paper_rule() {
    golden("block_push_paper", "scripts/regress/block_push_paper.toml", &[]);
}

#[test]
fn cylinder_paper_mesh() {
    golden("cylinder_paper", "geo/cylinder_paper.toml", &[]);
}

#[test]
fn tunnel_joints() {
    golden("tunnel_joints", "geo/tunnel_joints.toml", &[]);
}

#[test]
fn stack() {
    golden("stack", "geo/stack.toml", &[]);
}
