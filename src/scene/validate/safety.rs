//! Checks of `[safety]`: what is reduced (`reduce`, names of the contact
//! strength keys), which contacts (`contacts`, their group names; either
//! group of a `groups = [a, b]` entry names it), which strength the pairs
//! keep once they crack (`strength`, peak or residual), or instead the
//! loads a load factor search raises (`load`, `[[loads]]` groups and
//! "gravity"), and the search's `step`, `tolerance` and `max_factor`. A
//! search that would reduce nothing (every chosen parameter zero on every
//! chosen contact) or raise nothing is an error: its F would be the bound
//! whatever the scene.

use super::checker::{quoted_list, Checker, R};
use crate::scene::raw::RawSafety;
use crate::scene::{Contact, ContactGroups, LoadSpec, Raise, Reduce, Safety, Steps, Strengths};

/// The names `reduce` accepts.
const REDUCIBLE: &[&str] = &["friction", "cohesion", "tensile_strength"];

impl Checker<'_> {
    pub(in crate::scene) fn safety(
        &self,
        s: RawSafety,
        contacts: &[Contact],
        loads: &[LoadSpec],
        gravity: [f64; 3],
    ) -> R<Safety> {
        if contacts.is_empty() {
            return Err(self.err("safety", "the safety search divides the strength of the [[contacts]] by a factor, and this scene has none; add the contacts whose sliding you want to check, or remove [safety]."));
        }
        let defaults = Safety::all(contacts.len());
        let (raise, strengths, strength_given) = self.search_kind(&s, loads, gravity)?;
        let reduce = match s.reduce {
            None => defaults.reduce,
            Some(names) => self.reduce(&names)?,
        };
        let chosen = match s.contacts {
            None => defaults.contacts,
            Some(names) => self.chosen(&names, contacts)?,
        };
        let step = self.positive(
            s.step,
            defaults.steps.step,
            "safety.step",
            "the increase of F from trial to trial must be a finite number > 0.",
        )?;
        let tolerance = self.positive(
            s.tolerance,
            defaults.steps.tolerance,
            "safety.tolerance",
            "the relative tolerance on F must be a finite number > 0.",
        )?;
        if tolerance >= 1.0 {
            return Err(self.bad(
                "safety.tolerance",
                tolerance,
                "the relative tolerance on F must be below 1 (F is found within tolerance × F; 0.001 by default).",
            ));
        }
        let max_factor = self.positive(
            s.max_factor,
            defaults.steps.max_factor,
            "safety.max_factor",
            "the largest F tried must be a finite number > 1.",
        )?;
        if max_factor <= 1.0 {
            return Err(self.bad(
                "safety.max_factor",
                max_factor,
                "the largest F tried must exceed 1 (F = 1 is the scene as given; 10 by default).",
            ));
        }
        let reduces = |c: &Contact| {
            let s = &c.strength;
            (reduce.friction && s.friction > 0.0)
                || (reduce.cohesion && (s.cohesion > 0.0 || s.residual_cohesion > 0.0))
                || (reduce.tensile_strength && s.tensile_strength > 0.0)
        };
        if raise.is_none() && !chosen.iter().any(|&i| reduces(&contacts[i])) {
            return Err(self.err(
                "safety",
                format!("reduces nothing: {} of the chosen contacts ({}) is zero everywhere, so no factor would change the scene. Reduce a parameter they have (safety.reduce), or choose other contacts (safety.contacts).", reduce.names().join(", "), quoted_list(chosen.iter().map(|&i| name(&contacts[i])))),
            ));
        }
        let steps = Steps { step, tolerance, max_factor };
        Ok(Safety { reduce, contacts: chosen, strengths, strength_given, raise, steps })
    }

    /// What the search varies: the loads of `load` (which excludes the
    /// strength keys), or the strength, peak or residual.
    fn search_kind(&self, s: &RawSafety, loads: &[LoadSpec], gravity: [f64; 3]) -> R<(Option<Raise>, Strengths, bool)> {
        let raise = match &s.load {
            None => None,
            Some(names) => {
                for (key, given) in [
                    ("reduce", s.reduce.is_some()),
                    ("contacts", s.contacts.is_some()),
                    ("strength", s.strength.is_some()),
                ] {
                    if given {
                        return Err(self.err(format!("safety.{key}"), "belongs to a search that divides the strength of the contacts, and this [safety] raises loads (safety.load): a search does one or the other. Remove one of them (run the other search from a copy of the scene)."));
                    }
                }
                Some(self.raise(names, loads, gravity)?)
            }
        };
        let (strengths, strength_given) = match s.strength.as_deref() {
            None => (Strengths::Peak, false),
            Some("peak") => (Strengths::Peak, true),
            Some("residual") => (Strengths::Residual, true),
            Some(other) => return Err(self.bad("safety.strength", format!("{other:?}"), "use \"peak\" (each joint keeps its peak cohesion over the whole sliding surface, as limit equilibrium assumes; the default) or \"residual\" (a pair that slips or opens keeps only its residual_cohesion, as in the load steps).")),
        };
        Ok((raise, strengths, strength_given))
    }

    /// `load = [..]`: `[[loads]]` groups and "gravity", each once, at least
    /// one that loads something.
    fn raise(&self, names: &[String], loads: &[LoadSpec], gravity: [f64; 3]) -> R<Raise> {
        let known = || quoted_list(loads.iter().map(|l| l.group.as_str()).chain(["gravity"]));
        if names.is_empty() {
            return Err(
                self.err("safety.load", format!("is empty: name the loads the search raises, any of {}.", known()))
            );
        }
        let mut raise = Raise { loads: Vec::new(), gravity: false };
        for (j, n) in names.iter().enumerate() {
            let key = format!("safety.load[{j}]");
            let twice = || self.bad(&key, format!("{n:?}"), "listed twice; give each load once.");
            if n == "gravity" {
                if raise.gravity {
                    return Err(twice());
                }
                if gravity.iter().all(|&g| g == 0.0) {
                    return Err(self.bad(
                        &key,
                        format!("{n:?}"),
                        "the scene has no gravity (top-level gravity = [..]) to raise.",
                    ));
                }
                raise.gravity = true;
                continue;
            }
            let Some(i) = loads.iter().position(|l| &l.group == n) else {
                return Err(self.bad(
                    &key,
                    format!("{n:?}"),
                    format!("is not the group of a [[loads]] entry; the loads are {}.", known()),
                ));
            };
            if raise.loads.contains(&i) {
                return Err(twice());
            }
            raise.loads.push(i);
        }
        raise.loads.sort_unstable();
        Ok(raise)
    }

    /// `reduce = [..]`: a non-empty list of the strength keys, each once.
    fn reduce(&self, names: &[String]) -> R<Reduce> {
        if names.is_empty() {
            return Err(self.err(
                "safety.reduce",
                format!(
                    "is empty: list what is divided by F, any of {} (all three if omitted).",
                    quoted_list(REDUCIBLE)
                ),
            ));
        }
        let mut r = Reduce { friction: false, cohesion: false, tensile_strength: false };
        for (j, n) in names.iter().enumerate() {
            let key = format!("safety.reduce[{j}]");
            let flag = match n.as_str() {
                "friction" => &mut r.friction,
                "cohesion" => &mut r.cohesion,
                "tensile_strength" => &mut r.tensile_strength,
                _ => return Err(self.bad(key, format!("{n:?}"), format!("not a strength parameter; use any of {} (friction is f = tan(phi); cohesion includes the residual cohesion).", quoted_list(REDUCIBLE)))),
            };
            if *flag {
                return Err(self.bad(key, format!("{n:?}"), "listed twice; give each parameter once."));
            }
            *flag = true;
        }
        Ok(r)
    }

    /// `contacts = [..]`: group names of `[[contacts]]` entries, each once.
    fn chosen(&self, names: &[String], contacts: &[Contact]) -> R<Vec<usize>> {
        if names.is_empty() {
            return Err(self.err(
                "safety.contacts",
                "is empty: name the contact groups whose strength is reduced (all contacts if omitted).",
            ));
        }
        let mut out: Vec<usize> = Vec::new();
        for (j, n) in names.iter().enumerate() {
            let key = format!("safety.contacts[{j}]");
            let Some(i) = contacts.iter().position(|c| names_it(c, n)) else {
                return Err(self.bad(
                    key,
                    format!("{n:?}"),
                    format!(
                        "is not the group of a [[contacts]] entry; the scene's contacts are {}.",
                        quoted_list(contacts.iter().map(name))
                    ),
                ));
            };
            if out.contains(&i) {
                return Err(self.bad(
                    key,
                    format!("{n:?}"),
                    format!("names contacts[{i}] again; give each contact once."),
                ));
            }
            out.push(i);
        }
        out.sort_unstable();
        Ok(out)
    }

    /// A finite number > 0, or `default`.
    fn positive(&self, v: Option<f64>, default: f64, key: &str, what: &str) -> R<f64> {
        match v {
            None => Ok(default),
            Some(x) if x.is_finite() && x > 0.0 => Ok(x),
            Some(x) => Err(self.bad(key, x, what)),
        }
    }
}

/// Whether `n` is the group of contact `c` (either group of a pair).
fn names_it(c: &Contact, n: &str) -> bool {
    match &c.groups {
        ContactGroups::Shared(g) => g == n,
        ContactGroups::Pair(a, b) => a == n || b == n || format!("{a}|{b}") == n,
    }
}

/// The group a contact is known by in messages.
fn name(c: &Contact) -> String {
    match &c.groups {
        ContactGroups::Shared(g) => g.clone(),
        ContactGroups::Pair(a, b) => format!("{a}|{b}"),
    }
}
