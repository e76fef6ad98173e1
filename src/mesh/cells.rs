//! The mesh's data: cells (kind, nodes, gmsh tag), the physical groups
//! that hold them, and the node coordinates ([`Mesh`]).

use super::cell_kind::CellKind;

/// One mesh cell: its kind, its nodes (indices into `Mesh::coords`, gmsh
/// order) and its gmsh element tag (for messages).
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    pub kind: CellKind,
    pub nodes: Vec<usize>,
    pub tag: u64,
}

/// A gmsh physical group with the cells of all its entities.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    pub name: String,
    pub dim: usize,
    pub tag: i32,
    pub cells: Vec<Cell>,
}

impl Group {
    /// The distinct nodes of the group's cells, sorted.
    pub fn nodes(&self) -> Vec<usize> {
        let mut nodes: Vec<usize> = self.cells.iter().flat_map(|c| c.nodes.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}

/// Node coordinates and physical groups. Only nodes referenced by some group
/// need be meaningful; gmsh writes every node of a saved entity.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub coords: Vec<[f64; 3]>,
    /// gmsh node tag of each node, for messages.
    pub node_tags: Vec<u64>,
    pub groups: Vec<Group>,
}

impl Mesh {
    pub fn group(&self, name: &str) -> Option<&Group> {
        self.groups.iter().find(|g| g.name == name)
    }

    /// The highest dimension of any group (2 for a plane mesh, 3 for a solid).
    pub fn dim(&self) -> usize {
        self.groups.iter().map(|g| g.dim).max().unwrap_or(0)
    }

    /// Length of the bounding-box diagonal of all nodes used by a group.
    pub fn size(&self) -> f64 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for g in &self.groups {
            for c in &g.cells {
                for &n in &c.nodes {
                    for d in 0..3 {
                        lo[d] = lo[d].min(self.coords[n][d]);
                        hi[d] = hi[d].max(self.coords[n][d]);
                    }
                }
            }
        }
        (0..3).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt()
    }
}
