//! The mechanical model every later stage reads: bodies, loads, supports,
//! prescribed DOFs, contact pairs and groups, load cases and water.

use super::body::Body;
use super::boundary::{FacetLoad, NodalLoad, SupportDofs};
use super::pairs::{Interface, Pair};
use super::water::GroupWater;
use crate::fem::Analysis;

#[derive(Clone, Debug)]
pub struct Model {
    pub analysis: Analysis,
    pub nd: usize,
    pub thickness: f64,
    pub gravity: [f64; 3],
    pub coords: Vec<[f64; 3]>,
    pub bodies: Vec<Body>,
    pub loads: Vec<FacetLoad>,
    /// Point loads, and forces spread over a group or a body (`force = [..]`).
    pub nodal_loads: Vec<NodalLoad>,
    /// The DOFs each `[[supports]]` entry holds, in the scene's order (a
    /// DOF two entries hold counts for the later one, whose value it has).
    pub supports: Vec<SupportDofs>,
    /// Prescribed value of each DOF (`node * nd + c`), None when free.
    pub prescribed: Vec<Option<f64>>,
    pub pairs: Vec<Pair>,
    pub interfaces: Vec<Interface>,
    /// Mesh node of every model node.
    pub mesh_node: Vec<usize>,
    /// Load factor of each load case at each load step. Case 0 is the ramp
    /// k / load_steps, which also scales prescribed displacements.
    pub cases: Vec<Vec<f64>>,
    /// The load case of each of the description's loads (`[[loads]]`).
    pub load_cases: Vec<usize>,
    /// The load case of gravity.
    pub gravity_case: usize,
    /// The load case of the initial stresses: factor 1 at every step (they
    /// are there before the first load).
    pub initial_case: usize,
    /// The load case of the initial equilibrium stage's hold load (the
    /// in-situ traction on the bodies' outer faces, [`super::hold`]): 0 at
    /// every load step, 1 in the stage. None without the stage.
    pub hold_case: Option<usize>,
    /// The water in the joints: one entry per contact group that has some.
    pub water: Vec<GroupWater>,
    /// Pseudo-static seismic accelerations (global axes; times a body's
    /// density, its load per unit volume) and their load cases.
    pub seismic: Vec<([f64; 3], usize)>,
}

impl Model {
    pub fn n_nodes(&self) -> usize {
        self.coords.len()
    }

    /// The pair at every node of every interface facet (`[interface][facet][node]`),
    /// `usize::MAX` where the node is in no pair (the tip of a joint ending
    /// inside a body).
    pub fn facet_pairs(&self) -> Vec<Vec<Vec<usize>>> {
        let mut out: Vec<Vec<Vec<usize>>> = self
            .interfaces
            .iter()
            .map(|i| i.facets.iter().map(|f| vec![usize::MAX; f.nodes.len()]).collect())
            .collect();
        for (p, pair) in self.pairs.iter().enumerate() {
            for &(f, a) in &pair.shares {
                out[pair.contact][f][a] = p;
            }
        }
        out
    }

    /// The body of every model node (the first that has it; `usize::MAX`
    /// for a node of no body).
    pub fn body_of_node(&self) -> Vec<usize> {
        let mut out = vec![usize::MAX; self.n_nodes()];
        for (b, body) in self.bodies.iter().enumerate().rev() {
            for &n in body.cells.iter().flat_map(|c| &c.nodes) {
                out[n] = b;
            }
        }
        out
    }

    /// The factor of every load case in the initial equilibrium stage
    /// (None without it): gravity, the initial stresses and the hold load
    /// at 1, every other case (the loads, joint water, prescribed
    /// displacements) at 0.
    pub fn stage_factors(&self) -> Option<Vec<f64>> {
        let hold = self.hold_case?;
        let on = [self.gravity_case, self.initial_case, hold];
        Some((0..self.cases.len()).map(|c| if on.contains(&c) { 1.0 } else { 0.0 }).collect())
    }

    /// Names of the bodies, for messages.
    pub fn body_names(&self, ids: &[usize]) -> String {
        ids.iter().map(|&b| self.bodies[b].label()).collect::<Vec<_>>().join(", ")
    }
}
