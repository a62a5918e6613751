//! twisting-hemisphere (thesis §5.3.5, figs. 5.28–5.32; Sauer & De
//! Lorenzis 2015): a hollow neo-Hookean hemisphere (E = 50) pushed 1 mm
//! into a softer block (E = 10; `case.toml` says why) without friction
//! (pseudo-time t 0 → 1, 10 increments), then
//! twisted 180° about the vertical axis with μ = 0.5 (t 1 → 10, 90
//! increments). Measured: the vertical reaction F_z on the hemisphere's
//! rim and the twisting torque M_z (the moment column of its rigid-motion
//! patch), against the angle θ = (t − 1)·20°.
//!
//! Two meshes: the shipped case (`case.toml`, built-in generators, z up)
//! and the benchmark's coarse polyMesh (`case-polymesh.toml`, y up), which
//! is extracted from `../shared` into a temporary folder at run time
//! (`tar -xJf`).
//!
//! References (`../shared/benchmarks/twisting-hemisphere/reference/`):
//! the x column of all three files is already the twist angle in degrees
//! (0–180; the source plotted against the pseudo-time (θ·9/180) + 1, i.e.
//! t above). Sauer–De Lorenzis values are stored as plotted, a tenth of the
//! physical ones: F_z [N] = 10 × `deLorenzisForce.dat`, M [N·mm] = 10 ×
//! `deLorenzisMoment.dat` (the indentation force of this case and FEBio's
//! moment both confirm the factor). FEBio's moment (`febioMoment.dat`) is
//! in N·mm as stored.
use std::path::{Path, PathBuf};

use super::{cases_dir, extract_polymesh, interpolate, read_case, swap_master_slave, RunCost};
use crate::run_toml_in_with_history;

/// Which mesh the case runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshSource {
    /// `case.toml`: the built-in box and spherical-shell generators (z up).
    Generated,
    /// `case-polymesh.toml`: the benchmark's coarse polyMesh from `../shared` (y up).
    Benchmark,
}

impl MeshSource {
    /// (case file, master, slave, vertical force column, moment column,
    /// vertical force column of the block's fixed base).
    fn names(self) -> [&'static str; 6] {
        match self {
            MeshSource::Generated => [
                "case.toml",
                "block/zmax",
                "hemisphere/outer",
                "hemisphere/zmax:Fz",
                "hemisphere/zmax:Mz",
                "block/zmin:Fz",
            ],
            MeshSource::Benchmark => [
                "case-polymesh.toml",
                "block/block-contact",
                "hemisphere/sphere-contact",
                "hemisphere/sphere-displacement:Fy",
                "hemisphere/sphere-displacement:My",
                "block/block-fixed:Fy",
            ],
        }
    }
}
/// Scale of the stored Sauer–De Lorenzis values to N and N·mm.
pub const DE_LORENZIS_SCALE: f64 = 10.0;
/// Acceptance: plateau torque within 5 % of Sauer–De Lorenzis.
pub const TORQUE_TOLERANCE: f64 = 0.05;
/// Acceptance: F_z within 3 % of Sauer–De Lorenzis.
pub const FORCE_TOLERANCE: f64 = 0.03;

/// How to run the case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Stop at this pseudo-time (≤ 10; the twist starts at t = 1).
    pub until: f64,
    /// Block top slave, hemisphere master.
    pub swapped: bool,
    /// `Some(true)`: implicit, `Some(false)`: explicit coupling (default
    /// relaxation); `None`: as in the case file.
    pub implicit: Option<bool>,
    /// The mesh.
    pub mesh: MeshSource,
}

impl Default for Options {
    /// The case as shipped.
    fn default() -> Self {
        Options {
            until: 10.0,
            swapped: false,
            implicit: None,
            mesh: MeshSource::Generated,
        }
    }
}

/// What one run measured, one entry per increment.
#[derive(Debug, Clone, Default)]
pub struct Twist {
    /// Pseudo-time of each increment.
    pub time: Vec<f64>,
    /// Vertical reaction on the hemisphere's top annulus, N (upwards positive).
    pub force: Vec<f64>,
    /// Vertical reaction on the block's fixed base, N (upwards positive):
    /// equal to `force` when the contact transmits what it computes.
    pub base_force: Vec<f64>,
    /// Twisting torque about the vertical axis, N·mm (magnitude).
    pub torque: Vec<f64>,
    /// Outer iterations of each increment.
    pub outer_iterations: Vec<usize>,
    /// Every increment converged.
    pub converged: bool,
    /// The failure message, if any.
    pub failure: Option<String>,
    /// Cost of the run.
    pub cost: RunCost,
}

/// Twist angle in degrees at pseudo-time `t` (0 during the indentation).
pub fn angle_of(t: f64) -> f64 {
    ((t - 1.0) * 20.0).max(0.0)
}

impl Twist {
    /// (F_z, M) at pseudo-time `t` (linear between increments; NaN outside).
    pub fn at_time(&self, t: f64) -> (f64, f64) {
        (
            interpolate(&self.time, &self.force, t),
            interpolate(&self.time, &self.torque, t),
        )
    }

    /// (F_z, M) at twist angle `deg`.
    pub fn at_angle(&self, deg: f64) -> (f64, f64) {
        self.at_time(1.0 + deg / 20.0)
    }

    /// Pseudo-time of the last increment (how far the run got).
    pub fn reached(&self) -> f64 {
        self.time.last().copied().unwrap_or(0.0)
    }

    /// The worst relative miss of F_z on `reference` over the increments of
    /// the twist (t ≥ 1) and its angle, (angle, miss); NaN when the run never
    /// got there or a force was not finite.
    pub fn worst_force_error(&self, reference: &ReferenceCurve) -> (f64, f64) {
        self.time
            .iter()
            .zip(&self.force)
            .filter(|(t, _)| **t >= 1.0 - 1e-9)
            .map(|(t, f)| (angle_of(*t), f / reference.at(angle_of(*t)) - 1.0))
            // a NaN miss sticks: it is the worst
            .fold(None, |w: Option<(f64, f64)>, x| match w {
                Some(w) if w.1.is_nan() || (!x.1.is_nan() && w.1.abs() >= x.1.abs()) => Some(w),
                _ => Some(x),
            })
            .unwrap_or((f64::NAN, f64::NAN))
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

/// The benchmark folder in `shared`.
fn benchmark_dir(shared: &Path) -> PathBuf {
    shared.join("benchmarks/twisting-hemisphere")
}

/// Extracts the coarse polyMesh of `shared` into a fresh temporary folder
/// (which then holds `polyMesh/`) and returns that folder.
pub fn extract_mesh(shared: &Path) -> Result<PathBuf, String> {
    extract_polymesh(
        &benchmark_dir(shared).join("mesh/polyMesh_coarse.tar.xz"),
        "twisting-hemisphere",
    )
}

/// The case text for `opts`: the time intervals, coupling and master
/// choice edited (its mesh path `polyMesh` is relative to the case folder).
pub fn case_text(opts: &Options) -> String {
    let [file, master, slave, ..] = opts.mesh.names();
    let (_, mut text) = read_case("twisting-hemisphere", file);
    let intervals = if opts.until <= 1.0 {
        let n = (10.0 * opts.until).round().max(1.0);
        format!("intervals = [[{}, {n}]]", opts.until)
    } else {
        let n = (10.0 * (opts.until - 1.0)).round().max(1.0);
        format!("intervals = [[1.0, 10], [{}, {n}]]", opts.until)
    };
    text = text.replace("intervals = [[1.0, 10], [10.0, 90]]", &intervals);
    match opts.implicit {
        Some(true) => text = text.replace("coupling = \"explicit\"", "coupling = \"implicit\""),
        Some(false) => {
            // explicit coupling throughout, not switched to implicit
            text = text
                .replace("coupling = \"implicit\"", "coupling = \"explicit\"")
                .replace("[solver]\n", "[solver]\ncoupling_fallback = \"none\"\n");
        }
        None => {}
    }
    if opts.swapped {
        text = swap_master_slave(&text, master, slave);
    }
    text
}

/// Runs the case with `opts`; `shared` (`../shared`) is needed for
/// [`MeshSource::Benchmark`] only.
pub fn run(shared: Option<&Path>, opts: &Options) -> Result<Twist, String> {
    let [_, _, _, force_column, moment_column, base_column] = opts.mesh.names();
    let (out, history) = match opts.mesh {
        MeshSource::Generated => run_toml_in_with_history(
            &case_text(opts),
            Some(&cases_dir().join("twisting-hemisphere")),
        ),
        MeshSource::Benchmark => {
            let shared = shared.ok_or("the benchmark mesh needs ../shared")?;
            let dir = extract_mesh(shared)?;
            let r = run_toml_in_with_history(&case_text(opts), Some(&dir));
            let _ = std::fs::remove_dir_all(&dir);
            r
        }
    };
    Ok(Twist {
        time: history.column("time"),
        force: history.column(force_column).iter().map(|f| -f).collect(),
        base_force: history.column(base_column),
        torque: history
            .column(moment_column)
            .iter()
            .map(|m| m.abs())
            .collect(),
        outer_iterations: history.outer_iterations(),
        converged: out.converged,
        failure: out.failure.clone(),
        cost: RunCost::of(&out),
    })
}

/// A published curve against the twist angle (degrees), in N or N·mm.
#[derive(Debug, Clone)]
pub struct ReferenceCurve {
    /// Source and quantity.
    pub source: &'static str,
    /// (angle in degrees, value) points, sorted by angle.
    pub points: Vec<(f64, f64)>,
}

impl ReferenceCurve {
    /// The value at `deg` (linear between points; NaN outside).
    pub fn at(&self, deg: f64) -> f64 {
        let (x, y): (Vec<f64>, Vec<f64>) = self.points.iter().copied().unzip();
        interpolate(&x, &y, deg)
    }

    /// Mean value over `deg0 ≤ θ ≤ deg1` (trapezoids on the points and
    /// the interval ends).
    pub fn mean(&self, deg0: f64, deg1: f64) -> f64 {
        let n = 180;
        let h = (deg1 - deg0) / n as f64;
        let s: f64 = (0..=n)
            .map(|i| {
                let w = if i == 0 || i == n { 0.5 } else { 1.0 };
                w * self.at(deg0 + h * i as f64)
            })
            .sum();
        s * h / (deg1 - deg0)
    }
}

fn read_curve(path: &Path, scale: f64, source: &'static str) -> Result<ReferenceCurve, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut points = Vec::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let v: Vec<f64> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .map(|s| {
                s.parse::<f64>()
                    .map_err(|e| format!("{}: '{s}': {e}", path.display()))
            })
            .collect::<Result<_, _>>()?;
        if v.len() < 2 {
            return Err(format!(
                "{}: expected 'angle, value': {line}",
                path.display()
            ));
        }
        points.push((v[0], scale * v[1]));
    }
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    points.dedup_by(|a, b| a.0 == b.0);
    Ok(ReferenceCurve { source, points })
}

/// The published curves: Sauer–De Lorenzis F_z and M, FEBio M (N, N·mm).
pub struct References {
    /// Sauer–De Lorenzis vertical force.
    pub force: ReferenceCurve,
    /// Sauer–De Lorenzis twisting moment.
    pub torque: ReferenceCurve,
    /// FEBio twisting moment.
    pub torque_febio: ReferenceCurve,
}

/// Reads the three reference files of `shared`.
pub fn references(shared: &Path) -> Result<References, String> {
    let dir = benchmark_dir(shared).join("reference");
    Ok(References {
        force: read_curve(
            &dir.join("deLorenzisForce.dat"),
            DE_LORENZIS_SCALE,
            "Sauer–De Lorenzis F_z",
        )?,
        torque: read_curve(
            &dir.join("deLorenzisMoment.dat"),
            DE_LORENZIS_SCALE,
            "Sauer–De Lorenzis M",
        )?,
        torque_febio: read_curve(&dir.join("febioMoment.dat"), 1.0, "FEBio M")?,
    })
}
