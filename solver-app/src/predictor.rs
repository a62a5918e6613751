//! `solver.predictor = "linear"`: the first iterate of an increment is
//! extrapolated from the last accepted one (beyond the thesis, whose
//! increments start from the last converged displacement, §3.3).
//!
//! With `u_k` the converged displacement of increment k over the step
//! `h_k`, increment k+1 starts from `u_k + (h_{k+1}/h_k)(u_k − u_{k−1})`.
//! Under the updated Lagrangian form the cells are the same ones, carried
//! by the mesh, so the change of the last increment is the increment Δu
//! itself. Only the starting point changes: the converged result is the
//! same to the outer tolerance.
use fv_mesh::Vector;

/// The last accepted increment's change of the cell displacements.
#[derive(Debug, Clone)]
pub struct LinearPredictor {
    /// `u_k − u_{k−1}`, global numbering; meaningful when `change_step > 0`.
    change: Vec<Vector>,
    /// `h_k` of `change` (0: nothing recorded yet).
    change_step: f64,
    /// `h_{k+1}`, the step being solved.
    step: f64,
}

impl LinearPredictor {
    /// For `n` cells (all deformable bodies, global numbering).
    pub fn new(n: usize) -> Self {
        LinearPredictor {
            change: vec![Vector::zeros(); n],
            change_step: 0.0,
            step: 0.0,
        }
    }

    /// Sets the size of the step about to be solved.
    pub fn set_step(&mut self, step: f64) {
        self.step = step;
    }

    /// The factor `h_{k+1}/h_k` the recorded change is applied with (0
    /// before the first accepted increment).
    pub fn factor(&self) -> f64 {
        if self.change_step > 0.0 && self.step > 0.0 {
            self.step / self.change_step
        } else {
            0.0
        }
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
        self.change_step = self.step;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extrapolates_linearly_with_the_step_ratio() {
        let mut p = LinearPredictor::new(3);
        p.set_step(0.5);
        let mut u = vec![Vector::new(1.0, 0.0, 0.0); 3];
        p.predict(0, &mut u);
        assert_eq!(u[0], Vector::new(1.0, 0.0, 0.0), "nothing recorded yet");
        let start = vec![Vector::zeros(); 3];
        p.record(0, &u, &start);
        p.close_record();
        p.set_step(0.25);
        assert_eq!(p.factor(), 0.5);
        p.predict(1, &mut u[1..]);
        assert_eq!(u[0], Vector::new(1.0, 0.0, 0.0), "offset respected");
        assert_eq!(u[1], Vector::new(1.5, 0.0, 0.0));
        assert_eq!(u[2], Vector::new(1.5, 0.0, 0.0));
    }
}
