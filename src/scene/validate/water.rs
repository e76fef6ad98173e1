//! Checks of a contact's `water = { .. }`: one way of giving the pressure
//! (a uniform `pressure`, a flat `level`, an inclined `plane`, a diagram
//! `levels = [[s, h], ..]` in order of s, or `upstream` / `downstream` heads
//! over the joint), a
//! unit weight >= 0, a horizontal `along`, a drain of efficiency in [0, 1]
//! on a diagram, a `face` that names a hydrostatic `[[loads]]` entry, and
//! one factor per load step.

use super::checker::{fmt_vec, Checker, R};
use crate::scene::raw::{RawDrain, RawWater};
use crate::scene::{Analysis, Drain, JointWater, Levels, LoadKind, LoadSpec, WaterFace, WaterPressure};

impl Checker<'_> {
    /// The water of a contact at key `k` (`contacts[i].water`), with the
    /// scene's `loads` (for `face`) and `steps` load steps.
    pub(super) fn water(
        &self,
        k: &str,
        w: RawWater,
        loads: &[LoadSpec],
        analysis: Analysis,
        steps: usize,
    ) -> R<JointWater> {
        let face = w.face.as_deref().map(|f| self.water_face(k, f, loads)).transpose()?;
        let forms =
            [w.pressure.is_some(), w.level.is_some(), w.levels.is_some(), w.downstream.is_some(), w.plane.is_some()];
        if forms.iter().filter(|&&f| f).count() > 1 {
            return Err(self.err(
                k,
                "give the water pressure one way: pressure = u (uniform), level = h (a flat piezometric level), plane = [h0, dh/dx(, dh/dy)] (an inclined one), levels = [[s, h], ..] (a diagram along the flow) or upstream = h1 with downstream = h2 (from one end of the joint to the other), not several.",
            ));
        }
        let pressure = if let Some(u) = w.pressure {
            let u = self.finite(u, &format!("{k}.pressure"))?;
            if u < 0.0 {
                return Err(self.bad(
                    format!("{k}.pressure"),
                    u,
                    "water pressure pushes the faces of the joint apart and must be >= 0.",
                ));
            }
            for (given, name) in [
                (w.unit_weight.is_some(), "unit_weight"),
                (w.along.is_some(), "along"),
                (w.drain.is_some(), "drain"),
                (w.upstream.is_some(), "upstream"),
            ] {
                if given {
                    return Err(self.err(format!("{k}.{name}"), "a uniform pressure takes no unit weight, direction, drain or heads; remove it, or give the water as a level instead of pressure."));
                }
            }
            WaterPressure::Uniform(u)
        } else {
            let unit_weight = match (w.unit_weight, &face) {
                (Some(g), _) => self.unit_weight(&format!("{k}.unit_weight"), g)?,
                (None, Some(f)) => f.unit_weight,
                (None, None) => {
                    return Err(self.err(
                        format!("{k}.unit_weight"),
                        "missing; add `unit_weight` (the water's unit weight in the scene's units, 0.00981 MN/m3 or 9.81 kN/m3), or `face` naming the hydrostatic load whose water this is.",
                    ))
                }
            };
            let along = self.along(&format!("{k}.along"), w.along.as_deref(), analysis)?;
            let levels = self.levels(k, &w, face.as_ref(), analysis)?;
            let drain = w.drain.map(|d| self.drain(&format!("{k}.drain"), d, &levels)).transpose()?;
            WaterPressure::Level { unit_weight, along, levels, drain }
        };
        let factors = match w.factors {
            None => None,
            Some(f) => {
                let f = (f.iter().enumerate())
                    .map(|(j, &v)| self.finite(v, &format!("{k}.factors[{j}]")))
                    .collect::<R<Vec<f64>>>()?;
                if f.len() != steps {
                    return Err(self.err(
                        format!("{k}.factors"),
                        format!(
                            "has {} value(s) but [solver] load_steps = {steps}: give one load factor per step.",
                            f.len()
                        ),
                    ));
                }
                Some(f)
            }
        };
        Ok(JointWater { pressure, face, factors })
    }

    /// The `[[loads]]` entry on group `face` with a hydrostatic pressure.
    fn water_face(&self, k: &str, face: &str, loads: &[LoadSpec]) -> R<WaterFace> {
        let key = format!("{k}.face");
        let on = loads.iter().enumerate().filter(|(_, l)| l.group == face);
        let mut any = false;
        for (i, l) in on {
            any = true;
            if let LoadKind::Hydrostatic { surface, unit_weight } = l.kind {
                return Ok(WaterFace { group: face.to_string(), load: i, surface, unit_weight });
            }
        }
        let why = if any {
            "the [[loads]] entries on that group are not hydrostatic; give one pressure = { surface = .., unit_weight = .. }, the free water the joint's cracks fill with"
        } else {
            "no [[loads]] entry is on that group; name the face loaded by the free water (pressure = { surface, unit_weight }) that the joint's cracks open from: a dam's upstream face, a slope's tension crack"
        };
        Err(self.bad(key, format!("{face:?}"), format!("{why}.")))
    }

    /// A unit weight: finite and >= 0.
    fn unit_weight(&self, key: &str, g: f64) -> R<f64> {
        let g = self.finite(g, key)?;
        if g < 0.0 {
            return Err(self.bad(
                key,
                g,
                "the unit weight of water must be >= 0: the pressure grows with depth below the level. For a pressure that rises along the joint give the levels along the flow (levels = [[s, h], ..] or upstream / downstream).",
            ));
        }
        Ok(g)
    }

    /// The horizontal direction of the flow, unit length (default x).
    fn along(&self, key: &str, v: Option<&[f64]>, analysis: Analysis) -> R<[f64; 3]> {
        let Some(v) = v else { return Ok([1.0, 0.0, 0.0]) };
        let a = self.vec3(v, key, analysis)?;
        let vertical = if analysis == Analysis::Solid { 2 } else { 1 };
        let len = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        if a[vertical] != 0.0 || len == 0.0 {
            let want = if analysis == Analysis::Solid { "[dx, dy, 0]" } else { "[dx, 0]" };
            return Err(self.bad(
                key,
                fmt_vec(v),
                format!("the direction in which s = x . along is measured must be horizontal and not zero: {want}."),
            ));
        }
        Ok(a.map(|x| x / len))
    }

    /// The piezometric level: `level`, `levels` or the heads at the ends.
    fn levels(&self, k: &str, w: &RawWater, face: Option<&WaterFace>, analysis: Analysis) -> R<Levels> {
        if let Some(h) = w.level {
            return Ok(Levels::Flat(self.finite(h, &format!("{k}.level"))?));
        }
        if let Some(p) = &w.plane {
            let key = format!("{k}.plane");
            let want = if analysis == Analysis::Solid { 3 } else { 2 };
            if p.len() != want {
                let form = if want == 3 {
                    "[h0, dh/dx, dh/dy]: h = h0 + x dh/dx + y dh/dy"
                } else {
                    "[h0, dh/dx]: h = h0 + x dh/dx"
                };
                return Err(self.bad(key, fmt_vec(p), format!("give the inclined level as {form}.")));
            }
            let mut c = [0.0; 3];
            for (j, v) in p.iter().enumerate() {
                c[j] = self.finite(*v, &format!("{key}[{j}]"))?;
            }
            return Ok(Levels::Plane(c));
        }
        if let Some(rows) = &w.levels {
            let key = format!("{k}.levels");
            if rows.is_empty() {
                return Err(
                    self.err(key, "is empty; give points [s, h] along the flow (s = x . along), in order of s.")
                );
            }
            let mut table: Vec<[f64; 2]> = Vec::with_capacity(rows.len());
            for (j, r) in rows.iter().enumerate() {
                let &[s, h] = r.as_slice() else {
                    return Err(self.bad(
                        format!("{key}[{j}]"),
                        fmt_vec(r),
                        "give each point as [s, h]: the position along the flow and the piezometric level there.",
                    ));
                };
                let (s, h) = (self.finite(s, &format!("{key}[{j}][0]"))?, self.finite(h, &format!("{key}[{j}][1]"))?);
                if let Some(prev) = table.last() {
                    if s <= prev[0] {
                        return Err(self.bad(
                            format!("{key}[{j}]"),
                            fmt_vec(r),
                            format!("the points are out of order: s = {s} does not follow s = {} of the point before; list them in increasing s (s = x . along), each position once.", prev[0]),
                        ));
                    }
                }
                table.push([s, h]);
            }
            return Ok(Levels::Table(table));
        }
        match (w.upstream, w.downstream) {
            (up, Some(down)) => {
                let upstream = match (up, face) {
                    (Some(u), _) => self.finite(u, &format!("{k}.upstream"))?,
                    (None, Some(f)) => f.surface,
                    (None, None) => {
                        return Err(self.err(
                            format!("{k}.upstream"),
                            "missing; an uplift diagram needs the level at the upstream end (the reservoir's), or `face` naming the hydrostatic load it comes from.",
                        ))
                    }
                };
                Ok(Levels::Ends { upstream, downstream: self.finite(down, &format!("{k}.downstream"))? })
            }
            (Some(_), None) => Err(self.err(
                format!("{k}.downstream"),
                "missing; an uplift diagram from upstream to downstream needs the level at the downstream end (the tailwater, or the toe's height for no pressure there).",
            )),
            (None, None) => Err(self.err(
                k,
                "no water pressure given; add pressure = u (uniform), level = h (a flat piezometric level), plane = [h0, dh/dx(, dh/dy)] (an inclined one), levels = [[s, h], ..] (a diagram along the flow) or upstream = h1 with downstream = h2, with unit_weight.",
            )),
        }
    }

    /// A drain line on a diagram.
    fn drain(&self, key: &str, d: RawDrain, levels: &Levels) -> R<Drain> {
        if let Levels::Flat(_) | Levels::Plane(_) = levels {
            return Err(self.err(
                key,
                "a drain lowers an uplift diagram at its line; a level (flat or a plane) has none: give the diagram as levels = [[s, h], ..] or upstream / downstream.",
            ));
        }
        let at = self.finite(
            self.required(d.at, &format!("{key}.at"), "the drain line's position s = x . along")?,
            &format!("{key}.at"),
        )?;
        let e = self.required(d.efficiency, &format!("{key}.efficiency"), "the drains' efficiency, 0 to 1")?;
        let e = self.finite(e, &format!("{key}.efficiency"))?;
        if !(0.0..=1.0).contains(&e) {
            return Err(self.bad(
                format!("{key}.efficiency"),
                e,
                "the drains' efficiency is a fraction from 0 (no effect) to 1 (the head at the drain line down to the downstream level); USACE takes 0.25 to 0.5, USBR 2/3.",
            ));
        }
        Ok(Drain { at, efficiency: e })
    }
}
