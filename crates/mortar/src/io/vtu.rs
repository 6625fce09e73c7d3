//! VTU output for ParaView: ASCII XML `UnstructuredGrid` files of volume meshes with nodal
//! fields (point data), every body in one `<Piece>` (told apart by the cell field `piece`).
//!
//! A small writer of our own rather than the `vtkio` crate, whose last stable release dates
//! from 2021 (its 0.7 has stayed a release candidate) and which brings XML and compression
//! dependencies this needs none of. Keep all VTK knowledge in this module.
//!
//! Cell types, by the cell's Gmsh type (so a program's own cell of one of these types is
//! written too): Tri3 -> `VTK_TRIANGLE` (5), Quad4 -> `VTK_QUAD` (9), Tet4 -> `VTK_TETRA` (10),
//! Hex8 -> `VTK_HEXAHEDRON` (12), Tri6 -> `VTK_QUADRATIC_TRIANGLE` (22), Quad9 ->
//! `VTK_BIQUADRATIC_QUAD` (28), Quad8 -> `VTK_QUADRATIC_QUAD` (23), Tet10 ->
//! `VTK_QUADRATIC_TETRA` (24), Hex20 -> `VTK_QUADRATIC_HEXAHEDRON` (25), Hex27 ->
//! `VTK_TRIQUADRATIC_HEXAHEDRON` (29). The Gmsh node order of the 2D ones is VTK's; the 3D
//! second-order ones number their edge (and face) nodes differently and are permuted
//! (`vtk_order`). A cell of any other type (a program's own cubic triangle, say) is written
//! as the linear cell of its corners, its first nodes as in Gmsh's order (VTK's triangle,
//! quad, tetrahedron or hexahedron): every node and its values are still in the file, the
//! cell is drawn with straight edges.
//!
//! ```
//! use mortar::io::vtu::{write_vtu, VtuPiece};
//! use mortar::generate::{rectangle_mesh, CellShape};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let mesh = rectangle_mesh([0.0, 0.0], [1.0, 1.0], [2, 2], CellShape::Simplex, 1)?;
//! let t: Vec<f64> = mesh.coords().iter().map(|x| x.x + x.y).collect();
//! let path = std::env::temp_dir().join(format!("mortar-vtu-doc-{}.vtu", std::process::id()));
//! write_vtu(&path, &[VtuPiece { mesh: &mesh, point_data: vec![("temperature", &t)] }])?;
//! assert!(std::fs::read_to_string(&path)?.contains("NumberOfCells=\"8\""));
//! # std::fs::remove_file(&path)?;
//! # Ok(()) }
//! ```

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use mortar_core::element::{ElementRef, ReferenceDomain};
use mortar_fem::element::VolumeDomain;
use mortar_fem::mesh::VolumeMesh;

use super::IoError;

/// One body of a VTU file: its mesh and its nodal fields (name, one value per mesh node).
#[derive(Debug, Clone)]
pub struct VtuPiece<'a> {
    /// The mesh.
    pub mesh: &'a VolumeMesh,
    /// Nodal fields: name and values by mesh node index.
    pub point_data: Vec<(&'a str, &'a [f64])>,
}

/// The VTK cell type of a volume element, by its Gmsh type: those whose Gmsh node order is
/// VTK's (a program's own cell of one of these types is written too).
fn vtk_type(gmsh_type: Option<u32>) -> Option<u8> {
    match gmsh_type? {
        2 => Some(5),   // Tri3: VTK_TRIANGLE
        3 => Some(9),   // Quad4: VTK_QUAD
        4 => Some(10),  // Tet4: VTK_TETRA
        5 => Some(12),  // Hex8: VTK_HEXAHEDRON
        9 => Some(22),  // Tri6: VTK_QUADRATIC_TRIANGLE
        10 => Some(28), // Quad9: VTK_BIQUADRATIC_QUAD
        16 => Some(23), // Quad8: VTK_QUADRATIC_QUAD
        11 => Some(24), // Tet10: VTK_QUADRATIC_TETRA
        17 => Some(25), // Hex20: VTK_QUADRATIC_HEXAHEDRON
        12 => Some(29), // Hex27: VTK_TRIQUADRATIC_HEXAHEDRON
        _ => None,
    }
}

/// For the cell types whose VTK node order differs from Gmsh's: the Gmsh node at each VTK
/// position. VTK numbers a tetrahedron's edges 01 12 02 03 13 23 (Gmsh: 01 12 20 30 32 31), a
/// hexahedron's edges round the bottom, round the top, then the verticals (Gmsh: 01 03 04 12
/// 15 23 26 37 45 47 56 67), and its face centres -x +x -y +y -z +z (Gmsh: -z -y -x +x +y +z).
fn vtk_order(gmsh_type: Option<u32>) -> Option<&'static [usize]> {
    const HEX20: [usize; 20] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
    ];
    match gmsh_type? {
        11 => Some(&[0, 1, 2, 3, 4, 5, 6, 7, 9, 8]),
        17 => Some(&HEX20),
        12 => Some(&[
            0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15, 22, 23, 21, 24,
            20, 25, 26,
        ]),
        _ => None,
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The VTU document of `pieces`, written as one VTK piece holding every body (readers such
/// as meshio keep only the first of several pieces): nodes and cells of the bodies one after
/// the other, a cell field `piece` (the body's index) to tell them apart, and each nodal field
/// over all bodies (`NaN` on the nodes of a body that does not have it).
///
/// # Errors
/// [`IoError::Write`] (kind `InvalidInput`) naming the cell or field: an element without a
/// VTK cell type, or a field whose length is not the piece's node count.
pub fn vtu_string(path: &Path, pieces: &[VtuPiece<'_>]) -> Result<String, IoError> {
    vtu_string_with_vectors(path, pieces, &[])
}

/// [`vtu_string`] with vector point data besides the scalar fields: each `(name, values)` of
/// `vectors` has one slice per piece of `3 * nodes` values (`node * 3 + k`), written as one
/// `NumberOfComponents="3"` array.
///
/// # Errors
/// As [`vtu_string`], and for a vector field of the wrong length or piece count.
pub fn vtu_string_with_vectors(
    path: &Path,
    pieces: &[VtuPiece<'_>],
    vectors: &[(&str, Vec<&[f64]>)],
) -> Result<String, IoError> {
    let invalid = |message: String| IoError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, message),
    };
    let names = field_names(pieces, vectors).map_err(invalid)?;
    let nn: usize = pieces.iter().map(|p| p.mesh.node_count()).sum();
    let nc: usize = pieces.iter().map(|p| p.mesh.cell_count()).sum();
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
    );
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{nn}\" NumberOfCells=\"{nc}\">"
    );
    match names.first() {
        Some(name) => {
            let _ = writeln!(s, "      <PointData Scalars=\"{}\">", escape(name));
        }
        None => s.push_str("      <PointData>\n"),
    }
    for name in &names {
        let _ = writeln!(
            s,
            "        <DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">",
            escape(name)
        );
        let values = pieces.iter().flat_map(|piece| {
            let field = piece.point_data.iter().find(|(n, _)| n == name);
            (0..piece.mesh.node_count()).map(move |i| field.map_or(f64::NAN, |(_, v)| v[i]))
        });
        write_values(&mut s, values.map(|v| format!("{v:e}")));
        s.push_str("        </DataArray>\n");
    }
    for (name, values) in vectors {
        let _ = writeln!(
            s,
            "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" format=\"ascii\">",
            escape(name)
        );
        write_values(
            &mut s,
            values
                .iter()
                .flat_map(|v| v.iter().map(|x| format!("{x:e}"))),
        );
        s.push_str("        </DataArray>\n");
    }
    s.push_str("      </PointData>\n      <CellData Scalars=\"piece\">\n");
    s.push_str("        <DataArray type=\"Int32\" Name=\"piece\" format=\"ascii\">\n");
    write_values(
        &mut s,
        pieces
            .iter()
            .enumerate()
            .flat_map(|(p, piece)| (0..piece.mesh.cell_count()).map(move |_| p.to_string())),
    );
    s.push_str("        </DataArray>\n      </CellData>\n      <Points>\n");
    s.push_str("        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    write_values(
        &mut s,
        pieces.iter().flat_map(|piece| {
            piece
                .mesh
                .coords()
                .iter()
                .map(|x| format!("{:e} {:e} {:e}", x.x, x.y, x.z))
        }),
    );
    s.push_str("        </DataArray>\n      </Points>\n      <Cells>\n");
    let (types, offsets, conn) = cell_arrays(pieces, nc).map_err(invalid)?;
    s.push_str("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    write_values(&mut s, conn.into_iter());
    s.push_str("        </DataArray>\n");
    s.push_str("        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    write_values(&mut s, offsets.iter().map(|o| o.to_string()));
    s.push_str("        </DataArray>\n");
    s.push_str("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    write_values(&mut s, types.iter().map(|t| t.to_string()));
    s.push_str("        </DataArray>\n      </Cells>\n    </Piece>\n");
    s.push_str("  </UnstructuredGrid>\n</VTKFile>\n");
    Ok(s)
}

/// The scalar fields' names in order of first appearance, after checking every field's
/// length against its piece (a message naming the piece and the field otherwise).
fn field_names<'a>(
    pieces: &[VtuPiece<'a>],
    vectors: &[(&str, Vec<&[f64]>)],
) -> Result<Vec<&'a str>, String> {
    let invalid = |message: String| message;
    let mut names: Vec<&str> = Vec::new();
    for (p, piece) in pieces.iter().enumerate() {
        for (name, values) in &piece.point_data {
            if values.len() != piece.mesh.node_count() {
                return Err(invalid(format!(
                    "piece {p}: field {name:?} has {} values for {} nodes",
                    values.len(),
                    piece.mesh.node_count()
                )));
            }
            if !names.contains(name) {
                names.push(name);
            }
        }
    }
    for (name, values) in vectors {
        if values.len() != pieces.len() {
            return Err(invalid(format!(
                "vector field {name:?} has {} pieces for {}",
                values.len(),
                pieces.len()
            )));
        }
        for (p, (v, piece)) in values.iter().zip(pieces).enumerate() {
            if v.len() != 3 * piece.mesh.node_count() {
                return Err(invalid(format!(
                    "piece {p}: vector field {name:?} has {} values for 3 x {} nodes",
                    v.len(),
                    piece.mesh.node_count()
                )));
            }
        }
    }
    Ok(names)
}

/// The VTK cell types, offsets and connectivity of all pieces' cells (the nodes numbered
/// across pieces), `nc` cells in all; a message naming the piece and cell for a cell of
/// fewer nodes than its corners.
fn cell_arrays(pieces: &[VtuPiece<'_>], nc: usize) -> Result<CellArrays, String> {
    let invalid = |message: String| message;
    let mut types = Vec::with_capacity(nc);
    let mut offsets = Vec::with_capacity(nc);
    let mut conn = Vec::new();
    let mut first_node = 0usize;
    for (p, piece) in pieces.iter().enumerate() {
        let mesh = piece.mesh;
        for c in 0..mesh.cell_count() {
            let cell = mesh.cell(c);
            let node = |n: u32| (first_node + n as usize).to_string();
            match vtk_type(cell.element.gmsh_type()) {
                Some(t) => {
                    types.push(t);
                    match vtk_order(cell.element.gmsh_type()) {
                        Some(order) => conn.extend(order.iter().map(|&i| node(cell.nodes[i]))),
                        None => conn.extend(cell.nodes.iter().map(|&n| node(n))),
                    }
                }
                None => {
                    // The linear cell of the corners.
                    let (t, corners) = match cell.element.domain() {
                        VolumeDomain::Triangle => (5, 3),
                        VolumeDomain::Quadrilateral => (9, 4),
                        VolumeDomain::Tetrahedron => (10, 4),
                        VolumeDomain::Hexahedron => (12, 8),
                    };
                    if cell.nodes.len() < corners {
                        return Err(invalid(format!(
                            "piece {p}: cell {} is a {} of {} nodes, fewer than its corners",
                            cell.tag,
                            cell.element.name(),
                            cell.nodes.len()
                        )));
                    }
                    types.push(t);
                    conn.extend(cell.nodes[..corners].iter().map(|&n| node(n)));
                }
            }
            offsets.push(conn.len());
        }
        first_node += mesh.node_count();
    }
    Ok((types, offsets, conn))
}

/// VTK's cell types, offsets and connectivity (as text).
type CellArrays = (Vec<u8>, Vec<usize>, Vec<String>);

/// The VTK cell type of a surface element, by its Gmsh type (whose node order is VTK's for
/// each of these): Line2 -> `VTK_LINE` (3), Line3 -> `VTK_QUADRATIC_EDGE` (21), Tri3 ->
/// `VTK_TRIANGLE` (5), Tri6 -> `VTK_QUADRATIC_TRIANGLE` (22), Quad4 -> `VTK_QUAD` (9), Quad8 ->
/// `VTK_QUADRATIC_QUAD` (23), Quad9 -> `VTK_BIQUADRATIC_QUAD` (28).
fn vtk_surface_type(gmsh_type: Option<u32>) -> Option<u8> {
    match gmsh_type? {
        1 => Some(3),
        8 => Some(21),
        2 => Some(5),
        9 => Some(22),
        3 => Some(9),
        16 => Some(23),
        10 => Some(28),
        _ => None,
    }
}

/// The VTU document of a surface: `points`, `cells` (each its surface element and its node
/// indices into `points`, in the element's order) and nodal scalar fields.
///
/// Each cell is written with the VTK type of its element (see `vtk_surface_type`: the
/// quadratic edge, triangle and quads of second-order faces included); a cell of another
/// element (a program's own cubic line, say) as the linear cell of its corners (`VTK_LINE`,
/// `VTK_TRIANGLE` or `VTK_QUAD`), its other nodes still in the file.
///
/// # Errors
/// [`IoError::Write`] (kind `InvalidInput`) for a cell whose node count is not its element's,
/// a node index out of range or a field of the wrong length.
pub fn surface_vtu_string(
    path: &Path,
    points: &[nalgebra::Vector3<f64>],
    cells: &[(ElementRef, Vec<u32>)],
    point_data: &[(&str, &[f64])],
) -> Result<String, IoError> {
    let invalid = |message: String| IoError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, message),
    };
    let mut types = Vec::with_capacity(cells.len());
    let mut conn: Vec<&[u32]> = Vec::with_capacity(cells.len());
    for (c, (element, nodes)) in cells.iter().enumerate() {
        if nodes.len() != element.node_count() {
            return Err(invalid(format!(
                "surface cell {c} is a {} of {} nodes, given {}",
                element.name(),
                element.node_count(),
                nodes.len()
            )));
        }
        match vtk_surface_type(element.gmsh_type()) {
            Some(t) => {
                types.push(t);
                conn.push(nodes);
            }
            None => {
                let corners = element.corner_count();
                types.push(match element.domain() {
                    ReferenceDomain::Line => 3,
                    ReferenceDomain::Triangle => 5,
                    ReferenceDomain::Quadrilateral => 9,
                });
                conn.push(&nodes[..corners]);
            }
        }
        if let Some(n) = nodes.iter().find(|&&n| n as usize >= points.len()) {
            return Err(invalid(format!(
                "surface cell {c}: node {n} of {}",
                points.len()
            )));
        }
    }
    for (name, values) in point_data {
        if values.len() != points.len() {
            return Err(invalid(format!(
                "field {name:?} has {} values for {} nodes",
                values.len(),
                points.len()
            )));
        }
    }
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
    );
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        points.len(),
        cells.len()
    );
    s.push_str("      <PointData>\n");
    for (name, values) in point_data {
        let _ = writeln!(
            s,
            "        <DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">",
            escape(name)
        );
        write_values(&mut s, values.iter().map(|v| format!("{v:e}")));
        s.push_str("        </DataArray>\n");
    }
    s.push_str("      </PointData>\n      <Points>\n");
    s.push_str("        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    write_values(
        &mut s,
        points
            .iter()
            .map(|x| format!("{:e} {:e} {:e}", x.x, x.y, x.z)),
    );
    s.push_str("        </DataArray>\n      </Points>\n      <Cells>\n");
    s.push_str("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    write_values(
        &mut s,
        conn.iter().copied().flatten().map(|n| n.to_string()),
    );
    s.push_str("        </DataArray>\n");
    s.push_str("        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    write_values(
        &mut s,
        conn.iter().scan(0usize, |o, c| {
            *o += c.len();
            Some(o.to_string())
        }),
    );
    s.push_str("        </DataArray>\n");
    s.push_str("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    write_values(&mut s, types.iter().map(|t: &u8| t.to_string()));
    s.push_str("        </DataArray>\n      </Cells>\n    </Piece>\n");
    s.push_str("  </UnstructuredGrid>\n</VTKFile>\n");
    Ok(s)
}

/// Values, several per line.
fn write_values(s: &mut String, values: impl Iterator<Item = String>) {
    for (i, v) in values.enumerate() {
        s.push_str(if i % 6 == 0 { "          " } else { " " });
        s.push_str(&v);
        if i % 6 == 5 {
            s.push('\n');
        }
    }
    if !s.ends_with('\n') {
        s.push('\n');
    }
}

/// Writes `pieces` to `path` as an ASCII VTU file (see [`vtu_string`]).
///
/// # Errors
/// [`IoError::Write`] if the file cannot be written, or as [`vtu_string`].
pub fn write_vtu(path: &Path, pieces: &[VtuPiece<'_>]) -> Result<(), IoError> {
    let text = vtu_string(path, pieces)?;
    let write = |source| IoError::Write {
        path: path.to_path_buf(),
        source,
    };
    let mut f = std::fs::File::create(path).map_err(write)?;
    f.write_all(text.as_bytes()).map_err(write)?;
    f.flush().map_err(write)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{box_mesh, CellShape};

    #[test]
    /// Two bodies go in one `<Piece>`: meshio 5.3 reads only the first of several pieces, so
    /// two pieces would lose the second body. One piece holds both, node indices of the
    /// second body shifted past the first's, and a field one body lacks is NaN there.
    fn bodies_in_one_piece_counts_and_errors() {
        let a = box_mesh([0.0; 3], [1.0; 3], [1, 1, 2], CellShape::Tensor, 1).unwrap();
        let b = box_mesh(
            [1.0, 0.0, 0.0],
            [2.0, 1.0, 1.0],
            [1, 1, 1],
            CellShape::Simplex,
            1,
        )
        .unwrap();
        let ta = vec![1.5; a.node_count()];
        let tb = vec![f64::NAN; b.node_count()];
        let path = Path::new("unused.vtu");
        let s = vtu_string(
            path,
            &[
                VtuPiece {
                    mesh: &a,
                    point_data: vec![("T <\"x\">", &ta)],
                },
                VtuPiece {
                    mesh: &b,
                    point_data: vec![("T <\"x\">", &tb)],
                },
            ],
        )
        .unwrap();
        assert_eq!(s.matches("<Piece ").count(), 1);
        assert!(s.contains("NumberOfPoints=\"20\" NumberOfCells=\"8\""));
        // The piece field: 2 cells of body 0, 6 of body 1.
        assert!(s.contains("          0 0 1 1 1 1\n          1 1\n"), "{s}");
        // The last tetrahedron's nodes are those of the second body: indices 12 to 19.
        let conn = s
            .split("Name=\"connectivity\" format=\"ascii\">\n")
            .nth(1)
            .and_then(|r| r.split("</DataArray>").next())
            .unwrap();
        let ids: Vec<usize> = conn
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(ids.len(), 2 * 8 + 6 * 4);
        assert!(ids[..16].iter().all(|&i| i < 12));
        assert!(ids[16..].iter().all(|&i| (12..20).contains(&i)));
        let two_fields = vtu_string(
            path,
            &[
                VtuPiece {
                    mesh: &a,
                    point_data: vec![("T", &ta)],
                },
                VtuPiece {
                    mesh: &b,
                    point_data: vec![],
                },
            ],
        )
        .unwrap();
        assert_eq!(
            two_fields.matches("NaN").count(),
            8,
            "the second body has no T"
        );
        assert!(s.contains("Name=\"T &lt;&quot;x&quot;&gt;\""));
        assert!(s.contains(" 12 12\n") || s.contains(" 12 12 "), "hexahedra");
        let short = vec![0.0; 3];
        let err = vtu_string(
            path,
            &[VtuPiece {
                mesh: &a,
                point_data: vec![("T", &short)],
            }],
        )
        .unwrap_err();
        assert!(err.to_string().contains("3 values for 12 nodes"), "{err}");
    }
}
