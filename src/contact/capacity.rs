//! Whether parts that a state set leaves free to slide can carry their
//! loads along that motion: the capacity test that tells a Newton step's
//! overshoot from a loss of equilibrium.
//!
//! A semismooth Newton step on a block with several faces can open one of
//! them and close another slipping, and leave the block held by normals
//! and by slipping pairs' fixed friction alone: the interface system is
//! singular, whatever the loads. Whether the block would slide is a
//! question of work along its free rigid motion `v` (a group of parts
//! tied to each other moves as one):
//!
//! ```text
//! drive    = g . v                            the loads' work
//! capacity = sum over slipping pairs  b_p |[v]_t(x_p)|
//! ```
//!
//! with `g` the loads on the parts' rigid modes and `b_p` each slipping
//! pair's bound at its last normal force (cohesion where it keeps it).
//! The loads come from the last solve, which held every part in
//! equilibrium under the same load factors: minus the contact forces on a
//! part, on its modes (its supports do no work along a free motion, and
//! the joins of one body's substructures none along the group's). Where
//! the capacity exceeds the drive, friction holds the block and the set
//! is an overshoot: a pair must stick. Otherwise the loads exceed what
//! the contacts carry, a loss of equilibrium.

use super::mobility::{free_groups, free_motion, PartModes, Tie};
use crate::fem::vec3::{dot, norm, sub, unit};

/// A pair as the capacity test reads it.
pub struct PairLoad {
    /// The parts of its two sides (k, l).
    pub parts: [usize; 2],
    pub x: [f64; 3],
    pub normal: [f64; 3],
    /// The last solve's contact force on side k, global axes.
    pub force: [f64; 3],
    /// What it carries along a slip (0 unless it slips under the set tested).
    pub bound: f64,
}

/// One group of free parts, moving in its free motion.
#[derive(Debug)]
pub struct Capacity {
    pub parts: Vec<usize>,
    /// The loads' work along the motion (>= 0).
    pub drive: f64,
    /// The work the slipping pairs' friction can take along it.
    pub capacity: f64,
    /// Each pair's slip along the motion, `|[v]_t|` (0 off the group).
    pub slip: Vec<f64>,
}

impl Capacity {
    /// Friction holds the group: its free motion is an overshoot.
    pub fn holds(&self) -> bool {
        self.capacity > self.drive
    }
}

/// The capacity of each group of the parts `free` (of `modes`, ties
/// `ties` as the solver's check makes them) under the pairs `pairs`.
pub fn capacities(modes: &[PartModes], ties: &[Tie], free: &[usize], pairs: &[PairLoad]) -> Vec<Capacity> {
    let np = modes.len();
    let mut load = vec![[0.0; 6]; np];
    for pr in pairs.iter().filter(|pr| pr.parts[0] != pr.parts[1] && pr.parts.iter().all(|&q| q < np)) {
        for (side, sign) in [(0, -1.0), (1, 1.0)] {
            let q = pr.parts[side];
            let r = modes[q].modes.along(pr.x, pr.force.map(|f| sign * f));
            load[q].iter_mut().zip(r).for_each(|(a, b)| *a += b);
        }
    }
    let dot6 = |a: &[f64; 6], b: &[f64; 6]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    (free_groups(np, free, ties).into_iter())
        .filter_map(|group| {
            let g: Vec<[f64; 6]> = group.iter().map(|&q| load[q]).collect();
            let a = free_motion(modes, ties, &group, &g)?;
            let drive = g.iter().zip(&a).map(|(g, a)| dot6(g, a)).sum::<f64>().max(0.0);
            let velocity = |q: usize, x: [f64; 3]| -> [f64; 3] {
                match group.iter().position(|&r| r == q) {
                    Some(i) => std::array::from_fn(|c| dot6(&modes[q].modes.along(x, unit(c)), &a[i])),
                    None => [0.0; 3],
                }
            };
            let slip: Vec<f64> = (pairs.iter())
                .map(|pr| {
                    let v = sub(velocity(pr.parts[1], pr.x), velocity(pr.parts[0], pr.x));
                    let vn = dot(v, pr.normal);
                    norm(std::array::from_fn(|i| v[i] - vn * pr.normal[i]))
                })
                .collect();
            let capacity = pairs.iter().zip(&slip).map(|(pr, s)| pr.bound * s).sum();
            Some(Capacity { parts: group, drive, capacity, slip })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::rigid::RigidModes;
    use crate::fem::Analysis;

    /// A block of weight `w` on a plane through the origin dipping `psi`
    /// (part 1) on held ground (part 0), two pairs slipping at friction
    /// `f`: the free motion is the slide down the plane.
    fn block_on_plane(psi: f64, f: f64, w: f64) -> Vec<Capacity> {
        let (t, n) = ([psi.cos(), psi.sin(), 0.0], [-psi.sin(), psi.cos(), 0.0]);
        let plane = Analysis::PlaneStrain;
        let ground = PartModes::supported(
            RigidModes::new(plane, [0.0, -1.0, 0.0], 2.0),
            [
                ([-2.0, -1.0, 0.0], [1.0, 0.0, 0.0]),
                ([-2.0, -1.0, 0.0], [0.0, 1.0, 0.0]),
                ([2.0, -1.0, 0.0], [0.0, 1.0, 0.0]),
            ],
        );
        let block = PartModes::supported(RigidModes::new(plane, n.map(|x| 0.5 * x), 1.0), []);
        let at = |s: f64| t.map(|x| s * x);
        // the ground carries the weight, half at each pair (no moment about the centre)
        let pairs: Vec<PairLoad> = [at(-0.5), at(0.5)]
            .into_iter()
            .map(|x| PairLoad {
                parts: [1, 0],
                x,
                normal: n,
                force: [0.0, w / 2.0, 0.0],
                bound: f * w / 2.0 * psi.cos(),
            })
            .collect();
        let ties: Vec<Tie> = pairs.iter().map(|p| Tie::exact([1, 0], p.x, n)).collect();
        capacities(&[ground, block], &ties, &[1], &pairs)
    }

    #[test]
    fn a_block_on_a_plane_holds_while_its_friction_exceeds_the_slope() {
        let psi = 35f64.to_radians();
        for f in [0.6, 0.8] {
            let groups = block_on_plane(psi, f, 3.0);
            let [g] = &groups[..] else { panic!("{groups:?}") };
            assert_eq!(g.parts, vec![1]);
            // v = the unit slide scaled by its largest component (cos psi)
            let scale = psi.cos().max(psi.sin());
            assert!((g.drive * scale - 3.0 * psi.sin()).abs() < 1e-12, "W sin psi: {}", g.drive * scale);
            assert!((g.capacity / g.drive - f / psi.tan()).abs() < 1e-12, "f / tan psi: {}", g.capacity / g.drive);
            assert_eq!(g.holds(), f > psi.tan(), "tan 35 = 0.700, f = {f}");
            assert!(g.slip.iter().all(|s| (s * scale - 1.0).abs() < 1e-12), "{:?}", g.slip);
        }
    }
}
