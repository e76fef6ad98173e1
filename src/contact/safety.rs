//! Strength reduction: the factor of safety against sliding, as PLAXIS's
//! Safety phase (φ–c reduction) and RS2/RS3's shear strength reduction
//! define it. The strength of the chosen contacts is divided by a factor F,
//!
//! ```text
//! f_F = f / F   (f = tan φ)      c_F = c / F   (and the residual cohesion)      f_t,F = f_t / F
//! ```
//!
//! each switchable ([`Reduce`]), until no equilibrium is found; F is the
//! factor at which it is lost. Since c / f and f_t / c are left as they
//! are, the Coulomb apex c / f does not move.
//!
//! During the search a pair that cracks keeps its peak cohesion, the
//! limit-equilibrium convention, or the scene's residual cohesion
//! ([`Strengths`]).
//!
//! The search ([`upward`]) starts from the state that holds at F = 1 and
//! raises F step by step, every trial starting from the last state that
//! held (friction depends on the path), until a trial fails or F reaches
//! its bound; then it bisects between the last F that held and the first
//! that failed until they differ by at most `tolerance × F`. A scene that
//! already fails at F = 1 is searched below 1 ([`downward`]): every trial
//! there runs the load path from its start with the strengths raised to
//! 1 / F of the scene's. Only converged trials decide ([`Verdict`]): one
//! that neither holds nor fails is passed over while bracketing and ends
//! the bisection, and [`Bracket::decided`] says whether the factor is
//! closed all the same. What a trial is (one more contact iteration on the
//! condensed interface, or raised loads) is the caller's: these functions
//! only choose the factors, from what each trial returns.

use super::law::Strength;
use super::pair_law::PairLaw;

/// Which strength parameters are divided by F.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reduce {
    /// The friction coefficient f = tan φ.
    pub friction: bool,
    /// The cohesion and the residual cohesion.
    pub cohesion: bool,
    pub tensile_strength: bool,
}

impl Reduce {
    /// Every parameter (the default).
    pub const ALL: Reduce = Reduce { friction: true, cohesion: true, tensile_strength: true };

    /// The scene-file names of the parameters reduced.
    pub fn names(&self) -> Vec<&'static str> {
        [(self.friction, "friction"), (self.cohesion, "cohesion"), (self.tensile_strength, "tensile_strength")]
            .into_iter()
            .filter(|p| p.0)
            .map(|p| p.1)
            .collect()
    }

    /// The strength divided by `factor` where asked.
    pub fn strength(&self, s: &Strength, factor: f64) -> Strength {
        let by = |on: bool, v: f64| if on { v / factor } else { v };
        Strength {
            friction: by(self.friction, s.friction),
            cohesion: by(self.cohesion, s.cohesion),
            residual_cohesion: by(self.cohesion, s.residual_cohesion),
            tensile_strength: by(self.tensile_strength, s.tensile_strength),
        }
    }
}

/// The laws of every pair at the factor `factor`: those of the pairs
/// `chosen` reduced, the others as they are.
pub fn reduced(laws: &[PairLaw], chosen: &[bool], reduce: Reduce, factor: f64) -> Vec<PairLaw> {
    (laws.iter().zip(chosen))
        .map(|(l, &on)| if on { PairLaw { strength: reduce.strength(&l.strength, factor), ..*l } } else { *l })
        .collect()
}

/// Which strength a pair has during the search once it has slipped or
/// opened. Limit equilibrium (Hoek & Bray, USACE, RocPlane, Swedge) keeps
/// each joint's peak strength over the whole sliding surface; the load
/// steps' crack memory gives a pair that slips its residual cohesion
/// (0 unless the scene says), which brittle joints may want.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strengths {
    /// The cohesion a pair keeps once it slips or opens is its peak
    /// cohesion (the tensile strength is lost where it cracks, as in the
    /// load steps): the limit-equilibrium convention, the default.
    Peak,
    /// The scene's residual cohesion, as in the load steps.
    Residual,
}

impl Strengths {
    /// The scene-file spelling (`[safety] strength`).
    pub fn key(self) -> &'static str {
        match self {
            Strengths::Peak => "peak",
            Strengths::Residual => "residual",
        }
    }

    /// The other one.
    pub fn other(self) -> Strengths {
        match self {
            Strengths::Peak => Strengths::Residual,
            Strengths::Residual => Strengths::Peak,
        }
    }

    /// The laws the search starts from: the scene's, with the peak
    /// cohesion kept where a pair cracks for [`Strengths::Peak`].
    pub fn laws(self, laws: &[PairLaw]) -> Vec<PairLaw> {
        match self {
            Strengths::Residual => laws.to_vec(),
            Strengths::Peak => laws
                .iter()
                .map(|l| PairLaw { strength: Strength { residual_cohesion: l.strength.cohesion, ..l.strength }, ..*l })
                .collect(),
        }
    }

    /// Whether the two differ for these laws: some pair loses cohesion
    /// where it cracks.
    pub fn differ(laws: &[PairLaw]) -> bool {
        laws.iter().any(|l| l.strength.residual_cohesion < l.strength.cohesion)
    }
}

/// How the factors are chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Steps {
    /// The increase of F from trial to trial while bracketing (> 0).
    pub step: f64,
    /// The bracket is closed when `fails - holds <= tolerance * holds`.
    pub tolerance: f64,
    /// The largest F tried; below 1, the smallest is 1 / max_factor.
    pub max_factor: f64,
}

/// What a trial found: a state that holds, a loss of equilibrium found by
/// a converged iteration, or neither (the iteration did not converge even
/// when retried): such a trial decides nothing.
pub enum Verdict<S, E> {
    Holds(S),
    Fails(E),
    Undecided(E),
}

/// Where a search ended: the largest factor that held (with the caller's
/// state there) and the smallest that failed (with why), both from
/// converged trials, and the trials that decided nothing. `fails` is None
/// when the search reached `max_factor` and it held (or when no trial
/// above the last hold was decided); `holds` is None when a search below 1
/// reached 1 / max_factor and it failed.
pub struct Bracket<S, E> {
    pub holds: Option<(f64, S)>,
    pub fails: Option<(f64, E)>,
    pub undecided: Vec<(f64, E)>,
}

impl<S, E> Bracket<S, E> {
    /// Whether converged trials alone closed the bracket to the tolerance
    /// (or reached the bound holding): the factor is decided.
    pub fn decided(&self, steps: &Steps) -> bool {
        match (&self.holds, &self.fails) {
            (Some((h, _)), Some((f, _))) => f - h <= steps.tolerance * h * (1.0 + 1e-9),
            (Some((h, _)), None) => self.undecided.iter().all(|u| u.0 < *h) && *h >= steps.max_factor,
            (None, Some((f, _))) => self.undecided.iter().all(|u| u.0 > *f),
            (None, None) => false,
        }
    }
}

/// What bracketing upward does with a trial that decides nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OnUndecided {
    /// Passes it over: the next factor is tried from the same hold.
    PassOver,
    /// Ends the search there, undecided: for a caller with another way to
    /// decide F (rigid joints that fall back to joints that deform).
    Stop,
}

/// F from 1 up: `trial(F, from)` runs the trial at F from the state `from`
/// of the last factor that held (`start` at F = 1). A trial that decides
/// nothing is passed over while bracketing (the next factor is tried from
/// the same hold), or ends the search as `on_undecided` says, and ends
/// the bisection.
pub fn upward<S, E>(
    steps: &Steps,
    start: S,
    on_undecided: OnUndecided,
    mut trial: impl FnMut(f64, &S) -> Verdict<S, E>,
) -> Bracket<S, E> {
    let mut holds = (1.0, start);
    let mut undecided = Vec::new();
    let mut k = 0;
    let fails = loop {
        k += 1;
        let f = (1.0 + k as f64 * steps.step).min(steps.max_factor);
        match trial(f, &holds.1) {
            Verdict::Holds(s) => holds = (f, s),
            Verdict::Fails(e) => break (f, e),
            Verdict::Undecided(e) => {
                undecided.push((f, e));
                if on_undecided == OnUndecided::Stop {
                    return Bracket { holds: Some(holds), fails: None, undecided };
                }
            }
        }
        if f >= steps.max_factor {
            return Bracket { holds: Some(holds), fails: None, undecided };
        }
    };
    let (holds, fails) = bisect(steps, holds, fails, &mut undecided, |f, from: &S| trial(f, from));
    Bracket { holds: Some(holds), fails: Some(fails), undecided }
}

/// F from 1 down, when F = 1 fails with `at_one`: `trial(F)` runs the whole
/// load path at F from its start.
pub fn downward<S, E>(steps: &Steps, at_one: E, mut trial: impl FnMut(f64) -> Verdict<S, E>) -> Bracket<S, E> {
    let lowest = 1.0 / steps.max_factor;
    let mut fails = (1.0, at_one);
    let mut undecided = Vec::new();
    let mut k = 0;
    let holds = loop {
        k += 1;
        let f = (1.0 - k as f64 * steps.step).max(lowest);
        match trial(f) {
            Verdict::Holds(s) => break (f, s),
            Verdict::Fails(e) => fails = (f, e),
            Verdict::Undecided(e) => undecided.push((f, e)),
        }
        if f <= lowest {
            return Bracket { holds: None, fails: Some(fails), undecided };
        }
    };
    let (holds, fails) = bisect(steps, holds, fails, &mut undecided, |f, _: &S| trial(f));
    Bracket { holds: Some(holds), fails: Some(fails), undecided }
}

/// Halves the bracket (`holds` below `fails`) until it is within the
/// tolerance, each trial from the state of the last factor that held; a
/// trial that decides nothing ends it (the bracket stays as converged
/// trials left it).
fn bisect<S, E>(
    steps: &Steps,
    mut holds: (f64, S),
    mut fails: (f64, E),
    undecided: &mut Vec<(f64, E)>,
    mut trial: impl FnMut(f64, &S) -> Verdict<S, E>,
) -> ((f64, S), (f64, E)) {
    while fails.0 - holds.0 > steps.tolerance * holds.0 {
        let f = 0.5 * (holds.0 + fails.0);
        match trial(f, &holds.1) {
            Verdict::Holds(s) => holds = (f, s),
            Verdict::Fails(e) => fails = (f, e),
            Verdict::Undecided(e) => {
                undecided.push((f, e));
                break;
            }
        }
    }
    (holds, fails)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::SlipLaw;

    const STEPS: Steps = Steps { step: 0.1, tolerance: 1e-3, max_factor: 10.0 };

    #[test]
    fn every_switch_divides_its_own_parameter_and_no_other() {
        let s = Strength { friction: 0.6, cohesion: 2.0, tensile_strength: 1.0, residual_cohesion: 0.5 };
        assert_eq!(
            Reduce::ALL.strength(&s, 2.0),
            Strength { friction: 0.3, cohesion: 1.0, tensile_strength: 0.5, residual_cohesion: 0.25 }
        );
        let only_f = Reduce { friction: true, cohesion: false, tensile_strength: false };
        assert_eq!(only_f.strength(&s, 2.0), Strength { friction: 0.3, ..s });
        assert_eq!(only_f.names(), vec!["friction"]);
        let c_ft = Reduce { friction: false, cohesion: true, tensile_strength: true };
        assert_eq!(
            c_ft.strength(&s, 4.0),
            Strength { friction: 0.6, cohesion: 0.5, tensile_strength: 0.25, residual_cohesion: 0.125 }
        );
        // the Coulomb apex c / f stays where it is when both are reduced
        let r = Reduce::ALL.strength(&s, 3.7);
        assert!((r.cohesion / r.friction - s.cohesion / s.friction).abs() < 1e-12);
        // pairs not chosen keep their law
        let law = PairLaw { strength: s, slip: SlipLaw::Coulomb, stiffness: None };
        let laws = reduced(&[law, law], &[true, false], Reduce::ALL, 2.0);
        assert_eq!((laws[0].strength.friction, laws[1].strength), (0.3, s));
    }

    /// Each trial's factor and the factor of the state it started from.
    type Log = Vec<(f64, Option<f64>)>;

    /// A structure that holds while F <= limit; each state lists the
    /// factors that led to it (to see that trials start from the last hold).
    fn search_up(limit: f64, steps: &Steps) -> (Bracket<Vec<f64>, f64>, Log) {
        let mut log = Vec::new();
        let b = upward(steps, vec![1.0], OnUndecided::PassOver, |f, from: &Vec<f64>| {
            log.push((f, from.last().copied()));
            if f <= limit {
                Verdict::Holds([&from[..], &[f]].concat())
            } else {
                Verdict::Fails(f)
            }
        });
        (b, log)
    }

    #[test]
    fn upward_brackets_by_steps_then_bisects_to_the_tolerance_from_the_last_hold() {
        let (b, log) = search_up(1.2345, &STEPS);
        let (h, path) = b.holds.expect("holds");
        let (f, e) = b.fails.expect("fails");
        assert!(h <= 1.2345 && f > 1.2345 && f - h <= 1e-3 * h, "bracket [{h}, {f}]");
        assert_eq!(e, f);
        // 1.1, 1.2 hold; 1.3 fails; then halving 0.1 down to 1e-3: 7 trials
        let first: Vec<f64> = log[..3].iter().map(|t| t.0).collect();
        assert!(first.iter().zip([1.1, 1.2, 1.3]).all(|(a, b)| (a - b).abs() < 1e-12), "{first:?}");
        assert_eq!(log.len(), 3 + 7);
        // every trial starts from the last factor that held, and the path is monotone
        for w in path.windows(2) {
            assert!(w[1] > w[0], "{path:?}");
        }
        for (f, from) in &log {
            assert!(from.is_some_and(|x| x < *f));
        }
    }

    #[test]
    fn upward_says_when_it_reaches_its_bound_and_when_the_first_step_fails() {
        let (b, log) = search_up(100.0, &Steps { max_factor: 1.45, ..STEPS });
        assert!(b.fails.is_none(), "bound reached");
        assert_eq!(b.holds.expect("holds").0, 1.45);
        assert_eq!(log.last().map(|t| t.0), Some(1.45), "the bound itself is tried");
        let (b, _) = search_up(1.0004, &STEPS);
        let (h, _) = b.holds.expect("F = 1 holds");
        assert!((1.0..=1.0004).contains(&h) && b.fails.expect("fails").0 <= 1.0 + 1e-3 * h + 1e-15);
    }

    #[test]
    fn downward_finds_a_factor_below_one_from_fresh_starts_or_says_none_held() {
        let mut tried = Vec::new();
        let b = downward(&STEPS, 1.0, |f| {
            tried.push(f);
            if f <= 0.6789 {
                Verdict::Holds(f)
            } else {
                Verdict::Fails(f)
            }
        });
        let (h, s) = b.holds.expect("holds");
        let (f, _) = b.fails.expect("fails");
        assert!(h <= 0.6789 && f > 0.6789 && f - h <= 1e-3 * h && s == h, "[{h}, {f}]");
        assert!((tried[0] - 0.9).abs() < 1e-12 && (tried[3] - 0.6).abs() < 1e-12);
        let b = downward(&STEPS, 1.0, Verdict::<f64, f64>::Fails);
        assert!(b.holds.is_none());
        assert!((b.fails.expect("fails").0 - 0.1).abs() < 1e-12, "down to 1 / max_factor");
    }

    #[test]
    fn a_trial_that_decides_nothing_is_passed_over_and_leaves_the_bracket_open() {
        // holds up to 1.2345, but the iteration does not converge at 1.3
        let b = upward(&STEPS, 1.0, OnUndecided::PassOver, |f, _: &f64| {
            if (f - 1.3).abs() < 1e-9 {
                Verdict::Undecided(f)
            } else if f <= 1.2345 {
                Verdict::Holds(f)
            } else {
                Verdict::Fails(f)
            }
        });
        // 1.3 passed over, 1.4 fails: the bisection tries 1.3 again and stops
        let (h, f) = (b.holds.as_ref().expect("holds").0, b.fails.as_ref().expect("fails").0);
        assert!((h - 1.2).abs() < 1e-12 && (f - 1.4).abs() < 1e-12, "[{h}, {f}]");
        assert_eq!(b.undecided.len(), 2);
        assert!(!b.decided(&STEPS));
        // undecided only where converged trials bracket anyway: decided
        let b = upward(&STEPS, 1.0, OnUndecided::PassOver, |f, _: &f64| {
            if (f - 1.5).abs() < 1e-9 {
                Verdict::Undecided(f)
            } else if f <= 1.2345 {
                Verdict::Holds(f)
            } else {
                Verdict::Fails(f)
            }
        });
        assert!(b.decided(&STEPS) && b.undecided.is_empty());
        // nothing decided above the last hold up to the bound: open
        let open = |f, _: &f64| if f <= 1.1 { Verdict::Holds(f) } else { Verdict::Undecided(f) };
        let b = upward(&STEPS, 1.0, OnUndecided::PassOver, open);
        assert!(b.fails.is_none() && !b.decided(&STEPS));
        assert!((b.holds.expect("holds").0 - 1.1).abs() < 1e-12);
        assert_eq!(b.undecided.len(), 89, "1.2 to the bound, each tried");
    }

    #[test]
    fn a_search_told_to_stop_ends_at_its_first_undecided_trial() {
        let mut tried = Vec::new();
        let b = upward(&STEPS, 1.0, OnUndecided::Stop, |f, _: &f64| {
            tried.push(f);
            if (f - 1.3).abs() < 1e-9 {
                Verdict::Undecided(f)
            } else {
                Verdict::Holds(f)
            }
        });
        assert_eq!(tried.len(), 3, "1.1 and 1.2 hold, 1.3 decides nothing: {tried:?}");
        assert!((b.holds.as_ref().expect("holds").0 - 1.2).abs() < 1e-12);
        assert!(b.fails.is_none() && b.undecided.len() == 1 && !b.decided(&STEPS));
    }

    #[test]
    fn peak_strength_keeps_the_cohesion_where_a_pair_cracks_and_residual_the_scenes() {
        let s = Strength { friction: 0.7, cohesion: 25.0, tensile_strength: 5.0, residual_cohesion: 0.0 };
        let law = PairLaw { strength: s, slip: SlipLaw::Coulomb, stiffness: None };
        let peak = Strengths::Peak.laws(&[law]);
        assert_eq!(peak[0].strength, Strength { residual_cohesion: 25.0, ..s });
        assert_eq!(peak[0].strength.effective(true), (0.0, 25.0), "cracked: no tension, the peak cohesion");
        assert_eq!(Strengths::Residual.laws(&[law])[0].strength, s);
        assert!(Strengths::differ(&[law]) && !Strengths::differ(&peak));
        assert_eq!(Strengths::Peak.other(), Strengths::Residual);
    }
}
