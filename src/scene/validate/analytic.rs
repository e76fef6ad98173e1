//! Checks of `[analytic]`: the closed form a scene compares itself with
//! (Lamé's cylinder, Einstein & Schwartz's lined tunnel), its keys by kind
//! (keys of another kind are errors), and for the lined tunnel the bodies it
//! names and the far field their initial stress must agree with.

use super::checker::{fmt_vec, quoted_list, Checker, R};
use crate::scene::raw::RawAnalytic;
use crate::scene::{Analysis, Analytic, BodySpec, InitialStress};

/// The `kind` values `[analytic]` accepts.
const ANALYTIC_KINDS: &[&str] = &["lame_cylinder", "lined_tunnel"];

impl Checker<'_> {
    pub(super) fn analytic(&self, a: RawAnalytic, analysis: Analysis, bodies: &[BodySpec]) -> R<Analytic> {
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
            "lined_tunnel" => self.lined_tunnel(a, analysis, bodies).map(Analytic::LinedTunnel),
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
    fn lined_tunnel(&self, a: RawAnalytic, analysis: Analysis, bodies: &[BodySpec]) -> R<crate::analytic::LinedTunnel> {
        use crate::analytic::{LinedTunnel, TunnelSlip};
        if analysis != Analysis::PlaneStrain {
            return Err(self.bad(
                "analytic.kind",
                "\"lined_tunnel\"",
                format!("Einstein & Schwartz's lined tunnel is a plane strain solution, but analysis = \"{analysis}\"; use analysis = \"plane_strain\"."),
            ));
        }
        let (radius, thickness) = self.tunnel_size(&a)?;
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
                return Err(self.bad(
                    "analytic.slip",
                    format!("{other:?}"),
                    "use \"none\" (lining and ground bonded) or \"full\" (frictionless interface).",
                ))
            }
        };
        let (il, lining) = self.tunnel_body("lining", a.lining, "the lining's [[bodies]] group", bodies)?;
        let (ig, ground) = self.tunnel_body("ground", a.ground, "the ground's [[bodies]] group", bodies)?;
        if il == ig {
            return Err(self.bad(
                "analytic.ground",
                format!("{:?}", ground.group),
                "the ground must be another body than the lining.",
            ));
        }
        if bodies[il].initial.is_some() {
            return Err(self.err(
                format!("bodies[{il}].initial_stress"),
                "the lined tunnel's lining is installed stress-free (excavation loading): remove its initial stress.",
            ));
        }
        let szz0 = self.far_field_szz(ig, &bodies[ig], p, k)?;
        Ok(LinedTunnel { radius, thickness, p, k, slip, lining, ground, szz0 })
    }

    /// The lining's radius (of its middle surface) and thickness.
    fn tunnel_size(&self, a: &RawAnalytic) -> R<(f64, f64)> {
        let radius = self.required(a.radius, "analytic.radius", "the radius of the lining's middle surface")?;
        let radius = self.finite(radius, "analytic.radius")?;
        if radius <= 0.0 {
            return Err(self.bad("analytic.radius", radius, "the lining's radius must be > 0."));
        }
        let thickness = self.required(a.thickness, "analytic.thickness", "the lining's thickness")?;
        let thickness = self.finite(thickness, "analytic.thickness")?;
        if thickness <= 0.0 || thickness >= 2.0 * radius {
            return Err(self.bad(
                "analytic.thickness",
                thickness,
                format!("the lining's thickness must be > 0 and < 2 radius = {}.", 2.0 * radius),
            ));
        }
        Ok((radius, thickness))
    }

    /// The `[[bodies]]` entry `analytic.key` names (its index) and its
    /// elastic constants.
    fn tunnel_body(
        &self,
        key: &str,
        group: Option<String>,
        what: &str,
        bodies: &[BodySpec],
    ) -> R<(usize, crate::analytic::TunnelBody)> {
        use crate::analytic::TunnelBody;
        let key = format!("analytic.{key}");
        let g = self.group(group, &key, what)?;
        let i = bodies.iter().position(|b| b.group == g).ok_or_else(|| {
            self.bad(
                &key,
                format!("{g:?}"),
                format!(
                    "no [[bodies]] entry has this group; the bodies are {}.",
                    quoted_list(bodies.iter().map(|b| b.group.as_str()))
                ),
            )
        })?;
        let m = bodies[i].material;
        Ok((i, TunnelBody { group: g, e: m.e, nu: m.nu }))
    }

    /// The ground's out-of-plane far-field stress szz: its uniform initial
    /// stress must be the far field [-K P, -P, szz, 0] of `[analytic]`.
    fn far_field_szz(&self, ig: usize, ground: &BodySpec, p: f64, k: f64) -> R<f64> {
        Ok(match ground.initial {
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
        })
    }
}
