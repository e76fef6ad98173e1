//! The checker: turns the raw scene into a validated [`Scene`], key by key,
//! applying defaults. Every rule that fails is a [`SceneError::Invalid`](super::SceneError::Invalid)
//! naming the key path, the value as written and what to do. The checks of
//! the entries that name the mesh's groups (bodies, contacts, supports,
//! loads) are in `validate/groups.rs`, those of `[analytic]` in
//! `validate/analytic.rs`, of `[[sections]]` in `validate/sections.rs`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use super::raw::{RawFrame, RawGmsh, RawMaterial, RawOutput, RawProbe, RawScene, RawSolver, RawWater};
use super::validated::{Contact, GmshOptions, MeshSource, Output, Region, Scene, Solver, OUTPUT_FIELDS};
use crate::fem::Analysis;
use crate::mesh::joints::JointSpec;
use crate::model::{BodySpec, LoadSpec, Material};
use crate::recover::Probe;

mod analytic;
mod checker;
mod groups;
mod joints;
mod safety;
mod sections;
mod water;

pub(super) use checker::Checker;
use checker::{fmt_vec, quoted_list, R};

/// The Young's moduli a scene may give: beyond them the stiffness entries
/// (E times the elements' sizes, and Poisson factors up to ~1e3) leave
/// double precision's range. Measured on blocks3d: 1e-300 and 1e305 solve
/// as E = 3e4 does, scaled; 1e-310 ends in NaN, 1.7e308 in a singular
/// matrix. Inside, any consistent units give the same results, scaled.
const E_RANGE: (f64, f64) = (1e-300, 1e300);

/// `name` as it would appear in a key path: bare when it is a bare TOML key,
/// quoted otherwise.
fn key_name(name: &str) -> String {
    if !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
        name.to_string()
    } else {
        format!("{name:?}")
    }
}

/// The most load steps a scene may ask for.
const MAX_STEPS: usize = 100_000;
/// The most sample points on one probe.
const MAX_PROBE_POINTS: usize = 1_000_000;

impl Checker<'_> {
    /// The scene, key by key, in the order the errors are reported.
    pub(super) fn scene(&self, raw: RawScene) -> R<Scene> {
        let name = self.name();
        let title = raw.title.unwrap_or_else(|| name.clone());

        let analysis = self.required(
            raw.analysis,
            "analysis",
            "one of \"plane_strain\", \"plane_stress\", \"axisymmetric\", \"solid\"",
        )?;
        let mesh = self.mesh(raw.mesh)?;

        let thickness = self.thickness(raw.thickness, analysis)?;
        let gravity = match &raw.gravity {
            None => [0.0; 3],
            Some(g) => self.vec3(g, "gravity", analysis)?,
        };

        let gmsh = self.gmsh(raw.gmsh, &mesh)?;
        let materials = self.materials(raw.materials)?;
        let bodies = self.bodies(raw.bodies, &materials, analysis)?;
        let mut raw_contacts = raw.contacts;
        let contact_waters: Vec<_> = raw_contacts.iter_mut().map(|c| c.water.take()).collect();
        let mut contacts = self.contacts(raw_contacts, &bodies)?;
        let mut raw_joints = (raw.joint_sets, raw.joints);
        let joint_waters = self.joint_waters(&mut raw_joints.0, &mut raw_joints.1)?;
        let (joints, joint_contacts) = self.joints(raw_joints.0, raw_joints.1, &bodies, &contacts, analysis)?;
        self.joints_fit(&joints, &mesh, &gmsh)?;
        let first_joint = contacts.len();
        contacts.extend(joint_contacts);
        // a joint's water acts on the contact group the cutter makes of its faces
        let waters = contact_waters.into_iter().enumerate().map(|(i, w)| (i, format!("contacts[{i}].water"), w));
        let waters = waters.chain(joint_waters.into_iter().enumerate().map(|(j, (k, w))| (first_joint + j, k, w)));
        let max_blocks =
            self.at_least(raw.max_blocks, 1000, 1, "max_blocks", "the most blocks the joints may cut the bodies into")?;
        let supports =
            raw.supports.into_iter().enumerate().map(|(i, s)| self.support(i, s, analysis)).collect::<R<Vec<_>>>()?;
        let loads = raw.loads.into_iter().enumerate().map(|(i, l)| self.load(i, l, analysis)).collect::<R<Vec<_>>>()?;
        let solver = self.solver(raw.solver)?;
        self.factor_tables(&loads, &solver)?;
        self.attach_waters(&mut contacts, waters, &loads, analysis, solver.load_steps)?;
        let contact_key =
            |i: usize| i.checked_sub(first_joint).map_or(format!("contacts[{i}]"), |j| joints[j].key.clone());
        self.stiff_everywhere(&contacts, contact_key, &solver)?;
        let probes = self.probes(raw.probes, analysis)?;
        let analytic = raw.analytic.map(|a| self.analytic(a, analysis, &bodies)).transpose()?;
        let output = self.output(raw.output, analysis, &bodies)?;
        let safety = raw.safety.map(|s| self.safety(s, &contacts, &loads, gravity)).transpose()?;
        let sections = self.sections(raw.sections, analysis, &bodies)?;

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
            bonded: false,
            safety,
            joints,
            max_blocks,
            merge_slivers: raw.merge_slivers.unwrap_or(false),
            sections,
        })
    }

    /// The scene's name: its file's stem.
    fn name(&self) -> String {
        self.path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "scene".to_string())
    }

    /// The out-of-plane thickness (plane analyses only), 1 by default.
    fn thickness(&self, raw: Option<f64>, analysis: Analysis) -> R<f64> {
        Ok(match raw {
            None => 1.0,
            Some(t) if !analysis.has_thickness() => {
                return Err(self.bad(
                    "thickness",
                    t,
                    format!(
                        "thickness applies only to plane_strain and plane_stress; remove it for a {analysis} analysis."
                    ),
                ))
            }
            Some(t) if t.is_finite() && t > 0.0 && t <= 1e100 => t,
            Some(t) if t > 1e100 => {
                return Err(self.bad(
                    "thickness",
                    t,
                    "a thickness beyond 1e100 is beyond what double precision can carry through the stiffness (its products overflow); give the model in other units.",
                ))
            }
            Some(t) => return Err(self.bad("thickness", t, "the out-of-plane thickness must be a finite number > 0.")),
        })
    }

    /// Joints are cut into a .geo, and a structured mesh needs joints.
    fn joints_fit(&self, joints: &[JointSpec], mesh: &MeshSource, gmsh: &GmshOptions) -> R<()> {
        if let (Some(j), MeshSource::Msh(p)) = (joints.first(), mesh) {
            return Err(self.err(
                &j.key,
                format!("joints are cut into the bodies of a .geo, but mesh is the ready mesh {}; point mesh at the .geo (with SetFactory(\"OpenCASCADE\")), or give the joints as [[contacts]] groups of the mesh.", p.display()),
            ));
        }
        if gmsh.structured && joints.is_empty() {
            return Err(self.bad(
                "gmsh.structured",
                true,
                "structured meshes the blocks the joints cut ([[joint_sets]], [[joints]]); without joints, give Transfinite and Recombine in the .geo.",
            ));
        }
        Ok(())
    }

    /// `[solver]`, with its defaults.
    fn solver(&self, raw: Option<RawSolver>) -> R<Solver> {
        Ok(match raw {
            None => Solver::default(),
            Some(s) => Solver {
                load_steps: self.at_most(
                    self.at_least(s.load_steps, 1, 1, "solver.load_steps", "the number of load steps")?,
                    MAX_STEPS,
                    "solver.load_steps",
                    "load steps (each keeps its displacements and stresses for the result files)",
                )?,
                max_iterations: self.at_least(
                    s.max_iterations,
                    100,
                    1,
                    "solver.max_iterations",
                    "the contact iteration limit",
                )?,
                max_cuts: self.at_least(
                    s.max_cuts,
                    3,
                    0,
                    "solver.max_cuts",
                    "the number of halvings of a load step that does not converge",
                )?,
                rule: s.rule.unwrap_or_default(),
                interface: s.interface.unwrap_or_default(),
                initial_stage: s.initial_stage.unwrap_or(false),
                rigid_fallback: s.rigid_fallback.unwrap_or(true),
                augmented_lagrangian: s.augmented_lagrangian.unwrap_or(false),
                substructures: self.at_least(
                    s.substructures,
                    1,
                    1,
                    "solver.substructures",
                    "the number of pieces each body is cut into",
                )?,
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
        })
    }

    /// Load factor tables have one entry per load step.
    fn factor_tables(&self, loads: &[LoadSpec], solver: &Solver) -> R<()> {
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
                    format!(
                        "has {} value(s) but [solver] load_steps = {steps}: give one load factor per step.",
                        f.len()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The water of each contact `(index, key, water)`, checked once the
    /// loads are (a `face` names one).
    fn attach_waters(
        &self,
        contacts: &mut [Contact],
        waters: impl Iterator<Item = (usize, String, Option<RawWater>)>,
        loads: &[LoadSpec],
        analysis: Analysis,
        steps: usize,
    ) -> R<()> {
        for (i, k, w) in waters {
            if let Some(w) = w {
                contacts[i].water = Some(self.water(&k, w, loads, analysis, steps)?);
            }
        }
        Ok(())
    }

    fn mesh(&self, mesh: Option<String>) -> R<MeshSource> {
        let m = self.required(mesh, "mesh", "the .geo or .msh file, relative to the scene file")?;
        let rel = Path::new(&m);
        let ext = rel.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
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
        if full.is_dir() {
            return Err(self.bad(
                "mesh",
                format!("{m:?}"),
                format!("{} is a directory, not a mesh file; point mesh at the .geo or .msh file.", full.display()),
            ));
        }
        if !full.is_file() {
            let shown_dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
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
            Some(o) => return Err(self.bad("gmsh.order", o, "the element order must be 1 (linear) or 2 (quadratic).")),
        };
        let mut setnumber = Vec::new();
        for (name, v) in g.setnumber.unwrap_or_default() {
            let key = format!("gmsh.setnumber.{}", key_name(&name));
            let ident = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.');
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
            Some(c) => return Err(self.bad("gmsh.clscale", c, "the mesh size factor must be a finite number > 0.")),
        };
        let timeout = match g.timeout {
            None => GmshOptions::default().timeout,
            Some(t) if t.is_finite() && t > 0.0 && t <= 1e9 => t,
            Some(t) => {
                return Err(self.bad(
                    "gmsh.timeout",
                    t,
                    "gmsh's time limit must be a number of seconds > 0 (default 600).",
                ))
            }
        };
        Ok(GmshOptions { order, setnumber, clscale, timeout, structured: g.structured.unwrap_or(false) })
    }

    fn materials(&self, raw: BTreeMap<String, RawMaterial>) -> R<BTreeMap<String, Material>> {
        let mut out = BTreeMap::new();
        for (name, m) in raw {
            let k = format!("materials.{}", key_name(&name));
            let e = self.required(m.e, &format!("{k}.E"), "Young's modulus, > 0")?;
            if !(e.is_finite() && e > 0.0) {
                return Err(self.bad(format!("{k}.E"), e, "Young's modulus must be a finite number > 0."));
            }
            if !(E_RANGE.0..=E_RANGE.1).contains(&e) {
                return Err(self.bad(
                    format!("{k}.E"),
                    format!("{e:e}"),
                    "Young's modulus must lie between 1e-300 and 1e300: beyond, the stiffness matrices (E times the elements' sizes and Poisson factors) leave what double precision can hold (1e-308 to 1e308), and the solve ends in NaN or a singular matrix. Give E, the loads and the strengths in other units (the results are the same in any consistent units, scaled).",
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

    fn probes(&self, raw: Vec<RawProbe>, analysis: Analysis) -> R<Vec<Probe>> {
        let mut seen: BTreeMap<String, usize> = BTreeMap::new();
        let mut out = Vec::new();
        for (i, p) in raw.into_iter().enumerate() {
            let k = format!("probes[{i}]");
            let name = self.required(p.name, &format!("{k}.name"), "a name for the sampled line")?;
            if name.trim().is_empty() {
                return Err(self.bad(format!("{k}.name"), "\"\"", "give the probe a non-empty name."));
            }
            if let Some(j) = seen.insert(name.clone(), i) {
                return Err(self.bad(
                    format!("{k}.name"),
                    format!("{name:?}"),
                    format!("the name is already used by probes[{j}]; probe names must be unique."),
                ));
            }
            let from = self.required(p.from, &format!("{k}.from"), "the start point [x, y(, z)]")?;
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
            let points = match self.required(p.points, &format!("{k}.points"), "the number of sample points, >= 2")? {
                n if n >= 2 => self.at_most(
                    usize::try_from(n).map_err(|_| self.bad(format!("{k}.points"), n, "too many points."))?,
                    MAX_PROBE_POINTS,
                    &format!("{k}.points"),
                    "sample points on one probe",
                )?,
                n => {
                    return Err(self.bad(
                        format!("{k}.points"),
                        n,
                        "a probe needs at least 2 points (both ends of the line are sampled).",
                    ))
                }
            };
            out.push(Probe { name, from, to, points });
        }
        Ok(out)
    }

    fn output(&self, raw: Option<RawOutput>, analysis: Analysis, bodies: &[BodySpec]) -> R<Output> {
        let Some(raw) = raw else {
            return Ok(Output::default());
        };
        let frame = raw.frame.map(|f| self.frame(f, analysis, bodies)).transpose()?;
        let pressure_window = match raw.pressure_window {
            Some(w) if !(w.is_finite() && w > 0.0) => {
                return Err(self.bad(
                    "output.pressure_window",
                    w,
                    "the width over which the design bearing pressure is averaged must be a finite length > 0.",
                ))
            }
            w => w,
        };
        let colour_scale = raw.colour_scale.unwrap_or_default();
        let Some(fields) = raw.fields else {
            return Ok(Output { frame, pressure_window, colour_scale, ..Output::default() });
        };
        let mut seen = BTreeSet::new();
        for (i, f) in fields.iter().enumerate() {
            let key = format!("output.fields[{i}]");
            if !OUTPUT_FIELDS.contains(&f.as_str()) {
                return Err(self.bad(
                    key,
                    format!("{f:?}"),
                    format!("unknown field; the allowed ones are {}.", quoted_list(OUTPUT_FIELDS)),
                ));
            }
            if !seen.insert(f.as_str()) {
                return Err(self.bad(key, format!("{f:?}"), "listed twice; list each field once."));
            }
        }
        Ok(Output { fields, frame, pressure_window, colour_scale })
    }

    /// `[output] frame`: a box (`from`, `to`: the analysis's coordinates,
    /// `from` below `to` in each) or bodies (groups of `[[bodies]]`).
    fn frame(&self, raw: RawFrame, analysis: Analysis, bodies: &[BodySpec]) -> R<Region> {
        let k = "output.frame";
        match (raw.from, raw.to, raw.bodies) {
            (Some(from), Some(to), None) => {
                let from = self.vec3(&from, &format!("{k}.from"), analysis)?;
                let to = self.vec3(&to, &format!("{k}.to"), analysis)?;
                let dim = if analysis == Analysis::Solid { 3 } else { 2 };
                if let Some(d) = (0..dim).find(|&d| from[d] >= to[d]) {
                    return Err(self.bad(
                        format!("{k}.to"),
                        fmt_vec(&to[..dim]),
                        format!("its {} must exceed from's ({}): the box runs from its lowest corner to its highest.", ["x", "y", "z"][d], from[d]),
                    ));
                }
                Ok(Region::Box { from, to })
            }
            (None, None, Some(names)) => {
                if names.is_empty() {
                    return Err(self.bad(format!("{k}.bodies"), "[]", "name at least one body (a group of [[bodies]])."));
                }
                for (i, n) in names.iter().enumerate() {
                    if !bodies.iter().any(|b| &b.group == n) {
                        let known: Vec<String> = bodies.iter().map(|b| format!("{:?}", b.group)).collect();
                        return Err(self.bad(format!("{k}.bodies[{i}]"), format!("{n:?}"), format!("no [[bodies]] entry has this group; the bodies are {}.", known.join(", "))));
                    }
                }
                Ok(Region::Bodies(names))
            }
            _ => Err(self.err(
                k,
                "give either the box `frame = { from = [x0, y0(, z0)], to = [x1, y1(, z1)] }` or the bodies `frame = { bodies = [\"lining\"] }` that the deformed picture frames.",
            )),
        }
    }
}
