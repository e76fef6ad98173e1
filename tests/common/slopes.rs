//! Two rock slopes with closed forms, solved by several test files with
//! rigid joints and with joints that deform (tests/planar_slide.rs,
//! tests/topple.rs, tests/joint_stiffness_engineer.rs): [`planar`], Hoek &
//! Bray's planar slide held by its cohesion, and [`topple`], Goodman &
//! Bray's block on an inclined plane. Each scene takes its joint's extra
//! `[[contacts]]` lines (a residual cohesion, the joint's stiffness:
//! [`super::scenes::springs`]).

/// Hoek & Bray's planar failure with a tension crack in the upper slope
/// surface (Rock Slope Engineering), written from the figures
/// (tests/geo/planar_slide.geo):
///
///   F = (c A + (W cos psi - U - V sin psi) tan phi) / (W sin psi + V cos psi)
///
/// H = 20 m, face 70 degrees, plane psi = 35 degrees, crack z = 6 m deep
/// with z_w = 4 m of water, c = 50 kPa, phi = 30 degrees, rock 2.6 t/m3
/// (units kN, m, kPa), E = 1e7 kPa.
pub mod planar {
    use super::super::Case;

    pub const H: f64 = 20.0;
    pub const FACE: f64 = 70.0;
    pub const PSI: f64 = 35.0;
    pub const Z: f64 = 6.0;
    pub const Z_W: f64 = 4.0;
    pub const C: f64 = 50.0;
    pub const PHI: f64 = 30.0;
    pub const GAMMA: f64 = 2.6 * 9.81;
    pub const GW: f64 = 9.81;
    /// `[safety] tolerance` of the scenes.
    pub const TOL: f64 = 1.0e-4;
    /// The plane's water: from the crack's level to nothing at the toe.
    pub const PLANE_WATER: &str = "water = { face = \"crack_face\", downstream = 0.0, along = [-1.0, 0.0] }";

    /// A case with the slope's geometry copied in.
    pub fn case(tag: &str) -> Case {
        let case = Case::new(tag);
        case.copy("tests/geo/planar_slide.geo");
        case
    }

    /// The scene: `contact` the plane's extra lines (a residual cohesion,
    /// springs), `water` its water (or none), `crack` whether the crack
    /// holds water.
    pub fn scene(contact: &str, water: &str, crack: bool) -> String {
        let (steps, load) = if crack {
            (
                "load_steps = 2\ngravity_factors = [1.0, 1.0]",
                format!(
                    "[[loads]]\ngroup = \"crack_face\"\npressure = {{ surface = {}, unit_weight = {GW} }}\nfactors = [0.0, 1.0]\n",
                    H - Z + Z_W
                ),
            )
        } else {
            ("load_steps = 1", String::new())
        };
        format!(
            "title = \"Planar slide\"\nmesh = \"planar_slide.geo\"\nanalysis = \"plane_strain\"\ngravity = [0.0, -9.81]\n\n\
             [gmsh]\norder = 2\nsetnumber = {{ lc = 1.0 }}\n\n\
             [materials.rock]\nE = 1.0e7\nnu = 0.25\ndensity = 2.6\n\n\
             [[bodies]]\ngroup = \"block\"\nmaterial = \"rock\"\n\n[[bodies]]\ngroup = \"ground\"\nmaterial = \"rock\"\n\n\
             [[contacts]]\ngroup = \"slide\"\nfriction = {}\ncohesion = {C}\n{contact}\n{water}\n\n\
             [[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\"]\n\n[[supports]]\ngroup = \"sides\"\nfix = [\"x\"]\n\n\
             {load}\n[solver]\n{steps}\n\n[safety]\ntolerance = {TOL}\n",
            PHI.to_radians().tan()
        )
    }

    /// The cohesion kept where the plane slips: the plane's line.
    pub fn kept() -> String {
        format!("residual_cohesion = {C}")
    }

    /// The block's weight W and the plane's length A, from the figures.
    pub fn block() -> (f64, f64) {
        let psi = PSI.to_radians();
        let xc = (H - Z) / psi.tan();
        let pts = [[0.0, 0.0], [xc, H - Z], [xc, H], [H / FACE.to_radians().tan(), H]];
        let area = 0.5 * (0..4).map(|i| pts[i][0] * pts[(i + 1) % 4][1] - pts[(i + 1) % 4][0] * pts[i][1]).sum::<f64>();
        (area * GAMMA, (H - Z) / psi.sin())
    }

    /// The water forces: U = 1/2 gw z_w A on the plane, V = 1/2 gw z_w^2
    /// in the crack.
    pub fn water_forces() -> (f64, f64) {
        let (_, a) = block();
        (0.5 * GW * Z_W * a, 0.5 * GW * Z_W * Z_W)
    }

    /// Hoek & Bray's F with the water forces U (plane) and V (crack).
    pub fn hoek_bray(u: f64, v: f64) -> f64 {
        let (w, a) = block();
        let (psi, f) = (PSI.to_radians(), PHI.to_radians().tan());
        (C * a + (w * psi.cos() - u - v * psi.sin()) * f) / (w * psi.sin() + v * psi.cos())
    }

    /// The three waters: (name, the plane's water line, whether the crack
    /// holds water, Hoek & Bray's F): dry, V, U and V.
    pub fn waters() -> [(&'static str, &'static str, bool, f64); 3] {
        let (u, v) = water_forces();
        [
            ("dry", "", false, hoek_bray(0.0, 0.0)),
            ("crack", "", true, hoek_bray(0.0, v)),
            ("wet", PLANE_WATER, true, hoek_bray(u, v)),
        ]
    }
}

/// Goodman & Bray's block of width b (down the plane) and height h on a
/// plane inclined at theta (tests/geo/topple.geo, 4 quadratic elements
/// across the block, hex20 in 3D): it topples when b/h < tan(theta),
/// whatever its friction. h = 2, w = 1 (3D), theta = 20 degrees, tan(phi)
/// = 0.84, density 1, g = 10, E = 1000, nu = 0.25.
pub mod topple {
    use std::collections::HashMap;

    use super::super::cli::says;
    use super::super::{csv_rows, json, read, Case};

    pub const THETA: f64 = 20.0;
    pub const TAN_PHI: f64 = 0.84;
    pub const H: f64 = 2.0;

    /// A case with the block's geometry copied in.
    pub fn case(tag: &str) -> Case {
        let case = Case::new(tag);
        case.copy("tests/geo/topple.geo");
        case
    }

    /// The block b x h on the plane at theta, with a `[safety]` search;
    /// `joint` the joint's extra lines (springs).
    pub fn scene(b: f64, solid: bool, joint: &str) -> String {
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
             [[contacts]]\ngroup = \"joint\"\nfriction = {TAN_PHI}\n{joint}\n\n\
             [[supports]]\ngroup = \"base_bottom\"\nfix = {fix}\n\n[safety]\n",
            b / H,
            i32::from(solid)
        )
    }

    /// blocks.csv's row of the block (the second body).
    pub fn block_row(case: &Case, out: &str) -> HashMap<String, String> {
        let rows = csv_rows(&case.dir.join(out).join("blocks.csv"));
        rows.into_iter().find(|r| r["body"] == "block").expect("the block's row")
    }

    /// Solves the slender block b = 0.6 (b/h below tan(theta)) with `joint`
    /// as `name` (2D or 3D): it fails as given, named toppling about its
    /// toe (the corner at x = b, the edge along -z in 3D), the advice
    /// naming no strength, the results written. Returns the summary.
    pub fn assert_topples(case: &Case, name: &str, solid: bool, joint: &str) -> serde_json::Value {
        let b = 0.6;
        assert!(b / H < THETA.to_radians().tan(), "b/h below tan(theta): it topples");
        let dim = if solid { "3D" } else { "2D" };
        case.write(&format!("{name}.toml"), &scene(b, solid, joint));
        let o = case.cli(&["solve", &format!("{name}.toml"), "--out", name, "--quiet"]);
        let msg = String::from_utf8_lossy(&o.stderr).trim().to_string();
        assert_eq!(o.status.code(), Some(1), "{dim}: it fails as given:\n{msg}");
        assert!(msg.starts_with("error: ") && !msg.contains("\n\n") && !msg.contains("panicked"), "{msg}");
        let about = if solid {
            "\"block\" topples about the edge through (0.600, 0.000, "
        } else {
            "\"block\" topples about its corner at (0.600, 0.000)"
        };
        let helps = ["friction and cohesion cannot stop it", "No strength of its contacts makes it stand"];
        says(&msg, &["unsafe as given", about, helps[0], helps[1]]);
        for wrong in ["Raise the friction", "raise the friction", "against sliding"] {
            assert!(!msg.contains(wrong), "{dim}: advice that cannot help ({wrong:?}):\n{msg}");
        }
        let summary = json(&case.dir.join(name).join("summary.json"));
        let m = &summary["safety"]["failure"]["mechanism"];
        assert_eq!(m["kind"], "toppling", "{dim}");
        if solid {
            // the axis along the toe edge (z), turning down the plane
            let axis = m["blocks"][0]["rotation"].as_array().expect("rotation");
            let (ax, az) = (axis[0].as_f64().unwrap_or(1.0), axis[2].as_f64().unwrap_or(0.0));
            assert!(ax.abs() < 1e-6 * az.abs() && az < 0.0, "{dim}: about -z: {axis:?}");
        }
        assert_eq!(block_row(case, name)["state"], "toppling", "{dim}: blocks.csv");
        for f in ["blocks.csv", "mechanism.png", "report.md", &format!("{name}.vtu")] {
            assert!(case.dir.join(name).join(f).is_file(), "{dim}: {f} written");
        }
        says(&read(&case.dir.join(name).join("report.md")), &["**Mechanism: toppling.**", "## Blocks"]);
        summary
    }
}
