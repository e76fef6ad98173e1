//! Nodal forces of a solved load step: what each cell passes to its nodes,
//! what the step's loads apply there, what the contacts apply, and the
//! supports' reactions, which close the balance.
//!
//! A cell's internal nodal forces are its stresses integrated at the
//! quadrature points of its stiffness, `r_e = ∫ B̄ᵀ σ dV` with σ the total
//! stress (`K_e u_e` plus the initial stress's `∫ Bᵀ σ0 dV`, exactly as the
//! solve assembled them). Summed over the cells at a node they equal the
//! forces applied there — loads, contact forces and the support's reaction
//! — to round-off, so at a held DOF
//!
//! ```text
//! reaction = Σ_cells r_e − (body forces + facet loads + nodal loads) − contact
//! ```
//!
//! each load scaled by its case's factor at the step (body forces: gravity
//! and the seismic accelerations). Contact forces are the pairs'
//! `(sigma_n n + tau_t t + tau_b b) A`, taken from the interface basis to
//! the nodes ([`pair_forces`]; the forces themselves with
//! `traction = "lumped"`; with `"consistent"` their sum, not each node's),
//! and the water's push where a joint holds water (`sigma_n` is the
//! effective, solid-to-solid stress: the water loads both faces besides it).

use crate::contact::basis::FaceBasis;
use crate::fem::element::{self, dofs_per_node};
use crate::fem::material::d_matrix;
use crate::model::{Body, Model};
use crate::results::{ContactRun, StepResult};

/// Forces per model node, global components (zero where not asked for).
#[derive(Clone, Debug)]
pub struct NodeForces {
    /// Σ over the node's cells of their internal forces.
    pub internal: Vec<[f64; 3]>,
    /// The step's loads at the node: body forces, facet loads, nodal loads.
    pub applied: Vec<[f64; 3]>,
    /// The contact forces on the node.
    pub contact: Vec<[f64; 3]>,
}

impl NodeForces {
    /// What holds node `n` beyond its loads and contacts: the reaction of a
    /// support there (round-off at a free DOF).
    pub fn reaction(&self, n: usize) -> [f64; 3] {
        std::array::from_fn(|c| self.internal[n][c] - self.applied[n][c] - self.contact[n][c])
    }
}

/// The cell's coordinates and displacements, `nd` per node.
fn cell_data(model: &Model, nodes: &[usize], u: &[f64]) -> (Vec<[f64; 3]>, Vec<f64>) {
    let nd = model.nd;
    let xe = nodes.iter().map(|&n| model.coords[n]).collect();
    let ue = nodes.iter().flat_map(|&n| (0..nd).map(move |c| u[n * nd + c])).collect();
    (xe, ue)
}

/// The internal nodal forces `∫ B̄ᵀ σ dV` of one cell (`nd` per node, in
/// the cell's node order): `K_e u_e` and the initial stress's part, with
/// the stiffness's own rule and B-bar; zero for an inverted cell (which
/// the solve refused).
pub fn cell_internal(model: &Model, body: &Body, cell: &crate::mesh::Cell, u: &[f64]) -> Vec<f64> {
    let (analysis, nd) = (model.analysis, model.nd);
    let (xe, ue) = cell_data(model, &cell.nodes, u);
    let m = ue.len();
    let rule = element::stiffness_rule(analysis, cell.kind);
    let d = d_matrix(analysis, body.material.e, body.material.nu);
    let mut ke = Vec::new();
    if element::stiffness(analysis, cell.kind, body.material.nu, &xe, &d, model.thickness, &rule, &mut ke).is_err() {
        return vec![0.0; m];
    }
    let mut r: Vec<f64> = (0..m).map(|i| (0..m).map(|j| ke[i * m + j] * ue[j]).sum()).collect();
    if let Some(init) = body.initial {
        let sigma0 = |x: [f64; 3]| init.at(x, analysis, body.material.density, model.gravity);
        let mut f0 = vec![0.0; m];
        if element::initial_stress_force(analysis, cell.kind, &xe, &sigma0, model.thickness, &rule, &mut f0).is_ok() {
            // f0 = -∫ Bᵀ σ0: the initial stress's share of the internal forces is -f0
            r.iter_mut().zip(&f0).for_each(|(a, b)| *a -= b);
        }
    }
    debug_assert_eq!(m % nd, 0);
    r
}

/// The acceleration of a body's loads at the step: gravity at its case's
/// factor and, on a body with a density, every seismic acceleration at its
/// own (as the solve assembled them).
fn acceleration(model: &Model, body: &Body, factor: &dyn Fn(usize) -> f64) -> [f64; 3] {
    let mut a = model.gravity.map(|v| v * factor(model.gravity_case));
    for &(s, case) in model.seismic.iter().filter(|_| body.material.density > 0.0) {
        (0..3).for_each(|i| a[i] += s[i] * factor(case));
    }
    a
}

/// The cell's body force `∫ N ρ a dV` under the acceleration `a`.
fn cell_weight(model: &Model, body: &Body, cell: &crate::mesh::Cell, a: [f64; 3]) -> Vec<f64> {
    let nd = model.nd;
    let mut fe = vec![0.0; cell.nodes.len() * nd];
    let g = a.map(|v| v * body.material.density);
    if g.iter().any(|&v| v != 0.0) {
        let xe: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| model.coords[n]).collect();
        let _ = element::body_force(model.analysis, cell.kind, &xe, g, model.thickness, &mut fe);
    }
    fe
}

/// The nodal force of every pair on body I (its opposite on body II): the
/// contact's solid-to-solid force and the water's push in the joint, if
/// any. The solve's pair forces are in the interface basis
/// ([`crate::contact::basis`]: on tri6 and quad8 faces `f̃ = Qᵀ f`), so
/// the nodes' own forces are `Q⁻ᵀ f̃`: the same sum over each face, but
/// another share at each node, and the share is what a support node's
/// reaction is found from. The water's push is nodal already.
pub fn pair_forces(model: &Model, c: &ContactRun) -> Vec<[f64; 3]> {
    let n = model.pairs.len();
    let basis = FaceBasis::new(model);
    let solid: Vec<[f64; 3]> = (0..n).map(|p| c.force(p)).collect();
    let nodal: [Vec<f64>; 3] = std::array::from_fn(|i| {
        let component: Vec<f64> = solid.iter().map(|f| f[i]).collect();
        basis.inverse_transpose_apply(&component)
    });
    (0..n)
        .map(|p| {
            let water = c.water.as_ref().map_or([0.0; 3], |w| w.force[p]);
            std::array::from_fn(|i| nodal[i][p] + water[i])
        })
        .collect()
}

/// A facet load's nodal forces at factor `f` (`nd` per node of the facet).
fn facet_load(model: &Model, load: &crate::model::FacetLoad, f: f64) -> Vec<f64> {
    let xe: Vec<[f64; 3]> = load.cell.nodes.iter().map(|&k| model.coords[k]).collect();
    let mut fe = vec![0.0; xe.len() * model.nd];
    let (kind, analysis) = (&load.kind, model.analysis);
    let traction = |x: [f64; 3], nrm: [f64; 3]| kind.traction(x, nrm, analysis).map(|v| v * f);
    element::facet_force(analysis, load.cell.kind, &xe, load.sign, model.thickness, &traction, &mut fe);
    fe
}

fn add(to: &mut [[f64; 3]], nodes: &[usize], fe: &[f64], nd: usize) {
    for (a, &n) in nodes.iter().enumerate() {
        for c in 0..nd {
            to[n][c] += fe[a * nd + c];
        }
    }
}

/// The forces at the nodes `wanted` (by model node) of the step: the
/// internal forces of every cell that has one of them, and every load and
/// contact force there.
pub fn node_forces(model: &Model, step: &StepResult, wanted: &[bool]) -> NodeForces {
    let (n, nd) = (model.n_nodes(), model.nd);
    let factor = |case: usize| step.case_factors.get(case).copied().unwrap_or(step.load_factor);
    let mut out = NodeForces { internal: vec![[0.0; 3]; n], applied: vec![[0.0; 3]; n], contact: vec![[0.0; 3]; n] };
    for body in &model.bodies {
        let a = acceleration(model, body, &factor);
        for cell in body.cells.iter().filter(|c| c.nodes.iter().any(|&k| wanted[k])) {
            add(&mut out.internal, &cell.nodes, &cell_internal(model, body, cell, &step.u), nd);
            add(&mut out.applied, &cell.nodes, &cell_weight(model, body, cell, a), nd);
        }
    }
    for load in model.loads.iter().filter(|l| l.cell.nodes.iter().any(|&k| wanted[k])) {
        add(&mut out.applied, &load.cell.nodes, &facet_load(model, load, factor(load.case)), nd);
    }
    for load in model.nodal_loads.iter().filter(|l| wanted[l.node]) {
        (0..3).for_each(|c| out.applied[load.node][c] += load.force[c] * factor(load.case));
    }
    if let Some(c) = &step.contact {
        for (pair, f) in model.pairs.iter().zip(pair_forces(model, c)) {
            (0..3).for_each(|i| {
                out.contact[pair.k][i] += f[i];
                out.contact[pair.l][i] -= f[i];
            });
        }
    }
    for (k, &w) in wanted.iter().enumerate() {
        if !w {
            out.internal[k] = [0.0; 3];
            out.applied[k] = [0.0; 3];
            out.contact[k] = [0.0; 3];
        }
    }
    debug_assert_eq!(nd, dofs_per_node(model.analysis));
    out
}

/// The step's loads on each model body: its weight, its facet loads and
/// its nodal loads, global components.
pub fn applied_per_body(model: &Model, step: &StepResult) -> Vec<[f64; 3]> {
    let factor = |case: usize| step.case_factors.get(case).copied().unwrap_or(step.load_factor);
    let nd = model.nd;
    let mut out = vec![[0.0; 3]; model.bodies.len()];
    for (b, body) in model.bodies.iter().enumerate() {
        let a = acceleration(model, body, &factor);
        for cell in &body.cells {
            let fe = cell_weight(model, body, cell, a);
            (0..fe.len()).for_each(|i| out[b][i % nd] += fe[i]);
        }
    }
    for load in &model.loads {
        let fe = facet_load(model, load, factor(load.case));
        (0..fe.len()).for_each(|i| out[load.body][i % nd] += fe[i]);
    }
    for load in &model.nodal_loads {
        (0..3).for_each(|c| out[load.body][c] += load.force[c] * factor(load.case));
    }
    out
}
