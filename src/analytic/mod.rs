//! Closed-form solutions the tool checks itself against: Lamé's
//! thick-walled cylinder ([`lame`]) and Einstein & Schwartz's lined circular
//! tunnel ([`tunnel`]), each a displacement and stress field ([`Exact`]) for
//! the error norms of a scene's `[analytic]`.

pub mod lame;
pub mod tunnel;

pub use lame::Lame;
pub use tunnel::{LinedTunnel, TunnelBody, TunnelCoefficients, TunnelSlip};

use crate::scene::{Analysis, Analytic};

/// Displacement and stress `[xx, yy, zz, xy, yz, xz]` of a closed form at a point.
pub trait Exact {
    fn displacement(&self, x: [f64; 3]) -> [f64; 3];
    fn stress(&self, x: [f64; 3]) -> [f64; 6];
}

/// The closed form a scene's `[analytic]` names, for the material of its
/// first body (the lined tunnel carries its own two materials).
pub fn exact(analytic: &Analytic, analysis: Analysis, e: f64, nu: f64) -> Box<dyn Exact> {
    match analytic {
        &Analytic::LameCylinder { a, b, p } => Box::new(Lame { a, b, p, e, nu, analysis }),
        Analytic::LinedTunnel(t) => Box::new(t.clone()),
    }
}
