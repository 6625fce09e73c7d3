//! Matrix Market output of sparse matrices (`coordinate real general`).
//!
//! Our own writer rather than `sprs::io::write_matrix_market`: sprs prints values with `{}`,
//! which round-trips but spells `1e-300` with three hundred digits, and cannot add comment
//! lines. Here values are written with `{:e}`, Rust's shortest representation that reads back
//! to the same `f64` (at most 17 significant digits), and entries follow the CSR order: by
//! row, then column. The files read back with `sprs::io::read_matrix_market`.

use std::fmt::Write as _;

use sprs::CsMat;

/// The text of a Matrix Market file holding `matrix`, with `comments` as `%` lines after the
/// banner (line breaks in a comment start new comment lines).
///
/// ```
/// let m = sprs::CsMat::new((2, 3), vec![0, 1, 2], vec![2, 0], vec![0.1, -2.5e-300]);
/// let text = mortar::io::matrix_market::to_string(&m, &["an example"]);
/// assert!(text.starts_with("%%MatrixMarket matrix coordinate real general\n% an example\n2 3 2\n"));
/// assert!(text.contains("1 3 1e-1\n2 1 -2.5e-300\n"));
/// ```
pub fn to_string(matrix: &CsMat<f64>, comments: &[&str]) -> String {
    let mut out = String::with_capacity(64 + 32 * matrix.nnz());
    banner(&mut out, "coordinate", comments);
    let _ = writeln!(out, "{} {} {}", matrix.rows(), matrix.cols(), matrix.nnz());
    // A CSC matrix iterates by column: write by row all the same.
    let csr;
    let matrix = if matrix.is_csr() {
        matrix
    } else {
        csr = matrix.to_csr();
        &csr
    };
    for (v, (r, c)) in matrix.iter() {
        let _ = writeln!(out, "{} {} {v:e}", r + 1, c + 1);
    }
    out
}

/// The text of a Matrix Market file holding the dense matrix of `rows` (each of `cols`
/// values) as an `array real general`: the banner, `comments` as `%` lines, `rows cols`, then
/// the values column by column (the format's order), each written as [`to_string`] writes
/// them. `scipy.io.mmread` and `numpy` read it back as a dense array.
///
/// ```
/// let text = mortar::io::matrix_market::dense_to_string(&[[1.0, 2.0], [3.0, 4.0]], 2, &["x"]);
/// assert_eq!(text, "%%MatrixMarket matrix array real general\n% x\n2 2\n1e0\n3e0\n2e0\n4e0\n");
/// ```
pub fn dense_to_string<R: AsRef<[f64]>>(rows: &[R], cols: usize, comments: &[&str]) -> String {
    let mut out = String::with_capacity(64 + 24 * rows.len() * cols);
    banner(&mut out, "array", comments);
    let _ = writeln!(out, "{} {cols}", rows.len());
    for c in 0..cols {
        for r in rows {
            let _ = writeln!(out, "{:e}", r.as_ref()[c]);
        }
    }
    out
}

/// The banner of a real general matrix in `format` (`coordinate` or `array`) and `comments`
/// as `%` lines (line breaks in a comment start new comment lines).
fn banner(out: &mut String, format: &str, comments: &[&str]) {
    let _ = writeln!(out, "%%MatrixMarket matrix {format} real general");
    for c in comments {
        for line in c.lines() {
            out.push_str("% ");
            out.push_str(line);
            out.push('\n');
        }
    }
}
