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

/// The model's warnings ([`crate::model::warnings`]), each with the scene
/// file's name in front.
pub fn model_warnings(scene: &Scene, model: &Model) -> Vec<String> {
    in_scene(scene, crate::model::warnings::warnings(model))
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
