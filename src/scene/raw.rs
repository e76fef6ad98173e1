//! The scene as written: serde structures that mirror the TOML. Unknown keys
//! are rejected (`deny_unknown_fields`); every field is optional so that a
//! missing key is reported by the checker with its full key path, not by
//! serde. Enumerated values (`analysis`, `slip`, `rule`, `traction`) are read
//! straight into the physics' own enums.

use serde::Deserialize;
use std::collections::BTreeMap;

use super::validated::ColourScale;
use crate::contact::{InterfaceSolver, SlipLaw, StateRule, TractionRecovery};
use crate::fem::Analysis;
use crate::mesh::joints::Shape;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub(super) title: Option<String>,
    pub(super) mesh: Option<String>,
    pub(super) analysis: Option<Analysis>,
    pub(super) thickness: Option<f64>,
    pub(super) gravity: Option<Vec<f64>>,
    pub(super) gmsh: Option<RawGmsh>,
    #[serde(default)]
    pub(super) materials: BTreeMap<String, RawMaterial>,
    #[serde(default)]
    pub(super) bodies: Vec<RawBody>,
    #[serde(default)]
    pub(super) contacts: Vec<RawContact>,
    #[serde(default)]
    pub(super) supports: Vec<RawSupport>,
    #[serde(default)]
    pub(super) loads: Vec<RawLoad>,
    pub(super) solver: Option<RawSolver>,
    #[serde(default)]
    pub(super) probes: Vec<RawProbe>,
    pub(super) analytic: Option<RawAnalytic>,
    pub(super) output: Option<RawOutput>,
    pub(super) safety: Option<RawSafety>,
    #[serde(default)]
    pub(super) joint_sets: Vec<RawJoint>,
    #[serde(default)]
    pub(super) joints: Vec<RawJoint>,
    pub(super) max_blocks: Option<i64>,
    pub(super) merge_slivers: Option<bool>,
    #[serde(default)]
    pub(super) sections: Vec<RawSection>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawGmsh {
    pub(super) order: Option<i64>,
    pub(super) setnumber: Option<BTreeMap<String, f64>>,
    pub(super) clscale: Option<f64>,
    pub(super) timeout: Option<f64>,
    pub(super) structured: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMaterial {
    #[serde(rename = "E")]
    pub(super) e: Option<f64>,
    pub(super) nu: Option<f64>,
    pub(super) density: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBody {
    pub(super) group: Option<String>,
    pub(super) material: Option<String>,
    pub(super) initial_stress: Option<Vec<f64>>,
    pub(super) k0: Option<f64>,
    pub(super) surface: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawContact {
    pub(super) group: Option<String>,
    pub(super) groups: Option<Vec<String>>,
    pub(super) friction: Option<f64>,
    pub(super) cohesion: Option<f64>,
    pub(super) tensile_strength: Option<f64>,
    pub(super) slip: Option<SlipLaw>,
    pub(super) residual_cohesion: Option<f64>,
    pub(super) normal_stiffness: Option<f64>,
    pub(super) shear_stiffness: Option<f64>,
    pub(super) traction: Option<TractionRecovery>,
    pub(super) water: Option<RawWater>,
}

/// `water = { .. }` of a contact: a uniform `pressure`, or a piezometric
/// `level`, `levels = [[s, h], ..]` or `upstream` / `downstream` heads with
/// a `unit_weight`; `along`, `drain`, `face` and `factors` beside them.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawWater {
    pub(super) pressure: Option<f64>,
    pub(super) unit_weight: Option<f64>,
    pub(super) level: Option<f64>,
    pub(super) levels: Option<Vec<Vec<f64>>>,
    pub(super) plane: Option<Vec<f64>>,
    pub(super) upstream: Option<f64>,
    pub(super) downstream: Option<f64>,
    pub(super) along: Option<Vec<f64>>,
    pub(super) drain: Option<RawDrain>,
    pub(super) face: Option<String>,
    pub(super) factors: Option<Vec<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDrain {
    pub(super) at: Option<f64>,
    pub(super) efficiency: Option<f64>,
}

/// `[[joint_sets]]` and `[[joints]]`: where the joints lie; every other
/// key is kept in `contact`, which the checker reads as a [`RawContact`]
/// (so a joint takes every `[[contacts]]` key, and a key neither knows is
/// refused there: serde's `flatten` would ignore it).
#[derive(Deserialize)]
pub(super) struct RawJoint {
    pub(super) name: Option<String>,
    pub(super) dip: Option<f64>,
    pub(super) dip_direction: Option<f64>,
    pub(super) angle: Option<f64>,
    pub(super) spacing: Option<f64>,
    pub(super) offset: Option<f64>,
    pub(super) point: Option<Vec<f64>>,
    pub(super) bodies: Option<Vec<String>>,
    pub(super) persistence: Option<f64>,
    pub(super) gap: Option<f64>,
    pub(super) shape: Option<Shape>,
    pub(super) centre: Option<Vec<f64>>,
    pub(super) extent: Option<RawFrame>,
    pub(super) snap: Option<f64>,
    #[serde(flatten)]
    pub(super) contact: toml::Table,
}

/// The keys of [`RawJoint`] itself, for messages.
pub(super) const JOINT_KEYS: &[&str] = &[
    "name",
    "dip",
    "dip_direction",
    "angle",
    "spacing",
    "offset",
    "point",
    "bodies",
    "persistence",
    "gap",
    "shape",
    "centre",
    "extent",
    "snap",
];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSupport {
    pub(super) group: Option<String>,
    pub(super) fix: Option<Vec<String>>,
    pub(super) ux: Option<f64>,
    pub(super) uy: Option<f64>,
    pub(super) uz: Option<f64>,
}

/// `pressure = P` or `pressure = { surface = y0, unit_weight = gamma }`.
#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum RawPressure {
    Value(f64),
    Hydrostatic(RawHydrostatic),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawHydrostatic {
    pub(super) surface: f64,
    pub(super) unit_weight: f64,
    /// Westergaard's hydrodynamic pressure under this seismic coefficient
    /// instead of the hydrostatic one, with the reservoir's `base`.
    pub(super) westergaard: Option<f64>,
    pub(super) base: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLoad {
    pub(super) group: Option<String>,
    pub(super) pressure: Option<RawPressure>,
    pub(super) traction: Option<Vec<f64>>,
    pub(super) seismic: Option<RawSeismic>,
    pub(super) factors: Option<Vec<f64>>,
    pub(super) force: Option<Vec<f64>>,
    pub(super) moment: Option<RawMoment>,
    pub(super) point: Option<Vec<f64>>,
}

/// `moment = M` (about z, 2D) or `moment = [mx, my, mz]` (3D).
#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum RawMoment {
    Scalar(f64),
    Vector(Vec<f64>),
}

/// `seismic = { kh = .., kv = .., direction = [..] }`: a pseudo-static
/// acceleration on every body with a density.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSeismic {
    pub(super) kh: Option<f64>,
    pub(super) kv: Option<f64>,
    pub(super) direction: Option<Vec<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSolver {
    pub(super) load_steps: Option<i64>,
    pub(super) max_iterations: Option<i64>,
    pub(super) max_cuts: Option<i64>,
    pub(super) rule: Option<StateRule>,
    pub(super) gravity_factors: Option<Vec<f64>>,
    pub(super) substructures: Option<i64>,
    pub(super) interface: Option<InterfaceSolver>,
    pub(super) initial_stage: Option<bool>,
    pub(super) rigid_fallback: Option<bool>,
    pub(super) augmented_lagrangian: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawProbe {
    pub(super) name: Option<String>,
    pub(super) from: Option<Vec<f64>>,
    pub(super) to: Option<Vec<f64>>,
    pub(super) points: Option<i64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAnalytic {
    pub(super) kind: Option<String>,
    pub(super) a: Option<f64>,
    pub(super) b: Option<f64>,
    pub(super) p: Option<f64>,
    pub(super) radius: Option<f64>,
    pub(super) thickness: Option<f64>,
    pub(super) k: Option<f64>,
    pub(super) slip: Option<String>,
    pub(super) lining: Option<String>,
    pub(super) ground: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOutput {
    pub(super) fields: Option<Vec<String>>,
    pub(super) frame: Option<RawFrame>,
    pub(super) pressure_window: Option<f64>,
    pub(super) colour_scale: Option<ColourScale>,
}

/// `frame = { from = [..], to = [..] }` or `frame = { bodies = [..] }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFrame {
    pub(super) from: Option<Vec<f64>>,
    pub(super) to: Option<Vec<f64>>,
    pub(super) bodies: Option<Vec<String>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSafety {
    pub(super) reduce: Option<Vec<String>>,
    pub(super) contacts: Option<Vec<String>>,
    pub(super) step: Option<f64>,
    pub(super) tolerance: Option<f64>,
    pub(super) max_factor: Option<f64>,
    pub(super) strength: Option<String>,
    pub(super) load: Option<Vec<String>>,
}

/// `[[sections]]`: a line or plane across members, or a beam or ring body
/// cut at stations.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSection {
    pub(super) name: Option<String>,
    pub(super) from: Option<Vec<f64>>,
    pub(super) to: Option<Vec<f64>>,
    pub(super) point: Option<Vec<f64>>,
    pub(super) normal: Option<Vec<f64>>,
    pub(super) bodies: Option<Vec<String>>,
    pub(super) beam: Option<String>,
    pub(super) ring: Option<String>,
    pub(super) stations: Option<i64>,
    pub(super) axis: Option<Vec<f64>>,
    pub(super) centre: Option<Vec<f64>>,
}
