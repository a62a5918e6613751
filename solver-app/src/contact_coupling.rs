//! Contact between bodies with explicit Neumann–Neumann coupling (thesis
//! §4.1.3, §3.3): every outer iteration the contact surfaces are moved to
//! the current displacement (cell-to-point least squares, eqs. 3.31–3.32,
//! or the rigid motion), candidate pairs are detected (§4.2), the contact
//! algorithm computes the tractions on both surfaces (§4.3–4.4), and the
//! under-relaxed tractions (eq. 4.13) become the traction condition of the
//! contact patches.
use crate::case::{
    Augmentation, Case, Coupling as CouplingName, Detection, FacePosition, InputError, ScalarValue,
};
use crate::model::Body;
use crate::profile::Phase;
use contact_detect::{
    CandidatePairs, DetectParams, DetectionMethod, Detector, PairReuse, DEFAULT_SKIN,
};
use contact_force::{
    ContactAlgorithm, ContactLaw, ContactStats, ContactTractions, Coupling, ExplicitRelaxation,
    GgiWeights, PenaltyParams, SurfaceContact, SurfaceMaterial, SymmetryPlane,
};
use fv_discretise::{LinearisedContact, PatchCondition};
use fv_mesh::{CellToPoint, Surface, Vector};

mod algorithm_choice;
mod augmentation_choice;
mod friction_stiffness;
mod frictionless_support;
mod penalty_scale;
mod restart;
mod state_evaluation;
mod traction_jacobian;

pub use algorithm_choice::AlgorithmChoice;
pub use augmentation_choice::AugmentationChoice;
pub use friction_stiffness::{friction_normal_coupling, friction_stiffness};
pub use frictionless_support::frictionless_slide;
pub use penalty_scale::PenaltyScale;
pub use traction_jacobian::TractionJacobianWork;

/// Fraction of a face's previous linearisation contact fraction kept when
/// the face opens against a rigid body (see [`ContactSide::beta`]):
/// without it the face overshoots, separates, and closes again forever.
/// Between two deformable bodies with a stiff penalty β does not fade at
/// all within an increment when their springs are solved coupled
/// ([`ContactSide::beta`]). A β below [`BETA_FLOOR`] is zero.
const BETA_MEMORY: f64 = 0.5;

/// The smallest β kept: a face open for 30 updates has no spring left,
/// instead of one of 1e-83 ε_n (denormal arithmetic, and a spring per
/// GGI pair assembled for nothing).
const BETA_FLOOR: f64 = 1e-9;

/// A face whose gap is at most this fraction of its size (√area) touches
/// and gets the spring of a face in contact (β = 1) although it carries no
/// pressure yet. Bodies meshed touching start so: a punch held by the
/// contact alone was otherwise free in its first outer iteration, sank
/// 0.12 mm (470 times the converged penetration) into its foundation
/// (NAFEMS punch), was thrown clear by the springs of that penetration,
/// and fell back freely for 20 more; with Nagata smoothing the cycle never
/// ended. The springs only shape the path (see [`ContactSide::beta`]).
const TOUCHING_GAP: f64 = 1e-6;

/// Whether face `i` of a contact side carries no pressure but has its gap
/// closed to within [`TOUCHING_GAP`] of its size: bodies meshed touching.
/// A one-sided penalty has no derivative there, so the linearisations
/// give such a face the spring of a face in contact.
pub fn touching_without_pressure(
    side: &ContactSide,
    contact: &contact_force::SurfaceContact,
    i: usize,
) -> bool {
    let c = contact.contact_fraction.get(i).copied().unwrap_or(0.0);
    let g = contact.gap.get(i).copied().unwrap_or(f64::INFINITY);
    c == 0.0 && g.is_finite() && g <= TOUCHING_GAP * side.surface.face_mag[i].sqrt()
}

/// The share of face `i`'s penalty spring in a linearisation: its contact
/// fraction, or 1 where it is [`touching_without_pressure`].
pub fn linearised_fraction(
    side: &ContactSide,
    contact: &contact_force::SurfaceContact,
    i: usize,
) -> f64 {
    if touching_without_pressure(side, contact, i) {
        1.0
    } else {
        contact.contact_fraction.get(i).copied().unwrap_or(0.0)
    }
}

/// ε_n times the mean half-cell compliance δ_n/K of the two contact
/// surfaces above which a pair of deformable bodies counts as stiffly
/// coupled: then the linearisation starts from the carried traction
/// ([`carried_traction_base`]) and the displacement components are solved
/// in turn across the cell springs ([`crate::springs_in_turn`]; formerly
/// the springs got a dominant diagonal instead, the counts below), or,
/// with inclined normals ([`INCLINED_SHARE`]), the springs are solved
/// coupled and β does not fade within the increment.
/// Measured on concentric cylinders (40 against 30 faces; ε_n δ/K ≈ 0.49
/// per unit `penalty_scale`): without it the iteration diverges from
/// `penalty_scale` 6 (ratio 2.9) up — 5.5 still converges, in 783 outer
/// iterations — with it 5.5, 6, 9, 11 and 33.5 (ε_n/E = 1000) take 393,
/// 352, 386, 268 and 297 (with the springs solved coupled,
/// [`INCLINED_SHARE`]: 72, 75, 82, 88 and 123). But at the default penalty (ratio 0.47–0.72
/// on the validation cases) it costs 1.5–2× (concentric cylinders 140 →
/// 222, concentric spheres 102 → 164), and there it stalled curved beams
/// at `penalty_scale` 4 (ratio 2.0); so only above this ratio.
const STIFF_PENALTY: f64 = 2.5;

/// Share of a stiff pair's normal stiffness that couples displacement
/// components ([`ContactInterface::inclined_share`]) above which the
/// springs are solved with their whole tensor
/// ([`crate::coupled_spring_solve`]) instead of the components in turn
/// and the carried-traction base. Measured (with the dominant diagonal
/// that preceded the components in turn): concentric cylinders (normals
/// at every angle, share 0.64) at ε_n/E = 1000 take 123 outer iterations
/// coupled against 297; a sphere on a block (share 0.13–0.16, normals
/// near the axis) takes 362 against 475, but at 4× the wall time (the
/// coupled solve costs about 50 conjugate-gradient iterations per outer
/// iteration on 3-D meshes), so it stays on the segregated path (84 outer
/// iterations in turn since).
const INCLINED_SHARE: f64 = 0.4;

/// Contact updates within one increment after which the tangential
/// relaxation starts to halve, and the updates between halvings: faces
/// that switch between stick and slip from one outer iteration to the next
/// can hold the loop in a cycle (seen as a period-3 cycle of two corner
/// faces of a compressed rubber block); a smaller relaxation damps it. The
/// converged traction does not depend on the relaxation.
const STICK_SLIP_PATIENCE: usize = 150;
/// Smallest fraction of the configured tangential relaxation.
const STICK_SLIP_MIN_FRACTION: f64 = 1.0 / 32.0;

/// Window of contact updates over which explicit coupling judges its
/// normal relaxation (beyond the thesis): when a window has not halved the
/// smallest change of the applied tractions of the window before, and the
/// computed normal force went back and forth in at least an eighth of its
/// updates, the relaxation halves. The relaxed iteration
/// t ← t + α (t_computed − t) is stable only for α below about
/// 2/(1 + ε_n c), c the compliance of the whole contact patch: under a flat
/// punch 40 faces wide (penalty_scale 1) the default 0.1 oscillated for
/// 20,000 outer iterations at a residual of 5e-2. A stable iteration
/// (at least 0.9965 per update) is not touched.
const NORMAL_STALL_PATIENCE: usize = 200;
/// Smallest fraction of the configured normal relaxation.
const NORMAL_MIN_FRACTION: f64 = 1.0 / 64.0;
/// Contact updates of an increment before explicit coupling's normal
/// relaxation may be damped ([`NORMAL_STALL_PATIENCE`]): an iteration that
/// converges slowly but surely, with a small relaxation at a stiff penalty
/// (1,800–2,700 outer iterations in the implicit-efficiency sweeps), is not
/// touched.
const EXPLICIT_DAMPING_START: usize = 4000;

/// Relaxation of the linearised normal traction t* of implicit coupling.
/// With 1 the iteration can settle into a period-two cycle between two
/// deformable bodies whose faceted curved surfaces touch in patches
/// (concentric cylinders, 40 against 30 faces); 0.7 removes it and costs
/// under 10 % more outer iterations on Hertz and the patch test.
const IMPLICIT_NORMAL_RELAXATION: f64 = 0.7;

/// A penalty spring between two cells of the global system (implicit
/// coupling of two deformable bodies).
#[derive(Debug, Clone, Copy)]
pub struct CellSpring {
    /// Global cell numbers (master side, slave side).
    pub cells: (u32, u32),
    /// Spring stiffness along the normal, N/m.
    pub stiffness: f64,
    /// Spring stiffness across the normal (friction linearised as sticking), N/m.
    pub tangential: f64,
    /// Direction of the spring (the master normal): component c carries
    /// stiffness·n_c² + tangential·(1 − n_c²).
    pub normal: Vector,
    /// Solve the components in turn, each with the off-diagonal parts at
    /// the corrections of those before it (stiff pairs whose normals stay
    /// near the axes, `STIFF_PENALTY`; [`crate::springs_in_turn`]).
    pub in_turn: bool,
    /// Solve the whole spring tensor, components coupled (stiff pairs with
    /// inclined normals, `INCLINED_SHARE`; [`crate::coupled_spring_solve`]).
    pub coupled: bool,
}

impl CellSpring {
    /// The diagonal entry (c, c) of the spring tensor k_n n⊗n + k_t (I − n⊗n).
    #[inline]
    pub fn tensor_diagonal(&self, c: usize) -> f64 {
        let nc2 = self.normal[c] * self.normal[c];
        self.stiffness * nc2 + self.tangential * (1.0 - nc2)
    }

    /// The off-diagonal entry (c, d), c ≠ d, of the spring tensor.
    #[inline]
    pub fn tensor_off_diagonal(&self, c: usize, d: usize) -> f64 {
        (self.stiffness - self.tangential) * self.normal[c] * self.normal[d]
    }
}

/// A contact surface: one patch of one body.
pub struct ContactSide {
    /// Body index.
    pub body: usize,
    /// Patch index in the body's mesh.
    pub patch: usize,
    /// The surface at the current positions.
    pub surface: Surface,
    /// The patch is a deformable body's and in several contact pairs (their
    /// coupling is explicit, or implicit against rigid bodies only, checked
    /// when the case is read): its contact condition is the sum of the
    /// pairs' tractions and penalty springs.
    shared: bool,
    /// Positions of the surface points on the body's mesh: initial, or at
    /// the start of the increment under the updated Lagrangian form.
    initial: Vec<Vector>,
    /// Displacement of the surface points (workspace).
    point_u: Vec<Vector>,
    /// Current positions (workspace).
    current: Vec<Vector>,
    /// Face centres of the surface at `initial`.
    initial_centres: Vec<Vector>,
    /// Per face, the boundary displacement minus the displacement of the
    /// moved surface's face centre (`face_position = "boundary-value"`;
    /// empty otherwise, and for a rigid body): [`contact_force::FaceShifts`].
    face_shift: Vec<Vector>,
    /// Applied (relaxed) traction per face.
    pub applied: Vec<Vector>,
    /// GGI-weighted displacement of the opposite body's owner cells at the
    /// last contact evaluation (implicit coupling of deformable bodies).
    opposite_reference: Vec<Vector>,
    /// δ/K of the opposite surface seen by each face (GGI-weighted; 0 when
    /// the opposite body is rigid), eq. 4.64.
    opposite_compliance: Vec<f64>,
    /// The same, now (workspace of [`ContactSet::track_opposite_cells`]).
    opposite_now: Vec<Vector>,
    /// Contact fraction β of the linearisation: the current one or, if
    /// larger, the previous one times [`BETA_MEMORY`], so a face that opened
    /// in one iteration keeps a fading penalty spring in the matrix for a
    /// few more (the springs only shape the path; the converged traction is
    /// the contact algorithm's). Between two stiffly coupled deformable
    /// bodies whose springs are solved coupled the largest β of the
    /// increment is kept: a body held by contact (the inner of two
    /// concentric tubes under pressure) otherwise loses its springs within
    /// three open iterations and crosses the gap several times over in the
    /// next; each increment of a stiff pair starts from the converged β.
    beta: Vec<f64>,
    /// `applied`, `beta` and `opposite_reference` at the start of the
    /// current attempt at an increment (restored when it is redone with a
    /// smaller step).
    saved: (Vec<Vector>, Vec<f64>, Vec<Vector>),
    /// Contact state of every face (open, pressed, sticking, slipping) at
    /// the last renewal of Newton's frozen data
    /// ([`ContactSet::evaluate_state`]).
    state_signature: Vec<u8>,
}

/// GGI-weighted average over the opposite faces of `value(opposite face)`
/// for every face of the master (`master_side`) or the slave surface, into
/// `out` (zero where a face overlaps nothing).
fn ggi_average<T>(ggi: &GgiWeights, master_side: bool, value: impl Fn(usize) -> T, out: &mut [T])
where
    T: Copy + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T> + Default,
{
    for (i, o) in out.iter_mut().enumerate() {
        let (faces, w) = if master_side {
            ggi.master_row(i)
        } else {
            ggi.slave_row(i)
        };
        let (sum, den) = faces
            .iter()
            .zip(w)
            .fold((T::default(), 0.0), |(s, d), (&j, &w)| {
                (s + value(j as usize) * w, d + w)
            });
        *o = if den > 0.0 {
            sum * (1.0 / den)
        } else {
            T::default()
        };
    }
}

/// Sets the opposite-cell shift (u_Ph − u_Ph*, eq. 4.69) of the linearised
/// contact condition of side `this`.
fn track_side(
    ggi: &GgiWeights,
    master_side: bool,
    this: &mut ContactSide,
    other: &ContactSide,
    bodies: &mut [Body],
) {
    let b = &bodies[other.body];
    ggi_average(
        ggi,
        master_side,
        |j| owner_u(b, other, j),
        &mut this.opposite_now,
    );
    if let PatchCondition::LinearisedContact(lc) =
        &mut bodies[this.body].momentum.conditions[this.patch]
    {
        for ((s, u), r) in lc
            .opposite_shift
            .iter_mut()
            .zip(&this.opposite_now)
            .zip(&this.opposite_reference)
        {
            *s = u - r;
        }
    }
}

/// Displacement of the owner cell of face `i` of a contact side.
/// The contact forces of `stats` as the bodies receive them. The contact
/// algorithm integrates the tractions over the moved contact surfaces, but a
/// small-strain body takes its boundary tractions per undeformed area: on
/// soft bodies (Hertz at p0/E ≈ 5 %) the two differ by 1–2 %, and only the
/// second balances the reactions. Rigid and updated-Lagrangian bodies take
/// the current areas, as the algorithm did. The normal and frictional force
/// are those on the master body, or, when the master is rigid, minus those
/// on the slave.
fn transmitted_forces(
    stats: &mut ContactStats,
    tractions: &ContactTractions,
    master: &ContactSide,
    slave: &ContactSide,
    bodies: &[Body],
) {
    let on_body = |side: &ContactSide, contact: &SurfaceContact| {
        let b = &bodies[side.body];
        let (mut normal, mut tangential, mut total) = (0.0, Vector::zeros(), Vector::zeros());
        for f in 0..contact.n_faces() {
            let a = if b.rigid || b.momentum.law.is_updated_lagrangian() {
                side.surface.face_mag[f]
            } else {
                b.geom.face_mag(b.mesh.patches[side.patch].start + f)
            };
            normal += contact.pressure[f] * a;
            tangential += contact.tangential_traction[f] * a;
            total += contact.traction(f) * a;
        }
        (normal, tangential, total)
    };
    let (normal_m, tangential_m, total_m) = on_body(master, &tractions.master);
    let (normal_s, tangential_s, total_s) = on_body(slave, &tractions.slave);
    (stats.normal_force, stats.tangential_force) = if bodies[master.body].rigid {
        (normal_s, -tangential_s)
    } else {
        (normal_m, tangential_m)
    };
    stats.master_force = total_m;
    stats.slave_force = total_s;
}

/// The planar `symmetry` and `wedge` patches of a body as planes: a
/// smoothed master's point normals lie in them (thesis Fig. 4.40; on a
/// wedge plane the axisymmetric normal lies in the plane as well), and the
/// pointwise algorithm does not count the master's edges on them as the
/// surface's border. A curved one is left out.
fn symmetry_planes(body: &Body) -> Vec<SymmetryPlane> {
    let g = &body.geom;
    let mut planes = Vec::new();
    for (p, cond) in body.mesh.patches.iter().zip(&body.momentum.conditions) {
        let Some(first) = p.faces().next() else {
            continue;
        };
        if !matches!(cond, PatchCondition::Symmetry | PatchCondition::Wedge(_)) {
            continue;
        }
        let (c0, n0) = (g.face_centres[first], g.face_normal(first));
        let extent = p
            .faces()
            .fold(0.0f64, |e, f| e.max((g.face_centres[f] - c0).norm()));
        let planar = p.faces().all(|f| {
            g.face_normal(f).dot(&n0) > 1.0 - 1e-9
                && (g.face_centres[f] - c0).dot(&n0).abs() <= 1e-9 * extent.max(1.0)
        });
        if planar {
            planes.push(SymmetryPlane::new(c0, n0));
        }
    }
    planes
}

fn owner_u(b: &Body, side: &ContactSide, i: usize) -> Vector {
    b.momentum.u[b.mesh.owner[b.mesh.patches[side.patch].start + i] as usize]
}

/// δ_n/K of the owner cell of face `i` of a contact side (c_i of eq. 4.64);
/// 0 for a rigid body.
fn half_cell_compliance(b: &Body, side: &ContactSide, i: usize) -> f64 {
    if b.rigid {
        return 0.0;
    }
    let f = b.mesh.patches[side.patch].start + i;
    b.momentum.normal_distance(f) / b.momentum.k
}

/// The base traction of eq. 4.52 for a face whose spring reaches the
/// opposite *cell* through the opposite half cell (c_h): the opposite face
/// moves by c_h times the change of the traction it carries, so the
/// linearisation starts from the traction the half cells carry now,
/// `carried` (eq. 4.52 at the current u_b; this face's, standing for the
/// opposite one's, which matches it once converged), and moves towards the
/// contact algorithm's `target` by 1/(1 + ε_n β c_h) — eqs. 4.60 and 4.56
/// with the opposite face eliminated, as in eq. 4.68 (its u_bh* and a_h
/// terms). Starting from `target` instead assumes the opposite half cell
/// already carries it: where the traction jumps (faceted arcs interfering
/// by 1.8e-4 m at ε_n/E = 1000, t* 18× the load) the first solve then
/// opened the gap to ten times the interference. `s_n` = ε_n β c_h and
/// `s_t` = ε_t β c_h split the change along `normal` and across it. At
/// convergence `carried` = `target` and the base is the contact traction.
fn carried_traction_base(
    carried: Vector,
    target: Vector,
    normal: Vector,
    s_n: f64,
    s_t: f64,
) -> Vector {
    let d = target - carried;
    let dn = normal * normal.dot(&d);
    carried + dn / (1.0 + s_n) + (d - dn) / (1.0 + s_t)
}

/// One `[[contact]]` pair with its detector, algorithm and coupling state.
pub struct ContactInterface {
    /// `<body>/<patch>` of the slave, for reports.
    pub slave_name: String,
    /// `<body>/<patch>` of the master, for reports.
    pub master_name: String,
    /// Master side.
    pub master: ContactSide,
    /// Slave side.
    pub slave: ContactSide,
    /// The normal penalty scale and why (given or chosen).
    pub penalty_scale: PenaltyScale,
    /// Augmented Lagrangian updates or not, and why (given or chosen).
    pub augmentation_choice: AugmentationChoice,
    /// The contact algorithm, and why.
    pub algorithm_choice: AlgorithmChoice,
    detector: Box<dyn Detector + Send>,
    pairs: CandidatePairs,
    /// The last detection (Newton–Krylov: `pairs` is the union of the
    /// attempt's detections, `state_evaluation::accumulate_pairs`).
    detected: CandidatePairs,
    /// Whether `pairs` holds a detection of the current attempt.
    pairs_this_attempt: bool,
    algorithm: Box<dyn ContactAlgorithm>,
    law: ContactLaw,
    params: PenaltyParams,
    /// μ against time (`friction` of the case: a constant or a table).
    friction: ScalarValue,
    /// (K, G, Ω/Γ) per face of the master and the slave; `None` = rigid.
    materials: [Option<FaceMaterial>; 2],
    /// Whether the penalty was evaluated on the contacting faces of this increment.
    penalty_localised: bool,
    coupling: ExplicitRelaxation,
    /// `coupling` (its accumulated tractions λ of eq. 4.13) at the start of
    /// the current attempt at an increment.
    coupling_saved: ExplicitRelaxation,
    /// The GGI weights of the last contact update before the attempt: the
    /// first outer iteration of a redone attempt averages the opposite
    /// cells with them (eq. 4.69), as `opposite_reference` was averaged.
    ggi_saved: GgiWeights,
    /// The configured tangential relaxation (before any damping).
    tangential_relaxation: f64,
    /// The configured normal relaxation of explicit coupling, and the
    /// fraction of it in use ([`NORMAL_STALL_PATIENCE`]; kept for the run).
    normal_relaxation: f64,
    normal_damping: f64,
    /// Smallest relative change of the applied tractions in the last
    /// window of [`NORMAL_STALL_PATIENCE`] contact updates, and in the
    /// current window; the updates of the current window.
    best_change: f64,
    window_min: f64,
    window_updates: usize,
    /// The computed normal force, its last change, and how often the
    /// change flipped sign in the current window (an oscillation, not a
    /// slow approach).
    last_force: f64,
    last_force_change: f64,
    flips: usize,
    /// Implicit coupling (thesis §4.5): linearised normal traction.
    pub implicit: bool,
    /// Gaps between the faces at their boundary displacements
    /// ([`FacePosition::BoundaryValue`]).
    face_shifts: bool,
    /// Both bodies are deformable (the springs join cells of two bodies).
    pub deformable_pair: bool,
    /// A deformable pair with ε_n δ/K above [`STIFF_PENALTY`] (set until
    /// the penalty of the increment is localised: neither ε_n nor the
    /// geometry changes within an increment after that).
    stiff: bool,
    /// A stiff pair whose springs are solved with the components coupled
    /// ([`INCLINED_SHARE`]); once set it holds until the increment ends.
    coupled_components: bool,
    /// Augmented Lagrangian updates (`contact.augmentation`), the
    /// multiplier λ per slave face (the pressure the penalty adds to), its
    /// value at the start of the attempt, the updates made in the
    /// increment, and the slave faces' shifts with λ/ε_n (workspace).
    augmentation: Option<Augmentation>,
    multiplier: Vec<f64>,
    multiplier_saved: Vec<f64>,
    augmentation_updates: usize,
    /// Multiplier updates of the accepted increments, over the run.
    pub augmentation_updates_run: usize,
    /// The largest true penetration and the slave cells' mean height at the
    /// increment's first multiplier update (for the log).
    first_update: (f64, f64),
    /// The largest true penetration at the increment's last multiplier
    /// update ([`STALL_RATIO`]).
    last_update_penetration: f64,
    augmented_shift: Vec<Vector>,
    /// λ/ε_n averaged onto the master faces (workspace).
    augmented_master: Vec<f64>,
    /// Tractions, pressures and gaps of the last call.
    pub tractions: ContactTractions,
    /// Summary of the last call.
    pub stats: ContactStats,
}

impl ContactInterface {
    /// Whether μ is zero at every time.
    pub fn frictionless(&self) -> bool {
        match &self.friction {
            ScalarValue::Constant(mu) => *mu == 0.0,
            ScalarValue::Table(rows) => rows.iter().all(|&(_, mu)| mu == 0.0),
        }
    }

    /// The gaps the algorithm measured with the slave faces moved on by
    /// λ/ε_n ([`ContactSet::update`]) back to the faces' own: the output
    /// and the augmentation's test see the true penetration.
    fn unshift_augmented_gaps(&mut self) {
        let eps = self.law.normal_penalty;
        if !(eps > 0.0) || self.multiplier.is_empty() {
            return;
        }
        let slave = &mut self.tractions.slave;
        let mut max_penetration = 0.0f64;
        for (f, g) in slave.gap.iter_mut().enumerate() {
            if g.is_finite() {
                *g += self.multiplier.get(f).copied().unwrap_or(0.0) / eps;
                if slave.pressure[f] > 0.0 {
                    max_penetration = max_penetration.max(-*g);
                }
            }
        }
        self.stats.max_penetration = max_penetration;
        // the master faces' gaps were measured against the moved slave
        // faces they overlap (GGI weights)
        let master = &mut self.tractions.master;
        self.augmented_master.resize(master.gap.len(), 0.0);
        let multiplier = &self.multiplier;
        ggi_average(
            &self.tractions.ggi,
            true,
            |j| multiplier.get(j).copied().unwrap_or(0.0) / eps,
            &mut self.augmented_master,
        );
        for (g, &d) in master.gap.iter_mut().zip(&self.augmented_master) {
            if g.is_finite() {
                *g += d;
            }
        }
    }

    /// One Uzawa update of the augmented Lagrangian, λ ← p (the pressure
    /// λ + ε_n g⁻ of the last contact update), unless the largest true
    /// penetration is within `penetration` of the mean height of the slave
    /// cells in contact (and, with `pressure`, ε_n times it within
    /// `pressure` of the largest contact pressure), the increment has had
    /// its `max_updates`, or the last update did not reduce the
    /// penetration ([`STALL_RATIO`]).
    /// Returns whether λ changed (the outer loop must go on).
    fn augment(&mut self, bodies: &[Body]) -> bool {
        let Some(aug) = self.augmentation else {
            return false;
        };
        let n = self.slave.surface.n_faces();
        if self.multiplier.len() != n {
            self.multiplier = vec![0.0; n];
        }
        let pressure = &self.tractions.slave.pressure;
        if pressure.len() != n || self.augmentation_updates >= aug.max_updates {
            return false;
        }
        // mean height of the slave cells in contact (the case reader
        // refuses a rigid slave with augmentation)
        let b = &bodies[self.slave.body];
        let first = b.mesh.patches[self.slave.patch].start;
        let (mut h, mut k) = (0.0, 0usize);
        for (f, &p) in pressure.iter().enumerate() {
            if p > 0.0 {
                h += 2.0 * b.momentum.normal_distance(first + f);
                k += 1;
            }
        }
        let within_height = self.stats.max_penetration <= aug.penetration * h / k as f64;
        let within_pressure = aug.pressure.is_none_or(|share| {
            let p_max = pressure.iter().fold(0.0f64, |m, &p| m.max(p));
            self.law.normal_penalty * self.stats.max_penetration <= share * p_max
        });
        if k == 0 || (within_height && within_pressure) {
            return false;
        }
        if self.augmentation_updates > 0
            && self.stats.max_penetration > STALL_RATIO * self.last_update_penetration
        {
            return false;
        }
        self.last_update_penetration = self.stats.max_penetration;
        if self.augmentation_updates == 0 {
            self.first_update = (self.stats.max_penetration, h / k as f64);
        }
        for (l, &p) in self.multiplier.iter_mut().zip(pressure) {
            *l = if p.is_finite() { p.max(0.0) } else { 0.0 };
        }
        self.augmentation_updates += 1;
        true
    }
}

/// All contacts of a case plus the cell-to-point operators they need.
#[derive(Default)]
pub struct ContactSet {
    /// The contact pairs in case order.
    pub interfaces: Vec<ContactInterface>,
    /// Cell-to-point interpolation of every body (built for bodies in contact).
    cell_to_point: Vec<Option<CellToPoint>>,
    /// Contact updates in the current increment (attempt).
    updates_in_increment: usize,
    /// Seconds in detection and in the contact force.
    pub times: crate::profile::PhaseTimes,
    /// Contacts whose multipliers were first updated in the increments
    /// committed since [`Self::take_newly_augmented`] was last called.
    newly_augmented: Vec<usize>,
    /// `FVC_TRACE=2`: print the contact statistics of every update (read
    /// once, not per outer iteration).
    trace: bool,
    /// See [`ContactSet::deepest_penetration`].
    deepest_penetration: f64,
}

fn side(
    bodies: &[Body],
    case: &Case,
    key: &str,
    (body, patch): &(String, String),
) -> Result<(usize, usize), InputError> {
    let src = &case.source;
    let bi = bodies
        .iter()
        .position(|b| &b.name == body)
        .ok_or_else(|| src.error(key, format!("unknown body '{body}'")))?;
    let b = &bodies[bi];
    let pi = b.mesh.patch_index(patch).ok_or_else(|| {
        let names: Vec<&str> = b.mesh.patches.iter().map(|p| p.name.as_str()).collect();
        src.error(
            key,
            format!(
                "body '{body}' has no patch '{patch}'; its mesh has: {}",
                names.join(", ")
            ),
        )
    })?;
    if b.mesh.patches[pi].size == 0 {
        return Err(src.error(
            key,
            format!("patch '{body}/{patch}' has no faces, so it cannot be a contact surface"),
        ));
    }
    if b.patch_specs[pi].is_some() && !b.rigid {
        return Err(src.error(
            key,
            format!("patch '{body}/{patch}' is a contact surface and must not have a boundary condition of its own (remove [body.boundary.{patch}])"),
        ));
    }
    Ok((bi, pi))
}

/// K, G and Ω/Γ per face of a contact surface (inputs of eqs. 4.4a/4.4b).
type FaceMaterial = (Vec<f64>, Vec<f64>, Vec<f64>);

fn surface_material(body: &Body, surface: &Surface) -> FaceMaterial {
    let n = surface.n_faces();
    let k = vec![body.momentum.law.implicit_stiffness(); n];
    let g = vec![body.momentum.law.shear_modulus(); n];
    let len = surface
        .faces
        .iter()
        .map(|&f| {
            let f = f as usize;
            body.geom.cell_volumes[body.mesh.owner[f] as usize] / body.geom.face_mag(f)
        })
        .collect();
    (k, g, len)
}

/// Augmented Lagrangian: an update of the multipliers must have brought the
/// largest penetration under this fraction of the one at the previous
/// update, or the increment makes no more updates (beyond the thesis). On a
/// nearly incompressible body the per-face penetrations keep an odd–even
/// part that Uzawa updates do not reduce: in the die drawing (ν = 0.495,
/// penalty scale 1, tolerance 1e-3 of the cell height) the largest
/// penetration stalled at 1.1–1.2 times the tolerance after five updates,
/// every further update fed the multipliers' alternation along the land
/// (neighbouring faces at 0.02 and 2.4 MPa where the pressure is 1.4 MPa),
/// and the run diverged at 0.18 m, where the drawn material reaches the
/// land, at every cut-back. Stopping there it runs to the end: steady force
/// 626.0 N (−2.25 % against eq. 5.1), 1,338 outer iterations per
/// increment. Where the updates converge (Hertz cylinder: 83 → 114 outer
/// iterations, peak pressure −7.6 → −0.8 %; sphere on a block: largest
/// penetration 2.8e-4 → 5.6e-6 m in two updates) nothing changes.
const STALL_RATIO: f64 = 0.7;

/// Penalty parameters (eqs. 4.4a/4.4b) from the faces of both deformable
/// surfaces, or, with `pairs`, from the faces that have a candidate partner
/// only: Γ_c and Ω_c are averages over the *contacting* faces and cells
/// (thesis §4.1.2), so a surface refined at the contact gets the penalty of
/// its contact cells, not of its coarse far field.
fn penalty_law(
    params: &PenaltyParams,
    master: &Surface,
    slave: &Surface,
    materials: &[Option<FaceMaterial>; 2],
    pairs: Option<&CandidatePairs>,
) -> Result<ContactLaw, contact_force::ContactError> {
    let masked = |side: usize, n: usize| -> Option<Vec<f64>> {
        let pairs = pairs?;
        let mut keep = vec![false; n];
        for (m, s) in pairs.iter() {
            keep[if side == 0 { m } else { s } as usize] = true;
        }
        let k = &materials[side].as_ref()?.0;
        Some(
            k.iter()
                .zip(&keep)
                .map(|(&k, &keep)| if keep { k } else { 0.0 })
                .collect(),
        )
    };
    let km = masked(0, master.n_faces());
    let ks = masked(1, slave.n_faces());
    fn view<'a>(
        material: &'a Option<FaceMaterial>,
        k: &'a Option<Vec<f64>>,
    ) -> Option<SurfaceMaterial<'a>> {
        material.as_ref().map(|(kf, g, l)| SurfaceMaterial {
            stiffness: k.as_deref().unwrap_or(kf),
            shear_modulus: g,
            cell_length: l,
        })
    }
    let (mm, sm) = (view(&materials[0], &km), view(&materials[1], &ks));
    params.contact_law(master, mm.as_ref(), slave, sm.as_ref())
}

impl ContactInterface {
    /// The normal penalty ε_n in use (eq. 4.4a, Pa/m): after the first
    /// contact update of an increment, from the faces that have a candidate
    /// partner.
    pub fn normal_penalty(&self) -> f64 {
        self.law.normal_penalty
    }

    /// The tangential (stick) penalty ε_t in use (eq. 4.4b) when the pair
    /// has friction, else 0.
    pub fn tangential_penalty(&self) -> f64 {
        if self.law.friction > 0.0 {
            self.law.tangential_penalty
        } else {
            0.0
        }
    }

    /// The opposite cells' displacements, GGI-averaged onto each side's
    /// faces (u_Ph* of eq. 4.69), as the reference their motion is measured
    /// from until the next contact evaluation.
    fn record_opposite_reference(&mut self, bodies: &[Body]) {
        let (bm, bs) = (&bodies[self.master.body], &bodies[self.slave.body]);
        let (master, slave, ggi) = (&mut self.master, &mut self.slave, &self.tractions.ggi);
        ggi_average(
            ggi,
            true,
            |j| owner_u(bs, slave, j),
            &mut master.opposite_reference,
        );
        ggi_average(
            ggi,
            false,
            |j| owner_u(bm, master, j),
            &mut slave.opposite_reference,
        );
    }

    /// The deformable sides' patches as linearised contact conditions
    /// (implicit coupling, eq. 4.52), grounded against a rigid body.
    fn linearise_patches(&self, bodies: &mut [Body]) {
        let grounded = bodies[self.master.body].rigid || bodies[self.slave.body].rigid;
        for side in [&self.master, &self.slave] {
            let b = &mut bodies[side.body];
            if !b.rigid {
                let mut lc = LinearisedContact::new(side.surface.n_faces());
                lc.grounded = grounded;
                b.momentum.conditions[side.patch] = PatchCondition::LinearisedContact(lc);
            }
        }
    }
}

impl ContactInterface {
    /// Explicit coupling, after [`EXPLICIT_DAMPING_START`] contact updates
    /// of the increment (`updates`): records the relative change `change`
    /// of the applied tractions of this update, and at the end of each
    /// window of [`NORMAL_STALL_PATIENCE`] updates halves the normal
    /// relaxation in use (down to [`NORMAL_MIN_FRACTION`] of the configured
    /// one; [`ContactSet::update`] applies it) if the window stalled while
    /// the force oscillated.
    fn damp_stalled_normal_relaxation(&mut self, change: f64, updates: usize) {
        if updates <= EXPLICIT_DAMPING_START {
            return;
        }
        let force_change = self.stats.normal_force - self.last_force;
        self.last_force = self.stats.normal_force;
        self.flips += usize::from(force_change * self.last_force_change < 0.0);
        self.last_force_change = force_change;
        self.window_min = self.window_min.min(change);
        self.window_updates += 1;
        if self.window_updates < NORMAL_STALL_PATIENCE {
            return;
        }
        // a window of updates that did not halve the smallest change of the
        // one before, the computed force going back and forth (a slow
        // approach neither stalls nor flips)
        let stalled = !(self.window_min <= 0.5 * self.best_change);
        let oscillating = 8 * self.flips >= self.window_updates;
        if stalled && oscillating && self.normal_damping > NORMAL_MIN_FRACTION {
            self.normal_damping *= 0.5;
            self.best_change = f64::INFINITY;
        } else {
            self.best_change = self.window_min;
        }
        self.window_min = f64::INFINITY;
        self.window_updates = 0;
        self.flips = 0;
    }

    /// β of the linearisation from the last contact fractions: the larger
    /// of the fraction and `memory` times the previous β (0: the fraction).
    /// A face without pressure whose gap is closed to within
    /// [`TOUCHING_GAP`] of its size counts as wholly in contact.
    fn update_beta(&mut self, memory: f64) {
        for (side, fraction) in [
            (&mut self.master, &self.tractions.master),
            (&mut self.slave, &self.tractions.slave),
        ] {
            for i in 0..side.beta.len() {
                let c = linearised_fraction(side, fraction, i);
                let b = &mut side.beta[i];
                let kept = *b * memory;
                *b = if kept < BETA_FLOOR { c } else { kept.max(c) };
            }
        }
    }

    /// Share of the contact normal stiffness that couples displacement
    /// components, Σ_f |Γ_f| Σ_{c≠d} |n_c n_d| / Σ_f |Γ_f| over the master
    /// faces under pressure: 0 for normals along an axis, 2/π for 2-D
    /// normals spread evenly over a quarter circle.
    fn inclined_share(&self) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        let pressure = &self.tractions.master.pressure;
        let surface = &self.master.surface;
        for (f, &p) in pressure.iter().enumerate().take(surface.n_faces()) {
            if !(p > 0.0) {
                continue;
            }
            let n = surface.face_normals[f];
            let a = surface.face_mag[f];
            num += a * 2.0 * ((n.x * n.y).abs() + (n.y * n.z).abs() + (n.x * n.z).abs());
            den += a;
        }
        if den > 0.0 {
            num / den
        } else {
            0.0
        }
    }

    /// Whether the pair is deformable and ε_n times the mean half-cell
    /// compliance of both surfaces exceeds [`STIFF_PENALTY`].
    fn stiffly_coupled(&self, bodies: &[Body]) -> bool {
        if !self.deformable_pair {
            return false;
        }
        let (bm, bs) = (&bodies[self.master.body], &bodies[self.slave.body]);
        let (nm, ns) = (self.master.surface.n_faces(), self.slave.surface.n_faces());
        let sum = (0..nm)
            .map(|i| half_cell_compliance(bm, &self.master, i))
            .chain((0..ns).map(|i| half_cell_compliance(bs, &self.slave, i)))
            .sum::<f64>();
        self.law.normal_penalty * sum / (nm + ns).max(1) as f64 > STIFF_PENALTY
    }
}

impl ContactSet {
    /// Whether body `bi` is a side of any contact pair.
    pub fn involves(&self, bi: usize) -> bool {
        self.interfaces
            .iter()
            .any(|c| c.master.body == bi || c.slave.body == bi)
    }

    /// Whether a face of a deformable body's contact side is
    /// [`touching_without_pressure`] at the last evaluation.
    pub fn any_touching_without_pressure(&self, bodies: &[Body]) -> bool {
        self.interfaces.iter().any(|c| {
            [
                (&c.master, &c.tractions.master),
                (&c.slave, &c.tractions.slave),
            ]
            .into_iter()
            .any(|(side, contact)| {
                !bodies[side.body].rigid
                    && (0..side.surface.n_faces())
                        .any(|i| touching_without_pressure(side, contact, i))
            })
        })
    }

    /// Builds the contact pairs of a case (after the bodies).
    pub fn new(case: &Case, bodies: &[Body]) -> Result<Self, InputError> {
        let src = &case.source;
        let mut set = ContactSet {
            interfaces: Vec::new(),
            cell_to_point: (0..bodies.len()).map(|_| None).collect(),
            updates_in_increment: 0,
            times: Default::default(),
            newly_augmented: Vec::new(),
            trace: std::env::var_os("FVC_TRACE").is_some_and(|v| v == "2"),
            deepest_penetration: 0.0,
        };
        for (ci, c) in case.contacts.iter().enumerate() {
            let key = format!("contact[{ci}]");
            let implicit = c.coupling == CouplingName::Implicit;
            let detection = match c.detection {
                Detection::AdvancingFront => "advancing-front",
                Detection::Bvh => "bvh",
                Detection::BruteForce => "brute-force",
            };
            let method = DetectionMethod::from_name(detection)
                .map_err(|e| src.error(&format!("{key}.detection"), e.to_string()))?;
            let (mb, mp) = side(bodies, case, &format!("{key}.master"), &c.master)?;
            let (sb, sp) = side(bodies, case, &format!("{key}.slave"), &c.slave)?;
            let algorithm_choice =
                AlgorithmChoice::choose(c.algorithm, &c.friction, (&bodies[mb], mp), &bodies[sb]);
            let kind = algorithm_choice.value();
            let make_side = |b: usize, p: usize| -> Result<ContactSide, InputError> {
                let surface = Surface::new(&bodies[b].mesh, p)
                    .map_err(|e| src.error(&key, format!("contact surface: {e}")))?;
                let n = surface.n_points();
                Ok(ContactSide {
                    body: b,
                    patch: p,
                    initial: surface.points.clone(),
                    point_u: vec![Vector::zeros(); n],
                    current: surface.points.clone(),
                    initial_centres: surface.face_centres.clone(),
                    face_shift: Vec::new(),
                    applied: vec![Vector::zeros(); surface.n_faces()],
                    opposite_compliance: vec![0.0; surface.n_faces()],
                    opposite_reference: vec![Vector::zeros(); surface.n_faces()],
                    opposite_now: vec![Vector::zeros(); surface.n_faces()],
                    beta: vec![0.0; surface.n_faces()],
                    saved: (Vec::new(), Vec::new(), Vec::new()),
                    state_signature: Vec::new(),
                    shared: false,
                    surface,
                })
            };
            let master = make_side(mb, mp)?;
            let slave = make_side(sb, sp)?;
            let materials = [
                (!bodies[mb].rigid).then(|| surface_material(&bodies[mb], &master.surface)),
                (!bodies[sb].rigid).then(|| surface_material(&bodies[sb], &slave.surface)),
            ];
            let stiff_ok =
                case.solver.nonlinear == fv_nonlinear::NonlinearMethod::NewtonKrylov || implicit;
            let penalty_scale = PenaltyScale::choose(
                c.penalty_scale,
                (&bodies[mb], mp),
                (&bodies[sb], sp),
                stiff_ok,
            );
            let augmentation_choice =
                AugmentationChoice::choose(c.augmentation, (&bodies[mb], mp), (&bodies[sb], sp));
            let params = PenaltyParams {
                penalty_scale: penalty_scale.value(),
                tangential_penalty_scale: c.tangential_penalty_scale,
                friction: c.friction.at(0.0),
                slip_history: c.slip_history,
            };
            let law = penalty_law(&params, &master.surface, &slave.surface, &materials, None)
                .map_err(|e| src.error(&key, e.to_string()))?;
            // implicit: the normal (§4.5) and the frictional traction are
            // linearised and only mildly relaxed
            let (normal_relaxation, tangential_relaxation) = if implicit {
                (IMPLICIT_NORMAL_RELAXATION, IMPLICIT_NORMAL_RELAXATION)
            } else {
                (c.relaxation_normal, c.relaxation_tangential)
            };
            let coupling = ExplicitRelaxation::new(normal_relaxation, tangential_relaxation)
                .map_err(|e| src.error(&format!("{key}.relaxation"), e.to_string()))?;
            // the configured method searches; between searches the pairs
            // are found among those listed then (same pairs, see PairReuse)
            let detector: Box<dyn Detector + Send> = Box::new(
                PairReuse::new(method, DetectParams::default(), DEFAULT_SKIN)
                    .map_err(|e| src.error(&format!("{key}.detection"), e.to_string()))?,
            );
            for b in [mb, sb] {
                if !bodies[b].rigid && set.cell_to_point[b].is_none() {
                    set.cell_to_point[b] = Some(CellToPoint::new(&bodies[b].mesh, &bodies[b].geom));
                }
            }
            let mut algorithm = kind.build();
            // the model's symmetry planes: a rigid master has no conditions
            // of its own, but a plane of the slave's cuts it alike (the
            // die of an axisymmetric die drawing)
            let mut planes = symmetry_planes(&bodies[mb]);
            planes.extend(symmetry_planes(&bodies[sb]));
            algorithm.set_symmetry_planes(&planes);
            set.interfaces.push(ContactInterface {
                slave_name: format!("{}/{}", c.slave.0, c.slave.1),
                master_name: format!("{}/{}", c.master.0, c.master.1),
                master,
                slave,
                penalty_scale,
                augmentation_choice,
                algorithm_choice,
                detector,
                pairs: CandidatePairs::new(),
                detected: CandidatePairs::new(),
                pairs_this_attempt: false,
                algorithm,
                law,
                params,
                friction: c.friction.clone(),
                materials,
                penalty_localised: false,
                coupling_saved: coupling.clone(),
                ggi_saved: GgiWeights::new(),
                coupling,
                tangential_relaxation,
                normal_relaxation,
                normal_damping: 1.0,
                best_change: f64::INFINITY,
                window_min: f64::INFINITY,
                window_updates: 0,
                last_force: 0.0,
                last_force_change: 0.0,
                flips: 0,
                implicit,
                face_shifts: c.face_position == FacePosition::BoundaryValue,
                deformable_pair: !bodies[mb].rigid && !bodies[sb].rigid,
                stiff: false,
                coupled_components: false,
                augmentation: augmentation_choice.value(),
                multiplier: Vec::new(),
                multiplier_saved: Vec::new(),
                augmentation_updates: 0,
                augmentation_updates_run: 0,
                first_update: (0.0, 0.0),
                last_update_penetration: 0.0,
                augmented_shift: Vec::new(),
                augmented_master: Vec::new(),
                tractions: ContactTractions::new(),
                stats: ContactStats::default(),
            });
        }
        let mut uses = std::collections::HashMap::<(usize, usize), usize>::new();
        for side in set.interfaces.iter().flat_map(|c| [&c.master, &c.slave]) {
            *uses.entry((side.body, side.patch)).or_default() += 1;
        }
        for c in &mut set.interfaces {
            for side in [&mut c.master, &mut c.slave] {
                side.shared = !bodies[side.body].rigid && uses[&(side.body, side.patch)] > 1;
            }
        }
        Ok(set)
    }

    /// The friction coefficients at time `t` (the end of the increment
    /// about to be solved): μ of a `friction` time table applies from the
    /// first increment whose end time it covers.
    pub fn set_time(&mut self, t: f64) {
        for ci in &mut self.interfaces {
            let mu = ci.friction.at(t);
            ci.params.friction = mu;
            ci.law.friction = mu;
        }
    }

    /// Whether there is any contact.
    pub fn is_empty(&self) -> bool {
        self.interfaces.is_empty()
    }

    /// Whether any contact uses implicit coupling (the matrix then changes
    /// every outer iteration).
    pub fn is_implicit(&self) -> bool {
        self.interfaces.iter().any(|c| c.implicit)
    }

    /// The smallest fraction of its configured normal relaxation that an
    /// explicitly coupled contact uses (1 when none was damped): the outer
    /// tolerance is scaled by it, since the displacement correction that
    /// the tractions cause shrinks with the relaxation.
    pub fn explicit_relaxation_fraction(&self) -> f64 {
        self.interfaces
            .iter()
            .filter(|c| !c.implicit)
            .map(|c| c.normal_damping)
            .fold(1.0, f64::min)
    }

    /// Turns the contact patches of implicitly coupled contacts into
    /// linearised contact conditions (called once, after the bodies are built).
    pub fn prepare_conditions(&self, bodies: &mut [Body]) {
        for ci in self.interfaces.iter().filter(|c| c.implicit) {
            ci.linearise_patches(bodies);
        }
    }

    /// Whether any contact is coupled explicitly.
    pub fn has_explicit(&self) -> bool {
        self.interfaces.iter().any(|c| !c.implicit)
    }

    /// The explicitly coupled contacts (their indices in the case).
    pub fn explicit_contacts(&self) -> Vec<usize> {
        (0..self.interfaces.len())
            .filter(|&i| !self.interfaces[i].implicit)
            .collect()
    }

    /// The explicitly coupled contacts whose normal relaxation has been
    /// damped to its smallest fraction ([`NORMAL_MIN_FRACTION`]): their
    /// iteration oscillated through every halving, and each increment now
    /// takes thousands of outer iterations.
    pub fn explicit_at_smallest_relaxation(&self) -> Vec<usize> {
        (0..self.interfaces.len())
            .filter(|&i| {
                let ci = &self.interfaces[i];
                !ci.implicit && ci.normal_damping <= NORMAL_MIN_FRACTION
            })
            .collect()
    }

    /// Couples the contacts `which` implicitly from now on (thesis §4.5),
    /// between increments or attempts: their patches become linearised
    /// contact conditions, their relaxation that of implicit coupling, and
    /// the tractions they carry are where the linearisation starts. The
    /// caller checks that the case allows it (a patch shared by pairs
    /// between deformable bodies does not).
    pub fn couple_implicitly(&mut self, which: &[usize], bodies: &mut [Body]) {
        for &i in which {
            let Some(ci) = self.interfaces.get_mut(i) else {
                continue;
            };
            if ci.implicit {
                continue;
            }
            ci.implicit = true;
            // the next update localises the penalty again and judges the
            // pair's stiffness (`stiff`), as at the start of an increment
            ci.penalty_localised = false;
            ci.normal_relaxation = IMPLICIT_NORMAL_RELAXATION;
            ci.tangential_relaxation = IMPLICIT_NORMAL_RELAXATION;
            ci.normal_damping = 1.0;
            // (the next attempt's `save_start` copies them into its start state)
            ci.coupling.set_normal_factor(IMPLICIT_NORMAL_RELAXATION);
            ci.coupling
                .set_tangential_factor(IMPLICIT_NORMAL_RELAXATION);
            ci.linearise_patches(bodies);
            if ci.deformable_pair {
                // the opposite cells' motion (eq. 4.69) counts from here
                ci.record_opposite_reference(bodies);
            }
        }
    }

    /// Implicit coupling of deformable bodies: how far the opposite cells
    /// moved since the last contact evaluation, into every linearised contact
    /// condition (u_Ph − u_Ph* of eq. 4.69), before the boundary values are
    /// refreshed.
    pub fn track_opposite_cells(&mut self, bodies: &mut [Body]) {
        for ci in self.interfaces.iter_mut().filter(|c| c.implicit) {
            if bodies[ci.master.body].rigid || bodies[ci.slave.body].rigid {
                continue;
            }
            let ggi = &ci.tractions.ggi;
            track_side(ggi, true, &mut ci.master, &ci.slave, bodies);
            track_side(ggi, false, &mut ci.slave, &ci.master, bodies);
        }
    }

    /// The penalty springs between cells of two deformable bodies in
    /// implicit contact (thesis eqs. 4.60–4.72): for every overlapping pair
    /// of master face m and slave face s, a spring along the master normal
    /// joining the owner cells, of stiffness
    /// `ω_ms β_m / (δ_m/K_m + 1/ε_n + δ_s/K_s)` (GGI overlap ω_ms, contact
    /// fraction β_m: the half cells and the penalty in series). Global cell
    /// numbers. Clears `out` first.
    pub fn cell_springs(&self, bodies: &[Body], out: &mut Vec<CellSpring>) {
        out.clear();
        for ci in self.interfaces.iter().filter(|c| c.implicit) {
            let (bm, bs) = (&bodies[ci.master.body], &bodies[ci.slave.body]);
            if bm.rigid || bs.rigid {
                continue;
            }
            let inv_eps = 1.0 / ci.law.normal_penalty;
            let inv_eps_t = if ci.law.friction > 0.0 && ci.law.tangential_penalty > 0.0 {
                1.0 / ci.law.tangential_penalty
            } else {
                f64::INFINITY
            };
            let face = |b: &Body, side: &ContactSide, i: usize| {
                let f = b.mesh.patches[side.patch].start + i;
                let cell = b.offset + b.mesh.owner[f] as usize;
                (cell as u32, b.momentum.normal_distance(f) / b.momentum.k)
            };
            for m in 0..ci.master.surface.n_faces() {
                let beta = ci.master.beta[m];
                if !(beta > 0.0) {
                    continue;
                }
                let (cm, compliance_m) = face(bm, &ci.master, m);
                let normal = ci.master.surface.face_normals[m];
                let (slaves, overlaps) = ci.tractions.ggi.master_row(m);
                for (&s, &w) in slaves.iter().zip(overlaps) {
                    let (cs, compliance_s) = face(bs, &ci.slave, s as usize);
                    out.push(CellSpring {
                        cells: (cm, cs),
                        stiffness: w * beta / (compliance_m + inv_eps + compliance_s),
                        tangential: w * beta / (compliance_m + inv_eps_t + compliance_s),
                        normal,
                        in_turn: ci.stiff && !ci.coupled_components,
                        coupled: ci.coupled_components,
                    });
                }
            }
        }
    }

    /// End of an increment, after the bodies' meshes moved (updated
    /// Lagrangian): the surfaces' base positions become the moved mesh
    /// points and the cell-to-point weights follow the new geometry.
    pub fn end_increment(&mut self, bodies: &[Body]) {
        for (bi, op) in self.cell_to_point.iter_mut().enumerate() {
            if let Some(op) = op {
                if bodies[bi].momentum.law.is_updated_lagrangian() {
                    op.update_weights(&bodies[bi].mesh, &bodies[bi].geom);
                }
            }
        }
        for ci in &mut self.interfaces {
            for side in [&mut ci.master, &mut ci.slave] {
                let b = &bodies[side.body];
                if b.rigid || !b.momentum.law.is_updated_lagrangian() {
                    continue;
                }
                for (x, &p) in side.initial.iter_mut().zip(&side.surface.point_ids) {
                    *x = b.mesh.points[p as usize];
                }
                for (f, c) in side.initial_centres.iter_mut().enumerate() {
                    *c = side.surface.face_centre_at(f, &side.initial);
                }
            }
        }
    }

    /// Moves one contact surface to the current displacement of its body.
    fn move_side(side: &mut ContactSide, bodies: &[Body], c2p: &[Option<CellToPoint>]) {
        let b = &bodies[side.body];
        if b.rigid {
            for (u, x0) in side.point_u.iter_mut().zip(&side.initial) {
                *u = b.rigid_displacement(x0);
            }
        } else if let Some(op) = &c2p[side.body] {
            // the increment on the mesh of the start of the increment (the
            // total displacement under small strain)
            let (u, u_b) = b.momentum.increment();
            op.interpolate_points(&side.surface.point_ids, u, u_b, &mut side.point_u);
            if let Some(w) = &b.wedge_points {
                w.apply_listed(&side.surface.point_ids, &mut side.point_u);
            }
        }
        for ((x, x0), u) in side
            .current
            .iter_mut()
            .zip(&side.initial)
            .zip(&side.point_u)
        {
            *x = x0 + u;
        }
        side.surface.update_points(&side.current);
    }

    /// The shift of every face of a deformable side (`FaceShifts`): its
    /// boundary displacement (the increment under the updated Lagrangian
    /// form) minus the displacement of the moved surface's face centre.
    fn face_shifts(side: &mut ContactSide, bodies: &[Body]) {
        let b = &bodies[side.body];
        side.face_shift.clear();
        if b.rigid {
            return;
        }
        let start = b.mesh.patches[side.patch].start - b.mesh.n_internal_faces();
        let u_b = &b.momentum.increment().1[start..start + side.surface.n_faces()];
        side.face_shift.extend(
            u_b.iter()
                .zip(&side.surface.face_centres)
                .zip(&side.initial_centres)
                .map(|((u, c), c0)| u - (c - c0)),
        );
    }

    /// One contact update (outer-iteration steps 1–3 of DESIGN.md): move the
    /// surfaces, detect, compute and relax the tractions, and set them as
    /// the traction condition of the contact patches.
    pub fn update(&mut self, bodies: &mut [Body]) -> Result<f64, String> {
        let mut max_change = 0.0f64;
        self.updates_in_increment += 1;
        // a lasting stick–slip cycle: damp the tangential relaxation
        let damping = if self.updates_in_increment > STICK_SLIP_PATIENCE {
            let halvings = (self.updates_in_increment - STICK_SLIP_PATIENCE) / 100 + 1;
            0.5f64.powi(halvings as i32).max(STICK_SLIP_MIN_FRACTION)
        } else {
            1.0
        };
        // a patch in several pairs sums their tractions and springs
        for ci in &self.interfaces {
            for side in [&ci.master, &ci.slave].into_iter().filter(|s| s.shared) {
                match &mut bodies[side.body].momentum.conditions[side.patch] {
                    PatchCondition::Traction(t) => t.fill(Vector::zeros()),
                    PatchCondition::LinearisedContact(lc) => {
                        lc.traction.fill(Vector::zeros());
                        lc.stiffness.fill(0.0);
                        lc.tangential_stiffness.fill(0.0);
                    }
                    _ => {}
                }
            }
        }
        for ci in &mut self.interfaces {
            let start = std::time::Instant::now();
            ci.coupling
                .set_tangential_factor(ci.tangential_relaxation * damping);
            let deformable_pair = ci.deformable_pair;
            if !ci.implicit {
                ci.coupling
                    .set_normal_factor(ci.normal_relaxation * ci.normal_damping);
            }
            if ci.implicit && deformable_pair {
                // implicit coupling of two deformable bodies: the linearised
                // springs carry the convergence and the relaxation of t* only
                // damps; a cycle of faces that open and close (coincident
                // faceted spheres, a period-4 cycle of the contact area
                // 3 → 22 mm²) is damped the same way as a stick–slip cycle.
                // Not against a rigid body: there a slow increment (die
                // drawing, 27,000 outer iterations near the stall) only
                // slowed down further and landed 1.3 % lower.
                ci.coupling
                    .set_normal_factor(IMPLICIT_NORMAL_RELAXATION * damping);
            }
            Self::move_side(&mut ci.master, bodies, &self.cell_to_point);
            Self::move_side(&mut ci.slave, bodies, &self.cell_to_point);
            ci.apply_face_shifts(bodies);
            ci.detector
                .detect(&ci.master.surface, &ci.slave.surface, &mut ci.pairs)
                .map_err(|e| format!("contact {}: detection: {e}", ci.slave_name))?;
            let force_start = self.times.lap(Phase::ContactDetection, start);
            let localising = !ci.penalty_localised;
            if !ci.penalty_localised && !ci.pairs.is_empty() {
                // first detection of the increment: penalty of the contacting faces
                if let Ok(law) = penalty_law(
                    &ci.params,
                    &ci.master.surface,
                    &ci.slave.surface,
                    &ci.materials,
                    Some(&ci.pairs),
                ) {
                    ci.law = law;
                }
                ci.penalty_localised = true;
            }
            ci.compute_tractions()?;
            transmitted_forces(&mut ci.stats, &ci.tractions, &ci.master, &ci.slave, bodies);
            let info = ci
                .coupling
                .apply(&ci.tractions, &mut ci.master.applied, &mut ci.slave.applied)
                .map_err(|e| format!("contact {}: {e}", ci.slave_name))?;
            max_change = max_change.max(info.relative_change());
            if !ci.implicit {
                ci.damp_stalled_normal_relaxation(
                    info.relative_change(),
                    self.updates_in_increment,
                );
            }
            if self.trace {
                // the force the bodies' residuals carry on their contact
                // patches (last residual evaluation) against the force of
                // the contact algorithm
                let carried = |side: &ContactSide| {
                    let b = &bodies[side.body];
                    if b.rigid {
                        Vector::zeros()
                    } else {
                        b.momentum.patch_force(&b.mesh, side.patch)
                    }
                };
                let (cm, cs) = (carried(&ci.master), carried(&ci.slave));
                eprintln!(
                    "    contact {}: carried by master [{:.4e} {:.4e} {:.4e}] slave [{:.4e} {:.4e} {:.4e}]",
                    ci.slave_name, cm.x, cm.y, cm.z, cs.x, cs.y, cs.z
                );
                eprintln!(
                    "    contact {}: force {:.6e} slave force [{:.4e} {:.4e} {:.4e}] master force [{:.4e} {:.4e} {:.4e}] stick {} slip {} max pen {:.4e} area {:.4e} eps {:.3e}",
                    ci.slave_name,
                    ci.stats.normal_force,
                    ci.stats.slave_force.x,
                    ci.stats.slave_force.y,
                    ci.stats.slave_force.z,
                    ci.stats.master_force.x,
                    ci.stats.master_force.y,
                    ci.stats.master_force.z,
                    ci.stats.n_stick,
                    ci.stats.n_slip,
                    ci.stats.max_penetration,
                    ci.stats.contact_area,
                    ci.law.normal_penalty
                );
            }
            let eps = ci.law.normal_penalty;
            let (eps_t, friction) = (ci.law.tangential_penalty, ci.law.friction);
            if ci.implicit {
                if localising {
                    ci.stiff = ci.stiffly_coupled(bodies);
                }
                if ci.stiff && !ci.coupled_components {
                    ci.coupled_components = ci.inclined_share() > INCLINED_SHARE;
                }
                // β stays within the increment where the springs are solved
                // coupled (the inner of two concentric tubes, held by contact
                // only, crossed the gap once its springs faded); elsewhere
                // a face that opened would stay anchored by ε_n β to where
                // it was (sphere–block at ε_n/E = 1000: 477 outer iterations
                // with β kept, 365 fading; 167 and 114 with face shifts)
                ci.update_beta(if ci.stiff && ci.coupled_components {
                    1.0
                } else {
                    BETA_MEMORY
                });
                let (bm, bs) = (&bodies[ci.master.body], &bodies[ci.slave.body]);
                let (master, slave, ggi) = (&mut ci.master, &mut ci.slave, &ci.tractions.ggi);
                ggi_average(
                    ggi,
                    true,
                    |j| half_cell_compliance(bs, slave, j),
                    &mut master.opposite_compliance,
                );
                ggi_average(
                    ggi,
                    false,
                    |j| half_cell_compliance(bm, master, j),
                    &mut slave.opposite_compliance,
                );
                if deformable_pair {
                    ci.record_opposite_reference(bodies);
                }
            }
            // the carried-traction base damps the segregated splitting; the
            // coupled solve takes the springs whole and starts from t*
            let carried_base = ci.stiff && !ci.coupled_components;
            for side in [&ci.master, &ci.slave] {
                let b = &mut bodies[side.body];
                if b.rigid {
                    continue;
                }
                let start = b.mesh.patches[side.patch].start - b.mesh.n_internal_faces();
                match &mut b.momentum.conditions[side.patch] {
                    PatchCondition::Traction(t) if side.shared => {
                        t.iter_mut().zip(&side.applied).for_each(|(t, a)| *t += a)
                    }
                    PatchCondition::Traction(t) => t.copy_from_slice(&side.applied),
                    PatchCondition::LinearisedContact(lc) => {
                        // eq. 4.52 about the current state, with the penalty
                        // in series with the opposite half cell (c_h of eqs.
                        // 4.64, 4.67): the opposite cell, not its face, is
                        // what stays put while this face is solved
                        let eps_t = if friction > 0.0 { eps_t } else { 0.0 };
                        let u_b = &b.momentum.u_b[start..start + lc.reference.len()];
                        for (i, (&beta, &ch)) in
                            side.beta.iter().zip(&side.opposite_compliance).enumerate()
                        {
                            let normal = side.surface.face_normals[i];
                            let series = |c: f64| if c > 0.0 { c / (1.0 + c * ch) } else { 0.0 };
                            if side.shared {
                                // against rigid bodies only: grounded springs add
                                lc.traction[i] += side.applied[i];
                                lc.normal[i] = normal;
                                lc.stiffness[i] += series(eps * beta);
                                lc.tangential_stiffness[i] += series(eps_t * beta);
                                continue;
                            }
                            lc.traction[i] = if carried_base && ch > 0.0 {
                                carried_traction_base(
                                    lc.traction_at(i, &u_b[i]),
                                    side.applied[i],
                                    normal,
                                    eps * beta * ch,
                                    eps_t * beta * ch,
                                )
                            } else {
                                side.applied[i]
                            };
                            lc.normal[i] = normal;
                            lc.stiffness[i] = series(eps * beta);
                            lc.tangential_stiffness[i] = series(eps_t * beta);
                        }
                        // between two deformable bodies: each receives the
                        // force the contact computed (against a rigid body
                        // nothing is to be conserved, and the die drawing's
                        // last increments diverged with it)
                        if deformable_pair && b.momentum.law.is_updated_lagrangian() {
                            let first = b.mesh.patches[side.patch].start;
                            let mesh_mag = b.geom.face_areas[first..].iter().map(|a| a.norm());
                            for ((r, &a), a0) in lc
                                .area_ratio
                                .iter_mut()
                                .zip(&side.surface.face_mag)
                                .zip(mesh_mag)
                            {
                                let ratio = a / a0;
                                *r = if ratio.is_finite() { ratio } else { 0.0 };
                            }
                        }
                        let n = lc.reference.len();
                        lc.reference
                            .copy_from_slice(&b.momentum.u_b[start..start + n]);
                        lc.opposite_shift
                            .iter_mut()
                            .for_each(|v| *v = Vector::zeros());
                    }
                    _ => {}
                }
            }
            self.times.lap(Phase::ContactForce, force_start);
        }
        Ok(max_change)
    }

    /// The contacts (case order) whose augmented Lagrangian updated its
    /// multipliers for the first time in the run since the last call, each
    /// with the largest penetration and the slave cells' mean height at that
    /// first update.
    pub fn take_newly_augmented(&mut self) -> Vec<(usize, f64, f64)> {
        let out = self
            .newly_augmented
            .iter()
            .map(|&i| {
                let (penetration, height) = self.interfaces[i].first_update;
                (i, penetration, height)
            })
            .collect();
        self.newly_augmented.clear();
        out
    }

    /// Augmented Lagrangian: one Uzawa update of every augmented contact
    /// whose penetration is still too large, once the outer loop has
    /// converged for the current multipliers. Returns whether any changed.
    pub fn augment(&mut self, bodies: &[Body]) -> bool {
        let mut changed = false;
        for ci in &mut self.interfaces {
            changed |= ci.augment(bodies);
        }
        changed
    }

    /// Records the coupling state at the start of an attempt at an
    /// increment.
    pub fn save_start(&mut self) {
        self.updates_in_increment = 0;
        for ci in &mut self.interfaces {
            ci.pairs_this_attempt = false;
            ci.best_change = f64::INFINITY;
            ci.window_min = f64::INFINITY;
            ci.window_updates = 0;
            ci.flips = 0;
            ci.last_force_change = 0.0;
            ci.coupling_saved.clone_from(&ci.coupling);
            ci.ggi_saved.clone_from(&ci.tractions.ggi);
            ci.multiplier_saved.clone_from(&ci.multiplier);
            ci.augmentation_updates = 0;
            for side in [&mut ci.master, &mut ci.slave] {
                side.saved.0.clone_from(&side.applied);
                side.saved.1.clone_from(&side.beta);
                side.saved.2.clone_from(&side.opposite_reference);
            }
        }
    }

    /// Back to the state of [`Self::save_start`]: a failed attempt (which
    /// may have left non-finite tractions) is forgotten.
    pub fn restore_start(&mut self) {
        for ci in &mut self.interfaces {
            // the relaxation accumulates the tractions it applies: a diverged
            // attempt leaves them huge or non-finite, and the next attempt
            // would start from them
            ci.coupling.clone_from(&ci.coupling_saved);
            // the failed attempt's last weights pair other faces (or none,
            // after a blow-up): measured with them, the opposite cells'
            // motion since `opposite_reference` would be spurious
            ci.tractions.ggi.clone_from(&ci.ggi_saved);
            ci.multiplier.clone_from(&ci.multiplier_saved);
            ci.augmentation_updates = 0;
            ci.coupled_components = false;
            for side in [&mut ci.master, &mut ci.slave] {
                side.applied.clone_from(&side.saved.0);
                side.beta.clone_from(&side.saved.1);
                // the opposite cells' displacement of the last contact
                // update: the next attempt's first outer iteration measures
                // their motion from it (eq. 4.69) before updating it
                side.opposite_reference.clone_from(&side.saved.2);
            }
        }
    }

    /// End of a converged increment: friction history.
    pub fn commit_increment(&mut self) {
        self.updates_in_increment = 0;
        for (i, ci) in self.interfaces.iter_mut().enumerate() {
            if ci.augmentation_updates > 0 && ci.augmentation_updates_run == 0 {
                self.newly_augmented.push(i);
            }
            ci.augmentation_updates_run += ci.augmentation_updates;
            ci.augmentation_updates = 0;
            ci.algorithm
                .commit_increment(&ci.master.surface, &ci.slave.surface);
            // β carries over: the next increment starts with the springs of
            // the converged contact (a body held only by contact would
            // otherwise be free in its first outer iteration); between
            // deformable bodies, whose β only grows within an increment,
            // from the converged contact fractions
            if ci.implicit && ci.stiff {
                ci.update_beta(0.0);
            }
            ci.penalty_localised = false;
            ci.coupled_components = false;
        }
    }
}
