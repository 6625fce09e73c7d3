//! `DistributedError`: what a distributed coupling answers when it cannot give its rows.

use mortar_core::MortarError;

/// Why a distributed coupling failed. Every rank of the communicator gets an error when any
/// rank fails: the failing rank its own cause, the others [`DistributedError::RankFailed`]
/// naming the lowest failing rank and its cause, so that no rank waits for a message that a
/// failed rank will never send.
#[derive(Debug, thiserror::Error)]
pub enum DistributedError {
    /// The coupling of this rank's part failed (bad input on this rank, an interface the core
    /// refuses).
    #[error("rank {rank}: {source}")]
    Coupling {
        /// This rank.
        rank: usize,
        /// The core's error.
        #[source]
        source: MortarError,
    },
    /// Another rank failed; every rank stops.
    #[error("rank {rank} failed: {cause}")]
    RankFailed {
        /// The lowest rank that failed.
        rank: usize,
        /// Its error, as it printed it.
        cause: String,
    },
    /// A face received from another rank names an element type this rank's registry does
    /// not hold: register user elements on every rank.
    #[error("rank {rank}: a face from rank {from} has the element type {name:?}, which this rank's registry does not hold (register user elements on every rank)")]
    UnknownElement {
        /// This rank.
        rank: usize,
        /// The rank that sent the face.
        from: usize,
        /// The element's name.
        name: String,
    },
    /// Two ranks gave the same node tag different coordinates.
    #[error("rank {rank}: node {tag} of the {side} has the coordinates {ours:?} here and {theirs:?} on rank {from}")]
    InconsistentNode {
        /// This rank.
        rank: usize,
        /// The other rank.
        from: usize,
        /// Which surface.
        side: &'static str,
        /// The node tag.
        tag: u64,
        /// The coordinates on this rank.
        ours: [f64; 3],
        /// The coordinates on the other rank.
        theirs: [f64; 3],
    },
    /// A message between ranks could not be read (truncated or from another program).
    #[error("rank {rank}: a message from rank {from} is malformed: {what}")]
    Malformed {
        /// This rank.
        rank: usize,
        /// The sender.
        from: usize,
        /// What was wrong.
        what: &'static str,
    },
    /// The program was started by `mpirun` on several ranks, but built without MPI.
    #[error("started on {ranks} MPI ranks, but built without MPI: build with `--features mortar-mpi/mpi` (Open MPI: apt-get install libopenmpi-dev openmpi-bin libclang-dev)")]
    NotBuilt {
        /// The ranks `mpirun` started.
        ranks: usize,
    },
    /// MPI was already started, by this program or a library, when the toolkit tried to.
    #[error(
        "MPI was already started: start it once, with `World::start`, before anything else uses it"
    )]
    AlreadyStarted,
    /// No slave face of any rank overlaps a master face.
    #[error("no slave face of any of the {ranks} ranks overlaps a master face ({slave_faces} slave faces, {master_faces} master faces in all)")]
    NoOverlap {
        /// The ranks.
        ranks: usize,
        /// Slave faces over all ranks.
        slave_faces: usize,
        /// Master faces over all ranks.
        master_faces: usize,
    },
}

/// The result of a distributed operation.
pub type Result<T> = std::result::Result<T, DistributedError>;
