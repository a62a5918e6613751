//! The seam between the time loop and the method that solves an
//! increment ([`fv_nonlinear::NonlinearMethod`]): the time loop — load
//! steps, cut-backs, force control, output, summary — is the same for
//! every method and calls it through [`NonlinearSolver`].
use std::ops::ControlFlow;

use crate::case::SolverSettings;
use crate::contact_coupling::ContactSet;
use crate::model::Body;
use crate::newton::NewtonKrylovSolver;
use crate::predictor::PathChange;
use crate::profile::PhaseTimes;
use crate::segregated::{IncrementInfo, SegregatedSolver, SolveError};
use fv_nonlinear::NonlinearMethod;

/// A method that solves the balance of one increment.
pub trait NonlinearSolver {
    /// Which method this is.
    fn method(&self) -> NonlinearMethod;

    /// Sets up what depends on the geometry and the material stiffness
    /// (the segregated matrices); called at the start, after every
    /// increment that moved the meshes and when the time step changes.
    fn prepare(&mut self, bodies: &[Body]) -> Result<(), SolveError>;

    /// The change of the prescribed values over the step the next
    /// [`Self::solve_increment`] solves, from `t0` to `t1` (predictor).
    fn set_step(&mut self, path: &PathChange, t0: f64, t1: f64);

    /// The attempts at the current increment that failed so far (0 for a
    /// new increment): the next attempt starts more cautiously.
    fn set_divergence_retries(&mut self, retries: u32);

    /// Whether the next attempt is the increment's last: no smaller step
    /// follows if it fails, so a method that gives up early on slow
    /// progress (to let a cut-back try) may iterate on instead.
    fn set_final_attempt(&mut self, _last: bool) {}

    /// Whether a failed attempt with explicitly coupled contacts would be
    /// redone with them coupled implicitly (thesis §4.5), so that a method
    /// may give up early on an explicit coupling that stalls.
    fn set_coupling_switch(&mut self, _available: bool) {}

    /// Solves one increment; on entry the bodies hold the converged state
    /// of the previous one and the conditions of this one, on exit the
    /// fields are those of the final iterate. `on_iteration` hears of every
    /// nonlinear iteration (number, residual); when it breaks, the attempt
    /// ends with [`SolveError::Interrupted`].
    fn solve_increment(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
        on_iteration: &mut dyn FnMut(usize, f64) -> ControlFlow<()>,
    ) -> Result<IncrementInfo, SolveError>;

    /// After a failed attempt was undone (`Body::restore_start`,
    /// `ContactSet::restore_start`): the fields that follow from the
    /// restored displacements — boundary values, gradients, stresses, the
    /// forces through the faces (the reactions), the contact surfaces and
    /// tractions — which the failed attempt left as its own. A failed run
    /// calls it before it writes the restored state as its last.
    fn refresh_restored(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
    ) -> Result<(), String>;

    /// Cells of all deformable bodies.
    fn n_unknowns(&self) -> usize;

    /// Seconds per phase so far.
    fn times(&self) -> PhaseTimes;

    /// Adds seconds to the phases (the time loop's own work).
    fn times_mut(&mut self) -> &mut PhaseTimes;

    /// What the method chose since the last call that the log should say
    /// (e.g. a preconditioner it switched to).
    fn take_notes(&mut self) -> Vec<String> {
        Vec::new()
    }

    /// Restart: what the method carries from one increment to the next
    /// (the segregated method's linear predictor; Newton–Krylov's choice
    /// of the assembled Jacobian as preconditioner).
    fn save_state(&self, _out: &mut fv_mesh::StateArrays) {}

    /// Restart: takes back what [`Self::save_state`] put (`bodies` as
    /// restored).
    fn restore_state(
        &mut self,
        _bodies: &[Body],
        _state: &fv_mesh::StateArrays,
    ) -> Result<(), String> {
        Ok(())
    }
}

/// The solver of `settings.nonlinear` for the bodies (whose contact
/// conditions the contact set prepared for that method:
/// [`prepare_contact_conditions`]).
pub fn build(
    bodies: &[Body],
    contacts: &ContactSet,
    settings: &SolverSettings,
) -> Box<dyn NonlinearSolver> {
    match settings.nonlinear {
        NonlinearMethod::Segregated => Box::new(SegregatedSolver::new(bodies, settings)),
        NonlinearMethod::NewtonKrylov => {
            Box::new(NewtonKrylovSolver::new(bodies, contacts, settings))
        }
    }
}

/// The contact patches' conditions for `method`: implicit couplings as
/// linearised conditions for the segregated method, every contact patch a
/// face-balance condition for Newton–Krylov.
pub fn prepare_contact_conditions(
    method: NonlinearMethod,
    contacts: &ContactSet,
    bodies: &mut [Body],
) {
    match method {
        NonlinearMethod::Segregated => contacts.prepare_conditions(bodies),
        NonlinearMethod::NewtonKrylov => contacts.prepare_state_conditions(bodies),
    }
}

impl NonlinearSolver for SegregatedSolver {
    fn method(&self) -> NonlinearMethod {
        NonlinearMethod::Segregated
    }

    fn take_notes(&mut self) -> Vec<String> {
        SegregatedSolver::take_notes(self)
    }

    fn prepare(&mut self, bodies: &[Body]) -> Result<(), SolveError> {
        let linear = self.linear_settings();
        self.assemble_and_factorise(bodies, &linear)
    }

    fn set_step(&mut self, path: &PathChange, t0: f64, t1: f64) {
        SegregatedSolver::set_step(self, path, t0, t1);
    }

    fn set_divergence_retries(&mut self, retries: u32) {
        SegregatedSolver::set_divergence_retries(self, retries);
    }

    fn set_coupling_switch(&mut self, available: bool) {
        SegregatedSolver::set_coupling_switch(self, available);
    }

    fn solve_increment(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
        on_iteration: &mut dyn FnMut(usize, f64) -> ControlFlow<()>,
    ) -> Result<IncrementInfo, SolveError> {
        SegregatedSolver::solve_increment(self, bodies, contacts, on_iteration)
    }

    fn refresh_restored(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
    ) -> Result<(), String> {
        contacts.evaluate_state(bodies, fv_nonlinear::Frozen::Renew)?;
        self.update_fields(bodies).map_err(|e| e.to_string())?;
        Ok(())
    }

    fn n_unknowns(&self) -> usize {
        SegregatedSolver::n_unknowns(self)
    }

    fn save_state(&self, out: &mut fv_mesh::StateArrays) {
        if let Some(p) = self.predictor() {
            p.save_state("solver/predictor", out);
        }
    }

    fn restore_state(
        &mut self,
        _bodies: &[Body],
        state: &fv_mesh::StateArrays,
    ) -> Result<(), String> {
        match self.predictor_mut() {
            Some(p) => p.restore_state("solver/predictor", state),
            None => Ok(()),
        }
    }

    fn times(&self) -> PhaseTimes {
        self.times
    }

    fn times_mut(&mut self) -> &mut PhaseTimes {
        &mut self.times
    }
}
