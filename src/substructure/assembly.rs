//! Assembly of one part (a set of bodies joined by shared nodes): stiffness
//! and load vector (body forces, initial stresses, facet loads, nodal
//! forces) over a given DOF numbering.
//!
//! `dof_of[node * nd + c]` is the equation of a DOF or [`NONE`]. A DOF with a
//! prescribed value (`Model::prescribed`) that is not numbered moves its
//! `K_e u` contribution to the right-hand side; a DOF that is neither
//! numbered nor prescribed belongs to another part and is skipped.

use crate::fem::element::{self, Inverted};
use crate::fem::material::d_matrix;
use crate::fem::quadrature;
use crate::fem::sparse::{SymMatrix, NONE};
use crate::mesh::CellKind;
use crate::model::{Model, ModelError};

/// Stiffness (lower triangle) and right-hand sides of a part, one per load
/// case (`Model::cases`; prescribed displacements belong to case 0).
pub struct Assembled {
    pub k: SymMatrix,
    pub f: Vec<Vec<f64>>,
}

fn cell_coords(model: &Model, nodes: &[usize]) -> Vec<[f64; 3]> {
    nodes.iter().map(|&n| model.coords[n]).collect()
}

fn element_dofs(nodes: &[usize], nd: usize, dof_of: &[usize], out: &mut Vec<usize>) {
    out.clear();
    for &n in nodes {
        for c in 0..nd {
            out.push(dof_of[n * nd + c]);
        }
    }
}

/// Assembles the cells `cells` ((body, index in its cells)) of the model
/// into `n` equations, with the loads on their faces.
pub fn assemble(model: &Model, cells: &[(usize, usize)], dof_of: &[usize], n: usize) -> Result<Assembled, ModelError> {
    let nd = model.nd;
    let cell_nodes = cells.iter().map(|&(b, c)| model.bodies[b].cells[c].nodes.as_slice());
    let mut k = SymMatrix::pattern(n, nd, dof_of, cell_nodes);
    let mut f = vec![vec![0.0; n]; model.cases.len()];
    let mut ke = Vec::new();
    let mut dofs = Vec::new();
    let mut rules: Vec<(CellKind, Vec<quadrature::QuadPoint>)> = Vec::new();
    // the part's cells body by body (their cells are listed that way)
    for run in cells.chunk_by(|a, b| a.0 == b.0) {
        let body = &model.bodies[run[0].0];
        let d = d_matrix(model.analysis, body.material.e, body.material.nu);
        let g = model.gravity;
        let weight = [g[0] * body.material.density, g[1] * body.material.density, g[2] * body.material.density];
        let has_weight = weight.iter().any(|&w| w != 0.0);
        for cell in run.iter().map(|&(_, c)| &body.cells[c]) {
            let rule = match rules.iter().find(|(kind, _)| *kind == cell.kind) {
                Some((_, r)) => r,
                None => {
                    rules.push((cell.kind, element::stiffness_rule(model.analysis, cell.kind)));
                    &rules.last().expect("just pushed").1
                }
            };
            let xe = cell_coords(model, &cell.nodes);
            let inverted =
                |e: Inverted| ModelError::Inverted { body: body.name.clone(), tag: cell.tag, det_j: e.det_j };
            element::stiffness(model.analysis, cell.kind, body.material.nu, &xe, &d, model.thickness, rule, &mut ke)
                .map_err(inverted)?;
            element_dofs(&cell.nodes, nd, dof_of, &mut dofs);
            k.add(&dofs, &ke);
            let m = dofs.len();
            let mut fe = vec![0.0; m];
            if has_weight {
                element::body_force(model.analysis, cell.kind, &xe, weight, model.thickness, &mut fe)
                    .map_err(inverted)?;
                scatter(&dofs, &fe, &mut f[model.gravity_case]);
                fe.iter_mut().for_each(|v| *v = 0.0);
            }
            // pseudo-static seismic accelerations, on bodies with a density
            for &(a, case) in model.seismic.iter().filter(|_| body.material.density > 0.0) {
                let force = a.map(|c| c * body.material.density);
                element::body_force(model.analysis, cell.kind, &xe, force, model.thickness, &mut fe)
                    .map_err(inverted)?;
                scatter(&dofs, &fe, &mut f[case]);
                fe.iter_mut().for_each(|v| *v = 0.0);
            }
            if let Some(init) = body.initial {
                fe.iter_mut().for_each(|v| *v = 0.0);
                let sigma0 = |x: [f64; 3]| init.at(x, model.analysis, body.material.density, model.gravity);
                element::initial_stress_force(model.analysis, cell.kind, &xe, &sigma0, model.thickness, rule, &mut fe)
                    .map_err(inverted)?;
                scatter(&dofs, &fe, &mut f[model.initial_case]);
                fe.iter_mut().for_each(|v| *v = 0.0);
            }
            // prescribed displacements: f -= K_e[:, j] u_j
            prescribed_force(model, &cell.nodes, &dofs, &ke, &mut fe);
            scatter(&dofs, &fe, &mut f[0]);
        }
    }
    face_and_point_loads(model, cells, dof_of, &mut f);
    Ok(Assembled { k, f })
}

/// `fe -= K_e[:, j] u_j` for each prescribed displacement u_j of the cell
/// at `nodes` (its `dofs` NONE there).
fn prescribed_force(model: &Model, nodes: &[usize], dofs: &[usize], ke: &[f64], fe: &mut [f64]) {
    let (nd, m) = (model.nd, dofs.len());
    for (j, &node) in nodes.iter().enumerate() {
        for c in 0..nd {
            let jj = j * nd + c;
            if dofs[jj] != NONE {
                continue;
            }
            if let Some(u) = model.prescribed[node * nd + c] {
                if u != 0.0 {
                    for i in 0..m {
                        fe[i] -= ke[i * m + jj] * u;
                    }
                }
            }
        }
    }
}

/// The loads on the facets of the `cells` and the point loads and forces
/// spread onto nodes whose owning cell is one of them, into `f`.
fn face_and_point_loads(model: &Model, cells: &[(usize, usize)], dof_of: &[usize], f: &mut [Vec<f64>]) {
    let nd = model.nd;
    let mut dofs = Vec::new();
    for load in &model.loads {
        if cells.binary_search(&(load.body, load.element)).is_err() {
            continue;
        }
        element_dofs(&load.cell.nodes, nd, dof_of, &mut dofs);
        let xe = cell_coords(model, &load.cell.nodes);
        let mut fe = vec![0.0; dofs.len()];
        let (kind, analysis) = (&load.kind, model.analysis);
        let traction = |x: [f64; 3], n: [f64; 3]| kind.traction(x, n, analysis);
        element::facet_force(model.analysis, load.cell.kind, &xe, load.sign, model.thickness, &traction, &mut fe);
        scatter(&dofs, &fe, &mut f[load.case]);
    }
    // point loads and forces spread onto nodes, with the cell that owns each
    for load in &model.nodal_loads {
        if cells.binary_search(&(load.body, load.element)).is_ok() {
            for c in 0..nd {
                let d = dof_of[load.node * nd + c];
                if d != NONE {
                    f[load.case][d] += load.force[c];
                }
            }
        }
    }
}

fn scatter(dofs: &[usize], fe: &[f64], f: &mut [f64]) {
    for (i, &d) in dofs.iter().enumerate() {
        if d != NONE {
            f[d] += fe[i];
        }
    }
}
