//! VTU output for ParaView: ASCII XML `UnstructuredGrid` files of volume meshes with nodal
//! fields (point data), one `<Piece>` per body.
//!
//! A small writer of our own rather than the `vtkio` crate, whose last stable release dates
//! from 2021 (its 0.7 has stayed a release candidate) and which brings XML and compression
//! dependencies this needs none of. Keep all VTK knowledge in this module.
//!
//! Cell types: Tri3 -> `VTK_TRIANGLE` (5), Quad4 -> `VTK_QUAD` (9), Tet4 -> `VTK_TETRA` (10),
//! Hex8 -> `VTK_HEXAHEDRON` (12); the Gmsh node order of these is VTK's.
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

use mortar_core::mesh::VolumeMesh;

use super::IoError;

/// One body of a VTU file: its mesh and its nodal fields (name, one value per mesh node).
#[derive(Debug, Clone)]
pub struct VtuPiece<'a> {
    /// The mesh.
    pub mesh: &'a VolumeMesh,
    /// Nodal fields: name and values by mesh node index.
    pub point_data: Vec<(&'a str, &'a [f64])>,
}

/// The VTK cell type of a volume element, by name.
fn vtk_type(name: &str) -> Option<u8> {
    match name {
        "Tri3" => Some(5),
        "Quad4" => Some(9),
        "Tet4" => Some(10),
        "Hex8" => Some(12),
        _ => None,
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The VTU document of `pieces` (each piece also gets a cell field `piece`: its index).
///
/// # Errors
/// [`IoError::Write`] (kind `InvalidInput`) naming the cell or field: an element without a
/// VTK cell type, or a field whose length is not the piece's node count.
pub fn vtu_string(path: &Path, pieces: &[VtuPiece<'_>]) -> Result<String, IoError> {
    let invalid = |message: String| IoError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, message),
    };
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
    );
    for (p, piece) in pieces.iter().enumerate() {
        let mesh = piece.mesh;
        let (nn, nc) = (mesh.node_count(), mesh.cell_count());
        let _ = writeln!(
            s,
            "    <Piece NumberOfPoints=\"{nn}\" NumberOfCells=\"{nc}\">"
        );
        let first = piece.point_data.first().map(|(n, _)| escape(n));
        match &first {
            Some(name) => {
                let _ = writeln!(s, "      <PointData Scalars=\"{name}\">");
            }
            None => s.push_str("      <PointData>\n"),
        }
        for (name, values) in &piece.point_data {
            if values.len() != nn {
                return Err(invalid(format!(
                    "piece {p}: field {name:?} has {} values for {nn} nodes",
                    values.len()
                )));
            }
            let _ = writeln!(
                s,
                "        <DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">",
                escape(name)
            );
            write_values(&mut s, values.iter().map(|v| format!("{v:e}")));
            s.push_str("        </DataArray>\n");
        }
        s.push_str("      </PointData>\n      <CellData Scalars=\"piece\">\n");
        s.push_str("        <DataArray type=\"Int32\" Name=\"piece\" format=\"ascii\">\n");
        write_values(&mut s, (0..nc).map(|_| p.to_string()));
        s.push_str("        </DataArray>\n      </CellData>\n      <Points>\n");
        s.push_str(
            "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
        );
        write_values(
            &mut s,
            mesh.coords()
                .iter()
                .map(|x| format!("{:e} {:e} {:e}", x.x, x.y, x.z)),
        );
        s.push_str("        </DataArray>\n      </Points>\n      <Cells>\n");
        let mut types = Vec::with_capacity(nc);
        let mut offsets = Vec::with_capacity(nc);
        let mut conn = Vec::new();
        for c in 0..nc {
            let cell = mesh.cell(c);
            let t = vtk_type(cell.element.name()).ok_or_else(|| {
                invalid(format!(
                    "piece {p}: cell {} is a {}, which has no VTK cell type here",
                    cell.tag,
                    cell.element.name()
                ))
            })?;
            types.push(t);
            conn.extend(cell.nodes.iter().map(|n| n.to_string()));
            offsets.push(conn.len());
        }
        s.push_str("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
        write_values(&mut s, conn.into_iter());
        s.push_str("        </DataArray>\n");
        s.push_str("        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
        write_values(&mut s, offsets.iter().map(|o| o.to_string()));
        s.push_str("        </DataArray>\n");
        s.push_str("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
        write_values(&mut s, types.iter().map(|t| t.to_string()));
        s.push_str("        </DataArray>\n      </Cells>\n    </Piece>\n");
    }
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
    fn pieces_counts_and_errors() {
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
        assert_eq!(s.matches("<Piece ").count(), 2);
        assert!(s.contains("NumberOfPoints=\"12\" NumberOfCells=\"2\""));
        assert!(s.contains("NumberOfPoints=\"8\" NumberOfCells=\"6\""));
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
