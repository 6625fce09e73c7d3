//! A disc in a square or a ball in a cube (`Inclusion`): O-grid meshes of the inclusion
//! (`ball_mesh`) and of the box around it (`box_with_hole_mesh`).

use std::collections::HashMap;

use mortar_elements::volume::{HEX8, QUAD4, TRI3};
use mortar_fem::element::VolumeElementRef;
use mortar_fem::mesh::{VolumeMesh, VolumeMeshError};
use nalgebra::Vector3;

use super::CellShape;

/// A spherical inclusion in a box: a disc in a square (`dim = 2`, plane `z = 0`) or a ball in
/// a cube (`dim = 3`), both centred at `centre`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inclusion {
    /// 2 or 3.
    pub dim: usize,
    /// The centre of the box and of the inclusion (`z` ignored in 2D).
    pub centre: [f64; 3],
    /// The radius of the inclusion.
    pub radius: f64,
    /// The half-width of the box (greater than the radius).
    pub half_width: f64,
}

impl Inclusion {
    /// The unit square (cube) `[0, 1]^dim` with an inclusion of radius `radius` at its centre.
    pub fn unit(dim: usize, radius: f64) -> Self {
        Self {
            dim,
            centre: [0.5, 0.5, if dim == 3 { 0.5 } else { 0.0 }],
            radius,
            half_width: 0.5,
        }
    }
}

/// Which body of an inclusion geometry a builder makes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Part {
    /// The ball: a core cube of half-width `core` and a shell out to the sphere.
    Ball { core: f64 },
    /// The box of half-width `half` minus the ball.
    Hole { half: f64 },
}

/// An O-grid: `2 dim` blocks between the cube face grid (in cube coordinates
/// `q in [-1, 1]^dim`, `|q|_inf = 1`) and the sphere, plus (for the ball) the core cube.
/// Nodes are keyed by integers (the radial layer and the cube lattice point), so that blocks
/// share their nodes exactly.
struct OGrid {
    dim: usize,
    centre: Vector3<f64>,
    radius: f64,
    n: i64,
    layers: i64,
    part: Part,
    mesh: VolumeMesh,
    tags: HashMap<[i64; 4], u64>,
    next_tag: u64,
}

impl OGrid {
    fn point(&self, key: [i64; 4]) -> [f64; 3] {
        let [r, qi @ ..] = key;
        let mut q = Vector3::zeros();
        for d in 0..self.dim {
            q[d] = qi[d] as f64 / self.n as f64;
        }
        let x = match (self.part, r) {
            (Part::Ball { core }, r) if r < 0 => self.centre + q * core,
            (part, r) => {
                let rho = r as f64 / self.layers as f64;
                // Equiangular points on the sphere (cubed sphere), uniform on the flat side.
                let mut qe = Vector3::zeros();
                for d in 0..self.dim {
                    qe[d] = (std::f64::consts::FRAC_PI_4 * q[d]).tan();
                }
                let sphere = self.centre + qe.normalize() * self.radius;
                match part {
                    Part::Ball { core } => (self.centre + q * core) * (1.0 - rho) + sphere * rho,
                    Part::Hole { half } => sphere * (1.0 - rho) + (self.centre + q * half) * rho,
                }
            }
        };
        x.into()
    }

    fn node(&mut self, key: [i64; 4]) -> Result<u64, VolumeMeshError> {
        if let Some(&t) = self.tags.get(&key) {
            return Ok(t);
        }
        let tag = self.next_tag;
        self.mesh.add_node(tag, self.point(key))?;
        self.tags.insert(key, tag);
        self.next_tag += 1;
        Ok(tag)
    }

    /// Adds a quad or hex given by lattice keys in tensor order (x fastest), reordered to a
    /// positive orientation; 2D quads are cut in two triangles for `CellShape::Simplex`.
    fn cell(&mut self, keys: &[[i64; 4]], shape: CellShape) -> Result<(), VolumeMeshError> {
        let tags: Vec<u64> = keys
            .iter()
            .map(|&k| self.node(k))
            .collect::<Result<_, _>>()?;
        // Tensor order -> Gmsh order.
        let (el, order): (VolumeElementRef, &[usize]) = if self.dim == 2 {
            (&QUAD4, &[0, 1, 3, 2])
        } else {
            (&HEX8, &[0, 1, 3, 2, 4, 5, 7, 6])
        };
        let mut cell: Vec<u64> = order.iter().map(|&i| tags[i]).collect();
        let x: Vec<Vector3<f64>> = cell
            .iter()
            .map(|t| self.mesh.coords()[self.mesh.node_index(*t).expect("added") as usize])
            .collect();
        let centre = el.domain().centre();
        if el.jacobian(&x, &centre).determinant() < 0.0 {
            // Mirror the first reference direction.
            let mirror: &[usize] = if self.dim == 2 {
                &[1, 0, 3, 2]
            } else {
                &[1, 0, 3, 2, 5, 4, 7, 6]
            };
            cell = mirror.iter().map(|&i| cell[i]).collect();
        }
        if self.dim == 2 && shape == CellShape::Simplex {
            self.mesh.add_cell(&TRI3, &[cell[0], cell[1], cell[2]])?;
            self.mesh.add_cell(&TRI3, &[cell[0], cell[2], cell[3]])?;
        } else {
            self.mesh.add_cell(el, &cell)?;
        }
        Ok(())
    }

    /// The shell blocks: one per cube face, `n^(dim-1)` cells across and `layers` radially.
    fn shells(&mut self, shape: CellShape) -> Result<(), VolumeMeshError> {
        let n = self.n;
        let dim = self.dim;
        let across = if dim == 2 { 1 } else { n };
        for axis in 0..dim {
            for sign in [-1i64, 1] {
                let others: Vec<usize> = (0..dim).filter(|&d| d != axis).collect();
                for r in 0..self.layers {
                    for j in 0..across {
                        for i in 0..n {
                            let mut keys = Vec::with_capacity(8);
                            for dr in 0..2 {
                                for dj in 0..(dim as i64 - 1) {
                                    for di in 0..2 {
                                        let mut k = [r + dr, 0, 0, 0];
                                        k[1 + axis] = sign * n;
                                        k[1 + others[0]] = 2 * (i + di) - n;
                                        if dim == 3 {
                                            k[1 + others[1]] = 2 * (j + dj) - n;
                                        }
                                        keys.push(k);
                                    }
                                }
                            }
                            self.cell(&keys, shape)?;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The core cube of the ball: `n^dim` cells.
    fn core(&mut self) -> Result<(), VolumeMeshError> {
        let n = self.n;
        let dim = self.dim;
        let nk = if dim == 2 { 1 } else { n };
        let key = |i: i64, j: i64, k: i64| {
            let q = [2 * i - n, 2 * j - n, if dim == 3 { 2 * k - n } else { 0 }];
            let boundary = q[..dim].iter().any(|c| c.abs() == n);
            [if boundary { 0 } else { -1 }, q[0], q[1], q[2]]
        };
        for k in 0..nk {
            for j in 0..n {
                for i in 0..n {
                    let mut keys = Vec::with_capacity(8);
                    for dk in 0..(dim as i64 - 1) {
                        for dj in 0..2 {
                            for di in 0..2 {
                                keys.push(key(i + di, j + dj, k + dk));
                            }
                        }
                    }
                    self.cell(&keys, CellShape::Tensor)?;
                }
            }
        }
        Ok(())
    }
}

fn check(dim: usize, radius: f64, n: usize, layers: usize) -> Result<(), VolumeMeshError> {
    let bad = |reason: String| VolumeMeshError::BadCell {
        cell: 0,
        element: "O-grid",
        reason,
    };
    if dim != 2 && dim != 3 {
        return Err(bad(format!("dimension {dim} (2 or 3)")));
    }
    if !(radius > 0.0 && radius.is_finite()) || n == 0 || layers == 0 {
        return Err(bad(format!(
            "radius {radius}, {n} cells across and {layers} layers (all positive)"
        )));
    }
    Ok(())
}

/// The inclusion of `geometry`: a disc (`dim = 2`, in the plane `z = 0`) or ball
/// (`dim = 3`), meshed by an O-grid of Quad4 / Hex8: a core square (cube) of half-width
/// `radius / 2` with `n` cells per side, and `2 dim` blocks of `n` (x `n`) cells across and
/// `layers` cells radially out to the circle (sphere), whose nodes are equiangular (the cubed
/// sphere): `4 n` boundary edges in 2D, `6 n^2` boundary quads in 3D. Nodes are tagged from
/// `first_node_tag`.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for a dimension other than 2 or 3, a non-positive radius, or
/// zero cells.
pub fn ball_mesh(
    geometry: &Inclusion,
    n: usize,
    layers: usize,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    let Inclusion {
        dim,
        centre,
        radius,
        ..
    } = *geometry;
    check(dim, radius, n, layers)?;
    let mut g = OGrid {
        dim,
        centre: Vector3::from(centre),
        radius,
        n: n as i64,
        layers: layers as i64,
        part: Part::Ball { core: radius / 2.0 },
        mesh: VolumeMesh::new(),
        tags: HashMap::new(),
        next_tag: first_node_tag,
    };
    g.core()?;
    g.shells(CellShape::Tensor)?;
    Ok(g.mesh)
}

/// The box of `geometry` (a square for `dim = 2`, a cube for `dim = 3`) minus its inclusion:
/// an O-grid of
/// `2 dim` blocks with `n` (x `n`) cells along each side and `layers` cells from the circle
/// (sphere, equiangular nodes) to the box. In 2D the quads are cut into Tri3 for
/// `CellShape::Simplex`; in 3D the cells are Hex8 whatever `shape`. Nodes are tagged from
/// `first_node_tag`.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for a dimension other than 2 or 3, a radius not inside the
/// box, or zero cells.
pub fn box_with_hole_mesh(
    geometry: &Inclusion,
    n: usize,
    layers: usize,
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    let Inclusion {
        dim,
        centre,
        radius,
        half_width,
    } = *geometry;
    check(dim, radius, n, layers)?;
    if radius.is_nan() || radius >= half_width {
        return Err(VolumeMeshError::BadCell {
            cell: 0,
            element: "O-grid",
            reason: format!("radius {radius} is not below the half-width {half_width}"),
        });
    }
    let mut g = OGrid {
        dim,
        centre: Vector3::from(centre),
        radius,
        n: n as i64,
        layers: layers as i64,
        part: Part::Hole { half: half_width },
        mesh: VolumeMesh::new(),
        tags: HashMap::new(),
        next_tag: first_node_tag,
    };
    g.shells(shape)?;
    Ok(g.mesh)
}
