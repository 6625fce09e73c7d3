//! An element of one's own, end to end: the library ships elements up to order
//! two; here a program adds the cubic pair Gmsh writes with `-order 3` in 2D, the ten-node
//! triangle (Gmsh type 21) and its four-node edges (Gmsh type 26), and uses them through the
//! library's own doors on a file Gmsh made (`tests/meshes/so3_2d_tri10.msh`, two bodies meshed
//! apart, 3 against 4 cubic edges on their interface): the interface lines are read by the
//! Gmsh reader, tied by `Interface` and the coupling and checked by `mortar::testing`'s patch
//! test (sum(D) = the interface's length, D 1 = M 1, D x = M x, row sums against nodal areas,
//! D diagonal for dual multipliers), then coupled again by `mortar couple` and solved as a
//! tied-heat scene file by `mortar run`, both from `mortar_app::cli::run_from` with the program's
//! registries (a program's `main` would be `mortar_app::cli::main_with(registries)`).
//!
//! ```sh
//! cargo run --release --example extend_element [OUT_DIR]
//! ```

use std::process::ExitCode;

use mortar::core::element::volume::VolumeDomain::Triangle;
use mortar::core::element::ReferenceDomain;
use mortar::elements::{LagrangeCell, LagrangeFace};
use mortar::extend::Registries;
use mortar::io::read_gmsh_surface;
use mortar::testing::patch_test;
use mortar::{assemble_coupling, CouplingOptions, Interface};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

// ---- the user's code: the two elements' nodes and faces (15 lines as rustfmt lays them out, comments and blank lines not counted) ----
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
// ---- end of the elements ----

/// The Gmsh file: two unit squares side by side in Tri10 cells, made by
/// `tests/meshes/make_second_order_meshes.py` (`Mesh.ElementOrder = 3`).
const MESH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/meshes/so3_2d_tri10.msh");

/// The scene: `T = 0` at `x = 0`, heat flux 2 entering at `x = 2`, `k` 1 on the left and 2 on
/// the right: `T = 2 x` on the left, `2 + (x - 1)` on the right, exact for these elements.
const SCENE: &str = r#"kind = "tied_heat"
[bodies.left]
mesh = "MESH"
group = "left"
conductivity = 1.0
dirichlet = [{ group = "left_x0", value = 0.0 }]
[bodies.right]
mesh = "MESH"
group = "right"
conductivity = 2.0
neumann = [{ group = "right_x1", flux = 2.0 }]
[interface]
slave = { body = "right", group = "right_x0" }
master = { body = "left", group = "left_x1" }
"#;

/// Runs the example, writing into `out` (the scene and the outputs of `couple` and `run`).
pub fn run(out: &std::path::Path) -> Res<()> {
    std::fs::create_dir_all(out)?;
    // ---- the user's code: registering and using the elements (26 lines) ----
    // Lagrange elements from their nodes: the library finds their cubic shape functions.
    let mut registries = Registries::default();
    let line4 = LagrangeFace::new("Line4", ReferenceDomain::Line, 2, &LINE4, Some(26))?;
    let line4 = registries.elements.add(line4.with_reversal(&[1, 0, 3, 2]));
    let tri = LagrangeCell::new("Tri10", Triangle, &TRI10, &TRI10_EDGES, line4, Some(21))?;
    registries.cells.add(tri);
    let read = |group| read_gmsh_surface(MESH, Some(group), &registries.elements);
    let (mut slave, mut master) = (read("right_x0")?, read("left_x1")?);
    slave.orient_outward()?; // outward from their Tri10 cells: facing each other
    master.orient_outward()?;
    let interface = Interface::new(slave.mesh, master.mesh)?;
    let c = assemble_coupling(&interface, &CouplingOptions::default().dual())?;
    let patch = patch_test(&interface, &c, true).worst(); // D 1 = M 1, D x = M x, D diagonal
    println!(
        "sum(D) = {:.15} (length 1), patch test {patch:.1e}",
        c.stats.area
    );
    assert!((c.stats.area - 1.0).abs() < 1e-12 && patch < 1e-12);
    std::fs::write(out.join("scene.toml"), SCENE.replace("MESH", MESH))?;
    let o = out.display(); // the two commands as a user types them (paths without spaces)
    for command in [
        format!("mortar couple --slave {MESH}#right_x0 --master {MESH}#left_x1 --out {o}/couple"),
        format!("mortar run {o}/scene.toml --out {o}/scene"),
    ] {
        let args: Vec<&str> = command.split_whitespace().collect();
        assert_eq!(
            mortar_app::cli::run_from(&args, &registries),
            ExitCode::SUCCESS
        );
    }
    // ---- end of the user's code ----
    check_scene(out, &registries)
}

/// Solves the scene file through the library with the same registries and checks the
/// temperature against the exact one.
fn check_scene(out: &std::path::Path, registries: &Registries) -> Res<()> {
    use mortar_scenes::file::{tied_heat::TiedHeatSpec, FileScene, FileSystem};
    let path = out.join("scene.toml");
    let text = SCENE.replace("MESH", MESH);
    let solved =
        TiedHeatSpec::parse(&text, &path)?.solve_with(&path, out, &FileSystem, registries)?;
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
