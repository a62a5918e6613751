//! shallow-ironing (thesis §5.3.2, figs. 5.17–5.19, table 5.2; §4.5
//! figs. 4.32–4.33): a block with a rounded bottom (E = 6896 MPa) pressed
//! 1 mm into a foundation (E = 689.6 MPa) and dragged 10 mm along it,
//! μ = 0.3, plane strain. Measured: the reaction on the block top,
//! H = Fx and V = −Fy (N per mm of thickness), the global coefficient of
//! friction μ_g = H/V at t = 1.5 (thesis table 5.2: 0.32) and how much H
//! oscillates while the block slides.
use std::path::Path;

use super::{cases_dir, interpolate, read_case, swap_master_slave, RunCost};
use crate::run_toml_in_with_history;

/// μ_g = H/V at t = 1.5 of the thesis (table 5.2).
pub const MU_G_THESIS: f64 = 0.32;
/// Acceptance band of μ_g at t = 1.5 (benchmark table).
pub const MU_G_BAND: (f64, f64) = (0.30, 0.36);
/// Largest oscillation of H while sliding, relative to its mean (benchmark table).
pub const OSCILLATION_LIMIT: f64 = 0.01;
/// Interval of the slide (time) over which the oscillation of H is measured.
pub const OSCILLATION_INTERVAL: (f64, f64) = (1.2, 1.9);
/// Half width of the moving average for the oscillation of H: 12
/// increments each side, 0.5 mm of slide, five foundation faces.
pub const OSCILLATION_HALF_WINDOW: usize = 12;
/// The contact surfaces as shipped: foundation top master, block arc slave.
pub const MASTER: &str = "foundation/ymax";
/// The slave surface as shipped.
pub const SLAVE: &str = "block/bottom";

/// How to run the case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Stop at this time (≤ 2; the slide starts at t = 1).
    pub until: f64,
    /// Increments of the indentation (t 0 → 1; 100 as shipped).
    pub indentation_steps: usize,
    /// Increment of the slide in time (0.002 as shipped, i.e. 0.02 mm).
    pub slide_step: f64,
    /// `Some(true)`: implicit, `Some(false)`: explicit coupling (with
    /// `relaxation`), under the segregated method; `None`: as in the case
    /// file.
    pub implicit: Option<bool>,
    /// Under-relaxation of both traction parts under explicit coupling
    /// (eq. 4.13; 0.1, the default, stops at t = 0.335).
    pub relaxation: f64,
    /// Block arc master, foundation top slave.
    pub swapped: bool,
    /// `Some(f)`: `penalty_scale = f` instead of the case file's.
    pub penalty_scale: Option<f64>,
}

impl Default for Options {
    /// The case as shipped.
    fn default() -> Self {
        Options {
            until: 2.0,
            indentation_steps: 100,
            slide_step: 0.002,
            implicit: None,
            relaxation: 0.1,
            swapped: false,
            penalty_scale: None,
        }
    }
}

/// What one run measured, one entry per increment.
#[derive(Debug, Clone, Default)]
pub struct Ironing {
    /// Time of each increment.
    pub time: Vec<f64>,
    /// Horizontal reaction on the block top, H = Fx (N/mm).
    pub horizontal: Vec<f64>,
    /// Vertical reaction on the block top, V = −Fy (N/mm).
    pub vertical: Vec<f64>,
    /// Outer iterations of each increment.
    pub outer_iterations: Vec<usize>,
    /// Every increment converged.
    pub converged: bool,
    /// The failure message, if any.
    pub failure: Option<String>,
    /// Cost of the run.
    pub cost: RunCost,
}

impl Ironing {
    /// (H, V) at time `t` (linear between increments; NaN outside the run).
    pub fn forces_at(&self, t: f64) -> (f64, f64) {
        (
            interpolate(&self.time, &self.horizontal, t),
            interpolate(&self.time, &self.vertical, t),
        )
    }

    /// Global coefficient of friction μ_g = H/V at time `t` (table 5.2).
    pub fn mu_g(&self, t: f64) -> f64 {
        let (h, v) = self.forces_at(t);
        h / v
    }

    /// Oscillation of H over `t0 ≤ t ≤ t1`: the largest deviation of H from
    /// its centred moving average over `2 half_window + 1` increments,
    /// relative to the mean H over the interval. NaN if the window does
    /// not fit in the run.
    pub fn oscillation(&self, t0: f64, t1: f64, half_window: usize) -> f64 {
        let h = &self.horizontal;
        let idx: Vec<usize> = (0..self.time.len())
            .filter(|&i| self.time[i] >= t0 - 1e-9 && self.time[i] <= t1 + 1e-9)
            .collect();
        let (Some(&first), Some(&last)) = (idx.first(), idx.last()) else {
            return f64::NAN;
        };
        if first < half_window || last + half_window >= h.len() {
            return f64::NAN;
        }
        let mean = idx.iter().map(|&i| h[i]).sum::<f64>() / idx.len() as f64;
        let deviation = idx.iter().fold(0.0f64, |m, &i| {
            let window = &h[i - half_window..=i + half_window];
            let average = window.iter().sum::<f64>() / window.len() as f64;
            m.max((h[i] - average).abs())
        });
        deviation / mean.abs()
    }

    /// Mean outer iterations per increment over `t0 < t ≤ t1`.
    pub fn mean_outer(&self, t0: f64, t1: f64) -> f64 {
        let n: Vec<usize> = self
            .time
            .iter()
            .zip(&self.outer_iterations)
            .filter(|(&t, _)| t > t0 + 1e-9 && t <= t1 + 1e-9)
            .map(|(_, &n)| n)
            .collect();
        n.iter().sum::<usize>() as f64 / n.len().max(1) as f64
    }
}

/// The case text for `opts`: the time intervals, coupling and master
/// choice edited (its mesh path is relative to the shipped case's folder).
pub fn case_text(opts: &Options) -> String {
    let (_, mut text) = read_case("shallow-ironing", "case.toml");
    let intervals = if opts.until <= 1.0 {
        let n = (opts.indentation_steps as f64 * opts.until)
            .round()
            .max(1.0);
        format!("intervals = [[{}, {n}]]", opts.until)
    } else {
        let n = ((opts.until - 1.0) / opts.slide_step).round().max(1.0);
        format!(
            "intervals = [[1.0, {}], [{}, {n}]]",
            opts.indentation_steps, opts.until
        )
    };
    text = text.replace("intervals = [[1.0, 100], [2.0, 500]]", &intervals);
    // a choice of coupling is the segregated method's
    if opts.implicit.is_some() {
        text = super::pinned_segregated(&text);
    }
    match opts.implicit {
        Some(true) => {}
        Some(false) => {
            text = text.replace(
                "coupling = \"implicit\"",
                &format!(
                    "coupling = \"explicit\"\nrelaxation = {{ normal = {r}, tangential = {r} }}",
                    r = opts.relaxation
                ),
            );
            // explicit coupling throughout, not switched to implicit
            text = text.replace("[solver]\n", "[solver]\ncoupling_fallback = \"none\"\n");
        }
        None => {}
    }
    if let Some(f) = opts.penalty_scale {
        // the case file's one `penalty_scale = …` line, whatever it holds
        let shipped = text
            .lines()
            .find(|l| l.starts_with("penalty_scale ="))
            .map(str::to_owned)
            .expect("case.toml sets penalty_scale");
        text = text.replace(&shipped, &format!("penalty_scale = {f:?}"));
    }
    if opts.swapped {
        text = swap_master_slave(&text, MASTER, SLAVE);
    }
    text
}

/// Runs the case with `opts`.
pub fn run(opts: &Options) -> Ironing {
    let (out, history) =
        run_toml_in_with_history(&case_text(opts), Some(&cases_dir().join("shallow-ironing")));
    Ironing {
        time: history.column("time"),
        horizontal: history.column("block/top:Fx"),
        vertical: history.column("block/top:Fy").iter().map(|f| -f).collect(),
        outer_iterations: history.outer_iterations(),
        converged: out.converged,
        failure: out.failure.clone(),
        cost: RunCost::of(&out),
    }
}

/// A published curve of H or V against time, in N/mm (the stored values
/// × 100, `../shared/benchmarks/shallow-ironing/reference/`).
#[derive(Debug, Clone)]
pub struct ReferenceCurve {
    /// Source (Code_Aster, Yastrebov, ...).
    pub source: &'static str,
    /// (t, H) points.
    pub horizontal: Vec<(f64, f64)>,
    /// (t, V) points.
    pub vertical: Vec<(f64, f64)>,
}

impl ReferenceCurve {
    /// (H, V) at `t` (linear between points; NaN outside).
    pub fn forces_at(&self, t: f64) -> (f64, f64) {
        let at = |c: &[(f64, f64)]| {
            let (x, y): (Vec<f64>, Vec<f64>) = c.iter().copied().unzip();
            interpolate(&x, &y, t)
        };
        (at(&self.horizontal), at(&self.vertical))
    }
}

/// Scale of the stored reference values to N per mm (benchmark table).
pub const REFERENCE_SCALE: f64 = 100.0;

fn read_columns(path: &Path) -> Result<Vec<Vec<f64>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split_whitespace()
                .map(|v| {
                    v.parse::<f64>()
                        .map_err(|e| format!("{}: '{v}': {e}", path.display()))
                })
                .collect()
        })
        .collect()
}

fn sorted(mut c: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    c.sort_by(|a, b| a.0.total_cmp(&b.0));
    c
}

/// The five published curves from `shared` (`../shared`): Code_Aster,
/// Fischer–Wriggers, Hartmann–Oliver, Poulios–Renard (one file per
/// component, `t value`) and Yastrebov (`yastrebov.dat`: t, H, −V).
pub fn reference_curves(shared: &Path) -> Result<Vec<ReferenceCurve>, String> {
    let dir = shared.join("benchmarks/shallow-ironing/reference");
    let pair = |name: &str| -> Result<Vec<(f64, f64)>, String> {
        let rows = read_columns(&dir.join(format!("{name}.dat")))?;
        Ok(sorted(
            rows.iter()
                .filter(|r| r.len() >= 2)
                .map(|r| (r[0], REFERENCE_SCALE * r[1]))
                .collect(),
        ))
    };
    let mut curves = Vec::new();
    for (source, stem) in [
        ("Code_Aster", "aster"),
        ("Fischer–Wriggers", "fischerWriggers"),
        ("Hartmann–Oliver", "hartmannOliver"),
        ("Poulios–Renard", "pouliosRenard"),
    ] {
        curves.push(ReferenceCurve {
            source,
            horizontal: pair(&format!("{stem}Horizontal"))?,
            vertical: pair(&format!("{stem}Vertical"))?,
        });
    }
    // yastrebov.dat: time, H, V (V negative: the reaction on the block top)
    let rows = read_columns(&dir.join("yastrebov.dat"))?;
    let kept: Vec<&Vec<f64>> = rows.iter().filter(|r| r.len() >= 3).collect();
    curves.push(ReferenceCurve {
        source: "Yastrebov",
        horizontal: kept
            .iter()
            .map(|r| (r[0], REFERENCE_SCALE * r[1]))
            .collect(),
        vertical: kept
            .iter()
            .map(|r| (r[0], -REFERENCE_SCALE * r[2]))
            .collect(),
    });
    Ok(curves)
}
