//! Where a run's time goes: wall seconds per phase of the outer iteration,
//! summed over the run, for the log and `summary.json`. Each phase is
//! timed by one `Instant` pair per outer iteration and body (tens of
//! nanoseconds against the milliseconds of an iteration).
use std::time::Instant;

/// A phase of the solution (thesis §3.3 steps i–iv and chapter 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Matrix coefficients and their IC/ILU factorisation (per increment
    /// under large strain; per outer iteration with implicit contact).
    MatrixAssembly,
    /// Boundary-face values (displacement, traction and symmetry conditions).
    BoundaryValues,
    /// Least-squares gradient, deformation and stress.
    GradientAndStress,
    /// Explicit right-hand side: the force residual of every cell.
    ResidualAssembly,
    /// The linear solves of the three components.
    LinearSolve,
    /// Contact surfaces moved, and the OBB / advancing-front detection.
    ContactDetection,
    /// Penalty tractions, friction return map and the coupling update.
    ContactForce,
    /// Mesh motion and state commit at the end of an increment.
    MeshMotion,
    /// Anderson mixing of the outer iterates (`solver.acceleration`).
    Acceleration,
}

impl Phase {
    /// Every phase, in report order.
    pub const ALL: [Phase; 9] = [
        Phase::MatrixAssembly,
        Phase::BoundaryValues,
        Phase::GradientAndStress,
        Phase::ResidualAssembly,
        Phase::LinearSolve,
        Phase::ContactDetection,
        Phase::ContactForce,
        Phase::MeshMotion,
        Phase::Acceleration,
    ];

    /// Name in the log and in `summary.json`.
    pub fn name(self) -> &'static str {
        match self {
            Phase::MatrixAssembly => "matrix_assembly",
            Phase::BoundaryValues => "boundary_values",
            Phase::GradientAndStress => "gradient_and_stress",
            Phase::ResidualAssembly => "residual_assembly",
            Phase::LinearSolve => "linear_solve",
            Phase::ContactDetection => "contact_detection",
            Phase::ContactForce => "contact_force",
            Phase::MeshMotion => "mesh_motion",
            Phase::Acceleration => "acceleration",
        }
    }
}

/// Seconds spent per [`Phase`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PhaseTimes {
    seconds: [f64; Phase::ALL.len()],
}

impl PhaseTimes {
    /// Adds the time since `start` to `phase`; returns now, the start of
    /// the next phase.
    pub fn lap(&mut self, phase: Phase, start: Instant) -> Instant {
        let now = Instant::now();
        self.seconds[phase as usize] += now.duration_since(start).as_secs_f64();
        now
    }

    /// Adds `seconds` to `phase`.
    pub fn add(&mut self, phase: Phase, seconds: f64) {
        self.seconds[phase as usize] += seconds;
    }

    /// Seconds of `phase`.
    pub fn get(&self, phase: Phase) -> f64 {
        self.seconds[phase as usize]
    }

    /// Adds another account (e.g. the contact set's to the solver's).
    pub fn merge(&mut self, other: &PhaseTimes) {
        for (a, b) in self.seconds.iter_mut().zip(&other.seconds) {
            *a += b;
        }
    }

    /// Sum over the phases.
    pub fn total(&self) -> f64 {
        self.seconds.iter().sum()
    }

    /// One line for the log: each phase's share of `wall` seconds, largest
    /// first, and the rest (output, set-up) as `other`.
    pub fn report(&self, wall: f64) -> String {
        let mut parts: Vec<(f64, &str)> = Phase::ALL
            .iter()
            .map(|&p| (self.get(p), p.name()))
            .filter(|(s, _)| *s > 0.0)
            .collect();
        parts.push(((wall - self.total()).max(0.0), "other"));
        parts.sort_by(|a, b| b.0.total_cmp(&a.0));
        let wall = wall.max(f64::MIN_POSITIVE);
        let shares: Vec<String> = parts
            .iter()
            .map(|(s, n)| format!("{n} {:.1} %", 100.0 * s / wall))
            .collect();
        format!("profile: {}", shares.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn laps_accumulate_and_report_sorted_shares() {
        let mut t = PhaseTimes::default();
        t.seconds[Phase::LinearSolve as usize] = 3.0;
        t.seconds[Phase::ContactForce as usize] = 1.0;
        let mut u = PhaseTimes::default();
        u.seconds[Phase::LinearSolve as usize] = 1.0;
        t.merge(&u);
        assert_eq!(t.get(Phase::LinearSolve), 4.0);
        assert_eq!(t.total(), 5.0);
        assert_eq!(
            t.report(10.0),
            "profile: other 50.0 %, linear_solve 40.0 %, contact_force 10.0 %"
        );
        let start = Instant::now();
        let next = t.lap(Phase::MeshMotion, start);
        assert!(next >= start && t.get(Phase::MeshMotion) >= 0.0);
    }
}
