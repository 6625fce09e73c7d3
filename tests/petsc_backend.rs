//! The physics' elastic solve through PETSc (`mortar::petsc::PetscBackend`, CG with algebraic
//! multigrid) against the direct backend: a plane-strain block (64 x 32 Quad4, 4 290 free
//! unknowns) held at its bottom, pressed and sheared on its top. Source: the direct sparse
//! Cholesky solve of the same system; the Krylov solve's relative tolerance 1e-10 bounds the
//! difference by about the condition number's share of it (measured 1.4e-10, 85 CG
//! iterations with GAMG).
//! In a build without PETSc (`--features petsc` absent) the same call is a typed error that
//! says how to get it.

use mortar::generate::{rectangle_mesh, CellShape};
use mortar::petsc::{KrylovMethod, PetscBackend, Preconditioner, SolveOptions};
use mortar::physics::elastic::{
    solve_elastic_on, solve_elastic_with, ComponentSet, ElasticBody, ElasticMaterial,
    ElasticOptions,
};
use nalgebra::Vector3;

#[test]
fn an_elastic_solve_through_petsc_matches_the_direct_one() {
    let mesh = rectangle_mesh([0.0, 0.0], [2.0, 1.0], [64, 32], CellShape::Tensor, 1).unwrap();
    let body = ElasticBody::new("block", mesh, ElasticMaterial::new(200e9, 0.3))
        .with_dirichlet_where(
            |f| f.centroid.y < 1e-9,
            ComponentSet::All,
            |_| Vector3::zeros(),
        )
        .unwrap()
        .with_traction_where(
            |f| f.centroid.y > 1.0 - 1e-9,
            |x| Vector3::new(2e7 * x.x, -1e8, 0.0),
        )
        .unwrap();
    let options = ElasticOptions::default();
    let direct = solve_elastic_with(&body, &options).unwrap();
    let mut petsc = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg);
    petsc.rtol = 1e-10;
    let backend = PetscBackend::new(petsc);
    let solved = solve_elastic_on(&body, &options, &backend);
    if !mortar::petsc::is_built() {
        let e = solved.unwrap_err().to_string();
        assert!(e.contains("--features petsc"), "{e}");
        return;
    }
    let u = solved.unwrap();
    let norm = direct.iter().map(|v| v * v).sum::<f64>().sqrt();
    let diff = u
        .iter()
        .zip(&direct)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt()
        / norm;
    let report = &backend.reports()[0];
    println!("elastic block through PETSc: {report}; relative difference {diff:.2e}");
    assert!(report.reason.is_converged(), "{report}");
    assert_eq!(report.ksp_type, "cg");
    assert!(diff < 1e-8, "{diff:e}");
}

/// The contact patch test of `examples/scenes/contact_blocks.toml` (two non-matching blocks,
/// 50 MPa carried as a uniform pressure: the closed form) with `[solve] backend = "petsc"`:
/// the pressures and displacements of the direct solve to 1e-11 of their largest values
/// (measured 5.6e-13 and 1.3e-13, the Krylov tolerance 1e-12), the
/// same Newton steps, the report naming PETSc's CG with GAMG. Without PETSc in the build the
/// same key is refused before anything is read, saying how to get it.
#[test]
fn a_contact_scene_through_petsc_matches_the_direct_solve() {
    use mortar_scenes::file::contact::ContactSpec;
    use mortar_scenes::file::{FileScene, FileSystem};
    use mortar_scenes::linear_solver::BackendChoice;

    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes/contact_blocks.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let base = path.parent().unwrap();
    let direct = ContactSpec::parse(&text, &path)
        .unwrap()
        .solve(&path, base, &FileSystem)
        .unwrap();
    assert_eq!(direct.linear_solver.name, "direct");
    let with_petsc = format!("{text}\n[solve]\nbackend = \"petsc\"\n");
    let spec = ContactSpec::parse(&with_petsc, &path);
    if !mortar::petsc::is_built() {
        let err = spec.map(|_| ()).unwrap_err().to_string();
        assert!(
            err.contains("solve.backend") && err.contains("--features petsc"),
            "{err}"
        );
        return;
    }
    let spec = spec.unwrap();
    assert_eq!(spec.solve.backend, BackendChoice::Petsc);
    let petsc = spec.solve(&path, base, &FileSystem).unwrap();
    let (a, b) = (&direct.solution, &petsc.solution);
    let largest = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = |x: &[f64], y: &[f64]| {
        x.iter()
            .zip(y)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max)
            / largest(x)
    };
    let dp = diff(&a.pressure, &b.pressure);
    let du = (0..2)
        .map(|k| diff(&a.displacements[k], &b.displacements[k]))
        .fold(0.0, f64::max);
    let steps = |s: &mortar::physics::contact::ContactSolution| {
        s.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>()
    };
    let reports = petsc.linear_solver.reports();
    println!(
        "contact_blocks through PETSc: pressure {dp:.1e}, displacement {du:.1e} off the direct \
         solve; {}",
        petsc.linear_solver.summary_line()
    );
    assert!(
        dp < 1e-11 && du < 1e-11,
        "pressure {dp:e}, displacement {du:e}"
    );
    assert_eq!(steps(a), steps(b));
    assert_eq!(petsc.linear_solver.name, "petsc");
    assert!(
        b.formulation.contains("backend") && !b.formulation.contains("Cholesky"),
        "the formulation names the backend, not the direct factorisation: {}",
        b.formulation
    );
    assert!(
        a.formulation.contains("sparse Cholesky"),
        "{}",
        a.formulation
    );
    assert!(!reports.is_empty());
    assert!(reports
        .iter()
        .all(|r| r.ksp_type == "cg" && r.pc_type == "gamg" && r.near_null_space));
}

/// A Krylov solve that stops short of its tolerance (here allowed 2 iterations) is a typed
/// error naming the system, the load and Newton step, PETSc's method, the iterations and the
/// residual, and what to change; nothing is written.
#[test]
fn a_krylov_solve_that_does_not_converge_names_the_system_and_the_step() {
    use mortar_scenes::file::contact::ContactSpec;
    use mortar_scenes::file::{FileScene, FileSystem};

    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes/contact_blocks.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = format!("{text}\n[solve]\nbackend = \"petsc\"\npetsc_options = \"-ksp_max_it 2\"\n");
    let spec = ContactSpec::parse(&text, &path);
    if !mortar::petsc::is_built() {
        // Without PETSc the scene is refused as it is read, saying how to get it.
        let err = spec.map(|_| ()).unwrap_err().to_string();
        assert!(err.contains("--features petsc"), "{err}");
        return;
    }
    let err = spec
        .unwrap()
        .solve(&path, path.parent().unwrap(), &FileSystem)
        .unwrap_err()
        .to_string();
    println!("{err}");
    for needle in [
        "contact Newton system at load step 1, Newton step 0",
        "did not converge",
        "after 2 iterations",
        "relative residual",
        "linear_tolerance",
    ] {
        assert!(err.contains(needle), "{needle:?} not in {err}");
    }
}

/// The tied heat convergence study (the sine solution on two non-matching bodies tied by dual
/// mortar, `mortar_scenes::tied_heat`) with the condensed system solved by PETSc's CG with
/// GAMG against the direct sparse Cholesky: the same L2 and H1 errors (to the Krylov
/// tolerance's share) and so the same rates, 2.00 in L2 and 1.00 in H1 (the closed-form
/// orders of linear elements, Wohlmuth 2001). Levels n = 8, 16, 32 in 2D; 4, 8 in 3D.
#[test]
fn tied_heat_rates_through_petsc_are_the_direct_ones() {
    use mortar::physics::LinearSolve;
    use mortar_scenes::tied_heat::{rate, Geometry, TiedHeatScene};
    let backend = PetscBackend::automatic(1e-12, "");
    let linear = LinearSolve {
        backend: Some(&backend),
        ..LinearSolve::default()
    };
    for (dim, levels) in [(2, &[8, 16, 32][..]), (3, &[4, 8][..])] {
        let mut runs = Vec::new();
        for &n in levels {
            let scene = TiedHeatScene::new(dim, Geometry::Straight, n);
            let direct = scene.run().unwrap();
            let petsc = scene.run_on(&linear);
            if !mortar::petsc::is_built() {
                let e = petsc.unwrap_err().to_string();
                assert!(e.contains("--features petsc"), "{e}");
                return;
            }
            let petsc = petsc.unwrap();
            let (dl2, dh1) = (
                (petsc.l2 - direct.l2).abs() / direct.l2,
                (petsc.h1 - direct.h1).abs() / direct.h1,
            );
            println!(
                "{dim}D n = {n}: L2 {:.6e} (direct {:.6e}, off {dl2:.1e}), H1 {:.6e} (off {dh1:.1e})",
                petsc.l2, direct.l2, petsc.h1
            );
            assert!(dl2 < 1e-9 && dh1 < 1e-9, "{dl2:e} {dh1:e}");
            runs.push((direct, petsc));
        }
        for w in runs.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            let (l2, h1) = (
                rate(a.1.h, a.1.l2, b.1.h, b.1.l2),
                rate(a.1.h, a.1.h1, b.1.h, b.1.h1),
            );
            let direct = rate(a.0.h, a.0.l2, b.0.h, b.0.l2);
            println!("{dim}D rates through PETSc: L2 {l2:.3}, H1 {h1:.3} (direct L2 {direct:.3})");
            assert!((l2 - direct).abs() < 1e-6, "{l2} {direct}");
            assert!(l2 > 1.9 && h1 > 0.9, "{l2} {h1}");
        }
        let report = &backend.reports()[0];
        assert_eq!(
            (report.ksp_type.as_str(), report.pc_type.as_str()),
            ("cg", "gamg")
        );
    }
}

/// The coupled pellet (the built-in scene, to 12 s: the gap closes at about 9 s) with Newton's
/// Jacobians through PETSc (GMRES(100) with ILU(0)) against Newton with the bordered sparse LU.
/// Source: the direct run of the same scene; the Krylov solves' relative tolerance (1e-12)
/// leaves Newton's iterates, and so the history, as the direct one's (measured 7e-12 relative
/// over the whole 30 s history, the same 88 Newton steps).
#[test]
fn the_coupled_pellet_through_petsc_matches_the_direct_newton() {
    use mortar_scenes::pellet::{run, PelletScene};

    let text = "kind = \"pellet\"\n[time]\nend = 12.0\n[solver]\nmethod = \"newton\"\n";
    let with_petsc = format!("{text}backend = \"petsc\"\n");
    let parsed = PelletScene::from_toml(&with_petsc);
    if !mortar::petsc::is_built() {
        let err = parsed.map(|_| ()).unwrap_err().to_string();
        assert!(
            err.contains("solver.backend") && err.contains("--features petsc"),
            "{err}"
        );
        return;
    }
    let dir = std::env::temp_dir().join(format!("mortar_pellet_petsc_{}", std::process::id()));
    let direct = run(
        &PelletScene::from_toml(text).unwrap(),
        &dir.join("direct"),
        false,
    )
    .unwrap();
    let petsc = run(&parsed.unwrap(), &dir.join("petsc"), false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(direct["linear_solver"]["backend"], "direct");
    assert_eq!(petsc["linear_solver"]["backend"], "petsc");
    assert_eq!(petsc["linear_solver"]["methods"][0], "gmres+ilu");
    assert_eq!(
        direct["solver"]["newton_iterations"],
        petsc["solver"]["newton_iterations"]
    );
    let mut worst = 0.0f64;
    let history = direct["history"].as_object().unwrap();
    for (key, column) in history {
        let (Some(a), Some(b)) = (column.as_array(), petsc["history"][key].as_array()) else {
            continue;
        };
        assert_eq!(a.len(), b.len(), "{key}");
        // Relative to the column's largest value (a pressure is 0 before contact).
        let scale = a
            .iter()
            .filter_map(|x| x.as_f64())
            .fold(0.0, |m, x| x.abs().max(m));
        for (x, y) in a.iter().zip(b) {
            if let (Some(x), Some(y)) = (x.as_f64(), y.as_f64()) {
                worst = worst.max((x - y).abs() / scale.max(f64::MIN_POSITIVE));
            }
        }
    }
    assert!(history.contains_key("center_temperature"));
    assert!(worst < 1e-6, "history differs by {worst:e}");
}

/// The Hertz verifications with the contact Newton's systems through PETSc (CG with GAMG, the
/// bodies' rigid motions as its near null space) against the direct solves: a cylinder of 24
/// arc cells (2D) and a sphere octant of 8 cells a direction (3D). Source: the direct runs of
/// the same scenes (Johnson's closed forms are the direct runs' own checks); the Krylov
/// tolerance (1e-12) leaves the Newton steps, the active set and the errors against the closed
/// forms the direct ones'.
#[test]
fn hertz_errors_through_petsc_are_the_direct_ones() {
    use mortar_scenes::hertz::{HertzScene, HertzSphereScene};
    let backend = PetscBackend::automatic(1e-12, "");
    let cylinder = HertzScene::new(24);
    let direct = cylinder.run().unwrap();
    let problem = cylinder.build().unwrap();
    let solved = problem.solve_on(&cylinder.contact, Some(&backend));
    if !mortar::petsc::is_built() {
        let e = solved.unwrap_err().to_string();
        assert!(e.contains("--features petsc"), "{e}");
        return;
    }
    let petsc = cylinder.evaluate(&problem, &solved.unwrap(), 0.0);
    assert_eq!(
        (petsc.steps.len(), petsc.active),
        (direct.steps.len(), direct.active)
    );
    for (p, d) in [
        (petsc.peak_error(), direct.peak_error()),
        (petsc.half_width_error(), direct.half_width_error()),
    ] {
        assert!((p - d).abs() < 1e-8, "2D: {p:e} against {d:e}");
    }
    let sphere = HertzSphereScene::new(8);
    let direct = sphere.run().unwrap();
    let before = backend.reports().len();
    let petsc = sphere.run_on(Some(&backend)).unwrap();
    let sphere_reports = &backend.reports()[before..];
    assert!(
        !sphere_reports.is_empty()
            && sphere_reports
                .iter()
                .all(|r| r.ksp_type == "cg" && r.pc_type == "hypre"),
        "3D elasticity through BoomerAMG: {:?}",
        sphere_reports
            .iter()
            .map(|r| (&r.ksp_type, &r.pc_type))
            .collect::<Vec<_>>()
    );
    assert_eq!(
        (petsc.steps.len(), petsc.active, petsc.max_newton_steps()),
        (direct.steps.len(), direct.active, direct.max_newton_steps())
    );
    for (p, d) in [
        (
            petsc.peak_error_at_approach(),
            direct.peak_error_at_approach(),
        ),
        (
            petsc.load_error_at_approach(),
            direct.load_error_at_approach(),
        ),
        (
            petsc.radius_error_at_approach(),
            direct.radius_error_at_approach(),
        ),
    ] {
        assert!((p - d).abs() < 1e-8, "3D: {p:e} against {d:e}");
    }
    assert!(backend.reports().iter().all(|r| r.ksp_type == "cg"));
}
