//! The pellet and cladding of a user's Gmsh file (`[mesh] file`), in place of the generated
//! section: the rod's 2D cross-section (its axis at the origin; an eccentric pellet, say) or
//! an r-z section (x = r, y = z) of a pellet segment (a dished and chamfered pellet, say),
//! from a plane of symmetry at `z = 0` to its end at the largest `z`.
//!
//! The file names its parts by physical groups: the cells of [`PELLET`] and [`CLADDING`];
//! the pellet's lateral surface [`PELLET_OUTER`] (the slave side of the gap) and the
//! cladding's inner and outer surfaces [`CLADDING_INNER`] (the master side) and
//! [`CLADDING_OUTER`] (the coolant's); optionally [`PELLET_FREE`], the pellet's other surfaces
//! the plenum gas presses on (dishes, chamfers). A stack of pellets is one pellet body of
//! several parts whose lands bear on each other: in r-z, [`PELLET_LANDS_LOWER`] and
//! [`PELLET_LANDS_UPPER`] (both or neither) name the lower lands of the pellets above another
//! and the upper lands of those below (the slave and master sides of the pellet-pellet
//! contact). In r-z the ends are found by coordinate: each body's bottom (its smallest `z`) is
//! held axially, its top (its largest `z`: the pellet's land, or the mid-plane of the top
//! pellet of a stack) is kept plane by the body's axial unknown. In 2D the cross-section is whole (the
//! cladding's surfaces closed curves) and each body is held against rigid motion at two or
//! three nodes of its surfaces.

use std::collections::HashSet;
use std::f64::consts::PI;
use std::path::Path;

use mortar_elements::volume::VolumeRegistry;
use mortar_fem::mesh::{BoundaryFace, VolumeMesh};

use super::PelletError;
use mortar::io::gmsh::{read_gmsh_volume, GmshVolume};
use mortar::io::IoError;

/// The physical group of the pellet's cells.
pub const PELLET: &str = "pellet";
/// The physical group of the cladding's cells.
pub const CLADDING: &str = "cladding";
/// The pellet's lateral surface facing the cladding (the gap's slave side).
pub const PELLET_OUTER: &str = "pellet_outer";
/// The pellet's surfaces wetted by the plenum gas besides [`PELLET_OUTER`] (optional).
pub const PELLET_FREE: &str = "pellet_free";
/// The lower lands of the pellets of a stack that rest on another (the slave side of the
/// pellet-pellet contact; optional, with [`PELLET_LANDS_UPPER`]).
pub const PELLET_LANDS_LOWER: &str = "pellet_lands_lower";
/// The upper lands of the pellets of a stack that another rests on (the master side).
pub const PELLET_LANDS_UPPER: &str = "pellet_lands_upper";
/// The cladding's inner surface (the gap's master side).
pub const CLADDING_INNER: &str = "cladding_inner";
/// The cladding's outer surface (coolant temperature and pressure).
pub const CLADDING_OUTER: &str = "cladding_outer";

/// A set of boundary faces, by cell and local face number.
pub type FaceSet = HashSet<(u32, u8)>;

/// Whether `face` is in `set`.
pub fn contains(set: &FaceSet, face: &BoundaryFace) -> bool {
    set.contains(&(face.cell, face.local_face))
}

/// The bodies and surfaces of a pellet file, and the measures the scene takes from them.
#[derive(Debug, Clone)]
pub struct FileGeometry {
    /// The pellet's cells.
    pub pellet: VolumeMesh,
    /// The cladding's cells.
    pub cladding: VolumeMesh,
    /// [`PELLET_OUTER`]'s faces.
    pub pellet_outer: FaceSet,
    /// [`PELLET_FREE`]'s faces (empty without the group).
    pub pellet_free: FaceSet,
    /// [`CLADDING_INNER`]'s faces.
    pub cladding_inner: FaceSet,
    /// [`CLADDING_OUTER`]'s faces.
    pub cladding_outer: FaceSet,
    /// A stack's lands, [`PELLET_LANDS_LOWER`]'s and [`PELLET_LANDS_UPPER`]'s faces (`None`
    /// without the groups).
    pub lands: Option<[FaceSet; 2]>,
    /// Whether the section is r-z (else the 2D cross-section).
    pub axisymmetric: bool,
    /// The largest radius of the pellet's lateral surface (m).
    pub pellet_radius: f64,
    /// The smallest radius of the cladding's inner surface (m).
    pub inner_radius: f64,
    /// The largest radius of the cladding's outer surface (m).
    pub outer_radius: f64,
    /// The widest radial distance between the gap's sides (m): the largest radius of the
    /// cladding's inner surface less the smallest of the pellet's lateral one.
    pub widest_gap: f64,
    /// The axial extent of the cladding (m): the segment's height in r-z, 1 in 2D.
    pub height: f64,
    /// The pellet's volume (m^3: revolved in r-z; its area, m^2, in 2D).
    pub pellet_volume: f64,
    /// The area of the pellet's top end (the land) projected on the plane `z = H` (m^2): the
    /// area over which the next pellet bears on it (r-z); the pellet's area in 2D.
    pub land_area: f64,
    /// The areas enclosed by the cladding's inner and outer surfaces (m^2; 2D only, 0 in r-z).
    pub enclosed_areas: [f64; 2],
}

impl FileGeometry {
    /// Reads `path`, an r-z section if `axisymmetric`, else a 2D cross-section.
    ///
    /// # Errors
    /// [`PelletError::Io`] for a file or group that cannot be read (naming the file and the
    /// group); [`PelletError::Invalid`] for 3D cells, an r-z section with a node at `r < 0`,
    /// radii not ordered `a < b < c` (the pellet's largest, the cladding's smallest inner and
    /// largest outer), or, in 2D, cladding surfaces that are not closed curves.
    pub fn read(path: &Path, axisymmetric: bool) -> Result<Self, PelletError> {
        let registry = VolumeRegistry::default();
        let pellet = read_gmsh_volume(path, PELLET, &registry)?;
        let cladding = read_gmsh_volume(path, CLADDING, &registry)?;
        let invalid = |what: String| PelletError::Invalid(format!("{}: {what}", path.display()));
        for body in [&pellet, &cladding] {
            if body.dimension != 2 {
                return Err(invalid(format!(
                    "group \"{}\" has {}D cells: a pellet file is an r-z section (2D cells, x = r, y = z)",
                    body.group.name, body.dimension
                )));
            }
            if let Some(x) = body
                .mesh
                .coords()
                .iter()
                .find(|x| axisymmetric && x.x < -1e-12)
            {
                return Err(invalid(format!(
                    "group \"{}\" has a node at r = x = {} < 0: an r-z section lies at x >= 0",
                    body.group.name, x.x
                )));
            }
        }
        let faces = |body: &GmshVolume, group: &str| -> Result<FaceSet, IoError> {
            Ok(body
                .boundary_faces_in(group)?
                .iter()
                .map(|f| (f.cell, f.local_face))
                .collect())
        };
        let pellet_outer = faces(&pellet, PELLET_OUTER)?;
        let pellet_free = match faces(&pellet, PELLET_FREE) {
            Err(IoError::GroupNotFound { .. }) => FaceSet::new(),
            other => other?,
        };
        let cladding_inner = faces(&cladding, CLADDING_INNER)?;
        let cladding_outer = faces(&cladding, CLADDING_OUTER)?;
        let optional = |group: &str| match faces(&pellet, group) {
            Err(IoError::GroupNotFound { .. }) => Ok(None),
            other => other.map(Some),
        };
        let lands = match (optional(PELLET_LANDS_LOWER)?, optional(PELLET_LANDS_UPPER)?) {
            (Some(lower), Some(upper)) if axisymmetric => Some([lower, upper]),
            (None, None) => None,
            (Some(_), Some(_)) => {
                return Err(invalid(format!(
                    "groups \"{PELLET_LANDS_LOWER}\" and \"{PELLET_LANDS_UPPER}\" (a stack's \
                     lands) in a 2D cross-section: a stack is an r-z section"
                )))
            }
            _ => {
                return Err(invalid(format!(
                    "one of the groups \"{PELLET_LANDS_LOWER}\" and \"{PELLET_LANDS_UPPER}\" \
                     without the other: a stack's lands are given in pairs"
                )))
            }
        };
        let (pellet, cladding) = (pellet.mesh, cladding.mesh);
        // The radii of a group's nodes: x in r-z, the distance from the axis in 2D.
        let radius = |x: &nalgebra::Vector3<f64>| if axisymmetric { x.x } else { x.xy().norm() };
        let radii = |mesh: &VolumeMesh, set: &FaceSet| -> Result<Vec<f64>, PelletError> {
            Ok(mesh
                .boundary_faces()?
                .iter()
                .filter(|f| contains(set, f))
                .flat_map(|f| f.nodes.iter().map(|&n| radius(&mesh.coords()[n as usize])))
                .collect())
        };
        let max = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let (outer, inner) = (
            radii(&pellet, &pellet_outer)?,
            radii(&cladding, &cladding_inner)?,
        );
        let (a, b) = (max(&outer), min(&inner));
        let widest_gap = max(&inner) - min(&outer);
        let c = max(&radii(&cladding, &cladding_outer)?);
        if !(a > 0.0 && a < b && b < c) {
            return Err(invalid(format!(
                "the radii of \"{PELLET_OUTER}\" (largest {a}), \"{CLADDING_INNER}\" (smallest \
                 {b}) and \"{CLADDING_OUTER}\" (largest {c}) are not ordered 0 < a < b < c"
            )));
        }
        // The measures: per unit length in 2D, over the segment in r-z.
        let (height, pellet_volume, land_area, enclosed_areas) = if axisymmetric {
            let (height, pellet_volume, land_area) = rz_measures(&pellet, &cladding, path)?;
            (height, pellet_volume, land_area, [0.0; 2])
        } else {
            let area = super::outputs::mesh_area(&pellet).abs();
            let enclosed = [
                enclosed_area(&cladding, &cladding_inner, path, CLADDING_INNER)?,
                enclosed_area(&cladding, &cladding_outer, path, CLADDING_OUTER)?,
            ];
            (1.0, area, area, enclosed)
        };
        Ok(Self {
            pellet,
            cladding,
            pellet_outer,
            pellet_free,
            cladding_inner,
            cladding_outer,
            lands,
            axisymmetric,
            pellet_radius: a,
            inner_radius: b,
            outer_radius: c,
            widest_gap,
            height,
            pellet_volume,
            land_area,
            enclosed_areas,
        })
    }

    /// The volume inside the cladding not taken by the pellet nor by the radial gap between
    /// `r = a` and `r = b` (m^3): the dishes and chamfers, `pi a^2 H - V_pellet` (r-z; 0 in
    /// 2D, where the gap is all there is).
    pub fn end_voids(&self) -> f64 {
        if !self.axisymmetric {
            return 0.0;
        }
        (PI * self.pellet_radius.powi(2) * self.height - self.pellet_volume).max(0.0)
    }

    /// The gap's volume in the file's geometry (m^3 in r-z: `pi (b^2 - a^2) H`; m^2 per unit
    /// length in 2D: the area enclosed by the cladding's inner surface less the pellet's).
    pub fn gap_volume(&self) -> f64 {
        if self.axisymmetric {
            PI * (self.inner_radius.powi(2) - self.pellet_radius.powi(2)) * self.height
        } else {
            self.enclosed_areas[0] - self.pellet_volume
        }
    }
}

/// An r-z section's height (the cladding's axial extent), the pellet's revolved volume and
/// its land's area; both bodies must start at `z = 0`.
fn rz_measures(
    pellet: &VolumeMesh,
    cladding: &VolumeMesh,
    path: &Path,
) -> Result<(f64, f64, f64), PelletError> {
    let invalid = |what: String| PelletError::Invalid(format!("{}: {what}", path.display()));
    let (lo, hi) = cladding
        .coords()
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x.y), hi.max(x.y))
        });
    let height = hi - lo;
    let pellet_bottom = pellet
        .coords()
        .iter()
        .map(|x| x.y)
        .fold(f64::INFINITY, f64::min);
    if lo.abs() > 1e-9 * height || pellet_bottom.abs() > 1e-9 * height {
        return Err(invalid(format!(
            "the section starts at z = {pellet_bottom} (pellet) and z = {lo} (cladding): \
             both bodies start at the plane of symmetry z = y = 0"
        )));
    }
    let pellet_volume = revolved_volume(pellet);
    let land_area = top_area(pellet)?;
    if !(height > 0.0 && pellet_volume > 0.0 && land_area > 0.0) {
        return Err(invalid(format!(
            "a degenerate section: cladding height {height}, pellet volume {pellet_volume}, \
             land area {land_area}"
        )));
    }
    Ok((height, pellet_volume, land_area))
}

/// The area a closed curve of boundary faces (straight edges of a 2D mesh) encloses: the
/// shoelace sum over its edges, which must form closed loops (every node on two edges).
fn enclosed_area(
    mesh: &VolumeMesh,
    set: &FaceSet,
    path: &Path,
    group: &str,
) -> Result<f64, PelletError> {
    let x = mesh.coords();
    let mut ends = std::collections::HashMap::<u32, usize>::new();
    let mut twice = 0.0;
    for f in mesh.boundary_faces()?.iter().filter(|f| contains(set, f)) {
        let (p, q) = (f.nodes[0], f.nodes[f.nodes.len().min(2) - 1]);
        *ends.entry(p).or_default() += 1;
        *ends.entry(q).or_default() += 1;
        let (p, q) = (x[p as usize], x[q as usize]);
        twice += p.x * q.y - q.x * p.y;
    }
    if let Some((&node, _)) = ends.iter().find(|(_, &n)| n != 2) {
        return Err(PelletError::Invalid(format!(
            "{}: group \"{group}\" is not a closed curve (node tag {} ends it): a 2D \
             cross-section is the whole rod",
            path.display(),
            mesh.node_tags()[node as usize]
        )));
    }
    Ok(0.5 * twice.abs())
}

/// `2 pi int r dA` over the cells of an r-z mesh (Pappus; straight-sided cells, node order
/// cyclic as Gmsh gives Tri3 and Quad4).
pub(super) fn revolved_volume(mesh: &VolumeMesh) -> f64 {
    let x = mesh.coords();
    let moment: f64 = (0..mesh.cell_count())
        .map(|c| {
            let nodes = mesh.cell(c).nodes;
            let n = nodes.len().min(4);
            (0..n)
                .map(|i| {
                    let (p, q) = (x[nodes[i] as usize], x[nodes[(i + 1) % n] as usize]);
                    (p.x + q.x) * (p.x * q.y - q.x * p.y)
                })
                .sum::<f64>()
                / 6.0
        })
        .sum();
    2.0 * PI * moment.abs()
}

/// The area of the boundary faces of an r-z mesh at its largest `z`, revolved and projected
/// on that plane: `sum pi |r_2^2 - r_1^2|`.
fn top_area(mesh: &VolumeMesh) -> Result<f64, PelletError> {
    let x = mesh.coords();
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    let tol = 1e-9 * (hi - lo);
    Ok(mesh
        .boundary_faces()?
        .iter()
        .filter(|f| f.nodes.iter().all(|&n| x[n as usize].y >= hi - tol))
        .map(|f| {
            let (r1, r2) = (x[f.nodes[0] as usize].x, x[f.nodes[1] as usize].x);
            PI * (r2 * r2 - r1 * r1).abs()
        })
        .sum())
}
