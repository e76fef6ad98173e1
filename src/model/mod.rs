//! The mechanical model built from a mesh and its description ([`ModelSpec`]): bodies with their
//! cells, boundary loads on facets, supports, and contact pairs.
//!
//! Blocks: a body group may hold many volumes, and the contact groups'
//! facets cut it into blocks (connected pieces between contact facets).
//! Every block is a [`Body`] of the model, and a part of its own for the
//! condensation: a rock mass of 500 blocks is one `[[bodies]]` entry.
//!
//! Contact splitting: a node of a contact facet gets one copy per fan of
//! cells around it (the first keeps the mesh node, the others get new model
//! nodes at the same place), so the sides of a contact can move apart, and
//! where contacts cross every block keeps its own copy. Pairs follow the
//! facets, so one copy can be in several pairs. With `groups = [a, b]` the
//! two sides already have their own nodes, which are paired by position.
//! Which side is I is written once, in contacts.rs.
//!
//! Everything else (loads, supports) refers to mesh nodes; loads are moved to
//! the copy of the cell the loaded facet bounds, supports hold the copies of
//! the cells their facets bound (a point support every copy).
//!
//! [`Model::build`] (build.rs) takes the steps in order: bodies, contacts
//! (topology.rs: blocks and fans; facet_cells.rs: the two cells of every
//! contact facet; contacts.rs: the split and the pairs),
//! supports, the rigid-motion check (held.rs), loads, pair normals
//! (normals.rs: a copy in several pairs takes its surface's normal) and
//! areas. build_input.rs holds what every step reads, errors.rs what can be
//! wrong ([`ModelError`]).
//! What the built model makes legal but a user may not mean (bodies bonded
//! by shared nodes without a contact) is in warnings.rs.

mod build;
mod build_input;
mod contacts;
mod errors;
mod facet_cells;
mod forces;
mod held;
mod hold;
pub mod insitu;
mod joint_water;
mod normals;
pub mod quality;
mod spec;
mod topology;
pub mod water;

pub use contacts::CREASE_ANGLE;
pub use errors::{ModelError, Near, Unfused, Unpaired};
pub use forces::NodalLoad;
pub mod warnings;

pub use spec::{
    BodySpec, ContactGroups, ContactSpec, ForceLoad, InitialStress, LoadKind, LoadSpec, Material, ModelSpec,
    SupportSpec,
};
pub use water::{GroupWater, JointWater};

use crate::fem::Analysis;
use crate::mesh::Cell;

/// A body of the model (a block of a `[[bodies]]` entry): cells in model
/// node numbering.
#[derive(Clone, Debug)]
pub struct Body {
    /// The body group's name.
    pub name: String,
    /// Its `[[bodies]]` entry, and when the group's contact facets cut it
    /// into several blocks: which, of how many, and where (the mean of its
    /// cells' nodes), to name it in messages.
    pub group: usize,
    pub block: Option<Block>,
    pub material: Material,
    pub cells: Vec<Cell>,
    /// In-situ stress the body carries before any load.
    pub initial: Option<InitialStress>,
}

/// Where a block sits in its body group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    pub index: usize,
    pub of: usize,
    pub centre: [f64; 3],
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

/// The DOFs (`node * nd + c`) one support group holds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SupportDofs {
    /// The support's group.
    pub group: String,
    pub dofs: Vec<usize>,
}

/// One contact node pair: k on body I, l on body II.
#[derive(Clone, Debug)]
pub struct Pair {
    pub k: usize,
    pub l: usize,
    pub contact: usize,
    /// Unit outward normal of body I at k (area-weighted over its facets,
    /// and over those of the pairs it shares a copy with on a smooth
    /// surface: [`normals`]).
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

#[derive(Clone, Debug)]
pub struct Model {
    pub analysis: Analysis,
    pub nd: usize,
    pub thickness: f64,
    pub gravity: [f64; 3],
    pub coords: Vec<[f64; 3]>,
    pub bodies: Vec<Body>,
    pub loads: Vec<FacetLoad>,
    /// Point loads, and forces spread over a group or a body (`force = [..]`).
    pub nodal_loads: Vec<NodalLoad>,
    /// The DOFs each `[[supports]]` entry holds, in the scene's order (a
    /// DOF two entries hold counts for the later one, whose value it has).
    pub supports: Vec<SupportDofs>,
    /// Prescribed value of each DOF (`node * nd + c`), None when free.
    pub prescribed: Vec<Option<f64>>,
    pub pairs: Vec<Pair>,
    pub interfaces: Vec<Interface>,
    /// Mesh node of every model node.
    pub mesh_node: Vec<usize>,
    /// Load factor of each load case at each load step. Case 0 is the ramp
    /// k / load_steps, which also scales prescribed displacements.
    pub cases: Vec<Vec<f64>>,
    /// The load case of each of the description's loads (`[[loads]]`).
    pub load_cases: Vec<usize>,
    /// The load case of gravity.
    pub gravity_case: usize,
    /// The load case of the initial stresses: factor 1 at every step (they
    /// are there before the first load).
    pub initial_case: usize,
    /// The load case of the initial equilibrium stage's hold load (the
    /// in-situ traction on the bodies' outer faces, [`hold`]): 0 at every
    /// load step, 1 in the stage. None without the stage.
    pub hold_case: Option<usize>,
    /// The water in the joints: one entry per contact group that has some.
    pub water: Vec<GroupWater>,
    /// Pseudo-static seismic accelerations (global axes; times a body's
    /// density, its load per unit volume) and their load cases.
    pub seismic: Vec<([f64; 3], usize)>,
}

impl Body {
    /// `"rock"`, or `"rock" block 3 of 8` for a block of a group cut into several.
    pub fn label(&self) -> String {
        match self.block {
            None => format!("\"{}\"", self.name),
            Some(b) => {
                let c = b.centre;
                format!(
                    "\"{}\" block {} of {} (centre at ({:.4}, {:.4}, {:.4}))",
                    self.name,
                    b.index + 1,
                    b.of,
                    c[0],
                    c[1],
                    c[2]
                )
            }
        }
    }

    /// The initial stress at x (zero without one).
    pub fn initial_at(&self, x: [f64; 3], analysis: Analysis, gravity: [f64; 3]) -> [f64; 6] {
        self.initial.map_or([0.0; 6], |i| i.at(x, analysis, self.material.density, gravity))
    }
}

impl Model {
    pub fn n_nodes(&self) -> usize {
        self.coords.len()
    }

    /// The pair at every node of every interface facet (`[interface][facet][node]`),
    /// `usize::MAX` where the node is in no pair (the tip of a joint ending
    /// inside a body).
    pub fn facet_pairs(&self) -> Vec<Vec<Vec<usize>>> {
        let mut out: Vec<Vec<Vec<usize>>> = self
            .interfaces
            .iter()
            .map(|i| i.facets.iter().map(|f| vec![usize::MAX; f.nodes.len()]).collect())
            .collect();
        for (p, pair) in self.pairs.iter().enumerate() {
            for &(f, a) in &pair.shares {
                out[pair.contact][f][a] = p;
            }
        }
        out
    }

    /// The body of every model node (the first that has it; `usize::MAX`
    /// for a node of no body).
    pub fn body_of_node(&self) -> Vec<usize> {
        let mut out = vec![usize::MAX; self.n_nodes()];
        for (b, body) in self.bodies.iter().enumerate().rev() {
            for &n in body.cells.iter().flat_map(|c| &c.nodes) {
                out[n] = b;
            }
        }
        out
    }

    /// The factor of every load case in the initial equilibrium stage
    /// (None without it): gravity, the initial stresses and the hold load
    /// at 1, every other case (the loads, joint water, prescribed
    /// displacements) at 0.
    pub fn stage_factors(&self) -> Option<Vec<f64>> {
        let hold = self.hold_case?;
        let on = [self.gravity_case, self.initial_case, hold];
        Some((0..self.cases.len()).map(|c| if on.contains(&c) { 1.0 } else { 0.0 }).collect())
    }

    /// Names of the bodies, for messages.
    pub fn body_names(&self, ids: &[usize]) -> String {
        ids.iter().map(|&b| self.bodies[b].label()).collect::<Vec<_>>().join(", ")
    }
}
