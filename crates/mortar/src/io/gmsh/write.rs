//! Writing surface meshes, and bodies with groups of their boundary faces, as Gmsh 4.1
//! files, ASCII or binary.

use std::collections::HashMap;
use std::path::Path;

use mortar_core::element::ReferenceDomain;
use mortar_core::SurfaceMesh;
use mortar_fem::mesh::{BoundaryFace, VolumeMesh};

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
    let mut parts = Vec::with_capacity(surfaces.len());
    for (mesh, name) in surfaces {
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
            let nodes = face
                .nodes
                .iter()
                .map(|&n| mesh.node_tags()[n as usize])
                .collect();
            push_element(&mut by_type, t, (face.tag, nodes));
        }
        let nodes = mesh
            .node_tags()
            .iter()
            .zip(mesh.coords())
            .map(|(&tag, x)| (tag, [x.x, x.y, x.z]))
            .collect();
        parts.push(Part {
            dim: dim.unwrap_or(2),
            name,
            blocks: by_type,
            nodes,
        });
    }
    parts_bytes(&parts, format)
}

/// Writes a body and named sets of its boundary faces into one Gmsh 4.1 file; see
/// [`msh41_volume_bytes`].
///
/// # Errors
/// As [`msh41_volume_bytes`]; [`IoError::Write`] if the file cannot be written.
pub fn write_msh41_volume(
    body: (&VolumeMesh, &str),
    face_groups: &[(&[BoundaryFace], &str)],
    path: impl AsRef<Path>,
    format: MshFormat,
) -> Result<(), IoError> {
    let bytes = msh41_volume_bytes(body, face_groups, format)?;
    let path = path.as_ref();
    std::fs::write(path, bytes).map_err(|source| IoError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// The bytes of a Gmsh 4.1 file holding a body `(mesh, name)` (its cells: entity and
/// physical group 1 of the body's dimension) and groups of its boundary faces (entity and physical
/// group `i + 2` of one dimension less, each named as given), such as the Dirichlet and
/// Neumann boundaries and the interface side of a scene. Node and cell tags are kept; face
/// elements are numbered after the largest cell tag, in order.
///
/// # Errors
/// [`IoError::Unwritable`] for a name with a quote or line break, a cell without a Gmsh
/// type, or a face index beyond the mesh.
pub fn msh41_volume_bytes(
    body: (&VolumeMesh, &str),
    face_groups: &[(&[BoundaryFace], &str)],
    format: MshFormat,
) -> Result<Vec<u8>, IoError> {
    let (mesh, name) = body;
    let unwritable = |reason: String| IoError::Unwritable { reason };
    let dim = mesh.dim().unwrap_or(3) as i32;
    let mut cells: Vec<Block> = Vec::new();
    let mut next_tag = 1;
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        let Some(t) = cell.element.gmsh_type() else {
            return Err(unwritable(format!(
                "cell {} of \"{name}\" is a {}, which has no Gmsh type",
                cell.tag,
                cell.element.name()
            )));
        };
        let nodes = cell
            .nodes
            .iter()
            .map(|&n| mesh.node_tags()[n as usize])
            .collect();
        push_element(&mut cells, t, (cell.tag, nodes));
        next_tag = next_tag.max(cell.tag + 1);
    }
    let all_nodes: Vec<(u64, [f64; 3])> = mesh
        .node_tags()
        .iter()
        .zip(mesh.coords())
        .map(|(&tag, x)| (tag, [x.x, x.y, x.z]))
        .collect();
    let mut parts = vec![Part {
        dim,
        name,
        blocks: cells,
        nodes: all_nodes,
    }];
    for (faces, group) in face_groups {
        let mut by_type: Vec<Block> = Vec::new();
        for f in faces.iter() {
            let Some(t) = f.element.gmsh_type() else {
                return Err(unwritable(format!(
                    "a face of \"{group}\" is a {}, which has no Gmsh type",
                    f.element.name()
                )));
            };
            let mut nodes = Vec::with_capacity(f.nodes.len());
            for &n in &f.nodes {
                match mesh.node_tags().get(n as usize) {
                    Some(&tag) => nodes.push(tag),
                    None => {
                        return Err(unwritable(format!(
                            "a face of \"{group}\" refers to node index {n}, beyond the mesh"
                        )))
                    }
                }
            }
            push_element(&mut by_type, t, (next_tag, nodes));
            next_tag += 1;
        }
        parts.push(Part {
            dim: dim - 1,
            name: group,
            blocks: by_type,
            nodes: Vec::new(),
        });
    }
    parts_bytes(&parts, format)
}

fn push_element(blocks: &mut Vec<Block>, t: u32, element: Element) {
    match blocks.iter_mut().find(|(ty, _)| *ty == t) {
        Some((_, list)) => list.push(element),
        None => blocks.push((t, vec![element])),
    }
}

/// One entity and physical group of a written file.
struct Part<'a> {
    dim: i32,
    name: &'a str,
    blocks: Vec<Block>,
    /// The nodes to write with this entity (nodes already written by an earlier part are
    /// skipped).
    nodes: Vec<(u64, [f64; 3])>,
}

/// Part `i` becomes entity `i + 1` of its dimension and physical group `i + 1`.
fn parts_bytes(parts: &[Part<'_>], format: MshFormat) -> Result<Vec<u8>, IoError> {
    let checked = CheckedParts::of(parts)?;
    let mut w = Writer::new(format);
    write_header(&mut w, parts, &checked.bboxes);
    write_nodes(&mut w, parts, &checked.own_nodes);
    write_elements(&mut w, parts, &checked.element_tags);
    Ok(w.buf)
}

/// What the parts of a file hold once checked: each part's nodes not written by an earlier
/// part, each part's bounding box, and the part of each element tag.
struct CheckedParts {
    own_nodes: Vec<Vec<(u64, [f64; 3])>>,
    bboxes: Vec<([f64; 3], [f64; 3])>,
    element_tags: HashMap<u64, usize>,
}

impl CheckedParts {
    /// Checks `parts`: names without quotes or line breaks, each element tag in one part,
    /// each node tag at one position.
    fn of(parts: &[Part<'_>]) -> Result<Self, IoError> {
        let unwritable = |reason: String| IoError::Unwritable { reason };
        let mut node_owner: HashMap<u64, [f64; 3]> = HashMap::new();
        let mut element_tags: HashMap<u64, usize> = HashMap::new();
        let mut own_nodes: Vec<Vec<(u64, [f64; 3])>> = Vec::with_capacity(parts.len());
        let mut bboxes = Vec::with_capacity(parts.len());
        for (s, part) in parts.iter().enumerate() {
            let name = part.name;
            if name.contains(['"', '\n', '\r']) {
                return Err(unwritable(format!(
                    "physical name {name:?} contains a quote or a line break"
                )));
            }
            for (_, list) in &part.blocks {
                for (tag, _) in list {
                    if let Some(other) = element_tags.insert(*tag, s) {
                        return Err(unwritable(format!(
                            "element tag {tag} is used by \"{}\" and \"{name}\"",
                            parts[other].name
                        )));
                    }
                }
            }
            let mut mine = Vec::new();
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            for &(tag, x) in &part.nodes {
                for k in 0..3 {
                    lo[k] = lo[k].min(x[k]);
                    hi[k] = hi[k].max(x[k]);
                }
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
            if part.nodes.is_empty() {
                (lo, hi) = ([0.0; 3], [0.0; 3]);
            }
            bboxes.push((lo, hi));
            own_nodes.push(mine);
        }
        Ok(Self {
            own_nodes,
            bboxes,
            element_tags,
        })
    }
}

/// The `$MeshFormat`, `$PhysicalNames` and `$Entities` sections.
fn write_header(w: &mut Writer, parts: &[Part<'_>], bboxes: &[([f64; 3], [f64; 3])]) {
    let format = w.format;
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
    w.text(&format!("{}\n", parts.len()));
    for (s, part) in parts.iter().enumerate() {
        w.text(&format!("{} {} \"{}\"\n", part.dim, s + 1, part.name));
    }
    w.text("$EndPhysicalNames\n$Entities\n");
    let count = |d: i32| parts.iter().filter(|p| p.dim == d).count();
    for n in [0, count(1), count(2), count(3)] {
        w.size(n as u64);
    }
    w.eol();
    for want in [1, 2, 3] {
        for (s, part) in parts.iter().enumerate() {
            if part.dim != want {
                continue;
            }
            w.int((s + 1) as i32);
            let (lo, hi) = bboxes[s];
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
}

/// The `$Nodes` section: each part's own nodes in its entity.
fn write_nodes(w: &mut Writer, parts: &[Part<'_>], own_nodes: &[Vec<(u64, [f64; 3])>]) {
    let total_nodes: usize = own_nodes.iter().map(Vec::len).sum();
    let (min_node, max_node) = min_max(own_nodes.iter().flatten().map(|n| n.0));
    w.text("$Nodes\n");
    for v in [parts.len() as u64, total_nodes as u64, min_node, max_node] {
        w.size(v);
    }
    w.eol();
    for (s, nodes) in own_nodes.iter().enumerate() {
        w.int(parts[s].dim);
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
}

/// The `$Elements` section: each part's blocks in its entity.
fn write_elements(w: &mut Writer, parts: &[Part<'_>], element_tags: &HashMap<u64, usize>) {
    let block_count: usize = parts.iter().map(|p| p.blocks.len()).sum();
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
    for (s, part) in parts.iter().enumerate() {
        for (t, list) in &part.blocks {
            w.int(part.dim);
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
