//! The discretised balance of every deformable body, with the contact
//! tractions, as a function of the state x — the increment of the cell
//! displacements and of the traction-type faces' values over the step
//! ([`StateLayout`]). This is the F(x) of Newton's method: the same faces,
//! Rhie–Chow term, boundary conditions and contact tractions as the
//! segregated method, with the boundary values and contact tractions
//! computed from x inside the call.
use super::jacobian::{AssembledJacobian, JacobianFactor};
use super::layout::StateLayout;
use super::preconditioning::JACOBIAN_REUSE_KRYLOV;
use super::segregated_operator::SegregatedOperator;
use super::step_limit::contact_step_limit;
use crate::contact_coupling::ContactSet;
use crate::model::Body;
use crate::profile::{Phase, PhaseTimes};
use fv_discretise::MomentumParams;
use fv_mesh::Vector;
use fv_nonlinear::{Frozen, Inadmissible, NonlinearProblem};
use std::time::Instant;

/// A step may deepen the deepest contact penetration to this fraction of
/// the face's cell height, or to [`PENETRATION_GROWTH`] times the
/// penetration of the point it starts from if that is more; a trial point
/// beyond is refused and the line search shortens the step. A penalty
/// traction is a model of contact for penetrations small against the
/// cells: a Newton step that ignores a contact it has not met yet can move
/// a surface into the other body by a large part of a cell, where the
/// pairs and the direction of their normals no longer describe the
/// contact, and the iteration wandered (curved beams: steps of tens of
/// millimetres from a state 0.5 mm through the other beam). The start of an
/// increment is not refused: a rigid body moved by its prescribed motion
/// can put it deep into the other surface. A full cell rather than half:
/// the linear predictor of the curved beams' first touch reaches 0.76 of
/// a cell, and the start halved to stay within half a cell needed 14
/// Newton iterations against 7 from the full prediction.
const PENETRATION_LIMIT: f64 = 1.0;
/// See [`PENETRATION_LIMIT`].
const PENETRATION_GROWTH: f64 = 1.5;

/// Newton steps in a row whose Krylov solves, preconditioned by the ILU(0)
/// of the assembled Jacobian, use all their iterations before `"auto"`
/// factorises the Jacobian exactly. A tetrahedral cantilever (3,609 cells)
/// stalls at every step (the linear residual 0.6–1.0 after 200 Krylov
/// iterations: the incomplete factor misses the bending) and needs the LU;
/// the coarse wire drawing in plastic flow reached the limit once in a
/// failed attempt (0.13 against a forcing term of 0.1) and ran on well
/// with the ILU(0).
pub const ILU_STALLS_BEFORE_LU: usize = 2;

/// Newton steps in a row whose Krylov solves, preconditioned by the LU of
/// the assembled Jacobian with the contact springs, need more than
/// [`SPRING_KRYLOV`] iterations before the contact block becomes the
/// derivative of the contact forces
/// ([`AssembledJacobian::use_contact_derivative`]), for the rest of the
/// run. With an exact block the LU's solves take one to five iterations;
/// the springs' took 2–7 at the die's penalty scale 1 (more than 10 in
/// 6 % of the steps, rarely in a row) and 8–17 at 100.
pub const SPRING_STALLS: usize = 3;
/// See [`SPRING_STALLS`].
pub const SPRING_KRYLOV: usize = 10;

/// The Jacobian factorised by ILU(0) is kept for the next Newton step
/// while the last linear solve needed at most this many Krylov iterations
/// (the LU: [`JACOBIAN_REUSE_KRYLOV`]). Its solves take 10–40 iterations
/// where the LU's take a few, and most of its cost is the assembly of the
/// blocks, not the factorisation. Measured with 15 / 60, one thread:
/// sphere on a block at ε_n/E = 1000 7.0 / 5.3 s (17 Newton iterations
/// both, 513 / 492 Krylov), coarse wire drawing with the flow share of the
/// Rhie–Chow term 92 / 71 s (steady force 290.82 / 290.83 N).
pub const ILU_REUSE_KRYLOV: usize = 60;

/// The force scale is at least this fraction of Σ K |Γ| over the bodies'
/// boundary faces (a state at rest, with nothing loaded).
const REFERENCE_FLOOR: f64 = 1e-12;

/// A residual norm below this fraction of Σ K |Γ| is converged whatever
/// the tolerance: the round-off of the face forces of a body at rest. A
/// stress-free elastoplastic bar turned rigidly by 90° in ten increments
/// stalled at ‖F‖ ≈ 2e-5 of its (round-off) force scale with Newton steps
/// of 1e-15, below what doubles resolve, against a tolerance of 1e-9.
const ROUNDOFF_FLOOR: f64 = 1e-13;

/// Workspaces of the residual, kept across increments.
#[derive(Debug, Default)]
pub struct ResidualWork {
    /// Per body, the face rows of its boundary faces.
    face_rows: Vec<Vec<Vector>>,
    /// The state at the start of the increment (cells' u, faces' u_b).
    pub start: Vec<f64>,
    /// The force scale of the increment's first evaluation (0 before it).
    start_scale: f64,
    /// Per node, the stiffness scale D of the pseudo-transient
    /// continuation (`NonlinearProblem::damping`).
    damping: Vec<f64>,
}

impl ResidualWork {
    /// Sized for `bodies`.
    pub fn new(bodies: &[Body], layout: &StateLayout) -> Self {
        ResidualWork {
            face_rows: bodies
                .iter()
                .map(|b| {
                    if b.rigid {
                        Vec::new()
                    } else {
                        vec![Vector::zeros(); b.mesh.n_faces() - b.mesh.n_internal_faces()]
                    }
                })
                .collect(),
            start: vec![0.0; layout.len()],
            start_scale: 0.0,
            damping: vec![0.0; layout.n_nodes],
        }
    }

    /// Records the bodies' current values as the start of the increment.
    pub fn record_start(&mut self, bodies: &[Body], layout: &StateLayout) {
        self.start_scale = 0.0;
        for b in bodies.iter().filter(|b| !b.rigid) {
            for (i, u) in b.momentum.u.iter().enumerate() {
                let k = 3 * (b.offset + i);
                self.start[k..k + 3].copy_from_slice(u.as_slice());
            }
        }
        for (node, &(bi, bf)) in layout.face_of_node.iter().enumerate() {
            let u = bodies[bi as usize].momentum.u_b[bf as usize];
            let k = 3 * (layout.n_cells + node);
            self.start[k..k + 3].copy_from_slice(u.as_slice());
        }
        self.record_damping(bodies, layout);
    }

    /// The diagonal of the segregated operator per node (eq. 3.29 with the
    /// boundary coefficients of eq. 3.19): Σ K |Γ| / |d| over a cell's
    /// faces, K |Γ| / d_n for a face node.
    fn record_damping(&mut self, bodies: &[Body], layout: &StateLayout) {
        self.damping.iter_mut().for_each(|d| *d = 0.0);
        for (bi, b) in bodies.iter().enumerate().filter(|(_, b)| !b.rigid) {
            let k = b.momentum.k;
            let ni = b.mesh.n_internal_faces();
            for f in 0..ni {
                let a = k * b.geom.face_mag(f) / b.geom.delta(&b.mesh, f).norm();
                self.damping[b.offset + b.mesh.owner[f] as usize] += a;
                self.damping[b.offset + b.mesh.neighbour[f] as usize] += a;
            }
            for f in ni..b.mesh.n_faces() {
                let a = k * b.geom.face_mag(f) / b.momentum.normal_distance(f);
                if !a.is_finite() {
                    continue;
                }
                self.damping[b.offset + b.mesh.owner[f] as usize] += a;
                if let Some(node) = layout.face_node(bi, f - ni) {
                    self.damping[node] = a;
                }
            }
        }
    }
}

/// F(x) of the model for [`fv_nonlinear::NewtonKrylov`].
pub struct ModelProblem<'a> {
    /// The bodies (their fields hold the last evaluated state).
    pub bodies: &'a mut [Body],
    /// The contact pairs.
    pub contacts: &'a mut ContactSet,
    /// Numbering of the unknowns.
    pub layout: &'a StateLayout,
    /// Discretisation parameters.
    pub params: MomentumParams,
    /// Workspaces and the start of the increment.
    pub work: &'a mut ResidualWork,
    /// The segregated operator with the contact springs (the
    /// preconditioner when there is no assembled Jacobian).
    pub preconditioner: &'a mut SegregatedOperator,
    /// The assembled Jacobian, when it preconditions.
    pub jacobian: &'a mut Option<AssembledJacobian>,
    /// `"auto"`: a Newton step whose linear solve needed more Krylov
    /// iterations than this makes the assembled Jacobian precondition from
    /// the next step on (`None`: never).
    pub switch_after: Option<usize>,
    /// How the Jacobian switched to is factorised.
    pub switch_factor: JacobianFactor,
    /// The Krylov iterations that made it switch, if it did.
    pub switched: Option<usize>,
    /// `"auto"`: [`ILU_STALLS_BEFORE_LU`] Newton steps in a row whose
    /// linear solves needed more Krylov iterations than this with the
    /// ILU(0) of the assembled Jacobian make its LU precondition from the
    /// next step on (`None`: never).
    pub exact_after: Option<usize>,
    /// Consecutive Newton steps beyond `exact_after` with the ILU(0).
    pub ilu_stalls: usize,
    /// The Krylov iterations that made it factorise exactly, if it did.
    pub made_exact: Option<usize>,
    /// Seconds per phase.
    pub times: &'a mut PhaseTimes,
    /// Force scale of the last renewed evaluation.
    pub reference: f64,
    /// Contact faces that changed state at the last renewal.
    pub changes: usize,
    /// Mean distance between neighbouring cell centres: the typical size of
    /// an unknown for the finite-difference step of the Jacobian products,
    /// whose perturbation is then √ε × this per unknown where the state is
    /// zero, a strain of √ε — large against the round-off of the stresses
    /// (a strain of ε), small against any nonlinearity. (A fraction of the
    /// bodies' extent instead, 1e-6, gave strains of 1e-12 on a slender
    /// beam, whose products then carried 1e-4 relative noise, and Newton
    /// steps solved to 1e-10 reduced the residual by 12 % only.)
    pub cell_size: f64,
    /// Σ K |Γ| over the bodies' boundary faces ([`stiffness_area`]).
    pub stiffness_area: f64,
    /// Residual evaluations made.
    pub evaluations: usize,
    /// Why the last evaluation was refused, if it was.
    pub last_refusal: Option<String>,
    /// The pseudo-transient shift σ of the next linear solve
    /// (`NonlinearProblem::set_shift`).
    pub shift: f64,
    /// `linear.preconditioner = "jacobian"`: the assembled Jacobian
    /// factorises the continuation's operator −J + σ D, and its contact
    /// block becomes the derivative of the contact forces once the
    /// springs stall ([`SPRING_STALLS`]). Not under `"auto"`: there the
    /// two, measured on the validation suite, cost two asserted figures
    /// (docs/newton-krylov.md, "Contact derivative").
    pub exact_contact: bool,
    /// Deepest contact penetration (fraction of the cell height) of the
    /// last renewal, and of the accepted base point (`None` before the
    /// first).
    pub penetration: (f64, Option<f64>),
    /// Whether the assembled Jacobian was assembled at a state of this
    /// attempt. With the derivative of the contact forces as its contact
    /// block it is not kept from the last increment or attempt: that is
    /// the derivative where the faces were, and the step moved them in and
    /// out of contact (die drawing, augmented: 19–29 Krylov iterations per
    /// first Newton step with the old block, 1–5 with a fresh one).
    pub jacobian_of_this_attempt: bool,
    /// Consecutive Newton steps beyond [`SPRING_KRYLOV`] with the LU of
    /// the springs' Jacobian.
    pub spring_stalls: usize,
    /// The Krylov iterations that made the contact block the derivative,
    /// if they did.
    pub made_contact_derivative: Option<usize>,
}

/// Mean distance between neighbouring cell centres of the deformable bodies.
pub fn mean_cell_size(bodies: &[Body]) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for b in bodies.iter().filter(|b| !b.rigid) {
        for f in 0..b.mesh.n_internal_faces() {
            sum += b.geom.delta(&b.mesh, f).norm();
            n += 1;
        }
    }
    if n > 0 {
        sum / n as f64
    } else {
        1.0
    }
}

/// Σ K |Γ| over the boundary faces of the deformable bodies: the force
/// scale of a unit strain, of which [`REFERENCE_FLOOR`] is the smallest
/// residual reference and [`ROUNDOFF_FLOOR`] the round-off.
pub fn stiffness_area(bodies: &[Body]) -> f64 {
    let mut s = 0.0;
    for b in bodies.iter().filter(|b| !b.rigid) {
        let ni = b.mesh.n_internal_faces();
        let area: f64 = b.geom.face_areas[ni..].iter().map(|a| a.norm()).sum();
        s += b.momentum.k * area;
    }
    s
}

impl ModelProblem<'_> {
    /// Whether the assembled Jacobian, the tangent itself, preconditions.
    pub fn linear_preconditioner_is_tangent(&self) -> bool {
        self.jacobian.is_some()
    }

    /// Sets the bodies' unknown fields to the start plus `x`.
    fn scatter(&mut self, x: &[f64]) {
        let start = &self.work.start;
        for b in self.bodies.iter_mut().filter(|b| !b.rigid) {
            for (i, u) in b.momentum.u.iter_mut().enumerate() {
                let k = 3 * (b.offset + i);
                *u = Vector::new(
                    start[k] + x[k],
                    start[k + 1] + x[k + 1],
                    start[k + 2] + x[k + 2],
                );
            }
        }
        for (node, &(bi, bf)) in self.layout.face_of_node.iter().enumerate() {
            let k = 3 * (self.layout.n_cells + node);
            self.bodies[bi as usize].momentum.u_b[bf as usize] = Vector::new(
                start[k] + x[k],
                start[k + 1] + x[k + 1],
                start[k + 2] + x[k + 2],
            );
        }
    }

    fn evaluate(&mut self, x: &[f64], f: &mut [f64], frozen: Frozen) -> Result<(), Inadmissible> {
        self.evaluations += 1;
        let t0 = Instant::now();
        self.scatter(x);
        for b in self.bodies.iter_mut().filter(|b| !b.rigid) {
            b.momentum
                .boundary_values_and_gradient_of_state(&b.mesh, &b.geom);
            b.measure_loaded_faces();
        }
        let t1 = self.times.lap(Phase::BoundaryValues, t0);
        for b in self.bodies.iter_mut().filter(|b| !b.rigid) {
            b.momentum.take_inverted_face_point();
            if let Some((cell, jacobian)) = b.momentum.update_stress() {
                return Err(Inadmissible(format!(
                    "body '{}': cell {cell}: relative Jacobian det f = {jacobian:.3e} is not positive",
                    b.name
                )));
            }
        }
        self.times.lap(Phase::GradientAndStress, t1);
        if !self.contacts.is_empty() {
            let changes = self
                .contacts
                .evaluate_state(self.bodies, frozen)
                .map_err(Inadmissible)?;
            if frozen == Frozen::Renew {
                self.changes = changes;
                let deepest = self.contacts.deepest_penetration();
                self.penetration.0 = deepest;
                if let Some(base) = self.penetration.1 {
                    let allowed = PENETRATION_LIMIT.max(PENETRATION_GROWTH * base);
                    if deepest > allowed {
                        return Err(Inadmissible(format!(
                            "a contact face penetrates the other surface by {deepest:.3} of its cell's height, more than the step may deepen it to ({allowed:.3})"
                        )));
                    }
                }
            }
        }
        let t2 = Instant::now();
        let mut scale2 = 0.0;
        for (b, rows) in self.bodies.iter_mut().zip(self.work.face_rows.iter_mut()) {
            if b.rigid {
                continue;
            }
            scale2 +=
                b.momentum
                    .compute_residual_with_face_rows(&b.mesh, &b.geom, &self.params, rows);
            // a boundary face whose own gradient inverts its point: the
            // segregated iteration passes through such states with the
            // cell's stress, the state function refuses them (beyond the
            // crossing the face force grows like 1 / distance)
            if let Some(cell) = b.momentum.take_inverted_face_point() {
                return Err(Inadmissible(format!(
                    "body '{}': the gradient of a boundary face of cell {cell} inverts its point",
                    b.name
                )));
            }
        }
        // gather: cells, then face rows; unsolved components are zero
        let unsolved = self.layout.unsolved;
        for b in self.bodies.iter().filter(|b| !b.rigid) {
            for (i, r) in b.momentum.residual.iter().enumerate() {
                let k = 3 * (b.offset + i);
                f[k..k + 3].copy_from_slice(r.as_slice());
            }
        }
        for (node, &(bi, bf)) in self.layout.face_of_node.iter().enumerate() {
            let k = 3 * (self.layout.n_cells + node);
            let r = self.work.face_rows[bi as usize][bf as usize];
            f[k..k + 3].copy_from_slice(r.as_slice());
        }
        for (c, &off) in unsolved.iter().enumerate() {
            if off {
                f.iter_mut().skip(c).step_by(3).for_each(|v| *v = 0.0);
            }
        }
        self.times.lap(Phase::ResidualAssembly, t2);
        if !f.iter().all(|v| v.is_finite()) {
            return Err(Inadmissible("the residual is not finite".into()));
        }
        if frozen == Frozen::Renew {
            // the forces the cells balance now, or, if larger, at the
            // increment's first iterate: a state near equilibrium with no
            // stress (a rigid translation) balances no forces, and the
            // imbalance the increment started from is its scale
            let scale = scale2.sqrt();
            if self.work.start_scale == 0.0 {
                self.work.start_scale = scale;
            }
            self.reference = scale
                .max(self.work.start_scale)
                .max(REFERENCE_FLOOR * self.stiffness_area);
        }
        Ok(())
    }
}

impl NonlinearProblem for ModelProblem<'_> {
    fn len(&self) -> usize {
        self.layout.len()
    }

    fn residual(&mut self, x: &[f64], f: &mut [f64], frozen: Frozen) -> Result<(), Inadmissible> {
        let r = self.evaluate(x, f, frozen);
        if let Err(e) = &r {
            self.last_refusal = Some(e.0.clone());
        }
        r
    }

    fn residual_reference(&self) -> f64 {
        self.reference
    }

    fn typical_size(&self) -> f64 {
        self.cell_size
    }

    fn damping(&self, v: &[f64], out: &mut [f64]) -> bool {
        for ((o, v), d) in out
            .chunks_exact_mut(3)
            .zip(v.chunks_exact(3))
            .zip(&self.work.damping)
        {
            for c in 0..3 {
                o[c] = d * v[c];
            }
        }
        true
    }

    fn roundoff_floor(&self) -> f64 {
        ROUNDOFF_FLOOR * self.stiffness_area
    }

    fn changes_at_last_renewal(&self) -> usize {
        self.changes
    }

    fn step_limit(&self, _x: &[f64], dx: &[f64]) -> f64 {
        contact_step_limit(self.bodies, self.contacts, self.layout, dx)
    }

    fn set_shift(&mut self, sigma: f64) {
        self.shift = sigma;
    }

    fn accept(&mut self) {
        self.penetration.1 = Some(self.penetration.0);
    }

    fn prepare_preconditioner(
        &mut self,
        _x: &[f64],
        last_krylov: Option<usize>,
    ) -> Result<(), Inadmissible> {
        let t = Instant::now();
        if let (None, Some(limit), Some(k)) =
            (self.jacobian.as_ref(), self.switch_after, last_krylov)
        {
            if k > limit {
                *self.jacobian = Some(AssembledJacobian::new(
                    self.bodies,
                    self.layout,
                    self.switch_factor,
                ));
                self.switched = Some(k);
            }
        }
        if let (Some(j), Some(limit), Some(k)) =
            (self.jacobian.as_mut(), self.exact_after, last_krylov)
        {
            if j.kind() == JacobianFactor::Ilu0 {
                self.ilu_stalls = if k > limit { self.ilu_stalls + 1 } else { 0 };
                if self.ilu_stalls >= ILU_STALLS_BEFORE_LU {
                    j.refactor_as(JacobianFactor::Lu);
                    self.made_exact = Some(k);
                }
            }
        }
        if let (Some(j), Some(k)) = (self.jacobian.as_mut(), last_krylov) {
            if self.exact_contact
                && !self.contacts.is_empty()
                && j.kind() == JacobianFactor::Lu
                && !j.contact_derivative()
            {
                self.spring_stalls = if k > SPRING_KRYLOV {
                    self.spring_stalls + 1
                } else {
                    0
                };
                if self.spring_stalls >= SPRING_STALLS {
                    j.use_contact_derivative();
                    self.made_contact_derivative = Some(k);
                }
            }
        }
        let reuse_limit = match self.jacobian.as_ref().map(|j| j.kind()) {
            Some(JacobianFactor::Ilu0) => ILU_REUSE_KRYLOV,
            _ => JACOBIAN_REUSE_KRYLOV,
        };
        let fresh = self.jacobian_of_this_attempt
            || self.contacts.is_empty()
            || self
                .jacobian
                .as_ref()
                .is_some_and(|j| !j.contact_derivative());
        let reuse = last_krylov.is_some_and(|k| k <= reuse_limit) && fresh;
        let shift = if self.exact_contact { self.shift } else { 0.0 };
        let r = match self.jacobian.as_mut() {
            // the assembled Jacobian is costly to factorise: kept while it
            // serves (an older Jacobian still preconditions the products of
            // the current one)
            Some(j) if reuse && j.is_factorised() && j.shift() == shift => Ok(()),
            Some(j) => {
                self.jacobian_of_this_attempt = true;
                let shift = (shift, self.work.damping.as_slice());
                let r = j.assemble(
                    self.bodies,
                    &mut *self.contacts,
                    self.layout,
                    &self.params,
                    shift,
                );
                if r.is_err() && self.exact_after.is_some() && j.kind() == JacobianFactor::Ilu0 {
                    // an ILU(0) that no diagonal shift keeps regular
                    j.refactor_as(JacobianFactor::Lu);
                    self.made_exact = Some(last_krylov.unwrap_or(0));
                    j.assemble(
                        self.bodies,
                        &mut *self.contacts,
                        self.layout,
                        &self.params,
                        shift,
                    )
                } else {
                    r
                }
            }
            None => self
                .preconditioner
                .assemble(self.bodies, self.contacts, self.layout),
        }
        .map_err(|e| Inadmissible(e.to_string()));
        self.times.lap(Phase::MatrixAssembly, t);
        r
    }

    /// The factorised Jacobian, a sparse Cholesky factor or the multigrid
    /// V-cycles are; the IC(0)-PCG inner solves are not.
    fn linear_preconditioner(&self) -> bool {
        self.jacobian.is_some() || self.preconditioner.is_linear()
    }

    fn precondition(&mut self, r: &[f64], z: &mut [f64]) {
        let t = Instant::now();
        let ok = match self.jacobian.as_mut() {
            Some(j) => j.apply(r, z).is_ok(),
            None => {
                self.preconditioner.apply(r, z);
                true
            }
        };
        if !ok || !z.iter().all(|v| v.is_finite()) {
            // a singular factor (a body that nothing holds yet): the
            // identity rather than a non-finite direction
            z.copy_from_slice(r);
        }
        self.times.lap(Phase::LinearSolve, t);
    }
}
