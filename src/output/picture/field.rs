//! The quantity that colours the deformed picture, its spelling and its
//! name for a reader.

use crate::fem::Analysis;

/// The quantity that colours the deformed picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    VonMises,
    /// Magnitude of the displacement.
    Displacement,
    Sxx,
    Syy,
    Szz,
    Sxy,
    Syz,
    Sxz,
}

impl Field {
    pub const ALL: [Field; 8] =
        [Field::VonMises, Field::Displacement, Field::Sxx, Field::Syy, Field::Szz, Field::Sxy, Field::Syz, Field::Sxz];

    /// Spelling for file names and command lines (`von_mises`, `sxx`, ...).
    pub fn key(self) -> &'static str {
        match self {
            Field::VonMises => "von_mises",
            Field::Displacement => "displacement",
            Field::Sxx => "sxx",
            Field::Syy => "syy",
            Field::Szz => "szz",
            Field::Sxy => "sxy",
            Field::Syz => "syz",
            Field::Sxz => "sxz",
        }
    }

    pub fn parse(s: &str) -> Option<Field> {
        Field::ALL.into_iter().find(|f| f.key() == s)
    }

    /// Name for a reader; axisymmetric models have x = r and y = z (the axis).
    pub fn label(self, analysis: Analysis) -> &'static str {
        let axi = analysis == Analysis::Axisymmetric;
        match self {
            Field::VonMises => "von Mises stress",
            Field::Displacement => "displacement |u|",
            Field::Sxx if axi => "σrr (radial stress)",
            Field::Syy if axi => "σzz (axial stress)",
            Field::Szz if axi => "σθθ (hoop stress)",
            Field::Sxy if axi => "σrz (shear stress)",
            Field::Sxx => "σxx (normal stress)",
            Field::Syy => "σyy (normal stress)",
            Field::Szz => "σzz (normal stress)",
            Field::Sxy => "σxy (shear stress)",
            Field::Syz => "σyz (shear stress)",
            Field::Sxz => "σxz (shear stress)",
        }
    }

    /// Index in the stress vector `[xx, yy, zz, xy, yz, xz]`.
    pub(super) fn component(self) -> Option<usize> {
        match self {
            Field::VonMises | Field::Displacement => None,
            Field::Sxx => Some(0),
            Field::Syy => Some(1),
            Field::Szz => Some(2),
            Field::Sxy => Some(3),
            Field::Syz => Some(4),
            Field::Sxz => Some(5),
        }
    }
}
