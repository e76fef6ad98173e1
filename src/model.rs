//! The mechanical model built from a mesh and a scene: bodies with their
//! cells, boundary loads on facets, supports, and contact pairs.
//!
//! Contact splitting: a node on a contact group gets one copy per body that
//! uses it (the first body keeps the mesh node, the others get new model
//! nodes at the same place), so the two sides of a contact can move apart.
//! With `groups = [a, b]` the two sides already have their own nodes, which
//! are paired by position. Pairs are ordered (k on body I, l on body II),
//! body I being the one listed first in `[[bodies]]`.
//!
//! Everything else (loads, supports) refers to mesh nodes; loads are moved to
//! the copy of the body the loaded facet bounds, supports hold every copy.

use std::collections::HashMap;

use crate::fem::element::{self, dofs_per_node};
use crate::mesh::{Cell, Mesh};
use crate::fem::Analysis;
use crate::scene::{ContactGroups, InitialStress, LoadKind, Scene};

/// A body of the model: cells in model node numbering.
#[derive(Clone, Debug)]
pub struct Body {
    pub name: String,
    pub e: f64,
    pub nu: f64,
    pub density: f64,
    pub cells: Vec<Cell>,
    /// In-situ stress the body carries before any load.
    pub initial: Option<InitialStress>,
}

/// A load on one boundary facet of one body.
#[derive(Clone, Debug)]
pub struct FacetLoad {
    pub cell: Cell,
    /// Turns the facet's natural normal into the body's outward normal.
    pub sign: f64,
    pub kind: LoadKind,
    /// The body whose boundary the facet is.
    pub body: usize,
    /// Its load case (index into `Model::cases`).
    pub case: usize,
}

/// One contact node pair: k on body I, l on body II.
#[derive(Clone, Debug)]
pub struct Pair {
    pub k: usize,
    pub l: usize,
    pub contact: usize,
    /// Unit outward normal of body I at k (area-weighted over its facets).
    pub normal: [f64; 3],
    /// Area the pair controls, `∫ N_k dA` over the facets of body I (with
    /// thickness or 2 pi r as for every other integral).
    pub area: f64,
}

/// One contact surface: the two bodies and the facets on body I's side.
#[derive(Clone, Debug)]
pub struct Interface {
    pub name: String,
    /// A body of each side (the first listed).
    pub body_i: usize,
    pub body_ii: usize,
    /// Every body on side I (a shared group may join several bodies to one).
    pub side_i: Vec<usize>,
    pub facets: Vec<Cell>,
}

#[derive(Clone, Debug)]
pub struct Model {
    /// The scene file, for messages.
    pub scene: String,
    pub analysis: Analysis,
    pub nd: usize,
    pub thickness: f64,
    pub gravity: [f64; 3],
    pub coords: Vec<[f64; 3]>,
    pub bodies: Vec<Body>,
    pub loads: Vec<FacetLoad>,
    /// Prescribed value of each DOF (`node * nd + c`), None when free.
    pub prescribed: Vec<Option<f64>>,
    pub pairs: Vec<Pair>,
    pub interfaces: Vec<Interface>,
    /// Mesh node of every model node.
    pub mesh_node: Vec<usize>,
    /// Load factor of each load case at each load step. Case 0 is the ramp
    /// k / load_steps, which also scales prescribed displacements.
    pub cases: Vec<Vec<f64>>,
    /// The load case of gravity.
    pub gravity_case: usize,
    /// The load case of the initial stresses: factor 1 at every step (they
    /// are there before the first load).
    pub initial_case: usize,
}

impl Body {
    /// The initial stress at x (zero without one).
    pub fn initial_at(&self, x: [f64; 3], analysis: Analysis, gravity: [f64; 3]) -> [f64; 6] {
        self.initial.map_or([0.0; 6], |i| i.at(x, analysis, self.density, gravity))
    }
}

#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    #[error("{scene}: {key} = \"{group}\" is not a physical group of the mesh `{mesh}`; it has: {known}. Check the name in the .geo's Physical statements")]
    UnknownGroup { scene: String, key: String, group: String, mesh: String, known: String },
    #[error("{scene}: {key} = \"{group}\" is a physical {found}, but a {wanted} is needed here")]
    WrongDimension { scene: String, key: String, group: String, found: String, wanted: String },
    #[error("{scene}: {key}: {msg}")]
    Invalid { scene: String, key: String, msg: String },
    #[error("{scene}: {key} = \"{group}\" is a physical {dim} of the mesh `{mesh}` without elements: its Physical statement names no entity that exists (gmsh keeps such a group without a word). Check the entity numbers in the .geo's Physical statement for \"{group}\"")]
    EmptyGroup { scene: String, key: String, group: String, dim: String, mesh: String },
    #[error("element {tag} of body \"{body}\" is inverted or degenerate (Jacobian determinant {det_j:.3e}): fix the mesh (node order or a collapsed element)")]
    Inverted { body: String, tag: u64, det_j: f64 },
}

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

struct Builder<'a> {
    mesh: &'a Mesh,
    scene: &'a Scene,
    scene_name: String,
}

impl<'a> Builder<'a> {
    fn group(&self, key: &str, name: &str, dims: &[usize]) -> Result<&'a crate::mesh::Group, ModelError> {
        let g = self.mesh.group(name).ok_or_else(|| ModelError::UnknownGroup {
            scene: self.scene_name.clone(),
            key: key.to_string(),
            group: name.to_string(),
            mesh: self.scene.mesh.path().display().to_string(),
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
                scene: self.scene_name.clone(),
                key: key.to_string(),
                group: name.to_string(),
                found: dim_name(g.dim).to_string(),
                wanted: dims.iter().map(|&d| dim_name(d)).collect::<Vec<_>>().join(" or "),
            });
        }
        if g.cells.is_empty() {
            return Err(ModelError::EmptyGroup {
                scene: self.scene_name.clone(),
                key: key.to_string(),
                group: name.to_string(),
                dim: dim_name(g.dim).to_string(),
                mesh: self.scene.mesh.path().display().to_string(),
            });
        }
        Ok(g)
    }

    fn invalid(&self, key: String, msg: String) -> ModelError {
        ModelError::Invalid { scene: self.scene_name.clone(), key, msg }
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
fn facet_bodies(nb: &[Vec<usize>], facet: &Cell) -> Vec<usize> {
    let corners = &facet.nodes[..facet.kind.n_corners()];
    let mut set = nb[corners[0]].clone();
    for n in &corners[1..] {
        set.retain(|b| nb[*n].contains(b));
    }
    set
}

impl Model {
    pub fn build(mesh: &Mesh, scene: &Scene) -> Result<Model, ModelError> {
        let b = Builder { mesh, scene, scene_name: scene.path.display().to_string() };
        let sd = scene.analysis.dim();
        let nd = dofs_per_node(scene.analysis);

        // 0. The mesh's dimension is the analysis's: a plane analysis of a 3D
        // mesh (or of a 3D .geo meshed in 2D) is a wrong `analysis`, not a
        // wrong body group.
        let mesh_dim = mesh.dim();
        if mesh_dim != sd {
            return Err(b.invalid(
                "analysis".into(),
                format!(
                    "analysis = \"{}\" needs a {sd}D mesh with the bodies as physical {}s, but the mesh `{}` is {mesh_dim}D (it has physical {}s): {}",
                    scene.analysis,
                    dim_name(sd),
                    scene.mesh.path().display(),
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
        for (i, body) in scene.bodies.iter().enumerate() {
            let g = b.group(&format!("bodies[{i}].group"), &body.group, &[sd])?;
            let m = scene.material_of(body);
            if let Some(InitialStress::Geostatic { .. }) = body.initial {
                if m.density <= 0.0 || scene.gravity.iter().all(|&g| g == 0.0) {
                    return Err(b.invalid(
                        format!("bodies[{i}].k0"),
                        format!(
                            "a geostatic initial stress needs the weight of body \"{}\": give its material a density > 0 and the scene a gravity = [..]",
                            body.group
                        ),
                    ));
                }
            }
            bodies.push(Body {
                name: body.group.clone(),
                e: m.e,
                nu: m.nu,
                density: m.density,
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
        if scene.analysis == Analysis::Axisymmetric {
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
        let mut coords = mesh.coords.clone();
        let mut mesh_node: Vec<usize> = (0..coords.len()).collect();
        // (body, mesh node) -> model node, for split nodes only
        let mut copy: HashMap<(usize, usize), usize> = HashMap::new();
        let mut raw_pairs: Vec<(usize, usize, usize)> = Vec::new(); // (k, l, contact)
        let mut interfaces = Vec::new();
        // Junctions: a node where contacts meet is paired only by the
        // contact it lies inside, not by those that end there (a vertical
        // joint ending on a dam's base: the two blocks stay joined at that
        // one node, which pairs with the rock).
        let mut ceded: std::collections::HashSet<(usize, usize)> = std::collections::HashSet::new();
        {
            let shared: Vec<(usize, &crate::mesh::Group)> = scene
                .contacts
                .iter()
                .enumerate()
                .filter_map(|(ci, c)| match &c.groups {
                    ContactGroups::Shared(name) => mesh.group(name).map(|g| (ci, g)),
                    ContactGroups::Pair(..) => None,
                })
                .collect();
            let ends: Vec<Vec<usize>> = shared.iter().map(|(_, g)| curve_ends(&g.cells)).collect();
            let nodes: Vec<Vec<usize>> = shared.iter().map(|(_, g)| g.nodes()).collect();
            for (a, (ca, _)) in shared.iter().enumerate() {
                for &n in &ends[a] {
                    let inside_other = (0..shared.len()).any(|o| o != a && nodes[o].binary_search(&n).is_ok() && ends[o].binary_search(&n).is_err());
                    if inside_other {
                        ceded.insert((*ca, n));
                    }
                }
            }
        }
        for (ci, contact) in scene.contacts.iter().enumerate() {
            match &contact.groups {
                ContactGroups::Shared(name) => {
                    let key = format!("contacts[{ci}].group");
                    let g = b.group(&key, name, &[sd - 1])?;
                    let [side_i, side_ii] = contact_sides(&b, &key, name, &nb, &bodies, &g.cells)?;
                    for n in g.nodes() {
                        if ceded.contains(&(ci, n)) {
                            continue;
                        }
                        let l = coords.len();
                        coords.push(mesh.coords[n]);
                        mesh_node.push(n);
                        // side II's bodies at this node share one copy
                        for &bii in side_ii.iter().filter(|&&x| nb[n].contains(&x)) {
                            if copy.insert((bii, n), l).is_some() {
                                return Err(b.invalid(
                                    key.clone(),
                                    format!(
                                        "node at {:?} of body \"{}\" lies inside two contacts: contacts may meet only where one of them ends (a joint ending on a base); crossing contacts are not supported",
                                        mesh.coords[n], bodies[bii].name
                                    ),
                                ));
                            }
                        }
                        raw_pairs.push((n, l, ci));
                    }
                    interfaces.push(Interface { name: name.clone(), body_i: side_i[0], body_ii: side_ii[0], side_i, facets: g.cells.clone() });
                }
                ContactGroups::Pair(na, nb_name) => {
                    let ka = format!("contacts[{ci}].groups[0]");
                    let kb = format!("contacts[{ci}].groups[1]");
                    let ga = b.group(&ka, na, &[sd - 1])?;
                    let gb = b.group(&kb, nb_name, &[sd - 1])?;
                    let ba = single_body(&b, &ka, na, &nb, &bodies, &ga.cells)?;
                    let bb = single_body(&b, &kb, nb_name, &nb, &bodies, &gb.cells)?;
                    if ba == bb {
                        return Err(b.invalid(
                            format!("contacts[{ci}].groups"),
                            format!(
                                "both \"{na}\" and \"{nb_name}\" bound body \"{}\": a contact between a body and itself is not supported; split the body into two physical groups",
                                bodies[ba].name
                            ),
                        ));
                    }
                    let (gi, gii, bi, bii) = if ba < bb { (ga, gb, ba, bb) } else { (gb, ga, bb, ba) };
                    let pairs = pair_by_position(&mesh.coords, &gi.nodes(), &gii.nodes(), 1e-6 * size)
                        .map_err(|msg| b.invalid(format!("contacts[{ci}].groups"), format!("pairing the nodes of \"{}\" with those of \"{}\": {msg}", gi.name, gii.name)))?;
                    raw_pairs.extend(pairs.into_iter().map(|(k, l)| (k, l, ci)));
                    let name = format!("{}|{}", gi.name, gii.name);
                    interfaces.push(Interface { name, body_i: bi, body_ii: bii, side_i: vec![bi], facets: gi.cells.clone() });
                }
            }
        }
        for (bi, body) in bodies.iter_mut().enumerate() {
            for c in &mut body.cells {
                for n in &mut c.nodes {
                    if let Some(&m) = copy.get(&(bi, *n)) {
                        *n = m;
                    }
                }
            }
        }
        // Side I keeps the mesh node unless another contact copied it for
        // that body (a base on the far side of a joint's end): facets and
        // pairs use side I's own node.
        let side_i_node = |side: &[usize], n: usize| side.iter().filter(|&&bd| nb[n].contains(&bd)).find_map(|&bd| copy.get(&(bd, n)).copied()).unwrap_or(n);
        for iface in &mut interfaces {
            for f in &mut iface.facets {
                let owner = facet_bodies(&nb, f).into_iter().find(|o| iface.side_i.contains(o));
                for n in &mut f.nodes {
                    if let Some(o) = owner {
                        *n = copy.get(&(o, *n)).copied().unwrap_or(*n);
                    }
                }
            }
        }
        for (k, _, ci) in &mut raw_pairs {
            *k = side_i_node(&interfaces[*ci].side_i, *k);
        }
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
        for (i, s) in scene.supports.iter().enumerate() {
            let g = b.group(&format!("supports[{i}].group"), &s.group, &(0..=sd).collect::<Vec<_>>())?;
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
        let steps = scene.solver.load_steps;
        let mut cases: Vec<Vec<f64>> = vec![(1..=steps).map(|k| k as f64 / steps as f64).collect()];
        for (i, load) in scene.loads.iter().enumerate() {
            let case = match &load.factors {
                None => 0,
                Some(f) => {
                    cases.push(f.clone());
                    cases.len() - 1
                }
            };
            let key = format!("loads[{i}].group");
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
                let sign = facet_sign(&coords, &cell, &bodies[body].cells, &incidences[body]).ok_or_else(|| {
                    b.invalid(key.clone(), format!("element {} of group \"{}\" is not a face of an element of body \"{}\"", f.tag, load.group, bodies[body].name))
                })?;
                loads.push(FacetLoad { cell, sign, kind: load.kind.clone(), body, case });
            }
        }

        // 5. Pair normals and areas from body I's facets.
        let mut model = Model {
            scene: b.scene_name.clone(),
            analysis: scene.analysis,
            nd,
            thickness: scene.thickness,
            gravity: scene.gravity,
            coords,
            bodies,
            loads,
            prescribed,
            pairs: Vec::new(),
            interfaces,
            mesh_node,
            gravity_case: match &scene.solver.gravity_factors {
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
                let sign = facet_sign(&model.coords, f, &model.bodies[body].cells, &incidences[body]).ok_or_else(|| {
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

    pub fn n_nodes(&self) -> usize {
        self.coords.len()
    }

    /// Names of the bodies, for messages.
    pub fn body_names(&self, ids: &[usize]) -> String {
        ids.iter().map(|&b| format!("\"{}\"", self.bodies[b].name)).collect::<Vec<_>>().join(", ")
    }
}

/// Value of rigid-body mode `m` at displacement component `a` of a point at
/// `x` (relative to the cluster's centre): translations, then rotations.
fn rigid_mode(analysis: Analysis, m: usize, a: usize, x: [f64; 3]) -> f64 {
    match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => match (m, a) {
            (0, 0) | (1, 1) => 1.0,
            (2, 0) => -x[1],
            (2, 1) => x[0],
            _ => 0.0,
        },
        // only the axial translation is rigid: a radial one strains the hoop
        Analysis::Axisymmetric => f64::from(u8::from(m == 0 && a == 1)),
        Analysis::Solid => {
            if m < 3 {
                return f64::from(u8::from(m == a));
            }
            // omega x x with omega the unit vector of axis m - 3
            let w = m - 3;
            let (i, j) = ((w + 1) % 3, (w + 2) % 3);
            if a == i {
                -x[j]
            } else if a == j {
                x[i]
            } else {
                0.0
            }
        }
    }
}

/// Fails naming the bodies and the motion when some rigid-body motion of a
/// cluster of bodies is stopped by no prescribed DOF.
fn check_held(b: &Builder, coords: &[[f64; 3]], bodies: &[Body], nb: &[Vec<usize>], interfaces: &[Interface], prescribed: &[Option<f64>]) -> Result<(), ModelError> {
    let analysis = b.scene.analysis;
    let nd = dofs_per_node(analysis);
    let mut parent: Vec<usize> = (0..bodies.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let links = nb.iter().flat_map(|v| v.windows(2).map(|w| (w[0], w[1]))).chain(interfaces.iter().map(|i| (i.body_i, i.body_ii)));
    for (p, q) in links.collect::<Vec<_>>() {
        let (rp, rq) = (root(&mut parent, p), root(&mut parent, q));
        parent[rp] = rq;
    }
    let names: &[&str] = match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => &["translation in x", "translation in y", "rotation about z"],
        Analysis::Axisymmetric => &["translation along the axis (y)"],
        Analysis::Solid => &["translation in x", "translation in y", "translation in z", "rotation about x", "rotation about y", "rotation about z"],
    };
    let nm = names.len();
    for r in 0..bodies.len() {
        let members: Vec<usize> = (0..bodies.len()).filter(|&i| root(&mut parent, i) == r).collect();
        if members.is_empty() {
            continue;
        }
        let mut nodes: Vec<usize> = members.iter().flat_map(|&i| bodies[i].cells.iter().flat_map(|c| c.nodes.iter().copied())).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &n in &nodes {
            for d in 0..3 {
                lo[d] = lo[d].min(coords[n][d]);
                hi[d] = hi[d].max(coords[n][d]);
            }
        }
        let centre: [f64; 3] = std::array::from_fn(|d| 0.5 * (lo[d] + hi[d]));
        let size = (0..3).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
        // Gram matrix of the rigid modes over the prescribed DOFs: singular
        // exactly when some combination of them moves no prescribed DOF
        let mut g = nalgebra::DMatrix::<f64>::zeros(nm, nm);
        for &n in &nodes {
            let x: [f64; 3] = std::array::from_fn(|d| (coords[n][d] - centre[d]) / size);
            for a in 0..nd {
                if prescribed[n * nd + a].is_some() {
                    let phi: Vec<f64> = (0..nm).map(|m| rigid_mode(analysis, m, a, x)).collect();
                    for i in 0..nm {
                        for j in 0..nm {
                            g[(i, j)] += phi[i] * phi[j];
                        }
                    }
                }
            }
        }
        let eig = nalgebra::SymmetricEigen::new(g);
        let mut free: Vec<&str> = (0..nm).filter(|&k| eig.eigenvalues[k] < 1e-9).map(|k| names[eig.eigenvectors.column(k).iamax()]).collect();
        free.sort_unstable();
        free.dedup();
        if !free.is_empty() {
            let one = members.len() == 1;
            return Err(b.invalid(
                "supports".into(),
                format!(
                    "{} {} not held: no support stops {} {} (contacts counted as closed), so the stiffness matrix is singular. Add a support that stops it (fix = [..] on a physical point, curve or surface)",
                    if one { "body" } else { "bodies" },
                    members.iter().map(|&i| format!("\"{}\"", bodies[i].name)).collect::<Vec<_>>().join(", "),
                    if one { "its" } else { "their" },
                    free.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// Sign making the natural normal of `facet` outward for the body cell that has it as a face.
fn facet_sign(coords: &[[f64; 3]], facet: &Cell, cells: &[Cell], inc: &Incidence) -> Option<f64> {
    let ci = inc.containing(cells, &facet.nodes[..facet.kind.n_corners()])?;
    let fc: Vec<[f64; 3]> = facet.nodes.iter().map(|&n| coords[n]).collect();
    let cc: Vec<[f64; 3]> = cells[ci].nodes.iter().map(|&n| coords[n]).collect();
    Some(element::outward_sign(facet.kind, &fc, cells[ci].kind, &cc))
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

/// The bodies on either side of a shared contact group: every facet lies
/// between two bodies, and the bodies split into two sides (a dam's base
/// group has the rock on one side and every block on the other). Side I is
/// the side of the body listed first in `[[bodies]]`.
fn contact_sides(b: &Builder, key: &str, name: &str, nb: &[Vec<usize>], bodies: &[Body], facets: &[Cell]) -> Result<[Vec<usize>; 2], ModelError> {
    let mut edges: Vec<(usize, usize)> = Vec::new();
    for f in facets {
        let owners = facet_bodies(nb, f);
        match owners.as_slice() {
            [x, y] => edges.push((*x.min(y), *x.max(y))),
            [one] => {
                return Err(b.invalid(
                    key.to_string(),
                    format!(
                        "group \"{name}\" touches only body \"{}\" (element {}): a contact needs a body on each side sharing the {} (group = ..), or two coincident groups (groups = [..]); a contact between a body and itself is not supported, split the body into two physical groups",
                        bodies[*one].name,
                        f.tag,
                        if f.kind.dim() == 1 { "curve" } else { "surface" }
                    ),
                ))
            }
            [] => return Err(b.invalid(key.to_string(), format!("element {} of group \"{name}\" touches no body", f.tag))),
            many => {
                return Err(b.invalid(
                    key.to_string(),
                    format!("element {} of group \"{name}\" is shared by more than two bodies ({})", f.tag, many.len()),
                ))
            }
        }
    }
    edges.sort_unstable();
    edges.dedup();
    let Some(first) = edges.iter().map(|e| e.0).min() else {
        return Err(b.invalid(key.to_string(), format!("group \"{name}\" has no elements")));
    };
    // two-colour the bodies the group joins, starting from the first one
    let mut side: HashMap<usize, usize> = HashMap::from([(first, 0)]);
    loop {
        let mut changed = false;
        for &(x, y) in &edges {
            match (side.get(&x).copied(), side.get(&y).copied()) {
                (Some(a), None) => {
                    side.insert(y, 1 - a);
                    changed = true;
                }
                (None, Some(a)) => {
                    side.insert(x, 1 - a);
                    changed = true;
                }
                (Some(a), Some(c)) if a == c => {
                    return Err(b.invalid(
                        key.to_string(),
                        format!(
                            "group \"{name}\" joins bodies that cannot be put on two sides of one interface (\"{}\" and \"{}\" are on the same side): give the contacts their own groups",
                            bodies[x].name, bodies[y].name
                        ),
                    ))
                }
                _ => {}
            }
        }
        if !changed {
            break;
        }
    }
    if edges.iter().any(|(x, _)| !side.contains_key(x)) {
        return Err(b.invalid(key.to_string(), format!("group \"{name}\" is made of pieces between unrelated bodies: give each piece its own contact group")));
    }
    let mut sides = [Vec::new(), Vec::new()];
    for (&body, &sd) in &side {
        sides[sd].push(body);
    }
    sides[0].sort_unstable();
    sides[1].sort_unstable();
    Ok(sides)
}

/// The end nodes of a group of line facets: corner nodes of one facet only.
/// (Surfaces have no ends in this sense: junctions of contact surfaces in 3D
/// are not supported.)
fn curve_ends(facets: &[Cell]) -> Vec<usize> {
    let mut count: HashMap<usize, usize> = HashMap::new();
    for f in facets.iter().filter(|f| f.kind.dim() == 1) {
        for &n in &f.nodes[..2] {
            *count.entry(n).or_default() += 1;
        }
    }
    let mut ends: Vec<usize> = count.into_iter().filter(|&(_, c)| c == 1).map(|(n, _)| n).collect();
    ends.sort_unstable();
    ends
}

/// The one body a group (one side of a `groups = [..]` contact) bounds.
fn single_body(b: &Builder, key: &str, name: &str, nb: &[Vec<usize>], bodies: &[Body], facets: &[Cell]) -> Result<usize, ModelError> {
    let mut found = None;
    for f in facets {
        let owners = facet_bodies(nb, f);
        match (owners.as_slice(), found) {
            ([one], None) => found = Some(*one),
            ([one], Some(prev)) if *one == prev => {}
            _ => {
                return Err(b.invalid(
                    key.to_string(),
                    format!(
                        "element {} of group \"{name}\" must bound exactly one body (it bounds {}); with groups = [..] each group is the face of one body",
                        f.tag,
                        if owners.is_empty() { "none".to_string() } else { owners.iter().map(|&o| format!("\"{}\"", bodies[o].name)).collect::<Vec<_>>().join(", ") }
                    ),
                ))
            }
        }
    }
    found.ok_or_else(|| b.invalid(key.to_string(), format!("group \"{name}\" has no elements")))
}

/// Pairs every node of `a` with the one node of `b` within `tol`; error when
/// a node has no partner or several.
fn pair_by_position(coords: &[[f64; 3]], a: &[usize], b: &[usize], tol: f64) -> Result<Vec<(usize, usize)>, String> {
    // Sort b by x and search a window: robust for large offsets because only
    // differences of nearby coordinates are compared.
    let mut sorted: Vec<usize> = b.to_vec();
    sorted.sort_by(|&p, &q| coords[p][0].total_cmp(&coords[q][0]));
    let xs: Vec<f64> = sorted.iter().map(|&n| coords[n][0]).collect();
    let mut pairs = Vec::with_capacity(a.len());
    let mut used = vec![false; sorted.len()];
    let mut lonely = Vec::new();
    for &k in a {
        let x = coords[k];
        let lo = xs.partition_point(|&v| v < x[0] - tol);
        let hits: Vec<usize> = (lo..sorted.len())
            .take_while(|&j| xs[j] <= x[0] + tol)
            .filter(|&j| element::norm(element::sub(coords[sorted[j]], x)) <= tol)
            .collect();
        match hits.as_slice() {
            [j] => {
                used[*j] = true;
                pairs.push((k, sorted[*j]));
            }
            [] => lonely.push(x),
            _ => return Err(format!("node at {:?} has {} partners within {:.1e}: the mesh has duplicate nodes", x, hits.len(), tol)),
        }
    }
    lonely.extend(sorted.iter().zip(&used).filter(|(_, &u)| !u).map(|(&n, _)| coords[n]));
    if !lonely.is_empty() {
        let first: Vec<String> = lonely.iter().take(5).map(|p| format!("({:.6}, {:.6}, {:.6})", p[0], p[1], p[2])).collect();
        return Err(format!(
            "{} node(s) find no partner on the other side within {:.1e}, first at {}: the two groups must have coincident nodes (same mesh divisions on both curves/surfaces)",
            lonely.len(),
            tol,
            first.join(", ")
        ));
    }
    Ok(pairs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::CellKind;

    #[test]
    fn pairing_by_position_is_robust_far_from_origin() {
        let base = [5.0e5, 4.2e6, 0.0];
        let mut coords = Vec::new();
        for i in 0..5 {
            coords.push([base[0] + i as f64 * 0.1, base[1] + 0.3 * i as f64, 0.0]);
        }
        for i in (0..5).rev() {
            // the same points, with round-off
            coords.push([base[0] + i as f64 * 0.1 + 1e-9, base[1] + 0.3 * i as f64 - 1e-9, 0.0]);
        }
        let pairs = pair_by_position(&coords, &[0, 1, 2, 3, 4], &[5, 6, 7, 8, 9], 1e-6 * 2.0).unwrap();
        assert_eq!(pairs, vec![(0, 9), (1, 8), (2, 7), (3, 6), (4, 5)]);
        coords[5][0] += 0.05;
        let err = pair_by_position(&coords, &[0, 1, 2, 3, 4], &[5, 6, 7, 8, 9], 1e-6 * 2.0).unwrap_err();
        assert!(err.contains("no partner"), "{err}");
    }

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
