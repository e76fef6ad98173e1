//! The mechanical model built from a mesh and its description ([`ModelSpec`]): bodies with their
//! cells, boundary loads on facets, supports, and contact pairs.
//!
//! Contact splitting: a node on a contact group gets one copy per body that
//! uses it (the first body keeps the mesh node, the others get new model
//! nodes at the same place), so the two sides of a contact can move apart.
//! With `groups = [a, b]` the two sides already have their own nodes, which
//! are paired by position. Pairs are ordered (k on body I, l on body II),
//! body I being the one listed first in `[[bodies]]`.
//!
//! Everything else (loads, supports) refers to mesh nodes; loads are moved to
//! the copy of the body the loaded facet bounds, supports hold every copy.
//!
//! [`Model::build`] (build.rs) takes the steps in order: bodies, contacts,
//! supports, the rigid-motion check, loads, pair normals and areas. The
//! contact split, the node pairing and the junctions of contacts are in
//! contacts.rs; the check that every rigid-body motion is held in held.rs.
//! What the built model makes legal but a user may not mean (bodies bonded
//! by shared nodes without a contact) is in warnings.rs.

mod build;
mod contacts;
mod held;
mod spec;
pub mod warnings;

pub use spec::{BodySpec, ContactGroups, ContactSpec, InitialStress, LoadKind, LoadSpec, ModelSpec, SupportSpec};

use crate::fem::Analysis;
use crate::mesh::Cell;

/// A body of the model: cells in model node numbering.
#[derive(Clone, Debug)]
pub struct Body {
    pub name: String,
    pub e: f64,
    pub nu: f64,
    pub density: f64,
    pub cells: Vec<Cell>,
    /// In-situ stress the body carries before any load.
    pub initial: Option<InitialStress>,
}

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

/// One contact node pair: k on body I, l on body II.
#[derive(Clone, Debug)]
pub struct Pair {
    pub k: usize,
    pub l: usize,
    pub contact: usize,
    /// Unit outward normal of body I at k (area-weighted over its facets).
    pub normal: [f64; 3],
    /// Area the pair controls, `∫ N_k dA` over the facets of body I (with
    /// thickness or 2 pi r as for every other integral).
    pub area: f64,
}

/// One contact surface: the two bodies and the facets on body I's side.
#[derive(Clone, Debug)]
pub struct Interface {
    pub name: String,
    /// A body of each side (the first listed).
    pub body_i: usize,
    pub body_ii: usize,
    /// Every body on side I (a shared group may join several bodies to one).
    pub side_i: Vec<usize>,
    pub facets: Vec<Cell>,
}

#[derive(Clone, Debug)]
pub struct Model {
    /// The scene file, for messages.
    pub scene: String,
    pub analysis: Analysis,
    pub nd: usize,
    pub thickness: f64,
    pub gravity: [f64; 3],
    pub coords: Vec<[f64; 3]>,
    pub bodies: Vec<Body>,
    pub loads: Vec<FacetLoad>,
    /// Prescribed value of each DOF (`node * nd + c`), None when free.
    pub prescribed: Vec<Option<f64>>,
    pub pairs: Vec<Pair>,
    pub interfaces: Vec<Interface>,
    /// Mesh node of every model node.
    pub mesh_node: Vec<usize>,
    /// Load factor of each load case at each load step. Case 0 is the ramp
    /// k / load_steps, which also scales prescribed displacements.
    pub cases: Vec<Vec<f64>>,
    /// The load case of gravity.
    pub gravity_case: usize,
    /// The load case of the initial stresses: factor 1 at every step (they
    /// are there before the first load).
    pub initial_case: usize,
}

impl Body {
    /// The initial stress at x (zero without one).
    pub fn initial_at(&self, x: [f64; 3], analysis: Analysis, gravity: [f64; 3]) -> [f64; 6] {
        self.initial.map_or([0.0; 6], |i| i.at(x, analysis, self.density, gravity))
    }
}

#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    #[error("{scene}: {key} = \"{group}\" is not a physical group of the mesh `{mesh}`; it has: {known}. Check the name in the .geo's Physical statements")]
    UnknownGroup { scene: String, key: String, group: String, mesh: String, known: String },
    #[error("{scene}: {key} = \"{group}\" is a physical {found}, but a {wanted} is needed here")]
    WrongDimension { scene: String, key: String, group: String, found: String, wanted: String },
    #[error("{scene}: {key}: {msg}")]
    Invalid { scene: String, key: String, msg: String },
    #[error("{scene}: {key} = \"{group}\" is a physical {dim} of the mesh `{mesh}` without elements: its Physical statement names no entity that exists (gmsh keeps such a group without a word). Check the entity numbers in the .geo's Physical statement for \"{group}\"")]
    EmptyGroup { scene: String, key: String, group: String, dim: String, mesh: String },
    #[error("element {tag} of body \"{body}\" is inverted or degenerate (Jacobian determinant {det_j:.3e}): fix the mesh (node order or a collapsed element)")]
    Inverted { body: String, tag: u64, det_j: f64 },
}

impl Model {
    pub fn n_nodes(&self) -> usize {
        self.coords.len()
    }

    /// Names of the bodies, for messages.
    pub fn body_names(&self, ids: &[usize]) -> String {
        ids.iter().map(|&b| format!("\"{}\"", self.bodies[b].name)).collect::<Vec<_>>().join(", ")
    }
}
