//! BiCGStab with an ILU(0) preconditioner, for the nonsymmetric matrices of implicit contact coupling.
//!
//! Written by hand, like [`crate::pcg_ic0`]: no maintained crate offers a
//! cache-friendly preconditioned Krylov solver with a reusable incomplete
//! factorisation.
//!
//! ILU(0): `M = (I + L)(D + U)` with the pattern of `A` (zero fill-in),
//! computed row by row (IKJ order) with a dense position map; stored as
//! `M = (D + L D)(I + D⁻¹ U)`: two contiguous strict triangles plus `D⁻¹`,
//! the layout the IC(0) factor uses (the backward sweep reads no diagonal).
//! A pivot smaller than `10⁻¹⁰ |a_ii|` restarts the factorisation on
//! `A + α diag(A)` with `α = 10⁻³, 2·10⁻³, …` (reported by
//! [`BicgstabIlu0::factorisation_info`]); a zero diagonal entry is an error.
//!
//! BiCGStab (van der Vorst 1992) with right preconditioning, so the residual
//! it monitors is the true residual `b − A x` (up to rounding). Each
//! iteration runs five fused memory passes: the direction update fused with
//! the forward sweep of `M⁻¹p`, the backward sweep fused with the trailing
//! mat-vec `v = A p̂` and `r̂ᵀv`, `s = r − αv` fused with `‖s‖` and the forward
//! sweep of `M⁻¹s`, the backward sweep fused with `t = A ŝ`, `tᵀs`, `tᵀt`, and
//! the `x`, `r` update fused with `‖r‖` and `r̂ᵀr`. If `r̂ᵀr` (nearly)
//! vanishes the shadow residual is reset to `r`. [`BicgstabIlu0::solve`]
//! allocates nothing.

use crate::csr::{CsrMatrix, SplitFactor};
use crate::linear_solver::{
    check_len, krylov_start, FactorisationInfo, LinearSolver, LinearSolverError, SolveInfo,
};

/// First relative diagonal shift tried after an ILU(0) pivot breakdown.
const SHIFT_INITIAL: f64 = 1e-3;
/// Restarts allowed before giving up.
const MAX_RESTARTS: usize = 40;
/// A pivot must exceed this fraction of its (shifted) diagonal entry in magnitude.
const PIVOT_REL_MIN: f64 = 1e-10;
/// Sentinel of the position map.
const NONE: u32 = u32::MAX;

/// Stopping parameters of BiCGStab (same meaning as [`crate::pcg_ic0::PcgParams`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BicgstabParams {
    /// Stop when `‖r‖₂ ≤ tolerance · ‖r₀‖₂` (relative to the initial residual).
    pub tolerance: f64,
    /// Iteration limit (each iteration = two mat-vecs); reaching it returns `converged: false`.
    pub max_iterations: usize,
}

impl Default for BicgstabParams {
    fn default() -> Self {
        BicgstabParams {
            tolerance: 1e-6,
            max_iterations: 1000,
        }
    }
}

/// BiCGStab with an ILU(0) preconditioner; the factorisation and all work vectors are reused across solves.
#[derive(Debug, Clone, Default)]
pub struct BicgstabIlu0 {
    /// System size.
    n: usize,
    /// Parameters used by [`LinearSolver::solve`].
    params: BicgstabParams,
    /// The ILU(0) factor.
    factor: SplitFactor,
    /// Factorisation scratch aligned with A's values.
    lu: Vec<f64>,
    /// Dense column → value-index map of the current row (scratch).
    pos: Vec<u32>,
    /// Pattern the symbolic data was built for.
    pattern_id: Option<u64>,
    /// Whether `factor` is valid.
    factorised: bool,
    /// Diagnostics.
    info: FactorisationInfo,
    /// Residual (also holds `s`).
    r: Vec<f64>,
    /// Shadow residual.
    rhat: Vec<f64>,
    /// Search direction.
    p: Vec<f64>,
    /// `A p̂`.
    v: Vec<f64>,
    /// `M⁻¹ p`.
    ph: Vec<f64>,
    /// `M⁻¹ s`.
    sh: Vec<f64>,
    /// `A ŝ`.
    t: Vec<f64>,
}

impl BicgstabIlu0 {
    /// Creates a solver for `n` unknowns with default [`BicgstabParams`]; allocates the work vectors once.
    pub fn new(n: usize) -> Self {
        Self::with_params(n, BicgstabParams::default())
    }

    /// Creates a solver for `n` unknowns with the given parameters.
    pub fn with_params(n: usize, params: BicgstabParams) -> Self {
        let mut s = BicgstabIlu0 {
            params,
            ..Default::default()
        };
        s.resize(n);
        s
    }

    /// Parameters used by [`LinearSolver::solve`].
    pub fn params(&self) -> &BicgstabParams {
        &self.params
    }

    /// Mutable parameters used by [`LinearSolver::solve`].
    pub fn params_mut(&mut self) -> &mut BicgstabParams {
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
        for v in [
            &mut self.r,
            &mut self.rhat,
            &mut self.p,
            &mut self.v,
            &mut self.ph,
            &mut self.sh,
            &mut self.t,
        ] {
            v.clear();
            v.resize(n, 0.0);
        }
        self.pos.clear();
        self.pos.resize(n, NONE);
    }

    /// One ILU(0) attempt with relative shift `shift`; `Ok(None)` on success, `Ok(Some(row))` on a tiny pivot.
    fn numeric(&mut self, a: &CsrMatrix, shift: f64) -> Result<Option<usize>, LinearSolverError> {
        let n = a.n();
        let (rp, ci, dg) = (a.row_ptr(), a.col_idx(), a.diag_index());
        let lu = &mut self.lu;
        lu.clear();
        lu.extend_from_slice(a.values());
        let pos = &mut self.pos;
        let f = self.factor.parts_mut();
        let inv = f.inv_diag;
        for i in 0..n {
            let (s, d, e) = (rp[i] as usize, dg[i] as usize, rp[i + 1] as usize);
            let aii = lu[d];
            if aii == 0.0 {
                return Err(LinearSolverError::ZeroPivot { row: i });
            }
            if !aii.is_finite() {
                return Err(LinearSolverError::NonFinite { what: "matrix" });
            }
            lu[d] = aii * (1.0 + shift);
            for k in s..e {
                pos[ci[k] as usize] = k as u32;
            }
            for k in s..d {
                // lu[k] is final here: L_f,ij = l_ij u_jj; the multiplier is l_ij.
                let j = ci[k] as usize;
                let lij = lu[k] * inv[j];
                for m in dg[j] as usize + 1..rp[j + 1] as usize {
                    let pk = pos[ci[m] as usize];
                    if pk != NONE {
                        lu[pk as usize] -= lij * lu[m];
                    }
                }
            }
            for k in s..e {
                pos[ci[k] as usize] = NONE;
            }
            let piv = lu[d];
            if !piv.is_finite() {
                return Err(LinearSolverError::NonFinite { what: "matrix" });
            }
            if piv.abs() <= PIVOT_REL_MIN * aii.abs() * (1.0 + shift) {
                return Ok(Some(i));
            }
            inv[i] = 1.0 / piv;
        }
        // Split into the contiguous triangles (same order as A's rows):
        // L_f = L D as computed, U_b = D⁻¹ U.
        for i in 0..n {
            let (s, d, e) = (rp[i] as usize, dg[i] as usize, rp[i + 1] as usize);
            let l0 = f.lptr[i] as usize;
            f.lval[l0..l0 + (d - s)].copy_from_slice(&lu[s..d]);
            let u0 = f.uptr[i] as usize;
            let di = inv[i];
            for (ub, &u) in f.uval[u0..u0 + (e - d - 1)].iter_mut().zip(&lu[d + 1..e]) {
                *ub = u * di;
            }
        }
        Ok(None)
    }

    /// Computes the ILU(0) factorisation of `a`, reusing the symbolic data and buffers when the pattern is unchanged.
    ///
    /// Resizes the work vectors if `a`'s size differs from the one given to
    /// [`BicgstabIlu0::new`]. Tiny pivots trigger diagonal shifting (see the
    /// module documentation).
    pub fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        self.factorised = false;
        if a.n() != self.n {
            self.resize(a.n());
            self.pattern_id = None;
        }
        if self.pattern_id != Some(a.pattern_id()) {
            self.factor.set_pattern_from(a);
            self.pattern_id = Some(a.pattern_id());
            self.info.symbolic_analyses += 1;
        }
        let mut shift = 0.0;
        let mut restarts = 0;
        while let Some(row) = self.numeric(a, shift)? {
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
        self.factorised = true;
        Ok(())
    }

    /// Applies the factorised ILU(0) preconditioner, `z = M⁻¹ r` (one
    /// forward and one backward sweep), e.g. inside another Krylov method.
    /// Allocates nothing.
    pub fn apply_preconditioner(&self, r: &[f64], z: &mut [f64]) -> Result<(), LinearSolverError> {
        if !self.factorised {
            return Err(LinearSolverError::NotFactorised);
        }
        check_len("r", r.len(), self.n)?;
        check_len("z", z.len(), self.n)?;
        self.factor.apply(r, z);
        Ok(())
    }

    /// Solves `a x = b` by ILU(0)-preconditioned BiCGStab; `x` is the initial guess on input. Allocates nothing.
    ///
    /// `a` must have the factorised size; it may differ in values (and
    /// pattern) from the factorised matrix. Reaching `max_iterations` is not
    /// an error (`converged: false`); a breakdown (`r̂ᵀA p̂ = 0`, `A ŝ = 0`
    /// with `s ≠ 0`, `ω = 0`) is.
    pub fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
        params: &BicgstabParams,
    ) -> Result<SolveInfo, LinearSolverError> {
        const METHOD: &str = "BiCGStab";
        if !self.factorised {
            return Err(LinearSolverError::NotFactorised);
        }
        let n = self.n;
        check_len("matrix", a.n(), n)?;
        check_len("b", b.len(), n)?;
        check_len("x", x.len(), n)?;
        let fac = &self.factor;
        let dinv = fac.inv_diag();
        let (r, rhat, p, v, ph, sh, t) = (
            &mut self.r[..],
            &mut self.rhat[..],
            &mut self.p[..],
            &mut self.v[..],
            &mut self.ph[..],
            &mut self.sh[..],
            &mut self.t[..],
        );

        let (mut info, target) = krylov_start(a, b, x, r, params.tolerance, params.max_iterations)?;
        let Some(target) = target else {
            return Ok(info);
        };
        let r0 = info.initial_residual;
        rhat.copy_from_slice(r);
        let mut rr = r0 * r0;
        let mut rho_new = rr; // r̂ᵀr
        let (mut rho, mut alpha, mut omega) = (1.0, 1.0, 1.0);
        let mut restart = true;
        let mut rhat_norm = r0;

        for it in 1..=params.max_iterations {
            // Shadow-residual reset when r̂ᵀr nearly vanishes.
            if !restart && rho_new.abs() <= 1e-14 * rr.sqrt() * rhat_norm {
                rhat.copy_from_slice(r);
                rhat_norm = rr.sqrt();
                rho_new = rr;
                restart = true;
            }
            let beta = (rho_new / rho) * (alpha / omega);

            // Pass 1: p = r + β(p − ω v), forward sweep of p̂ = M⁻¹ p.
            let mut w_prev = 0.0;
            for i in 0..n {
                let pi = if restart {
                    r[i]
                } else {
                    r[i] + beta * (p[i] - omega * v[i])
                };
                p[i] = pi;
                let wi = fac.forward_row(i, pi, ph, w_prev) * dinv[i];
                ph[i] = wi;
                w_prev = wi;
            }
            restart = false;
            // Pass 2: backward sweep of p̂ (rows descending), trailing v = A p̂, r̂ᵀv.
            let mut rv = 0.0;
            let mut m = n;
            let mut z_next = 0.0;
            for i in (0..n).rev() {
                let zi = fac.backward_row(i, ph[i], ph, z_next);
                ph[i] = zi;
                z_next = zi;
                while m > 0 && a.min_col(m - 1) >= i {
                    m -= 1;
                    let vm = a.row_times(m, ph);
                    v[m] = vm;
                    rv += rhat[m] * vm;
                }
            }
            if !rv.is_finite() {
                return Err(LinearSolverError::NonFinite {
                    what: "BiCGStab iteration",
                });
            }
            if rv == 0.0 {
                return Err(LinearSolverError::Breakdown {
                    method: METHOD,
                    iteration: it,
                    reason: "r̂ᵀA p̂ = 0",
                });
            }
            alpha = rho_new / rv;
            // Pass 3: s = r − α v (in r), ‖s‖², forward sweep of ŝ = M⁻¹ s.
            let mut ss = 0.0;
            let mut w_prev = 0.0;
            for i in 0..n {
                let si = r[i] - alpha * v[i];
                r[i] = si;
                ss += si * si;
                let wi = fac.forward_row(i, si, sh, w_prev) * dinv[i];
                sh[i] = wi;
                w_prev = wi;
            }
            info.iterations = it;
            let sn = ss.sqrt();
            if sn <= target {
                for (xi, &phi) in x.iter_mut().zip(ph.iter()) {
                    *xi += alpha * phi;
                }
                info.final_residual = sn;
                info.converged = true;
                return Ok(info);
            }
            // Pass 4: backward sweep of ŝ (rows descending), trailing t = A ŝ, tᵀs, tᵀt.
            let (mut ts, mut tt) = (0.0, 0.0);
            let mut m = n;
            let mut z_next = 0.0;
            for i in (0..n).rev() {
                let zi = fac.backward_row(i, sh[i], sh, z_next);
                sh[i] = zi;
                z_next = zi;
                while m > 0 && a.min_col(m - 1) >= i {
                    m -= 1;
                    let tm = a.row_times(m, sh);
                    t[m] = tm;
                    ts += tm * r[m];
                    tt += tm * tm;
                }
            }
            if !(tt > 0.0) || !ts.is_finite() {
                return Err(if tt.is_finite() && ts.is_finite() {
                    LinearSolverError::Breakdown {
                        method: METHOD,
                        iteration: it,
                        reason: "A ŝ = 0 with s ≠ 0",
                    }
                } else {
                    LinearSolverError::NonFinite {
                        what: "BiCGStab iteration",
                    }
                });
            }
            omega = ts / tt;
            if omega == 0.0 {
                return Err(LinearSolverError::Breakdown {
                    method: METHOD,
                    iteration: it,
                    reason: "ω = 0 (stagnation)",
                });
            }
            // Pass 5: x += α p̂ + ω ŝ, r = s − ω t, ‖r‖², r̂ᵀr.
            rr = 0.0;
            rho = rho_new;
            rho_new = 0.0;
            for i in 0..n {
                x[i] += alpha * ph[i] + omega * sh[i];
                let ri = r[i] - omega * t[i];
                r[i] = ri;
                rr += ri * ri;
                rho_new += rhat[i] * ri;
            }
            let rn = rr.sqrt();
            info.final_residual = rn;
            if !rn.is_finite() {
                return Err(LinearSolverError::NonFinite {
                    what: "BiCGStab residual",
                });
            }
            if rn <= target {
                info.converged = true;
                return Ok(info);
            }
        }
        Ok(info)
    }
}

impl LinearSolver for BicgstabIlu0 {
    fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        BicgstabIlu0::factorise(self, a)
    }

    fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
    ) -> Result<SolveInfo, LinearSolverError> {
        let params = self.params;
        BicgstabIlu0::solve(self, a, b, x, &params)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csr::test_util::*;
    use crate::direct::DirectSolver;

    fn direct_lu(a: &CsrMatrix, b: &[f64]) -> Vec<f64> {
        let mut d = DirectSolver::lu();
        d.factorise(a).unwrap();
        let mut x = vec![0.0; a.n()];
        LinearSolver::solve(&mut d, a, b, &mut x).unwrap();
        x
    }

    fn check(a: &CsrMatrix, seed: u64) -> usize {
        let n = a.n();
        let b = rhs(n, seed);
        let mut s = BicgstabIlu0::new(n);
        s.factorise(a).unwrap();
        let mut x = vec![0.0; n];
        let info = s.solve(a, &b, &mut x, &BicgstabParams::default()).unwrap();
        assert!(info.converged, "{info:?}");
        let rel = rel_residual(a, &b, &x);
        assert!(rel <= 1e-6 * 1.01, "true residual {rel}");
        let mut xt = vec![0.0; n];
        let tight = BicgstabParams {
            tolerance: 1e-12,
            ..Default::default()
        };
        assert!(s.solve(a, &b, &mut xt, &tight).unwrap().converged);
        let diff = rel_diff(&xt, &direct_lu(a, &b));
        assert!(diff < 1e-8, "BiCGStab vs direct {diff}");
        info.iterations
    }

    #[test]
    fn convection_diffusion_3d() {
        let a = convection_diffusion(20, 20, 20, [2.0, -1.0, 0.5]);
        assert!(a.max_asymmetry() > 1.0);
        let it = check(&a, 1);
        assert!(it < 100, "{it}");
    }

    #[test]
    fn convection_diffusion_2d_strong() {
        let a = convection_diffusion(60, 60, 1, [20.0, 5.0, 0.0]);
        check(&a, 2);
    }

    #[test]
    fn symmetric_laplacian_and_random() {
        check(&laplacian(20, 20, 20, 1e-3), 3);
        check(&random_spd(2000, 4, 7), 4);
    }

    #[test]
    fn ilu0_is_exact_on_pattern() {
        let a = convection_diffusion(6, 5, 4, [1.0, 2.0, -3.0]);
        let n = a.n();
        let mut s = BicgstabIlu0::new(n);
        s.factorise(&a).unwrap();
        let f = &s.factor;
        let mut l = vec![0.0; n * n];
        let mut u = vec![0.0; n * n];
        // M = (D + L_f)(I + U_b)
        for i in 0..n {
            l[i * n + i] = 1.0 / f.inv_diag()[i];
            u[i * n + i] = 1.0;
            let (cols, vals) = f.lower().row(i);
            for (&c, &v) in cols.iter().zip(vals) {
                l[i * n + c as usize] = v;
            }
            let (cols, vals) = f.upper().row(i);
            for (&c, &v) in cols.iter().zip(vals) {
                u[i * n + c as usize] = v;
            }
        }
        for i in 0..n {
            let (cols, vals) = a.row(i);
            for (&j, &aij) in cols.iter().zip(vals) {
                let j = j as usize;
                let m: f64 = (0..n).map(|k| l[i * n + k] * u[k * n + j]).sum();
                assert!((m - aij).abs() < 1e-10 * (1.0 + aij.abs()));
            }
        }
    }

    #[test]
    fn factorisation_reused_and_contact_entries() {
        let mut a = convection_diffusion(10, 10, 6, [1.0, 0.0, -1.0]);
        let n = a.n();
        let mut s = BicgstabIlu0::new(n);
        LinearSolver::factorise(&mut s, &a).unwrap();
        for c in 0..3 {
            let b = rhs(n, 20 + c);
            let mut x = vec![0.0; n];
            let info = LinearSolver::solve(&mut s, &a, &b, &mut x).unwrap();
            assert!(info.converged);
            assert!(rel_residual(&a, &b, &x) <= 1e-6 * 1.01);
        }
        assert_eq!(s.factorisation_info().numeric_factorisations, 1);
        let b = rhs(n, 25);
        let mut x = vec![0.0; n];
        let before = allocations();
        assert!(
            s.solve(&a, &b, &mut x, &BicgstabParams::default())
                .unwrap()
                .converged
        );
        assert_eq!(allocations(), before, "BicgstabIlu0::solve allocated");
        // grow the pattern with nonsymmetric "contact" couplings between far cells
        let g = a
            .add_entries(&[(0, n as u32 - 1), (5, 300), (599, 2)])
            .unwrap();
        for &slot in &g.slots {
            a.values_mut()[slot as usize] = -0.3;
        }
        // lagged preconditioner with the new matrix still converges
        let b = rhs(n, 30);
        let mut x = vec![0.0; n];
        assert!(
            LinearSolver::solve(&mut s, &a, &b, &mut x)
                .unwrap()
                .converged
        );
        assert!(rel_residual(&a, &b, &x) <= 1e-6 * 1.01);
        s.factorise(&a).unwrap();
        assert_eq!(s.factorisation_info().symbolic_analyses, 2);
        check(&a, 31);
    }

    #[test]
    fn zero_pivot_is_an_error() {
        let a = CsrMatrix::from_triplets(2, &[(0, 1, 1.0), (1, 0, 1.0), (1, 1, 1.0)]).unwrap();
        let mut s = BicgstabIlu0::new(2);
        assert_eq!(
            s.factorise(&a),
            Err(LinearSolverError::ZeroPivot { row: 0 })
        );
    }
}
