//! The sections of an MSH 4.1 file that a surface reader needs, ASCII or binary.
//!
//! Layout (Gmsh reference manual, "MSH file format", version 4.1): `$MeshFormat` first, then
//! any of `$PhysicalNames` (always text), `$Entities`, `$Nodes`, `$Elements`, and sections this
//! reader skips (`$Periodic`, `$NodeData`, ...). In binary files the data of `$Entities`,
//! `$Nodes` and `$Elements` is raw `int` (4 bytes), `size_t` (8 bytes) and `double`.

use std::collections::HashMap;

use super::cursor::{parse_token, quote, Cursor, Encoding};
use super::element_types;
use crate::io::error::IoError;

/// A named physical group (`$PhysicalNames`).
#[derive(Debug, Clone)]
pub(super) struct PhysicalName {
    pub dim: i32,
    pub tag: i32,
    pub name: String,
}

/// One entity block of `$Elements`.
#[derive(Debug, Clone)]
pub(super) struct ElementBlock {
    pub dim: i32,
    pub entity: i32,
    pub element_type: i32,
    /// Elements in the block.
    pub count: usize,
    /// Whether the caller keeps the block (see [`Keep`]): then tags, positions and nodes are
    /// kept.
    pub kept: bool,
    /// Element tags (all of them if kept, else only the first).
    pub tags: Vec<u64>,
    /// Byte positions of the elements (as `tags`).
    pub positions: Vec<usize>,
    /// Node tags, `nodes_per_element` per element.
    pub nodes: Vec<u64>,
    pub nodes_per_element: usize,
}

/// The parts of an MSH file the surface reader needs.
#[derive(Debug, Default)]
pub(super) struct MshData {
    pub physical_names: Vec<PhysicalName>,
    /// Physical tags of each entity, by `(dimension, tag)`; `None` without `$Entities`.
    pub entities: Option<HashMap<(i32, i32), Vec<i32>>>,
    /// Node tag to index into `coords` and `node_positions`.
    pub node_index: HashMap<u64, usize>,
    pub coords: Vec<[f64; 3]>,
    /// Byte position of each node's coordinates.
    pub node_positions: Vec<usize>,
    pub blocks: Vec<ElementBlock>,
}

/// Which element blocks to keep: given a block's dimension and Gmsh element type, `Some(n)`
/// (the type's node count) to keep its elements, `None` to skip them.
pub(super) type Keep<'a> = &'a dyn Fn(i32, i32) -> Option<usize>;

/// Parses the whole file.
pub(super) fn parse(cur: &mut Cursor<'_>, keep: Keep<'_>) -> Result<MshData, IoError> {
    parse_mesh_format(cur)?;
    let mut data = MshData::default();
    loop {
        cur.skip_whitespace();
        if cur.at_end() {
            break;
        }
        let (pos, line) = cur.line();
        let header = String::from_utf8_lossy(line).trim().to_string();
        match header.as_str() {
            "$PhysicalNames" => parse_physical_names(cur, &mut data)?,
            "$Entities" => parse_entities(cur, &mut data)?,
            "$Nodes" => parse_nodes(cur, &mut data)?,
            "$Elements" => parse_elements(cur, &mut data, keep)?,
            "$MeshFormat" => {
                return Err(cur.malformed(pos, "a second $MeshFormat section"));
            }
            h if h.starts_with('$')
                && !h.starts_with("$End")
                && !h.contains(char::is_whitespace) =>
            {
                cur.skip_section(&h[1..])?
            }
            _ => {
                return Err(cur.malformed(
                    pos,
                    format!(
                        "expected a section header such as $Nodes, found {}",
                        quote(line)
                    ),
                ))
            }
        }
    }
    Ok(data)
}

/// `$MeshFormat`: version 4.1, file type 0 (ASCII) or 1 (binary), data size 8; in binary
/// files followed by the `int` 1 that gives the byte order.
fn parse_mesh_format(cur: &mut Cursor<'_>) -> Result<(), IoError> {
    cur.skip_whitespace();
    let (pos, first) = cur.line();
    if first.trim_ascii() != b"$MeshFormat" {
        return Err(cur.malformed(
            pos,
            format!(
                "not a Gmsh MSH file: expected $MeshFormat, found {}",
                quote(first)
            ),
        ));
    }
    cur.skip_whitespace();
    let (pos, line) = cur.line();
    let fields: Vec<&[u8]> = line
        .split(|b| b.is_ascii_whitespace())
        .filter(|f| !f.is_empty())
        .collect();
    let Some(&version) = fields.first() else {
        return Err(if cur.at_end() {
            cur.truncated("the $MeshFormat section")
        } else {
            cur.malformed(
                pos,
                "empty $MeshFormat line: expected \"4.1 0 8\" or \"4.1 1 8\"",
            )
        });
    };
    if version != b"4.1" {
        return Err(IoError::UnsupportedVersion {
            path: cur.path().to_path_buf(),
            at: cur.location(pos),
            version: String::from_utf8_lossy(version).into_owned(),
        });
    }
    if fields.len() != 3 {
        return Err(cur.malformed(
            pos,
            format!(
                "expected \"4.1 <file-type> <data-size>\" in $MeshFormat, found {}",
                quote(line)
            ),
        ));
    }
    let binary = match parse_token::<i32>(fields[1]) {
        Some(0) => false,
        Some(1) => true,
        _ => {
            return Err(cur.malformed(
                pos,
                format!(
                    "file type must be 0 (ASCII) or 1 (binary), found {}",
                    quote(fields[1])
                ),
            ))
        }
    };
    if parse_token::<i32>(fields[2]) != Some(8) {
        return Err(cur.malformed(
            pos,
            format!(
                "data size must be 8 (the size of size_t), found {}",
                quote(fields[2])
            ),
        ));
    }
    if binary {
        let at = cur.pos();
        let marker = cur.raw4("the endianness marker of $MeshFormat")?;
        let big_endian = match marker {
            [1, 0, 0, 0] => false,
            [0, 0, 0, 1] => true,
            _ => {
                cur.set_encoding(Encoding::Binary { big_endian: false });
                return Err(cur.malformed(
                    at,
                    format!("bad endianness marker {marker:?}: expected the int 1"),
                ));
            }
        };
        cur.set_encoding(Encoding::Binary { big_endian });
    }
    cur.expect_end("MeshFormat")
}

/// `$PhysicalNames`, text in every file: `count`, then `dim tag "name"` per line.
fn parse_physical_names(cur: &mut Cursor<'_>, data: &mut MshData) -> Result<(), IoError> {
    let n = cur.ascii_size("the number of physical names")?;
    for _ in 0..n {
        let dim = cur.ascii_int("the dimension of a physical name")?;
        let tag = cur.ascii_int("the tag of a physical name")?;
        cur.skip_whitespace();
        let (pos, line) = cur.line();
        let name = match line.trim_ascii() {
            [b'"', inner @ .., b'"'] if !inner.contains(&b'"') => {
                String::from_utf8_lossy(inner).into_owned()
            }
            _ => {
                return Err(cur.malformed(
                    pos,
                    format!("expected a quoted physical name, found {}", quote(line)),
                ))
            }
        };
        data.physical_names.push(PhysicalName { dim, tag, name });
    }
    cur.expect_end("PhysicalNames")
}

/// `$Entities`: points, curves, surfaces, volumes with their physical tags.
fn parse_entities(cur: &mut Cursor<'_>, data: &mut MshData) -> Result<(), IoError> {
    let mut counts = [0usize; 4];
    for (dim, c) in counts.iter_mut().enumerate() {
        *c = cur.count(
            [
                "the number of points",
                "the number of curves",
                "the number of surfaces",
                "the number of volumes",
            ][dim],
        )?;
    }
    let mut entities = HashMap::new();
    for (dim, &n) in counts.iter().enumerate() {
        let kind = ["point", "curve", "surface", "volume"][dim];
        for _ in 0..n {
            let tag = cur.int(format_args!("a {kind} tag"))?;
            let bounds = if dim == 0 { 3 } else { 6 };
            for _ in 0..bounds {
                cur.float(format_args!("the bounding box of {kind} {tag}"))?;
            }
            let physicals_n =
                cur.count(format_args!("the number of physical tags of {kind} {tag}"))?;
            let mut physicals = Vec::with_capacity(physicals_n);
            for _ in 0..physicals_n {
                physicals.push(cur.int(format_args!("a physical tag of {kind} {tag}"))?);
            }
            if dim > 0 {
                let bounding = cur.count(format_args!(
                    "the number of bounding entities of {kind} {tag}"
                ))?;
                for _ in 0..bounding {
                    cur.int(format_args!("a bounding entity of {kind} {tag}"))?;
                }
            }
            entities.insert((dim as i32, tag), physicals);
        }
    }
    data.entities = Some(entities);
    cur.expect_end("Entities")
}

/// `$Nodes`: per entity block the node tags, then their coordinates (and parametric
/// coordinates, which are skipped).
fn parse_nodes(cur: &mut Cursor<'_>, data: &mut MshData) -> Result<(), IoError> {
    let header = {
        cur.skip_whitespace_if_ascii();
        cur.pos()
    };
    let blocks = cur.count("the number of node blocks")?;
    let total = cur.count("the number of nodes")?;
    cur.size("the smallest node tag")?;
    cur.size("the largest node tag")?;
    // A node takes at least 8 bytes (tag and three coordinates, in text).
    let capacity = cur.capacity(total, 8);
    data.coords.reserve(capacity);
    data.node_positions.reserve(capacity);
    data.node_index.reserve(capacity);
    let mut read = 0usize;
    let mut tags = Vec::new();
    for _ in 0..blocks {
        let dim = cur.int("the dimension of a node block")?;
        let entity = cur.int("the entity tag of a node block")?;
        cur.skip_whitespace_if_ascii();
        let param_pos = cur.pos();
        let parametric = cur.int("the parametric flag of a node block")?;
        if !(0..=1).contains(&parametric) || !(0..=3).contains(&dim) {
            return Err(cur.malformed(
                param_pos,
                format!("node block of entity {entity}: bad dimension {dim} or parametric flag {parametric}"),
            ));
        }
        let n = cur.count(format_args!(
            "the number of nodes of the block of entity {entity} (dimension {dim})"
        ))?;
        tags.clear();
        for _ in 0..n {
            tags.push(cur.size(format_args!(
                "a node tag of the block of entity {entity} (dimension {dim})"
            ))?);
        }
        let extra = if parametric == 1 { dim as usize } else { 0 };
        for &tag in &tags {
            cur.skip_whitespace_if_ascii();
            let pos = cur.pos();
            let mut x = [0.0; 3];
            for (k, xk) in x.iter_mut().enumerate() {
                *xk = cur.float(format_args!(
                    "the {} coordinate of node {tag}",
                    ["x", "y", "z"][k]
                ))?;
            }
            for _ in 0..extra {
                cur.float(format_args!("a parametric coordinate of node {tag}"))?;
            }
            let index = data.coords.len();
            if data.node_index.insert(tag, index).is_some() {
                return Err(IoError::DuplicateNode {
                    path: cur.path().to_path_buf(),
                    at: cur.location(pos),
                    node: tag,
                });
            }
            data.coords.push(x);
            data.node_positions.push(pos);
        }
        read += n;
    }
    if read != total {
        return Err(cur.malformed(
            header,
            format!("the $Nodes header announces {total} nodes, its blocks hold {read}"),
        ));
    }
    cur.expect_end("Nodes")
}

/// `$Elements`: per entity block the element type, then per element its tag and node tags.
fn parse_elements(cur: &mut Cursor<'_>, data: &mut MshData, keep: Keep<'_>) -> Result<(), IoError> {
    cur.skip_whitespace_if_ascii();
    let header = cur.pos();
    let blocks = cur.count("the number of element blocks")?;
    let total = cur.count("the number of elements")?;
    cur.size("the smallest element tag")?;
    cur.size("the largest element tag")?;
    let mut read = 0usize;
    for _ in 0..blocks {
        cur.skip_whitespace_if_ascii();
        let block_pos = cur.pos();
        let dim = cur.int("the dimension of an element block")?;
        let entity = cur.int("the entity tag of an element block")?;
        let element_type = cur.int("the element type of an element block")?;
        let count = cur.count(format_args!(
            "the number of elements of the block of entity {entity} (dimension {dim})"
        ))?;
        let registered = keep(dim, element_type);
        let nodes_per_element = element_types::node_count(element_type).or(registered);
        let kept = registered.is_some();
        let mut block = ElementBlock {
            dim,
            entity,
            element_type,
            count,
            kept,
            tags: Vec::new(),
            positions: Vec::new(),
            nodes: Vec::new(),
            nodes_per_element: nodes_per_element.unwrap_or(0),
        };
        if kept {
            // An element takes at least two bytes per tag (in text).
            let npe = block.nodes_per_element;
            let capacity = cur.capacity(count, 2 * (npe + 1));
            block.tags.reserve(capacity);
            block.positions.reserve(capacity);
            block.nodes.reserve(capacity * npe);
        }
        match (cur.encoding(), nodes_per_element) {
            (Encoding::Binary { .. }, None) => {
                return Err(cur.malformed(
                    block_pos,
                    format!(
                        "element block of entity {entity} (dimension {dim}) has Gmsh element type {element_type}, whose node count this reader does not know, so the binary data cannot be read"
                    ),
                ));
            }
            (Encoding::Binary { .. }, Some(n)) => {
                for i in 0..count {
                    let pos = cur.pos();
                    let tag = cur.size("an element tag")?;
                    if kept || i == 0 {
                        block.tags.push(tag);
                        block.positions.push(pos);
                    }
                    for _ in 0..n {
                        let node = cur.size(format_args!("a node tag of element {tag}"))?;
                        if kept {
                            block.nodes.push(node);
                        }
                    }
                }
            }
            (Encoding::Ascii, n) => {
                for i in 0..count {
                    read_ascii_element(cur, &mut block, n, i == 0)?;
                }
            }
        }
        read += count;
        data.blocks.push(block);
    }
    if read != total {
        return Err(cur.malformed(
            header,
            format!("the $Elements header announces {total} elements, its blocks hold {read}"),
        ));
    }
    cur.expect_end("Elements")
}

/// One element line of a text file: its tag, then exactly its type's node count of node tags.
fn read_ascii_element(
    cur: &mut Cursor<'_>,
    block: &mut ElementBlock,
    nodes: Option<usize>,
    first: bool,
) -> Result<(), IoError> {
    cur.skip_whitespace();
    if cur.at_end() {
        return Err(cur.truncated(format!(
            "the elements of the block of entity {} (dimension {})",
            block.entity, block.dim
        )));
    }
    let (pos, line) = cur.line();
    let mut fields = line
        .split(|b| b.is_ascii_whitespace())
        .filter(|f| !f.is_empty());
    let tag_field = fields.next().unwrap_or_default();
    let Some(tag) = parse_token::<u64>(tag_field) else {
        return Err(cur.malformed(
            pos,
            format!(
                "expected an element tag (a non-negative integer), found {}",
                quote(tag_field)
            ),
        ));
    };
    if block.kept || first {
        block.tags.push(tag);
        block.positions.push(pos);
    }
    let start = block.nodes.len();
    let mut got = 0usize;
    for f in fields {
        let Some(node) = parse_token::<u64>(f) else {
            return Err(cur.malformed(
                pos,
                format!(
                    "element {tag}: expected a node tag (a non-negative integer), found {}",
                    quote(f)
                ),
            ));
        };
        if block.kept {
            block.nodes.push(node);
        }
        got += 1;
    }
    if let Some(n) = nodes {
        if got < n && cur.line_cut_short() {
            return Err(cur.truncated(format_args!("the node tags of element {tag}")));
        }
        if got != n {
            block.nodes.truncate(start);
            return Err(cur.malformed(
                pos,
                format!(
                    "element {tag} has {got} node tags, but a {} (Gmsh type {}) has {n}",
                    element_types::type_name(block.element_type),
                    block.element_type
                ),
            ));
        }
    }
    Ok(())
}

impl Cursor<'_> {
    /// In text files, moves to the next token (so that its position is the one reported).
    pub(super) fn skip_whitespace_if_ascii(&mut self) {
        if self.encoding() == Encoding::Ascii {
            self.skip_whitespace();
        }
    }
}
