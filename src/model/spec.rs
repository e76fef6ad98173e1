//! What a model is built from ([`ModelSpec`]): the bodies with their
//! materials and initial stresses, the contact interfaces, supports and loads
//! by physical group, the load steps and the analysis. The scene file is one
//! way to write it (`Scene::model_spec`); the model builder knows only this.
//!
//! Messages about a group name the input the way its author wrote it:
//! every entry carries `key`, where the input defined it (`bodies[0]`,
//! `contacts[2]`). The builder appends the field it is about
//! (`bodies[0].group`, `contacts[2].groups[1]`); the driver puts the
//! input file's name in front.

use super::water::JointWater;
use crate::fem::Analysis;

/// The model's description, independent of the file format it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelSpec {
    /// The mesh file, for messages.
    pub mesh: String,
    pub analysis: Analysis,
    /// Out-of-plane thickness (plane analyses; 1 otherwise).
    pub thickness: f64,
    /// Acceleration of gravity; z = 0 in 2D.
    pub gravity: [f64; 3],
    pub bodies: Vec<BodySpec>,
    pub contacts: Vec<ContactSpec>,
    pub supports: Vec<SupportSpec>,
    pub loads: Vec<LoadSpec>,
    /// Number of load steps; load case 0 is the ramp k / load_steps.
    pub load_steps: usize,
    /// Gravity's factor at each load step; None: the ramp.
    pub gravity_factors: Option<Vec<f64>>,
    /// Run the initial equilibrium stage (a step 0 that holds the bodies'
    /// outer faces at their in-situ traction, `[solver] initial_stage`).
    pub initial_stage: bool,
}

/// One body: a physical surface (2D) or volume (3D) of one material.
#[derive(Debug, Clone, PartialEq)]
pub struct BodySpec {
    /// Where the input defined it, e.g. `bodies[0]`.
    pub key: String,
    pub group: String,
    pub material: Material,
    /// Stress carried before any load; None: stress-free.
    pub initial: Option<InitialStress>,
}

/// Linear isotropic elasticity and the mass a body weighs with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus (> 0).
    pub e: f64,
    /// Poisson's ratio (-1 < nu < 0.5).
    pub nu: f64,
    /// Mass density (with `gravity`; 0 for a weightless body).
    pub density: f64,
}

/// One contact interface, by its physical group(s).
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSpec {
    /// Where the input defined it, e.g. `contacts[0]`.
    pub key: String,
    pub groups: ContactGroups,
    /// The water in the joint, if any.
    pub water: Option<JointWater>,
}

/// Displacement conditions on a physical group.
#[derive(Debug, Clone, PartialEq)]
pub struct SupportSpec {
    /// Where the input defined it, e.g. `supports[0]`.
    pub key: String,
    pub group: String,
    /// Components (x, y, z) held at zero.
    pub fix: [bool; 3],
    /// Prescribed displacements (never together with `fix` on a component).
    pub prescribed: [Option<f64>; 3],
}

/// A surface load on a physical group.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadSpec {
    /// Where the input defined it, e.g. `loads[0]`.
    pub key: String,
    pub group: String,
    pub kind: LoadKind,
    /// Load factor at each load step; None: the ramp k / load_steps.
    pub factors: Option<Vec<f64>>,
}

/// The stress a body carries before any load (in-situ stress; `initial_stress
/// = [..]` or `k0` with `surface` in the scene).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InitialStress {
    /// A uniform stress `[xx, yy, zz, xy, yz, xz]` (tension positive).
    Uniform([f64; 6]),
    /// Geostatic: vertical stress `-density |g| depth` below the level
    /// `surface` (y in 2D, z in 3D), horizontal stresses `k0` times it.
    Geostatic { k0: f64, surface: f64 },
}

impl InitialStress {
    /// The stress at point x for a body of the given density under gravity g.
    pub fn at(&self, x: [f64; 3], analysis: Analysis, density: f64, gravity: [f64; 3]) -> [f64; 6] {
        match *self {
            InitialStress::Uniform(s) => s,
            InitialStress::Geostatic { k0, surface } => {
                let v = if analysis == Analysis::Solid { 2 } else { 1 };
                let depth = (surface - x[v]).max(0.0);
                let g = (gravity[0] * gravity[0] + gravity[1] * gravity[1] + gravity[2] * gravity[2]).sqrt();
                let sv = -density * g * depth;
                let mut s = [k0 * sv, k0 * sv, k0 * sv, 0.0, 0.0, 0.0];
                s[v] = sv;
                s
            }
        }
    }
}

/// Which physical groups make up a contact interface.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactGroups {
    /// `group = "A-A"`: one curve/surface shared by two bodies.
    Shared(String),
    /// `groups = ["face_1", "face_2"]`: two groups whose nodes coincide pairwise.
    Pair(String, String),
}

/// What a load applies.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadKind {
    /// Normal pressure, positive pressing into the body.
    Pressure(f64),
    /// Hydrostatic pressure `unit_weight * (surface - y)` below the level
    /// `surface` (y in 2D, z in 3D), zero above it.
    Hydrostatic { surface: f64, unit_weight: f64 },
    /// Traction vector (x, y, z), per unit area; z = 0 in 2D.
    Traction([f64; 3]),
    /// Westergaard's hydrodynamic pressure on a dam's upstream face under
    /// a horizontal seismic coefficient `kh` (a fraction of g), a pressure
    /// like the others: `7/8 kh unit_weight sqrt(H (surface - y))` below
    /// `surface` (y in 2D, z in 3D), H = surface - base the reservoir's
    /// depth (the depth below the surface taken at most H).
    Westergaard { kh: f64, surface: f64, base: f64, unit_weight: f64 },
    /// A pseudo-static seismic acceleration on every body with a density,
    /// as fractions of |g|: `kh` along the horizontal `direction`, `kv`
    /// upwards (against gravity). A body load: the entry names no group.
    Seismic { kh: f64, kv: f64, direction: [f64; 3] },
    /// A force and a moment at a point, spread over the group's nodes
    /// (a physical point), facets (a curve or surface) or cells (a body)
    /// so that they carry exactly that resultant (`model/forces.rs`).
    Force(ForceLoad),
    /// The in-situ traction `σ0(x) n` of a body's initial stress on its
    /// boundary (the initial equilibrium stage's hold load): `stress` of a
    /// body of `density` under `gravity`. The model makes it; no scene
    /// key names it.
    InSitu { stress: InitialStress, density: f64, gravity: [f64; 3] },
}

impl LoadKind {
    /// The pressure (positive into the body) at x of a pressure load, with
    /// `vertical` the height axis (1 in 2D, 2 in 3D); None for the others.
    pub fn pressure_at(&self, x: [f64; 3], vertical: usize) -> Option<f64> {
        match *self {
            LoadKind::Pressure(p) => Some(p),
            LoadKind::Hydrostatic { surface, unit_weight } => Some(unit_weight * (surface - x[vertical]).max(0.0)),
            LoadKind::Westergaard { kh, surface, base, unit_weight } => {
                let h = surface - base;
                let depth = (surface - x[vertical]).clamp(0.0, h.max(0.0));
                Some(0.875 * kh * unit_weight * (h * depth).sqrt())
            }
            LoadKind::Traction(_) | LoadKind::Seismic { .. } | LoadKind::Force(_) | LoadKind::InSitu { .. } => None,
        }
    }

    /// The traction on a facet at x whose outward unit normal is n: a
    /// pressure ([`LoadKind::pressure_at`], its level y in 2D, z in 3D)
    /// presses against n; a traction is itself; the in-situ traction is
    /// `σ0(x) n`; a seismic load (a body
    /// load) and a force (spread onto nodes when the model is built) are
    /// no facet traction: zero.
    pub fn traction(&self, x: [f64; 3], n: [f64; 3], analysis: Analysis) -> [f64; 3] {
        let vertical = if analysis == Analysis::Solid { 2 } else { 1 };
        match (self, self.pressure_at(x, vertical)) {
            (_, Some(p)) => [-p * n[0], -p * n[1], -p * n[2]],
            (LoadKind::Traction(t), None) => *t,
            (LoadKind::InSitu { stress, density, gravity }, None) => {
                stress_times(&stress.at(x, analysis, *density, *gravity), n)
            }
            (_, None) => [0.0; 3],
        }
    }
}

/// `σ n` for the stress `[xx, yy, zz, xy, yz, xz]`.
pub fn stress_times(s: &[f64; 6], n: [f64; 3]) -> [f64; 3] {
    [
        s[0] * n[0] + s[3] * n[1] + s[5] * n[2],
        s[3] * n[0] + s[1] * n[1] + s[4] * n[2],
        s[5] * n[0] + s[4] * n[1] + s[2] * n[2],
    ]
}

/// `force = [..]`, `moment = ..`, `point = [..]` of a load: the force and
/// the moment (about z in 2D) acting at `point` (default: the centroid of
/// what they are spread over), totals on the model (over `thickness` in
/// plane analyses).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceLoad {
    pub force: [f64; 3],
    pub moment: [f64; 3],
    pub point: Option<[f64; 3]>,
}
