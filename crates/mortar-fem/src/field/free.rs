//! The unknowns of a field left free by its prescribed values.

use mortar_core::linalg::SparseMatrix;

/// The index of an unknown that is prescribed (not free).
pub const FIXED: u32 = u32::MAX;

/// The free numbering of `n` unknowns of which `fixed` are prescribed: per unknown its index
/// among the free ones (increasing with the unknown), or [`FIXED`]; and the free count.
///
/// ```
/// use mortar_fem::field::free::{free_numbering, FIXED};
/// assert_eq!(free_numbering(4, &[1, 3]), (vec![0, FIXED, 1, FIXED], 2));
/// ```
///
/// # Panics
/// If an entry of `fixed` is not below `n`.
pub fn free_numbering(n: usize, fixed: &[u32]) -> (Vec<u32>, usize) {
    let mut free = vec![0u32; n];
    for &d in fixed {
        free[d as usize] = FIXED;
    }
    let mut m = 0u32;
    for f in free.iter_mut() {
        if *f != FIXED {
            *f = m;
            m += 1;
        }
    }
    (free, m as usize)
}

/// The block-diagonal matrix `diag(blocks)` (CSR, the blocks' unknowns concatenated)
/// restricted to its free unknowns, `free` a numbering from [`free_numbering`] (increasing,
/// so each row's columns stay sorted): built row by row in compressed form, no triplets.
///
/// # Panics
/// If `free` is shorter than the blocks' rows together.
pub fn free_block(blocks: &[&SparseMatrix], free: &[u32], nfree: usize) -> SparseMatrix {
    let mut ptr = Vec::with_capacity(nfree + 1);
    let (mut idx, mut val) = (Vec::new(), Vec::new());
    ptr.push(0usize);
    let mut offset = 0usize;
    for block in blocks {
        for (i, row) in block.outer_iterator().enumerate() {
            if free[offset + i] == FIXED {
                continue;
            }
            for (j, v) in row.iter() {
                let c = free[offset + j];
                if c != FIXED {
                    idx.push(c as usize);
                    val.push(*v);
                }
            }
            ptr.push(idx.len());
        }
        offset += block.rows();
    }
    SparseMatrix::new((nfree, nfree), ptr, idx, val)
}
