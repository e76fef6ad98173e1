//! What went wrong while building or writing result files.

use std::path::PathBuf;

/// What went wrong while building or writing result files. Messages name the
/// file, field or cell concerned and the cause.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("cannot create result directory {}: {source}", path.display())]
    CreateDir {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot write result file {}: {source}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot move {} into place as {}: {source}", from.display(), to.display())]
    Rename {
        from: PathBuf,
        to: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot lock the result directory ({}): {source}", path.display())]
    Lock {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot write results into {}: {why}; choose another --out", path.display())]
    InvalidDir { path: PathBuf, why: String },
    #[error("cannot write result file {}: a directory of that name is in the way; move it elsewhere", path.display())]
    InTheWay { path: PathBuf },
    #[error("cannot carry the files of {} into the new set of results: {source}", from.display())]
    Carry {
        from: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot write into {}: it is {what}, which a run never follows or replaces; remove it (or give another --out)", path.display())]
    NotOurs { path: PathBuf, what: &'static str },
    #[error("cannot keep {} as it is: it is a mount point, and a run replaces the result directory in one step, which cannot take a mount along; mount it elsewhere or give another --out", path.display())]
    MountPoint { path: PathBuf },
    #[error("cannot keep {} as it is: {why}; move it out of the result directory, run as its owner, or give another --out", path.display())]
    CannotKeep { path: PathBuf, why: String },
    #[error("invalid result file name {name:?} in {}: it must be a plain file name", dir.display())]
    InvalidName { dir: PathBuf, name: String },
    #[error(
        "{location} field `{field}` has {len} values, expected {} ({n_comp} per {location} × {count} {location}s)",
        *n_comp as u128 * *count as u128
    )]
    FieldLength { location: &'static str, field: String, n_comp: usize, count: usize, len: usize },
    #[error("{location} field `{field}` has no components")]
    NoComponents { location: &'static str, field: String },
    #[error("cell {index} (gmsh element {tag}, {kind}) has {actual} nodes, expected {expected}")]
    CellNodes { index: usize, tag: u64, kind: &'static str, expected: usize, actual: usize },
    #[error("cell {index} (gmsh element {tag}) refers to node {node}, but there are only {n_points} points")]
    NodeOutOfRange { index: usize, tag: u64, node: usize, n_points: usize },
    #[error("too many {what} for a VTU file: {count}")]
    TooLarge { what: &'static str, count: usize },
    #[error("cannot encode the VTU data: {0}")]
    Vtk(String),
}
