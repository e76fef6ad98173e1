//! Joints that deform: `normal_stiffness` k_n and `shear_stiffness` k_s
//! on a contact (3DEC's and UDEC's kn and ks), the state rule of their
//! pairs (`Elastic`) and where their springs start ([`unloaded`]).
//!
//! A closed pair of area A is a spring, `λ = A K (r - r0)` with `K =
//! diag(k_n, k_s, k_s)`, r its relative displacement (local axes n, t, b)
//! and r0 where its spring carries nothing; no axis is tied. Its trial
//! force is that spring's, and the law is the return mapping of
//! Mohr–Coulomb plasticity with a tension cut-off, judged from r alone:
//!
//! ```text
//! λ_n = A k_n (r_n - r0_n) >= A f_t     open (λ = 0)
//! |λ_T,trial| <= b(p), p = -λ_n          stick (λ_T = λ_T,trial)
//! otherwise                              slip  (λ_T = b(p) λ_T,trial / |λ_T,trial|)
//! ```
//!
//! with b(p) the Coulomb bound (`law::friction_bound`). A converged step
//! moves r0 along the joint by the plastic slip (`r0_T = r_T - λ_T / (A
//! k_s)`), and an open pair's r0 along the joint follows it (it closes
//! without shear); r0_n never moves: a joint opens and closes where its
//! normal spring is unloaded.
//!
//! Each iteration solves the interface with every closed pair a spring,
//! a slipping one's friction linearised at the last iterate (Newton on
//! the return mapping: with m the trial's direction and β = b / |λ_T,trial|,
//! `λ_T = (b + f Δp) m + β A k_s (I - m m^T) Δr_T`), then judges every
//! pair from its r. Newton's full step can overshoot (a rocking block
//! whose every pair opens at once): between the point a solve was
//! linearised at and the solve, the forces of both are the same load's,
//! so the interface's forces are affine along the step and the law's
//! residual can be had anywhere on it without another solve; the step is
//! the first of 1, 1/2, ... `MIN_STEP` that lowers it (`Elastic::line_search`).
//! Where the states judged leave a body free, they are judged again
//! halfway back along the step ([`Rule::step_back`]) before the failure
//! stands. The rigid joint's machinery (ties, junctions' shares
//! of their loops' forces, locked slips, cycle breaking) is not needed:
//! every pair's force is a function of its own r, where joints cross too.
//!
//! In-situ stress: the springs start carrying it ([`unloaded`]), so that a
//! rock mass in equilibrium with its joints does not move at the first
//! step (r0 = -K⁻¹ λ0 / A with λ0 the in-situ traction times the area).

use super::frame::tangential;
use super::history::{cracked, law_at, History};
use super::iteration::{Next, Rule, Verdict};
use super::law::{friction_bound, ContactState, Stiffness};
use super::options::SlipLaw;
use super::outcome::Summary;
use super::pair_law::PairLaw;
use super::system::{InterfaceProblem, InterfaceSolution, Relation};
use crate::fem::vec3::{dot, norm, sub};

/// Forces below this fraction of the largest pair force are round-off: a
/// pair within it of a limit keeps its state (or its round-off would flip
/// it from solve to solve).
const FORCE_ROUND_OFF: f64 = 1e-12;

/// The friction of slipping pairs has settled when it is within this
/// fraction of the largest pair force of the return mapping's.
const SETTLED: f64 = 1e-10;

/// The shortest step the line search and a step back take, of the whole.
const MIN_STEP: f64 = 1.0 / 64.0;

/// The state rule of joints that deform, through one load step.
pub(super) struct Elastic<'p> {
    problem: &'p InterfaceProblem<'p>,
    laws: &'p [PairLaw],
    /// Where each pair's spring carries nothing (local axes): the step's
    /// start's, with an open pair's following it along the joint.
    unloaded: Vec<[f64; 3]>,
    /// Where the friction is linearised: the point the last verdict was
    /// judged at.
    rel: Vec<[f64; 3]>,
    /// The step's start (the last converged step's end), the point the
    /// last verdict was judged at, and the step it was taken along: from
    /// a point to a solve, `alpha` of the way.
    start: Point,
    at: Option<Point>,
    from: Option<Point>,
    to: Option<Point>,
    alpha: f64,
    /// The states the last verdict was judged from, and its round-off.
    judged_from: Vec<ContactState>,
    tol: f64,
    /// Which pairs' springs follow them along the joint while they are
    /// open (None: every pair's), and those that followed this step.
    follows: Option<Vec<bool>>,
    followed: Vec<bool>,
}

/// A pair's springs, `A diag(k_n, k_s, k_s)`.
pub(super) fn springs(k: Stiffness, area: f64) -> [f64; 3] {
    [area * k.normal, area * k.shear, area * k.shear]
}

/// The stiffness of every pair of a model whose joints deform (None where
/// any pair's is rigid: the scene gives it to all or none).
pub fn stiffness(laws: &[PairLaw]) -> Option<Vec<Stiffness>> {
    laws.iter().map(|l| l.stiffness).collect()
}

/// Where each pair's spring carries nothing at the start, from the
/// traction on body I there (`traction`, global axes: the in-situ
/// stress's): `r0 = -K⁻¹ λ0`, λ0 the traction in the pair's axes times
/// its area.
pub fn unloaded(problem: &InterfaceProblem, stiffness: &[Stiffness], traction: &[[f64; 3]]) -> Vec<[f64; 3]> {
    (insitu_forces(problem, traction).iter().enumerate())
        .map(|(p, f)| {
            let k = springs(stiffness[p], problem.area(p));
            std::array::from_fn(|a| -f[a] / k[a])
        })
        .collect()
}

/// Each pair's force on body I under the in-situ `traction` (global axes,
/// on body I) over its area, in its local axes: what a joint carries
/// before anything moves.
pub fn insitu_forces(problem: &InterfaceProblem, traction: &[[f64; 3]]) -> Vec<[f64; 3]> {
    (traction.iter().enumerate())
        .map(|(p, t)| {
            let (area, frame) = (problem.area(p), &problem.frames()[p]);
            std::array::from_fn(|a| area * dot(frame[a], *t))
        })
        .collect()
}

/// A pair's trial force: its spring's at `r`.
fn trial(k: [f64; 3], r: [f64; 3], r0: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|a| k[a] * (r[a] - r0[a]))
}

impl<'p> Elastic<'p> {
    pub fn new(problem: &'p InterfaceProblem<'p>, laws: &'p [PairLaw], h: &History) -> Elastic<'p> {
        Elastic {
            problem,
            laws,
            unloaded: h.unloaded.clone(),
            rel: h.rel_start.clone(),
            start: Point::new(&h.rel_start, &h.force),
            at: None,
            from: None,
            to: None,
            alpha: 1.0,
            judged_from: Vec::new(),
            tol: 0.0,
            follows: None,
            followed: vec![false; laws.len()],
        }
    }

    /// The rule of an augmented Lagrangian round ([`super::augmented`]),
    /// whose springs stand for rigid joints: a pair's spring follows it
    /// along the joint while it is open only where the pair was open at
    /// the step's start (`start`, the states there), as the rigid joint's
    /// stick reference does, and a converged round leaves where in
    /// `History::offset`. (A spring that followed every opening pair
    /// would tie a pair that opened at one iterate and closed at the next
    /// where it closed, while the rounds' multipliers hold it where the
    /// step started: on blocks3d's first step, rounds from its start, such
    /// pairs slid 3e-5 m, their springs stretched 2 to 23 times the
    /// largest pair force, and the stretch grew round after round; held,
    /// it fell from 1 to 3.9e-7 in nine rounds.)
    pub fn holding(mut self, start: &[ContactState]) -> Self {
        self.follows = Some(start.iter().map(|s| *s == ContactState::Open).collect());
        self
    }

    fn springs(&self, p: usize) -> [f64; 3] {
        springs(self.laws[p].stiffness.expect("a joint that deforms"), self.problem.area(p))
    }

    /// The relation of pair `p` in state `state`.
    fn relation(&self, h: &History, p: usize, state: ContactState) -> Relation {
        let (k, r0) = (self.springs(p), self.unloaded[p]);
        let mut spring = [[0.0; 3]; 3];
        for a in 0..3 {
            spring[a][a] = k[a];
        }
        let stuck: [f64; 3] = std::array::from_fn(|a| -k[a] * r0[a]);
        match state {
            ContactState::Open => Relation::elastic(state, [0.0; 3], [[0.0; 3]; 3]),
            ContactState::Stick => Relation::elastic(state, stuck, spring),
            ContactState::Slip => {
                let law = law_at(h, self.laws, p);
                let lam = trial(k, self.rel[p], r0);
                let lt = tangential(lam);
                let size = norm(lt);
                let mut force = [stuck[0], 0.0, 0.0];
                for row in spring.iter_mut().skip(1) {
                    *row = [0.0; 3];
                }
                if law.slip == SlipLaw::Frictionless || size == 0.0 {
                    // no friction, or no direction to give it yet
                    return Relation::elastic(state, force, spring);
                }
                let pk = -lam[0];
                let (bk, db) = friction_bound(&law.strength, cracked(h, p), self.problem.area(p), pk);
                let m = lt.map(|x| x / size);
                let beta = (bk / size).min(1.0);
                for i in 1..3 {
                    // the friction follows the pressure, p = -k_n (r_n - r0_n)
                    spring[i][0] = -db * k[0] * m[i];
                    for j in 1..3 {
                        spring[i][j] = beta * k[j] * (f64::from(u8::from(i == j)) - m[i] * m[j]);
                    }
                }
                for i in 1..3 {
                    let at_k: f64 = (1..3).map(|j| spring[i][j] * self.rel[p][j]).sum();
                    force[i] = (bk - db * pk + db * k[0] * r0[0]) * m[i] - at_k;
                }
                Relation::elastic(state, force, spring)
            }
        }
    }

    /// Pair `p`'s state and force at the relative displacement `r` by
    /// the return mapping, from its state in `h` (within `tol` of a limit
    /// it keeps that state).
    fn map(&self, h: &History, p: usize, r: [f64; 3], tol: f64) -> (ContactState, [f64; 3]) {
        let (st, law) = (h.states[p], law_at(h, self.laws, p));
        let (k, area) = (self.springs(p), self.problem.area(p));
        let lam = trial(k, r, self.unloaded[p]);
        let cr = cracked(h, p);
        let ft = law.strength.tensile_limit(cr) * area;
        // open where the normal spring pulls beyond the tensile strength
        // (an open pair stays so while it would not press)
        let opens = match st {
            ContactState::Open => lam[0] >= -tol,
            _ => lam[0] >= ft + tol || (ft == 0.0 && lam[0] > tol),
        };
        if opens {
            return (ContactState::Open, [0.0; 3]);
        }
        let (b, _) = friction_bound(&law.strength, cr, area, -lam[0]);
        let shear = norm(tangential(lam));
        let next = match st {
            ContactState::Slip if law.slip == SlipLaw::Frictionless => ContactState::Slip,
            ContactState::Slip if shear >= b - tol => ContactState::Slip,
            ContactState::Stick if shear <= b + tol || shear <= tol => ContactState::Stick,
            _ if shear > b => ContactState::Slip,
            _ => ContactState::Stick,
        };
        if next == ContactState::Stick {
            return (next, lam);
        }
        // (a frictionless slip carries no shear: the paper's)
        let cut = if shear > 0.0 && law.slip == SlipLaw::Coulomb { b / shear } else { 0.0 };
        (next, [lam[0], lam[1] * cut, lam[2] * cut])
    }

    /// How far the forces `point` carries are from the law at its relative
    /// displacements: the sum of squares over the pairs.
    fn merit(&self, h: &History, point: &Point, tol: f64) -> f64 {
        (0..self.laws.len())
            .map(|p| {
                let (_, f) = self.map(h, p, point.rel[p], tol);
                point.miss(p, f).powi(2)
            })
            .sum()
    }

    /// The step along `from` -> `to` (two solves of this step's load: the
    /// forces are affine along it) whose forces' merit falls enough below
    /// `from`'s, halving from the whole; the best tried where none does.
    fn line_search(&self, h: &History, from: &Point, to: &Point, tol: f64, floor: f64) -> f64 {
        let at_start = self.merit(h, from, tol);
        let (mut best, mut alpha) = ((f64::INFINITY, 1.0), 1.0);
        while alpha >= MIN_STEP {
            let m = self.merit(h, &from.towards(to, alpha), tol);
            if m <= (1.0 - 1e-4 * alpha) * at_start || m <= floor {
                return alpha;
            }
            if m < best.0 {
                best = (m, alpha);
            }
            alpha *= 0.5;
        }
        best.1
    }

    /// Judges every pair at the point `alpha` along the last step: its
    /// state there, where the next solve is linearised, and the largest
    /// difference between the point's forces and the law's of the pairs
    /// that keep their state.
    fn verdict_at(&mut self, h: &History, tol: f64) -> (Vec<ContactState>, f64) {
        let (Some(from), Some(to)) = (&self.from, &self.to) else { return (h.states.clone(), 0.0) };
        let point = from.towards(to, self.alpha);
        let mut next = h.states.clone();
        let mut law = 0.0f64;
        for p in 0..self.laws.len() {
            let (state, f) = self.map(h, p, point.rel[p], tol);
            next[p] = state;
            if state == h.states[p] {
                law = law.max(point.miss(p, f));
            }
            // an open pair closes without shear, where it is
            if h.states[p] == ContactState::Open && self.follows.as_ref().is_none_or(|f| f[p]) {
                self.unloaded[p][1] = point.rel[p][1];
                self.unloaded[p][2] = point.rel[p][2];
                self.followed[p] = true;
            }
        }
        self.rel.clone_from(&point.rel);
        self.at = Some(point);
        (next, law)
    }
}

/// The relative displacements of every pair and the forces of a solve,
/// or a point between two.
#[derive(Clone)]
struct Point {
    rel: Vec<[f64; 3]>,
    force: Vec<[f64; 3]>,
}

impl Point {
    fn new(rel: &[[f64; 3]], force: &[[f64; 3]]) -> Point {
        Point { rel: rel.to_vec(), force: force.to_vec() }
    }

    /// The point `alpha` of the way to `to`.
    fn towards(&self, to: &Point, alpha: f64) -> Point {
        if alpha == 1.0 {
            return to.clone();
        }
        let mix = |a: &[[f64; 3]], b: &[[f64; 3]]| -> Vec<[f64; 3]> {
            a.iter().zip(b).map(|(x, y)| std::array::from_fn(|i| x[i] + alpha * (y[i] - x[i]))).collect()
        };
        Point { rel: mix(&self.rel, &to.rel), force: mix(&self.force, &to.force) }
    }

    /// How far pair `p`'s force at this point is from `f`.
    fn miss(&self, p: usize, f: [f64; 3]) -> f64 {
        norm(sub(f, self.force[p]))
    }
}

impl Rule for Elastic<'_> {
    fn relations(&self, h: &History) -> Vec<Relation> {
        (0..self.laws.len()).map(|p| self.relation(h, p, h.states[p])).collect()
    }

    fn judge(&mut self, h: &mut History, solution: &InterfaceSolution, _summary: &mut Summary) -> Verdict {
        let scale = solution.forces.iter().map(|f| norm(*f)).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        self.tol = FORCE_ROUND_OFF * scale;
        let to = Point::new(&solution.rel, &solution.forces);
        // from the point the solve was linearised at: a line search once
        // two solves of the step's load are in (before, the step's start)
        let floor = (SETTLED * scale).powi(2) * self.laws.len() as f64;
        self.alpha = match &self.at {
            Some(at) => self.line_search(h, at, &to, self.tol, floor),
            None => 1.0,
        };
        self.from = Some(self.at.take().unwrap_or_else(|| self.start.clone()));
        self.to = Some(to);
        self.judged_from.clone_from(&h.states);
        let (next, law) = self.verdict_at(h, self.tol);
        let settled = self.alpha == 1.0 && law <= (SETTLED * scale).max(solution.accuracy);
        Verdict { next: Next::States(next), settled, law }
    }

    /// The states judged at the last step's end could not be solved (a
    /// body they leave free): judged again halfway back along it.
    fn step_back(&mut self, h: &mut History) -> bool {
        if self.from.is_none() || self.alpha < 2.0 * MIN_STEP {
            return false;
        }
        self.alpha *= 0.5;
        h.states.clone_from(&self.judged_from);
        let (next, _) = self.verdict_at(h, self.tol);
        h.states = next;
        true
    }

    fn slip_reference(&self) -> Option<&[[f64; 3]]> {
        Some(&self.unloaded)
    }

    /// The springs' unloaded positions move along the joint by the step's
    /// plastic slip.
    fn commit(self, h: &mut History) {
        if self.follows.is_some() {
            for (p, r0) in self.unloaded.iter().enumerate().filter(|(p, _)| self.followed[*p]) {
                h.offset[p] = [0.0, r0[1], r0[2]];
            }
        }
        let mut unloaded = self.unloaded;
        for (p, r0) in unloaded.iter_mut().enumerate() {
            if h.states[p] == ContactState::Slip {
                let k = springs(self.laws[p].stiffness.expect("a joint that deforms"), self.problem.area(p));
                let (r, f) = (h.rel_start[p], h.force[p]);
                r0[1] = r[1] - f[1] / k[1];
                r0[2] = r[2] - f[2] / k[2];
            }
        }
        h.unloaded = unloaded;
    }
}
