//! Newton–Krylov on model problems with known solutions: the Bratu
//! problem (smooth, strongly nonlinear) and a chain of springs pressed onto
//! an obstacle by a penalty (a contact active set, nonsmooth), both
//! preconditioned by the tridiagonal Laplacian as the finite-volume solver
//! is by its segregated operator.
use fv_nonlinear::{
    Frozen, Inadmissible, NewtonError, NewtonKrylov, NewtonParams, NonlinearProblem,
};

/// Solves the tridiagonal system (−1, d_i, −1) z = r (Thomas algorithm).
fn tridiagonal(diag: &[f64], r: &[f64], z: &mut [f64], work: &mut [f64]) {
    let n = r.len();
    let mut c_prev = 0.0;
    let mut z_prev = 0.0;
    for i in 0..n {
        let m = diag[i] + c_prev; // diag − (−1)·c_prev with c_i = −1/m
        let c = -1.0 / m;
        z[i] = (r[i] + z_prev) / m;
        work[i] = c;
        c_prev = c;
        z_prev = z[i];
    }
    for i in (0..n.saturating_sub(1)).rev() {
        z[i] -= work[i] * z[i + 1];
    }
}

/// −u'' − λ eᵘ = 0 on (0, 1), u(0) = u(1) = 0, second-order differences,
/// scaled by h² (F_i = u_{i−1} − 2u_i + u_{i+1} + h² λ e^{u_i}).
struct Bratu {
    n: usize,
    lambda: f64,
    evaluations: usize,
    work: Vec<f64>,
    diag: Vec<f64>,
}

impl NonlinearProblem for Bratu {
    fn len(&self) -> usize {
        self.n
    }
    fn residual(&mut self, x: &[f64], f: &mut [f64], _: Frozen) -> Result<(), Inadmissible> {
        self.evaluations += 1;
        let h = 1.0 / (self.n + 1) as f64;
        for i in 0..self.n {
            let left = if i > 0 { x[i - 1] } else { 0.0 };
            let right = if i + 1 < self.n { x[i + 1] } else { 0.0 };
            f[i] = left - 2.0 * x[i] + right + h * h * self.lambda * x[i].exp();
        }
        Ok(())
    }
    fn residual_reference(&self) -> f64 {
        let h = 1.0 / (self.n + 1) as f64;
        h * h * self.lambda * (self.n as f64).sqrt()
    }
    fn typical_size(&self) -> f64 {
        1.0
    }
    fn prepare_preconditioner(&mut self, _: &[f64], _: Option<usize>) -> Result<(), Inadmissible> {
        self.diag.clear();
        self.diag.resize(self.n, 2.0);
        Ok(())
    }
    fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
        tridiagonal(&self.diag, r, z, &mut self.work);
    }
}

#[test]
fn bratu_converges_quadratically_to_the_lower_branch() {
    let n = 200;
    let mut p = Bratu {
        n,
        lambda: 3.0,
        evaluations: 0,
        work: vec![0.0; n],
        diag: Vec::new(),
    };
    let mut x = vec![0.0; n];
    let params = NewtonParams {
        tolerance: 1e-10,
        ..Default::default()
    };
    let mut residuals = Vec::new();
    let info = NewtonKrylov::new(n, params)
        .solve(&mut p, &mut x, &mut |r| {
            residuals.push(r.residual);
            std::ops::ControlFlow::Continue(())
        })
        .unwrap();
    assert!(info.converged, "{info:?}");
    assert!(info.iterations <= 6, "{info:?} {residuals:?}");
    assert_eq!(info.residual_evaluations, p.evaluations);
    // lower branch of λ = 3: u(1/2) = 0.2 ... the exact solution
    // u = −2 ln(cosh((x − ½) θ/2)/cosh(θ/4)) with θ = √(2λ) cosh(θ/4)
    let mut theta: f64 = 1.0;
    for _ in 0..200 {
        theta = (2.0 * 3.0f64).sqrt() * (theta / 4.0).cosh();
    }
    let mid = 2.0 * (theta / 4.0).cosh().ln();
    let got = x[n / 2 - 1].max(x[n / 2]);
    assert!((got - mid).abs() < 1e-4 * mid, "u(1/2) {got} against {mid}");
}

/// A start whose residual overflows (e^800) is refused as such, not
/// iterated from or taken as converged: an unstable dynamic run's state
/// at 1e150 had been accepted with 0 iterations for 70 increments.
#[test]
fn an_overflowed_start_is_refused() {
    let n = 20;
    let mut p = Bratu {
        n,
        lambda: 3.0,
        evaluations: 0,
        work: vec![0.0; n],
        diag: Vec::new(),
    };
    let mut x = vec![800.0; n];
    let result = NewtonKrylov::new(n, NewtonParams::default())
        .solve(&mut p, &mut x, &mut |_| std::ops::ControlFlow::Continue(()));
    match result {
        Err(NewtonError::Start(e)) => assert!(e.0.contains("not finite"), "{}", e.0),
        other => panic!("{other:?}"),
    }
}

/// A chain of n unit springs, ends held at 0, each node pulled down by
/// `load`, resting by a penalty ε on obstacles at heights `obstacle[i]`:
/// F_i = u_{i−1} − 2u_i + u_{i+1} − load + ε max(obstacle_i − u_i, 0).
struct SpringsOnObstacle {
    n: usize,
    load: f64,
    penalty: f64,
    obstacle: Vec<f64>,
    /// Active set frozen at the last renewal (as contact pairs are).
    active: Vec<bool>,
    changes: usize,
    work: Vec<f64>,
    diag: Vec<f64>,
}

impl NonlinearProblem for SpringsOnObstacle {
    fn len(&self) -> usize {
        self.n
    }
    fn residual(&mut self, x: &[f64], f: &mut [f64], frozen: Frozen) -> Result<(), Inadmissible> {
        for i in 0..self.n {
            let left = if i > 0 { x[i - 1] } else { 0.0 };
            let right = if i + 1 < self.n { x[i + 1] } else { 0.0 };
            let pen = self.obstacle[i] - x[i];
            if frozen == Frozen::Renew {
                if i == 0 {
                    self.changes = 0;
                }
                self.changes += usize::from(self.active[i] != (pen > 0.0));
                self.active[i] = pen > 0.0;
            }
            let contact = if self.active[i] {
                self.penalty * pen
            } else {
                0.0
            };
            f[i] = left - 2.0 * x[i] + right - self.load + contact;
        }
        Ok(())
    }
    fn residual_reference(&self) -> f64 {
        self.load * (self.n as f64).sqrt()
    }
    fn typical_size(&self) -> f64 {
        1.0
    }
    fn changes_at_last_renewal(&self) -> usize {
        self.changes
    }
    fn prepare_preconditioner(&mut self, _: &[f64], _: Option<usize>) -> Result<(), Inadmissible> {
        self.diag.clear();
        self.diag.extend(
            self.active
                .iter()
                .map(|&a| 2.0 + if a { self.penalty } else { 0.0 }),
        );
        Ok(())
    }
    fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
        tridiagonal(&self.diag, r, z, &mut self.work);
    }
}

#[test]
fn penalty_contact_active_set_settles_in_a_few_newton_iterations() {
    let n = 101;
    let obstacle: Vec<f64> = (0..n)
        .map(|i| {
            let s = (i as f64 - 50.0) / 50.0;
            -20.0 + 10.0 * s * s
        })
        .collect();
    let mut p = SpringsOnObstacle {
        n,
        load: 0.05,
        penalty: 1e4,
        obstacle: obstacle.clone(),
        active: vec![false; n],
        changes: 0,
        work: vec![0.0; n],
        diag: Vec::new(),
    };
    let mut x = vec![0.0; n];
    let params = NewtonParams {
        tolerance: 1e-8,
        ..Default::default()
    };
    let mut flagged = 0;
    let info = NewtonKrylov::new(n, params)
        .solve(&mut p, &mut x, &mut |r| {
            flagged += usize::from(r.discontinuity);
            std::ops::ControlFlow::Continue(())
        })
        .unwrap();
    assert!(info.converged, "{info:?}");
    assert!(info.iterations <= 25, "{info:?}");
    // the steps taken across a change of the active set whatever their
    // residual are the ones the iteration reports (and FVC_TRACE marks)
    assert!(info.discontinuity_steps > 0, "{info:?}");
    assert_eq!(flagged, info.discontinuity_steps, "{info:?}");
    // the free chain sags to a parabola of depth load n²/8 ≈ 64 > 20: the
    // middle rests on the obstacle, penetrating by about load/penalty
    let mid = n / 2;
    assert!(
        (x[mid] - obstacle[mid]).abs() < 1e-3,
        "{} vs {}",
        x[mid],
        obstacle[mid]
    );
    // the residual of the true (renewed) active set is converged
    let mut f = vec![0.0; n];
    p.residual(&x, &mut f, Frozen::Renew).unwrap();
    let r = f.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(r <= 1e-8 * p.residual_reference() * 1.01, "{r}");
}

/// F(x) = b − x, whose every Newton step the problem trusts only to
/// `limit` of its length (as open contact faces bound a step): the
/// residual falls by the factor 1 − limit per step, a creep.
struct TrustedFraction {
    b: Vec<f64>,
    limit: f64,
}

impl NonlinearProblem for TrustedFraction {
    fn len(&self) -> usize {
        self.b.len()
    }
    fn residual(&mut self, x: &[f64], f: &mut [f64], _: Frozen) -> Result<(), Inadmissible> {
        for ((f, b), x) in f.iter_mut().zip(&self.b).zip(x) {
            *f = b - x;
        }
        Ok(())
    }
    fn residual_reference(&self) -> f64 {
        1.0
    }
    fn typical_size(&self) -> f64 {
        1.0
    }
    fn step_limit(&self, _: &[f64], _: &[f64]) -> f64 {
        self.limit
    }
    fn prepare_preconditioner(&mut self, _: &[f64], _: Option<usize>) -> Result<(), Inadmissible> {
        Ok(())
    }
    fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
        z.copy_from_slice(r);
    }
}

#[test]
fn a_creeping_solve_stops_once_its_rate_cannot_reach_the_tolerance() {
    let solve = |limit: f64, window: usize| {
        let mut p = TrustedFraction {
            b: vec![1.0, -2.0, 0.5],
            limit,
        };
        let mut x = vec![0.0; 3];
        let params = NewtonParams {
            tolerance: 1e-8,
            max_iterations: 50,
            rate_abort_window: window,
            pseudo_transient: None,
            ..Default::default()
        };
        NewtonKrylov::new(3, params)
            .solve(&mut p, &mut x, &mut |_| std::ops::ControlFlow::Continue(()))
    };
    // 2 % per step: 0.98^k reaches 1e-8 only after 912 steps; stopped as
    // soon as the window of 10 steps has measured that
    match solve(0.02, 10) {
        Err(fv_nonlinear::NewtonError::Stagnated {
            iteration, steps, ..
        }) => assert_eq!((iteration, steps), (10, 10)),
        other => panic!("{other:?}"),
    }
    // without the window it runs out of its 50 iterations, unconverged
    let info = solve(0.02, 0).unwrap();
    assert!(!info.converged && info.iterations == 50, "{info:?}");
    let start = 5.25f64.sqrt(); // ‖b‖
    assert!(
        (info.residual / (start * 0.98f64.powi(50)) - 1.0).abs() < 1e-6,
        "{info:?}"
    );
    // 70 % per step (0.3^k): 16 steps, not stopped
    let info = solve(0.7, 10).unwrap();
    assert!(info.converged && info.iterations == 16, "{info:?}");
}

/// The linear problem F(u) = h² − (−u_{i−1} + 2u_i − u_{i+1}) (a string
/// under a uniform load) with no preconditioner: its Krylov solves need
/// a long basis, as the fine wire drawing's did.
struct UnpreconditionedString {
    n: usize,
}

impl NonlinearProblem for UnpreconditionedString {
    fn len(&self) -> usize {
        self.n
    }
    fn residual(&mut self, x: &[f64], f: &mut [f64], _: Frozen) -> Result<(), Inadmissible> {
        let h = 1.0 / (self.n + 1) as f64;
        for i in 0..self.n {
            let left = if i > 0 { x[i - 1] } else { 0.0 };
            let right = if i + 1 < self.n { x[i + 1] } else { 0.0 };
            f[i] = h * h + left - 2.0 * x[i] + right;
        }
        Ok(())
    }
    fn residual_reference(&self) -> f64 {
        let h = 1.0 / (self.n + 1) as f64;
        h * h * (self.n as f64).sqrt()
    }
    fn typical_size(&self) -> f64 {
        0.1
    }
    fn prepare_preconditioner(&mut self, _: &[f64], _: Option<usize>) -> Result<(), Inadmissible> {
        Ok(())
    }
    fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
        z.copy_from_slice(r);
    }
    fn linear_preconditioner(&self) -> bool {
        true
    }
}

#[test]
fn a_krylov_solve_that_stops_short_grows_the_restart() {
    let n = 100;
    let h = 1.0 / (n + 1) as f64;
    let solve = |growth_limit: usize| {
        let params = NewtonParams {
            tolerance: 1e-8,
            max_iterations: 30,
            restart_growth_limit: growth_limit,
            krylov: fv_nonlinear::GmresParams {
                restart: 4,
                max_iterations: 16,
                ..Default::default()
            },
            ..Default::default()
        };
        let mut solver = NewtonKrylov::new(n, params);
        let mut x = vec![0.0; n];
        let info = solver.solve(&mut UnpreconditionedString { n }, &mut x, &mut |_| {
            std::ops::ControlFlow::Continue(())
        });
        (info, solver.krylov_params(), x)
    };
    // GMRES(4) capped at 16 products: the string's 100 modes are beyond it
    let (short, krylov, _) = solve(0);
    assert_eq!(krylov.restart, 4);
    assert!(!matches!(short, Ok(ref i) if i.converged), "{short:?}");
    // grown by doubling (at most to GMRES(128)), 4 cycles a solve:
    // converged
    let (grown, krylov, x) = solve(128);
    let grown = grown.unwrap();
    assert!(grown.converged, "{grown:?}");
    assert!(
        krylov.restart > 4 && krylov.restart <= 128 && krylov.restart.is_power_of_two(),
        "{krylov:?}"
    );
    assert_eq!(krylov.max_iterations, 4 * krylov.restart);
    // the string's deflection u(x) = x (1 − x) / 2, exact at the nodes
    for (i, u) in x.iter().enumerate() {
        let s = (i + 1) as f64 * h;
        assert!(
            (u - s * (1.0 - s) / 2.0).abs() < 1e-6 * 0.125,
            "u({s}) = {u}"
        );
    }
}
