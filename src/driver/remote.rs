//! The other MPI ranks as the iterative interface sees them: while rank 0
//! solves the interface by GMRES, every application of S sends each part's
//! interface displacements to the part's rank, which applies S through its
//! interior factor and sends `S d` back ([`Ranks`] on rank 0, [`serve`] on
//! the others). Nothing else travels during the contact iteration; rank 0
//! ends each interface stage with [`Ranks::done`].

use crate::contact::system::iterative::Remote;
use crate::parallel::{Comm, CommExt};
use crate::substructure::Condensed;

/// What rank 0 asks of the other ranks while it solves the iterative interface.
#[derive(serde::Serialize, serde::Deserialize)]
enum Service {
    /// Apply the S of these parts (number, columns) to their `k` columns.
    Apply { k: usize, work: Vec<(usize, Vec<f64>)> },
    /// The interface stage is over (for this load step).
    Done,
}

/// The other ranks' parts as rank 0's iterative interface sees them: each
/// application of S scatters every part's columns to its owner and gathers
/// `S d` back (8 nc bytes each way per part and column).
pub(super) struct Ranks<'c> {
    pub comm: &'c dyn Comm,
    /// The rank of each part.
    pub owner: Vec<usize>,
}

impl Ranks<'_> {
    /// Ends the other ranks' [`serve`].
    pub fn done(&self) {
        let per_rank: Vec<Service> = (0..self.comm.size()).map(|_| Service::Done).collect();
        let _: Service = self.comm.scatter(&per_rank);
    }
}

impl Remote for Ranks<'_> {
    fn send(&self, work: Vec<(usize, Vec<f64>)>, k: usize) {
        let mut per_rank: Vec<Service> = (0..self.comm.size()).map(|_| Service::Apply { k, work: Vec::new() }).collect();
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
pub(super) fn serve(comm: &dyn Comm, mine: &[(usize, Condensed)]) {
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
