//! Step 5b of [`Model::build`](super::Model::build): the water of every
//! contact group that has some, on the model's pairs ([`GroupWater`]): the
//! uplift diagram's ends read off the joint, and for a joint whose cracks
//! fill, the pairs on the face it connects to (where a crack starts) and
//! which pairs share a facet (how a crack runs along the joint).

use std::collections::HashSet;

use super::builder::Builder;
use super::water::{Diagram, Field, Fill, GroupWater, JointWater, Levels, WaterFace, WaterPressure};
use super::{Model, ModelError};
use crate::fem::Analysis;

/// The water of every contact of the description that has some; `signs`:
/// each interface facet's outward sign for side I; `cases`: each
/// contact's water load case.
pub(super) fn resolve(
    b: &Builder,
    model: &Model,
    signs: &[Vec<f64>],
    cases: &[Option<usize>],
) -> Result<Vec<GroupWater>, ModelError> {
    let vertical = if model.analysis == Analysis::Solid { 2 } else { 1 };
    let mut out = Vec::new();
    for (ci, c) in b.spec.contacts.iter().enumerate() {
        let (Some(water), Some(case)) = (&c.water, cases[ci]) else { continue };
        let key = format!("{}.water", c.key);
        let pairs: Vec<usize> = (0..model.pairs.len()).filter(|&p| model.pairs[p].contact == ci).collect();
        let field = field(b, model, ci, water, &key)?;
        let mut group = GroupWater { contact: ci, field, fill: None, case, signs: signs[ci].clone(), vertical };
        if let Some(face) = &water.face {
            group.fill = Some(fill(b, model, &group, &pairs, face, &key)?);
        }
        out.push(group);
    }
    Ok(out)
}

/// The pressure field of contact `ci`'s water, the ends of an uplift
/// diagram given by its heads read off the joint's extent along the flow.
fn field(b: &Builder, model: &Model, ci: usize, water: &JointWater, key: &str) -> Result<Field, ModelError> {
    let (unit_weight, along, levels, drain) = match &water.pressure {
        WaterPressure::Uniform(u) => return Ok(Field::Uniform(*u)),
        WaterPressure::Level { unit_weight, along, levels, drain } => (*unit_weight, *along, levels, *drain),
    };
    let points = match levels {
        Levels::Plane(plane) => return Ok(Field::Plane { unit_weight, along, plane: *plane }),
        Levels::Flat(h) => vec![[0.0, *h]],
        Levels::Table(t) => t.clone(),
        Levels::Ends { upstream, downstream } => {
            let (lo, hi) = extent(model, ci, along);
            if hi - lo <= 1e-9 * (hi.abs() + lo.abs()).max(1.0) {
                return Err(b.invalid(
                    format!("{key}.upstream"),
                    format!(
                        "the joint \"{}\" has no length along the flow direction along = [{}, {}, {}] (its nodes all lie at s = {lo}), so it has no upstream and downstream ends: give `along` as the horizontal direction in which the water flows under the joint",
                        model.interfaces[ci].name, along[0], along[1], along[2]
                    ),
                ));
            }
            vec![[lo, *upstream], [hi, *downstream]]
        }
    };
    Ok(Field::Level { unit_weight, along, diagram: Diagram { points, drain } })
}

/// The smallest and largest `x . along` over the facets of contact `ci`.
fn extent(model: &Model, ci: usize, along: [f64; 3]) -> (f64, f64) {
    let s = |n: usize| (0..3).map(|i| model.coords[n][i] * along[i]).sum::<f64>();
    model.interfaces[ci]
        .facets
        .iter()
        .flat_map(|f| f.nodes.iter().map(|&n| s(n)))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
}

/// Where the cracks of `group` fill from: the pairs of the joint on the
/// face `face` (a `[[loads]]` group), which must be at the joint's
/// upstream end, and the pairs' neighbours along the joint.
fn fill(
    b: &Builder,
    model: &Model,
    group: &GroupWater,
    pairs: &[usize],
    water: &WaterFace,
    key: &str,
) -> Result<Fill, ModelError> {
    let face = &water.group;
    let g = b.group(&format!("{key}.face"), face, &[model.analysis.dim() - 1])?;
    let on_face: HashSet<usize> = g.cells.iter().flat_map(|c| c.nodes.iter().copied()).collect();
    let name = &model.interfaces[group.contact].name;
    let index_of: std::collections::HashMap<usize, usize> = pairs.iter().enumerate().map(|(i, &p)| (p, i)).collect();
    let seeds: Vec<usize> =
        (0..pairs.len()).filter(|&i| on_face.contains(&model.mesh_node[model.pairs[pairs[i]].k])).collect();
    if seeds.is_empty() {
        return Err(b.invalid(
            format!("{key}.face"),
            format!(
                "the joint \"{name}\" does not meet the face \"{face}\" (they have no node in common), so no crack of it can fill from that face's water: name the loaded face the joint ends on (a dam's upstream face at the heel, a slope's tension crack)"
            ),
        ));
    }
    let s = |i: usize| group.s(model.coords[model.pairs[pairs[i]].k]);
    let mean = |ix: &mut dyn Iterator<Item = usize>| {
        let (sum, n) = ix.fold((0.0, 0usize), |(a, n), i| (a + s(i), n + 1));
        sum / n.max(1) as f64
    };
    let at_face = mean(&mut seeds.iter().copied());
    let middle = mean(&mut (0..pairs.len()));
    if at_face > middle {
        let a = group.along();
        return Err(b.invalid(
            format!("{key}.face"),
            format!(
                "the face \"{face}\" is at the downstream end of the joint \"{name}\" along the flow direction [{}, {}, {}]: s = x . along must grow away from the face the cracks fill from; turn `along` round",
                a[0], a[1], a[2]
            ),
        ));
    }
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); pairs.len()];
    for facet in &model.facet_pairs()[group.contact] {
        let here: Vec<usize> = facet.iter().filter_map(|p| index_of.get(p).copied()).collect();
        for &i in &here {
            neighbours[i].extend(here.iter().copied().filter(|&j| j != i));
        }
    }
    for n in &mut neighbours {
        n.sort_unstable();
        n.dedup();
    }
    Ok(Fill { surface: water.surface, unit_weight: water.unit_weight, seeds, pairs: pairs.to_vec(), neighbours })
}
