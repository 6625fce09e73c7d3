//! Rendering a solved tied heat scene: a VTU per body (its temperatures), `report.json`
//! (the formulation and why, the unknowns, the interface, the seconds per phase) and the
//! terminal's summary.

use std::path::Path;
use std::time::Instant;

use mortar::io::vtu::{vtu_string, VtuPiece};
use mortar_physics::heat::HeatBody;
use serde_json::Value;

use super::SolvedTiedHeat;
use crate::file::two_bodies::{report_bytes, warning_texts};
use crate::file::{SceneError, SceneOutput, SolvedScene};

impl SolvedScene for SolvedTiedHeat {
    /// The VTU file of each body (`NAME.vtu`, nodal `temperature`), `report.json` and a
    /// readable summary.
    ///
    /// # Errors
    /// [`SceneError::Other`] if a file cannot be rendered.
    fn output(&self) -> Result<SceneOutput, SceneError> {
        let t_out = Instant::now();
        let mut files = Vec::with_capacity(3);
        let mut body_reports = Vec::with_capacity(2);
        for (i, body) in self.problem.bodies().iter().enumerate() {
            let (file, report) = self.body_output(i, body)?;
            files.push(file);
            body_reports.push(report);
        }
        let seconds_output = t_out.elapsed().as_secs_f64();
        let warnings = warning_texts(
            &self.problem.tie().coupling().warnings,
            "interface",
            self.spec.interface.search_radius,
        );
        let report = self.report(&body_reports, &warnings, seconds_output);
        let json =
            report_bytes(&report).map_err(|e| SceneError::Other(format!("report.json: {e}")))?;
        files.push(("report.json".to_string(), json));
        let summary = self.summary(&body_reports);
        Ok(SceneOutput {
            files,
            summary,
            warnings,
        })
    }
}

impl SolvedTiedHeat {
    /// Body `i`'s VTU file (`NAME.vtu`, nodal `temperature`) and its entry in the report
    /// (with its temperature range).
    fn body_output(
        &self,
        i: usize,
        body: &HeatBody,
    ) -> Result<((String, Vec<u8>), Value), SceneError> {
        let t = &self.solution.temperatures[i];
        let file = format!("{}.vtu", body.name);
        let vtu = vtu_string(
            Path::new(&file),
            &[VtuPiece {
                mesh: &body.mesh,
                point_data: vec![("temperature", t)],
            }],
        )
        .map_err(|e| SceneError::Other(e.to_string()))?;
        let (lo, hi) = t
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let report = serde_json::json!({
            "name": body.name,
            "role": if i == 0 { "slave" } else { "master" },
            "mesh": self.labels[i],
            "nodes": body.mesh.node_count(),
            "cells": body.mesh.cell_count(),
            "temperature_min": lo,
            "temperature_max": hi,
            "vtu": file,
        });
        Ok(((file, vtu.into_bytes()), report))
    }

    /// The unknowns: the nodes of both bodies.
    fn dofs(&self) -> usize {
        self.problem
            .bodies()
            .iter()
            .map(|b| b.mesh.node_count())
            .sum()
    }

    /// The report's `"solver"` entry: the direct solve (no iterations), or the Krylov
    /// solves' iterations.
    fn solver_entry(&self) -> Value {
        let reports = self.linear_solver.reports();
        if reports.is_empty() {
            serde_json::json!({ "kind": "sparse direct", "iterations": Value::Null })
        } else {
            let iterations: Vec<usize> = reports.iter().map(|r| r.iterations).collect();
            serde_json::json!({ "kind": "PETSc Krylov", "iterations": iterations })
        }
    }

    /// `report.json`'s value: the scene and its solve, the formulation, the interface, the
    /// bodies' entries, the warnings and the seconds per phase (`seconds_output` rendering
    /// the VTU files).
    fn report(&self, body_reports: &[Value], warnings: &[String], seconds_output: f64) -> Value {
        let (problem, solution) = (&self.problem, &self.solution);
        let f = &solution.formulation;
        let s = solution.seconds;
        let stats = &problem.tie().coupling().stats;
        let interface = &self.spec.interface;
        serde_json::json!({
            "kind": "tied_heat",
            "scene": self.path.display().to_string(),
            "title": self.spec.title,
            "dimension": self.dimension,
            "mode": self.spec.solve.mode,
            "steps": self.steps,
            "dt": self.spec.solve.dt,
            "time": self.time,
            "dofs": self.dofs(),
            "formulation": {
                "name": f.formulation.describe(),
                "factorisation": f.factorisation,
                "reason": f.reason,
                "unknowns": f.unknowns,
                "nonzeros": f.nonzeros,
                "multipliers": f.multipliers,
                "redistributed": f.redistributed,
                "dropped": f.dropped,
            },
            "solver": self.solver_entry(),
            "linear_solver": self.linear_solver.json(),
            "interface": {
                "slave": format!("{}#{}", self.files[0].display(), interface.slave.group),
                "master": format!("{}#{}", self.files[1].display(), interface.master.group),
                "multipliers": interface.multipliers,
                "integration": interface.integration,
                "coupling": self.coupling,
                "slave_nodes": problem.tie().slave_nodes().len(),
                "master_nodes": problem.tie().master_nodes().len(),
                "area": stats.area,
            },
            "bodies": body_reports,
            "warnings": warnings,
            "seconds": {
                "read": self.t_read,
                "assembly": s.assembly,
                "coupling": s.coupling,
                "loads": s.loads,
                "system": s.system,
                "factorisation": s.factorisation,
                "solve": s.solve,
                "output": seconds_output,
                "total": self.t_start.elapsed().as_secs_f64(),
            },
        })
    }

    /// The terminal's summary: the sizes and steps, the formulation, each body's
    /// temperature range (from its entry in `body_reports`) and the seconds per phase.
    fn summary(&self, body_reports: &[Value]) -> String {
        let (steps, time) = (self.steps, self.time);
        let s = self.solution.seconds;
        let bodies = self.problem.bodies();
        format!(
            "tied heat, {}D, {} unknowns ({} + {} nodes){}\nformulation: {}\n{}\ntemperature: {}\nseconds: read {:.3}, assembly {:.3}, coupling {:.3}, factorisation {:.3}, solve {:.3}, total {:.3}",
            self.dimension,
            self.dofs(),
            bodies[0].mesh.node_count(),
            bodies[1].mesh.node_count(),
            if steps > 0 {
                format!(", {steps} steps to t = {time}")
            } else {
                String::new()
            },
            self.solution.formulation,
            self.linear_solver.summary_line(),
            body_reports
                .iter()
                .map(|b| format!(
                    "{} in [{:.6}, {:.6}]",
                    b["name"].as_str().unwrap_or(""),
                    b["temperature_min"].as_f64().unwrap_or(f64::NAN),
                    b["temperature_max"].as_f64().unwrap_or(f64::NAN)
                ))
                .collect::<Vec<_>>()
                .join(", "),
            self.t_read,
            s.assembly,
            s.coupling,
            s.factorisation,
            s.solve,
            self.t_start.elapsed().as_secs_f64(),
        )
    }
}
