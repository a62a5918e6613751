//! IC(0) with its triangles stored: `E` (strict lower, CSR) and `D̃⁻¹ Eᵀ`
//! (CSR of the scaled transpose, so the backward sweep gathers instead of
//! scattering), for graphs with triangles (tetrahedral and polyhedral
//! meshes), where `E` differs from `A`'s lower triangle.
//!
//! `E_ij = a_ij − Σ_{k<j} E_ik E_jk / d̃_k` ((i,j) in the pattern, i > j, k
//! in both rows), `d̃_i = a_ii (1 + shift) − Σ_{k<i} E_ik² / d̃_k`, computed
//! up-looking row by row.

use super::factor::Ic0Sweeps;
use crate::csr::{CsrMatrix, SplitFactor};
use crate::linear_solver::LinearSolverError;

/// `E`, `D̃⁻¹ Eᵀ` and `D̃⁻¹` (see the module documentation).
#[derive(Debug, Clone, Default)]
pub(crate) struct FullFactor {
    /// `L_f = E`, `U_b = D̃⁻¹ Eᵀ`, `D̃⁻¹`.
    pub(crate) factor: SplitFactor,
    /// Upper-triangle position of each lower-triangle entry (transpose map).
    lower_to_upper: Vec<u32>,
    /// Pattern the symbolic data was built for.
    pattern_id: Option<u64>,
}

impl FullFactor {
    /// Builds the factor pattern for `a`'s pattern unless it is the one
    /// built last.
    pub(crate) fn prepare(&mut self, a: &CsrMatrix) {
        if self.pattern_id == Some(a.pattern_id()) && self.factor.inv_diag().len() == a.n() {
            return;
        }
        self.factor
            .set_pattern_transposed_from(a, &mut self.lower_to_upper);
        self.pattern_id = Some(a.pattern_id());
    }

    /// One IC(0) attempt with relative shift `shift`; `Ok(None)` on success,
    /// `Ok(Some(row))` on a pivot below `pivot_rel_min` of its diagonal entry.
    pub(crate) fn numeric(
        &mut self,
        a: &CsrMatrix,
        shift: f64,
        pivot_rel_min: f64,
    ) -> Result<Option<usize>, LinearSolverError> {
        let n = a.n();
        let (rp, av, dg) = (a.row_ptr(), a.values(), a.diag_index());
        let f = self.factor.parts_mut();
        let (lptr, lcol) = (f.lptr, f.lcol);
        // E is built in the lower value array (L_f = E).
        let e = f.lval;
        let rd = f.inv_diag;
        for i in 0..n {
            let aii = av[dg[i] as usize];
            if aii.is_nan() || aii <= 0.0 {
                return Err(LinearSolverError::NotPositiveDefinite { row: i, value: aii });
            }
            let (ls, le) = (lptr[i] as usize, lptr[i + 1] as usize);
            let a_row = rp[i] as usize; // lower entries of A's row i start here, in the same order
            let mut d = aii * (1.0 + shift);
            for k in ls..le {
                let j = lcol[k] as usize;
                let mut s = av[a_row + (k - ls)];
                // Σ over k' < j in both row i (entries ls..k) and row j (all its lower entries).
                let (mut p1, mut p2, e2) = (ls, lptr[j] as usize, lptr[j + 1] as usize);
                while p1 < k && p2 < e2 {
                    let (c1, c2) = (lcol[p1], lcol[p2]);
                    if c1 == c2 {
                        s -= e[p1] * e[p2] * rd[c1 as usize];
                        p1 += 1;
                        p2 += 1;
                    } else if c1 < c2 {
                        p1 += 1;
                    } else {
                        p2 += 1;
                    }
                }
                e[k] = s;
                d -= s * s * rd[j];
            }
            if !d.is_finite() {
                return Err(LinearSolverError::NonFinite { what: "matrix" });
            }
            if d <= pivot_rel_min * aii * (1.0 + shift) {
                return Ok(Some(i));
            }
            rd[i] = 1.0 / d;
        }
        // L_f = E stays; U_b = D̃⁻¹ Eᵀ: lower entry (i, j) becomes upper entry (j, i), scaled by 1/d̃_j.
        for (k, &ek) in e.iter().enumerate() {
            f.uval[self.lower_to_upper[k] as usize] = ek * rd[lcol[k] as usize];
        }
        Ok(None)
    }
}

impl Ic0Sweeps for FullFactor {
    fn inv_diag(&self) -> &[f64] {
        self.factor.inv_diag()
    }

    #[inline(always)]
    fn forward_row(&self, _a: &CsrMatrix, i: usize, rhs_i: f64, w: &[f64], w_prev: f64) -> f64 {
        self.factor.forward_row(i, rhs_i, w, w_prev)
    }

    #[inline(always)]
    fn backward_row(&self, _a: &CsrMatrix, i: usize, w_i: f64, z: &[f64], z_next: f64) -> f64 {
        self.factor.backward_row(i, w_i, z, z_next)
    }
}
