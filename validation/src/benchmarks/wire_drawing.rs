//! Wire drawing (thesis §5.4.1): a quarter of a Ø2 mm steel wire (J2
//! elastoplastic, E = 190 GPa, σ_Y = 0.85 GPa, H' = 0.5 GPa) drawn 8.3 mm
//! through an elastic die (E = 600 GPa) to Ø1.72 mm, μ = 0.08, 10 MPa back
//! tension. The drawing force on the quarter, the axial reaction on the
//! pulled end, against the thesis's per-mesh forces and its Richardson
//! extrapolation. Case: `validation/cases/wire-drawing` (units mm, N).
use super::{read_case, steady_mean, RunCost};
use crate::run_toml_in_with_history;

/// The thesis's steady drawing force on the quarter per wire mesh
/// (cells, N): coarse, medium, fine, very fine (§5.4.1).
pub const THESIS_FORCES: [(usize, f64); 4] = [
    (2_400, 312.7),
    (19_200, 301.1),
    (153_600, 291.7),
    (1_228_800, 285.0),
];

/// The thesis's Richardson extrapolation of its drawing force, N.
pub const THESIS_RICHARDSON: f64 = 282.8;

/// Largest deviation of the thesis's coarse-mesh force from its mean, as a
/// fraction ("less than 1.8 %").
pub const THESIS_OSCILLATION: f64 = 0.018;

/// Time (s) from which the force is steady: the material of the straight
/// wire (behind the pre-shaped nose and its fillet, which begins 1.9 mm
/// before the die's land) has passed the land's end after 2.3 mm, 0.028 s.
pub const STEADY_FROM: f64 = 0.03;

/// Richardson extrapolation from the forces on two meshes whose spacing
/// differs by 2, of order `order`: f_fine + (f_fine − f_coarse)/(2^p − 1).
/// The thesis's 282.8 N is this with p = 2 from its two finest meshes
/// (285.0 + (285.0 − 291.7)/3).
pub fn richardson(coarse: f64, fine: f64, order: f64) -> f64 {
    fine + (fine - coarse) / (2f64.powf(order) - 1.0)
}

/// The wire meshes of the case (both from `wire.py`; the die is the same).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WireMesh {
    /// `case.toml`, `wire.msh`: 2,400 hexahedra (the thesis's coarse count).
    Coarse,
    /// `medium.toml`, `wire-medium.msh` (`wire.py --refine 1`): 19,200.
    Medium,
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct WireRun {
    /// Time of every converged increment, s.
    pub time: Vec<f64>,
    /// Drawing force on the quarter (x reaction on `wire/pulled`), N.
    pub force: Vec<f64>,
    /// Outer (or Newton) iterations of those increments.
    pub outer_iterations: Vec<usize>,
    /// Whether every increment converged.
    pub converged: bool,
    /// Why the run stopped, if it did.
    pub failure: Option<String>,
    /// Cost.
    pub cost: RunCost,
}

impl WireRun {
    /// Mean force from [`STEADY_FROM`] to the end and the largest
    /// deviation from it as a fraction of it; `None` before that time.
    pub fn steady(&self) -> Option<(f64, f64)> {
        steady_mean(&self.time, &self.force, STEADY_FROM)
    }
}

/// Runs the case on `mesh` (its own settings; `edit` may change the case
/// text first).
pub fn run_edited(mesh: WireMesh, edit: impl Fn(String) -> String) -> WireRun {
    let (dir, text) = match mesh {
        WireMesh::Coarse => read_case("wire-drawing", "case.toml"),
        WireMesh::Medium => read_case("wire-drawing", "medium.toml"),
    };
    let (out, history) = run_toml_in_with_history(&edit(text), Some(&dir));
    // history.csv also holds the increment a failed run stopped in: drop it
    let n = history.rows.len() - usize::from(!out.converged && !history.rows.is_empty());
    WireRun {
        time: history.column("time")[..n].to_vec(),
        force: history.column("wire/pulled:Fx")[..n].to_vec(),
        outer_iterations: history.outer_iterations()[..n].to_vec(),
        converged: out.converged,
        failure: out.failure.clone(),
        cost: RunCost::of(&out),
    }
}

/// [`run_edited`] as shipped.
pub fn run(mesh: WireMesh) -> WireRun {
    run_edited(mesh, |t| t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn richardson_of_the_thesis_two_finest_meshes_is_its_282_8_n() {
        let r = richardson(THESIS_FORCES[2].1, THESIS_FORCES[3].1, 2.0);
        assert!((r - THESIS_RICHARDSON).abs() < 0.05, "{r}");
    }

    #[test]
    fn steady_window_mean_and_deviation() {
        let run = WireRun {
            time: vec![0.01, 0.03, 0.04, 0.05],
            force: vec![100.0, 99.0, 101.0, 100.0],
            outer_iterations: vec![1; 4],
            converged: true,
            failure: None,
            cost: RunCost::default(),
        };
        let (mean, dev) = run.steady().expect("window reached");
        assert!((mean - 100.0).abs() < 1e-12 && (dev - 0.01).abs() < 1e-12);
    }
}
