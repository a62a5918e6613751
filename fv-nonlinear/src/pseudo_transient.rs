//! Pseudo-transient continuation (Kelley & Keyes, SIAM J. Numer. Anal.
//! 35, 1998; Coffey, Kelley & Keyes 2003 for its use with Newton–Krylov):
//! when Newton's step finds no decrease of ‖F‖, or Newton's accepted
//! steps stop making progress, the next steps solve
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
//! While σ > 0 a step need not decrease ‖F‖ ([`PseudoTransientParams::accept_growth`]):
//! it is a step of a motion, not of a minimisation of ‖F‖.
//!
//! **Limit points.** Past a limit point of the equilibrium path (a shell
//! that buckles under a prescribed displacement) there is no equilibrium
//! near the last one: ‖F‖ has a local minimum there, where J is singular,
//! and Newton creeps towards it with steps cut to 10⁻³ of their length.
//! The way to the next equilibrium is the damped motion down the unstable
//! mode, along which the stiffness is *negative* and ‖F‖ first grows.
//! Two measures keep the continuation on that way:
//!
//! - σ stays above [`PseudoTransientParams::negative_curvature_margin`] ×
//!   the negative stiffness measured along the step, δᵀ(−J)δ / δᵀDδ
//!   (`curvature` of [`PseudoTransient::accepted`]): the shifted
//!   operator stays positive along the mode, and the step goes down it
//!   rather than, as Newton's, back up towards the limit point;
//! - σ is dropped for Newton only when it is small against a *positive*
//!   measured stiffness ([`PseudoTransientParams::newton_fraction`]), not
//!   merely small (near the limit point the stiffness is 10⁻⁵ of D).
//!
//! Measured on the concentric spheres (benchmark polyMesh), whose inner
//! sphere buckles at 5.8 mm: without them Newton crept at ‖F‖ = 9 × 10⁻⁴
//! with steps of 10⁻³–10⁻⁵ of their length, the continuation (switched on
//! only after failed line searches, then dropped at σ = 10⁻³ as the
//! residual fell) moved the shells 0.2–0.4 mm along the mode and handed
//! back to Newton, which went back; every cut-back down to 6 × 10⁻³ mm
//! failed likewise. With them the increment 5.8 → 5.9 mm takes 34 Newton
//! iterations: σ falling from its start, a dozen steps down the mode
//! (measured curvature −1 … −5 × 10⁻⁵, ‖F‖ rising from 2 × 10⁻⁴ to
//! 4 × 10⁻³), then Newton converges; the next increments take 5–7.

/// σ is at least multiplied by this after a full step.
const FULL_STEP_REDUCTION: f64 = 0.5;

/// Parameters of the continuation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PseudoTransientParams {
    /// σ when the continuation first switches on. Concentric spheres
    /// (coarse, generated mesh), the most Newton iterations in an
    /// increment: 42 from 1, 39 from 0.1, 34 from 0.01 (benchmark
    /// polyMesh: 35, 33, 33); the first steps only halve σ.
    pub initial: f64,
    /// Factor on σ at every further failure.
    pub growth: f64,
    /// Largest σ; a failure beyond it ends the solve.
    pub max: f64,
    /// σ below this fraction of `initial` is dropped (pure Newton), if it
    /// is also small against the stiffness along the step
    /// ([`Self::newton_fraction`]).
    pub drop_below: f64,
    /// Accepted Newton steps in a row without
    /// [`crate::line_search::STALL_PROGRESS`], one of them with a negative
    /// stiffness along itself, after which the continuation switches on
    /// as after a failed line search (0: only then) — where Newton creeps
    /// within `CONTINUATION_BAND` × the floor band of
    /// [`crate::NewtonParams`].
    /// Concentric spheres past buckling: Newton crept for 40 iterations
    /// at 9 × 10⁻⁴ with steps of 10⁻³ of their length, the line search
    /// never failing. Not farther out, nor without the negative
    /// stiffness: the curved beams' first increment on 5 × 100 cells
    /// (μ = 0.6; stalled at 3–13 × 10⁻², negative stiffness from friction
    /// now and then) was carried by the damped motion to an equilibrium
    /// without contact (F_x 0.002 or 0.2 N; its cut-back finds 2.09 N).
    pub stall_trigger: usize,
    /// While σ > 0 a step is accepted when its residual norm is at most
    /// this factor of the base point's (no decrease asked for: down an
    /// unstable mode ‖F‖ grows, 2 × 10⁻⁴ → 4 × 10⁻³ over a dozen steps on
    /// the concentric spheres); a larger one is halved.
    pub accept_growth: f64,
    /// σ is kept at least this many times −δᵀ(−J)δ / δᵀDδ when that is
    /// negative. 2 and 4 took the same 35 Newton iterations through the
    /// concentric spheres' buckling; without the bound (σ falling on as
    /// the residual fell) the shifted step turned back up the mode.
    pub negative_curvature_margin: f64,
    /// σ is dropped (Newton) only when also below this fraction of the
    /// measured δᵀ(−J)δ / δᵀDδ along the step: the shift then changes the
    /// step by less than it. Concentric spheres: at σ = 1.7 × 10⁻⁴, four
    /// times the stiffness along the step (4 × 10⁻⁵), Newton took over
    /// (below 10⁻³) and crept at 3 × 10⁻³ with steps of 4 % of their
    /// length. Not this alone: the shifted step, filtered of the soft
    /// modes, is stiff along itself (die drawing: 0.6 at σ = 0.1, the
    /// Newton step 10⁻⁷), and Newton took over after one step and crept
    /// to a floor 8 % off the force.
    pub newton_fraction: f64,
    /// When the continuation switches on again in the same solve, σ
    /// starts at this many times the σ it handed over to Newton at (at
    /// most `initial`) rather than at `initial`: the halvings from
    /// `initial` are spent once.
    pub reentry_factor: f64,
    /// A Newton step whose stiffness along itself (δᵀ(−J)δ / δᵀDδ, with
    /// its noise) is below this fraction of the stiffest Newton step of
    /// the solve, and which the line search had to shorten, is taken
    /// along a near-singular mode of J that the residual does not follow:
    /// it is refused and the continuation switches on at
    /// [`Self::soft_shift`] × that stiffest step (0: never, the default).
    /// At 10⁻² it took the concentric spheres' buckling from 98 Newton
    /// iterations to 43, but on the frictional curved beams the damped
    /// motion it starts wandered along the soft mode of the sliding
    /// contact (steps of 0.3–1.2 mm, ‖F‖ up tenfold) for up to 25
    /// iterations: off, with the faster rate abort and the regrowing
    /// sub-steps, μ = 0.3 needs at most 45 in an increment instead of
    /// 72, the spheres 42 instead of 36.
    pub soft_step: f64,
    /// See `soft_step`.
    pub soft_shift: f64,
    /// When a stalled Newton run switches the continuation on
    /// ([`Self::stall_trigger`]) having measured a negative stiffness κ
    /// along one of its steps, σ starts at this many times |κ| (at most
    /// `initial`) instead of at `initial`: the halvings from `initial`
    /// down to [`Self::negative_curvature_margin`] × |κ| are steps that
    /// barely move along the unstable mode. 0 (the default): start at
    /// `initial`. At 8 (one halving above the margin) the concentric
    /// spheres' second buckling at 8.3 mm (κ = −4 × 10⁻⁵) took 36 Newton
    /// iterations instead of 42, the curved beams and the die drawing on
    /// the coarse mesh unchanged; but the die-drawing validation tests
    /// failed (steady force spread 2.95 % over 2 %; the fine mesh inverted
    /// a cell at increment 49: stalls there measure κ ≈ −10⁻⁸, so σ
    /// started near 10⁻⁷, no damping at all). With the start held to at
    /// least `drop_below` × `initial` they passed, but the fine mesh took
    /// 312 s instead of 16. Off until a start that serves both is found.
    pub unstable_start: f64,
}

impl Default for PseudoTransientParams {
    fn default() -> Self {
        PseudoTransientParams {
            initial: 0.1,
            growth: 10.0,
            max: 1e4,
            drop_below: 1e-2,
            stall_trigger: 3,
            accept_growth: 2.0,
            negative_curvature_margin: 4.0,
            newton_fraction: 0.1,
            reentry_factor: 10.0,
            soft_step: 0.0,
            soft_shift: 0.1,
            unstable_start: 0.0,
        }
    }
}

/// The shift σ of one solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PseudoTransient {
    params: PseudoTransientParams,
    sigma: f64,
    /// σ when the continuation last handed over to Newton (0: never).
    handed_over: f64,
    /// Line-search failures rescued so far.
    pub rescues: usize,
}

impl PseudoTransient {
    /// Off (σ = 0).
    pub fn new(params: PseudoTransientParams) -> Self {
        PseudoTransient {
            params,
            sigma: 0.0,
            handed_over: 0.0,
            rescues: 0,
        }
    }

    /// The parameters.
    pub fn params(&self) -> &PseudoTransientParams {
        &self.params
    }

    /// The current shift (0: Newton).
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// After a failed line search or a stalled Newton: switches the
    /// continuation on or strengthens it; false when it is already at its
    /// largest.
    pub fn rescue(&mut self) -> bool {
        let next = if self.sigma > 0.0 {
            self.sigma * self.params.growth
        } else if self.handed_over > 0.0 {
            (self.handed_over * self.params.reentry_factor).min(self.params.initial)
        } else {
            self.params.initial
        };
        if !(next <= self.params.max) {
            return false;
        }
        self.sigma = next;
        self.rescues += 1;
        true
    }

    /// Switches the continuation on at `sigma` (or keeps a larger σ) after
    /// a soft Newton step ([`PseudoTransientParams::soft_step`]); false
    /// when `sigma` is not positive and finite or beyond the largest.
    pub fn rescue_at(&mut self, sigma: f64) -> bool {
        if !(sigma > 0.0 && sigma <= self.params.max) {
            return false;
        }
        self.sigma = self.sigma.max(sigma);
        self.rescues += 1;
        true
    }

    /// After a stalled Newton run that met the negative stiffness
    /// `curvature` (δᵀ(−J)δ / δᵀDδ < 0) along a step: switches the
    /// continuation on at [`PseudoTransientParams::unstable_start`] × its
    /// magnitude (at most `initial`), or as [`Self::rescue`] does when
    /// that is off, the stiffness is not negative, or σ is already on.
    pub fn rescue_unstable(&mut self, curvature: f64) -> bool {
        let start = (self.params.unstable_start * -curvature).min(self.params.initial);
        if self.sigma > 0.0 || !(start > 0.0) {
            return self.rescue();
        }
        self.rescue_at(start)
    }

    /// After an accepted step of length `lambda` from residual norm
    /// `before` to `after` (SER; at least halved after a full step), whose
    /// linear solve measured `curvature` = δᵀ(−J)δ / δᵀDδ along the step
    /// (NaN: not measured).
    pub fn accepted(&mut self, before: f64, after: f64, lambda: f64, curvature: f64) {
        if self.sigma == 0.0 || !(before > 0.0) {
            return;
        }
        let mut ratio = after / before;
        if lambda >= 1.0 {
            ratio = ratio.min(FULL_STEP_REDUCTION);
        }
        self.sigma = (self.sigma * ratio).min(self.params.max);
        if curvature < 0.0 {
            // down an unstable mode: never Newton
            self.sigma = self
                .sigma
                .max(self.params.negative_curvature_margin * -curvature);
            return;
        }
        let newton = self.sigma < self.params.drop_below * self.params.initial
            && !(self.sigma >= self.params.newton_fraction * curvature);
        if newton {
            self.handed_over = self.sigma;
            self.sigma = 0.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn switched_evolution_relaxation() {
        let mut p = PseudoTransient::new(PseudoTransientParams {
            initial: 1.0,
            ..Default::default()
        });
        assert_eq!(p.sigma(), 0.0);
        // nothing to relax while off
        p.accepted(1.0, 0.1, 1.0, f64::NAN);
        assert_eq!(p.sigma(), 0.0);
        assert!(p.rescue());
        assert_eq!(p.sigma(), 1.0);
        assert!(p.rescue());
        assert_eq!(p.sigma(), 10.0);
        // σ follows the residual after a shortened step
        p.accepted(1.0, 0.8, 0.5, f64::NAN);
        assert_eq!(p.sigma(), 8.0);
        // and at least halves after a full one
        p.accepted(1.0, 0.8, 1.0, f64::NAN);
        assert_eq!(p.sigma(), 4.0);
        p.accepted(1.0, 1e-4, 1.0, f64::NAN);
        // 4e-4 < 1e-2 × 1: back to Newton
        assert_eq!(p.sigma(), 0.0);
        assert_eq!(p.rescues, 2);
        // at its largest a failure ends the solve
        let mut q = PseudoTransient::new(PseudoTransientParams {
            initial: 1.0,
            max: 10.0,
            ..Default::default()
        });
        assert!(q.rescue() && q.rescue());
        assert!(!q.rescue());
    }

    #[test]
    fn a_soft_step_switches_the_shift_on_at_the_given_value() {
        let mut p = PseudoTransient::new(PseudoTransientParams::default());
        assert!(!p.rescue_at(0.0) && !p.rescue_at(f64::NAN) && !p.rescue_at(1e5));
        assert_eq!((p.sigma(), p.rescues), (0.0, 0));
        assert!(p.rescue_at(3e-4));
        assert_eq!((p.sigma(), p.rescues), (3e-4, 1));
        // a larger σ already on is kept
        assert!(p.rescue());
        assert!(p.rescue_at(1e-4));
        assert!((p.sigma() - 3e-3).abs() < 1e-15);
    }

    #[test]
    fn a_stall_on_an_unstable_mode_starts_the_shift_above_its_stiffness() {
        let on = PseudoTransientParams {
            unstable_start: 8.0,
            ..Default::default()
        };
        let mut p = PseudoTransient::new(on);
        // κ = −4e-5: σ = 8 × 4e-5, not the initial 0.1
        assert!(p.rescue_unstable(-4e-5));
        assert!((p.sigma() - 3.2e-4).abs() < 1e-18);
        // one halving reaches the margin (4 |κ|), which holds it
        p.accepted(1.0, 1.0, 1.0, -4e-5);
        p.accepted(1.0, 1.0, 1.0, -4e-5);
        p.accepted(1.0, 1.0, 1.0, -4e-5);
        assert!((p.sigma() - 1.6e-4).abs() < 1e-18);
        // a very negative stiffness starts at `initial` at most
        let mut q = PseudoTransient::new(on);
        assert!(q.rescue_unstable(-1.0));
        assert_eq!(q.sigma(), 0.1);
        // off, or no negative stiffness: as `rescue`
        let mut r = PseudoTransient::new(PseudoTransientParams {
            unstable_start: 0.0,
            ..Default::default()
        });
        assert!(r.rescue_unstable(-4e-5));
        assert_eq!(r.sigma(), 0.1);
        assert!(r.rescue_unstable(f64::NAN));
        assert!((r.sigma() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn measured_stiffness_keeps_the_shift_on_an_unstable_mode() {
        let mut p = PseudoTransient::new(PseudoTransientParams {
            initial: 1.0,
            ..Default::default()
        });
        assert!(p.rescue());
        // full steps halve σ, but not below 4 × the negative stiffness
        p.accepted(1.0, 1.5, 1.0, -0.1);
        assert_eq!(p.sigma(), 0.5);
        p.accepted(1.0, 1.5, 1.0, -0.2);
        assert_eq!(p.sigma(), 0.8);
        // far below drop_below, yet the stiffness along the step is negative
        for _ in 0..20 {
            p.accepted(1.0, 0.5, 1.0, -1e-6);
        }
        assert_eq!(p.sigma(), 4e-6);
        // a positive stiffness of 1e-5: σ = 2e-6 is not small against it
        p.accepted(1.0, 1.0, 1.0, 1e-5);
        assert_eq!(p.sigma(), 2e-6);
        // 1e-6 < 0.1 × 1e-4: Newton
        p.accepted(1.0, 1.0, 1.0, 1e-4);
        assert_eq!(p.sigma(), 0.0);
        // switched on again: 10 × the σ it handed over at
        assert!(p.rescue());
        assert!((p.sigma() - 1e-5).abs() < 1e-18);
        // small against a stiff step, but not small: kept
        let mut q = PseudoTransient::new(PseudoTransientParams {
            initial: 1.0,
            ..Default::default()
        });
        assert!(q.rescue());
        q.accepted(1.0, 0.5, 1.0, 100.0);
        assert_eq!(q.sigma(), 0.5);
    }
}
