//! `fvc plot RESULTS_DIR`: PNG plots of a finished or interrupted run,
//! written to `RESULTS_DIR/plots/`:
//!
//! - `forces.png`: the force columns of `history.csv` against time
//!   (reaction force components, contact forces, moments) — [`forces`];
//! - `iterations.png`: nonlinear iterations per increment, linear
//!   iterations per increment when `log.txt` records them, and the
//!   residual each increment ended at — [`iterations`];
//! - `contact_pressure_<body>-<patch>.png`, one per contact patch: the
//!   contact pressure along the patch at the last increment written to the
//!   `.h5` — [`pressure`];
//! - `field_von_mises.png` for a two-dimensional (one-cell-thick) model:
//!   the deformed mesh at the last increment, cells filled by the von
//!   Mises stress, contact patches drawn — [`field`].
//!
//! Only what the run wrote is read (`history.csv`, the `.h5`, and
//! `summary.json` / `log.txt` when present), so a run that was stopped
//! part-way plots up to where it got. Text is drawn with DejaVu Sans
//! embedded in the binary: no system fonts or font libraries are needed.
//!
//! ```no_run
//! let written = solver_app::plot::plot_results(
//!     std::path::Path::new("results/hertz-cylinder-coarse"),
//!     &mut |p| println!("{}", p.display()),
//! )?;
//! # Ok::<(), solver_app::plot::PlotError>(())
//! ```
mod chart;
pub mod data;
pub mod field;
pub mod forces;
pub mod iterations;
pub mod patch_geometry;
pub mod pressure;

use std::path::{Path, PathBuf};

pub use data::{History, ResultsFolder};

/// Errors of `fvc plot`.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The folder is not a results folder of `fvc run` (exit code 2).
    #[error("{}: not a results folder of `fvc run`: {reason}", dir.display())]
    NotResults {
        /// The folder given.
        dir: PathBuf,
        /// What is missing, and a hint where the results may be.
        reason: String,
    },
    /// A results file could not be read or is malformed (exit code 1).
    #[error("{}: {message}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// A plot could not be drawn or written (exit code 1).
    #[error("{}: {message}", path.display())]
    Draw {
        /// The PNG file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}

impl PlotError {
    /// Exit code of `fvc plot` for this error: 2 for a folder that is not a
    /// results folder (bad input), 1 otherwise.
    pub fn exit_code(&self) -> u8 {
        match self {
            PlotError::NotResults { .. } => 2,
            _ => 1,
        }
    }

    pub(crate) fn read(path: &Path, message: impl std::fmt::Display) -> Self {
        PlotError::Read {
            path: path.to_path_buf(),
            message: message.to_string(),
        }
    }
}

/// What [`plot_results`] did.
#[derive(Debug, Default)]
pub struct PlotReport {
    /// The PNG files written, in order.
    pub written: Vec<PathBuf>,
    /// Plots left out and why (e.g. no increment in the `.h5` yet).
    pub notes: Vec<String>,
}

/// Writes every plot of the results folder `dir` into `dir/plots/`
/// (created if needed), calling `on_written` with each file's path as soon
/// as it is written.
///
/// Fails with [`PlotError::NotResults`] when `dir` lacks `history.csv` or
/// an `.h5` file, and with the other variants when a file cannot be read
/// or a plot cannot be written.
pub fn plot_results(
    dir: &Path,
    on_written: &mut dyn FnMut(&Path),
) -> Result<PlotReport, PlotError> {
    let folder = ResultsFolder::open(dir)?;
    let history = History::read(&folder.history_csv)?;
    let out = dir.join("plots");
    std::fs::create_dir_all(&out).map_err(|e| PlotError::Draw {
        path: out.clone(),
        message: format!("cannot create the folder: {e}"),
    })?;
    let mut report = PlotReport::default();
    if let Some(note) = &history.dropped_line {
        report.notes.push(note.clone());
    }
    let mut wrote = |p: PathBuf, report: &mut PlotReport| {
        on_written(&p);
        report.written.push(p);
    };
    if history.rows.is_empty() {
        report.notes.push(format!(
            "{}: no increment recorded yet; forces.png and iterations.png left out",
            folder.history_csv.display()
        ));
    } else {
        let path = out.join("forces.png");
        forces::plot(&folder, &history, &path)?;
        wrote(path, &mut report);
        let path = out.join("iterations.png");
        iterations::plot(&folder, &history, &path)?;
        wrote(path, &mut report);
    }
    let file = folder.open_h5()?;
    if data::last_increment(&file).is_none() {
        report.notes.push(format!(
            "{}: no increment written yet; contact pressure and field plots left out",
            folder.h5.display()
        ));
        return Ok(report);
    }
    for patch in pressure::contact_patches(&folder, &history) {
        let name = format!(
            "contact_pressure_{}.png",
            data::file_stem(&format!("{}-{}", patch.body, patch.patch))
        );
        let path = out.join(name);
        match pressure::plot(&folder, &history, &file, &patch, &path)? {
            None => wrote(path, &mut report),
            Some(note) => report.notes.push(note),
        }
    }
    match field::read_last_plane_model(&file).map_err(|e| PlotError::read(&folder.h5, e))? {
        Some(model) => {
            let path = out.join(field::VON_MISES_PNG);
            field::plot(&folder, &model, &path)?;
            wrote(path, &mut report);
        }
        None => report.notes.push(format!(
            "{} is drawn for two-dimensional (one-cell-thick) models only; left out",
            field::VON_MISES_PNG
        )),
    }
    Ok(report)
}
