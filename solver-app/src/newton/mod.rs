//! Newton–Krylov for the whole model: bodies, materials and contact in one
//! Newton loop ([`fv_nonlinear::NewtonKrylov`] over the residual of
//! [`residual::ModelProblem`]), preconditioned by the segregated operator
//! with the contact springs ([`segregated_operator`]) or by the assembled
//! Jacobian ([`jacobian`]; [`preconditioning`] says which).
//!
//! An increment starts from the linear response of its start state to
//! the step ([`start`]). Around the Newton solve: the augmented
//! Lagrangian multipliers are updated between Newton solves (each solve's
//! multipliers frozen), and force-controlled patches correct their
//! displacement between them (Algorithm 1), until neither changes.
pub mod jacobian;
pub mod layout;
pub mod preconditioning;
pub mod residual;
pub mod segregated_operator;
mod start;
mod step_limit;

use std::ops::ControlFlow;

use crate::case::{LinearMethod, SolverSettings, NEWTON_FINAL_ATTEMPT_ITERATIONS};
use crate::contact_coupling::ContactSet;
use crate::model::Body;
use crate::predictor::PathChange;
use crate::profile::PhaseTimes;
use crate::segregated::{unsolved_directions, IncrementInfo, SolveError};
use fv_discretise::MomentumParams;
use fv_nonlinear::{
    Frozen, GmresParams, IterationReport, NewtonError, NewtonInfo, NewtonKrylov, NewtonParams,
    NonlinearProblem,
};
use jacobian::{
    AssembledJacobian, JacobianFactor, LU_LIMIT, LU_LIMIT_3D, RESCUE_LU_LIMIT_3D,
    STALLED_LU_LIMIT_3D,
};
use layout::StateLayout;
use preconditioning::{Preconditioning, SWITCH_KRYLOV_ITERATIONS};
use residual::{
    mean_cell_size, stiffness_area, ModelProblem, ResidualWork, ILU_STALLS_BEFORE_LU,
    SPRING_KRYLOV, SPRING_STALLS,
};
use segregated_operator::SegregatedOperator;
use start::{FirstIterate, LastChange};

/// Newton solves per increment at most (the first, then one per
/// multiplier update or force correction).
const MAX_NEWTON_SOLVES: usize = 40;

/// Meshes of at least this many cells hold GMRES's basis to
/// [`KRYLOV_BASIS_BYTES_PER_CELL`] unless the case gives `linear.restart`
/// ([`budgeted_restart`]); every case of the contact battery is smaller.
const KRYLOV_BUDGET_CELLS: usize = 100_000;

/// Bytes per cell of the Krylov basis (restart + 1 vectors of the state)
/// on a large mesh: GMRES(20) rather than GMRES(30) on the 64³ box
/// (835,584 unknowns), the run within 2 kB per cell. Measured (Newton /
/// Krylov iterations, peak RSS), box 64³ with multigrid: restart 30: 3 /
/// 74, 546 MB; 25: 3 / 74, 514 MB; 20: 3 / 73, 481 MB. The contact
/// battery at restart 20 instead of 30: docs/kernel-performance.md.
const KRYLOV_BASIS_BYTES_PER_CELL: usize = 540;

/// Shortest restart the budget cuts to.
const MIN_BUDGETED_RESTART: usize = 10;

/// The restart a budgeted GMRES grows back to, doubling, after Krylov
/// solves that stop short of their forcing term
/// (`NewtonParams::restart_growth_limit`): the fine wire drawing (153,600
/// wire cells) stalled near 10⁻⁴ with GMRES(20) and converged with
/// GMRES(100) (docs/newton-krylov.md, "Known limits"). Its basis then
/// takes 101 vectors, 2.4 kB per cell in 3D, on the cases that need it.
const GROWN_RESTART_LIMIT: usize = 100;

/// GMRES's restart for `n` unknowns on `cells` cells: `restart` on small
/// meshes, else the longest within [`KRYLOV_BASIS_BYTES_PER_CELL`] (at
/// least [`MIN_BUDGETED_RESTART`]).
fn budgeted_restart(restart: usize, n: usize, cells: usize) -> usize {
    if cells < KRYLOV_BUDGET_CELLS || n == 0 {
        return restart;
    }
    let vectors = KRYLOV_BASIS_BYTES_PER_CELL * cells / (8 * n);
    restart.min(vectors.saturating_sub(1).max(MIN_BUDGETED_RESTART))
}

/// `"auto"` preconditions a plane (or axisymmetric) problem of at most
/// this many unknowns with the assembled Jacobian from its first Newton
/// step, not only after a step the segregated operator served badly.
/// Measured 2026-11-30, wall time auto before → from the start (unknowns):
/// curved beams μ = 0 / 0.3 / 0.6 2.92 / 4.38 / 3.68 → 1.74 / 3.80 / 2.95 s
/// (1,400; Newton iterations in the run 394 / 628 / 582 → 294 / 609 / 553);
/// the axisymmetric concentric spheres (2,880) failed at 5.6 mm, buckling,
/// and now run to the end (6.1 s); die drawing (302) and the concentric
/// cylinders (1,800) unchanged. Above: the factorisation fills in and
/// costs more than the Krylov iterations it saves — Hertz coarse (3,356)
/// 0.05 → 0.13 s, rigid-cylinder indent (7,388) 0.15 → 0.79 s, Hertz fine
/// (13,172) 0.26 → 1.04 s.
pub const START_JACOBIAN_LIMIT: usize = 3_000;

/// A contact between two deformable bodies whose normal penalty scale is
/// at least this stiffens the problem beyond what the segregated
/// operator's per-component springs precondition (they keep n_c² of the
/// spring k n⊗n joining the two bodies and drop its off-diagonal part,
/// which grows with k where the normal turns): on a plane problem
/// `"auto"` factorises the Jacobian from the first step whatever its size
/// (up to [`LU_LIMIT`]). Measured on the two tubes of issue 47 (2,240
/// cells, 5,600 unknowns, penalty ×1000): from the segregated operator,
/// GMRES needed 60 and then 200 Krylov iterations at the third and
/// fourth Newton steps, the switch to the Jacobian came too late, and
/// Newton crept at line-search steps of 0.1 (41 iterations, 1.4–2.0 s);
/// factorised from the start, 9 iterations and 0.38–0.43 s, the
/// interface force the same to 1e-6. At ×10 the segregated operator
/// serves (3 iterations, 0.17 s). Against a rigid flat it serves at ×100
/// too (Hertz coarse / fine: 0.10 / 0.68 s, against 0.30 / 2.69 s
/// factorised), so rigid pairs keep it.
pub const STIFF_PENALTY_SCALE: f64 = 100.0;

/// Whether `"auto"` preconditions with the assembled Jacobian from the
/// first step ([`START_JACOBIAN_LIMIT`], [`STIFF_PENALTY_SCALE`]), and the
/// solved unknowns.
fn auto_starts_assembled(layout: &StateLayout, contacts: &ContactSet) -> (bool, usize) {
    let solved = layout.unsolved.iter().filter(|u| !**u).count();
    let unknowns = layout.solved_len();
    let limit = if stiff_contact(contacts) {
        LU_LIMIT
    } else {
        START_JACOBIAN_LIMIT
    };
    (solved <= 2 && unknowns <= limit, unknowns)
}

/// Whether a contact between two deformable bodies has a normal penalty
/// scale of [`STIFF_PENALTY_SCALE`] or more.
fn stiff_contact(contacts: &ContactSet) -> bool {
    contacts
        .interfaces
        .iter()
        .any(|ci| ci.deformable_pair && ci.penalty_scale.value() >= STIFF_PENALTY_SCALE)
}

/// When `"auto"` switches from the segregated operator to the assembled
/// Jacobian, factorised (`NewtonKrylovSolver::switch_after`).
enum AutoSwitch {
    /// After a Newton step of more than [`SWITCH_KRYLOV_ITERATIONS`]
    /// Krylov iterations: a plane problem up to [`LU_LIMIT`] unknowns, a
    /// 3-D one up to [`LU_LIMIT_3D`].
    BeyondKrylov,
    /// A 3-D problem up to [`STALLED_LU_LIMIT_3D`] unknowns: after a Newton
    /// step whose Krylov solve used all its iterations, the Jacobian
    /// factorised by ILU(0); after [`residual::ILU_STALLS_BEFORE_LU`] such
    /// solves in a row preconditioned by it, by LU.
    Incomplete,
}

/// The switch of `"auto"` for the state's size, if any.
fn auto_switch(layout: &StateLayout) -> Option<AutoSwitch> {
    let solved = layout.unsolved.iter().filter(|u| !**u).count();
    let unknowns = layout.solved_len();
    if unknowns <= if solved <= 2 { LU_LIMIT } else { LU_LIMIT_3D } {
        Some(AutoSwitch::BeyondKrylov)
    } else if solved > 2 && unknowns <= STALLED_LU_LIMIT_3D {
        Some(AutoSwitch::Incomplete)
    } else {
        None
    }
}

/// What `"auto"` preconditions the bodies' Newton steps with, and why
/// (`fvc check` and the run's log).
pub fn auto_preconditioner_report(bodies: &[Body], contacts: &ContactSet) -> String {
    let layout = StateLayout::new(bodies, unsolved_directions(bodies));
    match auto_starts_assembled(&layout, contacts) {
        (true, n) if stiff_contact(contacts) => format!(
            "the assembled Jacobian, factorised, from the first step (a plane problem of {n} unknowns with a contact of penalty scale {STIFF_PENALTY_SCALE} or more between two deformable bodies)"
        ),
        (true, n) => format!(
            "the assembled Jacobian, factorised, from the first step (a plane problem of {n} unknowns, at most {START_JACOBIAN_LIMIT})"
        ),
        (false, n) => {
            let switch = match auto_switch(&layout) {
                Some(AutoSwitch::BeyondKrylov) => format!(", switched to the assembled Jacobian (factorised) after a Newton step that needs more than {SWITCH_KRYLOV_ITERATIONS} Krylov iterations"),
                Some(AutoSwitch::Incomplete) if n <= RESCUE_LU_LIMIT_3D => format!(", switched to the assembled Jacobian (ILU(0)) after a Newton step whose Krylov solve used all its iterations, and to its LU after {ILU_STALLS_BEFORE_LU} such steps in a row with the ILU(0)"),
                Some(AutoSwitch::Incomplete) => ", switched to the assembled Jacobian (ILU(0)) after a Newton step whose Krylov solve used all its iterations".to_string(),
                None => String::new(),
            };
            format!(
                "the segregated operator ({n} unknowns; more than {START_JACOBIAN_LIMIT}, or three-dimensional){switch}"
            )
        }
    }
}

/// The Newton–Krylov method and its workspaces (built once per run).
pub struct NewtonKrylovSolver {
    newton: NewtonKrylov,
    /// The Newton parameters of an attempt that a cut-back may follow,
    /// and of the increment's last attempt.
    attempt_params: NewtonParams,
    final_attempt_params: NewtonParams,
    layout: StateLayout,
    operator: SegregatedOperator,
    /// The assembled Jacobian, once it preconditions.
    jacobian: Option<AssembledJacobian>,
    preconditioning: Preconditioning,
    work: ResidualWork,
    params: MomentumParams,
    /// The state of the current increment.
    x: Vec<f64>,
    /// Start and end time of the step being solved.
    step_times: (f64, f64),
    cell_size: f64,
    stiffness_area: f64,
    /// What the solver chose during the run, for the log.
    notes: Vec<String>,
    /// Whether a body is plastic: an increment whose Newton solve fails
    /// from one [`FirstIterate`] is tried from the other before it is cut
    /// back.
    plastic: bool,
    /// Whether the Jacobian is factorised by LU for the current step only,
    /// after its ILU(0) stalled ([`AutoSwitch::Incomplete`]).
    exact_rescue: bool,
    /// The first iterate the last such retry converged from.
    preferred_start: FirstIterate,
    last_change: LastChange,
    /// Seconds per phase.
    pub times: PhaseTimes,
}

/// Newton parameters of the case's settings.
pub fn newton_params(settings: &SolverSettings) -> NewtonParams {
    let linear = settings.linear;
    let mut p = NewtonParams {
        tolerance: settings.tolerance,
        max_iterations: settings.max_outer,
        ..Default::default()
    };
    p.krylov = GmresParams {
        restart: linear.restart,
        max_iterations: linear.max_iterations,
        tolerance: linear.tolerance,
        // the segregated operator's IC(0)-PCG inner solves vary from one
        // application to the next; a fixed preconditioner (multigrid,
        // factorisations) gets plain GMRES instead
        // (`NonlinearProblem::linear_preconditioner`)
        flexible: true,
    };
    p.forcing.max = linear.tolerance;
    p.forcing.initial = p.forcing.initial.min(linear.tolerance);
    p
}

impl NewtonKrylovSolver {
    /// The solver for the bodies (their contact patches prepared with
    /// `ContactSet::prepare_state_conditions`).
    pub fn new(bodies: &[Body], contacts: &ContactSet, settings: &SolverSettings) -> Self {
        let unsolved = unsolved_directions(bodies);
        let layout = StateLayout::new(bodies, unsolved);
        let n = layout.len();
        let preconditioning = settings.linear.preconditioner;
        let direct = settings.linear.method == LinearMethod::Direct;
        let mut attempt_params = newton_params(settings);
        let plastic = bodies
            .iter()
            .any(|b| !b.rigid && b.momentum.law.plastic_strain().is_some());
        // only contact and plasticity make the residual non-smooth
        attempt_params.accept_floor = plastic || !contacts.interfaces.is_empty();
        let mut notes = Vec::new();
        if !settings.restart_given {
            let restart = budgeted_restart(attempt_params.krylov.restart, n, layout.n_cells);
            if restart < attempt_params.krylov.restart {
                notes.push(format!(
                    "GMRES restart {restart} instead of {} on {n} unknowns: its basis held to {} B per cell (set [solver] linear.restart to choose)",
                    attempt_params.krylov.restart, KRYLOV_BASIS_BYTES_PER_CELL
                ));
                attempt_params.krylov.restart = restart;
                attempt_params.restart_growth_limit = GROWN_RESTART_LIMIT;
            }
        }
        let final_attempt_params = NewtonParams {
            stall_abort_iterations: 0,
            rate_abort_window: 0,
            max_iterations: if settings.max_outer_given {
                settings.max_outer
            } else {
                NEWTON_FINAL_ATTEMPT_ITERATIONS.max(settings.max_outer)
            },
            ..attempt_params
        };
        let start_with_jacobian = preconditioning == Preconditioning::Jacobian
            || (preconditioning == Preconditioning::Auto
                && auto_starts_assembled(&layout, contacts).0);
        NewtonKrylovSolver {
            newton: NewtonKrylov::new(n, attempt_params),
            attempt_params,
            final_attempt_params,
            operator: SegregatedOperator::new(bodies, &layout, direct),
            jacobian: start_with_jacobian.then(|| {
                AssembledJacobian::new(
                    bodies,
                    &layout,
                    JacobianFactor::for_unknowns(layout.solved_len()),
                )
            }),
            preconditioning,
            work: ResidualWork::new(bodies, &layout),
            params: MomentumParams {
                rhie_chow: settings.rhie_chow,
                rhie_chow_history: settings.rhie_chow_history,
            },
            x: vec![0.0; n],
            step_times: (0.0, 0.0),
            cell_size: mean_cell_size(bodies),
            stiffness_area: stiffness_area(bodies),
            notes,
            plastic,
            exact_rescue: false,
            preferred_start: FirstIterate::Tangent,
            last_change: LastChange::default(),
            layout,
            times: PhaseTimes::default(),
        }
    }

    /// Bytes of the Newton workspaces (Krylov basis, work vectors,
    /// preconditioners).
    pub fn memory_bytes(&self) -> usize {
        self.newton.memory_bytes()
            + self.operator.memory_bytes()
            + self.jacobian.as_ref().map_or(0, |j| j.memory_bytes())
            + 8 * 2 * self.x.len()
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
        self.newton_and_problem(bodies, contacts).1
    }

    /// [`Self::problem`] beside the Newton solver's workspace.
    fn newton_and_problem<'a>(
        &'a mut self,
        bodies: &'a mut [Body],
        contacts: &'a mut ContactSet,
    ) -> (&'a mut NewtonKrylov, ModelProblem<'a>) {
        let problem = ModelProblem {
            bodies,
            contacts,
            layout: &self.layout,
            params: self.params,
            work: &mut self.work,
            preconditioner: &mut self.operator,
            jacobian: &mut self.jacobian,
            switch_after: None,
            switch_factor: JacobianFactor::Lu,
            switched: None,
            exact_after: None,
            ilu_stalls: 0,
            made_exact: None,
            times: &mut self.times,
            reference: 0.0,
            changes: 0,
            cell_size: self.cell_size,
            stiffness_area: self.stiffness_area,
            evaluations: 0,
            last_refusal: None,
            penetration: (0.0, None),
            shift: 0.0,
            exact_contact: self.preconditioning == Preconditioning::Jacobian,
            jacobian_of_this_attempt: false,
            spring_stalls: 0,
            made_contact_derivative: None,
        };
        (&mut self.newton, problem)
    }

    /// `"auto"` may switch to the assembled Jacobian when a Newton step
    /// needs more than [`SWITCH_KRYLOV_ITERATIONS`] Krylov iterations with
    /// the segregated operator ([`ModelProblem::prepare_preconditioner`]),
    /// if the system can be factorised: up to [`LU_LIMIT`] unknowns in two
    /// dimensions (plane or axisymmetric), [`LU_LIMIT_3D`] in three, where
    /// the LU fills in (the twisting hemisphere, 2,457 cells, ran its first
    /// 20 increments in 27–59 s with it, 6.6 s without). The concentric
    /// spheres (734 cells, 2,500 unknowns), which needed it after the shell
    /// buckles with IC(0), run without it with the multigrid V-cycles: 90
    /// increments, at most 36 Newton iterations, 10.9 s against 22.1 s
    /// switching to it.
    ///
    /// A larger 3-D system, up to [`STALLED_LU_LIMIT_3D`] unknowns, switches
    /// after a Krylov solve that used all its iterations, to the Jacobian
    /// factorised by ILU(0), and to its LU only after
    /// [`residual::ILU_STALLS_BEFORE_LU`] such solves in a row
    /// preconditioned by the ILU(0) ([`AutoSwitch::Incomplete`]). Measured on the coarse wire
    /// drawing with the flow share of the Rhie–Chow term (5,280 cells,
    /// 19,416 unknowns; first 12 increments, one thread): the segregated
    /// operator stalls at 200 Krylov iterations in the third; with the LU
    /// from then on 1.6–4.8 s per increment (7–10 Newton, 50–80 Krylov
    /// iterations), with the ILU(0) 0.5–0.9 s (8–15 Newton, 76–255 Krylov).
    ///
    /// Returns the Krylov iterations of a Newton step beyond which to
    /// switch and the factor switched to, if the switch may happen.
    fn switch_after(&self) -> Option<(usize, JacobianFactor)> {
        if self.preconditioning != Preconditioning::Auto || self.jacobian.is_some() {
            return None;
        }
        let cap = self.newton.krylov_params().max_iterations;
        match auto_switch(&self.layout)? {
            AutoSwitch::BeyondKrylov => Some((SWITCH_KRYLOV_ITERATIONS, JacobianFactor::Lu)),
            AutoSwitch::Incomplete => Some((
                cap.saturating_sub(1).max(SWITCH_KRYLOV_ITERATIONS),
                JacobianFactor::Ilu0,
            )),
        }
    }

    /// The Krylov iterations of a Newton step beyond which `"auto"`
    /// counts a solve preconditioned by the ILU(0) of the Jacobian as
    /// stalled: one that used all its iterations ([`AutoSwitch::Incomplete`],
    /// [`residual::ILU_STALLS_BEFORE_LU`]); none above
    /// [`RESCUE_LU_LIMIT_3D`] unknowns.
    fn exact_after(&self) -> Option<usize> {
        (self.preconditioning == Preconditioning::Auto
            && self.layout.solved_len() <= RESCUE_LU_LIMIT_3D
            && matches!(auto_switch(&self.layout), Some(AutoSwitch::Incomplete)))
        .then(|| self.newton.krylov_params().max_iterations.saturating_sub(1))
    }

    /// The Newton solve of the current first iterate, its counts added to
    /// `total`.
    fn newton_solve(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
        total: &mut NewtonInfo,
        on_iteration: &mut dyn FnMut(usize, f64) -> ControlFlow<()>,
    ) -> Result<NewtonInfo, NewtonError> {
        let switch_after = self.switch_after();
        let exact_after = self.exact_after();
        let mut x = std::mem::take(&mut self.x);
        let (newton, mut problem) = self.newton_and_problem(bodies, contacts);
        if let Some((k, factor)) = switch_after {
            problem.switch_after = Some(k);
            problem.switch_factor = factor;
        }
        problem.exact_after = exact_after;
        let done = total.iterations;
        let trace = std::env::var_os("FVC_TRACE").is_some();
        let result = newton.solve(&mut problem, &mut x, &mut |r| {
            if trace {
                trace_iteration(r);
            }
            if r.iteration > 0 {
                on_iteration(done + r.iteration, r.residual)
            } else {
                ControlFlow::Continue(())
            }
        });
        newton.release_krylov_pages();
        let (switched, switch_factor, made_exact, made_derivative) = (
            problem.switched,
            problem.switch_factor,
            problem.made_exact,
            problem.made_contact_derivative,
        );
        self.x = x;
        if let Some(krylov) = switched {
            let factor = match switch_factor {
                JacobianFactor::Lu => "",
                JacobianFactor::Ilu0 => ", factorised by ILU(0),",
            };
            self.notes.push(format!(
                "t = {:.6e}: a Newton step needed {krylov} Krylov iterations with the segregated operator as preconditioner; the assembled Jacobian{factor} preconditions from the next step on ([solver] linear.preconditioner = \"auto\")",
                self.step_times.1
            ));
        }
        if let Some(krylov) = made_exact {
            self.exact_rescue = true;
            self.notes.push(format!(
                "t = {:.6e}: {ILU_STALLS_BEFORE_LU} Newton steps in a row needed {krylov} Krylov iterations with the ILU(0) of the assembled Jacobian as preconditioner; its LU preconditions from the next Newton step to the end of the step ([solver] linear.preconditioner = \"auto\")",
                self.step_times.1
            ));
        }
        if let Some(krylov) = made_derivative {
            self.notes.push(format!(
                "t = {:.6e}: {SPRING_STALLS} Newton steps in a row needed more than {SPRING_KRYLOV} Krylov iterations (the last {krylov}) with the LU of the assembled Jacobian and the contact springs; from the next step on its contact block is the derivative of the contact forces (linear.preconditioner = \"jacobian\")",
                self.step_times.1
            ));
        }
        let counts = match &result {
            Ok(i) => *i,
            Err(NewtonError::LineSearch { info, .. })
            | Err(NewtonError::Stagnated { info, .. })
            | Err(NewtonError::Interrupted { info, .. })
            | Err(NewtonError::Preconditioner { info, .. }) => *info,
            Err(NewtonError::Start(_)) => NewtonInfo {
                residual_evaluations: 1,
                ..Default::default()
            },
        };
        total.accumulate(&counts);
        result
    }
}

/// `FVC_TRACE`: one line per Newton iteration.
fn trace_iteration(r: &IterationReport) {
    eprintln!(
        "    newton {}: residual {:.3e} eta {:.2e} krylov {} (linear residual {:.2e}) step {:.3e} |dx| {:.3e}{}{}{}",
        r.iteration,
        r.residual,
        r.forcing,
        r.krylov_iterations,
        r.linear_residual,
        r.step_length,
        r.step_norm,
        if r.discontinuity { " discontinuity" } else { "" },
        if r.shift > 0.0 {
            format!(" shift {:.1e}", r.shift)
        } else {
            String::new()
        },
        if r.iteration > 0 {
            format!(" curvature {:.2e} (± {:.1e})", r.curvature, r.curvature_noise)
        } else {
            String::new()
        }
    );
}

impl crate::nonlinear_solver::NonlinearSolver for NewtonKrylovSolver {
    fn method(&self) -> fv_nonlinear::NonlinearMethod {
        fv_nonlinear::NonlinearMethod::NewtonKrylov
    }

    fn prepare(&mut self, _bodies: &[Body]) -> Result<(), SolveError> {
        Ok(())
    }

    fn set_step(&mut self, _path: &PathChange, t0: f64, t1: f64) {
        self.step_times = (t0, t1);
    }

    fn set_divergence_retries(&mut self, _retries: u32) {}

    /// `"auto"` keeps the assembled Jacobian as preconditioner once it
    /// switched to it; a plastic body's increments keep their first
    /// iterate and the last change.
    fn save_state(&self, out: &mut fv_mesh::StateArrays) {
        // 0: none, 1: LU, 2: ILU(0)
        let jacobian = match self.jacobian.as_ref().map(|j| j.kind()) {
            None => 0.0,
            Some(JacobianFactor::Lu) if !self.exact_rescue => 1.0,
            Some(_) => 2.0,
        };
        out.put_scalar("solver/assembled_jacobian".into(), jacobian);
        self.last_change
            .save_state("solver/last_change", self.preferred_start, out);
    }

    fn restore_state(&mut self, bodies: &[Body], s: &fv_mesh::StateArrays) -> Result<(), String> {
        let name = "solver/assembled_jacobian";
        // a state written by the segregated method: nothing to restore
        let saved = if s.has(name) { s.scalar(name)? } else { 0.0 };
        if saved != 0.0 && self.jacobian.is_none() {
            let factor = if saved == 2.0 {
                JacobianFactor::Ilu0
            } else {
                JacobianFactor::Lu
            };
            self.jacobian = Some(AssembledJacobian::new(bodies, &self.layout, factor));
        }
        self.preferred_start =
            self.last_change
                .restore_state("solver/last_change", self.layout.len(), s)?;
        Ok(())
    }

    /// The last attempt neither stops on slow progress nor, unless the
    /// case gives `max_outer`, after [`crate::case::NEWTON_MAX_ITERATIONS`].
    fn set_final_attempt(&mut self, last: bool) {
        self.newton.params = if last {
            self.final_attempt_params
        } else {
            self.attempt_params
        };
    }

    fn solve_increment(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
        on_iteration: &mut dyn FnMut(usize, f64) -> ControlFlow<()>,
    ) -> Result<IncrementInfo, SolveError> {
        self.begin_increment(bodies);
        // a plastic body's increment may start from either first iterate
        // (docs/newton-krylov.md, "First iterate"): the one that served
        // last, the other if the Newton solve fails from it
        let two_starts = self.plastic && self.last_change.is_known();
        let mut start = if two_starts {
            self.preferred_start
        } else {
            FirstIterate::Tangent
        };
        let mut retried = false;
        self.first_iterate(start, bodies, contacts);
        let solved = [0, 1, 2].map(|c| !self.layout.unsolved[c]);
        let mut info = IncrementInfo {
            required: self.newton.params.tolerance,
            ..Default::default()
        };
        let mut total = NewtonInfo::default();
        let mut solves = 0;
        let restart_before = self.newton.krylov_params().restart;
        let outcome = loop {
            solves += 1;
            let result = self.newton_solve(bodies, contacts, &mut total, on_iteration);
            info.outer_iterations = total.iterations;
            info.linear_iterations = total.krylov_iterations;
            info.residual_evaluations = total.residual_evaluations;
            info.residual = total.residual;
            match result {
                Err(NewtonError::Start(e)) if self.x.iter().any(|v| *v != 0.0) => {
                    // the first iterate is not admissible after all: from
                    // the start state
                    let _ = e;
                    self.x.iter_mut().for_each(|v| *v = 0.0);
                    continue;
                }
                Err(NewtonError::Start(e)) => {
                    break Err(SolveError::Material(format!(
                        "the start of the increment is not admissible: {}",
                        e.0
                    )))
                }
                Err(NewtonError::Interrupted { .. }) => break Err(SolveError::Interrupted),
                Err(NewtonError::LineSearch { .. } | NewtonError::Stagnated { .. })
                | Ok(NewtonInfo {
                    converged: false, ..
                }) if two_starts && !retried && solves == 1 => {
                    if std::env::var_os("FVC_TRACE").is_some() {
                        eprintln!("    failed from {start:?}; again from {:?}", start.other());
                    }
                    retried = true;
                    start = start.other();
                    self.first_iterate(start, bodies, contacts);
                    solves = 0;
                    continue;
                }
                Err(e) => break Err(SolveError::Nonlinear(e.to_string())),
                Ok(i) if !i.converged => break Ok(false),
                Ok(_) => {}
            }
            if solves >= MAX_NEWTON_SOLVES {
                break Ok(false);
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
            // the Rhie–Chow share of cells that began to flow in this
            // increment
            if crate::model::follow_flow_of_increment(bodies) {
                continue;
            }
            break Ok(true);
        };
        if total.at_floor && matches!(outcome, Ok(true)) {
            self.notes.push(format!(
                "t = {:.6e}: converged at the residual floor {:.2e} (no Newton step decreased the residual further; up to {:.0} × the tolerance is accepted there: a residual that contact faces opening and closing, or cells crossing the yield surface, make non-smooth at the solution)",
                self.step_times.1,
                total.residual,
                self.newton.params.floor_factor
            ));
        } else if matches!(outcome, Ok(true)) && total.residual > self.newton.params.tolerance {
            // converged below the round-off floor, which is above
            // tolerance × the force scale (a load small against the
            // bodies' stiffness): the log's residual would look unconverged
            self.notes.push(format!(
                "t = {:.6e}: converged at the round-off floor, relative residual {:.2e} (10⁻¹³ Σ K|Γ| over the bodies' faces, above the tolerance {:.1e} × the force scale: a load small against the bodies' stiffness)",
                self.step_times.1,
                total.residual,
                self.newton.params.tolerance
            ));
        }
        let restart = self.newton.krylov_params().restart;
        if restart != restart_before {
            self.notes.push(format!(
                "t = {:.6e}: GMRES restart grown from {restart_before} to {restart}: a Krylov solve stopped short of its forcing term (its basis now {} B per cell)",
                self.step_times.1,
                (restart + 1) * 8 * self.layout.len() / self.layout.n_cells.max(1)
            ));
        }
        info.converged = outcome?;
        if info.converged {
            contacts.commit_increment();
            if std::mem::take(&mut self.exact_rescue) {
                // the LU served the hard step; the ILU(0) the next ones
                if let Some(j) = self.jacobian.as_mut() {
                    j.refactor_as(JacobianFactor::Ilu0);
                }
            }
            if retried && start != self.preferred_start {
                self.notes.push(format!(
                    "t = {:.6e}: the Newton solve failed from {} and converged from {}, which starts the next increments (a plastic body; docs/newton-krylov.md, \"First iterate\")",
                    self.step_times.1,
                    self.preferred_start.describe(),
                    start.describe()
                ));
                self.preferred_start = start;
            }
            if self.plastic {
                let (t0, t1) = self.step_times;
                self.last_change.record(&self.x, t1 - t0);
            }
        }
        Ok(info)
    }

    fn refresh_restored(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
    ) -> Result<(), String> {
        // the residual at the restored start (x = 0) sets every field of it
        self.begin_increment(bodies);
        let n = self.state_len();
        let (x, mut f) = (vec![0.0; n], vec![0.0; n]);
        self.problem(bodies, contacts)
            .residual(&x, &mut f, Frozen::Renew)
            .map_err(|e| e.0)
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

    fn take_notes(&mut self) -> Vec<String> {
        std::mem::take(&mut self.notes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_krylov_basis_of_a_large_mesh_is_held_to_its_budget() {
        // the 64³ box: 262,144 cells and 16,384 traction face nodes, three
        // components each
        let (cells, n) = (262_144, 3 * (262_144 + 16_384));
        // 540 B per cell = 21.2 vectors of 8 n bytes: GMRES(20)
        assert_eq!(budgeted_restart(30, n, cells), 20);
        assert!((20 + 1) * 8 * n <= KRYLOV_BASIS_BYTES_PER_CELL * cells);
        // a shorter restart is kept; small meshes keep theirs
        assert_eq!(budgeted_restart(12, n, cells), 12);
        assert_eq!(budgeted_restart(30, 3 * 19_904, 19_904), 30);
        // never below the floor, however many unknowns a cell has
        assert_eq!(
            budgeted_restart(30, 100 * cells, cells),
            MIN_BUDGETED_RESTART
        );
    }
}
