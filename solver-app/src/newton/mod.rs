//! Newton–Krylov for the whole model: bodies, materials and contact in
//! one Newton loop ([`fv_nonlinear::NewtonKrylov`] over the residual of
//! [`residual::ModelProblem`], preconditioned by the segregated operator
//! with the contact springs, [`preconditioner::StatePreconditioner`]).
//!
//! Around the Newton solve of an increment: the augmented Lagrangian
//! multipliers are updated between Newton solves (each solve's
//! multipliers frozen), and force-controlled patches correct their
//! displacement between them (Algorithm 1), until neither changes.
pub mod jacobian;
pub mod layout;
pub mod preconditioner;
pub mod residual;

use crate::case::{LinearSettings, SolverSettings};
use crate::contact_coupling::ContactSet;
use crate::model::Body;
use crate::predictor::PathChange;
use crate::profile::PhaseTimes;
use crate::segregated::{unsolved_directions, IncrementInfo, SolveError};
use fv_discretise::MomentumParams;
use fv_nonlinear::{GmresParams, NewtonError, NewtonKrylov, NewtonParams, NonlinearProblem};
use jacobian::AssembledJacobian;
use layout::StateLayout;
use preconditioner::StatePreconditioner;
use residual::{mean_cell_size, reference_floor, ModelProblem, ResidualWork};

/// The fraction of a step by which the conditions move to measure the
/// start state's response ([`NewtonKrylovSolver::linear_predictor`]).
const PREDICTOR_FRACTION: f64 = 1e-3;

/// Halvings of a predicted first iterate that is not admissible before
/// the increment starts from its beginning instead.
const START_HALVINGS: usize = 6;

/// Newton solves per increment at most (the first, then one per
/// multiplier update or force correction).
const MAX_NEWTON_SOLVES: usize = 40;

/// The Newton–Krylov method and its workspaces (built once per run).
pub struct NewtonKrylovSolver {
    newton: NewtonKrylov,
    layout: StateLayout,
    preconditioner: StatePreconditioner,
    /// The assembled Jacobian, when it preconditions.
    jacobian: Option<AssembledJacobian>,
    work: ResidualWork,
    params: MomentumParams,
    /// The state of the current increment.
    x: Vec<f64>,
    /// The last accepted increment's state change and the change of the
    /// prescribed values over it (the predictor extrapolates it).
    last_step: Vec<f64>,
    last_path: Option<PathChange>,
    path: PathChange,
    /// Workspace of the harmonic start.
    last_step_source: Vec<f64>,
    /// Start and end time of the step being solved.
    step_times: (f64, f64),
    retries: u32,
    cell_size: f64,
    reference_floor: f64,
    /// Seconds per phase.
    pub times: PhaseTimes,
}

/// Newton parameters of the case's settings.
pub fn newton_params(settings: &SolverSettings) -> NewtonParams {
    let linear: LinearSettings = settings.linear;
    let mut p = NewtonParams {
        tolerance: settings.tolerance,
        max_iterations: settings.max_outer,
        ..Default::default()
    };
    p.krylov = GmresParams {
        restart: linear.restart,
        max_iterations: linear.max_iterations,
        tolerance: linear.tolerance,
        flexible: std::env::var("FVC_NK_INNER").is_ok(),
    };
    p.forcing.max = linear.tolerance;
    p.forcing.initial = p.forcing.initial.min(linear.tolerance);
    p
}

impl NewtonKrylovSolver {
    /// The solver for the bodies (their contact patches prepared with
    /// `ContactSet::prepare_state_conditions`).
    pub fn new(bodies: &[Body], settings: &SolverSettings) -> Self {
        let unsolved = unsolved_directions(bodies);
        let layout = StateLayout::new(bodies, unsolved);
        let n = layout.len();
        NewtonKrylovSolver {
            newton: NewtonKrylov::new(n, newton_params(settings)),
            preconditioner: StatePreconditioner::new(
                bodies,
                &layout,
                settings.linear.method == crate::case::LinearMethod::Direct,
            ),
            jacobian: (std::env::var("FVC_NK_PC").as_deref() == Ok("jacobian"))
                .then(|| AssembledJacobian::new(bodies, &layout)),
            work: ResidualWork::new(bodies, &layout),
            params: MomentumParams {
                rhie_chow: settings.rhie_chow,
                rhie_chow_history: settings.rhie_chow_history,
            },
            x: vec![0.0; n],
            last_step: vec![0.0; n],
            last_path: None,
            path: PathChange::default(),
            last_step_source: Vec::new(),
            step_times: (0.0, 0.0),
            retries: 0,
            cell_size: mean_cell_size(bodies),
            reference_floor: reference_floor(bodies),
            layout,
            times: PhaseTimes::default(),
        }
    }

    /// Bytes of the Newton workspaces (Krylov basis, work vectors,
    /// preconditioner).
    pub fn memory_bytes(&self) -> usize {
        self.newton.memory_bytes() + self.preconditioner.memory_bytes() + 8 * 3 * self.x.len()
    }

    /// The numbering of the state.
    pub fn layout(&self) -> &StateLayout {
        &self.layout
    }

    /// Number of unknowns of the state.
    pub fn state_len(&self) -> usize {
        self.layout.len()
    }

    /// Prepares the bodies for the increment about to be solved (the
    /// kinematic faces' elimination, the unsolved directions) and records
    /// their current state as its start.
    pub fn begin_increment(&mut self, bodies: &mut [Body]) {
        for b in bodies.iter_mut().filter(|b| !b.rigid) {
            b.momentum.unsolved = self.layout.unsolved;
            b.momentum.prepare_state_function(&b.mesh, &b.geom);
        }
        self.work.record_start(bodies, &self.layout);
    }

    /// The residual F(x) of the increment begun by
    /// [`Self::begin_increment`], x the change of the state over it.
    pub fn problem<'a>(
        &'a mut self,
        bodies: &'a mut [Body],
        contacts: &'a mut ContactSet,
    ) -> ModelProblem<'a> {
        ModelProblem {
            bodies,
            contacts,
            layout: &self.layout,
            params: self.params,
            work: &mut self.work,
            preconditioner: &mut self.preconditioner,
            jacobian: self.jacobian.as_mut(),
            times: &mut self.times,
            reference: 0.0,
            changes: 0,
            cell_size: self.cell_size,
            reference_floor: self.reference_floor,
            evaluations: 0,
            last_refusal: None,
            penetration: (0.0, None),
        }
    }

    /// The source of the harmonic extension of the step of the prescribed
    /// values (displacement and normal-displacement faces) from the
    /// bodies' current boundary values, per node (interleaved); false
    /// when nothing prescribed moves.
    fn prescribed_step_source(&self, bodies: &[Body], rhs: &mut [f64]) -> bool {
        rhs.iter_mut().for_each(|v| *v = 0.0);
        let mut any = false;
        let mut column = vec![0.0; 0];
        for b in bodies.iter().filter(|b| !b.rigid) {
            for c in 0..3 {
                if self.layout.unsolved[c] {
                    continue;
                }
                column.clear();
                column.resize(b.mesh.n_cells, 0.0);
                any |= b
                    .momentum
                    .add_prescribed_step_source(&b.mesh, &b.geom, c, &mut column);
                for (i, v) in column.iter().enumerate() {
                    rhs[3 * (b.offset + i) + c] = *v;
                }
            }
        }
        any
    }

    /// The first iterate of Newton's method: the linear response of the
    /// start state to the step of the prescribed values and loads, as
    /// finite-element codes take it, x₀ = −J⁻¹ ∂F/∂t Δt: the change of the
    /// residual at the start state when the conditions move by a small
    /// fraction [`PREDICTOR_FRACTION`] of the step (so that what the step
    /// prescribes enters through the start's tangent, not through a jump
    /// of the prescribed faces away from their cells that may throw the
    /// faces' points far into a plastic or inverted state), solved with the
    /// preconditioner assembled at the start (the segregated operator: the
    /// harmonic extension of the step; the assembled Jacobian: the tangent
    /// step), the contact springs of the start included. False when a
    /// stage fails.
    fn linear_predictor(&mut self, bodies: &mut [Body], contacts: &mut ContactSet) -> bool {
        let (t0, t1) = self.step_times;
        if !(t1 > t0) {
            return false;
        }
        let th = t0 + PREDICTOR_FRACTION * (t1 - t0);
        let n = self.x.len();
        let zero = vec![0.0; n];
        let mut f0 = vec![0.0; n];
        let mut fh = vec![0.0; n];
        for b in bodies.iter_mut() {
            b.refresh_conditions(t0);
        }
        let ok = {
            let mut problem = self.problem(bodies, contacts);
            problem
                .residual(&zero, &mut f0, fv_nonlinear::Frozen::Renew)
                .is_ok()
                && problem.prepare_preconditioner(&zero, false).is_ok()
        };
        for b in bodies.iter_mut() {
            b.refresh_conditions(th);
        }
        let ok = ok && {
            let mut problem = self.problem(bodies, contacts);
            problem
                .residual(&zero, &mut fh, fv_nonlinear::Frozen::Keep)
                .is_ok()
        };
        for b in bodies.iter_mut() {
            b.refresh_conditions(t1);
        }
        if !ok {
            return false;
        }
        let rhs: Vec<f64> = fh
            .iter()
            .zip(&f0)
            .map(|(a, b)| (a - b) / PREDICTOR_FRACTION)
            .collect();
        let mut x0 = vec![0.0; n];
        self.problem(bodies, contacts).precondition(&rhs, &mut x0);
        if !x0.iter().all(|v| v.is_finite()) || x0.iter().all(|v| *v == 0.0) {
            return false;
        }
        self.x.copy_from_slice(&x0);
        true
    }

    /// Shortens the predicted first iterate until the residual can be
    /// evaluated there (no cell inverted, no contact face deeper than the
    /// penetration limit): by halves, [`START_HALVINGS`] times, then zero.
    fn admissible_start(&mut self, bodies: &mut [Body], contacts: &mut ContactSet) {
        let x0 = self.x.clone();
        let mut f = vec![0.0; x0.len()];
        let zero = vec![0.0; x0.len()];
        let mut problem = self.problem(bodies, contacts);
        // the unmoved state is the reference of the penetration a start
        // may add
        if problem
            .residual(&zero, &mut f, fv_nonlinear::Frozen::Renew)
            .is_ok()
        {
            problem.accept();
        }
        let mut scale = 1.0;
        let mut x = x0.clone();
        for _ in 0..=START_HALVINGS {
            for (x, v) in x.iter_mut().zip(&x0) {
                *x = v * scale;
            }
            if problem
                .residual(&x, &mut f, fv_nonlinear::Frozen::Renew)
                .is_ok()
            {
                drop(problem);
                self.x.copy_from_slice(&x);
                return;
            }
            scale *= 0.5;
        }
        drop(problem);
        self.x.iter_mut().for_each(|v| *v = 0.0);
    }

    /// The first iterate: the last increment's change scaled to this
    /// step, or zero.
    fn predict(&mut self) -> bool {
        self.x.iter_mut().for_each(|v| *v = 0.0);
        let Some(last) = &self.last_path else {
            return false;
        };
        if self.retries > 0 || std::env::var("FVC_NK_NOPRED").is_ok() {
            return false;
        }
        let s = self.path.continuation_of(last);
        if s == 0.0 {
            return false;
        }
        for (x, d) in self.x.iter_mut().zip(&self.last_step) {
            *x = s * d;
        }
        true
    }
}

impl crate::nonlinear_solver::NonlinearSolver for NewtonKrylovSolver {
    fn method(&self) -> fv_nonlinear::NonlinearMethod {
        fv_nonlinear::NonlinearMethod::NewtonKrylov
    }

    fn prepare(&mut self, _bodies: &[Body]) -> Result<(), SolveError> {
        Ok(())
    }

    fn set_step(&mut self, path: &PathChange, t0: f64, t1: f64) {
        self.path.clone_from(path);
        self.step_times = (t0, t1);
    }

    fn set_divergence_retries(&mut self, retries: u32) {
        self.retries = retries;
    }

    fn solve_increment(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
        on_iteration: &mut dyn FnMut(usize, f64),
    ) -> Result<IncrementInfo, SolveError> {
        // the step of the prescribed values, before the first evaluation
        // sets the boundary values to them
        let mut source = std::mem::take(&mut self.last_step_source);
        source.resize(self.x.len(), 0.0);
        let prescribed_step = self.prescribed_step_source(bodies, &mut source);
        self.begin_increment(bodies);
        let mut predicted = match std::env::var("FVC_NK_PRED").as_deref() {
            Ok("extrapolate") => self.predict(),
            Ok("none") => false,
            _ => self.linear_predictor(bodies, contacts),
        };
        if !predicted && prescribed_step && std::env::var("FVC_NK_NOHARM").is_err() {
            // no extrapolation to start from: the harmonic extension of
            // the prescribed step through the bodies (with the contact
            // springs of the start), as a first iterate that does not put
            // the whole step into the cells by the prescribed faces
            let zero = vec![0.0; source.len()];
            let mut f = vec![0.0; source.len()];
            let mut problem = self.problem(bodies, contacts);
            if problem
                .residual(&zero, &mut f, fv_nonlinear::Frozen::Renew)
                .is_ok()
                && problem.prepare_preconditioner(&zero, false).is_ok()
            {
                let mut x0 = vec![0.0; source.len()];
                if self.preconditioner.solve(&source, &mut x0, 1e-8).is_ok()
                    && x0.iter().all(|v| v.is_finite())
                {
                    self.x.copy_from_slice(&x0);
                    predicted = true;
                }
            }
        }
        self.last_step_source = source;
        if predicted {
            self.admissible_start(bodies, contacts);
        }
        let solved = [0, 1, 2].map(|c| !self.layout.unsolved[c]);
        let mut info = IncrementInfo {
            required: self.newton.params.tolerance,
            ..Default::default()
        };
        let mut total = fv_nonlinear::NewtonInfo::default();
        let mut solves = 0;
        loop {
            solves += 1;
            let mut problem = ModelProblem {
                bodies: &mut *bodies,
                contacts: &mut *contacts,
                layout: &self.layout,
                params: self.params,
                work: &mut self.work,
                preconditioner: &mut self.preconditioner,
                jacobian: self.jacobian.as_mut(),
                times: &mut self.times,
                reference: 0.0,
                changes: 0,
                cell_size: self.cell_size,
                reference_floor: self.reference_floor,
                evaluations: 0,
                last_refusal: None,
                penetration: (0.0, None),
            };
            let done = total.iterations;
            let trace = std::env::var_os("FVC_TRACE").is_some();
            let result = self.newton.solve(&mut problem, &mut self.x, &mut |r| {
                if trace {
                    eprintln!(
                        "    newton {}: residual {:.3e} eta {:.2e} krylov {} (linear residual {:.2e}) step {:.3e} x {:.3e}{}",
                        r.iteration,
                        r.residual,
                        r.forcing,
                        r.krylov_iterations,
                        r.linear_residual,
                        r.step_length,
                        r.step_norm,
                        if r.discontinuity { " discontinuity" } else { "" }
                    );
                }
                if r.iteration > 0 {
                    on_iteration(done + r.iteration, r.residual)
                }
            });
            let counts = match &result {
                Ok(i) => *i,
                Err(NewtonError::LineSearch { info, .. })
                | Err(NewtonError::Preconditioner { info, .. }) => *info,
                Err(NewtonError::Start(_)) => fv_nonlinear::NewtonInfo {
                    residual_evaluations: 1,
                    ..Default::default()
                },
            };
            total.accumulate(&counts);
            info.outer_iterations = total.iterations;
            info.linear_iterations = total.krylov_iterations;
            info.residual_evaluations = total.residual_evaluations;
            info.residual = total.residual;
            match result {
                Err(NewtonError::Start(e)) if predicted => {
                    // the extrapolated start inverts a cell: from the
                    // last converged state instead
                    let _ = e;
                    predicted = false;
                    self.x.iter_mut().for_each(|v| *v = 0.0);
                    continue;
                }
                Err(NewtonError::Start(e)) => {
                    return Err(SolveError::Material(format!(
                        "the start of the increment is not admissible: {}",
                        e.0
                    )))
                }
                Err(e) => return Err(SolveError::Nonlinear(e.to_string())),
                Ok(i) if !i.converged => return Ok(info),
                Ok(_) => {}
            }
            if solves >= MAX_NEWTON_SOLVES {
                return Ok(info);
            }
            // Algorithm 1 between Newton solves
            let mut reached = true;
            for b in bodies.iter_mut().filter(|b| !b.rigid) {
                reached &= b.correct_force_controls(solved);
            }
            if !reached {
                continue;
            }
            // augmented Lagrangian: one Uzawa update per converged solve
            if contacts.augment(bodies) {
                continue;
            }
            info.converged = true;
            break;
        }
        if std::env::var("FVC_NK_DEBUG").is_ok() {
            eprintln!(
                "DEBUG newton {} krylov {} evals {} inner {} backtracks {} disc {}",
                total.iterations,
                total.krylov_iterations,
                total.residual_evaluations,
                self.preconditioner.inner_iterations,
                total.backtracks,
                total.discontinuity_steps
            );
        }
        contacts.commit_increment();
        self.last_step.copy_from_slice(&self.x);
        self.last_path = Some(self.path.clone());
        Ok(info)
    }

    fn n_unknowns(&self) -> usize {
        self.layout.n_cells
    }

    fn times(&self) -> PhaseTimes {
        self.times
    }

    fn times_mut(&mut self) -> &mut PhaseTimes {
        &mut self.times
    }
}
