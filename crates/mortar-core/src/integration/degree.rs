use crate::element::SurfaceElement;

/// The degree of the mortar integrands `Phi_j N_k` and `Phi_j N_l^m`: the slave shape degree
/// plus the larger of the slave and master shape degrees, plus one when the slave is not
/// affine (its cells are integrated in its reference coordinates, with the Jacobian, linear
/// for a planar bilinear quad). That is 2 for tri-tri and line-line, 3 for a triangle against
/// a quad, 5 for a quad slave: exact for affine faces and for a planar quad slave against
/// triangles.
pub fn default_degree(slave: &dyn SurfaceElement, master: &dyn SurfaceElement) -> u32 {
    let ps = slave.shape_degree();
    let jacobian =
        u32::from(!slave.is_affine() && slave.domain() != crate::element::ReferenceDomain::Line);
    ps + ps.max(master.shape_degree()) + jacobian
}
