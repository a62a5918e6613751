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
use fv_nonlinear::{GmresParams, NewtonError, NewtonKrylov, NewtonParams};
use layout::StateLayout;
use preconditioner::StatePreconditioner;
use residual::{reference_floor, ModelProblem, ResidualWork};

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
    retries: u32,
    length_scale: f64,
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
            preconditioner: StatePreconditioner::new(bodies, &layout),
            work: ResidualWork::new(bodies, &layout),
            params: MomentumParams {
                rhie_chow: settings.rhie_chow,
                rhie_chow_history: settings.rhie_chow_history,
            },
            x: vec![0.0; n],
            last_step: vec![0.0; n],
            last_path: None,
            path: PathChange::default(),
            retries: 0,
            length_scale: bodies
                .iter()
                .map(|b| b.extent)
                .fold(f64::MIN_POSITIVE, f64::max),
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

    /// The first iterate: the last increment's change scaled to this
    /// step, or zero.
    fn predict(&mut self) -> bool {
        self.x.iter_mut().for_each(|v| *v = 0.0);
        let Some(last) = &self.last_path else {
            return false;
        };
        if self.retries > 0 {
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
        for b in bodies.iter_mut().filter(|b| !b.rigid) {
            b.momentum.unsolved = self.layout.unsolved;
            b.momentum.prepare_state_function(&b.mesh, &b.geom);
        }
        self.work.record_start(bodies, &self.layout);
        let mut predicted = self.predict();
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
                length_scale: self.length_scale,
                reference_floor: self.reference_floor,
                evaluations: 0,
                last_refusal: None,
            };
            let done = total.iterations;
            let result = self.newton.solve(&mut problem, &mut self.x, &mut |k, r| {
                if k > 0 {
                    on_iteration(done + k, r)
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
