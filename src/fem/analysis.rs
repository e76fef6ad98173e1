//! The kind of analysis: plane strain, plane stress, axisymmetric or solid.
//! It fixes the dimension of the mesh and of the displacement field, the
//! strain components an element carries and the volume measure (thickness,
//! `2 pi r` or none), so every kernel takes it.
//!
//! Its names (`"plane_strain"`, ...) are the ones the scene file, messages
//! and `summary.json` use. The enum derives `Deserialize` with those names so
//! that the scene reads `analysis = "..."` straight into it: one list of
//! variants, and serde's "unknown variant ..., expected one of ..." message
//! names them. serde is a data-model trait, not a file format: nothing here
//! knows TOML.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Kind of analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Analysis {
    PlaneStrain,
    PlaneStress,
    Axisymmetric,
    Solid,
}

impl Analysis {
    /// Spatial dimension of the mesh and of the displacement field: 2 or 3.
    pub fn dim(self) -> usize {
        match self {
            Analysis::Solid => 3,
            _ => 2,
        }
    }

    /// The analysis's name (`"plane_strain"`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            Analysis::PlaneStrain => "plane_strain",
            Analysis::PlaneStress => "plane_stress",
            Analysis::Axisymmetric => "axisymmetric",
            Analysis::Solid => "solid",
        }
    }

    /// True for the analyses that take a thickness (plane strain and stress).
    pub fn has_thickness(self) -> bool {
        matches!(self, Analysis::PlaneStrain | Analysis::PlaneStress)
    }
}

impl fmt::Display for Analysis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}
