//! `fvc run CASE --restart RESULTS/<title>/<title>.h5 [--from-increment K]`
//! (issue 45): a run continued from the state at the end of an increment
//! that an earlier run of the same case wrote, into the same results.
//!
//! Every increment whose fields are written also gets the state the next
//! increment starts from (`/restart/<k>`): the bodies' meshes, fields and
//! material state ([`crate::model::Body::save_state`]), the contact pairs'
//! state ([`ContactSet::save_state`]), what the nonlinear method carries
//! ([`NonlinearSolver::save_state`]) and the time loop's own
//! ([`Resumed`]). The time loop keeps no step size from one increment to
//! the next (a cut-back halves the step within its increment only), so
//! the time reached is all it needs of the time.
mod signature;

pub use signature::{case_signature, check_compatible};

use std::path::{Path, PathBuf};

use crate::case::{Case, InputError};
use crate::contact_coupling::ContactSet;
use crate::model::Body;
use crate::nonlinear_solver::NonlinearSolver;
use crate::output::{read_restart_index, read_restart_state};
use fv_mesh::StateArrays;

/// Where `--restart` continues from.
#[derive(Debug, Clone)]
pub struct RestartFrom {
    /// The results file (`<title>.h5`).
    pub file: PathBuf,
    /// `--from-increment`: the increment; `None` = the last one with a
    /// restart state.
    pub increment: Option<usize>,
}

/// The time loop's figures at the end of the increment continued from.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Resumed {
    /// The increment.
    pub k: usize,
    /// Its time (of its last converged sub-step if a later one failed).
    pub time: f64,
    /// Totals of the run so far (`summary.json`).
    pub outer_iterations: usize,
    /// Linear iterations so far.
    pub linear_iterations: usize,
    /// Residual evaluations so far.
    pub residual_evaluations: usize,
    /// Wall-clock seconds of the runs so far.
    pub wall_seconds: f64,
    /// Every increment so far converged (or was accepted with `continue`).
    pub converged: bool,
    /// Explicit contacts were switched to implicit coupling (the switch
    /// is made once a run).
    pub switched_coupling: bool,
    /// Time step of the last step taken (the temporal term's).
    pub dt_prev: f64,
}

const RUN: &str = "run/figures";

impl Resumed {
    fn save(&self, out: &mut StateArrays) {
        out.put_scalars(
            RUN.into(),
            &[
                self.k as f64,
                self.time,
                self.outer_iterations as f64,
                self.linear_iterations as f64,
                self.residual_evaluations as f64,
                self.wall_seconds,
                f64::from(u8::from(self.converged)),
                f64::from(u8::from(self.switched_coupling)),
                self.dt_prev,
            ],
        );
    }

    fn load(s: &StateArrays) -> Result<Self, String> {
        let mut r = [0.0; 9];
        s.scalars_into(RUN, &mut r)?;
        Ok(Resumed {
            k: r[0] as usize,
            time: r[1],
            outer_iterations: r[2] as usize,
            linear_iterations: r[3] as usize,
            residual_evaluations: r[4] as usize,
            wall_seconds: r[5],
            converged: r[6] != 0.0,
            switched_coupling: r[7] != 0.0,
            dt_prev: r[8],
        })
    }
}

/// The state to write with increment `run.k`: everything the next
/// increment starts from.
pub fn capture(
    run: &Resumed,
    bodies: &[Body],
    contacts: &ContactSet,
    solver: &dyn NonlinearSolver,
) -> StateArrays {
    let mut out = StateArrays::new();
    run.save(&mut out);
    for b in bodies {
        b.save_state(&mut out);
    }
    contacts.save_state(&mut out);
    solver.save_state(&mut out);
    out
}

/// Reads the state `from` names for the case of `bodies` and `contacts`:
/// a missing file, a file without restart data, an increment without a
/// state, or a case that does not fit the file is an input error naming
/// the file (exit 2).
pub fn load(
    from: &RestartFrom,
    bodies: &[Body],
    contacts: &ContactSet,
) -> Result<StateArrays, InputError> {
    let file = &from.file;
    let fail = |msg: String| InputError::new(file, msg);
    if !file.is_file() {
        return Err(fail(
            "--restart: no such results file (give RESULTS/<title>/<title>.h5 of an earlier run)"
                .into(),
        ));
    }
    let index = read_restart_index(file)
        .map_err(|e| fail(format!("--restart: cannot read the results file: {e}")))?;
    if index.increments.is_empty() {
        return Err(fail(
            "--restart: the file holds no restart state (written by a run before restarts existed, or stopped before its first increment was written)".into(),
        ));
    }
    check_compatible(file, &index.case, &case_signature(bodies, contacts))?;
    let k = match from.increment {
        None => index.increments[index.increments.len() - 1].0,
        Some(k) if index.increments.iter().any(|&(i, _)| i == k) => k,
        Some(k) => {
            let list: Vec<String> = index
                .increments
                .iter()
                .map(|(i, _)| i.to_string())
                .collect();
            let why = if index.written.contains(&k) {
                "its fields are written but not its state"
            } else {
                "the file does not hold it"
            };
            return Err(fail(format!(
                "--from-increment {k}: {why}; the increments it can continue from are {}",
                abbreviate(&list)
            )));
        }
    };
    read_restart_state(file, k)
        .map_err(|e| fail(format!("--restart: cannot read increment {k}: {e}")))
}

/// The results folder of a continued run: the folder of the file, which
/// must be this case's `<title>.h5`; `--output`, if also given, must name
/// the same folder.
pub fn results_folder(
    case: &Case,
    from: &RestartFrom,
    output: Option<&Path>,
) -> Result<PathBuf, InputError> {
    let file = &from.file;
    let expected = format!("{}.h5", case.title);
    if file.file_name().and_then(|n| n.to_str()) != Some(expected.as_str()) {
        return Err(InputError::new(
            file,
            format!(
                "--restart: this case (title '{}') writes its results to {expected}; give that file of an earlier run",
                case.title
            ),
        ));
    }
    let dir = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if let Some(o) = output {
        let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
            (Ok(a), Ok(b)) => a == b,
            _ => a == b,
        };
        if !same(&o.join(&case.title), &dir) {
            return Err(InputError::new(
                file,
                format!(
                    "--restart continues the results in {}, but --output names {}; leave --output out",
                    dir.display(),
                    o.join(&case.title).display()
                ),
            ));
        }
    }
    Ok(dir)
}

/// `1, 2, 3, …, 40` for long lists.
fn abbreviate(list: &[String]) -> String {
    if list.len() <= 12 {
        return list.join(", ");
    }
    format!(
        "{}, …, {}",
        list[..6].join(", "),
        list[list.len() - 3..].join(", ")
    )
}

/// Sets the bodies, the contact pairs and the method to the state `s`
/// (read by [`load`] for the same case); returns the time loop's figures.
/// The order matters: the meshes first (the contact surfaces follow them),
/// then the couplings switched to implicit (the contact patches' conditions
/// change kind), then the fields, then the contact state.
pub fn apply(
    s: &StateArrays,
    file: &Path,
    bodies: &mut [Body],
    contacts: &mut ContactSet,
    solver: &mut dyn NonlinearSolver,
) -> Result<Resumed, InputError> {
    let fail = |e: String| InputError::new(file, format!("--restart: {e}"));
    let run = Resumed::load(s).map_err(fail)?;
    for b in bodies.iter_mut() {
        b.restore_mesh(s).map_err(fail)?;
    }
    contacts.restore_couplings(bodies, s).map_err(fail)?;
    for b in bodies.iter_mut() {
        b.restore_state(s).map_err(fail)?;
    }
    contacts.restore_state(bodies, s).map_err(fail)?;
    solver.restore_state(bodies, s).map_err(fail)?;
    Ok(run)
}
