//! Stress recovery: the Cauchy stress per cell and averaged at the nodes, with the von Mises
//! stress; in 2D plane strain, generalized plane strain (an axial strain) or r-z.

use mortar_fem::element::{CellValues, MAX_CELL_NODES};
use nalgebra::Vector3;
use rayon::prelude::*;

use super::assembly::{check, hoop_factor, reinit_cell, ElasticOptions, CELL_CHUNK};
use super::body::ElasticBody;
use super::material::von_mises;
use crate::error::PhysicsError;
use crate::field::cells;

/// A cell's mean stress and its volume.
type CellMean = ([f64; 6], f64);

/// Recovered Cauchy stresses, in Voigt order `[xx, yy, zz, yz, xz, xy]` (tensor components,
/// Pa). In the axisymmetric geometry (r -> x, z -> y, theta -> z) the order reads
/// `[rr, zz, tt, 0, 0, rz]`: the hoop stress `sigma_tt` is in the `zz` slot (index 2).
#[derive(Debug, Clone, PartialEq)]
pub struct StressField {
    /// Per mesh node: the average of the mean stresses of the cells around it, weighted by
    /// the cells' volumes (areas in 2D). NaN at a node of no cell.
    pub nodal: Vec<[f64; 6]>,
    /// Per mesh node: the von Mises stress of the averaged nodal stress (not an average of
    /// von Mises stresses).
    pub von_mises: Vec<f64>,
    /// Per cell: its mean stress, `int sigma / |cell|` by the cell's quadrature rule.
    pub cells: Vec<[f64; 6]>,
}

/// Recovers the stress of the displacement `displacement` (numbered by the body's
/// [`layout`](ElasticBody::layout)):
/// `sigma = lambda tr(eps) I + 2 mu eps - 3 K alpha (T - T_ref) I` at every quadrature point
/// of every cell, with `eps = sym(grad u)` less the body's eigenstrain
/// ([`ElasticBody::eigenstrain`], if any) and `T` the body's temperature field
/// interpolated (no thermal term without one). In 2D (plane strain) `eps_zz = 0`, so
/// `sigma_zz = lambda (eps_xx + eps_yy) - 3 K alpha (T - T_ref)` and
/// `sigma_xz = sigma_yz = 0`. In the axisymmetric geometry ([`ElasticOptions::geometry`]) the
/// strain is `[eps_rr, eps_zz, eps_tt = u_r / r, 0, 0, gamma_rz]` in the Voigt slots
/// `[xx, yy, zz, yz, xz, xy]`, so the hoop stress `sigma_tt` lands in the `zz` slot, and the
/// von Mises stress includes it; the cell means and volumes are those of the revolved cells
/// (weight `2 pi r`).
///
/// The cell mean is the quadrature-weighted mean over the cell (`int sigma / |cell|`); the
/// nodal value is the mean of the cell means of the cells around the node weighted by the
/// cell volumes, `sum_c |c| sigma_c / sum_c |c|` (exact for a constant stress; for a
/// varying one a first-order smoothing, not a superconvergent recovery). The cells are
/// processed in parallel over fixed chunks and the nodal sums taken in cell order (bit-for-bit
/// the same for any thread count).
///
/// # Errors
/// [`PhysicsError::WrongLength`] if `displacement` does not have `nodes * dim` values; as
/// [`assemble_elastic_stiffness`](super::assemble_elastic_stiffness) otherwise.
pub fn recover_stress(
    body: &ElasticBody,
    displacement: &[f64],
    options: &ElasticOptions,
) -> Result<StressField, PhysicsError> {
    recover_stress_with_axial_strain(body, displacement, 0.0, options)
}

/// [`recover_stress`] of a 2D body in generalized plane strain
/// ([`GeneralizedPlaneStrain`](super::GeneralizedPlaneStrain)): the axial strain is
/// `eps_zz = axial_strain` instead of zero, so
/// `sigma_zz = lambda (eps_xx + eps_yy) + (lambda + 2 mu) eps_zz - 3 K alpha (T - T_ref)`
/// and the in-plane normal stresses gain `lambda eps_zz`. Ignored (must be zero) in 3D and in
/// the axisymmetric geometry, whose hoop strain is in that slot.
///
/// # Errors
/// As [`recover_stress`]; [`PhysicsError::InvalidInput`] for a non-zero `axial_strain` on a
/// 3D or axisymmetric body.
pub fn recover_stress_with_axial_strain(
    body: &ElasticBody,
    displacement: &[f64],
    axial_strain: f64,
    options: &ElasticOptions,
) -> Result<StressField, PhysicsError> {
    check(body, options)?;
    if axial_strain != 0.0 && (body.layout().components != 2 || options.geometry.is_axisymmetric())
    {
        return Err(body.invalid(format!(
            "an axial strain ({axial_strain}) is a 2D Cartesian body's generalized plane strain"
        )));
    }
    let layout = body.layout();
    if displacement.len() != layout.len() {
        return Err(PhysicsError::WrongLength {
            what: format!("body {:?}: displacement", body.name),
            expected: layout.len(),
            got: displacement.len(),
        });
    }
    let recovery = Recovery {
        body,
        displacement,
        axial_strain,
        options,
    };
    let cells = body.mesh.cell_count();
    let chunks: Vec<Result<Vec<CellMean>, PhysicsError>> = (0..cells.div_ceil(CELL_CHUNK))
        .into_par_iter()
        .map(|ch| {
            let mut out = Vec::with_capacity(CELL_CHUNK);
            let mut cell = CellScratch::new();
            for c in ch * CELL_CHUNK..((ch + 1) * CELL_CHUNK).min(cells) {
                out.push(recovery.cell_mean(c, &mut cell)?);
            }
            Ok(out)
        })
        .collect();
    let (nodal, cell_stress) = nodal_average(body, chunks)?;
    let von_mises = nodal.iter().map(von_mises).collect();
    Ok(StressField {
        nodal,
        von_mises,
        cells: cell_stress,
    })
}

/// The stress of one displacement of a body, cell by cell
/// ([`recover_stress_with_axial_strain`]).
struct Recovery<'a> {
    body: &'a ElasticBody,
    displacement: &'a [f64],
    axial_strain: f64,
    options: &'a ElasticOptions,
}

/// The values of one cell: its quadrature, node coordinates, nodal displacements and
/// temperature differences.
struct CellScratch {
    cv: CellValues,
    x: [Vector3<f64>; MAX_CELL_NODES],
    ue: [Vector3<f64>; MAX_CELL_NODES],
    dt: [f64; MAX_CELL_NODES],
}

impl CellScratch {
    fn new() -> Self {
        Self {
            cv: CellValues::new(),
            x: [Vector3::zeros(); MAX_CELL_NODES],
            ue: [Vector3::zeros(); MAX_CELL_NODES],
            dt: [0.0; MAX_CELL_NODES],
        }
    }
}

impl Recovery<'_> {
    /// Cell `c`'s mean stress and volume (`cell`: the scratch values, reset here).
    fn cell_mean(&self, c: usize, cell: &mut CellScratch) -> Result<CellMean, PhysicsError> {
        let (body, options) = (self.body, self.options);
        let layout = body.layout();
        let dim = layout.components;
        let t_ref = body.material.reference_temperature;
        let nodes = body.mesh.cell(c).nodes;
        let nn = reinit_cell(body, options, c, &mut cell.cv, &mut cell.x)?;
        for (u, &n) in cell.ue.iter_mut().zip(nodes) {
            *u = Vector3::zeros();
            for i in 0..dim {
                u[i] = self.displacement[layout.dof(n, i) as usize];
            }
        }
        if let Some(t) = &body.temperature {
            for (d, &n) in cell.dt.iter_mut().zip(nodes) {
                *d = t[n as usize] - t_ref;
            }
        } else {
            cell.dt[..nn].fill(0.0);
        }
        let cv = &cell.cv;
        let mut sum = [0.0; 6];
        let mut volume = 0.0;
        for q in 0..cv.len() {
            let w = cells::weight(cv, q, options.geometry);
            let strain = self.strain(cv, q, &cell.ue[..nn]);
            let s = body.material.stress(&strain, cv.value(q, &cell.dt[..nn]));
            for (acc, v) in sum.iter_mut().zip(s) {
                *acc += v * w;
            }
            volume += w;
        }
        Ok((sum.map(|v| v / volume), volume))
    }

    /// The strain at point `q` of a cell (`cv`) of nodal displacements `ue`, Voigt order
    /// with engineering shears, less the body's eigenstrain: the axial strain in the zz
    /// slot, or in r-z the hoop strain `u_r / r`.
    fn strain(&self, cv: &CellValues, q: usize, ue: &[Vector3<f64>]) -> [f64; 6] {
        let axi = self.options.geometry.is_axisymmetric();
        let g = cv.gradients(q);
        // The displacement gradient h[i][j] = du_i/dx_j (zero third row and column in 2D).
        let mut h = [[0.0; 3]; 3];
        h[2][2] = self.axial_strain;
        for (u, ga) in ue.iter().zip(g) {
            for i in 0..3 {
                for j in 0..3 {
                    h[i][j] += u[i] * ga[j];
                }
            }
        }
        if axi {
            // The hoop strain u_r / r, in the zz slot.
            let ur: f64 = cv.shape(q).iter().zip(ue).map(|(n, u)| n * u.x).sum();
            h[2][2] = ur * hoop_factor(cv, q, axi);
        }
        let mut strain = [
            h[0][0],
            h[1][1],
            h[2][2],
            h[1][2] + h[2][1],
            h[0][2] + h[2][0],
            h[0][1] + h[1][0],
        ];
        if let Some(e) = &self.body.eigenstrain {
            for (s, e) in strain.iter_mut().zip(e) {
                *s -= e;
            }
        }
        strain
    }
}

/// The nodal stresses, the volume-weighted means of the cell means `chunks` (in cell
/// order) of the cells around each node (NaN at a node of no cell), and the cell means.
#[allow(clippy::type_complexity)]
fn nodal_average(
    body: &ElasticBody,
    chunks: Vec<Result<Vec<CellMean>, PhysicsError>>,
) -> Result<(Vec<[f64; 6]>, Vec<[f64; 6]>), PhysicsError> {
    let mesh = &body.mesh;
    let n = mesh.node_count();
    let mut nodal = vec![[0.0; 6]; n];
    let mut weight = vec![0.0; n];
    let mut cell_stress = Vec::with_capacity(mesh.cell_count());
    let mut c = 0;
    for ch in chunks {
        for (s, volume) in ch? {
            for &node in mesh.cell(c).nodes {
                let acc = &mut nodal[node as usize];
                for (a, v) in acc.iter_mut().zip(s) {
                    *a += volume * v;
                }
                weight[node as usize] += volume;
            }
            cell_stress.push(s);
            c += 1;
        }
    }
    for (s, w) in nodal.iter_mut().zip(&weight) {
        *s = if *w > 0.0 {
            s.map(|v| v / w)
        } else {
            [f64::NAN; 6]
        };
    }
    Ok((nodal, cell_stress))
}
