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
mod ffi;
pub mod geometry;
mod sizes;
mod slivers;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

pub use ffi::LoadError;
pub use geometry::Shape;

/// How a joint is oriented.
#[derive(Clone, Debug, PartialEq)]
pub enum Orientation {
    /// 3D: dip and dip direction, degrees.
    Dip { dip: f64, dip_direction: f64 },
    /// 2D: the trace's angle from +x, degrees.
    Angle(f64),
}

impl Orientation {
    /// The unit normal n (upward in 3D).
    pub fn normal(&self) -> [f64; 3] {
        match *self {
            Orientation::Dip { dip, dip_direction } => geometry::normal_3d(dip, dip_direction),
            Orientation::Angle(a) => geometry::normal_2d(a),
        }
    }

    /// `60/030` (dip / dip direction) or `angle 60`.
    pub fn label(&self) -> String {
        match *self {
            Orientation::Dip { dip, dip_direction } => format!("{}/{:0>3}", trim(dip), trim(dip_direction)),
            Orientation::Angle(a) => format!("angle {}", trim(a)),
        }
    }
}

/// A number without trailing zeros (six decimals at most).
pub(crate) fn trim(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// Where the planes of a joint lie.
#[derive(Clone, Debug, PartialEq)]
pub enum Placement {
    /// A set: plane k is n . x = offset + k spacing.
    Set { spacing: f64, offset: f64 },
    /// One plane through a point.
    Single { point: [f64; 3] },
}

/// Finite joints: each plane holds joints of `size` (a square's side or a
/// disc's diameter; a trace's length in 2D) with rock bridges of `gap`
/// between them, on a grid centred where the plane is nearest `centre`
/// (default: the centre of the joint's bodies, or a single joint's point).
#[derive(Clone, Debug, PartialEq)]
pub struct Persistence {
    pub size: f64,
    pub gap: f64,
    pub shape: Shape,
    pub centre: Option<[f64; 3]>,
}

/// One `[[joint_sets]]` or `[[joints]]` entry, validated.
#[derive(Clone, Debug, PartialEq)]
pub struct JointSpec {
    /// Where the scene defined it (`joint_sets[0]`, `joints[1]`).
    pub key: String,
    /// The contact group it becomes.
    pub name: String,
    pub orientation: Orientation,
    pub placement: Placement,
    /// The body groups it cuts (never empty: the scene fills in every body).
    pub bodies: Vec<String>,
    pub persistence: Option<Persistence>,
    /// Only the parts of the planes inside this box (`from`, `to`).
    pub extent: Option<([f64; 3], [f64; 3])>,
    /// A plane that passes closer than this to a corner of its bodies is
    /// moved onto the corner (0: never).
    pub snap: f64,
}

/// Changes whenever the cutter would make another mesh of the same input.
const CUTTER_VERSION: u32 = 3;

/// Every joint of a scene and the most blocks it may make.
#[derive(Clone, Debug, PartialEq)]
pub struct CutJob {
    pub joints: Vec<JointSpec>,
    pub max_blocks: usize,
    /// Mesh the blocks structured where gmsh can (`[gmsh] structured`):
    /// hexahedra in six-sided blocks of four-sided faces, quadrangles in
    /// four-sided 2D blocks.
    pub structured: bool,
    /// Bond each sliver block to a neighbour (`merge_slivers`, [`slivers`]).
    pub merge_slivers: bool,
}

impl CutJob {
    /// The job as text for the mesh cache's key (`{:?}` keeps every bit of
    /// the numbers), with the cutter's version: a cutter that cuts
    /// differently makes new meshes.
    pub fn key_text(&self) -> String {
        format!("cutter {CUTTER_VERSION} {self:?}")
    }
}

/// One plane a joint produced.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlaneReport {
    /// k of a set's plane (None for a single joint).
    pub k: Option<i64>,
    /// d of n . x = d, after any snap.
    pub offset: f64,
    /// The area of its faces in the bodies (length of its traces in 2D).
    pub area: f64,
    /// The corner it was snapped onto and how far it moved.
    pub snapped: Option<([f64; 3], f64)>,
}

/// What one joint produced.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct JointReport {
    pub key: String,
    pub name: String,
    pub label: String,
    pub normal: [f64; 3],
    pub planes: Vec<PlaneReport>,
    /// Faces (curves in 2D) of its contact group.
    pub faces: usize,
}

impl JointReport {
    pub fn area(&self) -> f64 {
        self.planes.iter().map(|p| p.area).sum()
    }
}

/// One block after the cut: a volume (surface in 2D) of a body group.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BlockReport {
    pub body: String,
    /// Volume (area in 2D).
    pub volume: f64,
    /// 6 V / A (4 A / P in 2D): a cube's edge, three times a thin slab's thickness.
    pub thickness: f64,
    pub centre: [f64; 3],
    /// The mesh size the .geo asks for nearest its centre.
    pub size: f64,
}

impl BlockReport {
    /// Thinner than a tenth of the mesh size there: a sliver the mesh
    /// fills with flat elements.
    pub fn is_sliver(&self) -> bool {
        self.thickness < self.size / 10.0
    }
}

/// A plane that passes close to a corner of its bodies without going
/// through it: the sliver it cuts off ruins the mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NearMiss {
    pub key: String,
    pub name: String,
    pub k: Option<i64>,
    pub offset: f64,
    pub corner: [f64; 3],
    pub distance: f64,
    /// The mesh size the .geo asks for at the corner.
    pub size: f64,
}

/// What the cut made, kept beside the mesh (`<msh>.cut.json`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CutReport {
    pub joints: Vec<JointReport>,
    pub blocks: Vec<BlockReport>,
    pub near_misses: Vec<NearMiss>,
    /// Slivers bonded to a neighbour (`merge_slivers`).
    #[serde(default)]
    pub merged: usize,
    /// Quadratic elements made straight where they folded on a curved
    /// face (the .geo's `Mesh.HighOrderOptimize`, done deterministically).
    #[serde(default)]
    pub straightened: usize,
}

/// Why the joints could not be cut.
#[derive(Debug, thiserror::Error)]
pub enum JointError {
    #[error("the scene has joints, which the tool cuts with gmsh's library libgmsh.so.4.8 (Debian package libgmsh4.8, installed with the gmsh package: `apt-get install -y gmsh`, or `make deps`), but it could not be loaded: {why}")]
    Library { why: LoadError },

    #[error("gmsh failed on `{}` while cutting the joints: {detail}; fix the .geo (open it in the gmsh GUI to see the problem)", geo.display())]
    Gmsh { geo: PathBuf, detail: String },

    #[error("`{}` is not an OpenCASCADE model: the joints are cut by OpenCASCADE, so start the .geo with `SetFactory(\"OpenCASCADE\");` and build the bodies with it", geo.display())]
    NotOcc { geo: PathBuf },

    #[error("{key}.bodies: `{}` has no physical {what} \"{group}\"; name a body group of the .geo", geo.display())]
    NoBody { key: String, geo: PathBuf, what: &'static str, group: String },

    #[error("{key}: the joint name \"{name}\" is already a physical group of `{}`; the joint's faces become a contact group of that name, so give the joint another name", geo.display())]
    NameTaken { key: String, name: String, geo: PathBuf },

    #[error("{key} (\"{name}\", {label}) cuts nothing: {why}")]
    CutsNothing { key: String, name: String, label: String, why: String },

    #[error("the joints cut the bodies into {count} blocks, more than max_blocks = {max}: a mesh and a contact solve of that many blocks take long. Widen the spacing, limit sets with `bodies` or `extent`, or raise the top-level `max_blocks` to at least {count} if you mean it")]
    TooManyBlocks { count: usize, max: usize },

    #[error("cutting the joints into `{}` lost every entity of its physical group \"{group}\", which the cutter should have kept on the pieces: please report it with the .geo and the scene; meanwhile build the joints in the .geo and name them in [[contacts]]", geo.display())]
    LostGroup { geo: PathBuf, group: String },

    #[error("{what} `{}`: {source}", path.display())]
    Io {
        what: &'static str,
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

impl JointError {
    /// Whether the error is about a key of the scene (the caller names the
    /// scene file), rather than about gmsh, the .geo or a file.
    pub fn is_about_scene(&self) -> bool {
        matches!(
            self,
            JointError::NoBody { .. }
                | JointError::NameTaken { .. }
                | JointError::CutsNothing { .. }
                | JointError::TooManyBlocks { .. }
        )
    }
}

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

/// What the mesher is given besides the joints.
#[derive(Clone, Debug)]
pub struct MeshArgs<'a> {
    pub geo: &'a Path,
    pub dim: usize,
    pub order: usize,
    pub setnumber: &'a [(String, f64)],
    pub clscale: Option<f64>,
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
