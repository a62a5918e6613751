//! IC(0) on a graph without triangles (OpenFOAM's DIC): `E` is `A`'s
//! strict lower triangle, so `d̃_i = a_ii (1 + shift) − Σ_{j<i} a_ij² / d̃_j`
//! is all there is to compute. Forward sweep `t_i = r_i − Σ_{j<i} a_ij w_j`,
//! `w_i = t_i / d̃_i`, from a copy of `A`'s lower triangle; backward sweep
//! `z_i = w_i − Σ_{j>i} (a_ij / d̃_i) z_j` from `A`'s own upper triangle
//! (`A` symmetric: `a_ij = a_ji = E_ji`), which the PCG's backward pass
//! streams anyway for its trailing mat-vec.
//!
//! Why a copy of the lower triangle: `A`'s rows hold their lower and
//! upper entries side by side, so a sweep over either half of `A` streams
//! all of `A` (88 B per row on the 64³ box). Reading `A` in both sweeps
//! measured 20 % slower per PCG iteration than the stored factor (64³
//! Laplacian, 4.98 against 4.04 ms, the least of 12 interleaved runs at
//! load 3); with the compact lower triangle (40 B per row) the forward
//! pass streams what it did and the backward pass no `D̃⁻¹ Eᵀ`.
//!
//! The same factor as [`super::full_factor::FullFactor`] on such a graph,
//! to the bit: its `E_ij = a_ij − Σ_k …` has no term, its pivots subtract
//! the same products in the same order, and its stored `E_ji · (1/d̃_i)` is
//! the product the backward sweep forms here.

use super::factor::Ic0Sweeps;
use crate::csr::{CsrMatrix, TriCsr};
use crate::linear_solver::LinearSolverError;

/// `E = lower(A)` and `D̃⁻¹` of the DIC factor (see the module documentation).
#[derive(Debug, Clone, Default)]
pub(crate) struct DicFactor {
    /// `A`'s strict lower triangle.
    lower: TriCsr,
    /// `1/d̃_i`.
    inv_diag: Vec<f64>,
}

impl DicFactor {
    /// Sizes the diagonal for `n` rows.
    pub(crate) fn resize(&mut self, n: usize) {
        self.inv_diag.resize(n, 0.0);
    }

    /// One attempt with relative shift `shift`; `Ok(None)` on success,
    /// `Ok(Some(row))` on a pivot below `pivot_rel_min` of its diagonal entry.
    pub(crate) fn numeric(
        &mut self,
        a: &CsrMatrix,
        shift: f64,
        pivot_rel_min: f64,
    ) -> Result<Option<usize>, LinearSolverError> {
        let (rp, ci, av, dg) = (a.row_ptr(), a.col_idx(), a.values(), a.diag_index());
        let rd = &mut self.inv_diag;
        for i in 0..a.n() {
            let (s, di) = (rp[i] as usize, dg[i] as usize);
            let aii = av[di];
            if aii.is_nan() || aii <= 0.0 {
                return Err(LinearSolverError::NotPositiveDefinite { row: i, value: aii });
            }
            let mut d = aii * (1.0 + shift);
            for (&j, &aij) in ci[s..di].iter().zip(&av[s..di]) {
                d -= aij * aij * rd[j as usize];
            }
            if !d.is_finite() {
                return Err(LinearSolverError::NonFinite { what: "matrix" });
            }
            if d <= pivot_rel_min * aii * (1.0 + shift) {
                return Ok(Some(i));
            }
            rd[i] = 1.0 / d;
        }
        self.lower.set_lower_of(a);
        Ok(None)
    }
}

impl DicFactor {
    /// `A`'s strict lower triangle (the forward sweep's `E`).
    pub(crate) fn lower(&self) -> &TriCsr {
        &self.lower
    }
}

impl Ic0Sweeps for DicFactor {
    fn inv_diag(&self) -> &[f64] {
        &self.inv_diag
    }

    #[inline(always)]
    fn forward_row(&self, _a: &CsrMatrix, i: usize, rhs_i: f64, w: &[f64], w_prev: f64) -> f64 {
        self.lower.forward_row(i, rhs_i, w, w_prev)
    }

    #[inline(always)]
    fn backward_row(&self, a: &CsrMatrix, i: usize, w_i: f64, z: &[f64], z_next: f64) -> f64 {
        a.backward_row_of_upper(i, w_i, self.inv_diag[i], z, z_next)
    }

    /// The backward pass with `q = A p` in step with the sweep, from the
    /// row's diagonal and upper part only (`A` symmetric): row i gathers
    /// `q_i = a_ii p_i + Σ_{j>i} a_ij p_j` and scatters `a_ij p_i` into the
    /// rows j > i it is the lower part of (already gathered), and
    /// `pᵀq = Σ_i p_i (a_ii p_i + 2 Σ_{j>i} a_ij p_j)`. Each row of `A` is
    /// read once, by the sweep and the mat-vec together. `z`, `p` and `x`
    /// as [`Ic0Sweeps::backward_pass`] to the bit; `q` and `pᵀq` summed in
    /// another order (round-off).
    fn backward_pass(
        &self,
        a: &CsrMatrix,
        w: &mut [f64],
        p: &mut [f64],
        x: &mut [f64],
        q: &mut [f64],
        alpha: f64,
        beta: Option<f64>,
    ) -> f64 {
        let n = self.inv_diag.len();
        assert!(
            a.n() == n && w.len() == n && p.len() == n && x.len() == n && q.len() == n,
            "backward_pass: length mismatch"
        );
        let mut pq = 0.0;
        let mut z_next = 0.0;
        for i in (0..n).rev() {
            let zi = a.backward_row_of_upper(i, w[i], self.inv_diag[i], w, z_next);
            w[i] = zi;
            z_next = zi;
            let pi = match beta {
                None => zi,
                Some(beta) => {
                    x[i] += alpha * p[i];
                    zi + beta * p[i]
                }
            };
            p[i] = pi;
            let (aii, upper) = a.diagonal_and_upper(i);
            let mut s = 0.0;
            for (&c, &v) in upper.0.iter().zip(upper.1) {
                let c = c as usize;
                s += v * p[c];
                q[c] += v * pi;
            }
            q[i] = aii * pi + s;
            pq += pi * (aii * pi + 2.0 * s);
        }
        pq
    }
}
