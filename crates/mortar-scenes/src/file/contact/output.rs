//! Rendering a solved contact scene: a VTU per body (displacements and stresses),
//! `interface.vtu` (the slave surface with its gap and contact pressure), `report.json` and
//! the terminal's summary.

use std::path::Path;
use std::time::Instant;

use mortar::io::vtu::{surface_vtu_string, vtu_string_with_vectors, VtuPiece};
use mortar_core::element::ElementRef;
use mortar_physics::elastic::ElasticBody;
use nalgebra::Vector3;
use serde_json::Value;

use super::{SolvedContact, STRESS_NAMES};
use crate::file::two_bodies::{report_bytes, warning_texts};
use crate::file::{SceneError, SceneOutput, SolvedScene};

/// A file that cannot be rendered.
fn other(e: &dyn std::fmt::Display) -> SceneError {
    SceneError::Other(e.to_string())
}

impl SolvedScene for SolvedContact {
    /// `NAME.vtu` per body, `interface.vtu`, `report.json` and a summary.
    ///
    /// # Errors
    /// [`SceneError::Other`] if a file cannot be rendered.
    fn output(&self) -> Result<SceneOutput, SceneError> {
        let t_out = Instant::now();
        let mut files = Vec::with_capacity(4);
        let mut body_reports = Vec::with_capacity(2);
        for (i, body) in self.bodies.iter().enumerate() {
            let (file, report) = self.body_output(i, body)?;
            files.push(file);
            body_reports.push(report);
        }
        files.push(("interface.vtu".to_string(), self.interface_vtu()?));

        let pmax = self.solution.pressure.iter().fold(0.0f64, |a, x| a.max(*x));
        let mut seconds: serde_json::Map<String, Value> = self
            .seconds
            .iter()
            .map(|(k, v)| (k.to_string(), serde_json::json!(v)))
            .collect();
        seconds.insert(
            "output".into(),
            serde_json::json!(t_out.elapsed().as_secs_f64()),
        );
        seconds.insert(
            "total".into(),
            serde_json::json!(self.t_start.elapsed().as_secs_f64()),
        );
        let warnings = warning_texts(
            &self.tie.coupling().warnings,
            "contact",
            self.spec.contact.search_radius,
        );
        let report = self.report(body_reports, &warnings, pmax, seconds);
        let json = report_bytes(&report).map_err(|e| other(&e))?;
        files.push(("report.json".to_string(), json));
        Ok(SceneOutput {
            files,
            summary: self.summary(pmax),
            warnings,
        })
    }
}

impl SolvedContact {
    /// Body `i`'s VTU file (`NAME.vtu`: its displacements as 3-vectors, its stresses and von
    /// Mises stress at the nodes) and its entry in the report.
    fn body_output(
        &self,
        i: usize,
        body: &ElasticBody,
    ) -> Result<((String, Vec<u8>), Value), SceneError> {
        let dim = self.dimension;
        let n = body.mesh.node_count();
        let u = &self.solution.displacements[i];
        let mut u3 = vec![0.0; 3 * n];
        for node in 0..n {
            u3[3 * node..3 * node + dim].copy_from_slice(&u[dim * node..dim * node + dim]);
        }
        let (stress, vm) = &self.stresses[i];
        let comps: Vec<Vec<f64>> = (0..6)
            .map(|k| stress.iter().map(|s| s[k]).collect())
            .collect();
        let mut point_data: Vec<(&str, &[f64])> = STRESS_NAMES
            .iter()
            .zip(&comps)
            .map(|(name, c)| (*name, c.as_slice()))
            .collect();
        point_data.push(("von_mises", vm));
        let file = format!("{}.vtu", body.name);
        let vtu = vtu_string_with_vectors(
            Path::new(&file),
            &[VtuPiece {
                mesh: &body.mesh,
                point_data,
            }],
            &[("displacement", vec![&u3])],
        )
        .map_err(|e| other(&e))?;
        let umax = u.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let vmax = vm.iter().fold(0.0f64, |a, x| a.max(*x));
        let report = serde_json::json!({
            "name": body.name,
            "role": if i == 0 { "slave" } else { "master" },
            "mesh": self.labels[i],
            "nodes": n,
            "cells": body.mesh.cell_count(),
            "displacement_max": umax,
            "von_mises_max": vmax,
            "vtu": file,
        });
        Ok(((file, vtu.into_bytes()), report))
    }

    /// `interface.vtu`: the slave surface, its nodes in coupling row order, with the gap and
    /// the contact pressure.
    fn interface_vtu(&self) -> Result<Vec<u8>, SceneError> {
        let slave = &self.bodies[0];
        let rows = &self.tie.slave_nodes();
        let mut row_of = std::collections::HashMap::with_capacity(rows.len());
        for (j, &node) in rows.iter().enumerate() {
            row_of.insert(node, j as u32);
        }
        let points: Vec<Vector3<f64>> = rows
            .iter()
            .map(|&n| slave.mesh.coords()[n as usize])
            .collect();
        // Every node of a slave face has a row (the interface is made of these faces): a
        // face without is refused, not left out of the file.
        let cells = self
            .slave_faces
            .iter()
            .map(|f| {
                let nodes: Option<Vec<u32>> =
                    f.nodes.iter().map(|n| row_of.get(n).copied()).collect();
                nodes.map(|nodes| (f.element, nodes)).ok_or_else(|| {
                    SceneError::Other(format!(
                        "interface.vtu: a node of slave face {} (of cell {}) has no row of the \
                         coupling",
                        f.local_face, f.cell
                    ))
                })
            })
            .collect::<Result<Vec<(ElementRef, Vec<u32>)>, SceneError>>()?;
        let sol = &self.solution;
        let vtu = surface_vtu_string(
            Path::new("interface.vtu"),
            &points,
            &cells,
            &[("gap", &sol.gap), ("contact_pressure", &sol.pressure)],
        )
        .map_err(|e| other(&e))?;
        Ok(vtu.into_bytes())
    }

    /// `report.json`'s value: the scene, the law and interface, the load steps, the contact
    /// force and peak pressure `pmax`, the bodies' entries, the warnings and the seconds.
    fn report(
        &self,
        body_reports: Vec<Value>,
        warnings: &[String],
        pmax: f64,
        seconds: serde_json::Map<String, Value>,
    ) -> Value {
        let sol = &self.solution;
        let c = &self.spec.contact;
        serde_json::json!({
            "kind": "contact",
            "scene": self.path.display().to_string(),
            "title": self.spec.title,
            "dimension": self.dimension,
            "formulation": sol.formulation,
            "linear_solver": self.linear_solver.json(),
            "law": self.law,
            "interface": {
                "slave": format!("{}#{}", c.slave.body, c.slave.group),
                "master": format!("{}#{}", c.master.body, c.master.group),
                "multipliers": c.multipliers,
                "integration": c.integration,
                "coupling": self.coupling,
                "slave_nodes": self.tie.slave_nodes().len(),
                "vtu": "interface.vtu",
            },
            "load_steps": steps_json(&sol.steps),
            "active": sol.steps.last().map_or(0, |s| s.active),
            "contact_force": sol.force,
            "pressure_max": pmax,
            "bodies": body_reports,
            "warnings": warnings,
            "seconds": seconds,
        })
    }

    /// The terminal's summary: the sizes, the formulation, the load steps, the active nodes,
    /// the contact force and the peak pressure `pmax`.
    fn summary(&self, pmax: f64) -> String {
        let sol = &self.solution;
        format!(
            "contact, {}D, {} + {} nodes, {} slave interface nodes\nformulation: {}\n{}\nload steps: {} (Newton steps {:?}), active nodes {}, contact force {:.6e}, peak pressure {:.6e} Pa",
            self.dimension,
            self.bodies[0].mesh.node_count(),
            self.bodies[1].mesh.node_count(),
            self.tie.slave_nodes().len(),
            sol.formulation,
            self.linear_solver.summary_line(),
            sol.steps.len(),
            sol.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
            sol.steps.last().map_or(0, |s| s.active),
            sol.force,
            pmax,
        )
    }
}

/// The load steps of a contact solution as the reports write them.
pub(in crate::file) fn steps_json(steps: &[mortar_physics::contact::ContactStep]) -> Vec<Value> {
    steps
        .iter()
        .enumerate()
        .map(|(k, s)| {
            serde_json::json!({
                "step": k + 1,
                "load_factor": s.load_factor,
                "newton_steps": s.newton_steps,
                "settled_at": s.settled_at,
                "residuals": s.residuals,
                "active": s.active,
            })
        })
        .collect()
}
