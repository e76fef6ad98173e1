//! What the writers print of the scene, as data ([`About`]): its file,
//! name and title, the analysis, the `[output]` options, the joint sets,
//! the `[safety]` options, each contact's strength and slip law, the loads'
//! names, the factors each load takes at each step ([`Applied`]) and the
//! warnings. The driver fills it once from the scene; the writers read it
//! and never the scene. The `[output]` and `[safety]` tables' types live
//! here, and the scene speaks them.

use std::path::PathBuf;

use crate::analytic::Analytic;
use crate::contact::law::{Stiffness, Strength};
use crate::contact::safety::{Reduce, Steps, Strengths};
use crate::contact::SlipLaw;
use crate::fem::Analysis;
use crate::mesh::joints::JointSpec;
use crate::recover::Probe;

/// What the writers need of the scene, made by the driver.
#[derive(Clone, Debug)]
pub struct About {
    /// The scene file (messages and summary.json name it).
    pub path: PathBuf,
    /// The result files' stem and the pictures' title.
    pub name: String,
    pub title: String,
    pub analysis: Analysis,
    /// The out-of-plane thickness (plane analyses).
    pub thickness: f64,
    pub output: Output,
    /// The joint sets cut into the blocks (`[[joints]]`).
    pub joints: Vec<JointSpec>,
    pub probes: Vec<Probe>,
    /// The closed form the run is checked against (`[analytic]`).
    pub analytic: Option<Analytic>,
    /// `[safety]`, when the run searched for a factor of safety.
    pub safety: Option<Safety>,
    /// Each `[[contacts]]` entry's law, in scene order.
    pub contacts: Vec<ContactLaw>,
    /// Each `[[loads]]` entry's group, in scene order.
    pub loads: Vec<String>,
    /// The load-step table's columns.
    pub applied: Vec<Applied>,
    /// The time of each load step in the `.pvd` collections.
    pub step_times: Vec<f64>,
    /// What the scene and the model make legal but a user may not mean,
    /// one paragraph each, the scene file in front.
    pub warnings: Vec<String>,
}

/// A `[[contacts]]` entry's strength and slip law, whether the scene
/// gave its `residual_cohesion`, and its stiffness where it deforms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactLaw {
    pub strength: Strength,
    pub slip: SlipLaw,
    pub residual_given: bool,
    pub stiffness: Option<Stiffness>,
}

/// One column of the load-step table: the loads that share a sequence of
/// factors, and that sequence (one per step).
#[derive(Clone, Debug, PartialEq)]
pub struct Applied {
    pub name: String,
    pub factors: Vec<f64>,
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

/// The loads a load factor search raises (`[safety] load = [..]`): the
/// `[[loads]]` entries (indices) and gravity.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Raise {
    pub loads: Vec<usize>,
    pub gravity: bool,
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
