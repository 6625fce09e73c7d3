//! [`Interface::slave_face_into`] (a slave face gathered into the buffer of the face before,
//! as the coupling does chunk after chunk) gives what [`Interface::slave_face`] gives, bit for
//! bit, whatever face was in the buffer before: Quad4 after Tri3 and back, so that the
//! entries past a face's nodes are zero as a fresh gather leaves them.
//!
//! Reference: [`Interface::slave_face`] (a fresh gather).

use mortar::testing::{covered_pair_3d_with, CellKind, PairConfig};
use proptest::prelude::*;

use super::common::config;

proptest! {
    #![proptest_config(config(32))]

    #[test]
    fn gathered_into_a_used_buffer_is_a_fresh_gather(
        pair in covered_pair_3d_with(PairConfig {
            slave_kinds: vec![CellKind::Mixed],
            ..PairConfig::default()
        }),
        picks in prop::collection::vec(any::<prop::sample::Index>(), 1..40),
    ) {
        let interface = pair.interface().unwrap();
        let faces = interface.slave().face_count();
        let mut buffer = interface.slave_face(0);
        for pick in picks {
            let f = pick.index(faces);
            interface.slave_face_into(f, &mut buffer);
            let fresh = interface.slave_face(f);
            prop_assert_eq!(format!("{buffer:?}"), format!("{fresh:?}"), "face {}", f);
        }
    }
}
