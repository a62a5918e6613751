//! Globalisation of the Newton step: backtracking on ‖F‖ with a
//! non-monotone acceptance test (Grippo, Lampariello & Lucidi 1986) and
//! safeguarded quadratic interpolation of the step length (Dennis &
//! Schnabel §6.3; Eisenstat & Walker 1994 for the inexact-Newton
//! sufficient decrease 1 − α λ (1 − η)).
//!
//! The non-monotone reference — the largest residual norm of the last
//! few accepted iterates — lets a step through that raises ‖F‖ for a while,
//! as a contact active set that changes between two Newton iterates does
//! (MOOSE's contact "ping-pong"); a monotone test would cut such steps to
//! nothing.

/// Parameters of the line search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineSearchParams {
    /// α of the sufficient-decrease test.
    pub sufficient_decrease: f64,
    /// Accepted iterates whose largest residual norm is the reference.
    pub window: usize,
    /// Most step reductions per Newton iteration.
    pub max_backtracks: usize,
    /// Smallest and largest factor of one reduction.
    pub min_factor: f64,
    /// Full steps that change the problem's frozen data (a contact active
    /// set, [`crate::NonlinearProblem::changes_at_last_renewal`]) accepted
    /// per solve whatever their residual: across such a change ‖F‖ is no
    /// measure of progress (a penalty step into an obstacle that the
    /// linearisation did not know raises it by ε times the penetration,
    /// and the next step, which knows it, removes it). Abaqus calls them
    /// severe discontinuity iterations.
    pub discontinuity_steps: usize,
    /// See `min_factor`.
    pub max_factor: f64,
    /// Accepted iterates without progress after which the test turns
    /// monotone for a window ([`NonMonotone`]; 0: never).
    pub stall_iterations: usize,
}

impl Default for LineSearchParams {
    fn default() -> Self {
        LineSearchParams {
            sufficient_decrease: 1e-4,
            window: 5,
            max_backtracks: 10,
            min_factor: 0.1,
            discontinuity_steps: 8,
            max_factor: 0.5,
            stall_iterations: 3,
        }
    }
}

/// The reference norms of the non-monotone test, with a watchdog: when
/// [`LineSearchParams::stall_iterations`] accepted iterates in a row leave
/// the best residual so far above [`STALL_PROGRESS`] of itself (a cycle
/// between two active sets — a plastic or contact switch that each full
/// step crosses back — which the window maximum lets through), the next
/// `window` iterates must decrease the residual monotonically.
#[derive(Debug, Clone)]
pub struct NonMonotone {
    norms: Vec<f64>,
    window: usize,
    stall_iterations: usize,
    best: f64,
    stalled: usize,
    monotone_left: usize,
}

/// An iterate improves on the best residual so far when it is below this
/// fraction of it.
pub const STALL_PROGRESS: f64 = 0.9;

impl NonMonotone {
    /// An empty history of `window` iterates (at least one); a watchdog
    /// after `stall_iterations` iterates without progress (0: none).
    pub fn new(window: usize, stall_iterations: usize) -> Self {
        NonMonotone {
            norms: Vec::with_capacity(window.max(1)),
            window: window.max(1),
            stall_iterations,
            best: f64::INFINITY,
            stalled: 0,
            monotone_left: 0,
        }
    }

    /// Records the residual norm of an accepted iterate.
    pub fn push(&mut self, norm: f64) {
        if self.norms.len() == self.window {
            self.norms.remove(0);
        }
        self.norms.push(norm);
        self.monotone_left = self.monotone_left.saturating_sub(1);
        if norm < STALL_PROGRESS * self.best || self.best == f64::INFINITY {
            self.best = norm;
            self.stalled = 0;
        } else if self.stall_iterations > 0 {
            self.stalled += 1;
            if self.stalled >= self.stall_iterations {
                self.monotone_left = self.window;
                self.stalled = 0;
                self.best = norm;
            }
        }
    }

    /// Forgets the recorded norms (a new active set's residual is no
    /// measure against the old one's); the watchdog keeps its count and
    /// its best residual.
    pub fn restart_window(&mut self) {
        self.norms.clear();
    }

    /// Whether the watchdog holds the test monotone.
    pub fn is_monotone(&self) -> bool {
        self.monotone_left > 0
    }

    /// The largest recorded norm, or the last while the watchdog holds
    /// (∞ when none).
    pub fn reference(&self) -> f64 {
        if self.norms.is_empty() {
            return f64::INFINITY;
        }
        if self.is_monotone() {
            return self.norms[self.norms.len() - 1];
        }
        self.norms.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }
}

/// Whether a trial with norm `trial` at step length `lambda` decreases
/// enough against the non-monotone `reference`, for a Newton step solved
/// with forcing term `eta`.
pub fn sufficient(trial: f64, reference: f64, lambda: f64, eta: f64, p: &LineSearchParams) -> bool {
    trial.is_finite() && trial <= (1.0 - p.sufficient_decrease * lambda * (1.0 - eta)) * reference
}

/// The next step length after `lambda` failed with trial norm `trial`
/// from the current norm `f0`: the minimiser of the quadratic through
/// φ(0) = f0², φ′(0) = −2 (1 − η) f0² and φ(λ) = trial², kept within
/// [min_factor, max_factor] × λ; an inadmissible or non-finite trial
/// takes the largest reduction.
pub fn next_length(lambda: f64, f0: f64, trial: f64, eta: f64, p: &LineSearchParams) -> f64 {
    if !trial.is_finite() {
        return p.min_factor * lambda;
    }
    let phi0 = f0 * f0;
    let dphi0 = -2.0 * (1.0 - eta) * phi0;
    let phi = trial * trial;
    let curvature = phi - phi0 - dphi0 * lambda;
    let q = if curvature > 0.0 {
        -dphi0 * lambda * lambda / (2.0 * curvature)
    } else {
        p.max_factor * lambda
    };
    q.clamp(p.min_factor * lambda, p.max_factor * lambda)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_monotone_reference_is_the_window_maximum() {
        let mut h = NonMonotone::new(3, 0);
        assert_eq!(h.reference(), f64::INFINITY);
        for v in [5.0, 1.0, 2.0, 0.5] {
            h.push(v);
        }
        // 5.0 left the window
        assert_eq!(h.reference(), 2.0);
    }

    #[test]
    fn watchdog_turns_a_cycle_monotone() {
        let mut h = NonMonotone::new(5, 3);
        // progress, then a two-cycle that the window maximum would accept
        for v in [1.0, 0.5, 0.6, 0.52] {
            h.push(v);
            assert!(!h.is_monotone());
        }
        assert_eq!(h.reference(), 1.0);
        h.push(0.6);
        // three iterates without a 10 % gain on 0.5: the last is the reference
        assert!(h.is_monotone());
        assert_eq!(h.reference(), 0.6);
        // progress from there: monotone for the rest of the window only
        for (i, v) in [0.4, 0.2, 0.1, 0.05, 0.02].into_iter().enumerate() {
            h.push(v);
            assert_eq!(h.is_monotone(), i < 4, "{i}");
        }
        assert_eq!(h.reference(), 0.4);
    }

    #[test]
    fn interpolated_length_is_safeguarded() {
        let p = LineSearchParams::default();
        // a trial far above the start: the quadratic's minimum is tiny → 0.1 λ
        assert_eq!(next_length(1.0, 1.0, 100.0, 0.0, &p), 0.1);
        // a trial just above: the minimum is near λ/2 or beyond → 0.5 λ
        assert_eq!(next_length(1.0, 1.0, 1.0, 0.0, &p), 0.5);
        // exact quadratic: φ(λ) = (1 − λ)² + 3λ² → minimum at λ = 1/4
        let trial = (0.0f64 + 3.0).sqrt();
        assert!((next_length(1.0, 1.0, trial, 0.0, &p) - 0.25).abs() < 1e-12);
        assert_eq!(next_length(0.5, 1.0, f64::NAN, 0.0, &p), 0.05);
        assert!(sufficient(0.5, 1.0, 1.0, 0.1, &p));
        assert!(!sufficient(1.0, 1.0, 1.0, 0.1, &p));
        assert!(!sufficient(f64::NAN, 1.0, 1.0, 0.1, &p));
    }
}
