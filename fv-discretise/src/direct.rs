//! Sparse direct solver: a thin wrapper around faer's sparse Cholesky (`LLᵀ`) and LU factorisations.
//!
//! The symbolic factorisation (fill-reducing ordering, elimination tree,
//! supernodes) is computed once per sparsity pattern with
//! `faer::sparse::linalg::solvers::{SymbolicLlt, SymbolicLu}` and reused by
//! every numeric factorisation of a matrix with the same pattern (same
//! [`CsrMatrix::pattern_id`], or an equal pattern). The CSR → CSC value
//! permutation is cached with it, so refactorising costs one scatter plus
//! faer's numeric factorisation. The LU goes through faer's low-level
//! interface (`faer::sparse::linalg::lu`): its numeric factors and its
//! scratch are kept and refilled, not allocated anew per factorisation and
//! per solve as faer's `Lu::try_new_with_symbolic` and `Solve` do (on the
//! Newton preconditioner of curved beams, refactorised hundreds of times,
//! those allocations and their page faults were a tenth of the LU's time).

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::lu::{self as sparse_lu, LuRef, NumericLu};
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Side};

use crate::csr::CsrMatrix;
use crate::linear_solver::{
    check_len, FactorisationInfo, LinearSolver, LinearSolverError, SolveInfo,
};

/// Which faer factorisation the [`DirectSolver`] uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DirectMethod {
    /// Sparse Cholesky `LLᵀ` of a symmetric positive definite matrix (only the lower triangle is read).
    Cholesky,
    /// Sparse LU with partial pivoting, for any nonsingular matrix.
    Lu,
}

/// Symbolic factorisation of either kind.
#[derive(Debug, Clone)]
enum Symbolic {
    /// Cholesky.
    Llt(SymbolicLlt<usize>),
    /// LU (faer's low-level symbolic factors).
    Lu(Box<sparse_lu::SymbolicLu<usize>>),
}

/// Numeric factorisation of either kind.
#[derive(Debug, Clone)]
enum Numeric {
    /// Cholesky.
    Llt(Llt<usize, f64>),
    /// LU: the factors are in [`DirectSolver::lu_numeric`].
    Lu,
}

/// faer's scratch memory with the size it was made for (cloned anew).
struct Scratch {
    size: StackReq,
    buffer: MemBuffer,
}

impl Scratch {
    fn new(size: StackReq) -> Self {
        Scratch {
            size,
            buffer: MemBuffer::new(size),
        }
    }

    fn try_new(size: StackReq) -> Result<Self, LinearSolverError> {
        let buffer =
            MemBuffer::try_new(size).map_err(|e| LinearSolverError::Direct(format!("{e:?}")))?;
        Ok(Scratch { size, buffer })
    }
}

impl Clone for Scratch {
    fn clone(&self) -> Self {
        Scratch::new(self.size)
    }
}

impl std::fmt::Debug for Scratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Scratch({:?})", self.size)
    }
}

/// Sparse direct solver (faer) behind the [`LinearSolver`] trait, reusing the symbolic factorisation.
#[derive(Debug, Clone)]
pub struct DirectSolver {
    /// Factorisation kind.
    method: DirectMethod,
    /// Pattern id of the cached symbolic data.
    pattern_id: Option<u64>,
    /// CSR pattern of the cached symbolic data (to recognise equal patterns with other ids).
    row_ptr: Vec<u32>,
    /// See `row_ptr`.
    col_idx: Vec<u32>,
    /// CSC structure handed to faer.
    csc: Option<SymbolicSparseColMat<usize>>,
    /// CSC position of each CSR value index.
    csr_to_csc: Vec<u32>,
    /// CSC values of the last factorised matrix.
    csc_values: Vec<f64>,
    /// Cached symbolic factorisation.
    symbolic: Option<Symbolic>,
    /// Last numeric factorisation.
    numeric: Option<Numeric>,
    /// LU factors, refilled by every numeric factorisation.
    lu_numeric: NumericLu<usize, f64>,
    /// Scratch of the LU's numeric factorisation and solves.
    lu_scratch: Scratch,
    /// Residual work vector.
    r: Vec<f64>,
    /// Diagnostics (the shift is always 0).
    info: FactorisationInfo,
}

impl DirectSolver {
    /// Creates a direct solver using `method`.
    pub fn new(method: DirectMethod) -> Self {
        DirectSolver {
            method,
            pattern_id: None,
            row_ptr: Vec::new(),
            col_idx: Vec::new(),
            csc: None,
            csr_to_csc: Vec::new(),
            csc_values: Vec::new(),
            symbolic: None,
            numeric: None,
            lu_numeric: NumericLu::new(),
            lu_scratch: Scratch::new(StackReq::EMPTY),
            r: Vec::new(),
            info: FactorisationInfo::default(),
        }
    }

    /// Direct solver using sparse Cholesky (symmetric positive definite matrices).
    pub fn cholesky() -> Self {
        Self::new(DirectMethod::Cholesky)
    }

    /// Direct solver using sparse LU (general matrices).
    pub fn lu() -> Self {
        Self::new(DirectMethod::Lu)
    }

    /// The factorisation kind.
    pub fn method(&self) -> DirectMethod {
        self.method
    }

    /// Reuse counters of the factorisations so far.
    pub fn factorisation_info(&self) -> FactorisationInfo {
        self.info
    }

    /// Whether the cached symbolic data fits `a`'s pattern.
    fn same_pattern(&self, a: &CsrMatrix) -> bool {
        self.symbolic.is_some()
            && (self.pattern_id == Some(a.pattern_id())
                || (self.row_ptr == a.row_ptr() && self.col_idx == a.col_idx()))
    }

    /// Rebuilds the CSC structure and faer's symbolic factorisation for `a`'s pattern.
    fn analyse(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        let n = a.n();
        let (col_ptr, row_idx, map) = a.csc_structure();
        let csc = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let symbolic = match self.method {
            DirectMethod::Cholesky => Symbolic::Llt(
                SymbolicLlt::try_new(csc.as_ref(), Side::Lower)
                    .map_err(|e| LinearSolverError::Direct(format!("{e:?}")))?,
            ),
            DirectMethod::Lu => {
                let s = sparse_lu::factorize_symbolic_lu(csc.as_ref(), Default::default())
                    .map_err(|e| LinearSolverError::Direct(format!("{e:?}")))?;
                let par = faer::get_global_parallelism();
                let need = s
                    .factorize_numeric_lu_scratch::<f64>(par, Default::default())
                    .or(s.solve_in_place_scratch::<f64>(1, par));
                self.lu_scratch = Scratch::try_new(need)?;
                Symbolic::Lu(Box::new(s))
            }
        };
        self.csc_values.clear();
        self.csc_values.resize(a.nnz(), 0.0);
        self.csr_to_csc = map;
        self.csc = Some(csc);
        self.symbolic = Some(symbolic);
        self.row_ptr = a.row_ptr().to_vec();
        self.col_idx = a.col_idx().to_vec();
        self.info.symbolic_analyses += 1;
        Ok(())
    }

    /// Factorises `a` with faer, reusing the symbolic factorisation when the pattern is unchanged.
    pub fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        self.numeric = None;
        if !self.same_pattern(a) {
            self.analyse(a)?;
        }
        self.pattern_id = Some(a.pattern_id());
        if a.values().iter().any(|v| !v.is_finite()) {
            return Err(LinearSolverError::NonFinite { what: "matrix" });
        }
        for (&v, &p) in a.values().iter().zip(&self.csr_to_csc) {
            self.csc_values[p as usize] = v;
        }
        let (Some(csc), Some(symbolic)) = (&self.csc, &self.symbolic) else {
            return Err(LinearSolverError::NotFactorised);
        };
        let mat = SparseColMatRef::new(csc.as_ref(), &self.csc_values);
        let numeric = match symbolic {
            Symbolic::Llt(s) => Numeric::Llt(
                Llt::try_new_with_symbolic(s.clone(), mat, Side::Lower)
                    .map_err(|e| LinearSolverError::Direct(format!("{e:?}")))?,
            ),
            Symbolic::Lu(s) => {
                s.factorize_numeric_lu(
                    &mut self.lu_numeric,
                    mat,
                    faer::get_global_parallelism(),
                    MemStack::new(&mut self.lu_scratch.buffer),
                    Default::default(),
                )
                .map_err(|e| LinearSolverError::Direct(format!("{e:?}")))?;
                Numeric::Lu
            }
        };
        self.numeric = Some(numeric);
        self.r.resize(a.n(), 0.0);
        self.info.numeric_factorisations += 1;
        Ok(())
    }

    /// Solves `a x = b` with the last factorisation; the input `x` only enters `initial_residual`.
    ///
    /// `a` is used for the residual norms only (pass the factorised matrix).
    /// `iterations` is 1; `converged` means the residual is finite.
    pub fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
    ) -> Result<SolveInfo, LinearSolverError> {
        if self.numeric.is_none() {
            return Err(LinearSolverError::NotFactorised);
        }
        let n = self.r.len();
        check_len("matrix", a.n(), n)?;
        check_len("b", b.len(), n)?;
        check_len("x", x.len(), n)?;
        let r0 = a.residual(b, x, &mut self.r);
        self.substitute(b, x)?;
        let r1 = a.residual(b, x, &mut self.r);
        Ok(SolveInfo {
            iterations: 1,
            initial_residual: r0,
            final_residual: r1,
            converged: r1.is_finite(),
        })
    }

    /// x = A⁻¹ b by the forward and backward substitutions of the last
    /// factorisation, without the residual norms of [`Self::solve`] (a
    /// preconditioner's application).
    pub fn substitute(&mut self, b: &[f64], x: &mut [f64]) -> Result<(), LinearSolverError> {
        let (Some(numeric), Some(symbolic)) = (&self.numeric, &self.symbolic) else {
            return Err(LinearSolverError::NotFactorised);
        };
        let n = self.r.len();
        check_len("b", b.len(), n)?;
        check_len("x", x.len(), n)?;
        x.copy_from_slice(b);
        let xm = MatMut::from_column_major_slice_mut(x, n, 1);
        match (numeric, symbolic) {
            (Numeric::Llt(f), _) => f.solve_in_place(xm),
            (Numeric::Lu, Symbolic::Lu(s)) => LuRef::new_unchecked(s, &self.lu_numeric)
                .solve_in_place_with_conj(
                    Conj::No,
                    xm,
                    faer::get_global_parallelism(),
                    MemStack::new(&mut self.lu_scratch.buffer),
                ),
            (Numeric::Lu, Symbolic::Llt(_)) => return Err(LinearSolverError::NotFactorised),
        }
        Ok(())
    }
}

impl LinearSolver for DirectSolver {
    fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        DirectSolver::factorise(self, a)
    }

    fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
    ) -> Result<SolveInfo, LinearSolverError> {
        DirectSolver::solve(self, a, b, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csr::test_util::*;

    #[test]
    fn cholesky_laplacian_3d() {
        let a = laplacian(20, 20, 20, 1e-3);
        let n = a.n();
        let mut d = DirectSolver::cholesky();
        d.factorise(&a).unwrap();
        for c in 0..3 {
            let b = rhs(n, c);
            let mut x = vec![0.0; n];
            let info = d.solve(&a, &b, &mut x).unwrap();
            assert!(info.converged);
            assert!(rel_residual(&a, &b, &x) < 1e-12);
        }
        // same values again, then scaled values: symbolic reused
        d.factorise(&a).unwrap();
        let mut a2 = a.clone();
        a2.values_mut().iter_mut().for_each(|v| *v *= 3.0);
        d.factorise(&a2).unwrap();
        // an equal pattern with another id is recognised too
        let a3 = laplacian(20, 20, 20, 1.0);
        assert_ne!(a3.pattern_id(), a.pattern_id());
        d.factorise(&a3).unwrap();
        let fi = d.factorisation_info();
        assert_eq!((fi.symbolic_analyses, fi.numeric_factorisations), (1, 4));
        let b = rhs(n, 9);
        let mut x = vec![0.0; n];
        d.solve(&a3, &b, &mut x).unwrap();
        assert!(rel_residual(&a3, &b, &x) < 1e-12);
    }

    #[test]
    fn lu_nonsymmetric_and_growth() {
        let mut a = convection_diffusion(15, 12, 10, [3.0, -1.0, 0.5]);
        let n = a.n();
        let mut d = DirectSolver::lu();
        d.factorise(&a).unwrap();
        let b = rhs(n, 4);
        let mut x = vec![0.0; n];
        d.solve(&a, &b, &mut x).unwrap();
        assert!(rel_residual(&a, &b, &x) < 1e-12);
        let g = a.add_entries(&[(3, 1500), (1700, 8)]).unwrap();
        for &s in &g.slots {
            a.values_mut()[s as usize] = -0.5;
        }
        d.factorise(&a).unwrap();
        assert_eq!(d.factorisation_info().symbolic_analyses, 2);
        d.solve(&a, &b, &mut x).unwrap();
        assert!(rel_residual(&a, &b, &x) < 1e-12);
    }

    #[test]
    fn cholesky_rejects_indefinite() {
        let a = CsrMatrix::from_triplets(2, &[(0, 0, 1.0), (1, 1, -2.0)]).unwrap();
        let mut d = DirectSolver::cholesky();
        assert!(matches!(d.factorise(&a), Err(LinearSolverError::Direct(_))));
        let mut x = [0.0; 2];
        assert_eq!(
            d.solve(&a, &[1.0, 1.0], &mut x),
            Err(LinearSolverError::NotFactorised)
        );
    }
}
