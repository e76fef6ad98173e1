//! Scene texts that several test files write: a repository scene with text
//! edits, two stacked blocks meeting on a joint, Lamé's cylinder with its
//! closed form, the supports of a box of ground and a joint's springs. Each
//! returns the TOML text; the test writes it into its case.

/// The `[[supports]]` of a plane box of ground: its `bottom` group fixed,
/// its "left" and "right" sides on rollers (x fixed).
pub fn on_rollers(bottom: &str) -> String {
    format!(
        "[[supports]]\ngroup = \"{bottom}\"\nfix = [\"x\", \"y\"]\n[[supports]]\ngroup = \"left\"\nfix = [\"x\"]\n\
         [[supports]]\ngroup = \"right\"\nfix = [\"x\"]"
    )
}

/// geo/blocks3d.toml on its coarse tet10 mesh (lc = 0.2: 918 interface
/// DOFs, partial slip under the oblique push), written with its geometry
/// into the case as "blocks.toml"; returns that name.
pub fn coarse_blocks(case: &super::Case) -> &'static str {
    case.copy("geo/blocks3d.geo");
    case.write(
        "blocks.toml",
        &edited("geo/blocks3d.toml", &[("setnumber = { lc = 0.1, hex = 0 }", "setnumber = { lc = 0.2, hex = 0 }")]),
    );
    "blocks.toml"
}

/// scripts/scaling/column.toml with `edits` after its mesh path, written as
/// `name` into the case with geo/blocks3d.geo where the scene finds it.
pub fn column(case: &super::Case, name: &str, edits: &[(&str, &str)]) {
    std::fs::create_dir_all(case.dir.join("geo")).expect("geo directory");
    std::fs::copy(super::repo_root().join("geo/blocks3d.geo"), case.dir.join("geo/blocks3d.geo"))
        .expect("copy the geometry");
    let mut all = vec![("mesh = \"../../geo/blocks3d.geo\"", "mesh = \"geo/blocks3d.geo\"")];
    all.extend_from_slice(edits);
    case.write(name, &edited("scripts/scaling/column.toml", &all));
}

/// The jointed 3D tunnel with two sets (J1, J2 of
/// tests/geo/tunnel3d_joints_coarse.toml) on its kept mesh
/// tests/geo/tunnel3d_joints_2sets.msh (1,779 pairs), copied into the case;
/// returns the scene's text.
pub fn tunnel_two_sets(case: &super::Case) -> String {
    case.copy("tests/geo/tunnel3d_joints_2sets.msh");
    edited(
        "tests/geo/tunnel3d_joints_coarse.toml",
        &[
            ("mesh = \"tunnel3d_joints.geo\"", "mesh = \"tunnel3d_joints_2sets.msh\""),
            ("[gmsh]\norder = 2\nsetnumber = { lc = 2.0, lc_far = 4.0 }\n", ""),
            ("[[contacts]]\ngroup = \"J3\"\nfriction = 0.7002\n\n", ""),
        ],
    )
}

/// A contact's lines that make its joint deform: `normal_stiffness` k_n
/// and `shear_stiffness` k_s (stress per length).
pub fn springs(k_n: f64, k_s: f64) -> String {
    format!("normal_stiffness = {k_n:?}\nshear_stiffness = {k_s:?}")
}

/// `repo_toml` (e.g. "geo/cylinder.toml") with `edits` (from, to) applied in
/// turn: each `from` must occur (the test names the scene it relies on), and
/// its first occurrence is replaced.
pub fn edited(repo_toml: &str, edits: &[(&str, &str)]) -> String {
    let mut text = super::repo_text(repo_toml);
    for (from, to) in edits {
        assert!(text.contains(from), "{repo_toml} no longer contains {from:?}: update this test");
        text = text.replacen(from, to, 1);
    }
    text
}

/// Two blocks of one material stacked: "bottom" under "top", bottom listed
/// first (body I, n = +y), meeting on the contact group "joint" (the groups
/// of tests/geo/contact_stack*.geo, stress_stack.geo and mech_blocks.geo).
/// `head` opens the scene (title, mesh, analysis, `[gmsh]`), `contact` holds
/// the joint's lines and `rest` the supports and loads.
pub fn two_blocks(head: &str, e: f64, nu: f64, contact: &str, rest: &str) -> String {
    format!(
        r#"{head}

[materials.m]
E = {e:?}
nu = {nu:?}

[[bodies]]
group = "bottom"
material = "m"

[[bodies]]
group = "top"
material = "m"

[[contacts]]
group = "joint"
{contact}

{rest}"#
    )
}

/// Lamé's thick cylinder: a = 3, b = 5, pressure p = 0.1 on the group
/// "inner", E = 2e5 in every body, and `[analytic] kind = "lame_cylinder"`
/// so that the run carries its relative L2 errors. `gmsh` holds the lines of
/// the `[gmsh]` table, `supports` (group, fixed components) pairs.
pub fn lame_cylinder(
    title: &str,
    mesh: &str,
    analysis: &str,
    gmsh: &str,
    nu: f64,
    bodies: &[&str],
    supports: &[(&str, &str)],
) -> String {
    let mut s = format!("title = \"{title}\"\nmesh = \"{mesh}\"\nanalysis = \"{analysis}\"\n\n[gmsh]\n{gmsh}\n\n[materials.m]\nE = 2.0e5\nnu = {nu:?}\n");
    for body in bodies {
        s += &format!("\n[[bodies]]\ngroup = \"{body}\"\nmaterial = \"m\"\n");
    }
    for (group, fix) in supports {
        s += &format!("\n[[supports]]\ngroup = \"{group}\"\nfix = {fix}\n");
    }
    s + "\n[[loads]]\ngroup = \"inner\"\npressure = 0.1\n\n[analytic]\nkind = \"lame_cylinder\"\na = 3.0\nb = 5.0\np = 0.1\n"
}
