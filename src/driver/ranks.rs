//! The MPI ranks of a run, and the only code that knows rank 0 from the
//! others. Rank 0 meshes, solves the interface, recovers the stresses and
//! writes; every rank condenses and recovers its own parts. Each function
//! here is one such meeting, the same call on every rank, returning rank
//! 0's share as `Some` there and `None` elsewhere:
//!
//! - [`agree`]: a stage's result; the first failure ends every rank;
//! - [`mesh`]: rank 0 runs gmsh, the others read what it wrote;
//! - [`Ranks::interface`]: the parts' operators gathered on rank 0, which
//!   sets up the interface;
//! - [`Ranks::on_root`]: rank 0 works (the contact iteration) while the
//!   others apply their parts' S for its iterative interface ([`Remote`]:
//!   each application sends a part's interface displacements to the part's
//!   rank, which sends `S d` back; nothing else travels then);
//! - [`Ranks::recover`]: rank 0 sends each part's interface displacements
//!   (or its failure) to the owner, which recovers the part's interior;
//! - [`Ranks::stop`], [`Ranks::gather`].
//!
//! Serial runs take the same path with [`Serial`](crate::parallel::Serial),
//! which moves nothing.

use std::path::{Path, PathBuf};

use super::meshing::mesh_into;
use super::run_options::RunOptions;
use crate::contact::system::iterative::Remote;
use crate::contact::system::InterfaceProblem;
use crate::error::{Error, Result, Wire};
use crate::mesh::{msh, Mesh};
use crate::model::Model;
use crate::output::files::Stage;
use crate::parallel::{Comm, CommExt};
use crate::scene::{MeshSource, Scene};
use crate::substructure::{Condensed, Operator, OperatorRef, Part};

/// The options as each rank runs them: progress on rank 0 only.
pub(super) fn options(comm: &dyn Comm, opts: &RunOptions) -> RunOptions {
    RunOptions { verbose: opts.verbose && comm.is_root(), ..opts.clone() }
}

/// Every rank's result of a stage; the first failure, in rank order, ends
/// every rank with that rank's error ([`Wire`]: the same variant; the rank
/// that failed keeps its own error as it was).
pub(super) fn agree<T>(comm: &dyn Comm, r: Result<T>) -> Result<T> {
    if comm.size() == 1 {
        return r;
    }
    let mine: Option<Wire> = r.as_ref().err().map(|e| e.to_wire(comm.rank()));
    let failed: Vec<Option<Wire>> = comm.gather(&mine);
    let first: Option<(usize, Wire)> =
        comm.broadcast(&failed.into_iter().enumerate().find_map(|(rank, w)| Some((rank, w?))));
    match (r, first) {
        (Ok(v), None) => Ok(v),
        (Err(e), Some((rank, _))) if rank == comm.rank() => Err(e),
        (_, Some((_, wire))) => Err(wire.into()),
        (Err(e), None) => Err(e),
    }
}

/// The mesh of a scene, on every rank: rank 0 runs gmsh for a .geo (or
/// reads the .msh); the others read the file it wrote. The mesh, its file,
/// and whether gmsh's earlier output was reused.
pub(super) fn mesh(
    comm: &dyn Comm,
    scene: &Scene,
    out: &Path,
    opts: &RunOptions,
) -> Result<(Mesh, PathBuf, bool, Option<Stage>)> {
    let meshed = if comm.is_root() { root_mesh(scene, out, opts).map(Some) } else { Ok(None) };
    let meshed = agree(comm, meshed)?;
    // where the others read it: the .msh, or the mesh in rank 0's stage
    let staged: Option<PathBuf> = meshed.as_ref().and_then(|(_, _, _, stage, rel)| Some(stage.as_ref()?.path_of(rel)));
    let read_at: Option<PathBuf> = comm.broadcast(&staged);
    match meshed {
        Some((mesh, msh, cached, stage, _)) => Ok((mesh, msh, cached, stage)),
        None => {
            let p = match (&scene.mesh, read_at) {
                (MeshSource::Msh(p), _) => p.clone(),
                (MeshSource::Geo(_), Some(p)) => p,
                (MeshSource::Geo(_), None) => return Err(Error::NoMeshSent),
            };
            Ok((msh::read_msh(&p)?, p, true, None))
        }
    }
}

/// Rank 0's mesh step: the run's staging directory (when results or a
/// mesh cache are written) and the mesh; with the mesh's path in the stage.
fn root_mesh(scene: &Scene, out: &Path, opts: &RunOptions) -> Result<(Mesh, PathBuf, bool, Option<Stage>, String)> {
    let geo = matches!(scene.mesh, MeshSource::Geo(_));
    let mut stage = if geo || !opts.skip_output { Some(Stage::begin(out, &mut |m| super::say(m))?) } else { None };
    if let Some(stage) = stage.as_ref().filter(|_| !opts.skip_output) {
        stage.refuse_in_the_way(&scene.name)?;
    }
    let (mesh, msh, cached) = mesh_into(scene, stage.as_mut(), opts.allow_geo_commands)?;
    let rel = format!("{}/{}.msh", crate::output::files::MESH_DIR, scene.name);
    Ok((mesh, msh, cached, stage, rel))
}

/// The ranks once every part has its owner.
pub(super) struct Ranks<'c> {
    comm: &'c dyn Comm,
    /// The rank of each part.
    owner: Vec<usize>,
    /// The other ranks apply their parts' S while rank 0 solves the
    /// (iterative) interface.
    serve: bool,
}

/// What rank 0 asks of the other ranks while it solves the iterative interface.
#[derive(serde::Serialize, serde::Deserialize)]
enum Service {
    /// Apply the S of these parts (number, columns) to their `k` columns.
    Apply { k: usize, work: Vec<(usize, Vec<f64>)> },
    /// The interface stage is over (for this load step).
    Done,
}

/// What rank 0 sends every rank at each load step.
#[derive(serde::Serialize, serde::Deserialize)]
enum Order {
    /// Recover these parts (index, interface displacements) under these load factors.
    Recover { lambda: Vec<f64>, parts: Vec<(usize, Vec<f64>)> },
    /// The run failed on rank 0 with this error.
    Stop(Wire),
}

impl<'c> Ranks<'c> {
    /// `applied`: the parts are condensed for the iterative interface.
    pub fn new(comm: &'c dyn Comm, owner: Vec<usize>, applied: bool) -> Ranks<'c> {
        Ranks { comm, owner, serve: applied && comm.size() > 1 }
    }

    pub fn comm(&self) -> &'c dyn Comm {
        self.comm
    }

    pub fn rank(&self) -> usize {
        self.comm.rank()
    }

    pub fn size(&self) -> usize {
        self.comm.size()
    }

    pub fn bytes_sent(&self) -> u64 {
        self.comm.bytes_sent()
    }

    /// Every rank's `value`, on rank 0.
    pub fn gather<T: serde::Serialize + serde::de::DeserializeOwned>(&self, value: &T) -> Option<Vec<T>> {
        let all = self.comm.gather(value);
        self.comm.is_root().then_some(all)
    }

    /// Whether every rank stops here, as rank 0 says.
    pub fn stop(&self, stop: bool) -> bool {
        self.comm.broadcast(&stop)
    }

    /// `f()` on rank 0, while the other ranks apply their parts' S (of
    /// `mine`) for its iterative interface.
    pub fn on_root<T>(&self, mine: &[(usize, Condensed)], f: impl FnOnce() -> T) -> Option<T> {
        if self.comm.is_root() {
            let v = f();
            if self.serve {
                self.done();
            }
            Some(v)
        } else {
            if self.serve {
                serve(self.comm, mine);
            }
            None
        }
    }

    /// The interface on rank 0, set up by `build` from every part's
    /// operator (received from its owner; this rank's own applied parts
    /// keep their factor) and the other ranks as its [`Remote`]; `None`
    /// elsewhere, or when `build` finds no interface.
    pub fn interface<'r>(
        &'r self,
        mine: &mut [(usize, Condensed)],
        build: impl FnOnce(&[OperatorRef<'_>], Option<&'r dyn Remote>) -> Result<Option<InterfaceProblem<'r>>>,
    ) -> Result<Option<InterfaceProblem<'r>>> {
        let received: Vec<(usize, Operator)> = if self.comm.size() > 1 {
            let ops: Vec<(usize, Operator)> = mine.iter_mut().map(|(i, c)| (*i, c.take_operator())).collect();
            let mut all: Vec<(usize, Operator)> = self.comm.gather(&ops).into_iter().flatten().collect();
            all.sort_by_key(|(i, _)| *i);
            all
        } else {
            Vec::new()
        };
        let remote: Option<&'r dyn Remote> = if self.serve { Some(self) } else { None };
        let mine: &[(usize, Condensed)] = mine;
        let built = self.on_root(mine, || {
            let ops: Vec<OperatorRef> = if self.comm.size() > 1 {
                (received.iter())
                    .map(|(i, o)| match mine.iter().find(|(j, _)| j == i) {
                        Some((_, c)) if c.is_applied() => c.operator(),
                        _ => o.as_ref(),
                    })
                    .collect()
            } else {
                mine.iter().map(|(_, c)| c.operator()).collect()
            };
            build(&ops, remote)
        });
        agree(self.comm, built.unwrap_or(Ok(None)))
    }

    /// The displacements of every part's nodes under the load factors
    /// `lambda`, on rank 0: rank 0's `answer` (each part's interface
    /// displacements, or why it has none) goes to the owners of `parts`, which
    /// recover their interiors (only when `need_u`) and send them back. A
    /// failure on rank 0 ends every rank, rank 0 with its own error.
    pub fn recover(
        &self,
        model: &Model,
        parts: &[Part],
        mine: &[(usize, Condensed)],
        answer: Option<Result<Vec<Vec<f64>>>>,
        lambda: &[f64],
        need_u: bool,
    ) -> Result<Option<Vec<f64>>> {
        let nd = model.nd;
        let values: Vec<(usize, Vec<f64>)> = if self.comm.size() == 1 {
            let mut d_c = answer.expect("one process is rank 0")?;
            if !need_u {
                Vec::new()
            } else {
                let d: Vec<(usize, Vec<f64>)> = mine.iter().map(|(i, _)| (*i, std::mem::take(&mut d_c[*i]))).collect();
                recover_parts(model, mine, &d, lambda)
            }
        } else {
            let (orders, failure) = self.orders(answer, lambda, need_u);
            match self.comm.scatter(&orders) {
                Order::Stop(wire) => return Err(failure.unwrap_or_else(|| wire.into())),
                Order::Recover { lambda, parts } => {
                    let local = if need_u { recover_parts(model, mine, &parts, &lambda) } else { Vec::new() };
                    self.comm.gather(&local).into_iter().flatten().collect()
                }
            }
        };
        if !self.comm.is_root() {
            return Ok(None);
        }
        let mut u = vec![0.0; model.n_nodes() * nd];
        for (i, vals) in &values {
            for (q, &n) in parts[*i].nodes(model).iter().enumerate() {
                u[n * nd..n * nd + nd].copy_from_slice(&vals[q * nd..q * nd + nd]);
            }
        }
        Ok(Some(u))
    }

    /// Rank 0's orders to every rank (empty elsewhere), and its own failure.
    fn orders(
        &self,
        answer: Option<Result<Vec<Vec<f64>>>>,
        lambda: &[f64],
        need_u: bool,
    ) -> (Vec<Order>, Option<Error>) {
        let size = self.comm.size();
        match answer {
            None => (Vec::new(), None),
            Some(Err(e)) => ((0..size).map(|_| Order::Stop(e.to_wire(0))).collect(), Some(e)),
            Some(Ok(d_c)) => {
                let parts = |r: usize| {
                    if need_u {
                        (0..d_c.len()).filter(|&i| self.owner[i] == r).map(|i| (i, d_c[i].clone())).collect()
                    } else {
                        Vec::new()
                    }
                };
                ((0..size).map(|r| Order::Recover { lambda: lambda.to_vec(), parts: parts(r) }).collect(), None)
            }
        }
    }

    /// Ends the other ranks' [`serve`].
    fn done(&self) {
        let per_rank: Vec<Service> = (0..self.comm.size()).map(|_| Service::Done).collect();
        let _: Service = self.comm.scatter(&per_rank);
    }
}

impl Remote for Ranks<'_> {
    fn send(&self, work: Vec<(usize, Vec<f64>)>, k: usize) {
        let mut per_rank: Vec<Service> =
            (0..self.comm.size()).map(|_| Service::Apply { k, work: Vec::new() }).collect();
        for (i, d) in work {
            if let Service::Apply { work, .. } = &mut per_rank[self.owner[i]] {
                work.push((i, d));
            }
        }
        let _: Service = self.comm.scatter(&per_rank);
    }

    fn receive(&self) -> Vec<(usize, Vec<f64>)> {
        self.comm.gather(&Vec::<(usize, Vec<f64>)>::new()).into_iter().flatten().collect()
    }
}

/// On the ranks other than 0: apply this rank's parts' S for rank 0 until
/// it says the interface stage is over.
fn serve(comm: &dyn Comm, mine: &[(usize, Condensed)]) {
    loop {
        match comm.scatter::<Service>(&[]) {
            Service::Done => return,
            Service::Apply { k, work } => {
                let out: Vec<(usize, Vec<f64>)> = (work.into_iter())
                    .map(|(i, d)| {
                        let (_, part) = mine.iter().find(|(j, _)| *j == i).expect("rank 0 sends a part to its owner");
                        (i, part.apply(&d, k))
                    })
                    .collect();
                comm.gather(&out);
            }
        }
    }
}

/// Recovers the interiors of `mine` under `lambda`: the displacements of
/// their nodes, part by part (node order of `Part::nodes`).
fn recover_parts(
    model: &Model,
    mine: &[(usize, Condensed)],
    d_c: &[(usize, Vec<f64>)],
    lambda: &[f64],
) -> Vec<(usize, Vec<f64>)> {
    let nd = model.nd;
    let mut u = vec![0.0; model.n_nodes() * nd];
    mine.iter()
        .zip(d_c)
        .map(|((i, c), (j, d))| {
            debug_assert_eq!(i, j);
            c.recover(model, d, lambda, &mut u);
            let values = c.part.nodes(model).iter().flat_map(|&n| u[n * nd..n * nd + nd].to_vec()).collect();
            (*i, values)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use std::sync::{Arc, Barrier, Mutex};

    use super::*;
    use crate::model::{ModelError, PartName};
    use crate::parallel::Comm;

    /// Ranks as threads of one process: each collective meets at a barrier
    /// and moves the bytes through shared slots, as MPI would.
    struct Threads {
        rank: usize,
        size: usize,
        slots: Arc<Mutex<Vec<Vec<u8>>>>,
        barrier: Arc<Barrier>,
    }

    impl Threads {
        /// Rank 0's view of every rank's `bytes` (the others get nothing).
        fn meet(&self, bytes: Vec<u8>) -> Vec<Vec<u8>> {
            self.slots.lock().expect("slots")[self.rank] = bytes;
            self.barrier.wait();
            let all = self.slots.lock().expect("slots").clone();
            self.barrier.wait();
            all
        }
    }

    impl Comm for Threads {
        fn rank(&self) -> usize {
            self.rank
        }
        fn size(&self) -> usize {
            self.size
        }
        fn gather_bytes(&self, bytes: Vec<u8>) -> Vec<Vec<u8>> {
            let all = self.meet(bytes);
            if self.rank == 0 {
                all
            } else {
                Vec::new()
            }
        }
        fn scatter_bytes(&self, _per_rank: Vec<Vec<u8>>) -> Vec<u8> {
            unimplemented!("agree does not scatter")
        }
        fn broadcast_bytes(&self, bytes: Vec<u8>) -> Vec<u8> {
            self.meet(bytes).swap_remove(0)
        }
        fn bytes_sent(&self) -> u64 {
            0
        }
    }

    /// `agree` on `size` thread ranks, rank r's result being `result(r)`:
    /// every rank's outcome.
    fn agree_on(size: usize, result: fn(usize) -> Result<usize>) -> Vec<Result<usize>> {
        let slots = Arc::new(Mutex::new(vec![Vec::new(); size]));
        let barrier = Arc::new(Barrier::new(size));
        std::thread::scope(|s| {
            let ranks: Vec<_> = (0..size)
                .map(|rank| {
                    let comm = Threads { rank, size, slots: slots.clone(), barrier: barrier.clone() };
                    s.spawn(move || agree(&comm, result(rank)))
                })
                .collect();
            ranks.into_iter().map(|h| h.join().expect("a rank")).collect()
        })
    }

    fn not_held(rank: usize) -> ModelError {
        ModelError::PartNotHeld { part: PartName { bodies: vec![format!("\"on rank {rank}\"")], piece: None } }
    }

    #[test]
    fn another_ranks_model_error_reaches_rank_0_as_the_same_variant() {
        let outcomes = agree_on(3, |r| if r == 0 { Ok(0) } else { Err(not_held(r).into()) });
        for (r, o) in outcomes.into_iter().enumerate() {
            match o {
                Err(Error::Model(m)) if matches!(&*m, ModelError::PartNotHeld { part } if part.to_string() == "body \"on rank 1\"") =>
                    {}
                o => panic!("rank {r}: rank 1's model error, not {o:?}"),
            }
        }
    }

    #[test]
    fn an_error_holding_an_os_error_arrives_as_its_message_and_rank() {
        fn read(_: usize) -> Result<usize> {
            let source = std::io::Error::from_raw_os_error(2);
            Err(crate::mesh::msh::MshError::Io { path: "m.msh".into(), source }.into())
        }
        let outcomes = agree_on(2, |r| if r == 1 { read(r) } else { Ok(r) });
        let text = read(1).expect_err("fails").to_string();
        match &outcomes[0] {
            Err(Error::Remote { rank: 1, message }) => assert_eq!(message, &text),
            o => panic!("rank 0: rank 1's message, not {o:?}"),
        }
        // rank 1 keeps its own error, whole
        assert!(matches!(&outcomes[1], Err(Error::Mesh(_))), "{:?}", outcomes[1]);
    }

    #[test]
    fn every_rank_ok_is_ok_and_the_first_failure_wins() {
        assert!(agree_on(2, Ok).into_iter().all(|o| o.is_ok()));
        let outcomes = agree_on(3, |r| if r == 0 { Ok(0) } else { Err(not_held(r).into()) });
        assert!(outcomes.iter().all(|o| matches!(o, Err(Error::Model(_)))));
    }
}
