//! Plug-ins of one's own written with no knowledge of the coupling's fast paths (the
//! mathematical methods only: a basis on a face, a direction at a point, the paired rule of a
//! face) give the D and M of the shipped ones they imitate, to round-off (1e-13 of the largest
//! entry), on interfaces where the shipped ones take every fast path they have: the sorted
//! merge of a straight 2D interface, the fused kernel of curved lines, the closed form of flat
//! triangles and quads in 3D. The shipped ones take those paths (their statistics say so);
//! the user's take the general path, one plug-in at a time and all three together.

use std::sync::Arc;

use mortar::core::integration::{IntegrationStrategy, PairedRule, SegmentBased, SegmentContext};
use mortar::core::interface::FaceGeometry;
use mortar::core::multiplier::{DualMultipliers, LmBasis, MultiplierSpace};
use mortar::core::projector::{ElementNormal, NodalNormalField, Projector};
use mortar::generate::{
    cylinder_surface, half_circle_mesh, square_quads, square_triangles, Diagonal,
};
use mortar::testing::polyline;
use mortar::{assemble_coupling, Coupling, CouplingOptions, Interface, Tolerances};
use nalgebra::{Vector2, Vector3};

use super::common::dm_deviations;

/// The standard multipliers, as a user writes them: the identity on every face.
#[derive(Debug)]
struct MyStandard;

impl MultiplierSpace for MyStandard {
    fn name(&self) -> &'static str {
        "my standard"
    }

    fn basis(&self, face: &FaceGeometry, _: &Tolerances) -> mortar::core::Result<LmBasis> {
        Ok(LmBasis::identity(face.node_count()))
    }
}

/// The dual multipliers (Cartesian), as a user takes them: the shipped basis, no claim.
#[derive(Debug)]
struct MyDual;

impl MultiplierSpace for MyDual {
    fn name(&self) -> &'static str {
        "my dual"
    }

    fn basis(&self, face: &FaceGeometry, tol: &Tolerances) -> mortar::core::Result<LmBasis> {
        DualMultipliers.basis(face, tol)
    }
}

/// The nodal normal field, as a user writes it.
#[derive(Debug)]
struct MyNodalNormals;

impl Projector for MyNodalNormals {
    fn name(&self) -> &'static str {
        "my nodal normals"
    }

    fn direction(
        &self,
        slave: &FaceGeometry,
        xi: &Vector2<f64>,
    ) -> (Vector3<f64>, [Vector3<f64>; 2]) {
        slave.normal_field(xi)
    }
}

/// The face's own normal at its centre, as a user writes it.
#[derive(Debug)]
struct MyElementNormal;

impl Projector for MyElementNormal {
    fn name(&self) -> &'static str {
        "my element normal"
    }

    fn direction(
        &self,
        slave: &FaceGeometry,
        _: &Vector2<f64>,
    ) -> (Vector3<f64>, [Vector3<f64>; 2]) {
        let c = slave.element.domain().centre();
        let n = slave.element.unit_normal(slave.node_coords(), &c);
        (n, [Vector3::zeros(); 2])
    }
}

/// The exact segmentation, as a user hands it on.
#[derive(Debug)]
struct MySegments;

impl IntegrationStrategy for MySegments {
    fn name(&self) -> String {
        "my segments".into()
    }

    fn paired_rule_into(
        &self,
        ctx: &SegmentContext<'_>,
        slave: &FaceGeometry,
        candidates: &[u32],
        out: &mut PairedRule,
    ) -> mortar::core::Result<()> {
        SegmentBased::default().paired_rule_into(ctx, slave, candidates, out)
    }
}

/// Which fast path the shipped plug-ins take on an interface.
#[derive(Debug, Clone, Copy)]
enum Path {
    StraightLines,
    FusedLines,
    ClosedForm,
}

/// The faces the coupling took by `path`.
fn faces_by(c: &Coupling, path: Path) -> usize {
    match path {
        Path::StraightLines => c.stats.straight_line_faces,
        Path::FusedLines => c.stats.fused_line_faces,
        Path::ClosedForm => c.stats.closed_form_faces,
    }
}

/// Points from `a` to `b` on the x-axis, graded by `t -> t^p`.
fn points(a: f64, b: f64, n: usize, p: f64) -> Vec<[f64; 2]> {
    (0..=n)
        .map(|i| [a + (b - a) * (i as f64 / n as f64).powf(p), 0.0])
        .collect()
}

/// The interfaces, each with the fast path the shipped plug-ins take on all its slave faces.
fn interfaces() -> Vec<(&'static str, Interface, Path)> {
    let tris = |n, d, flip| square_triangles(n, d, 0.0, flip, if flip { 1000 } else { 1 });
    let new = |s, m| Interface::new(s, m).unwrap();
    vec![
        (
            "straight lines",
            new(
                polyline(&points(0.0, 1.0, 10, 1.2), 1, false),
                polyline(&points(-0.1, 1.1, 13, 0.9), 1000, true),
            ),
            Path::StraightLines,
        ),
        (
            "arcs",
            new(
                half_circle_mesh(40, false, 1).unwrap(),
                half_circle_mesh(61, true, 1).unwrap(),
            ),
            Path::FusedLines,
        ),
        (
            "flat triangles",
            new(
                tris(6, Diagonal::Main, false).unwrap(),
                tris(7, Diagonal::Anti, true).unwrap(),
            ),
            Path::ClosedForm,
        ),
        (
            "flat quads against triangles",
            new(
                square_quads(5, 0.0, false, 1).unwrap(),
                tris(7, Diagonal::Anti, true).unwrap(),
            ),
            Path::ClosedForm,
        ),
        (
            "cylinder",
            new(
                cylinder_surface(1.0, 24, 6, false, false, 1).unwrap(),
                cylinder_surface(1.0, 37, 9, true, true, 1).unwrap(),
            ),
            Path::ClosedForm,
        ),
    ]
}

#[test]
fn plug_ins_of_ones_own_give_the_shipped_d_and_m() {
    for (what, interface, path) in interfaces() {
        for dual in [false, true] {
            for element_normal in [false, true] {
                let mut shipped = CouplingOptions::default();
                let mut mine = shipped.clone();
                if dual {
                    shipped = shipped.dual();
                }
                mine.multipliers = if dual {
                    Arc::new(MyDual)
                } else {
                    Arc::new(MyStandard)
                };
                if element_normal {
                    shipped.projector = Arc::new(ElementNormal);
                    mine.projector = Arc::new(MyElementNormal);
                } else {
                    shipped.projector = Arc::new(NodalNormalField);
                    mine.projector = Arc::new(MyNodalNormals);
                }
                mine.integration = Arc::new(MySegments);
                let reference = assemble_coupling(&interface, &shipped).unwrap();
                let faces = interface.slave().face_count();
                let name = format!("{what}, {}", shipped.describe());
                assert_eq!(faces_by(&reference, path), faces, "{name}: {path:?}");
                // Each of the user's plug-ins alone, then all three.
                let one = |f: &dyn Fn(&mut CouplingOptions)| {
                    let mut o = shipped.clone();
                    f(&mut o);
                    o
                };
                let variants = [
                    ("space", one(&|o| o.multipliers = mine.multipliers.clone())),
                    ("projector", one(&|o| o.projector = mine.projector.clone())),
                    (
                        "strategy",
                        one(&|o| o.integration = mine.integration.clone()),
                    ),
                    ("all three", mine.clone()),
                ];
                for (which, options) in variants {
                    let c = assemble_coupling(&interface, &options).unwrap();
                    let label = format!("{name}: the user's {which}");
                    for (matrix, dev) in dm_deviations(&reference, &c) {
                        assert!(dev <= 1e-13, "{label}: {matrix} deviates by {dev:e}");
                    }
                    assert_eq!(c.stats.pairs, reference.stats.pairs, "{label}");
                    assert!(c.warnings.is_empty(), "{label}: {:?}", c.warnings);
                    let area = (c.stats.area - reference.stats.area).abs();
                    assert!(area <= 1e-13 * reference.stats.area, "{label}: area");
                    if which == "all three" {
                        let fast = [Path::StraightLines, Path::FusedLines, Path::ClosedForm];
                        for p in fast {
                            assert_eq!(faces_by(&c, p), 0, "{label}: {p:?}");
                        }
                        assert!(c.recombined.is_none(), "{label}");
                    }
                }
            }
        }
    }
}
