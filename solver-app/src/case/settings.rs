//! `[analysis]`, `[time]`, `[solver]` and `[output]`.

use fv_discretise::{RhieChowHistory, RhieChowPlastic};
use fv_nonlinear::NonlinearMethod;

use crate::output::{Field, FieldSet, Precision};
use std::path::PathBuf;

use super::keys;
use super::reader::{fmt_num, Res, Table};

/// `analysis.kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AnalysisKind {
    /// `"static"`: load increments, no inertia (default).
    Static,
    /// `"dynamic"`: with inertia; needs `rho` on every non-rigid body.
    Dynamic,
}

/// `analysis.strain`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StrainKind {
    /// `"small"`: small strain (default).
    Small,
    /// `"large"`: updated Lagrangian (eq. 2.22).
    Large,
}

/// `[analysis]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Analysis {
    /// Static or dynamic.
    pub kind: AnalysisKind,
    /// Small or large strain.
    pub strain: StrainKind,
}

impl Default for Analysis {
    fn default() -> Self {
        Self {
            kind: AnalysisKind::Static,
            strain: StrainKind::Small,
        }
    }
}

/// `[time]`: `end` and the number of equal increments, or `intervals`
/// of equal increments each (e.g. an indentation phase in 100 and a
/// sliding phase in 500 increments, thesis §5.3.2).
#[derive(Debug, Clone, PartialEq)]
pub struct TimeControl {
    /// End time (> 0).
    pub end: f64,
    /// Number of increments in all (>= 1); `step = dt` in the file becomes `round(end/dt)`.
    pub steps: usize,
    /// `intervals = [[t_1, n_1], [t_2, n_2], ...]`: `n_i` equal increments
    /// from `t_{i-1}` (0 for the first) to `t_i`; empty: `steps` equal
    /// increments from 0 to `end`.
    pub intervals: Vec<(f64, usize)>,
}

impl TimeControl {
    /// `steps` equal increments from 0 to `end`.
    pub fn uniform(end: f64, steps: usize) -> Self {
        TimeControl {
            end,
            steps,
            intervals: Vec::new(),
        }
    }

    /// Size of the first increment (`end / steps` for equal increments).
    pub fn dt(&self) -> f64 {
        match self.intervals.first() {
            Some(&(t1, n1)) => t1 / n1 as f64,
            None => self.end / self.steps as f64,
        }
    }

    /// Time at the end of increment `k` (1-based; `k = steps` gives `end`
    /// exactly, as does the last increment of every interval).
    pub fn time_at(&self, k: usize) -> f64 {
        if k >= self.steps {
            return self.end;
        }
        let mut t0 = 0.0;
        let mut first = 0;
        for &(t1, n) in &self.intervals {
            if k <= first + n {
                let j = k - first;
                return if j == n {
                    t1
                } else {
                    t0 + (t1 - t0) * j as f64 / n as f64
                };
            }
            t0 = t1;
            first += n;
        }
        self.end * k as f64 / self.steps as f64
    }
}

/// `solver.on_nonconvergence`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OnNonConvergence {
    /// `"abort"`: stop with a solver failure (default).
    Abort,
    /// `"continue"`: warn and go on with the next increment.
    Continue,
}

/// `solver.acceleration`: how the outer iteration is accelerated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Acceleration {
    /// `"none"`: the thesis's under-relaxed Picard iteration.
    None,
    /// `"anderson"`: Anderson mixing of the last `acceleration_depth`
    /// iterates ([`crate::anderson`]).
    Anderson,
}

/// `solver.predictor`: the first iterate of an increment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Predictor {
    /// `"none"`: the displacement of the end of the last increment (the
    /// thesis).
    None,
    /// `"linear"`: that displacement plus the last accepted increment's
    /// change, scaled by the ratio of the step sizes (linear extrapolation
    /// in time). Only the first iterate changes, not the converged result.
    Linear,
}

/// `solver.coupling_fallback`: what a run does with explicitly coupled
/// contacts that fail an increment, or converge only at their smallest
/// relaxation (beyond the thesis).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CouplingFallback {
    /// `"implicit"` (default): couple them implicitly for the rest of the run.
    Implicit,
    /// `"none"`: keep explicit coupling (cut the step back instead), e.g.
    /// to compare the couplings.
    None,
}

/// `solver.linear.method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinearMethod {
    /// `"pcg-ic"`: preconditioned conjugate gradients with IC(0) (default).
    PcgIc,
    /// `"direct"`: sparse direct factorisation.
    Direct,
    /// `"bicgstab-ilu"`: BiCGStab with ILU(0), for nonsymmetric (implicitly coupled) systems.
    BicgstabIlu,
    /// `"gmres"`: restarted GMRES on Newton's linear systems, preconditioned
    /// by IC(0) of the segregated operator (`nonlinear = "newton-krylov"`
    /// only, whose default it is; there `"pcg-ic"`, `"bicgstab-ilu"` and
    /// `"direct"` select it too, the segregated methods' names meaning the
    /// same preconditioned Krylov solve).
    Gmres,
}

/// Default relative tolerance of the linear solves under Anderson
/// acceleration. The mixing models the outer iteration as one fixed map;
/// a Krylov solve stopped at 0.1 is a different map at every iteration
/// (plane-stress cantilever at depth 10: 1,123 outer iterations at 0.1,
/// 494 at 0.01, 86 at 1e-3, 72 at 1e-6, 69 with direct solves; a block
/// under a traction, depth 10: 156, 48, 42, 40, 38).
pub const ANDERSON_LINEAR_TOLERANCE: f64 = 1e-3;

/// `solver.linear`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearSettings {
    /// Method (default pcg-ic).
    pub method: LinearMethod,
    /// Relative residual reduction per outer iteration, in (0, 1) (default
    /// 0.1; [`ANDERSON_LINEAR_TOLERANCE`] under Anderson acceleration).
    pub tolerance: f64,
    /// Iteration cap (>= 1, default 500; Newton–Krylov: Krylov iterations
    /// per Newton step, default 200).
    pub max_iterations: usize,
    /// Newton–Krylov: GMRES restart length (>= 1, default 30).
    pub restart: usize,
    /// Newton–Krylov: the preconditioner (default auto).
    pub preconditioner: crate::newton::preconditioning::Preconditioning,
}

impl LinearSettings {
    /// The defaults under `acceleration`: a tighter tolerance under
    /// Anderson ([`ANDERSON_LINEAR_TOLERANCE`]).
    pub fn for_acceleration(acceleration: Acceleration) -> Self {
        match acceleration {
            Acceleration::None => Self::default(),
            Acceleration::Anderson => Self {
                tolerance: ANDERSON_LINEAR_TOLERANCE,
                ..Self::default()
            },
        }
    }
}

impl Default for LinearSettings {
    fn default() -> Self {
        Self {
            method: LinearMethod::PcgIc,
            tolerance: 0.1,
            max_iterations: 500,
            restart: 30,
            preconditioner: Default::default(),
        }
    }
}

/// Newton–Krylov's default largest forcing term: each Newton step's
/// linear solve reduces the residual at least this much (Eisenstat–Walker
/// tightens it as Newton converges).
pub const NEWTON_FORCING_MAX: f64 = 0.1;

/// The segregated method's default outer iterations per increment.
pub const SEGREGATED_MAX_OUTER: usize = 20000;

/// Newton–Krylov's default Newton iterations per increment.
pub const NEWTON_MAX_ITERATIONS: usize = 50;

/// Newton–Krylov's Newton iterations in the last attempt at an increment
/// (after the last cut-back) unless the case gives `max_outer`: there
/// slow progress is no reason to stop. Curved beams μ = 0.6 at 29.25 mm,
/// where the upper beam's tip slips off: at a sixteenth of the step
/// Newton still creeps, 2.6e-3 → 2.0e-3 in 15 iterations.
pub const NEWTON_FINAL_ATTEMPT_ITERATIONS: usize = 500;

impl LinearSettings {
    /// The defaults of Newton–Krylov: GMRES(30), forcing terms up to
    /// [`NEWTON_FORCING_MAX`], 200 Krylov iterations per Newton step.
    pub fn for_newton() -> Self {
        Self {
            method: LinearMethod::Gmres,
            tolerance: NEWTON_FORCING_MAX,
            max_iterations: 200,
            restart: 30,
            preconditioner: Default::default(),
        }
    }
}

/// `[solver]`: the nonlinear method and its settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// How an increment is solved (default Newton–Krylov).
    pub nonlinear: NonlinearMethod,
    /// In (0, 1), default 1e-6. Segregated: the relative correction of the
    /// outer loop. Newton–Krylov: the residual norm relative to the force
    /// scale ‖(Σ_f |force through f|)_P‖ over the cells (the forces each
    /// cell balances).
    pub tolerance: f64,
    /// Nonlinear iterations per increment (>= 1; default
    /// [`SEGREGATED_MAX_OUTER`] outer iterations of the segregated method,
    /// [`NEWTON_MAX_ITERATIONS`] Newton iterations).
    pub max_outer: usize,
    /// Whether the case gives `max_outer`; if not, Newton–Krylov's last
    /// attempt at an increment (no cut-back left) may run
    /// [`NEWTON_FINAL_ATTEMPT_ITERATIONS`].
    pub max_outer_given: bool,
    /// Displacement under-relaxation, in (0, 1] (default 1).
    pub relaxation: f64,
    /// What a non-converged increment does (default abort).
    pub on_nonconvergence: OnNonConvergence,
    /// Linear solver.
    pub linear: LinearSettings,
    /// Rhie–Chow coefficient α_RC (>= 0, default 0.1).
    pub rhie_chow: f64,
    /// Whether the case gives `rhie_chow`; if not, a body with pyramids,
    /// or with tetrahedra under large strain, takes 1
    /// (`model::rhie_chow_for_cell_shapes`).
    pub rhie_chow_given: bool,
    /// What the Rhie–Chow term acts on under large strain (default the
    /// increment, as the thesis).
    pub rhie_chow_history: RhieChowHistory,
    /// The Rhie–Chow stiffness where a body flows plastically (default
    /// the flow's share, [`RhieChowPlastic::Flow`]).
    pub rhie_chow_plastic: RhieChowPlastic,
    /// Outer-iteration acceleration (default anderson for a case without
    /// contact, none with contact: [`SolverSettings::for_analysis`]).
    pub acceleration: Acceleration,
    /// Iterates mixed by Anderson acceleration (1–20, default 10; held
    /// to a memory budget on large meshes unless given:
    /// `segregated::budgeted_depth`).
    pub acceleration_depth: usize,
    /// Whether the case gives `acceleration_depth`.
    pub acceleration_depth_given: bool,
    /// Whether the case gives `linear.restart` (else Newton's GMRES
    /// restart is held to a memory budget on large meshes:
    /// `newton::budgeted_restart`).
    pub restart_given: bool,
    /// First iterate of each increment (default linear under large strain,
    /// none otherwise).
    pub predictor: Predictor,
    /// Explicit contacts that fail: coupled implicitly (default) or kept.
    pub coupling_fallback: CouplingFallback,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            nonlinear: NonlinearMethod::NewtonKrylov,
            tolerance: 1e-6,
            max_outer: NEWTON_MAX_ITERATIONS,
            max_outer_given: false,
            relaxation: 1.0,
            on_nonconvergence: OnNonConvergence::Abort,
            linear: LinearSettings::for_newton(),
            rhie_chow: 0.1,
            rhie_chow_given: false,
            rhie_chow_history: RhieChowHistory::Incremental,
            rhie_chow_plastic: RhieChowPlastic::Flow,
            acceleration: Acceleration::None,
            acceleration_depth: 10,
            acceleration_depth_given: false,
            restart_given: false,
            predictor: Predictor::None,
            coupling_fallback: CouplingFallback::Implicit,
        }
    }
}

/// `[output]`.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputSettings {
    /// As written (relative to the working directory; default `results`);
    /// results go to `<directory>/<title>/`.
    pub directory: PathBuf,
    /// Write fields every k increments (>= 1, default 1).
    pub every: usize,
    /// Keep the restart state of the increments that are multiples of
    /// this (of those whose fields are written), and of the last one
    /// written (>= 1, default [`RESTART_EVERY`]).
    pub restart_every: usize,
    /// How the fields are stored (`"single"`, default, or `"double"`;
    /// restart states are double either way).
    pub precision: Precision,
    /// Which fields an increment stores (default all; the current points
    /// always).
    pub fields: FieldSet,
}

/// Default `[output] restart_every`: a state is about the size of the
/// fields of an increment, so keeping every tenth (and the last) adds
/// about a tenth to the results.
pub const RESTART_EVERY: usize = 10;

impl Default for OutputSettings {
    fn default() -> Self {
        Self {
            directory: PathBuf::from("results"),
            every: 1,
            restart_every: RESTART_EVERY,
            // half the results: shallow ironing (600 increments) 226 MB
            // in double, 131 MB (docs/solver-notes.md, "Results files")
            precision: Precision::Single,
            fields: FieldSet::ALL,
        }
    }
}

/// `analysis.kind` by name.
pub(crate) const ANALYSIS_KINDS: [(&str, AnalysisKind); 2] = [
    ("static", AnalysisKind::Static),
    ("dynamic", AnalysisKind::Dynamic),
];

/// `analysis.strain` by name.
pub(crate) const STRAIN_KINDS: [(&str, StrainKind); 2] =
    [("small", StrainKind::Small), ("large", StrainKind::Large)];

/// `solver.on_nonconvergence` by name.
pub(crate) const ON_NONCONVERGENCE: [(&str, OnNonConvergence); 2] = [
    ("abort", OnNonConvergence::Abort),
    ("continue", OnNonConvergence::Continue),
];

/// `solver.rhie_chow_plastic` by name (the library's names).
pub(crate) fn rhie_chow_plastic_names() -> [(&'static str, RhieChowPlastic); 2] {
    RhieChowPlastic::ALL.map(|k| (k.name(), k))
}

/// `solver.rhie_chow_history` by name (the library's names).
pub(crate) fn rhie_chow_histories() -> [(&'static str, RhieChowHistory); 2] {
    RhieChowHistory::ALL.map(|k| (k.name(), k))
}

/// `solver.acceleration` by name.
pub(crate) const ACCELERATIONS: [(&str, Acceleration); 2] = [
    ("none", Acceleration::None),
    ("anderson", Acceleration::Anderson),
];

/// `solver.predictor` by name.
pub(crate) const PREDICTORS: [(&str, Predictor); 2] =
    [("none", Predictor::None), ("linear", Predictor::Linear)];

/// `solver.coupling_fallback` by name.
pub(crate) const COUPLING_FALLBACKS: [(&str, CouplingFallback); 2] = [
    ("implicit", CouplingFallback::Implicit),
    ("none", CouplingFallback::None),
];

/// `solver.linear.method` by name.
pub(crate) const LINEAR_METHODS: [(&str, LinearMethod); 4] = [
    ("pcg-ic", LinearMethod::PcgIc),
    ("direct", LinearMethod::Direct),
    ("bicgstab-ilu", LinearMethod::BicgstabIlu),
    ("gmres", LinearMethod::Gmres),
];

pub(crate) fn analysis(t: &Table<'_>) -> Res<Analysis> {
    t.deny_unknown(keys::ANALYSIS)?;
    let d = Analysis::default();
    Ok(Analysis {
        kind: t.opt("kind", d.kind, |n| {
            n.choice("analysis kind", &ANALYSIS_KINDS)
        })?,
        strain: t.opt("strain", d.strain, |n| {
            n.choice("strain kind", &STRAIN_KINDS)
        })?,
    })
}

/// Largest increment count accepted from `step` (exactly representable).
const MAX_STEPS_FROM_STEP: f64 = 1e15;

pub(crate) fn time(t: &Table<'_>) -> Res<TimeControl> {
    t.deny_unknown(keys::TIME)?;
    if let Some(intervals) = t.get("intervals") {
        return time_intervals(t, &intervals.node());
    }
    let end = t.need("end", |n| n.positive())?;
    match (t.get("steps"), t.get("step")) {
        (Some(_), Some(step)) => Err(step.node().err("give either `steps` or `step`, not both")),
        (None, None) => Err(t.err_at_key(
            "steps",
            "missing `steps` (number of increments) or `step` (increment size)",
        )),
        (Some(steps), None) => Ok(TimeControl::uniform(end, steps.node().usize_min(1)?)),
        (None, Some(step)) => {
            let node = step.node();
            let dt = node.positive()?;
            let n = end / dt;
            let r = n.round();
            if n < 1.0 - 1e-9 {
                return Err(node.err(format!(
                    "step {} exceeds time.end = {}",
                    node.raw(),
                    fmt_num(end)
                )));
            }
            if r > MAX_STEPS_FROM_STEP {
                return Err(node.err(format!(
                    "step {} gives end/step = {} increments, too many",
                    node.raw(),
                    fmt_num(n)
                )));
            }
            if (n - r).abs() > 1e-9 * r {
                return Err(node.err(format!(
                    "end/step = {} is not an integer (within 1e-9 relative); \
                     choose a step that divides time.end = {} or give `steps`",
                    fmt_num(n),
                    fmt_num(end)
                )));
            }
            Ok(TimeControl::uniform(end, r as usize))
        }
    }
}

/// `time.intervals = [[t_1, n_1], ...]`: increasing end times, at least one
/// increment each; `end`, if given, must be the last `t_i`; `steps`/`step`
/// are not allowed with it.
fn time_intervals(t: &Table<'_>, node: &super::reader::Node<'_>) -> Res<TimeControl> {
    for key in ["steps", "step"] {
        if let Some(k) = t.get(key) {
            return Err(k
                .node()
                .err(format!("give either `intervals` or `{key}`, not both")));
        }
    }
    let mut intervals = Vec::new();
    let mut t_prev = 0.0;
    let mut steps = 0usize;
    for e in node.array()? {
        let pair = e.node().array()?;
        if pair.len() != 2 {
            return Err(e
                .node()
                .err("expected [end time, increments], e.g. [1.0, 100]"));
        }
        let t1 = pair[0].node().f64()?;
        if t1 <= t_prev {
            return Err(pair[0].node().err(format!(
                "interval end times must increase from 0, got {} after {}",
                pair[0].node().raw(),
                fmt_num(t_prev)
            )));
        }
        let n = pair[1].node().usize_min(1)?;
        steps = usize::checked_add(steps, n).ok_or_else(|| {
            pair[1]
                .node()
                .err("the intervals' increments add up to more than the largest integer")
        })?;
        intervals.push((t1, n));
        t_prev = t1;
    }
    if intervals.is_empty() {
        return Err(node.err("needs at least one [end time, increments]"));
    }
    if let Some(end) = t.get("end") {
        let e = end.node().positive()?;
        if (e - t_prev).abs() > 1e-12 * t_prev {
            return Err(end.node().err(format!(
                "time.end = {} differs from the last interval end {}",
                end.node().raw(),
                fmt_num(t_prev)
            )));
        }
    }
    Ok(TimeControl {
        end: t_prev,
        steps,
        intervals,
    })
}

fn tolerance(n: &super::reader::Node<'_>) -> Res<f64> {
    n.f64_if(|x| x > 0.0 && x < 1.0, "satisfy 0 < tolerance < 1")
}

impl SolverSettings {
    /// These settings with `method`, and its own defaults of the
    /// iteration count and the linear solver.
    pub fn for_method(&self, method: NonlinearMethod) -> Self {
        let mut s = *self;
        s.nonlinear = method;
        match method {
            NonlinearMethod::NewtonKrylov => {
                s.max_outer = NEWTON_MAX_ITERATIONS;
                s.linear = LinearSettings::for_newton();
            }
            NonlinearMethod::Segregated => {
                s.max_outer = SEGREGATED_MAX_OUTER;
                s.linear = LinearSettings::for_acceleration(s.acceleration);
            }
        }
        s
    }

    /// The defaults for `analysis`: as [`Default`] (Newton–Krylov), with
    /// the linear predictor under large strain (where it halves the outer
    /// iterations of curved beams and die drawing at unchanged results),
    /// and, for the segregated method on a case without contact, Anderson
    /// acceleration with its linear tolerance: 3–170× fewer outer
    /// iterations on every body measured alone (docs/solver-notes.md,
    /// "Outer iterations"), while with contact it gains nothing yet.
    pub fn for_analysis(analysis: &Analysis, has_contact: bool) -> Self {
        let mut s = Self::default();
        if analysis.strain == StrainKind::Large {
            s.predictor = Predictor::Linear;
        }
        if !has_contact {
            // the segregated method's (SolverSettings::for_method)
            s.acceleration = Acceleration::Anderson;
        }
        s
    }
}

/// The settings of a case without a `[solver]` table.
pub(crate) fn solver_without_table(
    defaults: &SolverSettings,
    nonlinear: Option<NonlinearMethod>,
) -> SolverSettings {
    defaults.for_method(nonlinear.unwrap_or(defaults.nonlinear))
}

pub(crate) fn solver(
    t: &Table<'_>,
    defaults: &SolverSettings,
    nonlinear_override: Option<NonlinearMethod>,
) -> Res<SolverSettings> {
    t.deny_unknown(keys::SOLVER)?;
    let nonlinear = t.opt("nonlinear", defaults.nonlinear, |n| {
        n.choice(
            "nonlinear method",
            &NonlinearMethod::ALL.map(|m| (m.name(), m)),
        )
    })?;
    let nonlinear = nonlinear_override.unwrap_or(nonlinear);
    let newton = nonlinear == NonlinearMethod::NewtonKrylov;
    let d = defaults.for_method(nonlinear);
    let acceleration = t.opt("acceleration", d.acceleration, |n| {
        n.choice("outer-iteration acceleration", &ACCELERATIONS)
    })?;
    let linear_defaults = if newton {
        LinearSettings::for_newton()
    } else {
        LinearSettings::for_acceleration(acceleration)
    };
    let mut restart_given = false;
    let linear = match t.get("linear") {
        None => linear_defaults,
        Some(l) => {
            let node = l.node();
            let table = node.table()?;
            restart_given = table.has("restart");
            let s = linear(&table, &linear_defaults)?;
            if s.method == LinearMethod::Gmres && !newton {
                if let Some(m) = table.get("method") {
                    return Err(m.node().err(
                        "method \"gmres\" solves Newton's linear systems: it needs [solver] nonlinear = \"newton-krylov\" (the segregated method solves with \"pcg-ic\", \"bicgstab-ilu\" or \"direct\")",
                    ));
                }
            }
            for key in ["restart", "preconditioner"] {
                if let (Some(r), false) = (table.get(key), newton) {
                    return Err(r.node().err(format!(
                        "{key} belongs to Newton's linear solves (nonlinear = \"newton-krylov\"); the segregated method has no use for it"
                    )));
                }
            }
            s
        }
    };
    Ok(SolverSettings {
        nonlinear,
        tolerance: t.opt("tolerance", d.tolerance, tolerance)?,
        max_outer: t.opt("max_outer", d.max_outer, |n| n.usize_min(1))?,
        max_outer_given: t.has("max_outer"),
        relaxation: t.opt("relaxation", d.relaxation, |n| {
            n.f64_if(|x| x > 0.0 && x <= 1.0, "satisfy 0 < relaxation <= 1")
        })?,
        on_nonconvergence: t.opt("on_nonconvergence", d.on_nonconvergence, |n| {
            n.choice("on_nonconvergence action", &ON_NONCONVERGENCE)
        })?,
        linear,
        rhie_chow: t.opt("rhie_chow", d.rhie_chow, |n| {
            n.f64_if(|x| x >= 0.0, "be >= 0")
        })?,
        rhie_chow_given: t.has("rhie_chow"),
        rhie_chow_history: t.opt("rhie_chow_history", d.rhie_chow_history, |n| {
            n.choice("Rhie–Chow history", &rhie_chow_histories())
        })?,
        rhie_chow_plastic: t.opt("rhie_chow_plastic", d.rhie_chow_plastic, |n| {
            n.choice(
                "Rhie–Chow stiffness in plastic flow",
                &rhie_chow_plastic_names(),
            )
        })?,
        acceleration,
        acceleration_depth_given: t.has("acceleration_depth"),
        restart_given,
        acceleration_depth: t.opt("acceleration_depth", d.acceleration_depth, |n| {
            let m = n.usize_min(1)?;
            if m > crate::anderson::MAX_DEPTH {
                return Err(n.err(format!(
                    "acceleration_depth = {m} is more than {}",
                    crate::anderson::MAX_DEPTH
                )));
            }
            Ok(m)
        })?,
        predictor: t.opt("predictor", d.predictor, |n| {
            n.choice("increment predictor", &PREDICTORS)
        })?,
        coupling_fallback: t.opt("coupling_fallback", d.coupling_fallback, |n| {
            n.choice("coupling fallback", &COUPLING_FALLBACKS)
        })?,
    })
}

fn linear(t: &Table<'_>, d: &LinearSettings) -> Res<LinearSettings> {
    t.deny_unknown(keys::LINEAR)?;
    Ok(LinearSettings {
        method: t.opt("method", d.method, |n| {
            n.choice("linear solver method", &LINEAR_METHODS)
        })?,
        tolerance: t.opt("tolerance", d.tolerance, tolerance)?,
        max_iterations: t.opt("max_iterations", d.max_iterations, |n| n.usize_min(1))?,
        preconditioner: t.opt("preconditioner", d.preconditioner, |n| {
            use crate::newton::preconditioning::Preconditioning;
            n.choice("preconditioner", &Preconditioning::ALL.map(|p| (p.name(), p)))
        })?,
        restart: t.opt("restart", d.restart, |n| {
            let m = n.usize_min(1)?;
            if m > MAX_RESTART {
                return Err(n.err(format!(
                    "restart = {m} is more than {MAX_RESTART} (each Krylov vector of the basis is kept in memory)"
                )));
            }
            Ok(m)
        })?,
    })
}

/// Largest GMRES restart length accepted.
pub const MAX_RESTART: usize = 500;

pub(crate) fn output(t: &Table<'_>) -> Res<OutputSettings> {
    t.deny_unknown(keys::OUTPUT)?;
    let d = OutputSettings::default();
    Ok(OutputSettings {
        directory: t.opt("directory", d.directory, |n| {
            n.nonempty_str().map(PathBuf::from)
        })?,
        every: t.opt("every", d.every, |n| n.usize_min(1))?,
        restart_every: t.opt("restart_every", d.restart_every, |n| n.usize_min(1))?,
        precision: t.opt("precision", d.precision, |n| {
            n.choice("output precision", &Precision::NAMES)
        })?,
        fields: t.opt("fields", d.fields, |n| {
            n.array()?
                .iter()
                .map(|item| item.node().choice("output field", &Field::NAMES))
                .collect()
        })?,
    })
}
