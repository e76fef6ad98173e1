//! Where two joints cross: a slip the crossing locks is freed by its twin.
//!
//! At a crossing of joints J1 and J2 four blocks meet, and four pairs join
//! their copies of a node: two on J1's plane (either side of J2) and two on
//! J2's. The verdict judges each pair by its own force, and where the
//! stress is near both joints' strength it lets slip the two pairs most
//! beyond their bounds, one of each joint: the diagonal through one block's
//! corner. With the other diagonal stuck, the other three blocks move as
//! one there, and that corner can slip relative to them only along both
//! planes at once: nowhere in 2D, or along the crossing line in 3D, across
//! the force that makes it slip (and nowhere where a support holds the
//! line's direction). Such a slip is not one: the loop's ties hold the
//! pairs still, their pressures are not fixed by the loop (pressing the
//! corner in raises both faces' pressures and friction, and puts the
//! other diagonal in tension), and the verdict turns from one diagonal to
//! the other. A k0 = 0.25 tunnel's initial stage (J1 and J2 at 60° and
//! 70° cut 50° corners, self-locking at tan 35°) did so at every crossing
//! on its end rollers and never converged (406 iterations and 3 cuts,
//! docs/convergence.md, "Slip hardening does not end the crossing-line
//! cycles").
//!
//! A joint can slip there only as a whole: its two pairs together, with
//! the blocks either side of it moving as two. So where the verdict lets
//! a pair slip that its crossing gives no room to ([`Room::None`], or a
//! [`Room::Line`] more than 60° from its shear force), its twin slips too
//! if it is near its own bound ([`NEAR_BOUND`]); the next solve and
//! verdict then judge the joint's slip, which is free. Far from its bound
//! the twin keeps the joint from slipping, and the pair is left to the
//! rules for a slip its loop locks (judged by its force as tied,
//! [`super::newton`]).

use super::frame::tangential;
use super::history::{cracked, law_at, History};
use super::law::{friction_bound, ContactState};
use super::pair_law::PairLaw;
use super::system::{InterfaceProblem, Room};
use crate::fem::vec3::norm;

/// A twin slips with its locked pair from this share of its bound on
/// (its shear over `b(p)` in the last solve). At 0.95 the tunnel's stage
/// did not converge (406 and 3 cuts); at 0.8 and 0.9 it did, and
/// blocks3d_confined took 27, 12 and 17, 12 iterations (27, 15 on main),
/// tunnel4sets 39 (30 on main); with any twin (0), 28, 12 and 44.
pub const NEAR_BOUND: f64 = 0.9;

/// A line of room is across a pair's shear force where the cosine of
/// their angle is below this (60°).
const ACROSS: f64 = 0.5;

/// Rounds of freeing at one crossing: it has two pairs of twins.
const ROUNDS: usize = 2;

/// Frees the slips `next` asks of pairs their crossing gives no room to,
/// by letting their twins near their bound slip too (see the module
/// header); `force` is each pair's contact force in the last solve, and a
/// freed twin takes its pair's `violation`. A twin `pinned` at a cluster's
/// candidate set keeps it: freed, it undid the candidate every iteration
/// (the 34k tunnel's pair 2078, pinned stuck, set slipping each time its
/// crossing's pair 2079 slipped, so that no candidate's trial settled).
pub(super) fn free_locked_slips(
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    h: &History,
    force: &[[f64; 3]],
    pinned: impl Fn(usize) -> bool,
    next: &mut [ContactState],
    violation: &mut [f64],
) {
    let no_room = |p: usize, room: Room| match room {
        Room::None => true,
        Room::Line(d) => {
            let t = tangential(force[p]);
            let l = norm(t);
            l > 0.0 && (d[1] * t[1] + d[2] * t[2]).abs() < ACROSS * l
        }
        Room::Free => false,
    };
    let mobilised = |q: usize| {
        let law = law_at(h, laws, q);
        let f = force[q];
        let (b, _) = friction_bound(&law.strength, cracked(h, q), problem.area(q), (-f[0]).max(0.0));
        norm(tangential(f)) / b.max(f64::MIN_POSITIVE)
    };
    // (a crossing's rooms depend on its own pairs' states alone: each is
    // freed on its own, up to a change per pair of twins)
    for jn in problem.crossings() {
        for _ in 0..ROUNDS {
            let rooms = jn.rooms(next);
            let locked = |j: usize| {
                let (p, q) = (jn.pairs[j], jn.pairs[jn.twin(j)?]);
                let twin_near =
                    next[q] == ContactState::Stick && !problem.held(q) && !pinned(q) && mobilised(q) >= NEAR_BOUND;
                (next[p] == ContactState::Slip && !problem.held(p) && no_room(p, rooms[j]) && twin_near)
                    .then_some((p, q))
            };
            let Some((p, q)) = (0..jn.pairs.len()).find_map(locked) else { break };
            next[q] = ContactState::Slip;
            violation[q] = violation[p];
        }
    }
}
