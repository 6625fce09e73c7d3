//! Typed errors of the core. Every error names what went wrong and where (side, face, node).

use std::fmt;

/// Which surface of an interface a face or node belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// The slave (non-mortar) surface: it carries the Lagrange multipliers.
    Slave,
    /// The master (mortar) surface.
    Master,
}

impl fmt::Display for Side {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Side::Slave => write!(f, "slave"),
            Side::Master => write!(f, "master"),
        }
    }
}

/// Where in a surface mesh a problem was found: the side (when known) and the face tag.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FaceLocation {
    /// The surface, when the face belongs to an interface.
    pub side: Option<Side>,
    /// The face's tag (the element tag of the input mesh, or its insertion index plus one).
    pub tag: u64,
}

impl fmt::Display for FaceLocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.side {
            Some(side) => write!(f, "{side} face {}", self.tag),
            None => write!(f, "face {}", self.tag),
        }
    }
}

/// How a face is inverted ([`MortarError::InvertedFace`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Inversion {
    /// The face's Jacobian changes sign or vanishes inside it: self-intersecting (a bow-tie
    /// quad) or non-convex. Its nodes must be moved or renumbered.
    SelfIntersecting,
    /// The face is numbered the other way round from the neighbours around it: reversing its
    /// node order ([`SurfaceMesh::reverse_face`](crate::SurfaceMesh::reverse_face)) mends it.
    AgainstNeighbours,
    /// The surface folds back onto itself at a node (the normals of the faces there cancel),
    /// so the averaged normal is undefined.
    FoldsBack,
    /// The slave face's normal points against the projection direction at its centre.
    AgainstProjection,
}

/// Which way a coordinate range is left ([`MortarError::CoordinateRange`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RangeLimit {
    /// Products of two coordinates would overflow: scale the meshes down.
    Overflow,
    /// Products of two lengths would underflow: scale the meshes up.
    Underflow,
}

/// Errors of the mortar core.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MortarError {
    /// A node coordinate is NaN or infinite.
    #[error("node {tag} has a non-finite coordinate {coords:?}")]
    NonFiniteCoordinate {
        /// Node tag.
        tag: u64,
        /// The offending coordinates.
        coords: [f64; 3],
    },
    /// Two nodes were given the same tag.
    #[error("node tag {tag} is used twice")]
    DuplicateNode {
        /// Node tag.
        tag: u64,
    },
    /// A face refers to a node that the mesh does not have.
    #[error("{face} refers to node {node}, which the mesh does not have")]
    UnknownNode {
        /// The face.
        face: FaceLocation,
        /// The missing node tag.
        node: u64,
    },
    /// A face was given the wrong number of nodes for its element.
    #[error("{face} is a {element} and needs {expected} nodes, got {got}")]
    WrongNodeCount {
        /// The face.
        face: FaceLocation,
        /// Element name.
        element: &'static str,
        /// Nodes the element needs.
        expected: usize,
        /// Nodes given.
        got: usize,
    },
    /// A face has (nearly) zero length or area, or repeats a node.
    #[error("{face} is degenerate: {reason}")]
    DegenerateFace {
        /// The face.
        face: FaceLocation,
        /// What makes it degenerate.
        reason: String,
    },
    /// A face is inverted: folded or self-intersecting, or oriented against its neighbours.
    #[error("{face} is inverted: {reason}")]
    InvertedFace {
        /// The face.
        face: FaceLocation,
        /// How it is inverted: what a program would act on (a face numbered against its
        /// neighbours can be reversed; a self-intersecting one must be remeshed).
        kind: Inversion,
        /// What makes it inverted, naming the nodes and faces.
        reason: String,
    },
    /// The faces of a surface do not make a surface that can be oriented: an edge shared by
    /// more than two faces (three lines at a node in 2D), or a one-sided piece.
    #[error("{face}: {reason}")]
    Topology {
        /// A face involved (the repeat, the last of a fin's faces in face order).
        face: FaceLocation,
        /// The tags of every face involved, `face` among them: a reader that knows where each
        /// face came from (a file and line) can say so for all of them.
        faces: Box<[u64]>,
        /// What is wrong, naming the faces and nodes.
        reason: String,
    },
    /// The coordinates are beyond what double precision carries through the coupling:
    /// products of two lengths (areas, the entries of D and M) would overflow (coordinates
    /// beyond [`MAX_COORDINATE`](crate::tolerances::MAX_COORDINATE) in magnitude) or underflow
    /// (an interface less than [`MIN_EXTENT`](crate::tolerances::MIN_EXTENT) across). Rescale
    /// the meshes (change their units): the coupling is the same at every scale in between.
    #[error(
        "the interface's coordinates reach {largest:e} in magnitude and span {extent:e}: {reason}"
    )]
    CoordinateRange {
        /// The largest magnitude of a coordinate, over both surfaces.
        largest: f64,
        /// The extent of the interface: the longest side of the box of both surfaces' nodes.
        extent: f64,
        /// Which way the range is left: the meshes are to be scaled down (overflow) or up
        /// (underflow).
        limit: RangeLimit,
        /// What would overflow or underflow, and the range supported.
        reason: String,
    },
    /// Faces of different reference dimension (lines and triangles) in one interface, or a
    /// 2D interface with a node off the xy-plane.
    #[error("dimension mismatch: {what}")]
    DimensionMismatch {
        /// The interface's dimension, set by its first slave face (lines: 2D, faces: 3D).
        expected: crate::interface::SpatialDim,
        /// The dimension of what disagrees: 3D for a face among lines or a node off the plane
        /// `z = 0` of a 2D interface, 2D for a line among faces.
        found: crate::interface::SpatialDim,
        /// What disagrees and where (the face or node by side and tag), for the message.
        what: String,
    },
    /// A surface has no faces.
    #[error("the {side} surface has no faces")]
    EmptySurface {
        /// The empty side.
        side: Side,
    },
    /// No slave face overlaps any master face.
    #[error("the interface has no overlap: no slave face overlaps a master face ({slave_faces} slave faces, {master_faces} master faces, {candidates} candidate pairs from the search{})", if *back_facing > 0 { format!(", {back_facing} of them skipped because the master face looks the same way as the slave: the master's normals must oppose the slave's (reverse the node order of the master faces)") } else { String::new() })]
    NoOverlap {
        /// Slave face count.
        slave_faces: usize,
        /// Master face count.
        master_faces: usize,
        /// Candidate pairs the bounding-box search found.
        candidates: usize,
        /// Candidate pairs skipped because the master face faces away from the slave.
        back_facing: usize,
    },
    /// The Newton iteration that maps a physical point back to a face's reference
    /// coordinates did not converge.
    #[error("projection of point {point:?} onto {face} did not converge after {iterations} Newton iterations (residual {residual:e})")]
    ProjectionFailed {
        /// The face projected onto.
        face: FaceLocation,
        /// The physical point.
        point: [f64; 3],
        /// Iterations made.
        iterations: usize,
        /// Final residual norm.
        residual: f64,
    },
    /// An option is out of its range (a quadrature degree no rule reaches, a zero thread count),
    /// or an operation the input does not allow (reversing a face whose element cannot say how).
    #[error("invalid option: {option} {value}: {reason}")]
    InvalidOption {
        /// The option (`"quadrature degree"`, `"threads"`, `"search radius"`, `"reversing"` a
        /// face, ...).
        option: &'static str,
        /// The value given, as written.
        value: String,
        /// Why it is refused (the range allowed).
        reason: String,
    },
    /// The coupling met what it would otherwise report as a warning (uncovered slave area,
    /// overlapping master faces, skipped pairs), and full coverage was required
    /// ([`CouplingOptions::require_full_coverage`](crate::CouplingOptions::require_full_coverage)).
    #[error("{0} (full coverage was required)")]
    IncompleteCoverage(Box<crate::assembly::CouplingWarning>),
    /// The axisymmetric (r-z) geometry was asked of a 3D interface
    /// ([`CouplingOptions::geometry`](crate::CouplingOptions::geometry)).
    #[error("the axisymmetric (r-z) geometry needs a 2D interface of lines in the plane z = 0 (x the radius, y the axis); this interface is 3D ({slave_faces} slave faces)")]
    AxisymmetricNeeds2D {
        /// Slave face count of the 3D interface.
        slave_faces: usize,
    },
    /// A node of an axisymmetric (r-z) interface lies at a negative radius: x is the radius
    /// and must be at least zero.
    #[error("{side} node {node} lies at the negative radius x = {radius:e}: an axisymmetric (r-z) model needs x = r >= 0")]
    NegativeRadius {
        /// The surface.
        side: Side,
        /// The node's tag.
        node: u64,
        /// Its x coordinate.
        radius: f64,
    },
    /// A multiplier space could not be built on a face (a singular local mass matrix).
    #[error("multiplier space {space} cannot be built on {face}: {reason}")]
    MultiplierSpace {
        /// The space.
        space: &'static str,
        /// The face.
        face: FaceLocation,
        /// Why.
        reason: String,
    },
}

/// The core's result type.
pub type Result<T, E = MortarError> = std::result::Result<T, E>;
