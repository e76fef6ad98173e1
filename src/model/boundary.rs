//! What loads and holds the model's boundary: loads on facets, loads at
//! nodes, and the DOFs each support holds.

use super::spec::LoadKind;
use crate::mesh::Cell;

/// A load on one boundary facet of one body.
#[derive(Clone, Debug)]
pub struct FacetLoad {
    pub cell: Cell,
    /// Turns the facet's natural normal into the body's outward normal.
    pub sign: f64,
    pub kind: LoadKind,
    /// The body whose boundary the facet is.
    pub body: usize,
    /// The body's cell (index in its `cells`) the facet is a face of.
    pub element: usize,
    /// Its load case (index into `Model::cases`).
    pub case: usize,
}

/// The DOFs (`node * nd + c`) one support group holds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SupportDofs {
    /// The support's group.
    pub group: String,
    pub dofs: Vec<usize>,
}

/// A force on one model node, in one load case, owned by one cell (for the
/// part that assembles it).
#[derive(Clone, Debug, PartialEq)]
pub struct NodalLoad {
    pub node: usize,
    pub force: [f64; 3],
    /// Its load case (index into `Model::cases`).
    pub case: usize,
    /// A cell that has the node: (body, index in its cells).
    pub body: usize,
    pub element: usize,
}
