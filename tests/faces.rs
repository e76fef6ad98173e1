//! Resultants per contact group and per block face pair (issue 17, item 5):
//! summary.json's `contact.groups` and `contact.faces`, `faces.csv`, and
//! report.md's tables, on the jointed column of tests/junctions.rs.
//!
//! ```text
//!   push on top (x), gravity (-z)      a 2 x 2 x 2 cube of eight unit blocks
//!        -->  +-------+-------+        (tests/geo/cross3d.geo, hex20) cut by
//!            /   b6  /  b7   /|        jx: x = 1, jy: y = 1, jz: z = 1,
//!           +-------+-------+ |        fixed at its base z = 0
//!          /   b4  /   b5  /| +
//!         +-------+-------+ |/|
//!         |  b0   |  b1   | + |
//!         +-------+-------+/
//! ```
//!
//! Goals, each asserted:
//! - the group jz carries the weight of the four blocks above it and the
//!   whole push, F = (4 q, 0, -4 rho g), to 1e-8; N = -4 rho g and T = 4 q
//!   in its mean frame n = +z; its area is 4 and each of its four face
//!   pairs has area 1;
//! - every upper block is in equilibrium under the resultants of its face
//!   pairs (+F where it is side I, -F where it is side II), its weight and
//!   the push on its top, to 1e-8: the face pairs are the forces between
//!   blocks;
//! - faces.csv's face pairs add up to summary.json's groups, and each face
//!   pair is the sum of its rows of contact.csv;
//! - report.md lists every group and the face pairs;
//! - on the paper's cylinder, the cut's one face pair carries the pressure
//!   on body 1's arc (F_x, to rounding) and Lamé's hoop force N = p a.

mod common;

use common::Case;

const RHO: f64 = 2.5e-3;
const G: f64 = 9.81;
const PUSH: f64 = 0.005;

#[test]
fn face_pairs_carry_the_forces_between_blocks_and_add_up_to_their_groups() {
    let case = Case::new("faces-column");
    case.copy("tests/geo/cross3d.geo");
    let text = format!(
        "title = \"jointed column\"\nmesh = \"cross3d.geo\"\nanalysis = \"solid\"\ngravity = [0.0, 0.0, -{G}]\n\n\
         [gmsh]\norder = 2\nsetnumber = {{ hex = 1, n = 2, serendipity = 1 }}\n\n\
         [materials.rock]\nE = 1000.0\nnu = 0.25\ndensity = {RHO}\n\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n\n\
         [[contacts]]\ngroup = \"jx\"\nfriction = 0.6\n\n[[contacts]]\ngroup = \"jy\"\nfriction = 0.6\n\n[[contacts]]\ngroup = \"jz\"\nfriction = 0.6\n\n\
         [[supports]]\ngroup = \"z0\"\nfix = [\"x\", \"y\", \"z\"]\n\n[[loads]]\ngroup = \"z1\"\ntraction = [{PUSH}, 0.0, 0.0]\n"
    );
    let run = case.run(&case.write("column.toml", &text)).unwrap_or_else(|e| panic!("column: {e:#}"));
    let out = case.out("column");
    let summary = common::json(&out.join("summary.json"));
    let groups = summary["contact"]["groups"].as_array().expect("contact.groups");
    assert_eq!(groups.len(), 3, "one entry per contact group");
    let weight = RHO * G * 4.0;
    let scale = weight.hypot(4.0 * PUSH);

    // the joint plane z = 1 carries the weight above it and the push
    let jz = groups.iter().find(|g| g["name"] == "jz").expect("jz");
    let f = common::json_vec3(&jz["force"]);
    let want = [4.0 * PUSH, 0.0, -weight];
    let err = (0..3).map(|i| (f[i] - want[i]).abs()).fold(0.0, f64::max) / scale;
    let (n, t) = (jz["normal_force"].as_f64().expect("N"), jz["shear_force"].as_f64().expect("T"));
    eprintln!("jz: F = {f:?} against {want:?} ({err:.1e}); N = {n:.6e}, T = {t:.6e}; area {}", jz["area"]["total"]);
    assert!(err < 1e-8, "jz carries {f:?}, not {want:?}");
    let nz = common::json_vec3(&jz["normal"]);
    assert!(
        nz[0].abs() < 1e-12 && nz[1].abs() < 1e-12 && (nz[2] - 1.0).abs() < 1e-12,
        "jz's mean normal is +z (side I below): {nz:?}"
    );
    assert!((n + weight).abs() < 1e-8 * scale && (t - 4.0 * PUSH).abs() < 1e-8 * scale, "N = {n}, T = {t}");
    assert!((jz["area"]["total"].as_f64().expect("area") - 4.0).abs() < 1e-12, "jz's area is 4");
    assert_eq!(jz["face_pairs"], 4);
    let mobilised = jz["mobilised_max"].as_f64().expect("mobilised");
    assert!((0.0..=1.0).contains(&mobilised), "mobilised friction {mobilised} in [0, 1]");

    // faces.csv: the face pairs add up to their groups
    let faces = common::csv_rows(&out.join("faces.csv"));
    assert_eq!(summary["contact"]["faces"]["count"].as_u64(), Some(faces.len() as u64));
    assert_eq!(faces.len(), 12, "four face pairs per joint plane");
    for g in groups {
        let rows: Vec<_> = faces.iter().filter(|r| r["contact"] == g["name"].as_str().expect("name")).collect();
        let area: f64 = rows.iter().map(|r| common::csv_num(r, "area")).sum();
        assert!((area - g["area"]["total"].as_f64().expect("area")).abs() < 1e-12);
        for (i, k) in ["f_x", "f_y", "f_z"].iter().enumerate() {
            let sum: f64 = rows.iter().map(|r| common::csv_num(r, k)).sum();
            assert!((sum - common::json_vec3(&g["force"])[i]).abs() < 1e-12 * scale, "{}: {k}", g["name"]);
        }
        for r in &rows {
            assert!((common::csv_num(r, "area") - 1.0).abs() < 1e-12, "each face pair is a unit square: {r:?}");
        }
    }

    // ... and each face pair is the sum of its rows of contact.csv
    let pairs = common::csv_rows(&out.join("contact.csv"));
    for r in &faces {
        let mine: Vec<_> = pairs
            .iter()
            .filter(|p| p["contact"] == r["contact"] && p["block_i"] == r["block_i"] && p["block_ii"] == r["block_ii"])
            .collect();
        assert_eq!(mine.len() as f64, common::csv_num(r, "pairs"));
        let fz: f64 = mine
            .iter()
            .map(|p| {
                (common::csv_num(p, "sigma_n") * common::csv_num(p, "n_z") + common::csv_num(p, "tau_z"))
                    * common::csv_num(p, "area")
            })
            .sum();
        assert!(
            (fz - common::csv_num(r, "f_z")).abs() < 1e-10 * scale,
            "contact.csv's rows of a face pair: {fz} against {}",
            common::csv_num(r, "f_z")
        );
    }

    // every upper block is held by its faces alone: F on it + weight + push = 0
    let m = &run.model;
    let upper: Vec<usize> =
        (0..m.bodies.len()).filter(|&b| m.bodies[b].block.expect("a block").centre[2] > 1.0).collect();
    assert_eq!(upper.len(), 4);
    let mut worst: f64 = 0.0;
    for &b in &upper {
        let mut sum = [PUSH, 0.0, -RHO * G];
        for r in &faces {
            let sign = if common::csv_num(r, "block_i") as usize == b {
                1.0
            } else if common::csv_num(r, "block_ii") as usize == b {
                -1.0
            } else {
                0.0
            };
            for (i, k) in ["f_x", "f_y", "f_z"].iter().enumerate() {
                sum[i] += sign * common::csv_num(r, k);
            }
        }
        worst = sum.iter().fold(worst, |w, v| w.max(v.abs() / scale));
    }
    eprintln!("upper blocks: out of balance by {worst:.1e} of the load");
    assert!(worst < 1e-8, "an upper block is out of balance under its face pairs: {worst:.1e}");

    // report.md: every group, and the face pairs
    let report = common::read(&out.join("report.md"));
    assert!(report.contains("## Contact groups") && report.contains("## Block faces"), "report.md has the two tables");
    for name in ["jx", "jy", "jz"] {
        assert!(
            report.lines().any(|l| l.starts_with(&format!("| {name} | 4 |"))),
            "report.md's group table has {name}"
        );
    }
    assert!(report.contains("All 12 block face pairs"), "twelve face pairs, all listed");
}

/// The paper's cylinder (a = 3, b = 5, p = 0.1, quarter model cut at 45
/// degrees): the cut's face pair carries, on body 1 (0 to 45 degrees), the
/// x-component of the pressure on its arc, F_x = -p a sin 45 degrees (the
/// symmetry plane y = 0 takes only y), to rounding; and in its mean frame
/// Lamé's hoop force across a radial cut, N = p a (b free), with no shear.
#[test]
fn the_cylinders_cut_carries_the_hoop_force() {
    let case = Case::new("faces-cylinder");
    case.copy("geo/cylinder.geo");
    let text =
        common::scenes::edited("geo/cylinder.toml", &[("setnumber = { lc = 0.05 }", "setnumber = { lc = 0.2 }")]);
    case.run(&case.write("cylinder.toml", &text)).unwrap_or_else(|e| panic!("cylinder: {e:#}"));
    let faces = common::csv_rows(&case.out("cylinder").join("faces.csv"));
    assert_eq!(faces.len(), 1, "one face pair: the cut");
    let (p, a) = (0.1, 3.0);
    let f = &faces[0];
    let (fx, n, t) = (common::csv_num(f, "f_x"), common::csv_num(f, "normal_force"), common::csv_num(f, "shear_force"));
    eprintln!(
        "cylinder's cut: F_x = {fx:.12} (-p a sin 45 = {:.12}), N = {n:.8} (p a = {}), T = {t:.2e}",
        -p * a * 0.5f64.sqrt(),
        p * a
    );
    assert!((fx + p * a * 0.5f64.sqrt()).abs() < 1e-10, "F_x = {fx}");
    assert!((n - p * a).abs() < 1e-4 * p * a && t < 1e-6 * p * a, "N = {n}, T = {t}");
    assert_eq!((f["name_i"].as_str(), f["name_ii"].as_str()), ("body_1", "body_2"), "two bodies: side I is the first");
}
