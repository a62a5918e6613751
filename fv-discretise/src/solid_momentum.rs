//! The segregated, deferred-correction discretisation of the solid momentum
//! equation for one body (thesis §3.2, eqs. 3.7–3.29).
//!
//! The balance of every cell P is written as a force residual
//!
//! F_P(u) = Σ_f Γ_f·σ_f + α_RC Σ_f K|Γ_f| [(u_N − u_P) − d_f·(∇u)_f]/(d_f·n_f)
//!          + Σ_b (boundary forces),
//!
//! i.e. the explicit surface source (3.15) with the Rhie–Chow stabilisation
//! (3.12 minus 3.14, scaled by α_RC). The implicit operator is the compact
//! (2μ+λ) Laplacian of (3.12) without its non-orthogonal part, matrix M with
//! a_N = −K|Γ_f|/(d_f·n_f) and the boundary diagonal of (3.19). Each outer
//! iteration solves M δ = F(u*) and sets u = u* + ω δ: the implicit and the
//! explicit diffusion terms of (3.7) are the same operator, so they cancel at
//! convergence and the converged field satisfies F(u) = 0 exactly (the
//! non-orthogonal correction of (3.12) cancels identically in this form).
//!
//! Under the updated Lagrangian form (eq. 3.6, [`StressLaw::UpdatedLagrangian`])
//! the same operators act on the displacement increment Δu = u − u_old on
//! the mesh of the start of the increment, and σ is replaced by
//! σ̂ = jσ·f⁻ᵀ (3.16); the unknown `u` stays the total displacement.
//!
//! The thesis's Rhie–Chow term acts on the increment: a converged
//! increment's stabilisation force is dropped when the next one starts from
//! Δu = 0, so the solution creeps under a held load and depends on the
//! number of increments (twisting hemisphere at α_RC = 1: the indentation
//! force 12.38, 12.01 and 11.90 N after 10, 20 and 40 increments, and 1.7 %
//! lost over ten held increments). With [`RhieChowHistory::Accumulated`]
//! every increment's force is carried into the later ones, turned and
//! stretched with its face (f_f·c_f, f_f the face's relative deformation
//! gradient), so that the stabilisation acts on the accumulated displacement
//! as it does on the total one under small strain (there, at α_RC = 0.1:
//! 12.20 and 12.21 N after 10 and 20 increments; held, +0.3 % in the first
//! held increment, which still relaxes the difference between the face
//! gradient's Nanson areas and the moved mesh, and within 3e-5 after). It
//! is not the default: the carried forces are a memory of the shape the
//! body had, and a body that flows far from it fights them (die drawing
//! stops at 0.04 of 0.25 m).
//!
//! With inertia (3.11) the cell balance gains −m_P ü_P (backward Euler, the
//! mass m_P = ρ_P Ω_P conserved) and the matrix diagonal m_P/Δt².
mod jacobian;
mod restart;
mod state_function;

pub use jacobian::StateNode;
pub use state_function::KinematicFaces;

use crate::stress_law::current_area_vector;
use crate::{LeastSquaresGradient, PatchCondition, StressLaw};
use fv_materials::{updated_lagrangian_stress, MaterialState};
use fv_mesh::{MeshGeometry, PolyMesh, Tensor, Vector};

/// Knobs of the discretisation.
#[derive(Debug, Clone, Copy)]
pub struct MomentumParams {
    /// Rhie–Chow scaling α_RC (thesis: 0.1).
    pub rhie_chow: f64,
    /// Whether the updated Lagrangian form keeps the Rhie–Chow force of
    /// the committed increments (see the module documentation).
    pub rhie_chow_history: RhieChowHistory,
}

impl Default for MomentumParams {
    fn default() -> Self {
        MomentumParams {
            rhie_chow: 0.1,
            rhie_chow_history: RhieChowHistory::Incremental,
        }
    }
}

/// What the Rhie–Chow stabilisation of the updated Lagrangian form acts on
/// (small strain: always the total displacement).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RhieChowHistory {
    /// The increment only, as in the thesis (eq. 3.12 minus 3.14 of Δu): a
    /// converged increment's stabilisation force is dropped when the next
    /// one starts.
    Incremental,
    /// The increment plus the forces of the committed increments, carried
    /// with their faces: the stabilisation of the accumulated displacement.
    Accumulated,
}

impl RhieChowHistory {
    /// Every variant, with its case-file name ([`Self::name`]).
    pub const ALL: [RhieChowHistory; 2] =
        [RhieChowHistory::Incremental, RhieChowHistory::Accumulated];

    /// The case-file name.
    pub fn name(self) -> &'static str {
        match self {
            RhieChowHistory::Incremental => "incremental",
            RhieChowHistory::Accumulated => "accumulated",
        }
    }
}

/// The stiffness of the Rhie–Chow term in a plastic body
/// ([`SolidMomentum::rhie_chow_plastic`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RhieChowPlastic {
    /// Where a cell flowed in the last committed increment, the share
    /// H'/(3μ + H') of the elastic stiffness, at least
    /// [`PLASTIC_RC_SHARE_FLOOR`] (the default).
    #[default]
    Flow,
    /// The elastic stiffness everywhere, as in the thesis.
    Elastic,
}

impl RhieChowPlastic {
    /// Every variant, with its case-file name ([`Self::name`]).
    pub const ALL: [RhieChowPlastic; 2] = [RhieChowPlastic::Flow, RhieChowPlastic::Elastic];

    /// The case-file name.
    pub fn name(self) -> &'static str {
        match self {
            RhieChowPlastic::Flow => "flow",
            RhieChowPlastic::Elastic => "elastic",
        }
    }
}

/// The temporal term of eq. (3.11): backward Euler on the cell
/// displacement, with the cell mass ρΩ conserved through the motion.
#[derive(Debug, Clone)]
pub struct Inertia {
    /// Mass m_P = ρ_P Ω_P of every cell.
    pub mass: Vec<f64>,
    /// Displacement at the two previous time instances (m−1, m−2).
    u_prev: Vec<Vector>,
    u_prev2: Vec<Vector>,
    /// Time step of this increment and of the previous one.
    dt: f64,
    dt_prev: f64,
}

impl Inertia {
    /// A body at rest with cell masses `mass`.
    pub fn new(mass: Vec<f64>) -> Self {
        let n = mass.len();
        Inertia {
            mass,
            u_prev: vec![Vector::zeros(); n],
            u_prev2: vec![Vector::zeros(); n],
            dt: 0.0,
            dt_prev: 0.0,
        }
    }

    /// Sets the time step of the coming increment.
    pub fn set_time_step(&mut self, dt: f64) {
        if self.dt_prev == 0.0 {
            self.dt_prev = dt;
        }
        self.dt = dt;
    }

    /// Time step of the current increment.
    pub fn time_step(&self) -> f64 {
        self.dt
    }

    /// Matrix diagonal m_P/Δt² of cell `i`.
    #[inline]
    pub fn diagonal(&self, i: usize) -> f64 {
        self.mass[i] / (self.dt * self.dt)
    }

    /// Inertia force −m_P ü_P of cell `i` at displacement `u` (eq. 3.11).
    #[inline]
    fn force(&self, i: usize, u: &Vector) -> Vector {
        let v_now = (u - self.u_prev[i]) / self.dt;
        let v_before = (self.u_prev[i] - self.u_prev2[i]) / self.dt_prev;
        -(v_now - v_before) * (self.mass[i] / self.dt)
    }

    /// Velocity of cell `i` at displacement `u` (backward difference).
    pub fn velocity(&self, i: usize, u: &Vector) -> Vector {
        (u - self.u_prev[i]) / self.dt
    }

    /// End of a converged time step: shifts the time levels.
    pub fn advance(&mut self, u: &[Vector]) {
        std::mem::swap(&mut self.u_prev, &mut self.u_prev2);
        self.u_prev.copy_from_slice(u);
        self.dt_prev = self.dt;
    }
}

/// Discretised momentum balance and fields of one body.
#[derive(Debug)]
pub struct SolidMomentum {
    /// Implicit stiffness K = 2μ + λ.
    pub k: f64,
    /// d·n of every face (boundary: d_b·n_b = |d_n|).
    dn: Vec<f64>,
    /// Boundary non-orthogonal vector k_b = d_b − (d_b·n) n (length), per boundary face.
    kb: Vec<Vector>,
    /// Least-squares gradient operator.
    pub gradient: LeastSquaresGradient,
    /// Condition of every patch.
    pub conditions: Vec<PatchCondition>,
    /// Constitutive law and formulation (small strain or updated Lagrangian).
    pub law: StressLaw,
    /// Temporal term (dynamic analyses).
    pub inertia: Option<Inertia>,
    /// Cell-centre displacement (total).
    pub u: Vec<Vector>,
    /// Boundary-face displacement (total; index face − n_internal_faces).
    pub u_b: Vec<Vector>,
    /// Directions the solver does not solve (the out-of-plane axis of a 2-D
    /// model, the circumferential axis of an axisymmetric wedge): the
    /// boundary values of every patch but the wedge planes keep no
    /// component along them. Set by the solver; all false by default.
    pub unsolved: [bool; 3],
    /// Total displacement at the start of the increment, cells and boundary
    /// faces (updated Lagrangian only; empty otherwise).
    u_old: Vec<Vector>,
    u_b_old: Vec<Vector>,
    /// Increment Δu = u − u_old, cells and boundary faces (updated
    /// Lagrangian only; empty otherwise).
    du: Vec<Vector>,
    du_b: Vec<Vector>,
    /// Normal derivative n·∇u on traction faces (eq. 3.22), per boundary
    /// face (of Δu under the updated Lagrangian form).
    pub snd_b: Vec<Vector>,
    /// Updated Lagrangian only, per boundary face with a traction-type
    /// condition: the face traction carried over from earlier increments
    /// that the owner cell's committed stress does not reproduce (a face's
    /// stress differs from its cell-centre value where the stress varies).
    /// Without it, eq. 3.23 would re-impose that difference as a normal
    /// derivative of *every* increment, and the boundary points would creep
    /// by g·d_n per increment at constant load (measured: a block dragged
    /// 10 m under a constant shear traction, its loaded face's lag grew by
    /// 1.5e-4 m per increment).
    traction_offset: Vec<Vector>,
    /// Updated Lagrangian only, per boundary face: the area vector of the
    /// face as the current iterate moves its points, per unit mesh area
    /// (Γ_moved/|Γ|), set by the solver for traction and pressure faces
    /// before every boundary update; zero = not measured, and the face
    /// gradient's Nanson vector j f⁻ᵀ·n is used instead. On a curved
    /// boundary the face gradient takes its tangential part from the owner
    /// cell's, whose hoop stretch lags the face's by O(h): a pressure
    /// applied in one increment then acted on an area 2.7 % short
    /// (neo-Hookean tube, 20 × 30 cells, r_i 1 → 1.556), and the answer
    /// depended on the number of increments. The moved points are the ones
    /// the mesh motion ends the increment with.
    pub moved_area: Vec<Vector>,
    /// Updated Lagrangian only: the material state of every boundary face
    /// whose force comes from its own stress (prescribed displacement,
    /// symmetry, normal displacement), advanced at the end of every
    /// increment by the face gradient of eq. 3.23 and committed with the
    /// cells. The face stress is then σ(f_b F_b) rather than σ(f_b F_P) of
    /// the owner cell: with the cell's state, each increment started the
    /// face from the cell-centre stress and had to rebuild the difference
    /// through a new normal derivative, so the solution crept at constant
    /// load (twisting hemisphere: F_z −5 % in ten increments of held
    /// indentation) and depended on the number of increments; die drawing
    /// stalled at 0.1825 m and now runs to the end.
    face_state: Option<MaterialState>,
    /// u, u_b and n·∇u at the start of the current attempt of an increment
    /// (to redo it with a smaller step, [`Self::restore_start`]; the small
    /// strain cell gradient is recomputed from them there rather than kept,
    /// 72 B per cell).
    saved: (Vec<Vector>, Vec<Vector>, Vec<Vector>),
    /// Cell gradient of the displacement on the current mesh: of u under
    /// small strain, of the increment Δu under the updated Lagrangian form.
    pub grad_u: Vec<Tensor>,
    /// Cell Cauchy stress.
    pub sigma: Vec<Tensor>,
    /// Cell surface-force tensor σ̂ = jσ·f⁻ᵀ (eq. 3.16; updated Lagrangian
    /// only, empty otherwise).
    sigma_hat: Vec<Tensor>,
    /// Force exerted on the body through every boundary face.
    pub face_force: Vec<Vector>,
    /// Force residual F_P of every cell.
    pub residual: Vec<Vector>,
    /// Updated Lagrangian with [`RhieChowHistory::Accumulated`] only, per
    /// internal face (empty otherwise; sized by the first residual that
    /// carries): the Rhie–Chow force of the current increment (of the
    /// latest residual evaluation), and the sum of those of the committed
    /// increments, carried with the material ([`Self::carry_stabilisation`];
    /// see the module documentation).
    rc_increment: Vec<Vector>,
    rc_carried: Vec<Vector>,
    /// Body force per unit volume ρb (eq. 3.18), per cell; empty = none.
    pub body_force: Vec<Vector>,
    /// α_RC of this body instead of [`MomentumParams::rhie_chow`] (set by
    /// the solver for cell shapes the thesis's 0.1 does not hold).
    pub rhie_chow_override: Option<f64>,
    /// The Rhie–Chow stiffness where the body flows plastically.
    pub rhie_chow_plastic: RhieChowPlastic,
    /// Plastic bodies only (empty otherwise): the share of the Rhie–Chow
    /// stiffness each cell keeps in this increment, H'/(3μ + H') (at
    /// least [`PLASTIC_RC_SHARE_FLOOR`]) where the cell flowed in the last
    /// committed increment, else 1 (see
    /// [`Self::scale_stabilisation_to_plastic_flow`]); a face takes the
    /// smaller of its two cells'.
    rc_cell_scale: Vec<f64>,
    /// Plastic bodies only: ε̄p of every cell at the start of the last
    /// committed increment (to tell the cells that flowed in it).
    eps_p_before: Vec<f64>,
    /// The boundary faces whose value follows from their owner's value and
    /// gradient, eliminated from the cell gradient when the balance is
    /// evaluated as a function of the state ([`Self::prepare_state_function`]).
    kinematic: KinematicFaces,
    /// Σ_f |force through f| of every cell at the last residual evaluation
    /// (workspace of [`Self::compute_residual_with_face_rows`]).
    force_scale: Vec<f64>,
    /// See [`Self::take_inverted_face_point`].
    inverted_face_point: std::cell::Cell<Option<usize>>,
}

/// Wedge face f, rotation `r` from the mid-plane onto its plane, unit
/// normal `n`, `d` from the owner centre x_P to the face centre x_f: what
/// R^T k_b (k_b = x_f − x_P', x_P' the projection of x_P on the face plane)
/// misses of the face centre rotated back into the mid-plane, R^T x_f − x_P
/// (rotation about the wedge axis). x_P' lies at radius r cos θ, so rotated
/// back it falls r (1 − cos θ) short of x_P along the mid-plane radial
/// direction. Small as it is, the cell's own gradient extrapolates the
/// wedge-face value, and the least-squares weights of the near wedge faces
/// amplify it: a solid bar under a uniform axial traction on a ±2.5° wedge
/// was off by 3.4 % of the traction in stress about the axis (validation
/// test `axisymmetric_bar`), and the nearly incompressible die-drawing
/// cylinder drew 5 % less force. With it, linear fields are exact.
fn wedge_back_shift(r: &Tensor, n: &Vector, d: Vector) -> Vector {
    let cos_t = ((r.trace() - 1.0) * 0.5).clamp(-1.0, 1.0);
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    if sin_t < 1e-9 {
        return Vector::zeros();
    }
    let axis = Vector::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    ) / (2.0 * sin_t);
    let dn = d.dot(n);
    // x_P − x_P' = −n (d·n); its distance from the face plane is r sin θ
    let radius = dn.abs() / sin_t;
    let e_mid = r.transpose() * axis.cross(n);
    let e_mid = if e_mid.dot(&(-*n * dn)) >= 0.0 {
        e_mid
    } else {
        -e_mid
    };
    -e_mid * (radius * (1.0 - cos_t))
}

impl SolidMomentum {
    /// Sets up the discretisation of a body at rest.
    pub fn new(
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        law: StressLaw,
        conditions: Vec<PatchCondition>,
    ) -> Self {
        let nf = mesh.n_faces();
        let ni = mesh.n_internal_faces();
        let nb = nf - ni;
        let nc = mesh.n_cells;
        let passive: Vec<bool> = conditions
            .iter()
            .map(|c| matches!(c, PatchCondition::Empty))
            .collect();
        let ul = law.is_updated_lagrangian();
        let ul_len = |n: usize| if ul { n } else { 0 };
        let face_state = match &law {
            StressLaw::UpdatedLagrangian { law, .. } => Some(law.new_state(nb)),
            _ => None,
        };
        let mut s = SolidMomentum {
            face_state,
            k: law.implicit_stiffness(),
            dn: vec![0.0; nf],
            kb: vec![Vector::zeros(); nb],
            gradient: LeastSquaresGradient::new(mesh, geom, &passive),
            conditions,
            law,
            inertia: None,
            u: vec![Vector::zeros(); nc],
            u_b: vec![Vector::zeros(); nb],
            unsolved: [false; 3],
            u_old: vec![Vector::zeros(); ul_len(nc)],
            u_b_old: vec![Vector::zeros(); ul_len(nb)],
            du: vec![Vector::zeros(); ul_len(nc)],
            du_b: vec![Vector::zeros(); ul_len(nb)],
            snd_b: vec![Vector::zeros(); nb],
            traction_offset: vec![Vector::zeros(); ul_len(nb)],
            moved_area: vec![Vector::zeros(); ul_len(nb)],
            saved: (
                vec![Vector::zeros(); nc],
                vec![Vector::zeros(); nb],
                vec![Vector::zeros(); nb],
            ),
            grad_u: vec![Tensor::zeros(); nc],
            sigma: vec![Tensor::zeros(); nc],
            sigma_hat: vec![Tensor::zeros(); ul_len(nc)],
            face_force: vec![Vector::zeros(); nb],
            residual: vec![Vector::zeros(); nc],
            body_force: Vec::new(),
            rc_increment: Vec::new(),
            rc_carried: Vec::new(),
            rhie_chow_override: None,
            rhie_chow_plastic: RhieChowPlastic::default(),
            rc_cell_scale: Vec::new(),
            eps_p_before: Vec::new(),
            kinematic: KinematicFaces::default(),
            force_scale: Vec::new(),
            inverted_face_point: std::cell::Cell::new(None),
        };
        s.update_geometry(mesh, geom);
        s
    }

    /// Recomputes the geometric coefficients (after mesh motion).
    pub fn update_geometry(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        let ni = mesh.n_internal_faces();
        for f in 0..mesh.n_faces() {
            let n = geom.face_normal(f);
            let d = geom.delta(mesh, f);
            // guard against faces whose d is (nearly) tangential
            let dn = d.dot(&n).max(0.05 * d.norm());
            self.dn[f] = dn;
            if f >= ni {
                self.kb[f - ni] = d - n * d.dot(&n);
            }
        }
        let passive: Vec<bool> = self
            .conditions
            .iter()
            .map(|c| matches!(c, PatchCondition::Empty))
            .collect();
        self.gradient.update(mesh, geom, &passive);
    }

    /// The displacement the mesh operators act on, cells and boundary
    /// faces: u under small strain, the increment Δu under the updated
    /// Lagrangian form (current after [`Self::update_boundary_values`]).
    #[inline]
    pub fn increment(&self) -> (&[Vector], &[Vector]) {
        if self.law.is_updated_lagrangian() {
            (&self.du, &self.du_b)
        } else {
            (&self.u, &self.u_b)
        }
    }

    /// Updated Lagrangian: the increment set to the motion
    /// Δu(x) = (Q − I) x + c of the configuration at the increment's start
    /// (a rigid motion Q, c carries it to x ↦ Q x + c): the cells, the
    /// boundary faces, the cell gradient and the normal derivatives, so
    /// that the first boundary update extrapolates the motion (with the
    /// gradient of rest, the faces lagged their cells by (Q − I)(x_f − x_P)).
    /// No-op under small strain.
    pub fn start_from_motion(
        &mut self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        q: &Tensor,
        c: &Vector,
    ) {
        if !self.law.is_updated_lagrangian() {
            return;
        }
        let ni = mesh.n_internal_faces();
        let motion = |x: &Vector| q * x + c - x;
        for ((u, u0), x) in self.u.iter_mut().zip(&self.u_old).zip(&geom.cell_centres) {
            *u = u0 + motion(x);
        }
        for (i, (ub, ub0)) in self.u_b.iter_mut().zip(&self.u_b_old).enumerate() {
            *ub = ub0 + motion(&geom.face_centres[ni + i]);
        }
        let step = q - Tensor::identity();
        for (i, g) in self.snd_b.iter_mut().enumerate() {
            *g = step * geom.face_normal(ni + i);
        }
        self.grad_u.iter_mut().for_each(|g| *g = step.transpose());
        for (d, (u, o)) in self.du.iter_mut().zip(self.u.iter().zip(&self.u_old)) {
            *d = u - o;
        }
        for (d, (u, o)) in self.du_b.iter_mut().zip(self.u_b.iter().zip(&self.u_b_old)) {
            *d = u - o;
        }
    }

    /// Displacement of cell `i` at the start of the increment (zero under
    /// small strain: the mesh operators act on the total displacement).
    #[inline]
    fn old(&self, i: usize) -> Vector {
        self.u_old.get(i).copied().unwrap_or_else(Vector::zeros)
    }

    /// [`Self::traction_offset`] of boundary face `b` carried by the
    /// increment's deformation gradient `f = I + ∇Δuᵀ` at the face (it turns
    /// with the material; zero in small strain).
    fn offset_at(&self, b: usize, grad_b: &Tensor) -> Vector {
        match self.traction_offset.get(b) {
            Some(m) => m + grad_b.transpose() * m,
            None => Vector::zeros(),
        }
    }

    /// Area vector per unit mesh area on which a traction or pressure acts
    /// at boundary face `b`: the moved face's ([`Self::moved_area`]) when
    /// measured, else the face gradient's (Nanson).
    #[inline]
    fn loaded_area(&self, b: usize, grad_b: &Tensor, n: &Vector) -> Vector {
        self.measured_moved_area(b)
            .unwrap_or_else(|| current_area_vector(self.law.is_updated_lagrangian(), grad_b, n))
    }

    /// [`Self::moved_area`] of boundary face `b`, if measured.
    #[inline]
    fn measured_moved_area(&self, b: usize) -> Option<Vector> {
        self.moved_area
            .get(b)
            .copied()
            .filter(|a| *a != Vector::zeros())
    }

    /// Forgets the measured [`Self::moved_area`] (they belong to the
    /// increment, or attempt, that measured them).
    fn forget_moved_areas(&mut self) {
        self.moved_area
            .iter_mut()
            .for_each(|a| *a = Vector::zeros());
    }

    fn has_traction_condition(cond: &PatchCondition) -> bool {
        matches!(
            cond,
            PatchCondition::Traction(_)
                | PatchCondition::Pressure(_)
                | PatchCondition::LinearisedContact(_)
        )
    }

    /// Sets the traction offset of every face with a traction-type
    /// condition to `value(self, b, owner, n, area_ratio)` (boundary face
    /// `b`; `area_ratio` the contact's moved-surface ratio of
    /// [`LinearisedContact::area_ratio`], if any).
    fn set_traction_offsets(
        &mut self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        value: impl Fn(&Self, usize, usize, &Vector, Option<f64>) -> Vector,
    ) {
        if self.traction_offset.is_empty() {
            return;
        }
        let ni = mesh.n_internal_faces();
        for (pi, p) in mesh.patches.iter().enumerate() {
            if !Self::has_traction_condition(&self.conditions[pi]) {
                continue;
            }
            for f in p.faces() {
                let n = geom.face_normal(f);
                let area_ratio = match &self.conditions[pi] {
                    PatchCondition::LinearisedContact(lc) => lc.moved_area_ratio(f - p.start),
                    _ => self.measured_moved_area(f - ni).map(|a| a.norm()),
                };
                let v = value(self, f - ni, mesh.owner[f] as usize, &n, area_ratio);
                self.traction_offset[f - ni] = v;
            }
        }
    }

    /// Updated Lagrangian, first half of carrying the face tractions over
    /// to the next increment (see [`Self::traction_offset`]); call on the
    /// converged increment *before* the mesh moves: stores the converged
    /// face traction per current area, `(n·σ̂_b + offset)/ratio`.
    pub fn hold_face_tractions(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        self.hold_face_states(mesh, geom);
        self.set_traction_offsets(mesh, geom, |m, b, o, n, area_ratio| {
            let grad_b = face_gradient(&m.grad_u[o], n, &m.snd_b[b]);
            let (t_b, ratio) = m.face_traction(o, &grad_b, n);
            // per current area as the traction was applied: a contact
            // face's over the moved surface's area
            let ratio = area_ratio.unwrap_or(ratio);
            let t = (t_b + m.offset_at(b, &grad_b)) / ratio;
            if t.iter().all(|v| v.is_finite()) {
                t
            } else {
                Vector::zeros()
            }
        });
    }

    /// End of a converged increment, before the mesh moves (updated
    /// Lagrangian, [`RhieChowHistory::Accumulated`]; a no-op otherwise, the
    /// carried forces being empty): the increment's Rhie–Chow force
    /// joins the carried ones, which turn and stretch with their face,
    /// c_f ← f_f·c_f + rc_f — the force the converged residual applied, so
    /// that the next increment starts in balance (module documentation).
    pub fn carry_stabilisation(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        for (f, (c, rc)) in self
            .rc_carried
            .iter_mut()
            .zip(&self.rc_increment)
            .enumerate()
        {
            let w = geom.weight(mesh, f);
            let grad_f = self.grad_u[mesh.owner[f] as usize] * w
                + self.grad_u[mesh.neighbour[f] as usize] * (1.0 - w);
            *c += grad_f.transpose() * *c + rc;
        }
    }

    /// Second half, after [`Self::commit_increment`] and the geometry
    /// update: the offset becomes the held traction minus what the newly
    /// committed owner stress gives on the moved face.
    pub fn carry_face_tractions(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        self.set_traction_offsets(mesh, geom, |m, b, o, n, _| {
            m.traction_offset[b] - m.face_traction(o, &Tensor::zeros(), n).0
        });
    }

    /// End of a converged increment of the updated Lagrangian form, after
    /// the mesh was moved by the increment and [`Self::update_geometry`]
    /// called: the trial material state is committed and the current
    /// displacement becomes the start of the next increment.
    pub fn commit_increment(&mut self) {
        if let Some(fs) = &mut self.face_state {
            fs.commit();
        }
        if let StressLaw::UpdatedLagrangian { state, .. } = &mut self.law {
            if !self.rc_cell_scale.is_empty() {
                self.eps_p_before.clear();
                self.eps_p_before
                    .extend_from_slice(state.equivalent_plastic_strain());
            }
            state.commit();
            self.u_old.copy_from_slice(&self.u);
            self.u_b_old.copy_from_slice(&self.u_b);
            self.du.iter_mut().for_each(|d| *d = Vector::zeros());
            self.du_b.iter_mut().for_each(|d| *d = Vector::zeros());
            self.grad_u.iter_mut().for_each(|g| *g = Tensor::zeros());
            self.snd_b.iter_mut().for_each(|g| *g = Vector::zeros());
            self.forget_contact_areas();
            self.forget_moved_areas();
        }
        if let Some(inertia) = &mut self.inertia {
            inertia.advance(&self.u);
        }
    }

    /// The moved contact surfaces' area ratios belong to the increment
    /// (attempt) that measured them: back to the face gradient's until
    /// the next contact update.
    fn forget_contact_areas(&mut self) {
        for cond in &mut self.conditions {
            if let PatchCondition::LinearisedContact(lc) = cond {
                lc.area_ratio.iter_mut().for_each(|r| *r = 0.0);
            }
        }
    }

    /// The cell displacement recorded by the last [`Self::save_start`]
    /// (the start of the current attempt at an increment), and the current
    /// one to update (the segregated solver measures the increment's
    /// displacement against it rather than keeping a copy, 24 B per cell).
    pub fn u_and_start_mut(&mut self) -> (&mut [Vector], &[Vector]) {
        (&mut self.u, &self.saved.0)
    }

    /// The cell displacement recorded by the last [`Self::save_start`].
    pub fn u_start(&self) -> &[Vector] {
        &self.saved.0
    }

    /// Records the fields at the start of an attempt at an increment.
    pub fn save_start(&mut self) {
        self.saved.0.copy_from_slice(&self.u);
        self.saved.1.copy_from_slice(&self.u_b);
        self.saved.2.copy_from_slice(&self.snd_b);
        self.scale_stabilisation_to_plastic_flow();
    }

    /// The Rhie–Chow stiffness α_RC(λ + 2μ) is elastic; where the material
    /// flows plastically its tangent along the flow is 2μH'/(3μ + H') —
    /// for a steel with H' = E/200, 1/230 of the elastic 2μ. There the
    /// elastic term, which does not yield, carried a share of the load
    /// that grew with the increment, and upsetting and punch indentation
    /// stalled after a few increments (docs/solver-notes.md, "Upsetting a
    /// J2 block"). So each cell that flowed in the last committed
    /// increment keeps the share H'/(3μ + H') of the term, at least
    /// [`PLASTIC_RC_SHARE_FLOOR`]; the others keep it all. The shares are
    /// set from the committed state at the start of every attempt and are
    /// frozen while it is solved.
    fn scale_stabilisation_to_plastic_flow(&mut self) {
        let StressLaw::UpdatedLagrangian { law, state } = &self.law else {
            return;
        };
        if law.hardening_slope(0.0).is_none() || self.rhie_chow_plastic == RhieChowPlastic::Elastic
        {
            return;
        }
        let mu3 = 3.0 * law.shear_modulus();
        let eps = state.equivalent_plastic_strain();
        self.rc_cell_scale.resize(eps.len(), 1.0);
        for (i, (s, &e)) in self.rc_cell_scale.iter_mut().zip(eps).enumerate() {
            // the start of the last committed increment; none before the
            // first (nothing has flowed)
            let before = self.eps_p_before.get(i).copied().unwrap_or(e);
            *s = match law.hardening_slope(e) {
                Some(h) if e > before => flow_share(h, mu3),
                _ => 1.0,
            };
        }
    }

    /// After a converged solve of the increment: the cells that flowed in
    /// it but kept the whole Rhie–Chow stiffness (they had not flowed in
    /// the last increment: the increment where a body first yields) take
    /// their share as well, and the solve is to be repeated; true when any
    /// share changed. The shares only fall within an increment, so the
    /// repetitions end. Without it the first yielding increment carried
    /// the elastic term: a J2 block upset by 3 % in one increment on
    /// 20 × 10 cells reacted 1,340 against CalculiX's 2,000.
    pub fn follow_flow_of_increment(&mut self) -> bool {
        if self.rc_cell_scale.is_empty() {
            return false;
        }
        let StressLaw::UpdatedLagrangian { law, state } = &self.law else {
            return false;
        };
        let mu3 = 3.0 * law.shear_modulus();
        let mut changed = false;
        for ((s, &e), &e0) in self
            .rc_cell_scale
            .iter_mut()
            .zip(state.trial_equivalent_plastic_strain())
            .zip(state.equivalent_plastic_strain())
        {
            if *s == 1.0 && e > e0 {
                if let Some(h) = law.hardening_slope(e) {
                    *s = flow_share(h, mu3);
                    changed |= *s < 1.0;
                }
            }
        }
        changed
    }

    /// The Rhie–Chow share of internal face `f` (1 but in plastic bodies).
    #[inline]
    pub fn rc_face_scale(&self, mesh: &PolyMesh, f: usize) -> f64 {
        face_scale(&self.rc_cell_scale, mesh, f)
    }

    /// Back to the fields of [`Self::save_start`], the trial material state
    /// dropped: the increment is redone (with a smaller step).
    pub fn restore_start(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        self.u.copy_from_slice(&self.saved.0);
        self.u_b.copy_from_slice(&self.saved.1);
        self.snd_b.copy_from_slice(&self.saved.2);
        if let Some(fs) = &mut self.face_state {
            fs.discard();
        }
        self.forget_contact_areas();
        self.forget_moved_areas();
        if let StressLaw::UpdatedLagrangian { law, state } = &mut self.law {
            state.discard();
            // the failed attempt may have left non-finite fields behind: the
            // stress of the committed state, the gradient of no increment
            for (i, (s, h)) in self
                .sigma
                .iter_mut()
                .zip(self.sigma_hat.iter_mut())
                .enumerate()
            {
                if let Some((c, _)) = law.update_point(&state.committed(i), &Tensor::zeros()) {
                    *s = c;
                    *h = c;
                }
            }
            self.grad_u.iter_mut().for_each(|g| *g = Tensor::zeros());
        } else {
            // small strain: the next boundary update extrapolates with the
            // last gradient, which a diverged attempt may have left huge or
            // non-finite (the retry then diverged in its first iteration):
            // the gradient of the restored fields
            self.gradient
                .vector_gradient(mesh, geom, &self.u, &self.u_b, &mut self.grad_u);
            // and the stress of the restored fields: a run that fails here
            // writes them as its last state
            self.update_stress();
        }
        if self.law.is_updated_lagrangian() {
            for ((d, u), o) in self.du.iter_mut().zip(&self.u).zip(&self.u_old) {
                *d = u - o;
            }
            for ((d, u), o) in self.du_b.iter_mut().zip(&self.u_b).zip(&self.u_b_old) {
                *d = u - o;
            }
        }
    }

    /// d_f·n_f of face f (boundary faces: the normal distance |d_n| of the
    /// owner centre), clipped as in the matrix coefficients.
    #[inline]
    pub fn normal_distance(&self, f: usize) -> f64 {
        self.dn[f]
    }

    /// Implicit Laplacian coefficient K|Γ_f|/(d_f·n_f) of face f (a
    /// boundary face: K|Γ_b|/|d_n|).
    #[inline]
    pub fn face_coefficient(&self, geom: &MeshGeometry, f: usize) -> f64 {
        self.k * geom.face_mag(f) / self.dn[f]
    }

    /// Adds the boundary contributions to the matrix diagonal of component
    /// `c` (0, 1, 2): eq. (3.19) for displacement faces, the normal part for
    /// symmetry and normal-displacement faces, nothing for traction faces;
    /// plus m_P/Δt² of the temporal term (3.11).
    pub fn add_boundary_diagonal(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        c: usize,
        diag: &mut [f64],
    ) {
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let a = self.face_coefficient(geom, f);
                let o = mesh.owner[f] as usize;
                let n = geom.face_normal(f);
                diag[o] += match cond {
                    PatchCondition::Displacement(_) => a,
                    PatchCondition::Symmetry
                    | PatchCondition::NormalDisplacement(_)
                    | PatchCondition::TangentialDisplacement(_) => {
                        cond.held_projection(&n).map_or(0.0, |pr| a * pr[(c, c)])
                    }
                    // hoop stiffness: K|Γ|/δ_n · sin²θ = K|Γ| sin θ / r per face
                    PatchCondition::Wedge(r) => a * (1.0 - r[f - p.start][(c, c)].powi(2)).max(0.0),
                    PatchCondition::Traction(_)
                    | PatchCondition::Pressure(_)
                    | PatchCondition::Empty => 0.0,
                    PatchCondition::LinearisedContact(lc) if !lc.grounded => 0.0,
                    PatchCondition::LinearisedContact(lc) => {
                        // penalty springs in series with the half cell (eq. 4.54 i)
                        a * lc.diagonal_factor(f - p.start, c, self.dn[f] / self.k)
                    }
                };
            }
        }
    }

    /// Adds to `rhs` (component c, one entry per cell) the boundary source
    /// of the step of the prescribed displacements from the current
    /// boundary values to the refreshed conditions: K|Γ|/|d_n| (Δu_b)_c of
    /// every `displacement` face, and K|Γ|/|d_n| n_c n·Δu_b of every
    /// `normal-displacement` face, at its owner cell. With the implicit
    /// Laplacian (the matrix of eq. 3.29 with [`Self::add_boundary_diagonal`])
    /// it gives the harmonic extension of the boundary step into the cells;
    /// returns whether any face has a step.
    pub fn add_prescribed_step_source(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        c: usize,
        rhs: &mut [f64],
    ) -> bool {
        let ni = mesh.n_internal_faces();
        let mut any = false;
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let step = match cond {
                    PatchCondition::Displacement(v) => v[f - p.start] - self.u_b[f - ni],
                    PatchCondition::NormalDisplacement(_)
                    | PatchCondition::TangentialDisplacement(_) => {
                        let n = geom.face_normal(f);
                        let held = cond.held_projection(&n).unwrap_or_else(Tensor::zeros);
                        cond.held_value(f - p.start, &n) - held * self.u_b[f - ni]
                    }
                    _ => continue,
                };
                if step[c] != 0.0 {
                    any = true;
                    let a = self.face_coefficient(geom, f);
                    rhs[mesh.owner[f] as usize] += a * step[c];
                }
            }
        }
        any
    }

    /// Adds to `rhs` (component c) the part of the `symmetry` and
    /// `normal-displacement` faces' condition n·u_b = v that the
    /// component's diagonal (a n_c², [`Self::add_boundary_diagonal`]) leaves
    /// out: −K|Γ|/|d_n| n_c Σ_{d≠c} n_d e_d of the owner's cell values `e`
    /// of the other components. With it, sweeps over the components solve
    /// the vector Laplacian whose boundary holds the face on an inclined
    /// plane; returns whether any such face is inclined (not normal to an
    /// axis), i.e. whether the term can be non-zero.
    pub fn add_inclined_plane_coupling(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        c: usize,
        e: &[Vector],
        rhs: &mut [f64],
    ) -> bool {
        let mut inclined = false;
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            if !cond.holds_part() {
                continue;
            }
            for f in p.faces() {
                let n = geom.face_normal(f);
                if n.iter().filter(|x| x.abs() > 1e-12).count() < 2 {
                    continue;
                }
                inclined = true;
                let o = mesh.owner[f] as usize;
                let held = cond.held_projection(&n).unwrap_or_else(Tensor::zeros);
                let cross: f64 = (0..3)
                    .filter(|&d| d != c)
                    .map(|d| held[(c, d)] * e[o][d])
                    .sum();
                rhs[o] -= self.face_coefficient(geom, f) * cross;
            }
        }
        inclined
    }

    /// Adds the temporal diagonal m_P/Δt² (eq. 3.11) to `diag` (no-op for
    /// static bodies).
    pub fn add_inertia_diagonal(&self, diag: &mut [f64]) {
        if let Some(inertia) = &self.inertia {
            for (i, d) in diag.iter_mut().enumerate() {
                *d += inertia.diagonal(i);
            }
        }
    }

    /// n·σ̂ at a boundary face (force per unit mesh area) and the ratio of
    /// the current to the mesh area, from the face gradient `grad_b`;
    /// falls back to the owner cell's stress when the face gradient inverts
    /// the point.
    #[inline]
    fn face_traction(&self, o: usize, grad_b: &Tensor, n: &Vector) -> (Vector, f64) {
        let ul = self.law.is_updated_lagrangian();
        let sig_hat = self.sigma_hat_at(o, grad_b);
        let ratio = if ul {
            current_area_vector(true, grad_b, n).norm()
        } else {
            1.0
        };
        (sig_hat * n, ratio)
    }

    /// Updates the boundary-face displacement from the cell values and the
    /// current gradient: prescribed (3.19), traction and pressure (3.22–3.24,
    /// with the normal-gradient correction 3.23), symmetry (3.26), wedge
    /// (rotation), linearised contact (4.53). Under the updated Lagrangian
    /// form the extrapolation acts on the increment; then Δu is refreshed.
    pub fn update_boundary_values(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        let ni = mesh.n_internal_faces();
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let b = f - ni;
                let o = mesh.owner[f] as usize;
                let n = geom.face_normal(f);
                let gp = self.grad_u[o];
                let base = self.u_b_old.get(b).copied().unwrap_or_else(Vector::zeros);
                // total displacement extrapolated from the owner along k_b
                let extrapolated = base + (self.u[o] - self.old(o)) + gp.transpose() * self.kb[b];
                let grad_at = |g: &Vector| face_gradient(&gp, &n, g);
                let u_b = match cond {
                    PatchCondition::Displacement(v) => v[f - p.start],
                    PatchCondition::Traction(t) => {
                        // g_b ← g_b + (t − n·σ̂_b)/K   (3.22–3.23)
                        let g = self.snd_b[b];
                        let grad_b = grad_at(&g);
                        let (t_b, _) = self.face_traction(o, &grad_b, &n);
                        let t_b = t_b + self.offset_at(b, &grad_b);
                        // (a plane-stress body: per unit initial thickness)
                        let ratio =
                            self.loaded_area(b, &grad_b, &n).norm() * self.law.thickness_stretch(o);
                        let g_new = g + (t[f - p.start] * ratio - t_b) / self.k;
                        self.snd_b[b] = g_new;
                        extrapolated + g_new * self.dn[f]
                    }
                    PatchCondition::Pressure(pr) => {
                        let g = self.snd_b[b];
                        let grad_b = grad_at(&g);
                        let (t_b, _) = self.face_traction(o, &grad_b, &n);
                        let t_b = t_b + self.offset_at(b, &grad_b);
                        let target = -self.loaded_area(b, &grad_b, &n)
                            * (pr[f - p.start] * self.law.thickness_stretch(o));
                        let g_new = g + (target - t_b) / self.k;
                        self.snd_b[b] = g_new;
                        extrapolated + g_new * self.dn[f]
                    }
                    PatchCondition::Symmetry
                    | PatchCondition::NormalDisplacement(_)
                    | PatchCondition::TangentialDisplacement(_) => {
                        let held = cond.held_projection(&n).unwrap_or_else(Tensor::zeros);
                        extrapolated - held * extrapolated + cond.held_value(f - p.start, &n)
                    }
                    PatchCondition::Empty => self.u[o],
                    PatchCondition::Wedge(r) => {
                        // the cell value at the face centre rotated back into the
                        // cell's plane, then rotated onto the face plane: exact
                        // for linear fields, also for the prisms on the axis
                        let r = r[f - p.start];
                        let back = r.transpose() * self.kb[b]
                            + wedge_back_shift(&r, &n, geom.delta(mesh, f));
                        // (of the increment under the updated Lagrangian form)
                        base + r * ((self.u[o] - self.old(o)) + gp.transpose() * back)
                    }
                    PatchCondition::LinearisedContact(lc) => {
                        // (3.22–3.23) with the traction of eq. 4.52, solved for
                        // the new normal derivative (eq. 4.53):
                        // (I + s N) g = g + (t* − ε β N (u_extr − u_b*) − n·σ_b)/K
                        let i = f - p.start;
                        let g = self.snd_b[b];
                        let grad_b = grad_at(&g);
                        let (t_b, ratio) = self.face_traction(o, &grad_b, &n);
                        let t_b = t_b + self.offset_at(b, &grad_b);
                        // the springs act per current area too: scaled
                        // with t* by the area ratio, the converged face
                        // traction is ratio · t(u_b), the force the
                        // residual applies (unscaled it was off by
                        // (ratio − 1) ε_n N (u_b − u_extr), 1.4 % on the
                        // twisting hemisphere's block, which the next
                        // increment then relaxed)
                        let area_ratio = lc.current_area_ratio(i, ratio);
                        let t_extr = lc.traction_at(i, &extrapolated) * area_ratio;
                        let r = g + (t_extr - t_b) / self.k;
                        let g_new =
                            lc.solve_normal_derivative(i, area_ratio * self.dn[f] / self.k, &r);
                        self.snd_b[b] = g_new;
                        extrapolated + g_new * self.dn[f]
                    }
                };
                self.u_b[b] = u_b;
                // a face off the wedge planes lies on the wedge mid-plane (or
                // in the plane of a 2-D model), where a displacement along an
                // unsolved direction is zero: a traction-type condition
                // whose normal tilts out of that plane (a contact face whose
                // wedge-plane points moved apart) would otherwise give it
                // one, the cell-to-point fit would pass it to the points of
                // the two wedge planes with opposite signs, and the tilt
                // would grow (die drawing with the cylinder as master)
                if !matches!(cond, PatchCondition::Wedge(_)) {
                    for (c, &off) in self.unsolved.iter().enumerate() {
                        if off {
                            self.u_b[b][c] = 0.0;
                            self.snd_b[b][c] = 0.0;
                        }
                    }
                }
            }
        }
        if self.law.is_updated_lagrangian() {
            for ((d, u), o) in self.du.iter_mut().zip(&self.u).zip(&self.u_old) {
                *d = u - o;
            }
            for ((d, u), o) in self.du_b.iter_mut().zip(&self.u_b).zip(&self.u_b_old) {
                *d = u - o;
            }
        }
    }

    /// Cell gradient (least squares) and stress from the current fields:
    /// σ of the total gradient (small strain), or σ from the increment
    /// gradient and the committed state, and σ̂ = jσ·f⁻ᵀ (updated Lagrangian).
    ///
    /// A cell that the current iterate inverts (det f ≤ 0) keeps the stress
    /// and trial state of the previous iterate: an intermediate iterate of
    /// the outer loop may overshoot, and only a converged state has to be
    /// admissible. Returns the first such cell and its det f, if any (the
    /// caller rejects a converged state that still has one).
    pub fn update_gradient_and_stress(
        &mut self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
    ) -> Option<(usize, f64)> {
        {
            let (u, u_b) = if self.law.is_updated_lagrangian() {
                (&self.du, &self.du_b)
            } else {
                (&self.u, &self.u_b)
            };
            self.gradient
                .vector_gradient(mesh, geom, u, u_b, &mut self.grad_u);
        }
        self.update_stress()
    }

    /// Cell gradient of the current u and u_b, of the increment u − u_old
    /// under the updated Lagrangian form formed where it is read (Δu and
    /// Δu_b, which the boundary update refreshes, are left as they are);
    /// the stress is not updated. For an iterate whose cells and boundary
    /// values were mixed (Anderson): the least-squares gradient is linear
    /// in them on a fixed mesh, so the gradient of the mix is the mix of
    /// the gradients.
    pub fn update_gradient(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        let (u, u_b) = (&self.u, &self.u_b);
        if self.law.is_updated_lagrangian() {
            let (u_old, u_b_old) = (&self.u_old, &self.u_b_old);
            self.gradient.vector_gradient_of(
                mesh,
                geom,
                |i| u[i] - u_old[i],
                |b| u_b[b] - u_b_old[b],
                &mut self.grad_u,
            );
        } else {
            self.gradient
                .vector_gradient(mesh, geom, u, u_b, &mut self.grad_u);
        }
    }

    /// Cell stress (and σ̂ under the updated Lagrangian form) from the
    /// current cell gradient. A cell whose increment is not invertible
    /// keeps its previous stress and trial state; the first such cell and
    /// its det f are returned.
    pub fn update_stress(&mut self) -> Option<(usize, f64)> {
        let mut inverted = None;
        match &mut self.law {
            StressLaw::Small(m) => {
                let stress = |sigma: &mut [Tensor], grad: &[Tensor]| {
                    for (s, g) in sigma.iter_mut().zip(grad) {
                        *s = m.stress(g);
                    }
                };
                match self.gradient.halves() {
                    Some(halves) => {
                        let (s0, s1) = self.sigma.split_at_mut(halves.split);
                        let (g0, g1) = self.grad_u.split_at(halves.split);
                        rayon::join(|| stress(s0, g0), || stress(s1, g1));
                    }
                    None => stress(&mut self.sigma, &self.grad_u),
                }
            }
            StressLaw::UpdatedLagrangian { law, state } => {
                for (i, ((g, sig), h)) in self
                    .grad_u
                    .iter()
                    .zip(self.sigma.iter_mut())
                    .zip(self.sigma_hat.iter_mut())
                    .enumerate()
                {
                    let f = Tensor::identity() + g.transpose();
                    match law.update_point(&state.committed(i), g) {
                        Some((s, trial)) => {
                            *sig = s;
                            state.set_trial(i, &trial);
                            *h = updated_lagrangian_stress(&s, &f).unwrap_or(s);
                        }
                        None => {
                            if inverted.is_none() {
                                inverted = Some((i, f.determinant()));
                            }
                        }
                    }
                }
            }
        }
        inverted
    }

    /// Gradient at boundary face f: the cell gradient with its normal part
    /// replaced by the compact normal derivative (u_b − u_P − k_b·∇u_P)/|d_n|
    /// (of the increment under the updated Lagrangian form).
    #[inline]
    fn boundary_gradient(&self, f: usize, b: usize, o: usize, n: &Vector) -> Tensor {
        let gp = self.grad_u[o];
        let (u, u_b) = self.increment();
        let snd = (u_b[b] - u[o] - gp.transpose() * self.kb[b]) / self.dn[f];
        gp + n * (snd - gp.transpose() * n).transpose()
    }

    /// Surface-force tensor σ̂ at boundary face f (σ under small strain).
    #[inline]
    fn boundary_sigma_hat(&self, f: usize, b: usize, o: usize, n: &Vector) -> Tensor {
        let g = self.boundary_gradient(f, b, o, n);
        match &self.face_state {
            Some(fs) => match self.law.point_stress_in(fs, b, &g) {
                Some((_, h)) => h,
                None => self.sigma_hat_at(o, &g),
            },
            None => self.sigma_hat_at(o, &g),
        }
    }

    /// Trial state of the stress faces from their converged face gradient
    /// (before the mesh moves); committed with the cells.
    fn hold_face_states(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        let Some(mut fs) = self.face_state.take() else {
            return;
        };
        if let StressLaw::UpdatedLagrangian { law, .. } = &self.law {
            let ni = mesh.n_internal_faces();
            for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
                if !matches!(
                    cond,
                    PatchCondition::Displacement(_)
                        | PatchCondition::Symmetry
                        | PatchCondition::NormalDisplacement(_)
                        | PatchCondition::TangentialDisplacement(_)
                ) {
                    continue;
                }
                for f in p.faces() {
                    let b = f - ni;
                    let o = mesh.owner[f] as usize;
                    let g = self.boundary_gradient(f, b, o, &geom.face_normal(f));
                    if let Some((_, trial)) = law.update_point(&fs.committed(b), &g) {
                        fs.set_trial(b, &trial);
                    }
                }
            }
        }
        self.face_state = Some(fs);
    }

    /// σ̂ at a point of cell `o` with gradient `grad`, or the cell's own σ̂
    /// when the gradient inverts the point.
    #[inline]
    fn sigma_hat_at(&self, o: usize, grad: &Tensor) -> Tensor {
        match self.law.point_stress(o, grad) {
            Some((_, h)) => h,
            None => {
                if self.inverted_face_point.get().is_none() {
                    self.inverted_face_point.set(Some(o));
                }
                if self.law.is_updated_lagrangian() {
                    self.sigma_hat[o]
                } else {
                    self.sigma[o]
                }
            }
        }
    }

    /// The owner cell of the first boundary face whose face gradient
    /// inverted its point (det f ≤ 0) since the last call, its stress then
    /// taken from the cell: the segregated iteration passes through such
    /// iterates, the state function of Newton's method refuses them.
    pub fn take_inverted_face_point(&self) -> Option<usize> {
        self.inverted_face_point.take()
    }

    /// Computes the force residual F_P of every cell and the force through
    /// every boundary face (see the module documentation).
    pub fn compute_residual(
        &mut self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        params: &MomentumParams,
    ) {
        self.residual_and_face_balance(mesh, geom, params, None);
    }

    /// [`Self::compute_residual`] with the faces of traction-type
    /// conditions (traction, pressure, contact) as unknowns of their own:
    /// the cells take the force of the face's own stress, n·σ̂_b|Γ| (plus
    /// the carried offset), and `face_rows[b]` receives the balance of
    /// face b, the applied force minus that one (eqs. 3.21–3.23 as an
    /// equation rather than a fixed-point step; zero at the solution, where
    /// both forms agree). Other entries of `face_rows` are left alone.
    /// Returns Σ_P (Σ_f |force through f|)² over the cells, the square of
    /// the force scale the residual is judged against.
    pub fn compute_residual_with_face_rows(
        &mut self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        params: &MomentumParams,
        face_rows: &mut [Vector],
    ) -> f64 {
        self.force_scale.clear();
        self.force_scale.resize(mesh.n_cells, 0.0);
        self.residual_and_face_balance(mesh, geom, params, Some(face_rows));
        self.force_scale.iter().map(|s| s * s).sum()
    }

    fn residual_and_face_balance(
        &mut self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        params: &MomentumParams,
        mut face_rows: Option<&mut [Vector]>,
    ) {
        let scale_forces = face_rows.is_some();
        let mut force_scale = std::mem::take(&mut self.force_scale);
        let ni = mesh.n_internal_faces();
        let ul = self.law.is_updated_lagrangian();
        if self.body_force.len() == self.residual.len() {
            for ((r, b), v) in self
                .residual
                .iter_mut()
                .zip(&self.body_force)
                .zip(&geom.cell_volumes)
            {
                *r = b * *v;
            }
        } else {
            self.residual.iter_mut().for_each(|r| *r = Vector::zeros());
        }
        if let Some(inertia) = &self.inertia {
            for (i, (r, u)) in self.residual.iter_mut().zip(&self.u).enumerate() {
                *r += inertia.force(i, u);
            }
        }
        // moved out while the fields are read (no allocation: the buffers return)
        let mut residual = std::mem::take(&mut self.residual);
        let mut face_force = std::mem::take(&mut self.face_force);
        let mut rc_increment = std::mem::take(&mut self.rc_increment);
        let alpha = self.rhie_chow_override.unwrap_or(params.rhie_chow);
        let carry = ul && params.rhie_chow_history == RhieChowHistory::Accumulated;
        if carry && self.rc_carried.len() != ni {
            // once per body: nothing is carried before the first residual
            self.rc_carried = vec![Vector::zeros(); ni];
            rc_increment = vec![Vector::zeros(); ni];
        }
        let sig_cells: &[Tensor] = if ul { &self.sigma_hat } else { &self.sigma };
        let (u_inc, _) = self.increment();
        let faces = InternalFaceForces {
            mesh,
            geom,
            sig_cells,
            grad_u: &self.grad_u,
            u_inc,
            dn: &self.dn,
            rc_carried: &self.rc_carried,
            rc_cell_scale: &self.rc_cell_scale,
            alpha,
            k: self.k,
            carry,
        };
        let scale = if scale_forces {
            &mut force_scale[..]
        } else {
            &mut []
        };
        let rc = if carry {
            &mut rc_increment[..]
        } else {
            &mut []
        };
        match self.gradient.halves() {
            Some(halves) => {
                // each half with the faces of its cells, in the one-thread order
                let (h, fs) = (halves.split, halves.face_split);
                let (r0, r1) = residual.split_at_mut(h);
                let (s0, s1) = if scale.is_empty() {
                    (&mut [][..], &mut [][..])
                } else {
                    scale.split_at_mut(h)
                };
                let (rc0, rc1) = if rc.is_empty() {
                    (&mut [][..], &mut [][..])
                } else {
                    rc.split_at_mut(fs)
                };
                rayon::join(
                    || faces.add_to_cells(0..fs, &[], 0, r0, s0, rc0),
                    || faces.add_to_cells(fs..ni, &halves.cross, h, r1, s1, rc1),
                );
            }
            None => faces.add_to_cells(0..ni, &[], 0, &mut residual, scale, rc),
        }
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let b = f - ni;
                let o = mesh.owner[f] as usize;
                let n = geom.face_normal(f);
                let area = geom.face_areas[f];
                let current_mag = || {
                    if ul {
                        let g = self.boundary_gradient(f, b, o, &n);
                        current_area_vector(true, &g, &area).norm()
                    } else {
                        geom.face_mag(f)
                    }
                };
                // a traction-type face as an unknown: the cell takes the
                // force of the face's own stress, the face row the balance
                let mut balance = |applied: Vector, g: &Tensor| match face_rows.as_deref_mut() {
                    Some(rows) => {
                        let internal = (self.face_traction(o, g, &n).0 + self.offset_at(b, g))
                            * geom.face_mag(f);
                        rows[b] = applied - internal;
                        internal
                    }
                    None => applied,
                };
                let force = match cond {
                    PatchCondition::Displacement(_) => self.boundary_sigma_hat(f, b, o, &n) * area,
                    PatchCondition::Traction(t) => {
                        let g = self.boundary_gradient(f, b, o, &n);
                        balance(
                            t[f - p.start]
                                * (self.loaded_area(b, &g, &n).norm()
                                    * geom.face_mag(f)
                                    * self.law.thickness_stretch(o)),
                            &g,
                        )
                    }
                    PatchCondition::Pressure(pr) => {
                        let g = self.boundary_gradient(f, b, o, &n);
                        balance(
                            -self.loaded_area(b, &g, &n)
                                * (geom.face_mag(f)
                                    * pr[f - p.start]
                                    * self.law.thickness_stretch(o)),
                            &g,
                        )
                    }
                    PatchCondition::LinearisedContact(lc) => {
                        let i = f - p.start;
                        let mag = match lc.moved_area_ratio(i) {
                            Some(r) => r * geom.face_mag(f),
                            None => current_mag(),
                        };
                        let g = self.boundary_gradient(f, b, o, &n);
                        balance(lc.traction_at(i, &self.u_b[b]) * mag, &g)
                    }
                    PatchCondition::Symmetry
                    | PatchCondition::NormalDisplacement(_)
                    | PatchCondition::TangentialDisplacement(_) => {
                        let s = self.boundary_sigma_hat(f, b, o, &n);
                        cond.held_projection(&n).unwrap_or_else(Tensor::zeros) * (s * area)
                    }
                    PatchCondition::Empty => Vector::zeros(),
                    PatchCondition::Wedge(r) => {
                        let r = r[f - p.start];
                        (r * sig_cells[o] * r.transpose()) * area
                    }
                };
                face_force[b] = force;
                residual[o] += force;
                if scale_forces {
                    force_scale[o] += force.norm();
                }
            }
        }
        self.residual = residual;
        self.face_force = face_force;
        self.rc_increment = rc_increment;
        self.force_scale = force_scale;
    }

    /// Boundary (Cauchy) stress at every face of patch `p` (for output).
    pub fn boundary_stress(&self, mesh: &PolyMesh, geom: &MeshGeometry, p: usize) -> Vec<Tensor> {
        let ni = mesh.n_internal_faces();
        mesh.patches[p]
            .faces()
            .map(|f| {
                let o = mesh.owner[f] as usize;
                let n = geom.face_normal(f);
                let g = self.boundary_gradient(f, f - ni, o, &n);
                self.law
                    .point_stress(o, &g)
                    .map_or(self.sigma[o], |(s, _)| s)
            })
            .collect()
    }

    /// Total force exerted on the body through patch `p`.
    pub fn patch_force(&self, mesh: &PolyMesh, p: usize) -> Vector {
        let ni = mesh.n_internal_faces();
        mesh.patches[p]
            .faces()
            .map(|f| self.face_force[f - ni])
            .sum()
    }
}

/// What the force through an internal face reads (see
/// [`InternalFaceForces::force`]).
struct InternalFaceForces<'a> {
    mesh: &'a PolyMesh,
    geom: &'a MeshGeometry,
    /// σ of the cells (σ̂ under the updated Lagrangian form).
    sig_cells: &'a [Tensor],
    grad_u: &'a [Tensor],
    /// u (Δu under the updated Lagrangian form).
    u_inc: &'a [Vector],
    dn: &'a [f64],
    rc_carried: &'a [Vector],
    /// See [`SolidMomentum::rc_cell_scale`].
    rc_cell_scale: &'a [f64],
    /// α_RC.
    alpha: f64,
    /// The implicit stiffness of the Rhie–Chow term.
    k: f64,
    /// Whether the committed increments' Rhie–Chow forces are carried.
    carry: bool,
}

impl InternalFaceForces<'_> {
    /// The force of face `f` on its owner (minus that on its neighbour):
    /// the interpolated σ̂ on the area vector, with the Rhie–Chow term
    /// (and the carried one); and this increment's Rhie–Chow force.
    #[inline]
    fn force(&self, f: usize) -> (Vector, Vector) {
        let (mesh, geom) = (self.mesh, self.geom);
        let o = mesh.owner[f] as usize;
        let nb = mesh.neighbour[f] as usize;
        let w = geom.weight(mesh, f);
        let sig_f = self.sig_cells[o] * w + self.sig_cells[nb] * (1.0 - w);
        let mut force = sig_f * geom.face_areas[f];
        let mut rc = Vector::zeros();
        if self.alpha != 0.0 {
            let grad_f = self.grad_u[o] * w + self.grad_u[nb] * (1.0 - w);
            // the d-vector of the internal face, C_N − C_P
            let d = geom.cell_centres[nb] - geom.cell_centres[o];
            let jump = self.u_inc[nb] - self.u_inc[o] - grad_f.transpose() * d;
            let share = face_scale(self.rc_cell_scale, mesh, f);
            rc = jump * (self.alpha * share * self.k * geom.face_mag(f) / self.dn[f]);
            force += rc;
            if self.carry {
                // the committed increments' forces, moved with the face
                // by f_f = I + (∇Δu)_fᵀ
                let c = self.rc_carried[f];
                force += c + grad_f.transpose() * c;
            }
        }
        (force, rc)
    }

    /// The internal faces' forces on the cells `lo..lo + residual.len()`:
    /// those of `cross` (owner below `lo`) on their neighbour, those of
    /// `faces` on their owner and neighbour, only to cells of this range,
    /// in that order; with Σ|force| into `scale` (when not empty) and this
    /// increment's Rhie–Chow force of `faces` into `rc` (indexed from
    /// `faces.start`, when not empty).
    fn add_to_cells(
        &self,
        faces: std::ops::Range<usize>,
        cross: &[u32],
        lo: usize,
        residual: &mut [Vector],
        scale: &mut [f64],
        rc: &mut [Vector],
    ) {
        let mesh = self.mesh;
        let hi = lo + residual.len();
        for &f in cross {
            let f = f as usize;
            let nb = mesh.neighbour[f] as usize;
            let (force, _) = self.force(f);
            residual[nb - lo] -= force;
            if let Some(s) = scale.get_mut(nb - lo) {
                *s += force.norm();
            }
        }
        let f0 = faces.start;
        for f in faces {
            let o = mesh.owner[f] as usize;
            let nb = mesh.neighbour[f] as usize;
            let (force, rc_f) = self.force(f);
            if let Some(r) = rc.get_mut(f - f0) {
                *r = rc_f;
            }
            residual[o - lo] += force;
            if nb < hi {
                residual[nb - lo] -= force;
            }
            if !scale.is_empty() {
                let m = force.norm();
                scale[o - lo] += m;
                if nb < hi {
                    scale[nb - lo] += m;
                }
            }
        }
    }
}

/// The least share of the Rhie–Chow stiffness a plastically flowing cell
/// keeps. Measured on J2 upsetting and flat-punch indentation (E = 200e3,
/// H' = 1000, share H'/(3μ + H') = 0.0043; docs/solver-notes.md): with no
/// floor the frictionless punch stalled once cells under the punch had
/// flowed and stopped (an odd–even mode the term no longer held), with
/// 0.1 the frictional punch stalled and the sticking block's force rose
/// 5 % over a peer code's; 0.03 ran all nine cases within 1.2 % of
/// CalculiX where it was run.
pub const PLASTIC_RC_SHARE_FLOOR: f64 = 0.03;

/// The Rhie–Chow share of a flowing cell: H'/(3μ + H') for hardening
/// modulus `h` and `mu3` = 3μ, at least [`PLASTIC_RC_SHARE_FLOOR`].
#[inline]
fn flow_share(h: f64, mu3: f64) -> f64 {
    (h / (mu3 + h)).clamp(PLASTIC_RC_SHARE_FLOOR, 1.0)
}

/// The smaller of the two cells' shares of internal face `f` (1 when
/// `cell_scale` is empty).
#[inline]
fn face_scale(cell_scale: &[f64], mesh: &PolyMesh, f: usize) -> f64 {
    if cell_scale.is_empty() {
        return 1.0;
    }
    let o = mesh.owner[f] as usize;
    let n = mesh.neighbour[f] as usize;
    cell_scale[o].min(cell_scale[n])
}

/// The owner's gradient `gp` with its normal part replaced by the boundary
/// normal derivative `g` (eq. 3.23): `gp + n (g − gpᵀn)ᵀ`.
fn face_gradient(gp: &Tensor, n: &Vector, g: &Vector) -> Tensor {
    gp + n * (g - gp.transpose() * n).transpose()
}
