//! The first iterate of an increment's Newton solve.
use super::NewtonKrylovSolver;
use crate::contact_coupling::ContactSet;
use crate::model::Body;
use fv_nonlinear::{Frozen, NonlinearProblem};

/// Where an increment's Newton solve starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum FirstIterate {
    /// The linear response of the start state to the step
    /// ([`NewtonKrylovSolver::linear_predictor`]).
    Tangent,
    /// The last converged increment's change, scaled to this step
    /// ([`NewtonKrylovSolver::last_change_iterate`]).
    LastChange,
}

impl FirstIterate {
    /// For the log.
    pub(super) fn describe(self) -> &'static str {
        match self {
            FirstIterate::Tangent => "the linearised response to the step",
            FirstIterate::LastChange => "the last increment's change",
        }
    }

    /// The other one.
    pub(super) fn other(self) -> Self {
        match self {
            FirstIterate::Tangent => FirstIterate::LastChange,
            FirstIterate::LastChange => FirstIterate::Tangent,
        }
    }
}

/// The last converged increment's change of the state and its step, for
/// [`FirstIterate::LastChange`].
#[derive(Debug, Default)]
pub(super) struct LastChange {
    x: Vec<f64>,
    /// The step's length in time; zero before the first increment.
    dt: f64,
}

impl LastChange {
    /// Whether an increment has converged since the run (or its restart)
    /// began.
    pub(super) fn is_known(&self) -> bool {
        self.dt > 0.0
    }

    /// Keeps `x`, the change of a converged step of length `dt`.
    pub(super) fn record(&mut self, x: &[f64], dt: f64) {
        self.x.clear();
        self.x.extend_from_slice(x);
        self.dt = dt;
    }

    /// Restart: puts the change, its step and the first iterate that
    /// serves under `prefix` (nothing before the first record), so that a
    /// continued run starts its increments as the uninterrupted run does.
    pub(super) fn save_state(
        &self,
        prefix: &str,
        preferred: FirstIterate,
        out: &mut fv_mesh::StateArrays,
    ) {
        if !self.is_known() {
            return;
        }
        out.put_scalars(format!("{prefix}/change"), &self.x);
        out.put_scalar(format!("{prefix}/step"), self.dt);
        let last = f64::from(u8::from(preferred == FirstIterate::LastChange));
        out.put_scalar(format!("{prefix}/from_last_change"), last);
    }

    /// Restart: takes back [`Self::save_state`]'s record, if any, for a
    /// state of `n` unknowns; returns the first iterate that served.
    pub(super) fn restore_state(
        &mut self,
        prefix: &str,
        n: usize,
        s: &fv_mesh::StateArrays,
    ) -> Result<FirstIterate, String> {
        self.dt = 0.0;
        let change = format!("{prefix}/change");
        if !s.has(&change) {
            return Ok(FirstIterate::Tangent);
        }
        s.scalars_to_vec(&change, &mut self.x)?;
        if self.x.len() != n {
            return Err(format!(
                "{change}: {} values for a state of {n} unknowns",
                self.x.len()
            ));
        }
        self.dt = s.scalar(&format!("{prefix}/step"))?;
        Ok(if s.scalar(&format!("{prefix}/from_last_change"))? != 0.0 {
            FirstIterate::LastChange
        } else {
            FirstIterate::Tangent
        })
    }
}

/// The fraction of a step by which the conditions move to measure the
/// start state's response ([`NewtonKrylovSolver::linear_predictor`]).
const PREDICTOR_FRACTION: f64 = 1e-3;

/// Relative residual to which the first iterate of an increment with a
/// plastic body solves the tangent system, J x₀ = −∂F/∂t Δt, by GMRES
/// (the segregated operator preconditioning; the assembled Jacobian is the
/// tangent already). The segregated operator alone gives the harmonic
/// extension of the step, displacements without the Poisson contraction,
/// which throws the cells of a plastic body into states far from the
/// increment's: an 8³ block of the wire-drawing steel (E/H' = 380)
/// compressed by 1 % with free sides started at a relative residual of
/// 5.7e-2 from there and never converged, at any cut-back; from the
/// tangent's first iterate, 5.8e-3 and four Newton iterations.
const TANGENT_PREDICTOR_TOLERANCE: f64 = 1e-2;

/// Most Jacobian products of that solve.
const TANGENT_PREDICTOR_PRODUCTS: usize = 60;

/// How deep, in cells, [`NewtonKrylovSolver::contact_closing_translations`]
/// puts a floating body's nearest contact face.
const CLOSING_PENETRATION: f64 = 1e-2;

/// Halvings of a predicted first iterate that is not admissible before
/// the increment starts from its beginning instead.
const START_HALVINGS: usize = 6;

impl NewtonKrylovSolver {
    /// The first iterate into `self.x` (see [`FirstIterate`]), shortened
    /// until admissible, or zero (the start state).
    pub(super) fn first_iterate(
        &mut self,
        start: FirstIterate,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
    ) {
        if start == FirstIterate::LastChange && self.last_change_iterate() {
            self.admissible_start(bodies, contacts);
            return;
        }
        self.x.iter_mut().for_each(|v| *v = 0.0);
        let predicted = self.linear_predictor(bodies, contacts);
        let moved = self.rigidly_moved_bodies(bodies, contacts);
        let closed = self.contact_closing_translations(bodies, contacts);
        if predicted || moved || closed {
            self.admissible_start(bodies, contacts);
        }
    }

    /// The last converged increment's change scaled to this step, as the
    /// segregated method's `predictor` extrapolates: on a steady process
    /// (a wire drawn through a die) each increment repeats the last. False
    /// when none is known.
    fn last_change_iterate(&mut self) -> bool {
        let (t0, t1) = self.step_times;
        if !self.last_change.is_known() || !(t1 > t0) {
            return false;
        }
        let scale = (t1 - t0) / self.last_change.dt;
        for (x, v) in self.x.iter_mut().zip(&self.last_change.x) {
            *x = v * scale;
        }
        true
    }

    /// A body held by nothing but one rigid-motion patch, under the
    /// updated Lagrangian form and in no contact pair, starts moved by the
    /// step's rigid motion (`Body::sole_rigid_motion_step`), as the
    /// segregated method starts it: the linear predictor of a rotation is
    /// a stretch (4.5 % at 0.3 rad), which yields an elastoplastic bar, and
    /// Newton wandered among its plastic-hinge equilibria. True when a
    /// body was moved.
    fn rigidly_moved_bodies(&mut self, bodies: &[Body], contacts: &ContactSet) -> bool {
        let (t0, t1) = self.step_times;
        let mut moved = false;
        for (bi, b) in bodies.iter().enumerate() {
            if b.rigid || !b.momentum.law.is_updated_lagrangian() || contacts.involves(bi) {
                continue;
            }
            let Some((q, c)) = b.sole_rigid_motion_step(t0, t1) else {
                continue;
            };
            let motion = |x: &fv_mesh::Vector| q * x + c - x;
            for (i, x) in b.geom.cell_centres.iter().enumerate() {
                let k = 3 * (b.offset + i);
                self.x[k..k + 3].copy_from_slice(motion(x).as_slice());
            }
            let ni = b.mesh.n_internal_faces();
            for (bf, node) in self.layout.faces_of(bi) {
                let k = 3 * node;
                self.x[k..k + 3].copy_from_slice(motion(&b.geom.face_centres[ni + bf]).as_slice());
            }
            moved = true;
        }
        moved
    }

    /// A body that nothing but contact holds, loaded by tractions or
    /// pressures and with every contact face open, has no stiffness along
    /// its load in the Jacobian: Newton's first direction threw a Hertz
    /// cylinder under a pressure 2.3 m off, and it never came back. Such a
    /// body starts translated rigidly along its load until its nearest
    /// contact face is [`CLOSING_PENETRATION`] of a cell deep, where the
    /// contact holds it (docs/newton-krylov.md, "Known limits"). Only when
    /// the body's conditions allow that translation (symmetry planes
    /// along it, no kinematic condition) and the analysis is static (no
    /// inertia). True when a body was moved.
    fn contact_closing_translations(&mut self, bodies: &[Body], contacts: &ContactSet) -> bool {
        use crate::case::BoundarySpec as B;
        let t1 = self.step_times.1;
        let mut moved = false;
        for (bi, b) in bodies.iter().enumerate() {
            // inertia holds a dynamic body: it must not jump into contact
            if b.rigid || b.momentum.inertia.is_some() || !contacts.involves(bi) {
                continue;
            }
            let mut load = fv_mesh::Vector::zeros();
            let mut planes = Vec::new();
            let mut free = true;
            for (p, spec) in b.patch_specs.iter().enumerate() {
                let faces = b.mesh.patches[p].faces();
                match spec {
                    None | Some(B::Empty) | Some(B::Wedge) => {}
                    Some(B::Symmetry) => {
                        planes.extend(faces.take(1).map(|f| b.geom.face_normal(f)))
                    }
                    Some(B::Traction { value }) => {
                        let area: f64 = faces.map(|f| b.geom.face_mag(f)).sum();
                        load += fv_mesh::Vector::from(value.at(t1)) * area;
                    }
                    Some(B::Pressure { value }) => {
                        let p = value.at(t1);
                        for f in faces {
                            load -= b.geom.face_normal(f) * (p * b.geom.face_mag(f));
                        }
                    }
                    Some(_) => free = false,
                }
            }
            let Some(d) = load.try_normalize(0.0) else {
                continue;
            };
            if !free || planes.iter().any(|n| n.dot(&d).abs() > 1e-6) {
                continue;
            }
            // the distance along d to the nearest contact face, all open
            let mut reach = f64::INFINITY;
            let mut open = true;
            for c in contacts.interfaces.iter() {
                for (side, gaps) in [
                    (&c.slave, &c.tractions.slave.gap),
                    (&c.master, &c.tractions.master.gap),
                ] {
                    if side.body != bi {
                        continue;
                    }
                    for (i, &g) in gaps.iter().enumerate() {
                        if !g.is_finite() {
                            continue;
                        }
                        if g <= 0.0 {
                            open = false;
                        }
                        let closing = side.surface.face_normals.get(i).map_or(0.0, |n| n.dot(&d));
                        if closing > 0.1 {
                            reach = reach.min(g / closing);
                        }
                    }
                }
            }
            if !open || !reach.is_finite() {
                continue;
            }
            let shift = d * (reach + CLOSING_PENETRATION * self.cell_size);
            for i in 0..b.mesh.n_cells {
                let k = 3 * (b.offset + i);
                self.x[k..k + 3].copy_from_slice(shift.as_slice());
            }
            for (_, node) in self.layout.faces_of(bi) {
                let k = 3 * node;
                self.x[k..k + 3].copy_from_slice(shift.as_slice());
            }
            moved = true;
        }
        moved
    }

    /// The linear response of the start state to the step of the
    /// prescribed values and loads, as finite-element codes take the first
    /// iterate, x₀ = −J⁻¹ ∂F/∂t Δt: the residual's change at the start
    /// state when the conditions move by the fraction
    /// [`PREDICTOR_FRACTION`] of the step, divided by it, solved with the
    /// preconditioner assembled at the start (the segregated operator: the
    /// harmonic extension of the step; the assembled Jacobian: the tangent
    /// step), the contact springs of the start included. What the step
    /// prescribes enters through the start's tangent, not as a jump of the
    /// prescribed faces away from their cells: from x = 0 the whole step
    /// sits in the half cells by those faces, whose points the jump can
    /// throw far into a plastic or inverted state (curved beams: Newton
    /// steps of tens of millimetres, and no convergence, from there).
    /// False when a stage fails or nothing moves.
    fn linear_predictor(&mut self, bodies: &mut [Body], contacts: &mut ContactSet) -> bool {
        let (t0, t1) = self.step_times;
        if !(t1 > t0) {
            return false;
        }
        let th = t0 + PREDICTOR_FRACTION * (t1 - t0);
        let n = self.x.len();
        let zero = vec![0.0; n];
        let mut f0 = vec![0.0; n];
        let mut fh = vec![0.0; n];
        conditions_at(bodies, t0);
        let ok = {
            let mut problem = self.problem(bodies, contacts);
            problem.residual(&zero, &mut f0, Frozen::Renew).is_ok()
                && problem.prepare_preconditioner(&zero, None).is_ok()
        };
        // The Jacobian products do not see a contact face that touches
        // without pressure (a one-sided penalty has no derivative at zero
        // gap); the preconditioners give it its spring. Where the step's
        // first fraction presses every such face, the tangent is taken
        // there (conditions at th), where their springs act both ways: a
        // J2 bar meshed touching a rigid platen, upset 30 % in ten steps,
        // converged to a non-uniform state (pressure 114–916, σ_xx ±300)
        // from the preconditioner's step. Where a face still touches
        // without pressure there, the preconditioner's step serves: a J2
        // block meshed touching two rigid plates, squeezed 1 % in one
        // step, was free along the squeeze in the tangent solve, started
        // 0.09 down where the plate moves 0.01, and Newton converged to a
        // curled state; from the preconditioner's step, 8 iterations to
        // the uniform one.
        let touching_at_start = contacts.any_touching_without_pressure(bodies);
        conditions_at(bodies, th);
        let ok = ok && {
            let mut problem = self.problem(bodies, contacts);
            problem.residual(&zero, &mut fh, Frozen::Keep).is_ok()
        };
        let touching = contacts.any_touching_without_pressure(bodies);
        // the tangent at the start is that of the conditions at t0, or at
        // th where the step presses the faces that touched
        let (tangent_time, base) = if touching_at_start {
            (th, &fh)
        } else {
            (t0, &f0)
        };
        conditions_at(bodies, tangent_time);
        let rhs: Vec<f64> = fh
            .iter()
            .zip(&f0)
            .map(|(a, b)| (a - b) / PREDICTOR_FRACTION)
            .collect();
        let mut x0 = vec![0.0; n];
        let plastic = bodies
            .iter()
            .any(|b| !b.rigid && b.momentum.law.plastic_strain().is_some());
        let ok = ok && {
            let (newton, mut problem) = self.newton_and_problem(bodies, contacts);
            problem.precondition(&rhs, &mut x0);
            // the tangent itself where a body is plastic (see
            // TANGENT_PREDICTOR_TOLERANCE) and no contact face touches
            // without pressure; a failed solve keeps the preconditioner's
            // step
            if plastic && !problem.linear_preconditioner_is_tangent() && !touching {
                let mut y = x0.clone();
                let solved = newton.tangent_solve(
                    &mut problem,
                    &zero,
                    base,
                    &rhs,
                    &mut y,
                    TANGENT_PREDICTOR_TOLERANCE,
                    TANGENT_PREDICTOR_PRODUCTS,
                );
                if solved.is_ok() && y.iter().all(|v| v.is_finite()) {
                    x0 = y;
                }
            }
            true
        };
        conditions_at(bodies, t1);
        if !ok {
            return false;
        }
        if !x0.iter().all(|v| v.is_finite()) || x0.iter().all(|v| *v == 0.0) {
            return false;
        }
        self.x.copy_from_slice(&x0);
        true
    }

    /// Shortens the predicted first iterate until the residual can be
    /// evaluated there — no cell or face point inverted, no contact face
    /// deeper than the penetration a step may add to the start's — by
    /// halves, [`START_HALVINGS`] times, then zero.
    fn admissible_start(&mut self, bodies: &mut [Body], contacts: &mut ContactSet) {
        let x0 = self.x.clone();
        let mut f = vec![0.0; x0.len()];
        let zero = vec![0.0; x0.len()];
        let mut x = x0.clone();
        let mut accepted = false;
        {
            let mut problem = self.problem(bodies, contacts);
            // the start state is the reference of the penetration a
            // first iterate may add
            if problem.residual(&zero, &mut f, Frozen::Renew).is_ok() {
                problem.accept();
            }
            let mut scale = 1.0;
            for _ in 0..=START_HALVINGS {
                for (x, v) in x.iter_mut().zip(&x0) {
                    *x = v * scale;
                }
                let r = problem.residual(&x, &mut f, Frozen::Renew);
                if r.is_ok() {
                    accepted = true;
                    break;
                }
                scale *= 0.5;
            }
        }
        if accepted {
            self.x.copy_from_slice(&x);
        } else {
            self.x.iter_mut().for_each(|v| *v = 0.0);
        }
    }
}

/// The bodies' conditions at time `t`, with the elimination of their
/// kinematic faces (`SolidMomentum::prepare_state_function`), which holds
/// the prescribed part of `normal-displacement` and
/// `tangential-displacement` faces: refreshing the conditions alone moved
/// only the `displacement` faces, so the first iterate ignored a step of
/// those conditions, and a thick sphere inflated by 50 % of its inner
/// radius in two steps failed at every cut-back with the start state
/// judged at the end of the step.
fn conditions_at(bodies: &mut [Body], t: f64) {
    for b in bodies.iter_mut() {
        b.refresh_conditions(t);
        if !b.rigid {
            b.momentum.prepare_state_function(&b.mesh, &b.geom);
        }
    }
}
