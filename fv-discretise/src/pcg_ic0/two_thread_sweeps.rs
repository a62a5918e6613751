//! One PCG solve shared by two threads with the sequential IC(0)'s own
//! sweeps (DIC storage), rows dealt out in chunks.
//!
//! The rows are cut into chunks of `s ≥ b/2` rows (`b` the matrix's
//! bandwidth, `max |i − j|` over its entries; one grid plane of the box,
//! `s` half a plane), dealt out alternately: chunk `c` is thread `c mod 2`'s.
//! Row `i` of chunk `c` reads rows `i − b … i + b`, so chunks `c − 2 … c + 2`:
//! in the sweeps only chunk `c ∓ 1` is the other thread's. Each thread
//! sweeps its own rows in the sequential order (forward ascending, backward
//! descending) and, before a row that reads a row of the other thread,
//! waits until the other thread has published that it is done (an atomic
//! progress counter, written every [`PUBLISH_ROWS`] rows and at the end of
//! a chunk, read only when the cached value falls short). No row waits for
//! a later one, so the two threads cannot wait for each other. On the
//! box's lexicographic order the leading thread never waits (a half-plane
//! reads only the plane below, its own, and its own lower half) and the
//! other trails it by one chunk.
//!
//! Every `w`, `z`, `p` and `x` entry is the one the sequential sweep forms,
//! to the bit (the same products summed in the same order); `q = A p` is
//! formed row by row (a gather, after both threads' `p` of the rows around
//! a chunk are final, chunk by chunk) and the sums `pᵀq`, `‖r‖²` and `rᵀz`
//! in two partial sums, so these differ from the sequential ones by
//! round-off: the same preconditioner, the same iteration up to
//! round-off.
//!
//! An iteration is the sequential one (see [`super`]) with two joins: the
//! backward passes (sweep, `x += α p`, `p = z + β p`, `q = A p` trailing by
//! two chunks, `pᵀq`) of both threads, then their forward passes (`r −= α q`,
//! `‖r‖²`, sweep, `rᵀz`). The initial residual and the final `x += α p`
//! are split in halves. The solve runs inside the thread pool
//! (`rayon::scope`), whose second worker takes the join's second half; it
//! is used only from outside the pool (a solve already on a worker, beside
//! other solves, is the sequential one, so that the second half never waits
//! behind the first on one worker), and by one solve at a time ([`claim`]:
//! two callers outside the pool, such as tests run side by side, would
//! otherwise each hold a worker waiting for a second half queued behind
//! it). Allocates nothing.

use super::{PcgParams, PcgWork};
use crate::csr::{CsrMatrix, TriCsr};
use crate::linear_solver::{check_len, LinearSolverError, SolveInfo};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Systems of at least this many rows are solved by two threads at once
/// when the pool has two or more.
pub(crate) const TWO_THREAD_ROWS: usize = 32_768;
/// At least this many chunks per thread (below, the trailing thread's last
/// chunk is too large a share).
const MIN_CHUNKS_PER_THREAD: usize = 8;
/// A thread publishes its progress after this many rows (and at the end of
/// each chunk).
const PUBLISH_ROWS: usize = 256;
/// Spins before a waiting thread yields its core.
const SPINS_BEFORE_YIELD: u32 = 64;

/// Whether a solve shared by two threads is under way (in this process).
static SHARED_SOLVE: AtomicBool = AtomicBool::new(false);

/// The right to share a solve between two threads, until dropped.
pub(crate) struct Claim(());

impl Drop for Claim {
    fn drop(&mut self) {
        SHARED_SOLVE.store(false, Ordering::Release);
    }
}

/// The right to share a solve between two threads, or `None` while
/// another shared solve is under way (that caller then solves alone).
pub(crate) fn claim() -> Option<Claim> {
    let free = SHARED_SOLVE
        .compare_exchange(false, true, Ordering::Acquire, Ordering::Relaxed)
        .is_ok();
    // (not `then_some`: a Claim made and dropped here releases the holder's)
    if free {
        Some(Claim(()))
    } else {
        None
    }
}

/// The chunking of a pattern for the two threads' sweeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TwoThreadSweeps {
    /// Rows.
    n: usize,
    /// Rows per chunk, at least half the bandwidth.
    chunk: usize,
}

impl TwoThreadSweeps {
    /// The chunking for `a`'s pattern, or `None` when its bandwidth leaves
    /// fewer than [`MIN_CHUNKS_PER_THREAD`] chunks per thread.
    pub(crate) fn for_matrix(a: &CsrMatrix) -> Option<Self> {
        let n = a.n();
        let bandwidth = (0..n).map(|i| i - a.min_col(i)).max().unwrap_or(0);
        let chunk = bandwidth.div_ceil(2).max(1);
        (n.div_ceil(chunk) >= 2 * MIN_CHUNKS_PER_THREAD).then_some(TwoThreadSweeps { n, chunk })
    }

    fn chunks(&self) -> usize {
        self.n.div_ceil(self.chunk)
    }

    /// First row of chunk `c` (`n` past the last).
    fn start(&self, c: usize) -> usize {
        (c * self.chunk).min(self.n)
    }
}

/// A progress counter on its own cache line.
#[repr(align(128))]
struct Progress(AtomicUsize);

/// A vector both threads read and write, each only its own rows, and reads
/// the other's rows only after the other has published them.
#[derive(Clone, Copy)]
struct Shared {
    ptr: *mut f64,
    len: usize,
}

// SAFETY: the threads write disjoint rows (their own chunks) and read a row
// of the other thread only after an acquire load has seen the release store
// the other made after writing it (see `Shared`'s users).
unsafe impl Send for Shared {}
// SAFETY: as for Send.
unsafe impl Sync for Shared {}

impl Shared {
    fn new(v: &mut [f64]) -> Self {
        Shared {
            ptr: v.as_mut_ptr(),
            len: v.len(),
        }
    }

    /// # Safety
    /// Row `i` is this thread's or published by the other.
    #[inline(always)]
    unsafe fn get(self, i: usize) -> f64 {
        assert!(i < self.len);
        // SAFETY: in bounds; no concurrent write (the caller's contract).
        unsafe { self.ptr.add(i).read() }
    }

    /// # Safety
    /// Row `i` is this thread's.
    #[inline(always)]
    unsafe fn set(self, i: usize, v: f64) {
        assert!(i < self.len);
        // SAFETY: in bounds; only this thread accesses its rows now.
        unsafe { self.ptr.add(i).write(v) }
    }
}

/// Waits until `other`'s counter satisfies `done` (cached in `seen`).
#[inline]
fn wait_for(other: &Progress, seen: &mut usize, done: impl Fn(usize) -> bool) {
    let mut spins = 0;
    while !done(*seen) {
        if spins < SPINS_BEFORE_YIELD {
            std::hint::spin_loop();
            spins += 1;
        } else {
            std::thread::yield_now();
        }
        *seen = other.0.load(Ordering::Acquire);
    }
}

/// The matrix, factor and vectors of one pass.
#[derive(Clone, Copy)]
struct Pass<'a> {
    sweeps: TwoThreadSweeps,
    a: &'a CsrMatrix,
    lower: &'a TriCsr,
    inv_diag: &'a [f64],
    progress: &'a [Progress; 2],
}

/// IC(0)-PCG of `a x = b` on two threads (see the module documentation)
/// with the DIC factor's `D̃⁻¹` `inv_diag` and `A`'s strict lower triangle
/// `lower`; `x` is the initial guess. `_claim`: no other shared solve
/// runs meanwhile.
#[allow(clippy::too_many_arguments)]
pub(crate) fn pcg_two_threads(
    _claim: &Claim,
    sweeps: TwoThreadSweeps,
    lower: &TriCsr,
    inv_diag: &[f64],
    a: &CsrMatrix,
    b: &[f64],
    x: &mut [f64],
    params: &PcgParams,
    work: &mut PcgWork,
) -> Result<SolveInfo, LinearSolverError> {
    let n = sweeps.n;
    check_len("matrix", a.n(), n)?;
    check_len("b", b.len(), n)?;
    check_len("x", x.len(), n)?;
    check_len("factor", inv_diag.len(), n)?;
    let progress = [Progress(AtomicUsize::new(0)), Progress(AtomicUsize::new(0))];
    let pass = Pass {
        sweeps,
        a,
        lower,
        inv_diag,
        progress: &progress,
    };
    rayon::scope(|_| iterate(pass, b, x, params, work))
}

/// The iteration of [`pcg_two_threads`], on a worker of the pool.
fn iterate(
    pass: Pass<'_>,
    b: &[f64],
    x: &mut [f64],
    params: &PcgParams,
    work: &mut PcgWork,
) -> Result<SolveInfo, LinearSolverError> {
    let (a, h) = (pass.a, pass.sweeps.n / 2);
    let (r, q, p, w) = (
        &mut work.r[..],
        &mut work.q[..],
        &mut work.p[..],
        &mut work.y[..],
    );

    // r = b − A x, ‖r‖
    let (r0, r1) = r.split_at_mut(h);
    let xs = &*x;
    let (rr0, rr1) = rayon::join(
        || residual_rows(a, 0, b, xs, r0),
        || residual_rows(a, h, b, xs, r1),
    );
    let r_norm = (rr0 + rr1).sqrt();
    if !r_norm.is_finite() {
        return Err(LinearSolverError::NonFinite {
            what: "initial residual",
        });
    }
    let mut info = SolveInfo {
        iterations: 0,
        initial_residual: r_norm,
        final_residual: r_norm,
        converged: r_norm == 0.0,
    };
    if info.converged || params.max_iterations == 0 {
        return Ok(info);
    }
    let target = params.tolerance * r_norm;

    let (mut rz, _) = forward(pass, r, q, w, None);
    let mut beta = 0.0;
    let mut alpha = 0.0; // x += α p is deferred to the next backward pass (or the exit)
    for it in 1..=params.max_iterations {
        let pq = backward(pass, w, p, x, q, alpha, (it > 1).then_some(beta));
        if !(pq > 0.0) {
            return Err(LinearSolverError::pcg_curvature(it, pq));
        }
        alpha = rz / pq;
        let (rz_new, rr) = forward(pass, r, q, w, Some(alpha));
        let rn = rr.sqrt();
        info.record_pcg_residual(it, rn)?;
        if rn <= target || it == params.max_iterations {
            let (x0, x1) = x.split_at_mut(h);
            let (p0, p1) = p.split_at(h);
            rayon::join(|| axpy(alpha, p0, x0), || axpy(alpha, p1, x1));
            info.converged = rn <= target;
            return Ok(info);
        }
        beta = rz_new / rz;
        rz = rz_new;
    }
    Ok(info)
}

/// `x += α p`.
fn axpy(alpha: f64, p: &[f64], x: &mut [f64]) {
    for (xi, &pi) in x.iter_mut().zip(p) {
        *xi += alpha * pi;
    }
}

/// Rows `lo..lo + r.len()` of `r = b − A x`; returns their `‖r‖²`.
fn residual_rows(a: &CsrMatrix, lo: usize, b: &[f64], x: &[f64], r: &mut [f64]) -> f64 {
    let mut rr = 0.0;
    for (li, ri) in r.iter_mut().enumerate() {
        let i = lo + li;
        let v = b[i] - a.row_times(i, x);
        *ri = v;
        rr += v * v;
    }
    rr
}

/// The forward pass of both threads: `r −= α q` (when `alpha` is given),
/// `w = (D̃ + E)⁻¹ r`; returns `(rᵀz, ‖r‖²)`.
fn forward(
    pass: Pass<'_>,
    r: &mut [f64],
    q: &[f64],
    w: &mut [f64],
    alpha: Option<f64>,
) -> (f64, f64) {
    for p in pass.progress {
        p.0.store(0, Ordering::Relaxed);
    }
    let (r, w) = (Shared::new(r), Shared::new(w));
    let ((rz0, rr0), (rz1, rr1)) = rayon::join(
        || forward_rows(pass, 0, r, q, w, alpha),
        || forward_rows(pass, 1, r, q, w, alpha),
    );
    (rz0 + rz1, rr0 + rr1)
}

/// Thread `t`'s forward pass over its chunks, ascending. Its counter:
/// all its rows below it are done.
fn forward_rows(
    pass: Pass<'_>,
    t: usize,
    r: Shared,
    q: &[f64],
    w: Shared,
    alpha: Option<f64>,
) -> (f64, f64) {
    let sw = pass.sweeps;
    let (mine, other) = (&pass.progress[t], &pass.progress[1 - t]);
    let rd = pass.inv_diag;
    let mut seen = 0;
    let (mut rz, mut rr) = (0.0, 0.0);
    for c in (t..sw.chunks()).step_by(2) {
        let (lo, hi) = (sw.start(c), sw.start(c + 1));
        let other_lo = sw.start(c.saturating_sub(1));
        for i in lo..hi {
            // SAFETY: r, q and w rows of this thread's chunk; the other
            // thread's w rows read below after waiting for them.
            unsafe {
                let ri = match alpha {
                    Some(alpha) => {
                        let v = r.get(i) - alpha * q[i];
                        r.set(i, v);
                        v
                    }
                    None => r.get(i),
                };
                rr += ri * ri;
                let (cols, vals) = pass.lower.row(i);
                // the last column in the other thread's chunk before this one
                if let Some(&need) = cols
                    .iter()
                    .rev()
                    .find(|&&j| (j as usize) < lo && (j as usize) >= other_lo)
                {
                    let need = need as usize;
                    wait_for(other, &mut seen, |g| g > need);
                }
                // as `TriCsr::forward_row`: the nearest column last
                let t = match cols.split_last() {
                    None => ri,
                    Some((&c_last, rest)) => {
                        let mut s = 0.0;
                        for (&j, &v) in rest.iter().zip(vals) {
                            s += v * w.get(j as usize);
                        }
                        (ri - s) - vals[rest.len()] * w.get(c_last as usize)
                    }
                };
                let wi = t * rd[i];
                w.set(i, wi);
                rz += t * wi;
            }
            if (i + 1 - lo) % PUBLISH_ROWS == 0 {
                mine.0.store(i + 1, Ordering::Release);
            }
        }
        // the next chunk is the other thread's
        mine.0.store(sw.start(c + 2), Ordering::Release);
    }
    mine.0.store(sw.n, Ordering::Release);
    (rz, rr)
}

/// The backward pass of both threads: `z = (I + D̃⁻¹Eᵀ)⁻¹ w` in `w`,
/// `x += α p_old`, `p = z + β p_old` (`p = z` without `beta`), `q = A p`;
/// returns `pᵀq`.
fn backward(
    pass: Pass<'_>,
    w: &mut [f64],
    p: &mut [f64],
    x: &mut [f64],
    q: &mut [f64],
    alpha: f64,
    beta: Option<f64>,
) -> f64 {
    let n = pass.sweeps.n;
    for g in pass.progress {
        g.0.store(n, Ordering::Relaxed);
    }
    let v = [
        Shared::new(w),
        Shared::new(p),
        Shared::new(x),
        Shared::new(q),
    ];
    let (pq0, pq1) = rayon::join(
        || backward_rows(pass, 0, v, alpha, beta),
        || backward_rows(pass, 1, v, alpha, beta),
    );
    pq0 + pq1
}

/// Thread `t`'s backward pass over its chunks, descending, with `q = A p`
/// of a chunk once the `p` it reads is final; returns its rows' `pᵀq`. Its
/// counter: all its rows at or above it are done.
fn backward_rows(
    pass: Pass<'_>,
    t: usize,
    [w, p, x, q]: [Shared; 4],
    alpha: f64,
    beta: Option<f64>,
) -> f64 {
    let sw = pass.sweeps;
    let a = pass.a;
    let (rp, ci, av, dg) = (a.row_ptr(), a.col_idx(), a.values(), a.diag_index());
    let (mine, other) = (&pass.progress[t], &pass.progress[1 - t]);
    let rd = pass.inv_diag;
    let mut seen = sw.n;
    let mut pq = 0.0;
    let chunks = sw.chunks();
    if t >= chunks {
        mine.0.store(0, Ordering::Release);
        return 0.0;
    }
    // this thread's chunks, the highest first
    let top = t + 2 * ((chunks - 1 - t) / 2);
    // the next chunk of q to form (descending over this thread's chunks)
    let mut q_next = Some(top);
    // q of chunk c reads p of chunks c − 2 … c + 2: this thread's c − 2
    // (or c itself at the bottom) and the other's c − 1 (c + 1 at chunk 0)
    let q_ready = |c: usize, swept: usize, seen: usize| {
        let own = if c >= 2 { swept <= c - 2 } else { swept <= c };
        let other = seen <= sw.start(if c >= 1 { c - 1 } else { 1 });
        own && other
    };
    let matvec = |c: usize, pq: &mut f64| {
        for m in sw.start(c)..sw.start(c + 1) {
            let (s, e) = (rp[m] as usize, rp[m + 1] as usize);
            let mut qm = 0.0;
            for (&j, &v) in ci[s..e].iter().zip(&av[s..e]) {
                // SAFETY: p rows final (`q_ready`).
                qm += v * unsafe { p.get(j as usize) };
            }
            // SAFETY: q and p rows of this thread's chunk c.
            unsafe {
                q.set(m, qm);
                *pq += p.get(m) * qm;
            }
        }
    };
    let mut c = top;
    loop {
        let (lo, hi) = (sw.start(c), sw.start(c + 1));
        let other_hi = sw.start(c + 2);
        for i in (lo..hi).rev() {
            let (di, e) = (dg[i] as usize, rp[i + 1] as usize);
            let (cols, vals) = (&ci[di + 1..e], &av[di + 1..e]);
            // the first column in the other thread's chunk after this one
            if let Some(&need) = cols
                .iter()
                .find(|&&j| (j as usize) >= hi && (j as usize) < other_hi)
            {
                let need = need as usize;
                wait_for(other, &mut seen, |g| g <= need);
            }
            // SAFETY: w, p and x rows of this thread's chunk; the other
            // thread's w rows read after waiting for them above.
            unsafe {
                // as `CsrMatrix::backward_row_of_upper`: the nearest column last
                let scale = rd[i];
                let wi = w.get(i);
                let zi = match cols.split_first() {
                    None => wi,
                    Some((&c_first, rest)) => {
                        let mut sum = 0.0;
                        for (&j, &v) in rest.iter().zip(&vals[1..]) {
                            sum += scale * v * w.get(j as usize);
                        }
                        (wi - sum) - scale * vals[0] * w.get(c_first as usize)
                    }
                };
                w.set(i, zi);
                let pi = match beta {
                    None => zi,
                    Some(beta) => {
                        let po = p.get(i);
                        x.set(i, x.get(i) + alpha * po);
                        zi + beta * po
                    }
                };
                p.set(i, pi);
            }
            if (hi - i) % PUBLISH_ROWS == 0 {
                mine.0.store(i, Ordering::Release);
            }
        }
        // the next chunk down is the other thread's
        mine.0
            .store(sw.start(c.saturating_sub(1)), Ordering::Release);
        // q of the chunks whose p is final by now (without waiting)
        while let Some(cq) = q_next {
            if !q_ready(cq, c, seen) {
                seen = other.0.load(Ordering::Acquire);
                if !q_ready(cq, c, seen) {
                    break;
                }
            }
            matvec(cq, &mut pq);
            q_next = cq.checked_sub(2);
        }
        if c < 2 {
            break;
        }
        c -= 2;
    }
    // the rest once the other thread's sweep is done
    mine.0.store(0, Ordering::Release);
    wait_for(other, &mut seen, |g| g == 0);
    while let Some(cq) = q_next {
        matvec(cq, &mut pq);
        q_next = cq.checked_sub(2);
    }
    pq
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One claim at a time: a second caller is refused, and refusing it
    /// leaves the first claim held (a refused claim once released it, and
    /// two validation tests' solves each held a worker waiting for the
    /// other half).
    #[test]
    fn a_refused_claim_leaves_the_holder_s_claim() {
        let first = loop {
            match claim() {
                Some(c) => break c,
                // another test's shared solve finishes first
                None => std::thread::yield_now(),
            }
        };
        assert!(claim().is_none());
        assert!(claim().is_none(), "the refused claim released the first");
        drop(first);
    }
}
