//! What a block does when equilibrium is lost, named from its rigid
//! motion: the motion that nothing holds, driven by its loads
//! ([`super::mobility::free_motion`]), `v(x) = t + ω × (x - c)` with t the
//! motion of its centroid c and ω its rotation. Against the pairs of its
//! faces that stay closed (outward normal n of the block at each):
//!
//! ```text
//! no closed pair                      free (t along gravity: it falls) or lifting
//! |v| at the closed pairs < 0.3 |t|   toppling: it turns about them (ω: the axis)
//! -v . n > 0.5 |v| on the closed area lifting: it leaves them
//! otherwise                           sliding along their joint(s); on two planes
//!                                     or more, along their line of intersection;
//!                                     turning as it slides (|ω| size > 0.5 |t|):
//!                                     round a curved joint, about a point
//! ```
//!
//! A toppling block turns about the edge where its last pairs stay closed
//! (Goodman & Bray: a block of width b and height h on a plane at θ topples
//! when b/h < tan θ, whatever its friction, and slides when tan φ < tan θ),
//! so friction or cohesion cannot stop it: only what holds its heel down or
//! its toe in place. [`BlockState::helps`] says what can.
//!
//! A block that stands carries its load through faces in compression; the
//! normal force's point of action on a face (its centre of pressure) lies
//! at an eccentricity e from the face's centroid. Its margin against
//! toppling about that face's edge is [`toppling_margin`]
//!
//! ```text
//! F_topple = d / e     d: the distance from the centroid to the edge along e
//! ```
//!
//! which for a block on a plane is (b/2) / ((h/2) tan θ) = (b/h) / tan θ.

use crate::fem::vec3::{cross, dot, norm, sub};
use crate::model::Model;

/// What a block does: it stands, or how it moves once nothing holds it
/// (blocks.csv's `state`; the geometry of a free part's motion is
/// [`crate::fem::rigid::RigidMotion`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
pub enum BlockState {
    Held,
    Sliding,
    Toppling,
    Lifting,
    Free,
}

impl BlockState {
    /// The spelling in blocks.csv and summary.json.
    pub fn key(self) -> &'static str {
        match self {
            BlockState::Held => "held",
            BlockState::Sliding => "sliding",
            BlockState::Toppling => "toppling",
            BlockState::Lifting => "lifting",
            BlockState::Free => "free",
        }
    }

    /// The integer of the block VTU field `block_state`.
    pub fn code(self) -> i32 {
        self as i32
    }

    /// What can hold a block that moves this way.
    pub fn helps(self) -> &'static str {
        match self {
            BlockState::Held => "",
            BlockState::Sliding => "raise the friction or cohesion of the joints it slides on, lower the load along them, or hold the block (a support or bolts across the joints)",
            BlockState::Toppling => "friction and cohesion cannot stop it (its toe stays put while it turns): hold its heel down (tensile strength of the joint, bolts, a support), buttress it, widen its base or lower the load that turns it",
            BlockState::Lifting => "hold it down (tensile strength of the joint, bolts, a support) or lower the load that lifts it; friction and cohesion carry nothing once a joint opens",
            BlockState::Free => "support it (bolts into stable rock, a support): its joints are open and nothing carries it; friction and cohesion carry nothing once a joint opens",
        }
    }
}

/// A pair of a block's face that stays closed.
#[derive(Clone, Copy, Debug)]
pub struct Closed {
    pub x: [f64; 3],
    /// The block's outward unit normal there.
    pub normal: [f64; 3],
    pub area: f64,
    /// Its contact group.
    pub contact: usize,
}

/// How one block moves: its kind, the motion of its centroid and its
/// rotation (scaled with the mechanism: only directions and ratios mean
/// anything), and where it moves on.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockMotion {
    pub block: usize,
    pub state: BlockState,
    /// The point `translation` is the motion of (the block's centre).
    pub centre: [f64; 3],
    pub translation: [f64; 3],
    pub rotation: [f64; 3],
    /// Toppling: the mean position of the pairs it turns about; sliding
    /// round a curved contact: the point it turns about (on the axis, the
    /// point nearest its centre).
    pub pivot: Option<[f64; 3]>,
    /// The contact groups of the closed pairs it moves on, ascending.
    pub on: Vec<usize>,
    /// Sliding on faces of two directions or more: along their line of
    /// intersection.
    pub along_line: bool,
}

/// How equilibrium was lost: the blocks that move and how, the one that
/// moves most first; `kind` is its motion.
#[derive(Clone, Debug, PartialEq)]
pub struct Mechanism {
    pub kind: BlockState,
    pub blocks: Vec<BlockMotion>,
}

impl Mechanism {
    /// The blocks, the one that moves most first (by the motion of their
    /// centroids, with their rotation times `size` each).
    pub fn new(mut blocks: Vec<BlockMotion>, sizes: &[f64]) -> Option<Mechanism> {
        let amount = |b: &BlockMotion, s: f64| norm(b.translation).max(norm(b.rotation) * s);
        let mut order: Vec<(f64, BlockMotion)> =
            blocks.drain(..).zip(sizes).map(|(b, &s)| (amount(&b, s), b)).collect();
        order.sort_by(|a, b| b.0.total_cmp(&a.0));
        let blocks: Vec<BlockMotion> = order.into_iter().map(|(_, b)| b).collect();
        Some(Mechanism { kind: blocks.first()?.state, blocks })
    }

    /// The displacement of the point `x` of block `block` (zero for a block
    /// not in the mechanism).
    pub fn at(&self, block: usize, x: [f64; 3]) -> [f64; 3] {
        let Some(b) = self.blocks.iter().find(|b| b.block == block) else { return [0.0; 3] };
        let r = cross(b.rotation, sub(x, b.centre));
        std::array::from_fn(|i| b.translation[i] + r[i])
    }

    /// The motion of a block of the mechanism (Held for one not in it).
    pub fn of(&self, block: usize) -> BlockState {
        self.blocks.iter().find(|b| b.block == block).map_or(BlockState::Held, |b| b.state)
    }
}

/// Names the motion of block `block` with centroid `centre` and size
/// `size` (its largest distance from the centroid), moving by `t` at its
/// centroid and turning by `omega`, on its closed pairs `closed`, under
/// gravity `gravity` (module header).
pub fn classify(
    block: usize,
    centre: [f64; 3],
    size: f64,
    (t, omega): ([f64; 3], [f64; 3]),
    closed: &[Closed],
    gravity: [f64; 3],
) -> BlockMotion {
    let v = |x: [f64; 3]| -> [f64; 3] {
        let r = cross(omega, sub(x, centre));
        [t[0] + r[0], t[1] + r[1], t[2] + r[2]]
    };
    let scale = norm(t).max(norm(omega) * size);
    let mut out = BlockMotion {
        block,
        state: BlockState::Sliding,
        centre,
        translation: t,
        rotation: omega,
        pivot: None,
        on: Vec::new(),
        along_line: false,
    };
    if closed.is_empty() || scale == 0.0 {
        let falls = norm(gravity) > 0.0 && dot(t, gravity) > 0.5 * norm(t) * norm(gravity);
        out.state = if falls { BlockState::Free } else { BlockState::Lifting };
        return out;
    }
    let mut on: Vec<usize> = closed.iter().map(|c| c.contact).collect();
    on.sort_unstable();
    on.dedup();
    out.on = on;
    let at_closed = closed.iter().map(|c| norm(v(c.x))).fold(0.0, f64::max);
    if at_closed < 0.3 * norm(t).max(1e-300) && norm(omega) > 0.0 {
        let a: f64 = closed.iter().map(|c| c.area).sum();
        let w = |c: &Closed| if a > 0.0 { c.area / a } else { 1.0 / closed.len() as f64 };
        out.pivot = Some(std::array::from_fn(|i| closed.iter().map(|c| w(c) * c.x[i]).sum()));
        out.state = BlockState::Toppling;
        return out;
    }
    let area: f64 = closed.iter().map(|c| c.area).sum::<f64>().max(f64::MIN_POSITIVE);
    // moving against its outward normal, a block leaves the face
    let leaving: f64 = closed.iter().map(|c| -c.area * dot(v(c.x), c.normal) / norm(v(c.x)).max(1e-300)).sum::<f64>();
    if leaving > 0.5 * area {
        out.state = BlockState::Lifting;
        return out;
    }
    if norm(omega) * size > TURNING * norm(t) {
        // sliding round a curved contact: about the axis's point nearest the centroid
        let ww = dot(omega, omega);
        out.pivot = Some(std::array::from_fn(|i| centre[i] + cross(omega, t)[i] / ww));
        return out;
    }
    // translating on face directions more than ~15 degrees apart: along
    // their line of intersection (in 3D: traces in a plane meet at a
    // point, and a block slides along one of them)
    let n0 = closed[0].normal;
    let planar = t[2] == 0.0 && closed.iter().all(|c| c.normal[2] == 0.0);
    out.along_line = !planar && closed.iter().any(|c| norm(cross(c.normal, n0)) > 0.26);
    out
}

/// A sliding block whose rotation moves its farthest point by more than
/// this many times its centroid's motion turns as it slides (round a
/// curved contact) rather than translating.
const TURNING: f64 = 0.5;

/// A face's margin against toppling about its edge: `d / e` with e the
/// eccentricity of the normal force's point of action from the face's
/// centroid, d the distance from the centroid to the face's edge along e
/// (the farthest of `points`, the face's pair positions, that way).
/// Infinite when the force acts at the centroid; None for a face in
/// tension or without force.
pub fn toppling_margin(centroid: [f64; 3], action: [f64; 3], points: &[[f64; 3]]) -> Option<f64> {
    let e = sub(action, centroid);
    let le = norm(e);
    if points.is_empty() {
        return None;
    }
    if le == 0.0 {
        return Some(f64::INFINITY);
    }
    let dir = e.map(|x| x / le);
    let d = points.iter().map(|&p| dot(sub(p, centroid), dir)).fold(f64::NEG_INFINITY, f64::max);
    Some(d / le)
}

/// The mechanism for a reader: each moving block (at most five, the one
/// that moves most first) and how, e.g. `"top" topples about its corner
/// at (1.000, 0.000)`, `"wedge" slides along the line of intersection of
/// "J1" and "J2", towards (0.000, 0.866, -0.500)`.
pub fn describe(model: &Model, m: &Mechanism) -> String {
    let nd = model.nd;
    let point = |x: [f64; 3]| {
        // (no "-0.000" for a round-off below the last digit)
        let c: Vec<String> =
            x[..nd.clamp(2, 3)].iter().map(|&v| format!("{:.3}", if v.abs() < 5e-4 { 0.0 } else { v })).collect();
        format!("({})", c.join(", "))
    };
    let dir = |v: [f64; 3]| {
        let l = norm(v);
        point(if l > 0.0 { v.map(|x| x / l) } else { v })
    };
    let joints = |on: &[usize]| -> String {
        let names: Vec<String> = on.iter().map(|&c| format!("\"{}\"", model.interfaces[c].name)).collect();
        match names.len() {
            0 => "its faces".into(),
            1 => names[0].clone(),
            _ => format!("{} and {}", names[..names.len() - 1].join(", "), names[names.len() - 1]),
        }
    };
    let mut parts: Vec<String> = m
        .blocks
        .iter()
        .take(5)
        .map(|b| {
            let who = model.bodies[b.block].label();
            match b.state {
                BlockState::Sliding if b.along_line => format!(
                    "{who} slides along the line of intersection of {}, towards {}",
                    joints(&b.on),
                    dir(b.translation)
                ),
                BlockState::Sliding => match b.pivot {
                    Some(at) if nd == 3 => format!(
                        "{who} slides round {}, turning about the axis along {} through {}",
                        joints(&b.on),
                        dir(b.rotation),
                        point(at)
                    ),
                    Some(at) => format!("{who} slides round {}, turning about {}", joints(&b.on), point(at)),
                    None => format!("{who} slides along {}, towards {}", joints(&b.on), dir(b.translation)),
                },
                BlockState::Toppling => {
                    let at = b.pivot.map_or(String::new(), point);
                    if nd == 3 {
                        format!(
                            "{who} topples about the edge through {at} along {} (on {})",
                            dir(b.rotation),
                            joints(&b.on)
                        )
                    } else {
                        format!("{who} topples about its corner at {at} (on {})", joints(&b.on))
                    }
                }
                BlockState::Lifting => {
                    format!("{who} lifts off {}, moving towards {}", joints(&b.on), dir(b.translation))
                }
                BlockState::Free => {
                    format!("{who} falls free, held by none of its joints, towards {}", dir(b.translation))
                }
                BlockState::Held => format!("{who} holds"),
            }
        })
        .collect();
    if m.blocks.len() > 5 {
        parts.push(format!("and {} more block(s)", m.blocks.len() - 5));
    }
    parts.join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOWN: [f64; 3] = [0.0, -9.81, 0.0];

    /// A 2D block of width b and height h on y = 0, its base pairs closed
    /// at `xs` (outward normal -y).
    fn base(xs: &[f64]) -> Vec<Closed> {
        xs.iter().map(|&x| Closed { x: [x, 0.0, 0.0], normal: [0.0, -1.0, 0.0], area: 0.1, contact: 3 }).collect()
    }

    #[test]
    fn a_block_turning_about_its_toe_topples_and_one_moving_along_its_base_slides() {
        let c = [0.5, 2.0, 0.0];
        // rotation about the toe (1, 0) by w: the centroid moves by w e_z x (c - toe)
        let w = [0.0, 0.0, -0.01];
        let t = cross(w, sub(c, [1.0, 0.0, 0.0]));
        let b = classify(7, c, 2.1, (t, w), &base(&[1.0]), DOWN);
        assert_eq!(b.state, BlockState::Toppling);
        assert_eq!(b.pivot, Some([1.0, 0.0, 0.0]));
        assert_eq!(b.on, vec![3]);
        // along the base, every pair closed: sliding on one plane
        let b = classify(7, c, 2.1, ([1.0, 0.0, 0.0], [0.0; 3]), &base(&[0.0, 0.5, 1.0]), DOWN);
        assert_eq!((b.state, b.along_line, b.pivot), (BlockState::Sliding, false, None));
        // leaving its base: lifting; nothing closed: falling or lifting
        let b = classify(7, c, 2.1, ([0.0, 1.0, 0.0], [0.0; 3]), &base(&[0.0, 1.0]), DOWN);
        assert_eq!(b.state, BlockState::Lifting);
        assert_eq!(classify(7, c, 2.1, ([0.0, -1.0, 0.0], [0.0; 3]), &[], DOWN).state, BlockState::Free);
        assert_eq!(classify(7, c, 2.1, ([0.0, 1.0, 0.0], [0.0; 3]), &[], DOWN).state, BlockState::Lifting);
    }

    #[test]
    fn a_block_turning_in_a_round_seat_slides_round_it_about_its_centre() {
        // a half-disc below y = 0 turning about the arc's centre (0, 0):
        // its pairs on the arc move along it, none leaves it
        let c = [0.0, -4.0 / (3.0 * std::f64::consts::PI), 0.0];
        let w = [0.0, 0.0, 0.2];
        let arc: Vec<Closed> = (1..8)
            .map(|i| {
                let a = std::f64::consts::PI * (1.0 + i as f64 / 8.0);
                Closed { x: [a.cos(), a.sin(), 0.0], normal: [a.cos(), a.sin(), 0.0], area: 0.4, contact: 2 }
            })
            .collect();
        let b = classify(1, c, 1.1, (cross(w, sub(c, [0.0; 3])), w), &arc, DOWN);
        assert_eq!((b.state, b.along_line), (BlockState::Sliding, false));
        let p = b.pivot.expect("the point it turns about");
        assert!(norm(p) < 1e-12, "{p:?}");
    }

    #[test]
    fn a_wedge_on_two_planes_slides_along_their_line() {
        let s = 0.5f64.sqrt();
        let planes = [
            Closed { x: [-1.0, 0.0, 1.0], normal: [-s, 0.0, -s], area: 1.0, contact: 0 },
            Closed { x: [1.0, 0.0, 1.0], normal: [s, 0.0, -s], area: 1.0, contact: 1 },
        ];
        let b = classify(0, [0.0, 0.0, 1.5], 2.0, ([0.0, 1.0, -0.3], [0.0; 3]), &planes, [0.0, 0.0, -1.0]);
        assert_eq!((b.state, b.along_line, b.on.clone()), (BlockState::Sliding, true, vec![0, 1]));
    }

    #[test]
    fn a_block_in_a_plane_on_two_traces_slides_along_one_not_a_line() {
        // bedding dipping 35 degrees and a cross joint at 60: the block moves
        // down the bedding, touching the cross joint where it leaves it
        let (a, b) = (35f64.to_radians(), 60f64.to_radians());
        let traces = [
            Closed { x: [0.0, 0.0, 0.0], normal: [-a.sin(), -a.cos(), 0.0], area: 1.0, contact: 0 },
            Closed { x: [1.0, 1.0, 0.0], normal: [-b.sin(), b.cos(), 0.0], area: 0.2, contact: 1 },
        ];
        let down = [a.cos(), -a.sin(), 0.0];
        let m = classify(0, [0.5, 0.5, 0.0], 1.0, (down, [0.0; 3]), &traces, DOWN);
        assert_eq!((m.state, m.along_line), (BlockState::Sliding, false));
    }

    #[test]
    fn the_margin_of_a_block_on_a_plane_is_b_over_h_over_tan_theta() {
        // b = 1, h = 2, theta = 20 degrees: the normal force acts (h/2) tan(theta)
        // downhill of the base's centre
        let (b, h, theta) = (1.0, 2.0, 20f64.to_radians());
        let e = 0.5 * h * theta.tan();
        let m = toppling_margin([0.0; 3], [e, 0.0, 0.0], &[[-0.5 * b, 0.0, 0.0], [0.5 * b, 0.0, 0.0]]);
        let exact = b / h / theta.tan();
        assert!((m.expect("a margin") - exact).abs() < 1e-12, "{m:?} against {exact}");
        assert_eq!(toppling_margin([0.0; 3], [0.0; 3], &[[1.0, 0.0, 0.0]]), Some(f64::INFINITY));
    }

    #[test]
    fn the_block_that_moves_most_names_the_mechanism() {
        let slide = |block, x: f64| BlockMotion {
            block,
            centre: [0.0; 3],
            state: if block == 1 { BlockState::Toppling } else { BlockState::Sliding },
            translation: [x, 0.0, 0.0],
            rotation: [0.0; 3],
            pivot: None,
            on: vec![],
            along_line: false,
        };
        let m = Mechanism::new(vec![slide(0, 0.2), slide(1, 1.0)], &[1.0, 1.0]).expect("blocks");
        assert_eq!((m.kind, m.blocks[0].block), (BlockState::Toppling, 1));
        assert_eq!((m.of(0), m.of(5)), (BlockState::Sliding, BlockState::Held));
        assert!(BlockState::Toppling.helps().contains("cannot"));
        assert!(Mechanism::new(vec![], &[]).is_none());
    }
}
