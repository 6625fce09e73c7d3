//! `CouplingOptions`: the multiplier space, integration strategy, projector, thread count and
//! measure a coupling is computed with, and their defaults.

use std::sync::Arc;

use super::WholeInterface;
use crate::error::Result;
use crate::geometry::ModelGeometry;
use crate::integration::{ElementBased, IntegrationStrategy, SegmentBased};
use crate::multiplier::{DualMultipliers, LinearMultipliers, MultiplierSpace, StandardMultipliers};
use crate::projector::{NodalNormalField, Projector};

/// How to compute the coupling: multiplier space, integration strategy, projector, threads,
/// and the measure of the interface.
///
/// The default is standard multipliers, segment-based integration of automatic degree (exact
/// on affine faces), the averaged nodal normal field, rayon's default thread count, and the
/// Cartesian measure.
#[derive(Debug, Clone)]
pub struct CouplingOptions {
    /// The multiplier space.
    pub multipliers: Arc<dyn MultiplierSpace>,
    /// The integration strategy.
    pub integration: Arc<dyn IntegrationStrategy>,
    /// The projection direction field.
    pub projector: Arc<dyn Projector>,
    /// Worker threads. `None`: called on a rayon pool's thread (inside a user's
    /// `pool.install`, or a parallel loop over several interfaces), the coupling runs on that
    /// pool; called from any other thread, on a kept pool of rayon's default size (the core
    /// count, or `RAYON_NUM_THREADS` as it is when the first such call starts the pool; see
    /// [`assemble_coupling`](super::assemble_coupling)). D and M do not depend on it.
    pub threads: Option<usize>,
    /// Make every [`CouplingWarning`](super::CouplingWarning) (uncovered slave area,
    /// overlapping master faces, skipped pairs) an error ([`MortarError::IncompleteCoverage`](crate::MortarError)).
    pub require_full_coverage: bool,
    /// The measure of the interface: [`ModelGeometry::Cartesian`] (the default: area in 3D,
    /// length in 2D), or [`ModelGeometry::Axisymmetric`] for a 2D interface in the r-z plane
    /// (`x = r >= 0`): every point of the paired rule is weighted by `2 pi r` at its slave
    /// position, so that `D[j,k] = int Phi_j N_k^s 2 pi r ds` and
    /// `M[j,l] = int Phi_j N_l^m 2 pi r ds` are integrals over the revolved surface, and the
    /// multiplier space is built for that measure (the dual basis is biorthogonal with respect
    /// to `2 pi r ds`: its coefficients come from the face's r-weighted mass matrix). The
    /// automatic degree stays exact for straight lines: the Gauss rule of degree 2 is exact to
    /// degree 3, the degree of `r Phi_j N_k`. Refused for a 3D interface
    /// ([`MortarError::AxisymmetricNeeds2D`](crate::MortarError::AxisymmetricNeeds2D)) and for
    /// a node at a negative radius ([`MortarError::NegativeRadius`](crate::MortarError::NegativeRadius)).
    ///
    /// The body assemblies of `mortar-physics` take the same setting in their options; give
    /// both the same.
    pub geometry: ModelGeometry,
    /// The whole interface this one is a part of (`None`: this interface is whole): the
    /// order, chunks and paths are then the whole's, so that the rows of the slave nodes
    /// whose faces and their neighbours' this part holds are the whole's bit for bit (see
    /// [`WholeInterface`]). A distributed coupling sets it.
    pub whole: Option<Arc<WholeInterface>>,
}

impl Default for CouplingOptions {
    fn default() -> Self {
        Self {
            multipliers: Arc::new(StandardMultipliers),
            integration: Arc::new(SegmentBased::default()),
            projector: Arc::new(NodalNormalField),
            threads: None,
            require_full_coverage: false,
            geometry: ModelGeometry::Cartesian,
            whole: None,
        }
    }
}

impl CouplingOptions {
    /// Dual (biorthogonal) multipliers.
    pub fn dual(mut self) -> Self {
        self.multipliers = Arc::new(DualMultipliers);
        self
    }

    /// Standard multipliers.
    pub fn standard(mut self) -> Self {
        self.multipliers = Arc::new(StandardMultipliers);
        self
    }

    /// Linear multipliers on second-order faces (standard on first-order ones): see
    /// [`LinearMultipliers`].
    pub fn linear(mut self) -> Self {
        self.multipliers = Arc::new(LinearMultipliers);
        self
    }

    /// Segment-based integration of the given degree (`None`: automatic).
    ///
    /// # Errors
    /// An invalid degree.
    pub fn segment_based(mut self, degree: Option<u32>) -> Result<Self> {
        self.integration = Arc::new(SegmentBased::new(degree)?);
        Ok(self)
    }

    /// Element-based integration of the given degree (`None`: automatic).
    ///
    /// # Errors
    /// An invalid degree.
    pub fn element_based(mut self, degree: Option<u32>) -> Result<Self> {
        self.integration = Arc::new(ElementBased::new(degree)?);
        Ok(self)
    }

    /// A fixed number of worker threads.
    pub fn threads(mut self, threads: usize) -> Self {
        self.threads = Some(threads);
        self
    }

    /// Turns every coupling warning into an error (see
    /// [`require_full_coverage`](Self::require_full_coverage)).
    pub fn require_full_coverage(mut self, yes: bool) -> Self {
        self.require_full_coverage = yes;
        self
    }

    /// The axisymmetric (r-z) measure `2 pi r ds` (see [`geometry`](Self::geometry)).
    pub fn axisymmetric(self) -> Self {
        self.with_geometry(ModelGeometry::Axisymmetric)
    }

    /// The measure of the interface (see [`geometry`](Self::geometry)).
    pub fn with_geometry(mut self, geometry: ModelGeometry) -> Self {
        self.geometry = geometry;
        self
    }

    /// A one-line description of the formulation, e.g.
    /// `"standard multipliers, segment-based, degree auto, nodal-normal-field projection"`
    /// (followed by `", axisymmetric (2 pi r)"` for the axisymmetric measure).
    pub fn describe(&self) -> String {
        let mut s = format!(
            "{} multipliers, {}, {} projection",
            self.multipliers.name(),
            self.integration.name(),
            self.projector.name()
        );
        if self.geometry.is_axisymmetric() {
            s.push_str(", axisymmetric (2 pi r)");
        }
        s
    }
}
