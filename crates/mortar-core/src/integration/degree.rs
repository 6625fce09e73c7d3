//! The default quadrature degree of the mortar integrands for a pair of faces.

use crate::element::SurfaceElement;

/// The degree of the mortar integrands `Phi_j N_k` and `Phi_j N_l^m` on affine faces: the
/// slave shape degree plus the larger of the slave and master shape degrees (2 for tri-tri and
/// line-line, 3 for a triangle against a quad, 4 for quad-quad). The 3D segmenter adds one
/// for a slave face whose Jacobian varies (a non-parallelogram quad, integrated in its
/// reference coordinates with the Jacobian as a factor).
pub fn default_degree(slave: &dyn SurfaceElement, master: &dyn SurfaceElement) -> u32 {
    let ps = slave.shape_degree();
    ps + ps.max(master.shape_degree())
}
