//! The validated scene: what a scene TOML says once `raw.rs` has read it
//! and `validate.rs` has checked it, with defaults applied ([`Scene`]), and
//! its tables: contacts, `[solver]`, `[safety]`, `[gmsh]`, `[output]`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::analytic::Analytic;
use crate::contact::law::{Stiffness, Strength};
use crate::contact::{InterfaceSolver, SlipLaw, StateRule, TractionRecovery};
use crate::fem::Analysis;
use crate::mesh::joints::JointSpec;
use crate::model::water::JointWater;
use crate::model::{BodySpec, ContactGroups, LoadSpec, Material, SupportSpec};
use crate::recover::sections::SectionSpec;
use crate::recover::Probe;
pub use crate::results::about::{ColourScale, Output, Raise, Region, Safety, OUTPUT_FIELDS};

/// `[[contacts]]`: an interface and its strength.
#[derive(Debug, Clone, PartialEq)]
pub struct Contact {
    pub groups: ContactGroups,
    /// `friction`, `cohesion`, `tensile_strength` and `residual_cohesion`
    /// (each default 0; the residual cohesion at most the cohesion).
    pub strength: Strength,
    pub slip: SlipLaw,
    /// `normal_stiffness` and `shear_stiffness` (both or neither, > 0):
    /// a joint that deforms; None: rigid, the paper's.
    pub stiffness: Option<Stiffness>,
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
    /// Contact state iterations per step (default 100), >= 1; where
    /// rigid joints may fall back, 30 at most unless the step's states
    /// have all but settled (`crate::contact::cutting::SHORT_ITERATIONS`).
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
    /// Where rigid joints end a load step without converging, solve the
    /// scene again with joints that deform and say so (default true;
    /// `crate::driver`'s fallback).
    pub rigid_fallback: bool,
    /// Where rigid joints' Newton iteration does not end a load step,
    /// solve it again by augmented Lagrangian rounds through stiff
    /// springs, which end at the rigid joints' answer (default false;
    /// [`crate::contact`]'s `augmented`), before any fallback.
    pub augmented_lagrangian: bool,
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
            rigid_fallback: true,
            augmented_lagrangian: false,
        }
    }
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
