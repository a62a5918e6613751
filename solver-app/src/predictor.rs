//! `solver.predictor = "linear"`: the first iterate of an increment is
//! extrapolated from the last accepted one (beyond the thesis, whose
//! increments start from the last converged displacement, §3.3).
//!
//! With `u_k` the converged displacement of increment k, increment k+1
//! starts from `u_k + s (u_k − u_{k−1})`. The factor s follows the loading
//! path: with ΔL_k the change of the prescribed values over increment k
//! (displacements, rigid motions, forces, tractions and pressures of every
//! body, [`crate::model::Body::prescribed_values`]), s is the projection
//! ΔL_{k+1}·ΔL_k / |ΔL_k|², which is h_{k+1}/h_k on a straight path. Where
//! the path turns (ΔL_{k+1} more than [`PATH_TOLERANCE`] off the direction
//! of ΔL_k), starts or stops, s = 0: the increment starts from u_k. The
//! twisting hemisphere shows why: extrapolating the last push down into
//! the first increment of the twist (or of a hold) pushed the hemisphere
//! 0.1 mm further into the block, the contact force jumped 37 % and the
//! increment diverged and was cut back.
//!
//! The first increment has nothing to extrapolate: the solver starts it
//! from the harmonic extension of the step of the prescribed displacements
//! instead (`SegregatedSolver::start_from_harmonic_extension`).
//!
//! Under the updated Lagrangian form the cells are the same ones, carried
//! by the mesh, so the change of the last increment is the increment Δu
//! itself. Only the starting point changes: the converged result is the
//! same to the outer tolerance.
use fv_mesh::Vector;

/// Largest part of the new step's change of the prescribed values, relative
/// to its length, that may lie off the direction of the last step's change
/// for the predictor to extrapolate (0.1: the path turns by under 6°).
pub const PATH_TOLERANCE: f64 = 0.1;

/// The change of the prescribed values over a step, in two groups whose
/// units differ: displacements (m) and loads (N, Pa).
#[derive(Debug, Clone, Default)]
pub struct PathChange {
    /// Displacements and rigid motions.
    pub kinematic: Vec<f64>,
    /// Forces, tractions and pressures.
    pub loads: Vec<f64>,
}

impl PathChange {
    /// Empties both groups (the capacity stays).
    pub fn clear(&mut self) {
        self.kinematic.clear();
        self.loads.clear();
    }

    /// `self = end − self`, entry by entry (`end` has the same layout).
    pub fn subtract_from(&mut self, end: &PathChange) {
        for (a, b) in [
            (&mut self.kinematic, &end.kinematic),
            (&mut self.loads, &end.loads),
        ] {
            for (x, y) in a.iter_mut().zip(b) {
                *x = y - *x;
            }
        }
    }

    /// The factor s with which `self` continues `last` (see the module
    /// documentation); 0 where the path turns, starts or stops.
    pub fn continuation_of(&self, last: &PathChange) -> f64 {
        let mut s: Option<f64> = None;
        for (new, old) in [
            (&self.kinematic, &last.kinematic),
            (&self.loads, &last.loads),
        ] {
            if new.len() != old.len() {
                return 0.0;
            }
            let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
            let (nn, oo, no) = (dot(new, new), dot(old, old), dot(new, old));
            if nn == 0.0 && oo == 0.0 {
                continue;
            }
            if nn == 0.0 || oo == 0.0 || !(nn.is_finite() && oo.is_finite()) {
                return 0.0;
            }
            let sg = no / oo;
            let off = (nn - 2.0 * sg * no + sg * sg * oo).max(0.0).sqrt();
            if off > PATH_TOLERANCE * nn.sqrt() {
                return 0.0;
            }
            match s {
                None => s = Some(sg),
                Some(s0) if (sg - s0).abs() > PATH_TOLERANCE * s0.abs().max(sg.abs()) => {
                    return 0.0
                }
                Some(_) => {}
            }
        }
        s.unwrap_or(0.0)
    }
}

/// The last accepted increment's change of the cell displacements.
#[derive(Debug, Clone)]
pub struct LinearPredictor {
    /// `u_k − u_{k−1}`, global numbering; meaningful when `recorded`.
    change: Vec<Vector>,
    /// Whether an increment has been recorded.
    recorded: bool,
    /// The change of the prescribed values over the recorded increment.
    recorded_path: PathChange,
    /// The change of the prescribed values over the step being solved.
    path: PathChange,
}

impl LinearPredictor {
    /// For `n` cells (all deformable bodies, global numbering).
    pub fn new(n: usize) -> Self {
        LinearPredictor {
            change: vec![Vector::zeros(); n],
            recorded: false,
            recorded_path: PathChange::default(),
            path: PathChange::default(),
        }
    }

    /// Sets the change of the prescribed values over the step about to be
    /// solved.
    pub fn set_step(&mut self, path: &PathChange) {
        self.path.clone_from(path);
    }

    /// The factor s the recorded change is applied with (0 before the first
    /// accepted increment).
    pub fn factor(&self) -> f64 {
        if self.recorded {
            self.path.continuation_of(&self.recorded_path)
        } else {
            0.0
        }
    }

    /// Whether no increment has been accepted yet (nothing to extrapolate:
    /// the solver starts from the harmonic extension of the boundary step).
    pub fn is_empty(&self) -> bool {
        !self.recorded
    }

    /// Adds the extrapolated change to the cells `offset..offset + u.len()`.
    pub fn predict(&self, offset: usize, u: &mut [Vector]) {
        let s = self.factor();
        if s == 0.0 {
            return;
        }
        for (u, d) in u.iter_mut().zip(&self.change[offset..]) {
            *u += d * s;
        }
    }

    /// Records a converged increment: `end − start` of the cells from
    /// `offset`, over the step set by [`Self::set_step`]. Call for every
    /// deformable body, then [`Self::close_record`].
    pub fn record(&mut self, offset: usize, end: &[Vector], start: &[Vector]) {
        for ((c, e), s) in self.change[offset..].iter_mut().zip(end).zip(start) {
            *c = e - s;
        }
    }

    /// Ends [`Self::record`]: the recorded change belongs to the current step.
    pub fn close_record(&mut self) {
        self.recorded_path.clone_from(&self.path);
        self.recorded = true;
    }

    /// Restart: puts the recorded change and its path under `prefix`
    /// (nothing before the first record).
    pub fn save_state(&self, prefix: &str, out: &mut fv_mesh::StateArrays) {
        if !self.recorded {
            return;
        }
        out.put_vectors(format!("{prefix}/change"), &self.change);
        out.put_scalars(
            format!("{prefix}/path_kinematic"),
            &self.recorded_path.kinematic,
        );
        out.put_scalars(format!("{prefix}/path_loads"), &self.recorded_path.loads);
    }

    /// Restart: takes back the record of [`Self::save_state`], if any.
    pub fn restore_state(&mut self, prefix: &str, s: &fv_mesh::StateArrays) -> Result<(), String> {
        let change = format!("{prefix}/change");
        if !s.has(&change) {
            self.recorded = false;
            return Ok(());
        }
        s.vectors_into(&change, &mut self.change)?;
        let path = &mut self.recorded_path;
        s.scalars_to_vec(&format!("{prefix}/path_kinematic"), &mut path.kinematic)?;
        s.scalars_to_vec(&format!("{prefix}/path_loads"), &mut path.loads)?;
        self.recorded = true;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(kinematic: &[f64], loads: &[f64]) -> PathChange {
        PathChange {
            kinematic: kinematic.to_vec(),
            loads: loads.to_vec(),
        }
    }

    #[test]
    fn extrapolates_linearly_with_the_step_ratio() {
        let mut p = LinearPredictor::new(3);
        p.set_step(&path(&[0.0, -0.5, 0.0], &[]));
        let mut u = vec![Vector::new(1.0, 0.0, 0.0); 3];
        p.predict(0, &mut u);
        assert_eq!(u[0], Vector::new(1.0, 0.0, 0.0), "nothing recorded yet");
        let start = vec![Vector::zeros(); 3];
        p.record(0, &u, &start);
        p.close_record();
        // half the step along the same path
        p.set_step(&path(&[0.0, -0.25, 0.0], &[]));
        assert_eq!(p.factor(), 0.5);
        p.predict(1, &mut u[1..]);
        assert_eq!(u[0], Vector::new(1.0, 0.0, 0.0), "offset respected");
        assert_eq!(u[1], Vector::new(1.5, 0.0, 0.0));
        assert_eq!(u[2], Vector::new(1.5, 0.0, 0.0));
    }

    #[test]
    fn no_extrapolation_where_the_path_turns_starts_or_stops() {
        // push down, then twist (a rotation, orthogonal): twisting hemisphere
        let down = path(&[0.0, 0.0, -0.1, 0.0, 0.0], &[]);
        let twist = path(&[0.0, 0.0, 0.0, 0.07, -0.07], &[]);
        assert_eq!(twist.continuation_of(&down), 0.0);
        // a hold after the push, and a push after a hold
        let hold = path(&[0.0; 5], &[]);
        assert_eq!(hold.continuation_of(&down), 0.0);
        assert_eq!(down.continuation_of(&hold), 0.0);
        // a turn of 10° is too much, one of 3° is not
        let turned = |deg: f64| {
            let a = deg.to_radians();
            path(&[0.0, -0.1 * a.sin(), -0.1 * a.cos(), 0.0, 0.0], &[])
        };
        assert_eq!(turned(10.0).continuation_of(&down), 0.0);
        let s = turned(3.0).continuation_of(&down);
        assert!((s - 3f64.to_radians().cos()).abs() < 1e-12, "{s}");
        // reversal: the elastic way back
        let up = path(&[0.0, 0.0, 0.05, 0.0, 0.0], &[]);
        assert!((up.continuation_of(&down) + 0.5).abs() < 1e-12);
    }

    #[test]
    fn displacement_and_load_groups_must_agree() {
        let last = path(&[0.1, 0.0], &[100.0]);
        // both doubled: s = 2; the load doubled but not the displacement: 0
        assert!((path(&[0.2, 0.0], &[200.0]).continuation_of(&last) - 2.0).abs() < 1e-12);
        assert_eq!(path(&[0.1, 0.0], &[200.0]).continuation_of(&last), 0.0);
        // a load that starts, and layouts that differ
        assert_eq!(
            path(&[0.1, 0.0], &[100.0]).continuation_of(&path(&[0.1, 0.0], &[0.0])),
            0.0
        );
        assert_eq!(path(&[0.1], &[100.0]).continuation_of(&last), 0.0);
    }

    #[test]
    fn path_change_is_end_minus_start() {
        let mut a = path(&[1.0, 2.0], &[10.0]);
        a.subtract_from(&path(&[1.5, 1.0], &[30.0]));
        assert_eq!(a.kinematic, vec![0.5, -1.0]);
        assert_eq!(a.loads, vec![20.0]);
    }
}
