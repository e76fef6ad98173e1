//! The scene file: the TOML that sits next to a `.geo` and says what the mesh's
//! physical groups are (bodies, contact interfaces, supports, loads), which
//! materials they are made of, and how to solve. [`Scene::load`] reads, parses
//! and validates it; every failure is a one-paragraph [`SceneError`] naming the
//! scene file, the key path (`materials.rock.nu`, `contacts[1].friction`), the
//! bad value and what to do. Unknown or misspelt keys are errors, never ignored.
//! A short example (the full key list is in DESIGN.md §4):
//!
//! ```toml
//! mesh     = "cylinder.geo"   # or .msh; relative to this file
//! analysis = "plane_strain"   # plane_strain | plane_stress | axisymmetric | solid
//!
//! [materials.rock]
//! E  = 2.0e5
//! nu = 0.167
//!
//! [[bodies]]
//! group = "body_1"
//! material = "rock"
//!
//! [[contacts]]
//! group = "A-A"
//! friction = 0.8
//!
//! [[supports]]
//! group = "symmetry_x0"
//! fix = ["x"]
//!
//! [[loads]]
//! group = "inner_surface"
//! pressure = 0.1
//! ```
//!
//! Validated values are stored with defaults applied; vectors are always 3
//! components (z = 0 for the 2D analyses). The physics owns its vocabulary
//! and the scene holds it as is: a body is a [`BodySpec`] with its
//! [`Material`], a support a [`SupportSpec`], a load a [`LoadSpec`] (model),
//! a contact's strength a [`Strength`] and the safety search's factors
//! [`Steps`] (contact). The TOML as written is `raw.rs`, converted once by
//! the checker; [`Scene::model_spec`] hands the model builder its
//! description.
//!
//! Here: [`Scene::load`] and its kin; `validated.rs` holds the validated
//! types (re-exported here). `raw.rs` is the TOML as
//! written (serde, unknown keys rejected), `errors.rs` the error type and the
//! mapping of toml's errors onto it, `validate.rs` (with `validate/`) the
//! checker that turns the raw scene into this one, key by key.

use std::path::Path;

use crate::mesh::joints::CutJob;
use crate::model::{ContactSpec, ModelSpec};

mod errors;
mod raw;
#[cfg(test)]
mod tests;
mod validate;
mod validated;

pub use errors::SceneError;
pub use validated::{
    ColourScale, Contact, GmshOptions, MeshSource, Output, Raise, Region, Safety, Scene, Solver, OUTPUT_FIELDS,
};

pub use crate::analytic::Analytic;
pub use crate::contact::law::{Stiffness, Strength};
pub use crate::contact::safety::{Reduce, Steps, Strengths};
pub use crate::contact::{InterfaceSolver, SlipLaw, StateRule, TractionRecovery};
pub use crate::fem::Analysis;
pub use crate::model::water::{Drain, JointWater, Levels, WaterFace, WaterPressure};
pub use crate::model::{BodySpec, ContactGroups, ForceLoad, InitialStress, LoadKind, LoadSpec, Material, SupportSpec};
pub use crate::recover::sections::{Cut, SectionSpec};
pub use crate::recover::Probe;

/// The most bytes a scene file may have: a scene is a page of TOML.
const MAX_SCENE_BYTES: u64 = 16 << 20;

/// The text of the scene file `path`: a plain file (not a device such as
/// /dev/zero, whose reading never ends), of at most 16 MB.
fn read_scene(path: &Path) -> Result<String, SceneError> {
    use std::io::Read;
    let err = |source: std::io::Error| SceneError::Read { path: path.to_path_buf(), source };
    let file = std::fs::File::open(path).map_err(err)?;
    let meta = file.metadata().map_err(err)?;
    if !meta.is_file() {
        let what = if meta.is_dir() { "a directory" } else { "not a plain file (a device, a pipe or a socket)" };
        return Err(err(std::io::Error::other(format!("it is {what}; give the path of a scene's .toml file"))));
    }
    let mut text = String::new();
    file.take(MAX_SCENE_BYTES + 1).read_to_string(&mut text).map_err(err)?;
    if text.len() as u64 > MAX_SCENE_BYTES {
        return Err(err(std::io::Error::other(
            "it is larger than 16 MB, which no scene is; give the path of a scene's .toml file",
        )));
    }
    Ok(text)
}

impl Scene {
    /// Read, parse and validate the scene file at `path`.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        Scene::parse(&read_scene(path)?, path)
    }

    /// Parse and validate scene text. `path` is used in messages, for the
    /// scene name, and to resolve `mesh` (which must exist).
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let raw: raw::RawScene = toml::from_str(text).map_err(|e| errors::toml_error(text, path, &e))?;
        validate::Checker { path }.scene(raw)
    }

    /// Whether the scene has contacts and their joints deform
    /// (`normal_stiffness`: validation gives it to every contact or none).
    pub fn joints_deform(&self) -> bool {
        self.contacts.first().is_some_and(|c| c.stiffness.is_some())
    }

    /// Bonds every contact ([`Scene::bonded`]): the bodies keep the nodes
    /// they share, and the run is the monolithic solve (with nothing to
    /// reduce in a safety search).
    pub fn bond_all(&mut self) {
        self.contacts.clear();
        self.bonded = true;
        self.safety = None;
    }

    /// Gives every contact the joint stiffness `k`: its joints deform.
    pub fn give_joints_stiffness(&mut self, k: Stiffness) {
        self.contacts.iter_mut().for_each(|c| c.stiffness = Some(k));
    }

    /// The scene with a safety search: its own `[safety]`, or one with the
    /// defaults (`subcontact safety` on a scene without the table), checked
    /// as the table would be (a scene without contacts has nothing to reduce).
    pub fn with_safety(mut self) -> Result<Scene, SceneError> {
        if self.safety.is_none() {
            self.safety = Some(validate::Checker { path: &self.path }.safety(
                raw::RawSafety::default(),
                &self.contacts,
                &self.loads,
                self.gravity,
            )?);
        }
        Ok(self)
    }

    /// What the mesher cuts the bodies by, when the scene has joints.
    pub fn cut_job(&self) -> Option<CutJob> {
        (!self.joints.is_empty()).then(|| CutJob {
            joints: self.joints.clone(),
            max_blocks: self.max_blocks,
            merge_slivers: self.merge_slivers,
            structured: self.gmsh.structured,
        })
    }

    /// The key path that defined contact `i`: `contacts[i]`, or the
    /// `[[joint_sets]]` / `[[joints]]` entry it comes from.
    pub fn contact_key(&self, i: usize) -> String {
        let first_joint = self.contacts.len().saturating_sub(self.joints.len());
        match i.checked_sub(first_joint).and_then(|j| self.joints.get(j)) {
            Some(j) if !self.bonded => j.key.clone(),
            _ => format!("contacts[{i}]"),
        }
    }

    /// What is legal but probably not what the user meant: a tensile
    /// strength above the Coulomb apex c / f (a joint in tension above c / f
    /// has no shear strength left, so the robust rule opens it there).
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (i, c) in self.contacts.iter().enumerate() {
            let s = &c.strength;
            if s.above_apex() {
                // six significant digits, no trailing zeros
                let apex =
                    format!("{:.6}", s.cohesion / s.friction).trim_end_matches('0').trim_end_matches('.').to_string();
                let name = match &c.groups {
                    ContactGroups::Shared(g) => g.clone(),
                    ContactGroups::Pair(a, b) => format!("{a}|{b}"),
                };
                let then = match self.solver.rule {
                    StateRule::Robust => format!("its pairs open there (the run uses f_t = {apex})"),
                    StateRule::Paper => "the paper's rule keeps f_t, so a pair in tension between c / f and f_t slips with no shear strength and a body held by such pairs slides".to_string(),
                };
                out.push(format!(
                    "{}: contacts[{i}] (\"{name}\"): tensile_strength = {} exceeds the Coulomb apex c / f = {} / {} = {apex}: a joint in tension above c / f has no shear strength left, so {then}. Lower tensile_strength to at most c / f, or raise the cohesion, if that is not what you mean",
                    self.path.display(),
                    s.tensile_strength,
                    s.cohesion,
                    s.friction,
                ));
            }
        }
        out
    }

    /// A load's factors per step; a load the safety search raises (`own`)
    /// gets the ramp k / load_steps as its own when it has none, so that
    /// its load case is its own to raise.
    fn own_case(&self, factors: Option<&Vec<f64>>, own: bool) -> Option<Vec<f64>> {
        let n = self.solver.load_steps;
        factors.cloned().or_else(|| own.then(|| (1..=n).map(|k| k as f64 / n as f64).collect()))
    }

    /// The model's description: the bodies with their materials, contacts,
    /// supports and loads, each with the key path that defined it (for the
    /// model builder's messages).
    pub fn model_spec(&self) -> ModelSpec {
        let raise = self.safety.as_ref().and_then(|s| s.raise.as_ref());
        ModelSpec {
            mesh: self.mesh.path().display().to_string(),
            analysis: self.analysis,
            thickness: self.thickness,
            gravity: self.gravity,
            bodies: self.bodies.clone(),
            contacts: self
                .contacts
                .iter()
                .enumerate()
                .map(|(i, c)| ContactSpec {
                    key: self.contact_key(i),
                    groups: c.groups.clone(),
                    water: c.water.clone(),
                })
                .collect(),
            supports: self.supports.clone(),
            loads: (self.loads.iter().enumerate())
                .map(|(i, l)| LoadSpec {
                    factors: self.own_case(l.factors.as_ref(), raise.is_some_and(|r| r.loads.contains(&i))),
                    ..l.clone()
                })
                .collect(),
            load_steps: self.solver.load_steps,
            gravity_factors: self.own_case(self.solver.gravity_factors.as_ref(), raise.is_some_and(|r| r.gravity)),
            initial_stage: self.solver.initial_stage,
        }
    }
}
