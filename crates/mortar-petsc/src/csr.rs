//! The one place that reads the toolkit's sparse matrix type: its CSR arrays, borrowed when
//! the matrix is stored by rows from row 0, converted otherwise.

use std::borrow::Cow;

use mortar_core::linalg::SparseMatrix;

/// A matrix's CSR arrays: `indptr` (`nrows + 1` entries from 0), each row's column indices
/// ascending, and the values.
// Read only by the PETSc module, which the `petsc` feature brings.
#[cfg_attr(not(feature = "petsc"), allow(dead_code))]
#[derive(Debug)]
pub(crate) struct CsrParts<'a> {
    /// Rows.
    pub nrows: usize,
    /// Columns.
    pub ncols: usize,
    /// Row pointers.
    pub indptr: Cow<'a, [usize]>,
    /// Column indices.
    pub indices: Cow<'a, [usize]>,
    /// Values.
    pub data: Cow<'a, [f64]>,
}

/// The CSR arrays of `a`: borrowed if `a` is a CSR matrix whose row pointers start at 0, a
/// CSR copy's otherwise (a CSC matrix, a view of some rows).
pub(crate) fn csr_parts(a: &SparseMatrix) -> CsrParts<'_> {
    let (nrows, ncols) = a.shape();
    if a.is_csr() {
        let (indptr, indices, data) = a.view().into_raw_storage();
        if indptr.first() == Some(&0) {
            return CsrParts {
                nrows,
                ncols,
                indptr: Cow::Borrowed(indptr),
                indices: Cow::Borrowed(indices),
                data: Cow::Borrowed(data),
            };
        }
    }
    let (indptr, indices, data) = a.to_csr().into_raw_storage();
    CsrParts {
        nrows,
        ncols,
        indptr: Cow::Owned(indptr),
        indices: Cow::Owned(indices),
        data: Cow::Owned(data),
    }
}
