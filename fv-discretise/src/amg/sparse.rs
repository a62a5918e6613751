//! The row-compressed operators of the multigrid levels. The coarse ones
//! keep their columns in the order the Galerkin product met them (unsorted);
//! buffers are kept by their owner and refilled. The finest level is the
//! caller's [`CsrMatrix`], read through a [`View`], not copied.
use crate::csr::CsrMatrix;

/// A row-compressed square matrix (a coarse level's operator).
#[derive(Debug, Clone, Default)]
pub(crate) struct Sparse {
    pub n_rows: usize,
    pub ptr: Vec<u32>,
    pub col: Vec<u32>,
    pub val: Vec<f64>,
}

impl Sparse {
    /// The matrix, borrowed.
    pub fn view(&self) -> View<'_> {
        View {
            n_rows: self.n_rows,
            ptr: &self.ptr,
            col: &self.col,
            val: &self.val,
        }
    }
}

/// A borrowed row-compressed square matrix: a [`Sparse`] or a
/// [`CsrMatrix`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct View<'a> {
    pub n_rows: usize,
    pub ptr: &'a [u32],
    pub col: &'a [u32],
    pub val: &'a [f64],
}

impl<'a> View<'a> {
    /// The entries of `a`.
    pub fn of(a: &'a CsrMatrix) -> Self {
        View {
            n_rows: a.n(),
            ptr: a.row_ptr(),
            col: a.col_idx(),
            val: a.values(),
        }
    }

    /// The entries of row `i`.
    #[inline]
    pub fn row(&self, i: usize) -> (&'a [u32], &'a [f64]) {
        let (s, e) = (self.ptr[i] as usize, self.ptr[i + 1] as usize);
        (&self.col[s..e], &self.val[s..e])
    }
}
