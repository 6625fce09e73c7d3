//! `Exchange`: the collective operations the distributed coupling needs of a communicator,
//! `SelfExchange` (one rank, no MPI) and `agree` (every rank learns whether any failed).

use crate::error::{DistributedError, Result};

/// The collectives the distributed coupling is written on: each is called by every rank of
/// the communicator, in the same order. `MpiExchange` (feature `mpi`) runs them on MPI;
/// [`SelfExchange`] is the communicator of one rank.
pub trait Exchange {
    /// This rank, `0..size()`.
    fn rank(&self) -> usize;
    /// The number of ranks.
    fn size(&self) -> usize;
    /// Every rank's `bytes`, by rank, on every rank.
    fn all_gather(&self, bytes: &[u8]) -> Vec<Vec<u8>>;
    /// Sends `to[q]` to rank `q` (`to.len() == size()`) and returns what each rank sent here,
    /// by rank.
    fn all_to_all(&self, to: &[Vec<u8>]) -> Vec<Vec<u8>>;
    /// Every rank's `bytes`, by rank, on `root`; `None` on the other ranks.
    fn gather(&self, bytes: &[u8], root: usize) -> Option<Vec<Vec<u8>>>;
}

/// The communicator of one rank: every collective returns this rank's own data.
#[derive(Debug, Clone, Copy, Default)]
pub struct SelfExchange;

impl Exchange for SelfExchange {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn all_gather(&self, bytes: &[u8]) -> Vec<Vec<u8>> {
        vec![bytes.to_vec()]
    }
    fn all_to_all(&self, to: &[Vec<u8>]) -> Vec<Vec<u8>> {
        to.to_vec()
    }
    fn gather(&self, bytes: &[u8], _root: usize) -> Option<Vec<Vec<u8>>> {
        Some(vec![bytes.to_vec()])
    }
}

/// Every rank's outcome, agreed: `Ok` on every rank when every rank's `local` is `Ok`; else
/// on the failing ranks their own error and on the others [`DistributedError::RankFailed`]
/// with the lowest failing rank and its message. Collective: every rank calls it at the same
/// point, so that a rank that failed never leaves the others waiting in a later collective.
pub fn agree<T>(exchange: &(impl Exchange + ?Sized), local: Result<T>) -> Result<T> {
    let status = match &local {
        Ok(_) => Vec::new(),
        Err(e) => {
            let mut text = e.to_string().into_bytes();
            text.insert(0, 1);
            text
        }
    };
    let all = exchange.all_gather(&status);
    let first = all.iter().position(|s| !s.is_empty());
    match (local, first) {
        (Ok(v), None) => Ok(v),
        (Err(e), _) => Err(e),
        (Ok(_), Some(rank)) => Err(DistributedError::RankFailed {
            rank,
            cause: String::from_utf8_lossy(&all[rank][1..]).into_owned(),
        }),
    }
}
