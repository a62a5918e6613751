//! Preconditioned conjugate gradients with an incomplete Cholesky IC(0) preconditioner.
//!
//! Written by hand: no maintained crate offers a cache-friendly IC(0)-PCG
//! with a reusable factorisation (faer's matrix-free CG with faer-precond's
//! `Ic0` costs several mat-vecs per iteration; see `benches/linear_solvers.rs`).
//!
//! # Which IC(0)
//!
//! A true IC(0): the exact Cholesky factorisation restricted to the lower
//! pattern of `A` (zero fill-in), computed up-looking row by row. It is kept
//! in the root-free form `M = L̂ D̃ L̂ᵀ = (D̃ + E) D̃⁻¹ (D̃ + Eᵀ)` with
//!
//! ```text
//! E_ij = a_ij − Σ_{k<j} E_ik E_jk / d̃_k        (i > j, (i,j) ∈ pattern, k in both rows)
//! d̃_i  = a_ii − Σ_{k<i} E_ik² / d̃_k
//! ```
//!
//! OpenFOAM's DIC keeps `E = lower(A)` and only updates the diagonal; that is
//! the same factor when the cell graph has no triangles (structured
//! hexahedral meshes) but drops the `E_ik E_jk` corrections on tetrahedral
//! and polyhedral meshes, so it is not a true IC(0) there. Forward sweep
//! `t_i = r_i − Σ_j E_ij w_j`, `w_i = t_i / d̃_i`; backward sweep
//! `z_i = w_i − Σ_j (E_ji / d̃_i) z_j`.
//!
//! Storage ([`factor`]): where the graph has no triangles and `A` is
//! symmetric to the bit, `D̃⁻¹` and a copy of `E = lower(A)`, the backward
//! sweep reading `A`'s own upper triangle, which the trailing mat-vec of
//! the same pass streams anyway (the DIC storage of the same factor, to
//! the bit: [`dic_factor`]); elsewhere `E` (strict lower triangle, CSR),
//! `D̃⁻¹ Eᵀ` (CSR of the scaled transpose, so the backward sweep gathers
//! instead of scattering) and `D̃⁻¹`, all contiguous ([`full_factor`]).
//! Hence the solves and [`LinearSolver::precondition`] take the
//! factorised matrix.
//!
//! # Breakdown
//!
//! IC(0) of an SPD matrix that is not an H-matrix can meet a non-positive
//! pivot. Then the factorisation restarts on `A + α diag(A)` (Manteuffel's
//! shifted incomplete Cholesky), `α = 10⁻³, 2·10⁻³, 4·10⁻³, …`; the shift used
//! is reported by [`PcgIc0::factorisation_info`]. A non-positive diagonal
//! entry of `A` itself is an error.
//!
//! # One iteration = two memory passes
//!
//! Using `rᵀz = rᵀM⁻¹r = Σ_i t_i w_i = Σ_i d̃_i w_i²` (from the forward
//! sweep), `β` is known before the backward sweep, so an iteration is:
//!
//! 1. backward pass, rows descending: backward sweep for `z`, the deferred
//!    `x += α p`, `p = z + β p`, and, trailing behind it (each row as soon as
//!    the `p` entries it reads are final, about one grid plane later, still
//!    in cache), `q = A p` and `pᵀq`;
//! 2. forward pass, rows ascending: `r −= α q`, `‖r‖²`, forward sweep for
//!    `w`, `rᵀz`.
//!
//! The sweeps keep the nearest neighbour (`i ∓ 1`) in a register, so their
//! loop-carried dependency chain is one multiply and one subtraction.
//!
//! [`PcgIc0::solve`] allocates nothing.
//!
//! # Two threads
//!
//! On a pool of two threads or more, large systems in the DIC storage are
//! solved by two threads at once with the same sweeps, rows dealt out in
//! chunks and each thread waiting for the other's rows it reads
//! ([`two_thread_sweeps`]): the same preconditioner and iteration up to
//! the round-off of the sums.

mod dic_factor;
mod factor;
mod full_factor;
mod two_thread_sweeps;

use crate::csr::CsrMatrix;
use crate::linear_solver::{
    check_len, krylov_start, solve_in_turn, FactorisationInfo, LinearSolver, LinearSolverError,
    SolveInfo,
};
use factor::{Ic0Factor, Ic0Sweeps};
use std::time::Instant;
use two_thread_sweeps::{claim, pcg_two_threads, TwoThreadSweeps, TWO_THREAD_ROWS};

/// First relative diagonal shift tried after an IC(0) breakdown.
const SHIFT_INITIAL: f64 = 1e-3;
/// Restarts allowed before giving up (the shift then exceeds 10⁹).
const MAX_RESTARTS: usize = 40;
/// A pivot must exceed this fraction of its (shifted) diagonal entry.
const PIVOT_REL_MIN: f64 = 1e-10;

/// Stopping parameters of the Krylov solvers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PcgParams {
    /// Stop when `‖r‖₂ ≤ tolerance · ‖r₀‖₂` (relative to the initial residual).
    pub tolerance: f64,
    /// Iteration limit; reaching it returns `converged: false`, not an error.
    pub max_iterations: usize,
}

impl Default for PcgParams {
    fn default() -> Self {
        PcgParams {
            tolerance: 1e-6,
            max_iterations: 1000,
        }
    }
}

/// PCG with an IC(0) preconditioner; the factorisation and all work vectors are reused across solves.
#[derive(Debug, Clone, Default)]
pub struct PcgIc0 {
    /// System size.
    n: usize,
    /// Parameters used by [`LinearSolver::solve`].
    params: PcgParams,
    /// The IC(0) factor.
    factor: Ic0Factor,
    /// Pattern the symbolic data was built for.
    pattern_id: Option<u64>,
    /// Whether that pattern's graph has no triangles.
    triangle_free: bool,
    /// Whether `factor` holds a valid factorisation.
    factorised: bool,
    /// Diagnostics.
    info: FactorisationInfo,
    /// Work vectors of [`PcgIc0::solve`].
    work: PcgWork,
    /// Work vectors of the further right-hand sides solved at the same
    /// time by [`LinearSolver::solve_each`] (allocated at its first call).
    extra: Vec<PcgWork>,
    /// The chunking by which two threads share one solve with the DIC
    /// storage's sweeps ([`two_thread_sweeps`]), for the pattern factorised
    /// last (`None` when its bandwidth is too large for it).
    two_threads: Option<TwoThreadSweeps>,
    /// Seconds per iteration of the latest shared and lone solve, by which
    /// the solves that could be shared are made the faster way.
    share_timing: ShareTiming,
}

/// The wall time per iteration of the latest solve shared by two threads
/// and of the latest made by one, where both are possible. Another process
/// on one of the two cores stalls the shared sweeps at every row that
/// waits for the other thread (box64 with a compiler running: 18.9 s on
/// two threads against 11.9 s on one), so a solve is shared while that is
/// faster per iteration; the other way is tried on the second solve and
/// every [`PROBE_EVERY`]th.
#[derive(Debug, Clone, Copy, Default)]
struct ShareTiming {
    shared: f64,
    alone: f64,
    solves: u32,
}

/// Every this many solves that could be shared, one is made the way not in
/// use, to measure it again.
const PROBE_EVERY: u32 = 64;

impl ShareTiming {
    /// Whether the next solve is shared.
    fn share_next(&mut self) -> bool {
        self.solves = self.solves.wrapping_add(1);
        let probe = self.solves == 2 || self.solves.is_multiple_of(PROBE_EVERY);
        let shared_faster = self.alone == 0.0 || self.shared <= self.alone;
        shared_faster != probe
    }

    /// Records a solve that took `start.elapsed()` for `iterations`.
    fn record(&mut self, shared: bool, start: Instant, iterations: usize) {
        let t = start.elapsed().as_secs_f64() / (iterations + 1) as f64;
        if shared {
            self.shared = t;
        } else {
            self.alone = t;
        }
    }
}

/// The work vectors of one PCG solve.
#[derive(Debug, Clone, Default)]
struct PcgWork {
    /// Residual.
    r: Vec<f64>,
    /// `A p`.
    q: Vec<f64>,
    /// Search direction.
    p: Vec<f64>,
    /// Forward-sweep result `w`, overwritten by the preconditioned residual `z`.
    y: Vec<f64>,
}

impl PcgWork {
    fn new(n: usize) -> Self {
        let mut w = PcgWork::default();
        w.resize(n);
        w
    }

    fn resize(&mut self, n: usize) {
        for v in [&mut self.r, &mut self.q, &mut self.p, &mut self.y] {
            v.clear();
            v.resize(n, 0.0);
        }
    }
}

/// Systems of at least this many rows are solved side by side by
/// [`LinearSolver::solve_each`] (below, handing them to the thread pool
/// costs more than it saves).
const PARALLEL_ROWS: usize = 4096;
/// At most this many right-hand sides side by side (the three displacement
/// components); more are solved one after the other.
const MAX_SIDE_BY_SIDE: usize = 3;

impl PcgIc0 {
    /// Creates a solver for `n` unknowns with default [`PcgParams`]; allocates the work vectors once.
    pub fn new(n: usize) -> Self {
        Self::with_params(n, PcgParams::default())
    }

    /// Creates a solver for `n` unknowns with the given parameters.
    pub fn with_params(n: usize, params: PcgParams) -> Self {
        let mut s = PcgIc0 {
            params,
            ..Default::default()
        };
        s.resize(n);
        s
    }

    /// Parameters used by [`LinearSolver::solve`].
    pub fn params(&self) -> &PcgParams {
        &self.params
    }

    /// Mutable parameters used by [`LinearSolver::solve`].
    pub fn params_mut(&mut self) -> &mut PcgParams {
        &mut self.params
    }

    /// Diagonal shift and reuse counters of the factorisations so far.
    pub fn factorisation_info(&self) -> FactorisationInfo {
        self.info
    }

    /// Number of unknowns.
    pub fn n(&self) -> usize {
        self.n
    }

    /// (Re)allocates the work vectors for `n` unknowns.
    fn resize(&mut self, n: usize) {
        self.n = n;
        self.work.resize(n);
        self.extra.clear();
    }

    /// Computes the IC(0) factorisation of `a` (symmetric positive definite; only its lower triangle is read).
    ///
    /// Reuses the symbolic data and all buffers when `a`'s pattern is the one
    /// factorised last; resizes the work vectors if `a`'s size differs from
    /// the one given to [`PcgIc0::new`]. On a non-positive pivot it restarts
    /// with a diagonal shift (see the module documentation).
    pub fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        self.factorised = false;
        if a.n() != self.n {
            self.resize(a.n());
            self.pattern_id = None;
        }
        if self.pattern_id != Some(a.pattern_id()) {
            self.triangle_free = a.is_triangle_free();
            self.two_threads = TwoThreadSweeps::for_matrix(a);
            self.pattern_id = Some(a.pattern_id());
            self.info.symbolic_analyses += 1;
        }
        self.factor.prepare(a, self.triangle_free);
        let mut shift = 0.0;
        let mut restarts = 0;
        while let Some(row) = self.factor.numeric(a, shift, PIVOT_REL_MIN)? {
            restarts += 1;
            if restarts > MAX_RESTARTS {
                return Err(LinearSolverError::FactorisationFailed { row, shift });
            }
            shift = if shift == 0.0 {
                SHIFT_INITIAL
            } else {
                2.0 * shift
            };
        }
        self.info.diagonal_shift = shift;
        self.info.restarts = restarts;
        self.info.numeric_factorisations += 1;
        self.info.off_diagonals_of_matrix = self.factor.is_diagonal();
        self.factorised = true;
        Ok(())
    }

    /// Applies the preconditioner of the factorised matrix `a`, `z = M⁻¹ r`
    /// (one forward and one backward sweep), e.g. inside another Krylov
    /// method. `a` must be the matrix last factorised: on a graph without
    /// triangles the sweeps read its off-diagonals. Allocates nothing.
    pub fn apply_preconditioner(
        &self,
        a: &CsrMatrix,
        r: &[f64],
        z: &mut [f64],
    ) -> Result<(), LinearSolverError> {
        if !self.factorised {
            return Err(LinearSolverError::NotFactorised);
        }
        check_len("matrix", a.n(), self.n)?;
        check_len("r", r.len(), self.n)?;
        check_len("z", z.len(), self.n)?;
        self.factor.apply(a, r, z);
        Ok(())
    }

    /// Whether a solve is shared by two threads ([`two_thread_sweeps`]):
    /// the DIC storage on a pattern of small enough bandwidth, at least
    /// [`TWO_THREAD_ROWS`] rows, a pool of two threads or more, and a
    /// caller outside the pool (a solve beside others on a worker is made
    /// by that worker alone).
    fn shares_a_solve(&self) -> bool {
        self.two_threads.is_some()
            && self.factor.is_diagonal()
            && self.n >= TWO_THREAD_ROWS
            && rayon::current_thread_index().is_none()
            && rayon::current_num_threads() >= 2
    }

    /// Solves `a x = b` by IC(0)-PCG; `x` is the initial guess on input. Allocates nothing.
    ///
    /// `a` must be the symmetric positive definite matrix last factorised
    /// (on a graph without triangles the preconditioner's sweeps read its
    /// off-diagonals). Reaching `max_iterations` is not an error
    /// (`converged: false`).
    pub fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
        params: &PcgParams,
    ) -> Result<SolveInfo, LinearSolverError> {
        if !self.factorised {
            return Err(LinearSolverError::NotFactorised);
        }
        let Some(sweeps) = self.two_threads.filter(|_| self.shares_a_solve()) else {
            return pcg_with(&self.factor, self.n, a, b, x, params, &mut self.work);
        };
        let start = Instant::now();
        let claim = self.share_timing.share_next().then(claim).flatten();
        let result = match (&claim, &self.factor) {
            (Some(claim), Ic0Factor::Dic(f)) => {
                let (lower, inv_diag) = (f.lower(), f.inv_diag());
                let work = &mut self.work;
                pcg_two_threads(claim, sweeps, lower, inv_diag, a, b, x, params, work)
            }
            _ => pcg_with(&self.factor, self.n, a, b, x, params, &mut self.work),
        };
        if let Ok(info) = &result {
            self.share_timing
                .record(claim.is_some(), start, info.iterations);
        }
        result
    }
}

/// [`pcg`] with the factor's storage.
fn pcg_with(
    fac: &Ic0Factor,
    n: usize,
    a: &CsrMatrix,
    b: &[f64],
    x: &mut [f64],
    params: &PcgParams,
    work: &mut PcgWork,
) -> Result<SolveInfo, LinearSolverError> {
    match fac {
        Ic0Factor::Full(f) => pcg(f, n, a, b, x, params, work),
        Ic0Factor::Dic(f) => pcg(f, n, a, b, x, params, work),
    }
}

/// IC(0)-PCG with the factor `fac` of an `n` × `n` matrix and the work
/// vectors `work` (see the module documentation).
fn pcg<F: Ic0Sweeps>(
    fac: &F,
    n: usize,
    a: &CsrMatrix,
    b: &[f64],
    x: &mut [f64],
    params: &PcgParams,
    work: &mut PcgWork,
) -> Result<SolveInfo, LinearSolverError> {
    check_len("matrix", a.n(), n)?;
    check_len("b", b.len(), n)?;
    check_len("x", x.len(), n)?;
    let rd = fac.inv_diag();
    let (r, q, p, w) = (
        &mut work.r[..],
        &mut work.q[..],
        &mut work.p[..],
        &mut work.y[..],
    );

    let (mut info, target) = krylov_start(a, b, x, r, params.tolerance, params.max_iterations)?;
    let Some(target) = target else {
        return Ok(info);
    };

    // Forward sweep w = (D̃ + E)⁻¹ r and rᵀz = Σ t w.
    let mut rz = 0.0;
    let mut w_prev = 0.0;
    for i in 0..n {
        let t = fac.forward_row(a, i, r[i], w, w_prev);
        let wi = t * rd[i];
        w[i] = wi;
        w_prev = wi;
        rz += t * wi;
    }
    let mut beta = 0.0;
    let mut alpha = 0.0; // x += α p is deferred to the next backward pass (or the exit)
    for it in 1..=params.max_iterations {
        // Backward pass, rows descending: z = (I + U_b)⁻¹ w (in place), x += α p_old,
        // p = z + β p_old, q = A p, pᵀq.
        let pq = fac.backward_pass(a, w, p, x, q, alpha, (it > 1).then_some(beta));
        if !(pq > 0.0) {
            return Err(LinearSolverError::pcg_curvature(it, pq));
        }
        alpha = rz / pq;
        // Forward pass, rows ascending: r −= α q, ‖r‖², w = (D̃ + E)⁻¹ r, rᵀz.
        let mut rr = 0.0;
        let mut rz_new = 0.0;
        let mut w_prev = 0.0;
        for i in 0..n {
            let ri = r[i] - alpha * q[i];
            r[i] = ri;
            rr += ri * ri;
            let t = fac.forward_row(a, i, ri, w, w_prev);
            let wi = t * rd[i];
            w[i] = wi;
            w_prev = wi;
            rz_new += t * wi;
        }
        let rn = rr.sqrt();
        info.record_pcg_residual(it, rn)?;
        if rn <= target || it == params.max_iterations {
            for (xi, &pi) in x.iter_mut().zip(p.iter()) {
                *xi += alpha * pi;
            }
            info.converged = rn <= target;
            return Ok(info);
        }
        beta = rz_new / rz;
        rz = rz_new;
    }
    Ok(info)
}

impl LinearSolver for PcgIc0 {
    fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        PcgIc0::factorise(self, a)
    }

    fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
    ) -> Result<SolveInfo, LinearSolverError> {
        let params = self.params;
        PcgIc0::solve(self, a, b, x, &params)
    }

    /// The right-hand sides side by side on the thread pool, each with its
    /// own work vectors and the one factorisation (the same answers as one
    /// after the other, to the bit). Three solves side by side on two
    /// threads measured faster than each shared by both
    /// ([`two_thread_sweeps`]; see docs/kernel-performance.md).
    fn solve_each(
        &mut self,
        a: &CsrMatrix,
        b: &[&[f64]],
        x: &mut [&mut [f64]],
        info: &mut [SolveInfo],
    ) -> Result<(), LinearSolverError> {
        let k = b.len();
        if !(2..=MAX_SIDE_BY_SIDE).contains(&k)
            || self.n < PARALLEL_ROWS
            || rayon::current_num_threads() < 2
        {
            return solve_in_turn(self, a, b, x, info);
        }
        check_len("right-hand sides", x.len(), k)?;
        check_len("infos", info.len(), k)?;
        if !self.factorised {
            return Err(LinearSolverError::NotFactorised);
        }
        let n = self.n;
        while self.extra.len() + 1 < k {
            self.extra.push(PcgWork::new(n));
        }
        let (fac, params) = (&self.factor, self.params);
        let mut results: [Result<SolveInfo, LinearSolverError>; MAX_SIDE_BY_SIDE] =
            std::array::from_fn(|_| Ok(SolveInfo::default()));
        let works = std::iter::once(&mut self.work).chain(self.extra.iter_mut());
        rayon::scope(|s| {
            for (((b, x), work), result) in b.iter().zip(x.iter_mut()).zip(works).zip(&mut results)
            {
                s.spawn(move |_| *result = pcg_with(fac, n, a, b, x, &params, work));
            }
        });
        for (result, i) in results.into_iter().zip(info.iter_mut()) {
            *i = result?;
        }
        Ok(())
    }

    /// z = (D̃ + Eᵀ)⁻¹ D̃ (D̃ + E)⁻¹ r: one forward and one backward sweep.
    fn precondition(
        &self,
        a: &CsrMatrix,
        r: &[f64],
        z: &mut [f64],
    ) -> Result<bool, LinearSolverError> {
        self.apply_preconditioner(a, r, z).map(|()| true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csr::test_util::*;
    use crate::direct::DirectSolver;

    fn direct(a: &CsrMatrix, b: &[f64]) -> Vec<f64> {
        let mut d = DirectSolver::cholesky();
        d.factorise(a).unwrap();
        let mut x = vec![0.0; a.n()];
        LinearSolver::solve(&mut d, a, b, &mut x).unwrap();
        x
    }

    /// On a chain (no triangles, no fill) IC(0) is the exact Cholesky
    /// factor, so one application solves the system; on a 3-D grid it is
    /// the preconditioner PCG iterates with.
    #[test]
    fn applying_the_preconditioner_solves_a_chain_exactly() {
        let a = laplacian(40, 1, 1, 0.3);
        let b = rhs(a.n(), 3);
        let mut s = PcgIc0::new(a.n());
        assert_eq!(
            s.apply_preconditioner(&a, &b, &mut vec![0.0; a.n()]),
            Err(LinearSolverError::NotFactorised)
        );
        s.factorise(&a).unwrap();
        let mut z = vec![0.0; a.n()];
        s.apply_preconditioner(&a, &b, &mut z).unwrap();
        assert!(rel_residual(&a, &b, &z) < 1e-13);
        let grid = laplacian(6, 5, 4, 0.1);
        let b = rhs(grid.n(), 5);
        s.factorise(&grid).unwrap();
        let mut z = vec![0.0; grid.n()];
        s.apply_preconditioner(&grid, &b, &mut z).unwrap();
        let one_pcg_step = rel_residual(&grid, &b, &z);
        assert!(one_pcg_step > 1e-3 && one_pcg_step < 0.5, "{one_pcg_step}");
    }

    /// Checks 1e-6 and 1e-12 solves against the requested tolerance and the direct solution.
    fn check(a: &CsrMatrix, seed: u64) -> (usize, usize) {
        let n = a.n();
        let b = rhs(n, seed);
        let mut s = PcgIc0::new(n);
        s.factorise(a).unwrap();
        let mut x = vec![0.0; n];
        let info = s.solve(a, &b, &mut x, &PcgParams::default()).unwrap();
        assert!(info.converged, "{info:?}");
        let rel = rel_residual(a, &b, &x);
        assert!(rel <= 1e-6 * (1.0 + 1e-6), "true residual {rel}");
        assert!(
            (info.initial_residual - rel_residual(a, &b, &vec![0.0; n]) * norm(&b)).abs() < 1e-12
        );
        let mut xt = vec![0.0; n];
        let tight = PcgParams {
            tolerance: 1e-12,
            ..Default::default()
        };
        let info_t = s.solve(a, &b, &mut xt, &tight).unwrap();
        assert!(info_t.converged);
        let xd = direct(a, &b);
        let diff = rel_diff(&xt, &xd);
        assert!(diff < 1e-8, "PCG vs direct {diff}");
        (info.iterations, info_t.iterations)
    }

    fn norm(v: &[f64]) -> f64 {
        v.iter().map(|x| x * x).sum::<f64>().sqrt()
    }

    #[test]
    fn laplacian_3d_20() {
        let a = laplacian(20, 20, 20, 1e-3);
        let (it, it_t) = check(&a, 1);
        assert!(it < 60 && it_t < 150, "{it} {it_t}");
    }

    /// Three right-hand sides side by side (8,000 unknowns: above
    /// `PARALLEL_ROWS`, so on the pool when it has two threads or more)
    /// give, to the bit, the answers of three solves one after the other,
    /// and the work vectors of the side-by-side solves are reused.
    #[test]
    fn solve_each_equals_one_after_the_other() {
        let a = laplacian(20, 20, 20, 1e-3);
        let n = a.n();
        assert!(n >= PARALLEL_ROWS);
        let b: Vec<Vec<f64>> = (0..3).map(|k| rhs(n, 10 + k)).collect();
        let mut s = PcgIc0::new(n);
        s.factorise(&a).unwrap();
        let mut alone = Vec::new();
        for bk in &b {
            let mut x = vec![0.0; n];
            let info = LinearSolver::solve(&mut s, &a, bk, &mut x).unwrap();
            alone.push((x, info));
        }
        for _ in 0..2 {
            let mut x: Vec<Vec<f64>> = vec![vec![0.0; n]; 3];
            let mut info = [SolveInfo::default(); 3];
            let bs: Vec<&[f64]> = b.iter().map(|v| v.as_slice()).collect();
            let mut xs: Vec<&mut [f64]> = x.iter_mut().map(|v| v.as_mut_slice()).collect();
            s.solve_each(&a, &bs, &mut xs, &mut info).unwrap();
            for (k, (xa, ia)) in alone.iter().enumerate() {
                assert!(info[k].converged && info[k].iterations > 5, "{:?}", info[k]);
                assert_eq!(&info[k], ia);
                assert!(x[k].iter().zip(xa).all(|(p, q)| p.to_bits() == q.to_bits()));
            }
        }
        assert!(s.extra.len() <= 2);
        // mismatched counts are an error, not a panic
        let mut x0 = vec![0.0; n];
        let mut xs: Vec<&mut [f64]> = vec![x0.as_mut_slice()];
        let bs: Vec<&[f64]> = b.iter().map(|v| v.as_slice()).collect();
        let mut info = [SolveInfo::default(); 3];
        assert!(s.solve_each(&a, &bs, &mut xs, &mut info).is_err());
    }

    /// A 40³ Laplacian (64,000 rows, above `TWO_THREAD_ROWS`): two
    /// threads sharing one solve with the sequential IC(0)'s sweeps take
    /// the same iterations to the same solution as one thread (the sums
    /// differ by round-off), at a tight and at the outer loop's loose
    /// tolerance; on a one-thread pool no solve is shared.
    #[test]
    fn two_threads_share_one_solve_with_the_sequential_sweeps() {
        let a = laplacian(40, 40, 40, 1e-3);
        let n = a.n();
        assert!(n >= TWO_THREAD_ROWS);
        let b = rhs(n, 21);
        let pool = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
        };
        let mut s = PcgIc0::new(n);
        pool(1).install(|| {
            s.factorise(&a).unwrap();
            assert!(!s.shares_a_solve());
        });
        let sweeps = s.two_threads.expect("a 40³ grid has a small bandwidth");
        for tolerance in [1e-10, 0.1] {
            let params = PcgParams {
                tolerance,
                max_iterations: 1000,
            };
            let mut x1 = vec![0.0; n];
            let i1 = pool(1).install(|| s.solve(&a, &b, &mut x1, &params).unwrap());
            let Ic0Factor::Dic(f) = &s.factor else {
                panic!("a grid Laplacian has the DIC storage")
            };
            let mut x2 = vec![0.0; n];
            let mut work = PcgWork::new(n);
            let i2 = pool(2).install(|| {
                let claim = loop {
                    match claim() {
                        Some(c) => break c,
                        // another test's shared solve finishes first
                        None => std::thread::yield_now(),
                    }
                };
                pcg_two_threads(
                    &claim,
                    sweeps,
                    f.lower(),
                    f.inv_diag(),
                    &a,
                    &b,
                    &mut x2,
                    &params,
                    &mut work,
                )
                .unwrap()
            });
            assert!(i1.converged && i2.converged, "{i1:?} {i2:?}");
            assert_eq!(i1.iterations, i2.iterations);
            assert!(i1.iterations > 1);
            let rel = (i1.final_residual - i2.final_residual).abs() / i1.final_residual;
            assert!(rel < 1e-9, "{i1:?} {i2:?}");
            assert!(rel_diff(&x1, &x2) < 1e-12, "{}", rel_diff(&x1, &x2));
        }
    }

    /// Shared while that is faster per iteration (or the lone time is not
    /// known); the other way on the second solve and every 64th.
    #[test]
    fn solves_are_shared_while_that_is_faster() {
        let mut t = ShareTiming::default();
        let ways: Vec<bool> = (0..130).map(|_| t.share_next()).collect();
        let lone: Vec<usize> = (0..130).filter(|&k| !ways[k]).collect();
        assert_eq!(lone, [1, 63, 127]);
        let mut t = ShareTiming {
            shared: 2e-3,
            alone: 1e-3,
            solves: 0,
        };
        let shared: Vec<usize> = (0..130).filter(|_| t.share_next()).collect();
        assert_eq!(shared.len(), 3);
        t.shared = 0.5e-3;
        assert!(t.share_next());
    }

    #[test]
    fn laplacian_2d_60() {
        let a = laplacian(60, 60, 1, 0.0);
        check(&a, 2);
    }

    #[test]
    fn random_spd_with_triangles() {
        let a = random_spd(3000, 4, 42);
        assert!(a.max_asymmetry() == 0.0);
        check(&a, 3);
    }

    /// On a 1-D Laplacian (a tree: IC(0) has no dropped fill) one
    /// preconditioner application is the exact solve.
    #[test]
    fn precondition_is_exact_without_fill() {
        let a = laplacian(40, 1, 1, 0.1);
        let n = a.n();
        let mut s = PcgIc0::new(n);
        let b = rhs(n, 3);
        let mut z = vec![0.0; n];
        assert!(matches!(
            LinearSolver::precondition(&s, &a, &b, &mut z),
            Err(LinearSolverError::NotFactorised)
        ));
        s.factorise(&a).unwrap();
        assert!(LinearSolver::precondition(&s, &a, &b, &mut z).unwrap());
        let xd = direct(&a, &b);
        assert!(rel_diff(&z, &xd) < 1e-12, "{}", rel_diff(&z, &xd));
        // on a 2-D Laplacian it is an approximation, not the solve
        let a2 = laplacian(12, 12, 1, 0.1);
        let mut s2 = PcgIc0::new(a2.n());
        s2.factorise(&a2).unwrap();
        let b2 = rhs(a2.n(), 4);
        let mut z2 = vec![0.0; a2.n()];
        assert!(LinearSolver::precondition(&s2, &a2, &b2, &mut z2).unwrap());
        let d = rel_diff(&z2, &direct(&a2, &b2));
        assert!(d > 1e-4 && d < 0.5, "{d}");
    }

    /// On a graph without triangles (a 3-D grid, symmetric to the bit) the
    /// factor takes the DIC storage and is, to the bit, the full IC(0): the
    /// same pivots, the same preconditioned vector; PCG takes the same
    /// iterations to the same solution up to round-off. A graph with triangles, or values asymmetric by one ulp,
    /// get the full factor, and the grid the diagonal one again.
    #[test]
    fn diagonal_storage_is_the_full_factor_on_a_graph_without_triangles() {
        let a = laplacian(9, 8, 7, 0.05);
        let n = a.n();
        let mut s = PcgIc0::new(n);
        s.factorise(&a).unwrap();
        assert!(s.factorisation_info().off_diagonals_of_matrix);
        let Ic0Factor::Dic(diagonal) = &s.factor else {
            panic!("a grid gets the diagonal factor")
        };
        let mut full = full_factor::FullFactor::default();
        full.prepare(&a);
        assert_eq!(full.numeric(&a, 0.0, PIVOT_REL_MIN).unwrap(), None);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(diagonal.inv_diag()), bits(full.inv_diag()));
        let r = rhs(n, 7);
        let (mut z_full, mut z_diagonal) = (vec![0.0; n], vec![0.0; n]);
        full.apply(&a, &r, &mut z_full);
        diagonal.apply(&a, &r, &mut z_diagonal);
        assert_eq!(bits(&z_full), bits(&z_diagonal));
        assert!(
            rel_diff(&z_full, &r) > 0.1,
            "a preconditioner, not the identity"
        );
        let params = PcgParams::default();
        let mut work = PcgWork::new(n);
        let (mut x_full, mut x_diagonal) = (vec![0.0; n], vec![0.0; n]);
        let info_full = pcg(&full, n, &a, &r, &mut x_full, &params, &mut work).unwrap();
        let info_diagonal = pcg(diagonal, n, &a, &r, &mut x_diagonal, &params, &mut work).unwrap();
        // the DIC backward pass sums q = A p in another order: round-off
        assert!(
            info_full.converged && info_full.iterations > 5,
            "{info_full:?}"
        );
        assert_eq!(info_full.iterations, info_diagonal.iterations);
        let (f, d) = (info_full.final_residual, info_diagonal.final_residual);
        assert!((f - d).abs() <= 1e-10 * f, "{f} {d}");
        assert!(rel_diff(&x_full, &x_diagonal) < 1e-12);

        let with_triangles = random_spd(300, 3, 9);
        assert!(!with_triangles.is_triangle_free());
        let mut t = PcgIc0::new(with_triangles.n());
        t.factorise(&with_triangles).unwrap();
        assert!(!t.factorisation_info().off_diagonals_of_matrix);

        let mut skew = a.clone();
        let k = skew.entry_index(20, 19).unwrap();
        skew.values_mut()[k] = skew.values()[k].next_up();
        s.factorise(&skew).unwrap();
        assert!(!s.factorisation_info().off_diagonals_of_matrix);
        assert!(matches!(s.factor, Ic0Factor::Full(_)));
        s.factorise(&a).unwrap();
        assert!(s.factorisation_info().off_diagonals_of_matrix);
        assert_eq!(s.factorisation_info().symbolic_analyses, 1);
    }

    #[test]
    fn ic0_is_exact_on_pattern() {
        // ((D̃ + E) D̃⁻¹ (D̃ + E)ᵀ)_ij = a_ij on every stored entry when no shift was needed.
        let a = random_spd(300, 3, 9);
        let mut s = PcgIc0::new(a.n());
        s.factorise(&a).unwrap();
        assert_eq!(s.factorisation_info().diagonal_shift, 0.0);
        assert!(!s.factorisation_info().off_diagonals_of_matrix);
        let n = a.n();
        let Ic0Factor::Full(full) = &s.factor else {
            panic!("a graph with triangles has the full factor")
        };
        let f = &full.factor;
        let mut l = vec![0.0; n * n]; // D̃ + E, dense
        for i in 0..n {
            l[i * n + i] = 1.0 / f.inv_diag()[i];
            let (cols, vals) = f.lower().row(i);
            for (&c, &v) in cols.iter().zip(vals) {
                l[i * n + c as usize] = v;
            }
            // U_b row i holds E_ji / d̃_i
            let (cols, vals) = f.upper().row(i);
            for (&c, &v) in cols.iter().zip(vals) {
                let e_ci = f.lower().row(c as usize);
                let k = e_ci.0.binary_search(&(i as u32)).unwrap();
                assert!((v - e_ci.1[k] * f.inv_diag()[i]).abs() <= 1e-14 * v.abs());
            }
        }
        for i in 0..n {
            let (cols, vals) = a.row(i);
            for (&j, &aij) in cols.iter().zip(vals) {
                let j = j as usize;
                let m: f64 = (0..n)
                    .map(|k| l[i * n + k] * l[j * n + k] * f.inv_diag()[k])
                    .sum();
                assert!(
                    (m - aij).abs() < 1e-10 * (1.0 + aij.abs()),
                    "({i},{j}) {m} vs {aij}"
                );
            }
        }
    }

    #[test]
    fn factorisation_reused_for_three_components() {
        let a = laplacian(12, 10, 8, 0.01);
        let n = a.n();
        let mut s = PcgIc0::new(n);
        LinearSolver::factorise(&mut s, &a).unwrap();
        for c in 0..3 {
            let b = rhs(n, 10 + c);
            let mut x = vec![0.0; n];
            let info = LinearSolver::solve(&mut s, &a, &b, &mut x).unwrap();
            assert!(info.converged);
            assert!(rel_residual(&a, &b, &x) <= 1e-6 * (1.0 + 1e-6));
        }
        let fi = s.factorisation_info();
        assert_eq!((fi.symbolic_analyses, fi.numeric_factorisations), (1, 1));
        // solve allocates nothing
        let b = rhs(n, 13);
        let mut x = vec![0.0; n];
        let before = allocations();
        let info = s.solve(&a, &b, &mut x, &PcgParams::default()).unwrap();
        assert_eq!(allocations(), before, "PcgIc0::solve allocated");
        assert!(info.converged);
        // new values, same pattern: numeric only
        let mut a2 = a.clone();
        for v in a2.values_mut() {
            *v *= 2.0;
        }
        let before = allocations();
        s.factorise(&a2).unwrap();
        assert_eq!(allocations(), before, "refactorisation allocated");
        let fi = s.factorisation_info();
        assert_eq!((fi.symbolic_analyses, fi.numeric_factorisations), (1, 2));
    }

    #[test]
    fn warm_start_and_zero_rhs() {
        let a = laplacian(8, 8, 8, 0.1);
        let n = a.n();
        let b = rhs(n, 5);
        let mut s = PcgIc0::new(n);
        s.factorise(&a).unwrap();
        let mut x = vec![0.0; n];
        s.solve(&a, &b, &mut x, &PcgParams::default()).unwrap();
        // restart from the solution: converges immediately relative to the new (small) residual
        let info = s
            .solve(
                &a,
                &b,
                &mut x,
                &PcgParams {
                    tolerance: 1e-3,
                    ..Default::default()
                },
            )
            .unwrap();
        assert!(info.converged && info.initial_residual < 1e-5 * norm(&b));
        let mut z = vec![0.0; n];
        let info = s
            .solve(&a, &vec![0.0; n], &mut z, &PcgParams::default())
            .unwrap();
        assert!(info.converged && info.iterations == 0);
        assert!(z.iter().all(|&v| v == 0.0));
    }

    /// SPD by construction (sum of rank-one "element" matrices plus εI) but not an H-matrix.
    fn element_spd(n: usize, elements: usize, seed: u64) -> CsrMatrix {
        let mut rng = Lcg(seed);
        let mut t = Vec::new();
        for i in 0..n {
            t.push((i as u32, i as u32, 1e-3));
        }
        for _ in 0..elements {
            let mut nodes = [0usize; 3];
            nodes[0] = rng.next_below(n);
            nodes[1] = (nodes[0] + 1 + rng.next_below(n - 1)) % n;
            nodes[2] = loop {
                let c = rng.next_below(n);
                if c != nodes[0] && c != nodes[1] {
                    break c;
                }
            };
            let v: Vec<f64> = (0..3).map(|_| rng.next_f64() * 2.0 - 1.0).collect();
            for a in 0..3 {
                for b in 0..3 {
                    t.push((nodes[a] as u32, nodes[b] as u32, v[a] * v[b]));
                }
            }
        }
        CsrMatrix::from_triplets(n, &t).unwrap()
    }

    #[test]
    fn breakdown_is_shifted() {
        let mut shifted = 0;
        for seed in 0..200 {
            let a = element_spd(40, 30, seed);
            let n = a.n();
            let mut s = PcgIc0::new(n);
            s.factorise(&a).unwrap();
            let fi = s.factorisation_info();
            if fi.restarts > 0 {
                shifted += 1;
                assert!(fi.diagonal_shift > 0.0);
                let b = rhs(n, seed);
                let mut x = vec![0.0; n];
                let info = s.solve(&a, &b, &mut x, &PcgParams::default()).unwrap();
                assert!(info.converged);
                assert!(rel_residual(&a, &b, &x) < 1e-5);
            }
        }
        assert!(shifted > 0, "no IC(0) breakdown found");
        let mut s = PcgIc0::new(2);
        let mut bad = CsrMatrix::from_triplets(2, &[(0, 0, 1.0), (1, 1, -1.0)]).unwrap();
        assert!(matches!(
            s.factorise(&bad),
            Err(LinearSolverError::NotPositiveDefinite { row: 1, .. })
        ));
        bad.values_mut()[0] = f64::NAN;
        assert!(s.factorise(&bad).is_err());
    }

    #[test]
    fn errors() {
        let a = laplacian(4, 4, 1, 0.0);
        let mut s = PcgIc0::new(16);
        let mut x = vec![0.0; 16];
        assert_eq!(
            s.solve(&a, &[1.0; 16], &mut x, &PcgParams::default()),
            Err(LinearSolverError::NotFactorised)
        );
        s.factorise(&a).unwrap();
        assert!(matches!(
            s.solve(&a, &[1.0; 15], &mut x, &PcgParams::default()),
            Err(LinearSolverError::DimensionMismatch { .. })
        ));
    }
}
