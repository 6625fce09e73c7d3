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
