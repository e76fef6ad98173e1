//! Closed-form solutions the tool checks itself against, and the checks a
//! scene's `[analytic]` asks for.
//!
//! The closed forms are displacement and stress fields ([`Exact`]) for the
//! error norms: Lamé's thick-walled cylinder ([`lame`]) and Einstein &
//! Schwartz's lined circular tunnel ([`tunnel`]). Beyond the norms, each
//! kind compares what its application is about ([`check`]): the paper's
//! Tables 1 and 2 for the cylinder ([`paper`]), the lining's thrust and
//! moment for the tunnel ([`lining`]). A check reads the solved run
//! ([`Solution`]) and returns report sections and summary entries
//! ([`Check`]), which the output writers include as they are.

pub mod lame;
pub mod lining;
pub mod paper;
pub mod tunnel;

pub use lame::Lame;
pub use tunnel::{LinedTunnel, TunnelBody, TunnelCoefficients, TunnelSlip};

use crate::contact::law::PairResult;
use crate::model::Model;
use crate::fem::Analysis;

/// Displacement and stress `[xx, yy, zz, xy, yz, xz]` of a closed form at a point.
pub trait Exact {
    fn displacement(&self, x: [f64; 3]) -> [f64; 3];
    fn stress(&self, x: [f64; 3]) -> [f64; 6];
}

/// `[analytic]`: a known solution used for error norms.
#[derive(Debug, Clone, PartialEq)]
pub enum Analytic {
    /// `kind = "lame_cylinder"`: thick-walled cylinder, inner radius `a`,
    /// outer radius `b`, internal pressure `p`, centred on the z axis.
    LameCylinder { a: f64, b: f64, p: f64 },
    /// `kind = "lined_tunnel"`: Einstein & Schwartz's circular lining in
    /// elastic ground under excavation loading (plane strain, centred on the
    /// origin, theta from +x):
    ///
    /// ```toml
    /// [analytic]
    /// kind = "lined_tunnel"
    /// radius = 5.0        # R: radius of the lining's middle surface
    /// thickness = 0.125   # t
    /// p = 0.6             # P: vertical far-field stress, compression positive
    /// k = 0.5             # K: horizontal / vertical far-field stress
    /// slip = "none"       # none (bonded, default) | full (frictionless)
    /// lining = "lining"   # [[bodies]] group of the lining (its material: E_l, nu_l)
    /// ground = "rock"     # [[bodies]] group of the ground (E, nu)
    /// ```
    ///
    /// The ground's `initial_stress`, when given, must be the far field
    /// `[-K P, -P, szz, 0]`; the lining starts stress-free.
    LinedTunnel(LinedTunnel),
}

/// The closed form a scene's `[analytic]` names, for the material of its
/// first body (the lined tunnel carries its own two materials).
pub fn exact(analytic: &Analytic, analysis: Analysis, e: f64, nu: f64) -> Box<dyn Exact> {
    match analytic {
        &Analytic::LameCylinder { a, b, p } => Box::new(Lame { a, b, p, e, nu, analysis }),
        Analytic::LinedTunnel(t) => Box::new(t.clone()),
    }
}

/// Lamé's cylinder of a `lame_cylinder` `[analytic]`, in the model's
/// analysis and with the material of its first body.
pub fn lame(analytic: &Analytic, model: &Model) -> Option<Lame> {
    match *analytic {
        Analytic::LameCylinder { a, b, p } => {
            let b0 = &model.bodies[0];
            Some(Lame { a, b, p, e: b0.e, nu: b0.nu, analysis: model.analysis })
        }
        Analytic::LinedTunnel(_) => None,
    }
}

/// What a check reads of a solved run (its last load step).
pub struct Solution<'a> {
    pub model: &'a Model,
    pub u: &'a [f64],
    /// The probe points inside the model: position and stress
    /// `[xx, yy, zz, xy, yz, xz]`, probe after probe.
    pub probed: Vec<([f64; 3], [f64; 6])>,
    /// The contact pairs' results (None without contact).
    pub pairs: Option<&'a [PairResult]>,
}

/// What a check adds to the results, beyond the error norms.
#[derive(Clone, Debug, Default)]
pub struct Check {
    /// Markdown sections for report.md.
    pub report: String,
    /// Entries of summary.json.
    pub summary: serde_json::Map<String, serde_json::Value>,
}

/// The check a scene's `[analytic]` asks for: the paper's tables for Lamé's
/// cylinder, the lining's thrust and moment for the lined tunnel.
pub fn check(analytic: &Analytic, sol: &Solution) -> Check {
    match analytic {
        Analytic::LameCylinder { .. } => lame(analytic, sol.model).map(|l| paper::check(&l, sol)).unwrap_or_default(),
        Analytic::LinedTunnel(t) => lining::check(t, sol),
    }
}
