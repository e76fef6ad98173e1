//! The mesh as the rest of the program sees it: node coordinates, and cells
//! grouped by gmsh physical group. Cells keep gmsh's node order; node indices
//! are 0-based positions in `Mesh::coords` (gmsh tags are kept for messages).
//!
//! Reading `.msh` files lives in [`msh`], running the gmsh CLI in [`gmsh`],
//! what a `.geo` defines and runs in [`geo`], cutting bodies by joint sets
//! (through gmsh's API) in [`joints`].
//! Nothing here knows about elasticity.

pub mod cell_kind;
pub mod cells;
pub mod geo;
pub mod gmsh;
pub mod joints;
pub mod msh;

pub use cell_kind::CellKind;
pub use cells::{Cell, Group, Mesh};
