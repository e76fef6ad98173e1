//! One load step of a run: the displacements, the nodal stresses and, with
//! contact, each pair's state, stresses, frame, area and water, and how the
//! contact iteration went.

use crate::contact::law::{ContactState, PairResult};
use crate::contact::Summary;
use crate::recover::BodyStress;

/// One load step.
pub struct StepResult {
    pub step: usize,
    /// The ramp factor k / load_steps (loads without `factors`, prescribed
    /// displacements, gravity without `gravity_factors`).
    pub load_factor: f64,
    /// The factor of every load case at this step (`Model::cases`).
    pub case_factors: Vec<f64>,
    pub u: Vec<f64>,
    /// Nodal stresses (empty when `[output] fields` leaves stress out).
    pub stresses: Vec<BodyStress>,
    pub contact: Option<ContactRun>,
}

/// The contact result of a load step: each pair's state, stresses, frame
/// and area, and how the iteration went.
#[derive(Clone)]
pub struct ContactRun {
    pub states: Vec<ContactState>,
    pub pairs: Vec<PairResult>,
    /// Each pair's frame, rows n, t, b (global components): `sigma_n`,
    /// `tau_t`, `tau_b` are along them.
    pub frames: Vec<[[f64; 3]; 3]>,
    /// The area each pair controls (its stresses times it are its forces).
    pub areas: Vec<f64>,
    pub summary: Summary,
    /// The water in the joints at each pair, when they have some: its
    /// pressure u at the pair's node, and its force on body I (global
    /// axes) pushing the faces apart. `pairs` holds the solid-to-solid
    /// stresses, the effective `sigma_n'`; the total is `sigma_n' - u`.
    pub water: Option<PairWater>,
    /// How far each pair's stresses are from the contact law in its state
    /// (stress units; `contact::law::law_residual` over the pair's area).
    pub law_residual: Vec<f64>,
    /// Whether each pair has cracked by the step's end (the contact
    /// iteration's crack memory: in an earlier step, on the way through
    /// this one, or open or slipping now): it has no tensile strength and
    /// its residual cohesion. Empty: none cracked.
    pub cracked: Vec<bool>,
}

/// The water at every pair of a step (zero on dry pairs).
#[derive(Clone, Debug)]
pub struct PairWater {
    pub pressure: Vec<f64>,
    pub force: Vec<[f64; 3]>,
}

impl ContactRun {
    /// Whether pair `p` has cracked by the step's end ([`ContactRun::cracked`]).
    pub fn is_cracked(&self, p: usize) -> bool {
        self.cracked.get(p).copied().unwrap_or(false)
    }

    /// The pair farthest from the contact law and its residual relative to
    /// the largest traction `|(sigma_n, tau)|` of any pair (None without
    /// pairs or residuals).
    pub fn worst_law_residual(&self) -> Option<(usize, f64)> {
        let scale = self.pairs.iter().map(|r| r.sigma_n.hypot(r.tau())).fold(0.0, f64::max);
        let (p, r) = self.law_residual.iter().copied().enumerate().max_by(|a, b| a.1.total_cmp(&b.1))?;
        Some((p, if scale > 0.0 { r / scale } else { r }))
    }

    /// The shear traction of pair `p` on body I in global axes.
    pub fn shear(&self, p: usize) -> [f64; 3] {
        let (f, r) = (&self.frames[p], &self.pairs[p]);
        std::array::from_fn(|i| r.tau_t * f[1][i] + r.tau_b * f[2][i])
    }

    /// The water pressure at pair `p` (0 when dry).
    pub fn water_pressure(&self, p: usize) -> f64 {
        self.water.as_ref().map_or(0.0, |w| w.pressure[p])
    }

    /// The total normal stress at pair `p`, `sigma_n' - u`.
    pub fn sigma_n_total(&self, p: usize) -> f64 {
        self.pairs[p].sigma_n - self.water_pressure(p)
    }

    /// The contact force of pair `p` on body I in global axes.
    pub fn force(&self, p: usize) -> [f64; 3] {
        let (f, r, a) = (&self.frames[p], &self.pairs[p], self.areas[p]);
        std::array::from_fn(|i| (r.sigma_n * f[0][i] + r.tau_t * f[1][i] + r.tau_b * f[2][i]) * a)
    }
}
