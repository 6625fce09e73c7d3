//! `World`: the MPI world of a program that `mpirun` started on several ranks, whatever the
//! build: started when the program was built with MPI, an error naming the fix when not.

use crate::error::{DistributedError, Result};
use crate::exchange::Exchange;

/// Whether this build links MPI (the `mpi` feature).
pub const BUILT_WITH_MPI: bool = cfg!(feature = "mpi");

/// The rank count that `mpirun` (Open MPI's or a PMI launcher's) gave this process, if it
/// started it.
pub fn launched_ranks() -> Option<usize> {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"]
        .iter()
        .find_map(|v| std::env::var(v).ok()?.trim().parse().ok())
}

/// The MPI world of a program started by `mpirun` on more than one rank: an [`Exchange`]
/// over every rank. Hold it while the program uses MPI; MPI stops when it is dropped.
pub struct World {
    #[cfg(feature = "mpi")]
    exchange: crate::mpi::MpiExchange,
    #[cfg(feature = "mpi")]
    _mpi: crate::mpi::Mpi,
    #[cfg(not(feature = "mpi"))]
    never: std::convert::Infallible,
}

impl std::fmt::Debug for World {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("World")
            .field("rank", &self.rank())
            .field("size", &self.size())
            .finish()
    }
}

impl World {
    /// Starts MPI when `mpirun` started this process on more than one rank; `None` when it
    /// did not, or on one rank (the program then runs as one process).
    ///
    /// # Errors
    /// [`DistributedError::NotBuilt`] when `mpirun` started several ranks of a build without
    /// MPI; [`DistributedError::AlreadyStarted`] when MPI was started already.
    pub fn start() -> Result<Option<World>> {
        let Some(ranks) = launched_ranks().filter(|&n| n > 1) else {
            return Ok(None);
        };
        #[cfg(feature = "mpi")]
        {
            let _ = ranks;
            let mpi = crate::mpi::Mpi::initialize().ok_or(DistributedError::AlreadyStarted)?;
            let exchange = mpi.world();
            Ok(Some(World {
                exchange,
                _mpi: mpi,
            }))
        }
        #[cfg(not(feature = "mpi"))]
        Err(DistributedError::NotBuilt { ranks })
    }
}

#[cfg(feature = "mpi")]
impl Exchange for World {
    fn rank(&self) -> usize {
        self.exchange.rank()
    }
    fn size(&self) -> usize {
        self.exchange.size()
    }
    fn all_gather(&self, bytes: &[u8]) -> Vec<Vec<u8>> {
        self.exchange.all_gather(bytes)
    }
    fn all_to_all(&self, to: &[Vec<u8>]) -> Vec<Vec<u8>> {
        self.exchange.all_to_all(to)
    }
    fn gather(&self, bytes: &[u8], root: usize) -> Option<Vec<Vec<u8>>> {
        self.exchange.gather(bytes, root)
    }
}

#[cfg(not(feature = "mpi"))]
impl Exchange for World {
    fn rank(&self) -> usize {
        match self.never {}
    }
    fn size(&self) -> usize {
        match self.never {}
    }
    fn all_gather(&self, _: &[u8]) -> Vec<Vec<u8>> {
        match self.never {}
    }
    fn all_to_all(&self, _: &[Vec<u8>]) -> Vec<Vec<u8>> {
        match self.never {}
    }
    fn gather(&self, _: &[u8], _: usize) -> Option<Vec<Vec<u8>>> {
        match self.never {}
    }
}
