//! Structured volume meshes: rectangles and boxes of Quad4/Tri3 or Hex8/Tet4 cells, uniform
//! or graded (`CellShape`, `rectangle_mesh`, `box_mesh`, `graded_points`).

use mortar_elements::volume::{HEX8, QUAD4, TET4, TRI3};
use mortar_fem::mesh::{VolumeMesh, VolumeMeshError};

/// The cells of a structured volume mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CellShape {
    /// Triangles (2D: each square cut along its `(0,0)-(1,1)` diagonal) or tetrahedra (3D:
    /// six per cube, the Kuhn split along the main diagonal, conforming across cubes).
    Simplex,
    /// Quadrilaterals (2D) or hexahedra (3D).
    Tensor,
}

/// The rectangle `[lo, hi]` in the plane `z = 0` with `cells[0] x cells[1]` cells, Quad4 or
/// Tri3 (positively oriented). Nodes are tagged from `first_node_tag`, row by row from `lo`;
/// cells from 1.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for zero cells, or non-finite corners.
pub fn rectangle_mesh(
    lo: [f64; 2],
    hi: [f64; 2],
    cells: [usize; 2],
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    check_cells(&cells)?;
    let points = |d: usize| -> Vec<f64> {
        (0..=cells[d])
            .map(|i| lo[d] + (hi[d] - lo[d]) * i as f64 / cells[d] as f64)
            .collect()
    };
    tensor_rectangle(&points(0), &points(1), shape, first_node_tag)
}

/// The rectangle of the tensor grid `xs x ys` in the plane `z = 0` (each strictly increasing,
/// at least two points): `(xs.len() - 1) x (ys.len() - 1)` cells, Quad4 or Tri3 (positively
/// oriented, triangles cut along each cell's lower-left to upper-right diagonal). Nodes are
/// tagged from `first_node_tag`, row by row from `(xs[0], ys[0])`, x fastest; cells from 1.
/// With [`graded_points`] it makes a rectangle refined towards a side or a corner.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for fewer than two points in a direction, or points that are
/// not finite and strictly increasing.
pub fn grid_rectangle_mesh(
    xs: &[f64],
    ys: &[f64],
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    check_points(&[("x", xs), ("y", ys)])?;
    tensor_rectangle(xs, ys, shape, first_node_tag)
}

/// Each axis's points: at least two, finite and strictly increasing.
fn check_points(axes: &[(&str, &[f64])]) -> Result<(), VolumeMeshError> {
    for &(axis, p) in axes {
        if p.len() < 2 {
            return Err(grid_error(format!(
                "needs at least two {axis} points, got {}",
                p.len()
            )));
        }
        let increasing = |w: &[f64]| w[0].partial_cmp(&w[1]) == Some(std::cmp::Ordering::Less);
        if let Some(w) = p
            .windows(2)
            .find(|w| !increasing(w) || !w[0].is_finite() || !w[1].is_finite())
        {
            return Err(grid_error(format!(
                "the {axis} points must be finite and strictly increasing, got {} then {}",
                w[0], w[1]
            )));
        }
    }
    Ok(())
}

fn grid_error(reason: String) -> VolumeMeshError {
    VolumeMeshError::BadCell {
        cell: 0,
        element: "structured mesh",
        reason,
    }
}

/// `cells + 1` points from `start` to `end` (either way round), the cells growing
/// geometrically away from `start` by the factor `grading^(1 / cells)` from one to the next:
/// `x_i = start + (end - start) f(i / cells)` with `f(s) = (grading^s - 1) / (grading - 1)`
/// (`f(s) = s` for `grading = 1`, uniform). `f'(1) / f'(0) = grading`, so the last cell over
/// the first is `grading^((cells - 1) / cells)`, close to `grading`; and since the mapping
/// does not depend on `cells`, doubling `cells` splits every cell in two (the coarse points
/// are every other fine point), as uniform refinement would. The first and last points are
/// exactly `start` and `end`.
///
/// # Panics
/// If `cells` is zero or `grading` is not finite and at least 1 (a grading below 1 would
/// refine towards `end`: swap the ends instead).
pub fn graded_points(start: f64, end: f64, cells: usize, grading: f64) -> Vec<f64> {
    assert!(cells > 0, "graded_points: zero cells");
    assert!(
        grading >= 1.0 && grading.is_finite(),
        "graded_points: grading {grading} is not finite and at least 1"
    );
    (0..=cells)
        .map(|i| {
            if i == cells {
                end
            } else {
                start + (end - start) * grading_map(i as f64 / cells as f64, grading)
            }
        })
        .collect()
}

/// `f(s) = (g^s - 1) / (g - 1)` on `[0, 1]` (`s` for `g = 1`): `f(0) = 0`, `f(1) = 1`,
/// `f'(1) / f'(0) = g`.
pub(crate) fn grading_map(s: f64, g: f64) -> f64 {
    let l = g.ln();
    if l < 1e-12 {
        s
    } else {
        (s * l).exp_m1() / l.exp_m1()
    }
}

/// The tensor-grid rectangle (points checked by the caller).
fn tensor_rectangle(
    xs: &[f64],
    ys: &[f64],
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    let (nx, ny) = (xs.len() - 1, ys.len() - 1);
    let mut m = VolumeMesh::new();
    let id = |i: usize, j: usize| first_node_tag + (i + (nx + 1) * j) as u64;
    for (j, &y) in ys.iter().enumerate() {
        for (i, &x) in xs.iter().enumerate() {
            m.add_node(id(i, j), [x, y, 0.0])?;
        }
    }
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            match shape {
                CellShape::Tensor => {
                    m.add_cell(&QUAD4, &[a, b, c, d])?;
                }
                CellShape::Simplex => {
                    m.add_cell(&TRI3, &[a, b, c])?;
                    m.add_cell(&TRI3, &[a, c, d])?;
                }
            }
        }
    }
    Ok(m)
}

/// The box `[lo, hi]` with `cells[0] x cells[1] x cells[2]` cells, Hex8 or Tet4 (six per
/// cube, positively oriented). Nodes are tagged from `first_node_tag`, x fastest; cells from 1.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for zero cells, or non-finite corners.
pub fn box_mesh(
    lo: [f64; 3],
    hi: [f64; 3],
    cells: [usize; 3],
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    check_cells(&cells)?;
    let points = |d: usize| -> Vec<f64> {
        (0..=cells[d])
            .map(|i| lo[d] + (hi[d] - lo[d]) * (i as f64 / cells[d] as f64))
            .collect()
    };
    tensor_box(&[points(0), points(1), points(2)], shape, first_node_tag)
}

/// The box of the tensor grid `xs x ys x zs` (each strictly increasing, at least two points):
/// `(xs.len() - 1) x (ys.len() - 1) x (zs.len() - 1)` cells, Hex8 or Tet4 (six per cube, the
/// Kuhn split of [`box_mesh`]), positively oriented. Nodes are tagged from `first_node_tag`,
/// x fastest, then y, then z; cells from 1. With [`graded_points`] it makes a box refined
/// towards a face, an edge or a corner.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for fewer than two points in a direction, or points that are
/// not finite and strictly increasing.
pub fn grid_box_mesh(
    xs: &[f64],
    ys: &[f64],
    zs: &[f64],
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    check_points(&[("x", xs), ("y", ys), ("z", zs)])?;
    tensor_box(
        &[xs.to_vec(), ys.to_vec(), zs.to_vec()],
        shape,
        first_node_tag,
    )
}

/// The tensor-grid box (points checked by the caller).
fn tensor_box(
    points: &[Vec<f64>; 3],
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    let [xs, ys, zs] = points;
    let (nx, ny, nz) = (xs.len() - 1, ys.len() - 1, zs.len() - 1);
    let mut m = VolumeMesh::new();
    let id =
        |i: usize, j: usize, k: usize| first_node_tag + (i + (nx + 1) * (j + (ny + 1) * k)) as u64;
    for (k, &z) in zs.iter().enumerate() {
        for (j, &y) in ys.iter().enumerate() {
            for (i, &x) in xs.iter().enumerate() {
                m.add_node(id(i, j, k), [x, y, z])?;
            }
        }
    }
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let c = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                match shape {
                    CellShape::Tensor => {
                        m.add_cell(&HEX8, &c)?;
                    }
                    CellShape::Simplex => {
                        for t in KUHN {
                            m.add_cell(&TET4, &t.map(|a| c[a]))?;
                        }
                    }
                }
            }
        }
    }
    Ok(m)
}

/// The six tetrahedra of a cube (Gmsh hexahedron corner numbers) around its main diagonal
/// 0-6, each positively oriented.
const KUHN: [[usize; 4]; 6] = [
    [0, 1, 2, 6],
    [0, 2, 3, 6],
    [0, 3, 7, 6],
    [0, 7, 4, 6],
    [0, 4, 5, 6],
    [0, 5, 1, 6],
];

fn check_cells(cells: &[usize]) -> Result<(), VolumeMeshError> {
    if cells.contains(&0) {
        return Err(VolumeMeshError::BadCell {
            cell: 0,
            element: "structured mesh",
            reason: format!("needs at least one cell per direction, got {cells:?}"),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn graded_points_grow_from_the_start() {
        for (start, end) in [(0.0, 8.0), (0.0, -8.0), (1.0, 3.0)] {
            let p = graded_points(start, end, 10, 50.0);
            assert_eq!((p[0], p[10]), (start, end));
            let h: Vec<f64> = p.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
            let q = 50f64.powf(0.1);
            for w in h.windows(2) {
                assert!((w[1] / w[0] - q).abs() < 1e-12);
            }
            // Doubling the cells halves them (every other point is the coarse one).
            let fine = graded_points(start, end, 20, 50.0);
            for (i, x) in p.iter().enumerate() {
                assert!((fine[2 * i] - x).abs() < 1e-14 * end.abs().max(1.0));
            }
        }
        let uniform = graded_points(0.0, 1.0, 4, 1.0);
        assert_eq!(uniform, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    }

    #[test]
    fn grid_rectangle_matches_rectangle_and_checks_points() {
        let a = rectangle_mesh([0.0, -1.0], [2.0, 0.5], [3, 2], CellShape::Simplex, 5).unwrap();
        let xs: Vec<f64> = (0..=3).map(|i| 2.0 * i as f64 / 3.0).collect();
        let ys: Vec<f64> = (0..=2).map(|j| -1.0 + 1.5 * j as f64 / 2.0).collect();
        let b = grid_rectangle_mesh(&xs, &ys, CellShape::Simplex, 5).unwrap();
        assert_eq!(a.coords(), b.coords());
        assert_eq!(a.node_tags(), b.node_tags());
        assert_eq!(a.cell_count(), b.cell_count());
        for c in 0..a.cell_count() {
            assert_eq!(a.cell(c).nodes, b.cell(c).nodes);
        }
        let t = CellShape::Tensor;
        assert!(grid_rectangle_mesh(&[0.0], &[0.0, 1.0], t, 1).is_err());
        assert!(grid_rectangle_mesh(&[0.0, 1.0, 1.0], &[0.0, 1.0], t, 1).is_err());
        assert!(grid_rectangle_mesh(&[0.0, 1.0], &[1.0, 0.0], t, 1).is_err());
        assert!(grid_rectangle_mesh(&[f64::NEG_INFINITY, 1.0], &[0.0, 1.0], t, 1).is_err());
        assert!(grid_rectangle_mesh(&[0.0, f64::NAN], &[0.0, 1.0], t, 1).is_err());
    }

    #[test]
    fn grid_box_matches_box_and_checks_points() {
        for shape in [CellShape::Tensor, CellShape::Simplex] {
            let a = box_mesh([0.0, -1.0, 2.0], [2.0, 0.5, 3.0], [3, 2, 2], shape, 5).unwrap();
            let xs: Vec<f64> = (0..=3).map(|i| 2.0 * (i as f64 / 3.0)).collect();
            let ys: Vec<f64> = (0..=2).map(|j| -1.0 + 1.5 * (j as f64 / 2.0)).collect();
            let zs: Vec<f64> = (0..=2).map(|k| 2.0 + (k as f64 / 2.0)).collect();
            let b = grid_box_mesh(&xs, &ys, &zs, shape, 5).unwrap();
            assert_eq!(a.coords(), b.coords());
            assert_eq!(a.node_tags(), b.node_tags());
            assert_eq!(a.cell_count(), b.cell_count());
            for c in 0..a.cell_count() {
                assert_eq!(a.cell(c).nodes, b.cell(c).nodes);
            }
        }
        let t = CellShape::Tensor;
        let ok = [0.0, 1.0];
        assert!(grid_box_mesh(&ok, &ok, &[0.0], t, 1).is_err());
        assert!(grid_box_mesh(&ok, &ok, &[1.0, 0.0], t, 1).is_err());
        assert!(grid_box_mesh(&ok, &[0.0, f64::NAN], &ok, t, 1).is_err());
    }
}
