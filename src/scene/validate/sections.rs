//! Checks of `[[sections]]`: a unique name and one way to cut — a line
//! `from`, `to` (2D) or a plane `point`, `normal` (3D) across members
//! (with the `bodies` it cuts), or a body named as a `beam` or a `ring`
//! cut at `stations` (with the beam's `axis`, the ring's `centre` and, in
//! 3D, its `axis`).

use std::collections::BTreeMap;

use super::checker::{fmt_vec, quoted_list, Checker, R};
use crate::recover::sections::{Cut, SectionSpec};
use crate::scene::raw::RawSection;
use crate::scene::{Analysis, BodySpec};

/// Stations of a beam or ring when `stations` is not given.
const DEFAULT_STATIONS: usize = 25;

impl Checker<'_> {
    pub(super) fn sections(
        &self,
        raw: Vec<RawSection>,
        analysis: Analysis,
        bodies: &[BodySpec],
    ) -> R<Vec<SectionSpec>> {
        let mut seen: BTreeMap<String, usize> = BTreeMap::new();
        let mut out = Vec::new();
        for (i, r) in raw.into_iter().enumerate() {
            let k = format!("sections[{i}]");
            let name = self.required(r.name.clone(), &format!("{k}.name"), "a name for the section")?;
            if name.trim().is_empty() || name.contains([',', '"', '\n', '/']) {
                return Err(self.bad(
                    format!("{k}.name"),
                    format!("{name:?}"),
                    "give the section a non-empty name without commas, quotes or slashes (it names rows of sections.csv and a picture).",
                ));
            }
            if let Some(j) = seen.insert(name.clone(), i) {
                return Err(self.bad(
                    format!("{k}.name"),
                    format!("{name:?}"),
                    format!("the name is already used by sections[{j}]; section names must be unique."),
                ));
            }
            if analysis == Analysis::Axisymmetric {
                return Err(self.err(k, "section forces are for plane and solid models: an axisymmetric cut is a cone or disc round the axis, whose forces this tool does not report; remove [[sections]]."));
            }
            let cut = self.cut(&k, r, analysis, bodies)?;
            out.push(SectionSpec { name, cut });
        }
        Ok(out)
    }

    /// The cut of `[[sections]]` entry `k`: a line (2D), a plane (3D), or
    /// stations along a beam or round a ring.
    fn cut(&self, k: &str, r: RawSection, analysis: Analysis, bodies: &[BodySpec]) -> R<Cut> {
        let solid = analysis == Analysis::Solid;
        let ways = [
            r.from.is_some() || r.to.is_some(),
            r.point.is_some() || r.normal.is_some(),
            r.beam.is_some(),
            r.ring.is_some(),
        ];
        if ways.iter().filter(|&&w| w).count() != 1 {
            let line = if solid {
                "point = [..] and normal = [..] (a plane)"
            } else {
                "from = [..] and to = [..] (a line across the member)"
            };
            return Err(self.err(k, format!("give one way to cut: {line}, beam = \"<body>\" (cut across its axis at `stations`), or ring = \"<body>\" (cut round its centre at `stations`).")));
        }
        if r.from.is_some() || r.to.is_some() {
            return self.line_cut(k, r, analysis, bodies);
        }
        if r.point.is_some() || r.normal.is_some() {
            return self.plane_cut(k, r, analysis, bodies);
        }
        self.round_cut(k, r, analysis, bodies)
    }

    /// A line across the member, `from` one end `to` the other (2D).
    fn line_cut(&self, k: &str, r: RawSection, analysis: Analysis, bodies: &[BodySpec]) -> R<Cut> {
        if analysis == Analysis::Solid {
            return Err(self.err(k, "a solid model is cut by a plane: give point = [x, y, z] and normal = [nx, ny, nz] instead of from and to."));
        }
        self.not_beam_keys(k, &r)?;
        let from = self.required(r.from, &format!("{k}.from"), "one end of the line [x, y]")?;
        let from = self.vec3(&from, &format!("{k}.from"), analysis)?;
        let to = self.required(r.to, &format!("{k}.to"), "the other end of the line [x, y]")?;
        let to = self.vec3(&to, &format!("{k}.to"), analysis)?;
        if from == to {
            return Err(self.bad(
                format!("{k}.to"),
                fmt_vec(&to[..2]),
                "the line has no length: give its two ends on either side of the member.",
            ));
        }
        Ok(Cut::Line { from, to, bodies: self.listed(k, r.bodies, bodies)? })
    }

    /// A plane through `point` with `normal` (3D).
    fn plane_cut(&self, k: &str, r: RawSection, analysis: Analysis, bodies: &[BodySpec]) -> R<Cut> {
        if analysis != Analysis::Solid {
            return Err(self.err(k, "a plane model is cut by a line: give from = [x, y] and to = [x, y] across the member instead of point and normal."));
        }
        self.not_beam_keys(k, &r)?;
        let point = self.required(r.point, &format!("{k}.point"), "a point of the plane [x, y, z]")?;
        let point = self.vec3(&point, &format!("{k}.point"), analysis)?;
        let normal = self.required(r.normal, &format!("{k}.normal"), "the plane's normal [nx, ny, nz]")?;
        let normal = self.direction(&normal, &format!("{k}.normal"), analysis)?;
        Ok(Cut::Plane { point, normal, bodies: self.listed(k, r.bodies, bodies)? })
    }

    /// Cuts at `stations` along a `beam`, or round a `ring`'s centre.
    fn round_cut(&self, k: &str, r: RawSection, analysis: Analysis, bodies: &[BodySpec]) -> R<Cut> {
        let solid = analysis == Analysis::Solid;
        self.only(k, r.bodies.is_some(), "bodies", "a line or plane (a beam or ring names its one body)")?;
        let axis = r.axis.as_ref().map(|a| self.direction(a, &format!("{k}.axis"), analysis)).transpose()?;
        if let Some(body) = r.beam {
            self.only(k, r.centre.is_some(), "centre", "ring")?;
            return Ok(Cut::Beam {
                body: self.body_of(k, "beam", body, bodies)?,
                stations: self.stations(k, r.stations)?,
                axis,
            });
        }
        let body = self.body_of(k, "ring", r.ring.unwrap_or_default(), bodies)?;
        let centre = match &r.centre {
            Some(c) => self.vec3(c, &format!("{k}.centre"), analysis)?,
            None => [0.0; 3],
        };
        let axis = match (axis, solid) {
            (Some(a), true) => a,
            (None, true) => return Err(self.err(format!("{k}.axis"), "missing; a ring in a solid model turns about an axis: give axis = [ax, ay, az] (the tunnel's direction).")),
            (Some(_), false) => return Err(self.err(format!("{k}.axis"), "a ring in a plane model turns about z; remove axis.")),
            (None, false) => [0.0, 0.0, 1.0],
        };
        Ok(Cut::Ring { body, stations: self.stations(k, r.stations)?, centre, axis })
    }

    /// A body group named at `k.key`: one of the `[[bodies]]`.
    fn body_of(&self, k: &str, key: &str, name: String, bodies: &[BodySpec]) -> R<String> {
        if bodies.iter().any(|b| b.group == name) {
            return Ok(name);
        }
        Err(self.bad(
            format!("{k}.{key}"),
            format!("{name:?}"),
            format!(
                "no [[bodies]] entry has this group; the bodies are {}.",
                quoted_list(bodies.iter().map(|b| &b.group))
            ),
        ))
    }

    /// The `bodies` a line or plane cuts (all when not given).
    fn listed(&self, k: &str, names: Option<Vec<String>>, bodies: &[BodySpec]) -> R<Vec<String>> {
        names.unwrap_or_default().into_iter().map(|n| self.body_of(k, "bodies", n, bodies)).collect()
    }

    /// `k.key`, when `present`, belongs to another way to cut (`with`).
    fn only(&self, k: &str, present: bool, key: &str, with: &str) -> R<()> {
        if present {
            return Err(self.err(format!("{k}.{key}"), format!("{key} goes with {with}; remove it.")));
        }
        Ok(())
    }

    /// A line or a plane takes none of a beam's or ring's keys.
    fn not_beam_keys(&self, k: &str, r: &RawSection) -> R<()> {
        self.only(k, r.stations.is_some(), "stations", "beam or ring")?;
        self.only(
            k,
            r.axis.is_some() || r.centre.is_some(),
            if r.axis.is_some() { "axis" } else { "centre" },
            "beam or ring",
        )
    }

    fn stations(&self, k: &str, n: Option<i64>) -> R<usize> {
        self.at_least(n, DEFAULT_STATIONS, 2, &format!("{k}.stations"), "the number of cuts along the body")
    }

    /// A direction: a vector of the analysis's components, not zero.
    fn direction(&self, v: &[f64], key: &str, analysis: Analysis) -> R<[f64; 3]> {
        let d = self.vec3(v, key, analysis)?;
        if d.iter().all(|&c| c == 0.0) {
            return Err(self.bad(key, fmt_vec(v), "a direction cannot be zero."));
        }
        Ok(d)
    }
}
