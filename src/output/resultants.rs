//! Resultants of the contact forces per contact group and per block face
//! pair, for a model cut into blocks: what each joint carries as a whole,
//! how much of its strength it uses, and how much of it sticks, slips and
//! opens.
//!
//! A face pair is the part of one contact group between two given blocks,
//! side I and side II as contact.csv's `block_i`, `block_ii` name them (so
//! summing contact.csv's rows of a face pair gives its resultant). Over the
//! pairs p of a group or face pair, with A_p the area a pair controls and
//! `f_p = (sigma_n n + tau_t t + tau_b b) A_p` its force on side I:
//!
//! ```text
//! F = sum f_p                      the resultant on side I (global x, y, z)
//! n = sum A_p n_p / |sum A_p n_p|  the mean unit normal (outward of side I)
//! N = F . n                        the normal force, tension positive
//! T = |F - N n|                    the shear force (magnitude in the plane of n)
//! ```
//!
//! On a plane face N and T are the face's normal and shear force; on a
//! curved or creased group (a lining, a V-groove) they are F's components
//! along and across the mean normal, and F is what to read.
//!
//! The mobilised friction of a pair is `|tau| / (c - f sigma_n)`, its shear
//! over its Mohr–Coulomb limit, with the cohesion it has at the end of the
//! step (the residual cohesion once it has cracked: opened or slipped in an
//! earlier step or on the way through this one, as the contact iteration
//! judged it, `ContactRun::cracked`). A stuck pair is at most 1. A slipping or open pair counts
//! as 1, fully mobilised, whatever it carries (a frictionless slip carries
//! no shear, an open pair nothing): the joint has failed there. So does a
//! stuck pair whose limit `c - f sigma_n` is not positive (in tension at or
//! beyond the Coulomb apex c / f): it has no shear strength left. A group
//! or face pair reports its largest value and where it is.
//!
//! With water in a joint, f_p is the solid-to-solid force (the effective
//! sigma_n'), and the water's force on side I, `w_p`, is summed apart:
//! `U = -(sum w_p) . n` is the uplift, the water's force pushing the faces
//! apart (positive); the total normal force across the joint is `N - U`.
//!
//! The areas of the pairs by state give the open, slip and stick areas.
//! Plain data in, plain data out: [`sum`] adds up per-pair records,
//! [`of_run`] makes them from a run's last load step.

use crate::contact::law::{ContactState, PairResult, Strength};
use crate::fem::vec3::dot;
use crate::results::Run;

/// What one pair adds to its group and face pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairRecord {
    /// Its contact group (index of the model's interfaces).
    pub contact: usize,
    /// The blocks (model bodies) of its sides I and II.
    pub blocks: [usize; 2],
    /// Where it is.
    pub x: [f64; 3],
    /// Its unit normal, outward of side I.
    pub normal: [f64; 3],
    pub area: f64,
    /// Its force on side I, global axes.
    pub force: [f64; 3],
    /// The force of the water in the joint on side I, global axes.
    pub water: [f64; 3],
    pub state: ContactState,
    /// Its mobilised friction ([`mobilised`]).
    pub mobilised: f64,
    /// A node of it is held by a support (where a joint meets a supported
    /// boundary: the support takes part of what the pair would carry).
    pub supported: bool,
}

/// The sums over the pairs of a group or face pair.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Resultant {
    pub pairs: usize,
    /// Areas by state, indexed by the status code: open, slip, stick.
    pub areas: [f64; 3],
    /// The resultant force on side I, global axes.
    pub force: [f64; 3],
    /// The water's resultant force on side I, global axes.
    pub water: [f64; 3],
    /// The mean unit normal, outward of side I (zero without pairs).
    pub normal: [f64; 3],
    /// The area-weighted mean position of the pairs.
    pub centre: [f64; 3],
    /// The largest mobilised friction, and the position of that pair.
    pub mobilised: f64,
    pub mobilised_at: [f64; 3],
    /// Its pairs with a supported node, and the largest mobilised friction
    /// of the others (0 when every pair is supported).
    pub supported: usize,
    pub mobilised_free: f64,
}

impl Resultant {
    /// The area of all its pairs.
    pub fn area(&self) -> f64 {
        self.areas.iter().sum()
    }

    /// The area that slips or opens, as a fraction of its area.
    pub fn failed_fraction(&self) -> f64 {
        let a = self.area();
        if a > 0.0 {
            (self.areas[0] + self.areas[1]) / a
        } else {
            0.0
        }
    }

    /// N = F . n: the normal force, tension positive.
    pub fn normal_force(&self) -> f64 {
        dot(self.force, self.normal)
    }

    /// U = -(sum w_p) . n: the water's force pushing the faces apart.
    pub fn uplift(&self) -> f64 {
        0.0 - dot(self.water, self.normal)
    }

    /// T = |F - N n|: the shear force.
    pub fn shear_force(&self) -> f64 {
        let n = self.normal_force();
        let s: [f64; 3] = std::array::from_fn(|i| self.force[i] - n * self.normal[i]);
        dot(s, s).sqrt()
    }

    fn add(&mut self, p: &PairRecord, weighted_normal: &mut [f64; 3]) {
        self.pairs += 1;
        self.areas[p.state.code() as usize] += p.area;
        for (i, n) in weighted_normal.iter_mut().enumerate() {
            self.force[i] += p.force[i];
            self.water[i] += p.water[i];
            *n += p.area * p.normal[i];
            self.centre[i] += p.area * p.x[i];
        }
        if self.pairs == 1 || p.mobilised > self.mobilised {
            self.mobilised = p.mobilised;
            self.mobilised_at = p.x;
        }
        if p.supported {
            self.supported += 1;
        } else {
            self.mobilised_free = self.mobilised_free.max(p.mobilised);
        }
    }

    fn finish(&mut self, weighted_normal: [f64; 3]) {
        let l = dot(weighted_normal, weighted_normal).sqrt();
        if l > 0.0 {
            self.normal = weighted_normal.map(|v| v / l);
        }
        let a = self.area();
        if a > 0.0 {
            self.centre = self.centre.map(|v| v / a);
        }
    }
}

/// The part of a contact group between two blocks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacePair {
    pub contact: usize,
    /// Blocks of sides I and II (model bodies).
    pub blocks: [usize; 2],
    pub resultant: Resultant,
}

/// Every contact group's resultant (in the model's order of interfaces)
/// and every face pair's (ordered by group, then block I, then block II).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Resultants {
    pub groups: Vec<Resultant>,
    pub faces: Vec<FacePair>,
}

impl Resultants {
    /// The `n` most mobilised face pairs, most first: by largest mobilised
    /// friction, then by the fraction of their area that slips or opens,
    /// then in [`Resultants::faces`]'s order.
    pub fn most_mobilised(&self, n: usize) -> Vec<&FacePair> {
        let mut v: Vec<&FacePair> = self.faces.iter().collect();
        v.sort_by(|a, b| {
            let (ra, rb) = (&a.resultant, &b.resultant);
            rb.mobilised.total_cmp(&ra.mobilised).then(rb.failed_fraction().total_cmp(&ra.failed_fraction()))
        });
        v.truncate(n);
        v
    }
}

/// Face pairs below this fraction of their contact group's median face
/// area are slivers: report.md's ranking leaves them out.
pub const SLIVER: f64 = 0.1;

/// Why a face pair is left out of report.md's ranking.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LeftOut {
    /// Every pair of it has a supported node: the supports carry it.
    Supported,
    /// Below [`SLIVER`] of its group's median face area.
    Sliver,
}

impl LeftOut {
    pub fn key(self) -> &'static str {
        match self {
            LeftOut::Supported => "supported",
            LeftOut::Sliver => "sliver",
        }
    }
}

impl Resultants {
    /// Why each face pair is left out of the ranking (None: it ranks).
    pub fn left_out(&self) -> Vec<Option<LeftOut>> {
        let mut median = vec![0.0; self.groups.len()];
        for (g, m) in median.iter_mut().enumerate() {
            let mut a: Vec<f64> = self.faces.iter().filter(|f| f.contact == g).map(|f| f.resultant.area()).collect();
            a.sort_by(f64::total_cmp);
            *m = a.get(a.len() / 2).copied().unwrap_or(0.0);
        }
        (self.faces.iter())
            .map(|f| {
                let q = &f.resultant;
                if q.pairs > 0 && q.supported == q.pairs {
                    Some(LeftOut::Supported)
                } else if q.area() < SLIVER * median[f.contact] {
                    Some(LeftOut::Sliver)
                } else {
                    None
                }
            })
            .collect()
    }

    /// The `n` most mobilised face pairs that matter (neither slivers nor
    /// supported all along), most first by their largest mobilised friction
    /// away from supported nodes, then by the fraction of their area that
    /// slips or opens.
    pub fn ranked(&self, n: usize) -> Vec<&FacePair> {
        let out = self.left_out();
        let mut v: Vec<&FacePair> = self.faces.iter().zip(&out).filter(|(_, o)| o.is_none()).map(|(f, _)| f).collect();
        v.sort_by(|a, b| {
            let (ra, rb) = (&a.resultant, &b.resultant);
            rb.mobilised_free.total_cmp(&ra.mobilised_free).then(rb.failed_fraction().total_cmp(&ra.failed_fraction()))
        });
        v.truncate(n);
        v
    }
}

/// The mobilised friction of a pair: `|tau| / (c - f sigma_n)` when it
/// sticks and that limit is positive, else 1 (module header). `cracked`:
/// it has opened or slipped before, so its cohesion is the residual one.
pub fn mobilised(state: ContactState, r: &PairResult, s: &Strength, cracked: bool) -> f64 {
    if state != ContactState::Stick {
        return 1.0;
    }
    let (_, c) = s.effective(cracked);
    let limit = c - s.friction * r.sigma_n;
    if limit > 0.0 {
        r.tau() / limit
    } else {
        1.0
    }
}

/// The resultants of `pairs` over `n_contacts` contact groups.
pub fn sum(pairs: &[PairRecord], n_contacts: usize) -> Resultants {
    let mut groups = vec![Resultant::default(); n_contacts];
    let mut group_normals = vec![[0.0; 3]; n_contacts];
    let mut index: std::collections::BTreeMap<(usize, [usize; 2]), usize> = Default::default();
    let mut faces: Vec<FacePair> = Vec::new();
    let mut face_normals: Vec<[f64; 3]> = Vec::new();
    for p in pairs {
        groups[p.contact].add(p, &mut group_normals[p.contact]);
        let f = *index.entry((p.contact, p.blocks)).or_insert_with(|| {
            faces.push(FacePair { contact: p.contact, blocks: p.blocks, resultant: Resultant::default() });
            face_normals.push([0.0; 3]);
            faces.len() - 1
        });
        faces[f].resultant.add(p, &mut face_normals[f]);
    }
    for (g, n) in groups.iter_mut().zip(group_normals) {
        g.finish(n);
    }
    for (f, n) in faces.iter_mut().zip(face_normals) {
        f.resultant.finish(n);
    }
    let faces = index.values().map(|&f| faces[f]).collect();
    Resultants { groups, faces }
}

/// The strength of every contact group of the run's scene.
pub fn strengths(run: &Run) -> Vec<Strength> {
    run.about.contacts.iter().map(|c| c.strength).collect()
}

/// The resultants of the run's last load step (None without contacts).
pub fn of_run(run: &Run) -> Option<Resultants> {
    let c = run.contact()?;
    let m = &run.model;
    let strength = strengths(run);
    let body = m.body_of_node();
    let held = |n: usize| (0..m.nd).any(|c| m.prescribed[n * m.nd + c].is_some());
    let records: Vec<PairRecord> = (m.pairs.iter().enumerate())
        .map(|(p, pair)| PairRecord {
            contact: pair.contact,
            blocks: [body[pair.k], body[pair.l]],
            x: m.coords[pair.k],
            normal: c.frames[p][0],
            area: c.areas[p],
            force: c.force(p),
            water: c.water.as_ref().map_or([0.0; 3], |w| w.force[p]),
            state: c.states[p],
            mobilised: mobilised(c.states[p], &c.pairs[p], &strength[pair.contact], c.is_cracked(p)),
            supported: held(pair.k) || held(pair.l),
        })
        .collect();
    Some(sum(&records, m.interfaces.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A record in the order of its fields (a table row reads best so).
    #[allow(clippy::too_many_arguments)]
    fn record(
        contact: usize,
        blocks: [usize; 2],
        x: [f64; 3],
        normal: [f64; 3],
        area: f64,
        force: [f64; 3],
        state: ContactState,
        mobilised: f64,
    ) -> PairRecord {
        PairRecord { contact, blocks, x, normal, area, force, water: [0.0; 3], state, mobilised, supported: false }
    }

    /// Two groups: "a" (z = 0) between blocks 0 | 1 and 0 | 2, "b" (x = 1)
    /// between 1 | 2. Each sum, mean normal, N, T, area by state and the
    /// largest mobilised friction by hand.
    #[test]
    fn sums_per_group_and_face_pair() {
        let z = [0.0, 0.0, 1.0];
        let x = [1.0, 0.0, 0.0];
        let pairs = [
            record(0, [0, 2], [1.5, 0.0, 0.0], z, 1.0, [0.5, 0.0, -4.0], ContactState::Stick, 0.25),
            record(0, [0, 1], [0.0, 0.0, 0.0], z, 0.5, [0.1, 0.2, -1.0], ContactState::Stick, 0.4),
            record(1, [1, 2], [1.0, 0.0, 0.5], x, 2.0, [0.0, 0.0, 0.0], ContactState::Open, 1.0),
            record(0, [0, 1], [1.0, 0.0, 0.0], z, 1.5, [0.3, 0.0, -2.0], ContactState::Slip, 1.0),
        ];
        let r = sum(&pairs, 2);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-14;
        // group "a": three pairs
        let a = &r.groups[0];
        assert_eq!(a.pairs, 3);
        assert_eq!(a.areas, [0.0, 1.5, 1.5]);
        assert!(close(a.force[0], 0.9) && close(a.force[1], 0.2) && close(a.force[2], -7.0));
        assert_eq!(a.normal, z);
        assert!(close(a.normal_force(), -7.0));
        assert!(close(a.shear_force(), (0.81f64 + 0.04).sqrt()));
        assert!(close(a.centre[0], (1.5 + 0.0 + 1.5) / 3.0));
        assert_eq!((a.mobilised, a.mobilised_at), (1.0, [1.0, 0.0, 0.0]));
        assert!(close(a.failed_fraction(), 0.5));
        // its face pairs, ordered by group then blocks: 0 | 1, then 0 | 2
        assert_eq!(
            r.faces.iter().map(|f| (f.contact, f.blocks)).collect::<Vec<_>>(),
            vec![(0, [0, 1]), (0, [0, 2]), (1, [1, 2])]
        );
        let f01 = &r.faces[0].resultant;
        assert_eq!(f01.pairs, 2);
        assert!(close(f01.force[0], 0.4) && close(f01.force[1], 0.2) && close(f01.force[2], -3.0));
        assert!(close(f01.centre[0], 1.5 / 2.0));
        assert_eq!(f01.areas, [0.0, 1.5, 0.5]);
        let f02 = &r.faces[1].resultant;
        assert_eq!((f02.pairs, f02.mobilised, f02.mobilised_at), (1, 0.25, [1.5, 0.0, 0.0]));
        // the face pairs of a group add up to the group
        for i in 0..3 {
            assert!(close(f01.force[i] + f02.force[i], a.force[i]));
        }
        // group "b": open, no force; the mean normal of a tilted set
        assert_eq!(r.groups[1].areas, [2.0, 0.0, 0.0]);
        assert_eq!((r.groups[1].normal_force(), r.groups[1].shear_force()), (0.0, 0.0));
        // most mobilised: 1.0 with all its area open, then 1.0 half slipping, then 0.25
        let order: Vec<[usize; 2]> = r.most_mobilised(10).iter().map(|f| f.blocks).collect();
        assert_eq!(order, vec![[1, 2], [0, 1], [0, 2]]);
        assert_eq!(r.most_mobilised(1).len(), 1);
    }

    /// The ranking leaves out faces supported all along and slivers, and
    /// ranks by the mobilised friction away from supported nodes.
    #[test]
    fn the_ranking_leaves_out_supported_faces_and_slivers() {
        let z = [0.0, 0.0, 1.0];
        let at = |blocks, area, mobilised, supported| PairRecord {
            supported,
            ..record(0, blocks, [0.0; 3], z, area, [0.0, 0.0, -1.0], ContactState::Stick, mobilised)
        };
        let pairs = [
            // 0 | 1: most mobilised at its supported node, 0.3 elsewhere
            at([0, 1], 1.0, 0.9, true),
            at([0, 1], 1.0, 0.3, false),
            // 0 | 2: supported all along
            at([0, 2], 2.0, 1.0, true),
            // 0 | 3: a sliver (0.04 against the median 2)
            at([0, 3], 0.04, 1.0, false),
            // 1 | 2 and 2 | 3
            at([1, 2], 2.0, 0.5, false),
            at([2, 3], 3.0, 0.2, false),
        ];
        let r = sum(&pairs, 1);
        let out: Vec<Option<&str>> = r.left_out().iter().map(|o| o.map(LeftOut::key)).collect();
        assert_eq!(out, vec![None, Some("supported"), Some("sliver"), None, None]);
        let order: Vec<[usize; 2]> = r.ranked(10).iter().map(|f| f.blocks).collect();
        assert_eq!(order, vec![[1, 2], [0, 1], [2, 3]]);
        assert_eq!((r.faces[0].resultant.supported, r.faces[0].resultant.mobilised_free), (1, 0.3));
    }

    /// The mean normal of a face whose pairs' normals differ (a crease):
    /// area-weighted, unit; N and T split F along and across it.
    #[test]
    fn mean_frame_of_a_crease() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let pairs = [
            record(0, [0, 1], [0.0; 3], [s, 0.0, s], 1.0, [-1.0, 0.0, -1.0], ContactState::Stick, 0.0),
            record(0, [0, 1], [0.0; 3], [-s, 0.0, s], 1.0, [1.0, 0.0, -1.0], ContactState::Stick, 0.0),
        ];
        let g = sum(&pairs, 1).groups[0];
        assert!((g.normal[2] - 1.0).abs() < 1e-15 && g.normal[0].abs() < 1e-15);
        assert!((g.normal_force() + 2.0).abs() < 1e-15 && g.shear_force() < 1e-15);
    }

    /// |tau| / (c - f sigma_n) on stuck pairs, 1 where the joint has failed
    /// or has no strength left; the residual cohesion once cracked.
    #[test]
    fn mobilised_friction_truth_table() {
        let s = Strength { friction: 0.5, cohesion: 1.0, tensile_strength: 0.5, residual_cohesion: 0.2 };
        let r = |sigma_n: f64, tau_t: f64, tau_b: f64| PairResult { sigma_n, tau_t, tau_b, gap: 0.0, slip: 0.0 };
        let stick = ContactState::Stick;
        // c - f sigma_n = 1 + 1 = 2, tau = 1
        assert!((mobilised(stick, &r(-2.0, 0.6, 0.8), &s, false) - 0.5).abs() < 1e-15);
        // cracked: 0.2 + 1 = 1.2
        assert!((mobilised(stick, &r(-2.0, 0.6, 0.8), &s, true) - 1.0 / 1.2).abs() < 1e-15);
        // in tension, below the apex c / f = 2: 1 - 0.25 = 0.75
        assert!((mobilised(stick, &r(0.5, 0.3, 0.0), &s, false) - 0.4).abs() < 1e-15);
        // at or beyond the apex (cracked: c = 0.2, apex 0.4): no strength left
        assert_eq!(mobilised(stick, &r(0.4, 0.0, 0.0), &s, true), 1.0);
        // slipping (whatever its shear) and open pairs have failed
        assert_eq!(mobilised(ContactState::Slip, &r(-2.0, 0.0, 0.0), &s, false), 1.0);
        assert_eq!(mobilised(ContactState::Open, &r(0.0, 0.0, 0.0), &s, false), 1.0);
    }
}
