//! The linear patch test: a linear field `f = a + b . x` is reproduced on flat, covered
//! interfaces, `D f_s = M f_m` to round-off, in any position of the plane.

use mortar::testing::{
    covered_pair_2d, covered_pair_3d, rotation_2d, translation, unit_quaternion, MeshPair,
    RigidMotion,
};
use mortar::CouplingOptions;
use nalgebra::Vector3;
use proptest::prelude::*;

use super::common::{config, couple, mat_vec, max_abs, nodal_values, norm_inf, segment_options};

/// `|D f_s - M f_m|_inf <= 1e-12 |D|_inf |f|_inf` for `f = a + b . (x - c)`, where `c` is the
/// image of the square's centre (so `|f|` measures the field across the interface, not its
/// offset far from the origin).
fn check_linear_field(
    pair: &MeshPair,
    motion: &RigidMotion,
    options: &CouplingOptions,
    a: f64,
    b: Vector3<f64>,
) -> Result<(), TestCaseError> {
    let moved = pair.transformed(|x| motion.apply(x)).unwrap();
    let (interface, coupling) = couple(&moved, options)?;
    let c = motion.apply(Vector3::new(0.5, 0.5, 0.0));
    let (fs, fm) = nodal_values(&coupling, &interface, |x| a + b.dot(&(x - c)));
    let df = mat_vec(&coupling.d, &fs);
    let mf = mat_vec(&coupling.m, &fm);
    let residual = df
        .iter()
        .zip(&mf)
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, f64::max);
    let scale = norm_inf(&coupling.d) * max_abs(&fs).max(max_abs(&fm));
    prop_assert!(
        residual <= crate::claims::claim("coupling.patch").bound * scale,
        "{}: |D f_s - M f_m| = {residual:e}, scale {scale:e} (relative {:e})",
        coupling.formulation,
        residual / scale
    );
    Ok(())
}

/// A rigid motion with a translation of at most 10: far translations cost accuracy in the
/// node coordinates themselves (see the invariance tests), not in the patch test.
fn motion(planar: bool) -> impl Strategy<Value = RigidMotion> {
    let rotation = if planar {
        rotation_2d().boxed()
    } else {
        unit_quaternion().boxed()
    };
    (rotation, translation(10.0, planar)).prop_map(|(rotation, translation)| RigidMotion {
        rotation,
        translation,
    })
}

fn field() -> impl Strategy<Value = (f64, Vector3<f64>)> {
    (-10.0..10.0f64, prop::array::uniform3(-10.0..10.0f64)).prop_map(|(a, b)| (a, Vector3::from(b)))
}

proptest! {
    #![proptest_config(config(64))]

    #[test]
    fn linear_field_is_reproduced_3d(
        pair in covered_pair_3d(),
        motion in motion(false),
        dual in any::<bool>(),
        (a, b) in field(),
    ) {
        check_linear_field(&pair, &motion, &segment_options(dual), a, b)?;
    }

    #[test]
    fn linear_field_is_reproduced_2d(
        pair in covered_pair_2d(),
        motion in motion(true),
        dual in any::<bool>(),
        (a, b) in field(),
    ) {
        let b = Vector3::new(b.x, b.y, 0.0);
        check_linear_field(&pair, &motion, &segment_options(dual), a, b)?;
    }

    #[test]
    fn linear_field_is_reproduced_element_based(
        pair in prop_oneof![covered_pair_2d(), covered_pair_3d()],
        dual in any::<bool>(),
        degree in 1..=8u32,
        (a, b) in field(),
    ) {
        let options = segment_options(dual).element_based(Some(degree)).unwrap();
        let b = if pair.slave.face(0).element.domain().dim() == 1 {
            Vector3::new(b.x, b.y, 0.0)
        } else {
            b
        };
        check_linear_field(&pair, &RigidMotion::identity(), &options, a, b)?;
    }
}
