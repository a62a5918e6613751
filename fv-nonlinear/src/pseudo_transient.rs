//! Pseudo-transient continuation (Kelley & Keyes, SIAM J. Numer. Anal.
//! 35, 1998; Coffey, Kelley & Keyes 2003 for its use with Newton–Krylov):
//! when Newton's step finds no decrease of ‖F‖, the next steps solve
//!
//! (−J + σ D) δ = F
//!
//! with D the problem's positive stiffness scale per unknown
//! ([`crate::NonlinearProblem::damping`]) — a pseudo-time step 1/σ of a
//! damped motion towards equilibrium. A large σ turns the step into a
//! short, diagonally scaled residual step that no soft mode can amplify;
//! σ → 0 recovers Newton. σ follows the switched evolution relaxation
//! (SER): σ ← σ ‖F_new‖/‖F_old‖ after each accepted step, so that it fades
//! as the residual falls and Newton's convergence returns — and at least
//! halves after a full step, which says the damping is more than the step
//! needed (with SER alone σ stayed at 0.25 while the residual fell 2 % per
//! step). The converged
//! state is F = 0 whatever the path: nothing of the damping remains in it.
//!
//! Where it is needed: a buckled shell pressed on a rigid plate (concentric
//! spheres after 8.3 mm) has a soft mode that the Newton direction follows
//! into the plate, and the line search found no decrease from 3e-5.

/// σ is at least multiplied by this after a full step.
const FULL_STEP_REDUCTION: f64 = 0.5;

/// Parameters of the continuation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PseudoTransientParams {
    /// σ when the line search first fails.
    pub initial: f64,
    /// Factor on σ at every further failure.
    pub growth: f64,
    /// Largest σ; a failure beyond it ends the solve.
    pub max: f64,
    /// σ below this fraction of `initial` is dropped (pure Newton).
    pub drop_below: f64,
}

impl Default for PseudoTransientParams {
    fn default() -> Self {
        PseudoTransientParams {
            initial: 1.0,
            growth: 10.0,
            max: 1e4,
            drop_below: 1e-3,
        }
    }
}

/// The shift σ of one solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PseudoTransient {
    params: PseudoTransientParams,
    sigma: f64,
    /// Line-search failures rescued so far.
    pub rescues: usize,
}

impl PseudoTransient {
    /// Off (σ = 0).
    pub fn new(params: PseudoTransientParams) -> Self {
        PseudoTransient {
            params,
            sigma: 0.0,
            rescues: 0,
        }
    }

    /// The current shift (0: Newton).
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// After a failed line search: switches the continuation on or
    /// strengthens it; false when it is already at its largest.
    pub fn rescue(&mut self) -> bool {
        let next = if self.sigma == 0.0 {
            self.params.initial
        } else {
            self.sigma * self.params.growth
        };
        if !(next <= self.params.max) {
            return false;
        }
        self.sigma = next;
        self.rescues += 1;
        true
    }

    /// After an accepted step of length `lambda` from residual norm
    /// `before` to `after` (SER; at least halved after a full step).
    pub fn accepted(&mut self, before: f64, after: f64, lambda: f64) {
        if self.sigma == 0.0 || !(before > 0.0) {
            return;
        }
        let mut ratio = after / before;
        if lambda >= 1.0 {
            ratio = ratio.min(FULL_STEP_REDUCTION);
        }
        self.sigma = (self.sigma * ratio).min(self.params.max);
        if self.sigma < self.params.drop_below * self.params.initial {
            self.sigma = 0.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn switched_evolution_relaxation() {
        let mut p = PseudoTransient::new(PseudoTransientParams::default());
        assert_eq!(p.sigma(), 0.0);
        // nothing to relax while off
        p.accepted(1.0, 0.1, 1.0);
        assert_eq!(p.sigma(), 0.0);
        assert!(p.rescue());
        assert_eq!(p.sigma(), 1.0);
        assert!(p.rescue());
        assert_eq!(p.sigma(), 10.0);
        // σ follows the residual after a shortened step
        p.accepted(1.0, 0.8, 0.5);
        assert_eq!(p.sigma(), 8.0);
        // and at least halves after a full one
        p.accepted(1.0, 0.8, 1.0);
        assert_eq!(p.sigma(), 4.0);
        p.accepted(1.0, 1e-4, 1.0);
        // 4e-4 < 1e-3 × 1: back to Newton
        assert_eq!(p.sigma(), 0.0);
        assert_eq!(p.rescues, 2);
        // at its largest a failure ends the solve
        let mut q = PseudoTransient::new(PseudoTransientParams {
            max: 10.0,
            ..Default::default()
        });
        assert!(q.rescue() && q.rescue());
        assert!(!q.rescue());
    }
}
