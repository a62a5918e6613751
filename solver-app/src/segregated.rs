//! The segregated solution procedure of thesis §3.3: one global sparse
//! system for all deformable bodies, outer (Picard) iterations, and one
//! linear solve per displacement component.
use crate::anderson::AndersonAcceleration;
use crate::case::{Acceleration, LinearMethod, LinearSettings, Predictor, SolverSettings};
use crate::contact_coupling::{CellSpring, ContactSet};
use crate::coupled_spring_solve::CoupledSpringSolve;
use crate::model::Body;
use crate::predictor::{LinearPredictor, PathChange};
use crate::profile::{Phase, PhaseTimes};
use crate::springs_in_turn;
use fv_discretise::{
    CsrMatrix, FaceSlots, LinearSolver, LinearSolverError, MomentumParams, SolveInfo,
};
use fv_mesh::{Tensor, Vector};
use std::ops::ControlFlow;
use std::time::Instant;

/// Smallest reference of the relative residual, as a fraction of the total
/// displacement norm (see [`SegregatedSolver::outer_iteration`]).
const RESIDUAL_TOTAL_FRACTION: f64 = 1e-3;

/// A force-controlled patch corrects its displacement (Algorithm 1) when
/// the relative residual is below this multiple of the tolerance: the patch
/// force is then settled to about the same fraction, enough for the secant
/// step, and the loop need not converge fully between corrections.
const FORCE_CORRECTION_RESIDUAL: f64 = 100.0;

/// Under Anderson acceleration an increment has converged only when the
/// applied contact tractions also changed by less than this, relative to
/// the largest, at the last contact update. The accelerated iterate
/// mixes displacements only, while the contact tractions follow by
/// relaxation: on a sphere pressed into a block (ε_n/E = 1000) the
/// displacement correction fell below 1e-6 with the tractions still moving
/// by 0.9 % per outer iteration and the pressures 29 % off (52 % at 1e-7).
/// Plain iterations end with a change of about 1e-5 there.
const ANDERSON_CONTACT_SETTLED: f64 = 1e-4;

/// Diagonal added to a body held only by implicit contact, relative to its
/// internal-face diagonal. It must stay far below the contact springs: at
/// 1e-3 it outweighed the tangential springs of parallel-cylinders and the
/// rigid mode crept (415 outer iterations instead of 162 in increment 1).
const FLOATING_STABILISATION: f64 = 1e-5;

/// An increment's displacement (root mean square over the cells) above
/// this many times the largest deformable body's extent has run away: the
/// attempt counts as diverged at once. Such an iteration used to grow by
/// 10¹⁴ per outer iteration while its relative residual read a steady 1.0
/// (displacement and correction growing together), until the stress
/// overflowed and the linear solver met a non-finite right-hand side
/// (concentric spheres' benchmark polyMesh, 5.9 mm).
const RUNAWAY_MOTION: f64 = 1e3;

/// Outer iterations in a period-two cycle of the residual after which the
/// displacement relaxation of the increment halves (beyond the thesis),
/// down to [`MIN_RELAXATION_FRACTION`] of the configured one. A Picard
/// iteration whose map overshoots (an eigenvalue at or below −1) can
/// settle into a cycle that no number of iterations leaves: the benchmark
/// mesh of the concentric spheres, its inner sphere buckled onto the base
/// plane, alternated between two contact states (plate force 6.75 and
/// 4.27 N, residual 0.8407 and 0.9692) for 20,000 outer iterations at
/// every cut-back. Halving the relaxation maps such an eigenvalue towards
/// 0. A cycle is a residual that returns to its value of two iterations
/// before ([`CYCLE_MATCH`]) after moving away from it ([`CYCLE_SWING`]):
/// a slow but steady iteration (a cantilever's 10⁵ outer iterations) and
/// a noisy one that still converges (frictional contact settling) are not
/// touched (a plain stall test, no new smallest residual in 300
/// iterations, slowed both until they failed). The residual keeps the
/// configured relaxation's scale, so the tolerance means the same.
const CYCLE_PATIENCE: usize = 500;
/// Relative match of a residual with the one two iterations before.
const CYCLE_MATCH: f64 = 1e-3;
/// Smallest relative change from one iteration to the next in a cycle.
const CYCLE_SWING: f64 = 1e-2;
/// Outer iterations without a new smallest residual (by
/// [`EXPLICIT_STALL_DECREASE`]) after which explicit contact coupling is
/// given up as stalled, when the attempt would be redone coupled
/// implicitly ([`SegregatedSolver::set_coupling_switch`]). The two-cylinder
/// pair (2,240 cells, penalty ×10, explicit) reached its smallest residual,
/// 9.1e-3, at outer iteration 433, wandered between 1e-2 and 0.3 up to
/// 5,000, then settled on a limit cycle at 1.0e-3 for 45,000 iterations:
/// 287 s spent before the switch at `max_outer`.
const EXPLICIT_STALL_ITERATIONS: usize = 1000;
/// The factor by which a residual must fall below the smallest so far to
/// count as progress of an explicit coupling ([`EXPLICIT_STALL_ITERATIONS`]).
const EXPLICIT_STALL_DECREASE: f64 = 0.9;
/// The outer residual, relative to the tolerance, below which the
/// augmented Lagrangian multipliers are updated (`contact.augmentation`):
/// an inexact Uzawa iteration, which does not converge the loop for
/// multipliers that are about to change. Hertz cylinder (coarse, penalty
/// scale 1) to the same answer: 190 outer iterations at 1 (updates at
/// convergence), 144 at 10, 114 at 100, 87 at 1,000; the die drawing
/// follows the reference force as closely at 100 as at 1,000.
const AUGMENTATION_RESIDUAL: f64 = 100.0;
/// Smallest fraction of the configured displacement relaxation, after
/// cycles or diverged attempts ([`SegregatedSolver::set_divergence_retries`]).
const MIN_RELAXATION_FRACTION: f64 = 1.0 / 16.0;

/// Meshes of at least this many cells hold Anderson's history to
/// [`ANDERSON_HISTORY_BYTES_PER_CELL`] unless the case gives
/// `acceleration_depth` ([`budgeted_depth`]).
const ANDERSON_BUDGET_CELLS: usize = 100_000;

/// Bytes per cell of Anderson's history on a large mesh, reckoned as
/// 2 m + 2 columns of the whole mixed state (cells, boundary values,
/// normal derivatives and the cell gradient, ~100 B per cell of a box),
/// so depth 3 rather than 10 on a box. (The iterates no longer hold the
/// gradient, `mix_iterates`: the history at that depth takes ~0.5 kB per
/// cell of a box, and the run 1.7 kB; the rule is kept so that the depth,
/// and with it the answer, stays what it was.) Measured,
/// segregated, 1 step (outer iterations, peak RSS): box64 (262,144 cells)
/// depth 10: 24, 980 MB (before the history's pages were released for
/// the output); 6: 24, 664 MB; 5: 26; 4: 27; 3: 28, 510 MB; a cantilever
/// 160 × 28 × 28 (125,440 cells, its end moved across) depth 10: 37,
/// 440 MB; 6: 40, 339 MB; 4: 53, 288 MB; 3: 53, 262 MB; 2: 56. Smaller
/// cases (not capped) at depth 10 / 6 / 4: axisymmetric bar 70 / 74 / 84
/// outer iterations; with `acceleration = "anderson"` hertz-cylinder fine
/// 56 / 53 / 56, concentric cylinders 34 / 39 / 46, flat punch 89 / 64 /
/// 66.
const ANDERSON_HISTORY_BYTES_PER_CELL: usize = 896;

/// Anderson's depth for `cells` cells whose mixed state has `n_mixed`
/// vectors: `depth` on small meshes, else the deepest history of 2 m + 2
/// columns within [`ANDERSON_HISTORY_BYTES_PER_CELL`] (at least 1).
fn budgeted_depth(depth: usize, n_mixed: usize, cells: usize) -> usize {
    if cells < ANDERSON_BUDGET_CELLS || n_mixed == 0 {
        return depth;
    }
    let column = n_mixed * std::mem::size_of::<Vector>();
    let columns = ANDERSON_HISTORY_BYTES_PER_CELL * cells / column;
    depth.min((columns.saturating_sub(2) / 2).max(1))
}

/// Components with matrices of their own are solved side by side from this
/// many unknowns (below, handing them to the thread pool costs more than it
/// saves).
const PARALLEL_COMPONENT_ROWS: usize = 4096;

/// The solver's own passes over a body's cells (gathering the residual,
/// scattering the correction, applying it with its norms, copying the
/// iterate for the acceleration) are split in two halves on two threads
/// from this many cells, when the pool has two threads or more.
const PARALLEL_PASS_CELLS: usize = 32_768;

/// Whether a pass over `n` cells is split over two threads.
fn split_pass(n: usize) -> bool {
    n >= PARALLEL_PASS_CELLS && rayon::current_num_threads() > 1
}

/// `pass(dst, src)` over the cells, in halves on two threads for long
/// vectors (`split_pass`); `src` as long as `dst`.
fn in_halves<A: Send, B: Sync>(dst: &mut [A], src: &[B], pass: impl Fn(&mut [A], &[B]) + Sync) {
    if split_pass(dst.len()) {
        let h = dst.len() / 2;
        let (d0, d1) = dst.split_at_mut(h);
        let (s0, s1) = src.split_at(h);
        rayon::join(|| pass(d0, s0), || pass(d1, s1));
    } else {
        pass(dst, src);
    }
}

/// `dst = src`, in halves on two threads for long vectors.
fn copy_cells(dst: &mut [Vector], src: &[Vector]) {
    in_halves(dst, src, |d, s| d.copy_from_slice(s));
}

/// The gradient's change in the acceleration's correction: `f` (the
/// gradient at the start of the outer iteration) becomes (g − f)/β; in
/// halves on two threads for long vectors.
fn gradient_change(f: &mut [Vector], g: &[Vector], beta: f64) {
    let change = |f: &mut [Vector], g: &[Vector]| {
        for (f, g) in f.iter_mut().zip(g) {
            *f = (g - *f) / beta;
        }
    };
    in_halves(f, g, change);
}

/// Component `c` of every correction `delta` set to `x`.
fn scatter_component(delta: &mut [Vector], x: &[f64], c: usize) {
    let scatter = |delta: &mut [Vector], x: &[f64]| {
        for (d, &x) in delta.iter_mut().zip(x) {
            d[c] = x;
        }
    };
    in_halves(delta, x, scatter);
}

/// The correction `delta` applied to the cells `u` (times `applied`,
/// unless `accelerating`: the mix has set them), with the squares of its
/// norm at the relaxation `relaxation`, of the increment u − u_start and of
/// u added to `sums`; in halves on two threads for long vectors (the sums
/// then in two parts).
fn apply_correction(
    u: &mut [Vector],
    u_start: &[Vector],
    delta: &[Vector],
    (accelerating, applied, relaxation): (bool, f64, f64),
    sums: [f64; 3],
) -> [f64; 3] {
    let pass = |u: &mut [Vector], u_start: &[Vector], delta: &[Vector], sums: [f64; 3]| {
        let [mut norm_delta, mut norm_incr, mut norm_total] = sums;
        for ((u, &u0), &d) in u.iter_mut().zip(u_start).zip(delta) {
            // accelerated: mixed by `mix_iterates`
            if !accelerating {
                *u += d * applied;
            }
            // measured at the configured relaxation (CYCLE_PATIENCE)
            norm_delta += (d * relaxation).norm_squared();
            norm_incr += (*u - u0).norm_squared();
            norm_total += u.norm_squared();
        }
        [norm_delta, norm_incr, norm_total]
    };
    if split_pass(u.len()) {
        let h = u.len() / 2;
        let (u0, u1) = u.split_at_mut(h);
        let (a, b) = rayon::join(
            || pass(u0, &u_start[..h], &delta[..h], sums),
            || pass(u1, &u_start[h..], &delta[h..], [0.0; 3]),
        );
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    } else {
        pass(u, u_start, delta, sums)
    }
}

/// Two or more deformable bodies are updated side by side (boundary
/// values, gradient and stress, residual) when the smallest has this many
/// cells.
const PARALLEL_BODY_CELLS: usize = 2048;

/// Outcome of one load increment.
#[derive(Debug, Clone, Copy, Default)]
pub struct IncrementInfo {
    /// Outer iterations used.
    pub outer_iterations: usize,
    /// Relative residual at exit.
    pub residual: f64,
    /// Whether the tolerance was reached.
    pub converged: bool,
    /// Linear-solver iterations, summed over components and outer iterations.
    pub linear_iterations: usize,
    /// Residual evaluations (Newton–Krylov: base points, line-search
    /// trials and Jacobian products; the segregated method evaluates one
    /// per outer iteration).
    pub residual_evaluations: usize,
    /// The residual the last outer iteration had to reach: the tolerance,
    /// tightened by a damped explicit contact relaxation
    /// ([`ContactSet::explicit_relaxation_fraction`]).
    pub required: f64,
    /// The applied contact tractions still changed by more than
    /// [`ANDERSON_CONTACT_SETTLED`] (relative) at the last outer iteration
    /// of an accelerated increment.
    pub contact_unsettled: bool,
    /// The attempt was given up because explicit contact coupling stalled
    /// ([`EXPLICIT_STALL_ITERATIONS`]).
    pub coupling_stalled: bool,
}

impl IncrementInfo {
    /// Why an increment that did not converge did not: the residual against
    /// the threshold it had to reach, or the contact tractions.
    pub fn shortfall(&self, tolerance: f64) -> String {
        if self.coupling_stalled {
            format!(
                "explicit coupling stalled: residual {:.3e}, no {:.0} % decrease of the smallest in {EXPLICIT_STALL_ITERATIONS} outer iterations",
                self.residual,
                100.0 * (1.0 - EXPLICIT_STALL_DECREASE)
            )
        } else if self.residual < self.required && self.contact_unsettled {
            format!(
                "residual {:.3e}, but the contact tractions still changed by more than {ANDERSON_CONTACT_SETTLED:.0e} per outer iteration",
                self.residual
            )
        } else if self.required < tolerance {
            format!(
                "residual {:.3e} > {:.3e}: the tolerance {:.1e} tightened with the damped explicit contact relaxation",
                self.residual, self.required, tolerance
            )
        } else {
            format!(
                "residual {:.3e} > tolerance {:.1e}",
                self.residual, tolerance
            )
        }
    }
}

/// Why an increment failed.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// The linear solver failed.
    #[error("linear solver: {0}")]
    Linear(#[from] LinearSolverError),
    /// NaN or infinity appeared in the solution or the force residual (the
    /// linear solve's right-hand side), or the increment ran away
    /// ([`RUNAWAY_MOTION`]).
    #[error("the solution diverged (non-finite or runaway displacement) in outer iteration {0}")]
    Diverged(usize),
    /// The contact update failed.
    #[error("{0}")]
    Contact(String),
    /// The material could not be evaluated (an increment inverts a cell).
    #[error("{0}")]
    Material(String),
    /// Newton's method stopped without a usable iterate (no step length
    /// decreased the residual, the preconditioner failed).
    #[error("{0}")]
    Nonlinear(String),
    /// The run was asked to stop (SIGINT, SIGTERM) during the attempt.
    #[error("interrupted")]
    Interrupted,
    /// The matrix is singular: a body cannot carry load in some direction.
    #[error("body '{body}'{part} is not held in the {axis} direction: give it a displacement, symmetry or normal-displacement condition (no rigid-body motion can be solved statically)")]
    Unconstrained {
        /// Body name.
        body: String,
        /// "x", "y" or "z".
        axis: &'static str,
        /// Empty for the whole body; else which face-connected region of
        /// its mesh, and what that suggests.
        part: String,
    },
}

/// The global linear system and the workspaces of the outer loop; built
/// once, refilled when the geometry or the material stiffness changes.
pub struct SegregatedSolver {
    /// What the solver chose that the log should say (taken by the run).
    notes: Vec<String>,
    /// One matrix per distinct component diagonal (usually one).
    matrices: Vec<CsrMatrix>,
    /// Matrix (index into `matrices`) of each component; `None` = not solved
    /// (the empty direction of a 2-D model).
    component_matrix: [Option<usize>; 3],
    /// One factorised solver per matrix.
    solvers: Vec<Box<dyn LinearSolver + Send>>,
    slots: FaceSlots,
    rhs: Vec<f64>,
    x: Vec<f64>,
    /// Right-hand sides and solutions of the components that share a
    /// matrix, solved side by side (`LinearSolver::solve_each`), or across
    /// the contact springs in turn; allocated when first used (on one
    /// thread the components are solved one after the other through `rhs`
    /// and `x`, [`SegregatedSolver::solve_components_one_by_one`]).
    rhs_each: [Vec<f64>; 3],
    x_each: [Vec<f64>; 3],
    /// Per-body reports of the bodies updated side by side.
    body_updates: Vec<BodyUpdate>,
    delta: Vec<Vector>,
    /// Largest bounding-box diagonal of the bodies.
    length_scale: f64,
    n: usize,
    params: MomentumParams,
    relaxation: f64,
    /// Fraction of `relaxation` applied in this increment ([`CYCLE_PATIENCE`]).
    relaxation_fraction: f64,
    /// Fraction of `relaxation` an increment starts with
    /// ([`SegregatedSolver::set_divergence_retries`]).
    start_fraction: f64,
    tolerance: f64,
    max_outer: usize,
    /// A stalled explicit contact coupling ends the attempt
    /// ([`EXPLICIT_STALL_ITERATIONS`]).
    coupling_switch: bool,
    linear: LinearSettings,
    /// Directions not solved (empty / wedge).
    unsolved: [bool; 3],
    /// Diagonal from the internal faces (global numbering).
    internal_diag: Vec<f64>,
    /// Diagonal of each component (workspace).
    diag_work: [Vec<f64>; 3],
    /// (body, component) held by implicit contact only.
    floating: Vec<(usize, usize)>,
    /// Per body, its face-connected regions when its mesh has more than
    /// one (empty otherwise); set by the first checked diagonal fill.
    regions: Option<Vec<Vec<Vec<u32>>>>,
    /// Penalty springs between deformable bodies (implicit contact, workspace).
    springs: Vec<CellSpring>,
    /// (row, col) of the springs' matrix entries, both orders (workspace).
    spring_entries: Vec<(u32, u32)>,
    /// Value indices of the springs' entries in the current matrices.
    spring_slots: Vec<u32>,
    new_spring_slots: Vec<u32>,
    /// Outer-iteration acceleration (`solver.acceleration = "anderson"`).
    anderson: Option<AndersonAcceleration>,
    /// Whether the current attempt uses it: an attempt after a diverged
    /// one runs the plain iteration ([`Self::set_divergence_retries`]).
    accelerate: bool,
    /// Largest relative change of the applied contact tractions at the
    /// last contact update ([`ContactSet::update`]).
    contact_change: f64,
    /// First iterate of an increment (`solver.predictor = "linear"`).
    predictor: Option<LinearPredictor>,
    /// Start and end time of the current step ([`Self::set_step`]).
    step_times: (f64, f64),
    /// Seconds per phase (the contact phases are in the contact set's).
    pub times: PhaseTimes,
    /// The linear step with the contact springs coupled across components.
    coupled: CoupledSpringSolve,
    /// Residual and correction per component (workspaces of `coupled`).
    coupled_rhs: [Vec<f64>; 3],
    coupled_x: [Vec<f64>; 3],
}

/// Component `c` of every deformable body's cell residual into the global
/// vector `out` (at the body's offset).
fn gather_residual(bodies: &[Body], c: usize, out: &mut [f64]) {
    let gather = |out: &mut [f64], residual: &[Vector]| {
        for (o, r) in out.iter_mut().zip(residual) {
            *o = r[c];
        }
    };
    for b in bodies.iter().filter(|b| !b.rigid) {
        let residual = &b.momentum.residual[..];
        let out = &mut out[b.offset..b.offset + residual.len()];
        in_halves(out, residual, gather);
    }
}

fn make_solver(s: &LinearSettings, n: usize) -> Box<dyn LinearSolver + Send> {
    match s.method {
        LinearMethod::PcgIc | LinearMethod::Gmres => Box::new(fv_discretise::PcgIc0::with_params(
            n,
            fv_discretise::PcgParams {
                tolerance: s.tolerance,
                max_iterations: s.max_iterations,
            },
        )),
        LinearMethod::BicgstabIlu => Box::new(fv_discretise::BicgstabIlu0::with_params(
            n,
            fv_discretise::BicgstabParams {
                tolerance: s.tolerance,
                max_iterations: s.max_iterations,
            },
        )),
        LinearMethod::Direct => Box::new(fv_discretise::DirectSolver::new(
            fv_discretise::DirectMethod::Cholesky,
        )),
    }
}

/// Relative residual to which the harmonic start of the first increment
/// is solved ([`SegregatedSolver::start_from_harmonic_extension`]).
const HARMONIC_START_TOLERANCE: f64 = 1e-6;
/// Most warm-started linear solves spent on it.
const HARMONIC_START_SOLVES: usize = 8;
/// Sweeps over the components of the harmonic start where `symmetry` or
/// `normal-displacement` faces lie on inclined planes, whose condition
/// n·u = v couples the components
/// ([`fv_discretise::SolidMomentum::add_inclined_plane_coupling`]), at
/// most. With one sweep the
/// start held the plane only in part: a neo-Hookean bar on a mesh rotated
/// off the axes, stretched 5 % in its first increment by a
/// normal-displacement with symmetry planes at its other end, diverged in
/// the third outer iteration (the same bar along the axes: 21 outer
/// iterations).
const HARMONIC_START_SWEEPS: usize = 30;
/// A sweep that changes the extension by less than this fraction of its
/// largest value ends the sweeps ([`HARMONIC_START_SWEEPS`]).
const HARMONIC_SWEEP_TOLERANCE: f64 = 1e-3;

/// Directions (0, 1, 2) that are not solved: the out-of-plane axis of a
/// 2-D model (every `empty` face normal along it) and the circumferential
/// axis of an axisymmetric wedge (the normal of its mid-plane along it:
/// the displacement has no swirl component, as OpenFOAM's solution
/// directions; a wedge whose mid-plane is not a coordinate plane, e.g.
/// from 0° to 5°, solves all three components — with the 8° margin on the
/// face normals this used to be, its cells lost the circumferential part
/// of their radial motion). Such a direction must be shared by every
/// deformable body.
pub(crate) fn unsolved_directions(bodies: &[Body]) -> [bool; 3] {
    // (any face seen, axis shared by all faces) for empty and for wedge faces
    let mut kinds = [(false, [true; 3]); 2];
    for b in bodies.iter().filter(|b| !b.rigid) {
        for (p, c) in b.mesh.patches.iter().zip(&b.momentum.conditions) {
            let (kind, rotations) = match c {
                fv_discretise::PatchCondition::Empty => (0, None),
                fv_discretise::PatchCondition::Wedge(r) => (1, Some(r)),
                _ => continue,
            };
            for (i, f) in p.faces().enumerate() {
                kinds[kind].0 = true;
                let threshold = 1.0 - 1e-6;
                // a wedge face's rotation takes the mid-plane's normal onto its own
                let n = match rotations {
                    Some(r) => r[i].transpose() * b.geom.face_normal(f),
                    None => b.geom.face_normal(f),
                };
                for d in 0..3 {
                    if n[d].abs() < threshold {
                        kinds[kind].1[d] = false;
                    }
                }
            }
        }
    }
    let mut out = [false; 3];
    for (seen, along) in kinds {
        for d in 0..3 {
            out[d] |= seen && along[d];
        }
    }
    out
}

impl SegregatedSolver {
    /// Builds the global pattern of the deformable bodies.
    pub fn new(bodies: &[Body], settings: &SolverSettings) -> Self {
        let mut owner = Vec::new();
        let mut neighbour = Vec::new();
        let mut n = 0;
        for b in bodies.iter().filter(|b| !b.rigid) {
            let off = b.offset as u32;
            let ni = b.mesh.n_internal_faces();
            owner.extend(b.mesh.owner[..ni].iter().map(|&o| o + off));
            neighbour.extend(b.mesh.neighbour.iter().map(|&x| x + off));
            n = n.max(b.offset + b.mesh.n_cells);
        }
        let (matrix, slots) = CsrMatrix::from_faces(n, &owner, &neighbour);
        let length_scale = bodies
            .iter()
            .map(|b| b.extent)
            .fold(f64::MIN_POSITIVE, f64::max);
        // the acceleration's correction: cells, then every deformable
        // body's boundary values, normal derivatives and cell gradients;
        // its iterate: the same without the gradients (`mix_iterates`)
        let n_mixed = n + bodies
            .iter()
            .filter(|b| !b.rigid)
            .map(mixed_state_len)
            .sum::<usize>();
        let n_iterate = n + bodies
            .iter()
            .filter(|b| !b.rigid)
            .map(iterate_state_len)
            .sum::<usize>();
        let mut notes = Vec::new();
        let depth = if settings.acceleration_depth_given {
            settings.acceleration_depth
        } else {
            budgeted_depth(settings.acceleration_depth, n_mixed, n)
        };
        if settings.acceleration == Acceleration::Anderson && depth < settings.acceleration_depth {
            notes.push(format!(
                "Anderson acceleration depth {depth} instead of {} on {n} cells: its history held to {} kB per cell (set [solver] acceleration_depth to choose)",
                settings.acceleration_depth,
                ANDERSON_HISTORY_BYTES_PER_CELL as f64 / 1024.0
            ));
        }
        SegregatedSolver {
            matrices: vec![matrix],
            component_matrix: [Some(0), Some(0), Some(0)],
            solvers: Vec::new(),
            slots,
            rhs: vec![0.0; n],
            x: vec![0.0; n],
            rhs_each: Default::default(),
            x_each: Default::default(),
            body_updates: Vec::new(),
            delta: vec![Vector::zeros(); n],
            length_scale,
            n,
            params: MomentumParams {
                rhie_chow: settings.rhie_chow,
                rhie_chow_history: settings.rhie_chow_history,
            },
            relaxation: settings.relaxation,
            relaxation_fraction: 1.0,
            start_fraction: 1.0,
            tolerance: settings.tolerance,
            max_outer: settings.max_outer,
            coupling_switch: false,
            linear: settings.linear,
            unsolved: [false; 3],
            internal_diag: vec![0.0; n],
            diag_work: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            floating: Vec::new(),
            regions: None,
            springs: Vec::new(),
            spring_entries: Vec::new(),
            spring_slots: Vec::new(),
            new_spring_slots: Vec::new(),
            accelerate: true,
            anderson: match settings.acceleration {
                Acceleration::None => None,
                Acceleration::Anderson => {
                    Some(AndersonAcceleration::new(n_iterate, n_mixed, depth))
                }
            },
            step_times: (0.0, 0.0),
            predictor: match settings.predictor {
                Predictor::None => None,
                Predictor::Linear => Some(LinearPredictor::new(n)),
            },
            times: PhaseTimes::default(),
            coupled: CoupledSpringSolve::default(),
            coupled_rhs: Default::default(),
            coupled_x: Default::default(),
            contact_change: 0.0,
            notes,
        }
    }

    /// Whether every deformable body is held: the segregated matrices of
    /// `settings` assemble and factorise (the check Newton–Krylov runs
    /// before it starts). The solver built for it has no acceleration or
    /// predictor workspace, which it never uses: Anderson's history alone
    /// is 2 kB per cell at depth 10. Returns the directions in which only
    /// contact holds a body, `(body, axis)`.
    pub fn check_held(
        bodies: &[Body],
        settings: &SolverSettings,
    ) -> Result<Vec<(usize, usize)>, SolveError> {
        let settings = SolverSettings {
            acceleration: Acceleration::None,
            predictor: Predictor::None,
            ..*settings
        };
        let mut solver = SegregatedSolver::new(bodies, &settings);
        solver.assemble_and_factorise(bodies, &settings.linear)?;
        Ok(solver.held_by_contact_alone().to_vec())
    }

    /// The directions in which only contact holds a body, `(body, axis)`,
    /// as the last assembly found.
    pub fn held_by_contact_alone(&self) -> &[(usize, usize)] {
        &self.floating
    }

    /// Sets the change of the prescribed values over the step the next
    /// [`Self::solve_increment`] solves (used by the predictor).
    pub fn set_step(&mut self, path: &PathChange, t0: f64, t1: f64) {
        if let Some(p) = &mut self.predictor {
            p.set_step(path);
        }
        self.step_times = (t0, t1);
    }

    /// The linear-solver settings of the run.
    pub fn linear_settings(&self) -> LinearSettings {
        self.linear
    }

    /// Number of unknowns per component.
    pub fn n_unknowns(&self) -> usize {
        self.n
    }

    /// Components solved (false for the empty direction of 2-D models).
    pub fn solved_components(&self) -> [bool; 3] {
        self.component_matrix.map(|m| m.is_some())
    }

    /// Assembles the implicit (2μ+λ) Laplacian (eq. 3.29, a_P and a_N) and
    /// factorises it: one factorisation per distinct component diagonal.
    pub fn assemble_and_factorise(
        &mut self,
        bodies: &[Body],
        linear: &LinearSettings,
    ) -> Result<(), SolveError> {
        let start = Instant::now();
        let result = self.assemble_and_factorise_untimed(bodies, linear);
        self.times.lap(Phase::MatrixAssembly, start);
        result
    }

    fn assemble_and_factorise_untimed(
        &mut self,
        bodies: &[Body],
        linear: &LinearSettings,
    ) -> Result<(), SolveError> {
        let base = &mut self.matrices[0];
        base.fill_zero();
        self.internal_diag.clear();
        self.internal_diag.resize(self.n, 0.0);
        {
            let v = base.values_mut();
            let mut g = 0;
            for b in bodies.iter().filter(|b| !b.rigid) {
                for f in 0..b.mesh.n_internal_faces() {
                    let a = b.momentum.face_coefficient(&b.geom, f);
                    v[self.slots.upper[g] as usize] -= a;
                    v[self.slots.lower[g] as usize] -= a;
                    self.internal_diag[b.offset + b.mesh.owner[f] as usize] += a;
                    self.internal_diag[b.offset + b.mesh.neighbour[f] as usize] += a;
                    g += 1;
                }
                // temporal term (eq. 3.11)
                let range = b.offset..b.offset + b.mesh.n_cells;
                b.momentum
                    .add_inertia_diagonal(&mut self.internal_diag[range]);
            }
        }
        self.unsolved = unsolved_directions(bodies);
        self.floating.clear();
        self.fill_diagonals(bodies, true)?;
        let comp = self.dedupe_diagonals();
        let template = self.matrices[0].clone();
        self.matrices.truncate(1);
        let n_matrices = comp.iter().flatten().max().map_or(1, |m| m + 1);
        while self.matrices.len() < n_matrices {
            self.matrices.push(template.clone());
        }
        self.component_matrix = comp;
        while self.solvers.len() < self.matrices.len() {
            self.solvers.push(make_solver(linear, self.n));
        }
        self.solvers.truncate(self.matrices.len());
        self.write_diagonals_and_factorise()
    }

    /// The diagonal of every solved component: internal faces plus the
    /// boundary contributions of every body (including the linearised
    /// contact stiffness of implicit coupling). With `check`, a component
    /// that gains nothing from the boundary is reported as unconstrained.
    fn fill_diagonals(&mut self, bodies: &[Body], check: bool) -> Result<(), SolveError> {
        // with `check`: the face-connected regions of every body whose mesh
        // has more than one, each of which must be held on its own (found
        // once: the mesh motion keeps the topology)
        let regions = if check {
            self.regions.get_or_insert_with(|| {
                bodies
                    .iter()
                    .map(|b| {
                        let r = fv_mesh::face_connected_regions(&b.mesh);
                        if r.len() > 1 {
                            r
                        } else {
                            Vec::new()
                        }
                    })
                    .collect()
            })
        } else {
            &Vec::new()
        };
        for c in 0..3 {
            if self.unsolved[c] {
                continue;
            }
            let d = &mut self.diag_work[c];
            d.clear();
            d.extend_from_slice(&self.internal_diag);
            for (bi, b) in bodies.iter().enumerate().filter(|(_, b)| !b.rigid) {
                let slice = &mut d[b.offset..b.offset + b.mesh.n_cells];
                let before: f64 = slice.iter().sum();
                b.momentum.add_boundary_diagonal(&b.mesh, &b.geom, c, slice);
                let after: f64 = slice.iter().sum();
                let held_by_contact = b
                    .momentum
                    .conditions
                    .iter()
                    .any(|c| matches!(c, fv_discretise::PatchCondition::LinearisedContact(_)));
                if check && b.momentum.inertia.is_none() && !(after > before * (1.0 + 1e-12)) {
                    if !held_by_contact {
                        return Err(SolveError::Unconstrained {
                            body: b.name.clone(),
                            axis: ["x", "y", "z"][c],
                            part: String::new(),
                        });
                    }
                    self.floating.push((bi, c));
                }
                if check && b.momentum.inertia.is_none() && !held_by_contact {
                    let internal = &self.internal_diag[b.offset..b.offset + b.mesh.n_cells];
                    let all = regions.get(bi).map(|r| r.as_slice()).unwrap_or(&[]);
                    for (k, region) in all.iter().enumerate() {
                        let (gain, base) = region.iter().fold((0.0, 0.0), |(g, s), &i| {
                            let i = i as usize;
                            (g + slice[i] - internal[i], s + internal[i])
                        });
                        if !(gain > 1e-12 * base) {
                            return Err(SolveError::Unconstrained {
                                body: b.name.clone(),
                                axis: ["x", "y", "z"][c],
                                part: format!(
                                    " (face-connected region{k} of {}, {} cells: a mesh of parts that are not joined — in Gmsh, BooleanFragments or Coherence — or a part that needs a condition of its own; zone = \"region{k}\" makes it a body of its own in a mesh without physical volumes or cellZones, in one with them a physical volume of its own does)",
                                    all.len(),
                                    region.len(),
                                ),
                            });
                        }
                    }
                }
            }
            // a body held only by implicit contact: a small diagonal keeps
            // the matrix regular before the contact springs take over (it
            // only damps the path; the residual is unchanged)
            for &(bi, fc) in &self.floating {
                if fc == c {
                    let b = &bodies[bi];
                    let range = b.offset..b.offset + b.mesh.n_cells;
                    for (di, ai) in d[range.clone()].iter_mut().zip(&self.internal_diag[range]) {
                        *di += FLOATING_STABILISATION * ai;
                    }
                }
            }
        }
        Ok(())
    }

    /// Matrix of each component: components with identical diagonals share one.
    fn dedupe_diagonals(&self) -> [Option<usize>; 3] {
        let mut comp: [Option<usize>; 3] = [None; 3];
        let mut first: Vec<usize> = Vec::with_capacity(3);
        for (c, slot) in comp.iter_mut().enumerate() {
            if self.unsolved[c] {
                continue;
            }
            *slot = Some(
                match first
                    .iter()
                    .position(|&e| self.diag_work[e] == self.diag_work[c])
                {
                    Some(i) => i,
                    None => {
                        first.push(c);
                        first.len() - 1
                    }
                },
            );
        }
        comp
    }

    /// Writes the component diagonals into their matrices and factorises.
    fn write_diagonals_and_factorise(&mut self) -> Result<(), SolveError> {
        for c in 0..3 {
            let Some(mi) = self.component_matrix[c] else {
                continue;
            };
            let m = &mut self.matrices[mi];
            let n = m.n();
            for i in 0..n {
                let k = m.diag_index()[i] as usize;
                m.values_mut()[k] = self.diag_work[c][i];
            }
        }
        for (s, m) in self.solvers.iter_mut().zip(&self.matrices) {
            s.factorise(m)?;
        }
        Ok(())
    }

    /// Implicit contact coupling: the contact stiffness changed, so every
    /// solved component gets its own matrix (the normal stiffness splits
    /// over the components as n_c²), the penalty springs between deformable
    /// bodies enter as cross-body coefficients (the pattern grows when new
    /// cell pairs come into contact; it never shrinks), and every matrix is
    /// refactorised.
    fn refactorise_with_contact(
        &mut self,
        bodies: &[Body],
        contacts: &ContactSet,
    ) -> Result<(), SolveError> {
        self.fill_diagonals(bodies, false)?;
        contacts.cell_springs(bodies, &mut self.springs);
        for sp in &self.springs {
            let (a, b) = (sp.cells.0 as usize, sp.cells.1 as usize);
            for c in 0..3 {
                let k = sp.tensor_diagonal(c);
                self.diag_work[c][a] += k;
                self.diag_work[c][b] += k;
            }
        }
        let mut solved = [0usize; 3];
        let mut n_solved = 0;
        for c in (0..3).filter(|&c| !self.unsolved[c]) {
            solved[n_solved] = c;
            n_solved += 1;
        }
        let solved = &solved[..n_solved];
        if self.matrices.len() < solved.len() {
            let template = self.matrices[0].clone();
            while self.matrices.len() < solved.len() {
                self.matrices.push(template.clone());
            }
            while self.solvers.len() < self.matrices.len() {
                self.solvers.push(make_solver(&self.linear, self.n));
            }
        }
        for (i, &c) in solved.iter().enumerate() {
            self.component_matrix[c] = Some(i);
        }
        // cross-body coefficients: remove last iteration's, add this one's
        self.spring_entries.clear();
        for sp in &self.springs {
            self.spring_entries.push(sp.cells);
            self.spring_entries.push((sp.cells.1, sp.cells.0));
        }
        for m in self.matrices.iter_mut() {
            for &k in &self.spring_slots {
                m.values_mut()[k as usize] = 0.0;
            }
        }
        // the pattern grows only when new cell pairs come into contact;
        // otherwise the slots are found without allocating
        if !self.matrices[0].find_entries(&self.spring_entries, &mut self.new_spring_slots) {
            for (mi, m) in self.matrices.iter_mut().enumerate() {
                let growth = m.add_entries(&self.spring_entries)?;
                if mi == 0 {
                    // every matrix has the same pattern and grows the same way
                    self.slots.remap(&growth);
                    self.new_spring_slots.clear();
                    self.new_spring_slots.extend_from_slice(&growth.slots);
                }
            }
        }
        std::mem::swap(&mut self.spring_slots, &mut self.new_spring_slots);
        for (&c, mi) in solved.iter().zip(0..) {
            let v = self.matrices[mi].values_mut();
            for (sp, slots) in self.springs.iter().zip(self.spring_slots.chunks_exact(2)) {
                let k = sp.tensor_diagonal(c);
                v[slots[0] as usize] -= k;
                v[slots[1] as usize] -= k;
            }
        }
        self.write_diagonals_and_factorise()
    }

    /// The linear predictor, if the case asks for one (restart).
    pub fn predictor(&self) -> Option<&LinearPredictor> {
        self.predictor.as_ref()
    }

    /// The linear predictor, if any, to restore (restart).
    pub fn predictor_mut(&mut self) -> Option<&mut LinearPredictor> {
        self.predictor.as_mut()
    }

    /// Records the displacement at the start of an increment (the reference
    /// of the relative residual) and tells every body which directions are
    /// not solved (`SolidMomentum::unsolved`).
    pub fn begin_increment(&mut self, bodies: &mut [Body], contacts: &ContactSet) {
        self.relaxation_fraction = self.start_fraction;
        for b in bodies.iter_mut().filter(|b| !b.rigid) {
            // the reference of the relative residual (`SolidMomentum::u_start`)
            b.momentum.save_start();
            b.momentum.unsolved = self.unsolved;
        }
        if let Some(p) = &self.predictor {
            if p.is_empty() {
                self.start_from_harmonic_extension(bodies, contacts);
            } else {
                for b in bodies.iter_mut().filter(|b| !b.rigid) {
                    p.predict(b.offset, &mut b.momentum.u);
                }
            }
        }
        self.start_rigidly_moved_bodies(bodies, contacts);
        if let Some(a) = &mut self.anderson {
            a.restart();
        }
    }

    /// A body held by nothing but one rigid-motion patch, under the updated
    /// Lagrangian form and in no contact pair, starts every increment moved
    /// by the step's rigid motion (`Body::sole_rigid_motion_step`), not from
    /// rest or the linear predictor's extrapolation: beyond the thesis. From
    /// rest the whole step's rotation sits in the cells by the patch, and
    /// an elastoplastic bar clamped at one end and turned 0.1 rad in one
    /// increment yielded there and converged to a self-equilibrated bent
    /// state with a plastic hinge (ε̄p 0.25) instead of turning rigidly.
    fn start_rigidly_moved_bodies(&mut self, bodies: &mut [Body], contacts: &ContactSet) {
        let (t0, t1) = self.step_times;
        for (bi, b) in bodies.iter_mut().enumerate() {
            if b.rigid || !b.momentum.law.is_updated_lagrangian() || contacts.involves(bi) {
                continue;
            }
            let Some((q, c)) = b.sole_rigid_motion_step(t0, t1) else {
                continue;
            };
            b.momentum.start_from_motion(&b.mesh, &b.geom, &q, &c);
        }
    }

    /// The first increment under `solver.predictor = "linear"` (nothing to
    /// extrapolate yet): the cells start from the harmonic extension of the
    /// step of the prescribed displacements (one solve per component with
    /// the factorised implicit Laplacian and the boundary source of
    /// [`fv_discretise::SolidMomentum::add_prescribed_step_source`]) instead
    /// of from where they are. Starting from rest, the whole step sits in
    /// the half cells next to the prescribed faces: a free hollow hemisphere
    /// moved rigidly 0.025 mm by its rim (half cells 0.039 mm thick) had
    /// its first iterate's rim cells nearly flattened, and the iteration
    /// diverged; so did 0.05 and 0.1 mm, where 0.0125 mm converged. The
    /// extension of a rigid translation is that translation.
    ///
    /// Bodies of a contact pair start from rest as before: the extension
    /// knows nothing of the other body and can push a surface through it
    /// (curved beams on a 5 × 100 mesh: the upper beam moved 0.5 mm into
    /// the lower one, 0.31 mm deep, and the increment converged to a
    /// frictional state with Fx 0.41 N instead of 2.1 N). A failed solve
    /// leaves the cells where they are. Called once per attempt of the
    /// first increment.
    fn start_from_harmonic_extension(&mut self, bodies: &mut [Body], contacts: &ContactSet) {
        let free: Vec<bool> = (0..bodies.len())
            .map(|bi| !bodies[bi].rigid && !contacts.involves(bi))
            .collect();
        if !free.iter().any(|&f| f) {
            return;
        }
        // the extension's cell values, all bodies (once per attempt of the
        // first increment: allocated here)
        let n: usize = bodies
            .iter()
            .filter(|b| !b.rigid)
            .map(|b| b.mesh.n_cells)
            .sum();
        let mut e = vec![Vector::zeros(); self.x.len().max(n)];
        for sweep in 0..HARMONIC_START_SWEEPS {
            let mut inclined = false;
            let mut change: f64 = 0.0;
            let mut size: f64 = 0.0;
            for c in 0..3 {
                let Some(mi) = self.component_matrix[c] else {
                    continue;
                };
                self.rhs.iter_mut().for_each(|r| *r = 0.0);
                let mut any = false;
                for (b, _) in bodies.iter().zip(&free).filter(|(_, &f)| f) {
                    let rows = &mut self.rhs[b.offset..b.offset + b.mesh.n_cells];
                    any |= b
                        .momentum
                        .add_prescribed_step_source(&b.mesh, &b.geom, c, rows);
                    let cells = &e[b.offset..b.offset + b.mesh.n_cells];
                    inclined |= b
                        .momentum
                        .add_inclined_plane_coupling(&b.mesh, &b.geom, c, cells, rows);
                }
                if !any && !inclined {
                    continue;
                }
                // warm-started solves: each reduces the residual by the outer
                // iterations' linear tolerance, until HARMONIC_START_TOLERANCE
                for (x, v) in self.x.iter_mut().zip(&e) {
                    *x = v[c];
                }
                let start = Instant::now();
                let mut first = None;
                let mut ok = true;
                for _ in 0..HARMONIC_START_SOLVES {
                    match self.solvers[mi].solve(&self.matrices[mi], &self.rhs, &mut self.x) {
                        Ok(info) => {
                            let r0 = *first.get_or_insert(info.initial_residual);
                            if info.final_residual <= HARMONIC_START_TOLERANCE * r0 {
                                break;
                            }
                        }
                        Err(_) => {
                            ok = false;
                            break;
                        }
                    }
                }
                self.times.lap(Phase::LinearSolve, start);
                if !ok || !self.x.iter().all(|x| x.is_finite()) {
                    // a failed solve leaves the cells where they are
                    return;
                }
                for (v, &x) in e.iter_mut().zip(&self.x) {
                    change = change.max((x - v[c]).abs());
                    size = size.max(x.abs());
                    v[c] = x;
                }
            }
            // without inclined planes the components are independent: one
            // sweep is the extension
            if !inclined
                || change <= HARMONIC_SWEEP_TOLERANCE * size
                || sweep + 1 == HARMONIC_START_SWEEPS
            {
                break;
            }
        }
        for (b, _) in bodies.iter_mut().zip(&free).filter(|(_, &f)| f) {
            for (u, v) in b.momentum.u.iter_mut().zip(&e[b.offset..]) {
                *u += v;
            }
        }
    }

    /// One outer iteration (thesis §3.3 i–iv): boundary values, gradient,
    /// stress and force residual of every body, one linear solve per
    /// component, under-relaxed update. Returns the relative residual
    /// ‖δ‖/max(‖u − u_start‖, 10⁻³‖u‖) and the linear iterations used.
    pub fn outer_iteration(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
    ) -> Result<(f64, usize), SolveError> {
        let mut linear_iterations = 0;
        if self.accelerating() {
            let start = Instant::now();
            self.snapshot_mixed_state(bodies);
            self.times.lap(Phase::Acceleration, start);
        }
        if !contacts.is_empty() {
            // boundary values consistent with the last solve, so that the
            // contact surfaces (and u_b* of eq. 4.52) are not one step behind
            let start = Instant::now();
            contacts.track_opposite_cells(bodies);
            for b in bodies.iter_mut() {
                b.update_boundary_values();
            }
            self.times.lap(Phase::BoundaryValues, start);
            self.contact_change = contacts.update(bodies).map_err(SolveError::Contact)?;
            if contacts.is_implicit() {
                let start = Instant::now();
                self.refactorise_with_contact(bodies, contacts)?;
                self.times.lap(Phase::MatrixAssembly, start);
            }
        }
        self.update_fields(bodies)?;
        let solved = if self.springs.iter().any(|s| s.coupled) {
            self.solve_coupled(bodies)
        } else if self.springs.iter().any(|s| s.in_turn) {
            self.solve_components_in_turn(bodies)
        } else {
            self.solve_components(bodies)
        };
        // the linear solvers check their right-hand side: a non-finite one
        // is an overflowed stress, a diverged iterate rather than a
        // linear-solver fault
        linear_iterations += solved.map_err(|e| match e {
            SolveError::Linear(LinearSolverError::NonFinite { what }) if what != "matrix" => {
                SolveError::Diverged(0)
            }
            e => e,
        })?;
        let mut norm_delta = 0.0;
        let mut norm_incr = 0.0;
        let mut norm_total = 0.0;
        if self.accelerating() {
            let start = Instant::now();
            self.mix_iterates(bodies);
            self.times.lap(Phase::Acceleration, start);
        }
        let accelerating = self.accelerating();
        let applied = self.relaxation * self.relaxation_fraction;
        for b in bodies.iter_mut().filter(|b| !b.rigid) {
            let off = b.offset;
            let (u_now, u_start) = b.momentum.u_and_start_mut();
            let delta = &self.delta[off..off + u_now.len()];
            let how = (accelerating, applied, self.relaxation);
            [norm_delta, norm_incr, norm_total] = apply_correction(
                u_now,
                u_start,
                delta,
                how,
                [norm_delta, norm_incr, norm_total],
            );
        }
        // every cell moved by the largest body's extent
        let body_scale = self.length_scale * (self.n as f64).sqrt();
        if !norm_delta.is_finite() || !(norm_incr.sqrt() <= RUNAWAY_MOTION * body_scale) {
            return Err(SolveError::Diverged(0));
        }
        // reference: the increment's displacement, but not less than
        // RESIDUAL_TOTAL_FRACTION of the total (an increment in which little
        // changes, e.g. a load held constant, must not be judged on round-off)
        // nor than a length-scale floor (nothing moves at all)
        let floor = 1e-14 * body_scale;
        let reference = norm_incr
            .sqrt()
            .max(RESIDUAL_TOTAL_FRACTION * norm_total.sqrt())
            .max(floor);
        Ok((norm_delta.sqrt() / reference, linear_iterations))
    }

    /// The correction of every solved component, one linear solve each.
    /// Components that share a matrix share its one factorisation and are
    /// solved side by side by its solver (`LinearSolver::solve_each`);
    /// components with their own matrices (the contact springs differ per
    /// component) are solved side by side on the thread pool from
    /// [`PARALLEL_COMPONENT_ROWS`] unknowns. Each solve is the one it would
    /// be alone, so the results do not depend on the number of threads.
    /// Returns the linear iterations.
    fn solve_components(&mut self, bodies: &[Body]) -> Result<usize, SolveError> {
        if rayon::current_num_threads() == 1 {
            return self.solve_components_one_by_one(bodies);
        }
        self.allocate_each();
        // jobs: one per matrix, with the components it solves
        let mut job_matrix = [usize::MAX; 3];
        let mut job_components = [[0usize; 3]; 3];
        let mut job_len = [0usize; 3];
        let mut jobs = 0;
        for c in 0..3 {
            let Some(mi) = self.component_matrix[c] else {
                self.delta.iter_mut().for_each(|d| d[c] = 0.0);
                continue;
            };
            let j = match job_matrix[..jobs].iter().position(|&m| m == mi) {
                Some(j) => j,
                None => {
                    job_matrix[jobs] = mi;
                    jobs += 1;
                    jobs - 1
                }
            };
            job_components[j][job_len[j]] = c;
            job_len[j] += 1;
            gather_residual(bodies, c, &mut self.rhs_each[c]);
            self.x_each[c].iter_mut().for_each(|x| *x = 0.0);
        }
        let start = Instant::now();
        let [r0, r1, r2] = &self.rhs_each;
        let rhs: [&[f64]; 3] = [r0, r1, r2];
        let [x0, x1, x2] = &mut self.x_each;
        let mut x: [Option<&mut [f64]>; 3] = [Some(x0), Some(x1), Some(x2)];
        let side_by_side =
            jobs > 1 && self.n >= PARALLEL_COMPONENT_ROWS && rayon::current_num_threads() > 1;
        // each job's outcome and reports, in the order of its components
        let mut outcomes: [(Result<(), LinearSolverError>, [SolveInfo; 3]); 3] =
            std::array::from_fn(|_| (Ok(()), [SolveInfo::default(); 3]));
        let [o0, o1, o2] = &mut outcomes;
        let mut outcome_of = [Some(o0), Some(o1), Some(o2)];
        let (matrices, solvers) = (&self.matrices, &mut self.solvers);
        // in place: without spawns nothing is handed to the pool
        rayon::in_place_scope(|s| {
            for (mi, solver) in solvers.iter_mut().enumerate() {
                let Some(j) = job_matrix[..jobs].iter().position(|&m| m == mi) else {
                    continue;
                };
                let Some((result, info)) = outcome_of[j].take() else {
                    continue;
                };
                let comps = &job_components[j][..job_len[j]];
                let mut b: [&[f64]; 3] = [&[]; 3];
                let mut xs: [&mut [f64]; 3] = [&mut [], &mut [], &mut []];
                for (k, &c) in comps.iter().enumerate() {
                    b[k] = rhs[c];
                    xs[k] = x[c].take().unwrap_or_default();
                }
                let (a, n) = (&matrices[mi], comps.len());
                let mut job =
                    move || *result = solver.solve_each(a, &b[..n], &mut xs[..n], &mut info[..n]);
                if side_by_side {
                    s.spawn(move |_| job());
                } else {
                    job();
                }
            }
        });
        self.times.lap(Phase::LinearSolve, start);
        let mut linear_iterations = 0;
        for (j, (result, info)) in outcomes.into_iter().enumerate().take(jobs) {
            result?;
            for (&c, i) in job_components[j][..job_len[j]].iter().zip(info) {
                linear_iterations += i.iterations;
                scatter_component(&mut self.delta, &self.x_each[c], c);
            }
        }
        Ok(linear_iterations)
    }

    /// [`Self::solve_components`] on one thread: every component's solve
    /// is the one `LinearSolver::solve_each` would make there (one after
    /// the other from zero, with the same factorisation), through one
    /// right-hand side and one solution instead of three of each (48 B per
    /// cell less).
    fn solve_components_one_by_one(&mut self, bodies: &[Body]) -> Result<usize, SolveError> {
        let mut linear_iterations = 0;
        for c in 0..3 {
            let Some(mi) = self.component_matrix[c] else {
                self.delta.iter_mut().for_each(|d| d[c] = 0.0);
                continue;
            };
            gather_residual(bodies, c, &mut self.rhs);
            self.x.iter_mut().for_each(|x| *x = 0.0);
            let start = Instant::now();
            let info = self.solvers[mi].solve(&self.matrices[mi], &self.rhs, &mut self.x);
            self.times.lap(Phase::LinearSolve, start);
            linear_iterations += info?.iterations;
            scatter_component(&mut self.delta, &self.x, c);
        }
        Ok(linear_iterations)
    }

    /// [`Self::rhs_each`] and [`Self::x_each`] of length n.
    fn allocate_each(&mut self) {
        for v in self.rhs_each.iter_mut().chain(self.x_each.iter_mut()) {
            v.resize(self.n, 0.0);
        }
    }

    /// The correction of every solved component, one after another across
    /// the stiff contact springs ([`springs_in_turn::solve_in_turn`]);
    /// returns the linear iterations.
    fn solve_components_in_turn(&mut self, bodies: &[Body]) -> Result<usize, SolveError> {
        self.allocate_each();
        for c in 0..3 {
            gather_residual(bodies, c, &mut self.rhs_each[c]);
        }
        let start = Instant::now();
        let iterations = springs_in_turn::solve_in_turn(
            &self.matrices,
            &self.component_matrix,
            &mut self.solvers,
            &self.springs,
            &mut self.rhs_each,
            &mut self.x_each,
        )?;
        self.times.lap(Phase::LinearSolve, start);
        for (c, x) in self.x_each.iter().enumerate() {
            for (d, &x) in self.delta.iter_mut().zip(x) {
                d[c] = x;
            }
        }
        Ok(iterations)
    }

    /// The correction of all components at once with the contact springs'
    /// whole tensors ([`CoupledSpringSolve`]); returns the iterations of the
    /// coupled system.
    fn solve_coupled(&mut self, bodies: &[Body]) -> Result<usize, SolveError> {
        for c in 0..3 {
            self.coupled_rhs[c].resize(self.n, 0.0);
            self.coupled_x[c].resize(self.n, 0.0);
            gather_residual(bodies, c, &mut self.coupled_rhs[c]);
        }
        let start = Instant::now();
        let info = self.coupled.solve(
            &self.matrices,
            &self.component_matrix,
            &mut self.solvers,
            &self.springs,
            &self.coupled_rhs,
            &mut self.coupled_x,
            self.linear.tolerance,
            self.linear.max_iterations,
        )?;
        self.times.lap(Phase::LinearSolve, start);
        for (i, d) in self.delta.iter_mut().enumerate() {
            for (c, x) in self.coupled_x.iter().enumerate() {
                d[c] = if self.component_matrix[c].is_some() {
                    x[i]
                } else {
                    0.0
                };
            }
        }
        Ok(info.iterations + info.linear_iterations)
    }

    /// The acceleration's iterate besides the cells at the start of an
    /// outer iteration: u_b and n·∇u of every deformable body into the
    /// history's current iterate, the cell gradient into its correction
    /// (their change is taken at the end). The stacked iterate is the
    /// cells' displacement, then per deformable body its boundary values
    /// u_b and normal derivatives n·∇u ([`iterate_state_len`]); the
    /// stacked correction the same, with every body's cell gradient after
    /// its n·∇u ([`mixed_state_len`]).
    fn snapshot_mixed_state(&mut self, bodies: &[Body]) {
        let Some(anderson) = &mut self.anderson else {
            return;
        };
        let (x, f) = anderson.current_mut();
        let (mut at_x, mut at_f) = (self.n, self.n);
        for b in bodies.iter().filter(|b| !b.rigid) {
            let (len_x, len_f) = (iterate_state_len(b), mixed_state_len(b));
            read_mixed_state(b, &mut x[at_x..at_x + len_x]);
            copy_cells(
                &mut f[at_f + len_x..at_f + len_f],
                gradient_columns(&b.momentum.grad_u),
            );
            at_x += len_x;
            at_f += len_f;
        }
    }

    /// Anderson step over the whole state of the outer iteration: the
    /// cells with their correction δ, and with the change this iteration
    /// made to them every boundary face's value u_b and normal derivative
    /// n·∇u (eq. 3.23) and the cell gradient the next boundary update
    /// extrapolates with. All are carried from one iteration to the next,
    /// so the map the history describes depends on all of them; mixed on
    /// the cells alone it has a memory the mixing cannot see (plane-stress
    /// cantilever: 3,177 outer iterations at depth 5, 85 over the whole
    /// state). The gradient is not recomputed from the mixed cells and
    /// boundary values: those two are not a consistent pair, and across a
    /// thin wedge cell their mismatch is a huge hoop gradient (the shell
    /// under a pole load diverged; now 70 against 491 plain). Its mix is
    /// the gradient of Σ α_k u_k and Σ α_k u_b'_k, the cells each
    /// iteration's gradient was formed from (before their correction) and
    /// the boundary values it was formed with, which the history has
    /// without it: the least-squares gradient is linear in them
    /// (`SolidMomentum::update_gradient`). So the history's iterates hold
    /// no gradient (72 B per cell and column less), only its corrections
    /// do, for γ; the same iteration up to round-off. The whole mixed
    /// iterate, cells included, is written back to the bodies.
    fn mix_iterates(&mut self, bodies: &mut [Body]) {
        let Some(anderson) = &mut self.anderson else {
            return;
        };
        let beta = self.relaxation;
        let (x, f) = anderson.current_mut();
        let (mut at_x, mut at_f) = (self.n, self.n);
        for b in bodies.iter().filter(|b| !b.rigid) {
            let (off, nc) = (b.offset, b.mesh.n_cells);
            copy_cells(&mut x[off..off + nc], &b.momentum.u);
            copy_cells(&mut f[off..off + nc], &self.delta[off..off + nc]);
            // the state this iteration left, less the one it started from
            // (the gradient's: in f since `snapshot_mixed_state`)
            let (len_x, len_f) = (iterate_state_len(b), mixed_state_len(b));
            let f = &mut f[at_f..at_f + len_f];
            let (boundary, gradient) = f.split_at_mut(len_x);
            read_mixed_state(b, boundary);
            for (f, x) in boundary.iter_mut().zip(&x[at_x..at_x + len_x]) {
                *f = (*f - x) / beta;
            }
            gradient_change(gradient, gradient_columns(&b.momentum.grad_u), beta);
            at_x += len_x;
            at_f += len_f;
        }
        anderson.step(beta);
        let (mut at_x, mut at_f) = (self.n, self.n);
        for b in bodies.iter_mut().filter(|b| !b.rigid) {
            write_mixed_state(b, anderson, at_x, at_f);
            let off = b.offset;
            let m = &mut b.momentum;
            let cells = off..off + m.u.len();
            anderson.next_iterate_uncorrected(cells.clone(), &mut m.u);
            m.update_gradient(&b.mesh, &b.geom);
            anderson.next_iterate(cells, off, &mut m.u);
            at_x += iterate_state_len(b);
            at_f += mixed_state_len(b);
        }
    }

    /// Refreshes boundary values, gradient, stress, residual and boundary
    /// forces from the current displacement (for output after convergence).
    /// Returns a description of the first cell the current iterate inverts,
    /// if any (its previous stress is kept; see
    /// [`fv_discretise::SolidMomentum::update_gradient_and_stress`]).
    pub fn update_fields(&mut self, bodies: &mut [Body]) -> Result<Option<String>, SolveError> {
        let params = &self.params;
        let deformable = bodies.iter().filter(|b| !b.rigid);
        let side_by_side = deformable.clone().count() > 1
            && deformable.map(|b| b.mesh.n_cells).min().unwrap_or(0) >= PARALLEL_BODY_CELLS
            && rayon::current_num_threads() > 1;
        self.body_updates
            .resize(bodies.len(), BodyUpdate::default());
        let start = Instant::now();
        if side_by_side {
            use rayon::prelude::*;
            bodies
                .par_iter_mut()
                .zip(self.body_updates.par_iter_mut())
                .for_each(|(b, out)| *out = update_body_fields(b, params));
        } else {
            for (b, out) in bodies.iter_mut().zip(self.body_updates.iter_mut()) {
                *out = update_body_fields(b, params);
            }
        }
        // side by side, each body's phases are timed on its thread and the
        // wall time is shared out among the phases in proportion
        let mut seconds = [0.0; 3];
        for u in &self.body_updates {
            for (s, d) in seconds.iter_mut().zip(u.seconds) {
                *s += d;
            }
        }
        let total: f64 = seconds.iter().sum();
        let scale = if side_by_side && total > 0.0 {
            start.elapsed().as_secs_f64() / total
        } else {
            1.0
        };
        for (phase, s) in [
            Phase::BoundaryValues,
            Phase::GradientAndStress,
            Phase::ResidualAssembly,
        ]
        .into_iter()
        .zip(seconds)
        {
            self.times.add(phase, s * scale);
        }
        Ok(self.body_updates.iter_mut().find_map(|u| u.inverted.take()))
    }

    /// What the solver chose since the last call that the log should say.
    pub fn take_notes(&mut self) -> Vec<String> {
        std::mem::take(&mut self.notes)
    }

    /// Whether the current attempt mixes its iterates (Anderson).
    fn accelerating(&self) -> bool {
        self.anderson.is_some() && self.accelerate
    }

    /// Whether the contact tractions have settled enough for the
    /// displacement residual to decide convergence
    /// ([`ANDERSON_CONTACT_SETTLED`]; always without acceleration).
    fn contact_settled(&self) -> bool {
        !self.accelerating() || self.contact_change <= ANDERSON_CONTACT_SETTLED
    }

    /// The attempts at the current load increment that diverged so far
    /// (beyond the thesis): each halves the displacement relaxation the
    /// next attempts start with, as the run halves their step. A diverging
    /// iteration (an inverted cell, a non-finite residual) overshoots; a
    /// smaller step alone does not help when the overshoot is the
    /// iteration's own, as on the concentric spheres' benchmark mesh at
    /// 8.0 mm, where steps of 0.1 down to 0.00625 mm all diverged within
    /// 20 outer iterations from the same converged state. 0 for a new
    /// increment.
    pub fn set_divergence_retries(&mut self, retries: u32) {
        // the acceleration extrapolates from its history; after a diverged
        // attempt the plain, under-relaxed iteration is the safer one
        self.accelerate = retries == 0;
        self.start_fraction = 0.5f64
            .powi(retries.min(16) as i32)
            .max(MIN_RELAXATION_FRACTION);
    }

    /// Whether a failed attempt with explicit contact coupling would be
    /// redone coupled implicitly: then an explicit coupling that stalls
    /// ends the attempt after [`EXPLICIT_STALL_ITERATIONS`] instead of
    /// running to `max_outer`.
    pub fn set_coupling_switch(&mut self, available: bool) {
        self.coupling_switch = available;
    }

    /// Solves one load increment by outer iterations; on entry the bodies
    /// hold the converged fields of the previous increment and the boundary
    /// values of this one. On exit the fields are consistent with the final
    /// displacement. `on_iteration` hears of every outer iteration; when
    /// it breaks, the attempt ends with [`SolveError::Interrupted`].
    pub fn solve_increment(
        &mut self,
        bodies: &mut [Body],
        contacts: &mut ContactSet,
        mut on_iteration: impl FnMut(usize, f64) -> ControlFlow<()>,
    ) -> Result<IncrementInfo, SolveError> {
        self.begin_increment(bodies, contacts);
        let mut info = IncrementInfo {
            required: self.tolerance,
            ..Default::default()
        };
        let has_force_control = bodies.iter().any(|b| !b.force_controls.is_empty());
        // the last two residuals and the iterations in a period-two cycle
        let (mut last, mut before_last, mut in_cycle) = (f64::NAN, f64::NAN, 0usize);
        let watch_stall = self.coupling_switch && contacts.has_explicit();
        let (mut smallest, mut smallest_at) = (f64::INFINITY, 0usize);
        for outer in 1..=self.max_outer {
            let (residual, linear) =
                self.outer_iteration(bodies, contacts)
                    .map_err(|e| match e {
                        SolveError::Diverged(_) => SolveError::Diverged(outer),
                        e => e,
                    })?;
            info.linear_iterations += linear;
            info.outer_iterations = outer;
            info.residual_evaluations = outer;
            info.residual = residual;
            if on_iteration(outer, residual).is_break() {
                return Err(SolveError::Interrupted);
            }
            let cycling = (residual / before_last - 1.0).abs() < CYCLE_MATCH
                && (residual / last - 1.0).abs() > CYCLE_SWING;
            in_cycle = if cycling { in_cycle + 1 } else { 0 };
            (before_last, last) = (last, residual);
            if residual < EXPLICIT_STALL_DECREASE * smallest {
                (smallest, smallest_at) = (residual, outer);
            }
            if watch_stall && outer - smallest_at >= EXPLICIT_STALL_ITERATIONS {
                info.coupling_stalled = true;
                break;
            }
            if in_cycle >= CYCLE_PATIENCE
                && !self.accelerating()
                && self.relaxation_fraction > MIN_RELAXATION_FRACTION
            {
                self.relaxation_fraction *= 0.5;
                in_cycle = 0;
            }
            // Algorithm 1: force-controlled patches correct their
            // displacement (secant) once the loop has settled for the
            // current one, until the patch force is reached
            if has_force_control && residual < FORCE_CORRECTION_RESIDUAL * self.tolerance {
                self.update_fields(bodies)?;
                let solved = self.solved_components();
                let mut reached = true;
                for b in bodies.iter_mut().filter(|b| !b.rigid) {
                    reached &= b.correct_force_controls(solved);
                }
                if let (false, Some(a)) = (reached, &mut self.anderson) {
                    // the corrected boundary displacement changes the map
                    a.restart();
                }
                if !reached || residual >= self.tolerance {
                    continue;
                }
            }
            info.required = self.tolerance * contacts.explicit_relaxation_fraction();
            info.contact_unsettled = !self.contact_settled();
            // augmented Lagrangian: near convergence for the current
            // multipliers, update them while the penetration is large
            if residual < AUGMENTATION_RESIDUAL * info.required
                && !info.contact_unsettled
                && contacts.augment(bodies)
            {
                if let Some(a) = &mut self.anderson {
                    a.restart();
                }
                continue;
            }
            if residual < info.required && !info.contact_unsettled {
                // the Rhie–Chow share of cells that began to flow in this
                // increment
                if crate::model::follow_flow_of_increment(bodies) {
                    if let Some(a) = &mut self.anderson {
                        a.restart();
                    }
                    continue;
                }
                info.converged = true;
                break;
            }
        }
        // the history is dead until the next increment restarts it
        if let Some(a) = &mut self.anderson {
            a.release_pages();
        }
        if let Some(msg) = self.update_fields(bodies)? {
            // a converged state must be admissible
            return Err(SolveError::Material(msg));
        }
        if info.converged {
            contacts.commit_increment();
            if let Some(p) = &mut self.predictor {
                for b in bodies.iter().filter(|b| !b.rigid) {
                    p.record(b.offset, &b.momentum.u, b.momentum.u_start());
                }
                p.close_record();
            }
        }
        Ok(info)
    }
}

/// What [`update_body_fields`] reports: seconds in boundary values,
/// gradient and stress, residual; the first inverted cell, if any.
#[derive(Debug, Clone, Default)]
struct BodyUpdate {
    seconds: [f64; 3],
    inverted: Option<String>,
}

/// Length of a body's part of the accelerated correction besides its
/// cells: boundary values and normal derivatives per boundary face, and
/// the cell gradient as three columns per cell.
fn mixed_state_len(b: &Body) -> usize {
    iterate_state_len(b) + 3 * b.momentum.grad_u.len()
}

/// Length of a body's part of the accelerated iterate besides its cells:
/// boundary values and normal derivatives per boundary face.
fn iterate_state_len(b: &Body) -> usize {
    2 * b.momentum.u_b.len()
}

/// A body's u_b and n·∇u into `out` ([`iterate_state_len`]).
fn read_mixed_state(b: &Body, out: &mut [Vector]) {
    let m = &b.momentum;
    let nb = m.u_b.len();
    out[..nb].copy_from_slice(&m.u_b);
    out[nb..2 * nb].copy_from_slice(&m.snd_b);
}

/// The inverse of [`read_mixed_state`]: the body's u_b and n·∇u of the
/// next iterate of `anderson`, from entry `at_x` of the iterate and
/// `at_f` of the correction.
fn write_mixed_state(b: &mut Body, anderson: &AndersonAcceleration, at_x: usize, at_f: usize) {
    let m = &mut b.momentum;
    let nb = m.u_b.len();
    anderson.next_iterate(at_x..at_x + nb, at_f, &mut m.u_b);
    anderson.next_iterate(at_x + nb..at_x + 2 * nb, at_f + nb, &mut m.snd_b);
}

// a Tensor is its three columns one after the other, each laid out as a
// Vector (nalgebra's column-major ArrayStorage, repr(C))
const _: () = assert!(
    std::mem::size_of::<Tensor>() == 3 * std::mem::size_of::<Vector>()
        && std::mem::align_of::<Tensor>() == std::mem::align_of::<Vector>()
);

/// The columns of the cell gradients, three vectors per cell.
fn gradient_columns(g: &[Tensor]) -> &[Vector] {
    // SAFETY: a Tensor is three Vectors without padding (asserted above),
    // column j at offset j; `g` is 3 len() Vectors for its lifetime
    unsafe { std::slice::from_raw_parts(g.as_ptr().cast::<Vector>(), 3 * g.len()) }
}

/// Boundary values, gradient and stress, and force residual of one body
/// from its current displacement (nothing for a rigid body).
fn update_body_fields(b: &mut Body, params: &MomentumParams) -> BodyUpdate {
    let mut out = BodyUpdate::default();
    if b.rigid {
        return out;
    }
    let t0 = Instant::now();
    b.update_boundary_values();
    let m = &mut b.momentum;
    let t1 = Instant::now();
    let bad = m.update_gradient_and_stress(&b.mesh, &b.geom);
    let t2 = Instant::now();
    if let Some((cell, jacobian)) = bad {
        out.inverted = Some(format!(
            "body '{}': cell {cell}: relative Jacobian det f = {jacobian:.3e} is not positive (the increment inverts the cell; use more steps, and give a prescribed value as a table to ramp it: a constant one is applied in full from the first increment)",
            b.name
        ));
    }
    m.compute_residual(&b.mesh, &b.geom, params);
    let t3 = Instant::now();
    out.seconds = [
        (t1 - t0).as_secs_f64(),
        (t2 - t1).as_secs_f64(),
        (t3 - t2).as_secs_f64(),
    ];
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message of an unconverged increment names the threshold that
    /// was missed: the tolerance itself, the tolerance tightened by a
    /// damped explicit relaxation (the residual may then be below the
    /// configured tolerance), or the contact tractions.
    #[test]
    fn shortfall_names_the_missed_threshold() {
        let plain = IncrementInfo {
            residual: 3e-6,
            required: 1e-6,
            ..Default::default()
        };
        assert_eq!(
            plain.shortfall(1e-6),
            "residual 3.000e-6 > tolerance 1.0e-6"
        );
        let tightened = IncrementInfo {
            residual: 6.677e-7,
            required: 2.5e-7,
            ..Default::default()
        };
        let msg = tightened.shortfall(1e-6);
        assert!(msg.starts_with("residual 6.677e-7 > 2.500e-7"), "{msg}");
        assert!(msg.contains("tightened"), "{msg}");
        let unsettled = IncrementInfo {
            residual: 5e-7,
            required: 1e-6,
            contact_unsettled: true,
            ..Default::default()
        };
        let msg = unsettled.shortfall(1e-6);
        assert!(
            msg.contains("contact tractions still changed by more than 1e-4"),
            "{msg}"
        );
    }

    #[test]
    fn anderson_depth_is_held_to_the_budget_on_large_meshes_only() {
        use super::budgeted_depth;
        // a box's mixed state: ~4.4 vectors per cell
        let mixed = |cells: usize| cells * 44 / 10;
        assert_eq!(budgeted_depth(10, mixed(32_768), 32_768), 10);
        assert_eq!(budgeted_depth(10, mixed(262_144), 262_144), 3);
        assert_eq!(budgeted_depth(2, mixed(262_144), 262_144), 2);
        // a huge mixed state per cell still keeps one column pair
        assert_eq!(budgeted_depth(10, 100 * 262_144, 262_144), 1);
    }
}
