//! Checks of the entries that name the mesh's physical groups:
//! `[[bodies]]` (material, initial stress), `[[contacts]]` (one shared group
//! or two coincident ones, strengths), `[[supports]]` (fixed and prescribed
//! components) and `[[loads]]` (pressure, hydrostatic, traction, factors).
//! Whether the groups exist in the mesh is the model builder's check.

use std::collections::BTreeMap;

use super::checker::{quoted_list, Checker, R};
use crate::contact::law::Stiffness;
use crate::scene::raw::{RawBody, RawContact, RawLoad, RawMoment, RawPressure, RawSeismic, RawSupport};
use crate::scene::{
    Analysis, BodySpec, Contact, ContactGroups, ForceLoad, InitialStress, LoadKind, LoadSpec, Material, Solver,
    StateRule, Strength, SupportSpec,
};

impl Checker<'_> {
    pub(super) fn bodies(
        &self,
        raw: Vec<RawBody>,
        materials: &BTreeMap<String, Material>,
        analysis: Analysis,
    ) -> R<Vec<BodySpec>> {
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
            let group =
                self.group(b.group, &format!("{k}.group"), "the body's physical surface (2D) or volume (3D)")?;
            let material = self.required(b.material, &format!("{k}.material"), "a material name from [materials]")?;
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
            out.push(BodySpec { key: k, group, material: materials[&material], initial });
        }
        Ok(out)
    }

    pub(super) fn contacts(&self, raw: Vec<RawContact>, bodies: &[BodySpec]) -> R<Vec<Contact>> {
        let mut seen: BTreeMap<Vec<String>, usize> = BTreeMap::new();
        let mut out = Vec::new();
        for (i, mut c) in raw.into_iter().enumerate() {
            let k = format!("contacts[{i}]");
            let groups = match (c.group.take(), c.groups.take()) {
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
                return Err(self
                    .err(&gkey, format!("the same interface is already contacts[{j}]; define each interface once.")));
            }
            out.push(self.strength(&k, groups, c)?);
        }
        Ok(out)
    }

    /// The contact of entry `k` (`contacts[1]`, `joint_sets[0]`) on
    /// `groups`: its strength keys checked, defaults applied.
    pub(super) fn strength(&self, k: &str, groups: ContactGroups, c: RawContact) -> R<Contact> {
        // the water of a [[contacts]] entry or a joint is taken before and checked with the loads
        debug_assert!(c.water.is_none());
        let friction = self.non_negative(c.friction, &format!("{k}.friction"), "the friction coefficient")?;
        let cohesion = self.non_negative(c.cohesion, &format!("{k}.cohesion"), "the cohesion")?;
        let tensile_strength =
            self.non_negative(c.tensile_strength, &format!("{k}.tensile_strength"), "the tensile strength")?;
        let residual_cohesion =
            self.non_negative(c.residual_cohesion, &format!("{k}.residual_cohesion"), "the residual cohesion")?;
        if residual_cohesion > cohesion {
            return Err(self.bad(
                format!("{k}.residual_cohesion"),
                residual_cohesion,
                format!("the cohesion kept after opening cannot exceed the cohesion ({cohesion}); lower it or raise cohesion."),
            ));
        }
        let stiffness = self.stiffness(k, c.normal_stiffness, c.shear_stiffness)?;
        Ok(Contact {
            groups,
            strength: Strength { friction, cohesion, tensile_strength, residual_cohesion },
            slip: c.slip.unwrap_or_default(),
            stiffness,
            residual_given: c.residual_cohesion.is_some(),
            traction: c.traction.unwrap_or_default(),
            water: None,
        })
    }

    /// Joint stiffness on every contact or on none (`key` names contact
    /// i's entry), and with what the deforming joints' rule supports.
    pub(super) fn stiff_everywhere(
        &self,
        contacts: &[Contact],
        key: impl Fn(usize) -> String,
        solver: &Solver,
    ) -> R<()> {
        let Some(stiff) = contacts.iter().position(|c| c.stiffness.is_some()) else { return Ok(()) };
        if let Some(rigid) = contacts.iter().position(|c| c.stiffness.is_none()) {
            return Err(self.err(
                format!("{}.normal_stiffness", key(rigid)),
                format!("missing, while {} gives its joint a stiffness: give every contact and joint set normal_stiffness and shear_stiffness, or none (rigid joints and joints that deform cannot yet meet where joints cross).", key(stiff)),
            ));
        }
        if solver.rule == StateRule::Paper {
            return Err(self.bad("solver.rule", "\"paper\"", format!("the paper's rule has rigid joints only, and {} gives its joint a stiffness; use rule = \"robust\" (the default), or leave out the stiffness.", key(stiff))));
        }
        Ok(())
    }

    /// The joint stiffness of entry `k`: `normal_stiffness` and
    /// `shear_stiffness` together, each finite and > 0, or neither.
    fn stiffness(&self, k: &str, normal: Option<f64>, shear: Option<f64>) -> R<Option<Stiffness>> {
        const WHAT: &str = "a joint's stiffness is stress per unit relative displacement (MPa/m where stresses are in MPa and lengths in m; 3DEC's kn and ks)";
        let (normal, shear) = match (normal, shear) {
            (None, None) => return Ok(None),
            (Some(n), Some(s)) => (n, s),
            (Some(_), None) => {
                return Err(self.err(
                    format!("{k}.shear_stiffness"),
                    format!("missing beside normal_stiffness; give both ({WHAT}), or neither for a rigid joint."),
                ))
            }
            (None, Some(_)) => {
                return Err(self.err(
                    format!("{k}.normal_stiffness"),
                    format!("missing beside shear_stiffness; give both ({WHAT}), or neither for a rigid joint."),
                ))
            }
        };
        for (v, key) in [(normal, "normal_stiffness"), (shear, "shear_stiffness")] {
            if !(v.is_finite() && v > 0.0) {
                return Err(self.bad(
                    format!("{k}.{key}"),
                    v,
                    format!("must be > 0: {WHAT}; leave both keys out for a rigid joint."),
                ));
            }
        }
        Ok(Some(Stiffness { normal, shear }))
    }

    pub(super) fn support(&self, i: usize, s: RawSupport, analysis: Analysis) -> R<SupportSpec> {
        let k = format!("supports[{i}]");
        let group = self.group(s.group, &format!("{k}.group"), "a physical point, curve or surface")?;
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
                                if analysis == Analysis::Solid { " or \"z\"" } else { "" }
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
                    return Err(self.bad(key, shown, format!("{c:?} is listed twice; list each component once.")));
                }
                fix[d] = true;
            }
        }
        let mut prescribed = [None; 3];
        for (d, (name, v)) in [("ux", s.ux), ("uy", s.uy), ("uz", s.uz)].into_iter().enumerate() {
            let Some(v) = v else { continue };
            let key = format!("{k}.{name}");
            let v = self.finite(v, &key)?;
            if d == 2 && analysis != Analysis::Solid {
                return Err(self.bad(
                    key,
                    v,
                    format!("uz exists only in a solid analysis; a {analysis} analysis has ux and uy."),
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
        Ok(SupportSpec { key: k, group, fix, prescribed })
    }

    pub(super) fn load(&self, i: usize, l: RawLoad, analysis: Analysis) -> R<LoadSpec> {
        let k = format!("loads[{i}]");
        if let Some(sm) = l.seismic {
            let forced = l.force.is_some() || l.moment.is_some() || l.point.is_some();
            if l.group.is_some() || l.pressure.is_some() || l.traction.is_some() || forced {
                return Err(self.err(
                    k,
                    "a seismic load acts on every body with a density and names no group, pressure, traction or force: give it an entry of its own, [[loads]] seismic = { kh = .., kv = .. } with its factors.",
                ));
            }
            let kind = self.seismic(&format!("{k}.seismic"), sm, analysis)?;
            let factors = self.factors(&k, l.factors)?;
            return Ok(LoadSpec { key: k, group: String::new(), kind, factors });
        }
        let group = self.group(
            l.group,
            &format!("{k}.group"),
            "a physical curve (2D) or surface (3D); with force = [..], also a physical point or a body",
        )?;
        let forced = l.force.is_some() || l.moment.is_some();
        let has_point = l.point.is_some();
        let kind = match (l.pressure, l.traction) {
            (Some(_), Some(_)) => {
                return Err(self.err(k, "both pressure and traction are given; a load is one or the other: split it into two [[loads]] entries."))
            }
            (Some(_), None) | (None, Some(_)) if forced => {
                return Err(self.err(k, "a load is a pressure, a traction or a force (with its moment): split it into several [[loads]] entries."))
            }
            (None, None) if forced => LoadKind::Force(self.force_load(&k, l.force, l.moment, l.point, analysis)?),
            (None, None) => {
                return Err(self.err(
                    k,
                    format!("the load on {group:?} has no value; add pressure = P (positive presses into the body), traction = [tx, ty(, tz)], or force = [fx, fy(, fz)] (a point, a patch or a body)."),
                ))
            }
            (Some(RawPressure::Value(p)), None) => LoadKind::Pressure(self.finite(p, &format!("{k}.pressure"))?),
            (Some(RawPressure::Hydrostatic(h)), None) => {
                let unit_weight = self.finite(h.unit_weight, &format!("{k}.pressure.unit_weight"))?;
                if unit_weight < 0.0 {
                    return Err(self.bad(format!("{k}.pressure.unit_weight"), unit_weight, "the unit weight of the fluid must be >= 0."));
                }
                let surface = self.finite(h.surface, &format!("{k}.pressure.surface"))?;
                match (h.westergaard, h.base) {
                    (None, None) => LoadKind::Hydrostatic { surface, unit_weight },
                    (Some(kh), Some(base)) => {
                        let kh = self.finite(kh, &format!("{k}.pressure.westergaard"))?;
                        let base = self.finite(base, &format!("{k}.pressure.base"))?;
                        if base >= surface {
                            return Err(self.bad(format!("{k}.pressure.base"), base, format!("the reservoir's bottom must lie below its surface ({surface}).")));
                        }
                        LoadKind::Westergaard { kh, surface, base, unit_weight }
                    }
                    (Some(_), None) => return Err(self.err(format!("{k}.pressure.base"), "missing; Westergaard's pressure needs the reservoir's depth: give base = the height of its bottom (y in 2D, z in 3D).")),
                    (None, Some(_)) => return Err(self.err(format!("{k}.pressure.westergaard"), "missing; base goes with westergaard = kh (the horizontal seismic coefficient) for the hydrodynamic pressure; remove base for a hydrostatic one.")),
                }
            }
            (None, Some(t)) => LoadKind::Traction(self.vec3(&t, &format!("{k}.traction"), analysis)?),
        };
        if has_point && !forced {
            return Err(self.err(format!("{k}.point"), "point is where a force or moment acts: it goes with force = [..] or moment = .., not with a pressure or traction."));
        }
        let factors = self.factors(&k, l.factors)?;
        Ok(LoadSpec { key: k, group, kind, factors })
    }

    /// `factors = [..]` of a load: finite numbers (their count is checked with the load steps).
    fn factors(&self, k: &str, f: Option<Vec<f64>>) -> R<Option<Vec<f64>>> {
        f.map(|f| (f.iter().enumerate()).map(|(j, &v)| self.finite(v, &format!("{k}.factors[{j}]"))).collect())
            .transpose()
    }

    /// A seismic load: finite coefficients, a horizontal direction (x by default).
    fn seismic(&self, k: &str, s: RawSeismic, analysis: Analysis) -> R<LoadKind> {
        let kh = self.finite(s.kh.unwrap_or(0.0), &format!("{k}.kh"))?;
        let kv = self.finite(s.kv.unwrap_or(0.0), &format!("{k}.kv"))?;
        let vertical = if analysis == Analysis::Solid { 2 } else { 1 };
        let direction = match s.direction {
            None => [1.0, 0.0, 0.0],
            Some(d) => {
                let v = self.vec3(&d, &format!("{k}.direction"), analysis)?;
                let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                if v[vertical] != 0.0 || len == 0.0 {
                    return Err(self.bad(
                        format!("{k}.direction"),
                        super::fmt_vec(&d),
                        "the direction of kh must be horizontal and not zero (kv is the vertical part).",
                    ));
                }
                v.map(|c| c / len)
            }
        };
        Ok(LoadKind::Seismic { kh, kv, direction })
    }

    /// `force`, `moment` and `point` of a load: 2 or 3 components as the
    /// analysis has; the moment a number about z in 2D, three in 3D. Not in
    /// axisymmetry, where a point is a ring and a moment has no meaning.
    fn force_load(
        &self,
        k: &str,
        force: Option<Vec<f64>>,
        moment: Option<RawMoment>,
        point: Option<Vec<f64>>,
        analysis: Analysis,
    ) -> R<ForceLoad> {
        if analysis == Analysis::Axisymmetric {
            return Err(self.err(
                format!("{k}.force"),
                "an axisymmetric model has no points to load (a point is a ring round the axis): give a traction = [..] on a short curve instead.",
            ));
        }
        let force = match force {
            Some(f) => self.vec3(&f, &format!("{k}.force"), analysis)?,
            None => [0.0; 3],
        };
        let moment = match (moment, analysis.dim()) {
            (None, _) => [0.0; 3],
            (Some(RawMoment::Scalar(m)), 2) => [0.0, 0.0, self.finite(m, &format!("{k}.moment"))?],
            (Some(RawMoment::Vector(v)), 3) if v.len() == 3 => self.vec3(&v, &format!("{k}.moment"), analysis)?,
            (Some(RawMoment::Scalar(m)), _) => {
                return Err(self.bad(
                    format!("{k}.moment"),
                    m,
                    "a solid analysis needs the moment's 3 components [mx, my, mz].",
                ))
            }
            (Some(RawMoment::Vector(v)), _) => {
                let shown = format!("{v:?}");
                let what = if analysis.dim() == 2 {
                    format!("a {analysis} analysis turns about z only: give the moment as one number (counterclockwise positive).")
                } else {
                    "give the moment's 3 components [mx, my, mz].".to_string()
                };
                return Err(self.bad(format!("{k}.moment"), shown, what));
            }
        };
        let point = point.map(|p| self.vec3(&p, &format!("{k}.point"), analysis)).transpose()?;
        Ok(ForceLoad { force, moment, point })
    }
}
