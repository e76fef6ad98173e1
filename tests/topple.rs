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
//! quadratic elements across the block (hex20 in 3D, two layers along z);
//! the scene is tests/common/slopes.rs's.

mod common;

use common::csv_num;
use common::slopes::topple::{self, block_row, scene, H, TAN_PHI, THETA};
use common::{csv_rows, json};

#[test]
fn a_slender_block_topples_and_is_named_so_in_2d_and_3d() {
    let case = topple::case("topple-slender");
    for solid in [false, true] {
        topple::assert_topples(&case, if solid { "slender3D" } else { "slender2D" }, solid, "");
    }
}

#[test]
fn a_stout_block_stands_with_its_toppling_margin_and_slides_at_tan_phi_over_tan_theta() {
    let case = topple::case("topple-stout");
    let b = 0.9;
    let tan = THETA.to_radians().tan();
    assert!(b / H > tan, "b/h above tan(theta): it stands");
    for solid in [false, true] {
        let dim = if solid { "3D" } else { "2D" };
        let name = format!("stout{dim}.toml");
        case.write(&name, &scene(b, solid, ""));
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
