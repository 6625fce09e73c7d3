//! A coupling written into an earlier coupling's arrays (`assemble_coupling_reusing`) is the
//! fresh coupling bit for bit, whatever the earlier one was: of another interface, larger or
//! smaller, 2D or 3D, with another multiplier space or strategy.
//!
//! Reference: `assemble_coupling` on the same interface and options (the reuse changes where
//! the arrays live, not a value).

use mortar::generate::{half_circle_mesh, line_mesh};
use mortar::testing::covered_pair;
use mortar::{assemble_coupling, assemble_coupling_reusing, Coupling, CouplingOptions, Interface};
use proptest::prelude::*;

use super::common::{config, couple, ok};

/// The bits of everything a coupling returns that reuse could touch: D's and M's arrays,
/// the node lists, the normals and the area.
fn all_bits(c: &Coupling) -> Vec<u64> {
    let mut v = Vec::new();
    for a in [&c.d, &c.m] {
        v.push(a.rows() as u64);
        v.push(a.cols() as u64);
        v.extend(a.indptr().raw_storage().iter().map(|&i| i as u64));
        v.extend(a.indices().iter().map(|&i| i as u64));
        v.extend(a.data().iter().map(|x| x.to_bits()));
    }
    v.extend(&c.slave_nodes);
    v.extend(&c.master_nodes);
    v.extend(
        c.slave_normals
            .iter()
            .flat_map(|n| n.iter().map(|x| x.to_bits())),
    );
    v.push(c.stats.area.to_bits());
    v
}

/// The options of `which`: standard, dual (its D's round-off dropped into a new array), or
/// element-based.
fn options(which: usize) -> CouplingOptions {
    match which {
        0 => CouplingOptions::default(),
        1 => CouplingOptions::default().dual(),
        _ => CouplingOptions::default().element_based(Some(6)).unwrap(),
    }
}

/// `interface` coupled with `now` into the arrays of `previous` gives the fresh coupling's
/// bits.
fn same_as_fresh(
    interface: &Interface,
    now: &CouplingOptions,
    previous: Coupling,
) -> Result<(), TestCaseError> {
    let fresh = ok(assemble_coupling(interface, now))?;
    let reused = ok(assemble_coupling_reusing(interface, now, previous))?;
    prop_assert!(all_bits(&fresh) == all_bits(&reused), "differs when reused");
    prop_assert_eq!(fresh.stats.pairs, reused.stats.pairs);
    Ok(())
}

proptest! {
    #![proptest_config(config(24))]

    #[test]
    fn reusing_any_earlier_coupling_gives_the_fresh_bits(
        earlier in covered_pair(),
        pair in covered_pair(),
        was in 0..3usize,
        now in 0..3usize,
        threads in 1..=2usize,
    ) {
        let (_, previous) = couple(&earlier, &options(was))?;
        let interface = ok(pair.interface())?;
        same_as_fresh(&interface, &options(now).threads(threads), previous)?;
    }
}

/// The straight 2D path (the sorted merge, which writes D and M in place) and the general
/// 2D path (an arc), each reusing a larger and a smaller coupling of the other, then its own.
#[test]
fn both_2d_paths_reuse_larger_and_smaller_couplings() {
    let straight = |n: usize| {
        Interface::new(
            line_mesh(n, false, 1).unwrap(),
            line_mesh(n + 7, true, 100_000).unwrap(),
        )
        .unwrap()
    };
    let arc = |n: usize| {
        Interface::new(
            half_circle_mesh(n, false, 1).unwrap(),
            half_circle_mesh(n + 5, true, 100_000).unwrap(),
        )
        .unwrap()
    };
    for dual in [false, true] {
        let opts = if dual {
            CouplingOptions::default().dual()
        } else {
            CouplingOptions::default()
        };
        for (now, larger, smaller, straight_faces) in [
            (straight(600), arc(900), arc(200), 600),
            (arc(600), straight(900), straight(200), 0),
        ] {
            let fresh = assemble_coupling(&now, &opts).unwrap();
            // The straight interface is the merge's (which writes into the spare arrays),
            // the arc the general path's.
            assert_eq!(fresh.stats.straight_line_faces, straight_faces);
            let mut last = None;
            for earlier in [&larger, &smaller, &now] {
                let previous = assemble_coupling(earlier, &opts).unwrap();
                let reused = assemble_coupling_reusing(&now, &opts, previous).unwrap();
                assert!(all_bits(&fresh) == all_bits(&reused), "dual {dual}");
                last = Some(reused);
            }
            // And the coupling just made, reused again.
            let again = assemble_coupling_reusing(&now, &opts, last.unwrap()).unwrap();
            assert!(all_bits(&fresh) == all_bits(&again), "dual {dual}, again");
        }
    }
}
