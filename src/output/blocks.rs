//! Blocks as results: what each block (model body) does in a state of the
//! run, for `blocks.csv` (the run's last load step; `safety_blocks.csv` at
//! the safety search's F), the VTU cell field `block_state` and report.md's
//! ranking of the blocks that move most against their neighbours.
//!
//! Over a block's volume V, with the consistent nodal weights w_n = ∫ N_n
//! dV (Σ w_n = V, exact for isoparametric cells since Σ N_n x_n = x):
//!
//! ```text
//! c   = Σ w_n x_n / V                 the centroid
//! u_c = Σ w_n u_n / V                 its displacement
//! J ω = Σ w_n r_n × u_n,  r_n = x_n - c,  J = Σ w_n (|r_n|² I - r_n r_n^T)
//! ```
//!
//! ω is the block's rotation (radians, the least-squares rigid fit: exact
//! for a rigid motion). Its displacement relative to its neighbours is
//! `|u_c - Σ_f A_f u_c(f) / Σ_f A_f|` over the face pairs f it shares
//! (A_f their areas). Its largest mobilised friction is the largest over
//! the pairs of its faces ([`super::resultants::mobilised`]), its open
//! fraction the share of its faces' area that is open, and its toppling
//! margin ([`toppling_margin`]) the smallest over the faces it rests on
//! (its outward normal there along gravity) that carry a share of its
//! weight in compression, from a tenth to twice it (a block clamped by
//! the stress of the rock round it does not rest on a face): d / e,
//! e the eccentricity of the normal force's point of action from the
//! face's centroid, d the distance from the centroid to the face's edge
//! that way (Goodman & Bray's (b/h) / tan θ for a block on a plane).
//! Its state: held, or how it moves in the mechanism of a loss of
//! equilibrium ([`BlockState`]).

use std::fmt::Write;

use nalgebra::{Matrix3, Vector3};

use super::resultants::mobilised;
use crate::contact::law::{ContactState, Strength};
use crate::contact::mechanism::{toppling_margin, BlockState, Mechanism};
use crate::fem::element::body_force;
use crate::fem::vec3::{cross, dot, norm, sub};
use crate::model::Model;
use crate::results::{ContactRun, Run};

/// Blocks in report.md's ranking.
pub const MOST_BLOCKS: usize = 15;

/// One block in one state.
#[derive(Clone, Debug)]
pub struct Block {
    pub block: usize,
    pub volume: f64,
    pub centroid: [f64; 3],
    pub displacement: [f64; 3],
    pub rotation: [f64; 3],
    /// |u_c| relative to the area-weighted mean of its neighbours'.
    pub relative: f64,
    pub mobilised: f64,
    /// The open share of its faces' area.
    pub open: f64,
    pub toppling_margin: Option<f64>,
    pub state: BlockState,
}

/// Each block's nodes and their weights ∫ N dV, its volume and centroid.
struct Weights {
    nodes: Vec<(usize, f64)>,
    volume: f64,
    centroid: [f64; 3],
}

/// Block `b`'s volume (its area times the thickness in plane analyses).
pub fn volume(model: &Model, b: usize) -> f64 {
    weights(model, b).volume
}

fn weights(model: &Model, b: usize) -> Weights {
    let nd = model.nd;
    let mut w = vec![0.0; model.n_nodes()];
    let mut used = Vec::new();
    for cell in &model.bodies[b].cells {
        let xe: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| model.coords[n]).collect();
        let mut fe = vec![0.0; cell.nodes.len() * nd];
        // inverted cells were refused when the model was built
        let _ = body_force(model.analysis, cell.kind, &xe, [1.0, 0.0, 0.0], model.thickness, &mut fe);
        for (a, &n) in cell.nodes.iter().enumerate() {
            if w[n] == 0.0 {
                used.push(n);
            }
            w[n] += fe[a * nd];
        }
    }
    let nodes: Vec<(usize, f64)> = used.into_iter().map(|n| (n, w[n])).collect();
    let volume: f64 = nodes.iter().map(|x| x.1).sum();
    let v = if volume > 0.0 { volume } else { 1.0 };
    let centroid = std::array::from_fn(|i| nodes.iter().map(|&(n, w)| w * model.coords[n][i]).sum::<f64>() / v);
    Weights { nodes, volume, centroid }
}

/// The displacement of the centroid and the rotation of a block.
fn kinematics(model: &Model, w: &Weights, u: &[f64]) -> ([f64; 3], [f64; 3]) {
    let nd = model.nd;
    let at = |n: usize| -> [f64; 3] {
        std::array::from_fn(|c| if c < nd { u.get(n * nd + c).copied().unwrap_or(0.0) } else { 0.0 })
    };
    let v = if w.volume > 0.0 { w.volume } else { 1.0 };
    let uc: [f64; 3] = std::array::from_fn(|i| w.nodes.iter().map(|&(n, x)| x * at(n)[i]).sum::<f64>() / v);
    let mut j = Matrix3::<f64>::zeros();
    let mut m = Vector3::<f64>::zeros();
    for &(n, x) in &w.nodes {
        let r = sub(model.coords[n], w.centroid);
        let rv = Vector3::from(r);
        j += x * (Matrix3::identity() * dot(r, r) - rv * rv.transpose());
        m += x * Vector3::from(cross(r, at(n)));
    }
    let omega = match model.analysis {
        crate::fem::Analysis::Axisymmetric => [0.0; 3],
        crate::fem::Analysis::Solid => j.try_inverse().map_or([0.0; 3], |ji| (ji * m).into()),
        _ => [0.0, 0.0, if j[(2, 2)] > 0.0 { m[2] / j[(2, 2)] } else { 0.0 }],
    };
    (uc, omega)
}

/// Every block of the model in the state `u`, `c` (pair strengths
/// `strength` per contact group, cracked where `c` says so), with the
/// states of a `mechanism` where one was found.
pub fn blocks(
    model: &Model,
    u: &[f64],
    c: Option<&ContactRun>,
    strength: &[Strength],
    mechanism: Option<&Mechanism>,
) -> Vec<Block> {
    let nb = model.bodies.len();
    let w: Vec<Weights> = (0..nb).map(|b| weights(model, b)).collect();
    let kin: Vec<([f64; 3], [f64; 3])> = w.iter().map(|w| kinematics(model, w, u)).collect();
    let faces = c.map(|c| Faces::of(model, c, strength)).unwrap_or_default();
    (0..nb)
        .map(|b| {
            let (uc, omega) = kin[b];
            let (mut area, mut sum) = (0.0, [0.0; 3]);
            for (nb_, a) in faces.neighbours(b) {
                area += a;
                (0..3).for_each(|i| sum[i] += a * kin[nb_].0[i]);
            }
            let relative = if area > 0.0 { norm(std::array::from_fn(|i| uc[i] - sum[i] / area)) } else { norm(uc) };
            Block {
                block: b,
                volume: w[b].volume,
                centroid: w[b].centroid,
                displacement: uc,
                rotation: omega,
                relative,
                mobilised: faces.mobilised[b],
                open: if faces.area[b] > 0.0 { faces.open[b] / faces.area[b] } else { 0.0 },
                toppling_margin: faces.margin(
                    model,
                    b,
                    model.bodies[b].material.density * norm(model.gravity) * w[b].volume,
                ),
                state: mechanism.map_or(BlockState::Held, |m| m.of(b)),
            }
        })
        .collect()
}

/// The blocks' faces in one contact state.
#[derive(Default)]
struct Faces {
    /// Per block: the largest mobilised friction, its faces' area and open area.
    mobilised: Vec<f64>,
    area: Vec<f64>,
    open: Vec<f64>,
    /// Per face pair (contact, block I, block II): area, normal force
    /// (compression positive) and its moment sums, pair positions, the
    /// mean outward normal of block I.
    pairs: std::collections::BTreeMap<(usize, usize, usize), Face>,
    gravity: [f64; 3],
}

#[derive(Default)]
struct Face {
    area: f64,
    centre: [f64; 3],
    normal: [f64; 3],
    pressure: f64,
    moment: [f64; 3],
    points: Vec<[f64; 3]>,
}

impl Faces {
    fn of(model: &Model, c: &ContactRun, strength: &[Strength]) -> Faces {
        let nb = model.bodies.len();
        let body = model.body_of_node();
        let mut f = Faces {
            mobilised: vec![0.0; nb],
            area: vec![0.0; nb],
            open: vec![0.0; nb],
            pairs: Default::default(),
            gravity: model.gravity,
        };
        for (p, pair) in model.pairs.iter().enumerate() {
            let (i, ii) = (body[pair.k], body[pair.l]);
            let a = c.areas[p];
            let m = mobilised(c.states[p], &c.pairs[p], &strength[pair.contact], c.is_cracked(p));
            for b in [i, ii] {
                f.mobilised[b] = f.mobilised[b].max(m);
                f.area[b] += a;
                if c.states[p] == ContactState::Open {
                    f.open[b] += a;
                }
            }
            let face = f.pairs.entry((pair.contact, i, ii)).or_default();
            let x = model.coords[pair.k];
            let press = -c.pairs[p].sigma_n * a;
            face.area += a;
            face.pressure += press;
            (0..3).for_each(|k| {
                face.centre[k] += a * x[k];
                face.normal[k] += a * c.frames[p][0][k];
                face.moment[k] += press * x[k];
            });
            face.points.push(x);
        }
        f
    }

    /// The blocks sharing a face with `b`, and the face's area.
    fn neighbours(&self, b: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.pairs.iter().filter_map(move |(&(_, i, ii), face)| match (i == b, ii == b) {
            (true, false) => Some((ii, face.area)),
            (false, true) => Some((i, face.area)),
            _ => None,
        })
    }

    /// The smallest toppling margin of the faces block `b` (of weight
    /// `weight`) rests on: those below it (its outward normal along
    /// gravity) that carry a share of its weight, not a multiple of it (a
    /// block clamped by the stress of the rock round it does not rest).
    fn margin(&self, model: &Model, b: usize, weight: f64) -> Option<f64> {
        let supported = |blk: usize| {
            crate::recover::body_nodes(&model.bodies[blk])
                .iter()
                .any(|&n| (0..model.nd).any(|c| model.prescribed[n * model.nd + c].is_some()))
        };
        if supported(b) {
            return None;
        }
        let mut best: Option<f64> = None;
        for (&(_, i, ii), face) in &self.pairs {
            let sign = if i == b {
                1.0
            } else if ii == b {
                -1.0
            } else {
                continue;
            };
            // it rests on the face where its outward normal is along gravity
            let rests = norm(self.gravity) == 0.0 || sign * dot(face.normal, self.gravity) > 0.0;
            // it carries a share of the block's weight, not a multiple of it
            let carries = weight <= 0.0 || (0.1 * weight..=2.0 * weight).contains(&face.pressure);
            if !rests || !carries || face.pressure <= 0.0 || face.area <= 0.0 {
                continue;
            }
            let centre = face.centre.map(|v| v / face.area);
            let action = face.moment.map(|v| v / face.pressure);
            if let Some(m) = toppling_margin(centre, action, &face.points) {
                best = Some(best.map_or(m, |x: f64| x.min(m)));
            }
        }
        best
    }
}

/// `blocks.csv`: one row per block.
pub fn blocks_csv(model: &Model, blocks: &[Block]) -> String {
    let mut s = String::from("block,body,name,volume,x,y,z,u_x,u_y,u_z,rotation_x,rotation_y,rotation_z,relative_displacement,mobilised_max,open_fraction,toppling_margin,state\n");
    for b in blocks {
        let nums: Vec<String> = [b.volume]
            .iter()
            .chain(&b.centroid)
            .chain(&b.displacement)
            .chain(&b.rotation)
            .chain(&[b.relative, b.mobilised, b.open])
            .map(|v| format!("{v:.9e}"))
            .collect();
        let margin =
            b.toppling_margin.map_or(String::new(), |m| if m.is_finite() { format!("{m:.6}") } else { "inf".into() });
        let _ = writeln!(
            s,
            "{},{},{},{},{margin},{}",
            b.block,
            super::csv::csv_field(&model.bodies[b.block].name),
            super::csv::csv_field(&super::faces::block_name(model, b.block)),
            nums.join(","),
            b.state.key()
        );
    }
    s
}

/// The blocks ranked: those in a mechanism first, then by displacement
/// relative to their neighbours.
pub fn ranked(blocks: &[Block]) -> Vec<&Block> {
    let mut v: Vec<&Block> = blocks.iter().collect();
    v.sort_by(|a, b| {
        (b.state != BlockState::Held)
            .cmp(&(a.state != BlockState::Held))
            .then(b.relative.total_cmp(&a.relative))
            .then(norm(b.displacement).total_cmp(&norm(a.displacement)))
    });
    v
}

/// report.md's section on the blocks (empty with one block).
pub fn report(model: &Model, blocks: &[Block], displaced: bool) -> String {
    if blocks.len() < 2 {
        return String::new();
    }
    let mut s = String::from("\n## Blocks\n\n");
    let ranked = ranked(blocks);
    let n = ranked.len().min(MOST_BLOCKS);
    let _ = writeln!(s, "The {n} of {} blocks that move most against their neighbours (displacement of the centroid relative to the area-weighted mean of the blocks it shares faces with), those of a mechanism first; every block in `blocks.csv`, and in the VTU as cell data `block` and `block_state` (0 held, 1 sliding, 2 toppling, 3 lifting, 4 free).{}\n", blocks.len(), if displaced { "" } else { " The displacements were not recovered ([output] fields has no displacement): the ranking is by state alone" });
    let _ = writeln!(s, "| block | centroid | displacement | relative | rotation (rad) | mobilised max | open faces | toppling margin | state |\n|---|---|---|---|---|---|---|---|---|");
    let nd = model.nd;
    for b in &ranked[..n] {
        let margin =
            b.toppling_margin.map_or("–".into(), |m| if m.is_finite() { format!("{m:.3}") } else { "∞".into() });
        let rot = if nd == 3 { format!("{:.3e}", norm(b.rotation)) } else { format!("{:.3e}", b.rotation[2]) };
        let _ = writeln!(
            s,
            "| {} | {} | {:.4e} | {:.4e} | {rot} | {:.3} | {:.0} % | {margin} | {} |",
            super::faces::block_name(model, b.block),
            point(b.centroid, nd),
            norm(b.displacement),
            b.relative,
            b.mobilised,
            100.0 * b.open,
            b.state.key()
        );
    }
    let edge: Vec<String> = blocks
        .iter()
        .filter(|b| b.toppling_margin.is_some_and(|m| m < 3.0))
        .map(|b| format!("{} {:.3}", super::faces::block_name(model, b.block), b.toppling_margin.unwrap_or(0.0)))
        .collect();
    if !edge.is_empty() {
        let _ = writeln!(s, "\nBlocks that rest on an edge-loaded face (the normal force acts outside the middle third: toppling margin d / e below 3; it topples at 1): {}.", edge.join(", "));
    }
    s
}

fn point(x: [f64; 3], nd: usize) -> String {
    let c: Vec<String> = x[..nd.clamp(2, 3)].iter().map(|v| format!("{v:.3}")).collect();
    format!("({})", c.join(", "))
}

/// The blocks of the run's last load step (None without contacts); when
/// the scene is unsafe as given, with the states of its mechanism.
pub fn of_run(run: &Run) -> Option<Vec<Block>> {
    let c = run.contact()?;
    let mechanism = run.safety.as_ref().filter(|s| s.below_one).and_then(|s| s.failure.as_ref()?.mechanism.as_ref());
    let strength = super::resultants::strengths(run);
    Some(blocks(&run.model, &run.last().u, Some(c), &strength, mechanism))
}

/// The blocks at the safety search's F (its last state that holds), with
/// the states of the failing trial's mechanism and the strength at F.
pub fn at_safety(run: &Run) -> Option<Vec<Block>> {
    let s = run.safety.as_ref().filter(|s| !s.below_one)?;
    let last = s.last.as_ref()?;
    let c = last.contact.as_ref()?;
    let mut strength = super::resultants::strengths(run);
    if let (crate::results::SearchKind::Strength(st), Some(o), Some(f)) = (s.kind, run.about.safety.as_ref(), s.factor)
    {
        for &i in &o.contacts {
            let law =
                crate::contact::PairLaw { strength: strength[i], slip: run.about.contacts[i].slip, stiffness: None };
            strength[i] = o.reduce.strength(&st.laws(&[law])[0].strength, f);
        }
    }
    let mechanism = s.failure.as_ref().and_then(|f| f.mechanism.as_ref());
    Some(blocks(&run.model, &last.u, Some(c), &strength, mechanism))
}

/// summary.json's `blocks`: how many, in which state, the file, and the
/// blocks that move most.
pub fn summary(model: &Model, blocks: &[Block]) -> serde_json::Value {
    let mut states = std::collections::BTreeMap::new();
    for b in blocks {
        *states.entry(b.state.key()).or_insert(0usize) += 1;
    }
    let most: Vec<serde_json::Value> = ranked(blocks)
        .into_iter()
        .take(5)
        .map(|b| {
            serde_json::json!({ "block": b.block, "name": super::faces::block_name(model, b.block), "centroid": b.centroid,
                "displacement": b.displacement, "relative_displacement": b.relative, "rotation": b.rotation,
                "mobilised_max": b.mobilised, "toppling_margin": b.toppling_margin.filter(|m| m.is_finite()), "state": b.state.key() })
        })
        .collect();
    serde_json::json!({ "count": blocks.len(), "file": "blocks.csv", "states": states, "most_moving": most })
}

/// report.md's section on the run's blocks.
pub fn run_report(run: &Run, blocks: Option<&[Block]>) -> String {
    let Some(blocks) = blocks else { return String::new() };
    report(&run.model, blocks, run.about.output.wants("displacement") || !run.about.probes.is_empty())
}
