//! `AuxiliaryPlane`: the plane through a slave face's centre with its orthonormal in-plane
//! basis, onto which the 3D segmenter projects both faces before clipping.

use nalgebra::{Vector2, Vector3};

/// A plane through `origin` with unit normal `normal` and an orthonormal in-plane basis
/// `(t1, t2)` with `t1 x t2 = normal`, so that counter-clockwise in-plane order matches the
/// right-hand rule about the normal.
///
/// Coordinates are taken relative to `origin`, which keeps round-off small for meshes far from
/// the global origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AuxiliaryPlane {
    /// A point of the plane (the slave face centre).
    pub origin: Vector3<f64>,
    /// The unit normal.
    pub normal: Vector3<f64>,
    /// First in-plane unit vector.
    pub t1: Vector3<f64>,
    /// Second in-plane unit vector, `normal x t1`.
    pub t2: Vector3<f64>,
}

impl AuxiliaryPlane {
    /// The plane through `origin` with normal `normal` (normalised here); `hint` is a vector
    /// not parallel to the normal that fixes `t1` (its in-plane part, normalised). Returns `None`
    /// if the normal is zero or `hint` is parallel to it.
    pub fn new(origin: Vector3<f64>, normal: Vector3<f64>, hint: Vector3<f64>) -> Option<Self> {
        let normal = normal.try_normalize(0.0)?;
        let t1 = (hint - normal * hint.dot(&normal)).try_normalize(0.0)?;
        let t2 = normal.cross(&t1);
        Some(Self {
            origin,
            normal,
            t1,
            t2,
        })
    }

    /// The plane through `origin` with normal `normal`, with a basis chosen from the normal's
    /// smallest component.
    pub fn from_normal(origin: Vector3<f64>, normal: Vector3<f64>) -> Option<Self> {
        let a = normal.abs();
        let hint = if a.x <= a.y && a.x <= a.z {
            Vector3::x()
        } else if a.y <= a.z {
            Vector3::y()
        } else {
            Vector3::z()
        };
        Self::new(origin, normal, hint)
    }

    /// In-plane coordinates of the orthogonal projection of `x`.
    #[inline]
    pub fn project(&self, x: &Vector3<f64>) -> Vector2<f64> {
        let d = x - self.origin;
        Vector2::new(d.dot(&self.t1), d.dot(&self.t2))
    }

    /// The 3D point with in-plane coordinates `p`.
    #[inline]
    pub fn lift(&self, p: &Vector2<f64>) -> Vector3<f64> {
        self.origin + self.t1 * p.x + self.t2 * p.y
    }
}
