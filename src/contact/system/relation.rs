//! What a pair's unknowns are asked to satisfy in one solve ([`Relation`]:
//! its state, targets and linearised friction force) and what it can carry
//! ([`Limit`]).

use crate::contact::law::ContactState;

/// What a pair's unknowns are asked to satisfy in one solve.
#[derive(Clone, Copy, Debug)]
pub struct Relation {
    pub state: ContactState,
    /// `r` on tied axes: stick ties all axes, slip the normal one (its
    /// target is 0: the pair touches).
    pub target: [f64; 3],
    /// On free tangential axes of slipping pairs, the force on body I is
    /// `force + coupling * p + spring * r` (local t, b components; p = -λ_n
    /// the normal pressure force), so that a Newton step can linearise the
    /// Coulomb law; zero for the paper's fixed friction force.
    pub force: [f64; 3],
    pub coupling: [f64; 3],
    pub spring: [[f64; 3]; 3],
    /// The normal pressure force p the relation was linearised at: a pair
    /// at a junction whose pressure is not solved for (see
    /// [`super::junction::pressure`]) takes `force + coupling * pressure`.
    pub pressure: f64,
    /// What the pair can carry, for a junction choosing its tied forces.
    pub limit: Limit,
    /// A joint that deforms ([`crate::contact::elastic`]): no axis is
    /// tied, open or closed; closed, its force on body I is `force +
    /// spring r` on every axis (`coupling` unused: a slipping pair's
    /// friction follows its normal spring through `spring`'s t / b rows'
    /// normal column).
    pub elastic: bool,
    /// Its force under the in-situ stress (local axes; zero without one):
    /// a junction's loops keep their part of it (see [`super::junction`]).
    pub prior: [f64; 3],
}

/// What a pair can carry in force, `λ_n <= tension` and `|λ_T| <= cohesion
/// - friction λ_n` (λ on body I, tension positive; cohesion and tension are
/// strengths times the pair's area): where a junction's tied forces are not
/// unique, it takes the least-norm ones within these (see [`super::junction`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    pub tension: f64,
    pub cohesion: f64,
    pub friction: f64,
}

impl Limit {
    /// No limit.
    pub const NONE: Limit = Limit { tension: f64::INFINITY, cohesion: f64::INFINITY, friction: 0.0 };
}

impl Relation {
    /// Stuck at `target`, open, or slipping with a known tangential force.
    pub fn simple(state: ContactState, target: [f64; 3], force: [f64; 3]) -> Relation {
        Relation {
            state,
            target,
            force,
            coupling: [0.0; 3],
            spring: [[0.0; 3]; 3],
            pressure: 0.0,
            limit: Limit::NONE,
            elastic: false,
            prior: [0.0; 3],
        }
    }

    /// A joint that deforms, in `state`: closed, its force is `force +
    /// spring r`; open, nothing.
    pub fn elastic(state: ContactState, force: [f64; 3], spring: [[f64; 3]; 3]) -> Relation {
        Relation { force, spring, elastic: true, ..Relation::simple(state, [0.0; 3], [0.0; 3]) }
    }

    /// The force of a joint that deforms at the relative displacement `r`
    /// (zero where it is open).
    pub fn spring_force(&self, r: [f64; 3]) -> [f64; 3] {
        if self.state == ContactState::Open {
            return [0.0; 3];
        }
        std::array::from_fn(|a| self.force[a] + (0..3).map(|c| self.spring[a][c] * r[c]).sum::<f64>())
    }

    /// The same relation with what the pair can carry.
    pub fn within(self, limit: Limit) -> Relation {
        Relation { limit, ..self }
    }

    /// The same relation with its in-situ force.
    pub fn after(self, prior: [f64; 3]) -> Relation {
        Relation { prior, ..self }
    }

    pub fn free_axis(&self, a: usize) -> bool {
        if self.elastic {
            return true;
        }
        match self.state {
            ContactState::Stick => false,
            ContactState::Slip => a > 0,
            ContactState::Open => true,
        }
    }
}
