//! Writes docs/performance.md from its template (`tests/verification/performance_template.md`),
//! reading every figure the benchmarks wrote to JSON under `docs/` (`bench.json`,
//! `bench_small_calls.json`, `bench_tied_heat.json`, `bench_contact.json`,
//! `bench_pellet.json`, `bench_pellet_dials.json`, `curved_segmentation.json`,
//! `tied_heat_*.json`) with the placeholders of
//! the verification page (`tests/verification/claims.rs`). `cargo test --test verification`
//! fails when the committed page differs from what this writes.
//!
//! ```text
//! cargo run --release --example performance_doc   # writes docs/performance.md
//! ```

#[path = "../tests/verification/claims.rs"]
mod claims;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let page = claims::render_performance()?;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/performance.md");
    std::fs::write(&path, page)?;
    println!("wrote {}", path.display());
    Ok(())
}
