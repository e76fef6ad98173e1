//! Checks of `[[joint_sets]]` and `[[joints]]`: the name (the contact
//! group the joint becomes), the orientation (dip in [0, 90] and dip
//! direction in [0, 360) in 3D, the trace's angle in 2D), the placement
//! (a set's spacing > 0 and offset, a single joint's point), the bodies it
//! cuts, persistence (size, gap, shape, centre), extent, snap, and every
//! `[[contacts]]` strength key and its `water`. Whether the planes cut anything is the
//! cutter's check (it needs the geometry).

use std::collections::BTreeMap;

use super::checker::{fmt_vec, quoted_list, Checker, R};
use crate::mesh::joints::{JointSpec, Orientation, Persistence, Placement, Shape};
use crate::scene::raw::{RawContact, RawFrame, RawJoint, RawWater, JOINT_KEYS};
use crate::scene::{Analysis, BodySpec, Contact, ContactGroups};

/// Which table an entry is in.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Set,
    Single,
}

impl Checker<'_> {
    /// The joints of both tables (sets first) and the contact each becomes.
    pub(super) fn joints(
        &self,
        sets: Vec<RawJoint>,
        singles: Vec<RawJoint>,
        bodies: &[BodySpec],
        contacts: &[Contact],
        analysis: Analysis,
    ) -> R<(Vec<JointSpec>, Vec<Contact>)> {
        let mut seen: BTreeMap<String, String> = BTreeMap::new();
        let mut out = (Vec::new(), Vec::new());
        let entries = sets
            .into_iter()
            .enumerate()
            .map(|(i, r)| (format!("joint_sets[{i}]"), Kind::Set, r))
            .chain(singles.into_iter().enumerate().map(|(i, r)| (format!("joints[{i}]"), Kind::Single, r)));
        for (k, kind, raw) in entries {
            let (spec, contact) = self.joint(&k, kind, raw, bodies, contacts, analysis)?;
            if let Some(other) = seen.insert(spec.name.clone(), k.clone()) {
                return Err(self.bad(
                    format!("{k}.name"),
                    format!("{:?}", spec.name),
                    format!("the name is already {other}'s; each joint's name is its contact group, so give every joint its own."),
                ));
            }
            out.0.push(spec);
            out.1.push(contact);
        }
        Ok(out)
    }

    /// The `water` of each joint, sets first, taken out of its entry with
    /// the key it had (`joint_sets[0].water`): checked once the loads are
    /// (a `face` names one), it acts on the joint's contact group.
    pub(super) fn joint_waters(
        &self,
        sets: &mut [RawJoint],
        singles: &mut [RawJoint],
    ) -> R<Vec<(String, Option<RawWater>)>> {
        let keys = (0..sets.len()).map(|i| format!("joint_sets[{i}].water"));
        let keys = keys.chain((0..singles.len()).map(|i| format!("joints[{i}].water")));
        keys.zip(sets.iter_mut().chain(singles.iter_mut()))
            .map(|(k, raw)| {
                let w =
                    raw.contact.remove("water").map(|v| v.try_into()).transpose().map_err(|e: toml::de::Error| {
                        self.err(&k, format!("{}.", e.message().trim().trim_end_matches('.')))
                    })?;
                Ok((k, w))
            })
            .collect()
    }

    fn joint(
        &self,
        k: &str,
        kind: Kind,
        mut raw: RawJoint,
        bodies: &[BodySpec],
        contacts: &[Contact],
        analysis: Analysis,
    ) -> R<(JointSpec, Contact)> {
        let name =
            self.group(raw.name.take(), &format!("{k}.name"), "the joint, the contact group its faces become")?;
        if let Some(j) = bodies.iter().position(|b| b.group == name) {
            return Err(self.bad(format!("{k}.name"), format!("{name:?}"), format!("{name:?} is the group of bodies[{j}]; name the joint after itself (its faces become a contact group of that name).")));
        }
        if let Some(j) = contacts.iter().position(|c| matches!(&c.groups, ContactGroups::Shared(g) if *g == name)) {
            return Err(self.bad(
                format!("{k}.name"),
                format!("{name:?}"),
                format!("{name:?} is already the group of contacts[{j}]; give the joint its own name."),
            ));
        }
        let rest = std::mem::take(&mut raw.contact);
        let contact: RawContact = toml::Value::Table(rest).try_into().map_err(|e: toml::de::Error| {
            self.err(k, format!("{}. Unknown keys are errors, not ignored: a joint takes {} and the keys of [[contacts]] listed above.", e.message().trim().trim_end_matches('.'), quoted_list(JOINT_KEYS)))
        })?;
        if contact.group.is_some() || contact.groups.is_some() {
            return Err(self.err(
                k,
                format!(
                    "a joint's faces become the contact group named by its name ({name:?}); remove group / groups."
                ),
            ));
        }
        let orientation = self.orientation(k, &raw, analysis)?;
        let placement = self.placement(k, kind, &raw, analysis)?;
        let cut = match &raw.bodies {
            None => bodies.iter().map(|b| b.group.clone()).collect(),
            Some(list) => self.joint_bodies(k, list, bodies)?,
        };
        let persistence = self.persistence(k, kind, &raw, analysis)?;
        let extent = raw.extent.take().map(|e| self.extent(k, e, analysis)).transpose()?;
        let snap = self.non_negative(raw.snap, &format!("{k}.snap"), "the snap distance")?;
        let contact = self.strength(k, ContactGroups::Shared(name.clone()), contact)?;
        let spec =
            JointSpec { key: k.to_string(), name, orientation, placement, bodies: cut, persistence, extent, snap };
        Ok((spec, contact))
    }

    fn orientation(&self, k: &str, raw: &RawJoint, analysis: Analysis) -> R<Orientation> {
        if analysis.dim() == 2 {
            if raw.dip.is_some() || raw.dip_direction.is_some() {
                return Err(self.err(k, format!("dip and dip_direction orient a plane in 3D; a {analysis} analysis cuts its bodies by traces: give angle (degrees from +x, counter-clockwise).")));
            }
            let a = self.required(raw.angle, &format!("{k}.angle"), "the trace's angle from +x, degrees")?;
            return Ok(Orientation::Angle(self.finite(a, &format!("{k}.angle"))?));
        }
        if raw.angle.is_some() {
            return Err(self.err(format!("{k}.angle"), "angle orients a trace in 2D; a plane in 3D has dip (degrees below horizontal) and dip_direction (degrees clockwise from north, +y)."));
        }
        let dip = self.required(raw.dip, &format!("{k}.dip"), "degrees below horizontal, 0 to 90")?;
        if !(dip.is_finite() && (0.0..=90.0).contains(&dip)) {
            return Err(self.bad(format!("{k}.dip"), dip, "the dip is the angle of the plane below horizontal, from 0 (horizontal) to 90 (vertical). A plane that seems to dip more dips 180 - dip the other way: give that, with the dip direction turned by 180."));
        }
        let dd = self.required(
            raw.dip_direction,
            &format!("{k}.dip_direction"),
            "degrees clockwise from north (+y), 0 to 360",
        )?;
        if !(dd.is_finite() && (0.0..360.0).contains(&dd)) {
            let hint = if dd.is_finite() {
                format!(" ({dd} is {} degrees)", crate::mesh::joints::trim(dd.rem_euclid(360.0)))
            } else {
                String::new()
            };
            return Err(self.bad(format!("{k}.dip_direction"), dd, format!("the dip direction is the azimuth of the dip vector, clockwise from north (+y): 0 <= dip_direction < 360{hint}.")));
        }
        Ok(Orientation::Dip { dip, dip_direction: dd })
    }

    fn placement(&self, k: &str, kind: Kind, raw: &RawJoint, analysis: Analysis) -> R<Placement> {
        match kind {
            Kind::Set => {
                if raw.point.is_some() {
                    return Err(self.err(format!("{k}.point"), "a point places one joint ([[joints]]); a set's planes are n . x = offset + k spacing: give spacing and offset."));
                }
                let spacing = self.required(
                    raw.spacing,
                    &format!("{k}.spacing"),
                    "the distance between the planes, along their normal",
                )?;
                if !(spacing.is_finite() && spacing > 0.0) {
                    return Err(self.bad(
                        format!("{k}.spacing"),
                        spacing,
                        "the spacing between the planes of a set must be a finite number > 0.",
                    ));
                }
                let offset = self.finite(raw.offset.unwrap_or(0.0), &format!("{k}.offset"))?;
                Ok(Placement::Set { spacing, offset })
            }
            Kind::Single => {
                if raw.spacing.is_some() || raw.offset.is_some() {
                    return Err(self.err(k, "spacing and offset place the planes of a set ([[joint_sets]]); a single joint goes through point = [x, y(, z)]."));
                }
                let p = self.required(
                    raw.point.clone(),
                    &format!("{k}.point"),
                    "a point of the joint's plane, [x, y(, z)]",
                )?;
                Ok(Placement::Single { point: self.vec3(&p, &format!("{k}.point"), analysis)? })
            }
        }
    }

    fn joint_bodies(&self, k: &str, list: &[String], bodies: &[BodySpec]) -> R<Vec<String>> {
        let key = format!("{k}.bodies");
        if list.is_empty() {
            return Err(self.bad(
                key,
                "[]",
                "name at least one body group the joint cuts (or leave bodies out: every body).",
            ));
        }
        for (i, n) in list.iter().enumerate() {
            if !bodies.iter().any(|b| &b.group == n) {
                return Err(self.bad(
                    format!("{key}[{i}]"),
                    format!("{n:?}"),
                    format!(
                        "no [[bodies]] entry has this group; the bodies are {}.",
                        quoted_list(bodies.iter().map(|b| &b.group))
                    ),
                ));
            }
            if list[..i].contains(n) {
                return Err(self.bad(format!("{key}[{i}]"), format!("{n:?}"), "listed twice; list each body once."));
            }
        }
        Ok(list.to_vec())
    }

    fn persistence(&self, k: &str, kind: Kind, raw: &RawJoint, analysis: Analysis) -> R<Option<Persistence>> {
        let Some(size) = raw.persistence else {
            if raw.gap.is_some() || raw.shape.is_some() || raw.centre.is_some() {
                return Err(self.err(k, "gap, shape and centre describe finite joints: give persistence (the size of each joint) too, or remove them."));
            }
            return Ok(None);
        };
        if !(size.is_finite() && size > 0.0) {
            return Err(self.bad(format!("{k}.persistence"), size, "the size of each joint (a trace's length in 2D, a square's side or a disc's diameter in 3D) must be a finite number > 0."));
        }
        let gap = match (kind, raw.gap) {
            (Kind::Single, Some(_)) => return Err(self.err(format!("{k}.gap"), "a single joint is one patch of size persistence round its point: gap (the rock bridge between the joints of a set) does not apply.")),
            (Kind::Single, None) => 0.0,
            (Kind::Set, None) => return Err(self.err(format!("{k}.gap"), "missing; a set of finite joints needs the rock bridge between them along the plane: add gap = ... (> 0).")),
            (Kind::Set, Some(g)) if g.is_finite() && g > 0.0 => g,
            (Kind::Set, Some(g)) => return Err(self.bad(format!("{k}.gap"), g, "the rock bridge between joints must be a finite number > 0 (leave persistence out for joints that run through).")),
        };
        let centre = match (&raw.centre, kind) {
            (Some(_), Kind::Single) => {
                return Err(self.err(format!("{k}.centre"), "a single joint is centred on its point; remove centre."))
            }
            (Some(c), Kind::Set) => Some(self.vec3(c, &format!("{k}.centre"), analysis)?),
            (None, _) => None,
        };
        Ok(Some(Persistence { size, gap, shape: raw.shape.unwrap_or(Shape::Square), centre }))
    }

    fn extent(&self, k: &str, e: RawFrame, analysis: Analysis) -> R<([f64; 3], [f64; 3])> {
        let key = format!("{k}.extent");
        let (Some(from), Some(to), None) = (e.from, e.to, e.bodies) else {
            return Err(self.err(key, "give the box the joint is limited to, extent = { from = [x0, y0(, z0)], to = [x1, y1(, z1)] }; to limit it to bodies, use bodies = [..]."));
        };
        let from = self.vec3(&from, &format!("{key}.from"), analysis)?;
        let to = self.vec3(&to, &format!("{key}.to"), analysis)?;
        if let Some(d) = (0..analysis.dim()).find(|&d| from[d] >= to[d]) {
            return Err(self.bad(
                format!("{key}.to"),
                fmt_vec(&to[..analysis.dim()]),
                format!(
                    "its {} must exceed from's ({}): the box runs from its lowest corner to its highest.",
                    ["x", "y", "z"][d],
                    from[d]
                ),
            ));
        }
        Ok((from, to))
    }
}
