//! [`Model::build`]: the model from a mesh and a [`ModelSpec`], in numbered
//! steps, each (but the assembly of the model) a function (here, or in
//! contacts.rs, held.rs, quality.rs) that returns what it built. Each step
//! resolves the physical groups it names (with a message naming the input's
//! key when a group is missing, empty or of the wrong dimension) and moves
//! what it builds onto the model nodes the contact split made.

use std::collections::HashMap;

use super::body::{Block, Body};
use super::boundary::{FacetLoad, SupportDofs};
use super::build_input::Builder;
use super::contacts::{self, facet_sign, RawPair, Split};
use super::errors::ModelError;
use super::held::check_held;
use super::mechanical::Model;
use super::pairs::Pair;
use super::spec::{InitialStress, LoadKind, ModelSpec};
use super::topology::Topology;
use crate::fem::element::{self, dofs_per_node};
use crate::fem::Analysis;
use crate::mesh::{Cell, Mesh};

impl Model {
    /// The model from a mesh and its description: the steps below, in
    /// order, each a function of this file (or of a sibling) that resolves
    /// the groups it names and returns what it built.
    pub fn build(mesh: &Mesh, spec: &ModelSpec) -> Result<Model, ModelError> {
        let b = Builder { mesh, spec };
        // 0. The mesh's dimension is the analysis's.
        check_dimension(&b)?;
        // 1. Bodies: the cells of every body group, in the plane of the analysis.
        let groups = body_groups(&b)?;
        let size = mesh.size();
        check_plane(&b, &groups, size)?;
        // 2. Contacts: the blocks, one node per fan along the contact
        // facets, and the pairs.
        let topo = Topology::new(mesh.coords.len(), spec.analysis.dim(), &groups);
        let split = contacts::split(&b, &topo, size)?;
        let bodies = blocks(spec, &topo, &split.block, &split.cells, &split.coords);
        // 3. Supports, and 3b. every rigid-body motion held by one.
        let (prescribed, support_dofs) = supports(&b, &topo, &split)?;
        let links: Vec<(usize, usize)> = split.pairs.iter().map(|p| (p.k, p.l)).collect();
        check_held(&b, &split.coords, &bodies, &links, &prescribed)?;
        // 4. Load cases, and loads, each facet on the copy of the cell it bounds.
        let cases = Cases::new(spec);
        let loads = loads(&b, &topo, &split, &bodies, &cases.of_load)?;
        let nodal_loads = super::forces::nodal_loads(&b, &topo, &split, &bodies, &cases.of_load)?;
        // 5. Pair normals and areas from their facets on side I.
        let mut model = Model {
            analysis: spec.analysis,
            nd: dofs_per_node(spec.analysis),
            thickness: spec.thickness,
            gravity: spec.gravity,
            coords: split.coords,
            bodies,
            loads,
            nodal_loads,
            supports: support_dofs,
            prescribed,
            pairs: Vec::new(),
            interfaces: split.interfaces,
            mesh_node: split.mesh_node,
            cases: cases.factors,
            load_cases: cases.of_load.clone(),
            gravity_case: cases.gravity,
            initial_case: cases.initial,
            hold_case: cases.hold,
            water: Vec::new(),
            seismic: Vec::new(),
        };
        model.pairs = pair_normals(&model, &split.pairs, &split.signs);
        // 5a. The initial stage's hold load on the bodies' outer faces.
        if let Some(case) = cases.hold {
            let hold = super::hold::loads(&model, case);
            model.loads.extend(hold);
        }
        // 5b. The water in the joints, on the pairs.
        model.water = super::joint_water::resolve(&b, &model, &split.signs, &cases.of_water)?;
        model.seismic = seismic(&b, &cases.of_load)?;
        // 6. Every cell positive over its whole extent, not only where it
        // is integrated.
        super::quality::folded(&model)?;
        Ok(model)
    }
}

/// Ok when the mesh's dimension is the analysis's: a plane analysis of a
/// 3D mesh (or of a 3D .geo meshed in 2D) is a wrong `analysis`, not a
/// wrong body group, and the message says so.
fn check_dimension(b: &Builder) -> Result<(), ModelError> {
    let (mesh, spec) = (b.mesh, b.spec);
    let (sd, mesh_dim) = (spec.analysis.dim(), mesh.dim());
    if mesh_dim != sd {
        return Err(ModelError::MeshDimension {
            analysis: spec.analysis,
            needs: sd,
            mesh: spec.mesh.clone(),
            has: mesh_dim,
        });
    }
    Ok(())
}

/// The cells of every body group, in `[[bodies]]` order; a geostatic
/// initial stress without the weight to make it is an error.
fn body_groups<'a>(b: &Builder<'a>) -> Result<Vec<&'a [Cell]>, ModelError> {
    let spec = b.spec;
    let mut groups: Vec<&[Cell]> = Vec::with_capacity(spec.bodies.len());
    for body in &spec.bodies {
        let g = b.group(&format!("{}.group", body.key), &body.group, &[spec.analysis.dim()])?;
        if let Some(InitialStress::Geostatic { .. }) = body.initial {
            if body.material.density <= 0.0 || spec.gravity.iter().all(|&g| g == 0.0) {
                return Err(ModelError::Weightless { key: format!("{}.k0", body.key), body: body.group.clone() });
            }
        }
        groups.push(&g.cells);
    }
    Ok(groups)
}

/// The prescribed value of every DOF (`node * nd + c`), None where free,
/// and the DOFs each support holds (a DOF two supports hold is the later
/// one's, whose value it takes).
/// A point support holds every copy of its node; a support on a curve or
/// surface holds the copies of the cells its facets bound, so a support on
/// one body's face next to a contact does not drag the other body's copy
/// of the shared corner node (a symmetry line crossing a contact bounds
/// both bodies: both held).
fn supports(b: &Builder, topo: &Topology, split: &Split) -> Result<(Vec<Option<f64>>, Vec<SupportDofs>), ModelError> {
    let (sd, nd) = (b.spec.analysis.dim(), dofs_per_node(b.spec.analysis));
    let mut copies_of: Vec<Vec<usize>> = vec![Vec::new(); b.mesh.coords.len()];
    for (m, &n) in split.mesh_node.iter().enumerate() {
        copies_of[n].push(m);
    }
    let mut prescribed: Vec<Option<f64>> = vec![None; split.coords.len() * nd];
    let mut owner: Vec<usize> = vec![usize::MAX; split.coords.len() * nd];
    for (si, s) in b.spec.supports.iter().enumerate() {
        let g = b.group(&format!("{}.group", s.key), &s.group, &(0..=sd).collect::<Vec<_>>())?;
        let mut held: Vec<usize> = Vec::new();
        for cell in &g.cells {
            let owners = if cell.kind.dim() == 0 { Vec::new() } else { topo.bounding(cell) };
            for &n in &cell.nodes {
                if owners.is_empty() {
                    held.extend(copies_of[n].iter().copied());
                } else {
                    held.extend(owners.iter().map(|&c| topo.node_in(&split.cells, c, n)));
                }
            }
        }
        held.sort_unstable();
        held.dedup();
        for m in held {
            for c in 0..nd {
                let value = match s.prescribed[c] {
                    Some(v) => v,
                    None if s.fix[c] => 0.0,
                    None => continue,
                };
                prescribed[m * nd + c] = Some(value);
                owner[m * nd + c] = si;
            }
        }
    }
    let mut groups: Vec<SupportDofs> =
        b.spec.supports.iter().map(|s| SupportDofs { group: s.group.clone(), dofs: Vec::new() }).collect();
    for (dof, &o) in owner.iter().enumerate() {
        if o != usize::MAX {
            groups[o].dofs.push(dof);
        }
    }
    Ok((prescribed, groups))
}

/// The load cases, numbered as the model numbers them.
struct Cases {
    /// Load factor of each case at each load step.
    factors: Vec<Vec<f64>>,
    /// The case of each of the description's loads.
    of_load: Vec<usize>,
    /// The case of each contact's water (None: a dry contact).
    of_water: Vec<Option<usize>>,
    /// The case of gravity, and of the initial stresses.
    gravity: usize,
    initial: usize,
    /// The case of the initial stage's hold load (0 at every step).
    hold: Option<usize>,
}

impl Cases {
    /// The ramp k / load_steps (case 0, for whatever has no factors of its
    /// own), then each load's own factors, each joint water's, gravity's,
    /// and the initial stresses' (1 at every step: they are there before
    /// the first load). Joint water without factors takes the case of the
    /// face it connects to, or the ramp. With the initial stage, gravity
    /// without factors has a case of its own at 1 throughout (it is there
    /// in full from the stage on), and the hold load one at 0 throughout
    /// (the stage's factors are [`Model::stage_factors`]).
    fn new(spec: &ModelSpec) -> Cases {
        let steps = spec.load_steps;
        let mut factors: Vec<Vec<f64>> = vec![(1..=steps).map(|k| k as f64 / steps as f64).collect()];
        let mut case_of = |own: &Option<Vec<f64>>| match own {
            None => 0,
            Some(f) => {
                factors.push(f.clone());
                factors.len() - 1
            }
        };
        let of_load: Vec<usize> = spec.loads.iter().map(|load| case_of(&load.factors)).collect();
        let of_water = (spec.contacts.iter())
            .map(|c| {
                c.water.as_ref().map(|w| match (&w.factors, &w.face) {
                    (None, Some(face)) => of_load[face.load],
                    (own, _) => case_of(own),
                })
            })
            .collect();
        let full = (spec.initial_stage && spec.gravity_factors.is_none()).then(|| vec![1.0; steps]);
        let gravity = case_of(if full.is_some() { &full } else { &spec.gravity_factors });
        factors.push(vec![1.0; steps]);
        let initial = factors.len() - 1;
        let hold = spec.initial_stage.then(|| {
            factors.push(vec![0.0; steps]);
            factors.len() - 1
        });
        Cases { factors, of_load, of_water, gravity, initial, hold }
    }
}

/// Every facet of every load group on the copy of the cell it bounds, with
/// the sign that makes its normal outward and its load case (`of_load`);
/// a facet on no body's boundary, or between two bodies, is an error, and
/// so is a pressure or traction on a point. Forces (`force = [..]`) are
/// spread onto nodes instead ([`super::forces`]).
fn loads(
    b: &Builder,
    topo: &Topology,
    split: &Split,
    bodies: &[Body],
    of_load: &[usize],
) -> Result<Vec<FacetLoad>, ModelError> {
    let mut loads = Vec::new();
    for (load, &case) in b.spec.loads.iter().zip(of_load) {
        if matches!(load.kind, LoadKind::Force(_) | LoadKind::Seismic { .. }) {
            continue;
        }
        let key = format!("{}.group", load.key);
        if b.mesh.group(&load.group).is_some_and(|g| g.dim == 0) {
            return Err(ModelError::TractionOnPoint { key, group: load.group.clone() });
        }
        let g = b.group(&key, &load.group, &[b.spec.analysis.dim() - 1])?;
        let pressure = load.kind.pressure_at([0.0; 3], 1).is_some();
        for (cell, sign, body, element) in placed_facets(topo, split, bodies, &key, g, pressure)? {
            loads.push(FacetLoad { cell, sign, kind: load.kind.clone(), body, element, case });
        }
    }
    Ok(loads)
}

/// The seismic loads' accelerations, `|g| (kh direction + kv up)` with up
/// against gravity, and their load cases (`of_load`).
fn seismic(b: &Builder, of_load: &[usize]) -> Result<Vec<([f64; 3], usize)>, ModelError> {
    let g = b.spec.gravity;
    let size = element::norm(g);
    let mut out = Vec::new();
    for (load, &case) in b.spec.loads.iter().zip(of_load) {
        let LoadKind::Seismic { kh, kv, direction } = load.kind else { continue };
        if size == 0.0 {
            return Err(ModelError::SeismicWithoutGravity { key: format!("{}.seismic", load.key) });
        }
        out.push((std::array::from_fn(|i| size * kh * direction[i] - kv * g[i]), case));
    }
    Ok(out)
}

/// The facets of a boundary group `g` on the copies of the cells they
/// bound: (facet in model nodes, the sign that makes its normal outward,
/// body, index in the body's cells). A facet on no body's boundary, or
/// between two bodies, is an error about `key` (the latter with a hint on
/// water in joints when the load is a `pressure`).
pub(super) fn placed_facets(
    topo: &Topology,
    split: &Split,
    bodies: &[Body],
    key: &str,
    g: &crate::mesh::Group,
    pressure: bool,
) -> Result<Vec<(Cell, f64, usize, usize)>, ModelError> {
    let placed = placed(&split.block, bodies.len());
    let mut out = Vec::new();
    for f in &g.cells {
        let c = match topo.bounding(f).as_slice() {
            [one] => *one,
            [] => return Err(ModelError::LoadOffBoundary { key: key.to_string(), tag: f.tag, group: g.name.clone() }),
            owners => {
                return Err(ModelError::LoadBetweenBodies {
                    key: key.to_string(),
                    tag: f.tag,
                    group: g.name.clone(),
                    bodies: owners.iter().map(|&c| bodies[split.block[c]].label()).collect(),
                    pressure,
                });
            }
        };
        let mut cell = f.clone();
        for n in &mut cell.nodes {
            *n = topo.node_in(&split.cells, c, *n);
        }
        let (body, element) = placed[c];
        let sign = facet_sign(&split.coords, &cell, &split.cells[c]);
        out.push((cell, sign, body, element));
    }
    Ok(out)
}

/// Where each cell went: (its body, its index in the body's cells), as
/// [`blocks`] puts the cells of every block in order.
pub(super) fn placed(block: &[usize], n_bodies: usize) -> Vec<(usize, usize)> {
    let mut placed = vec![(0, 0); block.len()];
    let mut count = vec![0; n_bodies];
    for (c, &bl) in block.iter().enumerate() {
        placed[c] = (bl, count[bl]);
        count[bl] += 1;
    }
    placed
}

/// The pairs with their normals and areas, integrated over the facets of
/// side I each pair takes them from (`signs`: each facet's outward sign);
/// where a copy is in several pairs, the normal of its surface there
/// ([`super::normals`]).
fn pair_normals(model: &Model, raw_pairs: &[RawPair], signs: &[Vec<f64>]) -> Vec<Pair> {
    let mut points: HashMap<(usize, usize), Vec<FacetPoint>> = HashMap::new();
    let mut sums = Vec::with_capacity(raw_pairs.len());
    let mut areas = Vec::with_capacity(raw_pairs.len());
    for p in raw_pairs {
        let (mut nk, mut area) = ([0.0; 3], 0.0);
        for s in &p.shares {
            let pts = points
                .entry((p.contact, s.facet))
                .or_insert_with(|| facet_points(model, &model.interfaces[p.contact].facets[s.facet]));
            let sign = signs[p.contact][s.facet];
            for q in pts.iter() {
                let a = s.node;
                area += q.w * q.da * q.measure * q.n[a];
                // normals weighted by geometry only (N_a >= 0 weights
                // avoid cancelling on serendipity faces)
                for i in 0..3 {
                    nk[i] += sign * q.unit[i] * q.w * q.da * q.n[a].abs();
                }
            }
        }
        sums.push(nk);
        areas.push(area);
    }
    let copies: Vec<[usize; 2]> = raw_pairs.iter().map(|p| [p.k, p.l]).collect();
    let contacts: Vec<usize> = raw_pairs.iter().map(|p| p.contact).collect();
    let normals = super::normals::smooth_normals(&copies, &contacts, &sums, &model.mesh_node);
    (raw_pairs.iter().zip(normals).zip(areas))
        .map(|((p, normal), area)| Pair {
            k: p.k,
            l: p.l,
            contact: p.contact,
            normal,
            area,
            shares: p.shares.iter().map(|s| (s.facet, s.node)).collect(),
        })
        .collect()
}

/// Plane models lie in z = 0, axisymmetric ones in x = r >= 0.
fn check_plane(b: &Builder, groups: &[&[Cell]], size: f64) -> Result<(), ModelError> {
    let (mesh, spec) = (b.mesh, b.spec);
    let cells = || groups.iter().enumerate().flat_map(|(i, cs)| cs.iter().map(move |c| (i, c)));
    if spec.analysis.dim() == 2 {
        let tol = 1e-9 * size.max(1.0);
        if let Some((body, cell)) = cells().find(|(_, c)| c.nodes.iter().any(|&n| mesh.coords[n][2].abs() > tol)) {
            return Err(ModelError::NotInPlane { tag: cell.tag, body: spec.bodies[body].group.clone() });
        }
    }
    if spec.analysis == Analysis::Axisymmetric {
        let tol = 1e-9 * size;
        if let Some((body, cell)) = cells().find(|(_, c)| c.nodes.iter().any(|&n| mesh.coords[n][0] < -tol)) {
            return Err(ModelError::NegativeRadius { tag: cell.tag, body: spec.bodies[body].group.clone() });
        }
    }
    Ok(())
}

/// The model's bodies: one per block, in block order, each with the
/// material of its body group.
fn blocks(spec: &ModelSpec, topo: &Topology, block: &[usize], cells: &[Cell], coords: &[[f64; 3]]) -> Vec<Body> {
    let n = block.iter().map(|&b| b + 1).max().unwrap_or(0);
    let mut group_of = vec![0; n];
    let mut members: Vec<Vec<Cell>> = vec![Vec::new(); n];
    for (c, &bl) in block.iter().enumerate() {
        group_of[bl] = topo.body[c];
        members[bl].push(cells[c].clone());
    }
    let per_group: Vec<usize> = (0..spec.bodies.len()).map(|g| group_of.iter().filter(|&&x| x == g).count()).collect();
    let mut seen = vec![0; spec.bodies.len()];
    members
        .into_iter()
        .enumerate()
        .map(|(bl, cells)| {
            let g = group_of[bl];
            let body = &spec.bodies[g];
            let block = (per_group[g] > 1).then(|| {
                let nodes: Vec<usize> = cells.iter().flat_map(|c| c.nodes.iter().copied()).collect();
                let centre = std::array::from_fn(|d| {
                    nodes.iter().map(|&n| coords[n][d]).sum::<f64>() / nodes.len().max(1) as f64
                });
                Block { index: seen[g], of: per_group[g], centre }
            });
            seen[g] += 1;
            Body { name: body.group.clone(), group: g, block, material: body.material, cells, initial: body.initial }
        })
        .collect()
}

/// A quadrature point of a facet: weight, shape values, natural unit
/// normal, area element and the analysis's measure (thickness, 2 pi r).
struct FacetPoint {
    w: f64,
    n: Vec<f64>,
    unit: [f64; 3],
    da: f64,
    measure: f64,
}

/// The points that integrate `∫ N_a dA` and the normal over a facet.
fn facet_points(model: &Model, f: &Cell) -> Vec<FacetPoint> {
    let fc: Vec<[f64; 3]> = f.nodes.iter().map(|&n| model.coords[n]).collect();
    crate::fem::quadrature::rule(f.kind, 2 * f.kind.order() + 2)
        .iter()
        .map(|q| {
            let (n, unit, da, x) = element::facet_point(f.kind, &fc, q.xi);
            let measure = element::measure(model.analysis, model.thickness, &x);
            FacetPoint { w: q.w, n, unit, da, measure }
        })
        .collect()
}
