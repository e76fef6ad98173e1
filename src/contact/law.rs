//! The contact law: how a node pair is judged from its contact stresses.
//!
//! Sign conventions (DESIGN.md §4), written once here: for a pair (k on body
//! I, l on body II), `n` is the outward normal of body I at k and (n, t, b) a
//! right-handed frame. `sigma_n, tau_t, tau_b` are the traction on body I from
//! body II in that frame, tension positive; `tau = sqrt(tau_t^2 + tau_b^2)`.
//! `gap = (u_l - u_k) . n` is positive when the pair opens; `slip` is the
//! magnitude of the tangential part of `u_l - u_k`.
//!
//! The paper's criteria (eq. 15–17), with f_t the tensile strength, f the
//! friction coefficient and c the cohesion:
//!
//! ```text
//! sigma_n >= f_t                                 open
//! sigma_n <  f_t  and  tau >= c - f sigma_n      slip
//! otherwise                                      stick
//! ```
//!
//! A pair already open carries no stress, so its stresses cannot judge it:
//! it stays open while its gap is not negative and closes (sticks) when the
//! bodies would interpenetrate. A slipping pair stays slipping unless it opens.
//! A pair that has opened or slipped is cracked: from then on its tensile
//! strength is zero and its cohesion the residual cohesion.

/// State of a contact pair; the number is the `status` code of the outputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ContactState {
    Open = 0,
    Slip = 1,
    Stick = 2,
}

impl ContactState {
    pub fn code(self) -> i32 {
        self as i32
    }
    pub fn name(self) -> &'static str {
        match self {
            ContactState::Open => "open",
            ContactState::Slip => "slip",
            ContactState::Stick => "stick",
        }
    }
}

/// Strength parameters of one contact surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Strength {
    pub friction: f64,
    pub cohesion: f64,
    pub tensile_strength: f64,
    pub residual_cohesion: f64,
}

/// What the last solve gave at one pair.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairResult {
    pub sigma_n: f64,
    pub tau_t: f64,
    pub tau_b: f64,
    pub gap: f64,
    pub slip: f64,
}

impl PairResult {
    pub fn tau(&self) -> f64 {
        self.tau_t.hypot(self.tau_b)
    }
}

impl Strength {
    /// Tensile strength and cohesion in force, once cracked or not.
    fn effective(&self, cracked: bool) -> (f64, f64) {
        if cracked {
            (0.0, self.residual_cohesion)
        } else {
            (self.tensile_strength, self.cohesion)
        }
    }

    /// The Mohr–Coulomb shear limit `c - f sigma_n` (never negative).
    pub fn shear_limit(&self, sigma_n: f64, cracked: bool) -> f64 {
        let (_, c) = self.effective(cracked);
        (c - self.friction * sigma_n).max(0.0)
    }
}

/// The paper's rule: every pair judged by eq. 15–17 from its stresses
/// alone, whatever its state (an open pair carries no stress, so it is
/// judged stuck again: this rule cycles on opening problems).
pub fn judge_paper(r: &PairResult, s: &Strength) -> ContactState {
    if r.sigma_n >= s.tensile_strength {
        ContactState::Open
    } else if r.tau() >= s.cohesion - s.friction * r.sigma_n {
        ContactState::Slip
    } else {
        ContactState::Stick
    }
}

/// What the robust rule needs besides the stresses: the slip increment of
/// this step along the assumed friction direction, and tolerances.
#[derive(Clone, Copy, Debug)]
pub struct Kinematics {
    /// `(slip increment) . (friction direction)`: negative when the pair
    /// moves against the friction it was given (then it is stuck).
    pub slip_along: f64,
    /// Whether the slip law carries friction (Coulomb) or not.
    pub coulomb: bool,
    /// Gaps below `-gap_tol` count as closed, slips below `slip_tol` as none.
    pub gap_tol: f64,
    pub slip_tol: f64,
}

/// The robust rule: the next state of a pair from its current state.
///
/// - stick: eq. 15–17 on its stresses;
/// - slip: open when `sigma_n >= f_t`; stuck again when, with Coulomb
///   friction, its slip increment runs against the friction direction;
/// - open: stuck again when the bodies would interpenetrate (gap < 0),
///   otherwise open whatever its (zero) stress says.
///
/// Cracked pairs (ever opened or slipped) have `f_t = 0` and the residual cohesion.
pub fn judge(current: ContactState, r: &PairResult, s: &Strength, cracked: bool, k: &Kinematics) -> ContactState {
    let (ft, _) = s.effective(cracked);
    match current {
        ContactState::Open => {
            if r.gap < -k.gap_tol {
                ContactState::Stick
            } else {
                ContactState::Open
            }
        }
        ContactState::Slip => {
            if r.sigma_n >= ft {
                ContactState::Open
            } else if k.coulomb && k.slip_along < -k.slip_tol {
                ContactState::Stick
            } else {
                ContactState::Slip
            }
        }
        ContactState::Stick => {
            if r.sigma_n >= ft {
                ContactState::Open
            } else if r.tau() >= s.shear_limit(r.sigma_n, cracked) {
                ContactState::Slip
            } else {
                ContactState::Stick
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::ContactState::*;
    use super::*;

    const S: Strength = Strength { friction: 0.5, cohesion: 1.0, tensile_strength: 2.0, residual_cohesion: 0.0 };

    fn r(sigma_n: f64, tau: f64, gap: f64) -> PairResult {
        PairResult { sigma_n, tau_t: tau, tau_b: 0.0, gap, slip: 0.0 }
    }

    fn kin(slip_along: f64, tol: f64) -> Kinematics {
        Kinematics { slip_along, coulomb: true, gap_tol: tol, slip_tol: tol }
    }

    #[test]
    fn truth_table_of_the_paper_criteria() {
        // (sigma_n, tau) -> state, from stick
        let cases = [
            ((2.0, 0.0), Open),   // at the tensile strength
            ((3.0, 5.0), Open),   // above it, whatever the shear
            ((1.5, 0.0), Stick),  // tension below f_t, no shear: limit c - f s = 0.25
            ((1.5, 0.25), Slip),  // on the limit (binary-exact numbers: 1 - 0.5 * 1.9 is not 0.05)
            ((1.5, 0.2499), Stick),
            ((-4.0, 2.9), Stick), // compression raises the limit to 3
            ((-4.0, 3.0), Slip),
            ((-4.0, -3.5), Slip), // shear sign does not matter
        ];
        for ((sn, tau), want) in cases {
            assert_eq!(judge(Stick, &r(sn, tau, 0.0), &S, false, &kin(0.0, 0.0)), want, "sigma_n {sn} tau {tau}");
        }
    }

    #[test]
    fn cracked_pairs_lose_tensile_strength_and_cohesion() {
        assert_eq!(judge(Stick, &r(0.5, 0.0, 0.0), &S, false, &kin(0.0, 0.0)), Stick);
        assert_eq!(judge(Stick, &r(0.5, 0.0, 0.0), &S, true, &kin(0.0, 0.0)), Open);
        assert_eq!(judge(Stick, &r(-1.0, 0.6, 0.0), &S, true, &kin(0.0, 0.0)), Slip);
    }

    #[test]
    fn open_pairs_follow_their_gap() {
        assert_eq!(judge(Open, &r(0.0, 0.0, 1e-3), &S, true, &kin(0.0, 1e-12)), Open);
        assert_eq!(judge(Open, &r(0.0, 0.0, -1e-3), &S, true, &kin(0.0, 1e-12)), Stick);
        assert_eq!(judge(Slip, &r(-1.0, 0.0, 0.0), &S, true, &kin(0.0, 1e-12)), Slip);
        assert_eq!(judge(Slip, &r(0.1, 0.0, 0.0), &S, true, &kin(0.0, 1e-12)), Open);
    }

    #[test]
    fn slipping_pairs_stick_again_when_they_move_against_their_friction() {
        assert_eq!(judge(Slip, &r(-1.0, 0.5, 0.0), &S, true, &kin(1e-3, 1e-12)), Slip);
        assert_eq!(judge(Slip, &r(-1.0, 0.5, 0.0), &S, true, &kin(-1e-3, 1e-12)), Stick);
        let frictionless = Kinematics { coulomb: false, ..kin(-1e-3, 1e-12) };
        assert_eq!(judge(Slip, &r(-1.0, 0.0, 0.0), &S, true, &frictionless), Slip);
    }

    #[test]
    fn paper_rule_judges_open_pairs_by_their_zero_stress() {
        assert_eq!(judge_paper(&r(0.0, 0.0, 1e-3), &S), Stick);
        assert_eq!(judge_paper(&r(2.5, 0.0, 0.0), &S), Open);
        assert_eq!(judge_paper(&r(-4.0, 3.0, 0.0), &S), Slip);
    }

    #[test]
    fn shear_limit_is_mohr_coulomb_and_never_negative() {
        assert_eq!(S.shear_limit(-4.0, false), 3.0);
        assert_eq!(S.shear_limit(-4.0, true), 2.0);
        assert_eq!(S.shear_limit(3.0, false), 0.0);
    }
}
