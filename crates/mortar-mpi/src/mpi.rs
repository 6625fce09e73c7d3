//! `MpiExchange`: the collectives of [`Exchange`] on an MPI communicator, through rsmpi (the
//! one module of the toolkit that calls it).

use mpi::datatype::{Partition, PartitionMut};
use mpi::topology::{Communicator, SimpleCommunicator};
use mpi::traits::*;
use mpi::Count;

use crate::exchange::Exchange;

/// MPI, started for the program: hold it while the program uses MPI (it stops MPI when
/// dropped). Start it once, before anything else that uses MPI (PETSc finds it started).
pub struct Mpi {
    universe: mpi::environment::Universe,
}

impl std::fmt::Debug for Mpi {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Mpi").finish_non_exhaustive()
    }
}

impl Mpi {
    /// Starts MPI; `None` if it is already started (by this program or a library).
    pub fn initialize() -> Option<Self> {
        mpi::initialize().map(|universe| Self { universe })
    }

    /// The world communicator's exchange.
    pub fn world(&self) -> MpiExchange {
        MpiExchange {
            comm: self.universe.world(),
        }
    }

    /// Stops every rank at once with `code` (`MPI_Abort`): for a failure the ranks cannot
    /// agree on, such as a panic.
    pub fn abort(&self, code: i32) -> ! {
        self.universe.world().abort(code)
    }
}

/// The [`Exchange`] of an MPI communicator.
pub struct MpiExchange {
    comm: SimpleCommunicator,
}

impl std::fmt::Debug for MpiExchange {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MpiExchange")
            .field("rank", &self.rank())
            .field("size", &self.size())
            .finish()
    }
}

/// Counts and displacements of the buffers `lens`, as MPI takes them.
fn layout(lens: &[usize]) -> (Vec<Count>, Vec<Count>) {
    let counts: Vec<Count> = lens
        .iter()
        .map(|&n| Count::try_from(n).expect("a message of at most 2 GiB"))
        .collect();
    let displs = counts
        .iter()
        .scan(0 as Count, |at, &n| {
            let here = *at;
            *at = at.checked_add(n).expect("messages of at most 2 GiB in all");
            Some(here)
        })
        .collect();
    (counts, displs)
}

/// The buffer split by `counts`, each part's leading byte (see [`framed`]) dropped.
fn split(all: &[u8], counts: &[Count]) -> Vec<Vec<u8>> {
    let mut at = 0usize;
    counts
        .iter()
        .map(|&n| {
            let part = all[at + 1..at + n as usize].to_vec();
            at += n as usize;
            part
        })
        .collect()
}

/// `bytes` after one leading byte. Every buffer handed to MPI holds at least that byte: the
/// address of an empty buffer is `1`, which Open MPI reads as `MPI_IN_PLACE`.
fn framed(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len() + 1);
    out.push(0);
    out.extend_from_slice(bytes);
    out
}

impl MpiExchange {
    /// Every rank's length, by rank.
    fn lengths(&self, len: usize) -> Vec<usize> {
        let mine = len as u64;
        let mut all = vec![0u64; self.size()];
        self.comm.all_gather_into(&mine, &mut all[..]);
        all.into_iter().map(|n| n as usize).collect()
    }
}

impl Exchange for MpiExchange {
    fn rank(&self) -> usize {
        self.comm.rank() as usize
    }

    fn size(&self) -> usize {
        self.comm.size() as usize
    }

    fn all_gather(&self, bytes: &[u8]) -> Vec<Vec<u8>> {
        let bytes = &framed(bytes)[..];
        let (counts, displs) = layout(&self.lengths(bytes.len()));
        let total = counts.iter().map(|&n| n as usize).sum();
        let mut all = vec![0u8; total];
        {
            let mut into = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
            self.comm.all_gather_varcount_into(bytes, &mut into);
        }
        split(&all, &counts)
    }

    fn all_to_all(&self, to: &[Vec<u8>]) -> Vec<Vec<u8>> {
        assert_eq!(to.len(), self.size(), "one buffer per rank");
        let to: Vec<Vec<u8>> = to.iter().map(|b| framed(b)).collect();
        let send_lens: Vec<usize> = to.iter().map(Vec::len).collect();
        let send_len = send_lens.iter().map(|&n| n as u64).collect::<Vec<_>>();
        let mut recv_len = vec![0u64; self.size()];
        self.comm.all_to_all_into(&send_len[..], &mut recv_len[..]);
        let recv_lens: Vec<usize> = recv_len.iter().map(|&n| n as usize).collect();
        let (send_counts, send_displs) = layout(&send_lens);
        let (recv_counts, recv_displs) = layout(&recv_lens);
        let flat: Vec<u8> = to.concat();
        let mut all = vec![0u8; recv_lens.iter().sum()];
        {
            let from = Partition::new(&flat[..], &send_counts[..], &send_displs[..]);
            let mut into = PartitionMut::new(&mut all[..], &recv_counts[..], &recv_displs[..]);
            self.comm.all_to_all_varcount_into(&from, &mut into);
        }
        split(&all, &recv_counts)
    }

    fn gather(&self, bytes: &[u8], root: usize) -> Option<Vec<Vec<u8>>> {
        let bytes = &framed(bytes)[..];
        let lens = self.lengths(bytes.len());
        let root_process = self.comm.process_at_rank(root as i32);
        if self.rank() != root {
            root_process.gather_varcount_into(bytes);
            return None;
        }
        let (counts, displs) = layout(&lens);
        let mut all = vec![0u8; lens.iter().sum()];
        {
            let mut into = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
            root_process.gather_varcount_into_root(bytes, &mut into);
        }
        Some(split(&all, &counts))
    }
}
