//! Integration strategies: they turn a slave face and its candidate master faces into a
//! *paired quadrature rule* — points each with a slave and a master reference coordinate and a
//! weight. They see geometry only, never shape functions or multipliers; the integrator
//! (`assembly`) never sees polygons.
//!
//! - [`SegmentBased`]: exact segmentation. In 2D, the master nodes are projected onto the slave
//!   line along the projector's field and Gauss points placed on each overlap segment. In 3D,
//!   both faces are projected onto the auxiliary plane through the slave face centre, clipped,
//!   the clip polygon triangulated (the fan from a vertex where the quadrature is exact for the
//!   integrands, from its centroid otherwise), and each triangle's quadrature points mapped
//!   back to both faces.
//!
//! Only master faces that face the slave count: their normal must oppose the projection
//! direction (the slave's outward normal), as it does when both surfaces carry their bodies'
//! outward normals. This keeps the far side of a thin master body out of the coupling.
//!
//! - [`ElementBased`]: quadrature points of the slave face, each projected onto the master face
//!   it falls on. Cheap, but inexact where a slave face spans master edges.
//! - [`AdaptiveElementBased`]: the same on leaves of a recursive split of the slave face,
//!   refined where master edges cross it: a reference for curved faces, built without
//!   clipping or flat sub-faces (slow).
//!
//! A strategy of one's own implements [`IntegrationStrategy`] (a name and the paired rule of a
//! face). The coupling's fused kernels are [`SegmentBased`]'s segmentation in another form,
//! which it takes for a [`SegmentBased`] found by its type; the one fact a strategy may state
//! besides, that a face's candidates may be handed over in parts, is apart, in
//! [`IntegrationFastPaths`].

mod adaptive;
pub(crate) mod affine_moments;
pub(crate) mod closed_form;
pub mod curved_3d;
mod degree;
mod element_based;
mod segment_based;
pub(crate) mod segments_2d;
pub(crate) mod segments_3d;

use std::any::Any;

use nalgebra::{Vector2, Vector3};

pub use adaptive::{AdaptiveElementBased, MAX_ADAPTIVE_DEPTH};
pub use degree::default_degree;
pub use element_based::ElementBased;
pub use segment_based::{SegmentBased, MAX_QUAD_SUBDIVISION};

use crate::element::MAX_FACE_NODES;
use crate::error::{MortarError, Result, Side};
use crate::geometry::{wider_than, Polygon};
use crate::interface::{FaceGeometry, Interface, MasterFaces};
use crate::projector::Projector;

/// One point of a paired quadrature rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairedPoint {
    /// The master face, by its slot in [`SegmentContext::masters`] (its index in the master
    /// mesh is `masters.face_index(slot)`).
    pub master: u32,
    /// Reference coordinates on the slave face.
    pub xi_slave: Vector2<f64>,
    /// Reference coordinates on the master face.
    pub xi_master: Vector2<f64>,
    /// The weight (a measure of slave surface: quadrature weight times Jacobian).
    pub weight: f64,
}

/// A paired quadrature rule for one slave face, with its counts. Points of one master face are
/// consecutive.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PairedRule {
    /// The points.
    pub points: Vec<PairedPoint>,
    /// Master faces with a non-empty overlap.
    pub pairs: u32,
    /// Integration cells (clip triangles, 2D segments, or slave faces for element-based).
    pub cells: u32,
    /// The quadrature degrees used, as a bit set (bit `d` set when degree `d` was used).
    pub degrees: u32,
    /// Candidate master faces skipped because they face away from the slave (their normal
    /// does not oppose the projection direction): the far side of a thin body, or a master
    /// surface oriented the wrong way round.
    pub back_facing: u32,
    /// Candidate pairs dropped because a point could not be mapped between the faces (a
    /// failed projection); their area counts as uncovered.
    pub skipped: u32,
    /// The first such failure, naming the face and the point.
    pub first_skipped: Option<MortarError>,
    /// The fraction of the slave face that the points cover, measured exactly where the
    /// strategy can (clip polygon areas against the face's projection, segment lengths in
    /// reference coordinates, reference weights of the points that found a master face);
    /// `None` lets the coupling compare the sum of the weights with the face's measure.
    pub covered: Option<f64>,
}

impl PairedRule {
    /// Empties the rule, keeping its allocation.
    pub fn clear(&mut self) {
        self.points.clear();
        self.pairs = 0;
        self.cells = 0;
        self.degrees = 0;
        self.back_facing = 0;
        self.skipped = 0;
        self.first_skipped = None;
        self.covered = None;
    }

    /// Records a pair dropped because of `error` (its points already removed).
    pub fn skip(&mut self, error: MortarError) {
        self.skipped += 1;
        if self.first_skipped.is_none() {
            self.first_skipped = Some(error);
        }
    }
}

/// What a strategy may look at besides the slave face: the interface and the projector.
#[derive(Debug, Clone, Copy)]
pub struct SegmentContext<'a> {
    /// The interface.
    pub interface: &'a Interface,
    /// The projection direction field.
    pub projector: &'a dyn Projector,
    /// The master faces stored in the spatial order of the search tree, addressed by slot
    /// (read these rather than the mesh: the candidates of one slave face then lie together
    /// in memory).
    pub masters: &'a MasterFaces,
}

impl SegmentContext<'_> {
    /// The geometry of the master face in slot `slot` (from the packed copy; no nodal
    /// normals, as [`Interface::master_face`]).
    pub fn master_face(&self, slot: u32) -> FaceGeometry {
        let s = slot as usize;
        let mut nodes = [Vector3::zeros(); MAX_FACE_NODES];
        let (element, _) = self.masters.coords_into(self.interface, s, &mut nodes);
        FaceGeometry {
            index: self.masters.face_index(s) as u32,
            tag: self.masters.tag(self.interface, s),
            side: Side::Master,
            element,
            nodes,
            normals: [Vector3::zeros(); MAX_FACE_NODES],
        }
    }

    /// The tag of the master face in slot `slot`.
    pub fn master_tag(&self, slot: u32) -> u64 {
        self.masters.tag(self.interface, slot as usize)
    }
}

/// An integration strategy: the user's speed-for-accuracy dial.
///
/// Implement this to add a strategy: its [`name`](IntegrationStrategy::name) and the paired
/// rule of a slave face against its candidates
/// ([`paired_rule_into`](IntegrationStrategy::paired_rule_into)) are all the coupling needs:
/// it integrates D and M on the points it is handed.
///
/// **Fast paths.** Two of the coupling's fast paths are [`SegmentBased`]'s own segmentation
/// written for special faces: the fused kernel for straight two-node lines in 2D (and the
/// sorted merge of a straight interface), and the closed-form integration of the clip
/// polygons of flat first-order faces in 3D (see
/// [`assemble_coupling`](crate::assemble_coupling)). The coupling takes them when the strategy *is* a [`SegmentBased`] (it looks at the type,
/// hence the [`Any`] bound, which every `'static` type meets), for its degree: nothing to
/// claim, and nothing a strategy of one's own can claim wrongly; any other strategy, a wrapper
/// of [`SegmentBased`] included, goes through
/// [`paired_rule_into`](IntegrationStrategy::paired_rule_into) on every face. The one fact
/// the coupling cannot find, whether a face's candidates may be handed over in parts, is the
/// method of [`IntegrationFastPaths`], which a strategy reaches the coupling through by
/// returning itself from [`fast_paths`](IntegrationStrategy::fast_paths). The default, `None`,
/// claims nothing and is always correct: a strategy of one's own computes the same D and M
/// (to round-off) as the strategy it imitates without knowing of any of this.
pub trait IntegrationStrategy: Any + Send + Sync + std::fmt::Debug {
    /// A description, such as `"segment-based, degree auto"`.
    fn name(&self) -> String;

    /// Writes the paired rule of `slave` against its `candidates` (master faces as slots of
    /// [`SegmentContext::masters`], ascending: see [`SegmentContext::master_face`]) into `out`
    /// (cleared first). A pair whose points cannot be mapped between the
    /// faces is dropped and recorded with [`PairedRule::skip`] (the coupling counts it and
    /// warns), never dropped silently.
    ///
    /// # Errors
    /// A typed error for an invalid option, or a slave face that cannot be segmented at all.
    fn paired_rule_into(
        &self,
        ctx: &SegmentContext<'_>,
        slave: &FaceGeometry,
        candidates: &[u32],
        out: &mut PairedRule,
    ) -> Result<()>;

    /// The facts about this strategy that the coupling's fast paths rely on (see the trait's
    /// documentation), if it states any. The default, `None`, states none: always correct.
    fn fast_paths(&self) -> Option<&dyn IntegrationFastPaths> {
        None
    }
}

/// Facts about an [`IntegrationStrategy`] that let the coupling take a fast path, reached
/// through [`IntegrationStrategy::fast_paths`]. Every method has a default that claims
/// nothing and is always correct; a strategy overrides those it knows to hold.
///
/// (A trait for one fact, as the other plug-ins have theirs,
/// [`MultiplierFastPaths`](crate::multiplier::MultiplierFastPaths) and
/// [`ProjectorFastPaths`](crate::projector::ProjectorFastPaths): one shape for the three, and
/// room for a fact more with its default without touching a strategy that states none.)
pub trait IntegrationFastPaths {
    /// Whether the rule of a slave face against its candidates may be built from parts of
    /// the candidate list: true when the points of each candidate depend on that candidate
    /// and the slave face alone, so that the rules of consecutive parts, concatenated, are
    /// the rule of the whole list (their counts added, their `covered` fractions summed).
    /// The coupling then asks for [`CANDIDATE_BATCH`] candidates at a time and integrates
    /// each part before the next, so that a coarse slave face against a million master
    /// faces needs the memory of one batch of points, not of all of them. The default,
    /// false, passes every candidate of a face in one call.
    fn splits_over_candidates(&self) -> bool {
        false
    }
}

/// What the closed-form integration of clip polygons needs to know of the [`SegmentBased`]
/// strategy that segments 3D faces ([`SegmentBased::polygon_segments`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PolygonSegments {
    /// The quadrature degree on each clip triangle; `None`: [`default_degree`]. A degree below
    /// the integrands' keeps the strategy (its quadrature is then not exact).
    pub degree: Option<u32>,
}

/// What the fused kernel for straight two-node lines needs to know of the [`SegmentBased`]
/// strategy that segments them ([`SegmentBased::line_segments`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LineSegments {
    /// The degree of the Gauss rule on each segment; `None`: [`default_degree`].
    pub degree: Option<u32>,
}

/// Candidates per call of [`IntegrationStrategy::paired_rule_into`] for a strategy that
/// [splits over candidates](IntegrationFastPaths::splits_over_candidates): far more than a
/// slave face meets at ordinary mesh ratios (about ten), so that only a face much coarser
/// than its master is split.
pub const CANDIDATE_BATCH: usize = 4096;

/// How many times the coordinates' rounding (`8 eps |x|`) a clip polygon must be wide to
/// count when its area is below what the rounding alone gives two faces that only touch
/// (`8 eps |x|` times the slave face's diameter). Such faces become a sliver about one
/// rounding wide; the factor leaves room for the few roundings the projection into the plane
/// adds. A genuine small overlap is far wider: 1e-5 at 1e5 from the origin (5.6e4 roundings,
/// `tests/integration/small_overlaps.rs`); on the benchmark's cylinder at n = 1024, 382
/// corner triangles of 1e-18 to 1e-17 (1e-13 of a face, 1e-10 to 2e-9 wide: 1e5 roundings
/// and more), which a test on the area alone would drop.
pub(crate) const SLIVER_ROUNDINGS: f64 = 64.0;

/// Whether a 3D clip polygon `clip` of (signed) `area` counts as an overlap: more than
/// `floor` (the tolerance's fraction of the smaller face), and more than the area the
/// coordinates' `rounding` alone gives two faces that only touch (`rounding` times the slave
/// face's `diameter`), or else wider than [`SLIVER_ROUNDINGS`] roundings ([`wider_than`]):
/// a small overlap far from the origin (1e-5 wide, of area 5e-11, at 1e5) is an overlap.
/// The one rule of the flat paths (`SlavePlane::overlap_counts`) and the curved one.
#[inline]
pub(crate) fn overlap_counts(
    area: f64,
    floor: f64,
    rounding: f64,
    diameter: f64,
    clip: &Polygon,
) -> bool {
    area > floor.max(rounding * diameter) || (area > floor && wide_sliver(area, clip, rounding))
}

/// Whether a clip polygon of `area` is wider than the rounding's slivers (rare: out of the
/// per-pair path).
#[cold]
#[inline(never)]
fn wide_sliver(area: f64, clip: &Polygon, rounding: f64) -> bool {
    wider_than(area, &clip.vertices, SLIVER_ROUNDINGS * rounding)
}
