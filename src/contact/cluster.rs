//! The cluster fallback of the robust rule: where the state iteration
//! stalls or cycles on a few pairs, their pressures are solved for, then
//! their state sets tried one by one.
//!
//! The semismooth Newton iteration judges every pair from the last solve.
//! At a crossing whose slipping pairs wedge it (their friction's gain on
//! their pressures at or beyond 1) the iterates with all of them slipping
//! do not settle: with the states held the friction residual grows from
//! solve to solve (a stall), or the cycle breaker turns one pair back and
//! forth for ever (a cycle). Either their pressures must be solved
//! together or one of them must stick, and the iteration, judging each
//! pair alone, does neither.
//!
//! [`Search`] watches the verdicts. It fires when
//!
//! - the states have been held for [`STALL`] tight solves and the slipping
//!   pairs' friction residual has not decreased over them (a stall), or
//!   has fallen by less than [`SLOW`] (slow: a first one only solves for
//!   pressures, below), or it has grown [`DIVERGING`]-fold in each of
//!   the last two (a stall too, seen sooner), or
//! - once the cycle breaker is on, the iteration has gone back [`REVISITS`]
//!   times to a state set it had already solved with (a cycle).
//!
//! A first stall is often no want of a state set: a junction takes its
//! slipping pairs' pressures from the last solve where its loops carry
//! none of them, and where their friction's gain on those pressures is 1
//! or more that fixed point diverges although the set has a solution;
//! below 1 it converges, but only linearly where Newton's steps converge
//! quadratically (the unconfined block mass in tet4,
//! tests/corpus/blocks3d_linear.toml, step 2: four pairs' residual fell
//! by 0.67 a solve, 31 solves after its states settled). A first stall
//! or slow run solves for those pressures: the
//! slipping pairs whose friction residual is at least [`SHARE`] of the
//! worst are linearised at pressures solved for by multisecant (Anderson)
//! steps on the last solves ([`Secant`]: exact in `m + 1` solves where the
//! solve is affine in their `m` pressures) until the states change, the
//! friction settles (the stall is solved) or, once its window of `m + 1`
//! solves is full, [`STALL`] solves in a row have left the residual no
//! lower than where the stall was seen (the steps do nothing). Where the
//! friction's direction moves with the pressures the solve is not affine
//! in them and the steps converge more slowly: the four-set tunnel in tet4
//! (tests/corpus/tunnel4sets_linear.toml) solved a crossing's twin pairs'
//! pressures in 15 solves, the residual falling by 1e5 with ups and
//! downs, its last solves within a few times what the solves resolve the
//! forces to: a bound on the solves, or on the residual's fall over a
//! few of them, ends such a secant unsolved (docs/corpus.md, "Where the
//! 35 go").
//!
//! A second stall, or a cycle, makes a *cluster*: for a stall the
//! slipping pairs far from the law as above, for a cycle the pairs that
//! changed state since the cycle breaker came on (or in the last
//! [`WINDOW`] iterations, if more), at most [`MAX_PAIRS`], those that
//! changed most and are furthest from the law first. Its candidate sets
//! are every combination of stick and slip of its pairs (and open, for a
//! pair open now or in the window, or that the law opened in a set
//! tried), but the set it stalled or cycled in; they are tried in this
//! order: fewest pairs changed from the step's start, then from the
//! current set, then stick before slip before open pair by pair (at most
//! [`MAX_SETS`]).
//!
//! A candidate is tried on the whole interface: the cluster's pairs are
//! held at it while the other pairs are judged as usual but change one at
//! a time, the most violated first (as under the cycle breaker: where
//! they all changed at once, the pairs round a cluster kept changing
//! whatever set it held). Once the others keep their states and the
//! friction has settled, the candidate is taken
//! if every cluster pair is judged to keep its state too (the law holds at
//! every pair: the iteration has converged), and rejected otherwise, as it
//! is after [`TRIAL`] iterations that do not settle or when it leaves a
//! part free to slide. So the solution the iteration finds, where it needs
//! the candidates, is the admissible one with the fewest of the cluster's
//! pairs changed from the step's start: the least slip. Once every
//! candidate is rejected the search gives up for the step, and the
//! iteration goes on as before it fired.

use super::law::ContactState;
use nalgebra::{DMatrix, DVector};

/// Tight solves in a row with the states held over which a friction
/// residual that has not decreased is a stall.
const STALL: usize = 4;

/// Tight held solves whose friction residual fell by less than this
/// factor over [`STALL`] of them are slow: a Newton step's residual falls
/// by orders of magnitude a solve, a lagged pressure's fixed point by its
/// gain (0.67 a solve at the block mass: 0.2 over four).
const SLOW: f64 = 0.1;

/// Tight held solves whose friction residual grew by more than this factor
/// in each of the last two are diverging: a lagged fixed point whose gain
/// is beyond 1, a stall known without waiting out [`STALL`] solves. The
/// four-set tunnel in tet4 (tests/corpus/tunnel4sets_linear.toml): its
/// residual grew about 3.5 times a solve twice, for five and six held
/// solves each; 62 iterations -> 35, the same states pair by pair.
const DIVERGING: f64 = 2.0;

/// Returns to an earlier state set, once the cycle breaker is on, that
/// make a cycle the breaker does not end.
const REVISITS: usize = 2;

/// The iterations of a cycle whose changes make the cluster.
const WINDOW: usize = 8;

/// A slipping pair whose friction residual is at least this share of the
/// worst pair's is in the cluster.
const SHARE: f64 = 0.1;

/// Directions of the secant steps' least squares whose singular value is
/// below this share of the matrix's norm are dropped: the last solves
/// did not move the residual along them beyond their own error, and no
/// pressures remove an error. A junction's loop carries the sum of its
/// slipping pairs' pressures, to round-off: the four-set tunnel in tet4's
/// twins 2101 / 2102 (0.4429 MN in sum) left 1e-6 of it in every
/// residual, and fitting that moved their share by 2e-3 away from the
/// answer (0.2179 -> 0.2163; it settled at 0.2182), 18 solves in all;
/// at 1e-3, 15 (tests/corpus/tunnel4sets_linear.toml: 35 iterations ->
/// 32; dense 40 -> 38; the same states).
const SECANT_CUTOFF: f64 = 1e-3;

/// The most pairs in a cluster, and sets tried.
const MAX_PAIRS: usize = 6;
const MAX_SETS: usize = 64;

/// Iterations a candidate has for the other pairs to settle.
const TRIAL: usize = 8;

/// The fallback through one load step.
#[derive(Default)]
pub(super) struct Search {
    mode: Mode,
    /// The friction residuals of the tight solves in a row that held the states.
    held: Vec<f64>,
    /// Returns to an earlier set since the cycle breaker came on.
    revisits: usize,
    /// A stall's pressures have been solved for once this step.
    solved_pressures: bool,
}

#[derive(Default)]
enum Mode {
    #[default]
    Watching,
    Secant(Secant),
    Pinned(Pinned),
    Done,
}

/// A stall's slipping pairs whose pressures their friction is linearised
/// at (a junction takes its slipping pairs' pressures from there where its
/// loops carry none of them): the fixed point of those pressures, which
/// diverges where their friction's gain on them is 1 or more, solved for
/// by multisecant (Anderson) steps on the last `pairs + 1` solves, exact
/// once the solve is affine in them.
struct Secant {
    pairs: Vec<usize>,
    /// The pressures the next solve is linearised at.
    x: Vec<f64>,
    /// Those of the last solves, and the pressures those solves gave.
    xs: Vec<Vec<f64>>,
    gs: Vec<Vec<f64>>,
    /// The friction residual where the stall was seen, and those of its
    /// solves that were not loose, once the window was full.
    start: f64,
    residuals: Vec<f64>,
}

impl Secant {
    /// Secant steps on the pressures of `pairs`, from `x`, for a stall seen
    /// at friction residual `start`.
    fn new(pairs: Vec<usize>, x: Vec<f64>, start: f64) -> Secant {
        Secant { pairs, x, xs: Vec::new(), gs: Vec::new(), start, residuals: Vec::new() }
    }

    /// The solves the steps are taken on: `pairs + 1`.
    fn window(&self) -> usize {
        self.pairs.len() + 1
    }

    /// Whether the window holds all the solves it keeps.
    fn window_full(&self) -> bool {
        self.gs.len() >= self.window()
    }

    /// The pressures `g` the solve linearised at `x` gave: the next `x`.
    fn step(&mut self, g: Vec<f64>) {
        self.xs.push(std::mem::take(&mut self.x));
        self.gs.push(g);
        if self.xs.len() > self.window() {
            self.xs.remove(0);
            self.gs.remove(0);
        }
        let (m, k) = (self.pairs.len(), self.xs.len() - 1);
        if k == 0 {
            self.x = self.gs[0].clone();
            return;
        }
        let f = |j: usize, i: usize| self.gs[j][i] - self.xs[j][i];
        // least ||f_k + sum_j beta_j (f_j - f_k)||, then x = g_k + sum_j beta_j (g_j - g_k)
        let a = DMatrix::from_fn(m, k, |i, j| f(j, i) - f(k, i));
        let b = DVector::from_fn(m, |i, _| -f(k, i));
        let beta = (crate::fem::bounded::svd(a.clone(), true, true))
            .and_then(|svd| svd.solve(&b, SECANT_CUTOFF * a.norm()).ok())
            .unwrap_or_else(|| DVector::zeros(k));
        self.x = (0..m)
            .map(|i| {
                let x = self.gs[k][i] + (0..k).map(|j| beta[j] * (self.gs[j][i] - self.gs[k][i])).sum::<f64>();
                x.max(0.0)
            })
            .collect();
    }
}

/// The cluster and its candidate sets, one held at a time.
struct Pinned {
    pairs: Vec<usize>,
    /// The states each pair may take, and the cluster's states at the
    /// step's start and when the search fired (what the sets are ordered by).
    alphabet: Vec<Vec<ContactState>>,
    start: Vec<ContactState>,
    current: Vec<ContactState>,
    /// The sets tried (those before `at`), the one held and those to try.
    sets: Vec<Vec<ContactState>>,
    at: usize,
    trial: usize,
}

impl Pinned {
    /// A rejected set whose pairs the law sent to states they may not yet
    /// take (`judged`: theirs): they may now, and the sets not yet tried
    /// are made again.
    fn widen(&mut self, judged: &[ContactState]) {
        let mut wider = false;
        for (states, &s) in self.alphabet.iter_mut().zip(judged) {
            if !states.contains(&s) {
                states.push(s);
                wider = true;
            }
        }
        if wider {
            let tried = &self.sets[..=self.at];
            let fresh: Vec<_> = ordered(&self.alphabet, &self.start, &self.current)
                .into_iter()
                .filter(|s| !tried.contains(s))
                .collect();
            self.sets.truncate(self.at + 1);
            self.sets.extend(fresh);
            self.sets.truncate(MAX_SETS);
        }
    }
}

/// What the search made of one verdict while it held a candidate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Step {
    /// The candidate is held (the verdict's next states rewritten).
    Held,
    /// The candidate holds and every pair keeps its state: converged.
    Solved,
    /// Every candidate was rejected: the verdict is the rule's own.
    GaveUp,
}

/// What the search watches of one verdict.
pub(super) struct Watch<'a> {
    /// The states solved with, and those at the step's start.
    pub current: &'a [ContactState],
    pub start: &'a [ContactState],
    /// Every set solved with this step (the current one last).
    pub history: &'a [Vec<ContactState>],
    /// Where in `history` the cycle breaker came on, if it has.
    pub breaking_from: Option<usize>,
    /// Each slipping pair's friction residual (0 elsewhere), the worst,
    /// and the residual the friction counts as settled at.
    pub residuals: &'a [f64],
    pub residual: f64,
    pub tolerance: f64,
    /// The solve was loose (its forces judge states, not the friction).
    pub loose: bool,
    /// Its forces (local axes).
    pub forces: &'a [[f64; 3]],
    /// Pairs the cluster may not take (held by supports on both sides).
    pub fixed: &'a dyn Fn(usize) -> bool,
}

impl Search {
    /// The pressure force slipping pair `p`'s friction is linearised at,
    /// where a stall's pressures are being solved for.
    pub fn pressure(&self, p: usize) -> Option<f64> {
        let Mode::Secant(sec) = &self.mode else { return None };
        sec.pairs.iter().position(|&q| q == p).map(|i| sec.x[i])
    }

    /// While a stall's pressures are solved for: the `forces` of the solve
    /// with `current` give the next pressures, until the states change or
    /// the steps stall (then the search watches again). True when the
    /// solve kept the states and its friction `settled`: the stall is over.
    /// `residual`: the solve's friction residual, None where it was loose.
    pub fn feed(
        &mut self,
        current: &[ContactState],
        next: &[ContactState],
        forces: &[[f64; 3]],
        settled: bool,
        residual: Option<f64>,
    ) -> bool {
        let Mode::Secant(sec) = &mut self.mode else { return false };
        if next == current && settled {
            self.mode = Mode::Done;
            return true;
        }
        if sec.window_full() {
            sec.residuals.extend(residual);
        }
        let r = &sec.residuals;
        let stalled = r.len() >= STALL && r[r.len() - STALL..].iter().all(|&x| x >= sec.start);
        if next != current || stalled {
            self.mode = Mode::Watching;
            self.held.clear();
            return false;
        }
        sec.step(sec.pairs.iter().map(|&p| (-forces[p][0]).max(0.0)).collect());
        false
    }

    /// Whether the search is over for the step (solved, or every
    /// candidate rejected): it changes no verdict from now on.
    pub fn done(&self) -> bool {
        matches!(self.mode, Mode::Done)
    }

    /// Whether pair `p` is held at a candidate now.
    pub fn pins(&self, p: usize) -> bool {
        matches!(&self.mode, Mode::Pinned(pin) if pin.pairs.contains(&p))
    }

    /// While a candidate is held: judges it from the verdict `next` on the
    /// solve with `current` (`settled`: the friction agrees with the law
    /// and the solve was tight), and rewrites `next` to the candidate held
    /// next. None when no candidate is held.
    pub fn judge(&mut self, current: &[ContactState], next: &mut [ContactState], settled: bool) -> Option<Step> {
        let Mode::Pinned(pin) = &mut self.mode else { return None };
        pin.trial += 1;
        let set = &pin.sets[pin.at];
        let others_kept = (0..next.len()).all(|p| pin.pairs.contains(&p) || next[p] == current[p]);
        if others_kept && settled {
            let judged: Vec<ContactState> = pin.pairs.iter().map(|&p| next[p]).collect();
            if &judged == set {
                self.mode = Mode::Done;
                return Some(Step::Solved);
            }
            pin.widen(&judged);
            return Some(self.advance(next));
        }
        if pin.trial >= TRIAL {
            return Some(self.advance(next));
        }
        pin.pairs.iter().zip(set).for_each(|(&p, &s)| next[p] = s);
        Some(Step::Held)
    }

    /// The candidate held in `states` leaves a part free to slide: the
    /// next one is held instead (true), or none is left (false).
    pub fn reject(&mut self, states: &mut [ContactState]) -> bool {
        matches!(&self.mode, Mode::Pinned(_)) && self.advance(states) == Step::Held
    }

    /// Rejects the candidate held and writes the next into `next`.
    fn advance(&mut self, next: &mut [ContactState]) -> Step {
        let Mode::Pinned(pin) = &mut self.mode else { return Step::GaveUp };
        pin.at += 1;
        pin.trial = 0;
        match pin.sets.get(pin.at) {
            Some(set) => {
                pin.pairs.iter().zip(set).for_each(|(&p, &s)| next[p] = s);
                Step::Held
            }
            None => {
                self.mode = Mode::Done;
                Step::GaveUp
            }
        }
    }

    /// Watches a verdict `next` (the cycle breaker's already): when the
    /// iteration stalls or cycles, holds the cluster's first candidate in
    /// `next` and returns true.
    pub fn watch(&mut self, w: &Watch, next: &mut [ContactState]) -> bool {
        if !matches!(self.mode, Mode::Watching) {
            return false;
        }
        let kept = next == w.current;
        if !kept {
            self.held.clear();
        } else if !w.loose && w.residual > w.tolerance {
            self.held.push(w.residual);
        }
        let k = self.held.len();
        let grew = |i: usize| self.held[i] > DIVERGING * self.held[i - 1];
        let diverging = k >= 3 && grew(k - 1) && grew(k - 2);
        let stalled = diverging || (k > STALL && self.held[k - 1] >= self.held[k - 1 - STALL]);
        let slow = diverging || (k > STALL && self.held[k - 1] > SLOW * self.held[k - 1 - STALL]);
        if let Some(from) = w.breaking_from {
            if !kept && w.history[from.min(w.history.len())..].iter().any(|s| s.as_slice() == &next[..]) {
                self.revisits += 1;
            }
        }
        if !slow && self.revisits < REVISITS {
            return false;
        }
        if slow && !self.solved_pressures {
            self.solved_pressures = true;
            let pairs: Vec<usize> =
                cluster(w, &[], next, true).into_iter().filter(|&p| w.current[p] == ContactState::Slip).collect();
            if !pairs.is_empty() {
                let x = pairs.iter().map(|&p| (-w.forces[p][0]).max(0.0)).collect();
                self.mode = Mode::Secant(Secant::new(pairs, x, w.residual));
                return false;
            }
        }
        if !stalled && self.revisits < REVISITS {
            return false;
        }
        let from = window_start(w, stalled);
        let pairs = cluster(w, &w.history[from..], next, stalled);
        let alphabet = alphabet(&pairs, w.current, &w.history[from..]);
        let start: Vec<ContactState> = pairs.iter().map(|&p| w.start[p]).collect();
        let current: Vec<ContactState> = pairs.iter().map(|&p| w.current[p]).collect();
        let sets = ordered(&alphabet, &start, &current);
        if sets.is_empty() {
            self.mode = Mode::Done;
            return false;
        }
        pairs.iter().zip(&sets[0]).for_each(|(&p, &s)| next[p] = s);
        self.mode = Mode::Pinned(Pinned { pairs, alphabet, start, current, sets, at: 0, trial: 0 });
        true
    }
}

/// Where in the step's history the cluster's window starts: a stall's
/// window is its held solves (nothing changed in them); a cycle's reaches
/// back to where the cycle breaker came on, or [`WINDOW`] iterations if
/// that is further. The breaker keeps all but one pair of a cycle in
/// place, so the pairs that cycled together before it may take turns
/// after it, each changing alone: blocks3d_confined's pairs 211 and 335
/// traded stick and slip together twice, then 211 slipped once and 335
/// cycled alone, and a window of the last eight iterations held 335 only.
fn window_start(w: &Watch, stalled: bool) -> usize {
    let n = w.history.len();
    match (stalled, w.breaking_from) {
        (true, _) => n,
        (false, Some(from)) => from.min(n.saturating_sub(WINDOW)),
        (false, None) => n.saturating_sub(WINDOW),
    }
}

/// The pairs that changed in `window` (and from the current set to
/// `next`), in order; for a `stall` (none changed), the slipping pairs far
/// from the law. A cycle's slipping pairs whose friction has not settled
/// to round-off are not its cause: with them blocks3d_confined's cycle
/// made a cluster of pair 335 and five slipping pairs round it, whose
/// sets, held stuck, set the pairs round them trading slip and open
/// (law residual 3.4e-2 after 300 iterations; 3.1e-5 without them).
fn cluster(w: &Watch, window: &[Vec<ContactState>], next: &[ContactState], stall: bool) -> Vec<usize> {
    let n = w.current.len();
    let mut changes = vec![0usize; n];
    let sets: Vec<&[ContactState]> = window.iter().map(Vec::as_slice).chain([next]).collect();
    for pair in sets.windows(2) {
        (0..n).filter(|&p| pair[0][p] != pair[1][p]).for_each(|p| changes[p] += 1);
    }
    let worst = w.residuals.iter().fold(0.0, |a: f64, &b| a.max(b));
    let far = |p: usize| stall && w.residuals[p] > w.tolerance && w.residuals[p] >= SHARE * worst;
    let mut pairs: Vec<usize> = (0..n).filter(|&p| !(w.fixed)(p) && (changes[p] > 0 || far(p))).collect();
    pairs.sort_by(|&a, &b| changes[b].cmp(&changes[a]).then(w.residuals[b].total_cmp(&w.residuals[a])).then(a.cmp(&b)));
    pairs.truncate(MAX_PAIRS);
    pairs.sort_unstable();
    pairs
}

/// The states each of the cluster's `pairs` may take at first: stick and
/// slip, and open for a pair open now or in the `window`.
fn alphabet(pairs: &[usize], current: &[ContactState], window: &[Vec<ContactState>]) -> Vec<Vec<ContactState>> {
    use ContactState::{Open, Slip, Stick};
    pairs
        .iter()
        .map(|&p| {
            if current[p] == Open || window.iter().any(|s| s[p] == Open) {
                vec![Stick, Slip, Open]
            } else {
                vec![Stick, Slip]
            }
        })
        .collect()
}

/// The cluster's candidate sets from its `alphabet` in the order they are
/// tried (see the module header), without the `current` one.
fn ordered(alphabet: &[Vec<ContactState>], start: &[ContactState], current: &[ContactState]) -> Vec<Vec<ContactState>> {
    let mut sets: Vec<Vec<ContactState>> = vec![Vec::new()];
    for states in alphabet {
        sets = sets.iter().flat_map(|s| states.iter().map(move |&x| [s.as_slice(), &[x]].concat())).collect();
    }
    let differ = |set: &[ContactState], from: &[ContactState]| set.iter().zip(from).filter(|(a, b)| a != b).count();
    sets.retain(|s| differ(s, current) > 0);
    // (ContactState orders open < slip < stick: stick first is the reverse)
    sets.sort_by_cached_key(|s| {
        let order: Vec<std::cmp::Reverse<ContactState>> = s.iter().map(|&x| std::cmp::Reverse(x)).collect();
        (differ(s, start), differ(s, current), order)
    });
    sets.truncate(MAX_SETS);
    sets
}

#[cfg(test)]
mod tests {
    use super::ContactState::{Open, Slip, Stick};
    use super::*;

    fn watch<'a>(
        current: &'a [ContactState],
        history: &'a [Vec<ContactState>],
        residuals: &'a [f64],
        fixed: &'a dyn Fn(usize) -> bool,
    ) -> Watch<'a> {
        Watch {
            current,
            start: &[Stick; 4],
            history,
            breaking_from: None,
            residuals,
            residual: residuals.iter().fold(0.0, |a: f64, &b| a.max(b)),
            tolerance: 1e-12,
            loose: false,
            forces: &[[0.0; 3]; 4],
            fixed,
        }
    }

    #[test]
    fn a_stall_pins_the_slipping_pairs_far_from_the_law_least_slip_first() {
        let current = [Slip, Slip, Stick, Slip];
        let history = vec![current.to_vec(); 6];
        let residuals = [1e-2, 2e-3, 0.0, 5e-4];
        let never = |_| false;
        let mut search = Search::default();
        let mut next = current.to_vec();
        let stall = |search: &mut Search, next: &mut Vec<ContactState>| {
            (0..5)
                .map(|k| {
                    let w = Watch {
                        residual: 1e-2 * (1.0 + 0.05 * k as f64),
                        ..watch(&current, &history, &residuals, &never)
                    };
                    next.copy_from_slice(&current);
                    search.watch(&w, next)
                })
                .collect::<Vec<bool>>()
        };
        // five held solves whose residual grew: first the slipping pairs'
        // pressures are solved for (pair 3 is below 10 % of the worst)
        assert_eq!(stall(&mut search, &mut next), [false; 5]);
        assert_eq!((search.pressure(0), search.pressure(1), search.pressure(3)), (Some(0.0), Some(0.0), None));
        // the states change: watching again; a second stall pins the cluster
        assert!(!search.feed(&current, &[Stick, Slip, Stick, Slip], &[[0.0; 3]; 4], true, Some(1e-2)));
        assert_eq!(search.pressure(0), None);
        assert_eq!(stall(&mut search, &mut next), [false, false, false, false, true]);
        assert!(search.pins(0) && search.pins(1) && !search.pins(2) && !search.pins(3), "pair 3 is below 10 %");
        assert_eq!(next, [Stick, Stick, Stick, Slip], "both stuck: nearest the step's start");
        // the others keep their states, but pair 0 would slip again: the next set
        let mut judged = next.clone();
        judged[0] = Slip;
        let held = next.clone();
        assert_eq!(search.judge(&held, &mut judged, true), Some(Step::Held));
        assert_eq!(judged, [Stick, Slip, Stick, Slip], "one pair from the start, stick first pair by pair");
        // that one holds: converged
        let held = judged.clone();
        assert_eq!(search.judge(&held, &mut judged, true), Some(Step::Solved));
        assert_eq!(judged, held);
        assert_eq!(search.judge(&held, &mut judged, true), None, "done for the step");
    }

    #[test]
    fn a_slow_fall_of_the_friction_residual_solves_for_the_pressures_a_fast_one_does_not() {
        let current = [Slip, Slip, Stick, Slip];
        let history = vec![current.to_vec(); 6];
        let residuals = [1e-2, 2e-3, 0.0, 5e-4];
        let never = |_| false;
        // five held solves whose residual falls by `gain` a solve
        let held = |gain: f64| {
            let mut search = Search::default();
            let mut next = current.to_vec();
            for k in 0..5 {
                let w = Watch { residual: 1e-2 * gain.powi(k), ..watch(&current, &history, &residuals, &never) };
                assert!(!search.watch(&w, &mut next), "no cluster is pinned on a fall");
            }
            search.pressure(0)
        };
        // 0.67 a solve: 0.2 over four, above SLOW; 0.5 a solve: 0.0625, below
        assert_eq!(held(0.67), Some(0.0), "slow: the pressures are solved for");
        assert_eq!(held(0.5), None, "a fall as fast as this is left to the rule");
    }

    #[test]
    fn multisecant_steps_find_a_fixed_point_that_plain_iteration_leaves() {
        // g(x) = A x + c, gain 1.05 along the first axis: x = g(x) diverges
        let g = |x: &[f64]| vec![1.05 * x[0] + 0.1 * x[1] - 0.4, 0.9 * x[1] + 0.3];
        let mut sec = Secant::new(vec![7, 9], vec![1.0, 1.0], 1.0);
        for _ in 0..3 {
            let out = g(&sec.x);
            sec.step(out);
        }
        assert!((sec.x[0] - 2.0).abs() < 1e-9 && (sec.x[1] - 3.0).abs() < 1e-9, "{:?}", sec.x);
    }

    #[test]
    fn multisecant_steps_leave_the_sum_a_junction_carries_to_its_round_off() {
        // the four-set tunnel in tet4's twins 2101 / 2102: the pressures
        // their friction was linearised at and those the solves gave
        // (iterations 16-18); the loop carries their sum, 0.442888 MN, to
        // about 1e-6, and their share settled at 0.218164
        let x = vec![0.331160875425858, 0.1117271430618192];
        let gs = [
            [0.3279490701284237, 0.11493980788445227],
            [0.33784221055562685, 0.10504839697422341],
            [0.3310853528470162, 0.11180531108612769],
        ];
        let mut sec = Secant::new(vec![2101, 2102], x, 1.78e-4);
        for g in gs {
            sec.step(g.to_vec());
        }
        // (with every direction kept, 0.216316: away from it, 18 solves to settle)
        let share = sec.x[0] - sec.x[1];
        assert!((share - 0.218164).abs() < 1e-4, "the next share {share}: {:?}", sec.x);
    }

    #[test]
    fn multisecant_steps_that_leave_the_residual_where_the_stall_was_end() {
        let states = [Slip, Slip];
        // how many solves the secant lasts through, from a stall at `start`
        let lasts = |start: f64, residuals: &[f64]| {
            let mut search =
                Search { mode: Mode::Secant(Secant::new(vec![0, 1], vec![1.0, 1.0], start)), ..Search::default() };
            // (the window of m + 1 = 3 solves fills first, whatever the residual)
            (residuals.iter())
                .take_while(|&&r| {
                    search.feed(&states, &states, &[[-1.0, 0.0, 0.0]; 2], false, Some(r));
                    search.pressure(0).is_some()
                })
                .count()
        };
        assert_eq!(
            lasts(1.0, &[1.0, 5.0, 9.0, 1.0, 1.1, 0.9, 1.2, 1.3, 1.4, 1.5, 1.6]),
            9,
            "four solves at or above 1"
        );
        // the four-set tunnel in tet4's twin pairs, solve by solve until
        // their friction settled (tests/corpus/tunnel4sets_linear.toml),
        // the last ones at a few times what the solves resolve (4e-9)
        let tunnel = [
            6.16e-4, 2.41e-3, 7.42e-3, 5.33e-4, 9.08e-5, 1.73e-5, 3.16e-7, 5.32e-7, 1.37e-6, 3.12e-7, 1.26e-7, 9.50e-9,
            1.50e-8, 1.36e-8, 5.61e-8, 1.26e-8,
        ];
        assert_eq!(lasts(1.78e-4, &tunnel), tunnel.len(), "a residual that fell goes on, up and down");
    }

    #[test]
    fn a_cycle_pins_the_pairs_that_changed_and_gives_up_when_every_set_fails() {
        let a = vec![Stick, Slip, Stick, Stick];
        let b = vec![Stick, Stick, Stick, Stick];
        let history = vec![a.clone(), b.clone(), a.clone(), b.clone()];
        let residuals = [0.0; 4];
        let fixed = |p| p == 3;
        let mut search = Search::default();
        let w = Watch { breaking_from: Some(0), ..watch(&b, &history, &residuals, &fixed) };
        let mut next = a.clone();
        assert!(!search.watch(&w, &mut next), "one return to an earlier set");
        let mut next = a.clone();
        assert!(search.watch(&w, &mut next), "the second");
        assert!(search.pins(1) && !search.pins(0));
        // the cluster is pair 1 alone; its one other set than the current is slip
        assert_eq!(next, a);
        let mut judged = b.clone();
        assert_eq!(search.judge(&a, &mut judged, true), Some(Step::GaveUp));
        assert!(!search.reject(&mut judged));
    }

    #[test]
    fn a_cycle_pins_the_pairs_that_cycled_together_before_the_breaker_came_on() {
        // pairs 0 and 1 flip together, the breaker comes on (index 2), pair
        // 0 changes once, then pair 1 flips alone for more than WINDOW
        // iterations; pair 2 slips, its friction not settled
        let (a, b) = (vec![Stick, Stick, Slip, Stick], vec![Slip, Slip, Slip, Stick]);
        let mut history = vec![a.clone(), b.clone(), a.clone(), vec![Slip, Stick, Slip, Stick]];
        for k in 0..WINDOW + 2 {
            history.push(vec![Slip, [Stick, Slip][k % 2], Slip, Stick]);
        }
        let current = history.last().unwrap().clone();
        let mut next = current.clone();
        next[1] = [Stick, Slip][usize::from(current[1] == Stick)];
        let residuals = [0.0, 0.0, 1e-9, 0.0];
        let never = |_| false;
        let w = Watch { breaking_from: Some(2), ..watch(&current, &history, &residuals, &never) };
        let from = window_start(&w, false);
        assert_eq!(from, 2, "back to where the breaker came on");
        assert_eq!(cluster(&w, &history[from..], &next, false), [0, 1], "pair 2 did not cycle");
        // without the breaker's start the window is the last WINDOW iterations: pair 1 alone
        let late = Watch { breaking_from: None, ..w };
        let from = window_start(&late, false);
        assert_eq!(cluster(&late, &history[from..], &next, false), [1]);
        // a stall's cluster is its slipping pairs far from the law
        assert_eq!(cluster(&w, &[], &current, true), [2]);
    }

    #[test]
    fn open_is_tried_for_pairs_that_opened_or_that_the_law_opens() {
        let current = [Open, Slip, Stick, Stick];
        let history = vec![current.to_vec()];
        let letters = alphabet(&[0, 1], &current, &history);
        let sets = ordered(&letters, &[Stick, Stick], &[Open, Slip]);
        assert_eq!(sets.len(), 5, "3 x 2 sets but the current one");
        assert_eq!(sets[0], [Stick, Stick]);
        assert!(sets.iter().all(|s| s[1] != Open));
        // a set rejected where the law opened pair 1: it may open from then on
        let mut pin = Pinned {
            pairs: vec![0, 1],
            alphabet: letters,
            start: vec![Stick, Stick],
            current: vec![Open, Slip],
            sets,
            at: 0,
            trial: 0,
        };
        pin.widen(&[Stick, Open]);
        assert_eq!(pin.sets.len(), 8, "3 x 3 sets but the current one");
        assert_eq!(pin.sets[..2], [[Stick, Stick], [Stick, Slip]], "then one change from the start, stick first");
        assert_eq!(pin.sets[2], [Open, Stick]);
        assert_eq!(pin.sets[3], [Stick, Open]);
    }
}
