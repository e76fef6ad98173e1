//! The options of a contact interface and of its iteration: what a slipping
//! pair carries in shear ([`SlipLaw`]), how pair states are updated between
//! iterations ([`StateRule`]) and how contact stresses are recovered from the
//! pair forces ([`TractionRecovery`]).
//!
//! Their names (`"coulomb"`, `"robust"`, `"lumped"`, ...) are the ones the
//! scene file uses; like [`crate::fem::Analysis`] they derive `Deserialize`
//! with those names, so the scene reads them straight into these enums and
//! serde's unknown-variant message lists the choices.

use serde::Deserialize;
use std::fmt;

/// What a slipping contact pair carries in shear (`slip = "..."`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SlipLaw {
    /// The Mohr–Coulomb limit `c - f*sigma_n`, opposite to the slip (default).
    #[default]
    Coulomb,
    /// Zero shear while slipping (the seed paper's scheme).
    Frictionless,
}

impl SlipLaw {
    /// The scene-file spelling.
    pub fn as_str(self) -> &'static str {
        match self {
            SlipLaw::Coulomb => "coulomb",
            SlipLaw::Frictionless => "frictionless",
        }
    }
}

impl fmt::Display for SlipLaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// How contact stresses are recovered from the pair forces (`traction = "..."`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TractionRecovery {
    /// Force over the area the pair controls (the paper's eq. 14, default).
    #[default]
    Lumped,
    /// Solve the interface mass matrix `M t = f` (exact for tractions the
    /// facets' shape functions contain, end pairs included).
    Consistent,
}

/// The state update of the contact iteration (`[solver] rule = "..."`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StateRule {
    /// A semismooth Newton method on the interface (primal-dual active sets
    /// for Coulomb friction, `newton.rs`): stick, slip and open sets and the
    /// slip directions found together, the friction force linearised in the
    /// normal force and the slip direction; cracked pairs keep f_t = 0; a
    /// cycle of state sets is broken by changing only the most violated pair
    /// (default).
    #[default]
    Robust,
    /// The paper: every pair judged by eq. 15–17 from its stresses alone,
    /// every change at once; a cycle is reported, not resolved.
    Paper,
}

/// How the interface system is solved (`[solver] interface = "..."`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InterfaceSolver {
    /// Sparse for many small parts (a rock mass of blocks), else dense below
    /// 20,000 interface DOFs (summed over the parts, a joint counted once
    /// per side) and iterative from there on (default).
    #[default]
    Auto,
    /// Each part condensed to a dense S; the interface system reduced to the
    /// contact unknowns once and factorised densely at every iteration:
    /// fastest while S fits in memory.
    Dense,
    /// No S is formed: each part's interior is factorised alone, and the
    /// interface system is solved by preconditioned GMRES that applies S
    /// through those factors, warm-started from the last contact iteration:
    /// memory is the factors alone, for joints and cuts of 2e4 DOFs and
    /// more. With MPI each rank applies its own parts' S.
    Iterative,
    /// Each part condensed to a dense S; the interface means factorised
    /// once, sparse, and each set of contact states solved by GMRES in its
    /// free relative displacements alone: for many small parts, a rock
    /// mass of hundreds of blocks, where the joints are most of the model.
    Sparse,
}
