//! The load factor search (`[safety] load = [..]`, issue 34 item 3): the
//! chosen loads are raised by a factor F until equilibrium is lost, and F,
//! the mechanism and the last state that holds are reported, through the
//! gmsh CLI and the real binary, against rigid-body statics of a gravity
//! wall.
//!
//! Reference: a rectangular gravity wall B x Hw of unit weight gamma on a
//! joint of friction tan(phi), pushed by a uniform horizontal traction t
//! on its back (H = t Hw at mid-height); W = gamma B Hw:
//!
//! ```text
//!   overturning about the toe    F_o = M_r / M_o = (W B / 2) / (H Hw / 2)
//!   sliding on the base          F_s = W tan(phi) / H
//!
//!      t -->  +-----+
//!      t -->  |wall |  Hw = 4
//!      t -->  |     |
//!        +----+=====+----+  "base", tan(phi)
//!        |       rock    |          toe at (B, 0)
//! ```
//!
//! Goal: (1) tan(phi) = 1: the wall tips about its toe at F_o within 1 %
//! (named toppling about (B, 0)), and its toppling margin at F = 1 in
//! blocks.csv is F_o too; (2) tan(phi) = 0.4: it slides at F_s within 1 %;
//! (3) ten times the load: unsafe as given, F_o / 10 found below 1, results
//! written; (4) the keys: a load that is not a [[loads]] group, and
//! `load` beside `reduce`, are errors that say what to do.
//!
//! Parameters (geo/wall.{geo,toml}): B = 2, Hw = 4, gamma = 2.4 x 9.81,
//! t = 10 kPa, concrete E = 30 GPa on rock E = 20 GPa, quad9.

mod common;

use common::cli::{clean_failure, says};
use common::scenes::edited;
use common::{csv_num, csv_rows, json, Case};
use serde_json::Value;

const B: f64 = 2.0;
const HW: f64 = 4.0;
const GAMMA: f64 = 2.4 * 9.81;
const T: f64 = 10.0;

fn w() -> f64 {
    GAMMA * B * HW
}

/// Runs geo/wall.toml with `edits` into `out`; its summary's `safety`.
fn wall(case: &Case, name: &str, edits: &[(&str, &str)]) -> (Value, std::process::Output) {
    case.write(&format!("{name}.toml"), &edited("geo/wall.toml", edits));
    let o = case.cli(&["solve", &format!("{name}.toml"), "--out", name, "--quiet"]);
    let summary = case.dir.join(name).join("summary.json");
    let s = if summary.is_file() { json(&summary)["safety"].clone() } else { Value::Null };
    (s, o)
}

fn assert_near(what: &str, f: f64, exact: f64) {
    eprintln!("{what}: F = {f:.5} against {exact:.5}: {:+.3} %", 100.0 * (f / exact - 1.0));
    assert!((f / exact - 1.0).abs() < 0.01, "{what}: F = {f} against {exact}");
}

#[test]
fn a_gravity_wall_tips_about_its_toe_at_mr_over_mo_and_slides_at_w_tan_phi_over_h() {
    let case = Case::new("load-factor-wall");
    case.copy("geo/wall.geo");
    let h = T * HW;
    let overturning = (w() * B / 2.0) / (h * HW / 2.0);
    let sliding = |tan_phi: f64| w() * tan_phi / h;

    let (s, o) = wall(&case, "tips", &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    says(
        &String::from_utf8_lossy(&o.stdout),
        &["load factor (raising \"back\") F = 2.35", "topples about its corner at (2.000, 0.000)"],
    );
    assert_eq!(s["kind"], "load");
    assert_near("overturning", s["factor"].as_f64().expect("F"), overturning);
    assert!(sliding(1.0) > overturning, "sliding does not govern with tan(phi) = 1");
    let m = &s["failure"]["mechanism"];
    assert_eq!((m["kind"].as_str(), m["blocks"][0]["name"].as_str()), (Some("toppling"), Some("wall")));
    let pivot = m["blocks"][0]["pivot"].as_array().expect("pivot");
    assert!(
        (pivot[0].as_f64().unwrap_or(0.0) - B).abs() < 1e-9 && pivot[1].as_f64().unwrap_or(1.0).abs() < 1e-9,
        "about the toe: {pivot:?}"
    );
    let rows = csv_rows(&case.dir.join("tips/blocks.csv"));
    let at_one = rows.iter().find(|r| r["body"] == "wall").expect("the wall's row");
    assert_near("toppling margin at F = 1", csv_num(at_one, "toppling_margin"), overturning);

    let (s, o) = wall(&case, "slides", &[("friction = 1.0", "friction = 0.4")]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_near("sliding", s["factor"].as_f64().expect("F"), sliding(0.4));
    assert_eq!(s["failure"]["mechanism"]["kind"], "sliding");

    // ten times the load: unsafe as given, F below 1 from the start
    let (s, o) = wall(&case, "pushed", &[("traction = [10.0, 0.0]", "traction = [100.0, 0.0]")]);
    let msg = String::from_utf8_lossy(&o.stderr).trim().to_string();
    assert_eq!(o.status.code(), Some(1), "{msg}");
    says(
        &msg,
        &[
            "unsafe as given",
            "with its loads as given (F = 1)",
            "Its load factor is below 1: F = 0.23",
            "topples about its corner",
        ],
    );
    assert_near("overturning, below 1", s["factor"].as_f64().expect("F"), overturning / 10.0);
    assert_eq!(s["below_one"].as_bool(), Some(true));
}

#[test]
fn the_load_factor_keys_say_what_to_do() {
    let case = Case::new("load-factor-keys");
    case.copy("geo/wall.geo");
    let (_, o) = wall(&case, "unknown", &[("load = [\"back\"]", "load = [\"front\"]")]);
    let msg = clean_failure(&case, &o, &case.dir.join("unknown"));
    says(&msg, &["safety.load[0]", "\"front\"", "is not the group of a [[loads]] entry", "\"back\", \"gravity\""]);
    let (_, o) = wall(&case, "both", &[("load = [\"back\"]", "load = [\"back\"]\nreduce = [\"friction\"]")]);
    let msg = clean_failure(&case, &o, &case.dir.join("both"));
    says(&msg, &["safety.reduce", "a search does one or the other"]);
}
