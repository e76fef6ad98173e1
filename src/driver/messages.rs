//! The driver's typed errors and the one paragraph each becomes: a failed
//! contact iteration ([`ContactError`]: bodies nothing holds, bodies that
//! slide freely, a step that did not converge, ...) and a plan the MPI ranks
//! cannot follow ([`PlanError`]). Tests match the variants; a person reads
//! the paragraph, which names the scene, the load step and iteration, and
//! says what to do.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::contact::law::ContactState;
use crate::contact::mechanism::BlockState;
use crate::contact::system::SolveFailure;
use crate::contact::{Failed, SlipLaw, StateRule, Stop};
use crate::fem::rigid::RigidMotion;
use crate::fem::sparse::FactorError;
use crate::model::Model;
use crate::output::faces::block_name;
use crate::results::state_counts;
use crate::scene::Scene;
use crate::substructure::Part;

/// Why a step that is the same problem at any load
/// (`crate::contact::cutting::scales`) was not cut, as the run says it.
pub const NOT_CUT: &str = "not cut: it starts from no load, on joints of friction alone (no cohesion, tensile strength or water), so a half of it is the same problem at half the load and repeats its iterations";

/// Where in a run a contact iteration failed.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct At {
    /// The load step, when the scene has several.
    pub step: Option<usize>,
    pub iteration: usize,
    /// How many pairs were open, slipping and stuck then.
    pub states: [u32; 3],
    /// The augmented Lagrangian rounds among the iterations and their
    /// iterations, where the step was solved again by them. (u32: an
    /// error this size travels in every contact iteration's `Result`.)
    pub rounds: Option<[u32; 2]>,
}

/// A contact whose tensile strength exceeds its Coulomb apex c / f: the
/// robust rule opens its pairs at c / f already.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Apex {
    /// Its index in the scene's `[[contacts]]`.
    pub contact: usize,
    /// c / f, and the tensile strength the scene gives.
    pub opens_at: f64,
    pub tensile_strength: f64,
}

/// Why the contact iteration of a run failed.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum ContactError {
    /// Bodies held by nothing once their contact pairs opened; `places`:
    /// where each is, when it is a block of a group cut into several (a
    /// refused run writes no blocks.csv to look "rock #12" up in).
    NotHeld { at: At, bodies: Vec<String>, places: Vec<Option<[f64; 3]>>, apex: Vec<Apex> },
    /// Bodies that slide or rotate freely on their slipping pairs (none
    /// named when the cause was not found). `no_shear`: their slipping
    /// contacts carry no shear at all (no friction and no cohesion, or
    /// frictionless slip), so no load along the joint is to blame. `rule`:
    /// the paper's gives a slipping pair a fixed shear, which holds nothing
    /// across its slip (the robust rule's friction does). `motions`: what
    /// moves, by body (a ring turning in its hole); `places` as `NotHeld`'s.
    Sliding {
        at: At,
        bodies: Vec<String>,
        places: Vec<Option<[f64; 3]>>,
        no_shear: bool,
        rule: StateRule,
        motions: Vec<(String, RigidMotion)>,
    },
    /// A load step's iteration did not converge after `iterations`
    /// (`stop`: why) under `rule`;
    /// `results`: where the last iteration's results were written; `cuts`:
    /// the halvings of the step that were tried (`[solver] max_cuts`);
    /// `scaled`: none was, the step being the same problem at any load;
    /// `slipping_back`: the pairs that slip against their friction at the
    /// last iteration (report.md), which more iterations did not settle
    /// where measured; `rigid_joints`: where the joints are rigid, the
    /// normal and shear stiffness advised (the fallback's); `fell_back`:
    /// this was the run with joints that deform that rigid joints which
    /// did not converge fell back to.
    NotConverged {
        step: Option<usize>,
        iterations: usize,
        stop: Stop,
        slipping_back: usize,
        rigid_joints: Option<[f64; 2]>,
        fell_back: bool,
        cuts: usize,
        scaled: bool,
        rule: StateRule,
        results: Option<PathBuf>,
    },
    /// Substructures joined by bonded interfaces alone, and that system singular.
    BondedNotHeld,
    /// The interface mass matrix of the consistent traction recovery could
    /// not be factorised.
    Traction { reason: FactorError },
}

/// Why a safety search ends the run non-zero.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum SafetyError {
    /// The load steps lose equilibrium as given (`at_one`): the scene is
    /// unsafe. F was sought below 1, each trial running the load steps
    /// from the start: `holds` the largest factor that held (None: none
    /// down to 1 / `max_factor`), `fails` the smallest that failed.
    /// `mechanism`: how the blocks move at F = 1, for a reader, and the
    /// advice for it; `load`: a load factor search; `results`: where the
    /// results that exist were written.
    Unsafe {
        at_one: ContactError,
        holds: Option<f64>,
        fails: f64,
        max_factor: f64,
        mechanism: Option<(String, BlockState)>,
        load: bool,
        results: Option<PathBuf>,
    },
    /// Converged trials did not decide the factor: they hold at `holds`
    /// and fail at `fails` (None: none converged above), and the trials at
    /// `undecided` did not converge, even when retried; `rigid_joints`:
    /// where the joints are rigid, the normal and shear stiffness advised.
    Undecided {
        holds: f64,
        fails: Option<f64>,
        undecided: Vec<f64>,
        load: bool,
        rigid_joints: Option<[f64; 2]>,
        retry: RetryAdvice,
        results: Option<PathBuf>,
    },
}

/// What may decide the trials of a safety search that did not converge,
/// from how they stopped: only advice that can help those trials is given
/// (the message said "more max_iterations, a smaller safety.step, or the
/// other rule" to every search, where the trials of tests/safety.rs cycle
/// under the paper's rule and only the robust rule decides F).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct RetryAdvice {
    /// The scene's rule: the paper's reports a cycle and does not break
    /// it, and the robust rule's cycle breaker may end the trials.
    pub rule: StateRule,
    /// A trial stopped at its retry's budget of this many iterations with
    /// its states still changing (not cycling, not settled against the
    /// law): more iterations may end it.
    pub budget: Option<usize>,
}

impl SafetyError {
    /// The error with the results written to `out`.
    pub fn written(mut self, out: PathBuf) -> SafetyError {
        match &mut self {
            SafetyError::Unsafe { results, .. } | SafetyError::Undecided { results, .. } => *results = Some(out),
        }
        self
    }
}

/// Why the parts cannot be spread over the MPI ranks.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum PlanError {
    /// More ranks than parts; `substructures`: the cut the scene asked for.
    TooManyRanks { ranks: usize, parts: usize, substructures: usize },
}

impl std::error::Error for ContactError {}
impl std::error::Error for PlanError {}
impl std::error::Error for SafetyError {}

impl ContactError {
    /// The error of a failed iteration at load step `step`; `parts` are the
    /// parts in the interface's order.
    pub(super) fn failed(model: &Model, parts: &[Part], scene: &Scene, step: usize, f: Failed) -> ContactError {
        let (states, rounds) =
            (state_counts(&f.states).map(count), f.augmented.map(|r| [r.rounds, r.iterations].map(count)));
        let at = At { step: At::named(scene, step), iteration: f.iteration, states, rounds };
        // (a block of a group cut by joint sets by its number, "rock #3",
        // as blocks.csv and faces.csv name it: the group's name alone
        // would not say which of its blocks)
        let blocks = |ids: &[usize]| -> Vec<usize> {
            let mut bodies: Vec<usize> = ids.iter().flat_map(|&i| parts[i].bodies.iter().copied()).collect();
            bodies.sort_unstable();
            bodies.dedup();
            bodies
        };
        let names = |ids: &[usize]| -> Vec<String> { blocks(ids).iter().map(|&b| block_name(model, b)).collect() };
        // (and where each block of a group cut into several is)
        let named = |ids: &[usize]| -> (Vec<String>, Vec<Option<[f64; 3]>>) {
            let bodies = blocks(ids);
            let places = bodies.iter().map(|&b| model.bodies[b].block.map(|k| k.centre)).collect();
            (bodies.iter().map(|&b| block_name(model, b)).collect(), places)
        };
        match f.failure {
            SolveFailure::NotHeld(ids) => {
                let (bodies, places) = named(&ids);
                ContactError::NotHeld { at, bodies, places, apex: apex(scene) }
            }
            SolveFailure::Sliding(free) => {
                let (bodies, places) = named(&free);
                let no_shear = no_shear(model, scene, &f.states, &blocks(&free));
                let motions = (free.motions.iter()).map(|&(p, m)| (names(&[p]).join("\", \""), m)).collect();
                ContactError::Sliding { at, bodies, places, no_shear, rule: scene.solver.rule, motions }
            }
        }
    }
}

/// Where a contact's f_t exceeds the Coulomb apex c / f, the robust rule
/// opens its pairs at c / f already: worth saying where they let a body go.
fn apex(scene: &Scene) -> Vec<Apex> {
    if scene.solver.rule != StateRule::Robust {
        return Vec::new();
    }
    (scene.contacts.iter().enumerate())
        .filter(|(_, c)| c.strength.above_apex())
        .map(|(i, c)| {
            let s = &c.strength;
            Apex { contact: i, opens_at: s.cohesion / s.friction, tensile_strength: s.tensile_strength }
        })
        .collect()
}

/// Whether every slipping pair on the bodies `bodies` (all of them when
/// none is given) belongs to a contact that carries no shear once
/// slipping: no friction and no residual cohesion, or frictionless slip.
fn no_shear(model: &Model, scene: &Scene, states: &[ContactState], bodies: &[usize]) -> bool {
    let mut body_of = vec![usize::MAX; model.n_nodes()];
    for (b, body) in model.bodies.iter().enumerate() {
        body.cells.iter().flat_map(|c| &c.nodes).for_each(|&n| body_of[n] = b);
    }
    let named = |n: usize| bodies.is_empty() || bodies.contains(&body_of[n]);
    let mut slipping = (model.pairs.iter().zip(states))
        .filter(|(p, &s)| s == ContactState::Slip && (named(p.k) || named(p.l)))
        .peekable();
    slipping.peek().is_some()
        && slipping.all(|(p, _)| {
            let c = &scene.contacts[p.contact];
            c.slip == SlipLaw::Frictionless || (c.strength.friction == 0.0 && c.strength.residual_cohesion == 0.0)
        })
}

/// The motions that nothing holds, for a message: " (rotation about
/// (0.0000, 0.0000))", by body where there are several; empty when none
/// is known.
fn motions_named(motions: &[(String, RigidMotion)]) -> String {
    let mut bodies: Vec<&String> = motions.iter().map(|(b, _)| b).collect();
    bodies.dedup();
    let each: Vec<String> =
        (motions.iter()).map(|(b, m)| if bodies.len() > 1 { format!("\"{b}\": {m}") } else { m.to_string() }).collect();
    if each.is_empty() {
        String::new()
    } else {
        format!(" ({})", each.join("; "))
    }
}

/// "body \"a\"" or "bodies \"a\", \"b\"", a block of a group cut into
/// several with where it is: "body \"rock #12\" (centre at (x, y, z))".
fn bodies_named(bodies: &[String], places: &[Option<[f64; 3]>]) -> String {
    let named = |(i, b): (usize, &String)| match places.get(i).copied().flatten() {
        Some(c) => format!("\"{b}\" (centre at ({:.4}, {:.4}, {:.4}))", c[0], c[1], c[2]),
        None => format!("\"{b}\""),
    };
    let names = bodies.iter().enumerate().map(named).collect::<Vec<_>>().join(", ");
    format!("{} {names}", if bodies.len() == 1 { "body" } else { "bodies" })
}

/// A count as `At` keeps it (saturated: a count past u32 is past any
/// model this tool solves).
fn count(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

impl At {
    /// The load step `step` as a message names it: where the scene has
    /// several, or a stage before them (step 0, the stage, always).
    pub(super) fn named(scene: &Scene, step: usize) -> Option<usize> {
        (scene.solver.load_steps > 1 || scene.solver.initial_stage || step == 0).then_some(step)
    }
}

impl fmt::Display for At {
    /// "[load step k, ]contact iteration i (s stick, l slip, o open)".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.step {
            Some(0) => write!(f, "the initial equilibrium stage, ")?,
            Some(k) => write!(f, "load step {k}, ")?,
            None => {}
        }
        write!(
            f,
            "contact iteration {} ({} stick, {} slip, {} open",
            self.iteration, self.states[2], self.states[1], self.states[0]
        )?;
        match self.rounds {
            Some([rounds, iterations]) => {
                write!(f, "; {iterations} of the iterations in {rounds} augmented Lagrangian round(s))")
            }
            None => write!(f, ")"),
        }
    }
}

impl fmt::Display for ContactError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ContactError::NotHeld { at, bodies, places, apex } => {
                let one = bodies.len() == 1;
                let apex = if apex.is_empty() {
                    String::new()
                } else {
                    let each: Vec<String> = apex
                        .iter()
                        .map(|a| format!("contacts[{}] opens at c / f = {} (its tensile_strength {} exceeds that Coulomb apex: no shear strength is left there)", a.contact, a.opens_at, a.tensile_strength))
                        .collect();
                    format!(" ({})", each.join("; "))
                };
                write!(
                    f,
                    "{} {} held by nothing at {at}: {} contact pairs opened and no support holds {}{apex}. Add a support, or check the loads that pull the contact apart",
                    bodies_named(bodies, places),
                    if one { "is" } else { "are" },
                    if one { "its" } else { "their" },
                    if one { "it" } else { "them" },
                )
            }
            ContactError::Sliding { at, bodies, places, no_shear, rule, motions } => {
                let (who, moves, its) = match bodies.len() {
                    0 => ("a body".to_string(), "slides or rotates", "its"),
                    1 => (bodies_named(bodies, places), "slides or rotates", "its"),
                    _ => (bodies_named(bodies, places), "slide or rotate", "their"),
                };
                write!(
                    f,
                    "the interface system is singular at {at}: {who} {moves} freely{} on {its} contacts",
                    motions_named(motions)
                )?;
                if *no_shear {
                    write!(f, ", which carry no shear (no friction and no cohesion, or slip = \"frictionless\"): nothing holds {} along them, whatever the load. Add a support that holds {} tangentially, or give the contacts friction or cohesion", if bodies.len() > 1 { "them" } else { "it" }, if bodies.len() > 1 { "them" } else { "it" })
                } else if *rule == StateRule::Paper {
                    let it = if bodies.len() > 1 { "them" } else { "it" };
                    write!(f, " — loss of equilibrium: the load along the contact exceeds what friction and cohesion can carry; or the paper's rule, which gives a slipping pair a fixed shear, holds nothing across the slip once every pair holding {it} slips. Reduce the load, add a support that holds {it} tangentially, raise the friction or cohesion of {its} contacts, or use the default rule = \"robust\", whose friction holds across the slip")
                } else {
                    write!(f, " — loss of equilibrium: the load along the contact exceeds what friction and cohesion can carry. Reduce the load, add a support that holds {} tangentially, or raise the friction or cohesion of {its} contacts", if bodies.len() > 1 { "them" } else { "it" })
                }
            }
            ContactError::NotConverged { .. } => self.fmt_not_converged(f),
            ContactError::BondedNotHeld => {
                write!(f, "the bonded interface system of the substructures is singular: a body is not held")
            }
            ContactError::Traction { reason } => {
                write!(f, "consistent contact traction: the interface mass matrix: {reason}")
            }
        }
    }
}

impl ContactError {
    /// [`ContactError::NotConverged`] said: where the iteration stopped,
    /// why, the cuts tried, and where to look and what to try.
    fn fmt_not_converged(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ContactError::NotConverged {
            step,
            iterations,
            stop,
            slipping_back,
            rigid_joints,
            fell_back,
            cuts,
            scaled,
            rule,
            results,
        } = self
        else {
            return Ok(());
        };
        write!(f, "the contact iteration did not converge")?;
        match step {
            Some(0) => write!(f, " in the initial equilibrium stage ([solver] initial_stage: the in-situ stress with the contacts active, before any load)")?,
            Some(k) => write!(f, " at load step {k}")?,
            None => {}
        }
        let why = match stop {
            Stop::Cycled => " (the states cycle)",
            Stop::LawBroken => " (the states settled, but their forces break the contact law: see the law residual)",
            Stop::MaxIterations => "",
        };
        write!(f, " after {iterations} iteration(s){why}")?;
        if *fell_back {
            write!(f, " with joints that deform, which the run gave every contact when its rigid joints did not converge either (report.md says the stiffness; [solver] rigid_fallback)")?;
        }
        match (cuts, step) {
            (0, _) if *scaled => write!(f, ", {} ([solver] max_cuts)", NOT_CUT)?,
            (0, _) => {}
            (_, Some(0)) => write!(f, ", the stage cut {cuts} time(s) in halves (its load, or where the in-situ stress is beyond the joints' strength, the pieces that strength is brought down in; [solver] max_cuts)")?,
            _ => write!(f, ", the step cut {cuts} time(s) in halves ([solver] max_cuts)")?,
        }
        match results {
            Some(out) => where_to_look(f, out, *slipping_back, *rigid_joints, *rule),
            None => Ok(()),
        }
    }
}

/// Where the results of a step that did not converge are (`out`), what to
/// look for there and what to try: more iterations unless pairs slip
/// against their friction (`slipping_back`), the robust rule, joints that
/// deform where they are rigid.
fn where_to_look(
    f: &mut fmt::Formatter<'_>,
    out: &Path,
    slipping_back: usize,
    rigid_joints: Option<[f64; 2]>,
    rule: StateRule,
) -> fmt::Result {
    let other = if rule == StateRule::Paper { ", or the default rule = \"robust\"" } else { "" };
    write!(f, "; the results in {} are those of the last iteration (summary.json contact.converged = false, report.md says where the states kept changing, contact.csv and the contact VTU mark those pairs: `changes`). Look there for a block held by a few pairs, a joint at its strength, or a support missing", out.display())?;
    match slipping_back {
        0 => write!(f, "; or try more [solver] max_iterations{other}")?,
        n => write!(f, ". {n} pair(s) slip against their own friction (contact.csv: a law_residual about twice their shear): stuck, each is beyond its bound, and let slip its friction pushes it back, a wedge such as a corner where two joints cross near a free face; more iterations did not settle such pairs where that was measured (docs/convergence.md){other}")?,
    }
    match rigid_joints {
        Some(k) => joint_stiffness_advice(f, k),
        None => Ok(()),
    }
}

/// What a step of rigid joints that did not converge can try instead:
/// joints that deform, with the normal and shear stiffness `k` the run's
/// fallback would take (`[solver] rigid_fallback`, off where this is said).
fn joint_stiffness_advice(f: &mut fmt::Formatter<'_>, k: [f64; 2]) -> fmt::Result {
    write!(
        f,
        ". Or give the joints a stiffness, as 3DEC's and UDEC's have: normal_stiffness and shear_stiffness on every [[contacts]] and [[joint_sets]] entry, e.g. normal_stiffness = {} and shear_stiffness = {} (k_n = {} E / s, E the softest body's modulus and s the mean block size: the joints then add a tenth to the rock mass's compliance; k_s a tenth of k_n), or leave [solver] rigid_fallback at its default (true) and the run does so when rigid joints do not converge. Where rigid joints cross, their forces are shared by ties that can leave no state set keeping the law; a joint that deforms is a spring, and the jointed tunnels whose rigid joints did not end in 300 iterations end in 4 to 6 (README, \"Joints that deform\")",
        k[0],
        k[1],
        super::fallback::STIFFER,
    )
}

impl fmt::Display for PlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlanError::TooManyRanks { ranks, parts, substructures } => {
                let more = ranks.div_ceil((*parts).max(1)) * (*substructures).max(1);
                write!(
                    f,
                    "{ranks} MPI ranks but the model has {parts} part(s): every rank needs a part. Cut the bodies into more substructures ([solver] substructures = {more} or --substructures {more}), or run on at most {parts} rank(s)"
                )
            }
        }
    }
}

impl fmt::Display for SafetyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SafetyError::Unsafe { .. } => unsafe_message(self, f),
            SafetyError::Undecided { holds, fails, undecided, load, rigid_joints, retry, results } => {
                let what = if *load { "load factor" } else { "factor of safety" };
                let tried: Vec<String> = undecided.iter().map(|u| format!("{u:.4}")).collect();
                write!(f, "the {what} is not decided: the contact iteration did not converge at F = {} even when retried in smaller steps with more iterations, so those trials neither hold nor fail. Converged trials hold at F = {holds:.4}", tried.join(", "))?;
                match fails {
                    Some(x) => write!(f, " and fail at F = {x:.4}: F lies between them")?,
                    None => write!(f, " and none above converged: F is at least {holds:.4}")?,
                }
                if let Some(out) = results {
                    write!(f, "; the results in {} are those of the last state that holds", out.display())?;
                }
                let paper = retry.rule == StateRule::Paper;
                if paper {
                    write!(f, ". Solve it with [solver] rule = \"robust\" (the default): the paper's rule reports a cycle of states and does not break it")?;
                }
                if let Some(n) = retry.budget {
                    write!(f, ". Try more [solver] max_iterations: a trial stopped at its retry's {n} iterations with its states still changing")?;
                }
                let advised = paper || retry.budget.is_some();
                let or = if advised { "Or give" } else { "Give" };
                match rigid_joints {
                    // the safety search does not fall back itself: its
                    // trials would change the model between them
                    Some(k) => write!(f, ". {or} the joints a stiffness, normal_stiffness = {} and shear_stiffness = {} on every [[contacts]] and [[joint_sets]] entry (k_n = {} E / s, E the softest body's modulus and s the mean block size): where rigid joints cross, a trial's law can have no state set that keeps it, and joints that deform have no crossing ties (README, \"Joints that deform\")", k[0], k[1], super::fallback::STIFFER),
                    None if !advised => write!(f, ". safety.csv lists every trial and how it ended"),
                    None => Ok(()),
                }
            }
        }
    }
}

/// The paragraph of [`SafetyError::Unsafe`].
fn unsafe_message(e: &SafetyError, f: &mut fmt::Formatter<'_>) -> fmt::Result {
    let SafetyError::Unsafe { at_one, holds, fails, max_factor, mechanism, load, results } = e else {
        return Ok(());
    };
    let (cause, no_shear) = match at_one {
        ContactError::Sliding { at, bodies, places, no_shear, motions, .. } => {
            let who = if bodies.is_empty() { "a body".to_string() } else { bodies_named(bodies, places) };
            let verb = if bodies.len() > 1 { "move" } else { "moves" };
            (
                format!(
                    "the scene loses equilibrium at {at}: {who} {verb} freely{} on {} contacts",
                    motions_named(motions),
                    if bodies.len() > 1 { "their" } else { "its" }
                ),
                *no_shear,
            )
        }
        ContactError::NotHeld { at, bodies, places, .. } => {
            let one = bodies.len() == 1;
            (
                format!(
                    "the scene loses equilibrium at {at}: {} {} held by nothing once {} contacts open",
                    bodies_named(bodies, places),
                    if one { "is" } else { "are" },
                    if one { "its" } else { "their" }
                ),
                false,
            )
        }
        other => (other.to_string(), false),
    };
    let given = if *load { "its loads as given (F = 1)" } else { "the full strength of its contacts (F = 1)" };
    write!(f, "unsafe as given: with {given} {cause}")?;
    if let Some((how, _)) = mechanism {
        write!(f, ": {how}")?;
    }
    let what = if *load { "load factor" } else { "factor of safety (strength reduction)" };
    let by = if *load { "the raised loads multiplied by" } else { "the reduced strength parameters multiplied by" };
    let unhelped = mechanism
        .as_ref()
        .is_some_and(|m| matches!(m.1, BlockState::Toppling | BlockState::Lifting | BlockState::Free));
    match holds {
        None if unhelped && !*load => write!(f, ". No strength of its contacts makes it stand (the load steps fail even with the reduced strength parameters multiplied by {max_factor}, safety.max_factor): strength reduction has no factor for a block that {}", match mechanism.as_ref().map(|m| m.1) { Some(BlockState::Toppling) => "topples", Some(BlockState::Lifting) => "lifts off", _ => "falls free" })?,
        Some(h) if *h >= 1.0 && !*load => write!(f, ". The load steps lose cohesion where pairs slip or open (residual_cohesion, 0 where the scene is silent); with the peak strength kept over the whole sliding surface, as limit equilibrium keeps it, its {what} is F = {h:.4} (holds; fails from F = {fails:.4}): it stands by limit equilibrium, not with the residual strength the load steps use")?,
        Some(h) => write!(f, ". Its {what} is below 1: F = {h:.4} (the load steps hold with {by} {} = {:.4} and fail from F = {fails:.4} up; each trial ran the initial stage, if any, and the load steps from the start)", if *load { "F" } else { "1/F" }, if *load { *h } else { 1.0 / h })?,
        None => write!(f, ". Its {what} is below 1: F < {:.4}: the load steps fail even with {by} {} (safety.max_factor){}", 1.0 / max_factor, if *load { 1.0 / max_factor } else { *max_factor }, if no_shear { ", since the contacts the blocks slide on carry no shear (no friction and no cohesion, or slip = \"frictionless\")" } else { "" })?,
    }
    match results {
        Some(out) if holds.is_some_and(|h| h >= 1.0) && !*load => write!(f, ". The results in {} are the last load step that held (if any), the failing step's last iterate (not in equilibrium: summary.json contact.converged = false), the state at F (the safety_ files) and the mechanism (blocks.csv, report.md)", out.display())?,
        Some(out) => write!(f, ". A search upward needs a state that holds at F = 1, so none was made; the results in {} are the last load step that held (if any), the failing step's last iterate (not in equilibrium: summary.json contact.converged = false) and the mechanism (blocks.csv, report.md)", out.display())?,
        None => write!(f, ". A search upward needs a state that holds at F = 1, so none was made and no result files were written")?,
    }
    match mechanism {
        Some((_, motion)) => write!(f, ". To hold it: {}", motion.helps()),
        None => write!(
            f,
            ". Raise the friction or cohesion of those contacts, lower the loads, or hold the blocks that move"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn not_converged(slipping_back: usize) -> String {
        not_converged_with(slipping_back, None)
    }

    fn not_converged_with(slipping_back: usize, rigid_joints: Option<[f64; 2]>) -> String {
        ContactError::NotConverged {
            step: Some(1),
            iterations: 100,
            stop: Stop::Cycled,
            slipping_back,
            rigid_joints,
            fell_back: false,
            cuts: 0,
            scaled: false,
            rule: StateRule::Robust,
            results: Some(PathBuf::from("out")),
        }
        .to_string()
    }

    #[test]
    fn more_iterations_are_not_advised_where_pairs_slip_against_their_friction() {
        // (the 34k tunnel's pairs that slip back did not settle in 700 iterations)
        let plain = not_converged(0);
        assert!(plain.contains("or try more [solver] max_iterations"), "{plain}");
        let back = not_converged(3);
        assert!(!back.contains("max_iterations"), "{back}");
        assert!(back.contains("3 pair(s) slip against their own friction (contact.csv"), "{back}");
    }

    #[test]
    fn rigid_joints_are_advised_a_stiffness_from_the_rocks_modulus() {
        assert!(!not_converged(0).contains("normal_stiffness"));
        for back in [0, 3] {
            let said = not_converged_with(back, Some([13890.0, 1389.0]));
            assert!(said.contains("normal_stiffness = 13890 and shear_stiffness = 1389 "), "{said}");
            assert!(said.contains("rigid_fallback"), "{said}");
        }
    }

    /// An undecided search's message, with `rigid_joints` and `retry`.
    fn undecided(rigid_joints: Option<[f64; 2]>, retry: RetryAdvice) -> String {
        let (holds, fails, undecided) = (1.2, Some(1.4), vec![1.3]);
        let (load, results) = (false, None);
        SafetyError::Undecided { holds, fails, undecided, load, rigid_joints, retry, results }.to_string()
    }

    #[test]
    fn an_undecided_safety_factor_on_rigid_joints_is_advised_a_stiffness() {
        assert!(!undecided(None, RetryAdvice::default()).contains("normal_stiffness"));
        let said = undecided(Some([13890.0, 1389.0]), RetryAdvice::default());
        assert!(
            said.contains(
                ". Give the joints a stiffness, normal_stiffness = 13890 and shear_stiffness = 1389 on every"
            ),
            "{said}"
        );
    }

    #[test]
    fn an_undecided_safety_factor_is_advised_only_what_can_end_its_trials() {
        let cycled = undecided(None, RetryAdvice::default());
        for useless in ["max_iterations", "safety.step", "rule"] {
            assert!(!cycled.contains(useless), "{cycled}");
        }
        assert!(cycled.ends_with(". safety.csv lists every trial and how it ended"), "{cycled}");
        let paper = undecided(None, RetryAdvice { rule: StateRule::Paper, budget: None });
        assert!(paper.contains(". Solve it with [solver] rule = \"robust\" (the default)"), "{paper}");
        assert!(!paper.contains("max_iterations"), "{paper}");
        let settling = undecided(Some([13890.0, 1389.0]), RetryAdvice { rule: StateRule::Robust, budget: Some(400) });
        assert!(
            settling.contains(". Try more [solver] max_iterations: a trial stopped at its retry's 400 iterations"),
            "{settling}"
        );
        assert!(settling.contains(". Or give the joints a stiffness"), "{settling}");
    }
}
