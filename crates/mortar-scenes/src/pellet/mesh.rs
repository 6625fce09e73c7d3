//! The meshes of the pellet cross-section: an O-grid disc (the pellet) and a structured
//! polar annulus (the cladding), at different resolutions along the interface.

use mortar_elements::volume::QUAD4;
use mortar_fem::mesh::{VolumeMesh, VolumeMeshError};

use mortar::generate::{ball_mesh, Inclusion};

/// The pellet disc of radius `radius` centred at the origin: an O-grid with `n` core cells
/// per side and `layers` radial cells, `4 n` edges on the circle. Node tags from 1.
///
/// # Errors
/// Those of [`ball_mesh`].
pub fn pellet_mesh(radius: f64, n: usize, layers: usize) -> Result<VolumeMesh, VolumeMeshError> {
    ball_mesh(
        &Inclusion {
            dim: 2,
            centre: [0.0, 0.0, 0.0],
            radius,
            half_width: 2.0 * radius,
        },
        n,
        layers,
        1,
    )
}

/// The annulus `inner <= r <= outer` centred at the origin: `around` x `radial` Quad4 cells,
/// nodes on circles (uniform in angle, starting at the angle `phase`) and uniform in radius.
/// Node tags from 1.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for radii not `0 < inner < outer`, fewer than 3 cells
/// around or no cell radially.
pub fn annulus_mesh(
    inner: f64,
    outer: f64,
    around: usize,
    radial: usize,
    phase: f64,
) -> Result<VolumeMesh, VolumeMeshError> {
    if !(inner > 0.0 && outer > inner && outer.is_finite()) || around < 3 || radial == 0 {
        return Err(VolumeMeshError::BadCell {
            cell: 0,
            element: "annulus",
            reason: format!("radii {inner}..{outer}, {around} cells around and {radial} radially"),
        });
    }
    let mut mesh = VolumeMesh::new();
    let tag = |i: usize, j: usize| (j * around + i % around) as u64 + 1;
    for j in 0..=radial {
        let r = inner + (outer - inner) * j as f64 / radial as f64;
        for i in 0..around {
            let a = phase + std::f64::consts::TAU * i as f64 / around as f64;
            mesh.add_node(tag(i, j), [r * a.cos(), r * a.sin(), 0.0])?;
        }
    }
    for j in 0..radial {
        for i in 0..around {
            // (r, a) -> (r + dr, a) -> (r + dr, a + da) -> (r, a + da): counter-clockwise.
            mesh.add_cell(
                &QUAD4,
                &[tag(i, j), tag(i, j + 1), tag(i + 1, j + 1), tag(i + 1, j)],
            )?;
        }
    }
    Ok(mesh)
}
