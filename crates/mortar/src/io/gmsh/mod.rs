//! Gmsh MSH 4.1 meshes: read the faces of a surface (a whole file or one physical group),
//! read a body (the cells of a physical group of dimension 2 or 3) and select its boundary
//! faces by physical group ([`read_gmsh_volume`], [`GmshVolume::boundary_faces_in`]), write
//! surface meshes and bodies (ASCII or binary) for tests and examples.
//!
//! Why our own reader rather than the `mshio` crate (0.4): `mshio` does parse MSH 4.1 ASCII
//! and binary, but it skips `$PhysicalNames`, so a group cannot be selected by name; its errors
//! are nom backtraces (an input slice and a kind), not "file, line 17: node 12 ..."; and its
//! node-count table has slips (18-node prisms read as 28 nodes). The subset a mortar interface
//! needs (`$MeshFormat`, `$PhysicalNames`, `$Entities`, `$Nodes`, `$Elements`) is a few hundred
//! lines here, with every message naming the file, the line (ASCII) or byte offset (binary),
//! the group and the element or node tag.
//!
//! What is read:
//! - without a group: all elements of dimension 2 if the file has any, else all of
//!   dimension 1; a file with volume elements asks for a group instead;
//! - with a group (by physical name, or by physical tag if no name matches): the elements of
//!   the group's entities; groups of dimension 2 are preferred to groups of dimension 1 of
//!   the same name; groups of dimension 3 (and 0) are refused.
//!
//! Only nodes used by the selected faces go into the [`SurfaceMesh`], with their Gmsh tags,
//! and faces keep their Gmsh element tags. Points and unselected elements are ignored; an
//! element type the [`ElementRegistry`] does not know is an error only when selected.
//! Partitioned files (`$PartitionedEntities`) are read as if unpartitioned, which is right
//! only for whole-file selection.

mod cursor;
pub(crate) mod element_types;

mod parse;
mod volume;
mod write;

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use mortar_core::SurfaceMesh;
use mortar_elements::ElementRegistry;

pub use volume::{parse_gmsh_volume, read_gmsh_volume, read_volume, GmshVolume};
pub use write::{
    msh41_bytes, msh41_volume_bytes, write_msh41, write_msh41_ascii, write_msh41_binary,
    write_msh41_volume, Endianness, MshFormat,
};

use nalgebra::Vector3;

use self::cursor::{locations_of, Cursor, Encoding};
use self::parse::{ElementBlock, MshData};
use crate::io::error::{IoError, Location};

/// A physical group of a Gmsh file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PhysicalGroup {
    /// Its dimension (1 for lines, 2 for surfaces).
    pub dim: i32,
    /// Its physical tag.
    pub tag: i32,
    /// Its name (empty if the file names it not).
    pub name: String,
}

/// A surface read from a Gmsh file, with where each face came from.
#[derive(Debug, Clone)]
pub struct GmshSurface {
    /// The faces and the nodes they use.
    pub mesh: SurfaceMesh,
    /// The dimension of the faces: 1 (lines, a 2D problem) or 2 (a 3D problem).
    pub dimension: u8,
    /// The file.
    pub path: PathBuf,
    /// The physical group read, if one was asked for.
    pub group: Option<PhysicalGroup>,
    /// Whether the file is binary.
    pub binary: bool,
    face_locations: HashMap<u64, Location>,
    /// For each face (in mesh order), the centre of the one cell of the file (of the next
    /// dimension) that has it on its boundary, when there is exactly one.
    cell_centres: Vec<Option<Vector3<f64>>>,
}

impl GmshSurface {
    /// Where in the file the face (element) with tag `tag` is.
    pub fn face_location(&self, tag: u64) -> Option<Location> {
        self.face_locations.get(&tag).copied()
    }

    /// Orients every face outward from the one cell of the file it bounds (a surface of a
    /// body meshed in the same file, as Gmsh writes a mesh with its physical groups), and
    /// returns the number of faces reversed; `None`, leaving the faces as they are, when some
    /// face bounds no cell of the file, or two (an interior surface).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`](mortar_core::MortarError::InvalidOption) if a face's
    /// element cannot reverse its node order.
    pub fn orient_outward(&mut self) -> Result<Option<usize>, mortar_core::MortarError> {
        if self.cell_centres.is_empty() || self.cell_centres.iter().any(Option::is_none) {
            return Ok(None);
        }
        let mut flipped = 0;
        for f in 0..self.mesh.face_count() {
            let Some(cell) = self.cell_centres[f] else {
                continue;
            };
            let view = self.mesh.face(f);
            let el = view.element;
            let mut x = [Vector3::zeros(); mortar_core::element::MAX_FACE_NODES];
            let k = self.mesh.face_coords_into(f, &mut x);
            let c = el.domain().centre();
            // The unit normal: the scaled one times a length would under- or overflow for
            // meshes at 1e-120 or 1e120 (a product of three lengths).
            let normal = el.unit_normal(&x[..k], &c);
            if normal.dot(&(el.map(&x[..k], &c) - cell)) < 0.0 {
                self.mesh.reverse_face(f)?;
                flipped += 1;
            }
        }
        Ok(Some(flipped))
    }

    /// `path` or `path#group`, for messages.
    pub fn label(&self) -> String {
        match &self.group {
            Some(g) if !g.name.is_empty() => format!("{}#{}", self.path.display(), g.name),
            Some(g) => format!("{}#{}", self.path.display(), g.tag),
            None => self.path.display().to_string(),
        }
    }
}

/// Reads the faces of a Gmsh 4.1 file (ASCII or binary) into a surface mesh: the whole file,
/// or the physical group `group` (a name, or a physical tag).
///
/// # Errors
/// Every [`IoError`] of [`read_gmsh_surface`].
pub fn read_surface(
    path: impl AsRef<Path>,
    group: Option<&str>,
    registry: &ElementRegistry,
) -> Result<SurfaceMesh, IoError> {
    read_gmsh_surface(path, group, registry).map(|s| s.mesh)
}

/// As [`read_surface`], and keeps where each face is in the file, to point at it when the
/// interface check later finds it degenerate or inverted.
///
/// # Errors
/// [`IoError::Read`] if the file cannot be read; [`IoError::Malformed`],
/// [`IoError::Truncated`] and [`IoError::UnsupportedVersion`] for a broken file;
/// [`IoError::GroupNotFound`], [`IoError::GroupDimension`], [`IoError::GroupRequired`],
/// [`IoError::NoFaces`] and [`IoError::MissingSection`] for a selection that cannot be made;
/// [`IoError::UnsupportedElement`], [`IoError::UndefinedNode`],
/// [`IoError::NonFiniteCoordinate`], [`IoError::DuplicateNode`] and [`IoError::Mesh`] for
/// selected faces that cannot be built.
pub fn read_gmsh_surface(
    path: impl AsRef<Path>,
    group: Option<&str>,
    registry: &ElementRegistry,
) -> Result<GmshSurface, IoError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    parse_gmsh_surface(&bytes, path, group, registry)
}

/// As [`read_gmsh_surface`], from the bytes of a file; `path` names it in messages.
///
/// # Errors
/// As [`read_gmsh_surface`], except [`IoError::Read`].
pub fn parse_gmsh_surface(
    bytes: &[u8],
    path: &Path,
    group: Option<&str>,
    registry: &ElementRegistry,
) -> Result<GmshSurface, IoError> {
    let mut cur = Cursor::new(bytes, path);
    // Faces of the registry, and cells of any known type: a face's cell tells which way is
    // out of its body.
    let keep = |dim: i32, ty: i32| {
        let face = u32::try_from(ty)
            .ok()
            .and_then(|t| registry.by_gmsh_type(t))
            .filter(|_| dim == 1 || dim == 2)
            .map(|e| e.node_count());
        face.or_else(|| {
            (dim == 2 || dim == 3)
                .then(|| element_types::node_count(ty))
                .flatten()
        })
    };
    let data = parse::parse(&mut cur, &keep)?;
    let encoding = cur.encoding();
    let (blocks, dimension, group) = select(&data, path, group)?;
    build(
        &data, &blocks, dimension, group, path, bytes, encoding, registry,
    )
}

/// The element blocks to read, their dimension and the group.
fn select<'d>(
    data: &'d MshData,
    path: &Path,
    group: Option<&str>,
) -> Result<(Vec<&'d ElementBlock>, i32, Option<PhysicalGroup>), IoError> {
    let has = |dim: i32| data.blocks.iter().any(|b| b.dim == dim && b.count > 0);
    let Some(name) = group else {
        let required = |what| IoError::GroupRequired {
            path: path.to_path_buf(),
            what,
            available: describe_groups(data),
        };
        if has(3) {
            return Err(required("volume elements"));
        }
        // Surface elements in the plane z = 0 beside lines: a 2D mesh, its cells and their
        // boundary lines.
        let planar = || {
            data.blocks
                .iter()
                .filter(|b| b.dim == 2 && b.kept)
                .flat_map(|b| b.nodes.iter())
                .all(|n| {
                    data.node_index
                        .get(n)
                        .is_some_and(|&i| data.coords[i][2] == 0.0)
                })
        };
        if has(2) && has(1) && planar() {
            return Err(required(
                "a 2D mesh (surface elements in the plane z = 0, and lines)",
            ));
        }
        let dim = if has(2) { 2 } else { 1 };
        let blocks: Vec<_> = data
            .blocks
            .iter()
            .filter(|b| b.dim == dim && b.count > 0)
            .collect();
        if blocks.is_empty() {
            return Err(IoError::NoFaces {
                path: path.to_path_buf(),
                group: None,
            });
        }
        return Ok((blocks, dim, None));
    };

    let group = find_group(data, path, name)?;
    if group.dim != 1 && group.dim != 2 {
        return Err(IoError::GroupDimension {
            path: path.to_path_buf(),
            group: name.to_string(),
            dim: group.dim,
        });
    }
    let Some(entities) = &data.entities else {
        return Err(IoError::MissingSection {
            path: path.to_path_buf(),
            section: "$Entities",
            needed_for: format!("selecting physical group \"{name}\""),
        });
    };
    let members: HashSet<i32> = entities
        .iter()
        .filter(|((dim, _), phys)| *dim == group.dim && phys.iter().any(|p| p.abs() == group.tag))
        .map(|((_, tag), _)| *tag)
        .collect();
    let blocks: Vec<_> = data
        .blocks
        .iter()
        .filter(|b| b.dim == group.dim && b.count > 0 && members.contains(&b.entity))
        .collect();
    if blocks.is_empty() {
        return Err(IoError::NoFaces {
            path: path.to_path_buf(),
            group: Some(name.to_string()),
        });
    }
    let dim = group.dim;
    Ok((blocks, dim, Some(group)))
}

/// The nodes the elements of `blocks` use, ascending by tag, as `(tag, coordinates, position
/// in the file)`. An element naming a node the file does not define is an error at that
/// element, a non-finite coordinate an error at that node.
fn used_nodes(
    data: &MshData,
    blocks: &[&ElementBlock],
    path: &Path,
    at: &dyn Fn(usize) -> Location,
) -> Result<Vec<(u64, [f64; 3], usize)>, IoError> {
    let mut used: Vec<u64> = Vec::new();
    for b in blocks {
        for (i, nodes) in b.nodes.chunks_exact(b.nodes_per_element.max(1)).enumerate() {
            for &node in nodes {
                if !data.node_index.contains_key(&node) {
                    return Err(IoError::UndefinedNode {
                        path: path.to_path_buf(),
                        at: at(b.positions[i]),
                        element: b.tags[i],
                        node,
                    });
                }
            }
            used.extend_from_slice(nodes);
        }
    }
    used.sort_unstable();
    used.dedup();
    used.into_iter()
        .map(|tag| {
            let index = data.node_index[&tag];
            let (x, pos) = (data.coords[index], data.node_positions[index]);
            if x.iter().any(|c| !c.is_finite()) {
                return Err(IoError::NonFiniteCoordinate {
                    path: path.to_path_buf(),
                    at: at(pos),
                    node: tag,
                    coords: x,
                });
            }
            Ok((tag, x, pos))
        })
        .collect()
}

/// The groups named `name`, or else (none named so) the groups whose physical tag is `name`,
/// one per dimension that has it.
fn matching_groups(data: &MshData, name: &str) -> Vec<PhysicalGroup> {
    let mut found: Vec<PhysicalGroup> = data
        .physical_names
        .iter()
        .filter(|p| p.name == name)
        .map(|p| PhysicalGroup {
            dim: p.dim,
            tag: p.tag,
            name: p.name.clone(),
        })
        .collect();
    if found.is_empty() {
        if let Ok(tag) = name.parse::<i32>() {
            let mut dims: Vec<i32> = data
                .entities
                .iter()
                .flatten()
                .filter(|(_, phys)| phys.iter().any(|p| p.abs() == tag))
                .map(|((dim, _), _)| *dim)
                .collect();
            dims.sort_unstable();
            dims.dedup();
            found = dims
                .into_iter()
                .map(|dim| PhysicalGroup {
                    dim,
                    tag,
                    name: data
                        .physical_names
                        .iter()
                        .find(|p| p.dim == dim && p.tag == tag)
                        .map(|p| p.name.clone())
                        .unwrap_or_default(),
                })
                .collect();
        }
    }
    found
}

/// The group named `name`, or else the group whose physical tag is `name`. Of several, the
/// one of dimension 2, then 1, then the highest.
fn find_group(data: &MshData, path: &Path, name: &str) -> Result<PhysicalGroup, IoError> {
    let mut found = matching_groups(data, name);
    let rank = |g: &PhysicalGroup| match g.dim {
        2 => 5,
        1 => 4,
        d => d,
    };
    found.sort_by_key(|g| std::cmp::Reverse(rank(g)));
    found
        .into_iter()
        .next()
        .ok_or_else(|| IoError::GroupNotFound {
            path: path.to_path_buf(),
            group: name.to_string(),
            available: describe_groups(data),
        })
}

/// The physical groups of a file, described for messages.
fn describe_groups(data: &MshData) -> Vec<String> {
    data.physical_names
        .iter()
        .map(|p| format!("\"{}\" (dimension {}, tag {})", p.name, p.dim, p.tag))
        .collect()
}

/// The surface mesh of the selected blocks.
#[allow(clippy::too_many_arguments)]
fn build(
    data: &MshData,
    blocks: &[&ElementBlock],
    dimension: i32,
    group: Option<PhysicalGroup>,
    path: &Path,
    bytes: &[u8],
    encoding: Encoding,
    registry: &ElementRegistry,
) -> Result<GmshSurface, IoError> {
    let at = |pos: usize| cursor::location_of(bytes, pos, encoding);
    // Element types, then node references, then coordinates.
    for b in blocks {
        let registered = u32::try_from(b.element_type)
            .ok()
            .and_then(|t| registry.by_gmsh_type(t))
            .is_some();
        if !b.kept || !registered {
            let (tag, pos) = (
                b.tags.first().copied().unwrap_or(0),
                b.positions.first().copied().unwrap_or(0),
            );
            return Err(IoError::UnsupportedElement {
                path: path.to_path_buf(),
                at: at(pos),
                element: tag,
                element_type: b.element_type,
                type_name: element_types::type_name(b.element_type),
                supported: registry
                    .elements()
                    .iter()
                    .filter_map(|e| e.gmsh_type().map(|t| format!("{t} ({})", e.name())))
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
    }
    let used = used_nodes(data, blocks, path, &at)?;

    let faces: usize = blocks.iter().map(|b| b.tags.len()).sum();
    let mut mesh = SurfaceMesh::with_capacity(used.len(), faces);
    for &(tag, x, pos) in &used {
        // Tags are unique and coordinates finite here; any other refusal is reported as is.
        mesh.add_node(tag, x).map_err(|e| IoError::Malformed {
            path: path.to_path_buf(),
            at: at(pos),
            message: e.to_string(),
        })?;
    }

    let mut positions = Vec::with_capacity(faces);
    let mut tags = Vec::with_capacity(faces);
    for b in blocks {
        let Some(element) = u32::try_from(b.element_type)
            .ok()
            .and_then(|t| registry.by_gmsh_type(t))
        else {
            continue; // unreachable: unknown types were refused above
        };
        for (i, nodes) in b.nodes.chunks_exact(b.nodes_per_element.max(1)).enumerate() {
            let tag = b.tags[i];
            mesh.add_face_with_tag(tag, element, nodes)
                .map_err(|source| IoError::Mesh {
                    path: path.to_path_buf(),
                    at: at(b.positions[i]),
                    element: tag,
                    source,
                })?;
            positions.push(b.positions[i]);
            tags.push(tag);
        }
    }
    let mut order: Vec<usize> = (0..positions.len()).collect();
    order.sort_by_key(|&i| positions[i]);
    let sorted: Vec<usize> = order.iter().map(|&i| positions[i]).collect();
    let locations = locations_of(bytes, &sorted, encoding);
    let face_locations = order
        .iter()
        .zip(locations)
        .map(|(&i, loc)| (tags[i], loc))
        .collect();

    let cell_centres = adjacent_cell_centres(data, &mesh, dimension + 1);
    Ok(GmshSurface {
        mesh,
        dimension: if dimension == 1 { 1 } else { 2 },
        path: path.to_path_buf(),
        group,
        binary: encoding != Encoding::Ascii,
        face_locations,
        cell_centres,
    })
}

/// For each face of `mesh`, the centre (mean of the nodes) of the one cell of dimension
/// `cell_dim` in the file whose nodes include all the face's nodes; `None` for a face with
/// none or several. Only the cells touching the surface are looked at.
fn adjacent_cell_centres(
    data: &MshData,
    mesh: &SurfaceMesh,
    cell_dim: i32,
) -> Vec<Option<Vector3<f64>>> {
    let tags = mesh.node_tags();
    let on_surface: HashSet<u64> = tags.iter().copied().collect();
    // Cells touching the surface: their sorted node tags and centre; and by surface node.
    let mut cells: Vec<(Vec<u64>, Vector3<f64>)> = Vec::new();
    let mut by_node: HashMap<u64, Vec<u32>> = HashMap::new();
    for b in data.blocks.iter().filter(|b| b.dim == cell_dim && b.kept) {
        for nodes in b.nodes.chunks_exact(b.nodes_per_element.max(1)) {
            if !nodes.iter().any(|n| on_surface.contains(n)) {
                continue;
            }
            let mut centre = Vector3::zeros();
            for n in nodes {
                let Some(&i) = data.node_index.get(n) else {
                    return vec![None; mesh.face_count()];
                };
                centre += Vector3::from(data.coords[i]);
            }
            centre /= nodes.len() as f64;
            let id = cells.len() as u32;
            for n in nodes.iter().filter(|n| on_surface.contains(n)) {
                by_node.entry(*n).or_default().push(id);
            }
            let mut sorted = nodes.to_vec();
            sorted.sort_unstable();
            cells.push((sorted, centre));
        }
    }
    (0..mesh.face_count())
        .map(|f| {
            let face: Vec<u64> = mesh
                .face(f)
                .nodes
                .iter()
                .map(|&n| tags[n as usize])
                .collect();
            let mut found = by_node.get(&face[0])?.iter().filter(|&&c| {
                face.iter()
                    .all(|n| cells[c as usize].0.binary_search(n).is_ok())
            });
            let first = *found.next()?;
            found.next().is_none().then(|| cells[first as usize].1)
        })
        .collect()
}
