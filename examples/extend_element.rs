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

use mortar::core::element::volume::{VolumeDomain, VolumeElementRef};
use mortar::core::element::{ElementRef, ReferenceDomain};
use mortar::elements::{LagrangeCell, LagrangeFace};
use mortar::extend::Registries;
use mortar::io::{msh41_volume_bytes, read_gmsh_surface, MshFormat};
use mortar::{assemble_coupling, CouplingOptions, Interface, VolumeMesh};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

// ---- the user's code: the two elements (29 lines as rustfmt lays them out, comments and blank lines not counted) ----
/// Gmsh's cubic line (type 26): the ends, then the inner nodes.
static LINE4: [[f64; 2]; 4] = [[-1.0, 0.0], [1.0, 0.0], [-1.0 / 3.0, 0.0], [1.0 / 3.0, 0.0]];
const T: f64 = 1.0 / 3.0;
/// Gmsh's cubic triangle (type 21): corners, two nodes on each edge 1-2, 2-3, 3-1, centre.
static TRI10: [[f64; 3]; 10] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [T, 0.0, 0.0],
    [2.0 * T, 0.0, 0.0],
    [2.0 * T, T, 0.0],
    [T, 2.0 * T, 0.0],
    [0.0, 2.0 * T, 0.0],
    [0.0, T, 0.0],
    [T, T, 0.0],
];
/// Its edges as Line4 faces, outward for a counter-clockwise cell.
static TRI10_EDGES: [&[usize]; 3] = [&[0, 1, 3, 4], &[1, 2, 5, 6], &[2, 0, 7, 8]];

/// The two elements, Lagrange elements from their nodes (their cubic shape functions found
/// by the library), made to live as long as the program.
fn elements() -> Res<(ElementRef, VolumeElementRef)> {
    let line4 = LagrangeFace::new("Line4", ReferenceDomain::Line, 2, &LINE4, Some(26))?
        .with_reversal(&[1, 0, 3, 2]);
    let line4: ElementRef = Box::leak(Box::new(line4));
    let tri10 = LagrangeCell::new(
        "Tri10",
        VolumeDomain::Triangle,
        &TRI10,
        &TRI10_EDGES,
        line4,
        Some(21),
    )?;
    Ok((line4, Box::leak(Box::new(tri10))))
}
// ---- end of the elements ----

/// The unit square `[x0, x0 + 1] x [0, 1]` in `2 n^2` Tri10 cells.
fn tri10_square(tri10: VolumeElementRef, x0: f64, n: usize) -> Res<VolumeMesh> {
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
            mesh.add_cell(tri10, &cell.map(|(di, dj)| tag(a + di, b + dj)))?;
        }
    }
    Ok(mesh)
}

/// Writes body `name` on `[x0, x0 + 1] x [0, 1]` as `dir/name.msh`, with its faces at
/// `x = x0` (group `name_x0`) and `x = x0 + 1` (`name_x1`).
fn write_body(
    tri10: VolumeElementRef,
    dir: &std::path::Path,
    name: &str,
    x0: f64,
    n: usize,
) -> Res<()> {
    let mesh = tri10_square(tri10, x0, n)?;
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
    // ---- the user's code: registering and using the elements (40 lines) ----
    let mut registries = Registries::default();
    let (line4, tri10) = elements()?;
    registries.elements.register(line4);
    registries.cells.register(tri10);
    write_body(tri10, out, "left", 0.0, 3)?; // 3 x 3 squares of two Tri10: 3 lines, 10 nodes on x = 1
    write_body(tri10, out, "right", 1.0, 4)?; // 4 x 4: 4 lines, 13 nodes (4 shared: y = 0, 1/3, 2/3, 1)
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
    // The two commands as a user types them (OUT_DIR without spaces).
    let o = out.display();
    for command in [
        format!("mortar couple --slave {o}/right.msh#right_x0 --master {o}/left.msh#left_x1 --out {o}/couple"),
        format!("mortar run {o}/scene.toml --out {o}/scene"),
    ] {
        let args: Vec<&str> = command.split_whitespace().collect();
        if mortar::cli::run_from(&args, &registries) != ExitCode::SUCCESS {
            return Err(format!("`{command}` failed").into());
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
