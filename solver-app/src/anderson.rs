//! Anderson acceleration of the outer (Picard) iteration — beyond the
//! thesis, whose outer loop is a plain under-relaxed fixed-point iteration
//! u ← u + ω δ(u).
//!
//! Where one slow mode dominates (a slender beam bending against contact,
//! a plastic zone the elastic implicit Laplacian over-stiffens), the plain
//! iteration converges linearly with a factor close to one: the curved-beams
//! benchmark needs 800–4,500 outer iterations per increment at a factor of
//! 0.989–0.999. Anderson's method (Walker & Ni, SIAM J. Numer. Anal. 49,
//! 2011, "type II") replaces the step by the combination of the last `m`
//! iterates that minimises the linearised correction:
//!
//! γ = argmin ‖f_k − ΔF γ‖₂,  x_{k+1} = x_k + β f_k − (ΔX + β ΔF) γ,
//!
//! with f = δ the correction of the linear solve, ΔX and ΔF the differences
//! of successive iterates and corrections, β the under-relaxation. With
//! m = 0 it is the plain iteration. The solver's iterate x is the whole
//! state an outer iteration starts from, cells and boundary faces
//! (`SegregatedSolver::mix_iterates`).
//!
//! Written by hand: a few dot products and an m×m solve on the solver's
//! own stacked vectors; no crate offers it on these types.
//!
//! The correction may be longer than the iterate: its extra entries (the
//! change of the cell gradient, `SegregatedSolver::mix_iterates`) count in
//! the least-squares problem for γ, but their next iterate is not formed
//! here, so neither x nor ΔX holds them.
//!
//! Memory: the history is the one large store of the segregated method
//! (m = 10 columns of ΔX and ΔF: 1.4 kB per cell on a hexahedral mesh,
//! 29 B per iterate and 101 B per correction), so nothing else is kept in
//! full. The caller writes
//! the current iterate and its correction into buffers of the history
//! ([`AndersonAcceleration::current_mut`]), and reads the next iterate
//! from it ([`AndersonAcceleration::next_iterate`]) instead of getting it
//! back in a vector of its own: the new column is formed in place of the
//! previous iterate, the column it replaces becomes the next buffer, and
//! m + 1 vectors per side suffice (m + 2 with separate iterate buffers).
//! Buffers are allocated as the history first fills (a run that
//! converges in a few iterations never holds m columns); after that a
//! step allocates nothing. Between increments their pages go back to the
//! system ([`AndersonAcceleration::release_pages`]), so that the field
//! output does not come on top of them.
use std::ops::Range;

use fv_mesh::Vector;

/// Columns of an ill-conditioned history are dropped (oldest first) while
/// a pivot of the scaled normal equations falls below this.
const PIVOT_FLOOR: f64 = 1e-10;

/// The history is cleared when the correction grows by more than this
/// factor over the smallest since the last restart (the iterate left the
/// region where the stored differences describe the map, e.g. the contact
/// set changed).
const RESTART_GROWTH: f64 = 2.0;

/// Anderson mixing of depth `m` over stacked cell vectors.
#[derive(Debug, Clone)]
pub struct AndersonAcceleration {
    depth: usize,
    /// Lengths of the stacked iterate x and of the correction f (f's first
    /// `n_x` entries go with x's).
    n_x: usize,
    n_f: usize,
    /// Differences of successive iterates, ring of `depth` columns (a slot
    /// is empty until first used, or while its buffer is lent out as
    /// `x`).
    dx: Vec<Vec<Vector>>,
    /// Differences of successive corrections, same ring.
    df: Vec<Vec<Vector>>,
    /// The current iterate and correction, written by the caller
    /// ([`Self::current_mut`]); after a step, a spare buffer or none.
    x: Vec<Vector>,
    f: Vec<Vector>,
    /// The iterate and correction of the last step.
    x_prev: Vec<Vector>,
    f_prev: Vec<Vector>,
    has_prev: bool,
    /// Valid columns, and the ring slot the next one goes to.
    count: usize,
    next: usize,
    /// Gram matrix ΔFᵀΔF by ring slot (depth × depth, row-major).
    gram: Vec<f64>,
    /// Workspaces of the small solve.
    rhs: Vec<f64>,
    gamma: Vec<f64>,
    chol: Vec<f64>,
    smallest_correction: f64,
    /// Under-relaxation of the last step.
    beta: f64,
}

impl AndersonAcceleration {
    /// History of `depth` columns for iterates of `n_x` and corrections
    /// of `n_f ≥ n_x` cell vectors (allocated as it fills). `depth` is
    /// capped at [`MAX_DEPTH`].
    pub fn new(n_x: usize, n_f: usize, depth: usize) -> Self {
        assert!(n_f >= n_x, "Anderson: correction shorter than the iterate");
        let depth = depth.min(MAX_DEPTH);
        Self {
            depth,
            n_x,
            n_f,
            dx: vec![Vec::new(); depth],
            df: vec![Vec::new(); depth],
            x: Vec::new(),
            f: Vec::new(),
            x_prev: Vec::new(),
            f_prev: Vec::new(),
            has_prev: false,
            count: 0,
            next: 0,
            gram: vec![0.0; depth * depth],
            rhs: vec![0.0; depth],
            gamma: vec![0.0; depth],
            chol: vec![0.0; depth * depth],
            smallest_correction: f64::INFINITY,
            beta: 0.0,
        }
    }

    /// Forgets the history (a new increment, or a changed map).
    pub fn restart(&mut self) {
        self.has_prev = false;
        self.count = 0;
        self.next = 0;
        self.smallest_correction = f64::INFINITY;
    }

    /// Forgets the history and returns its buffers' pages to the system
    /// (they are resident again as the next increment's history fills,
    /// without new allocations): 2 m + 2 columns of the mixed state, 26 MB
    /// each at 64³, that would otherwise stay resident through the field
    /// output.
    pub fn release_pages(&mut self) {
        self.restart();
        for v in self.dx.iter_mut().chain(self.df.iter_mut()).chain([
            &mut self.x,
            &mut self.f,
            &mut self.x_prev,
            &mut self.f_prev,
        ]) {
            fv_nonlinear::vector_ops::release_pages(flat(v));
        }
    }

    /// Columns in use (for tests and diagnostics).
    pub fn columns(&self) -> usize {
        self.count
    }

    /// The buffers of the current iterate x and its correction f, for the
    /// caller to fill before [`Self::step`] (their contents on return are
    /// unspecified). A buffer comes from a column out of use, or from the
    /// oldest column of a full history, which the coming step replaces
    /// anyway (it leaves the valid set now, so that a step that never
    /// comes cannot read it); only while the history first fills is one
    /// allocated.
    pub fn current_mut(&mut self) -> (&mut [Vector], &mut [Vector]) {
        if self.x.len() != self.n_x {
            self.x = self.free_buffer(true);
        }
        if self.f.len() != self.n_f {
            self.f = self.free_buffer(false);
        }
        (&mut self.x, &mut self.f)
    }

    /// A buffer from the ΔX (`dx`, of length `n_x`) or ΔF ring (`n_f`).
    fn free_buffer(&mut self, dx: bool) -> Vec<Vector> {
        let n = if dx { self.n_x } else { self.n_f };
        if self.has_prev && self.count == self.depth && self.depth > 0 {
            // the oldest column, which the next step overwrites
            let ring = if dx { &mut self.dx } else { &mut self.df };
            if ring[self.next].len() == n {
                let b = std::mem::take(&mut ring[self.next]);
                // both of its halves leave the valid set together
                if !dx || self.df[self.next].len() != self.n_f {
                    self.count -= 1;
                }
                return b;
            }
        }
        let unused = (0..self.depth).find(|&j| {
            let ring = if dx { &self.dx } else { &self.df };
            !self.is_valid(j) && ring[j].len() == n
        });
        let ring = if dx { &mut self.dx } else { &mut self.df };
        match unused {
            Some(j) => std::mem::take(&mut ring[j]),
            None => vec![Vector::zeros(); n],
        }
    }

    /// Takes the step from the current iterate ([`Self::current_mut`])
    /// with the under-relaxation `beta`; the next iterate is then read
    /// with [`Self::next_iterate`].
    pub fn step(&mut self, beta: f64) {
        assert!(
            self.x.len() == self.n_x && self.f.len() == self.n_f,
            "Anderson step without a current iterate"
        );
        self.beta = beta;
        if self.depth == 0 {
            self.count = 0;
            std::mem::swap(&mut self.x, &mut self.x_prev);
            std::mem::swap(&mut self.f, &mut self.f_prev);
            return;
        }
        let norm_f = dot(&self.f, &self.f).sqrt();
        if norm_f > RESTART_GROWTH * self.smallest_correction {
            self.restart();
        }
        self.smallest_correction = self.smallest_correction.min(norm_f);
        let new_column = if self.has_prev {
            let s = self.next;
            // ΔX and ΔF in place of the previous iterate, which then
            // becomes the column of slot s
            let (n_x, n_f) = (self.n_x, self.n_f);
            let (xp, fp) = (&mut self.x_prev[..], &mut self.f_prev[..n_f]);
            let (x, f) = (&self.x[..], &self.f[..n_f]);
            if n_x >= PARALLEL_LEN && two_threads() {
                let h = n_x / 2;
                let (xp0, xp1) = xp.split_at_mut(h);
                let (fp0, fp1) = fp.split_at_mut(h);
                rayon::join(
                    || differences(xp0, fp0, &x[..h], &f[..h]),
                    || differences(xp1, fp1, &x[h..], &f[h..]),
                );
            } else {
                differences(xp, fp, x, f);
            }
            std::mem::swap(&mut self.dx[s], &mut self.x_prev);
            std::mem::swap(&mut self.df[s], &mut self.f_prev);
            // a replaced column whose buffer was not lent out
            if self.count == self.depth {
                self.count -= 1;
            }
            self.count = (self.count + 1).min(self.depth);
            self.next = (self.next + 1) % self.depth;
            Some(s)
        } else {
            None
        };
        // the current iterate is the next step's previous one; the buffers
        // x_prev held (the replaced column, or nothing) become the next
        // current ones
        std::mem::swap(&mut self.x, &mut self.x_prev);
        std::mem::swap(&mut self.f, &mut self.f_prev);
        self.has_prev = true;
        let f = &self.f_prev;
        // the new column's Gram row and the right-hand side ΔFᵀf: one pass
        // over the new column and f for every GRAM_GROUP stored columns
        let Some(s) = new_column else {
            for j in 0..self.depth {
                self.rhs[j] = if self.is_valid(j) {
                    dot(&self.df[j], f)
                } else {
                    0.0
                };
            }
            return self.solve_trimmed();
        };
        let mut valid = [0usize; MAX_DEPTH];
        let mut k = 0;
        for j in 0..self.depth {
            if self.is_valid(j) {
                valid[k] = j;
                k += 1;
            } else {
                self.rhs[j] = 0.0;
            }
        }
        for group in valid[..k].chunks(GRAM_GROUP) {
            let empty: &[Vector] = &[];
            let mut cols = [empty; GRAM_GROUP];
            for (c, &j) in group.iter().enumerate() {
                cols[c] = &self.df[j];
            }
            let sums = dot_pairs_split(&cols[..group.len()], &self.df[s], f);
            for (&j, &(g, r)) in group.iter().zip(&sums) {
                self.gram[s * self.depth + j] = g;
                self.gram[j * self.depth + s] = g;
                self.rhs[j] = r;
            }
        }
        self.solve_trimmed();
    }

    /// Solves the normal equations of the last step, dropping the oldest
    /// columns while they are too dependent ([`PIVOT_FLOOR`]).
    fn solve_trimmed(&mut self) {
        while self.count > 0 && !self.solve_normal_equations() {
            // drop the oldest column
            let oldest = (self.next + self.depth - self.count) % self.depth;
            self.rhs[oldest] = 0.0;
            self.count -= 1;
        }
        if self.count == 0 {
            self.gamma.iter_mut().for_each(|g| *g = 0.0);
        }
    }

    /// Entries `range` of the next iterate, x + β f − (ΔX + β ΔF) γ of the
    /// last [`Self::step`], written to `out` (of the range's length):
    /// `range` of x and ΔX with the entries of f and ΔF from `f_start`.
    ///
    /// Works on the entries as flat `f64`s, with the operations and their
    /// order of `x + β f` followed by one column at a time (the same bits
    /// as the vector form), the columns taken [`MIX_GROUP`] at a time in
    /// one pass each over `out` (one pass in all at the capped depth 3).
    pub fn next_iterate(&self, range: Range<usize>, f_start: usize, out: &mut [Vector]) {
        self.mix(range, f_start, self.beta, out);
    }

    /// [`Self::next_iterate`] without the correction: x − ΔX γ, the
    /// combination Σ α_k x_k of the stored iterates themselves (the cells
    /// whose gradient goes with the next iterate's boundary values).
    pub fn next_iterate_uncorrected(&self, range: Range<usize>, out: &mut [Vector]) {
        self.mix(range, 0, 0.0, out);
    }

    fn mix(&self, range: Range<usize>, f_start: usize, beta: f64, out: &mut [Vector]) {
        assert_eq!(
            out.len(),
            range.len(),
            "Anderson: output of the wrong length"
        );
        let f_range = f_start..f_start + range.len();
        let empty: &[Vector] = &[];
        let mut cols = [(0.0, empty, empty); MAX_DEPTH];
        let mut k = 0;
        for j in 0..self.depth {
            if self.is_valid(j) && self.gamma[j] != 0.0 {
                cols[k] = (
                    self.gamma[j],
                    &self.dx[j][range.clone()],
                    &self.df[j][f_range.clone()],
                );
                k += 1;
            }
        }
        let out = flat(out);
        let x = flat_ref(&self.x_prev[range.clone()]);
        let f = flat_ref(&self.f_prev[f_range]);
        let cols = &cols[..k];
        if out.len() >= 3 * PARALLEL_LEN && two_threads() {
            // the same operations on every entry, in halves
            let h = range.len() / 2;
            let (out0, out1) = out.split_at_mut(3 * h);
            let (mut c0, mut c1) = (
                [(0.0, empty, empty); MAX_DEPTH],
                [(0.0, empty, empty); MAX_DEPTH],
            );
            for ((p0, p1), &(g, dx, df)) in c0.iter_mut().zip(c1.iter_mut()).zip(cols) {
                let ((dx0, dx1), (df0, df1)) = (dx.split_at(h), df.split_at(h));
                (*p0, *p1) = ((g, dx0, df0), (g, dx1, df1));
            }
            rayon::join(
                || mix_groups(out0, &x[..3 * h], &f[..3 * h], beta, &c0[..k]),
                || mix_groups(out1, &x[3 * h..], &f[3 * h..], beta, &c1[..k]),
            );
        } else {
            mix_groups(out, x, f, beta, cols);
        }
    }

    /// [`Self::current_mut`], [`Self::step`] and [`Self::next_iterate`]
    /// on vectors of the caller's (tests).
    #[cfg(test)]
    fn step_vectors(&mut self, x: &mut [Vector], f: &[Vector], beta: f64) {
        let (xc, fc) = self.current_mut();
        xc.copy_from_slice(x);
        fc.copy_from_slice(f);
        self.step(beta);
        self.next_iterate(0..x.len(), 0, x);
    }

    /// Whether ring slot `j` holds one of the `count` newest columns.
    fn is_valid(&self, j: usize) -> bool {
        let age = (self.next + self.depth - 1 - j) % self.depth;
        age < self.count
    }

    /// Solves ΔFᵀΔF γ = ΔFᵀ f over the valid slots by a Cholesky
    /// factorisation of the diagonally scaled matrix; false when a pivot
    /// falls below [`PIVOT_FLOOR`] (the history is nearly dependent).
    fn solve_normal_equations(&mut self) -> bool {
        let m = self.depth;
        // the valid slots, oldest first: walk the ring
        let first = (self.next + m - self.count) % m;
        let k = self.count;
        let slot = |i: usize| (first + i) % m;
        let scale = |s: usize, gram: &[f64]| gram[s * m + s].sqrt();
        if (0..k).any(|i| !(scale(slot(i), &self.gram) > 0.0)) {
            return false; // a zero difference column (the map did not change)
        }
        // scaled matrix into chol (k × k, row-major)
        for i in 0..k {
            for j in 0..k {
                let (si, sj) = (slot(i), slot(j));
                self.chol[i * m + j] =
                    self.gram[si * m + sj] / (scale(si, &self.gram) * scale(sj, &self.gram));
            }
        }
        for i in 0..k {
            for j in 0..=i {
                let mut s = self.chol[i * m + j];
                for p in 0..j {
                    s -= self.chol[i * m + p] * self.chol[j * m + p];
                }
                if i == j {
                    if !(s >= PIVOT_FLOOR) {
                        return false;
                    }
                    self.chol[i * m + i] = s.sqrt();
                } else {
                    self.chol[i * m + j] = s / self.chol[j * m + j];
                }
            }
        }
        // forward and back substitution on the scaled right-hand side
        let mut y = [0.0; MAX_DEPTH];
        for i in 0..k {
            let si = slot(i);
            let mut s = self.rhs[si] / scale(si, &self.gram);
            for (p, yp) in y.iter().enumerate().take(i) {
                s -= self.chol[i * m + p] * yp;
            }
            y[i] = s / self.chol[i * m + i];
        }
        for i in (0..k).rev() {
            let mut s = y[i];
            for (p, yp) in y.iter().enumerate().take(k).skip(i + 1) {
                s -= self.chol[p * m + i] * yp;
            }
            y[i] = s / self.chol[i * m + i];
        }
        self.gamma.iter_mut().for_each(|g| *g = 0.0);
        for (i, yi) in y.iter().enumerate().take(k) {
            let si = slot(i);
            self.gamma[si] = yi / scale(si, &self.gram);
        }
        true
    }
}

/// Largest history depth accepted.
pub const MAX_DEPTH: usize = 20;

// a Vector is three f64s, laid out as [f64; 3] (nalgebra's Matrix is
// repr(C) around its repr(transparent) ArrayStorage)
const _: () = assert!(
    std::mem::size_of::<Vector>() == 3 * std::mem::size_of::<f64>()
        && std::mem::align_of::<Vector>() == std::mem::align_of::<f64>()
);

/// The entries of `v`, three per vector.
fn flat(v: &mut [Vector]) -> &mut [f64] {
    // SAFETY: a Vector is three f64s without padding (asserted above),
    // so `v` is 3 len() f64s, borrowed mutably for the returned lifetime
    unsafe { std::slice::from_raw_parts_mut(v.as_mut_ptr().cast::<f64>(), 3 * v.len()) }
}

/// The entries of `v`, three per vector (read-only).
fn flat_ref(v: &[Vector]) -> &[f64] {
    // SAFETY: as in `flat`, borrowed immutably
    unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<f64>(), 3 * v.len()) }
}

/// Vectors (of [`Vector`]s) of at least this many entries are taken in two
/// halves on two threads when the pool has two or more: the passes over
/// the iterates and the history (the mix, the differences, the dot
/// products). The mix and the differences are the same to the bit; the
/// dot products are summed in two parts.
const PARALLEL_LEN: usize = 32_768;

/// Whether the pool has two threads or more.
fn two_threads() -> bool {
    rayon::current_num_threads() >= 2
}

/// ΔX = x − x_prev and ΔF = f − f_prev in place of the previous iterate
/// and correction (`fp` and `f` longer than `xp` and `x`: the
/// correction's entries beyond the iterate, the gradient's change).
fn differences(xp: &mut [Vector], fp: &mut [Vector], x: &[Vector], f: &[Vector]) {
    for ((xp, fp), (xi, fi)) in xp.iter_mut().zip(fp.iter_mut()).zip(x.iter().zip(f)) {
        *xp = xi - *xp;
        *fp = fi - *fp;
    }
    let n_x = xp.len();
    for (fp, fi) in fp[n_x..].iter_mut().zip(&f[n_x..]) {
        *fp = fi - *fp;
    }
}

/// `out = x + β f − Σ γ (Δx + β Δf)` over the flat entries, the columns
/// [`MIX_GROUP`] at a time in one pass each.
fn mix_groups(
    out: &mut [f64],
    x: &[f64],
    f: &[f64],
    beta: f64,
    cols: &[(f64, &[Vector], &[Vector])],
) {
    let mut groups = cols.chunks(MIX_GROUP);
    let first = groups.next().unwrap_or(&[]);
    mix_columns(out, Some((x, f)), beta, first);
    for group in groups {
        mix_columns(out, None, beta, group);
    }
}

/// Columns of the history applied in one pass of [`mix_columns`].
const MIX_GROUP: usize = 3;

/// One pass of [`AndersonAcceleration::next_iterate`] over the flat
/// entries: `out = x + β f` first when `start` gives `(x, f)`, then
/// `out −= γ (Δx + β Δf)` for each of `cols` (at most [`MIX_GROUP`]), in
/// that order for every entry. Written as zipped iterators so that the
/// compiler vectorises it without bounds checks.
fn mix_columns(
    out: &mut [f64],
    start: Option<(&[f64], &[f64])>,
    beta: f64,
    cols: &[(f64, &[Vector], &[Vector])],
) {
    let n = out.len();
    let col = |c: usize| -> (f64, &[f64], &[f64]) {
        cols.get(c).map_or((0.0, &[][..], &[][..]), |&(g, x, f)| {
            (g, &flat_ref(x)[..n], &flat_ref(f)[..n])
        })
    };
    let (g0, x0, f0) = col(0);
    let (g1, x1, f1) = col(1);
    let (g2, x2, f2) = col(2);
    let step = |xi: &mut f64, g: f64, dx: f64, df: f64| *xi -= g * (dx + beta * df);
    let Some((x, f)) = start else {
        for &(g, dx, df) in cols.iter().take(MIX_GROUP) {
            for ((o, &a), &b) in out.iter_mut().zip(flat_ref(dx)).zip(flat_ref(df)) {
                step(o, g, a, b);
            }
        }
        return;
    };
    let (x, f) = (&x[..n], &f[..n]);
    let first = |x: f64, f: f64| {
        let mut xi = x;
        xi += beta * f;
        xi
    };
    let base = out.iter_mut().zip(x).zip(f);
    match cols.len() {
        0 => base.for_each(|((o, &x), &f)| *o = first(x, f)),
        1 => base
            .zip(x0.iter().zip(f0))
            .for_each(|(((o, &x), &f), (&a0, &b0))| {
                let mut xi = first(x, f);
                step(&mut xi, g0, a0, b0);
                *o = xi;
            }),
        2 => base.zip(x0.iter().zip(f0)).zip(x1.iter().zip(f1)).for_each(
            |((((o, &x), &f), (&a0, &b0)), (&a1, &b1))| {
                let mut xi = first(x, f);
                step(&mut xi, g0, a0, b0);
                step(&mut xi, g1, a1, b1);
                *o = xi;
            },
        ),
        _ => base
            .zip(x0.iter().zip(f0))
            .zip(x1.iter().zip(f1))
            .zip(x2.iter().zip(f2))
            .for_each(|(((((o, &x), &f), (&a0, &b0)), (&a1, &b1)), (&a2, &b2))| {
                let mut xi = first(x, f);
                step(&mut xi, g0, a0, b0);
                step(&mut xi, g1, a1, b1);
                step(&mut xi, g2, a2, b2);
                *o = xi;
            }),
    }
}

fn dot(a: &[Vector], b: &[Vector]) -> f64 {
    if a.len() >= PARALLEL_LEN && two_threads() {
        let h = a.len() / 2;
        let (s0, s1) = rayon::join(|| dot_of(&a[..h], &b[..h]), || dot_of(&a[h..], &b[h..]));
        s0 + s1
    } else {
        dot_of(a, b)
    }
}

fn dot_of(a: &[Vector], b: &[Vector]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x.dot(y)).sum()
}

/// [`dot_pairs`], in two halves on two threads for long vectors.
fn dot_pairs_split(cols: &[&[Vector]], b: &[Vector], c: &[Vector]) -> [(f64, f64); GRAM_GROUP] {
    let n = b.len();
    if n < PARALLEL_LEN || !two_threads() {
        return dot_pairs(cols, b, c);
    }
    let h = n / 2;
    let empty: &[Vector] = &[];
    let (mut lo, mut hi) = ([empty; GRAM_GROUP], [empty; GRAM_GROUP]);
    for ((l, u), a) in lo.iter_mut().zip(hi.iter_mut()).zip(cols) {
        (*l, *u) = a.split_at(h);
    }
    let k = cols.len();
    let (s0, s1) = rayon::join(
        || dot_pairs(&lo[..k], &b[..h], &c[..h]),
        || dot_pairs(&hi[..k], &b[h..], &c[h..]),
    );
    std::array::from_fn(|j| (s0[j].0 + s1[j].0, s0[j].1 + s1[j].1))
}

/// Stored columns whose Gram entries and ΔFᵀf one pass of [`dot_pairs`] forms.
const GRAM_GROUP: usize = 3;

/// (a·b, a·c) for every a of `cols` (at most [`GRAM_GROUP`]) in one pass
/// over b and c; each sum accumulated in index order, as a pass per a
/// would.
fn dot_pairs(cols: &[&[Vector]], b: &[Vector], c: &[Vector]) -> [(f64, f64); GRAM_GROUP] {
    let mut sums = [(0.0, 0.0); GRAM_GROUP];
    let n = b.len();
    assert!(
        c.len() == n && cols.iter().all(|a| a.len() == n),
        "Anderson: column lengths"
    );
    let bc = b.iter().zip(c);
    let add = |s: &mut (f64, f64), x: &Vector, y: &Vector, z: &Vector| {
        s.0 += x.dot(y);
        s.1 += x.dot(z);
    };
    let [s0, s1, s2] = &mut sums;
    match *cols {
        [a0] => bc.zip(a0).for_each(|((y, z), x0)| add(s0, x0, y, z)),
        [a0, a1] => bc.zip(a0.iter().zip(a1)).for_each(|((y, z), (x0, x1))| {
            add(s0, x0, y, z);
            add(s1, x1, y, z);
        }),
        [a0, a1, a2] => bc
            .zip(a0.iter().zip(a1).zip(a2))
            .for_each(|((y, z), ((x0, x1), x2))| {
                add(s0, x0, y, z);
                add(s1, x1, y, z);
                add(s2, x2, y, z);
            }),
        _ => {}
    }
    sums
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fixed-point map x ← x + (b − A x)/d of a diagonally dominant
    /// 3×3 system per cell (Jacobi), which converges slowly; Anderson
    /// reaches the solution in a few steps, the plain iteration does not.
    fn jacobi_iterations(depth: usize) -> usize {
        let n = 4;
        let a = nalgebra::Matrix3::new(1.0, 0.45, 0.0, 0.45, 1.0, 0.45, 0.0, 0.45, 1.0);
        let b = Vector::new(1.0, 2.0, 3.0);
        let exact = a.lu().solve(&b).unwrap();
        let mut x = vec![Vector::zeros(); n];
        let mut f = vec![Vector::zeros(); n];
        let mut aa = AndersonAcceleration::new(n, n, depth);
        for k in 1..=2000 {
            for (fi, xi) in f.iter_mut().zip(&x) {
                *fi = b - a * xi;
            }
            if f.iter().all(|fi| fi.norm() < 1e-12) {
                assert!(x.iter().all(|xi| (xi - exact).norm() < 1e-10));
                return k;
            }
            aa.step_vectors(&mut x, &f, 1.0);
        }
        usize::MAX
    }

    #[test]
    fn anderson_solves_a_linear_fixed_point_in_few_steps() {
        let plain = jacobi_iterations(0);
        let anderson = jacobi_iterations(5);
        // the Jacobi map of a 3×3 system: spectral radius 0.636, so the
        // plain iteration needs ~60 steps; Anderson with m ≥ 3 is exact
        // (up to round-off) after m + 1 steps (GMRES equivalence)
        assert!((50..80).contains(&plain), "plain {plain}");
        assert!(anderson <= 8, "anderson {anderson}");
    }

    #[test]
    fn dependent_history_is_trimmed_not_failed() {
        // a map whose corrections repeat exactly: ΔF has equal columns
        let mut aa = AndersonAcceleration::new(2, 2, 4);
        let mut x = vec![Vector::zeros(); 2];
        let f = vec![Vector::new(1.0, 0.0, 0.0); 2];
        for _ in 0..6 {
            aa.step_vectors(&mut x, &f, 0.5);
            assert!(x.iter().all(|v| v.iter().all(|c| c.is_finite())));
        }
        assert!(aa.columns() <= 1);
    }

    /// A state of cells x and a derived field y = L x formed from the
    /// cells before their correction, as the solver's cell gradient is
    /// (`SegregatedSolver::mix_iterates`): x ← x + β (b − A x − C y),
    /// y ← L x. Mixed over the whole state (x, y), or with y only in the
    /// correction and its next iterate L (Σ α_k x_k) formed from the
    /// uncorrected mix: the same iterates (to round-off), to the same
    /// fixed point. Returns the two trajectories' largest relative
    /// difference and the full run's distance from the fixed point.
    fn derived_field_runs() -> (f64, f64) {
        let n = 4;
        let a = nalgebra::Matrix3::new(1.0, 0.45, 0.0, 0.45, 1.0, 0.45, 0.0, 0.45, 1.0);
        let c = nalgebra::Matrix3::new(0.2, 0.0, 0.1, 0.0, -0.1, 0.0, 0.1, 0.0, 0.3);
        let l = nalgebra::Matrix3::new(1.0, 0.5, 0.0, -0.5, 1.0, 0.25, 0.0, 0.0, 2.0);
        let b = |i: usize| Vector::new(1.0, 2.0 - i as f64, 3.0);
        let beta = 0.8;
        let correction = |x: &[Vector], y: &[Vector], i: usize| b(i) - a * x[i] - c * y[i];
        // the whole state: x, then y
        let mut full = AndersonAcceleration::new(2 * n, 2 * n, 3);
        let mut state = vec![Vector::zeros(); 2 * n];
        // y in the correction only
        let mut short = AndersonAcceleration::new(n, 2 * n, 3);
        let (mut x, mut y) = (vec![Vector::zeros(); n], vec![Vector::zeros(); n]);
        let mut worst: f64 = 0.0;
        for _ in 0..40 {
            let (sx, sy) = state.split_at(n);
            let f: Vec<Vector> = (0..n)
                .map(|i| correction(sx, sy, i))
                .chain((0..n).map(|i| (l * sx[i] - sy[i]) / beta))
                .collect();
            full.step_vectors(&mut state, &f, beta);
            let (xc, fc) = short.current_mut();
            xc.copy_from_slice(&x);
            for i in 0..n {
                fc[i] = correction(&x, &y, i);
                fc[n + i] = (l * x[i] - y[i]) / beta;
            }
            short.step(beta);
            short.next_iterate_uncorrected(0..n, &mut y);
            for yi in y.iter_mut() {
                *yi = l * *yi;
            }
            short.next_iterate(0..n, 0, &mut x);
            for (s, v) in state.iter().zip(x.iter().chain(&y)) {
                worst = worst.max((s - v).norm() / s.norm().max(1e-300));
            }
        }
        // the fixed point: (A + C L) x = b
        let fixed = (a + c * l).lu();
        let distance = (0..n)
            .map(|i| (state[i] - fixed.solve(&b(i)).unwrap()).norm())
            .fold(0.0, f64::max);
        (worst, distance)
    }

    #[test]
    fn derived_field_mixed_from_the_uncorrected_cells_as_over_the_whole_state() {
        let (worst, distance) = derived_field_runs();
        assert!(worst < 1e-12, "trajectories differ by {worst:e}");
        assert!(distance < 1e-10, "fixed point missed by {distance:e}");
    }
}
