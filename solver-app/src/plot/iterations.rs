//! `iterations.png`: per increment, the nonlinear iterations
//! (`history.csv`'s `outer_iterations`: outer iterations of the segregated
//! method or Newton iterations), the linear (Krylov) iterations when
//! `log.txt` records them, and the residual the increment ended at.
use std::path::Path;

use super::chart::{colour, draw_figure, Panel, Series};
use super::data::{linear_iterations_from_log, History, ResultsFolder};
use super::forces::run_state;
use super::PlotError;

/// Per increment (1, 2, … in row order): nonlinear iterations, linear
/// iterations (`None` where the log has no line for the increment, or
/// there is no log) and the final residual.
#[derive(Debug, Clone, PartialEq)]
pub struct IterationCounts {
    /// Increment numbers.
    pub increment: Vec<usize>,
    /// Nonlinear iterations of each increment.
    pub nonlinear: Vec<f64>,
    /// Linear iterations of each increment.
    pub linear: Vec<Option<f64>>,
    /// Residual at the end of each increment.
    pub residual: Vec<f64>,
}

impl IterationCounts {
    /// From the history and the text of `log.txt` (if any).
    pub fn new(history: &History, log: Option<&str>) -> Self {
        let n = history.rows.len();
        let column = |name: &str| history.column(name).unwrap_or_else(|| vec![f64::NAN; n]);
        let linear_by_k = log.map(linear_iterations_from_log).unwrap_or_default();
        let increment: Vec<usize> = (1..=n).collect();
        IterationCounts {
            linear: increment
                .iter()
                .map(|k| linear_by_k.get(k).map(|&l| l as f64))
                .collect(),
            increment,
            nonlinear: column("outer_iterations"),
            residual: column("residual"),
        }
    }
}

/// Writes `iterations.png`.
pub fn plot(folder: &ResultsFolder, history: &History, path: &Path) -> Result<(), PlotError> {
    let log = match &folder.log {
        Some(p) => Some(std::fs::read_to_string(p).map_err(|e| PlotError::read(p, e))?),
        None => None,
    };
    let counts = IterationCounts::new(history, log.as_deref());
    let n = counts.increment.len();
    let x_range = Some((0.5, n as f64 + 0.5));
    let xs = || counts.increment.iter().map(|&k| k as f64);
    let method = folder
        .summary
        .as_ref()
        .and_then(|s| s.get("nonlinear"))
        .and_then(|m| m.as_str())
        .map(|m| format!(" ({m})"))
        .unwrap_or_default();
    let total: f64 = counts.nonlinear.iter().filter(|v| v.is_finite()).sum();
    let mut panels = vec![Panel {
        title: format!("Nonlinear iterations per increment{method}: {total} in all"),
        x_label: "increment".into(),
        y_label: "iterations".into(),
        series: vec![Series::curve(
            "nonlinear (outer / Newton) iterations",
            xs().zip(counts.nonlinear.iter().copied()).collect(),
            colour(0),
        )],
        x_range,
        y_zero: true,
        x_integer: true,
        y_integer: true,
        ..Default::default()
    }];
    if counts.linear.iter().any(Option::is_some) {
        let pts: Vec<(f64, f64)> = xs()
            .zip(&counts.linear)
            .filter_map(|(k, l)| l.map(|l| (k, l)))
            .collect();
        let total: f64 = pts.iter().map(|p| p.1).sum();
        panels.push(Panel {
            title: format!(
                "Linear (Krylov) iterations per increment, from log.txt: {total} in all"
            ),
            x_label: "increment".into(),
            y_label: "iterations".into(),
            series: vec![Series::curve("linear iterations", pts, colour(1))],
            x_range,
            y_zero: true,
            x_integer: true,
            y_integer: true,
            ..Default::default()
        });
    }
    panels.push(Panel {
        title: "Residual at the end of each increment".into(),
        x_label: "increment".into(),
        y_label: "residual (relative)".into(),
        series: vec![Series::curve(
            "final residual",
            xs().zip(counts.residual.iter().copied()).collect(),
            colour(3),
        )],
        x_range,
        y_log: true,
        x_integer: true,
        ..Default::default()
    });
    let caption = format!("{}: iterations{}", folder.title, run_state(folder, history));
    let height = 80 + 360 * panels.len() as u32;
    draw_figure(path, (1200, height), &caption, &panels)
}
