//! The contact pairs (k on body I, l on body II) and the contact groups
//! they belong to, each facet between two bodies.

use crate::mesh::Cell;

/// One contact node pair: k on body I, l on body II.
#[derive(Clone, Debug)]
pub struct Pair {
    pub k: usize,
    pub l: usize,
    pub contact: usize,
    /// Unit outward normal of body I at k (area-weighted over its facets,
    /// and over those of the pairs it shares a copy with on a smooth
    /// surface: [`super::normals`]).
    pub normal: [f64; 3],
    /// Area the pair controls, `∫ N_k dA` over the facets of body I (with
    /// thickness or 2 pi r as for every other integral).
    pub area: f64,
    /// The facets it takes its normal and area from: (index in its
    /// interface's `facets`, position of k in that facet).
    pub shares: Vec<(usize, usize)>,
}

/// One contact group: its facets, each between two bodies (blocks).
#[derive(Clone, Debug)]
pub struct Interface {
    pub name: String,
    /// The bodies of the first facet's two sides.
    pub body_i: usize,
    pub body_ii: usize,
    /// Every body on side I of some facet, ascending.
    pub side_i: Vec<usize>,
    /// The facets, in side I's model nodes.
    pub facets: Vec<Cell>,
    /// (body I, body II) of each facet.
    pub sides: Vec<[usize; 2]>,
}
