//! One load step of a run: the displacements, the nodal stresses and, with
//! contact, each pair's state, stresses, frame, area and water, and how the
//! contact iteration went.

use crate::contact::law::{ContactState, PairResult};
use crate::contact::Summary;
use crate::fem::vec3::norm;
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
    /// Crossings whose locked slipping pairs' friction is off the
    /// equilibrium solved: their pairs, and by how much in force (see
    /// `contact::system::InterfaceSolution::locked_off`). Empty: none.
    pub locked_off: Vec<(Vec<usize>, f64)>,
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

    /// The crossing whose locked friction is farthest off the equilibrium
    /// solved ([`ContactRun::locked_off`]): its pairs, the force, and the
    /// force relative to the largest pair force (None where none is off).
    pub fn worst_locked_off(&self) -> Option<(&[usize], f64, f64)> {
        let scale = (0..self.pairs.len()).map(|p| norm(self.force(p))).fold(0.0, f64::max);
        let (pairs, off) = self.locked_off.iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
        Some((pairs, *off, if scale > 0.0 { off / scale } else { *off }))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_worst_locked_crossing_is_read_against_the_largest_pair_force() {
        let pair = |sigma_n: f64, tau_t: f64| PairResult { sigma_n, tau_t, ..Default::default() };
        let mut c = ContactRun {
            states: vec![ContactState::Slip; 3],
            // forces 3 x 2 = 6 (5 x 1.2), 2 x 1 and 0
            pairs: vec![pair(-3.0, 4.0), pair(-2.0, 0.0), pair(0.0, 0.0)],
            frames: vec![[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]; 3],
            areas: vec![1.2, 1.0, 1.0],
            summary: Summary::default(),
            water: None,
            law_residual: Vec::new(),
            cracked: Vec::new(),
            locked_off: Vec::new(),
        };
        assert!(c.worst_locked_off().is_none(), "none off: nothing to say");
        c.locked_off = vec![(vec![0, 1], 0.03), (vec![2], 0.12)];
        let (pairs, f, r) = c.worst_locked_off().expect("two crossings off");
        assert_eq!((pairs, f), (&[2][..], 0.12));
        assert!((r - 0.02).abs() < 1e-15, "{r}");
    }
}
