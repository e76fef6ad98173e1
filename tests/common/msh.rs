//! A minimal MSH 4.1 ASCII writer, for meshes that gmsh does not make but
//! the tests need (e.g. hexahedra cut into pyramids): nodes, and physical
//! groups of cells, each group its own entity.

use std::fmt::Write;
use std::path::Path;

/// A physical group: its name, dimension, gmsh element type and cells (0-based node indices, gmsh order).
pub struct MshGroup {
    pub name: String,
    pub dim: usize,
    pub gmsh_type: i32,
    pub cells: Vec<Vec<usize>>,
}

/// Writes `nodes` and `groups` as an MSH 4.1 ASCII file; node tags are
/// index + 1, element tags run on over the groups.
pub fn write_msh41(path: &Path, nodes: &[[f64; 3]], groups: &[MshGroup]) {
    let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n");
    writeln!(s, "{}", groups.len()).unwrap();
    for (i, g) in groups.iter().enumerate() {
        writeln!(s, "{} {} \"{}\"", g.dim, i + 1, g.name).unwrap();
    }
    s += "$EndPhysicalNames\n$Entities\n";
    let count = |d: usize| groups.iter().filter(|g| g.dim == d).count();
    writeln!(s, "{} {} {} {}", count(0), count(1), count(2), count(3)).unwrap();
    // entity tag = physical tag = group index + 1; no bounding entities
    for d in 0..4 {
        for (i, _) in groups.iter().enumerate().filter(|(_, g)| g.dim == d) {
            if d == 0 {
                writeln!(s, "{} 0 0 0 1 {}", i + 1, i + 1).unwrap();
            } else {
                writeln!(s, "{} 0 0 0 0 0 0 1 {} 0", i + 1, i + 1).unwrap();
            }
        }
    }
    s += "$EndEntities\n$Nodes\n";
    let n = nodes.len();
    writeln!(s, "1 {n} 1 {n}\n3 {} 0 {n}", groups.iter().position(|g| g.dim == 3).map_or(1, |i| i + 1)).unwrap();
    for i in 0..n {
        writeln!(s, "{}", i + 1).unwrap();
    }
    for x in nodes {
        writeln!(s, "{:?} {:?} {:?}", x[0], x[1], x[2]).unwrap();
    }
    s += "$EndNodes\n$Elements\n";
    let total: usize = groups.iter().map(|g| g.cells.len()).sum();
    writeln!(s, "{} {total} 1 {total}", groups.len()).unwrap();
    let mut tag = 0;
    for (i, g) in groups.iter().enumerate() {
        writeln!(s, "{} {} {} {}", g.dim, i + 1, g.gmsh_type, g.cells.len()).unwrap();
        for c in &g.cells {
            tag += 1;
            let nodes: Vec<String> = c.iter().map(|v| (v + 1).to_string()).collect();
            writeln!(s, "{tag} {}", nodes.join(" ")).unwrap();
        }
    }
    s += "$EndElements\n";
    std::fs::write(path, s).expect("write .msh");
}
