//! The row-compressed operators of the multigrid levels. The coarse ones
//! keep their columns in the order the Galerkin product met them (unsorted);
//! buffers are kept by their owner and refilled.
use crate::csr::CsrMatrix;

/// A row-compressed `n_rows × n_cols` matrix.
#[derive(Debug, Clone, Default)]
pub(crate) struct Sparse {
    pub n_rows: usize,
    pub n_cols: usize,
    pub ptr: Vec<u32>,
    pub col: Vec<u32>,
    pub val: Vec<f64>,
}

impl Sparse {
    /// The entries of row `i`.
    #[inline]
    pub fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let (s, e) = (self.ptr[i] as usize, self.ptr[i + 1] as usize);
        (&self.col[s..e], &self.val[s..e])
    }

    /// Copies a square [`CsrMatrix`] into `self`, reusing the buffers.
    pub fn copy_from(&mut self, a: &CsrMatrix) {
        self.n_rows = a.n();
        self.n_cols = a.n();
        self.ptr.clear();
        self.ptr.extend_from_slice(a.row_ptr());
        self.col.clear();
        self.col.extend_from_slice(a.col_idx());
        self.val.clear();
        self.val.extend_from_slice(a.values());
    }
}
