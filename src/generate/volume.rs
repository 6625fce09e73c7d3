use mortar_core::mesh::{VolumeMesh, VolumeMeshError};
use mortar_elements::volume::{HEX8, QUAD4, TET4, TRI3};

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
    let [nx, ny] = cells;
    check_cells(&cells)?;
    let mut m = VolumeMesh::new();
    let id = |i: usize, j: usize| first_node_tag + (i + (nx + 1) * j) as u64;
    for j in 0..=ny {
        for i in 0..=nx {
            let x = lo[0] + (hi[0] - lo[0]) * i as f64 / nx as f64;
            let y = lo[1] + (hi[1] - lo[1]) * j as f64 / ny as f64;
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
    let [nx, ny, nz] = cells;
    check_cells(&cells)?;
    let mut m = VolumeMesh::new();
    let id =
        |i: usize, j: usize, k: usize| first_node_tag + (i + (nx + 1) * (j + (ny + 1) * k)) as u64;
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let p = [
                    i as f64 / nx as f64,
                    j as f64 / ny as f64,
                    k as f64 / nz as f64,
                ];
                m.add_node(
                    id(i, j, k),
                    std::array::from_fn(|d| lo[d] + (hi[d] - lo[d]) * p[d]),
                )?;
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
