//! Wire rolling (thesis §5.4.2): a quarter of a Ø2.7 mm steel wire (J2
//! elastoplastic, tabulated hardening from 1.3 GPa) rolled between two
//! flat neo-Hookean rolls (radii 60/89 mm, 60 rpm) to a gap of 1.89 mm,
//! μ = 0.1. The roll's vertical force and its torque about its axis, the
//! reaction and moment of the roll's bore. Case:
//! `validation/cases/wire-rolling` (units mm, N).
use super::{read_case, RunCost};
use crate::run_toml_in_with_history;

/// End of the closing of the rolls and of the ramp of their speed, s (40
/// increments of 3.5e-4 s).
pub const CLOSED_AT: f64 = 0.014;

/// Roll radius at the surface, mm.
pub const ROLL_RADIUS: f64 = 89.0;

/// Wire diameter and final gap between the rolls, mm.
pub const WIRE_DIAMETER: f64 = 2.7;
/// The gap the rolls close to, mm.
pub const GAP: f64 = 1.89;

/// What one run measured.
#[derive(Debug, Clone)]
pub struct RollingRun {
    /// Time of every converged increment, s.
    pub time: Vec<f64>,
    /// The roll's force on the wire towards the plane between the rolls,
    /// N (minus the y reaction of the roll's bore; the quarter model's
    /// half roll).
    pub force: Vec<f64>,
    /// The torque that turns the roll, N mm (the z moment of the bore's
    /// reaction about the roll's axis).
    pub torque: Vec<f64>,
    /// Area of the wire's surface in contact, mm².
    pub contact_area: Vec<f64>,
    /// Newton (or outer) iterations of those increments.
    pub iterations: Vec<usize>,
    /// Whether every increment converged.
    pub converged: bool,
    /// Why the run stopped, if it did.
    pub failure: Option<String>,
    /// Cost.
    pub cost: RunCost,
}

/// Runs `file` of the case (`edit` may change its text first).
pub fn run_edited(file: &str, edit: impl Fn(String) -> String) -> RollingRun {
    let (dir, text) = read_case("wire-rolling", file);
    let (out, history) = run_toml_in_with_history(&edit(text), Some(&dir));
    // history.csv also holds the increment a failed run stopped in: drop it
    let n = history.rows.len() - usize::from(!out.converged && !history.rows.is_empty());
    RollingRun {
        time: history.column("time")[..n].to_vec(),
        force: history.column("roll/inner:Fy")[..n]
            .iter()
            .map(|f| -f)
            .collect(),
        torque: history.column("roll/inner:Mz")[..n].to_vec(),
        contact_area: history.column("wire/outer:contact_area")[..n].to_vec(),
        iterations: history.outer_iterations()[..n].to_vec(),
        converged: out.converged,
        failure: out.failure.clone(),
        cost: RunCost::of(&out),
    }
}
