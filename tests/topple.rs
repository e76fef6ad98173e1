//! Goodman & Bray's block on an inclined plane (Goodman, R. E. and Bray,
//! J. W., 1976, "Toppling of rock slopes"; Hoek & Bray, *Rock Slope
//! Engineering*, ch. 9): a block of width b (down the plane) and height h
//! on a plane inclined at theta topples when b/h < tan(theta), whatever its
//! friction, and slides when tan(phi) < tan(theta).
//!
//! Goal (issue 29): on both sides of b/h = tan(theta), in 2D and 3D,
//! through the gmsh CLI and the real binary with `[safety]`:
//! (1) b/h = 0.30 < tan 20 = 0.364 with tan(phi) = 0.84: the scene fails as
//! given and the mechanism is named toppling, about the block's toe; the
//! message advises nothing friction or cohesion could do; the results are
//! written (blocks.csv says "toppling", mechanism.png); (2) b/h = 0.45 > tan
//! 20: the block stands; blocks.csv gives its toppling margin (b/h) /
//! tan(theta) within 1 %, and strength reduction finds it sliding at
//! F = tan(phi) / tan(theta) within 1 %.
//!
//! ```text
//!            g (turned by theta: x is down the plane)
//!          \ |      +--+
//!           \|      |  | h     block b x h (x w in 3D)
//!            v      |  |
//!         +---------+==+---------+  "joint", tan(phi) = 0.84
//!         |         base          |  held at its bottom
//!         +-----------------------+
//! ```
//!
//! Parameters: h = 2, b = 0.6 and 0.9, w = 1 (3D), theta = 20 degrees,
//! density 1, g = 10, E = 1000, nu = 0.25; tests/geo/topple.geo with 4
//! quadratic elements across the block (hex20 in 3D, two layers along z).

mod common;

use common::cli::says;
use common::{csv_num, csv_rows, json, read, Case};

const THETA: f64 = 20.0;
const TAN_PHI: f64 = 0.84;
const H: f64 = 2.0;

/// The block b x h on the plane at theta, with a `[safety]` search.
fn scene(b: f64, solid: bool) -> String {
    let (s, c) = THETA.to_radians().sin_cos();
    let (gravity, analysis, fix) = if solid {
        (format!("[{}, {}, 0.0]", 10.0 * s, -10.0 * c), "solid", "[\"x\", \"y\", \"z\"]")
    } else {
        (format!("[{}, {}]", 10.0 * s, -10.0 * c), "plane_strain", "[\"x\", \"y\"]")
    };
    format!(
        "title = \"a block b/h = {} on a plane at {THETA} degrees\"\nmesh = \"topple.geo\"\nanalysis = \"{analysis}\"\ngravity = {gravity}\n\n\
         [gmsh]\norder = 2\nsetnumber = {{ b = {b}, h = {H}, solid = {}, n = 4 }}\n\n\
         [materials.rock]\nE = 1000.0\nnu = 0.25\ndensity = 1.0\n\n\
         [[bodies]]\ngroup = \"base\"\nmaterial = \"rock\"\n\n[[bodies]]\ngroup = \"block\"\nmaterial = \"rock\"\n\n\
         [[contacts]]\ngroup = \"joint\"\nfriction = {TAN_PHI}\n\n\
         [[supports]]\ngroup = \"base_bottom\"\nfix = {fix}\n\n[safety]\n",
        b / H,
        i32::from(solid)
    )
}

/// blocks.csv's row of the block (the second body).
fn block_row(case: &Case, out: &str) -> std::collections::HashMap<String, String> {
    let rows = csv_rows(&case.dir.join(out).join("blocks.csv"));
    rows.into_iter().find(|r| r["body"] == "block").expect("the block's row")
}

#[test]
fn a_slender_block_topples_and_is_named_so_in_2d_and_3d() {
    let case = Case::new("topple-slender");
    case.copy("tests/geo/topple.geo");
    let b = 0.6;
    assert!(b / H < THETA.to_radians().tan(), "b/h below tan(theta): it topples");
    for solid in [false, true] {
        let dim = if solid { "3D" } else { "2D" };
        let name = format!("slender{dim}.toml");
        case.write(&name, &scene(b, solid));
        let out = format!("slender{dim}");
        let o = case.cli(&["solve", &name, "--out", &out, "--quiet"]);
        let msg = String::from_utf8_lossy(&o.stderr).trim().to_string();
        assert_eq!(o.status.code(), Some(1), "{dim}: it fails as given:\n{msg}");
        assert!(msg.starts_with("error: ") && !msg.contains("\n\n") && !msg.contains("panicked"), "{msg}");
        let about = if solid {
            "\"block\" topples about the edge through (0.600, 0.000, "
        } else {
            "\"block\" topples about its corner at (0.600, 0.000)"
        };
        says(
            &msg,
            &[
                "unsafe as given",
                about,
                "friction and cohesion cannot stop it",
                "No strength of its contacts makes it stand",
            ],
        );
        for wrong in ["Raise the friction", "raise the friction", "against sliding"] {
            assert!(!msg.contains(wrong), "{dim}: advice that cannot help ({wrong:?}):\n{msg}");
        }
        let summary = json(&case.dir.join(&out).join("summary.json"));
        let m = &summary["safety"]["failure"]["mechanism"];
        assert_eq!(m["kind"], "toppling", "{dim}");
        if solid {
            // the axis along the toe edge (z), turning down the plane
            let axis = m["blocks"][0]["rotation"].as_array().expect("rotation");
            let (ax, az) = (axis[0].as_f64().unwrap_or(1.0), axis[2].as_f64().unwrap_or(0.0));
            assert!(ax.abs() < 1e-6 * az.abs() && az < 0.0, "{dim}: about -z: {axis:?}");
        }
        assert_eq!(block_row(&case, &out)["state"], "toppling", "{dim}: blocks.csv");
        for f in ["blocks.csv", "mechanism.png", "report.md", &format!("slender{dim}.vtu")] {
            assert!(case.dir.join(&out).join(f).is_file(), "{dim}: {f} written");
        }
        says(&read(&case.dir.join(&out).join("report.md")), &["**Mechanism: toppling.**", "## Blocks"]);
    }
}

#[test]
fn a_stout_block_stands_with_its_toppling_margin_and_slides_at_tan_phi_over_tan_theta() {
    let case = Case::new("topple-stout");
    case.copy("tests/geo/topple.geo");
    let b = 0.9;
    let tan = THETA.to_radians().tan();
    assert!(b / H > tan, "b/h above tan(theta): it stands");
    for solid in [false, true] {
        let dim = if solid { "3D" } else { "2D" };
        let name = format!("stout{dim}.toml");
        case.write(&name, &scene(b, solid));
        let out = format!("stout{dim}");
        let o = case.cli(&["solve", &name, "--out", &out, "--quiet"]);
        assert!(o.status.success(), "{dim}: {}", String::from_utf8_lossy(&o.stderr));
        let row = block_row(&case, &out);
        let margin = csv_num(&row, "toppling_margin");
        let exact = b / H / tan;
        eprintln!("{dim}: toppling margin {margin:.5} against (b/h) / tan(theta) = {exact:.5}");
        assert!((margin / exact - 1.0).abs() < 0.01, "{dim}: margin {margin} against {exact}");
        assert_eq!(row["state"], "held");
        let s = json(&case.dir.join(&out).join("summary.json"))["safety"].clone();
        let f = s["factor"].as_f64().expect("F");
        eprintln!("{dim}: sliding F = {f:.5} against tan(phi) / tan(theta) = {:.5}", TAN_PHI / tan);
        assert!((f / (TAN_PHI / tan) - 1.0).abs() < 0.01, "{dim}: F = {f}");
        assert_eq!(s["failure"]["mechanism"]["kind"], "sliding");
        let at_f = csv_rows(&case.dir.join(&out).join("safety_blocks.csv"));
        assert!(at_f.iter().any(|r| r["body"] == "block" && r["state"] == "sliding"), "{dim}: at F the block slides");
    }
}
