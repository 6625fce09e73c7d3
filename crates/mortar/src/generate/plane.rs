//! The unit square at height `z`, as Tri3 (either diagonal) or Quad4 faces.

use mortar_core::error::Result;
use mortar_core::mesh::SurfaceMesh;
use mortar_elements::{QUAD4, TRI3};

/// Which diagonal cuts each square cell into two triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Diagonal {
    /// From the cell's `(0,0)` corner to its `(1,1)` corner.
    Main,
    /// From `(1,0)` to `(0,1)`.
    Anti,
}

fn grid_nodes(mesh: &mut SurfaceMesh, n: usize, z: f64, first_node_tag: u64) -> Result<()> {
    let h = 1.0 / n as f64;
    for j in 0..=n {
        for i in 0..=n {
            let tag = first_node_tag + (j * (n + 1) + i) as u64;
            mesh.add_node(tag, [i as f64 * h, j as f64 * h, z])?;
        }
    }
    Ok(())
}

/// The unit square `[0,1]^2` at height `z`, `n x n` cells each cut into two Tri3 along
/// `diagonal`. Normals point to `+z`, or `-z` if `flip`.
///
/// # Errors
/// None for `n >= 1`; the `Result` carries mesh-building errors through.
pub fn square_triangles(
    n: usize,
    diagonal: Diagonal,
    z: f64,
    flip: bool,
    first_node_tag: u64,
) -> Result<SurfaceMesh> {
    let mut mesh = SurfaceMesh::with_capacity((n + 1) * (n + 1), 2 * n * n);
    grid_nodes(&mut mesh, n, z, first_node_tag)?;
    let id = |i: usize, j: usize| first_node_tag + (j * (n + 1) + i) as u64;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            let tris = match diagonal {
                Diagonal::Main => [[a, b, c], [a, c, d]],
                Diagonal::Anti => [[a, b, d], [b, c, d]],
            };
            for t in tris {
                let t = if flip { [t[0], t[2], t[1]] } else { t };
                mesh.add_face(&TRI3, &t)?;
            }
        }
    }
    Ok(mesh)
}

/// The unit square at height `z` with `n x n` Quad4 cells. Normals point to `+z`, or `-z` if
/// `flip`.
///
/// # Errors
/// None for `n >= 1`.
pub fn square_quads(n: usize, z: f64, flip: bool, first_node_tag: u64) -> Result<SurfaceMesh> {
    let mut mesh = SurfaceMesh::with_capacity((n + 1) * (n + 1), n * n);
    grid_nodes(&mut mesh, n, z, first_node_tag)?;
    let id = |i: usize, j: usize| first_node_tag + (j * (n + 1) + i) as u64;
    for j in 0..n {
        for i in 0..n {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            let q = if flip { [q[0], q[3], q[2], q[1]] } else { q };
            mesh.add_face(&QUAD4, &q)?;
        }
    }
    Ok(mesh)
}
