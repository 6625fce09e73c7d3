//! The memory of second-order contact with dual multipliers, alone in its test binary so that
//! the process's peak resident size is this run's.
//!
//! The condensed Newton system (pressures eliminated through one pivot displacement per
//! active slave node) was assembled by pushing, for each entry of the stiffness between two
//! pivots, the product of their expansions as triplets: with Quad9 slave faces against a
//! Tet10 master each pivot expands into about 100 unknowns and its stiffness row meets some
//! 25 other pivots, so that the shipped Hex27/Tet10 pair of `tests/meshes/so_3d_hex27.msh`
//! (1,900 unknowns) peaked at 342 MB (a 13,600-unknown pair at 3.3 GB, 3.6 times standard
//! multipliers' saddle point). Summed row by row before they are stored, the same system
//! peaks at 38 MB (253 MB).

use std::path::Path;

use mortar_scenes::file::contact::ContactSpec;
use mortar_scenes::file::{FileScene, FileSystem};

/// The peak resident size of this process (`VmHWM` of `/proc/self/status`), in bytes.
#[cfg(target_os = "linux")]
fn peak_resident_bytes() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status");
    let line = status
        .lines()
        .find(|l| l.starts_with("VmHWM:"))
        .expect("a VmHWM line");
    let kb: u64 = line
        .split_whitespace()
        .nth(1)
        .and_then(|v| v.parse().ok())
        .expect("VmHWM in kB");
    kb * 1024
}

/// Linux only: the peak is read from `/proc` (the solver's code is the same everywhere).
#[cfg(target_os = "linux")]
#[test]
fn second_order_dual_contact_stays_small() {
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes/so_3d_hex27.msh");
    let text = format!(
        r#"kind = "contact"
[bodies.top]
mesh = "{mesh}"
group = "top"
youngs_modulus = 1e9
poisson_ratio = 0.3
dirichlet = [{{ group = "top_z1", component = "all", value = [0.0, 0.0, -0.001] }}]
[bodies.bottom]
mesh = "{mesh}"
group = "bottom"
youngs_modulus = 1e9
poisson_ratio = 0.3
dirichlet = [{{ group = "bottom_z0", component = "all", value = 0.0 }}]
[contact]
slave = {{ body = "top", group = "top_bottom" }}
master = {{ body = "bottom", group = "bottom_top" }}
multipliers = "dual"
"#,
        mesh = mesh.display()
    );
    let path = Path::new("memory.toml");
    let spec = ContactSpec::parse(&text, path).unwrap();
    let solved = spec.solve(path, Path::new(""), &FileSystem).unwrap();
    assert!(
        solved
            .solution
            .formulation
            .starts_with("pressures condensed"),
        "{}",
        solved.solution.formulation
    );
    assert_eq!(
        solved.solution.steps[0].active, 81,
        "every slave node in contact"
    );
    let peak = peak_resident_bytes();
    assert!(
        peak < 120 << 20,
        "peak resident size {} MB (at most 120 MB)",
        peak >> 20
    );
}
