//! The typed error of file input and output, and where in a file a problem was found.

use std::fmt;
use std::path::PathBuf;

use mortar_core::MortarError;
use mortar_fem::mesh::VolumeMeshError;

/// A place in an input file: a line number (text files) or a byte offset (binary files).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Location {
    /// A 1-based line number.
    Line(usize),
    /// A 0-based byte offset from the start of the file.
    Offset(usize),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(l) => write!(f, "line {l}"),
            Location::Offset(o) => write!(f, "byte offset {o}"),
        }
    }
}

/// Errors of reading and writing files. Each names the file and, where it applies, the
/// place in it (line or byte offset), the physical group, and the element or node tag.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum IoError {
    /// The file cannot be opened or read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A file or directory cannot be created, written or renamed.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file or directory.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The file breaks its format: a bad header, a bad number, a missing end marker.
    #[error("{}, {at}: {message}", path.display())]
    Malformed {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// What is wrong.
        message: String,
    },
    /// The file ends in the middle of a section.
    #[error("{}, {at}: the file ends while reading {what} (truncated file?)", path.display())]
    Truncated {
        /// The file.
        path: PathBuf,
        /// The end of the file.
        at: Location,
        /// What was being read.
        what: String,
    },
    /// A Gmsh file of another version than 4.1.
    #[error("{}, {at}: MSH format version {version} is not supported, only 4.1 (in Gmsh: Mesh.MshFileVersion = 4.1)", path.display())]
    UnsupportedVersion {
        /// The file.
        path: PathBuf,
        /// Where the version stands.
        at: Location,
        /// The version found.
        version: String,
    },
    /// A section the request needs is not in the file.
    #[error("{}: the file has no {section} section, which {needed_for} needs", path.display())]
    MissingSection {
        /// The file.
        path: PathBuf,
        /// The section, such as `$Entities`.
        section: &'static str,
        /// What needs it.
        needed_for: String,
    },
    /// No physical group has the requested name (or number).
    #[error("{}: no physical group named \"{group}\" (the file has: {})", path.display(), list_or_none(available))]
    GroupNotFound {
        /// The file.
        path: PathBuf,
        /// The requested group.
        group: String,
        /// The groups of the file, as `"name" (dimension d, tag t)`.
        available: Vec<String>,
    },
    /// The physical group is not made of lines or surfaces.
    #[error("{}: physical group \"{group}\" has dimension {dim}; only groups of lines (2D) or surfaces (3D) can be coupled for now", path.display())]
    GroupDimension {
        /// The file.
        path: PathBuf,
        /// The group.
        group: String,
        /// Its dimension.
        dim: i32,
    },
    /// The whole file was asked for, but it holds the cells of bodies (volume elements, or
    /// a 2D mesh: surface elements in the plane z = 0 beside lines), so which of its
    /// elements make the interface is not clear.
    #[error("{}: the file has {what}, so name the interface's physical group: {}#GROUP{}", path.display(), path.display(), if available.is_empty() { String::new() } else { format!(" (the file has: {})", available.join(", ")) })]
    GroupRequired {
        /// The file.
        path: PathBuf,
        /// What the file holds: "volume elements" or "a 2D mesh (surface elements in the
        /// plane z = 0, and lines)".
        what: &'static str,
        /// The physical groups of the file, described.
        available: Vec<String>,
    },
    /// Nothing to couple: no line or surface elements (in the group).
    #[error("{}: {} has no line or surface elements", path.display(), match group { Some(g) => format!("physical group \"{g}\""), None => "the file".to_string() })]
    NoFaces {
        /// The file.
        path: PathBuf,
        /// The group, if one was asked for.
        group: Option<String>,
    },
    /// A selected element has a type the element registry does not know.
    #[error("{}, {at}: element {element} is of Gmsh element type {element_type} ({type_name}), which is not supported (supported types: {supported}){}", path.display(), super::gmsh::element_types::unsupported_hint(*element_type))]
    UnsupportedElement {
        /// The file.
        path: PathBuf,
        /// Where the element is.
        at: Location,
        /// The element tag.
        element: u64,
        /// The Gmsh element type number.
        element_type: i32,
        /// A description of the type, such as `6-node triangle`.
        type_name: String,
        /// The supported types, as `1 (Line2), 2 (Tri3)`.
        supported: String,
    },
    /// An element refers to a node the file does not define.
    #[error("{}, {at}: element {element} refers to node {node}, which the file does not define", path.display())]
    UndefinedNode {
        /// The file.
        path: PathBuf,
        /// Where the element is.
        at: Location,
        /// The element tag.
        element: u64,
        /// The missing node tag.
        node: u64,
    },
    /// A node used by a selected face has a NaN or infinite coordinate.
    #[error("{}, {at}: node {node} has a non-finite coordinate ({}, {}, {})", path.display(), coords[0], coords[1], coords[2])]
    NonFiniteCoordinate {
        /// The file.
        path: PathBuf,
        /// Where the node's coordinates are.
        at: Location,
        /// The node tag.
        node: u64,
        /// Its coordinates.
        coords: [f64; 3],
    },
    /// The file defines a node twice.
    #[error("{}, {at}: node {node} is defined twice", path.display())]
    DuplicateNode {
        /// The file.
        path: PathBuf,
        /// Where the second definition is.
        at: Location,
        /// The node tag.
        node: u64,
    },
    /// The mesh refused an element (e.g. its node count does not match its registered type).
    #[error("{}, {at}: element {element}: {source}", path.display())]
    Mesh {
        /// The file.
        path: PathBuf,
        /// Where the element is.
        at: Location,
        /// The element tag.
        element: u64,
        /// The mesh's error.
        source: MortarError,
    },
    /// A physical group has the wrong dimension for its use (a body needs cells, a boundary
    /// condition or an interface side needs faces of the body's boundary).
    #[error("{}: physical group \"{group}\" has dimension {dim}, but {expected}", path.display())]
    WrongGroupDimension {
        /// The file.
        path: PathBuf,
        /// The group.
        group: String,
        /// Its dimension.
        dim: i32,
        /// What was expected, as a phrase (e.g. `a body needs a group of dimension 2 or 3`).
        expected: String,
    },
    /// A body's physical group holds no cells.
    #[error("{}: physical group \"{group}\" has no elements of dimension {dim}", path.display())]
    NoCells {
        /// The file.
        path: PathBuf,
        /// The group.
        group: String,
        /// The dimension of the group.
        dim: i32,
    },
    /// Every cell of a 2D body runs clockwise in the plane `z = 0` (a surface meshed with its
    /// normal along `-z`): each would be refused as inverted when assembled.
    #[error("{}: physical group \"{group}\": the whole 2D mesh is clockwise (all {cells} cells run clockwise in the xy-plane, their surface's normal along -z); the cells of a 2D body must run counter-clockwise: reverse the surface's orientation in Gmsh (e.g. ReverseMesh Surface{{...}};) and mesh it again", path.display())]
    ClockwiseMesh {
        /// The file.
        path: PathBuf,
        /// The body's group.
        group: String,
        /// Its cell count.
        cells: usize,
    },
    /// A body's mesh refused a node or a cell.
    #[error("{}, {at}: element {element}: {source}", path.display())]
    Cell {
        /// The file.
        path: PathBuf,
        /// Where the element (or node) is.
        at: Location,
        /// The element tag (the node tag for a refused node).
        element: u64,
        /// The mesh's error.
        source: VolumeMeshError,
    },
    /// An element of a face group is not a boundary face of the body read from the file.
    #[error("{}, {at}: element {element} of physical group \"{group}\" is not a boundary face of body \"{body}\"", path.display())]
    NotOnBoundary {
        /// The file.
        path: PathBuf,
        /// Where the element is.
        at: Location,
        /// The face group.
        group: String,
        /// The element tag.
        element: u64,
        /// The body's physical group.
        body: String,
    },
    /// An interface argument such as `mesh.msh#contact` cannot be understood.
    #[error("invalid interface argument \"{arg}\": {reason}")]
    InvalidArgument {
        /// The argument.
        arg: String,
        /// Why.
        reason: String,
    },
    /// A mesh cannot be written in the requested format.
    #[error("cannot write the mesh as Gmsh 4.1: {reason}")]
    Unwritable {
        /// Why.
        reason: String,
    },
}

fn list_or_none(items: &[String]) -> String {
    if items.is_empty() {
        "no named physical groups".to_string()
    } else {
        items.join(", ")
    }
}
