//! D and M are the same bit for bit whatever the thread count. Work is split into chunks of
//! 256 slave faces, so the slave meshes here have more than 256 faces (several chunks).

use mortar::core::linalg::SparseMatrix;
use mortar::testing::{covered_pair_3d_with, CellKind, MeshPair, PairConfig};
use mortar::{Coupling, CouplingOptions};
use proptest::prelude::*;

use super::common::{config, couple};

fn bits(a: &SparseMatrix) -> (Vec<u64>, Vec<usize>, Vec<usize>) {
    (
        a.data().iter().map(|v| v.to_bits()).collect(),
        a.indices().to_vec(),
        a.indptr().raw_storage().to_vec(),
    )
}

/// `coupled` succeeded on `threads` threads (`how`: where they came from) and gave the serial
/// run's D and M bit for bit.
fn same_bits_on(
    serial: &Coupling,
    coupled: Result<Coupling, mortar::MortarError>,
    threads: usize,
    how: &str,
) -> Result<(), TestCaseError> {
    let c = coupled.map_err(|e| TestCaseError::fail(format!("unexpected error: {e}")))?;
    prop_assert_eq!(c.stats.threads, threads);
    prop_assert!(
        bits(&serial.d) == bits(&c.d),
        "D differs ({} threads, {})",
        threads,
        how
    );
    prop_assert!(
        bits(&serial.m) == bits(&c.m),
        "M differs ({} threads, {})",
        threads,
        how
    );
    Ok(())
}

/// Large covered pairs: 17 to 22 slave cells per side gives at least 289 slave faces.
fn large_pair() -> impl Strategy<Value = MeshPair> {
    covered_pair_3d_with(PairConfig {
        slave_cells: 17..=22,
        master_cells: 8..=20,
        master_kinds: vec![CellKind::Triangles, CellKind::Mixed, CellKind::Quads],
        ..PairConfig::default()
    })
}

proptest! {
    #![proptest_config(config(16))]

    #[test]
    fn one_and_several_threads_give_identical_bits(
        pair in large_pair(),
        which in 0..3usize,
        threads in 2..=4usize,
    ) {
        prop_assert!(pair.slave.face_count() > 256);
        let base = match which {
            0 => CouplingOptions::default(),
            1 => CouplingOptions::default().dual(),
            _ => CouplingOptions::default().element_based(Some(6)).unwrap(),
        };
        let (_, serial) = couple(&pair, &base.clone().threads(1))?;
        let (_, parallel) = couple(&pair, &base.threads(threads))?;
        prop_assert_eq!(serial.stats.threads, 1);
        prop_assert_eq!(parallel.stats.threads, threads);
        prop_assert!(bits(&serial.d) == bits(&parallel.d), "D differs with {} threads", threads);
        prop_assert!(bits(&serial.m) == bits(&parallel.m), "M differs with {} threads", threads);
        prop_assert_eq!(serial.slave_nodes, parallel.slave_nodes);
        prop_assert_eq!(serial.master_nodes, parallel.master_nodes);
    }
}

proptest! {
    #![proptest_config(config(4))]

    /// Couplings asked for at the same time from several threads with the same thread count
    /// share one kept pool (`assembly/pool.rs`); each gets the serial run's D and M, bit for
    /// bit, and the thread count it asked for.
    #[test]
    fn calls_at_the_same_time_share_a_pool_and_give_identical_bits(pair in large_pair()) {
        let options = CouplingOptions::default();
        let (interface, serial) = couple(&pair, &options.clone().threads(1))?;
        let results: Vec<_> = std::thread::scope(|s| {
            let calls: Vec<_> = [2, 2, 2, 3]
                .into_iter()
                .map(|t| {
                    let (interface, options) = (&interface, options.clone().threads(t));
                    s.spawn(move || (t, mortar::assemble_coupling(interface, &options)))
                })
                .collect();
            calls.into_iter().map(|c| c.join().expect("no panic")).collect()
        });
        for (t, c) in results {
            same_bits_on(&serial, c, t, "shared")?;
        }
    }
}

proptest! {
    #![proptest_config(config(4))]

    /// With no thread count asked for, a coupling called inside an application's rayon pool
    /// runs on that pool (its thread count is the pool's), also from several of the pool's
    /// threads at once, and gives the serial run's D and M bit for bit. Before, it started a
    /// pool of its own of the core count, whatever the caller's pool.
    #[test]
    fn no_thread_count_runs_on_the_callers_pool(pair in large_pair()) {
        let options = CouplingOptions::default();
        let (interface, serial) = couple(&pair, &options.clone().threads(1))?;
        // One thread and three: at least one differs from the core count of any machine.
        for size in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(size).build().expect("a pool");
            let results: Vec<_> = pool.install(|| {
                use rayon::prelude::*;
                (0..3)
                    .into_par_iter()
                    .map(|_| mortar::assemble_coupling(&interface, &options))
                    .collect()
            });
            for c in results {
                same_bits_on(&serial, c, size, "the caller's pool")?;
            }
        }
    }
}
