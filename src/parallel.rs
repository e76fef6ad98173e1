//! Where a run's processes meet: one process ([`Serial`]), or the ranks of
//! an MPI job (`Mpi`, cargo feature `mpi`, over the system's OpenMPI by
//! the `mpi` crate).
//!
//! The substructure method needs few and coarse messages: each rank
//! condenses its own parts and sends rank 0 their condensed operators and
//! loads; rank 0 runs the contact iteration on the interface; rank 0 sends
//! each part's interface displacements back to its owner, which recovers
//! the part's interior; finally rank 0 gathers the fields it writes. So the
//! interface here is byte buffers (serialised with bincode) moved by
//! gather, scatter and broadcast, with a count of the bytes each rank sent.

use serde::de::DeserializeOwned;
use serde::Serialize;

/// The collective operations a run uses. Every rank calls every operation
/// in the same order.
pub trait Comm {
    fn rank(&self) -> usize;
    fn size(&self) -> usize;
    /// Every rank's buffer, on rank 0 (empty elsewhere).
    fn gather_bytes(&self, bytes: Vec<u8>) -> Vec<Vec<u8>>;
    /// Rank 0 gives one buffer per rank; each rank gets its own.
    fn scatter_bytes(&self, per_rank: Vec<Vec<u8>>) -> Vec<u8>;
    /// Rank 0's buffer, on every rank.
    fn broadcast_bytes(&self, bytes: Vec<u8>) -> Vec<u8>;
    /// Bytes this rank has sent so far.
    fn bytes_sent(&self) -> u64;
}

/// Typed wrappers over the byte operations.
pub trait CommExt: Comm {
    fn gather<T: Serialize + DeserializeOwned>(&self, value: &T) -> Vec<T> {
        self.gather_bytes(encode(value)).iter().map(|b| decode(b)).collect()
    }
    fn scatter<T: Serialize + DeserializeOwned>(&self, per_rank: &[T]) -> T {
        decode(&self.scatter_bytes(per_rank.iter().map(encode).collect()))
    }
    fn broadcast<T: Serialize + DeserializeOwned>(&self, value: &T) -> T {
        decode(&self.broadcast_bytes(if self.rank() == 0 { encode(value) } else { Vec::new() }))
    }
    fn is_root(&self) -> bool {
        self.rank() == 0
    }
}

impl<C: Comm + ?Sized> CommExt for C {}

fn encode<T: Serialize>(value: &T) -> Vec<u8> {
    bincode::serialize(value).expect("serialising a message")
}

fn decode<T: DeserializeOwned>(bytes: &[u8]) -> T {
    bincode::deserialize(bytes).expect("a message from another rank of the same build")
}

/// One process: every operation is the identity.
#[derive(Default)]
pub struct Serial;

impl Comm for Serial {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn gather_bytes(&self, bytes: Vec<u8>) -> Vec<Vec<u8>> {
        vec![bytes]
    }
    fn scatter_bytes(&self, per_rank: Vec<Vec<u8>>) -> Vec<u8> {
        per_rank.into_iter().next().unwrap_or_default()
    }
    fn broadcast_bytes(&self, bytes: Vec<u8>) -> Vec<u8> {
        bytes
    }
    fn bytes_sent(&self) -> u64 {
        0
    }
}

/// The ranks of an MPI job (`mpirun -np N subcontact solve ...`).
#[cfg(feature = "mpi")]
pub struct Mpi {
    _universe: mpi::environment::Universe,
    world: mpi::topology::SimpleCommunicator,
    sent: std::cell::Cell<u64>,
}

#[cfg(feature = "mpi")]
impl Mpi {
    /// Initialises MPI; None when it was initialised already.
    pub fn init() -> Option<Mpi> {
        let universe = mpi::initialize()?;
        let world = universe.world();
        Some(Mpi { _universe: universe, world, sent: std::cell::Cell::new(0) })
    }

    fn count(&self, n: usize) {
        self.sent.set(self.sent.get() + n as u64);
    }
}

#[cfg(feature = "mpi")]
impl Comm for Mpi {
    fn rank(&self) -> usize {
        use mpi::traits::Communicator;
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        use mpi::traits::Communicator;
        self.world.size() as usize
    }

    fn gather_bytes(&self, bytes: Vec<u8>) -> Vec<Vec<u8>> {
        use mpi::datatype::PartitionMut;
        use mpi::traits::{Communicator, Root};
        let root = self.world.process_at_rank(0);
        let n = bytes.len() as u64;
        if self.rank() != 0 {
            self.count(8 + bytes.len());
        }
        if self.rank() == 0 {
            let mut counts = vec![0u64; self.size()];
            root.gather_into_root(&n, &mut counts[..]);
            let counts_i: Vec<i32> = counts.iter().map(|&c| c as i32).collect();
            let displs: Vec<i32> = counts_i
                .iter()
                .scan(0, |acc, &c| {
                    let d = *acc;
                    *acc += c;
                    Some(d)
                })
                .collect();
            let mut buf = vec![0u8; counts.iter().sum::<u64>() as usize];
            {
                let mut part = PartitionMut::new(&mut buf[..], counts_i.clone(), &displs[..]);
                root.gather_varcount_into_root(&bytes[..], &mut part);
            }
            displs.iter().zip(&counts_i).map(|(&d, &c)| buf[d as usize..(d + c) as usize].to_vec()).collect()
        } else {
            root.gather_into(&n);
            root.gather_varcount_into(&bytes[..]);
            Vec::new()
        }
    }

    fn scatter_bytes(&self, per_rank: Vec<Vec<u8>>) -> Vec<u8> {
        use mpi::datatype::Partition;
        use mpi::traits::{Communicator, Root};
        let root = self.world.process_at_rank(0);
        let mut n = 0u64;
        if self.rank() == 0 {
            let counts: Vec<u64> = per_rank.iter().map(|b| b.len() as u64).collect();
            self.count(counts.iter().skip(1).sum::<u64>() as usize + 8 * (self.size() - 1));
            root.scatter_into_root(&counts[..], &mut n);
            let counts_i: Vec<i32> = counts.iter().map(|&c| c as i32).collect();
            let displs: Vec<i32> = counts_i
                .iter()
                .scan(0, |acc, &c| {
                    let d = *acc;
                    *acc += c;
                    Some(d)
                })
                .collect();
            let flat: Vec<u8> = per_rank.concat();
            let mut mine = vec![0u8; n as usize];
            let part = Partition::new(&flat[..], counts_i, &displs[..]);
            root.scatter_varcount_into_root(&part, &mut mine[..]);
            mine
        } else {
            root.scatter_into(&mut n);
            let mut mine = vec![0u8; n as usize];
            root.scatter_varcount_into(&mut mine[..]);
            mine
        }
    }

    fn broadcast_bytes(&self, bytes: Vec<u8>) -> Vec<u8> {
        use mpi::traits::{Communicator, Root};
        let root = self.world.process_at_rank(0);
        let mut n = bytes.len() as u64;
        if self.rank() == 0 {
            self.count((8 + bytes.len()) * (self.size() - 1));
        }
        root.broadcast_into(&mut n);
        let mut buf = if self.rank() == 0 { bytes } else { vec![0u8; n as usize] };
        root.broadcast_into(&mut buf[..]);
        buf
    }

    fn bytes_sent(&self) -> u64 {
        self.sent.get()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serial_operations_are_the_identity() {
        let c = Serial;
        assert_eq!(c.gather(&vec![1.5f64, 2.0]), vec![vec![1.5, 2.0]]);
        assert_eq!(c.scatter(&[String::from("part 0")]), "part 0");
        assert_eq!(c.broadcast(&(3usize, -1i64)), (3, -1));
        assert_eq!(c.bytes_sent(), 0);
        assert!(c.is_root());
    }
}
