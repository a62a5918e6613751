//! curved-beams (thesis §5.3.3; `../shared/benchmarks/README.md`): two
//! elastoplastic half-annuli slid past each other under the updated
//! Lagrangian form, 63 increments of 0.5 mm (`validation/cases/curved-beams`).
//! The reaction on the upper beam's driven ends against the slide, and its
//! peaks against Neto et al. (2016).
use std::path::Path;

use super::{read_case, swap_master_slave, RunCost};
use crate::{run_toml_with_history, HistoryTable};

/// Neto et al. (2016), as quoted by the benchmark table: (μ, peak |Fx|,
/// peak |Fy|) in N.
pub const NETO_PEAKS: [(f64, f64, f64); 3] =
    [(0.0, 9.5, 35.7), (0.3, 17.3, 39.0), (0.6, 27.7, 45.6)];

/// Acceptance: each peak within 3 % of Neto et al.
pub const TOLERANCE: f64 = 0.03;

/// Slide of the shipped case, mm (63 increments of 0.5 mm).
pub const FULL_SLIDE: f64 = 31.5;

/// The reaction of one run, increment by increment.
#[derive(Debug, Clone)]
pub struct CurvedBeams {
    /// Slide at the end of each converged increment, mm.
    pub slide: Vec<f64>,
    /// Fx and Fy of the reaction on the upper beam's two driven ends, N.
    pub fx: Vec<f64>,
    /// See `fx`.
    pub fy: Vec<f64>,
    /// Normal contact force and contact area of the pair per increment.
    pub normal_force: Vec<f64>,
    /// See `normal_force`, mm².
    pub contact_area: Vec<f64>,
    /// Nonlinear iterations of each increment (failed attempts and
    /// sub-steps included).
    pub iterations: Vec<usize>,
    /// Cost of the run.
    pub cost: RunCost,
    /// Why the run stopped early.
    pub failure: Option<String>,
}

impl CurvedBeams {
    /// Most nonlinear iterations in one increment.
    pub fn max_iterations(&self) -> usize {
        self.iterations.iter().copied().max().unwrap_or(0)
    }

    /// Largest |Fx| and the slide where it occurs.
    pub fn fx_peak(&self) -> (f64, f64) {
        peak(&self.slide, &self.fx)
    }

    /// Largest |Fy| and the slide where it occurs.
    pub fn fy_peak(&self) -> (f64, f64) {
        peak(&self.slide, &self.fy)
    }

    /// Slide reached, mm.
    pub fn reached(&self) -> f64 {
        self.slide.last().copied().unwrap_or(0.0)
    }

    /// Whether every increment converged.
    pub fn converged(&self) -> bool {
        self.failure.is_none()
    }
}

/// Largest |y| and the x where it occurs.
fn peak(x: &[f64], y: &[f64]) -> (f64, f64) {
    y.iter().zip(x).fold(
        (0.0, 0.0),
        |m, (&f, &t)| if f.abs() > m.0 { (f.abs(), t) } else { m },
    )
}

/// Neto et al.'s peaks for `mu` (a μ of the benchmark table).
pub fn neto_peaks(mu: f64) -> Option<(f64, f64)> {
    NETO_PEAKS
        .iter()
        .find(|(m, _, _)| (m - mu).abs() < 1e-9)
        .map(|&(_, fx, fy)| (fx, fy))
}

/// The shipped case with friction `mu`, up to `until` mm of slide
/// (0.5 mm per increment, as shipped), the upper beam master if
/// `upper_master`.
pub fn case_text(mu: f64, until: f64, upper_master: bool) -> String {
    let (_, text) = read_case("curved-beams", "case.toml");
    let steps = (until / 0.5).round() as usize;
    let text = text
        .replace("friction = 0.3", &format!("friction = {mu:.1}"))
        .replace("end = 31.5", &format!("end = {until}"))
        .replace("steps = 63", &format!("steps = {steps}"));
    if upper_master {
        swap_master_slave(&text, "lower/outer", "upper/outer")
    } else {
        text
    }
}

/// Runs a curved-beams case text and collects the reaction.
pub fn run_text(text: &str) -> CurvedBeams {
    let (out, history) = run_toml_with_history(text);
    CurvedBeams {
        slide: history.column("time"),
        fx: driven_ends(&history, "Fx"),
        fy: driven_ends(&history, "Fy"),
        normal_force: contact_column(&history, "normal_force"),
        contact_area: contact_column(&history, "contact_area"),
        iterations: history.outer_iterations(),
        cost: RunCost::of(&out),
        failure: if out.converged {
            None
        } else {
            out.failure.or(Some("not converged".into()))
        },
    }
}

/// [`case_text`] then [`run_text`].
pub fn run(mu: f64, until: f64, upper_master: bool) -> CurvedBeams {
    run_text(&case_text(mu, until, upper_master))
}

/// The contact pair's `quantity` (its history column is named after the
/// slave surface, so it moves when master and slave are swapped).
fn contact_column(history: &HistoryTable, quantity: &str) -> Vec<f64> {
    let suffix = format!("/outer:{quantity}");
    match history.columns.iter().find(|c| c.ends_with(&suffix)) {
        Some(name) => history.column(name),
        None => panic!("no column '*{suffix}' in {:?}", history.columns),
    }
}

/// `component` of the reaction summed over the upper beam's two driven ends.
fn driven_ends(history: &HistoryTable, component: &str) -> Vec<f64> {
    let a = history.column(&format!("upper/start:{component}"));
    let b = history.column(&format!("upper/end:{component}"));
    a.iter().zip(&b).map(|(a, b)| a + b).collect()
}

/// Neto et al.'s curve of `component` ("x" or "y") for `mu` from
/// `../shared/benchmarks/curved-beams/reference/neto-mu=<μ>-<component>.txt`
/// (slide in mm, force in N; |F| returned).
pub fn reference_curve(shared: &Path, mu: f64, component: &str) -> Result<Vec<(f64, f64)>, String> {
    let path = shared
        .join("benchmarks/curved-beams/reference")
        .join(format!("neto-mu={mu:.1}-{component}.txt"));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut points = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut it = line.split(',').map(|s| s.trim().parse::<f64>());
        match (it.next(), it.next()) {
            (Some(Ok(x)), Some(Ok(y))) => points.push((x, y.abs())),
            _ => return Err(format!("{}:{}: expected 'x, y'", path.display(), i + 1)),
        }
    }
    Ok(points)
}
