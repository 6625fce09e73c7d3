use std::sync::Arc;

use crate::error::Result;
use crate::integration::{ElementBased, IntegrationStrategy, SegmentBased};
use crate::multiplier::{DualMultipliers, MultiplierSpace, StandardMultipliers};
use crate::projector::{NodalNormalField, Projector};

/// How to compute the coupling: multiplier space, integration strategy, projector, threads.
///
/// The default is standard multipliers, segment-based integration of automatic degree (exact
/// on affine faces), the averaged nodal normal field, and rayon's default thread count.
#[derive(Debug, Clone)]
pub struct CouplingOptions {
    /// The multiplier space.
    pub multipliers: Arc<dyn MultiplierSpace>,
    /// The integration strategy.
    pub integration: Arc<dyn IntegrationStrategy>,
    /// The projection direction field.
    pub projector: Arc<dyn Projector>,
    /// Worker threads; `None` uses rayon's default (the core count, or `RAYON_NUM_THREADS`).
    pub threads: Option<usize>,
    /// Make every [`CouplingWarning`](super::CouplingWarning) (uncovered slave area, skipped
    /// pairs) an error ([`MortarError::IncompleteCoverage`](crate::MortarError)).
    pub require_full_coverage: bool,
}

impl Default for CouplingOptions {
    fn default() -> Self {
        Self {
            multipliers: Arc::new(StandardMultipliers),
            integration: Arc::new(SegmentBased::default()),
            projector: Arc::new(NodalNormalField),
            threads: None,
            require_full_coverage: false,
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

    /// A one-line description of the formulation, e.g.
    /// `"standard multipliers, segment-based, degree auto, nodal-normal-field projection"`.
    pub fn describe(&self) -> String {
        format!(
            "{} multipliers, {}, {} projection",
            self.multipliers.name(),
            self.integration.name(),
            self.projector.name()
        )
    }
}
