//! The [`LinearSolver`] trait shared by PCG + IC(0), BiCGStab + ILU(0) and the direct solver, and their error type.
//!
//! The iterative solvers are written by hand (no maintained crate offers a
//! cache-friendly IC(0)-PCG with a reusable factorisation); the direct
//! solver wraps faer.

use crate::csr::CsrMatrix;

/// Errors of the sparse storage and the linear solvers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinearSolverError {
    /// A vector or matrix has the wrong size.
    #[error("dimension mismatch in {what}: expected {expected}, got {found}")]
    DimensionMismatch {
        /// Which argument.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        found: usize,
    },
    /// An entry index lies outside the matrix.
    #[error("entry ({row}, {col}) lies outside the {n}x{n} matrix")]
    IndexOutOfBounds {
        /// Row index.
        row: u32,
        /// Column index.
        col: u32,
        /// Matrix size.
        n: usize,
    },
    /// The pattern needs more than `u32` indices.
    #[error("sparsity pattern too large for 32-bit indices ({nnz} entries)")]
    PatternTooLarge {
        /// Requested number of entries.
        nnz: usize,
    },
    /// `solve` was called before a successful `factorise`.
    #[error("solve called before a successful factorise")]
    NotFactorised,
    /// A diagonal entry is not positive where the method needs an SPD matrix.
    #[error("matrix is not positive definite: diagonal entry of row {row} is {value}")]
    NotPositiveDefinite {
        /// Row of the offending diagonal entry.
        row: usize,
        /// Its value.
        value: f64,
    },
    /// A zero diagonal entry makes the incomplete LU factorisation impossible.
    #[error("zero diagonal entry in row {row}")]
    ZeroPivot {
        /// Row of the zero diagonal entry.
        row: usize,
    },
    /// The incomplete factorisation kept breaking down despite diagonal shifting.
    #[error("incomplete factorisation broke down in row {row} even with diagonal shift {shift}")]
    FactorisationFailed {
        /// Row of the last failing pivot.
        row: usize,
        /// Largest shift tried.
        shift: f64,
    },
    /// NaN or infinity in the input or during the iterations.
    #[error("non-finite value in {what}")]
    NonFinite {
        /// Where it was found.
        what: &'static str,
    },
    /// The Krylov method broke down (e.g. `pᵀAp ≤ 0`: the matrix is not SPD).
    #[error("{method} breakdown at iteration {iteration}: {reason}")]
    Breakdown {
        /// Method name.
        method: &'static str,
        /// Iteration at which it happened.
        iteration: usize,
        /// What went wrong.
        reason: &'static str,
    },
    /// Error reported by faer's sparse direct factorisation.
    #[error("direct solver (faer): {0}")]
    Direct(String),
}

impl LinearSolverError {
    /// A conjugate-gradient iteration whose curvature `pᵀAp` is not
    /// positive: a breakdown (the matrix is not positive definite), or a
    /// non-finite iterate.
    pub fn pcg_curvature(iteration: usize, pq: f64) -> Self {
        if pq.is_finite() {
            LinearSolverError::Breakdown {
                method: "PCG",
                iteration,
                reason: "pᵀAp ≤ 0: matrix not positive definite",
            }
        } else {
            LinearSolverError::NonFinite {
                what: "PCG iteration",
            }
        }
    }
}

/// Outcome of one linear solve.
///
/// Residuals are absolute Euclidean norms: `initial_residual = ‖b − A x₀‖₂`
/// for the initial guess `x₀`; `final_residual` is the norm of the residual
/// at exit (the recursively updated one for the Krylov methods, the true one
/// for the direct solver). Convergence means
/// `final_residual ≤ tolerance · initial_residual`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolveInfo {
    /// Krylov iterations performed (1 for the direct solver, 0 if `x₀` already satisfied the tolerance).
    pub iterations: usize,
    /// `‖b − A x₀‖₂`.
    pub initial_residual: f64,
    /// Residual norm at exit.
    pub final_residual: f64,
    /// Whether the tolerance was met (`false`: `max_iterations` reached; `x` holds the last iterate).
    pub converged: bool,
}

impl SolveInfo {
    /// Records the residual norm `rn` after conjugate-gradient iteration
    /// `it`; a non-finite residual is an error.
    pub fn record_pcg_residual(&mut self, it: usize, rn: f64) -> Result<(), LinearSolverError> {
        self.iterations = it;
        self.final_residual = rn;
        if rn.is_finite() {
            Ok(())
        } else {
            Err(LinearSolverError::NonFinite {
                what: "PCG residual",
            })
        }
    }
}

/// Diagnostics of a solver's factorisations (the IC(0)/ILU(0) diagonal shift and reuse counters).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FactorisationInfo {
    /// Relative diagonal shift α of the last factorisation: the factor is that of `A + α diag(A)` (0 = unshifted).
    pub diagonal_shift: f64,
    /// Restarts the last factorisation needed after a non-positive (IC) or tiny (ILU) pivot.
    pub restarts: usize,
    /// Symbolic analyses since creation (pattern changes).
    pub symbolic_analyses: usize,
    /// IC(0) only: whether the last factor takes its off-diagonals from the
    /// matrix and stores only its diagonal (a graph without triangles, DIC).
    pub off_diagonals_of_matrix: bool,
    /// Numeric factorisations since creation.
    pub numeric_factorisations: usize,
}

/// A sparse linear solver: factorise once (per matrix), then solve any number of right-hand sides.
///
/// The solver holds its parameters (tolerance, iteration limit); the
/// implementors also offer inherent `solve` methods taking explicit
/// parameters — call through the trait as `LinearSolver::solve(&mut s, …)`
/// or via `dyn LinearSolver`.
pub trait LinearSolver {
    /// Computes (or recomputes, reusing the symbolic work when the pattern is unchanged) the factorisation of `a`.
    fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError>;

    /// Solves `a x = b` with the last factorisation; `x` holds the initial guess on input and the solution on output.
    ///
    /// `a` is the matrix the Krylov methods multiply with; it may differ in
    /// values from the factorised one (a lagged preconditioner), but must
    /// have the same size. The direct solver ignores `a` except for
    /// computing the residuals; IC(0) on a graph without triangles reads
    /// its off-diagonals in the sweeps (with a lagged `a`, the factorised
    /// pivots and `a`'s off-diagonals: still symmetric positive definite).
    fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
    ) -> Result<SolveInfo, LinearSolverError>;

    /// Solves `a x_k = b_k` for every right-hand side with the last
    /// factorisation (the displacement components of a segregated outer
    /// iteration); `info[k]` receives each solve's report. One after the
    /// other here; a solver may solve them side by side. Stops at the first
    /// error.
    fn solve_each(
        &mut self,
        a: &CsrMatrix,
        b: &[&[f64]],
        x: &mut [&mut [f64]],
        info: &mut [SolveInfo],
    ) -> Result<(), LinearSolverError> {
        solve_in_turn(self, a, b, x, info)
    }

    /// Applies the preconditioner of the last factorisation once, z = M⁻¹ r
    /// (for a caller's own Krylov iteration on a larger system whose
    /// diagonal blocks are the factorised matrices). `a` is the matrix last
    /// factorised: a preconditioner may read its coefficients rather than
    /// store them (IC(0) on a graph without triangles). Returns `false`,
    /// with `z` untouched, for solvers that have no cheap one; the caller
    /// then uses [`Self::solve`].
    fn precondition(
        &self,
        a: &CsrMatrix,
        r: &[f64],
        z: &mut [f64],
    ) -> Result<bool, LinearSolverError> {
        let _ = (a, r, z);
        Ok(false)
    }
}

/// [`LinearSolver::solve_each`] one right-hand side after the other.
pub fn solve_in_turn<S: LinearSolver + ?Sized>(
    solver: &mut S,
    a: &CsrMatrix,
    b: &[&[f64]],
    x: &mut [&mut [f64]],
    info: &mut [SolveInfo],
) -> Result<(), LinearSolverError> {
    check_len("right-hand sides", x.len(), b.len())?;
    check_len("infos", info.len(), b.len())?;
    for ((b, x), i) in b.iter().zip(x.iter_mut()).zip(info.iter_mut()) {
        *i = solver.solve(a, b, x)?;
    }
    Ok(())
}

/// The start of a Krylov solve: the initial residual `r = b − A x` and the
/// report of a solve that has not iterated yet, with the absolute target
/// `tolerance · ‖r₀‖`. `None` for the target when there is nothing to do
/// (`x` already exact, or no iterations allowed).
pub(crate) fn krylov_start(
    a: &CsrMatrix,
    b: &[f64],
    x: &[f64],
    r: &mut [f64],
    tolerance: f64,
    max_iterations: usize,
) -> Result<(SolveInfo, Option<f64>), LinearSolverError> {
    let r0 = a.residual(b, x, r);
    if !r0.is_finite() {
        return Err(LinearSolverError::NonFinite {
            what: "initial residual",
        });
    }
    let info = SolveInfo {
        iterations: 0,
        initial_residual: r0,
        final_residual: r0,
        converged: r0 == 0.0,
    };
    let target = (!info.converged && max_iterations > 0).then_some(tolerance * r0);
    Ok((info, target))
}

/// Checks that a slice has length `n`.
pub(crate) fn check_len(
    what: &'static str,
    found: usize,
    expected: usize,
) -> Result<(), LinearSolverError> {
    if found == expected {
        Ok(())
    } else {
        Err(LinearSolverError::DimensionMismatch {
            what,
            expected,
            found,
        })
    }
}
