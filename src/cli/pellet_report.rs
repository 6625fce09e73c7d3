//! Printing the pellet scene's report: JSON, or for a reader the thermal scene's
//! temperatures against the closed form, or the thermomechanical scene's model, results,
//! status and solver.

use std::path::Path;

use mortar_scenes::pellet;
use serde_json::Value;

/// Prints the pellet's report: JSON, or the steady temperatures against the closed form.
pub(super) fn print_pellet(report: &Value, out: &Path, json: bool) {
    if json {
        say!("{report}");
        return;
    }
    if report["models"]["mechanics"].as_bool() == Some(true) {
        print_coupled(report, out);
        return;
    }
    let num = |v: &Value| v.as_f64().map_or("n/a".to_string(), |x| format!("{x:.3}"));
    for key in [
        "center_temperature",
        "pellet_surface_temperature",
        "cladding_inner_temperature",
    ] {
        let closed = report
            .get("closed_form")
            .and_then(|c| c.get(key))
            .unwrap_or(&Value::Null);
        say!(
            "{key:<28} {} K   (closed form {} K)",
            num(&report[key]),
            num(closed)
        );
    }
    let rel = &report["error"]["center_relative_to_span"];
    if let Some(rel) = rel.as_f64() {
        say!("{:<28} {:.2e} of (T_0 - T_co)", "centre error", rel);
    }
    let solver = &report["solver"];
    say!(
        "{:<28} {} Newton steps, {} linear iterations, {} factorisations",
        format!("solver ({})", report["method"].as_str().unwrap_or("?")),
        solver["newton_iterations"],
        solver["linear_iterations"],
        solver["factorizations"]
    );
    if let Some(t) = report["seconds"]["total"].as_f64() {
        say!("{:<28} {t:.3} s", "time");
    }
    say!("output: {} (report.json, VTU over time)", out.display());
}

/// A report's number, NaN where it has none.
fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

/// Prints the thermomechanical pellet's report: what was modelled and why, and the results.
fn print_coupled(report: &Value, out: &Path) {
    print_modelled(report);
    print_contact_engaged(report);
    print_results(report);
    print_status(report);
    print_solver(report);
    say!("{:<28} {:.3} s", "time", num(&report["seconds"]["total"]));
    say!("output: {} (report.json, VTU over time)", out.display());
}

/// What was modelled: the elasticity (from the geometry and the axial model), the gap
/// conductance, the contact law, the plenum, and the relocation where there is one.
fn print_modelled(report: &Value) {
    let m = &report["models"];
    let law = m["contact_law"].as_str().unwrap_or("?");
    let free = m["axial"].as_str() == Some("generalized");
    let elasticity = match (m["geometry"].as_str(), free) {
        (Some("3d"), true) => "3D thermoelasticity (a segment, its top free axially)",
        (Some("3d"), false) => "3D thermoelasticity (a segment, ends held in z)",
        (Some("axisymmetric"), true) => "r-z thermoelasticity (a segment, its top free axially)",
        (Some("axisymmetric"), false) => "r-z thermoelasticity (a segment, ends held in z)",
        (_, true) => "generalized plane strain thermoelasticity (free axial expansion)",
        (_, false) => "plane-strain thermoelasticity",
    };
    say!(
        "{:<28} heat with k(T), {elasticity}, gap conductance on the",
        "modelled"
    );
    say!(
        "{:<28} mechanical gap, {law} contact law, plenum pressure (ideal gas)",
        ""
    );
    if let Some(model) = m["relocation"].as_str().filter(|&r| r != "none") {
        say!(
            "{:<28} {model} relocation at {} MWd/kgU: strain {:.3e} at full power",
            "",
            num(&m["burnup"]),
            num(&report["steady"]["relocation_strain"])
        );
    }
}

/// When contact engaged, and what that means for the law: the exponential law engages below
/// its onset gap xi, with the gap still open; the exact law engages at a closed gap.
fn print_contact_engaged(report: &Value) {
    let onset = report["models"]["contact_onset_gap"].as_f64();
    match (report["gap_closure_time"].as_f64(), onset) {
        (Some(t), Some(xi)) => say!(
            "{:<28} contact engaged at t = {t:.2} s (smallest gap below the onset of the pressure law, \
             xi = {:.2} um)",
            "gap",
            1e6 * xi
        ),
        (Some(t), None) => say!(
            "{:<28} contact engaged at t = {t:.2} s (gap closed, contact pressure positive)",
            "gap"
        ),
        (None, _) => say!(
            "{:<28} contact never engaged (the pressure stays at the gas pressure)",
            "gap"
        ),
    }
}

/// The results: the centre temperature, the final gap, the peak contact pressure, a stack's
/// lands, the plenum pressure and the steady state.
fn print_results(report: &Value) {
    let h = &report["history"];
    let last = |k: &str| h[k].as_array().and_then(|a| a.last()).map_or(f64::NAN, num);
    say!(
        "{:<28} {:.3} K",
        "centre temperature",
        num(&report["center_temperature"])
    );
    say!(
        "{:<28} {:.3} um (mean; min {:.3} um)",
        "final gap",
        1e6 * num(&report["gap"]),
        1e6 * last("min_gap")
    );
    say!(
        "{:<28} {:.3} MPa (interface, incl. gas)",
        "peak contact pressure",
        1e-6 * num(&report["peak_interface_pressure"])
    );
    // A stack's lands: the pellets bearing on each other.
    if let (Some(gap), Some(p)) = (
        h["land_min_gap"].as_array(),
        h["land_peak_contact_pressure"].as_array(),
    ) {
        let smallest = gap.iter().map(num).fold(f64::INFINITY, f64::min);
        let peak = p.iter().map(num).fold(f64::NEG_INFINITY, f64::max);
        say!(
            "{:<28} smallest gap {:.3} um, peak contact pressure {:.3} MPa",
            "pellet lands",
            1e6 * smallest,
            1e-6 * peak
        );
    }
    say!(
        "{:<28} {:.4} MPa",
        "plenum pressure",
        1e-6 * num(&report["plenum_pressure"])
    );
    let st = &report["steady"];
    say!(
        "{:<28} T0 {:.3} K, energy imbalance {:.1e}",
        "steady state (full power)",
        num(&st["center_temperature"]),
        num(&st["relative_imbalance"])
    );
}

/// The coupling's warnings (on stderr) and the model ranges the run left (docs/models.md,
/// section 3b), one line each, or that it left none.
fn print_status(report: &Value) {
    for w in report["coupling_warnings"].as_array().into_iter().flatten() {
        eprintln!("mortar: warning: {}", w.as_str().unwrap_or_default());
    }
    let limits = pellet::limits::summary_lines(&report["warnings"]);
    if limits.is_empty() {
        say!("{:<28} ok: every state within the models' ranges", "status");
    } else {
        say!(
            "{:<28} warnings: {} model range(s) left, the results there are not physical",
            "status",
            limits.len()
        );
        for line in limits {
            say!("  warning {line}");
        }
    }
}

/// The solver: its counts, why it was picked, and a fall-back to Newton.
fn print_solver(report: &Value) {
    let solver = &report["solver"];
    say!(
        "{:<28} {} Newton steps, {} linear iterations, {} factorisations, {} step cuts",
        format!("solver ({})", report["method"].as_str().unwrap_or("?")),
        solver["newton_iterations"],
        solver["linear_iterations"],
        solver["factorizations"],
        solver["step_cuts"]
    );
    let choice = &report["solver_choice"];
    if let Some(why) = choice["why"].as_str() {
        say!("{:<28} {why}", "");
    }
    if let Some(t) = choice["fallback_to_newton"]["time"].as_f64() {
        say!("{:<28} JFNK failed at t = {t} s: Newton took over", "");
    }
    let linear = &report["linear_solver"];
    if linear["backend"].as_str() == Some("petsc") {
        let its: Vec<u64> = linear["iterations"]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_u64).collect())
            .unwrap_or_default();
        let (lo, hi) = (its.iter().min(), its.iter().max());
        say!(
            "{:<28} PETSc {}: {} solves, {} to {} iterations",
            "linear solver",
            linear["methods"][0].as_str().unwrap_or("?"),
            its.len(),
            lo.map_or("?".into(), u64::to_string),
            hi.map_or("?".into(), u64::to_string)
        );
    }
}
