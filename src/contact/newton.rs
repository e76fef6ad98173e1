//! The robust state iteration: a semismooth Newton method on the condensed
//! interface (primal-dual active sets for 3D Coulomb friction, after Hüeber,
//! Stadler & Wohlmuth, SIAM J. Sci. Comput. 30(2), 2008).
//!
//! Per pair, in its local axes: λ the contact force on body I, p = -λ_n the
//! normal pressure force, s = r_T - r_ref the slip along the joint since the
//! pair's stick reference, b(p) = max(0, A c + f p) the Coulomb bound and
//! c_p the pair's stiffness. The law is the fixed point
//!
//! ```text
//! open:   λ = 0, gap >= 0                   closed: gap = 0, sigma_n < f_t
//! stick:  s = 0, |λ_T| < b(p)               slip:   λ_T = b(p) ξ / |ξ|,  ξ = λ_T + c_p s
//! ```
//!
//! Each iteration solves the interface system with the current sets, the
//! friction force of every slipping pair linearised at the last iterate
//! (direction n = ξ/|ξ|, β = b/|ξ| < 1):
//!
//! ```text
//! λ_T = (b + f (p - p_k)) n + k⊥ (I - n n^T) s,     k⊥ = c_p β / (1 - β)
//! ```
//!
//! which at convergence is the exact derivative of `λ_T = b(p) s / |s|`
//! (k⊥ = b / |s|): the slip direction is free in the joint plane and the
//! shear follows the normal force, both to second order. Then every pair is
//! judged by [`judge`] (its active set for the next iteration). The step has
//! converged when no state changes and every slipping pair's force agrees
//! with the nonlinear law. A state set that comes back after others (a
//! cycle the sets alone cannot leave) is broken by changing only the most
//! violated pair from then on. In 2D, a set that lets a block slide on a
//! joint that slips both ways (outwards from a point that sticks) keeps a
//! pair of it stuck ([`Newton::held_back`]): a Newton step's overshoot, not
//! a loss of equilibrium; so does, in 2D and 3D, a set under which the
//! free parts' slipping pairs carry more along their free motion than the
//! loads do there ([`super::capacity`]). A junction pair that has opened
//! twice in the step is judged by its own gap from then on, not by its
//! loop's forces, which pressed it shut and pulled it open by turns: the
//! loop holds its gap at zero whatever its state, and its least-norm
//! forces are not unique (tests/corpus/blocks3d_linear.toml, step 2: pair
//! 231, gap +5e-21, 1.5e-4 MN of tension stuck, 240 iterations without
//! end); open at zero gap with no force it meets the law exactly, and the
//! loop's other pairs carry the load.

use super::capacity::{capacities, PairLoad};
use super::cluster::{Search, Step, Watch};
use super::frame::tangential;
use super::history::{cracked, forget_step_cracks, law_at, opened_twice, History};
use super::iteration::{Next, Rule, Verdict};
use super::law::{friction_bound, judge, reads_stiffness, stiffness_in, ContactState, Trial};
use super::options::SlipLaw;
use super::outcome::{Stop, Summary};
use super::pair_law::{limit, PairLaw};
use super::system::{InterfaceProblem, InterfaceSolution, Limit, Relation};
use crate::fem::vec3::{dot, norm, sub};
use std::ops::ControlFlow;

/// The largest β = b / |ξ| the linearisation uses: k⊥ stays below 1e5 c_p
/// (a pair that just started slipping is nearly tied across its slip).
/// At the law's answer β = b / (b + c_p |s|) and k⊥ = b / |s|: a pair whose
/// slip is small beside b / c_p needs β near one, and a k⊥ capped below
/// b / |s| makes Newton's last steps linear. tests/corpus/tunnel4sets.toml's
/// crossing twins 2389 / 2390 slip 3.5e-8 m at b = 0.075 MN, c_p = 935
/// MN/m (k⊥ = 2,300 c_p): capped at 1000 c_p (0.999, the first cap, never
/// measured), their friction settled 2.6-fold a solve over the step's
/// last 14 solves.
const BETA_MAX: f64 = 0.99999;

/// Forces below this fraction of the largest pair force are round-off: a
/// stuck pair does not start slipping on them (see [`judge`]).
const FORCE_ROUND_OFF: f64 = 1e-12;

/// Below this part of the water's force on a pair, the effective normal
/// force a junction pair would carry closed is zero: the loop's forces are
/// solved with the water's as a right-hand side and resolve them to about
/// 1e-9 of it (3e-9 measured at the heel of geo/dam3d_joints_uplift.toml).
const WATER_ROUND_OFF: f64 = 1e-6;

/// Relative tolerance on the friction force of slipping pairs.
const FORCE_TOL: f64 = 1e-12;

/// Once the states have cycled, they change only when the slipping
/// pairs' friction is within this fraction of the largest force of the
/// law, or after this many iterations in a row that kept them, or once
/// a held solve has not cut the friction residual of the one before by
/// this factor (from the third held solve on): friction that turns
/// between two residuals does not settle, and waiting for it is lost.
const SETTLE_FIRST: f64 = 1e-8;
const MAX_HOLDS: usize = 4;
const HOLD_GAIN: f64 = 0.5;

/// ... or once, from a solve that is not loose, the most violated pair is
/// past its state by more than this many times the friction residual
/// (both relative to the largest force): the friction still to settle
/// moves the forces by about its residual, which cannot undo a violation
/// this much larger. `make tunnel3d` waited four holds for each of its
/// single changes at violations 6-150 times the residual: 37 iterations,
/// 27 so; tests/corpus/tunnel4sets.toml 39 and 33; the same states pair
/// by pair, and on the 28 regression cases (the wedge's safety search
/// 141 contact iterations in all, 111 so).
const DECIDED: f64 = 5.0;

/// How far clear of a loose solve's error (relative to the largest
/// force) each comparison of the cycle breaker must be for the loose
/// solve's verdict to stand ([`Newton::break_cycle`]).
const MARGIN: f64 = 10.0;

/// How many times a step keeps a pair stuck under parts a set left free
/// to slide that their slipping pairs hold ([`Newton::overshoot`]).
const MAX_OVERSHOOTS: usize = 8;

/// The robust rule through one load step: what it carries from solve to solve.
pub(super) struct Newton<'p> {
    problem: &'p InterfaceProblem<'p>,
    laws: &'p [PairLaw],
    /// The stick reference along the joint: where the step starts (no slip
    /// in this step); a pair open when the step began carries it along
    /// while it is open (it touches where it is).
    reference: Vec<[f64; 3]>,
    start: Vec<ContactState>,
    /// The last solve's forces and relative displacements (where the
    /// friction law is linearised).
    force: Vec<[f64; 3]>,
    rel: Vec<[f64; 3]>,
    /// A cycle was met: from then on only the most violated pair changes.
    one_at_a_time: bool,
    /// Iterations in a row that kept the states for the friction to settle,
    /// and the friction residual of the last of them.
    holds: usize,
    last_hold: f64,
    /// The last solve's forces of junction pairs as if their locked axes
    /// were tied (whether they stick: see `InterfaceSolution::as_tied`).
    as_tied: Vec<Option<[f64; 3]>>,
    /// The size of the water's force on each pair at the last solve (empty
    /// when dry).
    water: Vec<f64>,
    /// The states the last verdict was judged from, and how far each pair
    /// it changed was from its state (what [`Rule::hold_back`] picks by).
    judged_from: Vec<ContactState>,
    violation: Vec<f64>,
    /// Pairs kept stuck this step in place of a pair that let go (see
    /// [`Newton::held_back`], 2.).
    swapped: Vec<bool>,
    /// Times this step kept a pair stuck under parts their slipping
    /// pairs hold ([`Newton::overshoot`]).
    overshoots: usize,
    /// Where in the step's history the cycle breaker came on, and the
    /// fallback for a stall or a cycle it does not end ([`super::cluster`]).
    breaking_from: Option<usize>,
    search: Search,
    /// Each pair's in-situ force at this step's factor (empty without
    /// one): where its junction's share starts from.
    prior: Vec<[f64; 3]>,
    /// Each verdict's friction residual this step, beside the summary's
    /// state sets: where they close an orbit ([`super::orbit`]).
    residuals: Vec<f64>,
}

/// Every pair's next state, and how far each changing pair is from its
/// current state (relative to the largest force).
struct Judged {
    next: Vec<ContactState>,
    violation: Vec<f64>,
    /// The largest friction residual of pairs that keep slipping, and each one's.
    residual: f64,
    residuals: Vec<f64>,
    scale_f: f64,
}

impl<'p> Newton<'p> {
    pub fn new(problem: &'p InterfaceProblem<'p>, laws: &'p [PairLaw], h: &History, lambda: &[f64]) -> Newton<'p> {
        let factor = lambda.get(h.insitu_case).copied().unwrap_or(0.0);
        let reference = h.rel_start.iter().map(|&r| tangential(r)).collect();
        Newton {
            problem,
            laws,
            reference,
            start: h.states.clone(),
            force: h.force.clone(),
            rel: h.rel_start.clone(),
            one_at_a_time: false,
            holds: 0,
            last_hold: f64::INFINITY,
            as_tied: vec![None; laws.len()],
            water: Vec::new(),
            judged_from: Vec::new(),
            violation: Vec::new(),
            swapped: vec![false; laws.len()],
            overshoots: 0,
            breaking_from: None,
            search: Search::default(),
            prior: h.insitu.iter().map(|f| f.map(|x| factor * x)).collect(),
            residuals: Vec::new(),
        }
    }

    /// The relation pair `p` is solved with at this iteration; `line`: the
    /// one direction its junction leaves it to slip along, if so (its
    /// friction then acts along that line alone).
    fn relation(&self, h: &History, p: usize, line: Option<[f64; 3]>) -> Relation {
        let (law, area) = (&law_at(h, self.laws, p), self.problem.area(p));
        let (force, rel, reference) = (self.force[p], self.rel[p], self.reference[p]);
        let state = h.states[p];
        let target = [0.0, reference[1], reference[2]];
        if state != ContactState::Slip || law.slip == SlipLaw::Frictionless {
            return Relation::simple(state, target, [0.0; 3]);
        }
        let c = self.problem.stiffness(p);
        // (a pair that has just closed has p = 0 up to round-off: its bound
        // grows with the pressure it is about to get)
        let pk = self.search.pressure(p).unwrap_or((-force[0]).max(0.0));
        let (bk, db) = friction_bound(&law.strength, cracked(h, p), area, pk);
        let s = sub(tangential(rel), reference);
        let xi = along([0.0, force[1] + c * s[1], force[2] + c * s[2]], line);
        let lx = norm(xi);
        let scale = norm(force) + c * norm(s) + bk;
        let dir = match line {
            Some(_) => {
                let d = along(h.dir[p], line);
                let l = norm(d);
                if l > 0.0 {
                    d.map(|x| x / l)
                } else {
                    d
                }
            }
            None => h.dir[p],
        };
        let (n, beta) = if lx > 1e-14 * scale && lx > 0.0 {
            ([0.0, xi[1] / lx, xi[2] / lx], (bk / lx).min(BETA_MAX))
        } else if norm(dir) > 0.0 {
            (dir, 0.0)
        } else {
            // no direction yet (a pair that has just closed): no friction this time
            return Relation::simple(state, target, [0.0; 3]);
        };
        // the spring holds the slip across n within the directions it can
        // take: none on a line, whose only direction is n
        let kp = c * beta / (1.0 - beta);
        let mut spring = [[0.0; 3]; 3];
        for i in 1..3 {
            for j in 1..3 {
                let free = line.map_or(f64::from(u8::from(i == j)), |d| d[i] * d[j]);
                spring[i][j] = kp * (free - n[i] * n[j]);
            }
        }
        let mut constant = [0.0; 3];
        for i in 1..3 {
            constant[i] = (bk - db * pk) * n[i] - (1..3).map(|j| spring[i][j] * reference[j]).sum::<f64>();
        }
        Relation {
            state,
            target,
            force: constant,
            coupling: [0.0, db * n[1], db * n[2]],
            spring,
            pressure: pk,
            limit: Limit::NONE,
            elastic: false,
            prior: [0.0; 3],
        }
    }

    /// Judges every pair (1. of the iteration); `lines` as
    /// [`InterfaceProblem::slip_lines`] for the states solved.
    fn next_states(&self, h: &History, lines: &[Option<[f64; 3]>]) -> Judged {
        let n = self.laws.len();
        let (force, rel) = (&self.force, &self.rel);
        let scale_u = rel.iter().map(|v| norm(*v)).fold(0.0, f64::max);
        let scale_f = force.iter().map(|f| norm(*f)).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        let tol_u = 1e-10 * scale_u;
        let tol_f = FORCE_ROUND_OFF * scale_f;
        let mut next = h.states.clone();
        let mut violation = vec![0.0; n];
        let mut residuals = vec![0.0; n];
        for p in 0..n {
            let (st, law) = (h.states[p], &law_at(h, self.laws, p));
            let area = self.problem.area(p);
            let cr = cracked(h, p);
            let mut slip = sub(tangential(rel[p]), self.reference[p]);
            let mut trial_force = force[p];
            // a pair slipping on a line is judged along it
            if let (ContactState::Slip, Some(d)) = (st, lines[p]) {
                slip = along(slip, Some(d));
                let t = along(force[p], Some(d));
                trial_force = [force[p][0], t[1], t[2]];
            }
            let stiffness = stiffness_in(st, self.judged_gap(p), || self.problem.stiffness(p));
            let trial = Trial { force: trial_force, area, slip, gap: rel[p][0], stiffness };
            let coulomb = law.slip == SlipLaw::Coulomb;
            next[p] = match (self.as_tied[p], st) {
                // both sides held by supports: the supports carry it, it stays shut
                _ if self.problem.held(p) => ContactState::Stick,
                // an open junction pair its loop keeps shut: it closes (as
                // a closing pair does, where it is) unless the force it would
                // carry closed is tension beyond its strength; a force that
                // is zero to round-off of the water it balances (sigma_n' =
                // 0 where the water pressure is the contact pressure) keeps
                // it open, or it flips open and shut from solve to solve
                (Some(f), ContactState::Open)
                    if f[0]
                        >= law.strength.tensile_limit(cr) * area
                            - WATER_ROUND_OFF * self.water.get(p).unwrap_or(&0.0) =>
                {
                    ContactState::Open
                }
                // ... but one that has opened twice in the step stays open
                // while its gap does, judged as a lone pair is (see the
                // module header)
                (Some(_), ContactState::Open) if opened_twice(h, p) => {
                    judge(st, &trial, &law.strength, cr, coulomb, tol_u, tol_f)
                }
                (Some(_), ContactState::Open) => {
                    judge(st, &Trial { gap: f64::NEG_INFINITY, ..trial }, &law.strength, cr, coulomb, tol_u, tol_f)
                }
                // a slipping one it keeps from slipping: stuck if the loop
                // can carry its shear within every pair's bound; otherwise
                // judged by the force it carries slipping, the one reported
                // (slipping in tension, it opens)
                (Some(f), _) => {
                    let tied = Trial { force: f, ..trial };
                    match judge(ContactState::Stick, &tied, &law.strength, cr, coulomb, tol_u, tol_f) {
                        ContactState::Stick => ContactState::Stick,
                        _ => judge(st, &trial, &law.strength, cr, coulomb, tol_u, tol_f),
                    }
                }
                (None, _) => judge(st, &trial, &law.strength, cr, coulomb, tol_u, tol_f),
            };
            if st == ContactState::Slip && next[p] == ContactState::Slip {
                residuals[p] = friction_residual(law, cr, area, trial.stiffness, trial.force, slip);
            }
            if next[p] != st {
                let (b, _) = friction_bound(&law.strength, cr, area, -force[p][0]);
                violation[p] = match (st, next[p]) {
                    (_, ContactState::Open) => force[p][0] - law.strength.tensile_limit(cr) * area,
                    (ContactState::Stick, _) => norm(tangential(force[p])) - b,
                    (ContactState::Open, _) => -rel[p][0] / scale_u.max(f64::MIN_POSITIVE) * scale_f,
                    _ => b - norm(trial.xi()),
                } / scale_f;
            }
        }
        let residual = residuals.iter().fold(0.0, |a: f64, &b| a.max(b));
        Judged { next, violation, residual, residuals, scale_f }
    }

    /// A state set met before (a cycle): from then on only the most
    /// violated pair changes, once the slipping pairs' friction has
    /// settled under the current states (at most [`MAX_HOLDS`] iterations
    /// in a row keep them, while the friction residual keeps falling by
    /// [`HOLD_GAIN`], and the change is not already [`DECIDED`]): a
    /// change judged from a linearisation that has not settled is as
    /// likely to be undone by the next one (2. of the iteration).
    ///
    /// `loose`: the error of a loose solve's forces, relative to the
    /// largest (a change of states on the sparse interface; None for a
    /// tight one). Its verdict is taken only where each comparison it
    /// turns on (the most violated pair against the next, the violation
    /// against [`DECIDED`] residuals, the residual against
    /// [`SETTLE_FIRST`] and [`HOLD_GAIN`]) is clear of that error by
    /// [`MARGIN`]; elsewhere the same relations are solved again tightly
    /// and judged again ([`Cycle::Undecided`]), so that the breaker takes
    /// the path an exact solve takes.
    fn break_cycle(
        &mut self,
        h: &History,
        judged: &mut Judged,
        seen: &[Vec<ContactState>],
        loose: Option<f64>,
    ) -> Cycle {
        let mut changing: Vec<usize> = (0..judged.next.len()).filter(|&p| judged.next[p] != h.states[p]).collect();
        if changing.is_empty() || !(self.one_at_a_time || seen.contains(&judged.next)) {
            return Cycle::None;
        }
        // most violated first (the first of equals)
        let v = &judged.violation;
        changing.sort_by(|&a, &b| v[b].total_cmp(&v[a]).then(a.cmp(&b)));
        let violation = |k: usize| changing.get(k).map_or(0.0, |&p| v[p].max(0.0));
        let (worst, next) = (violation(0), violation(1));
        let residual = judged.residual / judged.scale_f;
        let last_hold = self.last_hold / judged.scale_f;
        let held = (self.holds >= 2).then_some(last_hold);
        if loose.is_some_and(|error| !sure(error, [worst, next], residual, held)) {
            judged.next.clone_from(&h.states);
            return Cycle::Undecided;
        }
        let met = if self.one_at_a_time { Cycle::None } else { Cycle::Met };
        self.one_at_a_time = true;
        let settling = self.holds < 2 || residual < HOLD_GAIN * last_hold;
        let decided = worst > DECIDED * residual;
        if residual > SETTLE_FIRST && self.holds < MAX_HOLDS && settling && !decided {
            self.holds += 1;
            self.last_hold = judged.residual;
            judged.next.clone_from(&h.states);
            return met;
        }
        self.holds = 0;
        self.last_hold = f64::INFINITY;
        for &p in &changing[1..] {
            judged.next[p] = h.states[p];
        }
        met
    }

    /// Step 2 of the iteration: a cycle broken ([`Newton::break_cycle`]),
    /// or, where the states stall or cycle all the same, the fallback of
    /// [`super::cluster`] set going. Where the cycle is
    /// [`Cycle::Undecided`], the verdict waits for a tight solve
    /// ([`Next::Again`]).
    fn break_or_pin(
        &mut self,
        h: &History,
        judged: &mut Judged,
        summary: &mut Summary,
        tolerance: f64,
        loose: bool,
    ) -> ControlFlow<Next> {
        match self.break_cycle(h, judged, &summary.history, loose.then(|| tolerance / judged.scale_f)) {
            Cycle::Undecided => return ControlFlow::Break(Next::Again),
            Cycle::Met => {
                summary.cycles_broken += 1;
                self.breaking_from = Some(summary.history.len().saturating_sub(1));
            }
            Cycle::None => {}
        }
        let problem = self.problem;
        let w = Watch {
            current: &h.states,
            start: &self.start,
            history: &summary.history,
            breaking_from: self.breaking_from,
            residuals: &judged.residuals,
            residual: judged.residual,
            tolerance,
            loose,
            forces: &self.force,
            fixed: &|p| problem.held(p),
        };
        self.search.watch(&w, &mut judged.next);
        ControlFlow::Continue(())
    }

    /// While a cluster's set is held: of the other pairs the verdict
    /// changes, only the most violated one changes (the cycle breaker's
    /// rule), so that the pairs round the cluster settle under the set
    /// rather than cycle round it.
    fn one_change(&self, h: &History, judged: &mut Judged) {
        let v = &judged.violation;
        let changing = (0..judged.next.len()).filter(|&p| !self.search.pins(p) && judged.next[p] != h.states[p]);
        let worst = changing.clone().max_by(|&a, &b| v[a].total_cmp(&v[b]).then(b.cmp(&a)));
        for p in changing.filter(|&p| Some(p) != worst).collect::<Vec<_>>() {
            judged.next[p] = h.states[p];
        }
    }

    /// Pairs that open in tension below their f_t: the Coulomb apex c / f
    /// opened them.
    fn apex_openings(&self, h: &History, next: &[ContactState]) -> usize {
        (0..next.len())
            .filter(|&p| next[p] == ContactState::Open && h.states[p] != ContactState::Open)
            .filter(|&p| {
                let (ft, _) = law_at(h, self.laws, p).strength.effective(cracked(h, p));
                self.force[p][0] < ft * self.problem.area(p)
            })
            .count()
    }
}

impl Newton<'_> {
    /// The pair to keep stuck when the states the last verdict chose leave
    /// the parts `sliding` free to slide. A Newton step overshoots where
    /// slip spreads over a joint: in 2D a slipping pair's linearised
    /// friction holds nothing along its slip, so a set in which every pair
    /// of a block slips leaves it free, although a joint that slips both
    /// ways (towards a point that sticks, as under an auxetic block pressed
    /// onto its base, or away from it, as under a soft pad) has a pair near
    /// that point that carries less than its bound once the others slip.
    /// Where the part's pairs pull it both ways (their last forces, global
    /// axes), the part does not slide as a block, and
    ///
    /// 1. if the verdict let several stuck pairs go at once, the one of them
    ///    that exceeded its bound the least, and has a strength, sticks;
    /// 2. if it let one go (to slip or open), the part's slipping pair
    ///    whose friction pulls against that one's shear and that is nearest
    ///    to sticking (smallest `|ξ| - b`) sticks in its place, each pair
    ///    once a step.
    ///
    /// In 3D a slipping pair's friction holds across its slip (see
    /// `InterfaceProblem::free`): neither applies. Then, in 2D and 3D,
    ///
    /// 3. where the slipping pairs of the free parts can carry more along
    ///    their free motion than the loads do there ([`capacities`]), the
    ///    set is an overshoot too, and the pair of theirs that moves in that
    ///    motion and is nearest to sticking sticks ([`Newton::overshoot`],
    ///    [`Rule::hold_back`]).
    ///
    /// Otherwise none: the loads exceed what the contacts carry, a loss of
    /// equilibrium.
    fn held_back(&self, h: &History, sliding: &[usize]) -> Option<(usize, Hold)> {
        let (before, n) = (&self.judged_from, h.states.len());
        if before.len() != n || self.problem.nd() != 2 {
            return None;
        }
        let on = |p: usize, part: usize| self.problem.parts_of(p).contains(&part);
        let both_ways = |part: usize| {
            let pulls: Vec<[f64; 3]> = (0..n)
                .filter(|&p| h.states[p] == ContactState::Slip && on(p, part))
                .map(|p| self.pull(p, part))
                .collect();
            pulls.iter().enumerate().any(|(i, a)| pulls[i + 1..].iter().any(|b| dot(*a, *b) < 0.0))
        };
        let parts: Vec<usize> = sliding.iter().copied().filter(|&part| both_ways(part)).collect();
        let released: Vec<usize> = (0..n)
            .filter(|&p| {
                before[p] == ContactState::Stick
                    && h.states[p] != ContactState::Stick
                    && parts.iter().any(|&q| on(p, q))
            })
            .collect();
        if (0..n).filter(|&p| h.states[p] != before[p]).count() >= 2 {
            // (a pair that carries no shear once cracked holds nothing stuck)
            let strong = released.iter().copied().filter(|&p| {
                let law = &law_at(h, self.laws, p);
                let s = &law.strength;
                law.slip == SlipLaw::Coulomb && (s.friction > 0.0 || s.residual_cohesion > 0.0)
            });
            if let Some(p) = least(strong, |p| self.violation[p]) {
                return Some((p, Hold::Released));
            }
        }
        let &[q] = released.as_slice() else { return None };
        let part = *parts.iter().find(|&&part| on(q, part))?;
        let shear = self.pull(q, part);
        let against = (0..n).filter(|&p| {
            h.states[p] == ContactState::Slip && before[p] == ContactState::Slip && !self.swapped[p] && on(p, part)
        });
        least(against.filter(|&p| dot(self.pull(p, part), shear) < 0.0), |p| self.excess(h, p))
            .map(|p| (p, Hold::InPlace))
    }

    /// The opening pair `p` is judged at, as `law::stiffness_in` asks it:
    /// the last solve's, or -∞ where a junction's loop keeps it shut (it is
    /// judged closing).
    fn judged_gap(&self, p: usize) -> f64 {
        if self.as_tied[p].is_some() {
            f64::NEG_INFINITY
        } else {
            self.rel[p][0]
        }
    }

    /// How far slipping pair `p`'s last force is past its bound, `|ξ| - b`.
    fn excess(&self, h: &History, p: usize) -> f64 {
        let slip = sub(tangential(self.rel[p]), self.reference[p]);
        let trial = Trial {
            force: self.force[p],
            area: self.problem.area(p),
            slip,
            gap: self.rel[p][0],
            stiffness: self.problem.stiffness(p),
        };
        norm(trial.xi())
            - friction_bound(&law_at(h, self.laws, p).strength, cracked(h, p), trial.area, -trial.force[0]).0
    }

    /// Rule 3 of [`Newton::held_back`]: the pair to keep stuck where the
    /// slipping pairs of a group of the parts `sliding` carry more along
    /// the group's free motion than its loads do there ([`capacities`]):
    /// of its slipping pairs that move in that motion and have a strength,
    /// the one nearest to sticking. None where no group is held so (a loss
    /// of equilibrium), or after [`MAX_OVERSHOOTS`] such holds this step.
    fn overshoot(&self, h: &History, sliding: &[usize]) -> Option<usize> {
        if self.overshoots >= MAX_OVERSHOOTS {
            return None;
        }
        let pairs = self.pair_loads(h);
        let pb = self.problem;
        let ties = pb.sliding_ties(&self.relations(h));
        let groups = capacities(pb.part_modes(), &ties, sliding, &pairs);
        groups.iter().filter(|g| g.holds()).find_map(|g| {
            let fast = g.slip.iter().fold(0.0, |a: f64, &b| a.max(b));
            let moving = (0..pairs.len()).filter(|&p| pairs[p].bound > 0.0 && g.slip[p] > 1e-6 * fast);
            least(moving, |p| self.excess(h, p))
        })
    }

    /// Every pair as [`capacities`] reads it under the states in `h`: its
    /// last force, and its bound at its last normal force where it slips.
    fn pair_loads(&self, h: &History) -> Vec<PairLoad> {
        let pb = self.problem;
        let frames = pb.frames();
        (0..h.states.len())
            .map(|p| {
                let (f, fr, law) = (self.force[p], &frames[p], &law_at(h, self.laws, p));
                let coulomb = law.slip == SlipLaw::Coulomb;
                let bound = |cracked| friction_bound(&law.strength, cracked, pb.area(p), (-f[0]).max(0.0)).0;
                let slips = coulomb && h.states[p] == ContactState::Slip;
                PairLoad {
                    parts: pb.parts_of(p),
                    x: pb.positions()[p],
                    normal: fr[0],
                    force: std::array::from_fn(|i| (0..3).map(|a| f[a] * fr[a][i]).sum()),
                    bound: if slips { bound(cracked(h, p)) } else { 0.0 },
                }
            })
            .collect()
    }

    /// The tangential force of pair `p` on `part` (one of its sides) in the
    /// last solve, global axes.
    fn pull(&self, p: usize, part: usize) -> [f64; 3] {
        let frame = &self.problem.frames()[p];
        let side = if self.problem.parts_of(p)[0] == part { 1.0 } else { -1.0 };
        let f = self.force[p];
        std::array::from_fn(|i| side * (f[1] * frame[1][i] + f[2] * frame[2][i]))
    }

    /// The directions of the pairs that slip `next` (3. of the iteration;
    /// a fallback where ξ vanishes), with the stiffness of those that
    /// start slipping formed together, and every pair's normal stress.
    fn keep_directions(
        &self,
        h: &mut History,
        lines: &[Option<[f64; 3]>],
        next: &[ContactState],
        solution: &InterfaceSolution,
    ) {
        self.problem.prepare_stiffness((0..next.len()).filter(|&p| next[p] == ContactState::Slip));
        for (p, &line) in lines.iter().enumerate() {
            if next[p] == ContactState::Slip {
                let slip = sub(tangential(self.rel[p]), self.reference[p]);
                let c = self.problem.stiffness(p);
                let xi = along([0.0, self.force[p][1] + c * slip[1], self.force[p][2] + c * slip[2]], line);
                let l = norm(xi);
                if l > 0.0 {
                    h.dir[p] = [0.0, xi[1] / l, xi[2] / l];
                }
            }
            h.sigma_n[p] = solution.pairs[p].sigma_n;
        }
    }
}

impl Rule for Newton<'_> {
    fn relations(&self, h: &History) -> Vec<Relation> {
        // the stiffness the relations and the next verdict read of slipping
        // pairs, formed together (an open pair's, where the verdict reads
        // it, in `judge`)
        self.problem.prepare_stiffness((0..h.states.len()).filter(|&p| h.states[p] == ContactState::Slip));
        let lines = self.problem.slip_lines(&h.states);
        (0..self.laws.len())
            .map(|p| {
                let within = limit(&law_at(h, self.laws, p), cracked(h, p), self.problem.area(p));
                let prior = self.prior.get(p).copied().unwrap_or([0.0; 3]);
                self.relation(h, p, lines[p]).within(within).after(prior)
            })
            .collect()
    }

    fn judge(&mut self, h: &mut History, solution: &InterfaceSolution, summary: &mut Summary) -> Verdict {
        self.force.clone_from(&solution.forces);
        self.rel.clone_from(&solution.rel);
        self.as_tied.clone_from(&solution.as_tied);
        self.water.clone_from(&solution.water);
        for p in 0..self.laws.len() {
            if h.states[p] == ContactState::Open && self.start[p] == ContactState::Open {
                self.reference[p] = tangential(self.rel[p]);
            }
        }
        // the stiffness of the open pairs that close or overlap, or that a
        // junction's loop keeps shut, formed together: the verdict and the
        // law's residual read it (`law::stiffness_in`)
        self.problem.prepare_stiffness(
            (0..h.states.len())
                .filter(|&p| h.states[p] == ContactState::Open && reads_stiffness(h.states[p], self.judged_gap(p))),
        );
        // 1. the next state of every pair; 2. a cycle broken, or a cluster's
        // set held (an iterative solve resolves the forces only to its residual)
        let lines = self.problem.slip_lines(&h.states);
        let mut judged = self.next_states(h, &lines);
        self.residuals.push(judged.residual);
        let tolerance = (FORCE_TOL * judged.scale_f).max(solution.accuracy);
        let settled = judged.residual <= tolerance;
        let tight = !solution.loose && !solution.inexact;
        let fed = (!solution.loose).then_some(judged.residual);
        if self.search.feed(&h.states, &judged.next, &solution.forces, settled && tight, fed) {
            summary.clusters_solved += 1;
        }
        let flow = match self.search.judge(&h.states, &mut judged.next, settled && tight) {
            Some(Step::Solved) => {
                summary.clusters_solved += 1;
                ControlFlow::Continue(())
            }
            Some(Step::Held) => {
                self.one_change(h, &mut judged);
                ControlFlow::Continue(())
            }
            Some(Step::GaveUp) | None => self.break_or_pin(h, &mut judged, summary, tolerance, solution.loose),
        };
        if let ControlFlow::Break(next) = flow {
            return Verdict { next, settled, law: judged.residual };
        }
        // a slip a crossing of two joints locks freed by its twin
        let pinned = |p: usize| self.search.pins(p);
        super::crossing::free_locked_slips(
            self.problem,
            self.laws,
            h,
            &self.force,
            pinned,
            &mut judged.next,
            &mut judged.violation,
        );
        // a cluster's pair held stuck is judged with the cracks of the set
        // held, not those of the iterates that cycled
        let held_stuck =
            (0..judged.next.len()).filter(|&p| self.search.pins(p) && judged.next[p] == ContactState::Stick);
        forget_step_cracks(h, held_stuck);
        summary.apex_openings += self.apex_openings(h, &judged.next);
        self.keep_directions(h, &lines, &judged.next, solution);
        self.judged_from.clone_from(&h.states);
        self.violation = judged.violation;
        // an orbit the search has nothing left to change repeats for ever
        if self.search.done() && super::orbit::period(&summary.history, &self.residuals).is_some() {
            summary.stop = Some(Stop::Cycled);
        }
        Verdict { next: Next::States(judged.next), settled, law: judged.residual }
    }

    /// A set the last verdict chose leaves `sliding` free to slide (see
    /// [`Newton::held_back`]): one pair of theirs sticks instead, and the
    /// step is solved again; false when none may, the parts do slide.
    fn hold_back(&mut self, h: &mut History, sliding: &[usize]) -> bool {
        // (a pair of a cluster's set held is not kept stuck: the set is rejected)
        let free = |p: &usize| !self.search.pins(*p);
        if let Some((p, how)) = self.held_back(h, sliding).filter(|(p, _)| free(p)) {
            h.states[p] = ContactState::Stick;
            self.swapped[p] |= how == Hold::InPlace;
            return true;
        }
        if self.judged_from.len() == h.states.len() {
            if let Some(p) = self.overshoot(h, sliding).filter(free) {
                h.states[p] = ContactState::Stick;
                self.overshoots += 1;
                return true;
            }
        }
        self.search.reject(&mut h.states)
    }

    fn slip_reference(&self) -> Option<&[[f64; 3]]> {
        Some(&self.reference)
    }

    /// The stick references of this step are where its pairs are tied from now on.
    fn commit(self, h: &mut History) {
        h.offset = self.reference;
    }
}

/// Whether the cycle breaker's verdict on a loose solve whose forces are
/// within `error` (relative to the largest) is the one an exact solve
/// would give: each comparison it turns on is clear of that error by
/// [`MARGIN`] times. `violations`: the worst changing pair's and the
/// next's; `residual`: the friction residual; `held`: the residual of
/// the last solve that held the states, where [`HOLD_GAIN`] is read
/// (from the third hold on). All relative to the largest force.
fn sure(error: f64, violations: [f64; 2], residual: f64, held: Option<f64>) -> bool {
    let clear = |a: f64, b: f64| (a - b).abs() > MARGIN * error;
    let [worst, next] = violations;
    clear(worst, next)
        && clear(worst, DECIDED * residual)
        && clear(residual, SETTLE_FIRST)
        && held.is_none_or(|h| clear(residual, HOLD_GAIN * h))
}

/// What [`Newton::break_cycle`] made of a verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Cycle {
    /// No cycle met for the first time (none, or one already being broken).
    None,
    /// The cycle met for the first time: from now on one change at a time.
    Met,
    /// A cycle met, or being broken, on a loose solve: its relations are
    /// to be solved again tightly before a change is taken.
    Undecided,
}

/// Which pair [`Newton::held_back`] keeps stuck: one of those the verdict
/// let go (1.), or a slipping one in place of the one it let go (2.).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Hold {
    Released,
    InPlace,
}

/// The pair of `pairs` with the smallest `value` (the first of equals).
fn least(pairs: impl Iterator<Item = usize>, value: impl Fn(usize) -> f64) -> Option<usize> {
    pairs.map(|p| (value(p), p)).min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1))).map(|(_, p)| p)
}

/// The shear of `v` (local axes) along `line`, or all of it without one.
fn along(v: [f64; 3], line: Option<[f64; 3]>) -> [f64; 3] {
    match line {
        Some(d) => {
            let s = v[1] * d[1] + v[2] * d[2];
            [0.0, s * d[1], s * d[2]]
        }
        None => tangential(v),
    }
}

/// How far a slipping pair's force is from the nonlinear law, `|λ_T - b ξ/|ξ||`.
fn friction_residual(law: &PairLaw, cracked: bool, area: f64, c: f64, force: [f64; 3], slip: [f64; 3]) -> f64 {
    let lt = tangential(force);
    if law.slip == SlipLaw::Frictionless {
        return norm(lt);
    }
    let (b, _) = friction_bound(&law.strength, cracked, area, -force[0]);
    let xi = [0.0, lt[1] + c * slip[1], lt[2] + c * slip[2]];
    let lx = norm(xi);
    if lx == 0.0 {
        return norm(lt);
    }
    norm([0.0, lt[1] - b * (xi[1] / lx), lt[2] - b * (xi[2] / lx)])
}

#[cfg(test)]
mod tests {
    use super::sure;

    /// The 86k tunnel's loose verdicts (docs/convergence.md, the
    /// forty-second session) stand; one whose two worst pairs, or whose
    /// violation and decided bound, are within ten errors of each other
    /// does not, nor one whose residual is that near `SETTLE_FIRST` or
    /// the last hold's half.
    #[test]
    fn a_loose_verdict_stands_where_its_error_cannot_change_it() {
        // decided by 134 residuals, pairs 0.015 apart, error 1e-7
        assert!(sure(1.06e-7, [8.36e-2, 6.88e-2], 6.24e-4, None));
        // not decided (0.0186 against 5 x 0.0114), clear all the same
        assert!(sure(6.7e-8, [1.86e-2, 1.61e-2], 1.14e-2, None));
        // the two worst pairs within ten errors: which changes is not known
        assert!(!sure(1e-7, [8.36e-2, 8.36e-2 - 5e-7], 6.24e-4, None));
        // a lone change: its violation against none
        assert!(sure(1e-7, [4.2e-4, 0.0], 2.8e-3, None));
        assert!(!sure(1e-4, [4.2e-4, 0.0], 2.8e-3, None));
        // the violation within ten errors of DECIDED residuals
        assert!(!sure(1e-7, [5e-3 + 5e-7, 0.0], 1e-3, None));
        // the residual at SETTLE_FIRST, or at half the last hold's
        assert!(!sure(1e-9, [1e-2, 0.0], 1.2e-8, None));
        assert!(!sure(1e-7, [1e-1, 0.0], 1e-3, Some(2e-3 + 1e-6)));
        assert!(sure(1e-7, [1e-1, 0.0], 1e-3, Some(4e-3)));
    }
}
