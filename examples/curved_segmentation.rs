//! The curved-face segmentation of second-order faces against its subdivision level
//! (issue 10 item 2): the sphere of radius 0.3 between a ball (Hex27, master) and the box
//! around it (Tet10, slave), the second-order nodes of both placed on the sphere, meshed
//! independently (2:3), coupled with dual multipliers at subdivision levels 1, 2, 4, 8 and by
//! the tolerance, against level 16 as the reference.
//!
//! Reported per level: the time of the coupling, pairs and integration cells; the error of
//! sum(D) against the slave surface's own area (its Jacobian integrated by a degree-20 rule:
//! a fully covered slave gives it exactly, so the error is the area the sub-triangles fail to
//! cover); the largest difference of D and of M from the reference, over the largest entry.
//! Prints a table and, with `--json FILE`, writes the figures.
//!
//! ```sh
//! cargo run --release --example curved_segmentation -- [--n 8] [--json FILE]
//! ```

use std::time::Instant;

use mortar::core::integration::curved_3d::DEFAULT_CURVED_TOLERANCE;
use mortar::core::integration::SegmentBased;
use mortar::core::quadrature::{Quadrature, QuadratureRule};
use mortar::generate::{
    ball_mesh, box_with_hole_mesh, onto_sphere, second_order_mesh, CellShape, Inclusion,
    SecondOrder,
};
use mortar::{assemble_coupling, Coupling, CouplingOptions, Interface, SurfaceMesh};
use nalgebra::Vector3;
use serde_json::json;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

fn main() -> Res<()> {
    run(&std::env::args().skip(1).collect::<Vec<_>>())
}

/// The largest entry-wise difference of two matrices of the same pattern or not, over the
/// largest entry of `b`.
fn difference(a: &sprs::CsMat<f64>, b: &sprs::CsMat<f64>) -> f64 {
    let scale = b.data().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a - b;
    diff.data().iter().fold(0.0f64, |m, v| m.max(v.abs())) / scale
}

/// The area of a surface mesh by a degree-20 rule on each face.
fn area(s: &SurfaceMesh) -> f64 {
    (0..s.face_count())
        .map(|f| {
            let face = s.face(f);
            let x: Vec<Vector3<f64>> = face.nodes.iter().map(|&n| s.coords()[n as usize]).collect();
            let rule = QuadratureRule::cached(face.element.domain(), 20).expect("degree 20");
            rule.points()
                .iter()
                .zip(rule.weights())
                .map(|(p, w)| w * face.element.jacobian_det(&x, p))
                .sum::<f64>()
        })
        .sum()
}

/// Runs the study with the arguments `[--n N] [--json FILE]`.
pub fn run(args: &[String]) -> Res<()> {
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
    };
    let n: usize = value("--n").map_or(Ok(8), |v| v.parse())?;
    let g = Inclusion::unit(3, 0.3);
    let (nb, mb) = (n / 2, 3 * n / 4);
    let place = || onto_sphere(g.centre, g.radius);
    let master = second_order_mesh(
        &ball_mesh(&g, nb, (nb / 2).max(1), 1)?,
        SecondOrder::Complete,
        place(),
    )?;
    let slave = second_order_mesh(
        &box_with_hole_mesh(&g, mb, (mb / 2).max(1), CellShape::Simplex, 1_000_001)?,
        SecondOrder::Complete,
        place(),
    )?;
    let c = Vector3::from(g.centre);
    let cut = 0.5 * (g.radius + g.half_width);
    let near = |f: &mortar::core::mesh::BoundaryFace| (f.centroid - c).norm() < cut;
    let (ms, ss) = (
        master.boundary_surface(near)?,
        slave.boundary_surface(near)?,
    );
    let slave_area = area(&ss);
    let interface = Interface::new(ss, ms)?;
    let couple = |strategy: SegmentBased| -> Res<(Coupling, f64)> {
        let mut options = CouplingOptions::default().dual().threads(1);
        options.integration = std::sync::Arc::new(strategy);
        let t = Instant::now();
        let c = assemble_coupling(&interface, &options)?;
        Ok((c, t.elapsed().as_secs_f64()))
    };
    let (reference, _) = couple(SegmentBased::default().with_subdivision(16)?)?;
    println!(
        "sphere r = 0.3, n = {n}: slave {} Tri6 faces, master {} Quad9 faces; slave area {slave_area:.12} (4 pi r^2 = {:.12})",
        interface.slave().face_count(),
        interface.master().face_count(),
        4.0 * std::f64::consts::PI * 0.09
    );
    println!(
        "{:>10} {:>9} {:>7} {:>9} {:>12} {:>10} {:>10}",
        "level", "seconds", "pairs", "cells", "sum(D) err", "D vs ref", "M vs ref"
    );
    let mut rows = Vec::new();
    let settings: Vec<(String, SegmentBased)> = [1, 2, 4, 8]
        .into_iter()
        .map(|l| Ok((l.to_string(), SegmentBased::default().with_subdivision(l)?)))
        .chain(std::iter::once(Ok((
            format!("tol {DEFAULT_CURVED_TOLERANCE:e}"),
            SegmentBased::default(),
        ))))
        .collect::<Res<_>>()?;
    for (name, strategy) in settings {
        let (c, seconds) = couple(strategy)?;
        let row = json!({
            "level": name,
            "seconds": seconds,
            "pairs": c.stats.pairs,
            "cells": c.stats.segments,
            "sum_d_error": (c.stats.area - slave_area) / slave_area,
            "d_vs_reference": difference(&c.d, &reference.d),
            "m_vs_reference": difference(&c.m, &reference.m),
        });
        println!(
            "{name:>10} {seconds:>9.4} {:>7} {:>9} {:>12.2e} {:>10.2e} {:>10.2e}",
            c.stats.pairs,
            c.stats.segments,
            row["sum_d_error"].as_f64().unwrap_or(f64::NAN),
            row["d_vs_reference"].as_f64().unwrap_or(f64::NAN),
            row["m_vs_reference"].as_f64().unwrap_or(f64::NAN)
        );
        rows.push(row);
    }
    if let Some(path) = value("--json") {
        let report = json!({ "case": "sphere r = 0.3, Tet10 box (slave) against Hex27 ball (master)", "n": n, "slave_area": slave_area, "levels": rows });
        std::fs::write(path, serde_json::to_string_pretty(&report)?)?;
    }
    Ok(())
}
