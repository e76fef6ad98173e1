//! What a cut made, kept beside its mesh as JSON: the planes and areas of
//! each joint, the blocks, and the planes that pass close to a corner.

use serde::{Deserialize, Serialize};

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
