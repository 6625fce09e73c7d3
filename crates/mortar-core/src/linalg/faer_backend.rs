//! The bridge to faer's sparse direct solvers.

use faer::sparse::{SparseColMat, Triplet};

use super::SparseMatrix;

/// A failure of the faer backend (building the matrix, or factorising it).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("sparse solver: {0}")]
pub struct FaerError(pub String);

/// Solves `a x = b` by faer's sparse LU factorisation.
///
/// # Errors
/// [`FaerError`] if the matrix cannot be built or is singular, or the sizes disagree.
pub fn solve_sparse_lu(a: &SparseMatrix, b: &[f64]) -> Result<Vec<f64>, FaerError> {
    let (n, m) = a.shape();
    if n != m || b.len() != n {
        return Err(FaerError(format!(
            "a {n}x{m} matrix cannot be solved against a vector of {}",
            b.len()
        )));
    }
    let triplets: Vec<Triplet<usize, usize, f64>> =
        a.iter().map(|(v, (r, c))| Triplet::new(r, c, *v)).collect();
    let mat = SparseColMat::<usize, f64>::try_new_from_triplets(n, m, &triplets)
        .map_err(|e| FaerError(format!("{e:?}")))?;
    let lu = mat.sp_lu().map_err(|e| FaerError(format!("{e:?}")))?;
    let mut x = faer::Mat::<f64>::from_fn(n, 1, |i, _| b[i]);
    use faer::linalg::solvers::SolveCore;
    lu.solve_in_place_with_conj(faer::Conj::No, x.as_mut());
    Ok((0..n).map(|i| x[(i, 0)]).collect())
}
