//! Writing surface meshes as Gmsh 4.1 files, ASCII or binary.

use std::collections::HashMap;
use std::path::Path;

use mortar_core::element::ReferenceDomain;
use mortar_core::SurfaceMesh;

use crate::io::error::IoError;

/// An element: its tag and node tags.
type Element = (u64, Vec<u64>);
/// An element block: the Gmsh type and its elements.
type Block = (u32, Vec<Element>);

/// Byte order of a binary file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Endianness {
    /// Least significant byte first (x86, ARM).
    Little,
    /// Most significant byte first.
    Big,
}

/// The encoding of a written MSH file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MshFormat {
    /// Text.
    Ascii,
    /// Binary with the given byte order (`size_t` of 8 bytes).
    Binary(Endianness),
}

/// Writes one surface mesh as a Gmsh 4.1 ASCII file: one entity and one physical group named
/// `physical_name`, node and element tags kept.
///
/// # Errors
/// As [`msh41_bytes`]; [`IoError::Write`] if the file cannot be written.
pub fn write_msh41_ascii(
    mesh: &SurfaceMesh,
    path: impl AsRef<Path>,
    physical_name: &str,
) -> Result<(), IoError> {
    write_msh41(&[(mesh, physical_name)], path, MshFormat::Ascii)
}

/// Writes one surface mesh as a Gmsh 4.1 binary file; see [`write_msh41_ascii`].
///
/// # Errors
/// As [`msh41_bytes`]; [`IoError::Write`] if the file cannot be written.
pub fn write_msh41_binary(
    mesh: &SurfaceMesh,
    path: impl AsRef<Path>,
    physical_name: &str,
    endianness: Endianness,
) -> Result<(), IoError> {
    write_msh41(
        &[(mesh, physical_name)],
        path,
        MshFormat::Binary(endianness),
    )
}

/// Writes several surfaces, each its own entity and physical group, into one Gmsh 4.1 file.
///
/// # Errors
/// As [`msh41_bytes`]; [`IoError::Write`] if the file cannot be written.
pub fn write_msh41(
    surfaces: &[(&SurfaceMesh, &str)],
    path: impl AsRef<Path>,
    format: MshFormat,
) -> Result<(), IoError> {
    let bytes = msh41_bytes(surfaces, format)?;
    let path = path.as_ref();
    std::fs::write(path, bytes).map_err(|source| IoError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// The bytes of a Gmsh 4.1 file holding `surfaces`: surface `i` becomes entity `i + 1` (a
/// curve for line meshes, a surface otherwise) and physical group `i + 1` with its name.
/// Node tags shared by several surfaces must have the same coordinates (the node is written
/// once); element tags must be unique over all surfaces.
///
/// # Errors
/// [`IoError::Unwritable`] for a name with a quote or line break, a face without a Gmsh type,
/// a node tag used with two positions, an element tag used twice, or a mesh of both lines and
/// faces.
pub fn msh41_bytes(
    surfaces: &[(&SurfaceMesh, &str)],
    format: MshFormat,
) -> Result<Vec<u8>, IoError> {
    let unwritable = |reason: String| IoError::Unwritable { reason };
    let mut dims = Vec::with_capacity(surfaces.len());
    let mut node_owner: HashMap<u64, [f64; 3]> = HashMap::new();
    let mut element_tags: HashMap<u64, usize> = HashMap::new();
    // Per surface: its nodes written here (tag, coordinates) and its element blocks.
    let mut own_nodes: Vec<Vec<(u64, [f64; 3])>> = Vec::with_capacity(surfaces.len());
    let mut blocks: Vec<Vec<Block>> = Vec::with_capacity(surfaces.len());
    for (s, (mesh, name)) in surfaces.iter().enumerate() {
        if name.contains(['"', '\n', '\r']) {
            return Err(unwritable(format!(
                "physical name {name:?} contains a quote or a line break"
            )));
        }
        let mut dim = None;
        let mut by_type: Vec<Block> = Vec::new();
        for f in 0..mesh.face_count() {
            let face = mesh.face(f);
            let d = if face.element.domain() == ReferenceDomain::Line {
                1
            } else {
                2
            };
            if *dim.get_or_insert(d) != d {
                return Err(unwritable(format!(
                    "surface \"{name}\" mixes lines and faces"
                )));
            }
            let Some(t) = face.element.gmsh_type() else {
                return Err(unwritable(format!(
                    "face {} of \"{name}\" is a {}, which has no Gmsh type",
                    face.tag,
                    face.element.name()
                )));
            };
            if let Some(other) = element_tags.insert(face.tag, s) {
                return Err(unwritable(format!(
                    "element tag {} is used by \"{}\" and \"{name}\"",
                    face.tag, surfaces[other].1
                )));
            }
            let nodes = face
                .nodes
                .iter()
                .map(|&n| mesh.node_tags()[n as usize])
                .collect();
            match by_type.iter_mut().find(|(ty, _)| *ty == t) {
                Some((_, list)) => list.push((face.tag, nodes)),
                None => by_type.push((t, vec![(face.tag, nodes)])),
            }
        }
        dims.push(dim.unwrap_or(2));
        blocks.push(by_type);
        let mut mine = Vec::new();
        for (&tag, x) in mesh.node_tags().iter().zip(mesh.coords()) {
            let x = [x.x, x.y, x.z];
            match node_owner.get(&tag) {
                Some(y) if y == &x => {}
                Some(_) => {
                    return Err(unwritable(format!(
                        "node tag {tag} has two positions (in \"{name}\" and an earlier surface)"
                    )))
                }
                None => {
                    node_owner.insert(tag, x);
                    mine.push((tag, x));
                }
            }
        }
        own_nodes.push(mine);
    }

    let mut w = Writer::new(format);
    w.text("$MeshFormat\n");
    match format {
        MshFormat::Ascii => w.text("4.1 0 8\n"),
        MshFormat::Binary(_) => {
            w.text("4.1 1 8\n");
            w.int(1);
            w.text("\n");
        }
    }
    w.text("$EndMeshFormat\n$PhysicalNames\n");
    w.text(&format!("{}\n", surfaces.len()));
    for (s, (_, name)) in surfaces.iter().enumerate() {
        w.text(&format!("{} {} \"{name}\"\n", dims[s], s + 1));
    }
    w.text("$EndPhysicalNames\n$Entities\n");
    let curves = dims.iter().filter(|&&d| d == 1).count();
    for n in [0, curves, surfaces.len() - curves, 0] {
        w.size(n as u64);
    }
    w.eol();
    for want in [1, 2] {
        for (s, (mesh, _)) in surfaces.iter().enumerate() {
            if dims[s] != want {
                continue;
            }
            w.int((s + 1) as i32);
            let (lo, hi) = mesh
                .bounding_box()
                .map(|(lo, hi)| ([lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z]))
                .unwrap_or_default();
            for v in lo.iter().chain(&hi) {
                w.float(*v);
            }
            w.size(1);
            w.int((s + 1) as i32);
            w.size(0);
            w.eol();
        }
    }
    w.end_section("Entities");

    let total_nodes: usize = own_nodes.iter().map(Vec::len).sum();
    let (min_node, max_node) = min_max(own_nodes.iter().flatten().map(|n| n.0));
    w.text("$Nodes\n");
    for v in [
        surfaces.len() as u64,
        total_nodes as u64,
        min_node,
        max_node,
    ] {
        w.size(v);
    }
    w.eol();
    for (s, nodes) in own_nodes.iter().enumerate() {
        w.int(dims[s]);
        w.int((s + 1) as i32);
        w.int(0);
        w.size(nodes.len() as u64);
        w.eol();
        for (tag, _) in nodes {
            w.size(*tag);
            w.eol();
        }
        for (_, x) in nodes {
            for c in x {
                w.float(*c);
            }
            w.eol();
        }
    }
    w.end_section("Nodes");

    let block_count: usize = blocks.iter().map(Vec::len).sum();
    let (min_el, max_el) = min_max(element_tags.keys().copied());
    w.text("$Elements\n");
    for v in [
        block_count as u64,
        element_tags.len() as u64,
        min_el,
        max_el,
    ] {
        w.size(v);
    }
    w.eol();
    for (s, by_type) in blocks.iter().enumerate() {
        for (t, list) in by_type {
            w.int(dims[s]);
            w.int((s + 1) as i32);
            w.int(*t as i32);
            w.size(list.len() as u64);
            w.eol();
            for (tag, nodes) in list {
                w.size(*tag);
                for n in nodes {
                    w.size(*n);
                }
                w.eol();
            }
        }
    }
    w.end_section("Elements");
    Ok(w.buf)
}

fn min_max(tags: impl Iterator<Item = u64>) -> (u64, u64) {
    tags.fold(None, |acc: Option<(u64, u64)>, t| match acc {
        None => Some((t, t)),
        Some((a, b)) => Some((a.min(t), b.max(t))),
    })
    .unwrap_or((0, 0))
}

/// Numbers as text (space-separated, one record per line) or as raw bytes.
struct Writer {
    buf: Vec<u8>,
    format: MshFormat,
    line_start: bool,
}

impl Writer {
    fn new(format: MshFormat) -> Self {
        Self {
            buf: Vec::new(),
            format,
            line_start: true,
        }
    }

    fn text(&mut self, s: &str) {
        self.buf.extend_from_slice(s.as_bytes());
        self.line_start = s.ends_with('\n');
    }

    fn field(&mut self, s: &str) {
        if !self.line_start {
            self.buf.push(b' ');
        }
        self.buf.extend_from_slice(s.as_bytes());
        self.line_start = false;
    }

    fn size(&mut self, v: u64) {
        match self.format {
            MshFormat::Ascii => self.field(&v.to_string()),
            MshFormat::Binary(Endianness::Little) => self.buf.extend_from_slice(&v.to_le_bytes()),
            MshFormat::Binary(Endianness::Big) => self.buf.extend_from_slice(&v.to_be_bytes()),
        }
    }

    fn int(&mut self, v: i32) {
        match self.format {
            MshFormat::Ascii => self.field(&v.to_string()),
            MshFormat::Binary(Endianness::Little) => self.buf.extend_from_slice(&v.to_le_bytes()),
            MshFormat::Binary(Endianness::Big) => self.buf.extend_from_slice(&v.to_be_bytes()),
        }
    }

    /// Shortest text that reads back to the same double.
    fn float(&mut self, v: f64) {
        match self.format {
            MshFormat::Ascii => {
                let a = v.abs();
                if a == 0.0 || (1e-4..1e15).contains(&a) {
                    self.field(&format!("{v}"))
                } else {
                    self.field(&format!("{v:e}"))
                }
            }
            MshFormat::Binary(Endianness::Little) => self.buf.extend_from_slice(&v.to_le_bytes()),
            MshFormat::Binary(Endianness::Big) => self.buf.extend_from_slice(&v.to_be_bytes()),
        }
    }

    fn eol(&mut self) {
        if self.format == MshFormat::Ascii {
            self.text("\n");
        }
    }

    fn end_section(&mut self, name: &str) {
        if self.format != MshFormat::Ascii {
            self.text("\n");
        }
        self.text(&format!("$End{name}\n"));
    }
}
