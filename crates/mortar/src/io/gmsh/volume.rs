//! Bodies (volume meshes) from Gmsh 4.1 files, and the faces of their boundary named by
//! physical groups of one dimension less.

use std::collections::{HashMap, HashSet};
use std::fmt;
use std::path::{Path, PathBuf};

use mortar_core::SurfaceMesh;
use mortar_elements::volume::VolumeRegistry;
use mortar_fem::element::MAX_CELL_NODES;
use mortar_fem::mesh::{BoundaryFace, VolumeMesh};

use super::cursor::{location_of, Cursor, Encoding};
use super::parse::{self, ElementBlock, MshData};
use super::{element_types, matching_groups, used_nodes, PhysicalGroup};
use crate::io::error::{IoError, Location};

/// A body read from a Gmsh file: the cells of one physical group of dimension 2 or 3, with
/// the file kept to select faces of the body's boundary by physical group
/// ([`boundary_faces_in`](GmshVolume::boundary_faces_in)).
pub struct GmshVolume {
    /// The cells of the group and the nodes they use (Gmsh node and element tags kept).
    pub mesh: VolumeMesh,
    /// The dimension of the cells: 2 or 3.
    pub dimension: u8,
    /// The file.
    pub path: PathBuf,
    /// The body's physical group.
    pub group: PhysicalGroup,
    /// Whether the file is binary.
    pub binary: bool,
    data: MshData,
    bytes: Vec<u8>,
    encoding: Encoding,
}

impl fmt::Debug for GmshVolume {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GmshVolume")
            .field("path", &self.path)
            .field("group", &self.group)
            .field("dimension", &self.dimension)
            .field("nodes", &self.mesh.node_count())
            .field("cells", &self.mesh.cell_count())
            .field("binary", &self.binary)
            .finish()
    }
}

/// Reads the cells of the physical group `group` (a name, or a physical tag) of a Gmsh 4.1
/// file (ASCII or binary) as a body.
///
/// # Errors
/// Every [`IoError`] of [`read_gmsh_volume`].
pub fn read_volume(
    path: impl AsRef<Path>,
    group: &str,
    registry: &VolumeRegistry,
) -> Result<VolumeMesh, IoError> {
    read_gmsh_volume(path, group, registry).map(|v| v.mesh)
}

/// As [`read_volume`], keeping the file to select boundary faces by physical group.
///
/// The group must have dimension 2 (Tri3, Quad4 cells in the plane `z = 0`) or 3 (Tet4,
/// Hex8); of several groups of that name, the one of dimension 3 is taken, then 2.
///
/// # Errors
/// [`IoError::Read`] if the file cannot be read; the format errors of
/// [`read_gmsh_surface`](super::read_gmsh_surface); [`IoError::GroupNotFound`],
/// [`IoError::WrongGroupDimension`] (a group of lines or points), [`IoError::NoCells`],
/// [`IoError::MissingSection`] (no `$Entities`) for a selection that cannot be made;
/// [`IoError::ClockwiseMesh`] for a 2D body whose cells all run clockwise;
/// [`IoError::UnsupportedElement`], [`IoError::UndefinedNode`],
/// [`IoError::NonFiniteCoordinate`] and [`IoError::Cell`] (a node of a 2D body off `z = 0`,
/// mixed cell dimensions) for cells that cannot be built.
pub fn read_gmsh_volume(
    path: impl AsRef<Path>,
    group: &str,
    registry: &VolumeRegistry,
) -> Result<GmshVolume, IoError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    parse_gmsh_volume(bytes, path, group, registry)
}

/// As [`read_gmsh_volume`], from the bytes of a file; `path` names it in messages.
///
/// # Errors
/// As [`read_gmsh_volume`], except [`IoError::Read`].
pub fn parse_gmsh_volume(
    bytes: Vec<u8>,
    path: &Path,
    group: &str,
    registry: &VolumeRegistry,
) -> Result<GmshVolume, IoError> {
    let (data, encoding) = {
        let mut cur = Cursor::new(&bytes, path);
        let keep = |dim: i32, ty: i32| {
            if (1..=3).contains(&dim) {
                element_types::node_count(ty).or_else(|| {
                    let t = u32::try_from(ty).ok()?;
                    registry
                        .by_gmsh_type(t, dim as usize)
                        .map(|e| e.node_count())
                })
            } else {
                None
            }
        };
        let data = parse::parse(&mut cur, &keep)?;
        (data, cur.encoding())
    };
    let group = find_group_of_dim(&data, path, group, &[3, 2], || {
        "a body needs a group of dimension 2 (a 2D body) or 3 (a 3D body)".to_string()
    })?;
    let blocks = group_blocks(&data, path, &group)?;
    if blocks.is_empty() {
        return Err(IoError::NoCells {
            path: path.to_path_buf(),
            group: group.name_or_tag(),
            dim: group.dim,
        });
    }
    let mesh = build_volume(&data, &blocks, group.dim, path, &bytes, encoding, registry)?;
    if group.dim == 2 && mesh.cell_count() > 0 && all_clockwise(&mesh) {
        return Err(IoError::ClockwiseMesh {
            path: path.to_path_buf(),
            group: group.name_or_tag(),
            cells: mesh.cell_count(),
        });
    }
    Ok(GmshVolume {
        mesh,
        dimension: group.dim as u8,
        path: path.to_path_buf(),
        group,
        binary: encoding != Encoding::Ascii,
        data,
        bytes,
        encoding,
    })
}

impl PhysicalGroup {
    /// The name, or the tag for an unnamed group.
    fn name_or_tag(&self) -> String {
        if self.name.is_empty() {
            self.tag.to_string()
        } else {
            self.name.clone()
        }
    }
}

impl GmshVolume {
    /// `path#group`, for messages.
    pub fn label(&self) -> String {
        format!("{}#{}", self.path.display(), self.group.name_or_tag())
    }

    /// The boundary faces of the body that are elements of the physical group `group` (a
    /// name or a physical tag) of the same file, of dimension one less than the body's (lines
    /// for a 2D body, surfaces for a 3D one). Faces come in the order of
    /// [`VolumeMesh::boundary_faces`], each once.
    ///
    /// # Errors
    /// [`IoError::GroupNotFound`], [`IoError::WrongGroupDimension`],
    /// [`IoError::MissingSection`], [`IoError::NoFaces`] for a group that cannot be selected;
    /// [`IoError::NotOnBoundary`] for an element of the group that is no boundary face of the
    /// body (a face of the other body, an inner face); [`IoError::Cell`] if the body's
    /// boundary cannot be extracted (a face shared by three cells).
    pub fn boundary_faces_in(&self, group: &str) -> Result<Vec<BoundaryFace>, IoError> {
        let want = i32::from(self.dimension) - 1;
        let dims = if want == 1 { "2D" } else { "3D" };
        let shape = if want == 1 { "lines" } else { "surfaces" };
        let g = find_group_of_dim(&self.data, &self.path, group, &[want], || {
            format!(
                "the boundary of the {dims} body \"{}\" is made of {shape}: a group of dimension {want} is needed",
                self.group.name_or_tag()
            )
        })?;
        let blocks = group_blocks(&self.data, &self.path, &g)?;
        if blocks.is_empty() {
            return Err(IoError::NoFaces {
                path: self.path.clone(),
                group: Some(group.to_string()),
            });
        }
        let faces = self.mesh.boundary_faces().map_err(|source| IoError::Cell {
            path: self.path.clone(),
            at: Location::Line(1),
            element: 0,
            source,
        })?;
        let key = |nodes: &mut Vec<u32>| {
            nodes.sort_unstable();
            nodes.clone()
        };
        let mut index: HashMap<Vec<u32>, usize> = HashMap::with_capacity(faces.len());
        let mut scratch = Vec::new();
        for (i, f) in faces.iter().enumerate() {
            scratch.clear();
            scratch.extend_from_slice(&f.nodes);
            index.insert(key(&mut scratch), i);
        }
        let mut selected = vec![false; faces.len()];
        for b in &blocks {
            let npe = b.nodes_per_element.max(1);
            for (i, nodes) in b.nodes.chunks_exact(npe).enumerate() {
                scratch.clear();
                let mut known = b.kept;
                for &t in nodes {
                    match self.mesh.node_index(t) {
                        Some(n) => scratch.push(n),
                        None => known = false,
                    }
                }
                let found = if known {
                    index.get(&key(&mut scratch)).copied()
                } else {
                    None
                };
                match found {
                    Some(f) => selected[f] = true,
                    None => {
                        return Err(IoError::NotOnBoundary {
                            path: self.path.clone(),
                            at: location_of(&self.bytes, b.positions[i], self.encoding),
                            group: group.to_string(),
                            element: b.tags[i],
                            body: self.group.name_or_tag(),
                        })
                    }
                }
            }
        }
        Ok(faces
            .into_iter()
            .zip(selected)
            .filter(|(_, s)| *s)
            .map(|(f, _)| f)
            .collect())
    }

    /// The faces of [`boundary_faces_in`](Self::boundary_faces_in) as an outward-oriented
    /// surface mesh with the body's node tags (an interface side).
    ///
    /// # Errors
    /// As [`boundary_faces_in`](Self::boundary_faces_in).
    pub fn boundary_surface_in(&self, group: &str) -> Result<SurfaceMesh, IoError> {
        let faces = self.boundary_faces_in(group)?;
        let chosen: HashSet<(u32, u8)> = faces.iter().map(|f| (f.cell, f.local_face)).collect();
        self.mesh
            .boundary_surface(|f| chosen.contains(&(f.cell, f.local_face)))
            .map_err(|source| IoError::Cell {
                path: self.path.clone(),
                at: Location::Line(1),
                element: 0,
                source,
            })
    }
}

/// The group named (or numbered) `name` of the first dimension of `dims` that has one; an
/// error naming the dimension found if it has none of those.
fn find_group_of_dim(
    data: &MshData,
    path: &Path,
    name: &str,
    dims: &[i32],
    expected: impl Fn() -> String,
) -> Result<PhysicalGroup, IoError> {
    let found = matching_groups(data, name);
    for d in dims {
        if let Some(g) = found.iter().find(|g| g.dim == *d) {
            return Ok(g.clone());
        }
    }
    match found.into_iter().max_by_key(|g| g.dim) {
        Some(g) => Err(IoError::WrongGroupDimension {
            path: path.to_path_buf(),
            group: name.to_string(),
            dim: g.dim,
            expected: expected(),
        }),
        None => Err(IoError::GroupNotFound {
            path: path.to_path_buf(),
            group: name.to_string(),
            available: data
                .physical_names
                .iter()
                .map(|p| format!("\"{}\" (dimension {}, tag {})", p.name, p.dim, p.tag))
                .collect(),
        }),
    }
}

/// The non-empty element blocks of the group's entities.
fn group_blocks<'d>(
    data: &'d MshData,
    path: &Path,
    group: &PhysicalGroup,
) -> Result<Vec<&'d ElementBlock>, IoError> {
    let Some(entities) = &data.entities else {
        return Err(IoError::MissingSection {
            path: path.to_path_buf(),
            section: "$Entities",
            needed_for: format!("selecting physical group \"{}\"", group.name_or_tag()),
        });
    };
    let members: HashSet<i32> = entities
        .iter()
        .filter(|((dim, _), phys)| *dim == group.dim && phys.iter().any(|p| p.abs() == group.tag))
        .map(|((_, tag), _)| *tag)
        .collect();
    Ok(data
        .blocks
        .iter()
        .filter(|b| b.dim == group.dim && b.count > 0 && members.contains(&b.entity))
        .collect())
}

/// The volume mesh of the selected cell blocks.
fn build_volume(
    data: &MshData,
    blocks: &[&ElementBlock],
    dim: i32,
    path: &Path,
    bytes: &[u8],
    encoding: Encoding,
    registry: &VolumeRegistry,
) -> Result<VolumeMesh, IoError> {
    let at = |pos: usize| location_of(bytes, pos, encoding);
    let mut elements = Vec::with_capacity(blocks.len());
    for b in blocks {
        let element = u32::try_from(b.element_type)
            .ok()
            .and_then(|t| registry.by_gmsh_type(t, dim as usize))
            .filter(|_| b.kept);
        let Some(element) = element else {
            return Err(IoError::UnsupportedElement {
                path: path.to_path_buf(),
                at: at(b.positions.first().copied().unwrap_or(0)),
                element: b.tags.first().copied().unwrap_or(0),
                element_type: b.element_type,
                type_name: element_types::type_name(b.element_type),
                supported: registry
                    .elements()
                    .iter()
                    .filter(|e| e.dim() == dim as usize)
                    .filter_map(|e| e.gmsh_type().map(|t| format!("{t} ({})", e.name())))
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        };
        elements.push(element);
    }
    let used = used_nodes(data, blocks, path, &at)?;
    let mut mesh = VolumeMesh::new();
    for &(tag, x, pos) in &used {
        mesh.add_node(tag, x).map_err(|source| IoError::Cell {
            path: path.to_path_buf(),
            at: at(pos),
            element: tag,
            source,
        })?;
    }
    for (b, element) in blocks.iter().zip(elements) {
        for (i, nodes) in b.nodes.chunks_exact(b.nodes_per_element.max(1)).enumerate() {
            mesh.add_cell_with_tag(b.tags[i], element, nodes)
                .map_err(|source| IoError::Cell {
                    path: path.to_path_buf(),
                    at: at(b.positions[i]),
                    element: b.tags[i],
                    source,
                })?;
        }
    }
    Ok(mesh)
}

/// Whether every cell of a 2D mesh has a negative Jacobian determinant at the centre of its
/// reference domain (runs clockwise in the xy-plane).
fn all_clockwise(mesh: &VolumeMesh) -> bool {
    let mut x = [nalgebra::Vector3::zeros(); MAX_CELL_NODES];
    (0..mesh.cell_count()).all(|c| {
        let n = mesh.cell_coords_into(c, &mut x);
        let element = mesh.cell(c).element;
        let centre = element.domain().centre();
        element.jacobian(&x[..n], &centre).determinant() < 0.0
    })
}
