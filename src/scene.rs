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
//! Validated values are stored in the public types below with defaults
//! applied; vectors are always 3 components (z = 0 for the 2D analyses).

use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::{Path, PathBuf};

use crate::model::{BodySpec, ContactSpec, LoadSpec, ModelSpec, SupportSpec};

pub use crate::analytic::Analytic;
pub use crate::contact::{SlipLaw, StateRule, TractionRecovery};
pub use crate::fem::Analysis;
pub use crate::model::{ContactGroups, InitialStress, LoadKind};
pub use crate::recover::Probe;

/// `[materials.NAME]`: linear isotropic elasticity.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Young's modulus (key `E`), > 0.
    pub e: f64,
    /// Poisson's ratio, -1 < nu < 0.5.
    pub nu: f64,
    /// Mass density (default 0), used with the top-level `gravity`.
    pub density: f64,
}

/// `[[bodies]]`: one substructure, a physical surface (2D) or volume (3D).
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    pub group: String,
    /// A key of [`Scene::materials`] (checked).
    pub material: String,
    /// Stress the body carries before any load (in-situ stress); reported
    /// stresses are totals. None: the body starts stress-free.
    pub initial: Option<InitialStress>,
}

/// `[[contacts]]`: an interface and its strength.
#[derive(Debug, Clone, PartialEq)]
pub struct Contact {
    pub groups: ContactGroups,
    /// Friction coefficient f (default 0).
    pub friction: f64,
    /// Cohesion c (default 0).
    pub cohesion: f64,
    /// Tensile strength f_t (default 0).
    pub tensile_strength: f64,
    pub slip: SlipLaw,
    /// Cohesion kept once the pair has opened (default 0, <= cohesion).
    pub residual_cohesion: f64,
    /// Contact stress recovery (default lumped).
    pub traction: TractionRecovery,
}

/// `[[supports]]`: displacement conditions on a physical group.
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    pub group: String,
    /// Components (x, y, z) held at zero (`fix = ["x", "y"]`).
    pub fix: [bool; 3],
    /// Prescribed displacements (`ux`, `uy`, `uz`). A component is never both
    /// in `fix` and prescribed (that is rejected).
    pub prescribed: [Option<f64>; 3],
}

/// `[[loads]]`: a surface load on a physical group.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    pub group: String,
    pub kind: LoadKind,
    /// Load factor at each load step (`factors = [..]`, one per step);
    /// None: the ramp k / load_steps.
    pub factors: Option<Vec<f64>>,
}

/// `[solver]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Solver {
    /// Load increments (default 1), >= 1.
    pub load_steps: usize,
    /// Contact state iterations per step (default 100), >= 1.
    pub max_iterations: usize,
    /// How pair states are updated between iterations (default robust).
    pub rule: StateRule,
    /// Factor of the gravity load at each step (default the ramp k / load_steps).
    pub gravity_factors: Option<Vec<f64>>,
}

impl Default for Solver {
    fn default() -> Self {
        Solver {
            load_steps: 1,
            max_iterations: 100,
            rule: StateRule::Robust,
            gravity_factors: None,
        }
    }
}

/// The `kind` values `[analytic]` accepts.
const ANALYTIC_KINDS: &[&str] = &["lame_cylinder", "lined_tunnel"];

/// `[gmsh]`: options for meshing a `.geo` with the gmsh CLI.
#[derive(Debug, Clone, PartialEq)]
pub struct GmshOptions {
    /// Element order, 1 or 2 (default 1): `gmsh -order`.
    pub order: usize,
    /// `gmsh -setnumber NAME VALUE`, sorted by name.
    pub setnumber: Vec<(String, f64)>,
    /// `gmsh -clscale`, > 0.
    pub clscale: Option<f64>,
}

impl Default for GmshOptions {
    fn default() -> Self {
        GmshOptions {
            order: 1,
            setnumber: Vec::new(),
            clscale: None,
        }
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

/// `[output]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// Body fields to compute and write, each one of [`OUTPUT_FIELDS`].
    pub fields: Vec<String>,
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
    pub bodies: Vec<Body>,
    pub contacts: Vec<Contact>,
    pub supports: Vec<Support>,
    pub loads: Vec<Load>,
    pub solver: Solver,
    pub probes: Vec<Probe>,
    pub analytic: Option<Analytic>,
    pub output: Output,
}

/// Why a scene could not be used. `Display` is one paragraph that starts with
/// the scene file's path.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{}: cannot read the scene file: {source}. Check the path and that the file is readable.", path.display())]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// TOML syntax, an unknown key, or a value of the wrong type.
    #[error("{}, line {line}, column {column}{}: {message}", path.display(), table.as_ref().map(|t| format!(" (in {t})")).unwrap_or_default())]
    Toml {
        path: PathBuf,
        line: usize,
        column: usize,
        /// The table the error is in, as a key path (`contacts[1]`), if any.
        table: Option<String>,
        message: String,
    },
    /// A value that parses but is not acceptable.
    #[error("{}: {key}{}: {message}", path.display(), value.as_ref().map(|v| format!(" = {v}")).unwrap_or_default())]
    Invalid {
        path: PathBuf,
        /// Key path, e.g. `materials.rock.nu`.
        key: String,
        /// The offending value as written in TOML, when there is one.
        value: Option<String>,
        /// What is wrong and what to do.
        message: String,
    },
}

impl SceneError {
    /// The key path the error is about, when known.
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::Read { .. } => None,
            SceneError::Toml { table, .. } => table.as_deref(),
            SceneError::Invalid { key, .. } => Some(key),
        }
    }
}

impl Scene {
    /// Read, parse and validate the scene file at `path`.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Scene::parse(&text, path)
    }

    /// Parse and validate scene text. `path` is used in messages, for the
    /// scene name, and to resolve `mesh` (which must exist).
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let raw: RawScene = toml::from_str(text).map_err(|e| toml_error(text, path, &e))?;
        Checker { path }.scene(raw)
    }

    /// The material of `body`. Panics only if `body` was not validated
    /// against this scene (validation guarantees the material exists).
    pub fn material_of(&self, body: &Body) -> &Material {
        &self.materials[&body.material]
    }

    /// The model's description: the bodies with their materials, contacts,
    /// supports and loads, each with the key path that defined it (for the
    /// model builder's messages).
    pub fn model_spec(&self) -> ModelSpec {
        ModelSpec {
            source: self.path.display().to_string(),
            mesh: self.mesh.path().display().to_string(),
            analysis: self.analysis,
            thickness: self.thickness,
            gravity: self.gravity,
            bodies: self
                .bodies
                .iter()
                .enumerate()
                .map(|(i, b)| {
                    let m = self.material_of(b);
                    BodySpec { key: format!("bodies[{i}]"), group: b.group.clone(), e: m.e, nu: m.nu, density: m.density, initial: b.initial }
                })
                .collect(),
            contacts: self.contacts.iter().enumerate().map(|(i, c)| ContactSpec { key: format!("contacts[{i}]"), groups: c.groups.clone() }).collect(),
            supports: self
                .supports
                .iter()
                .enumerate()
                .map(|(i, s)| SupportSpec { key: format!("supports[{i}]"), group: s.group.clone(), fix: s.fix, prescribed: s.prescribed })
                .collect(),
            loads: self
                .loads
                .iter()
                .enumerate()
                .map(|(i, l)| LoadSpec { key: format!("loads[{i}]"), group: l.group.clone(), kind: l.kind.clone(), factors: l.factors.clone() })
                .collect(),
            load_steps: self.solver.load_steps,
            gravity_factors: self.solver.gravity_factors.clone(),
        }
    }
}

// ---------------------------------------------------------------------------
// Raw (as written) structures. Every field is optional so that missing keys
// are reported by the checker with their full key path.

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    title: Option<String>,
    mesh: Option<String>,
    analysis: Option<Analysis>,
    thickness: Option<f64>,
    gravity: Option<Vec<f64>>,
    gmsh: Option<RawGmsh>,
    #[serde(default)]
    materials: BTreeMap<String, RawMaterial>,
    #[serde(default)]
    bodies: Vec<RawBody>,
    #[serde(default)]
    contacts: Vec<RawContact>,
    #[serde(default)]
    supports: Vec<RawSupport>,
    #[serde(default)]
    loads: Vec<RawLoad>,
    solver: Option<RawSolver>,
    #[serde(default)]
    probes: Vec<RawProbe>,
    analytic: Option<RawAnalytic>,
    output: Option<RawOutput>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGmsh {
    order: Option<i64>,
    setnumber: Option<BTreeMap<String, f64>>,
    clscale: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    #[serde(rename = "E")]
    e: Option<f64>,
    nu: Option<f64>,
    density: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    group: Option<String>,
    material: Option<String>,
    initial_stress: Option<Vec<f64>>,
    k0: Option<f64>,
    surface: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    group: Option<String>,
    groups: Option<Vec<String>>,
    friction: Option<f64>,
    cohesion: Option<f64>,
    tensile_strength: Option<f64>,
    slip: Option<SlipLaw>,
    residual_cohesion: Option<f64>,
    traction: Option<TractionRecovery>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSupport {
    group: Option<String>,
    fix: Option<Vec<String>>,
    ux: Option<f64>,
    uy: Option<f64>,
    uz: Option<f64>,
}

/// `pressure = P` or `pressure = { surface = y0, unit_weight = gamma }`.
#[derive(Deserialize)]
#[serde(untagged)]
enum RawPressure {
    Value(f64),
    Hydrostatic(RawHydrostatic),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHydrostatic {
    surface: f64,
    unit_weight: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoad {
    group: Option<String>,
    pressure: Option<RawPressure>,
    traction: Option<Vec<f64>>,
    factors: Option<Vec<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSolver {
    load_steps: Option<i64>,
    max_iterations: Option<i64>,
    rule: Option<StateRule>,
    gravity_factors: Option<Vec<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawProbe {
    name: Option<String>,
    from: Option<Vec<f64>>,
    to: Option<Vec<f64>>,
    points: Option<i64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAnalytic {
    kind: Option<String>,
    a: Option<f64>,
    b: Option<f64>,
    p: Option<f64>,
    radius: Option<f64>,
    thickness: Option<f64>,
    k: Option<f64>,
    slip: Option<String>,
    lining: Option<String>,
    ground: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOutput {
    fields: Option<Vec<String>>,
}

// ---------------------------------------------------------------------------
// TOML errors.

/// Turn a toml error into one paragraph with line, column, the enclosing
/// table and a hint on what to do.
fn toml_error(text: &str, path: &Path, e: &toml::de::Error) -> SceneError {
    let offset = e.span().map(|s| s.start).unwrap_or(0).min(text.len());
    let before = text.get(..offset).unwrap_or("");
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map(|i| i + 1).unwrap_or(0);
    let column = before[line_start..].chars().count() + 1;
    let line_text = text[line_start..].lines().next().unwrap_or("").trim();

    let msg = e.message().trim().replace('\n', "; ");
    let hint = if msg.starts_with("unknown field") {
        "Unknown keys are errors, not ignored: correct the spelling to one of the expected keys, or remove the line."
    } else if msg.starts_with("unknown variant") {
        "Use one of the listed values."
    } else if msg.starts_with("invalid type") {
        "Give the value the type shown (numbers unquoted, names in quotes, lists in [ ])."
    } else {
        "Fix the TOML syntax at that position."
    };
    let shown = if !line_text.is_empty() && line_text.chars().count() <= 80 {
        format!("`{line_text}`: ")
    } else {
        String::new()
    };
    SceneError::Toml {
        path: path.to_path_buf(),
        line,
        column,
        table: enclosing_table(text, line_start),
        message: format!("{shown}{msg}. {hint}"),
    }
}

/// The key path of the `[table]` or `[[array]]` header that governs the line
/// starting at `line_start` (`contacts[1]`, `materials.rock`), if any.
fn enclosing_table(text: &str, line_start: usize) -> Option<String> {
    let upto = text.get(
        ..line_start
            + text[line_start..]
                .find('\n')
                .unwrap_or(text.len() - line_start),
    )?;
    let mut current: Option<String> = None;
    let mut counts: BTreeMap<String, usize> = BTreeMap::new();
    for l in upto.lines() {
        let l = l.split('#').next().unwrap_or("").trim();
        let (name, array) =
            if let Some(inner) = l.strip_prefix("[[").and_then(|s| s.strip_suffix("]]")) {
                (inner.trim(), true)
            } else if let Some(inner) = l.strip_prefix('[').and_then(|s| s.strip_suffix(']')) {
                (inner.trim(), false)
            } else {
                continue;
            };
        // Skip continuation lines of multi-line arrays like `[1.0, 2.0]`.
        let first = name.chars().next();
        if !matches!(first, Some(c) if c.is_ascii_alphabetic() || c == '_' || c == '"' || c == '\'')
        {
            continue;
        }
        let name: String = name
            .split('.')
            .map(|p| p.trim())
            .collect::<Vec<_>>()
            .join(".");
        current = Some(if array {
            let n = counts.entry(name.clone()).or_insert(0);
            *n += 1;
            format!("{name}[{}]", *n - 1)
        } else {
            name
        });
    }
    current
}

// ---------------------------------------------------------------------------
// Validation.

/// `name` as it would appear in a key path: bare when it is a bare TOML key,
/// quoted otherwise.
fn key_name(name: &str) -> String {
    if !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        name.to_string()
    } else {
        format!("{name:?}")
    }
}

/// A list of names for messages: `"a", "b"`.
fn quoted_list<S: AsRef<str>>(items: impl IntoIterator<Item = S>) -> String {
    items
        .into_iter()
        .map(|s| format!("\"{}\"", s.as_ref()))
        .collect::<Vec<_>>()
        .join(", ")
}

fn fmt_vec(v: &[f64]) -> String {
    format!(
        "[{}]",
        v.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    )
}

struct Checker<'a> {
    path: &'a Path,
}

type R<T> = Result<T, SceneError>;

impl Checker<'_> {
    /// An error about `key` whose value is `value` (already formatted).
    fn bad(
        &self,
        key: impl Into<String>,
        value: impl fmt::Display,
        what: impl fmt::Display,
    ) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_path_buf(),
            key: key.into(),
            value: Some(value.to_string()),
            message: what.to_string(),
        }
    }

    /// An error about `key` without a value (missing, or about a whole table).
    fn err(&self, key: impl Into<String>, what: impl fmt::Display) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_path_buf(),
            key: key.into(),
            value: None,
            message: what.to_string(),
        }
    }

    fn required<T>(&self, v: Option<T>, key: &str, what: &str) -> R<T> {
        v.ok_or_else(|| {
            self.err(
                key,
                format!(
                    "missing; add `{}` ({what}).",
                    key.rsplit('.').next().unwrap_or(key)
                ),
            )
        })
    }

    fn group(&self, v: Option<String>, key: &str, what: &str) -> R<String> {
        let g = self.required(v, key, what)?;
        if g.trim().is_empty() {
            return Err(self.bad(
                key,
                "\"\"",
                format!("the group name is empty; give the name of {what} as written in the .geo."),
            ));
        }
        Ok(g)
    }

    fn finite(&self, v: f64, key: &str) -> R<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.bad(key, v, "must be a finite number."))
        }
    }

    fn non_negative(&self, v: Option<f64>, key: &str, what: &str) -> R<f64> {
        let v = self.finite(v.unwrap_or(0.0), key)?;
        if v < 0.0 {
            return Err(self.bad(key, v, format!("{what} must be >= 0 (0 if omitted).")));
        }
        Ok(v)
    }

    fn at_least(
        &self,
        v: Option<i64>,
        default: usize,
        min: i64,
        key: &str,
        what: &str,
    ) -> R<usize> {
        match v {
            None => Ok(default),
            Some(n) if n >= min => {
                usize::try_from(n).map_err(|_| self.bad(key, n, format!("{what} is too large.")))
            }
            Some(n) => Err(self.bad(key, n, format!("{what} must be at least {min}."))),
        }
    }

    /// A 2- or 3-component vector; 3 required for solid, z = 0 for the 2D analyses.
    fn vec3(&self, v: &[f64], key: &str, analysis: Analysis) -> R<[f64; 3]> {
        let shown = fmt_vec(v);
        if analysis == Analysis::Solid && v.len() != 3 {
            return Err(self.bad(key, shown, "a solid analysis needs 3 components [x, y, z]."));
        }
        if v.len() != 2 && v.len() != 3 {
            return Err(self.bad(
                key,
                shown,
                format!("give 2 components [x, y] (or 3 with z = 0) for a {analysis} analysis."),
            ));
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(self.bad(key, shown, "all components must be finite numbers."));
        }
        let z = v.get(2).copied().unwrap_or(0.0);
        if analysis.dim() == 2 && z != 0.0 {
            return Err(self.bad(
                key,
                shown,
                format!("a {analysis} analysis lies in the z = 0 plane, so the z component must be 0; drop it or use analysis = \"solid\"."),
            ));
        }
        Ok([v[0], v[1], z])
    }

    fn scene(&self, raw: RawScene) -> R<Scene> {
        let name = self
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "scene".to_string());
        let title = raw.title.unwrap_or_else(|| name.clone());

        let analysis = self.required(
            raw.analysis,
            "analysis",
            "one of \"plane_strain\", \"plane_stress\", \"axisymmetric\", \"solid\"",
        )?;
        let mesh = self.mesh(raw.mesh)?;

        let thickness = match raw.thickness {
            None => 1.0,
            Some(t) if !analysis.has_thickness() => {
                return Err(self.bad(
                    "thickness",
                    t,
                    format!("thickness applies only to plane_strain and plane_stress; remove it for a {analysis} analysis."),
                ))
            }
            Some(t) if t.is_finite() && t > 0.0 => t,
            Some(t) => return Err(self.bad("thickness", t, "the out-of-plane thickness must be a finite number > 0.")),
        };
        let gravity = match &raw.gravity {
            None => [0.0; 3],
            Some(g) => self.vec3(g, "gravity", analysis)?,
        };

        let gmsh = self.gmsh(raw.gmsh, &mesh)?;
        let materials = self.materials(raw.materials)?;
        let bodies = self.bodies(raw.bodies, &materials, analysis)?;
        let contacts = self.contacts(raw.contacts, &bodies)?;
        let supports = raw
            .supports
            .into_iter()
            .enumerate()
            .map(|(i, s)| self.support(i, s, analysis))
            .collect::<R<Vec<_>>>()?;
        let loads = raw
            .loads
            .into_iter()
            .enumerate()
            .map(|(i, l)| self.load(i, l, analysis))
            .collect::<R<Vec<_>>>()?;
        let solver = match raw.solver {
            None => Solver::default(),
            Some(s) => Solver {
                load_steps: self.at_least(
                    s.load_steps,
                    1,
                    1,
                    "solver.load_steps",
                    "the number of load steps",
                )?,
                max_iterations: self.at_least(
                    s.max_iterations,
                    100,
                    1,
                    "solver.max_iterations",
                    "the contact iteration limit",
                )?,
                rule: s.rule.unwrap_or_default(),
                gravity_factors: match s.gravity_factors {
                    None => None,
                    Some(f) => Some(
                        f.iter()
                            .enumerate()
                            .map(|(j, &v)| self.finite(v, &format!("solver.gravity_factors[{j}]")))
                            .collect::<R<Vec<f64>>>()?,
                    ),
                },
            },
        };
        // load factor tables have one entry per load step
        let steps = solver.load_steps;
        let tables = loads
            .iter()
            .enumerate()
            .filter_map(|(i, l)| l.factors.as_ref().map(|f| (format!("loads[{i}].factors"), f)))
            .chain(solver.gravity_factors.as_ref().map(|f| ("solver.gravity_factors".to_string(), f)));
        for (key, f) in tables {
            if f.len() != steps {
                return Err(self.err(
                    key,
                    format!("has {} value(s) but [solver] load_steps = {steps}: give one load factor per step.", f.len()),
                ));
            }
        }
        let probes = self.probes(raw.probes, analysis)?;
        let analytic = raw.analytic.map(|a| self.analytic(a, analysis, &bodies, &materials)).transpose()?;
        let output = self.output(raw.output)?;

        Ok(Scene {
            path: self.path.to_path_buf(),
            name,
            title,
            mesh,
            analysis,
            thickness,
            gravity,
            gmsh,
            materials,
            bodies,
            contacts,
            supports,
            loads,
            solver,
            probes,
            analytic,
            output,
        })
    }

    fn mesh(&self, mesh: Option<String>) -> R<MeshSource> {
        let m = self.required(
            mesh,
            "mesh",
            "the .geo or .msh file, relative to the scene file",
        )?;
        let rel = Path::new(&m);
        let ext = rel
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let dir = self.path.parent().unwrap_or(Path::new(""));
        let full = dir.join(rel);
        let source = match ext.as_deref() {
            Some("geo") => MeshSource::Geo(full.clone()),
            Some("msh") => MeshSource::Msh(full.clone()),
            _ => {
                return Err(self.bad(
                    "mesh",
                    format!("{m:?}"),
                    "the mesh must be a gmsh script ending in .geo (meshed with the gmsh CLI) or a mesh file ending in .msh.",
                ))
            }
        };
        if !full.is_file() {
            let shown_dir = if dir.as_os_str().is_empty() {
                Path::new(".")
            } else {
                dir
            };
            return Err(self.bad(
                "mesh",
                format!("{m:?}"),
                format!(
                    "the file {} does not exist (mesh paths are relative to the scene file's directory {}); create it or correct the path.",
                    full.display(),
                    shown_dir.display()
                ),
            ));
        }
        Ok(source)
    }

    fn gmsh(&self, raw: Option<RawGmsh>, mesh: &MeshSource) -> R<GmshOptions> {
        let Some(g) = raw else {
            return Ok(GmshOptions::default());
        };
        if let MeshSource::Msh(p) = mesh {
            return Err(self.err(
                "gmsh",
                format!(
                    "[gmsh] options apply only when mesh is a .geo, but mesh is the ready mesh {}; remove [gmsh] or point mesh at the .geo.",
                    p.display()
                ),
            ));
        }
        let order = match g.order {
            None => 1,
            Some(o @ (1 | 2)) => o as usize,
            Some(o) => {
                return Err(self.bad(
                    "gmsh.order",
                    o,
                    "the element order must be 1 (linear) or 2 (quadratic).",
                ))
            }
        };
        let mut setnumber = Vec::new();
        for (name, v) in g.setnumber.unwrap_or_default() {
            let key = format!("gmsh.setnumber.{}", key_name(&name));
            let ident = name
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                && name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.');
            if !ident {
                return Err(self.err(
                    key,
                    "not a gmsh parameter name; use the name of a DefineConstant in the .geo (letters, digits, _ and .).",
                ));
            }
            setnumber.push((name, self.finite(v, &key)?));
        }
        let clscale = match g.clscale {
            None => None,
            Some(c) if c.is_finite() && c > 0.0 => Some(c),
            Some(c) => {
                return Err(self.bad(
                    "gmsh.clscale",
                    c,
                    "the mesh size factor must be a finite number > 0.",
                ))
            }
        };
        Ok(GmshOptions {
            order,
            setnumber,
            clscale,
        })
    }

    fn materials(&self, raw: BTreeMap<String, RawMaterial>) -> R<BTreeMap<String, Material>> {
        let mut out = BTreeMap::new();
        for (name, m) in raw {
            let k = format!("materials.{}", key_name(&name));
            let e = self.required(m.e, &format!("{k}.E"), "Young's modulus, > 0")?;
            if !(e.is_finite() && e > 0.0) {
                return Err(self.bad(
                    format!("{k}.E"),
                    e,
                    "Young's modulus must be a finite number > 0.",
                ));
            }
            let nu = self.required(m.nu, &format!("{k}.nu"), "Poisson's ratio, -1 < nu < 0.5")?;
            if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
                let why = if nu >= 0.5 && nu.is_finite() {
                    " nu = 0.5 is incompressible, which this displacement formulation does not support; use 0.499 for a nearly incompressible material."
                } else {
                    ""
                };
                return Err(self.bad(
                    format!("{k}.nu"),
                    nu,
                    format!("Poisson's ratio must satisfy -1 < nu < 0.5.{why}"),
                ));
            }
            let density = self.non_negative(m.density, &format!("{k}.density"), "the density")?;
            out.insert(name, Material { e, nu, density });
        }
        Ok(out)
    }

    fn bodies(&self, raw: Vec<RawBody>, materials: &BTreeMap<String, Material>, analysis: Analysis) -> R<Vec<Body>> {
        if raw.is_empty() {
            return Err(self.err(
                "bodies",
                "no [[bodies]] given; add at least one [[bodies]] entry with group = \"<physical surface or volume>\" and material = \"<a name from [materials]>\".",
            ));
        }
        let mut seen: BTreeMap<String, usize> = BTreeMap::new();
        let mut out = Vec::new();
        for (i, b) in raw.into_iter().enumerate() {
            let k = format!("bodies[{i}]");
            let group = self.group(
                b.group,
                &format!("{k}.group"),
                "the body's physical surface (2D) or volume (3D)",
            )?;
            let material = self.required(
                b.material,
                &format!("{k}.material"),
                "a material name from [materials]",
            )?;
            if !materials.contains_key(&material) {
                let defined = if materials.is_empty() {
                    "none are defined; add a [materials.NAME] table with E and nu".to_string()
                } else {
                    format!("the defined ones are {}", quoted_list(materials.keys()))
                };
                return Err(self.bad(
                    format!("{k}.material"),
                    format!("{material:?}"),
                    format!("no such material in [materials]; {defined}."),
                ));
            }
            if let Some(j) = seen.insert(group.clone(), i) {
                return Err(self.bad(
                    format!("{k}.group"),
                    format!("{group:?}"),
                    format!("the group is already bodies[{j}]; each physical group is one body, so list it once."),
                ));
            }
            let initial = match (b.initial_stress, b.k0, b.surface) {
                (None, None, None) => None,
                (Some(v), None, None) => {
                    let want = if analysis == Analysis::Solid { 6 } else { 4 };
                    if v.len() != want {
                        return Err(self.bad(
                            format!("{k}.initial_stress"),
                            format!("{v:?}"),
                            format!("give {want} components: {}.", if want == 6 { "[sxx, syy, szz, sxy, syz, sxz]" } else { "[sxx, syy, szz, sxy]" }),
                        ));
                    }
                    let mut s6 = [0.0; 6];
                    for (j, x) in v.iter().enumerate() {
                        s6[j] = self.finite(*x, &format!("{k}.initial_stress[{j}]"))?;
                    }
                    Some(InitialStress::Uniform(s6))
                }
                (None, Some(k0), Some(surface)) => {
                    let k0 = self.finite(k0, &format!("{k}.k0"))?;
                    if k0 < 0.0 {
                        return Err(self.bad(format!("{k}.k0"), k0, "the earth pressure coefficient must be >= 0."));
                    }
                    Some(InitialStress::Geostatic { k0, surface: self.finite(surface, &format!("{k}.surface"))? })
                }
                (None, _, _) => {
                    return Err(self.err(
                        k,
                        "a geostatic initial stress needs both k0 (horizontal / vertical stress) and surface (the ground level: y in 2D, z in 3D).",
                    ))
                }
                (Some(_), _, _) => {
                    return Err(self.err(k, "give either initial_stress = [..] or k0 with surface, not both."));
                }
            };
            out.push(Body { group, material, initial });
        }
        Ok(out)
    }

    fn contacts(&self, raw: Vec<RawContact>, bodies: &[Body]) -> R<Vec<Contact>> {
        let mut seen: BTreeMap<Vec<String>, usize> = BTreeMap::new();
        let mut out = Vec::new();
        for (i, c) in raw.into_iter().enumerate() {
            let k = format!("contacts[{i}]");
            let groups = match (c.group, c.groups) {
                (Some(_), Some(_)) => {
                    return Err(self.err(
                        &k,
                        "both group and groups are given; use group = \"NAME\" for one curve/surface shared by two bodies, or groups = [\"a\", \"b\"] for two groups whose nodes coincide, not both.",
                    ))
                }
                (None, None) => {
                    return Err(self.err(
                        &k,
                        "no interface given; add group = \"NAME\" (one curve/surface shared by two bodies) or groups = [\"a\", \"b\"] (two groups whose nodes coincide pairwise).",
                    ))
                }
                (Some(g), None) => ContactGroups::Shared(self.group(Some(g), &format!("{k}.group"), "the interface curve/surface")?),
                (None, Some(gs)) => {
                    let key = format!("{k}.groups");
                    let shown = format!("[{}]", quoted_list(&gs));
                    let n = gs.len();
                    let Ok([a, b]) = <[String; 2]>::try_from(gs) else {
                        return Err(self.bad(key, shown, format!("give exactly 2 groups (one face on each body), not {n}.")));
                    };
                    if a.trim().is_empty() || b.trim().is_empty() {
                        return Err(self.bad(key, shown, "a group name is empty."));
                    }
                    if a == b {
                        return Err(self.bad(
                            key,
                            shown,
                            format!("the two groups must differ; for one group shared by both bodies write group = {a:?}."),
                        ));
                    }
                    ContactGroups::Pair(a, b)
                }
            };
            let names: Vec<String> = match &groups {
                ContactGroups::Shared(g) => vec![g.clone()],
                ContactGroups::Pair(a, b) => vec![a.clone(), b.clone()],
            };
            let gkey = match &groups {
                ContactGroups::Shared(_) => format!("{k}.group"),
                ContactGroups::Pair(..) => format!("{k}.groups"),
            };
            for n in &names {
                if let Some(j) = bodies.iter().position(|b| &b.group == n) {
                    return Err(self.bad(
                        &gkey,
                        format!("{n:?}"),
                        format!("{n:?} is the group of bodies[{j}]; a contact names the interface curve/surface between bodies, not a body."),
                    ));
                }
            }
            let mut sorted = names.clone();
            sorted.sort();
            if let Some(j) = seen.insert(sorted, i) {
                return Err(self.err(
                    &gkey,
                    format!(
                        "the same interface is already contacts[{j}]; define each interface once."
                    ),
                ));
            }
            let friction = self.non_negative(
                c.friction,
                &format!("{k}.friction"),
                "the friction coefficient",
            )?;
            let cohesion =
                self.non_negative(c.cohesion, &format!("{k}.cohesion"), "the cohesion")?;
            let tensile_strength = self.non_negative(
                c.tensile_strength,
                &format!("{k}.tensile_strength"),
                "the tensile strength",
            )?;
            let residual_cohesion = self.non_negative(
                c.residual_cohesion,
                &format!("{k}.residual_cohesion"),
                "the residual cohesion",
            )?;
            if residual_cohesion > cohesion {
                return Err(self.bad(
                    format!("{k}.residual_cohesion"),
                    residual_cohesion,
                    format!("the cohesion kept after opening cannot exceed the cohesion ({cohesion}); lower it or raise cohesion."),
                ));
            }
            out.push(Contact {
                groups,
                friction,
                cohesion,
                tensile_strength,
                slip: c.slip.unwrap_or_default(),
                residual_cohesion,
                traction: c.traction.unwrap_or_default(),
            });
        }
        Ok(out)
    }

    fn support(&self, i: usize, s: RawSupport, analysis: Analysis) -> R<Support> {
        let k = format!("supports[{i}]");
        let group = self.group(
            s.group,
            &format!("{k}.group"),
            "a physical point, curve or surface",
        )?;
        let mut fix = [false; 3];
        if let Some(list) = &s.fix {
            let key = format!("{k}.fix");
            let shown = format!("[{}]", quoted_list(list));
            for c in list {
                let d = match c.as_str() {
                    "x" => 0,
                    "y" => 1,
                    "z" => 2,
                    _ => {
                        return Err(self.bad(
                            key,
                            shown,
                            format!(
                                "{c:?} is not a component; use \"x\", \"y\"{}.",
                                if analysis == Analysis::Solid {
                                    " or \"z\""
                                } else {
                                    ""
                                }
                            ),
                        ))
                    }
                };
                if d == 2 && analysis != Analysis::Solid {
                    return Err(self.bad(
                        key,
                        shown,
                        format!("\"z\" exists only in a solid analysis; a {analysis} analysis has components \"x\" and \"y\"."),
                    ));
                }
                if fix[d] {
                    return Err(self.bad(
                        key,
                        shown,
                        format!("{c:?} is listed twice; list each component once."),
                    ));
                }
                fix[d] = true;
            }
        }
        let mut prescribed = [None; 3];
        for (d, (name, v)) in [("ux", s.ux), ("uy", s.uy), ("uz", s.uz)]
            .into_iter()
            .enumerate()
        {
            let Some(v) = v else { continue };
            let key = format!("{k}.{name}");
            let v = self.finite(v, &key)?;
            if d == 2 && analysis != Analysis::Solid {
                return Err(self.bad(
                    key,
                    v,
                    format!(
                        "uz exists only in a solid analysis; a {analysis} analysis has ux and uy."
                    ),
                ));
            }
            if fix[d] {
                return Err(self.bad(
                    key,
                    v,
                    format!(
                        "the component is also in fix (which holds it at zero); keep one: remove {:?} from fix to prescribe {v}, or remove {name}.",
                        ["x", "y", "z"][d]
                    ),
                ));
            }
            prescribed[d] = Some(v);
        }
        if !fix.iter().any(|&f| f) && prescribed.iter().all(Option::is_none) {
            return Err(self.err(
                k,
                format!(
                    "the support on {group:?} holds nothing; add fix = [\"x\", ...] (components held at zero) or a prescribed displacement ux = ... (uy, uz)."
                ),
            ));
        }
        Ok(Support {
            group,
            fix,
            prescribed,
        })
    }

    fn load(&self, i: usize, l: RawLoad, analysis: Analysis) -> R<Load> {
        let k = format!("loads[{i}]");
        let group = self.group(
            l.group,
            &format!("{k}.group"),
            "a physical curve (2D) or surface (3D)",
        )?;
        let kind = match (l.pressure, l.traction) {
            (Some(_), Some(_)) => {
                return Err(self.err(k, "both pressure and traction are given; a load is one or the other: split it into two [[loads]] entries."))
            }
            (None, None) => {
                return Err(self.err(
                    k,
                    format!("the load on {group:?} has no value; add pressure = P (positive presses into the body) or traction = [tx, ty(, tz)]."),
                ))
            }
            (Some(RawPressure::Value(p)), None) => LoadKind::Pressure(self.finite(p, &format!("{k}.pressure"))?),
            (Some(RawPressure::Hydrostatic(h)), None) => {
                let unit_weight = self.finite(h.unit_weight, &format!("{k}.pressure.unit_weight"))?;
                if unit_weight < 0.0 {
                    return Err(self.bad(format!("{k}.pressure.unit_weight"), unit_weight, "the unit weight of the fluid must be >= 0."));
                }
                LoadKind::Hydrostatic { surface: self.finite(h.surface, &format!("{k}.pressure.surface"))?, unit_weight }
            }
            (None, Some(t)) => LoadKind::Traction(self.vec3(&t, &format!("{k}.traction"), analysis)?),
        };
        let factors = match l.factors {
            None => None,
            Some(f) => Some(
                f.iter()
                    .enumerate()
                    .map(|(j, &v)| self.finite(v, &format!("{k}.factors[{j}]")))
                    .collect::<R<Vec<f64>>>()?,
            ),
        };
        Ok(Load { group, kind, factors })
    }

    fn probes(&self, raw: Vec<RawProbe>, analysis: Analysis) -> R<Vec<Probe>> {
        let mut seen: BTreeMap<String, usize> = BTreeMap::new();
        let mut out = Vec::new();
        for (i, p) in raw.into_iter().enumerate() {
            let k = format!("probes[{i}]");
            let name =
                self.required(p.name, &format!("{k}.name"), "a name for the sampled line")?;
            if name.trim().is_empty() {
                return Err(self.bad(
                    format!("{k}.name"),
                    "\"\"",
                    "give the probe a non-empty name.",
                ));
            }
            if let Some(j) = seen.insert(name.clone(), i) {
                return Err(self.bad(
                    format!("{k}.name"),
                    format!("{name:?}"),
                    format!("the name is already used by probes[{j}]; probe names must be unique."),
                ));
            }
            let from =
                self.required(p.from, &format!("{k}.from"), "the start point [x, y(, z)]")?;
            let from = self.vec3(&from, &format!("{k}.from"), analysis)?;
            let to = self.required(p.to, &format!("{k}.to"), "the end point [x, y(, z)]")?;
            let to = self.vec3(&to, &format!("{k}.to"), analysis)?;
            if from == to {
                return Err(self.bad(
                    format!("{k}.to"),
                    fmt_vec(&to),
                    "the end point equals from; give a line of non-zero length.",
                ));
            }
            let points = match self.required(
                p.points,
                &format!("{k}.points"),
                "the number of sample points, >= 2",
            )? {
                n if n >= 2 => usize::try_from(n)
                    .map_err(|_| self.bad(format!("{k}.points"), n, "too many points."))?,
                n => {
                    return Err(self.bad(
                        format!("{k}.points"),
                        n,
                        "a probe needs at least 2 points (both ends of the line are sampled).",
                    ))
                }
            };
            out.push(Probe {
                name,
                from,
                to,
                points,
            });
        }
        Ok(out)
    }

    fn analytic(&self, a: RawAnalytic, analysis: Analysis, bodies: &[Body], materials: &BTreeMap<String, Material>) -> R<Analytic> {
        let known = quoted_list(ANALYTIC_KINDS);
        let kind = self.required(a.kind.clone(), "analytic.kind", &format!("one of {known}"))?;
        // keys of the other kind are errors, not ignored
        let given: [(&str, bool); 9] = [
            ("a", a.a.is_some()),
            ("b", a.b.is_some()),
            ("p", a.p.is_some()),
            ("radius", a.radius.is_some()),
            ("thickness", a.thickness.is_some()),
            ("k", a.k.is_some()),
            ("slip", a.slip.is_some()),
            ("lining", a.lining.is_some()),
            ("ground", a.ground.is_some()),
        ];
        let allowed: &[&str] = match kind.as_str() {
            "lame_cylinder" => &["a", "b", "p"],
            "lined_tunnel" => &["radius", "thickness", "p", "k", "slip", "lining", "ground"],
            _ => &["a", "b", "p", "radius", "thickness", "k", "slip", "lining", "ground"],
        };
        if let Some((key, _)) = given.iter().find(|(key, on)| *on && !allowed.contains(key)) {
            return Err(self.err(
                format!("analytic.{key}"),
                format!("is not a key of kind = \"{kind}\"; its keys are {}. Remove the line.", quoted_list(allowed)),
            ));
        }
        match kind.as_str() {
            "lined_tunnel" => self.lined_tunnel(a, analysis, bodies, materials).map(Analytic::LinedTunnel),
            "lame_cylinder" => {
                let ra = self.required(a.a, "analytic.a", "the inner radius")?;
                let rb = self.required(a.b, "analytic.b", "the outer radius")?;
                let p = self.required(a.p, "analytic.p", "the internal pressure")?;
                let ra = self.finite(ra, "analytic.a")?;
                let rb = self.finite(rb, "analytic.b")?;
                let p = self.finite(p, "analytic.p")?;
                if ra <= 0.0 {
                    return Err(self.bad("analytic.a", ra, "the inner radius must be > 0."));
                }
                if rb <= ra {
                    return Err(self.bad(
                        "analytic.b",
                        rb,
                        format!("the outer radius must exceed the inner radius a = {ra}."),
                    ));
                }
                Ok(Analytic::LameCylinder { a: ra, b: rb, p })
            }
            other => Err(self.bad(
                "analytic.kind",
                format!("{other:?}"),
                format!("unknown analytic solution; the known kinds are {known}."),
            )),
        }
    }

    /// `[analytic] kind = "lined_tunnel"` (see [`crate::analytic::Analytic::LinedTunnel`]).
    fn lined_tunnel(&self, a: RawAnalytic, analysis: Analysis, bodies: &[Body], materials: &BTreeMap<String, Material>) -> R<crate::analytic::LinedTunnel> {
        use crate::analytic::{LinedTunnel, TunnelBody, TunnelSlip};
        if analysis != Analysis::PlaneStrain {
            return Err(self.bad(
                "analytic.kind",
                "\"lined_tunnel\"",
                format!("Einstein & Schwartz's lined tunnel is a plane strain solution, but analysis = \"{analysis}\"; use analysis = \"plane_strain\"."),
            ));
        }
        let radius = self.required(a.radius, "analytic.radius", "the radius of the lining's middle surface")?;
        let radius = self.finite(radius, "analytic.radius")?;
        if radius <= 0.0 {
            return Err(self.bad("analytic.radius", radius, "the lining's radius must be > 0."));
        }
        let thickness = self.required(a.thickness, "analytic.thickness", "the lining's thickness")?;
        let thickness = self.finite(thickness, "analytic.thickness")?;
        if thickness <= 0.0 || thickness >= 2.0 * radius {
            return Err(self.bad("analytic.thickness", thickness, format!("the lining's thickness must be > 0 and < 2 radius = {}.", 2.0 * radius)));
        }
        let p = self.required(a.p, "analytic.p", "the vertical far-field stress P, compression positive")?;
        let p = self.finite(p, "analytic.p")?;
        let k = self.required(a.k, "analytic.k", "the ratio K of horizontal to vertical far-field stress")?;
        let k = self.finite(k, "analytic.k")?;
        if k < 0.0 {
            return Err(self.bad("analytic.k", k, "the far-field stress ratio K must be >= 0."));
        }
        let slip = match a.slip.as_deref() {
            None | Some("none") => TunnelSlip::None,
            Some("full") => TunnelSlip::Full,
            Some(other) => {
                return Err(self.bad("analytic.slip", format!("{other:?}"), "use \"none\" (lining and ground bonded) or \"full\" (frictionless interface)."))
            }
        };
        let body = |key: &str, group: Option<String>, what: &str| -> R<(usize, TunnelBody)> {
            let key = format!("analytic.{key}");
            let g = self.group(group, &key, what)?;
            let i = bodies.iter().position(|b| b.group == g).ok_or_else(|| {
                self.bad(&key, format!("{g:?}"), format!("no [[bodies]] entry has this group; the bodies are {}.", quoted_list(bodies.iter().map(|b| b.group.as_str()))))
            })?;
            let m = &materials[&bodies[i].material];
            Ok((i, TunnelBody { group: g, e: m.e, nu: m.nu }))
        };
        let (il, lining) = body("lining", a.lining, "the lining's [[bodies]] group")?;
        let (ig, ground) = body("ground", a.ground, "the ground's [[bodies]] group")?;
        if il == ig {
            return Err(self.bad("analytic.ground", format!("{:?}", ground.group), "the ground must be another body than the lining."));
        }
        if bodies[il].initial.is_some() {
            return Err(self.err(
                format!("bodies[{il}].initial_stress"),
                "the lined tunnel's lining is installed stress-free (excavation loading): remove its initial stress.",
            ));
        }
        let szz0 = match bodies[ig].initial {
            None => 0.0,
            Some(InitialStress::Uniform(s)) => {
                let want = [-k * p, -p, s[2], 0.0];
                let tol = 1e-9 * p.abs().max(f64::MIN_POSITIVE);
                if (0..4).any(|j| (s[j] - want[j]).abs() > tol) {
                    return Err(self.bad(
                        format!("bodies[{ig}].initial_stress"),
                        fmt_vec(&s[..4]),
                        format!("[analytic] p = {p}, k = {k} mean the far field [-K P, -P, szz, 0] = {}: make the ground's initial stress and [analytic] agree.", fmt_vec(&want)),
                    ));
                }
                s[2]
            }
            Some(InitialStress::Geostatic { .. }) => {
                return Err(self.err(
                    format!("bodies[{ig}].k0"),
                    "the lined tunnel needs a uniform far field: give the ground initial_stress = [-K P, -P, szz, 0] instead of k0 and surface.",
                ))
            }
        };
        Ok(LinedTunnel { radius, thickness, p, k, slip, lining, ground, szz0 })
    }

    fn output(&self, raw: Option<RawOutput>) -> R<Output> {
        let Some(fields) = raw.and_then(|o| o.fields) else {
            return Ok(Output::default());
        };
        let mut seen = BTreeSet::new();
        for (i, f) in fields.iter().enumerate() {
            let key = format!("output.fields[{i}]");
            if !OUTPUT_FIELDS.contains(&f.as_str()) {
                return Err(self.bad(
                    key,
                    format!("{f:?}"),
                    format!(
                        "unknown field; the allowed ones are {}.",
                        quoted_list(OUTPUT_FIELDS)
                    ),
                ));
            }
            if !seen.insert(f.as_str()) {
                return Err(self.bad(key, format!("{f:?}"), "listed twice; list each field once."));
            }
        }
        Ok(Output { fields })
    }
}

// ---------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// The full example of DESIGN.md §4.
    const EXAMPLE: &str = r#"
title    = "Thick-walled cylinder, quarter model"
mesh     = "cylinder.geo"      # .geo (meshed by the gmsh CLI) or .msh; relative to this file
analysis = "plane_strain"      # plane_strain | plane_stress | axisymmetric | solid
thickness = 1.0                # plane analyses only

[gmsh]                          # used when mesh is a .geo
order = 2                       # element order (gmsh -order)
setnumber = { lc = 0.2 }        # gmsh -setnumber NAME VALUE

[materials.rock]
E = 2.0e5
nu = 0.167
density = 0.0                   # optional, with top-level gravity = [gx, gy, gz]

[[bodies]]                      # one substructure per entry
group = "body_1"                # physical surface (2D) / volume (3D)
material = "rock"

[[contacts]]
group = "A-A"                   # one physical curve/surface shared by two bodies,
# groups = ["face_1", "face_2"] # or two groups whose nodes coincide pairwise
friction = 0.8
cohesion = 2.0e4
tensile_strength = 3.0e5
slip = "coulomb"                # coulomb (default) | frictionless (the paper)

[[supports]]
group = "symmetry_x0"           # a physical point, curve or surface
fix = ["x"]                     # components held at zero; or prescribe: ux = 0.001 (uy, uz)

[[loads]]
group = "inner_surface"
pressure = 0.1                  # positive presses into the body; or traction = [tx, ty(, tz)]

[solver]
load_steps = 1
max_iterations = 100

[[probes]]                      # sample the solution along a line
name = "radial"
from = [2.7716, 1.1481]
to   = [4.6194, 1.9134]
points = 6

[analytic]                      # optional known solution, for error norms
kind = "lame_cylinder"
a = 3.0
b = 5.0
p = 0.1
"#;

    /// A fresh directory holding `cylinder.geo`, `cylinder.msh` and `cyl.toml`
    /// (the latter with `text`); returns the scene path.
    fn write_scene(text: &str) -> PathBuf {
        static N: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "subcontact_scene_test_{}_{}",
            std::process::id(),
            N.fetch_add(1, Ordering::SeqCst)
        ));
        std::fs::create_dir_all(&dir).expect("temp dir");
        std::fs::write(dir.join("cylinder.geo"), "// test\n").expect("write geo");
        std::fs::write(dir.join("cylinder.msh"), "").expect("write msh");
        let path = dir.join("cyl.toml");
        std::fs::write(&path, text).expect("write scene");
        path
    }

    /// Remove the directory `write_scene` made for `path`.
    fn clean(path: &Path) {
        if let Some(dir) = path.parent() {
            let _ = std::fs::remove_dir_all(dir);
        }
    }

    fn load(text: &str) -> Result<Scene, SceneError> {
        let path = write_scene(text);
        let r = Scene::load(&path);
        clean(&path);
        r
    }

    /// A minimal valid 2D scene plus `extra` appended.
    fn minimal(extra: &str) -> String {
        format!(
            "mesh = \"cylinder.geo\"\nanalysis = \"plane_strain\"\n[materials.rock]\nE = 1.0\nnu = 0.2\n[[bodies]]\ngroup = \"b1\"\nmaterial = \"rock\"\n{extra}"
        )
    }

    fn minimal_solid(extra: &str) -> String {
        minimal(extra).replace("plane_strain", "solid")
    }

    /// Expect an error whose message names the scene file and each of `needles`.
    fn rejects(text: &str, needles: &[&str]) -> String {
        let path = write_scene(text);
        let result = Scene::load(&path);
        clean(&path);
        let msg = match result {
            Ok(_) => panic!("accepted, expected an error mentioning {needles:?}:\n{text}"),
            Err(e) => e.to_string(),
        };
        assert!(
            msg.starts_with(&path.display().to_string()),
            "does not start with the file name: {msg}"
        );
        for n in needles {
            assert!(msg.contains(n), "message lacks {n:?}: {msg}");
        }
        assert!(!msg.contains('\n'), "not one paragraph: {msg}");
        msg
    }

    #[test]
    fn design_example_parses() {
        let path = write_scene(EXAMPLE);
        let s = Scene::load(&path).expect("example scene");
        assert_eq!(s.name, "cyl");
        assert_eq!(s.title, "Thick-walled cylinder, quarter model");
        assert_eq!(
            s.mesh,
            MeshSource::Geo(path.parent().unwrap().join("cylinder.geo"))
        );
        assert_eq!(s.analysis, Analysis::PlaneStrain);
        assert_eq!(s.analysis.dim(), 2);
        assert_eq!(s.thickness, 1.0);
        assert_eq!(
            s.gmsh,
            GmshOptions {
                order: 2,
                setnumber: vec![("lc".into(), 0.2)],
                clscale: None
            }
        );
        assert_eq!(
            s.materials["rock"],
            Material {
                e: 2.0e5,
                nu: 0.167,
                density: 0.0
            }
        );
        assert_eq!(
            s.bodies,
            vec![Body {
                group: "body_1".into(),
                material: "rock".into(),
                initial: None,
            }]
        );
        assert_eq!(s.material_of(&s.bodies[0]).e, 2.0e5);
        assert_eq!(
            s.contacts,
            vec![Contact {
                groups: ContactGroups::Shared("A-A".into()),
                friction: 0.8,
                cohesion: 2.0e4,
                tensile_strength: 3.0e5,
                slip: SlipLaw::Coulomb,
                residual_cohesion: 0.0,
                traction: TractionRecovery::Lumped,
            }]
        );
        assert_eq!(
            s.supports,
            vec![Support {
                group: "symmetry_x0".into(),
                fix: [true, false, false],
                prescribed: [None; 3]
            }]
        );
        assert_eq!(
            s.loads,
            vec![Load {
                group: "inner_surface".into(),
                kind: LoadKind::Pressure(0.1),
                factors: None,
            }]
        );
        assert_eq!(
            s.solver,
            Solver::default()
        );
        assert_eq!(
            s.probes,
            vec![Probe {
                name: "radial".into(),
                from: [2.7716, 1.1481, 0.0],
                to: [4.6194, 1.9134, 0.0],
                points: 6
            }]
        );
        assert_eq!(
            s.analytic,
            Some(Analytic::LameCylinder {
                a: 3.0,
                b: 5.0,
                p: 0.1
            })
        );
        assert_eq!(s.output, Output::default());
        // parse() from a string gives the same scene.
        assert_eq!(Scene::parse(EXAMPLE, &path).expect("parse"), s);
        clean(&path);
    }

    #[test]
    fn defaults_applied() {
        let s = load(&minimal("[[contacts]]\ngroup = \"i\"\n")).expect("minimal scene");
        assert_eq!(s.title, "cyl");
        assert_eq!(s.thickness, 1.0);
        assert_eq!(s.gravity, [0.0; 3]);
        assert_eq!(
            s.gmsh,
            GmshOptions {
                order: 1,
                setnumber: vec![],
                clscale: None
            }
        );
        assert_eq!(s.materials["rock"].density, 0.0);
        let c = &s.contacts[0];
        assert_eq!(
            (
                c.friction,
                c.cohesion,
                c.tensile_strength,
                c.residual_cohesion
            ),
            (0.0, 0.0, 0.0, 0.0)
        );
        assert_eq!(c.slip, SlipLaw::Coulomb);
        assert_eq!(
            s.solver,
            Solver::default()
        );
        assert!(s.supports.is_empty() && s.loads.is_empty() && s.probes.is_empty());
        assert_eq!(s.analytic, None);
        assert_eq!(
            s.output.fields,
            vec!["displacement".to_string(), "stress".to_string()]
        );
        assert!(s.output.wants("stress"));
    }

    #[test]
    fn other_forms_accepted() {
        let s = load(&("gravity = [0, 0, -9.81]\n".to_string() + &minimal_solid(
            "[[contacts]]\ngroups = [\"f1\", \"f2\"]\nslip = \"frictionless\"\ncohesion = 2\nresidual_cohesion = 1\n\
             [[supports]]\ngroup = \"s\"\nfix = [\"x\", \"z\"]\nuy = -0.001\n[[loads]]\ngroup = \"top\"\ntraction = [0, 0, -1]\n\
             [gmsh]\nclscale = 0.5\nsetnumber = { n = 4, lc = 0.1 }\n[output]\nfields = [\"stress\"]\n",
        )))
        .expect("solid scene");
        assert_eq!(s.gravity, [0.0, 0.0, -9.81]);
        assert_eq!(s.analysis.dim(), 3);
        assert_eq!(
            s.contacts[0].groups,
            ContactGroups::Pair("f1".into(), "f2".into())
        );
        assert_eq!(s.contacts[0].slip, SlipLaw::Frictionless);
        assert_eq!(s.supports[0].fix, [true, false, true]);
        assert_eq!(s.supports[0].prescribed, [None, Some(-0.001), None]);
        assert_eq!(s.loads[0].kind, LoadKind::Traction([0.0, 0.0, -1.0]));
        assert_eq!(
            s.gmsh.setnumber,
            vec![("lc".into(), 0.1), ("n".into(), 4.0)]
        );
        assert_eq!(s.gmsh.clscale, Some(0.5));
        assert_eq!(s.output.fields, vec!["stress".to_string()]);
        assert!(!s.output.wants("displacement"));

        let top = "gravity = [0, -9.81]\n".to_string()
            + &minimal("[[loads]]\ngroup = \"t\"\ntraction = [1, 2, 0]\n");
        let s = load(&top).expect("2D gravity");
        assert_eq!(s.gravity, [0.0, -9.81, 0.0]);
        assert_eq!(s.loads[0].kind, LoadKind::Traction([1.0, 2.0, 0.0]));

        let msh = minimal("").replace("cylinder.geo", "cylinder.msh");
        assert!(matches!(load(&msh).expect("msh").mesh, MeshSource::Msh(_)));
    }

    #[test]
    fn missing_file() {
        let path = std::env::temp_dir().join("subcontact_no_such_dir/none.toml");
        let msg = Scene::load(&path).expect_err("missing").to_string();
        assert!(
            msg.starts_with(&path.display().to_string()) && msg.contains("cannot read"),
            "{msg}"
        );
    }

    #[test]
    fn toml_syntax_and_types() {
        rejects(
            &minimal("friction = \n"),
            &["line 9, column 12", "bodies[0]", "invalid string"],
        );
        rejects(
            &minimal("[solver]\nload_steps = \"two\"\n"),
            &["line 10", "(in solver)", "expected i64"],
        );
        rejects(
            &minimal("").replace("plane_strain", "plane"),
            &["line 2", "plane_strain", "axisymmetric"],
        );
        rejects(
            &minimal("[[contacts]]\ngroup = \"i\"\nslip = \"stick\"\n"),
            &["contacts[0]", "coulomb", "frictionless"],
        );
    }

    #[test]
    fn misspelt_key() {
        let m = rejects(
            &minimal("[[contacts]]\ngroup = \"a\"\n[[contacts]]\ngroup = \"i\"\nfrction = 0.8\n"),
            &[
                "frction",
                "line 13",
                "contacts[1]",
                "friction",
                "tensile_strength",
            ],
        );
        assert!(m.contains("Unknown keys are errors"), "{m}");
        rejects(
            &minimal("").replace("nu = 0.2", "nu = 0.2\ne = 3"),
            &["materials.rock", "unknown field `e`", "`E`"],
        );
        rejects(
            &("titel = \"x\"\n".to_string() + &minimal("")),
            &["titel", "line 1", "`title`"],
        );
    }

    #[test]
    fn mesh_rules() {
        rejects(
            &minimal("").replace("cylinder.geo", "cylinder.stl"),
            &["mesh", "cylinder.stl", ".geo", ".msh"],
        );
        rejects(
            &minimal("").replace("cylinder.geo", "other.geo"),
            &["mesh", "other.geo", "does not exist"],
        );
        rejects(
            &minimal("").replace("mesh = \"cylinder.geo\"\n", ""),
            &["mesh", "missing"],
        );
        rejects(
            &minimal("").replace("analysis = \"plane_strain\"\n", ""),
            &["analysis", "missing"],
        );
        rejects(
            &minimal("[gmsh]\norder = 2\n").replace("cylinder.geo", "cylinder.msh"),
            &["gmsh", ".geo", "cylinder.msh"],
        );
    }

    #[test]
    fn material_rules() {
        let m = |from: &str, to: &str| minimal("").replace(from, to);
        rejects(
            &m("E = 1.0", "E = 0.0"),
            &["materials.rock.E", "= 0", "> 0"],
        );
        rejects(&m("E = 1.0", "E = inf"), &["materials.rock.E", "inf"]);
        rejects(&m("E = 1.0", "E = -5"), &["materials.rock.E", "-5"]);
        let msg = rejects(
            &m("nu = 0.2", "nu = 0.5"),
            &["materials.rock.nu", "= 0.5", "incompressible", "0.499"],
        );
        assert!(msg.contains("-1 < nu < 0.5"), "{msg}");
        rejects(&m("nu = 0.2", "nu = -1.0"), &["materials.rock.nu", "-1"]);
        rejects(
            &m("nu = 0.2", "nu = 0.2\ndensity = -1"),
            &["materials.rock.density", "-1", ">= 0"],
        );
        rejects(&m("nu = 0.2", ""), &["materials.rock.nu", "missing"]);
        rejects(
            &m("[materials.rock]", "[materials.\"soft clay\"]")
                .replace("\"rock\"", "\"soft clay\"")
                .replace("E = 1.0", "E = 0"),
            &["materials.\"soft clay\".E"],
        );
    }

    #[test]
    fn plane_and_solid_rules() {
        rejects(
            &("thickness = 0\n".to_string() + &minimal("")),
            &["thickness", "= 0", "> 0"],
        );
        rejects(
            &("thickness = 2\n".to_string() + &minimal_solid("")),
            &["thickness", "solid", "remove"],
        );
        rejects(
            &("gravity = [1]\n".to_string() + &minimal("")),
            &["gravity", "[1]", "2 components"],
        );
        rejects(
            &("gravity = [1, 2, 3, 4]\n".to_string() + &minimal("")),
            &["gravity", "2 components"],
        );
        rejects(
            &("gravity = [0, -9.8]\n".to_string() + &minimal_solid("")),
            &["gravity", "3 components"],
        );
        rejects(
            &("gravity = [0, -9.8, 1]\n".to_string() + &minimal("")),
            &["gravity", "z component must be 0"],
        );
        rejects(
            &minimal("[[supports]]\ngroup = \"s\"\nfix = [\"z\"]\n"),
            &["supports[0].fix", "\"z\"", "solid"],
        );
        rejects(
            &minimal("[[supports]]\ngroup = \"s\"\nuz = 0.1\n"),
            &["supports[0].uz", "solid"],
        );
        rejects(
            &minimal("[[loads]]\ngroup = \"l\"\ntraction = [0, 0, 1]\n"),
            &["loads[0].traction", "z component"],
        );
        rejects(
            &minimal_solid("[[loads]]\ngroup = \"l\"\ntraction = [0, 1]\n"),
            &["loads[0].traction", "3 components"],
        );
        let probe = "[[probes]]\nname = \"p\"\nfrom = [0, 0, 1]\nto = [1, 1]\npoints = 3\n";
        rejects(&minimal(probe), &["probes[0].from", "z component"]);
        rejects(&minimal_solid(probe), &["probes[0].to", "3 components"]);
    }

    #[test]
    fn body_rules() {
        let no_bodies =
            "mesh = \"cylinder.geo\"\nanalysis = \"solid\"\n[materials.rock]\nE = 1\nnu = 0.1\n";
        rejects(no_bodies, &["bodies", "at least one"]);
        rejects(
            &minimal("[[bodies]]\ngroup = \"b2\"\nmaterial = \"steel\"\n"),
            &["bodies[1].material", "\"steel\"", "\"rock\""],
        );
        rejects(
            &minimal("[[bodies]]\ngroup = \"b1\"\nmaterial = \"rock\"\n"),
            &["bodies[1].group", "\"b1\"", "bodies[0]"],
        );
        rejects(
            &minimal("[[bodies]]\nmaterial = \"rock\"\n"),
            &["bodies[1].group", "missing"],
        );
        rejects(
            &minimal("[[bodies]]\ngroup = \"\"\nmaterial = \"rock\"\n"),
            &["bodies[1].group", "empty"],
        );
        let no_mat = "mesh = \"cylinder.geo\"\nanalysis = \"solid\"\n[[bodies]]\ngroup = \"b\"\nmaterial = \"rock\"\n";
        rejects(no_mat, &["bodies[0].material", "none are defined"]);
    }

    #[test]
    fn contact_rules() {
        let c = |body: &str| {
            minimal(&format!(
                "[[contacts]]\ngroup = \"ok\"\n[[contacts]]\n{body}\n"
            ))
        };
        rejects(&c("friction = 0.1"), &["contacts[1]", "group", "groups"]);
        rejects(
            &c("group = \"a\"\ngroups = [\"b\", \"c\"]"),
            &["contacts[1]", "both"],
        );
        rejects(
            &c("groups = [\"b\"]"),
            &["contacts[1].groups", "[\"b\"]", "exactly 2"],
        );
        rejects(
            &c("groups = [\"b\", \"c\", \"d\"]"),
            &["contacts[1].groups", "exactly 2"],
        );
        rejects(
            &c("groups = [\"b\", \"b\"]"),
            &["contacts[1].groups", "differ"],
        );
        rejects(
            &c("group = \"b1\""),
            &["contacts[1].group", "\"b1\"", "bodies[0]"],
        );
        rejects(&c("group = \"ok\""), &["contacts[1].group", "contacts[0]"]);
        rejects(
            &c("friction = -0.1\ngroup = \"x\""),
            &["contacts[1].friction", "-0.1", ">= 0"],
        );
        rejects(
            &c("friction = nan\ngroup = \"x\""),
            &["contacts[1].friction", "NaN", "finite"],
        );
        rejects(
            &c("cohesion = -1\ngroup = \"x\""),
            &["contacts[1].cohesion", "-1"],
        );
        rejects(
            &c("tensile_strength = -1\ngroup = \"x\""),
            &["contacts[1].tensile_strength", "-1"],
        );
        rejects(
            &c("residual_cohesion = -1\ngroup = \"x\""),
            &["contacts[1].residual_cohesion", "-1"],
        );
        rejects(
            &c("cohesion = 1\nresidual_cohesion = 2\ngroup = \"x\""),
            &["contacts[1].residual_cohesion", "= 2", "cohesion (1)"],
        );
    }

    #[test]
    fn support_rules() {
        let s = |body: &str| minimal(&format!("[[supports]]\ngroup = \"s\"\n{body}\n"));
        rejects(&s(""), &["supports[0]", "fix", "ux"]);
        rejects(&s("fix = []"), &["supports[0]", "holds nothing"]);
        rejects(
            &s("fix = [\"w\"]"),
            &["supports[0].fix", "\"w\"", "\"x\", \"y\""],
        );
        rejects(&s("fix = [\"x\", \"x\"]"), &["supports[0].fix", "twice"]);
        rejects(
            &s("fix = [\"x\"]\nux = 0.1"),
            &["supports[0].ux", "0.1", "also in fix"],
        );
        rejects(&s("uy = inf"), &["supports[0].uy", "finite"]);
        rejects(
            &minimal("[[supports]]\nfix = [\"x\"]\n"),
            &["supports[0].group", "missing"],
        );
        rejects(
            &s("fix = [\"x\"]\nuz = 1").replace("plane_strain", "axisymmetric"),
            &["supports[0].uz", "axisymmetric"],
        );
    }

    #[test]
    fn load_rules() {
        let l = |body: &str| minimal(&format!("[[loads]]\ngroup = \"l\"\n{body}\n"));
        rejects(&l(""), &["loads[0]", "pressure", "traction"]);
        rejects(&l("pressure = 1\ntraction = [1, 0]"), &["loads[0]", "both"]);
        rejects(&l("pressure = nan"), &["loads[0].pressure", "finite"]);
        rejects(&l("traction = [1, nan]"), &["loads[0].traction", "finite"]);
    }

    #[test]
    fn solver_gmsh_probe_rules() {
        rejects(
            &minimal("[solver]\nload_steps = 0\n"),
            &["solver.load_steps", "= 0", "at least 1"],
        );
        rejects(
            &minimal("[solver]\nmax_iterations = -3\n"),
            &["solver.max_iterations", "-3"],
        );
        rejects(
            &minimal("[gmsh]\norder = 3\n"),
            &["gmsh.order", "= 3", "1", "2"],
        );
        rejects(&minimal("[gmsh]\nclscale = 0\n"), &["gmsh.clscale", "> 0"]);
        rejects(
            &minimal("[gmsh]\nsetnumber = { lc = inf }\n"),
            &["gmsh.setnumber.lc", "finite"],
        );
        rejects(
            &minimal("[gmsh]\nsetnumber = { \"a b\" = 1 }\n"),
            &["gmsh.setnumber.\"a b\"", "DefineConstant"],
        );
        let p = |name: &str, pts: i64| {
            format!("[[probes]]\nname = \"{name}\"\nfrom = [0, 0]\nto = [1, 1]\npoints = {pts}\n")
        };
        rejects(
            &minimal(&p("a", 1)),
            &["probes[0].points", "= 1", "at least 2"],
        );
        rejects(
            &minimal(&(p("a", 3) + &p("a", 3))),
            &["probes[1].name", "\"a\"", "unique"],
        );
        rejects(
            &minimal("[[probes]]\nname = \"a\"\nfrom = [1, 1]\nto = [1, 1]\npoints = 3\n"),
            &["probes[0].to", "non-zero length"],
        );
        rejects(
            &minimal("[[probes]]\nname = \"a\"\nfrom = [1, 1]\nto = [2, 1]\n"),
            &["probes[0].points", "missing"],
        );
    }

    #[test]
    fn analytic_and_output_rules() {
        let a = |body: &str| minimal(&format!("[analytic]\n{body}\n"));
        rejects(
            &a("kind = \"lame_cylinder\"\na = 5\nb = 3\np = 1"),
            &["analytic.b", "= 3", "a = 5"],
        );
        rejects(
            &a("kind = \"lame_cylinder\"\na = 0\nb = 3\np = 1"),
            &["analytic.a", "= 0", "> 0"],
        );
        rejects(
            &a("kind = \"lame_cylinder\"\na = 1\nb = 3\np = inf"),
            &["analytic.p", "finite"],
        );
        rejects(
            &a("kind = \"lame_cylinder\"\na = 1\nb = 3"),
            &["analytic.p", "missing"],
        );
        rejects(
            &a("kind = \"kirsch\""),
            &["analytic.kind", "\"kirsch\"", "\"lame_cylinder\""],
        );
        rejects(
            &a("kind = \"lame_cylinder\"\na = 1\nb = 3\np = 1\nq = 2"),
            &["analytic", "unknown field `q`"],
        );
        rejects(
            &minimal("[output]\nfields = [\"strain\"]\n"),
            &[
                "output.fields[0]",
                "\"strain\"",
                "\"displacement\", \"stress\"",
            ],
        );
        rejects(
            &minimal("[output]\nfields = [\"stress\", \"stress\"]\n"),
            &["output.fields[1]", "twice"],
        );
    }
}
