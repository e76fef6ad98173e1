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
//! Here: the validated types and [`Scene::load`]. `raw.rs` is the TOML as
//! written (serde, unknown keys rejected), `errors.rs` the error type and the
//! mapping of toml's errors onto it, `validate.rs` (with `validate/`) the
//! checker that turns the raw scene into this one, key by key.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::mesh::joints::{CutJob, JointSpec};
use crate::model::{ContactSpec, ModelSpec};

mod errors;
mod raw;
#[cfg(test)]
mod tests;
mod validate;

pub use errors::SceneError;

pub use crate::analytic::Analytic;
pub use crate::contact::law::Strength;
pub use crate::contact::safety::{Reduce, Steps, Strengths};
pub use crate::contact::{InterfaceSolver, SlipLaw, StateRule, TractionRecovery};
pub use crate::fem::Analysis;
pub use crate::model::water::{Drain, JointWater, Levels, WaterFace, WaterPressure};
pub use crate::model::{BodySpec, ContactGroups, ForceLoad, InitialStress, LoadKind, LoadSpec, Material, SupportSpec};
pub use crate::recover::sections::{Cut, SectionSpec};
pub use crate::recover::Probe;

/// `[[contacts]]`: an interface and its strength.
#[derive(Debug, Clone, PartialEq)]
pub struct Contact {
    pub groups: ContactGroups,
    /// `friction`, `cohesion`, `tensile_strength` and `residual_cohesion`
    /// (each default 0; the residual cohesion at most the cohesion).
    pub strength: Strength,
    pub slip: SlipLaw,
    /// Whether the scene gives `residual_cohesion` (the safety search
    /// says when its default decided something).
    pub residual_given: bool,
    /// Contact stress recovery (default lumped).
    pub traction: TractionRecovery,
    /// The water in the joint (`water = {..}`), if any.
    pub water: Option<JointWater>,
}

/// `[solver]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Solver {
    /// Load increments (default 1), >= 1.
    pub load_steps: usize,
    /// Contact state iterations per step (default 100), >= 1.
    pub max_iterations: usize,
    /// Halvings of a load step that does not converge (default 3: down to
    /// an eighth of it), >= 0; 0 turns load-step cutting off.
    pub max_cuts: usize,
    /// How pair states are updated between iterations (default robust).
    pub rule: StateRule,
    /// Factor of the gravity load at each step (default the ramp k / load_steps).
    pub gravity_factors: Option<Vec<f64>>,
    /// Pieces each part is cut into (default 1: bodies stay whole), >= 1.
    pub substructures: usize,
    /// How the interface system is solved (default auto).
    pub interface: InterfaceSolver,
    /// Bring the bodies to equilibrium with their in-situ stress and their
    /// contacts active before the loads, displacements then reset (a
    /// step 0; default false).
    pub initial_stage: bool,
}

impl Default for Solver {
    fn default() -> Self {
        Solver {
            load_steps: 1,
            max_iterations: 100,
            max_cuts: 3,
            rule: StateRule::Robust,
            gravity_factors: None,
            substructures: 1,
            interface: InterfaceSolver::Auto,
            initial_stage: false,
        }
    }
}

/// `[safety]`: the factor of safety against sliding by strength reduction
/// after the load steps (`solve` runs it when the table is there; `subcontact
/// safety` runs it on any scene, with these defaults when it is not).
#[derive(Debug, Clone, PartialEq)]
pub struct Safety {
    /// What is divided by F (`reduce = [..]`, default all three).
    pub reduce: Reduce,
    /// The `[[contacts]]` entries reduced, as indices (`contacts = [group
    /// names]`, default all).
    pub contacts: Vec<usize>,
    /// Peak (default) or the scene's residual strengths during the search
    /// (`strength = "peak" | "residual"`).
    pub strengths: Strengths,
    /// Whether the scene chose `strength` (else the default decided).
    pub strength_given: bool,
    /// `load = [..]`: a load factor search, which raises these loads
    /// instead of dividing the strength (None: strength reduction).
    pub raise: Option<Raise>,
    /// `step` (default 0.1), `tolerance` (default 1e-3) and `max_factor`
    /// (default 10).
    pub steps: Steps,
}

impl Safety {
    /// The defaults on a scene of `contacts` contacts: all reduced.
    pub fn all(contacts: usize) -> Safety {
        Safety {
            reduce: Reduce::ALL,
            contacts: (0..contacts).collect(),
            strengths: Strengths::Peak,
            strength_given: false,
            raise: None,
            steps: Steps { step: 0.1, tolerance: 1e-3, max_factor: 10.0 },
        }
    }
}

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

/// The loads a load factor search raises (`[safety] load = [..]`): the
/// `[[loads]]` entries (indices) and gravity.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Raise {
    pub loads: Vec<usize>,
    pub gravity: bool,
}

/// `[gmsh]`: options for meshing a `.geo` with the gmsh CLI.
#[derive(Debug, Clone, PartialEq)]
pub struct GmshOptions {
    /// Element order, 1 or 2 (default 1): `gmsh -order`.
    pub order: usize,
    /// `gmsh -setnumber NAME VALUE`, sorted by name.
    pub setnumber: Vec<(String, f64)>,
    /// `gmsh -clscale`, > 0.
    pub clscale: Option<f64>,
    /// gmsh's time limit in seconds (default 600).
    pub timeout: f64,
    /// With joints: mesh the blocks structured where gmsh can (default false).
    pub structured: bool,
}

impl Default for GmshOptions {
    fn default() -> Self {
        GmshOptions { order: 1, setnumber: Vec::new(), clscale: None, timeout: 600.0, structured: false }
    }
}

/// Where the mesh comes from; the path is already resolved against the
/// scene file's directory (an absolute `mesh` stays as written).
#[derive(Debug, Clone, PartialEq)]
pub enum MeshSource {
    /// A gmsh script, meshed by the gmsh CLI.
    Geo(PathBuf),
    /// A ready mesh (MSH 4.1).
    Msh(PathBuf),
}

impl MeshSource {
    pub fn path(&self) -> &Path {
        match self {
            MeshSource::Geo(p) | MeshSource::Msh(p) => p,
        }
    }
}

/// The fields `[output] fields` accepts (and its default: all of them).
pub const OUTPUT_FIELDS: &[&str] = &["displacement", "stress"];

/// What the deformed picture frames instead of the contacts
/// (`[output] frame` in the scene).
#[derive(Clone, Debug, PartialEq)]
pub enum Region {
    /// The cells whose centre lies in the box `from`..`to` (z is ignored in
    /// 2D).
    Box { from: [f64; 3], to: [f64; 3] },
    /// The named bodies (their groups) and the cells around them, within a
    /// quarter of their size.
    Bodies(Vec<String>),
}

/// `[output]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// Body fields to compute and write, each one of [`OUTPUT_FIELDS`].
    pub fields: Vec<String>,
    /// What the deformed picture frames (`frame = { from, to }` or
    /// `frame = { bodies }`); None: the contacts, when they are a small part
    /// of the model.
    pub frame: Option<Region>,
    /// The width over which the design bearing pressure is averaged
    /// (`pressure_window`, > 0); None: a tenth of each face's width.
    pub pressure_window: Option<f64>,
    /// The deformed picture's colour scales (`colour_scale`).
    pub colour_scale: ColourScale,
}

/// `[output] colour_scale`: a scale per body whose stresses lie far from the
/// others' (`per_body`, the default: the blocks of one body always share
/// one), or one for the whole model (`one`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ColourScale {
    #[default]
    PerBody,
    One,
}

impl Output {
    /// Whether `field` (e.g. `"stress"`) was asked for.
    pub fn wants(&self, field: &str) -> bool {
        self.fields.iter().any(|f| f == field)
    }
}

impl Default for Output {
    fn default() -> Self {
        Output {
            fields: OUTPUT_FIELDS.iter().map(|s| s.to_string()).collect(),
            frame: None,
            pressure_window: None,
            colour_scale: ColourScale::PerBody,
        }
    }
}

/// A parsed and validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The scene file as given to [`Scene::load`] / [`Scene::parse`].
    pub path: PathBuf,
    /// File stem of `path` (names the results directory).
    pub name: String,
    /// `title`, default `name`.
    pub title: String,
    pub mesh: MeshSource,
    pub analysis: Analysis,
    /// Out-of-plane thickness (plane analyses; default 1.0, and 1.0 otherwise).
    pub thickness: f64,
    /// Acceleration of gravity (default 0); z = 0 in 2D.
    pub gravity: [f64; 3],
    pub gmsh: GmshOptions,
    pub materials: BTreeMap<String, Material>,
    /// `[[bodies]]`, each with its material (`material = NAME` looked up).
    pub bodies: Vec<BodySpec>,
    pub contacts: Vec<Contact>,
    /// `[[supports]]`: the components held (`fix = [..]`) and prescribed
    /// (`ux`, `uy`, `uz`; never both on one component).
    pub supports: Vec<SupportSpec>,
    /// `[[loads]]`: a surface load on a physical group, a force and moment
    /// on a point, a boundary group or a body, or a seismic body load (no
    /// group); `factors = [..]` (None: the ramp k / load_steps).
    pub loads: Vec<LoadSpec>,
    pub solver: Solver,
    pub probes: Vec<Probe>,
    pub analytic: Option<Analytic>,
    pub output: Output,
    /// Every contact bonded on purpose (`solve --bonded`): `contacts` is
    /// empty and the bodies that shared them move as one, which no warning
    /// need point out.
    pub bonded: bool,
    /// The safety search after the load steps, when asked for.
    pub safety: Option<Safety>,
    /// `[[joint_sets]]` then `[[joints]]`: what cuts the bodies of the
    /// .geo. Each is also the last entries of `contacts`, in this order.
    pub joints: Vec<JointSpec>,
    /// The most blocks the joints may make (`max_blocks`, default 1000).
    pub max_blocks: usize,
    /// Bond each sliver block the joints cut to a neighbour (`merge_slivers`).
    pub merge_slivers: bool,
    /// Where section forces are reported (`[[sections]]`).
    pub sections: Vec<SectionSpec>,
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

    /// Bonds every contact ([`Scene::bonded`]): the bodies keep the nodes
    /// they share, and the run is the monolithic solve (with nothing to
    /// reduce in a safety search).
    pub fn bond_all(&mut self) {
        self.contacts.clear();
        self.bonded = true;
        self.safety = None;
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
