//! The lateral surface of a cylinder about the z-axis, in Quad4 or Tri3 faces.

use std::f64::consts::PI;

use mortar_core::error::Result;
use mortar_core::mesh::SurfaceMesh;
use mortar_elements::{QUAD4, TRI3};

/// The lateral surface of the cylinder of radius `radius` about the z-axis, `0 <= z <= 1`,
/// with `around` cells round and `along` cells along it: Quad4 cells, or each cut into two
/// Tri3 if `triangles`. Normals point outward, or inward if `flip`.
///
/// # Errors
/// None for `around >= 3`, `along >= 1`.
pub fn cylinder_surface(
    radius: f64,
    around: usize,
    along: usize,
    triangles: bool,
    flip: bool,
    first_node_tag: u64,
) -> Result<SurfaceMesh> {
    let mut mesh = SurfaceMesh::with_capacity(around * (along + 1), 2 * around * along);
    for j in 0..=along {
        for i in 0..around {
            let t = 2.0 * PI * i as f64 / around as f64;
            let tag = first_node_tag + (j * around + i) as u64;
            mesh.add_node(
                tag,
                [radius * t.cos(), radius * t.sin(), j as f64 / along as f64],
            )?;
        }
    }
    let id = |i: usize, j: usize| first_node_tag + (j * around + i % around) as u64;
    for j in 0..along {
        for i in 0..around {
            // Counter-clockwise seen from outside: (theta, z) is right-handed with the outward
            // normal.
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if triangles {
                for t in [[a, b, c], [a, c, d]] {
                    let t = if flip { [t[0], t[2], t[1]] } else { t };
                    mesh.add_face(&TRI3, &t)?;
                }
            } else {
                let q = if flip { [a, d, c, b] } else { [a, b, c, d] };
                mesh.add_face(&QUAD4, &q)?;
            }
        }
    }
    Ok(mesh)
}
