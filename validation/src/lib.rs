//! Verification and validation: analytical solutions (thesis appendix A and
//! classical elasticity), error norms, and helpers to run cases in tests.
#![warn(missing_docs)]

pub mod analytical;
pub mod benchmarks;
pub mod report;

use std::path::Path;

use solver_app::case::{parse_case_with, Case};

/// The nonlinear method every case of the validation runs with, when the
/// environment variable `FVC_NONLINEAR` names one (`newton-krylov`,
/// `segregated`): the suite is run under either method this way.
pub fn nonlinear_override() -> Option<fv_nonlinear::NonlinearMethod> {
    let name = std::env::var("FVC_NONLINEAR").ok()?;
    match fv_nonlinear::NonlinearMethod::from_name(&name) {
        Ok(m) => Some(m),
        Err(e) => panic!("FVC_NONLINEAR: {e}"),
    }
}

/// [`parse_case_with`] under [`nonlinear_override`], unless the case
/// chooses its method itself (`[solver] nonlinear`: a test of one method's
/// behaviour).
pub fn parse_case(text: &str, path: &Path) -> Result<Case, solver_app::case::InputError> {
    let Some(m) = nonlinear_override() else {
        return parse_case_with(text, path, None);
    };
    match parse_case_with(text, path, None) {
        Ok(case) if case.source.line_of("solver.nonlinear").is_some() => Ok(case),
        _ => parse_case_with(text, path, Some(m)),
    }
}
use solver_app::run::{run_case, RunOptions, RunOutcome};

/// Parses a case given as TOML text (relative mesh paths resolve against
/// `dir`) and runs it without writing files.
pub fn run_toml(text: &str, dir: &Path) -> RunOutcome {
    run_toml_edited(text, dir, false, |_| {})
}

/// Like [`run_toml`], with the parsed case changed by `edit` first (e.g.
/// [`benchmarks::CouplingSettings::apply`]); `no_cutbacks`: a failed
/// increment is not halved and redone, so the outer iterations are those
/// of the increments as given.
pub fn run_toml_edited(
    text: &str,
    dir: &Path,
    no_cutbacks: bool,
    edit: impl FnOnce(&mut Case),
) -> RunOutcome {
    let mut case = match parse_case(text, &dir.join("case.toml")) {
        Ok(c) => c,
        Err(e) => panic!("test case does not parse: {e}"),
    };
    edit(&mut case);
    match run_case(
        &case,
        &RunOptions {
            no_files: true,
            quiet: true,
            no_cutbacks,
            ..Default::default()
        },
    ) {
        Ok(o) => o,
        Err(e) => panic!("test case failed to start: {e}"),
    }
}

/// Moves every point not on the boundary of the box `[0, size]` by a
/// seeded pseudo-random offset of at most `amplitude·h` per direction.
pub fn distort_interior(
    mesh: &mut fv_mesh::PolyMesh,
    size: [f64; 3],
    h: f64,
    amplitude: f64,
    seed: u64,
) {
    let mut s = seed;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    for p in mesh.points.iter_mut() {
        let interior = (0..3).all(|d| p[d] > 1e-9 * size[d] && p[d] < size[d] * (1.0 - 1e-9));
        let offset = fv_mesh::Vector::new(rnd(), rnd(), rnd()) * amplitude * h;
        if interior {
            *p += offset;
        }
    }
}

/// Path of the shared benchmark data (`../shared` beside the project), if present.
pub fn shared_dir() -> Option<std::path::PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared");
    p.is_dir().then_some(p)
}

/// The rows of a run's `history.csv`, by column.
#[derive(Debug, Clone, Default)]
pub struct HistoryTable {
    /// Column names of the header.
    pub columns: Vec<String>,
    /// Values, row by row.
    pub rows: Vec<Vec<f64>>,
}

impl HistoryTable {
    /// Values of the column named `name`, one per increment.
    ///
    /// # Panics
    /// When there is no such column (a test helper).
    pub fn column(&self, name: &str) -> Vec<f64> {
        let Some(c) = self.columns.iter().position(|n| n == name) else {
            panic!("no column '{name}' in {:?}", self.columns)
        };
        self.rows.iter().map(|r| r[c]).collect()
    }

    /// The `outer_iterations` column as counts.
    pub fn outer_iterations(&self) -> Vec<usize> {
        self.column("outer_iterations")
            .iter()
            .map(|&n| n as usize)
            .collect()
    }
}

/// Like [`run_toml`] but writes the results into a fresh temporary folder
/// and returns the parsed `history.csv` as well (mesh paths must be absolute
/// or generators).
pub fn run_toml_with_history(text: &str) -> (RunOutcome, HistoryTable) {
    run_toml_in_with_history(text, None)
}

/// [`run_toml_with_history`] for a case whose relative mesh paths are
/// relative to `case_dir` (a shipped case read by
/// [`benchmarks::read_case`]), or to the temporary folder when `None`.
pub fn run_toml_in_with_history(text: &str, case_dir: Option<&Path>) -> (RunOutcome, HistoryTable) {
    let dir = std::env::temp_dir().join(format!(
        "fvc-history-{}-{}",
        std::process::id(),
        HISTORY_RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
    ));
    let case = match parse_case(text, &case_dir.unwrap_or(&dir).join("case.toml")) {
        Ok(c) => c,
        Err(e) => panic!("test case does not parse: {e}"),
    };
    let out = match run_case(
        &case,
        &RunOptions {
            output: Some(dir.clone()),
            quiet: true,
            ..Default::default()
        },
    ) {
        Ok(o) => o,
        Err(e) => panic!("test case failed to start: {e}"),
    };
    let path = dir.join(&case.title).join("history.csv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let columns = lines
        .next()
        .unwrap_or_default()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    (out, HistoryTable { columns, rows })
}

static HISTORY_RUNS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Mean over the faces of patch `patch` of `value(boundary face index,
/// face index)` (e.g. the boundary displacement `u_b[b]` or the face centre
/// `geom.face_centres[f]`). Panics if the body has no such patch (a test
/// set-up error).
pub fn patch_mean(
    body: &solver_app::model::Body,
    patch: &str,
    value: impl Fn(usize, usize) -> nalgebra::Vector3<f64>,
) -> nalgebra::Vector3<f64> {
    let pi = body
        .mesh
        .patch_index(patch)
        .unwrap_or_else(|| panic!("no patch '{patch}'"));
    let ni = body.mesh.n_internal_faces();
    let faces = body.mesh.patches[pi].faces();
    let n = faces.len() as f64;
    faces
        .map(|f| value(f - ni, f))
        .sum::<nalgebra::Vector3<f64>>()
        / n
}
