//! Tolerances, relative to element size, gathered in one place, and the range of coordinates
//! within which they make results independent of the scale.

/// The largest coordinate magnitude an interface may have: products of two coordinates
/// (areas, the entries of D and M, a face's scaled normal) then stay below 1e300, within
/// double precision with room for sums and quadrature weights. Beyond it,
/// [`Interface::new`](crate::Interface::new) refuses the meshes with
/// [`MortarError::CoordinateRange`](crate::MortarError::CoordinateRange). (Products of three,
/// such as the weighted gap `D x`, stay finite up to about 1e100.)
pub const MAX_COORDINATE: f64 = 1e150;

/// The smallest extent (largest side of the bounding box of both surfaces) an interface may
/// have: its faces, unless degenerate at least [`Tolerances::degenerate`] (1e-10) of it
/// across, then have areas above 1e-300, in double precision's normal range. Below it,
/// [`Interface::new`](crate::Interface::new) refuses the meshes with
/// [`MortarError::CoordinateRange`](crate::MortarError::CoordinateRange).
pub const MIN_EXTENT: f64 = 1e-140;

/// Tolerances used by the geometry, projection and validation code.
///
/// Every length tolerance is relative to the size of the face concerned (its diameter), every
/// area tolerance relative to its area, so results do not change under uniform scaling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// A face whose measure (length or area) is below `degenerate * diameter^k` is degenerate.
    pub degenerate: f64,
    /// Clip polygons whose area is below `clip_area * min(slave area, master area)` are
    /// discarded: they are zero-measure touching, e.g. along a shared edge. Small, so that
    /// genuine slivers (a node pushed 1e-3 h across an edge gives overlaps of 1e-13 of a face)
    /// are kept. 3D polygons of no more area than the coordinates' rounding alone could give
    /// two touching faces are discarded too, unless they are many times wider than that
    /// rounding: a small overlap far from the origin counts.
    pub clip_area: f64,
    /// Points closer than `merge * diameter` are merged when clipping.
    pub merge: f64,
    /// Newton convergence on reference coordinates.
    pub newton: f64,
    /// Newton iteration limit.
    pub newton_max_iterations: usize,
    /// How far outside its reference domain (in reference units) a projected point may fall
    /// and still count as on the face.
    pub reference_inside: f64,
    /// The search's boxes of a side whose nodes do not bound what the search must find
    /// (higher-order faces, which bulge out of their nodes' hull; slave faces of a projector
    /// that does not keep its directions within the nodal normals) are inflated by this
    /// fraction of the face diameter. Two-node lines, linear triangles and bilinear quads
    /// with the default projector need none: their boxes are exact but for a margin of
    /// rounding ([`Padding`](crate::search::Padding),
    /// [`CouplingStats::slave_box_inflation`](crate::CouplingStats::slave_box_inflation)).
    pub search_inflation: f64,
    /// How far from a slave face, along the slave's normal field and both ways, the search
    /// looks for master faces: across an open gap, or into a penetration. Beyond it a master
    /// face is not coupled, however it projects. By default
    /// ([`SearchRadius::DEFAULT`]) one face diameter, and as far as the nearest master surface
    /// for the slave faces that leaves uncovered, within a quarter of the interface's size.
    pub search_radius: SearchRadius,
    /// A slave face counts as uncovered when the master covers less than `1 - coverage` of
    /// its area, and as covered more than once when the master faces over it cover more
    /// than `1 + coverage` (see [`CouplingWarning`](crate::CouplingWarning)).
    pub coverage: f64,
}

/// The reach of the search along the slave's normal field (see
/// [`Tolerances::search_radius`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SearchRadius {
    /// This multiple of each slave face's diameter: follows the mesh, so a gap of the order of
    /// the element size is crossed whatever the units.
    FaceSize(f64),
    /// A fixed distance, in the units of the coordinates.
    Distance(f64),
    /// One face diameter, and, for each slave face that leaves uncovered, as far along the
    /// slave normals as the nearest master surface plus one face diameter, within `bound`
    /// times the interface's size (the diagonal of the slave surface's bounding box). An
    /// open gap is then crossed whatever its width relative to the faces (a pellet's 80 um
    /// gap with faces of 50 um as with faces of 0.4 mm), and only the nearest master layer
    /// is reached, not a surface behind it. [`SearchRadius::DEFAULT`] has `bound` 0.25.
    ///
    /// The coupling first searches one face diameter (as `FaceSize(1.0)`); only when that
    /// leaves slave area uncovered does it measure, for each slave face, the distance along
    /// its normal to the nearest master face within the bound, and couple again with each
    /// face's radius widened to it ([`CouplingStats::widened_search_faces`](crate::CouplingStats::widened_search_faces)).
    /// A covered interface costs nothing more.
    Nearest {
        /// The largest reach, as a fraction of the interface's size.
        bound: f64,
    },
}

impl SearchRadius {
    /// The default: [`SearchRadius::Nearest`] within a quarter of the interface's size.
    pub const DEFAULT: SearchRadius = SearchRadius::Nearest { bound: 0.25 };

    /// The radius for a face of diameter `diameter` (for [`SearchRadius::Nearest`], its
    /// first search: one diameter).
    pub fn for_face(&self, diameter: f64) -> f64 {
        match *self {
            SearchRadius::FaceSize(k) => k * diameter,
            SearchRadius::Distance(d) => d,
            SearchRadius::Nearest { .. } => diameter,
        }
    }

    /// Whether the value is finite and non-negative.
    pub fn is_valid(&self) -> bool {
        let v = match *self {
            SearchRadius::FaceSize(k) => k,
            SearchRadius::Distance(d) => d,
            SearchRadius::Nearest { bound } => bound,
        };
        v >= 0.0 && v.is_finite()
    }
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            degenerate: 1e-10,
            clip_area: 1e-14,
            merge: 1e-12,
            newton: 1e-13,
            newton_max_iterations: 30,
            reference_inside: 1e-9,
            search_inflation: 0.1,
            search_radius: SearchRadius::DEFAULT,
            coverage: 1e-9,
        }
    }
}
