//! Rigid motions and uniform scalings.

use std::f64::consts::TAU;

use mortar_core::error::Result;
use mortar_core::mesh::SurfaceMesh;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use proptest::prelude::*;

/// A rigid motion `x -> R x + t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidMotion {
    /// The rotation `R`.
    pub rotation: UnitQuaternion<f64>,
    /// The translation `t`.
    pub translation: Vector3<f64>,
}

impl RigidMotion {
    /// The identity.
    pub fn identity() -> Self {
        Self {
            rotation: UnitQuaternion::identity(),
            translation: Vector3::zeros(),
        }
    }

    /// The image `R x + t` of a point.
    pub fn apply(&self, x: Vector3<f64>) -> Vector3<f64> {
        self.rotation * x + self.translation
    }

    /// Moves every node of `mesh`.
    ///
    /// # Errors
    /// [`MortarError::NonFiniteCoordinate`](mortar_core::MortarError::NonFiniteCoordinate)
    /// if a moved coordinate overflows.
    pub fn apply_to(&self, mesh: &mut SurfaceMesh) -> Result<()> {
        mesh.transform(|x| self.apply(x))
    }
}

/// A value log-uniformly distributed in `[lo, hi]` (`0 < lo < hi`): its decimal exponent is
/// uniform. Shrinks towards `lo`.
///
/// # Panics
/// If not `0 < lo < hi`.
pub fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    assert!(0.0 < lo && lo < hi, "log_uniform needs 0 < lo < hi");
    (lo.log10()..=hi.log10()).prop_map(move |e| 10f64.powf(e).clamp(lo, hi))
}

/// A uniform scale factor, log-uniform in `[1e-6, 1e6]` (shrinks towards `1e-6`).
pub fn scale_factor() -> impl Strategy<Value = f64> {
    log_uniform(1e-6, 1e6)
}

prop_compose! {
    /// A uniformly distributed rotation of space, as a unit quaternion (Shoemake's method:
    /// three uniform numbers, no rejection).
    pub fn unit_quaternion()(u1 in 0.0..=1.0f64, u2 in 0.0..=1.0f64, u3 in 0.0..=1.0f64)
        -> UnitQuaternion<f64>
    {
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        let (s2, c2) = (TAU * u2).sin_cos();
        let (s3, c3) = (TAU * u3).sin_cos();
        UnitQuaternion::from_quaternion(Quaternion::new(b * c3, a * s2, a * c2, b * s3))
    }
}

prop_compose! {
    /// A rotation about the z-axis by an angle uniform in `[0, 2 pi)`: the rotations of a 2D
    /// problem, which keep the plane `z = 0` (exactly: the z-components stay zero).
    pub fn rotation_2d()(angle in 0.0..TAU) -> UnitQuaternion<f64> {
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle)
    }
}

prop_compose! {
    /// A translation of uniformly random direction whose length is 0, uniform in `[0, 1]`, or
    /// log-uniform in `[1e-3, max_length]`: small shifts and shifts far from the origin alike.
    /// With `planar`, the direction lies in the xy-plane (z exactly zero).
    pub fn translation(max_length: f64, planar: bool)(
        z in -1.0..=1.0f64,
        angle in 0.0..TAU,
        length in prop_oneof![
            Just(0.0),
            0.0..=1.0f64,
            log_uniform(1e-3, max_length.max(2e-3)),
        ],
    ) -> Vector3<f64> {
        let (s, c) = angle.sin_cos();
        let d = if planar {
            Vector3::new(c, s, 0.0)
        } else {
            let r = (1.0 - z * z).sqrt();
            Vector3::new(r * c, r * s, z)
        };
        d * length
    }
}

prop_compose! {
    /// A rigid motion of space: a uniform random rotation and a translation of length up to
    /// `1e6` (see [`translation`]).
    pub fn rigid_motion_3d()(
        rotation in unit_quaternion(),
        translation in translation(1e6, false),
    ) -> RigidMotion {
        RigidMotion { rotation, translation }
    }
}

prop_compose! {
    /// A rigid motion of the plane `z = 0`: a rotation about z and an in-plane translation of
    /// length up to `1e6`.
    pub fn rigid_motion_2d()(
        rotation in rotation_2d(),
        translation in translation(1e6, true),
    ) -> RigidMotion {
        RigidMotion { rotation, translation }
    }
}
