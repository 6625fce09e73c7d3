//! Line2 surfaces in the xy-plane: the unit segment and the half circle.

use mortar_core::error::Result;
use mortar_core::mesh::SurfaceMesh;
use mortar_elements::LINE2;

/// The segment `[0, 1]` on the x-axis with `n` Line2 elements. The lines run towards `+x`, so
/// the normal `(t_y, -t_x)` is `-y`: the outward normal of a body lying above the segment. With
/// `flip` they run towards `-x` and the normal is `+y` (a body below).
///
/// # Errors
/// None for `n >= 1`.
pub fn line_mesh(n: usize, flip: bool, first_node_tag: u64) -> Result<SurfaceMesh> {
    let mut mesh = SurfaceMesh::with_capacity(n + 1, n);
    for i in 0..=n {
        mesh.add_node(first_node_tag + i as u64, [i as f64 / n as f64, 0.0, 0.0])?;
    }
    for i in 0..n {
        let (a, b) = (first_node_tag + i as u64, first_node_tag + i as u64 + 1);
        if flip {
            mesh.add_face(&LINE2, &[b, a])?;
        } else {
            mesh.add_face(&LINE2, &[a, b])?;
        }
    }
    Ok(mesh)
}

/// The upper half of the unit circle (angles `0` to `pi`) with `n` Line2 elements, node `i`
/// at the angle `pi i / n` with tag `first_node_tag + i`. The lines run clockwise, from each
/// node to the one before it, so the normal `(t_y, -t_x)` points to the centre: the outward
/// normal of a body outside the circle. With `flip` they run anticlockwise and the normal
/// points away from the centre (a body inside). The benchmarks' curved 2D interface (`arc2d`).
///
/// ```
/// use mortar::generate::half_circle_mesh;
///
/// let arc = half_circle_mesh(8, false, 1)?;
/// assert_eq!((arc.node_count(), arc.face_count()), (9, 8));
/// # Ok::<(), mortar::MortarError>(())
/// ```
///
/// # Errors
/// None for `n >= 1`.
pub fn half_circle_mesh(n: usize, flip: bool, first_node_tag: u64) -> Result<SurfaceMesh> {
    let mut mesh = SurfaceMesh::with_capacity(n + 1, n);
    for i in 0..=n {
        let a = std::f64::consts::PI * i as f64 / n as f64;
        mesh.add_node(first_node_tag + i as u64, [a.cos(), a.sin(), 0.0])?;
    }
    for i in 0..n {
        let (a, b) = (first_node_tag + i as u64 + 1, first_node_tag + i as u64);
        if flip {
            mesh.add_face(&LINE2, &[b, a])?;
        } else {
            mesh.add_face(&LINE2, &[a, b])?;
        }
    }
    Ok(mesh)
}
