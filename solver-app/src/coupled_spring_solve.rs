//! The linear step of an outer iteration with the contact springs coupled
//! across the displacement components — beyond the thesis, which keeps the
//! off-diagonal parts of every tensor coefficient lagged (eq. 4.54 iv–v).
//!
//! A penalty spring k_n n⊗n + k_t (I − n⊗n) between two cells (implicit
//! coupling of deformable bodies, eqs. 4.60–4.72) is stiff against the
//! cells it joins once ε_n δ/K ≫ 1. The segregated solve keeps only its
//! diagonal k_n n_c² + k_t (1 − n_c²) in the matrix of component c; the
//! n_c n_d part goes to the next outer iteration. For a spring inclined to
//! the axes that splitting is poor both ways: without the lagged part in
//! the matrix each component takes up the whole normal approach (the gaps
//! zig-zag, and above ε_n δ/K ≈ 3 the iteration diverges); with it moved
//! onto the diagonal ([`crate::contact_coupling::CellSpring::component`])
//! the normal approach contracts, but a frictionless slide along an
//! inclined interface then meets a stiffness k_n that is not there and
//! converges, by a rough estimate, by the factor k_n/(K + k_n) per outer
//! iteration.
//!
//! Here the correction δ of all solved components solves the system with
//! the whole spring tensors, A δ = R, A = diag(A_c) + S_off (S_off the
//! springs' n_c n_d parts), by conjugate gradients preconditioned with the
//! components' own factorisations, one IC(0) application per component
//! ([`LinearSolver::precondition`]; a full component solve for solvers
//! without one, hence the flexible, Polak–Ribière form). A is symmetric
//! positive definite: the component matrices are, and each spring adds a
//! positive semi-definite 6×6 block. The residual R is the full one, as
//! before: the converged state does not change, only the path to it.
//!
//! Cost: the solve runs to `COUPLED_TOLERANCE`, not to the segregated
//! path's 0.1, and takes about 40 iterations on concentric cylinders and
//! 50 on the sphere–block mesh, so one outer iteration costs 3–4× a
//! segregated one; it is used only where the fewer outer iterations pay
//! for that ([`crate::contact_coupling`], `INCLINED_SHARE`).
//!
//! Written by hand: the operator is a sum of the project's CSR matrices and
//! a spring list, and the preconditioner is the project's own solvers; no
//! crate offers that combination.
use crate::contact_coupling::CellSpring;
use fv_discretise::{CsrMatrix, LinearSolver, LinearSolverError};

/// Relative residual of the coupled system at which the iteration stops
/// (or the linear tolerance of the case, if tighter). The component solves
/// of the segregated path stop at 0.1; here the frictionless slide along
/// the interface is the mode of the smallest eigenvalue, and a loose solve
/// leaves it behind: on concentric cylinders at ε_n/E = 1000, 1e-3 gives
/// 287 outer iterations, 1e-4 … 1e-6 give 123.
const COUPLED_TOLERANCE: f64 = 1e-4;

/// Workspaces of the coupled solve, allocated once per size.
#[derive(Default)]
pub struct CoupledSpringSolve {
    r: [Vec<f64>; 3],
    r_old: [Vec<f64>; 3],
    z: [Vec<f64>; 3],
    p: [Vec<f64>; 3],
    q: [Vec<f64>; 3],
}

/// What the coupled solve did.
#[derive(Debug, Clone, Copy, Default)]
pub struct CoupledSolveInfo {
    /// Iterations of the coupled system.
    pub iterations: usize,
    /// Iterations of the full component solves that stood in for the
    /// preconditioner (solvers without [`LinearSolver::precondition`]; 0
    /// with IC(0)).
    pub linear_iterations: usize,
}

impl CoupledSpringSolve {
    fn resize(&mut self, n: usize) {
        for v in self
            .r
            .iter_mut()
            .chain(self.r_old.iter_mut())
            .chain(self.z.iter_mut())
            .chain(self.p.iter_mut())
            .chain(self.q.iter_mut())
        {
            if v.len() != n {
                v.clear();
                v.resize(n, 0.0);
            }
        }
    }

    /// Solves A x = b for the solved components (`component_matrix[c]` is
    /// `Some`); `b[c]` is the residual of component c, `x[c]` receives the
    /// correction. `springs` are those assembled into the matrices (their
    /// off-diagonal tensor parts are added here). The iteration stops at the relative residual
    /// min(`tolerance`, `COUPLED_TOLERANCE`) or after `max_iterations`.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        matrices: &[CsrMatrix],
        component_matrix: &[Option<usize>; 3],
        solvers: &mut [Box<dyn LinearSolver + Send>],
        springs: &[CellSpring],
        b: &[Vec<f64>; 3],
        x: &mut [Vec<f64>; 3],
        tolerance: f64,
        max_iterations: usize,
    ) -> Result<CoupledSolveInfo, LinearSolverError> {
        let n = b[0].len();
        self.resize(n);
        // (component, its matrix) of the solved components
        let mut solved_buf = [(0usize, 0usize); 3];
        let mut n_solved = 0;
        for (c, m) in component_matrix.iter().enumerate() {
            if let Some(mi) = *m {
                solved_buf[n_solved] = (c, mi);
                n_solved += 1;
            }
        }
        let solved = &solved_buf[..n_solved];
        let tolerance = tolerance.min(COUPLED_TOLERANCE);
        let mut info = CoupledSolveInfo::default();
        let dot = |a: &[Vec<f64>; 3], b: &[Vec<f64>; 3]| -> f64 {
            solved
                .iter()
                .map(|&(c, _)| a[c].iter().zip(&b[c]).map(|(x, y)| x * y).sum::<f64>())
                .sum()
        };
        for &(c, _) in solved {
            x[c].iter_mut().for_each(|v| *v = 0.0);
            self.r[c].copy_from_slice(&b[c]);
        }
        let b_norm = dot(&self.r, &self.r).sqrt();
        if b_norm == 0.0 {
            return Ok(info);
        }
        // z = M⁻¹ r
        let precondition = |r: &[Vec<f64>; 3],
                            z: &mut [Vec<f64>; 3],
                            solvers: &mut [Box<dyn LinearSolver + Send>],
                            info: &mut CoupledSolveInfo|
         -> Result<(), LinearSolverError> {
            for &(c, mi) in solved {
                if !solvers[mi].precondition(&matrices[mi], &r[c], &mut z[c])? {
                    z[c].iter_mut().for_each(|v| *v = 0.0);
                    let si = solvers[mi].solve(&matrices[mi], &r[c], &mut z[c])?;
                    info.linear_iterations += si.iterations;
                }
            }
            Ok(())
        };
        precondition(&self.r, &mut self.z, solvers, &mut info)?;
        for &(c, _) in solved {
            self.p[c].copy_from_slice(&self.z[c]);
        }
        let mut rz = dot(&self.r, &self.z);
        for it in 1..=max_iterations {
            info.iterations = it;
            // q = A p
            for &(c, mi) in solved {
                matrices[mi].mul_vec(&self.p[c], &mut self.q[c]);
            }
            for sp in springs {
                let (a, bb) = (sp.cells.0 as usize, sp.cells.1 as usize);
                for &(c, _) in solved {
                    // the matrix holds the tensor's diagonal
                    let mut s = 0.0;
                    for &(d, _) in solved.iter().filter(|&&(d, _)| d != c) {
                        s += sp.tensor_off_diagonal(c, d) * (self.p[d][a] - self.p[d][bb]);
                    }
                    self.q[c][a] += s;
                    self.q[c][bb] -= s;
                }
            }
            let pq = dot(&self.p, &self.q);
            if !(pq > 0.0) {
                return Err(LinearSolverError::Breakdown {
                    method: "coupled spring CG",
                    iteration: it,
                    reason: "pᵀAp ≤ 0",
                });
            }
            let alpha = rz / pq;
            for &(c, _) in solved {
                let rows = x[c]
                    .iter_mut()
                    .zip(&mut self.r[c])
                    .zip(&mut self.r_old[c])
                    .zip(self.p[c].iter().zip(&self.q[c]));
                for (((xi, ri), ro), (pi, qi)) in rows {
                    *xi += alpha * pi;
                    *ro = *ri;
                    *ri -= alpha * qi;
                }
            }
            let r_norm = dot(&self.r, &self.r).sqrt();
            if r_norm <= tolerance * b_norm {
                break;
            }
            precondition(&self.r, &mut self.z, solvers, &mut info)?;
            // flexible (Polak–Ribière) β: the preconditioner is an inexact solve
            let rz_new = dot(&self.r, &self.z);
            let r_old_z = dot(&self.r_old, &self.z);
            let beta = (rz_new - r_old_z) / rz;
            rz = rz_new;
            for &(c, _) in solved {
                for (pi, zi) in self.p[c].iter_mut().zip(&self.z[c]) {
                    *pi = zi + beta * *pi;
                }
            }
        }
        Ok(info)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fv_discretise::PcgIc0;
    use fv_mesh::Vector;

    /// Two chains of `m` cells (two "bodies", each grounded at its outer
    /// end with stiffness `g`, inner coupling `c`) joined at their last
    /// cells by a spring inclined at 45° in x–y: the coupled solve must
    /// return the solution of the 2·2m system with the whole spring tensor.
    #[test]
    fn inclined_spring_solved_whole() {
        let m = 5;
        let n = 2 * m;
        let (g, c) = (1.0, 4.0);
        let spring = CellSpring {
            cells: ((m - 1) as u32, (2 * m - 1) as u32),
            stiffness: 50.0,
            tangential: 0.0,
            normal: Vector::new(1.0, 1.0, 0.0).normalize(),
            in_turn: false,
            coupled: true,
        };
        // one matrix per component: chain Laplacian + the spring's diagonal
        let mut matrices = Vec::new();
        for comp in 0..2 {
            let mut t = Vec::new();
            for body in 0..2 {
                let o = body * m;
                for i in 0..m {
                    let mut d = 0.0;
                    if i == 0 {
                        d += g;
                    }
                    if i + 1 < m {
                        d += c;
                        t.push(((o + i) as u32, (o + i + 1) as u32, -c));
                        t.push(((o + i + 1) as u32, (o + i) as u32, -c));
                    }
                    if i > 0 {
                        d += c;
                    }
                    t.push(((o + i) as u32, (o + i) as u32, d));
                }
            }
            let k = spring.tensor_diagonal(comp);
            let (a, b) = spring.cells;
            t.push((a, a, k));
            t.push((b, b, k));
            t.push((a, b, -k));
            t.push((b, a, -k));
            matrices.push(CsrMatrix::from_triplets(n, &t).unwrap());
        }
        let mut solvers: Vec<Box<dyn LinearSolver + Send>> = Vec::new();
        for a in &matrices {
            let mut s = PcgIc0::new(n);
            s.factorise(a).unwrap();
            solvers.push(Box::new(s));
        }
        // load: x on the first chain's end, y on the second's
        let mut b: [Vec<f64>; 3] = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        b[0][m - 1] = 1.0;
        b[1][2 * m - 1] = -0.5;
        let mut x: [Vec<f64>; 3] = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        let mut solve = CoupledSpringSolve::default();
        let info = solve
            .solve(
                &matrices,
                &[Some(0), Some(1), None],
                &mut solvers,
                &[spring],
                &b,
                &mut x,
                1e-12,
                100,
            )
            .unwrap();
        // dense reference: [A_x + S_xx, S_xy; S_yx, A_y + S_yy] with the
        // spring's off-diagonal k_n n_x n_y between the two components
        let dim = 2 * n;
        let mut dense = nalgebra::DMatrix::<f64>::zeros(dim, dim);
        for (comp, a) in matrices.iter().enumerate() {
            for i in 0..n {
                let (cols, vals) = a.row(i);
                for (&j, &v) in cols.iter().zip(vals) {
                    dense[(comp * n + i, comp * n + j as usize)] += v;
                }
            }
        }
        let (sa, sb) = (spring.cells.0 as usize, spring.cells.1 as usize);
        let kxy = spring.tensor_off_diagonal(0, 1);
        for (p, q, sign) in [(sa, sa, 1.0), (sb, sb, 1.0), (sa, sb, -1.0), (sb, sa, -1.0)] {
            dense[(p, n + q)] += sign * kxy;
            dense[(n + p, q)] += sign * kxy;
        }
        let rhs = nalgebra::DVector::from_iterator(dim, b[0].iter().chain(&b[1]).copied());
        let exact = dense.lu().solve(&rhs).unwrap();
        for i in 0..n {
            assert!((x[0][i] - exact[i]).abs() < 1e-9, "x[{i}]");
            assert!((x[1][i] - exact[n + i]).abs() < 1e-9, "y[{i}]");
            assert_eq!(x[2][i], 0.0);
        }
        // the spring couples the loads: the second chain moves in x too
        assert!(exact[2 * m - 1].abs() > 1e-3);
        assert!(info.iterations <= 2 * n, "{} iterations", info.iterations);
    }
}
