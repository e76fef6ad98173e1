//! Step 5b of [`Model::build`](super::Model::build): the water of every
//! contact group that has some, on the model's pairs ([`GroupWater`]): the
//! uplift diagram's ends read off the joint, and for a joint whose cracks
//! fill, its sheets (smooth pieces, which a crease ends), the pairs of
//! each on the face it connects to (where a crack starts) and which pairs
//! share a facet of the sheet (how a crack runs along it).

use std::collections::{HashMap, HashSet};

use super::build_input::Builder;
use super::contacts::CREASE_ANGLE;
use super::errors::ModelError;
use super::mechanical::Model;
use super::topology::UnionFind;
use super::water::{Diagram, Field, Fill, GroupWater, JointWater, Levels, Sheet, WaterFace, WaterPressure};
use crate::fem::vec3::{cross, dot, normalized, sub};
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
        let field = field(model, ci, water, &key)?;
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
fn field(model: &Model, ci: usize, water: &JointWater, key: &str) -> Result<Field, ModelError> {
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
                return Err(ModelError::JointNoLength {
                    key: format!("{key}.upstream"),
                    joint: model.interfaces[ci].name.clone(),
                    along,
                    s: lo,
                });
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
    let index_of: HashMap<usize, usize> = pairs.iter().enumerate().map(|(i, &p)| (p, i)).collect();
    let seeds: Vec<usize> =
        (0..pairs.len()).filter(|&i| on_face.contains(&model.mesh_node[model.pairs[pairs[i]].k])).collect();
    if seeds.is_empty() {
        return Err(ModelError::FaceOffJoint { key: format!("{key}.face"), joint: name.clone(), face: face.clone() });
    }
    let s = |i: usize| group.s(model.coords[model.pairs[pairs[i]].k]);
    let mean = |ix: &mut dyn Iterator<Item = usize>| {
        let (sum, n) = ix.fold((0.0, 0usize), |(a, n), i| (a + s(i), n + 1));
        sum / n.max(1) as f64
    };
    let at_face = mean(&mut seeds.iter().copied());
    let middle = mean(&mut (0..pairs.len()));
    if at_face > middle {
        return Err(ModelError::FaceDownstream {
            key: format!("{key}.face"),
            face: face.clone(),
            joint: name.clone(),
            along: group.along(),
        });
    }
    let (facet_sheet, sheets) = sheets(model, group.contact, &index_of, &seeds);
    Ok(Fill { surface: water.surface, unit_weight: water.unit_weight, pairs: pairs.to_vec(), facet_sheet, sheets })
}

/// The sheet of every facet of contact `ci` and every sheet's pairs, seeds
/// and neighbours (`index_of`: a model pair's index in the group's pairs;
/// `seeds`: the group's pairs on the face, by that index).
fn sheets(model: &Model, ci: usize, index_of: &HashMap<usize, usize>, seeds: &[usize]) -> (Vec<usize>, Vec<Sheet>) {
    let facet_sheet = sheets_of(model, ci);
    let n_sheets = facet_sheet.iter().map(|&k| k + 1).max().unwrap_or(0);
    let is_seed: HashSet<usize> = seeds.iter().copied().collect();
    let mut sheets: Vec<Sheet> = Vec::with_capacity(n_sheets);
    let mut local: Vec<HashMap<usize, usize>> = Vec::with_capacity(n_sheets);
    for _ in 0..n_sheets {
        sheets.push(Sheet { pairs: Vec::new(), seeds: Vec::new(), neighbours: Vec::new(), normal: [0.0; 3] });
        local.push(HashMap::new());
    }
    let facets = &model.interfaces[ci].facets;
    for ((facet, &k), cell) in model.facet_pairs()[ci].iter().zip(&facet_sheet).zip(facets) {
        let (sheet, index) = (&mut sheets[k], &mut local[k]);
        let n = facet_normal(model, cell);
        let sign = if dot(n, sheet.normal) < 0.0 { -1.0 } else { 1.0 };
        sheet.normal = std::array::from_fn(|d| sheet.normal[d] + sign * n[d]);
        let here: Vec<usize> = (facet.iter().filter_map(|p| index_of.get(p)))
            .map(|&i| {
                *index.entry(i).or_insert_with(|| {
                    sheet.pairs.push(i);
                    sheet.neighbours.push(Vec::new());
                    if is_seed.contains(&i) {
                        sheet.seeds.push(sheet.pairs.len() - 1);
                    }
                    sheet.pairs.len() - 1
                })
            })
            .collect();
        for &i in &here {
            sheet.neighbours[i].extend(here.iter().copied().filter(|&j| j != i));
        }
    }
    for sheet in &mut sheets {
        for n in &mut sheet.neighbours {
            n.sort_unstable();
            n.dedup();
        }
        let n = normalized(sheet.normal);
        let big = (0..3).max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs())).unwrap_or(0);
        sheet.normal = n.map(|c| if n[big] < 0.0 { -c } else { c });
    }
    (facet_sheet, sheets)
}

/// The sheet of every facet of contact `ci`: facets that share an edge (a
/// node in 2D) and whose normals turn by less than [`CREASE_ANGLE`] are
/// one sheet, so a crease, a step's side or a crossing joint ends one.
fn sheets_of(model: &Model, ci: usize) -> Vec<usize> {
    let facets = &model.interfaces[ci].facets;
    let normals: Vec<[f64; 3]> = facets.iter().map(|f| facet_normal(model, f)).collect();
    let mut edges: Vec<(usize, usize, usize)> = Vec::new();
    for (i, f) in facets.iter().enumerate() {
        let corners: Vec<usize> = f.nodes[..f.kind.n_corners()].iter().map(|&n| model.mesh_node[n]).collect();
        if corners.len() == 2 {
            edges.extend(corners.iter().map(|&a| (a, a, i)));
        } else {
            edges.extend((0..corners.len()).map(|c| {
                let (a, b) = (corners[c], corners[(c + 1) % corners.len()]);
                (a.min(b), a.max(b), i)
            }));
        }
    }
    edges.sort_unstable();
    let smooth = CREASE_ANGLE.to_radians().cos();
    let mut sets = UnionFind::new(facets.len());
    for (k, e) in edges.iter().enumerate() {
        for o in edges[k + 1..].iter().take_while(|o| (o.0, o.1) == (e.0, e.1)) {
            if dot(normals[e.2], normals[o.2]).abs() >= smooth {
                sets.join(e.2, o.2);
            }
        }
    }
    let mut sheet = vec![0; facets.len()];
    for (s, group) in sets.groups().into_iter().enumerate() {
        group.into_iter().for_each(|i| sheet[i] = s);
    }
    sheet
}

/// A facet's unit normal from its corners (its area vector in 3D, the
/// segment turned a quarter in 2D).
fn facet_normal(model: &Model, f: &crate::mesh::Cell) -> [f64; 3] {
    let x: Vec<[f64; 3]> = f.nodes[..f.kind.n_corners()].iter().map(|&n| model.coords[n]).collect();
    if x.len() == 2 {
        return normalized([x[1][1] - x[0][1], x[0][0] - x[1][0], 0.0]);
    }
    let mut m = [0.0; 3];
    for i in 0..x.len() {
        let w = cross(sub(x[i], x[0]), sub(x[(i + 1) % x.len()], x[0]));
        for d in 0..3 {
            m[d] += w[d];
        }
    }
    normalized(m)
}
