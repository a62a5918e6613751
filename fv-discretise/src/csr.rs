//! Compressed sparse row (CSR) storage for cell-centred finite-volume matrices.
//!
//! The storage is sprs's: [`CsrMatrix`] holds a `sprs::CsMatI<f64, u32>`
//! ([`CsrMatrix::as_sprs`], [`CsrMatrix::into_sprs`], and `TryFrom` for a
//! matrix built with sprs), the type the crates exchange. What sprs does not
//! do is written by hand over its index and value slices: the mat-vec and
//! triangular sweeps without bounds checks, the incomplete factorisations
//! and their preconditioned Krylov solvers ([`crate::pcg_ic0`],
//! [`crate::bicgstab_ilu0`]; sprs has neither, faer's matrix-free CG costs
//! several mat-vecs per iteration), the face slots and the pattern growth
//! below. Only the direct solver ([`crate::direct`]) wraps faer. Measured
//! on the 64³ box (docs/kernel-performance.md, "sprs storage"): the same
//! instructions per PCG iteration as the hand-written arrays it replaced.
//!
//! # Layout
//!
//! [`CsrMatrix`] stores `row_ptr`/`col_idx` as `u32` (mesh indices are `u32`
//! throughout the project), column indices sorted within each row, and the
//! position of every row's diagonal entry. Every row owns a diagonal entry,
//! even when its value is zero, so the factorisations never have to search
//! for it.
//!
//! # Assembly without searching
//!
//! [`CsrMatrix::from_faces`] builds the pattern of a cell-centred FV matrix
//! once from the OpenFOAM face addressing and returns [`FaceSlots`]: for each
//! internal face the value index of its two off-diagonal coefficients. An
//! assembly loop then reads
//!
//! ```text
//! a.fill_zero();
//! let v = a.values_mut();
//! for f in 0..n_internal {
//!     v[slots.upper[f] as usize] += a_on;  // row owner, column neighbour
//!     v[slots.lower[f] as usize] += a_no;  // row neighbour, column owner
//! }
//! ```
//!
//! and [`CsrMatrix::diag_index`] gives the diagonal slots. Accumulate (`+=`)
//! rather than assign: two faces between the same pair of cells share one
//! entry.
//!
//! # Unchecked indexing
//!
//! The per-entry kernels (`dot_unchecked` behind the mat-vec and the
//! triangular sweeps) skip bounds checks; the type invariants of
//! [`CsrMatrix`] and of the factor storage (private fields, established by
//! the constructors) prove every access in bounds, and each safe entry point
//! asserts the row index and vector length once per row. Measured on the
//! 64³ Laplacian (interleaved A/B runs): −26 % instructions and about −25 %
//! time per PCG iteration and per mat-vec against the bounds-checked version.
//!
//! # Pattern identity
//!
//! Every pattern gets a process-wide unique [`CsrMatrix::pattern_id`]; it
//! changes only when the pattern changes ([`CsrMatrix::add_entries`] adding a
//! new entry, or a new constructor call) and is kept by `clone`. The solvers
//! compare it to skip their symbolic work when only the values changed.

use std::sync::atomic::{AtomicU64, Ordering};

use sprs::CsMatI;

use crate::linear_solver::LinearSolverError;

/// Source of process-wide unique pattern identifiers.
static NEXT_PATTERN_ID: AtomicU64 = AtomicU64::new(1);

/// Returns a pattern identifier never handed out before in this process.
fn fresh_pattern_id() -> u64 {
    NEXT_PATTERN_ID.fetch_add(1, Ordering::Relaxed)
}

/// Marker for "no entry" in slot and scatter arrays.
const NONE: u32 = u32::MAX;

/// Square sparse matrix in CSR form with sorted rows and a diagonal entry in every row.
///
/// Invariants (the fields are private; every constructor and
/// [`CsrMatrix::add_entries`] establishes them, sprs's structure check
/// confirms the first five, and the unchecked kernels rely on them):
/// `row_ptr.len() == n + 1`, `row_ptr[0] == 0`, `row_ptr` is
/// nondecreasing, `row_ptr[n] == col_idx.len() == values.len()`, every
/// `col_idx[k] < n`, columns strictly increase within a row, and
/// `col_idx[diag[i]] == i` with `diag[i]` inside row `i`. Only the values
/// can change in place ([`CsrMatrix::values_mut`]).
#[derive(Debug, Clone)]
pub struct CsrMatrix {
    /// The matrix: row `i` occupies `row_ptr[i]..row_ptr[i + 1]` of the
    /// column indices (strictly increasing within each row) and the values.
    mat: CsMatI<f64, u32>,
    /// Value index of the diagonal entry of each row.
    diag: Vec<u32>,
    /// Identifier of the sparsity pattern (see the module documentation).
    pattern_id: u64,
}

impl PartialEq for CsrMatrix {
    /// Equal size, pattern and values (the pattern id is ignored).
    fn eq(&self, other: &Self) -> bool {
        self.mat == other.mat
    }
}

impl TryFrom<CsMatI<f64, u32>> for CsrMatrix {
    type Error = LinearSolverError;

    /// Adopts a square matrix built with sprs (CSC storage is converted);
    /// a row without a diagonal entry gets an explicit zero one.
    fn try_from(m: CsMatI<f64, u32>) -> Result<Self, Self::Error> {
        if m.rows() != m.cols() {
            return Err(LinearSolverError::DimensionMismatch {
                what: "columns of a square matrix",
                expected: m.rows(),
                found: m.cols(),
            });
        }
        let triplets: Vec<(u32, u32, f64)> = m.iter().map(|(&v, (r, c))| (r, c, v)).collect();
        CsrMatrix::from_triplets(m.rows(), &triplets)
    }
}

/// Value indices of the two off-diagonal coefficients of each internal face.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct FaceSlots {
    /// `upper[f]`: value index of entry (owner\[f\], neighbour\[f\]) (upper triangle, owner < neighbour).
    pub upper: Vec<u32>,
    /// `lower[f]`: value index of entry (neighbour\[f\], owner\[f\]) (lower triangle).
    pub lower: Vec<u32>,
}

impl FaceSlots {
    /// Refreshes both slot arrays after [`CsrMatrix::add_entries`] changed the pattern.
    pub fn remap(&mut self, growth: &PatternGrowth) {
        growth.remap(&mut self.upper);
        growth.remap(&mut self.lower);
    }
}

/// Outcome of [`CsrMatrix::add_entries`]: where the new entries live and how old slots moved.
///
/// Value indices held by the caller (the [`FaceSlots`], contact slots from an
/// earlier call, cached diagonal indices) are invalid after the pattern grew;
/// refresh them with [`PatternGrowth::remap`] / [`FaceSlots::remap`].
/// Diagonal indices can simply be re-read with [`CsrMatrix::diag_index`].
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct PatternGrowth {
    /// Value index of each requested entry (existing or new), in the order requested.
    pub slots: Vec<u32>,
    /// New value index of every old value index; empty when nothing was inserted.
    old_to_new: Vec<u32>,
}

impl PatternGrowth {
    /// True when at least one entry was inserted (old value indices moved).
    pub fn changed(&self) -> bool {
        !self.old_to_new.is_empty()
    }

    /// Number of value indices the pattern had before the call (0 when unchanged).
    pub fn old_nnz(&self) -> usize {
        self.old_to_new.len()
    }

    /// Translates value indices of the old pattern into the new one, in place (no-op if unchanged).
    ///
    /// # Panics
    /// If an index is not a value index of the old pattern.
    pub fn remap(&self, slots: &mut [u32]) {
        if self.changed() {
            for s in slots.iter_mut() {
                *s = self.old_to_new[*s as usize];
            }
        }
    }
}

/// `Σ_k vals[k] · x[cols[k]]` over `k` in `k0..k1`, without bounds checks (the sparse kernels' core).
///
/// # Safety
/// `k0 <= k1 <= cols.len()`, `k1 <= vals.len()` and `(cols[k] as usize) < x.len()`
/// for every `k` in `k0..k1`.
#[inline(always)]
unsafe fn dot_unchecked(cols: &[u32], vals: &[f64], k0: usize, k1: usize, x: &[f64]) -> f64 {
    debug_assert!(k0 <= k1 && k1 <= cols.len() && k1 <= vals.len());
    let mut s = 0.0;
    for k in k0..k1 {
        // SAFETY: k < k1 <= cols.len(), vals.len() and cols[k] < x.len(), by the contract.
        unsafe {
            let c = *cols.get_unchecked(k) as usize;
            debug_assert!(c < x.len());
            s += *vals.get_unchecked(k) * *x.get_unchecked(c);
        }
    }
    s
}

/// Converts a count to `u32`, failing with [`LinearSolverError::PatternTooLarge`].
fn to_u32(len: usize) -> Result<u32, LinearSolverError> {
    u32::try_from(len)
        .ok()
        .filter(|&v| v != NONE)
        .ok_or(LinearSolverError::PatternTooLarge { nnz: len })
}

/// Pattern built by [`build_pattern`]: `(row_ptr, col_idx, diag, slot of each input entry)`.
type BuiltPattern = (Vec<u32>, Vec<u32>, Vec<u32>, Vec<u32>);

/// Builds a sorted, duplicate-free CSR pattern holding every diagonal entry
/// plus the entries `(rows[e], cols[e])`, and returns the value index of each
/// input entry.
fn build_pattern(n: usize, rows: &[u32], cols: &[u32]) -> Result<BuiltPattern, LinearSolverError> {
    debug_assert_eq!(rows.len(), cols.len());
    to_u32(n)?;
    for (&r, &c) in rows.iter().zip(cols) {
        if r as usize >= n || c as usize >= n {
            return Err(LinearSolverError::IndexOutOfBounds { row: r, col: c, n });
        }
    }
    to_u32(n + rows.len())?;
    // Counting sort by row; the diagonal goes first in each row.
    let mut start = vec![0u32; n + 1];
    for &r in rows {
        start[r as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i] + 1;
    }
    // start[i] + i is the first position of row i (diagonal included).
    let total = n + rows.len();
    let mut buf: Vec<(u32, u32)> = vec![(0, 0); total];
    let mut next: Vec<u32> = (0..n).map(|i| start[i] + 1).collect();
    for i in 0..n {
        buf[start[i] as usize] = (i as u32, NONE);
    }
    for (e, (&r, &c)) in rows.iter().zip(cols).enumerate() {
        let p = &mut next[r as usize];
        buf[*p as usize] = (c, e as u32);
        *p += 1;
    }
    drop(next);
    let mut row_ptr = Vec::with_capacity(n + 1);
    let mut col_idx = Vec::with_capacity(total);
    let mut diag = vec![0u32; n];
    let mut slot_of = vec![NONE; rows.len()];
    row_ptr.push(0u32);
    for i in 0..n {
        let seg = &mut buf[start[i] as usize..start[i + 1] as usize];
        // Rows in mesh order are nearly sorted already; pattern sort is cheap.
        seg.sort_unstable();
        let row_begin = col_idx.len();
        for &(c, tag) in seg.iter() {
            if col_idx.len() == row_begin || *col_idx.last().unwrap_or(&NONE) != c {
                col_idx.push(c);
            }
            let slot = (col_idx.len() - 1) as u32;
            if c as usize == i {
                diag[i] = slot;
            }
            if tag != NONE {
                slot_of[tag as usize] = slot;
            }
        }
        row_ptr.push(col_idx.len() as u32);
    }
    Ok((row_ptr, col_idx, diag, slot_of))
}

impl CsrMatrix {
    /// Builds the pattern of a cell-centred FV matrix (diagonal + both entries of each internal face), values zero.
    ///
    /// `owner` and `neighbour` follow the OpenFOAM addressing; only the first
    /// `neighbour.len()` owners are used (so the full owner list, internal
    /// faces first, can be passed). Returns the matrix and the [`FaceSlots`]
    /// of the internal faces.
    ///
    /// # Panics
    /// If `owner` is shorter than `neighbour`, a cell index is `>= n_cells`,
    /// a face has `owner == neighbour`, or the pattern exceeds `u32` indices —
    /// all of which a validated mesh excludes.
    pub fn from_faces(n_cells: usize, owner: &[u32], neighbour: &[u32]) -> (CsrMatrix, FaceSlots) {
        let nf = neighbour.len();
        assert!(
            owner.len() >= nf,
            "from_faces: owner shorter than neighbour"
        );
        let mut rows = Vec::with_capacity(2 * nf);
        let mut cols = Vec::with_capacity(2 * nf);
        for (f, (&o, &nb)) in owner.iter().zip(neighbour).enumerate() {
            assert!(
                o != nb,
                "from_faces: face {f} has owner == neighbour == {o}"
            );
            rows.extend_from_slice(&[o, nb]);
            cols.extend_from_slice(&[nb, o]);
        }
        let (row_ptr, col_idx, diag, slot_of) =
            build_pattern(n_cells, &rows, &cols).unwrap_or_else(|e| panic!("from_faces: {e}"));
        let slots = FaceSlots {
            upper: slot_of.iter().step_by(2).copied().collect(),
            lower: slot_of.iter().skip(1).step_by(2).copied().collect(),
        };
        let nnz = col_idx.len();
        let a = CsrMatrix::from_parts(n_cells, row_ptr, col_idx, vec![0.0; nnz], diag);
        (a, slots)
    }

    /// Builds an `n × n` matrix from `(row, col, value)` triplets, summing duplicates (every diagonal entry is stored).
    pub fn from_triplets(
        n: usize,
        triplets: &[(u32, u32, f64)],
    ) -> Result<CsrMatrix, LinearSolverError> {
        let rows: Vec<u32> = triplets.iter().map(|t| t.0).collect();
        let cols: Vec<u32> = triplets.iter().map(|t| t.1).collect();
        let (row_ptr, col_idx, diag, slot_of) = build_pattern(n, &rows, &cols)?;
        let mut values = vec![0.0; col_idx.len()];
        for (t, &s) in triplets.iter().zip(&slot_of) {
            values[s as usize] += t.2;
        }
        Ok(CsrMatrix::from_parts(n, row_ptr, col_idx, values, diag))
    }

    /// Wraps arrays built by [`build_pattern`] (or the merge of
    /// [`CsrMatrix::add_entries`]) with a new pattern id.
    ///
    /// # Panics
    /// If the arrays break the CSR structure (sprs checks it: an internal
    /// error, never a user's).
    fn from_parts(
        n: usize,
        row_ptr: Vec<u32>,
        col_idx: Vec<u32>,
        values: Vec<f64>,
        diag: Vec<u32>,
    ) -> CsrMatrix {
        let mat = CsMatI::try_new((n, n), row_ptr, col_idx, values)
            .unwrap_or_else(|(.., e)| panic!("CsrMatrix: invalid CSR structure built: {e}"));
        CsrMatrix {
            mat,
            diag,
            pattern_id: fresh_pattern_id(),
        }
    }

    /// The matrix as sprs's CSR type, the matrix the crates exchange.
    pub fn as_sprs(&self) -> &CsMatI<f64, u32> {
        &self.mat
    }

    /// Unwraps the sprs matrix (the diagonal positions and the pattern id are dropped).
    pub fn into_sprs(self) -> CsMatI<f64, u32> {
        self.mat
    }

    /// Number of rows (= columns).
    #[inline]
    pub fn n(&self) -> usize {
        self.mat.rows()
    }

    /// Number of stored entries.
    #[inline]
    pub fn nnz(&self) -> usize {
        self.mat.nnz()
    }

    /// Row pointers: row `i` occupies value indices `row_ptr[i]..row_ptr[i + 1]`.
    #[inline]
    pub fn row_ptr(&self) -> &[u32] {
        self.mat.indptr().into_raw_storage()
    }

    /// Column indices (sorted within each row).
    #[inline]
    pub fn col_idx(&self) -> &[u32] {
        self.mat.indices()
    }

    /// Stored values.
    #[inline]
    pub fn values(&self) -> &[f64] {
        self.mat.data()
    }

    /// Mutable values, for assembly through [`FaceSlots`] and [`CsrMatrix::diag_index`] (the pattern stays fixed).
    #[inline]
    pub fn values_mut(&mut self) -> &mut [f64] {
        self.mat.data_mut()
    }

    /// Value index of each row's diagonal entry.
    pub fn diag_index(&self) -> &[u32] {
        &self.diag
    }

    /// Identifier of the sparsity pattern; equal ids imply equal patterns.
    pub fn pattern_id(&self) -> u64 {
        self.pattern_id
    }

    /// Column indices and values of row `i`.
    pub fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let (s, e) = (self.row_ptr()[i] as usize, self.row_ptr()[i + 1] as usize);
        (&self.col_idx()[s..e], &self.values()[s..e])
    }

    /// Value index of entry `(row, col)`, if stored (binary search).
    pub fn entry_index(&self, row: usize, col: usize) -> Option<usize> {
        if row >= self.n() {
            return None;
        }
        let (s, e) = (
            self.row_ptr()[row] as usize,
            self.row_ptr()[row + 1] as usize,
        );
        let c = u32::try_from(col).ok()?;
        self.col_idx()[s..e].binary_search(&c).ok().map(|k| s + k)
    }

    /// Sets every stored value to zero (the pattern is kept).
    pub fn fill_zero(&mut self) {
        self.values_mut().fill(0.0);
    }

    /// Computes `y = A x` without allocating.
    ///
    /// # Panics
    /// If `x.len() != n` or `y.len() != n`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        assert_eq!(x.len(), self.n(), "mul_vec: x has the wrong length");
        assert_eq!(y.len(), self.n(), "mul_vec: y has the wrong length");
        for (i, yi) in y.iter_mut().enumerate() {
            *yi = self.row_times(i, x);
        }
    }

    /// Computes `r = b − A x` without allocating and returns `‖r‖₂`.
    ///
    /// # Panics
    /// If a slice length differs from `n`.
    pub fn residual(&self, b: &[f64], x: &[f64], r: &mut [f64]) -> f64 {
        assert_eq!(x.len(), self.n(), "residual: x has the wrong length");
        assert_eq!(b.len(), self.n(), "residual: b has the wrong length");
        assert_eq!(r.len(), self.n(), "residual: r has the wrong length");
        let mut rr = 0.0;
        for (i, (ri, &bi)) in r.iter_mut().zip(b).enumerate() {
            let v = bi - self.row_times(i, x);
            *ri = v;
            rr += v * v;
        }
        rr.sqrt()
    }

    /// `(A x)_i`: the sparse kernel of the mat-vec (bounds checked once per row, not per entry).
    ///
    /// # Panics
    /// If `i >= n` or `x.len() != n`.
    #[inline(always)]
    pub(crate) fn row_times(&self, i: usize, x: &[f64]) -> f64 {
        assert!(
            i < self.n() && x.len() == self.n(),
            "row_times: index or length out of range"
        );
        // SAFETY: i < n and row_ptr.len() == n + 1, so i and i + 1 index row_ptr;
        // row_ptr is nondecreasing with row_ptr[n] == col_idx.len() == values.len(),
        // and every column index is < n == x.len() (type invariants).
        let row_ptr = self.row_ptr();
        unsafe {
            let s = *row_ptr.get_unchecked(i) as usize;
            let e = *row_ptr.get_unchecked(i + 1) as usize;
            dot_unchecked(self.col_idx(), self.values(), s, e, x)
        }
    }

    /// `w_i − Σ_{j>i} (scale · a_ij) z_j`: the backward sweep of a factor
    /// whose strict upper triangle is `A`'s own scaled by `scale` (DIC:
    /// `1/d̃_i`), with `z_next = z[i + 1]` passed in a register and applied
    /// last, in the order of [`SplitFactor::backward_row`].
    ///
    /// # Panics
    /// If `i >= n` or `z.len() != n`.
    #[inline(always)]
    pub(crate) fn backward_row_of_upper(
        &self,
        i: usize,
        w_i: f64,
        scale: f64,
        z: &[f64],
        z_next: f64,
    ) -> f64 {
        assert!(
            i < self.n() && z.len() == self.n(),
            "backward_row_of_upper: index or length out of range"
        );
        // SAFETY: i < n indexes row_ptr and diag; diag[i] < row_ptr[i + 1] <=
        // col_idx.len() == values.len(), so the upper part of row i,
        // diag[i] + 1..row_ptr[i + 1], lies within them, and every column
        // index is < n == z.len() (type invariants).
        let (col_idx, values) = (self.col_idx(), self.values());
        unsafe {
            let s = *self.diag.get_unchecked(i) as usize + 1;
            let e = *self.row_ptr().get_unchecked(i + 1) as usize;
            if s == e {
                return w_i;
            }
            let mut sum = 0.0;
            for k in s + 1..e {
                let c = *col_idx.get_unchecked(k) as usize;
                sum += scale * *values.get_unchecked(k) * *z.get_unchecked(c);
            }
            let t = w_i - sum;
            let c = *col_idx.get_unchecked(s) as usize;
            let zc = if c == i + 1 {
                z_next
            } else {
                *z.get_unchecked(c)
            };
            t - scale * *values.get_unchecked(s) * zc
        }
    }

    /// The diagonal entry of row `i` and its upper part (columns, values).
    ///
    /// # Panics
    /// If `i >= n`.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    pub(crate) fn diagonal_and_upper(&self, i: usize) -> (f64, (&[u32], &[f64])) {
        let (d, e) = (self.diag[i] as usize, self.row_ptr()[i + 1] as usize);
        (
            self.values()[d],
            (&self.col_idx()[d + 1..e], &self.values()[d + 1..e]),
        )
    }

    /// Whether the matrix is symmetric in pattern and values, to the bit.
    pub fn is_symmetric(&self) -> bool {
        let mut lower = 0usize;
        for i in 0..self.n() {
            let (s, d) = (self.row_ptr()[i] as usize, self.diag[i] as usize);
            lower += d - s;
            for k in s..d {
                let j = self.col_idx()[k] as usize;
                match self.entry_index(j, i) {
                    Some(kt) if self.values()[kt].to_bits() == self.values()[k].to_bits() => {}
                    _ => return false,
                }
            }
        }
        // every lower entry has its transpose: the pattern is symmetric when
        // the upper triangle has no more entries
        2 * lower + self.n() == self.nnz()
    }

    /// Whether the graph of the pattern (rows as vertices, off-diagonal
    /// entries as edges) has no triangle: no three rows each coupled to the
    /// other two. On such a graph IC(0) drops no fill from its off-diagonal
    /// entries (rows i and j > i share no third row), so its strict lower
    /// triangle is `A`'s own ([`crate::pcg_ic0`]). Structured hexahedral
    /// meshes (the 7-point face graph) have none; tetrahedral and polyhedral
    /// ones do. Reads the lower triangle only (a symmetric pattern).
    pub fn is_triangle_free(&self) -> bool {
        for i in 0..self.n() {
            let (s, d) = (self.row_ptr()[i] as usize, self.diag[i] as usize);
            let lower_i = &self.col_idx()[s..d];
            for &j in lower_i {
                let j = j as usize;
                let (sj, dj) = (self.row_ptr()[j] as usize, self.diag[j] as usize);
                // a common column c < j of rows i and j closes a triangle
                let lower_j = &self.col_idx()[sj..dj];
                let (mut p, mut q) = (0, 0);
                while p < lower_i.len() && q < lower_j.len() && (lower_i[p] as usize) < j {
                    match lower_i[p].cmp(&lower_j[q]) {
                        std::cmp::Ordering::Equal => return false,
                        std::cmp::Ordering::Less => p += 1,
                        std::cmp::Ordering::Greater => q += 1,
                    }
                }
            }
        }
        true
    }

    /// Smallest column index of row `i` (rows are never empty: the diagonal is always stored).
    ///
    /// # Panics
    /// If `i >= n`.
    #[inline(always)]
    pub(crate) fn min_col(&self, i: usize) -> usize {
        assert!(i < self.n(), "min_col: row out of range");
        // SAFETY: i < n indexes row_ptr (length n + 1); row i holds at least its
        // diagonal entry, so row_ptr[i] < row_ptr[i + 1] <= col_idx.len().
        unsafe {
            *self
                .col_idx()
                .get_unchecked(*self.row_ptr().get_unchecked(i) as usize) as usize
        }
    }

    /// Largest `|a_ij − a_ji|` over the stored entries (entries missing on one side count as 0).
    pub fn max_asymmetry(&self) -> f64 {
        let mut m: f64 = 0.0;
        for i in 0..self.n() {
            let (s, e) = (self.row_ptr()[i] as usize, self.row_ptr()[i + 1] as usize);
            for k in s..e {
                let j = self.col_idx()[k] as usize;
                let t = self.entry_index(j, i).map_or(0.0, |kt| self.values()[kt]);
                m = m.max((self.values()[k] - t).abs());
            }
        }
        m
    }

    /// Writes the value index of each entry of `extra` (row, col) to `out`
    /// (cleared first) and returns true when every entry is in the pattern;
    /// false at the first that is not (`out` is then incomplete and
    /// [`CsrMatrix::add_entries`] is needed). Allocates nothing once `out`
    /// has grown to `extra.len()`: the per-iteration check of the implicit
    /// contact's cross-body entries.
    pub fn find_entries(&self, extra: &[(u32, u32)], out: &mut Vec<u32>) -> bool {
        out.clear();
        for &(r, c) in extra {
            if r as usize >= self.n() || c as usize >= self.n() {
                return false;
            }
            match self.entry_index(r as usize, c as usize) {
                Some(k) => out.push(k as u32),
                None => return false,
            }
        }
        true
    }

    /// Grows the pattern with the entries `extra` (row, col); existing entries and repeats are fine.
    ///
    /// Values of existing entries are kept, new entries start at zero. When
    /// at least one entry is new the arrays are rebuilt (one O(nnz) merge,
    /// rows stay sorted), [`CsrMatrix::pattern_id`] changes and **every value
    /// index held elsewhere becomes stale**: refresh [`FaceSlots`] with
    /// [`FaceSlots::remap`], other slot arrays with [`PatternGrowth::remap`],
    /// and re-read [`CsrMatrix::diag_index`]. [`PatternGrowth::slots`] gives
    /// the (new) value index of each requested entry. When nothing is new the
    /// matrix, its id and all slots are unchanged.
    pub fn add_entries(
        &mut self,
        extra: &[(u32, u32)],
    ) -> Result<PatternGrowth, LinearSolverError> {
        let n = self.n();
        for &(r, c) in extra {
            if r as usize >= n || c as usize >= n {
                return Err(LinearSolverError::IndexOutOfBounds { row: r, col: c, n });
            }
        }
        // Sorted list of genuinely new entries.
        let mut new: Vec<(u32, u32)> = extra
            .iter()
            .copied()
            .filter(|&(r, c)| self.entry_index(r as usize, c as usize).is_none())
            .collect();
        new.sort_unstable();
        new.dedup();
        if new.is_empty() {
            let slots = extra
                .iter()
                .map(|&(r, c)| {
                    self.entry_index(r as usize, c as usize)
                        .map_or(NONE, |k| k as u32)
                })
                .collect();
            return Ok(PatternGrowth {
                slots,
                old_to_new: Vec::new(),
            });
        }
        let nnz_new = self.nnz() + new.len();
        to_u32(nnz_new)?;
        let mut row_ptr = Vec::with_capacity(n + 1);
        let mut col_idx = Vec::with_capacity(nnz_new);
        let mut values = Vec::with_capacity(nnz_new);
        let mut old_to_new = vec![0u32; self.nnz()];
        row_ptr.push(0u32);
        let mut q = 0; // cursor in `new`
        for i in 0..n {
            let (s, e) = (self.row_ptr()[i] as usize, self.row_ptr()[i + 1] as usize);
            let mut k = s;
            loop {
                let next_new = (q < new.len() && new[q].0 as usize == i).then(|| new[q].1);
                match (k < e, next_new) {
                    (false, None) => break,
                    (true, nn) if nn.is_none_or(|c| self.col_idx()[k] < c) => {
                        old_to_new[k] = col_idx.len() as u32;
                        col_idx.push(self.col_idx()[k]);
                        values.push(self.values()[k]);
                        k += 1;
                    }
                    (_, Some(c)) => {
                        col_idx.push(c);
                        values.push(0.0);
                        q += 1;
                    }
                    (true, None) => unreachable!("covered by the guarded arm"),
                }
            }
            row_ptr.push(col_idx.len() as u32);
        }
        let diag = self.diag.iter().map(|&d| old_to_new[d as usize]).collect();
        *self = CsrMatrix::from_parts(n, row_ptr, col_idx, values, diag);
        let slots = extra
            .iter()
            .map(|&(r, c)| {
                self.entry_index(r as usize, c as usize)
                    .map_or(NONE, |k| k as u32)
            })
            .collect();
        Ok(PatternGrowth { slots, old_to_new })
    }

    /// Compressed-sparse-column structure of the same matrix: `(col_ptr, row_idx, csr_to_csc)`.
    ///
    /// `csr_to_csc[k]` is the CSC position of CSR value index `k`; row
    /// indices are sorted within each column.
    pub(crate) fn csc_structure(&self) -> (Vec<usize>, Vec<usize>, Vec<u32>) {
        let n = self.n();
        let mut col_ptr = vec![0usize; n + 1];
        for &c in self.col_idx() {
            col_ptr[c as usize + 1] += 1;
        }
        for j in 0..n {
            col_ptr[j + 1] += col_ptr[j];
        }
        let mut next = col_ptr[..n].to_vec();
        let mut row_idx = vec![0usize; self.nnz()];
        let mut map = vec![0u32; self.nnz()];
        for i in 0..n {
            let (s, e) = (self.row_ptr()[i] as usize, self.row_ptr()[i + 1] as usize);
            for (&c, m) in self.col_idx()[s..e].iter().zip(&mut map[s..e]) {
                let p = next[c as usize];
                next[c as usize] += 1;
                row_idx[p] = i;
                *m = p as u32;
            }
        }
        (col_ptr, row_idx, map)
    }

    /// Copy of the matrix as a faer column-major sparse matrix (used by the direct solver and for cross-checks).
    pub fn to_faer(&self) -> faer::sparse::SparseColMat<usize, f64> {
        let (col_ptr, row_idx, map) = self.csc_structure();
        let mut val = vec![0.0; self.nnz()];
        for (k, &p) in map.iter().enumerate() {
            val[p as usize] = self.values()[k];
        }
        let symbolic = faer::sparse::SymbolicSparseColMat::new_checked(
            self.n(),
            self.n(),
            col_ptr,
            None,
            row_idx,
        );
        faer::sparse::SparseColMat::new(symbolic, val)
    }
}

/// One strict triangle of an incomplete factor in CSR form (crate-internal).
///
/// Invariants, relied upon by the unchecked sweeps and established only by
/// the `SplitFactor::set_pattern_*` methods (outside this module the
/// pattern is read-only and the values are exposed as fixed-length slices):
/// `ptr.len() == n + 1`, `ptr[0] == 0`, `ptr` nondecreasing,
/// `ptr[n] == col.len() == val.len()`, every `col[k] < n`, columns
/// increasing within a row; `n` is the owning factor's `inv_diag.len()`.
#[derive(Debug, Clone)]
pub(crate) struct TriCsr {
    /// Row pointers, length `n + 1`.
    ptr: Vec<u32>,
    /// Column indices, sorted within each row.
    col: Vec<u32>,
    /// Values.
    val: Vec<f64>,
}

impl Default for TriCsr {
    fn default() -> Self {
        TriCsr {
            ptr: vec![0],
            col: Vec::new(),
            val: Vec::new(),
        }
    }
}

impl TriCsr {
    /// Sets the triangle to `a`'s strict lower triangle, pattern and values
    /// (reusing the buffers; allocates nothing when the sizes are unchanged).
    pub(crate) fn set_lower_of(&mut self, a: &CsrMatrix) {
        let n = a.n();
        let (rp, ci, dg, av) = (a.row_ptr(), a.col_idx(), a.diag_index(), a.values());
        self.reset(n);
        self.val.clear();
        for i in 0..n {
            let (s, d) = (rp[i] as usize, dg[i] as usize);
            self.col.extend_from_slice(&ci[s..d]);
            self.val.extend_from_slice(&av[s..d]);
            self.ptr.push(self.col.len() as u32);
        }
    }

    /// Forward-sweep row `i`: `rhs_i − Σ_j val_ij w_j`, with
    /// `w_prev = w[i − 1]` passed in a register and applied last (the
    /// loop-carried dependency chain is one multiply and one subtraction).
    ///
    /// # Panics
    /// If `i >= n` or `w.len() != n`.
    #[inline(always)]
    pub(crate) fn forward_row(&self, i: usize, rhs_i: f64, w: &[f64], w_prev: f64) -> f64 {
        assert!(
            i + 1 < self.ptr.len() && w.len() + 1 == self.ptr.len(),
            "forward_row: out of range"
        );
        // SAFETY: i < n, and by the TriCsr invariants the row range lies within
        // col/val and every column index is < n == w.len().
        unsafe {
            let (s, e) = self.range_unchecked(i);
            if s == e {
                return rhs_i;
            }
            let t = rhs_i - dot_unchecked(&self.col, &self.val, s, e - 1, w);
            let c = *self.col.get_unchecked(e - 1) as usize;
            let wc = if c + 1 == i {
                w_prev
            } else {
                *w.get_unchecked(c)
            };
            t - *self.val.get_unchecked(e - 1) * wc
        }
    }

    /// Column indices and values of row `i`.
    #[inline(always)]
    pub(crate) fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let (s, e) = (self.ptr[i] as usize, self.ptr[i + 1] as usize);
        (&self.col[s..e], &self.val[s..e])
    }

    /// Clears the pattern to an empty `n × n` triangle.
    fn reset(&mut self, n: usize) {
        self.ptr.clear();
        self.ptr.reserve(n + 1);
        self.ptr.push(0);
        self.col.clear();
    }

    /// Sets every value to zero, sized to the pattern.
    fn zero_values(&mut self) {
        self.val.clear();
        self.val.resize(self.col.len(), 0.0);
    }

    /// Value range `(s, e)` of row `i < n`, unchecked.
    ///
    /// # Safety
    /// `i < n` (so `i + 1 < ptr.len()`).
    #[inline(always)]
    unsafe fn range_unchecked(&self, i: usize) -> (usize, usize) {
        // SAFETY: i + 1 < ptr.len() by the contract.
        unsafe {
            (
                *self.ptr.get_unchecked(i) as usize,
                *self.ptr.get_unchecked(i + 1) as usize,
            )
        }
    }
}

/// Mutable view of a [`SplitFactor`] for the numeric factorisations: read-only pattern, fixed-length values.
pub(crate) struct FactorParts<'a> {
    /// Lower row pointers.
    pub(crate) lptr: &'a [u32],
    /// Lower column indices.
    pub(crate) lcol: &'a [u32],
    /// Lower values `L_f`.
    pub(crate) lval: &'a mut [f64],
    /// Upper row pointers.
    pub(crate) uptr: &'a [u32],
    /// Upper values `U_b`.
    pub(crate) uval: &'a mut [f64],
    /// `D⁻¹`.
    pub(crate) inv_diag: &'a mut [f64],
}

/// Incomplete factor `M = (D + L_f)(I + U_b)` as two contiguous strict triangles plus `D⁻¹` (crate-internal).
///
/// Applying `M⁻¹` is a forward sweep `t_i = rhs_i − Σ_j L_f,ij w_j`,
/// `w_i = D⁻¹_i t_i` followed by a backward sweep `z_i = w_i − Σ_j U_b,ij z_j`;
/// no diagonal is touched in the backward sweep. ILU(0) `(I + L)(D + U)`
/// stores `L_f = L D` and `U_b = D⁻¹ U`; IC(0) `(D̃ + E) D̃⁻¹ (D̃ + Eᵀ)` stores
/// `L_f = E` and `U_b = D̃⁻¹ Eᵀ`, and then `rᵀM⁻¹r = Σ_i t_i w_i`.
#[derive(Debug, Clone, Default)]
pub(crate) struct SplitFactor {
    /// Strict lower triangle `L_f`.
    lower: TriCsr,
    /// Strict upper triangle `U_b`.
    upper: TriCsr,
    /// `D⁻¹`; its length is the factor size `n`.
    inv_diag: Vec<f64>,
}

impl SplitFactor {
    /// The strict lower triangle `L_f` (for tests).
    #[cfg(test)]
    pub(crate) fn lower(&self) -> &TriCsr {
        &self.lower
    }

    /// The strict upper triangle `U_b` (for tests).
    #[cfg(test)]
    pub(crate) fn upper(&self) -> &TriCsr {
        &self.upper
    }

    /// `D⁻¹`.
    pub(crate) fn inv_diag(&self) -> &[f64] {
        &self.inv_diag
    }

    /// Pattern (read-only) and values (mutable, fixed length) for the numeric factorisation.
    pub(crate) fn parts_mut(&mut self) -> FactorParts<'_> {
        FactorParts {
            lptr: &self.lower.ptr,
            lcol: &self.lower.col,
            lval: &mut self.lower.val,
            uptr: &self.upper.ptr,
            uval: &mut self.upper.val,
            inv_diag: &mut self.inv_diag,
        }
    }

    /// Pattern of ILU(0): lower row `i` mirrors `a`'s value indices `row_ptr[i]..diag[i]`, upper row `i` `diag[i] + 1..row_ptr[i + 1]`.
    pub(crate) fn set_pattern_from(&mut self, a: &CsrMatrix) {
        let n = a.n();
        let (rp, ci, dg) = (a.row_ptr(), a.col_idx(), a.diag_index());
        self.lower.reset(n);
        self.upper.reset(n);
        for i in 0..n {
            let (s, d, e) = (rp[i] as usize, dg[i] as usize, rp[i + 1] as usize);
            self.lower.col.extend_from_slice(&ci[s..d]);
            self.lower.ptr.push(self.lower.col.len() as u32);
            self.upper.col.extend_from_slice(&ci[d + 1..e]);
            self.upper.ptr.push(self.upper.col.len() as u32);
        }
        self.lower.zero_values();
        self.upper.zero_values();
        self.inv_diag.clear();
        self.inv_diag.resize(n, 0.0);
    }

    /// Pattern of IC(0): the strict lower part of `a` and its transpose; `lower_to_upper[k]` is the upper position of lower entry `k`.
    pub(crate) fn set_pattern_transposed_from(
        &mut self,
        a: &CsrMatrix,
        lower_to_upper: &mut Vec<u32>,
    ) {
        self.set_pattern_from(a);
        let n = a.n();
        let (lo, up) = (&self.lower, &mut self.upper);
        let nl = lo.col.len();
        up.ptr.clear();
        up.ptr.resize(n + 1, 0);
        for &c in &lo.col {
            up.ptr[c as usize + 1] += 1;
        }
        for i in 0..n {
            up.ptr[i + 1] += up.ptr[i];
        }
        up.col.clear();
        up.col.resize(nl, 0);
        lower_to_upper.clear();
        lower_to_upper.resize(nl, 0);
        let mut next: Vec<u32> = up.ptr[..n].to_vec();
        for i in 0..n {
            let (s, e) = (lo.ptr[i] as usize, lo.ptr[i + 1] as usize);
            for (&c, l2u) in lo.col[s..e].iter().zip(&mut lower_to_upper[s..e]) {
                let pos = next[c as usize];
                next[c as usize] += 1;
                up.col[pos as usize] = i as u32; // rows ascend, so columns sort within each row
                *l2u = pos;
            }
        }
        up.zero_values();
    }

    /// Forward-sweep row `i`: `t_i = rhs_i − Σ_j L_f,ij w_j`, with `w_prev = w[i − 1]` passed in a register.
    ///
    /// The entry of column `i − 1` (the last one, rows being sorted) is
    /// applied last from `w_prev`, which keeps the loop-carried dependency
    /// chain to one multiply and one subtraction.
    ///
    /// # Panics
    /// If `i >= n` or `w.len() != n`.
    #[inline(always)]
    pub(crate) fn forward_row(&self, i: usize, rhs_i: f64, w: &[f64], w_prev: f64) -> f64 {
        self.lower.forward_row(i, rhs_i, w, w_prev)
    }

    /// `z = (I + U_b)⁻¹ D⁻¹ (D + L_f)⁻¹ D r`: one forward and one backward
    /// sweep, the factor's application as a preconditioner (`z` must not
    /// alias `r`).
    pub(crate) fn apply(&self, r: &[f64], z: &mut [f64]) {
        let rd = &self.inv_diag;
        let n = rd.len();
        let mut w_prev = 0.0;
        for i in 0..n {
            let wi = self.forward_row(i, r[i], z, w_prev) * rd[i];
            z[i] = wi;
            w_prev = wi;
        }
        let mut z_next = 0.0;
        for i in (0..n).rev() {
            let zi = self.backward_row(i, z[i], z, z_next);
            z[i] = zi;
            z_next = zi;
        }
    }

    /// Backward-sweep row `i`: `z_i = w_i − Σ_j U_b,ij z_j`, with `z_next = z[i + 1]` passed in a register.
    ///
    /// # Panics
    /// If `i >= n` or `z.len() != n`.
    #[inline(always)]
    pub(crate) fn backward_row(&self, i: usize, w_i: f64, z: &[f64], z_next: f64) -> f64 {
        let up = &self.upper;
        assert!(
            i < self.inv_diag.len() && z.len() == self.inv_diag.len(),
            "backward_row: out of range"
        );
        // SAFETY: as in `forward_row`.
        unsafe {
            let (s, e) = up.range_unchecked(i);
            if s == e {
                return w_i;
            }
            let t = w_i - dot_unchecked(&up.col, &up.val, s + 1, e, z);
            let c = *up.col.get_unchecked(s) as usize;
            let zc = if c == i + 1 {
                z_next
            } else {
                *z.get_unchecked(c)
            };
            t - *up.val.get_unchecked(s) * zc
        }
    }
}

#[cfg(test)]
pub(crate) mod test_util {
    //! Test matrices shared by the solver tests.
    use super::CsrMatrix;

    use std::alloc::{GlobalAlloc, Layout, System};
    use std::cell::Cell;

    /// System allocator that counts allocations per thread, so tests can prove a solve allocates nothing.
    struct CountingAlloc;

    thread_local! {
        static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
    }

    // SAFETY: forwards to the system allocator; the counter is a const-initialised
    // thread-local without destructor, so touching it never allocates or re-enters.
    unsafe impl GlobalAlloc for CountingAlloc {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
            // SAFETY: same contract as the caller's.
            unsafe { System.alloc(layout) }
        }

        unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
            // SAFETY: same contract as the caller's.
            unsafe { System.dealloc(ptr, layout) }
        }

        unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
            // SAFETY: same contract as the caller's.
            unsafe { System.realloc(ptr, layout, new_size) }
        }
    }

    #[global_allocator]
    static GLOBAL: CountingAlloc = CountingAlloc;

    /// Allocations made by the current thread so far.
    pub(crate) fn allocations() -> usize {
        ALLOCATIONS.with(|c| c.get())
    }

    /// Cell index of `(i, j, k)` on an `nx × ny × nz` grid.
    fn cell(i: usize, j: usize, k: usize, nx: usize, ny: usize) -> u32 {
        (i + nx * (j + ny * k)) as u32
    }

    /// Internal-face addressing (owner < neighbour, sorted) of an `nx × ny × nz` structured grid.
    pub(crate) fn grid_faces(nx: usize, ny: usize, nz: usize) -> (Vec<u32>, Vec<u32>) {
        let (mut own, mut nei) = (Vec::new(), Vec::new());
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let c = cell(i, j, k, nx, ny);
                    if i + 1 < nx {
                        own.push(c);
                        nei.push(cell(i + 1, j, k, nx, ny));
                    }
                    if j + 1 < ny {
                        own.push(c);
                        nei.push(cell(i, j + 1, k, nx, ny));
                    }
                    if k + 1 < nz {
                        own.push(c);
                        nei.push(cell(i, j, k + 1, nx, ny));
                    }
                }
            }
        }
        (own, nei)
    }

    /// FV Laplacian of a structured grid: face coefficient 1, Dirichlet boundary faces add 2 to the diagonal, plus `boost`.
    pub(crate) fn laplacian(nx: usize, ny: usize, nz: usize, boost: f64) -> CsrMatrix {
        let n = nx * ny * nz;
        let (own, nei) = grid_faces(nx, ny, nz);
        let (mut a, slots) = CsrMatrix::from_faces(n, &own, &nei);
        let diag: Vec<u32> = a.diag_index().to_vec();
        let v = a.values_mut();
        for &d in &diag {
            v[d as usize] += boost;
        }
        for f in 0..own.len() {
            v[slots.upper[f] as usize] -= 1.0;
            v[slots.lower[f] as usize] -= 1.0;
            v[diag[own[f] as usize] as usize] += 1.0;
            v[diag[nei[f] as usize] as usize] += 1.0;
        }
        // Dirichlet boundary faces on the sides of every non-degenerate direction.
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let c = cell(i, j, k, nx, ny) as usize;
                    let mut nb = 0;
                    for (idx, len) in [(i, nx), (j, ny), (k, nz)] {
                        if len > 1 {
                            nb += usize::from(idx == 0) + usize::from(idx + 1 == len);
                        }
                    }
                    v[diag[c] as usize] += 2.0 * nb as f64;
                }
            }
        }
        a
    }

    /// Upwind convection–diffusion on a structured grid (nonsymmetric M-matrix), velocity `vel`, diffusion 1.
    pub(crate) fn convection_diffusion(
        nx: usize,
        ny: usize,
        nz: usize,
        vel: [f64; 3],
    ) -> CsrMatrix {
        let n = nx * ny * nz;
        let (own, nei) = grid_faces(nx, ny, nz);
        let (mut a, slots) = CsrMatrix::from_faces(n, &own, &nei);
        let diag: Vec<u32> = a.diag_index().to_vec();
        let v = a.values_mut();
        for f in 0..own.len() {
            let (o, nb) = (own[f] as usize, nei[f] as usize);
            let dir = if nb == o + 1 {
                0
            } else if nb == o + nx {
                1
            } else {
                2
            };
            let flux = vel[dir]; // face flux from owner to neighbour
                                 // owner row: -D - max(-F, 0) on neighbour, diagonal D + max(F, 0)
            v[slots.upper[f] as usize] += -1.0 - (-flux).max(0.0);
            v[diag[o] as usize] += 1.0 + flux.max(0.0);
            v[slots.lower[f] as usize] += -1.0 - flux.max(0.0);
            v[diag[nb] as usize] += 1.0 + (-flux).max(0.0);
        }
        for &d in &diag {
            v[d as usize] += 0.5; // Dirichlet-like boost for invertibility
        }
        a
    }

    /// Tiny deterministic LCG (Knuth's MMIX constants).
    pub(crate) struct Lcg(pub(crate) u64);

    impl Lcg {
        /// Next value in [0, 1).
        pub(crate) fn next_f64(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }

        /// Next index in `0..m`.
        pub(crate) fn next_below(&mut self, m: usize) -> usize {
            ((self.next_f64() * m as f64) as usize).min(m - 1)
        }
    }

    /// Random symmetric, strictly diagonally dominant (hence SPD) sparse matrix with mixed-sign off-diagonals.
    pub(crate) fn random_spd(n: usize, per_row: usize, seed: u64) -> CsrMatrix {
        let mut rng = Lcg(seed);
        let mut trip = Vec::new();
        let mut rowsum = vec![0.0; n];
        for i in 0..n {
            for _ in 0..per_row {
                let j = rng.next_below(n);
                if j == i {
                    continue;
                }
                let w = rng.next_f64() * 2.0 - 1.0;
                trip.push((i as u32, j as u32, w));
                trip.push((j as u32, i as u32, w));
                rowsum[i] += w.abs();
                rowsum[j] += w.abs();
            }
        }
        for (i, s) in rowsum.iter().enumerate() {
            trip.push((i as u32, i as u32, s * 1.05 + 0.01));
        }
        CsrMatrix::from_triplets(n, &trip).expect("valid triplets")
    }

    /// Deterministic right-hand side with entries in [-1, 1).
    pub(crate) fn rhs(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = Lcg(seed);
        (0..n).map(|_| rng.next_f64() * 2.0 - 1.0).collect()
    }

    /// `‖b − A x‖ / ‖b‖`.
    pub(crate) fn rel_residual(a: &CsrMatrix, b: &[f64], x: &[f64]) -> f64 {
        let mut r = vec![0.0; a.n()];
        let rn = a.residual(b, x, &mut r);
        rn / b.iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    /// `‖x − y‖ / ‖y‖`.
    pub(crate) fn rel_diff(x: &[f64], y: &[f64]) -> f64 {
        let d: f64 = x.iter().zip(y).map(|(a, b)| (a - b) * (a - b)).sum();
        let m: f64 = y.iter().map(|v| v * v).sum();
        (d / m).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::test_util::*;
    use super::*;

    /// A 4-cycle has no triangle, a 4-cycle with a chord has two, a 3-D
    /// grid none; symmetry is to the bit and in the pattern.
    #[test]
    fn triangles_and_symmetry_of_the_pattern() {
        let ring = |chord: bool| {
            let mut t = vec![(0, 0, 4.0), (1, 1, 4.0), (2, 2, 4.0), (3, 3, 4.0)];
            let mut edges = vec![(0, 1), (1, 2), (2, 3), (0, 3)];
            if chord {
                edges.push((0, 2));
            }
            for (i, j) in edges {
                t.push((i, j, -1.0));
                t.push((j, i, -1.0));
            }
            CsrMatrix::from_triplets(4, &t).unwrap()
        };
        assert!(ring(false).is_triangle_free());
        assert!(!ring(true).is_triangle_free());
        let grid = laplacian(5, 4, 3, 0.1);
        assert!(grid.is_triangle_free() && grid.is_symmetric());
        let mut skew = grid.clone();
        let k = skew.entry_index(7, 6).unwrap();
        skew.values_mut()[k] = skew.values()[k].next_up();
        assert!(!skew.is_symmetric());
        let one_sided =
            CsrMatrix::from_triplets(2, &[(0, 0, 1.0), (1, 1, 1.0), (1, 0, 0.0)]).unwrap();
        assert_eq!(one_sided.max_asymmetry(), 0.0);
        assert!(!one_sided.is_symmetric());
    }

    /// A matrix built with sprs (CSC, row 1 without a diagonal entry)
    /// becomes a [`CsrMatrix`] with the same product as sprs's own and an
    /// explicit zero diagonal; `as_sprs` hands back the same matrix.
    #[test]
    fn sprs_matrices_in_and_out() {
        let mut tri = sprs::TriMatI::<f64, u32>::new((3, 3));
        for &(r, c, v) in &[
            (0, 0, 4.0),
            (0, 1, -1.0),
            (1, 0, -2.0),
            (1, 2, 3.0),
            (2, 2, 5.0),
        ] {
            tri.add_triplet(r, c, v);
        }
        let a = CsrMatrix::try_from(tri.to_csc::<u32>()).unwrap();
        assert_eq!(a.nnz(), 6);
        assert_eq!(a.values()[a.diag_index()[1] as usize], 0.0);
        let x = [1.0, -2.0, 0.5];
        let mut y = [0.0; 3];
        a.mul_vec(&x, &mut y);
        assert_eq!(y, [6.0, -0.5, 2.5]);
        let mut by_sprs = [0.0; 3];
        sprs::prod::mul_acc_mat_vec_csr(a.as_sprs().view(), &x[..], &mut by_sprs[..]);
        assert_eq!(by_sprs, y);
        let wide = sprs::CsMatI::<f64, u32>::zero((2, 3));
        assert!(matches!(
            CsrMatrix::try_from(wide),
            Err(LinearSolverError::DimensionMismatch {
                expected: 2,
                found: 3,
                ..
            })
        ));
    }

    #[test]
    fn from_faces_pattern_and_slots() {
        // 2 × 2 × 1 grid: faces 0-1, 0-2, 1-3, 2-3
        let (own, nei) = grid_faces(2, 2, 1);
        let (a, slots) = CsrMatrix::from_faces(4, &own, &nei);
        assert_eq!(a.n(), 4);
        assert_eq!(a.nnz(), 4 + 2 * own.len());
        for i in 0..4 {
            let (cols, _) = a.row(i);
            assert!(cols.windows(2).all(|w| w[0] < w[1]), "row {i} sorted");
            assert_eq!(a.col_idx()[a.diag_index()[i] as usize] as usize, i);
        }
        for f in 0..own.len() {
            let (o, nb) = (own[f] as usize, nei[f] as usize);
            assert_eq!(a.entry_index(o, nb), Some(slots.upper[f] as usize));
            assert_eq!(a.entry_index(nb, o), Some(slots.lower[f] as usize));
        }
    }

    #[test]
    fn duplicate_faces_share_a_slot() {
        let (a, slots) = CsrMatrix::from_faces(3, &[0, 0, 1], &[1, 1, 2]);
        assert_eq!(a.nnz(), 3 + 4);
        assert_eq!(slots.upper[0], slots.upper[1]);
        assert_eq!(slots.lower[0], slots.lower[1]);
    }

    #[test]
    fn triplets_sum_duplicates_and_mul_vec() {
        let a = CsrMatrix::from_triplets(
            3,
            &[
                (0, 0, 2.0),
                (0, 2, 1.0),
                (0, 2, 1.0),
                (2, 1, -1.0),
                (1, 1, 3.0),
            ],
        )
        .unwrap();
        assert_eq!(a.nnz(), 5); // (0,0) (0,2) (1,1) (2,1) (2,2)
        let mut y = [0.0; 3];
        a.mul_vec(&[1.0, 2.0, 3.0], &mut y);
        assert_eq!(y, [8.0, 6.0, -2.0]);
        assert!(CsrMatrix::from_triplets(2, &[(0, 2, 1.0)]).is_err());
    }

    #[test]
    fn to_faer_matches_mul_vec() {
        let a = convection_diffusion(5, 4, 3, [1.0, -0.5, 0.25]);
        let f = a.to_faer();
        let x = rhs(a.n(), 7);
        let mut y = vec![0.0; a.n()];
        a.mul_vec(&x, &mut y);
        let xm = faer::Mat::from_fn(a.n(), 1, |i, _| x[i]);
        let ym = &f * &xm;
        for (i, yi) in y.iter().enumerate() {
            assert!((ym[(i, 0)] - yi).abs() < 1e-12);
        }
    }

    #[test]
    fn add_entries_keeps_values_and_remaps_slots() {
        let (own, nei) = grid_faces(3, 3, 1);
        let mut a = laplacian(3, 3, 1, 0.1);
        let (_, mut slots) = CsrMatrix::from_faces(9, &own, &nei);
        let before = a.clone();
        let id = a.pattern_id();
        // existing entries only: nothing changes
        let g = a.add_entries(&[(0, 1), (4, 4)]).unwrap();
        assert!(!g.changed());
        assert_eq!(a.pattern_id(), id);
        assert_eq!(
            g.slots,
            vec![a.entry_index(0, 1).unwrap() as u32, a.diag_index()[4]]
        );
        let mut found = Vec::new();
        assert!(a.find_entries(&[(0, 1), (4, 4)], &mut found));
        assert_eq!(found, g.slots);
        assert!(!a.find_entries(&[(0, 1), (0, 8)], &mut found));
        assert!(!a.find_entries(&[(9, 0)], &mut found));
        // new (contact-like) entries, with a repeat and an existing one
        let g = a
            .add_entries(&[(0, 8), (8, 0), (0, 8), (2, 6), (1, 0)])
            .unwrap();
        assert!(g.changed());
        assert_ne!(a.pattern_id(), id);
        assert_eq!(a.nnz(), before.nnz() + 3);
        assert_eq!(g.slots[0], g.slots[2]);
        assert_eq!(g.slots[0] as usize, a.entry_index(0, 8).unwrap());
        assert_eq!(a.values()[g.slots[0] as usize], 0.0);
        assert!(a.find_entries(&[(0, 8), (8, 0), (0, 8), (2, 6), (1, 0)], &mut found));
        assert_eq!(found, g.slots);
        slots.remap(&g);
        for f in 0..own.len() {
            let (o, nb) = (own[f] as usize, nei[f] as usize);
            assert_eq!(a.entry_index(o, nb), Some(slots.upper[f] as usize));
            assert_eq!(a.entry_index(nb, o), Some(slots.lower[f] as usize));
        }
        for i in 0..9 {
            let (cols, _) = a.row(i);
            assert!(cols.windows(2).all(|w| w[0] < w[1]));
            assert_eq!(a.col_idx()[a.diag_index()[i] as usize] as usize, i);
            for j in 0..9 {
                let old = before.entry_index(i, j).map(|k| before.values()[k]);
                let new = a.entry_index(i, j).map(|k| a.values()[k]);
                if let Some(v) = old {
                    assert_eq!(new, Some(v));
                }
            }
        }
        assert!(a.add_entries(&[(9, 0)]).is_err());
    }
}
