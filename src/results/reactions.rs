//! What the reactions of a solved load step hold (computed by
//! `recover::reactions`): every support group's force and moment, and
//! every body group's balance. Kept with the results so that the results
//! and the recovery that fills them do not import each other.

/// One support group's reaction, the force the support applies to the model.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SupportReaction {
    pub group: String,
    /// The DOFs it holds.
    pub dofs: usize,
    pub force: [f64; 3],
    /// The moment of its nodal reactions about `about` (z only in 2D).
    pub moment: [f64; 3],
    /// The centroid of its held nodes.
    pub about: [f64; 3],
}

/// One body group's forces (all its blocks): the loads (seismic body
/// forces included), the contact forces (with the water's push in its
/// joints) and the supports' reactions on it, and their sum.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BodyBalance {
    pub group: String,
    pub applied: [f64; 3],
    pub contact: [f64; 3],
    pub supports: [f64; 3],
    pub remainder: [f64; 3],
}

/// The reactions of a step.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Reactions {
    pub supports: Vec<SupportReaction>,
    pub bodies: Vec<BodyBalance>,
    /// The largest |force| left at a free DOF of a node next to a support,
    /// relative to the largest internal force there: the round-off of the
    /// balance (1e-10 or below when the solve is exact).
    pub free_residual: f64,
}
