//! [`Model::build`]: the model from a mesh and a [`ModelSpec`], in numbered
//! steps. Each step resolves the physical groups it names (with a message
//! naming the input's key when a group is missing, empty or of the wrong dimension)
//! and moves what it builds onto the model nodes the contact split made.

use std::collections::HashMap;

use super::contacts::{self, Split};
use super::held::check_held;
use super::{Body, FacetLoad, InitialStress, Model, ModelError, ModelSpec, Pair};
use crate::fem::element::{self, dofs_per_node};
use crate::fem::Analysis;
use crate::mesh::{Cell, Mesh};

fn dim_name(d: usize) -> &'static str {
    ["point", "curve", "surface", "volume"][d.min(3)]
}

/// Node → cells incidence (CSR) of one body's cells.
struct Incidence {
    start: Vec<usize>,
    cells: Vec<usize>,
}

impl Incidence {
    fn new(n_nodes: usize, cells: &[Cell]) -> Incidence {
        let mut count = vec![0usize; n_nodes + 1];
        for c in cells {
            for &n in &c.nodes {
                count[n + 1] += 1;
            }
        }
        for i in 0..n_nodes {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut list = vec![0; count[n_nodes]];
        for (ci, c) in cells.iter().enumerate() {
            for &n in &c.nodes {
                list[fill[n]] = ci;
                fill[n] += 1;
            }
        }
        Incidence { start: count, cells: list }
    }
    fn of(&self, node: usize) -> &[usize] {
        &self.cells[self.start[node]..self.start[node + 1]]
    }
    /// A cell containing every node of `nodes`.
    fn containing(&self, cells: &[Cell], nodes: &[usize]) -> Option<usize> {
        self.of(nodes[0]).iter().copied().find(|&ci| nodes.iter().all(|n| cells[ci].nodes.contains(n)))
    }
}

/// What every step reads, and the messages that name the input and the mesh.
pub(super) struct Builder<'a> {
    pub(super) mesh: &'a Mesh,
    pub(super) spec: &'a ModelSpec,
}

impl<'a> Builder<'a> {
    pub(super) fn group(&self, key: &str, name: &str, dims: &[usize]) -> Result<&'a crate::mesh::Group, ModelError> {
        let g = self.mesh.group(name).ok_or_else(|| ModelError::UnknownGroup {
            scene: self.spec.source.clone(),
            key: key.to_string(),
            group: name.to_string(),
            mesh: self.spec.mesh.clone(),
            known: self
                .mesh
                .groups
                .iter()
                .map(|g| format!("\"{}\" ({})", g.name, dim_name(g.dim)))
                .collect::<Vec<_>>()
                .join(", "),
        })?;
        if !dims.contains(&g.dim) {
            return Err(ModelError::WrongDimension {
                scene: self.spec.source.clone(),
                key: key.to_string(),
                group: name.to_string(),
                found: dim_name(g.dim).to_string(),
                wanted: dims.iter().map(|&d| dim_name(d)).collect::<Vec<_>>().join(" or "),
            });
        }
        if g.cells.is_empty() {
            return Err(ModelError::EmptyGroup {
                scene: self.spec.source.clone(),
                key: key.to_string(),
                group: name.to_string(),
                dim: dim_name(g.dim).to_string(),
                mesh: self.spec.mesh.clone(),
            });
        }
        Ok(g)
    }

    pub(super) fn invalid(&self, key: String, msg: String) -> ModelError {
        ModelError::Invalid { scene: self.spec.source.clone(), key, msg }
    }
}

/// Which bodies use each mesh node.
fn node_bodies(n_nodes: usize, bodies: &[Body]) -> Vec<Vec<usize>> {
    let mut nb: Vec<Vec<usize>> = vec![Vec::new(); n_nodes];
    for (b, body) in bodies.iter().enumerate() {
        for c in &body.cells {
            for &n in &c.nodes {
                if nb[n].last() != Some(&b) {
                    nb[n].push(b);
                }
            }
        }
    }
    for v in &mut nb {
        v.sort_unstable();
        v.dedup();
    }
    nb
}

/// Bodies containing every node of a facet (via their corner nodes).
pub(super) fn facet_bodies(nb: &[Vec<usize>], facet: &Cell) -> Vec<usize> {
    let corners = &facet.nodes[..facet.kind.n_corners()];
    let mut set = nb[corners[0]].clone();
    for n in &corners[1..] {
        set.retain(|b| nb[*n].contains(b));
    }
    set
}

impl Model {
    pub fn build(mesh: &Mesh, spec: &ModelSpec) -> Result<Model, ModelError> {
        let b = Builder { mesh, spec };
        let sd = spec.analysis.dim();
        let nd = dofs_per_node(spec.analysis);

        // 0. The mesh's dimension is the analysis's: a plane analysis of a 3D
        // mesh (or of a 3D .geo meshed in 2D) is a wrong `analysis`, not a
        // wrong body group.
        let mesh_dim = mesh.dim();
        if mesh_dim != sd {
            return Err(b.invalid(
                "analysis".into(),
                format!(
                    "analysis = \"{}\" needs a {sd}D mesh with the bodies as physical {}s, but the mesh `{}` is {mesh_dim}D (it has physical {}s): {}",
                    spec.analysis,
                    dim_name(sd),
                    spec.mesh,
                    dim_name(mesh_dim),
                    if mesh_dim == 3 {
                        "use analysis = \"solid\"".to_string()
                    } else {
                        "use a plane analysis (plane_strain, plane_stress, axisymmetric), or give the .geo physical volumes".to_string()
                    }
                ),
            ));
        }

        // 1. Bodies.
        let mut bodies = Vec::new();
        for body in &spec.bodies {
            let g = b.group(&format!("{}.group", body.key), &body.group, &[sd])?;
            if let Some(InitialStress::Geostatic { .. }) = body.initial {
                if body.density <= 0.0 || spec.gravity.iter().all(|&g| g == 0.0) {
                    return Err(b.invalid(
                        format!("{}.k0", body.key),
                        format!(
                            "a geostatic initial stress needs the weight of body \"{}\": give its material a density > 0 and the scene a gravity = [..]",
                            body.group
                        ),
                    ));
                }
            }
            bodies.push(Body {
                name: body.group.clone(),
                e: body.e,
                nu: body.nu,
                density: body.density,
                cells: g.cells.clone(),
                initial: body.initial,
            });
        }
        let size = mesh.size();
        if sd == 2 {
            let tol = 1e-9 * size.max(1.0);
            if let Some((body, cell)) = bodies
                .iter()
                .flat_map(|bd| bd.cells.iter().map(move |c| (bd, c)))
                .find(|(_, c)| c.nodes.iter().any(|&n| mesh.coords[n][2].abs() > tol))
            {
                return Err(b.invalid(
                    "analysis".into(),
                    format!(
                        "plane and axisymmetric analyses need a mesh in the plane z = 0, but element {} of body \"{}\" is not; use analysis = \"solid\" for a 3D mesh",
                        cell.tag, body.name
                    ),
                ));
            }
        }
        if spec.analysis == Analysis::Axisymmetric {
            let tol = 1e-9 * size;
            if let Some((body, cell)) = bodies
                .iter()
                .flat_map(|bd| bd.cells.iter().map(move |c| (bd, c)))
                .find(|(_, c)| c.nodes.iter().any(|&n| mesh.coords[n][0] < -tol))
            {
                return Err(b.invalid(
                    "analysis".into(),
                    format!("axisymmetric models lie in x = r >= 0, but element {} of body \"{}\" has x < 0", cell.tag, body.name),
                ));
            }
        }
        let nb = node_bodies(mesh.coords.len(), &bodies);

        // 2. Contacts: split shared nodes, pair coincident ones.
        let Split { coords, mesh_node, copy, pairs: raw_pairs, interfaces } = contacts::split(&b, &mut bodies, &nb, size)?;
        let n_model = coords.len();
        // every model node of each mesh node
        let mut copies_of: HashMap<usize, Vec<usize>> = HashMap::new();
        for (&(_, n), &m) in &copy {
            copies_of.entry(n).or_default().push(m);
        }

        // 3. Supports. A point support holds every copy of its node; a
        // support on a curve or surface holds the copies of the bodies its
        // facets bound, so a support on one body's face next to a contact
        // does not drag the other body's copy of the shared corner node
        // (a symmetry line crossing a contact bounds both bodies: both held).
        let mut prescribed: Vec<Option<f64>> = vec![None; n_model * nd];
        for s in &spec.supports {
            let g = b.group(&format!("{}.group", s.key), &s.group, &(0..=sd).collect::<Vec<_>>())?;
            let mut held: Vec<usize> = Vec::new();
            for cell in &g.cells {
                let owners = if cell.kind.dim() == 0 { Vec::new() } else { facet_bodies(&nb, cell) };
                for &n in &cell.nodes {
                    if owners.is_empty() {
                        held.push(n);
                        held.extend(copies_of.get(&n).into_iter().flatten().copied());
                    } else {
                        held.extend(owners.iter().map(|&o| copy.get(&(o, n)).copied().unwrap_or(n)));
                    }
                }
            }
            held.sort_unstable();
            held.dedup();
            for m in held {
                for c in 0..nd {
                    if let Some(v) = s.prescribed[c] {
                        prescribed[m * nd + c] = Some(v);
                    } else if s.fix[c] {
                        prescribed[m * nd + c] = Some(0.0);
                    }
                }
            }
        }

        // 3b. Every rigid-body motion of every cluster of bodies (joined by
        // shared nodes or contacts, contacts counted as closed) must be
        // stopped by a support: a free one makes the stiffness singular only
        // up to round-off, which the Cholesky factorisation may not notice.
        check_held(&b, &coords, &bodies, &nb, &interfaces, &prescribed)?;

        // 4. Loads, each facet on the copy of the body it bounds.
        let incidences: Vec<Incidence> = bodies.iter().map(|bd| Incidence::new(n_model, &bd.cells)).collect();
        let mut loads = Vec::new();
        let steps = spec.load_steps;
        let mut cases: Vec<Vec<f64>> = vec![(1..=steps).map(|k| k as f64 / steps as f64).collect()];
        for load in &spec.loads {
            let case = match &load.factors {
                None => 0,
                Some(f) => {
                    cases.push(f.clone());
                    cases.len() - 1
                }
            };
            let key = format!("{}.group", load.key);
            let g = b.group(&key, &load.group, &[sd - 1])?;
            for f in &g.cells {
                let owners = facet_bodies(&nb, f);
                let body = match owners.as_slice() {
                    [one] => *one,
                    [] => {
                        return Err(b.invalid(
                            key.clone(),
                            format!("element {} of group \"{}\" is not on the boundary of any body", f.tag, load.group),
                        ))
                    }
                    _ => {
                        return Err(b.invalid(
                            key.clone(),
                            format!(
                                "element {} of group \"{}\" lies between bodies {}: loads go on outer boundaries",
                                f.tag,
                                load.group,
                                owners.iter().map(|&o| format!("\"{}\"", bodies[o].name)).collect::<Vec<_>>().join(" and ")
                            ),
                        ))
                    }
                };
                let mut cell = f.clone();
                for n in &mut cell.nodes {
                    if let Some(&m) = copy.get(&(body, *n)) {
                        *n = m;
                    }
                }
                let (sign, element) = facet_sign(&coords, &cell, &bodies[body].cells, &incidences[body]).ok_or_else(|| {
                    b.invalid(key.clone(), format!("element {} of group \"{}\" is not a face of an element of body \"{}\"", f.tag, load.group, bodies[body].name))
                })?;
                loads.push(FacetLoad { cell, sign, kind: load.kind.clone(), body, element, case });
            }
        }

        // 5. Pair normals and areas from body I's facets.
        let mut model = Model {
            scene: spec.source.clone(),
            analysis: spec.analysis,
            nd,
            thickness: spec.thickness,
            gravity: spec.gravity,
            coords,
            bodies,
            loads,
            prescribed,
            pairs: Vec::new(),
            interfaces,
            mesh_node,
            gravity_case: match &spec.gravity_factors {
                None => 0,
                Some(f) => {
                    cases.push(f.clone());
                    cases.len() - 1
                }
            },
            initial_case: {
                cases.push(vec![1.0; steps]);
                cases.len() - 1
            },
            cases,
        };
        // per contact: a node where contacts meet gets the normal and area
        // of each contact's own facets
        let mut normals: Vec<HashMap<usize, ([f64; 3], f64)>> = Vec::with_capacity(model.interfaces.len());
        for iface in &model.interfaces {
            let mut acc: HashMap<usize, ([f64; 3], f64)> = HashMap::new();
            for f in &iface.facets {
                let corners = &f.nodes[..f.kind.n_corners()];
                let body = iface
                    .side_i
                    .iter()
                    .copied()
                    .find(|&bd| incidences[bd].containing(&model.bodies[bd].cells, corners).is_some())
                    .unwrap_or(iface.body_i);
                let (sign, _) = facet_sign(&model.coords, f, &model.bodies[body].cells, &incidences[body]).ok_or_else(|| {
                    b.invalid("contacts".into(), format!("element {} of contact \"{}\" is not a face of body \"{}\"", f.tag, iface.name, model.bodies[body].name))
                })?;
                accumulate_facet(&model, f, sign, &mut acc);
            }
            normals.push(acc);
        }
        for (k, l, contact) in raw_pairs {
            let (nk, ak) = normals[contact].get(&k).copied().unwrap_or(([0.0; 3], 0.0));
            let nrm = element::norm(nk);
            let n = if nrm > 0.0 { [nk[0] / nrm, nk[1] / nrm, nk[2] / nrm] } else { [0.0; 3] };
            let area = ak;
            model.pairs.push(Pair { k, l, contact, normal: n, area });
        }
        Ok(model)
    }
}

/// Sign making the natural normal of `facet` outward for the body cell that has it as a face.
/// The cell of `cells` that has `facet` as a face, and the sign that makes
/// the facet's natural normal outward for it.
fn facet_sign(coords: &[[f64; 3]], facet: &Cell, cells: &[Cell], inc: &Incidence) -> Option<(f64, usize)> {
    let ci = inc.containing(cells, &facet.nodes[..facet.kind.n_corners()])?;
    let fc: Vec<[f64; 3]> = facet.nodes.iter().map(|&n| coords[n]).collect();
    let cc: Vec<[f64; 3]> = cells[ci].nodes.iter().map(|&n| coords[n]).collect();
    Some((element::outward_sign(facet.kind, &fc, cells[ci].kind, &cc), ci))
}

/// Adds a facet's area-weighted outward normal and `∫ N_a dA` to its nodes.
fn accumulate_facet(model: &Model, f: &Cell, sign: f64, acc: &mut HashMap<usize, ([f64; 3], f64)>) {
    let fc: Vec<[f64; 3]> = f.nodes.iter().map(|&n| model.coords[n]).collect();
    let rule = crate::fem::quadrature::rule(f.kind, 2 * f.kind.order() + 2);
    for q in &rule {
        let (n, unit, da, x) = element::facet_point(f.kind, &fc, q.xi);
        let measure = element::measure(model.analysis, model.thickness, &x);
        for (a, &node) in f.nodes.iter().enumerate() {
            let e = acc.entry(node).or_insert(([0.0; 3], 0.0));
            e.1 += q.w * da * measure * n[a];
            // normals weighted by geometry only (N_a >= 0 weights avoid
            // cancelling on serendipity faces)
            for i in 0..3 {
                e.0[i] += sign * unit[i] * q.w * da * n[a].abs();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::CellKind;

    #[test]
    fn incidence_finds_the_cell_of_a_facet() {
        let cells = vec![
            Cell { kind: CellKind::Tri3, nodes: vec![0, 1, 2], tag: 1 },
            Cell { kind: CellKind::Tri3, nodes: vec![1, 3, 2], tag: 2 },
        ];
        let inc = Incidence::new(4, &cells);
        assert_eq!(inc.containing(&cells, &[3, 1]), Some(1));
        assert_eq!(inc.containing(&cells, &[0, 3]), None);
    }
}
