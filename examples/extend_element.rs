//! An element of one's own, end to end (issue 11): the library ships elements up to order
//! two; here a program adds the cubic pair Gmsh writes with `-order 3` in 2D, the ten-node
//! triangle (Gmsh type 21) and its four-node edges (Gmsh type 26), and uses them through the
//! library's own doors: two bodies meshed independently are written as Gmsh files, their
//! interface lines are read back by the Gmsh reader, tied by `Interface` and the coupling
//! (sum(D) = the interface's length, D 1 = M 1, standard and dual multipliers), then coupled
//! again by `mortar couple` and solved as a tied-heat scene file by `mortar run`, both from
//! `mortar::cli::run_from` with the program's registries (a program's `main` would be
//! `mortar::cli::main_with(registries)`).
//!
//! ```sh
//! cargo run --release --example extend_element [OUT_DIR]
//! ```

use std::process::ExitCode;

use mortar::core::element::volume::{VolumeDomain, VolumeElement};
use mortar::core::element::{ElementRef, ReferenceDomain, ReferenceElement, SurfaceElement};
use mortar::extend::Registries;
use mortar::io::{msh41_volume_bytes, read_gmsh_surface, MshFormat};
use mortar::{assemble_coupling, CouplingOptions, Interface, VolumeMesh};
use nalgebra::{Vector2, Vector3};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

// ---- the user's code: the two elements (131 lines as rustfmt lays them out, comments and blank lines not counted) ----
/// Four-node cubic line, Gmsh order: the ends -1, 1, then -1/3, 1/3 (Lagrange polynomials).
#[derive(Debug)]
struct Line4;
const LINE4_NODES: [f64; 4] = [-1.0, 1.0, -1.0 / 3.0, 1.0 / 3.0];
impl ReferenceElement for Line4 {
    fn name(&self) -> &'static str {
        "Line4"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Line
    }
    fn node_count(&self) -> usize {
        4
    }
    fn corner_count(&self) -> usize {
        2
    }
    fn shape_degree(&self) -> u32 {
        3
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        &[[-1.0, 0.0], [1.0, 0.0], [-1.0 / 3.0, 0.0], [1.0 / 3.0, 0.0]]
    }
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        let x = &LINE4_NODES;
        for i in 0..4 {
            let others = (0..4).filter(|&j| j != i);
            out[i] = others.map(|j| (xi.x - x[j]) / (x[i] - x[j])).product();
        }
    }
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        let x = &LINE4_NODES;
        for i in 0..4 {
            // d/dxi prod_(j != i) (xi - x_j) / (x_i - x_j): one factor differentiated at a time.
            let term = |k: usize| -> f64 {
                (0..4)
                    .filter(|&j| j != i)
                    .map(|j| if j == k { 1.0 } else { xi.x - x[j] } / (x[i] - x[j]))
                    .product()
            };
            out[i] = [(0..4).filter(|&k| k != i).map(term).sum(), 0.0];
        }
    }
}
impl SurfaceElement for Line4 {
    fn gmsh_type(&self) -> Option<u32> {
        Some(26)
    }
    // Reversed: the ends swap, and so do the inner nodes.
    fn reverse_nodes(&self, nodes: &mut [u32]) -> bool {
        nodes.len() == 4 && {
            nodes.swap(0, 1);
            nodes.swap(2, 3);
            true
        }
    }
}

/// Ten-node cubic triangle, Gmsh order: corners, two nodes on each edge 1-2, 2-3, 3-1 (the one
/// nearer the edge's first corner first), then the centre.
#[derive(Debug)]
struct Tri10;
impl VolumeElement for Tri10 {
    fn name(&self) -> &'static str {
        "Tri10"
    }
    fn domain(&self) -> VolumeDomain {
        VolumeDomain::Triangle
    }
    fn node_count(&self) -> usize {
        10
    }
    fn shape_degree(&self) -> u32 {
        3
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        const T: f64 = 1.0 / 3.0;
        &[
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [T, 0., 0.],
            [2. * T, 0., 0.],
            [2. * T, T, 0.],
            [T, 2. * T, 0.],
            [0., 2. * T, 0.],
            [0., T, 0.],
            [T, T, 0.],
        ]
    }
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        let mut g = [[0.0; 3]; 10];
        tri10(xi, out, &mut g);
    }
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        let mut n = [0.0; 10];
        tri10(xi, &mut n, out);
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(21)
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        &[&[0, 1, 3, 4], &[1, 2, 5, 6], &[2, 0, 7, 8]]
    }
    fn face_element(&self, _face: usize) -> ElementRef {
        &Line4
    }
}

/// The cubic functions of the barycentric coordinates L and their gradients: corners
/// `L (3L - 1)(3L - 2) / 2`, edge nodes `9/2 L_a L_b (3 L_a - 1)`, centre `27 L_1 L_2 L_3`.
fn tri10(xi: &Vector3<f64>, n: &mut [f64], g: &mut [[f64; 3]]) {
    let l = [1.0 - xi.x - xi.y, xi.x, xi.y];
    let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
    let mut put = |i: usize, v: f64, d: [f64; 3]| {
        n[i] = v;
        g[i] = [
            d[0] * dl[0][0] + d[1] * dl[1][0] + d[2] * dl[2][0],
            d[0] * dl[0][1] + d[1] * dl[1][1] + d[2] * dl[2][1],
            0.0,
        ];
    };
    for a in 0..3 {
        let mut d = [0.0; 3];
        d[a] = (27.0 * l[a] * l[a] - 18.0 * l[a] + 2.0) / 2.0;
        put(a, l[a] * (3.0 * l[a] - 1.0) * (3.0 * l[a] - 2.0) / 2.0, d);
        let b = (a + 1) % 3;
        // The edge a-b's node nearer a, then the one nearer b (their values, dN/dL).
        for (k, (p, q)) in [(a, b), (b, a)].into_iter().enumerate() {
            let mut d = [0.0; 3];
            d[p] = 4.5 * (6.0 * l[p] - 1.0) * l[q];
            d[q] = 4.5 * l[p] * (3.0 * l[p] - 1.0);
            put(3 + 2 * a + k, 4.5 * l[p] * l[q] * (3.0 * l[p] - 1.0), d);
        }
    }
    put(
        9,
        27.0 * l[0] * l[1] * l[2],
        [27.0 * l[1] * l[2], 27.0 * l[0] * l[2], 27.0 * l[0] * l[1]],
    );
}
// ---- end of the elements ----

/// The unit square `[x0, x0 + 1] x [0, 1]` in `2 n^2` Tri10 cells.
fn tri10_square(x0: f64, n: usize) -> Res<VolumeMesh> {
    let (m, mut mesh) = (3 * n + 1, VolumeMesh::new());
    let tag = |i: usize, j: usize| (j * m + i + 1) as u64;
    for (i, j) in (0..m).flat_map(|j| (0..m).map(move |i| (i, j))) {
        let h = 1.0 / (m - 1) as f64;
        mesh.add_node(tag(i, j), [x0 + i as f64 * h, j as f64 * h, 0.0])?;
    }
    // Each square of 3 x 3 grid steps in two triangles, their nodes as grid offsets.
    let lower = [
        (0, 0),
        (3, 0),
        (3, 3),
        (1, 0),
        (2, 0),
        (3, 1),
        (3, 2),
        (2, 2),
        (1, 1),
        (2, 1),
    ];
    let upper = [
        (0, 0),
        (3, 3),
        (0, 3),
        (1, 1),
        (2, 2),
        (2, 3),
        (1, 3),
        (0, 2),
        (0, 1),
        (1, 2),
    ];
    for (a, b) in (0..n).flat_map(|b| (0..n).map(move |a| (3 * a, 3 * b))) {
        for cell in [lower, upper] {
            mesh.add_cell(&Tri10, &cell.map(|(di, dj)| tag(a + di, b + dj)))?;
        }
    }
    Ok(mesh)
}

/// Writes body `name` on `[x0, x0 + 1] x [0, 1]` as `dir/name.msh`, with its faces at
/// `x = x0` (group `name_x0`) and `x = x0 + 1` (`name_x1`).
fn write_body(dir: &std::path::Path, name: &str, x0: f64, n: usize) -> Res<()> {
    let mesh = tri10_square(x0, n)?;
    let faces = mesh.boundary_faces()?;
    let at = |x: f64| {
        faces
            .iter()
            .filter(|f| (f.centroid.x - x).abs() < 1e-12)
            .cloned()
            .collect::<Vec<_>>()
    };
    let (g0, g1) = (format!("{name}_x0"), format!("{name}_x1"));
    let groups = [(&at(x0)[..], g0.as_str()), (&at(x0 + 1.0)[..], g1.as_str())];
    std::fs::write(
        dir.join(format!("{name}.msh")),
        msh41_volume_bytes((&mesh, name), &groups, MshFormat::Ascii)?,
    )?;
    Ok(())
}

/// The scene: `T = 0` at `x = 0`, heat flux 2 entering at `x = 2`, `k` 1 on the left and 2 on
/// the right: `T = 2 x` on the left, `2 + (x - 1)` on the right, exact for these elements.
const SCENE: &str = r#"kind = "tied_heat"
[bodies.left]
mesh = "left.msh"
group = "left"
conductivity = 1.0
dirichlet = [{ group = "left_x0", value = 0.0 }]
[bodies.right]
mesh = "right.msh"
group = "right"
conductivity = 2.0
neumann = [{ group = "right_x1", flux = 2.0 }]
[interface]
slave = { body = "right", group = "right_x0" }
master = { body = "left", group = "left_x1" }
"#;

/// Runs the example, writing into `out` (meshes, the scene, the outputs of `couple` and `run`).
pub fn run(out: &std::path::Path) -> Res<()> {
    std::fs::create_dir_all(out)?;
    // ---- the user's code: registering and using the elements (46 lines) ----
    let mut registries = Registries::default();
    registries.elements.register(&Line4);
    registries.cells.register(&Tri10);
    write_body(out, "left", 0.0, 3)?; // 3 x 3 squares of two Tri10: 3 lines, 10 nodes on x = 1
    write_body(out, "right", 1.0, 4)?; // 4 x 4: 4 lines, 13 nodes (4 shared: y = 0, 1/3, 2/3, 1)
    let read =
        |file: &str, group| read_gmsh_surface(out.join(file), Some(group), &registries.elements);
    for options in [
        CouplingOptions::default(),
        CouplingOptions::default().dual(),
    ] {
        let (mut slave, mut master) =
            (read("right.msh", "right_x0")?, read("left.msh", "left_x1")?);
        slave.orient_outward()?; // outward from their Tri10 cells: facing each other
        master.orient_outward()?;
        let c = assemble_coupling(&Interface::new(slave.mesh, master.mesh)?, &options)?;
        let worst = row_sums(&c.d)
            .into_iter()
            .zip(row_sums(&c.m))
            .fold(0.0, |w, (d, m)| f64::max(w, (d - m).abs()));
        println!(
            "{}: sum(D) = {:.15} (length 1), max |D 1 - M 1| = {worst:.1e}",
            c.formulation, c.stats.area
        );
        if (c.stats.area - 1.0).abs() > 1e-12 || worst > 1e-12 {
            return Err("D and M fail the patch test".into());
        }
    }
    std::fs::write(out.join("scene.toml"), SCENE)?;
    let (o, scene) = (out.display(), out.join("scene.toml").display().to_string());
    let couple = [
        "mortar",
        "couple",
        "--slave",
        &format!("{o}/right.msh#right_x0"),
        "--master",
        &format!("{o}/left.msh#left_x1"),
        "--out",
        &format!("{o}/couple"),
    ];
    let run = ["mortar", "run", &scene, "--out", &format!("{o}/scene")];
    for args in [&couple[..], &run[..]] {
        if mortar::cli::run_from(args, &registries) != ExitCode::SUCCESS {
            return Err(format!("`{}` failed", args.join(" ")).into());
        }
    }
    // ---- end of the user's code ----
    check_scene(out, &registries)
}

/// The row sums of a sparse matrix.
fn row_sums(a: &sprs::CsMat<f64>) -> Vec<f64> {
    a.outer_iterator()
        .map(|row| row.data().iter().sum())
        .collect()
}

/// Solves the scene file through the library with the same registries and checks the
/// temperature against the exact one.
fn check_scene(out: &std::path::Path, registries: &Registries) -> Res<()> {
    use mortar::scenes::file::{tied_heat::TiedHeatSpec, FileSystem};
    let path = out.join("scene.toml");
    let solved =
        TiedHeatSpec::parse(SCENE, &path)?.solve_with(&path, out, &FileSystem, registries)?;
    let mut worst: f64 = 0.0;
    for (body, t) in solved
        .problem
        .bodies()
        .iter()
        .zip(&solved.solution.temperatures)
    {
        for (x, t) in body.mesh.coords().iter().zip(t) {
            let exact = if x.x <= 1.0 { 2.0 * x.x } else { 1.0 + x.x };
            worst = worst.max((t - exact).abs());
        }
    }
    println!(
        "tied heat on Tri10 bodies: max |T - T_exact| = {worst:.1e} ({})",
        solved.solution.formulation.formulation.describe()
    );
    if worst > 1e-10 {
        return Err(format!("temperature off by {worst:e}").into());
    }
    Ok(())
}

fn main() -> Res<()> {
    let out = std::env::args().nth(1).map_or_else(
        || std::env::temp_dir().join("mortar-extend-element"),
        Into::into,
    );
    run(&out)?;
    println!("outputs in {}", out.display());
    Ok(())
}
