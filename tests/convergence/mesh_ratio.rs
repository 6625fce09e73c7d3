//! A coarse slave face against many master faces: the coupling splits the
//! face's candidates into batches of `CANDIDATE_BATCH` and must stay exact. On a flat covered
//! interface the closed forms are: the entries of D sum to the slave area (length in 2D),
//! `D 1 = M 1` row by row (constants reproduced), and `D x_s = M x_m` for the node
//! coordinates (a linear field reproduced: the patch test). Batched D and M are also the
//! same bit for bit as the face done in one batch, and on one thread as on two. (In 2D the
//! default path is the fused kernel for straight lines, which takes a face's candidates at
//! once; the batching is checked there through a strategy of one's own, which the coupling
//! does not take for `SegmentBased`.)

use std::sync::Arc;

use mortar::core::integration::{
    IntegrationFastPaths, IntegrationStrategy, PairedRule, SegmentBased, SegmentContext,
    CANDIDATE_BATCH,
};
use mortar::core::interface::FaceGeometry;
use mortar::generate::{line_mesh, square_quads};
use mortar::{assemble_coupling, Coupling, CouplingOptions, Interface};

/// Segment-based integration that takes every candidate of a face in one call (a strategy
/// that states no [`IntegrationFastPaths`]).
#[derive(Debug)]
struct Unsplit(SegmentBased);

impl IntegrationStrategy for Unsplit {
    fn name(&self) -> String {
        format!("{} (unsplit)", self.0.name())
    }

    fn paired_rule_into(
        &self,
        ctx: &SegmentContext<'_>,
        slave: &FaceGeometry,
        candidates: &[u32],
        out: &mut PairedRule,
    ) -> mortar::core::error::Result<()> {
        self.0.paired_rule_into(ctx, slave, candidates, out)
    }
}

/// Segment-based integration batched over the candidates, through the strategy (a 2D
/// interface of straight lines would otherwise go to the fused kernel, which takes a face's
/// candidates at once).
#[derive(Debug)]
struct Batched(SegmentBased);

impl IntegrationStrategy for Batched {
    fn name(&self) -> String {
        format!("{} (batched)", self.0.name())
    }

    fn paired_rule_into(
        &self,
        ctx: &SegmentContext<'_>,
        slave: &FaceGeometry,
        candidates: &[u32],
        out: &mut PairedRule,
    ) -> mortar::core::error::Result<()> {
        self.0.paired_rule_into(ctx, slave, candidates, out)
    }

    fn fast_paths(&self) -> Option<&dyn IntegrationFastPaths> {
        Some(self)
    }
}

impl IntegrationFastPaths for Batched {
    fn splits_over_candidates(&self) -> bool {
        true
    }
}

fn bits(c: &Coupling) -> Vec<u64> {
    let (d, m) = (&c.d, &c.m);
    let mut out: Vec<u64> = d
        .data()
        .iter()
        .chain(m.data())
        .map(|v| v.to_bits())
        .collect();
    out.extend(d.indices().iter().chain(m.indices()).map(|&i| i as u64));
    out
}

fn row_sums(a: &mortar::core::linalg::SparseMatrix) -> Vec<f64> {
    a.outer_iterator()
        .map(|r| r.iter().map(|(_, v)| v).sum())
        .collect()
}

fn check_exact(interface: &Interface, area: f64) {
    let options = CouplingOptions::default().threads(1);
    let c = assemble_coupling(interface, &options).unwrap();
    let tol = crate::claims::claim("coupling.mesh_ratio").bound;
    assert!(
        c.stats.candidates > 4 * CANDIDATE_BATCH,
        "{} candidates: several batches",
        c.stats.candidates
    );
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
    let sum: f64 = c.d.data().iter().sum();
    assert!(
        (sum - area).abs() <= tol * area,
        "sum of D {sum}, area {area}"
    );
    for (j, (d1, m1)) in row_sums(&c.d).iter().zip(row_sums(&c.m)).enumerate() {
        assert!(
            (d1 - m1).abs() <= tol * d1.abs(),
            "row {j}: D 1 = {d1}, M 1 = {m1}"
        );
    }
    let g = c.weighted_gap(
        &c.slave_positions(interface),
        &c.master_positions(interface),
    );
    for (j, gj) in g.iter().enumerate() {
        assert!(gj.amax() <= tol * area, "row {j}: D x_s - M x_m = {gj:?}");
    }
    let mut batched = options.clone();
    batched.integration = Arc::new(Batched(SegmentBased::default()));
    let batched = assemble_coupling(interface, &batched).unwrap();
    let mut unsplit = options.clone();
    unsplit.integration = Arc::new(Unsplit(SegmentBased::default()));
    let whole = assemble_coupling(interface, &unsplit).unwrap();
    assert_eq!(bits(&batched), bits(&whole), "batched and whole differ");
    let two = assemble_coupling(interface, &options.clone().threads(2)).unwrap();
    assert_eq!(bits(&c), bits(&two), "one and two threads differ");
}

#[test]
fn one_line_against_twenty_thousand_lines_is_exact() {
    let slave = line_mesh(1, false, 1).unwrap();
    let master = line_mesh(20_000, true, 1).unwrap();
    check_exact(&Interface::new(slave, master).unwrap(), 1.0);
}

#[test]
fn one_quad_against_a_hundred_and_fifty_squared_quads_is_exact() {
    let slave = square_quads(1, 0.0, false, 1).unwrap();
    let master = square_quads(150, 0.0, true, 1).unwrap();
    check_exact(&Interface::new(slave, master).unwrap(), 1.0);
}
