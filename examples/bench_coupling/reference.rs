//! D and M of a benchmark case saved by one build and compared by another: a change to the
//! coupling must leave D and M within 1e-13 (relative) of the previous build's on every case.
//!
//! `--save-reference DIR` writes the CSR arrays of D and M of each (case, n, order) to
//! `DIR/CASE_N_ORDER.dm` (little-endian: for D then M, rows, cols, nnz as u64, then indptr and
//! indices as u64, data as f64). `--reference DIR` reads that file in the child of the same
//! case and reports, for D and M, the largest difference in a row over the largest entry of
//! that row (both builds' entries; an entry one build has and the other not counts whole), and
//! whether both stay within `1e-13`.

use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use mortar::core::linalg::SparseMatrix;
use mortar::Coupling;
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// The relative tolerance within which D and M must match the saved build's.
pub const TOLERANCE: f64 = 1e-13;

/// The file of a case.
pub fn file(dir: &Path, case: &str, n: usize, order: &str) -> PathBuf {
    dir.join(format!("{case}_{n}_{order}.dm"))
}

/// Writes D and M of `c` to `path`.
pub fn save(path: &Path, c: &Coupling) -> Res<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let mut w = BufWriter::new(std::fs::File::create(path)?);
    for a in [&c.d, &c.m] {
        for v in [a.rows(), a.cols(), a.nnz()] {
            w.write_all(&(v as u64).to_le_bytes())?;
        }
        for &p in a.indptr().raw_storage() {
            w.write_all(&(p as u64).to_le_bytes())?;
        }
        for &i in a.indices() {
            w.write_all(&(i as u64).to_le_bytes())?;
        }
        for &x in a.data() {
            w.write_all(&x.to_le_bytes())?;
        }
    }
    w.flush()?;
    Ok(())
}

/// One matrix as read back: shape, indptr, indices, data.
struct Csr {
    rows: usize,
    cols: usize,
    indptr: Vec<usize>,
    indices: Vec<usize>,
    data: Vec<f64>,
}

fn read_matrix(r: &mut impl Read) -> Res<Csr> {
    let mut word = [0u8; 8];
    let mut u = |r: &mut dyn Read| -> Res<u64> {
        r.read_exact(&mut word)?;
        Ok(u64::from_le_bytes(word))
    };
    let (rows, cols, nnz) = (u(r)? as usize, u(r)? as usize, u(r)? as usize);
    let indptr = (0..=rows)
        .map(|_| u(r).map(|v| v as usize))
        .collect::<Res<Vec<_>>>()?;
    let indices = (0..nnz)
        .map(|_| u(r).map(|v| v as usize))
        .collect::<Res<Vec<_>>>()?;
    let data = (0..nnz)
        .map(|_| u(r).map(f64::from_bits))
        .collect::<Res<Vec<_>>>()?;
    if indptr.last() != Some(&nnz) {
        return Err("reference file: indptr does not end at nnz".into());
    }
    Ok(Csr {
        rows,
        cols,
        indptr,
        indices,
        data,
    })
}

/// The largest row-relative difference between `a` and the reference `b`: for each row,
/// `max |a_ij - b_ij| / max(|a_ij|, |b_ij|)` over the union of both rows' entries.
fn row_relative(a: &SparseMatrix, b: &Csr) -> Res<(f64, usize)> {
    if a.rows() != b.rows || a.cols() != b.cols {
        return Err(format!(
            "shape {}x{} against the reference's {}x{}",
            a.rows(),
            a.cols(),
            b.rows,
            b.cols
        )
        .into());
    }
    let ap = a.indptr();
    let ap = ap.raw_storage();
    let (mut worst, mut at) = (0.0f64, 0);
    for i in 0..b.rows {
        let (ai, av) = (&a.indices()[ap[i]..ap[i + 1]], &a.data()[ap[i]..ap[i + 1]]);
        let (bi, bv) = (
            &b.indices[b.indptr[i]..b.indptr[i + 1]],
            &b.data[b.indptr[i]..b.indptr[i + 1]],
        );
        let scale = av.iter().chain(bv).fold(0.0f64, |s, x| s.max(x.abs()));
        let (mut p, mut q, mut diff) = (0, 0, 0.0f64);
        while p < ai.len() || q < bi.len() {
            let (x, y) = match (ai.get(p), bi.get(q)) {
                (Some(&c), Some(&d)) if c == d => {
                    p += 1;
                    q += 1;
                    (av[p - 1], bv[q - 1])
                }
                (Some(&c), Some(&d)) if c < d => {
                    p += 1;
                    (av[p - 1], 0.0)
                }
                (Some(_), None) => {
                    p += 1;
                    (av[p - 1], 0.0)
                }
                _ => {
                    q += 1;
                    (0.0, bv[q - 1])
                }
            };
            diff = diff.max((x - y).abs());
        }
        if scale > 0.0 && diff / scale > worst {
            (worst, at) = (diff / scale, i);
        }
    }
    Ok((worst, at))
}

/// Compares D and M of `c` with the reference file at `path`.
pub fn compare(path: &Path, c: &Coupling) -> Res<Value> {
    let mut r = std::io::BufReader::new(std::fs::File::open(path)?);
    let (d, d_row) = row_relative(&c.d, &read_matrix(&mut r)?)?;
    let (m, m_row) = row_relative(&c.m, &read_matrix(&mut r)?)?;
    Ok(json!({
        "file": path.display().to_string(),
        "d_max_row_relative": d,
        "d_worst_row": d_row,
        "m_max_row_relative": m,
        "m_worst_row": m_row,
        "within_1e-13": d <= TOLERANCE && m <= TOLERANCE,
    }))
}
