//! Recovery after the solve: stresses at quadrature points, extrapolated to
//! the nodes and averaged per body (never across bodies), error norms
//! against a closed form, and values sampled along probe lines; the
//! nodal forces of a step, the supports' reactions and the section
//! forces of cuts through the bodies, and the bearing pressure of a
//! contact face ([`forces`], [`reactions`], [`sections`], [`bearing`]).

pub mod bearing;
pub mod forces;
pub mod reactions;
pub mod sections;

use crate::analytic::Exact;
use crate::fem::element::{self, dofs_per_node};
use crate::fem::material::{d_matrix, full_stress, von_mises};
use crate::fem::{quadrature, shape};
use crate::model::Model;

/// Nodal stresses of one body: `nodes[i]` is a model node, `stress[i]` its
/// averaged stress.
#[derive(Clone)]
pub struct BodyStress {
    pub nodes: Vec<usize>,
    pub stress: Vec<[f64; 6]>,
}

fn element_u(model: &Model, nodes: &[usize], u: &[f64]) -> Vec<f64> {
    let nd = model.nd;
    nodes.iter().flat_map(|&n| (0..nd).map(move |c| u[n * nd + c])).collect()
}

fn coords(model: &Model, nodes: &[usize]) -> Vec<[f64; 3]> {
    nodes.iter().map(|&n| model.coords[n]).collect()
}

/// Total stress at a point of a cell: the initial stress plus `D eps`, the
/// strain with the cell's mean dilatation where it uses B-bar
/// ([`element::mean_dilatation`]), as its stiffness did.
fn total_stress(
    model: &Model,
    body: &crate::model::Body,
    d: &[f64],
    p: &element::Point,
    ue: &[f64],
    mean: Option<f64>,
) -> [f64; 6] {
    let mut s = full_stress(
        model.analysis,
        body.material.e,
        body.material.nu,
        d,
        &element::strain(model.analysis, p, ue, mean),
    );
    if body.initial.is_some() {
        let s0 = body.initial_at(p.x, model.analysis, model.gravity);
        for (a, b) in s.iter_mut().zip(s0) {
            *a += b;
        }
    }
    s
}

/// The distinct nodes of a body, in order of first use by its cells.
pub fn body_nodes(body: &crate::model::Body) -> Vec<usize> {
    let mut seen = std::collections::HashSet::new();
    body.cells.iter().flat_map(|c| c.nodes.iter().copied()).filter(|n| seen.insert(*n)).collect()
}

/// Extrapolated, body-averaged nodal stresses.
pub fn nodal_stresses(model: &Model, u: &[f64]) -> Vec<BodyStress> {
    let mut local = vec![usize::MAX; model.n_nodes()];
    model
        .bodies
        .iter()
        .map(|body| {
            let d = d_matrix(model.analysis, body.material.e, body.material.nu);
            let nodes = body_nodes(body);
            for (i, &n) in nodes.iter().enumerate() {
                local[n] = i;
            }
            let mut sum = vec![[0.0; 6]; nodes.len()];
            let mut count = vec![0u32; nodes.len()];
            let mut cache: Vec<(crate::mesh::CellKind, Vec<quadrature::QuadPoint>, Vec<f64>)> = Vec::new();
            for cell in &body.cells {
                if !cache.iter().any(|(k, _, _)| *k == cell.kind) {
                    let rule = quadrature::stiffness_rule(cell.kind);
                    let ex = quadrature::extrapolation(cell.kind, &rule);
                    cache.push((cell.kind, rule, ex));
                }
                let (_, rule, ex) = cache.iter().find(|(k, _, _)| *k == cell.kind).expect("cached");
                let xe = coords(model, &cell.nodes);
                let ue = element_u(model, &cell.nodes, u);
                let mean = element::mean_dilatation(model.analysis, cell.kind, body.material.nu, &xe, &ue);
                let at_points: Vec<[f64; 6]> = rule
                    .iter()
                    .map(|q| match element::point(cell.kind, &xe, q.xi) {
                        Ok(p) => total_stress(model, body, &d, &p, &ue, mean),
                        Err(_) => [f64::NAN; 6],
                    })
                    .collect();
                let np = rule.len();
                for (a, &n) in cell.nodes.iter().enumerate() {
                    let li = local[n];
                    for comp in 0..6 {
                        sum[li][comp] += (0..np).map(|g| ex[a * np + g] * at_points[g][comp]).sum::<f64>();
                    }
                    count[li] += 1;
                }
            }
            for &n in &nodes {
                local[n] = usize::MAX;
            }
            let stress = sum.iter().zip(&count).map(|(s, &c)| s.map(|v| v / c.max(1) as f64)).collect();
            BodyStress { nodes, stress }
        })
        .collect()
}

/// Relative L2 errors of displacement and stress against a closed form.
pub struct Errors {
    pub displacement_l2: f64,
    pub stress_l2: f64,
}

/// `exact[b]` is the closed form of body b ([`fn@crate::analytic::exact`]).
pub fn errors(model: &Model, u: &[f64], exact: &[Box<dyn Exact>]) -> Errors {
    let (mut eu, mut nu_, mut es, mut ns) = (0.0, 0.0, 0.0, 0.0);
    let nd = dofs_per_node(model.analysis);
    for (body, exact) in model.bodies.iter().zip(exact) {
        let d = d_matrix(model.analysis, body.material.e, body.material.nu);
        for cell in &body.cells {
            let xe = coords(model, &cell.nodes);
            let ue = element_u(model, &cell.nodes, u);
            let mean = element::mean_dilatation(model.analysis, cell.kind, body.material.nu, &xe, &ue);
            let rule = quadrature::rule(cell.kind, 2 * cell.kind.order() + 2);
            for q in &rule {
                let Ok(p) = element::point(cell.kind, &xe, q.xi) else { continue };
                let w = q.w * p.det_j * if model.analysis == crate::fem::Analysis::Axisymmetric { p.x[0] } else { 1.0 };
                let ex = exact.displacement(p.x);
                for c in 0..nd {
                    let uh: f64 = (0..cell.kind.n_nodes()).map(|a| p.n[a] * ue[a * nd + c]).sum();
                    eu += w * (uh - ex[c]).powi(2);
                    nu_ += w * ex[c].powi(2);
                }
                let sh = total_stress(model, body, &d, &p, &ue, mean);
                let se = exact.stress(p.x);
                for c in 0..6 {
                    es += w * (sh[c] - se[c]).powi(2);
                    ns += w * se[c].powi(2);
                }
            }
        }
    }
    Errors { displacement_l2: (eu / nu_).sqrt(), stress_l2: (es / ns).sqrt() }
}

/// A probe line (`[[probes]]`): sample the solution at `points` equally
/// spaced points on the segment `from`–`to` (both ends included).
#[derive(Debug, Clone, PartialEq)]
pub struct Probe {
    pub name: String,
    pub from: [f64; 3],
    pub to: [f64; 3],
    pub points: usize,
}

/// Values at one probe point.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Sample {
    pub x: [f64; 3],
    pub displacement: [f64; 3],
    pub stress: [f64; 6],
    pub von_mises: f64,
    /// Whether the point lies in the model.
    pub found: bool,
}

/// Samples displacement and stress along a probe line, evaluated directly in
/// the element(s) containing each point (averaged where several do).
pub fn probe(model: &Model, u: &[f64], probe: &Probe) -> Vec<Sample> {
    let nd = model.nd;
    (0..probe.points)
        .map(|i| {
            let s = i as f64 / (probe.points - 1) as f64;
            let x: [f64; 3] = std::array::from_fn(|c| probe.from[c] + s * (probe.to[c] - probe.from[c]));
            let mut disp = [0.0; 3];
            let mut stress = [0.0; 6];
            let mut hits = 0.0;
            for body in &model.bodies {
                let d = d_matrix(model.analysis, body.material.e, body.material.nu);
                for cell in &body.cells {
                    let xe = coords(model, &cell.nodes);
                    if !in_box(&xe, x) {
                        continue;
                    }
                    let Some(xi) = shape::locate(cell.kind, &xe, x) else { continue };
                    let Ok(p) = element::point(cell.kind, &xe, xi) else { continue };
                    let ue = element_u(model, &cell.nodes, u);
                    for c in 0..nd {
                        disp[c] += (0..cell.kind.n_nodes()).map(|a| p.n[a] * ue[a * nd + c]).sum::<f64>();
                    }
                    let sh = total_stress(
                        model,
                        body,
                        &d,
                        &p,
                        &ue,
                        element::mean_dilatation(model.analysis, cell.kind, body.material.nu, &xe, &ue),
                    );
                    for c in 0..6 {
                        stress[c] += sh[c];
                    }
                    hits += 1.0;
                }
            }
            if hits > 0.0 {
                disp = disp.map(|v| v / hits);
                stress = stress.map(|v| v / hits);
            }
            Sample { x, displacement: disp, stress, von_mises: von_mises(&stress), found: hits > 0.0 }
        })
        .collect()
}

fn in_box(xe: &[[f64; 3]], x: [f64; 3]) -> bool {
    (0..3).all(|c| {
        let lo = xe.iter().map(|p| p[c]).fold(f64::INFINITY, f64::min);
        let hi = xe.iter().map(|p| p[c]).fold(f64::NEG_INFINITY, f64::max);
        let pad = 0.05 * (hi - lo);
        x[c] >= lo - pad && x[c] <= hi + pad
    })
}
