//! The kinds of cell, named and numbered as in gmsh: node counts, faces,
//! dimensions and names.

/// Cell kinds, named and numbered as in gmsh (`gmsh_code`). The reference
/// cells, node diagrams and node orders are in `fem/shape/nodes.rs`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellKind {
    Point1,
    Line2,
    Line3,
    Tri3,
    Tri6,
    Quad4,
    Quad8,
    Quad9,
    Tet4,
    Tet10,
    Hex8,
    Hex20,
    Hex27,
    Prism6,
    Prism15,
    Prism18,
    Pyramid5,
    Pyramid13,
    Pyramid14,
}

impl CellKind {
    pub const ALL: [CellKind; 19] = [
        CellKind::Point1,
        CellKind::Line2,
        CellKind::Line3,
        CellKind::Tri3,
        CellKind::Tri6,
        CellKind::Quad4,
        CellKind::Quad8,
        CellKind::Quad9,
        CellKind::Tet4,
        CellKind::Tet10,
        CellKind::Hex8,
        CellKind::Hex20,
        CellKind::Hex27,
        CellKind::Prism6,
        CellKind::Prism15,
        CellKind::Prism18,
        CellKind::Pyramid5,
        CellKind::Pyramid13,
        CellKind::Pyramid14,
    ];

    /// gmsh element type number (MSH format).
    pub fn gmsh_code(self) -> i32 {
        match self {
            CellKind::Point1 => 15,
            CellKind::Line2 => 1,
            CellKind::Line3 => 8,
            CellKind::Tri3 => 2,
            CellKind::Tri6 => 9,
            CellKind::Quad4 => 3,
            CellKind::Quad8 => 16,
            CellKind::Quad9 => 10,
            CellKind::Tet4 => 4,
            CellKind::Tet10 => 11,
            CellKind::Hex8 => 5,
            CellKind::Hex20 => 17,
            CellKind::Hex27 => 12,
            CellKind::Prism6 => 6,
            CellKind::Prism15 => 18,
            CellKind::Prism18 => 13,
            CellKind::Pyramid5 => 7,
            CellKind::Pyramid13 => 19,
            CellKind::Pyramid14 => 14,
        }
    }

    pub fn from_gmsh(code: i32) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.gmsh_code() == code)
    }

    pub fn n_nodes(self) -> usize {
        match self {
            CellKind::Point1 => 1,
            CellKind::Line2 => 2,
            CellKind::Line3 => 3,
            CellKind::Tri3 => 3,
            CellKind::Tri6 => 6,
            CellKind::Quad4 => 4,
            CellKind::Quad8 => 8,
            CellKind::Quad9 => 9,
            CellKind::Tet4 => 4,
            CellKind::Tet10 => 10,
            CellKind::Hex8 => 8,
            CellKind::Hex20 => 20,
            CellKind::Hex27 => 27,
            CellKind::Prism6 => 6,
            CellKind::Prism15 => 15,
            CellKind::Prism18 => 18,
            CellKind::Pyramid5 => 5,
            CellKind::Pyramid13 => 13,
            CellKind::Pyramid14 => 14,
        }
    }

    /// Number of corner (vertex) nodes; they come first in gmsh order.
    pub fn n_corners(self) -> usize {
        match self {
            CellKind::Point1 => 1,
            CellKind::Line2 | CellKind::Line3 => 2,
            CellKind::Tri3 | CellKind::Tri6 => 3,
            CellKind::Quad4 | CellKind::Quad8 | CellKind::Quad9 => 4,
            CellKind::Tet4 | CellKind::Tet10 => 4,
            CellKind::Hex8 | CellKind::Hex20 | CellKind::Hex27 => 8,
            CellKind::Prism6 | CellKind::Prism15 | CellKind::Prism18 => 6,
            CellKind::Pyramid5 | CellKind::Pyramid13 | CellKind::Pyramid14 => 5,
        }
    }

    /// Topological dimension.
    pub fn dim(self) -> usize {
        match self {
            CellKind::Point1 => 0,
            CellKind::Line2 | CellKind::Line3 => 1,
            CellKind::Tri3 | CellKind::Tri6 | CellKind::Quad4 | CellKind::Quad8 | CellKind::Quad9 => 2,
            _ => 3,
        }
    }

    /// Polynomial order of the geometry/interpolation (1 or 2).
    pub fn order(self) -> usize {
        if self.n_nodes() == self.n_corners() {
            1
        } else {
            2
        }
    }

    /// The edges of a facet kind (a line or a surface cell), gmsh order:
    /// `[middle, corner, corner]`, the middle node `usize::MAX` on linear
    /// kinds. A line is its own one edge.
    pub fn facet_edges(self) -> &'static [[usize; 3]] {
        const X: usize = usize::MAX;
        match self {
            CellKind::Line2 => &[[X, 0, 1]],
            CellKind::Line3 => &[[2, 0, 1]],
            CellKind::Tri3 => &[[X, 0, 1], [X, 1, 2], [X, 2, 0]],
            CellKind::Tri6 => &[[3, 0, 1], [4, 1, 2], [5, 2, 0]],
            CellKind::Quad4 => &[[X, 0, 1], [X, 1, 2], [X, 2, 3], [X, 3, 0]],
            CellKind::Quad8 | CellKind::Quad9 => &[[4, 0, 1], [5, 1, 2], [6, 2, 3], [7, 3, 0]],
            _ => &[],
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            CellKind::Point1 => "point1",
            CellKind::Line2 => "line2",
            CellKind::Line3 => "line3",
            CellKind::Tri3 => "tri3",
            CellKind::Tri6 => "tri6",
            CellKind::Quad4 => "quad4",
            CellKind::Quad8 => "quad8",
            CellKind::Quad9 => "quad9",
            CellKind::Tet4 => "tet4",
            CellKind::Tet10 => "tet10",
            CellKind::Hex8 => "hex8",
            CellKind::Hex20 => "hex20",
            CellKind::Hex27 => "hex27",
            CellKind::Prism6 => "prism6",
            CellKind::Prism15 => "prism15",
            CellKind::Prism18 => "prism18",
            CellKind::Pyramid5 => "pyramid5",
            CellKind::Pyramid13 => "pyramid13",
            CellKind::Pyramid14 => "pyramid14",
        }
    }
}
