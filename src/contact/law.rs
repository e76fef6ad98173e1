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
//! it stays open while its gap is not negative and closes when the bodies
//! would interpenetrate. A slipping pair carries the Coulomb force along its
//! slip and sticks again when the slip turns back against it ([`judge`]).
//! A pair that has opened or slipped is cracked: from then on its tensile
//! strength is zero and its cohesion the residual cohesion, but for a pair
//! that has parted (opened, closed and opened again within a step), which
//! has lost its cohesion altogether: the residual cohesion is what a joint
//! keeps once it slips, not once its faces have come apart. The tensile
//! strength never exceeds the Coulomb apex c / f, where the shear limit
//! runs out (Mohr–Coulomb with a tension cut-off).
//!
//! Why a parting costs the residual cohesion: at the corner of the tension
//! cut-off (sigma_n = f_t = 0 once cracked, tau up to c) a law in which an
//! open pair carries nothing and a closed one keeps c has no fixed point
//! at a pair that carries a shear below c at about zero normal stress,
//! where that shear puts it in tension. Stuck, it carries its shear and a
//! little tension, so it opens; open, it carries nothing, the bodies close
//! on it, and it sticks again, for ever (the crest wedges of
//! tests/corpus/slope2d_c020.toml and slope2d_linear.toml against their
//! roller: sigma_n 9e-5 MPa and tau 7e-3 MPa stuck, an overlap of 1.7e-7 m
//! open; 412 iterations without an answer). Mohr–Coulomb plasticity keeps
//! the traction at the corner, (0, c), while the pair both opens and slips:
//! an open pair carrying shear, which parted faces do not. Here the pair
//! closes again without cohesion, where the cone's apex is at sigma_n =
//! 0, tau = 0 and the open and closed states meet without a jump: it
//! slips on its friction or stays open. A single opening that the next
//! iterate closes costs nothing (`history::parted`): the first solve of a
//! step, all stuck, puts pairs in tension that its answer has closed, and
//! which ones depends on the step's size, not on the load path (a step
//! solved whole and cut in pieces end alike: tests/convergence.rs).

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

/// The stiffness of a joint that deforms (`normal_stiffness`,
/// `shear_stiffness` of a contact: stress per unit relative displacement,
/// 3DEC's and UDEC's kn and ks): a closed pair's force is `A k (r - r0)`
/// with `r0` where its spring carries nothing ([`super::elastic`]), not a
/// tie. None: the paper's rigid joint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stiffness {
    pub normal: f64,
    pub shear: f64,
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
    /// Tensile strength and cohesion, once cracked or not.
    pub fn effective(&self, cracked: bool) -> (f64, f64) {
        if cracked {
            (0.0, self.residual_cohesion)
        } else {
            (self.tensile_strength, self.cohesion)
        }
    }

    /// The tensile strength the pair can reach: f_t, but no more than the
    /// Coulomb apex c / f where the shear limit `c - f sigma_n` runs out (a
    /// joint in tension above c / f has no shear strength left: it opens).
    pub fn tensile_limit(&self, cracked: bool) -> f64 {
        let (ft, c) = self.effective(cracked);
        if self.friction > 0.0 {
            ft.min(c / self.friction)
        } else {
            ft
        }
    }

    /// Whether f_t exceeds the Coulomb apex c / f (then the apex limits it).
    pub fn above_apex(&self) -> bool {
        self.friction > 0.0 && self.tensile_strength > self.cohesion / self.friction
    }

    /// The Mohr–Coulomb shear limit `c - f sigma_n` (never negative).
    pub fn shear_limit(&self, sigma_n: f64, cracked: bool) -> f64 {
        let (_, c) = self.effective(cracked);
        (c - self.friction * sigma_n).max(0.0)
    }
}

/// The paper's rule: every pair judged by eq. 15–17 from its stresses
/// alone, whatever its state (an open pair carries no stress, so it is
/// judged stuck again: this rule cycles on opening problems). A `cracked`
/// pair (opened or slipped in an earlier step) has `f_t = 0` and the
/// residual cohesion.
pub fn judge_paper(r: &PairResult, s: &Strength, cracked: bool) -> ContactState {
    let (ft, c) = s.effective(cracked);
    if r.sigma_n >= ft {
        ContactState::Open
    } else if r.tau() >= c - s.friction * r.sigma_n {
        ContactState::Slip
    } else {
        ContactState::Stick
    }
}

/// The Coulomb bound of a closed pair in force: `b(p) = max(0, A c + f p)`
/// with p = -λ_n the normal pressure force, and `db/dp` (0 where the bound
/// is cut off at zero).
pub fn friction_bound(s: &Strength, cracked: bool, area: f64, p: f64) -> (f64, f64) {
    let (_, c) = s.effective(cracked);
    let arg = area * c + s.friction * p;
    // at arg = 0 (a pair just closing, p = 0) the bound grows with p
    if arg >= 0.0 && (arg > 0.0 || s.friction > 0.0) {
        (arg, s.friction)
    } else {
        (0.0, 0.0)
    }
}

/// What the robust rule judges a pair by, in its local axes (n, t, b).
#[derive(Clone, Copy, Debug)]
pub struct Trial {
    /// Contact force on body I (tension positive along n).
    pub force: [f64; 3],
    /// The area the pair controls (> 0).
    pub area: f64,
    /// Slip along the joint since the pair's stick reference (t, b).
    pub slip: [f64; 3],
    /// Opening of the pair.
    pub gap: f64,
    /// The pair's stiffness, which turns a slip into a force.
    pub stiffness: f64,
}

impl Trial {
    /// `ξ = λ_T + c s`: the friction force the pair would need to stop
    /// its slip; it sticks while that stays below the Coulomb bound.
    pub fn xi(&self) -> [f64; 3] {
        let c = self.stiffness;
        [0.0, self.force[1] + c * self.slip[1], self.force[2] + c * self.slip[2]]
    }
}

/// The stiffness a pair in `state` with opening `gap` is judged with
/// ([`Trial::stiffness`]): `c()` where the law reads it (a slipping pair's
/// ξ and the slip it runs against, an open pair's slip as it closes and
/// its overlap, [`judge`], [`law_residual`]); a stuck pair's verdict and
/// residual read none, nor do an open pair's that neither closes nor
/// overlaps (`gap >= 0`), and 1 stands for it there, so that a stiffness
/// that is costly to form (W's diagonal on the sparse interface) is formed
/// only where it is read. A pair judged as closing whatever its gap
/// (a junction's loop keeps it shut) is asked with a gap of -∞.
pub fn stiffness_in(state: ContactState, gap: f64, c: impl FnOnce() -> f64) -> f64 {
    if reads_stiffness(state, gap) {
        c()
    } else {
        1.0
    }
}

/// Whether the law reads the stiffness of a pair in `state` with opening
/// `gap` ([`stiffness_in`]): what to form ahead of a verdict.
pub fn reads_stiffness(state: ContactState, gap: f64) -> bool {
    match state {
        ContactState::Stick => false,
        ContactState::Open => gap < 0.0,
        ContactState::Slip => true,
    }
}

/// The robust rule's next state of a pair from its current state (the
/// active-set update of a semismooth Newton method):
///
/// - closed (stick or slip): open when `sigma_n >= f_t` (f_t capped at the
///   Coulomb apex c / f, where the shear strength runs out);
/// - open: closed again when the bodies would interpenetrate (gap below
///   `-gap_tol`), otherwise open whatever its (zero) stress says; a closing
///   pair that has moved along the joint since its stick reference closes
///   slipping that way (it carries no force yet: |ξ| = c |s| >= b(0)),
///   otherwise it sticks;
/// - stick: slipping when `|λ_T| >= b(p) + force_tol` (eq. 16, `tau >= c -
///   f sigma_n`) and its shear is more than `force_tol`, or it has no
///   strength at all (b = 0): a pair that carries nothing (a joint at a
///   free surface, its forces round-off) stays stuck instead of following
///   the sign of its round-off from solve to solve;
/// - slip: stuck again when `|ξ| < b(p) - force_tol` with `ξ = λ_T + c s`,
///   or when its slip runs against the friction force it carried (a slip
///   whose force `c |s|` is within `force_tol` has no direction).
///
/// A pair at its Coulomb limit to within `force_tol` with no slip in the
/// step (one that slipped in an earlier step or stage, under a load that
/// has not changed) is admissible both stuck and slipping: it keeps the
/// state it is in, or its round-off would flip it from solve to solve.
///
/// Cracked pairs (ever opened or slipped) have `f_t = 0` and the residual
/// cohesion; `coulomb` is false for frictionless slip, which never sticks
/// once slipping.
pub fn judge(
    current: ContactState,
    t: &Trial,
    s: &Strength,
    cracked: bool,
    coulomb: bool,
    gap_tol: f64,
    force_tol: f64,
) -> ContactState {
    let ft = s.tensile_limit(cracked);
    match current {
        ContactState::Open if t.gap >= -gap_tol => ContactState::Open,
        ContactState::Open => {
            // closing: no force yet; it sticks where it is unless it has
            // moved along the joint since its stick reference (then it
            // closes slipping that way, with the friction its pressure brings)
            let (b, _) = friction_bound(s, cracked, t.area, 0.0);
            let xi = t.xi();
            let moved = xi[1].hypot(xi[2]);
            if moved == 0.0 || moved < b {
                ContactState::Stick
            } else {
                ContactState::Slip
            }
        }
        _ if t.force[0] >= ft * t.area && t.force[0] > force_tol => ContactState::Open,
        ContactState::Stick => {
            let (b, _) = friction_bound(s, cracked, t.area, -t.force[0]);
            let lam_t = t.force[1].hypot(t.force[2]);
            let strengthless = s.friction == 0.0 && s.effective(cracked).1 <= 0.0;
            if strengthless || (lam_t >= b + force_tol && lam_t > force_tol) {
                ContactState::Slip
            } else {
                ContactState::Stick
            }
        }
        ContactState::Slip if !coulomb => ContactState::Slip,
        ContactState::Slip => {
            let (b, _) = friction_bound(s, cracked, t.area, -t.force[0]);
            let xi = t.xi();
            // slip that runs against the friction force it was given: the
            // pair stuck (a force below round-off has no direction, nor has
            // a slip whose force c |s| is)
            let lam_t = t.force[1].hypot(t.force[2]);
            let s_t = t.slip[1].hypot(t.slip[2]);
            let along = t.force[1] * t.slip[1] + t.force[2] * t.slip[2];
            let against =
                lam_t > 1e-9 * t.force[0].abs() && t.stiffness * s_t > force_tol && along < -1e-9 * lam_t * s_t;
            if against || xi[1].hypot(xi[2]) < b - force_tol {
                ContactState::Stick
            } else {
                ContactState::Slip
            }
        }
    }
}

/// How far a pair's force is from the contact law in its state, in force
/// units (the pair's stresses times its area): for a closed pair the
/// tension beyond `f_t`, and beyond the Coulomb bound `b(p)` when it
/// sticks or off it when it slips: `| |λ_T| - b(p) |`, and where the
/// trial carries a slip `s`, `|λ_T - b(p) s / |s||` (the friction of a
/// slip is along it: a pair at its bound slipping against or across its
/// force breaks the law), or `|λ_T|` for frictionless slip; for an open
/// pair the force it carries and the overlap `-gap` times its stiffness.
/// Zero where the law holds exactly: what a converged iteration reaches
/// to round-off, and what a run that did not converge reports pair by
/// pair. A zero slip checks the magnitude alone (a slip too small to
/// have a direction).
pub fn law_residual(state: ContactState, t: &Trial, s: &Strength, cracked: bool, coulomb: bool) -> f64 {
    let lam_t = t.force[1].hypot(t.force[2]);
    if state == ContactState::Open {
        return t.force[0].hypot(lam_t) + (-t.gap).max(0.0) * t.stiffness;
    }
    let tension = (t.force[0] - s.tensile_limit(cracked) * t.area).max(0.0);
    let (b, _) = friction_bound(s, cracked, t.area, -t.force[0]);
    let s_t = t.slip[1].hypot(t.slip[2]);
    let shear = match state {
        ContactState::Stick => (lam_t - b).max(0.0),
        _ if coulomb && s_t > 0.0 => {
            let (e1, e2) = (t.slip[1] / s_t, t.slip[2] / s_t);
            (t.force[1] - b * e1).hypot(t.force[2] - b * e2)
        }
        _ if coulomb => (lam_t - b).abs(),
        _ => lam_t,
    };
    tension.max(shear)
}

#[cfg(test)]
mod tests {
    use super::ContactState::*;
    use super::*;

    const S: Strength = Strength { friction: 0.5, cohesion: 1.0, tensile_strength: 2.0, residual_cohesion: 0.0 };

    /// A pair of unit area with stresses (sigma_n, tau along t), slip s along t and gap g.
    fn t(sigma_n: f64, tau: f64, slip: f64, gap: f64) -> Trial {
        Trial { force: [sigma_n, tau, 0.0], area: 1.0, slip: [0.0, slip, 0.0], gap, stiffness: 10.0 }
    }

    fn r(sigma_n: f64, tau: f64) -> PairResult {
        PairResult { sigma_n, tau_t: tau, tau_b: 0.0, gap: 0.0, slip: 0.0 }
    }

    #[test]
    fn truth_table_of_the_paper_criteria() {
        // (sigma_n, tau) -> state, from stick; the robust rule and the paper agree
        let cases = [
            ((2.0, 0.0), Open),  // at the tensile strength
            ((3.0, 5.0), Open),  // above it, whatever the shear
            ((1.5, 0.0), Stick), // tension below f_t, no shear: limit c - f s = 0.25
            ((1.5, 0.25), Slip), // on the limit (binary-exact numbers: 1 - 0.5 * 1.9 is not 0.05)
            ((1.5, 0.2499), Stick),
            ((-4.0, 2.9), Stick), // compression raises the limit to 3
            ((-4.0, 3.0), Slip),
            ((-4.0, -3.5), Slip), // shear sign does not matter
        ];
        for ((sn, tau), want) in cases {
            assert_eq!(judge(Stick, &t(sn, tau, 0.0, 0.0), &S, false, true, 0.0, 0.0), want, "sigma_n {sn} tau {tau}");
            assert_eq!(judge_paper(&r(sn, tau), &S, false), want, "paper: sigma_n {sn} tau {tau}");
        }
        // the shear direction in the joint plane does not matter either
        let diag = Trial { force: [-4.0, 2.1, 2.1], ..t(0.0, 0.0, 0.0, 0.0) };
        assert_eq!(judge(Stick, &diag, &S, false, true, 0.0, 0.0), Stick);
        let diag = Trial { force: [-4.0, 2.2, 2.2], ..diag };
        assert_eq!(judge(Stick, &diag, &S, false, true, 0.0, 0.0), Slip);
    }

    #[test]
    fn law_residual_is_the_distance_to_the_law_in_each_state() {
        // bound at sigma_n = -4: c + f p = 1 + 2 = 3; f_t = 2 (uncracked)
        let res = |st, tr: Trial| law_residual(st, &tr, &S, false, true);
        assert_eq!(res(Stick, t(-4.0, 2.5, 0.0, 0.0)), 0.0, "inside the cone");
        assert_eq!(res(Stick, t(-4.0, 3.5, 0.0, 0.0)), 0.5, "beyond the bound");
        assert_eq!(res(Slip, t(-4.0, 3.0, 0.1, 0.0)), 0.0, "on the cone");
        assert_eq!(res(Slip, t(-4.0, 2.0, 0.1, 0.0)), 1.0, "below it");
        // the friction of a slip runs along it: at the bound but against
        // the slip, or across it, the law is broken; a zero slip has no
        // direction to check
        assert_eq!(res(Slip, t(-4.0, -3.0, 0.1, 0.0)), 6.0, "against the slip");
        let across = Trial { slip: [0.0, 0.0, 0.1], ..t(-4.0, 3.0, 0.0, 0.0) };
        assert!((res(Slip, across) - 3.0 * 2f64.sqrt()).abs() < 1e-12, "across the slip");
        assert_eq!(res(Slip, t(-4.0, -3.0, 0.0, 0.0)), 0.0, "no slip");
        assert_eq!(res(Stick, t(2.5, 0.0, 0.0, 0.0)), 0.5, "tension beyond f_t");
        assert_eq!(res(Open, t(0.0, 0.0, 0.0, 1e-3)), 0.0);
        assert_eq!(res(Open, t(-3.0, 4.0, 0.0, 1e-3)), 5.0, "an open pair carries nothing");
        assert_eq!(res(Open, t(0.0, 0.0, 0.0, -0.1)), 1.0, "nor overlaps (stiffness 10)");
        // frictionless slip carries no shear; cracked pairs have no f_t
        assert_eq!(law_residual(Slip, &t(-4.0, 0.25, 0.1, 0.0), &S, false, false), 0.25);
        assert_eq!(law_residual(Stick, &t(0.5, 0.0, 0.0, 0.0), &S, true, true), 0.5);
    }

    #[test]
    fn cracked_pairs_lose_tensile_strength_and_cohesion() {
        assert_eq!(judge(Stick, &t(0.5, 0.0, 0.0, 0.0), &S, false, true, 0.0, 0.0), Stick);
        assert_eq!(judge(Stick, &t(0.5, 0.0, 0.0, 0.0), &S, true, true, 0.0, 0.0), Open);
        assert_eq!(judge(Stick, &t(-1.0, 0.6, 0.0, 0.0), &S, true, true, 0.0, 0.0), Slip);
        // the paper's rule too
        assert_eq!(judge_paper(&r(0.5, 0.0), &S, false), Stick);
        assert_eq!(judge_paper(&r(0.5, 0.0), &S, true), Open);
        assert_eq!(judge_paper(&r(-1.0, 0.6), &S, true), Slip);
    }

    #[test]
    fn open_pairs_follow_their_gap() {
        assert_eq!(judge(Open, &t(0.0, 0.0, 0.0, 1e-3), &S, true, true, 1e-12, 0.0), Open);
        assert_eq!(judge(Open, &t(0.0, 0.0, 0.0, -1e-3), &S, true, true, 1e-12, 0.0), Stick, "closes where it is");
        assert_eq!(
            judge(Open, &t(0.0, 0.0, 1e-3, -1e-3), &S, true, true, 1e-12, 0.0),
            Slip,
            "closes after moving along the joint"
        );
        let cohesive = Strength { residual_cohesion: 0.5, ..S };
        assert_eq!(
            judge(Open, &t(0.0, 0.0, 1e-3, -1e-3), &cohesive, true, true, 1e-12, 0.0),
            Stick,
            "a cohesive crack holds a small move"
        );
        assert_eq!(judge(Slip, &t(-1.0, 0.5, 0.0, 0.0), &S, true, true, 1e-12, 0.0), Slip);
        assert_eq!(judge(Slip, &t(0.1, 0.0, 0.0, 0.0), &S, true, true, 1e-12, 0.0), Open);
    }

    #[test]
    fn slipping_pairs_stick_again_when_they_move_against_their_friction() {
        // carrying the bound 0.5 along +t under sigma_n = -1
        assert_eq!(judge(Slip, &t(-1.0, 0.5, 1e-3, 0.0), &S, true, true, 1e-12, 0.0), Slip);
        assert_eq!(judge(Slip, &t(-1.0, 0.5, -1e-3, 0.0), &S, true, true, 1e-12, 0.0), Stick);
        // a large reversed slip makes |ξ| large, but it runs against the friction: stuck
        assert_eq!(judge(Slip, &t(-1.0, 0.5, -1.0, 0.0), &S, true, true, 1e-12, 0.0), Stick);
        assert_eq!(
            judge(Slip, &t(-1.0, 0.0, -1e-3, 0.0), &S, true, false, 1e-12, 0.0),
            Slip,
            "frictionless slip never sticks"
        );
    }

    #[test]
    fn a_pair_at_its_limit_to_round_off_keeps_its_state() {
        // bound 0.5 under sigma_n = -1 (cracked): one ulp either side of it,
        // with a slip of round-off size in any direction
        let tol = 1e-12;
        let (above, below) = (0.5 + 1e-16, 0.5 - 1e-16);
        for slip in [0.0, 1e-20, -1e-20] {
            assert_eq!(judge(Stick, &t(-1.0, above, 0.0, 0.0), &S, true, true, 0.0, tol), Stick);
            assert_eq!(judge(Slip, &t(-1.0, below, slip, 0.0), &S, true, true, 0.0, tol), Slip, "slip {slip:e}");
        }
        // beyond the band they change, as without it
        assert_eq!(judge(Stick, &t(-1.0, 0.5 + 1e-9, 0.0, 0.0), &S, true, true, 0.0, tol), Slip);
        assert_eq!(judge(Slip, &t(-1.0, 0.5 - 1e-9, 0.0, 0.0), &S, true, true, 0.0, tol), Stick);
        assert_eq!(judge(Slip, &t(-1.0, 0.5, -1e-9, 0.0), &S, true, true, 0.0, tol), Stick, "a real reversed slip");
    }

    #[test]
    fn a_stuck_pairs_verdict_and_residual_read_no_stiffness() {
        // across the stuck rows of the tables above, a slip of round-off
        // size or not, a cracked pair or not: any stiffness, the same answer
        let cases = [(2.0, 0.0), (1.5, 0.2499), (1.5, 0.25), (-4.0, 2.9), (-4.0, -3.5), (0.5, 0.0), (-1.0, 0.6)];
        for (sn, tau) in cases {
            for slip in [0.0, 1e-20, -1e-3, 1.0] {
                for cracked in [false, true] {
                    let at = |c: f64| Trial { stiffness: c, ..t(sn, tau, slip, 0.0) };
                    let verdict = |c| judge(Stick, &at(c), &S, cracked, true, 1e-12, 1e-12);
                    let residual = |c| law_residual(Stick, &at(c), &S, cracked, true);
                    let one = stiffness_in(Stick, 0.0, || panic!("a stuck pair's stiffness is not formed"));
                    for c in [1e-9, 10.0, 1e12] {
                        assert_eq!(verdict(c), verdict(one), "sigma_n {sn} tau {tau} slip {slip} stiffness {c}");
                        assert_eq!(residual(c), residual(one), "sigma_n {sn} tau {tau} slip {slip} stiffness {c}");
                    }
                }
            }
        }
        // where the law reads it, it is the pair's own
        assert_eq!(stiffness_in(Slip, 1.0, || 7.0), 7.0);
        assert_eq!(stiffness_in(Open, -1e-30, || 7.0), 7.0);
        assert_eq!(stiffness_in(Open, f64::NEG_INFINITY, || 7.0), 7.0);
    }

    #[test]
    fn an_open_pairs_verdict_and_residual_read_no_stiffness_unless_it_closes() {
        // open with a gap of zero or more, whatever it carries, slid or
        // not, judged with any gap tolerance: any stiffness, the same answer
        for gap in [0.0, 1e-20, 1.0] {
            for (sn, tau) in [(0.0, 0.0), (1e-14, -1e-14), (2.0, 0.5)] {
                for slip in [0.0, 1e-20, -1e-3, 1.0] {
                    for gap_tol in [0.0, 1e-12] {
                        let at = |c: f64| Trial { stiffness: c, ..t(sn, tau, slip, gap) };
                        let verdict = |c| judge(Open, &at(c), &S, true, true, gap_tol, 1e-12);
                        let residual = |c| law_residual(Open, &at(c), &S, true, true);
                        let one = stiffness_in(Open, gap, || panic!("an open pair's stiffness is not formed"));
                        for c in [1e-9, 10.0, 1e12] {
                            assert_eq!(verdict(c), verdict(one), "gap {gap} slip {slip} stiffness {c}");
                            assert_eq!(residual(c), residual(one), "gap {gap} slip {slip} stiffness {c}");
                        }
                    }
                }
            }
        }
        // a closing one reads it: a slip of 1e-3 closes sticking or
        // slipping as its stiffness makes of it a force below or above the
        // bound at no pressure (the cohesion, 1)
        let closing = |c: f64| Trial { stiffness: c, ..t(0.0, 0.0, 1e-3, -1.0) };
        assert_eq!(judge(Open, &closing(10.0), &S, false, true, 0.0, 1e-12), Stick);
        assert_eq!(judge(Open, &closing(1e4), &S, false, true, 0.0, 1e-12), Slip);
    }

    #[test]
    fn tensile_strength_is_capped_at_the_coulomb_apex() {
        let s = Strength { friction: 0.5, cohesion: 1.0, tensile_strength: 5.0, residual_cohesion: 0.0 };
        assert!(s.above_apex());
        assert_eq!(s.tensile_limit(false), 2.0);
        assert_eq!(judge(Stick, &t(2.5, 0.0, 0.0, 0.0), &s, false, true, 0.0, 0.0), Open, "above c/f the joint opens");
        assert_eq!(judge_paper(&r(2.5, 0.0), &s, false), Slip, "the paper's rule slips there with no shear strength");
        assert!(!S.above_apex());
    }

    #[test]
    fn paper_rule_judges_open_pairs_by_their_zero_stress() {
        assert_eq!(judge_paper(&r(0.0, 0.0), &S, false), Stick);
        assert_eq!(
            judge_paper(&r(0.0, 0.0), &S, true),
            Open,
            "a cracked pair has f_t = 0: its zero stress keeps it open"
        );
        assert_eq!(judge_paper(&r(2.5, 0.0), &S, false), Open);
        assert_eq!(judge_paper(&r(-4.0, 3.0), &S, false), Slip);
    }

    #[test]
    fn shear_limit_is_mohr_coulomb_and_never_negative() {
        assert_eq!(S.shear_limit(-4.0, false), 3.0);
        assert_eq!(S.shear_limit(-4.0, true), 2.0);
        assert_eq!(S.shear_limit(3.0, false), 0.0);
        assert_eq!(friction_bound(&S, false, 2.0, 4.0), (4.0, 0.5));
        assert_eq!(friction_bound(&S, true, 2.0, -1.0), (0.0, 0.0));
        assert_eq!(friction_bound(&S, true, 2.0, 0.0), (0.0, 0.5), "a closing pair's bound grows with its pressure");
    }
}
