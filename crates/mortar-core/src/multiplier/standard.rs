//! Standard multipliers: the slave shape functions themselves (`Phi_j = N_j`).

use super::{LmBasis, MultiplierFastPaths, MultiplierSpace};
use crate::element::ElementRef;
use crate::error::Result;
use crate::geometry::ModelGeometry;
use crate::interface::FaceGeometry;
use crate::tolerances::Tolerances;

/// Standard multipliers: `Phi_j = N_j`, the slave shape functions themselves.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StandardMultipliers;

impl MultiplierSpace for StandardMultipliers {
    fn name(&self) -> &'static str {
        "standard"
    }

    fn basis(&self, face: &FaceGeometry, _tol: &Tolerances) -> Result<LmBasis> {
        Ok(LmBasis::identity(face.node_count()))
    }

    fn fast_paths(&self) -> Option<&dyn MultiplierFastPaths> {
        Some(self)
    }
}

impl MultiplierFastPaths for StandardMultipliers {
    /// The identity on every face.
    fn basis_is_uniform(&self, _element: ElementRef, _geometry: ModelGeometry) -> bool {
        true
    }
}
