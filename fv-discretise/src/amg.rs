//! Conjugate gradients preconditioned by one V-cycle of aggregation
//! algebraic multigrid ([`hierarchy`]), and the V-cycle alone as a
//! preconditioner for an outer Krylov method.
//!
//! Written by hand: no maintained Rust crate offers algebraic multigrid
//! (faer-precond has IC/ILU, Jacobi, SSOR and sparse approximate inverses,
//! none of which reduces the smooth error of a large mesh). IC(0)-PCG needs
//! iterations in proportion to the cells across a body (about 33 per
//! component to a relative 0.1 inside Newton's preconditioner on the
//! 19,904-cell sphere on a block); one V-cycle does that work on the coarse
//! levels.
//!
//! The interface is [`crate::PcgIc0`]'s: factorise (here: build the
//! levels), then solve with a tolerance relative to the initial residual.
mod aggregation;
mod hierarchy;
mod sparse;

use crate::csr::CsrMatrix;
use crate::linear_solver::{
    check_len, krylov_start, FactorisationInfo, LinearSolver, LinearSolverError, SolveInfo,
};
use crate::pcg_ic0::PcgParams;
use hierarchy::Hierarchy;

/// PCG with an aggregation multigrid V-cycle as preconditioner.
/// The levels and all work vectors are kept from one factorisation to
/// the next; a solve allocates nothing after the first. The finest level
/// is the factorised matrix itself, not a copy: every solve and V-cycle
/// is given that matrix again (its pattern is checked, its values must be
/// the factorised ones).
#[derive(Debug, Clone, Default)]
pub struct PcgAmg {
    n: usize,
    params: PcgParams,
    hierarchy: Hierarchy,
    factorised: bool,
    info: FactorisationInfo,
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
}

impl PcgAmg {
    /// A solver for `n` unknowns with default [`PcgParams`] (the PCG work
    /// vectors are allocated by the first solve: a preconditioner that
    /// only applies V-cycles needs none).
    pub fn new(n: usize) -> Self {
        PcgAmg {
            n,
            ..Default::default()
        }
    }

    /// An error unless `a` is of the factorised matrix's pattern.
    fn check_factorised(&self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        if !self.factorised || !self.hierarchy.is_for(a) {
            return Err(LinearSolverError::NotFactorised);
        }
        check_len("matrix", a.n(), self.n)
    }

    /// Unknowns per level, finest first (after a factorisation).
    pub fn level_sizes(&self) -> Vec<usize> {
        self.hierarchy.level_sizes()
    }

    /// Entries of all the levels' operators over the finest one's.
    pub fn operator_complexity(&self) -> f64 {
        self.hierarchy.operator_complexity()
    }

    /// Builds the multigrid levels of `a` (symmetric, positive definite).
    pub fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        check_len("matrix", a.n(), self.n)?;
        self.factorised = false;
        self.hierarchy.build(a)?;
        self.info.numeric_factorisations += 1;
        self.factorised = true;
        Ok(())
    }

    /// `z = M⁻¹ r`: one V-cycle; `a` is the factorised matrix.
    pub fn apply_preconditioner(
        &mut self,
        a: &CsrMatrix,
        r: &[f64],
        z: &mut [f64],
    ) -> Result<(), LinearSolverError> {
        self.check_factorised(a)?;
        check_len("r", r.len(), self.n)?;
        check_len("z", z.len(), self.n)?;
        self.hierarchy.v_cycle(a, r, z);
        Ok(())
    }

    /// Solves `a x = b` by PCG to `‖r‖ ≤ tolerance ‖r₀‖`; `x` is the
    /// initial guess, `a` the factorised matrix.
    pub fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
        params: &PcgParams,
    ) -> Result<SolveInfo, LinearSolverError> {
        self.check_factorised(a)?;
        check_len("b", b.len(), self.n)?;
        check_len("x", x.len(), self.n)?;
        for v in [&mut self.r, &mut self.z, &mut self.p, &mut self.q] {
            v.resize(self.n, 0.0);
        }
        let (r, z, p, q) = (&mut self.r, &mut self.z, &mut self.p, &mut self.q);
        let (mut info, target) = krylov_start(a, b, x, r, params.tolerance, params.max_iterations)?;
        let Some(target) = target else {
            return Ok(info);
        };
        self.hierarchy.v_cycle(a, r, z);
        p.copy_from_slice(z);
        let mut rz: f64 = r.iter().zip(z.iter()).map(|(a, b)| a * b).sum();
        for it in 1..=params.max_iterations {
            a.mul_vec(p, q);
            let pq: f64 = p.iter().zip(q.iter()).map(|(a, b)| a * b).sum();
            if !(pq > 0.0) {
                return Err(LinearSolverError::Breakdown {
                    method: "PCG (AMG)",
                    iteration: it,
                    reason: "pᵀAp ≤ 0: matrix not positive definite",
                });
            }
            let alpha = rz / pq;
            let mut rr = 0.0;
            for i in 0..x.len() {
                x[i] += alpha * p[i];
                r[i] -= alpha * q[i];
                rr += r[i] * r[i];
            }
            let rn = rr.sqrt();
            info.record_pcg_residual(it, rn)?;
            if rn <= target {
                info.converged = true;
                break;
            }
            self.hierarchy.v_cycle(a, r, z);
            let rz_new: f64 = r.iter().zip(z.iter()).map(|(a, b)| a * b).sum();
            let beta = rz_new / rz;
            rz = rz_new;
            for (pi, &zi) in p.iter_mut().zip(z.iter()) {
                *pi = zi + beta * *pi;
            }
        }
        Ok(info)
    }
}

impl LinearSolver for PcgAmg {
    fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        PcgAmg::factorise(self, a)
    }

    fn solve(
        &mut self,
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
    ) -> Result<SolveInfo, LinearSolverError> {
        let params = self.params;
        PcgAmg::solve(self, a, b, x, &params)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PcgIc0;

    /// The 7-point Laplacian of an m³ grid of unit cells, held by a
    /// Dirichlet face on the bottom (the compact operator of eq. 3.29 on a
    /// box fixed at z = 0).
    fn box_laplacian(m: usize) -> CsrMatrix {
        let id = |i: usize, j: usize, k: usize| (i + m * (j + m * k)) as u32;
        let (mut owner, mut neighbour) = (Vec::new(), Vec::new());
        for k in 0..m {
            for j in 0..m {
                for i in 0..m {
                    for (di, dj, dk) in [(1, 0, 0), (0, 1, 0), (0, 0, 1)] {
                        if i + di < m && j + dj < m && k + dk < m {
                            owner.push(id(i, j, k));
                            neighbour.push(id(i + di, j + dj, k + dk));
                        }
                    }
                }
            }
        }
        let (mut a, slots) = CsrMatrix::from_faces(m * m * m, &owner, &neighbour);
        for (&u, &l) in slots.upper.iter().zip(&slots.lower) {
            a.values_mut()[u as usize] = -1.0;
            a.values_mut()[l as usize] = -1.0;
        }
        for i in 0..a.n() {
            let links = -a.row(i).1.iter().sum::<f64>();
            let bottom = if i < m * m { 2.0 } else { 0.0 };
            let d = a.diag_index()[i] as usize;
            a.values_mut()[d] = links + bottom;
        }
        a
    }

    #[test]
    fn multigrid_solves_the_box_laplacian_in_fewer_iterations_than_ic0() {
        let params = PcgParams {
            tolerance: 1e-8,
            max_iterations: 500,
        };
        let mut counts = Vec::new();
        for m in [12, 24] {
            let a = box_laplacian(m);
            let n = a.n();
            // right-hand side of a known solution
            let exact: Vec<f64> = (0..n).map(|i| ((i * 7919) % 101) as f64 / 101.0).collect();
            let mut b = vec![0.0; n];
            a.mul_vec(&exact, &mut b);
            let mut amg = PcgAmg::new(n);
            amg.factorise(&a).unwrap();
            let mut x = vec![0.0; n];
            let info = amg.solve(&a, &b, &mut x, &params).unwrap();
            assert!(info.converged);
            let err = x
                .iter()
                .zip(&exact)
                .map(|(x, e)| (x - e).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-5, "max error {err}");
            let mut ic = PcgIc0::new(n);
            ic.factorise(&a).unwrap();
            let mut y = vec![0.0; n];
            let ic_info = ic.solve(&a, &b, &mut y, &params).unwrap();
            assert!(amg.level_sizes().len() >= 2, "{:?}", amg.level_sizes());
            assert!(
                amg.operator_complexity() < 1.5,
                "{}",
                amg.operator_complexity()
            );
            counts.push((info.iterations, ic_info.iterations));
        }
        // measured: 19 / 27 on 12³, 26 / 45 on 24³ (to 1e-8): the gap
        // widens as the mesh is refined
        let ((amg12, ic12), (amg24, ic24)) = (counts[0], counts[1]);
        assert!(amg12 < ic12, "{counts:?}");
        assert!(3 * amg24 < 2 * ic24, "{counts:?}");
    }

    #[test]
    fn a_matrix_of_the_same_pattern_refills_the_levels_and_is_solved_as_well_as_by_a_fresh_set_up()
    {
        let mut a = box_laplacian(16);
        let n = a.n();
        let b: Vec<f64> = (0..n).map(|i| ((i * 31) % 17) as f64 - 8.0).collect();
        let mut reused = PcgAmg::new(n);
        reused.factorise(&a).unwrap();
        // stiffer bottom and a softer row: new values, same pattern
        for i in 0..n {
            let d = a.diag_index()[i] as usize;
            a.values_mut()[d] *= if i % 7 == 0 { 3.0 } else { 1.5 };
        }
        reused.factorise(&a).unwrap();
        let mut fresh = PcgAmg::new(n);
        fresh.factorise(&a).unwrap();
        let params = PcgParams {
            tolerance: 1e-10,
            max_iterations: 200,
        };
        let (mut x1, mut x2) = (vec![0.0; n], vec![0.0; n]);
        let i1 = reused.solve(&a, &b, &mut x1, &params).unwrap();
        let i2 = fresh.solve(&a, &b, &mut x2, &params).unwrap();
        assert!(i1.converged && i2.converged);
        // the aggregates of the first matrix serve the second as well
        assert!(i1.iterations <= i2.iterations + 2, "{i1:?} {i2:?}");
        let mut r = vec![0.0; n];
        let rn = a.residual(&b, &x1, &mut r);
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(rn <= 1e-10 * bn * 1.0001, "{rn} {bn}");
    }
}
