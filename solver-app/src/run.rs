//! `fvc run`: load, set up, solve every increment, write results.
use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::case::{Case, Coupling, InputError, OnNonConvergence};
use crate::contact_coupling::{frictionless_slide, ContactSet};
use crate::field_output::FieldOutput;
use crate::interrupt::{signal_name, Interrupt};
use crate::mesh_loading::load_mesh;
use crate::model::{build_bodies, Body};
use crate::nonlinear_solver::{self, NonlinearSolver};
use crate::predictor::PathChange;
use crate::progress::Progress;
use crate::restart::{RestartFrom, Resumed};
use crate::results::{
    history_columns, history_row, write_summary, History, RunLog, Summary, SummaryFigures,
};
use crate::segregated::{IncrementInfo, SegregatedSolver, SolveError};
use crate::words::{count, duration, Num};
use fv_nonlinear::NonlinearMethod;

/// Largest number of times a failed increment is halved and redone.
const MAX_CUTBACKS: usize = 4;

/// Converged sub-steps in a row after which a cut-back increment doubles
/// its sub-step again (undoing one halving): the hard stretch that failed
/// the first attempt is often shorter than the increment (curved beams
/// μ = 0.6 at 28.5 mm: the flank leaving the shoulder), and the rest of
/// the increment need not be crossed in the smallest steps. Abaqus grows
/// its time increment after two quick increments; after one, that
/// increment took 55 Newton iterations (69 after two, 129 without
/// regrowth), μ = 0.3's worst 44 (45).
const GROWTH_AFTER: usize = 1;

/// Whether the problem is linear in the load: every deformable body
/// small-strain (Hooke's law on the initial mesh) without force control or
/// inertia, and no contact. The outer iteration of a linear problem, and
/// its residual relative to the increment's displacement, do not depend on
/// the size of the step, so halving a step that failed to converge only
/// repeats the failure (a diverged attempt is still redone: the retry
/// starts more relaxed).
fn is_linear(bodies: &[Body], contacts: &ContactSet) -> bool {
    contacts.is_empty()
        && bodies.iter().all(|b| {
            b.rigid
                || (!b.momentum.law.is_updated_lagrangian()
                    && b.force_controls.is_empty()
                    && b.momentum.inertia.is_none())
        })
}

/// Command-line options of `fvc run`.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Overrides `[output] directory`.
    pub output: Option<PathBuf>,
    /// No progress bar; one log line per increment.
    pub quiet: bool,
    /// Write no files (tests and benchmarks).
    pub no_files: bool,
    /// A failed increment is not halved and redone (benchmarks that count
    /// the outer iterations of one step, e.g. the coupling efficiency of
    /// thesis Tables 4.5–4.7).
    pub no_cutbacks: bool,
    /// Asks the run to stop (SIGINT, SIGTERM; [`Interrupt::install`]):
    /// it ends after the write under way with the results so far.
    pub interrupt: Interrupt,
    /// `--restart`: continue an earlier run of the case from its results.
    pub restart: Option<RestartFrom>,
}

/// Result of a run.
pub struct RunOutcome {
    /// Every increment converged (or `continue` was asked).
    pub converged: bool,
    /// Why the run stopped early.
    pub failure: Option<String>,
    /// The signal that stopped the run before its end, if one did.
    pub interrupted: Option<i32>,
    /// The bodies with their final fields.
    pub bodies: Vec<Body>,
    /// The contact pairs with their final tractions.
    pub contacts: ContactSet,
    /// Summary figures.
    pub summary: Summary,
    /// Results directory (`None` with `no_files`).
    pub directory: Option<PathBuf>,
}

/// Errors that stop a run before it starts.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// Bad input: exit code 2.
    #[error("{0}")]
    Input(#[from] InputError),
    /// The results directory could not be written: exit code 1.
    #[error("cannot write results: {0}")]
    Output(String),
}

/// The results folder `dir` could not be created or written: an input
/// error naming `--output` or the case's `output.directory`.
fn unwritable(case: &Case, opts: &RunOptions, dir: &Path, e: &dyn std::fmt::Display) -> RunError {
    let msg = format!("cannot write the results folder '{}': {e}", dir.display());
    RunError::Input(match &opts.output {
        Some(o) => InputError::new(
            &case.source.path,
            format!("--output {}: {msg}", o.display()),
        ),
        None => case.source.error("output.directory", msg),
    })
}

/// The bodies of [`set_up`] and the contact pairs between them: everything
/// `run` validates before it solves (shared by `run` and `check`).
pub fn set_up_with_contacts(case: &Case) -> Result<(Vec<Body>, ContactSet), InputError> {
    let bodies = set_up(case)?;
    let contacts = ContactSet::new(case, &bodies)?;
    crate::initial_overlap::check_initial_overlap(case, &bodies, &contacts)?;
    Ok((bodies, contacts))
}

/// Loads every body's mesh and builds the model.
pub fn set_up(case: &Case) -> Result<Vec<Body>, InputError> {
    let mut meshes = Vec::with_capacity(case.bodies.len());
    for (i, b) in case.bodies.iter().enumerate() {
        meshes.push(load_mesh(&b.mesh, i, &case.source)?);
    }
    build_bodies(case, meshes)
}

/// An accepted increment or sub-step: the bodies end it (updated
/// Lagrangian: mesh moved, state committed; dynamics: time levels shifted)
/// and, when the meshes moved, the contact surfaces follow and the matrix
/// is reassembled.
fn accept_increment(
    bodies: &mut [Body],
    contacts: &mut ContactSet,
    solver: &mut dyn NonlinearSolver,
    meshes_move: bool,
) -> Result<(), SolveError> {
    let start = std::time::Instant::now();
    for b in bodies.iter_mut() {
        b.end_increment().map_err(SolveError::Material)?;
    }
    if meshes_move {
        contacts.end_increment(bodies);
    }
    solver
        .times_mut()
        .lap(crate::profile::Phase::MeshMotion, start);
    if meshes_move {
        solver.prepare(bodies)?;
    }
    Ok(())
}

/// Runs a validated case to the end (or to its first failure).
///
/// A body that nothing but its contacts holds in some direction (a punch
/// pressed by a load onto its foundation) cannot be solved with explicit
/// coupling, which applies the contact traction as a load (eq. 4.13): its
/// matrix is singular. Such contacts are then coupled implicitly (eq.
/// 4.52, the penalty springs in the matrix hold the body), and the log
/// says so; where that is not possible (a patch in several pairs between
/// deformable bodies) the case is an input error naming the contacts.
pub fn run_case(case: &Case, opts: &RunOptions) -> Result<RunOutcome, RunError> {
    run_case_noting(case, opts, None)
}

/// [`run_case`], with a warning for the log (the coupling it changed).
fn run_case_noting(
    case: &Case,
    opts: &RunOptions,
    note: Option<&str>,
) -> Result<RunOutcome, RunError> {
    let start = Instant::now();
    let (mut bodies, mut contacts) = set_up_with_contacts(case)?;
    let method = case.solver.nonlinear;
    nonlinear_solver::prepare_contact_conditions(method, &contacts, &mut bodies);
    let mut failure: Option<String> = None;
    // the temporal diagonal of the first assembly needs the first time step
    let first_dt = case.time.dt();
    for inertia in bodies
        .iter_mut()
        .filter_map(|b| b.momentum.inertia.as_mut())
    {
        inertia.set_time_step(first_dt);
    }
    // every body held (Newton–Krylov: contact holds whatever it touches,
    // whatever the coupling)
    let held = match method {
        // its own set-up checks (and may couple explicit contacts
        // implicitly first); the frictionless check needs implicit contacts
        NonlinearMethod::Segregated => {
            Ok(SegregatedSolver::check_held(&bodies, &case.solver).unwrap_or_default())
        }
        NonlinearMethod::NewtonKrylov => SegregatedSolver::check_held(&bodies, &case.solver),
    };
    if let Some(e) = held
        .as_ref()
        .ok()
        .and_then(|floating| frictionless_slide(case, &bodies, &contacts, floating))
    {
        return Err(RunError::Input(e));
    }
    let loaded_by_contact_alone = match (&held, method) {
        (Ok(floating), NonlinearMethod::NewtonKrylov) => loaded_floating_bodies(&bodies, floating),
        _ => Vec::new(),
    };
    let held = held.map(|_| ());
    let mut solver = nonlinear_solver::build(&bodies, &contacts, &case.solver);
    // `--restart`: the state of the increment continued from, before the
    // method sets up on the meshes
    let resumed = match &opts.restart {
        Some(from) => {
            let state = crate::restart::load(from, &bodies, &contacts)?;
            let file = &from.file;
            Some(crate::restart::apply(
                &state,
                file,
                &mut bodies,
                &mut contacts,
                solver.as_mut(),
            )?)
        }
        None => None,
    };
    if let Err(e) = held.and_then(|_| solver.prepare(&bodies)) {
        let may_switch = note.is_none() && method == NonlinearMethod::Segregated;
        match unheld_body(case, &e, may_switch) {
            Some(Ok((note, switched))) => return run_case_noting(&switched, opts, Some(&note)),
            Some(Err(input)) => return Err(RunError::Input(input)),
            None => failure = Some(e.to_string()),
        }
    }
    // a continued run with nothing left to solve writes the summary of the
    // state it continues from: evaluated, or its reactions were those of
    // no solve, zero (found by a fresh-clone walkthrough, 2026-12-01)
    if let Some(r) = resumed
        .as_ref()
        .filter(|r| r.time >= case.time.end - 1e-9 * case.time.end.abs())
    {
        for b in bodies.iter_mut() {
            b.refresh_conditions(r.time);
        }
        let _ = solver.refresh_restored(&mut bodies, &mut contacts);
    }
    // FVC_TRACE=1 prints the residual of every outer iteration, 2 also the
    // contact statistics (debugging aid)
    let trace_outer = std::env::var_os("FVC_TRACE").is_some_and(|v| v == "1" || v == "2");
    let dir = if opts.no_files {
        None
    } else {
        let dir = match &opts.restart {
            Some(from) => crate::restart::results_folder(case, from, opts.output.as_deref())?,
            None => opts
                .output
                .clone()
                .unwrap_or_else(|| case.output.directory.clone())
                .join(&case.title),
        };
        std::fs::create_dir_all(&dir).map_err(|e| unwritable(case, opts, &dir, &e))?;
        if opts.restart.is_none() {
            remove_stale_plots(&dir);
        }
        Some(dir)
    };
    let signature = crate::restart::case_signature(&bodies, &contacts);
    let io_err = |e: std::io::Error| RunError::Output(e.to_string());
    let out_err = |e: crate::output::OutputError| RunError::Output(e.to_string());
    // the result files are created before the first increment: a folder
    // that cannot take them is the input's (exit 2), not the solver's
    let (mut log, mut history, mut fields) = match (&dir, &resumed) {
        (Some(d), None) => (
            RunLog::create(d).map_err(|e| unwritable(case, opts, d, &e))?,
            Some(
                History::create(d, &bodies, &contacts)
                    .map_err(|e| unwritable(case, opts, d, &e))?,
            ),
            Some(
                FieldOutput::create(d, &case.title, &bodies, &signature, &case.output)
                    .map_err(|e| unwritable(case, opts, d, &e))?,
            ),
        ),
        // a continued run: the results so far, cut after its increment
        (Some(d), Some(r)) => (
            RunLog::append(d).map_err(|e| unwritable(case, opts, d, &e))?,
            Some(History::reopen(d, r.k).map_err(|e| unwritable(case, opts, d, &e))?),
            Some(
                FieldOutput::reopen(d, &case.title, &bodies, &signature, r.k, &case.output)
                    .map_err(|e| unwritable(case, opts, d, &e))?,
            ),
        ),
        (None, _) => (RunLog::none(), None, None),
    };
    let columns = history_columns(&bodies, &contacts);
    let columns: Vec<&str> = columns.iter().map(|s| s.as_str()).collect();
    let cells: usize = bodies.iter().map(|b| b.mesh.n_cells).sum();
    let resumed = resumed.unwrap_or(Resumed {
        converged: true,
        dt_prev: case.time.dt(),
        ..Default::default()
    });
    let mut summary = Summary {
        title: case.title.clone(),
        converged: resumed.converged,
        cells,
        nonlinear: method.name(),
        increments: resumed.k,
        time_reached: resumed.time,
        outer_iterations: resumed.outer_iterations,
        linear_iterations: resumed.linear_iterations,
        residual_evaluations: resumed.residual_evaluations,
        restarted_from: opts.restart.as_ref().map(|_| resumed.k),
        ..Default::default()
    };
    log.info(&format!(
        "case '{}' ({}): {}, {}, {}",
        case.title,
        case.source.path.display(),
        count(bodies.len(), "body", "bodies"),
        count(cells, "cell", "cells"),
        count(case.time.steps, "increment", "increments")
    ));
    log.info(&crate::check::solver_report(case, &bodies, &contacts));
    for line in crate::check::contact_report(&contacts) {
        log.info(&line);
    }
    if let Some(from) = &opts.restart {
        log.info(&format!(
            "continued from increment {} (t = {}) of {}; later increments of the results are replaced",
            resumed.k,
            Num(resumed.time),
            from.file.display()
        ));
    }
    if let Some(note) = note {
        log.warn(note);
        summary.coupling_switched.push(note.to_owned());
    }
    for w in short_tables(case) {
        log.warn(&w);
    }
    for n in bodies.iter().flat_map(|b| &b.setup_notes) {
        log.warn(n);
    }

    // a continued run goes on along the case's time grid from the time it
    // starts at, whatever grid the run that wrote the file had: increments
    // K + 1, K + 2, … at the grid's times after t_K (a case continued
    // with twice the steps solved t = 0.375 after t = 0.5)
    let (steps, grid_shift) = continued_grid(case, resumed.k, resumed.time);
    let tty = std::io::stderr().is_terminal() && !opts.quiet && !opts.no_files;
    let mut progress = Progress::new(tty, resumed.k, steps);

    let reassemble_every_increment = bodies
        .iter()
        .any(|b| !b.rigid && b.momentum.law.is_updated_lagrangian());
    let linear = is_linear(&bodies, &contacts);
    let mut t_prev = resumed.time;
    let mut dt_prev = resumed.dt_prev;
    // the change of the prescribed values over a step (predictor), and the
    // values at the end of the step (buffers kept across steps)
    let mut path = PathChange::default();
    let mut path_end = PathChange::default();
    let solve_start = Instant::now();
    let mut cell_iterations = 0.0;
    let mut switched_coupling = resumed.switched_coupling;
    // the increment of the last restart state written
    let mut last_state = opts.restart.as_ref().map(|_| resumed.k);
    let may_switch = case.solver.coupling_fallback == crate::case::CouplingFallback::Implicit
        && method == NonlinearMethod::Segregated;
    let mut evaluations = 0usize;
    let mut interrupted = None;
    // the summary's forces of the last increment written (the start
    // state's before the first)
    let mut figures = match dir {
        Some(_) => SummaryFigures::of(&bodies, &contacts),
        None => SummaryFigures::default(),
    };
    for k in resumed.k + 1..=steps {
        if failure.is_some() || interrupted.is_some() {
            break;
        }
        if let Some(sig) = opts.interrupt.requested() {
            interrupted = Some(sig);
            break;
        }
        let t = case.time.time_at(k.saturating_add_signed(grid_shift));
        let increment_clock = Instant::now();
        // the increment, in sub-steps when an attempt fails (cut-back)
        // converged while every sub-step is
        let mut total = IncrementInfo {
            converged: true,
            ..Default::default()
        };
        let mut t0 = t_prev;
        let mut h = t - t_prev;
        let mut cuts = 0;
        // converged sub-steps in a row since the last halving or doubling
        let mut converged_in_a_row = 0;
        // attempts that diverged: the next ones start more relaxed
        let mut diverged = 0;
        let result = loop {
            let t1 = if t0 + h >= t - 1e-9 * (t - t_prev) {
                t
            } else {
                t0 + h
            };
            for b in bodies.iter_mut() {
                b.refresh_conditions(t1);
                b.save_start();
            }
            contacts.set_time(t1);
            contacts.save_start();
            // time step of the temporal term; the matrix diagonal holds m/Δt²
            let mut dt_k = t1 - t0;
            if (dt_k - dt_prev).abs() <= 1e-9 * dt_prev {
                dt_k = dt_prev; // equal steps up to rounding: keep the factorisation
            }
            let mut has_inertia = false;
            for inertia in bodies
                .iter_mut()
                .filter_map(|b| b.momentum.inertia.as_mut())
            {
                inertia.set_time_step(dt_k);
                has_inertia = true;
            }
            if has_inertia && dt_k != dt_prev {
                if let Err(e) = solver.prepare(&bodies) {
                    break Err(e);
                }
            }
            dt_prev = dt_k;
            path.clear();
            path_end.clear();
            for b in bodies.iter() {
                b.prescribed_values(t0, &mut path.kinematic, &mut path.loads);
                b.prescribed_values(t1, &mut path_end.kinematic, &mut path_end.loads);
            }
            path.subtract_from(&path_end);
            solver.set_step(&path, t0, t1);
            solver.set_divergence_retries(diverged);
            solver.set_final_attempt(opts.no_cutbacks || cuts >= MAX_CUTBACKS);
            let switch_available = may_switch
                && !switched_coupling
                && !opts.no_cutbacks
                && !switchable_explicit_contacts(case, &contacts).is_empty();
            solver.set_coupling_switch(switch_available);
            let attempt = solver.solve_increment(&mut bodies, &mut contacts, &mut |outer, res| {
                if trace_outer {
                    eprintln!("  outer {outer}: residual {res:.3e}");
                }
                progress.iteration(outer, res);
                match opts.interrupt.requested() {
                    Some(_) => ControlFlow::Break(()),
                    None => ControlFlow::Continue(()),
                }
            });
            for note in solver.take_notes() {
                log.warn(&format!("increment {k}: {note}"));
            }
            if let Err(SolveError::Interrupted) = attempt {
                // back to the last converged state, which the results hold
                restore_start(&mut bodies, &mut contacts);
                break Err(SolveError::Interrupted);
            }
            let failed = match &attempt {
                Ok(info) => !info.converged,
                Err(e) => !matches!(e, crate::segregated::SolveError::Unconstrained { .. }),
            };
            // explicit coupling that failed: the attempt is redone, with the
            // same step, coupled implicitly (once; the contacts stay so)
            let switch = if failed && !opts.no_cutbacks && !switched_coupling && may_switch {
                switchable_explicit_contacts(case, &contacts)
            } else {
                Vec::new()
            };
            if !switch.is_empty() {
                let why = match &attempt {
                    Ok(info) => {
                        total.outer_iterations += info.outer_iterations;
                        total.linear_iterations += info.linear_iterations;
                        total.residual_evaluations += info.residual_evaluations;
                        if info.coupling_stalled {
                            format!(
                                "{} after {}",
                                info.shortfall(case.solver.tolerance),
                                count(info.outer_iterations, "outer iteration", "outer iterations")
                            )
                        } else {
                            format!(
                                "no convergence in {}",
                                count(info.outer_iterations, "outer iteration", "outer iterations")
                            )
                        }
                    }
                    Err(e) => e.to_string(),
                };
                restore_start(&mut bodies, &mut contacts);
                contacts.couple_implicitly(&switch, &mut bodies);
                switched_coupling = true;
                let note = format!(
                    "increment {k}: step t = {} → {} failed with explicit coupling ({why}); [[contact]] {} coupled implicitly from here on (thesis §4.5), the step redone",
                    Num(t0),
                    Num(t1),
                    contact_names(case, &switch)
                );
                log.warn(&note);
                summary.coupling_switched.push(note);
                continue;
            }
            // nothing prescribed changes with time (constant values apply in
            // full from the first increment): a smaller step of a static
            // problem is the same problem, and an attempt that merely did
            // not converge would be repeated as it was
            let constant_path =
                !has_inertia && path.kinematic.iter().chain(&path.loads).all(|x| *x == 0.0);
            if let (true, Ok(info)) = (failed && constant_path && !opts.no_cutbacks, &attempt) {
                log.warn(&format!(
                    "increment {k}: no convergence in {} ({}); not redone in smaller steps: no prescribed value changes over the step t = {} → {} (a constant value is applied in full from the first increment; give a load or a displacement as a table to ramp it), so a smaller step is the same problem",
                    count(info.outer_iterations, "outer iteration", "outer iterations"),
                    info.shortfall(case.solver.tolerance),
                    Num(t0),
                    Num(t1)
                ));
            } else if let (true, Ok(info)) = (failed && linear && !opts.no_cutbacks, &attempt) {
                log.warn(&format!(
                    "increment {k}: no convergence in {} ({}); not redone in smaller steps: the problem is linear (small strain, Hooke's law, no contact, no force control, no inertia), and its outer iteration converges no faster for a smaller load step; raise [solver] max_outer, or loosen tolerance",
                    count(info.outer_iterations, "outer iteration", "outer iterations"),
                    info.shortfall(case.solver.tolerance)
                ));
            } else if let (true, Err(e @ SolveError::Linear(_))) =
                (failed && linear && !opts.no_cutbacks, &attempt)
            {
                // the matrix of a linear problem does not depend on the step
                log.warn(&format!(
                    "increment {k}: {e}; not redone in smaller steps: the problem is linear and its matrix the same for any step. A matrix that is not positive definite usually means that a part of a body is held by nothing: a mesh of parts that are not joined (in Gmsh: BooleanFragments, or Coherence) or a region without a condition"
                ));
            } else if failed && !opts.no_cutbacks && cuts < MAX_CUTBACKS {
                let why = match &attempt {
                    Ok(info) => format!(
                        "no convergence in {}",
                        count(info.outer_iterations, "outer iteration", "outer iterations")
                    ),
                    Err(e) => e.to_string(),
                };
                match &attempt {
                    Ok(info) => {
                        total.outer_iterations += info.outer_iterations;
                        total.linear_iterations += info.linear_iterations;
                        total.residual_evaluations += info.residual_evaluations;
                    }
                    Err(_) => diverged += 1,
                }
                restore_start(&mut bodies, &mut contacts);
                cuts += 1;
                converged_in_a_row = 0;
                // half the step that failed: one clipped at the increment's
                // end is shorter than h, and halving h repeated it as it
                // was (a probe's 0.0875 → 0.1 three times)
                h = 0.5 * (t1 - t0);
                log.warn(&format!(
                    "increment {k}: step t = {} → {} failed ({why}); redone in steps of {}",
                    Num(t0),
                    Num(t1),
                    Num(h)
                ));
                continue;
            }
            match attempt {
                Ok(info) => {
                    total.outer_iterations += info.outer_iterations;
                    total.linear_iterations += info.linear_iterations;
                    total.residual_evaluations += info.residual_evaluations;
                    let go_on = info.converged
                        || case.solver.on_nonconvergence == OnNonConvergence::Continue;
                    if !go_on && t0 > t_prev {
                        // under `abort`, after converged sub-steps: back to
                        // the last of them, which the results report (as
                        // after an error) with its residual, not the
                        // unconverged iterate
                        restore_start(&mut bodies, &mut contacts);
                        break Err(SolveError::Nonlinear(format!(
                            "sub-step t = {t0:.6e} → {t1:.6e} did not converge in {} outer iterations ({})",
                            info.outer_iterations,
                            info.shortfall(case.solver.tolerance)
                        )));
                    }
                    total.residual = info.residual;
                    total.required = info.required;
                    total.contact_unsettled = info.contact_unsettled;
                    total.converged &= info.converged;
                    if t1 == t || !go_on {
                        // the fields are those of t1: an unconverged step
                        // under `abort` is reported at its own time
                        break Ok((total, t1));
                    }
                    if !info.converged {
                        // `continue`: keep the unconverged sub-step and go on
                        // to the end of the increment
                        log.warn(&format!(
                            "increment {k}: sub-step t = {} → {} did not converge in {} ({}); continuing",
                            Num(t0),
                            Num(t1),
                            count(info.outer_iterations, "outer iteration", "outer iterations"),
                            info.shortfall(case.solver.tolerance)
                        ));
                    }
                    // a sub-step: accept it and go on
                    if let Err(e) = accept_increment(
                        &mut bodies,
                        &mut contacts,
                        solver.as_mut(),
                        reassemble_every_increment,
                    ) {
                        break Err(e);
                    }
                    t0 = t1;
                    converged_in_a_row = if info.converged {
                        converged_in_a_row + 1
                    } else {
                        0
                    };
                    if converged_in_a_row >= GROWTH_AFTER && cuts > 0 {
                        converged_in_a_row = 0;
                        cuts -= 1;
                        h *= 2.0;
                    }
                }
                Err(e) => {
                    // back to the last accepted state (the increment's start,
                    // or its last converged sub-step): the results and the
                    // summary report it, not the failed iterate
                    restore_start(&mut bodies, &mut contacts);
                    break Err(e);
                }
            }
        };
        let increment_start = t_prev;
        t_prev = t;
        match result {
            Ok((info, t)) => {
                summary.increments = k;
                summary.time_reached = t;
                summary.outer_iterations += info.outer_iterations;
                summary.linear_iterations += info.linear_iterations;
                cell_iterations += (info.outer_iterations * solver.n_unknowns()) as f64;
                evaluations += info.residual_evaluations;
                summary.residual_evaluations += info.residual_evaluations;
                let seconds = increment_clock.elapsed().as_secs_f64();
                let line = format!(
                    "increment {k}/{} t = {}: {}, residual {:.3e}, {}, {}{}",
                    steps,
                    Num(t),
                    count(info.outer_iterations, "outer iteration", "outer iterations"),
                    info.residual,
                    count(
                        info.linear_iterations,
                        "linear iteration",
                        "linear iterations"
                    ),
                    duration(seconds),
                    if info.converged {
                        ""
                    } else {
                        " (NOT converged)"
                    }
                );
                if progress.is_shown() {
                    progress.increment_done(k, seconds);
                    log.write(&line);
                } else if opts.quiet || !opts.no_files {
                    log.info(&line);
                }
                // axisymmetric wedges: the full-revolution forces
                for l in crate::results::full_revolution_lines(&bodies, &contacts) {
                    log.write(&l);
                }
                let with_fields = k % case.output.every == 0 || k == steps || !info.converged;
                record_increment(
                    &mut history,
                    &mut fields,
                    &columns,
                    &IncrementRecord {
                        k,
                        t,
                        outer_iterations: info.outer_iterations,
                        residual: info.residual,
                        converged: info.converged,
                        with_fields,
                    },
                    &bodies,
                    &contacts,
                )?;
                if dir.is_some() {
                    figures = SummaryFigures::of(&bodies, &contacts);
                }
                let accepted =
                    info.converged || case.solver.on_nonconvergence == OnNonConvergence::Continue;
                if accepted {
                    // updated Lagrangian: move the meshes, commit the state;
                    // dynamics: shift the time levels
                    if let Err(e) = accept_increment(
                        &mut bodies,
                        &mut contacts,
                        solver.as_mut(),
                        reassemble_every_increment,
                    ) {
                        failure = Some(format!("after increment {k}: {e}"));
                    }
                    for (i, penetration, height) in contacts.take_newly_augmented() {
                        log.info(&format!(
                            "increment {k}: [[contact]] {}: largest penetration {penetration:.3e} = {:.2e} of the slave cells' mean height {height:.3e}: augmented Lagrangian updates of the contact pressure from here on",
                            contact_names(case, &[i]),
                            penetration / height,
                        ));
                    }
                    // explicit coupling that converged only at its smallest
                    // relaxation: the next increments would grind the same
                    // way, so they are coupled implicitly
                    let stalled = contacts.explicit_at_smallest_relaxation();
                    if !stalled.is_empty() && !switched_coupling && !opts.no_cutbacks && may_switch
                    {
                        let switch = switchable_explicit_contacts(case, &contacts);
                        if !switch.is_empty() {
                            contacts.couple_implicitly(&switch, &mut bodies);
                            switched_coupling = true;
                            let note = format!(
                                "increment {k}: explicit coupling of [[contact]] {} converged only at its smallest relaxation ({} outer iterations); [[contact]] {} coupled implicitly from the next increment on (thesis §4.5)",
                                contact_names(case, &stalled),
                                info.outer_iterations,
                                contact_names(case, &switch)
                            );
                            log.warn(&note);
                            summary.coupling_switched.push(note);
                        }
                    }
                }
                if !info.converged {
                    // the iterations of every attempt (the step cut back in
                    // between) are summed
                    let attempts = if cuts > 0 {
                        format!(" over {} attempts", cuts + 1)
                    } else {
                        String::new()
                    };
                    let mut msg = format!(
                        "increment {k} did not converge in {}{attempts} ({})",
                        count(info.outer_iterations, "outer iteration", "outer iterations"),
                        info.shortfall(case.solver.tolerance)
                    );
                    if let Some(name) = loaded_by_contact_alone.first() {
                        msg.push_str(&format!(
                            "; body '{name}' is held by contact alone and loaded by a traction or pressure, which Newton–Krylov cannot bring into contact while the contact is open: give the load as type = \"force\" (a total force, reached by displacement), or solve with nonlinear = \"segregated\""
                        ));
                    }
                    match case.solver.on_nonconvergence {
                        OnNonConvergence::Abort => {
                            failure = Some(msg);
                        }
                        OnNonConvergence::Continue => {
                            log.warn(&msg);
                            summary.converged = false;
                        }
                    }
                }
                // the state the next increment starts from, with the fields
                if let (true, true, None, Some(w)) = (with_fields, accepted, &failure, &mut fields)
                {
                    let run = Resumed {
                        k,
                        time: t,
                        outer_iterations: summary.outer_iterations,
                        linear_iterations: summary.linear_iterations,
                        residual_evaluations: summary.residual_evaluations,
                        wall_seconds: resumed.wall_seconds + start.elapsed().as_secs_f64(),
                        converged: summary.converged,
                        switched_coupling,
                        dt_prev,
                    };
                    let state = crate::restart::capture(&run, &bodies, &contacts, solver.as_ref());
                    w.write_restart(k, t, state).map_err(out_err)?;
                    // the last state stays, and every `restart_every`-th
                    if let Some(prev) = last_state.replace(k) {
                        if prev % case.output.restart_every != 0 {
                            w.drop_restart(prev).map_err(out_err)?;
                        }
                    }
                }
            }
            Err(e) => {
                let mut msg = format!("increment {k}: {e}");
                if t0 > increment_start {
                    // converged sub-steps of the failed increment: the last
                    // is written as increment k at its own time, with its
                    // contact surfaces and tractions (the failed attempt
                    // left its own behind)
                    // the conditions of t0: the failed attempt left its own
                    // (a sphere inflated by a normal-displacement was
                    // written at t0 with the inner face of the failed
                    // attempt's end, its reaction 2.3e9 against 8.4e4)
                    for b in bodies.iter_mut() {
                        b.refresh_conditions(t0);
                    }
                    if let Err(e) = solver.refresh_restored(&mut bodies, &mut contacts) {
                        log.warn(&format!(
                            "increment {k}: the state of t = {} could not be evaluated for the results: {e}",
                            Num(t0)
                        ));
                    }
                    record_increment(
                        &mut history,
                        &mut fields,
                        &columns,
                        &IncrementRecord {
                            k,
                            t: t0,
                            outer_iterations: total.outer_iterations,
                            residual: total.residual,
                            converged: true,
                            with_fields: true,
                        },
                        &bodies,
                        &contacts,
                    )?;
                    if dir.is_some() {
                        figures = SummaryFigures::of(&bodies, &contacts);
                    }
                    summary.outer_iterations += total.outer_iterations;
                    summary.linear_iterations += total.linear_iterations;
                    // increment k is in the results (at t0): the summary
                    // counts it, as /time/<k> and history.csv do
                    summary.increments = k;
                    summary.time_reached = t0;
                    msg.push_str(&format!(
                        "; its last converged sub-step, t = {}, is written as increment {k}",
                        Num(t0)
                    ));
                }
                match e {
                    SolveError::Interrupted => interrupted = opts.interrupt.requested(),
                    _ => failure = Some(msg),
                }
            }
        }
    }
    progress.finish();
    let solve_seconds = solve_start.elapsed().as_secs_f64();
    summary.wall_seconds = resumed.wall_seconds + start.elapsed().as_secs_f64();
    if let Some(f) = &failure {
        summary.converged = false;
        summary.failure = Some(f.clone());
        log.warn(&format!("run failed: {f}"));
    }
    if let Some(sig) = interrupted {
        // the run did not reach its end: not `converged`, whatever the
        // increments it solved
        summary.converged = false;
        summary.interrupted = Some(signal_name(sig));
    }
    if cell_iterations > 0.0 {
        log.info(&format!(
            "cost: {:.3} µs per cell per outer iteration; {:.1} outer iterations per increment; {} in all",
            solve_seconds * 1e6 / cell_iterations,
            summary.outer_iterations as f64 / summary.increments.max(1) as f64,
            count(summary.linear_iterations, "linear iteration", "linear iterations")
        ));
        if method == NonlinearMethod::NewtonKrylov && evaluations > 0 {
            log.info(&format!(
                "Newton–Krylov: {:.3} µs per cell per residual evaluation; {:.1} residual evaluations and {:.1} Krylov iterations per Newton iteration",
                solve_seconds * 1e6 / (evaluations * solver.n_unknowns()) as f64,
                evaluations as f64 / summary.outer_iterations.max(1) as f64,
                summary.linear_iterations as f64 / summary.outer_iterations.max(1) as f64
            ));
        }
        let mut times = solver.times();
        times.merge(&contacts.times);
        log.info(&times.report(solve_seconds));
        summary.profile = Some(times);
    }
    if let Some(w) = fields.take() {
        w.close().map_err(out_err)?;
    }
    if let Some(d) = &dir {
        if failure.is_none() && interrupted.is_none() {
            // the end state (what a normal run always reported)
            figures = SummaryFigures::of(&bodies, &contacts);
        }
        write_summary(d, &summary, &figures).map_err(io_err)?;
        let physics = figures.report();
        if !physics.is_empty() {
            log.result(&physics);
        }
        match interrupted {
            Some(sig) => log.warn(&format!(
                "interrupted by {} after increment {}/{} (t = {}): results so far in {}",
                signal_name(sig),
                summary.increments,
                steps,
                Num(summary.time_reached),
                d.display()
            )),
            None => log.result(&format!("results in {}", d.display())),
        }
    } else if let Some(sig) = interrupted {
        log.warn(&format!(
            "interrupted by {} after increment {}/{}",
            signal_name(sig),
            summary.increments,
            steps
        ));
    }
    Ok(RunOutcome {
        converged: failure.is_none() && interrupted.is_none(),
        failure,
        interrupted,
        bodies,
        contacts,
        summary,
        directory: dir,
    })
}

/// What [`record_increment`] writes for increment `k`.
struct IncrementRecord {
    k: usize,
    t: f64,
    outer_iterations: usize,
    residual: f64,
    converged: bool,
    /// The fields too (`[output] every`), not only the history row.
    with_fields: bool,
}

/// Appends increment `r.k`'s row to `history.csv` and to the HDF5
/// history, and its fields when asked.
fn record_increment(
    history: &mut Option<History>,
    fields: &mut Option<FieldOutput>,
    columns: &[&str],
    r: &IncrementRecord,
    bodies: &[Body],
    contacts: &ContactSet,
) -> Result<(), RunError> {
    let out_err = |e: crate::output::OutputError| RunError::Output(e.to_string());
    let row = history_row(r.t, r.outer_iterations, r.residual, bodies, contacts);
    if let Some(h) = history {
        h.append(&row)
            .map_err(|e| RunError::Output(e.to_string()))?;
    }
    if let Some(w) = fields {
        w.write_history(columns, &row).map_err(out_err)?;
        if r.with_fields {
            w.write(
                r.k,
                r.t,
                r.outer_iterations,
                r.residual,
                r.converged,
                bodies,
                contacts,
            )
            .map_err(out_err)?;
        }
    }
    Ok(())
}

/// Time tables of the boundary conditions that end before `[time] end`
/// (their last value is held from there) or start after 0 (their first
/// value is held until then): allowed, but usually a slip in the case
/// (a ramp meant to reach the end), so the log says so.
fn short_tables(case: &Case) -> Vec<String> {
    use crate::case::{BoundarySpec, ScalarValue, VectorValue};
    let end = case.time.end;
    let range = |key: String, first: f64, last: f64, out: &mut Vec<String>| {
        if last < end * (1.0 - 1e-9) {
            out.push(format!(
                "{key}: the table ends at t = {}, before [time] end = {}; its last value is held from there",
                Num(last),
                Num(end)
            ));
        }
        if first > 1e-12 * end.abs() {
            out.push(format!(
                "{key}: the table starts at t = {}; its first value is held before",
                Num(first)
            ));
        }
    };
    let vector = |key: String, v: &VectorValue, out: &mut Vec<String>| {
        if let VectorValue::Table(rows) = v {
            if let (Some(a), Some(b)) = (rows.first(), rows.last()) {
                range(key, a.0, b.0, out);
            }
        }
    };
    let scalar = |key: String, v: &ScalarValue, out: &mut Vec<String>| {
        if let ScalarValue::Table(rows) = v {
            if let (Some(a), Some(b)) = (rows.first(), rows.last()) {
                range(key, a.0, b.0, out);
            }
        }
    };
    let mut out = Vec::new();
    for (i, b) in case.bodies.iter().enumerate() {
        for (patch, spec) in &b.boundary {
            let key = format!("body[{i}].boundary.{patch}");
            match spec {
                BoundarySpec::Displacement { value }
                | BoundarySpec::TangentialDisplacement { value }
                | BoundarySpec::Traction { value }
                | BoundarySpec::Force { value } => vector(format!("{key}.value"), value, &mut out),
                BoundarySpec::NormalDisplacement { value } | BoundarySpec::Pressure { value } => {
                    scalar(format!("{key}.value"), value, &mut out)
                }
                BoundarySpec::RigidMotion {
                    translation,
                    rotation,
                } => {
                    if let Some(t) = translation {
                        vector(format!("{key}.translation"), t, &mut out);
                    }
                    if let Some(r) = rotation {
                        scalar(format!("{key}.rotation.angle"), &r.angle, &mut out);
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// What a body that nothing holds in some direction (`e` is
/// [`SolveError::Unconstrained`], else `None`) makes of the case: when
/// `may_switch` and explicit contacts hold it, those contacts coupled
/// implicitly (the note for the log and the changed case); otherwise the
/// input error naming the body and the axis.
fn unheld_body(
    case: &Case,
    e: &SolveError,
    may_switch: bool,
) -> Option<Result<(String, Case), InputError>> {
    let SolveError::Unconstrained { body, axis, .. } = e else {
        return None;
    };
    let held_by = explicit_contacts_of(case, body);
    let mut switched = case.clone();
    for &i in &held_by {
        switched.contacts[i].coupling = Coupling::Implicit;
    }
    if may_switch && !held_by.is_empty() && pairs_compatible(&switched) {
        let note = format!(
            "body '{body}' is held in the {axis} direction by contact alone: [[contact]] {} coupled implicitly (explicit coupling applies the contact traction as a load and cannot hold a body)",
            contact_names(case, &held_by)
        );
        return Some(Ok((note, switched)));
    }
    let hint = if held_by.is_empty() {
        String::new()
    } else {
        format!(
            "; held by contact only, it needs coupling = \"implicit\" on [[contact]] {} (explicit coupling applies the contact traction as a load and cannot hold a body)",
            contact_names(case, &held_by)
        )
    };
    Some(Err(InputError::new(
        &case.source.path,
        e.to_string() + &hint,
    )))
}

/// What `run` checks before it solves beyond [`set_up_with_contacts`], for
/// `fvc check` on the bodies and contacts that built: every body is held
/// in every direction (by its conditions or by implicit contact).
/// `Ok(Some(note))`: the run will couple the contacts that alone hold a
/// body implicitly.
pub fn check_support(
    case: &Case,
    mut bodies: Vec<Body>,
    contacts: ContactSet,
) -> Result<Option<String>, InputError> {
    contacts.prepare_conditions(&mut bodies);
    let mut solver = SegregatedSolver::new(&bodies, &case.solver);
    let Err(e) = solver.assemble_and_factorise(&bodies, &case.solver.linear) else {
        let floating = solver.held_by_contact_alone();
        return match frictionless_slide(case, &bodies, &contacts, floating) {
            Some(e) => Err(e),
            None => Ok(None),
        };
    };
    match unheld_body(case, &e, true) {
        Some(Ok((note, switched))) => {
            // the switched couplings build other contact conditions
            let (bodies, contacts) = set_up_with_contacts(&switched)?;
            let more = check_support(&switched, bodies, contacts)?;
            Ok(Some(match more {
                Some(more) => format!("{note}; {more}"),
                None => note,
            }))
        }
        Some(Err(input)) => Err(input),
        None => Ok(None),
    }
}

/// The deformable bodies that only contact holds in some direction
/// (`floating`, from [`SegregatedSolver::check_held`]) and that a traction
/// or pressure loads: Newton–Krylov does not bring such a body into
/// contact from an open start (docs/newton-krylov.md, "Known limits"), so
/// a failure names them with what runs instead.
fn loaded_floating_bodies(bodies: &[Body], floating: &[(usize, usize)]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for &(bi, _) in floating {
        let b = &bodies[bi];
        let loaded = b.patch_specs.iter().flatten().any(|s| {
            matches!(
                s,
                crate::case::BoundarySpec::Traction { .. }
                    | crate::case::BoundarySpec::Pressure { .. }
            )
        });
        if loaded && !names.contains(&b.name) {
            names.push(b.name.clone());
        }
    }
    names
}

/// The explicitly coupled contacts a body is in.
fn explicit_contacts_of(case: &Case, body: &str) -> Vec<usize> {
    (0..case.contacts.len())
        .filter(|&i| {
            let c = &case.contacts[i];
            c.coupling == Coupling::Explicit && (c.master.0 == body || c.slave.0 == body)
        })
        .collect()
}

/// The explicitly coupled contacts of a run, if they may all be coupled
/// implicitly instead (the case's shared-patch rule still holds then).
fn switchable_explicit_contacts(case: &Case, contacts: &ContactSet) -> Vec<usize> {
    let explicit = contacts.explicit_contacts();
    if explicit.is_empty() {
        return explicit;
    }
    let mut switched = case.clone();
    for &i in &explicit {
        switched.contacts[i].coupling = Coupling::Implicit;
    }
    if pairs_compatible(&switched) {
        explicit
    } else {
        Vec::new()
    }
}

/// Whether every patch shared by several pairs of `case` may be (the case
/// reader's rule, [`crate::case::shared_patch_conflict`]).
fn pairs_compatible(case: &Case) -> bool {
    let is_rigid =
        |side: &(String, String)| case.bodies.iter().any(|b| b.name == side.0 && b.rigid);
    case.contacts.iter().enumerate().all(|(i, spec)| {
        [&spec.master, &spec.slave].into_iter().all(|side| {
            case.contacts[..i]
                .iter()
                .all(|o| crate::case::shared_patch_conflict(spec, side, o, is_rigid).is_none())
        })
    })
}

/// `master – slave` of the contacts `which`, for messages.
fn contact_names(case: &Case, which: &[usize]) -> String {
    which
        .iter()
        .map(|&i| {
            let c = &case.contacts[i];
            format!(
                "{}/{} – {}/{}",
                c.master.0, c.master.1, c.slave.0, c.slave.1
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The last increment of a run continued from increment `k` at time `t`,
/// and the shift from its increments to the case's time grid: increment
/// `k + i` is solved to the grid's time `time_at(k + i + shift)`, the
/// grid's times after `t` one by one. A run that starts afresh (or
/// continues a run of the same grid) has no shift.
fn continued_grid(case: &Case, k: usize, t: f64) -> (usize, isize) {
    let steps = case.time.steps;
    if k == 0 {
        return (steps, 0);
    }
    let after = t + 1e-9 * case.time.end.abs();
    let first = (1..=steps)
        .find(|&j| case.time.time_at(j) > after)
        .unwrap_or(steps + 1);
    let shift = first as isize - (k as isize + 1);
    (steps.saturating_add_signed(-shift), shift)
}

/// Back to the last accepted state of every body and contact (the
/// increment's start, or its last converged sub-step).
fn restore_start(bodies: &mut [Body], contacts: &mut ContactSet) {
    for b in bodies.iter_mut() {
        b.restore_start();
    }
    contacts.restore_start();
}

/// A new run into a results folder takes away the PNG files an earlier
/// `fvc plot` left in its `plots/` (they showed the earlier run beside
/// the new results); other files stay.
fn remove_stale_plots(dir: &Path) {
    let plots = dir.join("plots");
    let Ok(entries) = std::fs::read_dir(&plots) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.extension().is_some_and(|x| x == "png") {
            let _ = std::fs::remove_file(&p);
        }
    }
    // only if empty now
    let _ = std::fs::remove_dir(&plots);
}
