//! Closed-form solutions the tool checks itself against, and the checks a
//! scene's `[analytic]` asks for.
//!
//! The closed forms are displacement and stress fields ([`Exact`]) for the
//! error norms: Lamé's thick-walled cylinder ([`mod@lame`]) and Einstein &
//! Schwartz's lined circular tunnel ([`tunnel`]). Beyond the norms, each
//! kind compares what its application is about ([`check`]): the paper's
//! Tables 1 and 2 for the cylinder ([`paper_tables`]), the lining's thrust and
//! moment for the tunnel ([`lining`]). A check reads the solved run
//! ([`Solution`]) and returns numbers ([`Check`]); `output::closed_form`
//! formats them for report.md and summary.json.

pub mod exact;
pub mod lame;
pub mod lining;
pub mod paper_tables;
pub mod solution;
pub mod tunnel;

pub use exact::Exact;
pub use lame::Lame;
pub use solution::Solution;
pub use tunnel::{LinedTunnel, TunnelBody, TunnelCoefficients, TunnelSlip};

use crate::model::Model;

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

/// The closed form a scene's `[analytic]` names, body by body (indexed as
/// `model.bodies`), each in its own material: Lamé's cylinder with the
/// body's E and nu; the lined tunnel carries its own two materials (lining
/// and ground, told apart by radius) for every body.
///
/// Lamé's formula is for one material. Where the bodies share it, as in
/// every shipped scene, each body's closed form is the same field. Where
/// they differ, each body is compared with Lamé's cylinder of its own
/// material: that is the solution where the bodies do not constrain each
/// other's radial displacement (sectors free to slide along radial cuts;
/// the stresses of Lamé's cylinder do not depend on E), not for bodies
/// bonded across a material change (the compound cylinder): the report
/// says so ([`paper_tables::materials_differ`]).
pub fn exact(analytic: &Analytic, model: &Model) -> Vec<Box<dyn Exact>> {
    model
        .bodies
        .iter()
        .map(|body| -> Box<dyn Exact> {
            match analytic {
                &Analytic::LameCylinder { a, b, p } => {
                    Box::new(Lame { a, b, p, e: body.material.e, nu: body.material.nu, analysis: model.analysis })
                }
                Analytic::LinedTunnel(t) => Box::new(t.clone()),
            }
        })
        .collect()
}

/// Lamé's cylinder of a `lame_cylinder` `[analytic]`, in the model's
/// analysis and with the material of its first body (the tables of
/// [`paper_tables`] use its stresses, which do not depend on the material but for
/// the axial one).
pub fn lame(analytic: &Analytic, model: &Model) -> Option<Lame> {
    match *analytic {
        Analytic::LameCylinder { a, b, p } => {
            let b0 = &model.bodies[0];
            Some(Lame { a, b, p, e: b0.material.e, nu: b0.material.nu, analysis: model.analysis })
        }
        Analytic::LinedTunnel(_) => None,
    }
}

/// What a check adds to the results, beyond the error norms: numbers,
/// which `output::closed_form` formats.
#[derive(Clone, Debug, Default)]
pub enum Check {
    /// No `[analytic]` check (or no result files written).
    #[default]
    None,
    /// The paper's tables of Lamé's cylinder for this run.
    Cylinder(paper_tables::CylinderCheck),
    /// The lining's thrust and moment against Einstein & Schwartz.
    Tunnel(lining::TunnelCheck),
}

/// The check a scene's `[analytic]` asks for: the paper's tables for Lamé's
/// cylinder, the lining's thrust and moment for the lined tunnel.
pub fn check(analytic: &Analytic, sol: &Solution) -> Check {
    match analytic {
        Analytic::LameCylinder { .. } => {
            lame(analytic, sol.model).map_or(Check::None, |l| Check::Cylinder(paper_tables::check(l, sol)))
        }
        Analytic::LinedTunnel(t) => Check::Tunnel(lining::check(t, sol)),
    }
}
