//! What a run warns of beyond its errors: what the scene and the model make
//! legal but a user may not mean, and in-situ stresses beyond strength,
//! each paragraph with the scene file in front.

use crate::contact::{PairLaw, SlipLaw};
use crate::model::insitu::JointStrength;
use crate::model::Model;
use crate::scene::Scene;

/// What is legal but probably not meant, one paragraph each: the scene's
/// ([`Scene::warnings`]) and the model's (bodies bonded by shared nodes,
/// [`crate::model::warnings`], unless the run bonded every contact on
/// purpose: [`Scene::bonded`]).
pub(crate) fn warnings(scene: &Scene, model: &Model) -> Vec<String> {
    let mut w = scene.warnings();
    if !scene.bonded {
        w.extend(model_warnings(scene, model));
    }
    w.extend(insitu_warnings(scene, model));
    w
}

/// The model's warnings ([`crate::model::warnings`], and its hairline
/// contact facets, [`hairline`]), each with the scene file's name in
/// front.
pub fn model_warnings(scene: &Scene, model: &Model) -> Vec<String> {
    let mut w = crate::model::warnings::warnings(model);
    w.extend(hairline(model).into_iter().map(|h| h.said()));
    in_scene(scene, w)
}

/// A pair controlling at most this share of its contact group's median
/// pair's area lies on a facet a hair wide ([`hairline`]). A mesh graded
/// from 0.5 to 10 m changes pair areas some 400-fold; the tiny pairs of
/// tests/corpus/dam3d.toml control 2e-5 of the median.
const HAIRLINE: f64 = 1e-4;

/// A contact group's pairs on hairline facets ([`HAIRLINE`]).
struct Hairline {
    name: String,
    pairs: usize,
    smallest: f64,
    median: f64,
    /// Where the smallest lies.
    at: [f64; 3],
}

impl Hairline {
    fn said(&self) -> String {
        let Hairline { name, pairs, smallest, median, at } = self;
        format!(
            "contact \"{name}\" has {pairs} pair(s) controlling {HAIRLINE:e} or less of its median pair's area (the smallest {smallest:.2e} against {median:.2e}, at ({:.3}, {:.3}, {:.3})): a facet a hair wide, as where two joints' traces meet the model's boundary a hair apart. Rigid joints across it are ill-conditioned: tests/corpus/dam3d.toml's two sets, whose traces met a side 1 mm apart, changed 628 pairs at once in one iteration, with pair forces 400 times the largest. Move one joint set's offset by a part of its spacing, or its snap where `check` lists the plane as snapped onto a corner (or one plane of the .geo), so that the traces meet at one point or well apart",
            at[0], at[1], at[2]
        )
    }
}

/// The contact groups with pairs on hairline facets, by the areas the
/// pairs control in the interface basis ([`crate::contact::basis`]: a
/// quadratic face's corners control none in the nodal one). A pair whose
/// two sides the supports hold on every axis is left out: nothing is
/// solved for there (slope3d's six on J1 and J2 lie on its fixed base).
fn hairline(model: &Model) -> Vec<Hairline> {
    let areas = crate::contact::basis::FaceBasis::new(model).areas;
    let nd = model.nd;
    let fixed = |n: usize| (0..nd).all(|c| model.prescribed[n * nd + c].is_some());
    let held = |p: usize| fixed(model.pairs[p].k) && fixed(model.pairs[p].l);
    let mut groups: Vec<Vec<(f64, usize)>> = vec![Vec::new(); model.interfaces.len()];
    for (p, pair) in model.pairs.iter().enumerate() {
        groups[pair.contact].push((areas[p], p));
    }
    let mut out = Vec::new();
    for (interface, mut group) in model.interfaces.iter().zip(groups) {
        group.sort_by(|a, b| a.0.total_cmp(&b.0));
        let Some(&(median, _)) = group.get(group.len() / 2) else { continue };
        let tiny: Vec<&(f64, usize)> =
            group.iter().take_while(|(a, _)| *a <= HAIRLINE * median).filter(|(_, p)| !held(*p)).collect();
        if let Some(&&(smallest, p)) = tiny.first() {
            let pairs = tiny.len();
            // (rounded as said, + 0.0: no -0.000)
            let at = model.coords[model.pairs[p].k].map(|x| (x * 1e3).round() / 1e3 + 0.0);
            out.push(Hairline { name: interface.name.clone(), pairs, smallest, median, at });
        }
    }
    out
}

/// The paragraphs `w`, each with the scene file's name in front.
fn in_scene(scene: &Scene, w: Vec<String>) -> Vec<String> {
    w.into_iter().map(|w| format!("{}: {w}", scene.path.display())).collect()
}

/// The contact groups the in-situ stress puts beyond their strength
/// ([`crate::model::insitu`]), one paragraph each.
pub fn insitu_warnings(scene: &Scene, model: &Model) -> Vec<String> {
    in_scene(scene, crate::model::insitu::warnings(model, &joint_strengths(scene)))
}

/// The largest mobilisation `|τ| / (c + f σn')` the in-situ stress puts
/// on a pair beyond its strength in shear (0 where none is), the pairs
/// carrying `laws` (the scene's, or a safety trial's: its strength
/// divided by F mobilises the joints F times as much where both c and f
/// are divided, and otherwise as the laws say): what the initial stage's
/// strength ramp starts from ([`crate::contact::ramp`]). The pairs of one
/// contact group share its law (a trial reduces groups, not pairs).
pub fn insitu_mobilised(scene: &Scene, model: &Model, laws: &[PairLaw]) -> f64 {
    let mut strengths = joint_strengths(scene);
    for (pair, law) in model.pairs.iter().zip(laws) {
        let s = &mut strengths[pair.contact];
        s.friction = law.strength.friction;
        s.cohesion = law.strength.cohesion;
        s.tensile_strength = law.strength.tensile_strength;
    }
    let beyond = crate::model::insitu::beyond(model, &strengths);
    beyond.iter().filter(|e| e.shear > 0).map(|e| e.mobilised).fold(0.0, f64::max)
}

/// What each contact group can carry, as the in-situ check reads it.
fn joint_strengths(scene: &Scene) -> Vec<JointStrength> {
    (scene.contacts.iter())
        .map(|c| JointStrength {
            friction: c.strength.friction,
            cohesion: c.strength.cohesion,
            tensile_strength: c.strength.tensile_strength,
            skip: c.slip == SlipLaw::Frictionless || c.water.is_some(),
        })
        .collect()
}
