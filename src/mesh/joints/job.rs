//! What a cut is asked: each joint's orientation, placement and
//! persistence ([`JointSpec`]), every joint of a scene ([`CutJob`]) and
//! what the mesher is given besides ([`MeshArgs`]).

use std::path::Path;

use super::geometry::{self, Shape};

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
const CUTTER_VERSION: u32 = 4;

/// Every joint of a scene and the most blocks it may make.
#[derive(Clone, Debug, PartialEq)]
pub struct CutJob {
    pub joints: Vec<JointSpec>,
    pub max_blocks: usize,
    /// Mesh the blocks structured where gmsh can (`[gmsh] structured`):
    /// hexahedra in six-sided blocks of four-sided faces, quadrangles in
    /// four-sided 2D blocks.
    pub structured: bool,
    /// Bond each sliver block to a neighbour (`merge_slivers`, `slivers`).
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

/// What the mesher is given besides the joints.
#[derive(Clone, Debug)]
pub struct MeshArgs<'a> {
    pub geo: &'a Path,
    pub dim: usize,
    pub order: usize,
    pub setnumber: &'a [(String, f64)],
    pub clscale: Option<f64>,
}
