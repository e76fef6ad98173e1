//! Joint sets and single joints by orientation: the tool cuts the bodies of
//! the user's `.geo` by the joints' planes and makes the physical groups
//! itself. Each joint set becomes the contact group named after it (its
//! faces that lie between two blocks, or inside one block where a finite
//! joint ends in intact rock); the user's own groups keep naming what they
//! named, however the joints cut them (a box face cut into pieces is still
//! "top").
//!
//! **How.** The `.geo` language cannot tell which piece of a
//! `BooleanFragments` came from which entity, and OpenCASCADE renumbers
//! what it cuts; gmsh's API can: `occ.fragment` returns, for every input,
//! its pieces. The tool calls gmsh's C API in-process through
//! `libgmsh.so.4.8` loaded at run time ([`ffi`]): the shared library the
//! Debian `gmsh` package itself runs on, so every machine that has the
//! gmsh CLI has it too, no new package or crate is needed (`dlopen` through
//! `libc`), and the binary builds and runs without it for scenes without
//! joints. Python's gmsh module would have needed `python3-gmsh` and a
//! Python that finds it; classifying facets after meshing would have lost
//! the user's groups on the pieces of cut faces (and curved faces).
//!
//! The steps ([`cut`]): open the `.geo` as the CLI would (`-setnumber`,
//! `-clscale`); keep its physical groups; mesh its boundary to measure the
//! sizes it asks for ([`sizes`]); lay each joint's patches (a polygon
//! covering its bodies, or finite joints with rock bridges, clipped to
//! `extent` and to its bodies) at the planes n . x = offset + k spacing
//! ([`geometry`]); fragment every volume (surface in 2D) and every entity
//! of the user's groups with the patches; keep the pieces of each joint
//! that lie between two blocks or inside one, drop those outside; rebuild
//! the groups from the pieces (with `merge_slivers`, a sliver's largest
//! joint face leaves its group: [`slivers`]); give the new points their sizes; mesh and
//! write MSH 4.1. What it made (planes, areas, blocks, planes passing close
//! to a corner) is a [`CutReport`], kept beside the mesh.
//!
//! Sign and angle conventions (DESIGN.md §4): x east, y north, z up; dip
//! below horizontal, dip direction clockwise from north; the upward normal
//! n = (sin dip sin dd, sin dip cos dd, cos dip); in 2D a trace at `angle`
//! from +x has n = (-sin angle, cos angle).

mod api;
mod curved;
mod cut;
pub mod cut_report;
mod ffi;
pub mod geometry;
pub mod job;
pub mod joint_error;
mod sizes;
mod slivers;

use std::path::{Path, PathBuf};

pub use cut_report::{BlockReport, CutReport, JointReport, NearMiss, PlaneReport};
pub use ffi::LoadError;
pub use geometry::Shape;
pub(crate) use job::trim;
pub use job::{CutJob, JointSpec, MeshArgs, Orientation, Persistence, Placement};
pub use joint_error::JointError;

/// Where the report of a cut mesh `msh` is kept.
pub fn report_path(msh: &Path) -> PathBuf {
    let mut s = msh.as_os_str().to_owned();
    s.push(".cut.json");
    PathBuf::from(s)
}

/// The report kept beside `msh`, if any.
pub fn read_report(msh: &Path) -> Option<CutReport> {
    let text = std::fs::read_to_string(report_path(msh)).ok()?;
    serde_json::from_str(&text).ok()
}

/// [`cut_and_mesh`] into `out`, and its report into `report` (both in the
/// run's stage: the caller removes them on failure).
pub fn mesh(args: &MeshArgs, job: &CutJob, out: &Path, report: &Path) -> Result<(), JointError> {
    let made = cut_and_mesh(args, job, out)?;
    let text = serde_json::to_string_pretty(&made).unwrap_or_default();
    std::fs::write(report, text).map_err(|e| JointError::Io {
        what: "cannot write",
        path: report.to_path_buf(),
        source: e,
    })
}

/// Opens the `.geo`, cuts its bodies by the joints, meshes and writes the
/// mesh (MSH 4.1, binary) to `out`; returns what the cut made.
pub fn cut_and_mesh(args: &MeshArgs, job: &CutJob, out: &Path) -> Result<CutReport, JointError> {
    let lib = ffi::Lib::get().map_err(|why| JointError::Library { why })?;
    let mut argv: Vec<String> = Vec::new();
    for (name, value) in args.setnumber {
        argv.extend(["-setnumber".to_string(), name.clone(), value.to_string()]);
    }
    if let Some(s) = args.clscale {
        argv.extend(["-clscale".to_string(), s.to_string()]);
    }
    let gmsh_err = |e: api::ApiError| JointError::Gmsh { geo: args.geo.to_path_buf(), detail: e.to_string() };
    let session = api::Session::start(lib, &argv).map_err(gmsh_err)?;
    cut::run(&session, args, job, out)
}
