//! Contact between the parts: pairs, frames, the law and the state
//! iteration of the substructure interface method.
//!
//! The iteration (paper §2.3 (6)): start with every pair stuck; solve the
//! interface system; judge every pair; repeat with the new states until the
//! state set repeats. Beyond the paper:
//!
//! - a slipping pair carries the Mohr–Coulomb shear `c - f sigma_n` on body
//!   I along its slip direction (equal and opposite on body II), taken from
//!   the previous solve, so the iteration also runs until that shear has
//!   settled (`slip = "frictionless"` keeps the paper's zero shear);
//! - open pairs close again on penetration, slipping pairs stick again when
//!   they move against their friction, cracked pairs keep f_t = 0 (law.rs);
//!   a pair closed when the step began that opened in one iteration and
//!   closes in a later one closes slipping if it has moved along the joint;
//! - a state set that comes back after others (a cycle) is broken by
//!   changing only the most violated pair from then on (`rule = "robust"`),
//!   or reported (`rule = "paper"`, which judges every pair by eq. 15–17
//!   alone, as the paper does);
//! - states, cracks and accumulated slip carry over from load step to load
//!   step (friction is path-dependent).

pub mod frame;
pub mod law;
pub mod options;
pub mod rigid;
pub mod system;
pub mod traction;

use law::{judge, judge_paper, ContactState, Kinematics, Strength};
use system::{InterfaceProblem, InterfaceSolution, Loading, SolveFailure};

pub use options::{SlipLaw, StateRule, TractionRecovery};

/// The law of one pair.
#[derive(Clone, Copy, Debug)]
pub struct PairLaw {
    pub strength: Strength,
    pub slip: SlipLaw,
}

/// What carries over from iteration to iteration and from step to step.
#[derive(Clone, Debug)]
pub struct History {
    pub states: Vec<ContactState>,
    /// Pairs that opened or slipped in a converged state (crack memory).
    pub cracked: Vec<bool>,
    /// Relative displacement kept on tied axes (slip accumulated before the
    /// pair stuck again); normal entry 0.
    pub offset: Vec<[f64; 3]>,
    /// Relative displacement at the start of the current step.
    pub rel_start: Vec<[f64; 3]>,
    /// Unit friction direction on body I of slipping pairs (local t, b).
    pub dir: Vec<[f64; 3]>,
    /// Normal stress last seen at each pair (for the Coulomb shear).
    pub sigma_n: Vec<f64>,
}

impl History {
    /// Every pair stuck, nothing cracked or slipped.
    pub fn new(n: usize) -> History {
        History {
            states: vec![ContactState::Stick; n],
            cracked: vec![false; n],
            offset: vec![[0.0; 3]; n],
            rel_start: vec![[0.0; 3]; n],
            dir: vec![[0.0; 3]; n],
            sigma_n: vec![0.0; n],
        }
    }
}

/// How the state iteration of one step ended.
pub struct Outcome {
    pub states: Vec<ContactState>,
    pub solution: InterfaceSolution,
    pub iterations: usize,
    pub converged: bool,
    /// A state set came back after other ones in between.
    pub cycled: bool,
    /// Cycles broken by changing one pair at a time (robust rule).
    pub cycles_broken: usize,
    /// State sets of every iteration (the ones solved with).
    pub history: Vec<Vec<ContactState>>,
}

/// A failed iteration: the failure and the states it happened with.
pub struct Failed {
    pub failure: SolveFailure,
    pub states: Vec<ContactState>,
    pub iteration: usize,
}

fn tangential(v: [f64; 3]) -> [f64; 3] {
    [0.0, v[1], v[2]]
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Whether a pair has lost its tensile strength and cohesion: it opened or
/// slipped in a converged state of an earlier step, or it is open or
/// slipping now. A state only passed through during the iteration leaves
/// no crack.
fn cracked(h: &History, p: usize) -> bool {
    h.cracked[p] || h.states[p] != ContactState::Stick
}

/// The friction force on body I of every slipping Coulomb pair.
fn friction(problem: &InterfaceProblem, laws: &[PairLaw], h: &History) -> Vec<[f64; 3]> {
    (0..laws.len())
        .map(|p| {
            if h.states[p] != ContactState::Slip || laws[p].slip == SlipLaw::Frictionless {
                return [0.0; 3];
            }
            let t = laws[p].strength.shear_limit(h.sigma_n[p], cracked(h, p)) * problem.area(p);
            [0.0, t * h.dir[p][1], t * h.dir[p][2]]
        })
        .collect()
}

/// Runs the state iteration of one load step under the load factors
/// `lambda`, starting from and updating `h`.
pub fn iterate(
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    rule: StateRule,
    lambda: &[f64],
    h: &mut History,
    max_iterations: usize,
) -> Result<Outcome, Failed> {
    let n = laws.len();
    // the states the step starts from (those the last step converged to)
    let start = h.states.clone();
    let mut history: Vec<Vec<ContactState>> = Vec::new();
    let mut iteration = 0;
    let mut one_at_a_time = false;
    let mut cycles_broken = 0;
    loop {
        iteration += 1;
        let shear = friction(problem, laws, h);
        let loading = Loading { lambda, shear: &shear, offset: &h.offset };
        let solution = problem.solve(&h.states, &loading).map_err(|failure| Failed { failure, states: h.states.clone(), iteration })?;
        history.push(h.states.clone());
        let r = &solution.pairs;
        let scale_u = solution.rel.iter().map(|v| norm(*v)).fold(0.0, f64::max);
        let scale_s = r.iter().map(|p| p.sigma_n.abs().max(p.tau())).fold(0.0, f64::max);
        let tol_u = 1e-10 * scale_u;
        // slip increments below round-off of the interface displacements
        // (not of the relative ones, which vanish where everything sticks)
        // are no slip
        let scale_d = solution.d_c.iter().flatten().fold(0.0, |m: f64, v| m.max(v.abs()));
        let slip_tol = 1e-9 * scale_d.max(scale_u);

        // 1. the next state of every pair, and how far it is from its current one
        let mut next = h.states.clone();
        let mut violation = vec![0.0; n];
        for p in 0..n {
            let st = h.states[p];
            let s = &laws[p].strength;
            let incr = tangential(sub(solution.rel[p], h.rel_start[p]));
            next[p] = match rule {
                StateRule::Paper => judge_paper(&r[p], s),
                StateRule::Robust => {
                    let k = Kinematics {
                        slip_along: dot(incr, h.dir[p]),
                        // a pair with no shear strength left slips freely:
                        // it cannot move against a friction it does not have
                        coulomb: laws[p].slip == SlipLaw::Coulomb && s.shear_limit(r[p].sigma_n, cracked(h, p)) > 0.0,
                        gap_tol: tol_u,
                        slip_tol: slip_tol,
                    };
                    match judge(st, &r[p], s, cracked(h, p), &k) {
                        // A pair closed when the step began that opened in an
                        // earlier iteration and closes again has moved along
                        // the joint since the step began: it closes slipping
                        // (sticking where that iteration left it would freeze
                        // a position the pair never had; the slip rule sticks
                        // it again if it then moves against its friction).
                        ContactState::Stick if st == ContactState::Open && start[p] != ContactState::Open && norm(incr) > tol_u => ContactState::Slip,
                        next => next,
                    }
                }
            };
            if next[p] != st {
                let (ft, _) = if cracked(h, p) { (0.0, 0.0) } else { (s.tensile_strength, 0.0) };
                violation[p] = match (st, next[p]) {
                    (_, ContactState::Open) => (r[p].sigma_n - ft) / scale_s.max(f64::MIN_POSITIVE),
                    (ContactState::Stick, ContactState::Slip) => (r[p].tau() - s.shear_limit(r[p].sigma_n, cracked(h, p))) / scale_s.max(f64::MIN_POSITIVE),
                    (ContactState::Open, _) => -r[p].gap / scale_u.max(f64::MIN_POSITIVE),
                    _ => -dot(incr, h.dir[p]) / scale_u.max(f64::MIN_POSITIVE),
                };
            }
        }
        // 2. a cycle: from now on change only the most violated pair
        let changed = next != h.states;
        if changed && rule == StateRule::Robust && (one_at_a_time || history.iter().any(|old| *old == next)) {
            if !one_at_a_time {
                one_at_a_time = true;
                cycles_broken += 1;
            }
            let worst = (0..n).filter(|&p| next[p] != h.states[p]).max_by(|&a, &b| violation[a].total_cmp(&violation[b]).then(b.cmp(&a)));
            let keep = worst.expect("some pair changes");
            for p in 0..n {
                if p != keep {
                    next[p] = h.states[p];
                }
            }
        }
        let cycled = changed && rule == StateRule::Paper && history.iter().any(|old| *old == next);

        // 3. carry the new states: friction directions, offsets, cracks; and
        // how far the Coulomb shear of slipping pairs still moves
        let mut shear_moved: f64 = 0.0;
        for p in 0..n {
            let (st, nx) = (h.states[p], next[p]);
            let incr = tangential(sub(solution.rel[p], h.rel_start[p]));
            if nx == ContactState::Slip {
                let d = if st == ContactState::Stick || norm(incr) <= tol_u {
                    // entering slip: friction keeps the direction of the stick shear
                    let t = [0.0, r[p].tau_t, r[p].tau_b];
                    if norm(t) > 0.0 {
                        t
                    } else {
                        h.dir[p]
                    }
                } else {
                    incr
                };
                let l = norm(d);
                if l > 0.0 {
                    let new = [0.0, d[1] / l, d[2] / l];
                    if st == ContactState::Slip && laws[p].slip == SlipLaw::Coulomb {
                        let turn = norm(sub(new, h.dir[p]));
                        shear_moved = shear_moved.max(turn * laws[p].strength.shear_limit(r[p].sigma_n, cracked(h, p)));
                    }
                    h.dir[p] = new;
                }
            }
            if nx == ContactState::Stick && st != ContactState::Stick {
                // stuck again: keep the slip of earlier steps; a re-closing
                // pair touches where it is
                h.offset[p] = if st == ContactState::Open { tangential(solution.rel[p]) } else { tangential(h.rel_start[p]) };
            }
            if nx == ContactState::Slip && st == ContactState::Slip && laws[p].slip == SlipLaw::Coulomb {
                let old = laws[p].strength.shear_limit(h.sigma_n[p], cracked(h, p));
                let new = laws[p].strength.shear_limit(r[p].sigma_n, cracked(h, p));
                shear_moved = shear_moved.max((new - old).abs());
            }
            h.sigma_n[p] = r[p].sigma_n;
        }
        let settled = shear_moved <= 1e-12 * scale_s.max(f64::MIN_POSITIVE);
        let converged = !changed && settled;
        if converged || cycled || iteration >= max_iterations {
            if converged {
                h.rel_start = solution.rel.clone();
                if rule == StateRule::Robust {
                    for p in 0..n {
                        h.cracked[p] |= h.states[p] != ContactState::Stick;
                    }
                }
            }
            let states = h.states.clone();
            h.states = next;
            return Ok(Outcome { states, solution, iterations: iteration, converged, cycled, cycles_broken, history });
        }
        h.states = next;
    }
}
