//! The cut through real gmsh: the pieces, the groups, the sizes, the
//! reports, and what is refused.

use super::*;
use crate::fem::vec3::{cross, norm, sub};
use crate::mesh::gmsh::tests::TestDir;
use crate::mesh::msh::read_msh;

/// A 10 m cube with a tunnel of radius 2 along y through its middle;
/// every face of the cube a group, the tunnel's wall a group.
pub(crate) const TUNNEL_BOX_GEO: &str = r#"
SetFactory("OpenCASCADE");
DefineConstant[ lc = {1.5, Name "lc"} ];
Box(1) = {0, 0, 0, 10, 10, 10};
Cylinder(2) = {5, -1, 5, 0, 12, 0, 2};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
MeshSize{ PointsOf{ Volume{:}; } } = lc;
e = 1e-3;
Physical Volume("rock") = {1};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 10 - e, 10 + e, 10 + e, 10 + e};
Physical Surface("base") = Surface In BoundingBox{-e, -e, -e, 10 + e, 10 + e, e};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 10 + e, 10 + e};
Physical Surface("wall") = Surface In BoundingBox{3 - e, -e, 3 - e, 7 + e, 10 + e, 7 + e};
"#;

pub(crate) fn set(name: &str, dip: f64, dd: f64, spacing: f64, offset: f64) -> JointSpec {
    JointSpec {
        key: format!("joint_sets[{name}]"),
        name: name.to_string(),
        orientation: Orientation::Dip { dip, dip_direction: dd },
        placement: Placement::Set { spacing, offset },
        bodies: vec!["rock".to_string()],
        persistence: None,
        extent: None,
        snap: 0.0,
    }
}

fn run(
    dir: &TestDir,
    geo: &str,
    dim: usize,
    joints: Vec<JointSpec>,
) -> Result<(crate::mesh::Mesh, CutReport), JointError> {
    let geo = dir.write("model.geo", geo);
    let out = dir.0.join("model.msh");
    let args = MeshArgs { geo: &geo, dim, order: 1, setnumber: &[], clscale: None };
    let report =
        cut_and_mesh(&args, &CutJob { joints, max_blocks: 1000, structured: false, merge_slivers: false }, &out)?;
    Ok((read_msh(&out).expect("the cut mesh reads"), report))
}

/// Three oblique sets through the box with a tunnel: the blocks fill the
/// rock's volume 1000 - 40 pi, each set is a contact group of its own, the
/// box's faces and the wall keep their groups (cut into pieces), and the
/// mesh's facets of each set add up to the areas the report gives.
#[test]
fn three_sets_cut_a_box_with_a_tunnel() {
    let dir = TestDir::new("joints-three-sets");
    let sets =
        vec![set("J1", 60.0, 30.0, 3.0, 1.3), set("J2", 70.0, 150.0, 3.0, 0.5), set("J3", 10.0, 270.0, 2.5, 0.2)];
    let (mesh, report) = run(&dir, TUNNEL_BOX_GEO, 3, sets).expect("the cut succeeds");
    let volume: f64 = report.blocks.iter().map(|b| b.volume).sum();
    let exact = 1000.0 - 40.0 * std::f64::consts::PI;
    assert!((volume - exact).abs() < 1e-6 * exact, "blocks fill the rock: {volume} against {exact}");
    assert!(report.blocks.iter().all(|b| b.body == "rock"));
    for name in ["rock", "top", "base", "x0", "wall", "J1", "J2", "J3"] {
        assert!(mesh.group(name).is_some_and(|g| !g.cells.is_empty()), "group {name} survives the cut");
    }
    // the top face keeps its area, 10 x 10, in pieces
    let top = facet_area(&mesh, "top");
    assert!((top - 100.0).abs() < 1e-9 * 100.0, "top area {top}");
    let wall = facet_area(&mesh, "wall");
    assert!((wall - 40.0 * std::f64::consts::PI).abs() < 0.02 * 40.0 * std::f64::consts::PI, "wall area {wall}");
    // every set meets the tunnel, whose wall the facets cut by chords: the
    // holes come out a little small
    for j in &report.joints {
        let a = facet_area(&mesh, &j.name);
        assert!(a >= j.area() && a < 1.01 * j.area(), "{}: mesh {a} against {}", j.name, j.area());
    }
}

/// The area of a group's linear facets (triangle corners).
fn facet_area(mesh: &crate::mesh::Mesh, group: &str) -> f64 {
    let g = mesh.group(group).expect("group");
    g.cells
        .iter()
        .map(|c| {
            let [a, b, d] = [0, 1, 2].map(|k| mesh.coords[c.nodes[k]]);
            0.5 * norm(cross(sub(b, a), sub(d, a)))
        })
        .sum()
}
