//! The auxiliary plane: an orthonormal right-handed frame; projection and lifting invert each
//! other in the plane and ignore the normal component.

use mortar_core::geometry::AuxiliaryPlane;
use nalgebra::Vector3;
use proptest::prelude::*;

fn vector() -> impl Strategy<Value = Vector3<f64>> {
    prop::array::uniform3(-10.0..10.0f64).prop_map(Vector3::from)
}

proptest! {
    #![proptest_config(crate::unit::config(128))]

    #[test]
    fn plane_frame_is_orthonormal_and_right_handed(
        origin in vector(),
        normal in vector().prop_filter("non-zero", |n| n.norm() > 1e-3),
        use_hint in any::<bool>(),
        hint in vector(),
    ) {
        let plane = if use_hint {
            AuxiliaryPlane::new(origin, normal, hint)
        } else {
            AuxiliaryPlane::from_normal(origin, normal)
        };
        // A hint parallel to the normal is the only way to fail with a non-zero normal.
        let sine = hint.cross(&normal).norm() / (hint.norm() * normal.norm());
        let Some(plane) = plane else {
            prop_assert!(use_hint && sine <= 1e-12);
            return Ok(());
        };
        // One Gram-Schmidt step leaves t1 orthogonal to the normal to about eps / sin(angle)
        // between hint and normal; the segmenter's hints are in-plane edges (sine near 1).
        prop_assume!(!use_hint || sine > 0.01);
        let n = normal.normalize();
        prop_assert!((plane.normal - n).norm() < 1e-13);
        for (a, b, want) in [
            (plane.t1, plane.t1, 1.0), (plane.t2, plane.t2, 1.0),
            (plane.t1, plane.t2, 0.0), (plane.t1, plane.normal, 0.0), (plane.t2, plane.normal, 0.0),
        ] {
            prop_assert!((a.dot(&b) - want).abs() < 1e-13);
        }
        prop_assert!((plane.t1.cross(&plane.t2) - plane.normal).norm() < 1e-13);
        if use_hint {
            // t1 is the in-plane direction of the hint.
            prop_assert!(plane.t1.dot(&hint) >= 0.0);
        }
    }

    #[test]
    fn project_and_lift_invert_each_other(
        origin in vector(),
        normal in vector().prop_filter("non-zero", |n| n.norm() > 1e-3),
        x in vector(),
        lift in -5.0..5.0f64,
    ) {
        let plane = AuxiliaryPlane::from_normal(origin, normal).unwrap();
        let p = plane.project(&x);
        let back = plane.lift(&p);
        // The lifted point differs from x by a multiple of the normal.
        prop_assert!((x - back).cross(&plane.normal).norm() <= 1e-12 * (1.0 + x.norm() + origin.norm()));
        prop_assert!((plane.project(&back) - p).norm() <= 1e-12 * (1.0 + p.norm()));
        let shifted = x + plane.normal * lift;
        prop_assert!((plane.project(&shifted) - p).norm() <= 1e-12 * (1.0 + x.norm() + origin.norm()));
        prop_assert!(plane.project(&origin).norm() == 0.0);
    }
}

#[test]
fn zero_normal_or_parallel_hint_gives_no_plane() {
    let o = Vector3::zeros();
    assert!(AuxiliaryPlane::new(o, Vector3::zeros(), Vector3::x()).is_none());
    assert!(AuxiliaryPlane::from_normal(o, Vector3::zeros()).is_none());
    assert!(AuxiliaryPlane::new(o, Vector3::z(), Vector3::z() * 3.0).is_none());
    for axis in [Vector3::x(), Vector3::y(), Vector3::z(), -Vector3::z()] {
        assert!(AuxiliaryPlane::from_normal(o, axis).is_some());
    }
}
