//! The contact files of a step: the interface as a VTU mesh of the pairs
//! (state, stresses, gap, slip) and contact.csv, one row per pair.

use super::csv::csv_field;
use super::unsettled;
use super::vtu::{self, Field, IntField};
use crate::error::Result;
use crate::mesh::Cell;
use crate::model::Model;
use crate::results::ContactRun;

/// The contact VTU's points and cells: every interface facet, then a
/// vertex cell per pair; the pair at each point (`usize::MAX`: none), and
/// each cell's interface and pair state (-1 for a facet).
struct ContactMesh {
    points: Vec<[f64; 3]>,
    pairs: Vec<usize>,
    cells: Vec<Cell>,
    iface_id: Vec<i32>,
    pair_status: Vec<i32>,
}

fn contact_mesh(model: &Model, c: &ContactRun) -> ContactMesh {
    let mut pair_of = vec![usize::MAX; model.n_nodes()];
    for (i, p) in model.pairs.iter().enumerate() {
        pair_of[p.k] = i;
    }
    let mut local = vec![usize::MAX; model.n_nodes()];
    let mut points = Vec::new();
    let mut pairs = Vec::new();
    let mut cells = Vec::new();
    let mut iface_id = Vec::new();
    let mut pair_status = Vec::new();
    for (ii, iface) in model.interfaces.iter().enumerate() {
        for f in &iface.facets {
            let nodes = f
                .nodes
                .iter()
                .map(|&n| {
                    if local[n] == usize::MAX {
                        local[n] = points.len();
                        points.push(model.coords[n]);
                        pairs.push(pair_of[n]);
                    }
                    local[n]
                })
                .collect();
            cells.push(Cell { kind: f.kind, nodes, tag: f.tag });
            iface_id.push(ii as i32);
            pair_status.push(-1);
        }
    }
    // a vertex cell per pair with its state as cell data, which ParaView
    // colours as categories (point data blends between 0, 1 and 2)
    for (i, p) in model.pairs.iter().enumerate() {
        if local[p.k] == usize::MAX {
            local[p.k] = points.len();
            points.push(model.coords[p.k]);
            pairs.push(i);
        }
        cells.push(Cell { kind: crate::mesh::CellKind::Point1, nodes: vec![local[p.k]], tag: 0 });
        iface_id.push(p.contact as i32);
        pair_status.push(c.states[i].code());
    }
    ContactMesh { points, pairs, cells, iface_id, pair_status }
}

/// The interfaces, as body I's facets, with the pair values at their
/// nodes, then one vertex cell per pair (at its node k) whose cell data
/// `pair_status` is its state (0 open, 1 slip, 2 stick; -1 on the facets);
/// cell data `interface` is the contact of every cell.
pub(super) fn contact_vtu(model: &Model, c: &ContactRun) -> Result<Vec<u8>> {
    let ContactMesh { points, pairs, cells, iface_id, pair_status } = contact_mesh(model, c);
    let get = |f: &dyn Fn(usize) -> f64| -> Vec<f64> {
        pairs.iter().map(|&p| if p == usize::MAX { 0.0 } else { f(p) }).collect()
    };
    let status: Vec<i32> = pairs.iter().map(|&p| if p == usize::MAX { -1 } else { c.states[p].code() }).collect();
    let sigma_n = get(&|p| c.sigma_n_total(p));
    let sigma_n_eff = get(&|p| c.pairs[p].sigma_n);
    let water = get(&|p| c.water_pressure(p));
    let tau = get(&|p| c.pairs[p].tau());
    let gap = get(&|p| c.pairs[p].gap);
    let slip = get(&|p| c.pairs[p].slip);
    let shear: Vec<f64> = pairs.iter().flat_map(|&p| if p == usize::MAX { [0.0; 3] } else { c.shear(p) }).collect();
    let area = get(&|p| c.areas[p]);
    let status_f: Vec<f64> = status.iter().map(|&s| s as f64).collect();
    let changes = unsettled::changes(c).map(|k| get(&|p| k[p] as f64));
    let mut point_data = vec![
        Field { name: "status", n_comp: 1, values: &status_f },
        Field { name: "sigma_n", n_comp: 1, values: &sigma_n },
        Field { name: "tau", n_comp: 1, values: &tau },
        Field { name: "gap", n_comp: 1, values: &gap },
        Field { name: "slip", n_comp: 1, values: &slip },
        Field { name: "shear", n_comp: 3, values: &shear },
        Field { name: "area", n_comp: 1, values: &area },
    ];
    if c.water.is_some() {
        point_data.push(Field { name: "water_pressure", n_comp: 1, values: &water });
        point_data.push(Field { name: "sigma_n_eff", n_comp: 1, values: &sigma_n_eff });
    }
    if let Some(k) = &changes {
        point_data.push(Field { name: "changes", n_comp: 1, values: k });
    }
    let law_residual = get(&|p| c.law_residual.get(p).copied().unwrap_or(0.0));
    point_data.push(Field { name: "law_residual", n_comp: 1, values: &law_residual });
    Ok(vtu::vtu_bytes(
        &points,
        &cells,
        &point_data,
        &[],
        &[IntField { name: "interface", values: &iface_id }, IntField { name: "pair_status", values: &pair_status }],
    )?)
}

/// One row per contact pair: position, state and the pair's values; with
/// water in the joints, `sigma_n` is the total normal stress and the rows
/// end with the water pressure u and the effective `sigma_n_eff = sigma_n
/// + u` the law judges.
pub(super) fn contact_csv(model: &Model, c: &ContactRun) -> String {
    let body = model.body_of_node();
    let changes = unsettled::changes(c);
    let mut s = String::from(
        "pair,x,y,z,status,sigma_n,tau_t,tau_b,gap,slip,area,tau_x,tau_y,tau_z,n_x,n_y,n_z,contact,block_i,block_ii",
    );
    if c.water.is_some() {
        s += ",water_pressure,sigma_n_eff";
    }
    s += if changes.is_some() { ",changes,law_residual\n" } else { ",law_residual\n" };
    for (i, (p, r)) in model.pairs.iter().zip(&c.pairs).enumerate() {
        let x = model.coords[p.k];
        let t = c.shear(i);
        let n = c.frames[i][0];
        s += &format!(
            "{i},{:.12e},{:.12e},{:.12e},{},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{},{},{}\n",
            x[0],
            x[1],
            x[2],
            c.states[i].code(),
            c.sigma_n_total(i),
            r.tau_t,
            r.tau_b,
            r.gap,
            r.slip,
            c.areas[i],
            t[0],
            t[1],
            t[2],
            n[0],
            n[1],
            n[2],
            csv_field(&model.interfaces[p.contact].name),
            body[p.k],
            body[p.l]
        );
        if c.water.is_some() {
            s.pop();
            s += &format!(",{:.12e},{:.12e}\n", c.water_pressure(i), r.sigma_n);
        }
        if let Some(k) = &changes {
            s.pop();
            s += &format!(",{}\n", k[i]);
        }
        s.pop();
        s += &format!(",{:.6e}\n", c.law_residual.get(i).copied().unwrap_or(0.0));
    }
    s
}
