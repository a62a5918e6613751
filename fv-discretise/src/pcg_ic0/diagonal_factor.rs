//! IC(0) on a graph without triangles, stored as its diagonal only
//! (OpenFOAM's DIC): `E` is `A`'s strict lower triangle, so
//! `d̃_i = a_ii (1 + shift) − Σ_{j<i} a_ij² / d̃_j` is all there is to
//! compute, and the sweeps read `A`'s values and pattern:
//! `t_i = r_i − Σ_{j<i} a_ij w_j`, `w_i = t_i / d̃_i`;
//! `z_i = w_i − Σ_{j>i} (a_ij / d̃_i) z_j` (`A` symmetric: `a_ij = a_ji = E_ji`).
//!
//! The same factor as [`super::full_factor::FullFactor`] on such a graph,
//! to the bit: its `E_ij = a_ij − Σ_k …` has no term, its pivots subtract
//! the same products in the same order, and its stored `E_ji · (1/d̃_i)` is
//! the product the backward sweep forms here.

use super::factor::Ic0Sweeps;
use crate::csr::CsrMatrix;
use crate::linear_solver::LinearSolverError;

/// `D̃⁻¹` of the DIC factor (see the module documentation).
#[derive(Debug, Clone, Default)]
pub(crate) struct DiagonalFactor {
    /// `1/d̃_i`.
    inv_diag: Vec<f64>,
}

impl DiagonalFactor {
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
        Ok(None)
    }
}

impl Ic0Sweeps for DiagonalFactor {
    fn inv_diag(&self) -> &[f64] {
        &self.inv_diag
    }

    #[inline(always)]
    fn forward_row(&self, a: &CsrMatrix, i: usize, rhs_i: f64, w: &[f64], w_prev: f64) -> f64 {
        a.forward_row_of_lower(i, rhs_i, w, w_prev)
    }

    #[inline(always)]
    fn backward_row(&self, a: &CsrMatrix, i: usize, w_i: f64, z: &[f64], z_next: f64) -> f64 {
        a.backward_row_of_upper(i, w_i, self.inv_diag[i], z, z_next)
    }
}
