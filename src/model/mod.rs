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

mod body;
mod boundary;
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
mod mechanical;
mod normals;
mod pairs;
pub mod quality;
mod spec;
pub(crate) mod topology;
pub mod water;

pub mod warnings;

pub use body::{Block, Body};
pub use boundary::{FacetLoad, NodalLoad, SupportDofs};
pub use contacts::CREASE_ANGLE;
pub use errors::{Bounded, ModelError, Near, PartName, Unfused, Unpaired};
pub use mechanical::Model;
pub use pairs::{Interface, Pair};

pub use spec::{
    BodySpec, ContactGroups, ContactSpec, ForceLoad, InitialStress, LoadKind, LoadSpec, Material, ModelSpec,
    SupportSpec,
};
pub use water::{GroupWater, JointWater};
