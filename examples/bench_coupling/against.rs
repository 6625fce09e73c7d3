//! `--against OTHER`: this build and another build's `bench_coupling` run alternately, case
//! by case, in one session, so that a speed-up is a ratio measured beside the other build
//! rather than guessed from runs on different days (this shared machine's speed varies by up
//! to 2x from one day to the next, and single runs by 5-15 % within the hour).
//!
//! ```text
//! cargo build --release --example bench_coupling && cp target/release/examples/bench_coupling /tmp/before
//! # ... change the code ...
//! cargo run --release --example bench_coupling -- --against /tmp/before \
//!     --at cylinder:1024,plane3d:708 --threads-list 1,2 --rounds 3 --json after_vs_before.json
//! ```
//!
//! Each round runs every (case, n, threads) with both builds, one process each
//! (`--single CASE N THREADS sorted`), the order of the two builds swapped from one round to
//! the next so that a drift of the machine's speed within the session does not favour
//! either. `--repeats` and `--repeat-large` are passed on to both builds (the other build must
//! know them). Reported per (case, n, threads): the median over the rounds of each build's
//! first run in its process, and, with more than one repeat, the median of all the runs after
//! the first; their ratios (other / this: above 1 means this build is faster); whether every
//! run of each build gave the same D and M digest (`dm_digest`: bit-identical operators), and
//! whether both builds did (a build that reorders the arithmetic differs in round-off only,
//! which `--reference` measures).

use std::ffi::OsStr;
use std::path::Path;

use serde_json::{json, Value};

use super::{run_single, Res};

/// The totals of every run of a record (`totals_all_repeats`).
fn totals(record: &Value) -> Res<Vec<f64>> {
    record["totals_all_repeats"]
        .as_array()
        .ok_or("a record without totals_all_repeats")?
        .iter()
        .map(|t| {
            t.as_f64()
                .ok_or_else(|| "a total that is not a number".into())
        })
        .collect()
}

/// The median of `v` (the mean of the middle two for an even count); `None` if empty.
fn median(v: &[f64]) -> Option<f64> {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let m = s.len() / 2;
    match s.len() {
        0 => None,
        k if k % 2 == 1 => Some(s[m]),
        _ => Some(0.5 * (s[m - 1] + s[m])),
    }
}

/// What one build gave for one (case, n, threads) over the rounds.
#[derive(Default)]
struct Runs {
    first: Vec<f64>,
    later: Vec<f64>,
    digests: Vec<String>,
    loads: Vec<f64>,
}

impl Runs {
    fn add(&mut self, record: &Value) -> Res<()> {
        let t = totals(record)?;
        self.first.push(*t.first().ok_or("a record with no run")?);
        self.later.extend_from_slice(&t[1..]);
        // A record without a digest must not pass for bit-identical.
        let digest = record["dm_digest"]
            .as_str()
            .ok_or("a record without dm_digest")?;
        self.digests.push(digest.to_owned());
        self.loads
            .push(record["load_average_1min"].as_f64().unwrap_or(f64::NAN));
        Ok(())
    }

    fn summary(&self) -> Value {
        json!({
            "first_runs": self.first,
            "first_median": median(&self.first),
            "later_runs": self.later,
            "later_median": median(&self.later),
            "digests": self.digests,
        })
    }
}

/// Runs the comparison and prints it; writes the records to `json` if given.
#[allow(clippy::too_many_arguments)]
pub fn run(
    this: &Path,
    other: &Path,
    at: &[(String, usize)],
    threads: &[usize],
    rounds: usize,
    repeats: usize,
    repeat_large: bool,
    reuse: bool,
    json: Option<&Path>,
) -> Res<()> {
    let mut results = Vec::new();
    for (case, n) in at {
        for &t in threads {
            let (mut mine, mut theirs) = (Runs::default(), Runs::default());
            for round in 0..rounds {
                // This build first in even rounds, the other first in odd ones.
                for k in 0..2 {
                    let this_turn = (k == 0) == (round % 2 == 0);
                    let (exe, runs) = if this_turn {
                        (this, &mut mine)
                    } else {
                        (other, &mut theirs)
                    };
                    let params = (case.as_str(), *n, t, "sorted");
                    let extra = reuse.then_some(OsStr::new("--reuse"));
                    runs.add(&run_single(exe, params, repeats, repeat_large, extra)?)?;
                }
            }
            // Each build deterministic (every run of it the same D and M), and both builds
            // the same bits: two questions, since a change of the arithmetic's order (within
            // the 1e-13 that `--reference` checks) is a difference between builds only.
            let steady = |r: &Runs| r.digests.iter().all(|d| *d == r.digests[0]);
            let within = steady(&mine) && steady(&theirs);
            let same = within && mine.digests.first() == theirs.digests.first();
            let ratio = |a: Option<f64>, b: Option<f64>| a.zip(b).map(|(a, b)| a / b);
            let first = ratio(median(&theirs.first), median(&mine.first));
            let later = ratio(median(&theirs.later), median(&mine.later));
            let loads: Vec<f64> = mine.loads.iter().chain(&theirs.loads).copied().collect();
            let shown = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:.4}"));
            println!(
                "{case} n={n} threads={t}: first runs {} s (this) against {} s (other), \
                 other/this {}; later runs {} against {}, other/this {}; D and M {}; \
                 {rounds} rounds, load {:.2}-{:.2}",
                shown(median(&mine.first)),
                shown(median(&theirs.first)),
                shown(first),
                shown(median(&mine.later)),
                shown(median(&theirs.later)),
                shown(later),
                match (same, within) {
                    (true, _) => "bit-identical in every run",
                    (false, true) => {
                        "bit-identical between runs of each build, different between the \
                         builds (--reference compares them)"
                    }
                    (false, false) => "DIFFER between runs of one build",
                },
                loads.iter().copied().fold(f64::INFINITY, f64::min),
                loads.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            );
            results.push(json!({
                "case": case, "n": n, "threads": t, "order": "sorted",
                "rounds": rounds, "repeats": repeats, "repeat_large": repeat_large, "reuse": reuse,
                "this": mine.summary(), "other": theirs.summary(),
                "this_exe": this.display().to_string(),
                "other_exe": other.display().to_string(),
                "other_over_this_first": first,
                "other_over_this_later": later,
                "dm_bit_identical": same,
                "dm_bit_identical_within_each_build": within,
                "load_average_1min": loads,
            }));
        }
    }
    let out = Value::Array(results);
    println!("{out}");
    if let Some(path) = json {
        std::fs::write(path, serde_json::to_string_pretty(&out)?)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
