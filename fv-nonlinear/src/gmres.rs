//! Restarted GMRES with right preconditioning (Saad & Schultz 1986; Saad,
//! *Iterative Methods for Sparse Linear Systems*, Alg. 9.5).
//!
//! Written by hand: faer 0.24 offers conjugate gradients, BiCGStab and
//! LSMR for matrix-free operators but no GMRES, and the Jacobian of a
//! contact problem is neither symmetric nor definite enough for the first
//! two to be reliable (BiCGStab breaks down on it; measured in
//! `benches/`). Right preconditioning keeps the residual the method
//! minimises the true one, ‖b − A x‖, which is what the Newton forcing term
//! bounds.
//!
//! With [`GmresParams::flexible`] it is Saad's flexible GMRES (FGMRES,
//! SIAM J. Sci. Comput. 14, 1993): the preconditioned vectors z_j are kept
//! and the update is x += Z y, so the preconditioner may change from one
//! iteration to the next — an inner Krylov solve, which costs far less
//! than the residual evaluation behind each outer iteration.
//!
//! Orthogonalisation is modified Gram–Schmidt with one reorthogonalisation
//! pass when the new vector lost more than [`REORTHOGONALISE`] of its norm
//! (Daniel–Gragg–Kaufman–Stewart). The workspace — the Krylov basis of
//! `restart + 1` vectors and the Hessenberg matrix — is allocated once
//! ([`Gmres::new`]); a solve allocates nothing.
use crate::problem::Inadmissible;
use crate::vector_ops::{axpy, dot, norm, release_pages, scale};

/// Reorthogonalise when ‖w‖ after Gram–Schmidt is below this fraction of
/// its norm before.
const REORTHOGONALISE: f64 = 1e-3;

/// A linear operator A and a right preconditioner M⁻¹ ≈ A⁻¹.
pub trait KrylovSystem {
    /// `out = A v`.
    fn apply(&mut self, v: &[f64], out: &mut [f64]) -> Result<(), Inadmissible>;
    /// `z = M⁻¹ r`.
    fn precondition(&mut self, r: &[f64], z: &mut [f64]);
}

/// Stopping and restart parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresParams {
    /// Krylov vectors per cycle before a restart.
    pub restart: usize,
    /// Most iterations (operator applications) in all.
    pub max_iterations: usize,
    /// Relative target: stop when ‖b − A x‖ ≤ tolerance ‖b − A x₀‖.
    pub tolerance: f64,
    /// Flexible GMRES: the preconditioner may vary between iterations
    /// (one more vector per iteration is kept).
    pub flexible: bool,
}

impl Default for GmresParams {
    fn default() -> Self {
        GmresParams {
            restart: 30,
            max_iterations: 300,
            tolerance: 1e-2,
            flexible: false,
        }
    }
}

/// Outcome of a solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GmresInfo {
    /// Operator applications (Krylov iterations).
    pub iterations: usize,
    /// ‖b − A x₀‖.
    pub initial_residual: f64,
    /// The residual norm at exit as GMRES estimates it (exact in exact
    /// arithmetic; checked against the true one at every restart).
    pub final_residual: f64,
    /// Whether the target was reached.
    pub converged: bool,
    /// Whether the solve stopped short of the target because a restart
    /// cycle no longer reduced the residual ([`STAGNATION`]).
    pub stagnated: bool,
}

/// A restart cycle that ends above this fraction of the residual it
/// started from ends the solve, once the residual is below
/// [`STAGNATION_BELOW`] of the initial one: restarted GMRES that has
/// stalled gains little from further cycles (measured on the sphere on a
/// block at ε_n/E = 1000: a Newton step asked for 9.4 × 10⁻³ and spent 200
/// iterations — seven cycles — to reach 1.3 × 10⁻², a quarter of all the
/// run's Krylov iterations).
pub const STAGNATION: f64 = 0.5;
/// See [`STAGNATION`]: the loosest forcing term of Newton's method, so that
/// a stalled solve still gives a step as good as an inexact Newton step.
pub const STAGNATION_BELOW: f64 = 0.1;

/// GMRES(m) and its workspace.
#[derive(Debug, Clone, Default)]
pub struct Gmres {
    n: usize,
    restart: usize,
    /// Krylov basis v_0 … v_m.
    basis: Vec<Vec<f64>>,
    /// The preconditioned basis z_0 … z_{m−1} (flexible GMRES only).
    preconditioned: Vec<Vec<f64>>,
    /// Hessenberg matrix, column j at `j * (restart + 1)`.
    hessenberg: Vec<f64>,
    /// Givens rotations.
    cos: Vec<f64>,
    sin: Vec<f64>,
    /// Right-hand side of the small least-squares problem.
    g: Vec<f64>,
    /// Its solution.
    y: Vec<f64>,
    /// Work vectors.
    w: Vec<f64>,
    z: Vec<f64>,
}

impl Gmres {
    /// Workspace for `n` unknowns and `restart` vectors per cycle (and
    /// as many preconditioned ones when `flexible`).
    pub fn new(n: usize, restart: usize, flexible: bool) -> Self {
        let m = restart.max(1);
        Gmres {
            n,
            restart: m,
            basis: (0..=m).map(|_| vec![0.0; n]).collect(),
            preconditioned: if flexible {
                (0..m).map(|_| vec![0.0; n]).collect()
            } else {
                Vec::new()
            },
            hessenberg: vec![0.0; (m + 1) * m],
            cos: vec![0.0; m],
            sin: vec![0.0; m],
            g: vec![0.0; m + 1],
            y: vec![0.0; m],
            w: vec![0.0; n],
            z: vec![0.0; n],
        }
    }

    /// Bytes held by the workspace.
    pub fn memory_bytes(&self) -> usize {
        8 * (self.n * (self.basis.len() + self.preconditioned.len() + 2)
            + self.hessenberg.len()
            + 4 * self.restart)
    }

    /// Returns the pages of the Krylov vectors to the operating system
    /// (their contents are dead between solves: every vector is written
    /// before it is read); the next solve touches them again as it needs
    /// them. Between the increments of a run that writes its fields, the
    /// basis of the last solve would otherwise stay resident through the
    /// output (at 64³: ~140 MB of the peak).
    pub fn release_pages(&mut self) {
        for v in self
            .basis
            .iter_mut()
            .chain(self.preconditioned.iter_mut())
            .chain([&mut self.w, &mut self.z])
        {
            release_pages(v);
        }
    }

    /// Solves A x = b; `x` holds the initial guess on entry. A different
    /// system size or restart length than [`Gmres::new`]'s reallocates; a
    /// flexible solve allocates the preconditioned basis if the workspace
    /// has none (a plain one leaves it unused: its pages are not touched).
    pub fn solve(
        &mut self,
        sys: &mut dyn KrylovSystem,
        b: &[f64],
        x: &mut [f64],
        params: &GmresParams,
    ) -> Result<GmresInfo, Inadmissible> {
        if b.len() != self.n || params.restart.max(1) != self.restart {
            *self = Gmres::new(b.len(), params.restart, params.flexible);
        } else if params.flexible && self.preconditioned.is_empty() {
            self.preconditioned = (0..self.restart).map(|_| vec![0.0; self.n]).collect();
        }
        let flexible = params.flexible;
        let m = self.restart;
        let mut info = GmresInfo::default();
        let x_zero = x.iter().all(|v| *v == 0.0);
        let mut target = 0.0;
        let mut cycle_start = f64::INFINITY;
        loop {
            // r = b − A x into v_0
            {
                let r = &mut self.basis[0];
                if x_zero && info.iterations == 0 {
                    r.copy_from_slice(b);
                } else {
                    sys.apply(x, &mut self.w)?;
                    for ((ri, bi), ai) in r.iter_mut().zip(b).zip(&self.w) {
                        *ri = bi - ai;
                    }
                }
            }
            let beta = norm(&self.basis[0]);
            if !beta.is_finite() {
                return Err(Inadmissible("GMRES: non-finite residual".into()));
            }
            if info.iterations == 0 {
                info.initial_residual = beta;
                target = params.tolerance * beta;
            }
            info.final_residual = beta;
            if beta <= target || beta == 0.0 {
                info.converged = true;
                return Ok(info);
            }
            if info.iterations >= params.max_iterations {
                return Ok(info);
            }
            if info.iterations > 0
                && beta > STAGNATION * cycle_start
                && beta <= STAGNATION_BELOW * info.initial_residual
            {
                info.stagnated = true;
                return Ok(info);
            }
            cycle_start = beta;
            scale(1.0 / beta, &mut self.basis[0]);
            self.g.iter_mut().for_each(|v| *v = 0.0);
            self.g[0] = beta;
            let mut k = 0; // columns built in this cycle
            while k < m && info.iterations < params.max_iterations {
                let j = k;
                // w = A M⁻¹ v_j (z_j kept when flexible)
                let z = if flexible {
                    &mut self.preconditioned[j]
                } else {
                    &mut self.z
                };
                sys.precondition(&self.basis[j], z);
                sys.apply(z, &mut self.w)?;
                info.iterations += 1;
                let before = norm(&self.w);
                let col = j * (m + 1);
                for i in 0..=j {
                    let h = dot(&self.w, &self.basis[i]);
                    self.hessenberg[col + i] = h;
                    axpy(-h, &self.basis[i], &mut self.w);
                }
                let mut after = norm(&self.w);
                if after < REORTHOGONALISE * before {
                    for i in 0..=j {
                        let h = dot(&self.w, &self.basis[i]);
                        self.hessenberg[col + i] += h;
                        axpy(-h, &self.basis[i], &mut self.w);
                    }
                    after = norm(&self.w);
                }
                if !after.is_finite() {
                    return Err(Inadmissible("GMRES: non-finite Krylov vector".into()));
                }
                self.hessenberg[col + j + 1] = after;
                // previous rotations on the new column, then its own
                for i in 0..j {
                    let (a, c) = (self.hessenberg[col + i], self.hessenberg[col + i + 1]);
                    self.hessenberg[col + i] = self.cos[i] * a + self.sin[i] * c;
                    self.hessenberg[col + i + 1] = -self.sin[i] * a + self.cos[i] * c;
                }
                let (a, c) = (self.hessenberg[col + j], self.hessenberg[col + j + 1]);
                let r = a.hypot(c);
                let (cs, sn) = if r == 0.0 { (1.0, 0.0) } else { (a / r, c / r) };
                self.cos[j] = cs;
                self.sin[j] = sn;
                self.hessenberg[col + j] = r;
                self.hessenberg[col + j + 1] = 0.0;
                self.g[j + 1] = -sn * self.g[j];
                self.g[j] *= cs;
                k = j + 1;
                info.final_residual = self.g[k].abs();
                let breakdown = after == 0.0;
                if info.final_residual <= target || breakdown {
                    break;
                }
                self.basis[j + 1].copy_from_slice(&self.w);
                scale(1.0 / after, &mut self.basis[j + 1]);
            }
            // y = H⁻¹ g (upper triangular k × k), x += M⁻¹ V y
            for i in (0..k).rev() {
                let mut s = self.g[i];
                for l in i + 1..k {
                    s -= self.hessenberg[l * (m + 1) + i] * self.y[l];
                }
                let d = self.hessenberg[i * (m + 1) + i];
                self.y[i] = if d != 0.0 { s / d } else { 0.0 };
            }
            if flexible {
                for i in 0..k {
                    axpy(self.y[i], &self.preconditioned[i], x);
                }
            } else {
                self.w.iter_mut().for_each(|v| *v = 0.0);
                for i in 0..k {
                    axpy(self.y[i], &self.basis[i], &mut self.w);
                }
                sys.precondition(&self.w, &mut self.z);
                axpy(1.0, &self.z, x);
            }
            if info.final_residual <= target {
                info.converged = true;
                return Ok(info);
            }
            if info.iterations >= params.max_iterations {
                return Ok(info);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dense test matrix with a Jacobi preconditioner.
    struct Dense {
        n: usize,
        a: Vec<f64>,
        jacobi: bool,
    }

    impl KrylovSystem for Dense {
        fn apply(&mut self, v: &[f64], out: &mut [f64]) -> Result<(), Inadmissible> {
            for (o, row) in out.iter_mut().zip(self.a.chunks_exact(self.n)) {
                *o = row.iter().zip(v).map(|(a, v)| a * v).sum();
            }
            Ok(())
        }
        fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
            for i in 0..self.n {
                z[i] = if self.jacobi {
                    r[i] / self.a[i * self.n + i]
                } else {
                    r[i]
                };
            }
        }
    }

    /// A nonsymmetric convection–diffusion matrix (1-D upwind), badly
    /// scaled rows.
    fn convection_diffusion(n: usize) -> Dense {
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            let s = 1.0 + 100.0 * (i % 3) as f64;
            a[i * n + i] = 3.0 * s;
            if i > 0 {
                a[i * n + i - 1] = -2.0 * s;
            }
            if i + 1 < n {
                a[i * n + i + 1] = -0.5 * s;
            }
        }
        Dense { n, a, jacobi: true }
    }

    #[test]
    fn solves_a_nonsymmetric_system_to_the_asked_residual_with_restarts() {
        let n = 120;
        let mut sys = convection_diffusion(n);
        let x_true: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin()).collect();
        let mut b = vec![0.0; n];
        sys.apply(&x_true, &mut b).unwrap();
        for (restart, flexible) in [(5, false), (20, false), (150, false), (5, true), (20, true)] {
            let mut x = vec![0.0; n];
            let mut g = Gmres::new(n, restart, flexible);
            let params = GmresParams {
                restart,
                max_iterations: 2000,
                tolerance: 1e-10,
                flexible,
            };
            let info = g.solve(&mut sys, &b, &mut x, &params).unwrap();
            assert!(info.converged, "restart {restart}: {info:?}");
            // the true residual, not GMRES's estimate
            let mut ax = vec![0.0; n];
            sys.apply(&x, &mut ax).unwrap();
            let r: f64 = ax
                .iter()
                .zip(&b)
                .map(|(p, q)| (p - q).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(r <= 1.1e-10 * norm(&b), "restart {restart}: {r}");
            let err: f64 = x
                .iter()
                .zip(&x_true)
                .map(|(p, q)| (p - q).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-7, "restart {restart}: {err}");
        }
    }

    #[test]
    fn with_a_fixed_preconditioner_plain_gmres_takes_the_flexible_iterates_in_one_workspace() {
        // x += M⁻¹ V y equals x += Z y when M is one linear map (Saad
        // 1993): the same iterations and solution, without the Z basis
        let n = 120;
        let mut sys = convection_diffusion(n);
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
        let mut g = Gmres::new(n, 7, false);
        let mut run = |flexible: bool| {
            let params = GmresParams {
                restart: 7,
                max_iterations: 500,
                tolerance: 1e-9,
                flexible,
            };
            let mut x = vec![0.0; n];
            let info = g.solve(&mut sys, &b, &mut x, &params).unwrap();
            (info, x)
        };
        let (plain, x_plain) = run(false);
        let (flexible, x_flexible) = run(true);
        assert!(plain.converged && flexible.converged);
        assert!(plain.iterations > 7, "restarted: {plain:?}");
        assert_eq!(plain.iterations, flexible.iterations);
        let scale = x_flexible.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = x_plain
            .iter()
            .zip(&x_flexible)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(diff < 1e-10 * scale, "{diff} {scale}");
        // the plain workspace held no preconditioned basis; the flexible
        // solve added it to the same workspace
        assert_eq!(g.preconditioned.len(), 7);
    }

    #[test]
    fn full_gmres_is_exact_in_n_steps_and_the_estimate_is_the_true_residual() {
        let n = 12;
        let mut sys = convection_diffusion(n);
        sys.jacobi = false;
        let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let mut x = vec![0.0; n];
        let mut g = Gmres::new(n, n, false);
        let params = GmresParams {
            restart: n,
            max_iterations: n,
            tolerance: 1e-300,
            flexible: false,
        };
        let info = g.solve(&mut sys, &b, &mut x, &params).unwrap();
        assert!(info.iterations <= n);
        let mut ax = vec![0.0; n];
        sys.apply(&x, &mut ax).unwrap();
        let r: f64 = ax
            .iter()
            .zip(&b)
            .map(|(p, q)| (p - q).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(r < 1e-9 * norm(&b), "{r}");
    }

    #[test]
    fn a_zero_right_hand_side_needs_no_iteration() {
        let mut sys = convection_diffusion(8);
        let mut x = vec![0.0; 8];
        let info = Gmres::new(8, 4, false)
            .solve(&mut sys, &[0.0; 8], &mut x, &GmresParams::default())
            .unwrap();
        assert!(info.converged && info.iterations == 0);
    }

    #[test]
    fn a_restart_cycle_without_progress_ends_the_solve_once_below_the_loosest_forcing() {
        // one unknown on the identity, eight on a cyclic shift: GMRES(3)
        // solves the first in one cycle, then no cycle reduces the shift
        // block's residual (its Krylov spaces miss the solution until
        // m ≥ 8)
        let n = 9;
        let mut a = vec![0.0; n * n];
        a[0] = 1.0;
        for i in 1..n {
            let next = if i + 1 < n { i + 1 } else { 1 };
            a[next * n + i] = 1.0;
        }
        let mut sys = Dense {
            n,
            a,
            jacobi: false,
        };
        let mut b = vec![0.0; n];
        b[0] = 20.0;
        b[1] = 1.0;
        let params = GmresParams {
            restart: 3,
            max_iterations: 300,
            tolerance: 1e-8,
            flexible: false,
        };
        let mut x = vec![0.0; n];
        let info = Gmres::new(n, 3, false)
            .solve(&mut sys, &b, &mut x, &params)
            .unwrap();
        assert!(info.stagnated && !info.converged, "{info:?}");
        // the first cycle takes the residual from √401 to about 1 (that of
        // the shift block), below a tenth; the second gains less than half
        // and the solve stops after it
        assert_eq!(info.iterations, 6, "{info:?}");
        assert!(info.final_residual < 1.1, "{info:?}");
    }
}
