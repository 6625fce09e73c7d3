//! A quarter of a disc refined towards one point of its rim: the cylinder of a 2D (plane
//! strain) Hertz contact, cut along its two planes of symmetry; and a quarter of an annulus
//! (the ring of a shrink fit).

use mortar_elements::volume::{QUAD4, TRI3};
use mortar_fem::mesh::{VolumeMesh, VolumeMeshError};

use super::volume::grading_map;
use super::CellShape;

/// The distance from the centre of the core rectangle's outer corner, as a fraction of the
/// radius.
const CORE: f64 = 0.5;

/// The lower-right quarter of the disc of radius `radius` centred at `centre`
/// (`x >= centre[0]`, `y <= centre[1]`), in the plane `z = 0`, with `n` cells along its arc,
/// refined towards the bottom point `(centre[0], centre[1] - radius)` (where the disc touches
/// a plane below it). Quad4, or Tri3 (each quad cut in two) for [`CellShape::Simplex`]; every
/// cell positively oriented. Nodes are tagged from `first_node_tag`, cells from 1.
///
/// The arc's nodes are at the angles (from the downward vertical, towards `+x`)
/// `theta_i = (pi / 2) f(i / n)`, `f(s) = (g^s - 1) / (g - 1)` with `g = grading` (see
/// [`graded_points`](super::graded_points)): the cells grow from the bottom point by the
/// factor `g^(1/n)` from one to the next, the last is about `g` times the first
/// (`g = 1`: uniform), and doubling `n` splits every cell in two (the meshes are nested along
/// the arc). The first cell's length is
/// `2 R sin(theta_1 / 2)`, about `(pi / 2) R ln(g) / ((g - 1) n)`.
///
/// The mesh is an O-grid of three blocks: a rectangular core `[cx, cx + R sin(t_M) / 2] x
/// [cy - R cos(t_M) / 2, cy]`, `t_M` the angle of the arc node nearest to 45 degrees, and two
/// shell blocks between the core and the arc, below and to the right of it, whose cells lie
/// along the rays from the centre through the arc nodes. Radially the shell is graded by the
/// same `f`, fine at the rim, with `n_r = round(n (1 - cos(t_M) / 2) / (pi / 2))` cells (at
/// least one), so that at the bottom point the first radial cell and the first arc cell have
/// about the same length. The core's columns continue the lower block's rays (and are as fine
/// near `x = cx`), its rows the right block's.
///
/// The boundary: the arc (`n` faces), the segment `x = cx` from the bottom point to the centre
/// and the segment `y = cy` from the centre to `(cx + R, cy)`, both exactly on their lines.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for a radius that is not positive and finite, a non-finite
/// centre, fewer than 2 arc cells, or a grading that is not finite and at least 1.
pub fn quarter_disc_mesh(
    radius: f64,
    centre: [f64; 2],
    n: usize,
    grading: f64,
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    let bad = |reason: String| VolumeMeshError::BadCell {
        cell: 0,
        element: "quarter disc mesh",
        reason,
    };
    if !(radius > 0.0 && radius.is_finite()) {
        return Err(bad(format!("radius {radius} is not positive and finite")));
    }
    if !centre.iter().all(|c| c.is_finite()) {
        return Err(bad(format!("centre {centre:?} is not finite")));
    }
    if n < 2 {
        return Err(bad(format!(
            "needs at least 2 cells along the arc, got {n}"
        )));
    }
    if !(grading >= 1.0 && grading.is_finite()) {
        return Err(bad(format!(
            "grading {grading} is not finite and at least 1"
        )));
    }
    let l = Layout::new(n, grading);
    let (na, nr) = (l.lower, l.radial);
    let [cx, cy] = centre;
    let theta_m = l.theta[na];
    let (half_x, half_y) = (CORE * radius * theta_m.sin(), CORE * radius * theta_m.cos());
    // The core's column abscissae (lower block's rays) and row ordinates (right block's rays),
    // the lines x = cx and y = cy and the core's sides exact.
    let core_x = |i: usize| -> f64 {
        match i {
            0 => cx,
            i if i == na => cx + half_x,
            i => cx + half_y * l.theta[i].tan(),
        }
    };
    let core_y = |j: usize| -> f64 {
        match j {
            j if j == n => cy,
            j if j == na => cy - half_y,
            j => cy - half_x / l.theta[j].tan(),
        }
    };
    // Where the ray of arc node i meets the core.
    let inner = |i: usize| -> [f64; 2] {
        if i <= na {
            [core_x(i), cy - half_y]
        } else {
            [cx + half_x, core_y(i)]
        }
    };
    let arc = |i: usize| -> [f64; 2] {
        match i {
            0 => [cx, cy - radius],
            i if i == n => [cx + radius, cy],
            i => [
                cx + radius * l.theta[i].sin(),
                cy - radius * l.theta[i].cos(),
            ],
        }
    };
    // Radial fractions from the core (0) to the arc (1), fine at the arc.
    let t: Vec<f64> = (0..=nr)
        .map(|k| 1.0 - grading_map((nr - k) as f64 / nr as f64, grading))
        .collect();

    // Nodes: the core (i = 0..=na columns, j = na..=n rows), then the shell layers
    // k = 1..=nr (k = 0 is the core's boundary), each i = 0..=n.
    let core_nodes = (na + 1) * (n - na + 1);
    let core_tag = |i: usize, j: usize| first_node_tag + ((j - na) * (na + 1) + i) as u64;
    let shell_tag = |i: usize, k: usize| -> u64 {
        match k {
            0 if i <= na => core_tag(i, na),
            0 => core_tag(na, i),
            k => first_node_tag + (core_nodes + (k - 1) * (n + 1) + i) as u64,
        }
    };
    let mut m = VolumeMesh::new();
    for j in na..=n {
        for i in 0..=na {
            m.add_node(core_tag(i, j), [core_x(i), core_y(j), 0.0])?;
        }
    }
    for k in 1..=nr {
        for i in 0..=n {
            let p = if k == nr {
                arc(i)
            } else {
                let (a, b) = (inner(i), arc(i));
                [a[0] + (b[0] - a[0]) * t[k], a[1] + (b[1] - a[1]) * t[k]]
            };
            m.add_node(shell_tag(i, k), [p[0], p[1], 0.0])?;
        }
    }
    let mut quad =
        |tags: [u64; 4]| -> Result<(), VolumeMeshError> { add_quad(&mut m, tags, shape) };
    for j in na..n {
        for i in 0..na {
            quad([
                core_tag(i, j),
                core_tag(i + 1, j),
                core_tag(i + 1, j + 1),
                core_tag(i, j + 1),
            ])?;
        }
    }
    for k in 0..nr {
        for i in 0..n {
            quad([
                shell_tag(i, k),
                shell_tag(i + 1, k),
                shell_tag(i + 1, k + 1),
                shell_tag(i, k + 1),
            ])?;
        }
    }
    Ok(m)
}

/// The lower-right quarter of the annulus `inner <= r <= outer` centred at the origin
/// (`x >= 0`, `y <= 0`, the quadrant of [`quarter_disc_mesh`] about its centre), in the plane
/// `z = 0`, polar-mapped: `cells[0]` equal cells in the angle `theta` (from the downward
/// vertical, towards `+x`: the node `(r sin(theta), -r cos(theta))`), `cells[1]` equal cells in
/// the radius. Quad4, or Tri3 (each quad cut in two) for [`CellShape::Simplex`]; every cell
/// positively oriented. Nodes are tagged from `first_node_tag`, ring by ring from the inner
/// arc (`tag = first + k (cells[0] + 1) + i`, `k` the radial index, `i` the angular one from
/// the bottom), cells from 1.
///
/// The boundary: the inner and the outer arc (`cells[0]` faces each, their nodes exactly on
/// the circles to round-off), the segment `x = 0` and the segment `y = 0` (`cells[1]` faces
/// each, exactly on their lines).
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for radii that are not finite with `0 < inner < outer`, or
/// zero cells in a direction.
pub fn quarter_annulus_mesh(
    inner: f64,
    outer: f64,
    cells: [usize; 2],
    shape: CellShape,
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    let bad = |reason: String| VolumeMeshError::BadCell {
        cell: 0,
        element: "quarter annulus mesh",
        reason,
    };
    if !(inner > 0.0 && outer > inner && outer.is_finite()) {
        return Err(bad(format!(
            "radii {inner} and {outer} are not finite with 0 < inner < outer"
        )));
    }
    let [nt, nr] = cells;
    if nt == 0 || nr == 0 {
        return Err(bad(format!(
            "needs at least one cell per direction, got {cells:?}"
        )));
    }
    let tag = |i: usize, k: usize| first_node_tag + (k * (nt + 1) + i) as u64;
    let mut m = VolumeMesh::new();
    for k in 0..=nr {
        let r = if k == nr {
            outer
        } else {
            inner + (outer - inner) * k as f64 / nr as f64
        };
        for i in 0..=nt {
            let p = match i {
                0 => [0.0, -r],
                i if i == nt => [r, 0.0],
                i => {
                    let t = std::f64::consts::FRAC_PI_2 * i as f64 / nt as f64;
                    [r * t.sin(), -r * t.cos()]
                }
            };
            m.add_node(tag(i, k), [p[0], p[1], 0.0])?;
        }
    }
    for k in 0..nr {
        for i in 0..nt {
            add_quad(
                &mut m,
                [tag(i, k), tag(i + 1, k), tag(i + 1, k + 1), tag(i, k + 1)],
                shape,
            )?;
        }
    }
    Ok(m)
}

/// The arc's angles and the blocks' cell counts.
#[derive(Debug, Clone)]
struct Layout {
    /// `theta_i`, `i = 0..=n`, from 0 to `pi / 2` exactly.
    theta: Vec<f64>,
    /// Arc cells of the lower block (the core's columns): the arc node nearest to 45 degrees.
    lower: usize,
    /// Radial cells of the shell.
    radial: usize,
}

impl Layout {
    fn new(n: usize, grading: f64) -> Self {
        use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
        let theta: Vec<f64> = (0..=n)
            .map(|i| {
                if i == n {
                    FRAC_PI_2
                } else {
                    FRAC_PI_2 * grading_map(i as f64 / n as f64, grading)
                }
            })
            .collect();
        let lower = (1..n)
            .min_by(|&a, &b| {
                (theta[a] - FRAC_PI_4)
                    .abs()
                    .total_cmp(&(theta[b] - FRAC_PI_4).abs())
            })
            .expect("n >= 2");
        let depth = 1.0 - CORE * theta[lower].cos();
        let radial = ((n as f64 * depth / FRAC_PI_2).round() as usize).max(1);
        Self {
            theta,
            lower,
            radial,
        }
    }
}

/// Adds the quad of corner tags `tags` (either orientation), turned positive; two triangles
/// for [`CellShape::Simplex`].
fn add_quad(m: &mut VolumeMesh, tags: [u64; 4], shape: CellShape) -> Result<(), VolumeMeshError> {
    let x = tags.map(|t| m.coords()[m.node_index(t).expect("added") as usize]);
    let area2: f64 = (0..4)
        .map(|a| {
            let b = (a + 1) % 4;
            x[a].x * x[b].y - x[b].x * x[a].y
        })
        .sum();
    let [a, b, c, d] = if area2 < 0.0 {
        [tags[0], tags[3], tags[2], tags[1]]
    } else {
        tags
    };
    match shape {
        CellShape::Tensor => {
            m.add_cell(&QUAD4, &[a, b, c, d])?;
        }
        CellShape::Simplex => {
            m.add_cell(&TRI3, &[a, b, c])?;
            m.add_cell(&TRI3, &[a, c, d])?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    const R: f64 = 1.5;
    const C: [f64; 2] = [0.25, 2.0];

    fn cases() -> Vec<(usize, f64)> {
        vec![
            (2, 1.0),
            (3, 1.0),
            (5, 4.0),
            (16, 1.0),
            (16, 20.0),
            (40, 8.0),
            (64, 200.0),
        ]
    }

    fn signed_area(x: &[Vector3<f64>]) -> f64 {
        0.5 * (0..x.len())
            .map(|a| {
                let b = (a + 1) % x.len();
                x[a].x * x[b].y - x[b].x * x[a].y
            })
            .sum::<f64>()
    }

    fn cell_coords(m: &VolumeMesh, c: usize) -> Vec<Vector3<f64>> {
        m.cell(c)
            .nodes
            .iter()
            .map(|&i| m.coords()[i as usize])
            .collect()
    }

    #[test]
    fn every_cell_has_a_positive_jacobian() {
        for (n, g) in cases() {
            for shape in [CellShape::Tensor, CellShape::Simplex] {
                let m = quarter_disc_mesh(R, C, n, g, shape, 1).unwrap();
                for c in 0..m.cell_count() {
                    let el = m.cell(c).element;
                    let x = cell_coords(&m, c);
                    // det J of Quad4 is affine in the reference coordinates: positive at the
                    // corners is positive everywhere.
                    let mut points: Vec<Vector3<f64>> = el
                        .node_reference_coords()
                        .iter()
                        .map(|&p| Vector3::from(p))
                        .collect();
                    points.push(el.domain().centre());
                    for xi in &points {
                        let det = el.jacobian(&x, xi).determinant();
                        assert!(
                            det > 0.0,
                            "n = {n}, grading {g}, {shape:?}: cell {c} has det J = {det:e} at \
                             {xi:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn area_is_the_inscribed_polygons() {
        for (n, g) in cases() {
            let l = Layout::new(n, g);
            // The centre and consecutive arc nodes: triangles of area R^2 sin(dtheta) / 2.
            let polygon: f64 = l
                .theta
                .windows(2)
                .map(|w| 0.5 * R * R * (w[1] - w[0]).sin())
                .sum();
            for shape in [CellShape::Tensor, CellShape::Simplex] {
                let m = quarter_disc_mesh(R, C, n, g, shape, 1).unwrap();
                let area: f64 = (0..m.cell_count())
                    .map(|c| signed_area(&cell_coords(&m, c)))
                    .sum();
                assert!(
                    (area - polygon).abs() < 1e-13 * polygon,
                    "n = {n}, grading {g}: area {area} against {polygon}"
                );
                // Inside the quarter disc, short of it by the chords' segments.
                let disc = std::f64::consts::FRAC_PI_4 * R * R;
                let segments: f64 = l
                    .theta
                    .windows(2)
                    .map(|w| 0.5 * R * R * ((w[1] - w[0]) - (w[1] - w[0]).sin()))
                    .sum();
                assert!(((disc - area) - segments).abs() < 1e-12 * disc);
            }
        }
    }

    #[test]
    fn node_cell_and_boundary_counts() {
        for (n, g) in cases() {
            let l = Layout::new(n, g);
            let (na, nr) = (l.lower, l.radial);
            let m = quarter_disc_mesh(R, C, n, g, CellShape::Tensor, 7).unwrap();
            assert_eq!(m.node_count(), (na + 1) * (n - na + 1) + nr * (n + 1));
            assert_eq!(m.cell_count(), na * (n - na) + n * nr);
            assert_eq!(m.node_tags()[0], 7);
            let tri = quarter_disc_mesh(R, C, n, g, CellShape::Simplex, 7).unwrap();
            assert_eq!(tri.node_count(), m.node_count());
            assert_eq!(tri.cell_count(), 2 * m.cell_count());
            // Boundary: n arc faces, nr + (n - na) on x = cx, nr + na on y = cy, nothing else.
            let faces = m.boundary_faces().unwrap();
            let on_arc = |f: &mortar_fem::mesh::BoundaryFace| {
                f.nodes.iter().all(|&i| {
                    let x = m.coords()[i as usize];
                    ((x.x - C[0]).hypot(x.y - C[1]) - R).abs() < 1e-14 * R
                })
            };
            let left = faces
                .iter()
                .filter(|f| f.nodes.iter().all(|&i| m.coords()[i as usize].x == C[0]))
                .count();
            let top = faces
                .iter()
                .filter(|f| f.nodes.iter().all(|&i| m.coords()[i as usize].y == C[1]))
                .count();
            let arc = faces.iter().filter(|f| on_arc(f)).count();
            assert_eq!(
                (arc, left, top),
                (n, nr + n - na, nr + na),
                "n = {n}, g = {g}"
            );
            assert_eq!(faces.len(), arc + left + top);
            // Every node inside the quarter disc.
            for x in m.coords() {
                assert!(x.x >= C[0] && x.y <= C[1]);
                assert!((x.x - C[0]).hypot(x.y - C[1]) <= R * (1.0 + 1e-14));
            }
        }
    }

    #[test]
    fn cells_are_smallest_at_the_bottom_point() {
        for (n, g) in cases() {
            let m = quarter_disc_mesh(R, C, n, g, CellShape::Tensor, 1).unwrap();
            let bottom = Vector3::new(C[0], C[1] - R, 0.0);
            // The arc faces ordered by angle from the bottom point.
            let mut arc: Vec<(f64, f64)> = m
                .boundary_faces()
                .unwrap()
                .iter()
                .filter(|f| {
                    f.nodes.iter().all(|&i| {
                        let x = m.coords()[i as usize];
                        ((x.x - C[0]).hypot(x.y - C[1]) - R).abs() < 1e-14 * R
                    })
                })
                .map(|f| {
                    let (a, b) = (
                        m.coords()[f.nodes[0] as usize],
                        m.coords()[f.nodes[1] as usize],
                    );
                    ((f.centroid - bottom).norm(), (a - b).norm())
                })
                .collect();
            arc.sort_by(|a, b| a.0.total_cmp(&b.0));
            for w in arc.windows(2) {
                if g == 1.0 {
                    assert!((w[1].1 - w[0].1).abs() < 1e-12 * R);
                } else {
                    assert!(w[1].1 > w[0].1, "n = {n}, g = {g}: {arc:?}");
                }
            }
            let first = arc[0].1;
            let expected =
                2.0 * R * (std::f64::consts::FRAC_PI_4 * grading_map(1.0 / n as f64, g)).sin();
            assert!((first - expected).abs() < 1e-12 * expected);
            // The last over the first is about the grading.
            let ratio = arc[n - 1].1 / first;
            assert!(
                ratio > 0.9 * g.powf((n as f64 - 1.0) / n as f64) && ratio < 1.1 * g,
                "n = {n}, g = {g}: {ratio}"
            );
            // The first radial cell at the bottom point is about as long as the first arc
            // cell (within the rounding of n_r).
            let above = m
                .coords()
                .iter()
                .filter(|x| x.x == C[0] && x.y > bottom.y)
                .map(|x| x.y - bottom.y)
                .fold(f64::INFINITY, f64::min);
            if n >= 16 {
                assert!(
                    above > 0.8 * first && above < 1.25 * first,
                    "n = {n}, g = {g}: radial {above}, arc {first}"
                );
            }
        }
    }

    #[test]
    fn refinement_splits_every_cell_in_two() {
        for g in [1.0, 8.0, 20.0] {
            for n in [8, 16, 32] {
                let (coarse, fine) = (Layout::new(n, g), Layout::new(2 * n, g));
                for (i, t) in coarse.theta.iter().enumerate() {
                    assert!(
                        (fine.theta[2 * i] - t).abs() < 1e-15,
                        "g = {g}, n = {n}, {i}"
                    );
                }
                // The contact cell: split in the ratio g^(1/2n), so about halved.
                let r = coarse.theta[1] / fine.theta[1];
                assert!(
                    (r - 1.0 - g.powf(0.5 / n as f64)).abs() < 1e-12,
                    "{g}, {n}: {r}"
                );
            }
        }
    }

    #[test]
    fn bad_input_is_refused() {
        let t = CellShape::Tensor;
        assert!(quarter_disc_mesh(0.0, C, 8, 2.0, t, 1).is_err());
        assert!(quarter_disc_mesh(f64::NAN, C, 8, 2.0, t, 1).is_err());
        assert!(quarter_disc_mesh(R, [f64::INFINITY, 0.0], 8, 2.0, t, 1).is_err());
        assert!(quarter_disc_mesh(R, C, 1, 2.0, t, 1).is_err());
        assert!(quarter_disc_mesh(R, C, 8, 0.5, t, 1).is_err());
        assert!(quarter_disc_mesh(R, C, 8, f64::INFINITY, t, 1).is_err());
    }
}
