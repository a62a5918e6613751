//! Which preconditioner Newton's linear systems get (`[solver] linear =
//! { preconditioner = "..." }`), by case-file name.
use std::fmt;

/// The preconditioners of Newton–Krylov.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Preconditioning {
    /// `"auto"`: the assembled Jacobian from the start on a small
    /// two-dimensional problem ([`super::START_JACOBIAN_LIMIT`]) or a
    /// two-dimensional one with a stiff contact between two deformable
    /// bodies ([`super::STIFF_PENALTY_SCALE`]); else the
    /// segregated operator, switched for the rest of the run to the
    /// assembled Jacobian when a linear solve needs more than
    /// [`SWITCH_KRYLOV_ITERATIONS`] Krylov iterations per Newton step, the
    /// problem is two-dimensional (plane or axisymmetric) and the system
    /// is small enough to factorise ([`super::jacobian::LU_LIMIT`]).
    /// Three-dimensional problems switch only when small
    /// ([`super::jacobian::LU_LIMIT_3D`]).
    #[default]
    Auto,
    /// `"segregated"`: the compact Laplacian per displacement component
    /// with the contact springs, solved by IC(0)-PCG
    /// ([`super::segregated_operator`]). Cheap and lean; weak where the
    /// components couple strongly (bending of slender bodies).
    Segregated,
    /// `"jacobian"`: the assembled Jacobian, factorised
    /// ([`super::jacobian`]). Newton's linear systems in a few Krylov
    /// iterations; its factorisation costs time and memory on large
    /// meshes. Only here does it factorise a continuation step's shifted
    /// operator and turn its contact block into the derivative of the
    /// contact forces when the springs stall
    /// ([`super::residual::SPRING_STALLS`]).
    Jacobian,
}

/// A Newton step whose linear solve needs more Krylov iterations than this
/// with the segregated operator makes `"auto"` switch to the assembled
/// Jacobian. The measured cases where the operator serves need 7–17
/// (Hertz, sphere on a block, concentric cylinders, flat punch); the
/// bending beams of the curved-beams benchmark needed 100–200 and stalled.
pub const SWITCH_KRYLOV_ITERATIONS: usize = 60;

/// The factorised Jacobian is kept for the next Newton step (the first of
/// the next increment too) while the last step's linear solve needed at
/// most this many Krylov iterations; the segregated operator is cheap and
/// rebuilt at every step. Measured on the two cases whose Newton paths it
/// changes near their hardest increments: 5 — die drawing runs to the end,
/// curved beams μ = 0.3 fail at 23.6 mm; 30 — the reverse (die drawing
/// fails at increment 74); 15 — both run (7.2 s, 5.9 s).
pub const JACOBIAN_REUSE_KRYLOV: usize = 15;

impl Preconditioning {
    /// Every choice, in the order of [`Preconditioning::valid_names`].
    pub const ALL: [Preconditioning; 3] = [
        Preconditioning::Auto,
        Preconditioning::Segregated,
        Preconditioning::Jacobian,
    ];

    /// The case-file name.
    pub fn name(self) -> &'static str {
        match self {
            Preconditioning::Auto => "auto",
            Preconditioning::Segregated => "segregated",
            Preconditioning::Jacobian => "jacobian",
        }
    }
}

impl fmt::Display for Preconditioning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
