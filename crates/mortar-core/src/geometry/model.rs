//! What a mesh describes: a body of its own coordinates, or the meridian section of a body of
//! revolution.

use std::f64::consts::PI;

use nalgebra::Vector3;

/// Radii within this fraction of a mesh's extent (its largest absolute x or y coordinate) of
/// zero are on the axis of an axisymmetric model: such a node is an axis node, and a radius
/// that small below zero counts as zero rather than negative.
pub const AXIS_TOLERANCE: f64 = 1e-12;

/// The geometry a 2D or 3D mesh models, and so the measure its integrals are taken with.
///
/// - [`Cartesian`](Self::Cartesian) (the default): the body is the mesh itself. A 3D mesh is
///   the body; a 2D mesh in the plane `z = 0` is a slice of unit thickness (integrals per unit
///   length: heat flows in W/m, forces in N/m, elasticity in plane strain). The measure is
///   `dx`.
/// - [`Axisymmetric`](Self::Axisymmetric): a 2D mesh in the plane `z = 0` is the meridian
///   section of a body of revolution about the y axis: the x coordinate is the radius
///   `r >= 0`, the y coordinate the axial coordinate `z`, and the angle `theta` runs round
///   the y axis. Integrals are over the full revolution: `dV = 2 pi r dr dz` on cells,
///   `dA = 2 pi r ds` on boundary lines and interfaces (heat flows in W, sources in W/m^3,
///   fluxes and tractions per unit area of the revolved surface). 3D meshes are refused.
///
/// Gauss points lie inside their cells and lines, never on the axis, so `1 / r` (the hoop
/// strain `u_r / r`) stays finite; a node on the axis (`r = 0`) carries no weight of its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum ModelGeometry {
    /// The mesh's own coordinates (a 2D mesh per unit thickness).
    #[default]
    Cartesian,
    /// A 2D mesh as the meridian (r-z) section of a body of revolution, `x = r`, `y = z`:
    /// the measure `2 pi r`.
    Axisymmetric,
}

impl ModelGeometry {
    /// Whether this is the axisymmetric (r-z) geometry.
    pub fn is_axisymmetric(self) -> bool {
        self == Self::Axisymmetric
    }

    /// The factor of the measure at the point `x`: 1 (Cartesian) or `2 pi r` with `r = x.x`
    /// (axisymmetric; a radius below zero counts as zero).
    #[inline]
    pub fn weight(self, x: &Vector3<f64>) -> f64 {
        match self {
            Self::Cartesian => 1.0,
            Self::Axisymmetric => 2.0 * PI * x.x.max(0.0),
        }
    }

    /// A lower-case name: `"cartesian"` or `"axisymmetric"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Cartesian => "cartesian",
            Self::Axisymmetric => "axisymmetric",
        }
    }

    /// The radius below which a node of the points `coords` is on the axis:
    /// [`AXIS_TOLERANCE`] times their largest absolute x or y coordinate.
    pub fn axis_tolerance(coords: &[Vector3<f64>]) -> f64 {
        AXIS_TOLERANCE
            * coords
                .iter()
                .fold(0.0f64, |m, x| m.max(x.x.abs()).max(x.y.abs()))
    }

    /// The first of `coords` at a negative radius (x below minus the
    /// [`axis_tolerance`](Self::axis_tolerance)) and its radius; always `None` for the
    /// Cartesian geometry.
    pub fn first_negative_radius(self, coords: &[Vector3<f64>]) -> Option<(usize, f64)> {
        if !self.is_axisymmetric() {
            return None;
        }
        let tol = Self::axis_tolerance(coords);
        coords
            .iter()
            .position(|x| x.x < -tol)
            .map(|i| (i, coords[i].x))
    }
}

impl std::fmt::Display for ModelGeometry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
