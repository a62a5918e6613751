//! The benchmarks of `../shared/benchmarks/README.md` as functions that run
//! a case and return what it measured; the tests assert on these figures
//! and the validation report plots them.
pub mod block_in_half_tube;
pub mod concentric_cylinders;
pub mod concentric_spheres;
pub mod coupling_efficiency;
pub mod curved_beams;
pub mod cut_across_x;
pub mod die_drawing;
pub mod flat_punch;
pub mod hertz_cylinder;
pub mod hertz_sphere;
pub mod nafems_punch;
pub mod parallel_cylinders;
pub mod rigid_cylinder;
pub mod shallow_ironing;
pub mod sphere_block;
pub mod strand_compacting;
pub mod twisting_blocks;
pub mod twisting_hemisphere;
pub mod wire_drawing;
pub mod wire_rolling;

use std::path::{Path, PathBuf};

/// Folder of the project's benchmark cases (`validation/cases`).
pub fn cases_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("cases")
}

/// The text of case `file` in `validation/cases/<case>` and that folder
/// (relative mesh paths resolve against it).
pub fn read_case(case: &str, file: &str) -> (PathBuf, String) {
    let dir = cases_dir().join(case);
    let text =
        std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("{case}/{file}: {e}"));
    (dir, text)
}

/// Case `file` of `validation/cases/<case>` with its mesh file `from`
/// replaced by `to` (a refined or moved variant beside it); panics when
/// the case no longer names `from`, so that the variant cannot silently
/// run the original mesh.
pub fn read_case_on_mesh(case: &str, file: &str, from: &str, to: &str) -> (PathBuf, String) {
    let (dir, text) = read_case(case, file);
    let text = replace_mesh(&text, &format!("{case}/{file}"), from, to);
    (dir, text)
}

/// Case text `text` (named `name` in messages) with its mesh file `from`
/// replaced by `to`; panics when the text does not name `from`.
pub fn replace_mesh(text: &str, name: &str, from: &str, to: &str) -> String {
    let quoted = format!("\"{from}\"");
    assert!(text.contains(&quoted), "{name} no longer names {from}");
    text.replace(&quoted, &format!("\"{to}\""))
}

/// The case text pinned to the segregated method (`[solver] nonlinear =
/// "segregated"`), for comparisons of its contact couplings and
/// accelerations, which the Newton–Krylov method does not have; panics
/// when the text has no `[solver]` table.
pub fn pinned_segregated(text: &str) -> String {
    assert!(
        text.contains("[solver]\n"),
        "the case has no [solver] table"
    );
    text.replacen("[solver]\n", "[solver]\nnonlinear = \"segregated\"\n", 1)
}

/// The keys a case author tunes per case (issue 46): contact coupling,
/// penalty scale, relaxation, Rhie–Chow factor and its stiffness in
/// plastic flow, predictor and outer iteration cap. A case without them
/// runs on the defaults a new user gets.
pub const TUNING_KEYS: [&str; 7] = [
    "coupling",
    "penalty_scale",
    "relaxation",
    "rhie_chow",
    "rhie_chow_plastic",
    "predictor",
    "max_outer",
];

/// The case text without its tuning keys ([`TUNING_KEYS`]): every line
/// that assigns one of them, in whatever table, is dropped (the shipped
/// cases give each on a line of its own).
pub fn strip_tuning_keys(text: &str) -> String {
    let assigns = |line: &str, key: &str| {
        line.trim_start()
            .strip_prefix(key)
            .is_some_and(|rest| rest.trim_start().starts_with('='))
    };
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        if !TUNING_KEYS.iter().any(|k| assigns(line, k)) {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// The case text with the `[[contact]]` surfaces `master` and `slave`
/// (`"<body>/<patch>"`) exchanged.
pub fn swap_master_slave(text: &str, master: &str, slave: &str) -> String {
    text.replace(&format!("master = \"{master}\""), "master = \"@\"")
        .replace(
            &format!("slave = \"{slave}\""),
            &format!("slave = \"{master}\""),
        )
        .replace("master = \"@\"", &format!("master = \"{slave}\""))
}

/// Coupling settings of a case's first `[[contact]]`, to override the
/// case file's (thesis §4.1.3 explicit, §4.5 implicit coupling).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CouplingSettings {
    /// Implicit coupling (the relaxation is then not used).
    pub implicit: bool,
    /// f_n^scale of eq. 4.4a.
    pub penalty_scale: f64,
    /// Under-relaxation of the normal and tangential traction (eq. 4.13),
    /// in (0, 1]; explicit coupling only.
    pub relaxation: f64,
    /// Outer iterations per increment at most (`[solver] max_outer`).
    pub max_outer: usize,
    /// Where a contact face is when the gap is measured (`face_position`).
    pub face_position: solver_app::case::FacePosition,
    /// Outer tolerance (`[solver] tolerance`); `None`: the case's.
    pub tolerance: Option<f64>,
}

impl CouplingSettings {
    /// Implicit coupling with penalty scale `penalty_scale`.
    pub fn implicit(penalty_scale: f64, max_outer: usize) -> Self {
        CouplingSettings {
            implicit: true,
            penalty_scale,
            relaxation: 1.0,
            max_outer,
            face_position: solver_app::case::FacePosition::Interpolated,
            tolerance: None,
        }
    }

    /// Explicit coupling with penalty scale `penalty_scale` and traction
    /// relaxation `relaxation`.
    pub fn explicit(penalty_scale: f64, relaxation: f64, max_outer: usize) -> Self {
        CouplingSettings {
            implicit: false,
            penalty_scale,
            relaxation,
            max_outer,
            face_position: solver_app::case::FacePosition::Interpolated,
            tolerance: None,
        }
    }

    /// The same with the outer tolerance `tolerance`.
    pub fn with_tolerance(self, tolerance: f64) -> Self {
        CouplingSettings {
            tolerance: Some(tolerance),
            ..self
        }
    }

    /// The same with the gaps measured between the faces at their boundary
    /// displacements (`face_position = "boundary-value"`).
    pub fn at_boundary_values(self) -> Self {
        CouplingSettings {
            face_position: solver_app::case::FacePosition::BoundaryValue,
            ..self
        }
    }

    /// Sets these on `case.contacts[0]` and `case.solver.max_outer`.
    ///
    /// # Panics
    /// When the case has no contact (a benchmark helper).
    pub fn apply(&self, case: &mut solver_app::case::Case) {
        use solver_app::case::Coupling;
        let Some(c) = case.contacts.first_mut() else {
            panic!("case '{}' has no [[contact]]", case.title)
        };
        c.coupling = if self.implicit {
            Coupling::Implicit
        } else {
            Coupling::Explicit
        };
        c.penalty_scale = Some(self.penalty_scale);
        c.relaxation_normal = self.relaxation;
        c.relaxation_tangential = self.relaxation;
        c.face_position = self.face_position;
        case.solver.max_outer = self.max_outer;
        if let Some(t) = self.tolerance {
            case.solver.tolerance = t;
        }
    }
}

/// Cost figures of one run.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunCost {
    /// Outer iterations summed over the increments.
    pub outer_iterations: usize,
    /// Increments.
    pub increments: usize,
    /// Wall time of the run, s.
    pub wall_seconds: f64,
    /// Cells of the deformable bodies.
    pub cells: usize,
}

impl RunCost {
    /// From a run's summary.
    pub fn of(out: &solver_app::run::RunOutcome) -> Self {
        RunCost {
            outer_iterations: out.summary.outer_iterations,
            increments: out.summary.increments,
            wall_seconds: out.summary.wall_seconds,
            cells: out.summary.cells,
        }
    }

    /// Microseconds per cell per outer iteration.
    pub fn us_per_cell_iteration(&self) -> f64 {
        1e6 * self.wall_seconds / (self.cells.max(1) * self.outer_iterations.max(1)) as f64
    }
}

/// Mean of `values` over the increments from `from` (s) and the largest
/// deviation from it as a fraction of it; `None` when none is that late.
pub fn steady_mean(time: &[f64], values: &[f64], from: f64) -> Option<(f64, f64)> {
    let v: Vec<f64> = time
        .iter()
        .zip(values)
        .filter(|(t, _)| **t >= from - 1e-12)
        .map(|(_, v)| *v)
        .collect();
    if v.is_empty() {
        return None;
    }
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let dev = v.iter().map(|x| (x - mean).abs()).fold(0.0, f64::max);
    Some((mean, dev / mean.abs()))
}

/// Linear interpolation of `(xs, ys)` (xs increasing) at `x`; NaN outside
/// (a curve is not extended beyond its ends).
pub fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let i = xs.partition_point(|&v| v < x);
    if i < xs.len() && (xs[i] - x).abs() <= 1e-9 * x.abs().max(1.0) {
        return ys[i];
    }
    if i == 0 || i >= xs.len() {
        return f64::NAN;
    }
    let (x0, x1, y0, y1) = (xs[i - 1], xs[i], ys[i - 1], ys[i]);
    y0 + (y1 - y0) * (x - x0) / (x1 - x0)
}

/// Extracts a benchmark's polyMesh archive (`tar -xJf`, holding
/// `polyMesh/`) into a fresh temporary folder named after `tag` and
/// returns that folder. Meshes in `../shared` are read from there, never
/// copied into the project.
pub fn extract_polymesh(archive: &Path, tag: &str) -> Result<PathBuf, String> {
    static RUNS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    if !archive.is_file() {
        return Err(format!("{} is missing", archive.display()));
    }
    let dir = std::env::temp_dir().join(format!(
        "fvc-{tag}-{}-{}",
        std::process::id(),
        RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let status = std::process::Command::new("tar")
        .arg("-xJf")
        .arg(archive)
        .arg("-C")
        .arg(&dir)
        .status()
        .map_err(|e| format!("tar -xJf {}: {e}", archive.display()))?;
    if !status.success() || !dir.join("polyMesh/points").is_file() {
        return Err(format!(
            "tar -xJf {} into {} failed ({status})",
            archive.display(),
            dir.display()
        ));
    }
    Ok(dir)
}
