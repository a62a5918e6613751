//! What Newton–Krylov needs of a discretised problem.

/// The residual could not be evaluated at this state (a cell inverted, a
/// non-finite value): the line search backtracks from it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct Inadmissible(pub String);

/// Whether a residual evaluation may renew the data that the Jacobian
/// products of a Newton step keep frozen (contact candidate pairs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Frozen {
    /// A new base point (start, line-search trial): renew them at `x`.
    Renew,
    /// A Jacobian product about the base point: keep them.
    Keep,
}

/// A nonlinear system F(x) = 0 of `len()` unknowns, with the frozen state
/// of the step (committed material state, friction history, multipliers)
/// inside the problem.
///
/// `residual` must be a function of `x` alone for a given frozen state: two
/// calls at the same `x` give the same bits. Nothing is carried from one
/// call to the next.
pub trait NonlinearProblem {
    /// Number of unknowns.
    fn len(&self) -> usize;

    /// Whether there are no unknowns.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// F(x) into `f`.
    fn residual(&mut self, x: &[f64], f: &mut [f64], frozen: Frozen) -> Result<(), Inadmissible>;

    /// The force (or other) scale the residual norm is judged against,
    /// of the last base point evaluated (`residual` with [`Frozen::Renew`]):
    /// converged when ‖F‖ ≤ tolerance × this.
    fn residual_reference(&self) -> f64;

    /// A residual norm the problem cannot resolve below (the round-off of
    /// its terms at rest): converged at the larger of this and tolerance ×
    /// [`Self::residual_reference`].
    fn roundoff_floor(&self) -> f64 {
        0.0
    }

    /// Typical size of an unknown, for the finite-difference step of the
    /// Jacobian products (`x` itself may be zero).
    fn typical_size(&self) -> f64;

    /// The pseudo-transient shift σ of the next linear solve (0: Newton),
    /// set before [`Self::prepare_preconditioner`]: the operator is then
    /// −J + σ D ([`Self::damping`]), and a preconditioner built from −J
    /// alone misses σ D exactly where the shift acts, along the soft modes
    /// of −J (there P⁻¹(−J + σD) has eigenvalues of order σ D / |λ|, and
    /// GMRES stalls). A problem that can should add σ D to what it
    /// factorises.
    fn set_shift(&mut self, _sigma: f64) {}

    /// Sets up the preconditioner about the base point `x` (after its
    /// residual was evaluated with [`Frozen::Renew`]). `last_krylov`: the
    /// Krylov iterations the previous Newton step's linear solve needed
    /// with the preconditioner it left (`None`: no step before, or it
    /// failed) — a problem whose preconditioner is costly to build may
    /// keep it while that is small, or change it when it is large.
    fn prepare_preconditioner(
        &mut self,
        x: &[f64],
        last_krylov: Option<usize>,
    ) -> Result<(), Inadmissible>;

    /// z = P⁻¹ r, P ≈ −J (the preconditioner approximates the *negative*
    /// Jacobian, as the segregated operator does: F(x + δ) ≈ F(x) − P δ).
    fn precondition(&mut self, r: &[f64], z: &mut [f64]);

    /// Whether [`Self::precondition`] is one fixed linear map from one
    /// [`Self::prepare_preconditioner`] to the next (a factorisation, a
    /// multigrid V-cycle), not an inner iterative solve to a tolerance.
    /// Then GMRES need not be flexible: x += M⁻¹ V y gives the iterate of
    /// x += Z y without keeping the preconditioned vectors Z (Saad 1993,
    /// §2), half the Krylov basis's memory.
    fn linear_preconditioner(&self) -> bool {
        false
    }

    /// How many constraints the last [`Frozen::Renew`] evaluation found
    /// active that were not at the one before it (contact faces that came
    /// into contact): a step that activates them crossed a kink of F that
    /// Newton's linear model could not see (0 for a smooth problem).
    fn changes_at_last_renewal(&self) -> usize {
        0
    }

    /// The longest fraction of the Newton step `dx` from the base point `x`
    /// the problem trusts its linear model for (1: all of it): the line
    /// search starts there. A problem whose residual turns sharply away
    /// from its linearisation a short way off (contact surfaces sliding
    /// over each other's facets) bounds how far one step may move them.
    fn step_limit(&self, _x: &[f64], _dx: &[f64]) -> f64 {
        1.0
    }

    /// `out = D v`, D a positive diagonal of the problem's stiffness scale
    /// per unknown (the pseudo-time term of [`crate::PseudoTransient`]);
    /// false when the problem has none (the continuation is then off).
    fn damping(&self, _v: &[f64], _out: &mut [f64]) -> bool {
        false
    }

    /// The last point evaluated with [`Frozen::Renew`] is the new base
    /// point of the iteration (the start, or a step the line search
    /// accepted).
    fn accept(&mut self) {}

    /// Components of the unknowns that are held fixed (their residual is
    /// zero by construction); `None` when all are free. Used only to keep
    /// the Krylov vectors clean.
    fn fixed(&self) -> Option<&[bool]> {
        None
    }
}
