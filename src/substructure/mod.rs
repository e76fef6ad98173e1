//! Substructures: the bodies of a model grouped into parts (bodies joined by
//! shared nodes move as one), each assembled and factorised once, and
//! condensed onto its contact interface.
//!
//! With the part's DOFs split into interior `i` and interface `c`,
//!
//! ```text
//! [K_ii K_ic] [d_i]   [F_i      ]
//! [K_ci K_cc] [d_c] = [F_c + f_c]       S = K_cc - K_ci K_ii^-1 K_ic
//!                                        G = F_c  - K_ci K_ii^-1 F_i
//! S d_c = G + f_c                        d_i = K_ii^-1 (F_i - K_ic d_c)
//! ```
//!
//! Interface DOFs are all components of the nodes in contact pairs, in
//! global axes, supported or not: supports of interface nodes are applied in
//! the interface system. A part without contact has no interface and is
//! solved directly.
//!
//! Two condensations ([`Condensation`]): the dense S, from one factorisation
//! with the interface ordered last ([`schur`]), or no S at all, the interior
//! factorised alone and S applied through it ([`interior`], for the
//! iterative interface of large joints and many substructures).

pub mod assembly;
pub mod interior;
pub mod ordering;
pub mod parts;
pub mod schur;
pub mod single_precision;
pub mod sparse_forward;
pub mod two_threads;

pub use parts::{cut, parts, Part};

use crate::fem::sparse::{FactorError, NONE};
use crate::model::{Model, ModelError};
use interior::{InteriorSolve, SharedSolve};
use ordering::Ordering;
use schur::PartialCholesky;

/// What the interface needs of a condensed part: its interface nodes, its
/// Schur complement ([`Schur`]) and the condensed loads G, one per load
/// case. What travels from a part's MPI rank to rank 0.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Operator {
    pub part: Part,
    pub nc: usize,
    pub g: Vec<Vec<f64>>,
    pub s: Schur,
}

/// A part's Schur complement as the interface gets it, by condensation.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub enum Schur {
    /// S itself, column-major nc x nc (empty once taken or freed).
    Dense(Vec<f64>),
    /// S applied on the part's own rank, through its interior factor; the
    /// interface gets the diagonal blocks of K_cc (nd x nd per interface
    /// node, row-major) for its preconditioner.
    Applied { diag: Vec<f64> },
}

/// An [`Operator`] borrowed from a [`Condensed`] part or a received one.
#[derive(Clone, Copy)]
pub struct OperatorRef<'a> {
    pub part: &'a Part,
    pub nc: usize,
    pub g: &'a [Vec<f64>],
    pub s: SchurRef<'a>,
}

/// A [`Schur`] borrowed; an applied one with its interior factor when the
/// part is on this rank.
#[derive(Clone, Copy)]
pub enum SchurRef<'a> {
    Dense(&'a [f64]),
    Applied { diag: &'a [f64], solve: Option<&'a SharedSolve> },
}

impl Operator {
    pub fn as_ref(&self) -> OperatorRef<'_> {
        let s = match &self.s {
            Schur::Dense(s) => SchurRef::Dense(s),
            Schur::Applied { diag } => SchurRef::Applied { diag, solve: None },
        };
        OperatorRef { part: &self.part, nc: self.nc, g: &self.g, s }
    }
}

/// How to condense a part with an interface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Condensation {
    /// The dense Schur complement S (the factor with its interface last).
    Dense,
    /// The interior factorised alone, S applied through it ([`interior`]).
    Applied,
}

/// A condensed part's factor and what the interface gets of it.
enum Factor {
    /// The part's factor with its interface ordered last ([`schur`]), and
    /// the S read off it.
    Schur { chol: Box<PartialCholesky>, s: Vec<f64> },
    /// The same with the factor freed to save memory
    /// ([`Condensed::drop_factor`]): made again to recover the interior.
    Freed { s: Vec<f64> },
    /// The interior factorised alone, which applies S ([`interior`]), and
    /// the diagonal blocks of K_cc.
    Interior { solve: SharedSolve, diag: Vec<f64> },
}

/// A factorised part, condensed onto its interface when it has one.
pub struct Condensed {
    pub part: Part,
    /// The model DOF of each interior equation (`0..ni`): what the part
    /// recovers. (A map from every model DOF, as the assembly takes, held
    /// by each of the 1,000-block cube's parts took 1.9 GB.)
    interior: Vec<usize>,
    /// The prescribed model DOFs of the part's nodes off its interface.
    fixed: Vec<usize>,
    pub ni: usize,
    /// Number of interface DOFs (`interface.len() * nd`).
    pub nc: usize,
    factor: Factor,
    /// Bytes of the factor's values.
    pub factor_bytes: usize,
    /// The load vectors `[F_i; F_c]`, one per load case.
    f: Vec<Vec<f64>>,
    /// Condensed loads, one per load case.
    pub g: Vec<Vec<f64>>,
    /// Seconds spent assembling, and factorising and condensing.
    pub assemble_s: f64,
    pub condense_s: f64,
    /// Normwise backward error of the part's sparse solves (the assembled
    /// system's residual), ~1e-16 for a healthy factorisation.
    pub backward_error: f64,
}

/// What factorising a part gives [`Condensed`].
struct Factored {
    factor: Factor,
    g: Vec<Vec<f64>>,
    factor_bytes: usize,
    backward_error: f64,
}

/// Why a part could not be solved.
pub fn not_held(model: &Model, part: &Part, e: FactorError) -> ModelError {
    let part = part.describe(model);
    match e {
        FactorError::NotPositiveDefinite => ModelError::PartNotHeld { part },
        FactorError::Resource(why) => ModelError::PartFactor { part, why },
    }
}

/// Number the interior free DOFs (0..ni) and the interface DOFs (ni..ni+nc).
pub fn numbering(model: &Model, part: &Part) -> (Vec<usize>, usize, usize) {
    let nd = model.nd;
    let mut dof_of = vec![NONE; model.n_nodes() * nd];
    let mut is_iface = vec![false; model.n_nodes()];
    for &n in &part.interface {
        is_iface[n] = true;
    }
    let mut seen = vec![false; model.n_nodes()];
    let mut ni = 0;
    for &(b, c) in &part.cells {
        for &n in &model.bodies[b].cells[c].nodes {
            if seen[n] || is_iface[n] {
                continue;
            }
            seen[n] = true;
            for comp in 0..nd {
                if model.prescribed[n * nd + comp].is_none() {
                    dof_of[n * nd + comp] = ni;
                    ni += 1;
                }
            }
        }
    }
    let mut next = ni;
    for &n in &part.interface {
        for comp in 0..nd {
            dof_of[n * nd + comp] = next;
            next += 1;
        }
    }
    (dof_of, ni, next - ni)
}

/// The model node of each interior equation `0..ni`.
pub fn interior_nodes(dof_of: &[usize], nd: usize, ni: usize) -> Vec<usize> {
    interior_dofs(dof_of, ni).into_iter().map(|i| i / nd).collect()
}

/// The model DOF of each interior equation `0..ni`.
fn interior_dofs(dof_of: &[usize], ni: usize) -> Vec<usize> {
    let mut dof = vec![0; ni];
    for (i, &d) in dof_of.iter().enumerate() {
        if d < ni {
            dof[d] = i;
        }
    }
    dof
}

/// Condenses every part, `threads` of them at a time (each thread runs
/// [`condense`] with the caller's faer parallelism), in the order given.
/// The first failing part, in that order, is the error.
///
/// Parts are independent, so this is the parallelism that pays on 2 cores:
/// blocks3d_hex (hex20, two parts of 51k and 54k interior equations),
/// quiet machine: 10.3 s one after the other, 5.3 s in two threads (1.9x),
/// where faer's `Par::rayon(2)` inside the factorisation gives 1.25x (3.9 ->
/// 3.1 s a part). With the other core busy two threads cost 5-7 % more
/// than one (16.6-18.0 s against 15.9-16.9 s), rayon(2) 20-50 % more.
pub fn condense_parts(
    model: &Model,
    parts: Vec<Part>,
    threads: usize,
    how: Condensation,
) -> Result<Vec<Condensed>, ModelError> {
    let threads = threads.clamp(1, parts.len().max(1));
    if threads == 1 {
        return parts.into_iter().map(|p| condense(model, p, how)).collect();
    }
    let n = parts.len();
    let queue = std::sync::Mutex::new(parts.into_iter().enumerate());
    let mut done: Vec<(usize, Result<Condensed, ModelError>)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut out = Vec::new();
                    loop {
                        // a poisoned queue means another worker panicked: its join re-raises it
                        let next = match queue.lock() {
                            Ok(mut q) => q.next(),
                            Err(_) => None,
                        };
                        let Some((i, part)) = next else { break };
                        out.push((i, condense(model, part, how)));
                    }
                    out
                })
            })
            .collect();
        workers.into_iter().flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e))).collect()
    });
    debug_assert_eq!(done.len(), n);
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, c)| c).collect()
}

/// Assembles, factorises and condenses a part.
pub fn condense(model: &Model, part: Part, how: Condensation) -> Result<Condensed, ModelError> {
    let t = std::time::Instant::now();
    let (dof_of, ni, nc) = numbering(model, &part);
    let a = assembly::assemble(model, &part.cells, &dof_of, ni + nc)?;
    let assemble_s = t.elapsed().as_secs_f64();
    let interior = interior_dofs(&dof_of, ni);
    let node_of: Vec<usize> = interior.iter().map(|&i| i / model.nd).collect();
    let ordering = Ordering::choose(ni, model.nd);
    // The caller's faer parallelism: sequential, as faer is built without its
    // `rayon` feature (it would add rayon and spindle). Measured on
    // blocks3d_hex (hex20, 51k interior equations a part), Par::rayon(2)
    // against Par::Seq: 3.1 s against 3.9 s a part on a quiet machine, 7.7-8.0
    // s against 4.9-6.5 s with other builds running; [`condense_parts`]'
    // threads use the two cores better.
    let par = faer::get_global_parallelism();
    let factored = if how == Condensation::Applied && nc > 0 {
        interior_factor(&a, ni, &node_of, ordering, par, model.nd)
    } else {
        schur_factor(&a, ni, &node_of, ordering, par)
    }
    .map_err(|e| not_held(model, &part, e))?;
    let nd = model.nd;
    let fixed = (part.nodes(model).into_iter().flat_map(|n| n * nd..n * nd + nd))
        .filter(|&i| dof_of[i] == NONE && model.prescribed[i].is_some())
        .collect();
    let condense_s = t.elapsed().as_secs_f64() - assemble_s;
    let Factored { factor, g, factor_bytes, backward_error } = factored;
    Ok(Condensed {
        part,
        interior,
        fixed,
        ni,
        nc,
        factor,
        factor_bytes,
        f: a.f,
        g,
        assemble_s,
        condense_s,
        backward_error,
    })
}

/// The part's factor with the interface last and S read off it; the
/// backward error of its solves of each load case.
fn schur_factor(
    a: &assembly::Assembled,
    ni: usize,
    node_of: &[usize],
    ordering: Ordering,
    par: faer::Par,
) -> Result<Factored, FactorError> {
    let n = a.k.n;
    let nc = n - ni;
    let chol = PartialCholesky::factor(&a.k, ni, node_of, ordering, par)?;
    let s = chol.schur(par);
    let (g, x) = chol.condensed_loads(&s, &a.f);
    let alpha = chol.alpha();
    let backward_error = (a.f.iter().enumerate())
        .map(|(k, f)| {
            let b: Vec<f64> = f[..ni].iter().copied().chain(std::iter::repeat_n(0.0, nc)).collect();
            a.k.backward_error(&x[k * n..(k + 1) * n], &b, alpha, ni)
        })
        .fold(0.0, f64::max);
    let factor_bytes = chol.stats().values * std::mem::size_of::<f64>();
    Ok(Factored { factor: Factor::Schur { chol: Box::new(chol), s }, g, factor_bytes, backward_error })
}

/// The part's interior factorised alone (S applied through it) and the
/// diagonal blocks of K_cc; the backward error of its interior solves.
fn interior_factor(
    a: &assembly::Assembled,
    ni: usize,
    node_of: &[usize],
    ordering: Ordering,
    par: faer::Par,
    nd: usize,
) -> Result<Factored, FactorError> {
    let nc = a.k.n - ni;
    let solve = InteriorSolve::factor(&a.k, ni, node_of, ordering, par)?;
    let (g, x) = solve.condensed_loads(&a.f);
    // K [x_i; 0] = [F_i; K_ci x_i]: the interface rows hold by construction
    let backward_error = (a.f.iter().enumerate())
        .map(|(k, f)| {
            let xk: Vec<f64> = x[k * ni..(k + 1) * ni].iter().copied().chain(std::iter::repeat_n(0.0, nc)).collect();
            let b: Vec<f64> = f[..ni].iter().chain(&a.k.mul(&xk)[ni..]).copied().collect();
            a.k.backward_error(&xk, &b, 0.0, ni)
        })
        .fold(0.0, f64::max);
    let (diag, factor_bytes) = (solve.diagonal_blocks(nd), solve.factor_bytes());
    Ok(Factored { factor: Factor::Interior { solve: SharedSolve::new(solve), diag }, g, factor_bytes, backward_error })
}

/// The factor of a part again (assembled and factorised as [`condense`]
/// did, so the same to the last bit): what recovers a part whose factor was
/// dropped.
fn refactor(model: &Model, part: &Part) -> PartialCholesky {
    let (dof_of, ni, nc) = numbering(model, part);
    let a = assembly::assemble(model, &part.cells, &dof_of, ni + nc).expect("the part was assembled before");
    let node_of = interior_nodes(&dof_of, model.nd, ni);
    PartialCholesky::factor(&a.k, ni, &node_of, Ordering::choose(ni, model.nd), faer::get_global_parallelism())
        .expect("the part was factorised before")
}

impl Condensed {
    /// The part's operator, borrowed.
    pub fn operator(&self) -> OperatorRef<'_> {
        let s = match &self.factor {
            Factor::Schur { s, .. } | Factor::Freed { s } => SchurRef::Dense(s),
            Factor::Interior { solve, diag } => SchurRef::Applied { diag, solve: Some(solve) },
        };
        OperatorRef { part: &self.part, nc: self.nc, g: &self.g, s }
    }

    /// How the part was condensed.
    pub fn how(&self) -> Condensation {
        match self.factor {
            Factor::Schur { .. } | Factor::Freed { .. } => Condensation::Dense,
            Factor::Interior { .. } => Condensation::Applied,
        }
    }

    /// Whether the part was condensed for the iterative interface.
    pub fn is_applied(&self) -> bool {
        self.how() == Condensation::Applied
    }

    /// The dense S (empty for a part condensed for the iterative interface,
    /// or once taken or freed).
    pub fn s(&self) -> &[f64] {
        match &self.factor {
            Factor::Schur { s, .. } | Factor::Freed { s } => s,
            Factor::Interior { .. } => &[],
        }
    }

    /// `S d` for the `k` columns of `d` (a part condensed for the iterative interface).
    pub fn apply(&self, d: &[f64], k: usize) -> Vec<f64> {
        match &self.factor {
            Factor::Interior { solve, .. } => solve.apply(d, k),
            _ => panic!("S applied of a part condensed densely"),
        }
    }

    /// The part's operator, its S moved out (to send it to another rank;
    /// the part keeps what recovers its interior).
    pub fn take_operator(&mut self) -> Operator {
        let s = match &mut self.factor {
            Factor::Schur { s, .. } | Factor::Freed { s } => Schur::Dense(std::mem::take(s)),
            Factor::Interior { diag, .. } => Schur::Applied { diag: diag.clone() },
        };
        Operator { part: self.part.clone(), nc: self.nc, g: self.g.clone(), s }
    }

    /// Frees the dense S once the interface holds what it needs of it.
    pub fn drop_schur(&mut self) {
        if let Factor::Schur { s, .. } | Factor::Freed { s } = &mut self.factor {
            *s = Vec::new();
        }
    }

    /// Frees the factor of a densely condensed part: [`Condensed::recover`]
    /// then assembles and factorises the part again (twice the
    /// factorisations, for a peak of one part's factor during recovery
    /// instead of all of them throughout the contact iteration).
    pub fn drop_factor(&mut self) {
        if let Factor::Schur { s, .. } = &mut self.factor {
            let s = std::mem::take(s);
            self.factor = Factor::Freed { s };
        }
    }

    /// The load vector combined with the load factors `lambda` (one per case).
    fn combine(v: &[Vec<f64>], lambda: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; v.first().map_or(0, |x| x.len())];
        for (x, &l) in v.iter().zip(lambda) {
            if l != 0.0 {
                for (o, xi) in out.iter_mut().zip(x) {
                    *o += l * xi;
                }
            }
        }
        out
    }

    /// The condensed load `G` for the load factors `lambda`.
    pub fn g_at(&self, lambda: &[f64]) -> Vec<f64> {
        Self::combine(&self.g, lambda)
    }

    /// Interior displacements from the interface displacements `d_c` under
    /// the load factors `lambda`, written into the model-wide displacement
    /// vector `u` (node-major, nd per node), together with `d_c` itself and
    /// the prescribed values (scaled by the ramp, case 0).
    pub fn recover(&self, model: &Model, d_c: &[f64], lambda: &[f64], u: &mut [f64]) {
        let nd = model.nd;
        let f = Self::combine(&self.f, lambda);
        let d_i = match &self.factor {
            Factor::Interior { solve, .. } => solve.interior(&f, d_c),
            Factor::Schur { chol, .. } => chol.interior(&f, &self.g_at(lambda), d_c),
            Factor::Freed { .. } => refactor(model, &self.part).interior(&f, &self.g_at(lambda), d_c),
        };
        for (&i, &d) in self.interior.iter().zip(&d_i) {
            u[i] = d;
        }
        for &i in &self.fixed {
            u[i] = model.prescribed[i].map_or(0.0, |v| v * lambda[0]);
        }
        for (q, &n) in self.part.interface.iter().enumerate() {
            for c in 0..nd {
                u[n * nd + c] = d_c[q * nd + c];
            }
        }
    }
}

#[cfg(test)]
mod tests;
