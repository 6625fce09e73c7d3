//! Speed for accuracy on curved interfaces with second-order faces,
//! on two surfaces whose areas are known:
//!
//! - `sphere`: the sphere of radius 0.3 between a ball (master) and the box around it
//!   (slave), both O-grids of Hex8 cells (equiangular on the sphere) raised to Hex27, meshed
//!   independently, the second-order nodes on the sphere (`generate::onto_sphere`); Quad4 or
//!   Quad9 faces; exact area `4 pi r^2`;
//! - `cylinder`: the quarter cylinder `r = 0.3`, `0 <= z <= 0.3` between a solid (an extruded
//!   quarter annulus `0.15 <= r <= 0.3`, Hex8 or Hex27, master: Quad4/Quad9 faces) and a tube
//!   around it (`0.3 <= r <= 0.45`, Hex8 or Hex20: Quad4/Quad8 faces, slave), meshed
//!   independently, the second-order nodes on the cylinder (`generate::onto_cylinder`); exact
//!   area `(pi / 2) r h`.
//!
//! Both with `n / 2 + 1` master and `3 n / 4 + 1` slave cells along each side of a patch (see
//! `cells`). The dials: element order (1 or 2), the curved-face subdivision level (1, 2, 4,
//! 8, 16, or from the default tolerance) and the multiplier space (standard, dual).
//!
//! Reported per option (one thread, median of `--repeats` couplings; levels 8 and 16 once):
//! the time of the coupling and the time per slave-master pair; the error of the interface
//! area, sum(D) against the exact area (this includes the geometric error of the quadratic
//! surface, which no subdivision removes: the reference's own area error shows it); the
//! errors of D and of M against an independent reference (largest entry difference over the
//! largest entry, and for M also the relative Frobenius norm); M against the level-16 M;
//! the error of the tied field: the slave values `D^-1 M u_m` of the master's nodal values
//! of `u = 1 + 2x - 3y + z`, against `u` at the slave nodes (largest, over the largest
//! `|u|`).
//!
//! The reference: `integration::AdaptiveElementBased` (no clipping, no flat sub-faces: the
//! slave face's reference domain split recursively where master edges cross it, degree-12
//! rules on the leaves, each point projected onto the curved master face by Newton), along
//! the projector's direction at each slave face's centre, as the segment-based strategy
//! projects (the normal of its auxiliary plane), to depth `--depth` (default 7). Its own
//! error is estimated by the change of D and M from depth `--depth - 1` (printed, and in the
//! JSON as `reference_change_d` and `reference_change_m`). The change of M from projecting
//! along the direction field at each point instead (the element-based convention) is
//! printed too (`reference_m_pointwise_direction`, standard multipliers).
//!
//! Prints a table and, with `--json FILE`, writes it.
//!
//! ```sh
//! cargo run --release --example curved_segmentation -- [--n 4] [--repeats 3] [--depth 7] \
//!     [--cases sphere,cylinder] [--json FILE]
//! ```

use std::time::Instant;

use mortar::core::integration::curved_3d::DEFAULT_CURVED_TOLERANCE;
use mortar::core::integration::{AdaptiveElementBased, IntegrationStrategy, SegmentBased};
use mortar::core::linalg::solve_sparse_lu;
use mortar::generate::{
    ball_mesh, box_with_hole_mesh, extrude_mesh, onto_cylinder, onto_sphere, quarter_annulus_mesh,
    second_order_mesh, CellShape, Inclusion, SecondOrder,
};
use mortar::{assemble_coupling, Coupling, CouplingOptions, Interface, VolumeMesh};
use nalgebra::Vector3;
use serde_json::json;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

fn main() -> Res<()> {
    run(&std::env::args().skip(1).collect::<Vec<_>>())
}

/// The curved surfaces of the study.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Case {
    /// The sphere r = 0.3.
    Sphere,
    /// The quarter cylinder r = 0.3, height 0.3.
    Cylinder,
}

/// The radius of both surfaces, and the cylinder's height.
const R: f64 = 0.3;
const H: f64 = 0.3;

impl Case {
    fn name(self) -> &'static str {
        match self {
            Case::Sphere => "sphere",
            Case::Cylinder => "cylinder",
        }
    }

    fn parse(s: &str) -> Res<Self> {
        match s {
            "sphere" => Ok(Case::Sphere),
            "cylinder" => Ok(Case::Cylinder),
            _ => Err(format!("unknown case {s:?} (sphere, cylinder)").into()),
        }
    }

    /// What the case measures, in a sentence.
    fn description(self) -> &'static str {
        match self {
            Case::Sphere => CASE,
            Case::Cylinder => {
                "quarter cylinder r = 0.3, h = 0.3: tube 0.3 <= r <= 0.45 of Hex8/Hex20 (slave, \
                 Quad4/Quad8 faces) around a solid 0.15 <= r <= 0.3 of Hex8/Hex27 (master, \
                 Quad4/Quad9 faces), extruded quarter annuli, 3n/4 + 1 and n/2 + 1 cells along \
                 the angle and along z"
            }
        }
    }

    /// The exact area of the curved surface.
    pub fn exact_area(self) -> f64 {
        match self {
            Case::Sphere => 4.0 * std::f64::consts::PI * R * R,
            Case::Cylinder => std::f64::consts::FRAC_PI_2 * R * H,
        }
    }

    /// The interface of the two bodies raised to `order`, at size `n`.
    pub fn interface(self, n: usize, order: u32) -> Res<Interface> {
        match self {
            Case::Sphere => sphere_interface(n, order),
            Case::Cylinder => cylinder_interface(n, order),
        }
    }
}

/// The largest entry of `a - b` over the largest entry of `b`.
pub fn difference(a: &sprs::CsMat<f64>, b: &sprs::CsMat<f64>) -> Res<f64> {
    if a.shape() != b.shape() {
        return Err(format!("shapes {:?} and {:?} differ", a.shape(), b.shape()).into());
    }
    let scale = b.data().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a - b;
    Ok(diff.data().iter().fold(0.0f64, |m, v| m.max(v.abs())) / scale)
}

/// `|a - b|_F / |b|_F`.
fn frobenius(a: &sprs::CsMat<f64>, b: &sprs::CsMat<f64>) -> f64 {
    let norm = |m: &sprs::CsMat<f64>| m.data().iter().map(|v| v * v).sum::<f64>().sqrt();
    norm(&(a - b)) / norm(b)
}

fn field(x: &Vector3<f64>) -> f64 {
    1.0 + 2.0 * x.x - 3.0 * x.y + x.z
}

/// The cells along a side of the master and of the slave at size `n`: `n / 2 + 1` and
/// `3 n / 4 + 1` (5 and 7 at n = 8, 3 and 4 at n = 4). Not 2:3: there the master's edges run
/// along the middle lines of slave faces (both meshes are uniform in the angle and in z),
/// which are lines of the curved segmentation's sub-triangles at even levels and of the
/// reference's leaves, a special case that flatters both.
fn cells(n: usize) -> (usize, usize) {
    (n / 2 + 1, 3 * n / 4 + 1)
}

/// The sphere's interface: a box of Tet cells (slave) around a ball of Hex cells (master).
fn sphere_interface(n: usize, order: u32) -> Res<Interface> {
    let g = Inclusion::unit(3, R);
    let (nb, mb) = cells(n);
    let raise = |m: VolumeMesh| -> Res<VolumeMesh> {
        Ok(match order {
            1 => m,
            _ => second_order_mesh(&m, SecondOrder::Complete, onto_sphere(g.centre, g.radius))?,
        })
    };
    let master = raise(ball_mesh(&g, nb, (nb / 2).max(1), 1)?)?;
    let slave = raise(box_with_hole_mesh(
        &g,
        mb,
        (mb / 2).max(1),
        CellShape::Simplex,
        1_000_001,
    )?)?;
    let c = Vector3::from(g.centre);
    let near = |f: &mortar::core::mesh::BoundaryFace| (f.centroid - c).norm() < 0.4;
    Ok(Interface::new(
        slave.boundary_surface(near)?,
        master.boundary_surface(near)?,
    )?)
}

/// The cylinder's interface: a tube of Hex8/Hex20 cells (slave) around a solid of
/// Hex8/Hex27 cells (master), both extruded quarter annuli about the z axis.
fn cylinder_interface(n: usize, order: u32) -> Res<Interface> {
    let (nb, mb) = cells(n);
    let body = |inner: f64, outer: f64, cells: usize, family: SecondOrder, first: u64| {
        let annulus = quarter_annulus_mesh(inner, outer, [cells, 1], CellShape::Tensor, first)?;
        let z: Vec<f64> = (0..=cells).map(|k| H * k as f64 / cells as f64).collect();
        let hex = extrude_mesh(&annulus, &z, first)?;
        Ok::<_, Box<dyn std::error::Error>>(match order {
            1 => hex,
            _ => second_order_mesh(&hex, family, onto_cylinder([0.0; 3], [0.0, 0.0, 1.0], R))?,
        })
    };
    let master = body(0.5 * R, R, nb, SecondOrder::Complete, 1)?;
    let slave = body(R, 1.5 * R, mb, SecondOrder::Serendipity, 1_000_001)?;
    // The lateral faces at r = R (the others' centroids are at least 0.05 R away from it).
    let near = |f: &mortar::core::mesh::BoundaryFace| (f.centroid.xy().norm() - R).abs() < 0.02;
    Ok(Interface::new(
        slave.boundary_surface(near)?,
        master.boundary_surface(near)?,
    )?)
}

/// The tied field's error: `D^-1 M u_m` against `u` at the slave nodes.
fn tied_error(c: &Coupling, i: &Interface) -> Res<f64> {
    let at = |mesh: &mortar::SurfaceMesh, tags: &[u64]| -> Vec<f64> {
        tags.iter()
            .map(|t| field(&mesh.coords()[mesh.node_index(*t).expect("tag") as usize]))
            .collect()
    };
    let (us, um) = (
        at(i.slave(), &c.slave_nodes),
        at(i.master(), &c.master_nodes),
    );
    let mu: Vec<f64> =
        c.m.outer_iterator()
            .map(|row| row.iter().map(|(j, v)| v * um[j]).sum())
            .collect();
    let u = solve_sparse_lu(&c.d, &mu)?;
    let scale = us.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    Ok(u.iter()
        .zip(&us)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale)
}

/// Runs the study with the arguments
/// `[--n N] [--repeats R] [--depth D] [--cases sphere,cylinder] [--json FILE]`.
pub fn run(args: &[String]) -> Res<()> {
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
    };
    let n: usize = value("--n").map_or(Ok(4), |v| v.parse())?;
    let repeats: usize = value("--repeats").map_or(Ok(3), |v| v.parse())?;
    let depth: u32 = value("--depth").map_or(Ok(7), |v| v.parse())?;
    let cases = value("--cases")
        .map_or("sphere,cylinder", |v| v.as_str())
        .split(',')
        .map(Case::parse)
        .collect::<Res<Vec<_>>>()?;
    let start = Instant::now();
    let mut rows = Vec::new();
    for &case in &cases {
        rows.extend(study_case(case, n, repeats, Some(depth))?);
    }
    println!("{:.0} s in all", start.elapsed().as_secs_f64());
    if let Some(path) = value("--json") {
        let report = json!({
            "cases": cases.iter().map(|c| json!({"case": c.name(), "description": c.description(),
                "exact_area": c.exact_area()})).collect::<Vec<_>>(),
            "reference": reference(depth)?.name(),
            "n": n, "repeats": repeats, "threads": 1, "rows": rows,
        });
        std::fs::write(path, serde_json::to_string_pretty(&report)?)?;
    }
    Ok(())
}

/// What [`study`] measures, in a sentence.
pub const CASE: &str = "sphere r = 0.3: box of Hex8/Hex27 (slave, Quad4/Quad9 faces) around a ball of Hex8/Hex27 (master), O-grids, 3n/4 + 1 and n/2 + 1 cells along each side of the 6 patches";

/// The reference strategy at maximum depth `depth` (see the module documentation).
pub fn reference(depth: u32) -> Res<AdaptiveElementBased> {
    Ok(AdaptiveElementBased::new(12, 2.min(depth), depth)?.along_centre_direction())
}

/// The sphere's rows without the independent reference (M against the same order's
/// level-16 M only, `m_error_vs_level_16`), as `bench_coupling --tradeoff` tabulates them:
/// see [`study_case`].
pub fn study(n: usize, repeats: usize) -> Res<Vec<serde_json::Value>> {
    study_case(Case::Sphere, n, repeats, None)
}

/// Every option of the dials on `case` at size `n`, each timed as the median of `repeats`
/// couplings (levels 8 and 16: one): one JSON object per option (case, order, level,
/// multipliers, faces, pairs, seconds, seconds per pair, area error, M against level 16,
/// tied-field error; with a reference depth, also the level-16 row, the errors of D and M
/// against the reference, the reference's area error, its change from one depth less and
/// its time), printed as a table as it goes.
pub fn study_case(
    case: Case,
    n: usize,
    repeats: usize,
    depth: Option<u32>,
) -> Res<Vec<serde_json::Value>> {
    let exact_area = case.exact_area();
    let couple = |i: &Interface,
                  strategy: &dyn Fn() -> Res<std::sync::Arc<dyn IntegrationStrategy>>,
                  dual: bool,
                  repeats: usize|
     -> Res<(Coupling, f64)> {
        let mut options = CouplingOptions::default().threads(1);
        if dual {
            options = options.dual();
        }
        options.integration = strategy()?;
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..repeats.max(1) {
            let t = Instant::now();
            last = Some(assemble_coupling(i, &options)?);
            times.push(t.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        Ok((last.expect("one run"), times[times.len() / 2]))
    };
    let segment = |level: Option<u32>| -> Res<std::sync::Arc<dyn IntegrationStrategy>> {
        Ok(std::sync::Arc::new(match level {
            Some(l) => SegmentBased::default().with_subdivision(l)?,
            None => SegmentBased::default(),
        }))
    };
    println!("{}", case.description());
    println!(
        "{:>8} {:>5} {:>8} {:>8} {:>5} {:>8} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "case",
        "order",
        "level",
        "mult.",
        "pairs",
        "seconds",
        "us/pair",
        "area err",
        "D err",
        "M err",
        "M err F",
        "M vs 16",
        "tied err"
    );
    let mut rows = Vec::new();
    for order in [1u32, 2] {
        let i = case.interface(n, order)?;
        let mut levels: Vec<Option<u32>> = match order {
            1 => vec![None],
            _ => vec![Some(1), Some(2), Some(4), Some(8), None],
        };
        if order == 2 && depth.is_some() {
            levels.insert(4, Some(16));
        }
        for dual in [false, true] {
            let mult = if dual { "dual" } else { "standard" };
            let (level16, seconds16) = couple(&i, &|| segment(Some(16)), dual, 1)?;
            // The reference, its change from one depth less, and (standard multipliers) the
            // change from projecting along the direction at each point.
            let reference = match depth {
                None => None,
                Some(depth) => {
                    let t = Instant::now();
                    let (r, _) =
                        couple(&i, &|| Ok(std::sync::Arc::new(reference(depth)?)), dual, 1)?;
                    let seconds = t.elapsed().as_secs_f64();
                    let (coarser, _) = couple(
                        &i,
                        &|| {
                            Ok(std::sync::Arc::new(reference(
                                depth.saturating_sub(1).max(1),
                            )?))
                        },
                        dual,
                        1,
                    )?;
                    let change = (difference(&coarser.d, &r.d)?, difference(&coarser.m, &r.m)?);
                    let pointwise = if dual {
                        None
                    } else {
                        let mut strategy = reference(depth)?;
                        strategy.along_centre_direction = false;
                        let (p, _) = couple(&i, &|| Ok(std::sync::Arc::new(strategy)), dual, 1)?;
                        Some(difference(&p.m, &r.m)?)
                    };
                    let area = (r.stats.area - exact_area).abs() / exact_area;
                    println!(
                        "{:>8} {order:>5} {:>8} {mult:>8} reference: {seconds:.1} s, area err \
                         {area:.2e} (the quadratic surface's), change from depth {}: D {:.1e}, \
                         M {:.1e}{}",
                        case.name(),
                        "ref",
                        depth - 1,
                        change.0,
                        change.1,
                        pointwise.map_or(String::new(), |p| format!(
                            "; M along the direction at each point: {p:.1e} off"
                        ))
                    );
                    Some((r, seconds, area, change, pointwise))
                }
            };
            for level in &levels {
                let runs = if level.is_some_and(|l| l >= 8) {
                    1
                } else {
                    repeats
                };
                let owned;
                let (c, seconds) = if *level == Some(16) {
                    (&level16, seconds16)
                } else {
                    owned = couple(&i, &|| segment(*level), dual, runs)?;
                    (&owned.0, owned.1)
                };
                let name = level.map_or(format!("tol {DEFAULT_CURVED_TOLERANCE:e}"), |l| {
                    l.to_string()
                });
                let per_pair = seconds / c.stats.pairs.max(1) as f64;
                let (area, m16, tied) = (
                    (c.stats.area - exact_area).abs() / exact_area,
                    difference(&c.m, &level16.m)?,
                    tied_error(c, &i)?,
                );
                let mut row = json!({
                    "case": case.name(), "order": order, "level": name, "multipliers": mult,
                    "slave_faces": i.slave().face_count(), "master_faces": i.master().face_count(),
                    "pairs": c.stats.pairs, "seconds": seconds, "seconds_per_pair": per_pair,
                    "area_error": area, "m_error_vs_level_16": m16, "tied_error": tied,
                });
                let (mut d_err, mut m_err, mut m_fro) = (f64::NAN, f64::NAN, f64::NAN);
                if let Some((r, ref_seconds, ref_area, change, pointwise)) = &reference {
                    (d_err, m_err, m_fro) = (
                        difference(&c.d, &r.d)?,
                        difference(&c.m, &r.m)?,
                        frobenius(&c.m, &r.m),
                    );
                    let extra = json!({
                        "d_error": d_err, "m_error": m_err,
                        "d_error_frobenius": frobenius(&c.d, &r.d), "m_error_frobenius": m_fro,
                        "reference_seconds": ref_seconds, "reference_area_error": ref_area,
                        "reference_change_d": change.0, "reference_change_m": change.1,
                        "reference_m_pointwise_direction": pointwise,
                    });
                    for (k, v) in extra.as_object().expect("object") {
                        row[k] = v.clone();
                    }
                }
                println!(
                    "{:>8} {order:>5} {name:>8} {mult:>8} {:>5} {seconds:>8.4} {:>8.1} {area:>9.2e} \
                     {d_err:>9.2e} {m_err:>9.2e} {m_fro:>9.2e} {m16:>9.2e} {tied:>9.2e}",
                    case.name(),
                    c.stats.pairs,
                    1e6 * per_pair
                );
                rows.push(row);
            }
        }
    }
    Ok(rows)
}
