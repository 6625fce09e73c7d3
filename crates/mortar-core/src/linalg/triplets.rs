use super::SparseMatrix;

/// `(row, column, value)` triplets whose duplicates are summed in insertion order, so that
/// the same triplets give the same matrix bit for bit.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Triplets {
    rows: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
}

impl Triplets {
    /// Adds one entry.
    #[inline]
    pub fn push(&mut self, row: u32, col: u32, val: f64) {
        self.rows.push(row as usize);
        self.cols.push(col as usize);
        self.vals.push(val);
    }

    /// Number of triplets.
    pub fn len(&self) -> usize {
        self.vals.len()
    }

    /// Whether there is no triplet.
    pub fn is_empty(&self) -> bool {
        self.vals.is_empty()
    }

    /// The triplets of `parts`, one after the other.
    pub fn concat<'a>(parts: impl Iterator<Item = &'a Triplets> + Clone) -> Triplets {
        let n = parts.clone().map(Triplets::len).sum();
        let mut out = Triplets {
            rows: Vec::with_capacity(n),
            cols: Vec::with_capacity(n),
            vals: Vec::with_capacity(n),
        };
        for p in parts {
            out.rows.extend_from_slice(&p.rows);
            out.cols.extend_from_slice(&p.cols);
            out.vals.extend_from_slice(&p.vals);
        }
        out
    }

    /// The `nrows x ncols` CSR matrix, duplicates summed (serially, in insertion order).
    ///
    /// # Panics
    /// If an index is out of range.
    pub fn to_csr(self, nrows: usize, ncols: usize) -> SparseMatrix {
        sprs::TriMat::from_triplets((nrows, ncols), self.rows, self.cols, self.vals).to_csr()
    }
}
