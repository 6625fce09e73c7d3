//! Perturbed structured meshes of the unit square and of the unit segment.

use std::f64::consts::TAU;
use std::ops::RangeInclusive;

use mortar_core::mesh::SurfaceMesh;
use mortar_elements::{LINE2, QUAD4, TRI3};
use proptest::prelude::*;

/// The largest node jitter of [`perturbed_square`], as a fraction of the cell size `h`.
///
/// Every node moves by at most `jitter * h` (Euclidean). A corner of a cell is at distance
/// `h / sqrt(2)` from the line through its two neighbours, and each of the three points moves
/// by at most `jitter * h`, so triangles stay positively oriented and quadrilaterals convex as
/// long as `2 * jitter < 1 / sqrt(2)`, i.e. `jitter < 0.3535`. At the bound used here, 0.3, the
/// worst corner keeps a distance of `0.107 h` from the line through its neighbours.
pub const MAX_SQUARE_JITTER: f64 = 0.3;

/// The largest node jitter of [`perturbed_line`], as a fraction of the cell size: below one
/// half, neighbouring nodes never cross.
pub const MAX_LINE_JITTER: f64 = 0.45;

/// How the cells of a structured square mesh are cut into faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CellKind {
    /// Every cell cut into two Tri3 along a randomly chosen diagonal.
    Triangles,
    /// Every cell one Quad4.
    Quads,
    /// Every cell independently one Quad4 or two Tri3 (either diagonal).
    Mixed,
}

impl CellKind {
    /// All kinds.
    pub const ALL: [CellKind; 3] = [CellKind::Triangles, CellKind::Quads, CellKind::Mixed];
}

/// Any [`CellKind`], shrinking towards `Triangles`.
pub fn cell_kind() -> impl Strategy<Value = CellKind> {
    prop::sample::select(CellKind::ALL.to_vec())
}

/// How one cell is cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum CellShape {
    MainDiagonal,
    AntiDiagonal,
    Quad,
}

fn cell_shape(kind: CellKind) -> BoxedStrategy<CellShape> {
    match kind {
        CellKind::Triangles => {
            prop::sample::select(vec![CellShape::MainDiagonal, CellShape::AntiDiagonal]).boxed()
        }
        CellKind::Quads => Just(CellShape::Quad).boxed(),
        CellKind::Mixed => prop::sample::select(vec![
            CellShape::Quad,
            CellShape::MainDiagonal,
            CellShape::AntiDiagonal,
        ])
        .boxed(),
    }
}

/// A structured mesh of the unit square `[0,1]^2` in the plane `z = 0`, with `n x n` cells
/// (`n` drawn from `cells`) cut as `kind` says, and every node moved by at most `jitter * h`
/// (`h = 1 / n`):
///
/// - interior nodes anywhere in the disc of radius `jitter * h` around their grid position;
/// - nodes on an edge of the square only along that edge, corners not at all,
///
/// so the mesh still covers exactly the unit square, and two meshes drawn by this strategy
/// cover the same surface. Faces are oriented with normal `+z`, or `-z` if `flip`.
///
/// Node tags are `1..=(n+1)^2` row by row from the corner `(0,0)`; face tags are their
/// positions plus one. Shrinks towards fewer cells and no jitter.
///
/// # Panics
/// If `jitter` is not in `[0, 0.35)` (quads could turn non-convex) or `cells` starts at 0.
pub fn perturbed_square(
    kind: CellKind,
    cells: RangeInclusive<usize>,
    jitter: f64,
    flip: bool,
) -> impl Strategy<Value = SurfaceMesh> {
    assert!(
        (0.0..0.35).contains(&jitter),
        "jitter {jitter} must be in [0, 0.35) to keep faces convex"
    );
    assert!(*cells.start() >= 1, "a square mesh needs at least one cell");
    cells.prop_flat_map(move |n| {
        let nodes = (n + 1) * (n + 1);
        (
            prop::collection::vec((0.0..=1.0f64, 0.0..TAU), nodes),
            prop::collection::vec(cell_shape(kind), n * n),
        )
            .prop_map(move |(offsets, shapes)| square_mesh(n, &offsets, &shapes, jitter, flip))
    })
}

/// Builds the mesh of [`perturbed_square`] from its random draws: per node a radius fraction
/// and an angle, per cell its shape.
fn square_mesh(
    n: usize,
    offsets: &[(f64, f64)],
    shapes: &[CellShape],
    jitter: f64,
    flip: bool,
) -> SurfaceMesh {
    let h = 1.0 / n as f64;
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u64 + 1;
    let mut mesh = SurfaceMesh::with_capacity((n + 1) * (n + 1), 2 * n * n);
    for j in 0..=n {
        for i in 0..=n {
            let (r, angle) = offsets[j * (n + 1) + i];
            let (dx, dy) = (r * jitter * h * angle.cos(), r * jitter * h * angle.sin());
            // Nodes on a vertical edge keep their x, on a horizontal edge their y.
            let on_x_edge = i == 0 || i == n;
            let on_y_edge = j == 0 || j == n;
            let x = if on_x_edge {
                i as f64 * h
            } else {
                i as f64 * h + dx
            };
            let y = if on_y_edge {
                j as f64 * h
            } else {
                j as f64 * h + dy
            };
            let x = if i == n { 1.0 } else { x };
            let y = if j == n { 1.0 } else { y };
            mesh.add_node(id(i, j), [x, y, 0.0])
                .expect("generated node tags are distinct and coordinates finite");
        }
    }
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            let result = match shapes[j * n + i] {
                CellShape::Quad => {
                    let q = if flip { [a, d, c, b] } else { [a, b, c, d] };
                    mesh.add_face(&QUAD4, &q).map(|_| ())
                }
                shape => {
                    let tris = if shape == CellShape::MainDiagonal {
                        [[a, b, c], [a, c, d]]
                    } else {
                        [[a, b, d], [b, c, d]]
                    };
                    tris.iter().try_for_each(|t| {
                        let t = if flip { [t[0], t[2], t[1]] } else { *t };
                        mesh.add_face(&TRI3, &t).map(|_| ())
                    })
                }
            };
            result.expect("generated faces refer to existing nodes");
        }
    }
    mesh
}

/// A Line2 mesh of the segment `[0, 1]` on the x-axis with `n` elements (`n` drawn from
/// `cells`), interior nodes moved along the axis by at most `jitter * h` (`h = 1 / n`), the
/// end nodes fixed. Traversed towards `+x` the normal is `-y`; with `flip` the lines run towards
/// `-x` and the normal is `+y` (as [`line_mesh`](crate::generate::line_mesh)).
///
/// Node tags are `1..=n+1` from `x = 0`. Shrinks towards fewer cells and no jitter.
///
/// # Panics
/// If `jitter` is not in `[0, 0.5)` or `cells` starts at 0.
pub fn perturbed_line(
    cells: RangeInclusive<usize>,
    jitter: f64,
    flip: bool,
) -> impl Strategy<Value = SurfaceMesh> {
    assert!(
        (0.0..0.5).contains(&jitter),
        "jitter {jitter} must be in [0, 0.5) to keep nodes in order"
    );
    assert!(*cells.start() >= 1, "a line mesh needs at least one cell");
    cells.prop_flat_map(move |n| {
        prop::collection::vec(-1.0..=1.0f64, n + 1).prop_map(move |offsets| {
            let h = 1.0 / n as f64;
            let mut mesh = SurfaceMesh::with_capacity(n + 1, n);
            for (i, u) in offsets.iter().enumerate() {
                let x = match i {
                    0 => 0.0,
                    i if i == n => 1.0,
                    i => i as f64 * h + u * jitter * h,
                };
                mesh.add_node(i as u64 + 1, [x, 0.0, 0.0])
                    .expect("generated node tags are distinct and coordinates finite");
            }
            for i in 0..n as u64 {
                let (a, b) = (i + 1, i + 2);
                let line = if flip { [b, a] } else { [a, b] };
                mesh.add_face(&LINE2, &line)
                    .expect("generated faces refer to existing nodes");
            }
            mesh
        })
    })
}

/// A polyline of two-node lines through `points` in the plane z = 0, nodes tagged from
/// `first_tag` in order, faces tagged from 1; with `reverse` each line runs backwards (its
/// normal on the other side).
///
/// # Panics
/// If `points` has fewer than two points, or a point is not finite.
pub fn polyline(points: &[[f64; 2]], first_tag: u64, reverse: bool) -> SurfaceMesh {
    assert!(points.len() >= 2, "a polyline needs two points");
    let mut m = SurfaceMesh::new();
    for (i, p) in points.iter().enumerate() {
        m.add_node(first_tag + i as u64, [p[0], p[1], 0.0])
            .expect("finite, distinct tags");
    }
    for i in 0..points.len() as u64 - 1 {
        let (a, b) = (first_tag + i, first_tag + i + 1);
        let nodes = if reverse { [b, a] } else { [a, b] };
        m.add_face(&LINE2, &nodes).expect("nodes just added");
    }
    m
}
