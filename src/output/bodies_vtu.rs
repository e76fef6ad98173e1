//! The bodies' VTU file: the deformed mesh with displacements, stresses
//! and the contact states of the pairs' nodes.

use super::vtu::{self, Field, IntField};
use crate::error::Result;
use crate::fem::material::von_mises;
use crate::mesh::Cell;
use crate::model::Model;
use crate::recover::BodyStress;

/// The bodies' VTU: each body's own nodes as points, so stresses averaged
/// per body stay apart where bodies share nodes; the displacement when
/// `displacement`, the stresses when there are some.
/// The bodies; `block_state`: each block's [`crate::contact::mechanism::BlockState`]
/// code as cell data (left out when empty).
pub(super) fn bodies_vtu(
    model: &Model,
    u: &[f64],
    stresses: &[BodyStress],
    displacement: bool,
    block_state: &[i32],
) -> Result<Vec<u8>> {
    let nd = model.nd;
    let mut points = Vec::new();
    let mut disp = Vec::new();
    let mut stress = Vec::new();
    let mut vm = Vec::new();
    let mut cells = Vec::new();
    let mut body_id = Vec::new();
    let mut block_id = Vec::new();
    let mut state = Vec::new();
    let mut local = vec![usize::MAX; model.n_nodes()];
    for (b, body) in model.bodies.iter().enumerate() {
        let base = points.len();
        // the body's own node list (stresses are averaged per body)
        let own: Vec<usize> = match stresses.get(b) {
            Some(bs) => bs.nodes.clone(),
            None => crate::recover::body_nodes(body),
        };
        for (i, &n) in own.iter().enumerate() {
            local[n] = base + i;
            points.push(model.coords[n]);
            for c in 0..3 {
                disp.push(if c < nd { u[n * nd + c] } else { 0.0 });
            }
            if let Some(bs) = stresses.get(b) {
                let s = &bs.stress[i];
                stress.extend_from_slice(s);
                vm.push(von_mises(s));
            }
        }
        for c in &body.cells {
            cells.push(Cell { kind: c.kind, nodes: c.nodes.iter().map(|&n| local[n]).collect(), tag: c.tag });
            body_id.push(body.group as i32);
            block_id.push(b as i32);
            if let Some(&s) = block_state.get(b) {
                state.push(s);
            }
        }
    }
    let mut point_data = Vec::new();
    if displacement {
        point_data.push(Field { name: "displacement", n_comp: 3, values: &disp });
    }
    if !stresses.is_empty() {
        point_data.push(Field { name: "stress", n_comp: 6, values: &stress });
        point_data.push(Field { name: "von_mises", n_comp: 1, values: &vm });
    }
    Ok(vtu::vtu_bytes(
        &points,
        &cells,
        &point_data,
        &[],
        &[
            IntField { name: "body", values: &body_id },
            IntField { name: "block", values: &block_id },
            IntField { name: "block_state", values: &state },
        ][..if state.is_empty() { 2 } else { 3 }],
    )?)
}
