//! Newton–Krylov for the whole model: bodies, materials and contact in
//! one Newton loop ([`fv_nonlinear::NewtonKrylov`] over the residual of
//! [`residual::ModelProblem`], preconditioned by the segregated operator
//! with the contact springs, [`preconditioner::StatePreconditioner`]).
//!
//! Around the Newton solve of an increment: the augmented Lagrangian
//! multipliers are updated between Newton solves (each solve's
//! multipliers frozen), and force-controlled patches correct their
//! displacement between them (Algorithm 1), until neither changes.
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
use layout::StateLayout;
use preconditioner::StatePreconditioner;
use residual::{mean_cell_size, reference_floor, ModelProblem, ResidualWork};

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
            times: &mut self.times,
            reference: 0.0,
            changes: 0,
            cell_size: self.cell_size,
            reference_floor: self.reference_floor,
            evaluations: 0,
            last_refusal: None,
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

    /// Shortens the predicted first iterate until the residual can be
    /// evaluated there (no cell inverted, no contact face deeper than the
    /// penetration limit): by halves, [`START_HALVINGS`] times, then zero.
    fn admissible_start(&mut self, bodies: &mut [Body], contacts: &mut ContactSet) {
        let x0 = self.x.clone();
        let mut f = vec![0.0; x0.len()];
        let mut scale = 1.0;
        for _ in 0..=START_HALVINGS {
            let x: Vec<f64> = x0.iter().map(|v| v * scale).collect();
            let mut problem = self.problem(bodies, contacts);
            if problem
                .residual(&x, &mut f, fv_nonlinear::Frozen::Renew)
                .is_ok()
            {
                self.x.copy_from_slice(&x);
                return;
            }
            scale *= 0.5;
        }
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

    fn set_step(&mut self, path: &PathChange, _t0: f64, _t1: f64) {
        self.path.clone_from(path);
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
        let mut predicted = self.predict();
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
                && problem.prepare_preconditioner(&zero).is_ok()
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
                times: &mut self.times,
                reference: 0.0,
                changes: 0,
                cell_size: self.cell_size,
                reference_floor: self.reference_floor,
                evaluations: 0,
                last_refusal: None,
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
