//! An octant of a ball refined towards one point of its sphere: the sphere of a 3D Hertz
//! contact, cut along its three planes of symmetry (two vertical, and the equator).

use mortar_elements::volume::HEX8;
use mortar_fem::mesh::{VolumeMesh, VolumeMeshError};
use nalgebra::Vector3;

use super::volume::grading_map;

/// The lower octant of the ball of radius `radius` centred at `centre` (`x >= centre[0]`,
/// `y >= centre[1]`, `z <= centre[2]`), refined towards its pole
/// `(centre[0], centre[1], centre[2] - radius)` (where the ball touches a plane below it):
/// `n x n x n` Hex8 cells, every one positively oriented. Nodes are tagged from
/// `first_node_tag`, cells from 1.
///
/// One structured block: the unit cube `q = (u, v, w) in [0, 1]^3` on the tensor grid
/// `u_i = f(i / n)`, `v_j = f(j / n)`, `w_k = 1 - f(1 - k / n)`, with the grading map
/// `f(s) = (g^s - 1) / (g - 1)` of [`graded_points`](super::graded_points) (`g = grading`:
/// the cells grow by `g^(1/n)` from one to the next, away from `u = 0`, `v = 0` and towards
/// `w = 0`), is mapped to the octant by the radial projection
/// `p = q |q|_inf / |q|_2`, `x = centre + radius (p_x, p_y, -p_z)`. The projection takes the
/// cube's faces `u = 1`, `v = 1` and `w = 1` to the sphere (to round-off), `w = 1` to the cap
/// around the pole where it is smooth (`|q|_inf = w` for `u, v < w`: the gnomonic map
/// `x = centre + radius (u, v, -1) / sqrt(1 + u^2 + v^2)` on `w = 1`), and the faces `u = 0`,
/// `v = 0`, `w = 0` exactly to the planes `x = centre[0]`, `y = centre[1]`, `z = centre[2]`.
/// At the pole the cells are near cubes of side `radius f(1 / n)`, about
/// `radius ln(g) / ((g - 1) n)` (`radius / n` for `g = 1`); doubling `n` splits the grid's cells in eight (nested grids,
/// the projection applied to the finer grid).
///
/// The projection is only Lipschitz where two components of `q` are equal and largest (on the
/// planes `u = w`, `v = w`, `u = v` away from the pole), where the cells fold slightly but
/// stay positively oriented for gradings up to 100 at least (checked by the tests).
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for a radius that is not positive and finite, a non-finite
/// centre, zero cells, or a grading that is not finite and at least 1.
pub fn ball_octant_mesh(
    radius: f64,
    centre: [f64; 3],
    n: usize,
    grading: f64,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    let bad = |reason: String| VolumeMeshError::BadCell {
        cell: 0,
        element: "ball octant mesh",
        reason,
    };
    if !(radius > 0.0 && radius.is_finite()) {
        return Err(bad(format!("radius {radius} is not positive and finite")));
    }
    if !centre.iter().all(|c| c.is_finite()) {
        return Err(bad(format!("centre {centre:?} is not finite")));
    }
    if n == 0 {
        return Err(bad("needs at least one cell per direction".into()));
    }
    if !(grading >= 1.0 && grading.is_finite()) {
        return Err(bad(format!(
            "grading {grading} is not finite and at least 1"
        )));
    }
    let t: Vec<f64> = (0..=n)
        .map(|i| match i {
            0 => 0.0,
            i if i == n => 1.0,
            i => grading_map(i as f64 / n as f64, grading),
        })
        .collect();
    let (uv, w): (&[f64], Vec<f64>) = (&t, (0..=n).map(|k| 1.0 - t[n - k]).collect());
    let c = Vector3::from(centre);
    let id =
        |i: usize, j: usize, k: usize| first_node_tag + (i + (n + 1) * (j + (n + 1) * k)) as u64;
    let mut m = VolumeMesh::new();
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                let q = Vector3::new(uv[i], uv[j], w[k]);
                let norm = q.norm();
                let p = if norm > 0.0 { q * (q.amax() / norm) } else { q };
                let x = c + radius * Vector3::new(p.x, p.y, -p.z);
                m.add_node(id(i, j, k), x.into())?;
            }
        }
    }
    // The map mirrors z: the tensor order with the two k layers swapped is positive.
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                m.add_cell(
                    &HEX8,
                    &[
                        id(i, j, k + 1),
                        id(i + 1, j, k + 1),
                        id(i + 1, j + 1, k + 1),
                        id(i, j + 1, k + 1),
                        id(i, j, k),
                        id(i + 1, j, k),
                        id(i + 1, j + 1, k),
                        id(i, j + 1, k),
                    ],
                )?;
            }
        }
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mortar_fem::element::VolumeElement;

    /// The smallest Jacobian determinant at the corners of any cell, over the cell's
    /// volume (a Hex8 is positively oriented, not folded, if it is positive at every corner).
    fn worst_corner_jacobian(m: &VolumeMesh) -> f64 {
        let mut worst = f64::INFINITY;
        for c in 0..m.cell_count() {
            let cell = m.cell(c);
            let x: Vec<Vector3<f64>> = cell.nodes.iter().map(|&n| m.coords()[n as usize]).collect();
            let centre = HEX8.jacobian(&x, &Vector3::zeros()).determinant();
            for xi in HEX8.node_reference_coords() {
                let d = HEX8.jacobian(&x, &Vector3::from(*xi)).determinant();
                worst = worst.min(d / centre.abs());
            }
        }
        worst
    }

    #[test]
    fn the_octant_is_positively_oriented_and_on_its_surfaces() {
        for (n, g) in [
            (1, 1.0),
            (4, 1.0),
            (8, 10.0),
            (12, 10.0),
            (16, 30.0),
            (6, 100.0),
        ] {
            let r = 2.0;
            let c = [1.0, -1.0, 3.0];
            let m = ball_octant_mesh(r, c, n, g, 7).unwrap();
            assert_eq!(m.cell_count(), n * n * n);
            assert_eq!(m.node_count(), (n + 1).pow(3));
            let worst = worst_corner_jacobian(&m);
            assert!(worst > 0.0, "n = {n}, g = {g}: {worst}");
            // The volume of the octant, to the faceting.
            let faces = m.boundary_faces().unwrap();
            let on_sphere =
                |x: &Vector3<f64>| ((x - Vector3::from(c)).norm() - r).abs() <= 1e-12 * r;
            let mut pole = false;
            for f in &faces {
                let x: Vec<Vector3<f64>> =
                    f.nodes.iter().map(|&k| m.coords()[k as usize]).collect();
                let flat = [
                    x.iter().all(|p| p.x == c[0]),
                    x.iter().all(|p| p.y == c[1]),
                    x.iter().all(|p| p.z == c[2]),
                ];
                assert!(
                    flat.iter().any(|&b| b) || x.iter().all(on_sphere),
                    "face {x:?}"
                );
                pole |= x
                    .iter()
                    .any(|p| (p - Vector3::new(c[0], c[1], c[2] - r)).norm() == 0.0);
            }
            assert!(pole);
        }
    }

    #[test]
    fn the_cells_at_the_pole_are_near_cubes() {
        let (n, g) = (12, 10.0);
        let m = ball_octant_mesh(1.0, [0.0, 0.0, 1.0], n, g, 1).unwrap();
        let h = (g.powf(1.0 / n as f64) - 1.0) / (g - 1.0);
        // The cell at the pole: the last layer in k, first in i and j.
        let x = |i: usize, j: usize, k: usize| m.coords()[i + (n + 1) * (j + (n + 1) * k)];
        let (p, a, b, up) = (x(0, 0, n), x(1, 0, n), x(0, 1, n), x(0, 0, n - 1));
        for e in [a - p, b - p, up - p] {
            assert!(
                (e.norm() / h - 1.0).abs() < 0.05,
                "{} against {h}",
                e.norm()
            );
        }
    }

    #[test]
    fn bad_input_is_refused() {
        assert!(ball_octant_mesh(0.0, [0.0; 3], 4, 1.0, 1).is_err());
        assert!(ball_octant_mesh(1.0, [f64::NAN, 0.0, 0.0], 4, 1.0, 1).is_err());
        assert!(ball_octant_mesh(1.0, [0.0; 3], 0, 1.0, 1).is_err());
        assert!(ball_octant_mesh(1.0, [0.0; 3], 4, 0.5, 1).is_err());
    }
}
