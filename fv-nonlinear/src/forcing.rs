//! Eisenstat–Walker forcing terms: how exactly each Newton step's linear
//! system is solved (Eisenstat & Walker, SIAM J. Sci. Comput. 17, 1996,
//! choice 2 with its safeguard; Kelley, *Iterative Methods for Linear and
//! Nonlinear Equations*, eq. 6.20, for the guard against oversolving the
//! last step).
//!
//! Far from the solution a loose linear solve saves Krylov iterations
//! whose accuracy the next Newton step would discard; near it the forcing
//! term follows the residual's decrease, η_k = γ (‖F_k‖/‖F_{k−1}‖)^α,
//! which keeps Newton's fast local convergence.

/// Parameters of the forcing sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForcingParams {
    /// η of the first Newton step.
    pub initial: f64,
    /// Largest η (the linear solve reduces the residual at least this much).
    pub max: f64,
    /// γ of choice 2.
    pub gamma: f64,
    /// α of choice 2.
    pub alpha: f64,
}

impl Default for ForcingParams {
    fn default() -> Self {
        ForcingParams {
            initial: 0.1,
            max: 0.5,
            gamma: 0.9,
            alpha: 2.0,
        }
    }
}

/// The forcing sequence of one nonlinear solve.
#[derive(Debug, Clone)]
pub struct Forcing {
    params: ForcingParams,
    last_eta: Option<f64>,
    last_norm: f64,
}

impl Forcing {
    /// A new sequence.
    pub fn new(params: ForcingParams) -> Self {
        Forcing {
            params,
            last_eta: None,
            last_norm: f64::NAN,
        }
    }

    /// η for the step from a residual of norm `norm`; `target` is the norm
    /// that ends the nonlinear solve (the linear solve need not go far
    /// below it: η ≥ ½ target/norm).
    pub fn next(&mut self, norm: f64, target: f64) -> f64 {
        let p = &self.params;
        let eta = match self.last_eta {
            None => p.initial,
            Some(prev) => {
                let mut eta = p.gamma * (norm / self.last_norm).powf(p.alpha);
                let guard = p.gamma * prev.powf(p.alpha);
                if guard > 0.1 {
                    eta = eta.max(guard);
                }
                eta
            }
        };
        let mut eta = eta.min(p.max);
        if norm > 0.0 {
            eta = eta.max(0.5 * target / norm).min(p.max);
        }
        self.last_eta = Some(eta);
        self.last_norm = norm;
        eta
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn follows_the_residual_decrease_with_its_safeguards() {
        let mut f = Forcing::new(ForcingParams::default());
        assert_eq!(f.next(1.0, 1e-8), 0.1);
        // residual ×0.1: η = 0.9 · 0.01 = 0.009; the guard 0.9 · 0.1² = 0.009 ≤ 0.1
        assert!((f.next(0.1, 1e-8) - 0.009).abs() < 1e-15);
        // stagnation: η capped at max
        assert_eq!(f.next(0.1, 1e-8), 0.5);
        // near the target: not below half of target/norm
        let mut g = Forcing::new(ForcingParams::default());
        g.next(1.0, 1e-8);
        assert!((g.next(1e-6, 1e-8) - 5e-3).abs() < 1e-15);
    }
}
