//! Why a `.msh` file could not be read: the file and the line or section
//! at fault.

use std::path::PathBuf;

use crate::mesh::cell_kind::CellKind;

/// Why a mesh file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MshError {
    #[error("mesh file `{}` does not exist: check `mesh =` in the scene", path.display())]
    NotFound { path: PathBuf },

    #[error("cannot read mesh file `{}`: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },

    #[error(
        "`{}` is not a complete MSH 4.1 file (truncated?): {detail}. Mesh the .geo again \
         with gmsh (-format msh41), or point `mesh =` in the scene at a complete file",
        path.display()
    )]
    Malformed { path: PathBuf, detail: String },

    #[error("`{}`: node {node} has the coordinates ({}, {}, {}), {}", path.display(), x[0], x[1], x[2], if x.iter().all(|v| v.is_finite()) { "beyond 1e100, where lengths, areas and stiffnesses overflow double precision: give the model in other units (or move it nearer the origin)" } else { "which are not numbers: the file is damaged or was written by a tool that lost them; mesh the .geo again with gmsh" })]
    NotFinite { path: PathBuf, node: u64, x: [f64; 3] },

    #[error("`{}` is MSH {version}: re-export it with gmsh -format msh41", path.display())]
    Version { path: PathBuf, version: String },

    #[error(
        "`{}` has no physical groups: add Physical Surface/Volume/Curve to the .geo, \
         gmsh saves only elements of physical groups",
        path.display()
    )]
    NoPhysicalGroups { path: PathBuf },

    #[error(
        "`{}` is a partitioned mesh: re-export it unpartitioned (gmsh -format msh41, \
         without -part)",
        path.display()
    )]
    Partitioned { path: PathBuf },

    #[error(
        "`{}`: physical group `{group}` has elements of gmsh type {code} ({name}), which \
         subcontact cannot use: mesh with elements of order 1 or 2 (`[gmsh] order = 1` or 2): \
         triangles or quadrangles in 2D; tetrahedra, hexahedra, prisms or pyramids in 3D \
         (supported: {supported})",
        path.display(),
        supported = supported_kinds()
    )]
    UnsupportedElement { path: PathBuf, code: i32, name: String, group: String },

    #[error(
        "`{}`: element {element} of physical group `{group}` uses node {node}, which is not \
         in the $Nodes section: the file is inconsistent, mesh the .geo again with gmsh",
        path.display()
    )]
    MissingNode { path: PathBuf, element: u64, node: u64, group: String },
}

fn supported_kinds() -> String {
    CellKind::ALL.iter().map(|k| k.name()).collect::<Vec<_>>().join(", ")
}
