//! The forces at one cut of a section: its resultant force and moment in
//! the cut's axes (N, V, V3, T, M, M2) and what lies on either side.

use crate::fem::vec3::dot;

/// The forces at one cut.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Station {
    /// Along the section: degrees from the ring's reference direction, the
    /// distance from a beam's end, 0 for a single cut.
    pub position: f64,
    /// Where the moments are taken: the middle of the cut across the member.
    pub at: [f64; 3],
    /// n, e2, e3.
    pub frame: [[f64; 3]; 3],
    /// On the -n side from the +n side, global axes.
    pub force: [f64; 3],
    /// About `at`, global axes.
    pub moment: [f64; 3],
    /// The extent of the cut across the member (along e2; a ring: radially).
    pub depth: f64,
    pub sides: Sides,
}

/// What lies on either side of a cut.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Sides {
    /// Material on both sides: the band of weights across the cut.
    Both,
    /// An end face: the forces of its nodes are the section's.
    End,
    /// A symmetry plane (its nodes held along n alone): the forces of its
    /// nodes along n are the section's, the rest the mirror half's.
    Symmetry,
}

impl Station {
    /// Normal force, tension positive.
    pub fn n(&self) -> f64 {
        dot(self.force, self.frame[0])
    }
    /// Shear force along e2 (beam convention: -F·e2).
    pub fn v(&self) -> f64 {
        -dot(self.force, self.frame[1])
    }
    /// Shear force along e3 (3D).
    pub fn v3(&self) -> f64 {
        -dot(self.force, self.frame[2])
    }
    /// Torque about n (3D).
    pub fn t(&self) -> f64 {
        dot(self.moment, self.frame[0])
    }
    /// Bending moment about e3 (sagging positive; 2D: about z).
    pub fn m(&self) -> f64 {
        dot(self.moment, self.frame[2])
    }
    /// Bending moment about e2 (3D).
    pub fn m2(&self) -> f64 {
        dot(self.moment, self.frame[1])
    }
}

/// A section's forces at each of its cuts that meets its bodies.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SectionForces {
    pub name: String,
    /// "line", "plane", "beam" or "ring".
    pub kind: &'static str,
    pub stations: Vec<Station>,
    /// Cuts that met no cell of the bodies.
    pub missed: usize,
}
