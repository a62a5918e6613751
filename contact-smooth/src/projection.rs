//! Orthogonal projection of a point onto one Nagata patch (thesis
//! eqs. 4.81–4.84, Fig. 4.41).
//!
//! Unknowns `r = [η, ζ, g]`; residual
//! `f(r) = x(η, ζ) + g n(η, ζ) − x_s` (eq. 4.81); Newton–Raphson
//! `r ← r − [∇f]⁻¹ f` (eq. 4.83) with the Jacobian
//! `∇f = [s₁ + g ∂n/∂η, s₂ + g ∂n/∂ζ, n]` (eq. 4.84), the normal derivatives
//! from the Weingarten equations ([`crate::normal_derivatives`]).
//!
//! # Start and safeguards
//!
//! * Start: the projection of `x_s` onto the flat face
//!   ([`NagataPatch::flat_start`]), moved into the domain, with
//!   `g₀ = (x_s − x)·n` there (the thesis starts from the patch midpoint;
//!   the flat projection is already within `O(h²)` of the answer).
//! * At most [`ProjectionParams::max_iterations`] (10, as in the thesis)
//!   updates; a parameter step longer than 1 is shortened to 1, and the
//!   iteration stops when it leaves the domain widened by 1 on every side
//!   (the foot then belongs to another patch).
//! * Converged when `|f| ≤ tolerance · (size + |g|)`.
//!
//! # Feet outside the domain
//!
//! If the iteration does not converge to a point of the domain (within
//! [`ProjectionParams::inside_tolerance`]), the foot is the point of the
//! patch boundary closest to `x_s` (a 1-D Newton search on each edge
//! curve), reported with `inside = false`; its signed distance is `±|x_s − x|`
//! with the sign of `(x_s − x)·n`.
use crate::patch::{DomainEdge, NagataPatch};
use crate::weingarten::normal_derivatives;
use crate::SmoothError;
use fv_mesh::{Real, Vector};

/// Knobs of the projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProjectionParams {
    /// Largest number of Newton–Raphson updates (thesis: 10).
    pub max_iterations: usize,
    /// Relative residual tolerance: converged when `|f| ≤ tolerance · (size + |g|)`.
    pub tolerance: Real,
    /// A converged foot counts as inside the patch when its local
    /// coordinates are in the domain widened by this much.
    pub inside_tolerance: Real,
}

impl Default for ProjectionParams {
    fn default() -> Self {
        ProjectionParams {
            max_iterations: 10,
            tolerance: 1e-12,
            inside_tolerance: 1e-9,
        }
    }
}

impl ProjectionParams {
    /// Checks `1 ≤ max_iterations ≤ 100`, `0 < tolerance < 1`,
    /// `0 ≤ inside_tolerance < 1`.
    pub fn validate(&self) -> Result<(), SmoothError> {
        if !(1..=100).contains(&self.max_iterations) {
            return Err(SmoothError::InvalidParameter {
                name: "max_iterations",
                value: self.max_iterations as Real,
                reason: "must be in 1..=100",
            });
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(SmoothError::InvalidParameter {
                name: "tolerance",
                value: self.tolerance,
                reason: "must be in (0, 1)",
            });
        }
        if !(self.inside_tolerance >= 0.0 && self.inside_tolerance < 1.0) {
            return Err(SmoothError::InvalidParameter {
                name: "inside_tolerance",
                value: self.inside_tolerance,
                reason: "must be in [0, 1)",
            });
        }
        Ok(())
    }
}

/// The foot of `x_s` on one patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchProjection {
    /// Local coordinate η of the foot.
    pub eta: Real,
    /// Local coordinate ζ of the foot.
    pub zeta: Real,
    /// The foot `x̂_m(η, ζ)`.
    pub point: Vector,
    /// Unit patch normal at the foot (eq. 4.82).
    pub normal: Vector,
    /// `g_n`: `x_s = x̂_m + g_n n` for an interior foot, positive on the
    /// side the normal points to; `±|x_s − x̂_m|` for a boundary foot.
    pub signed_distance: Real,
    /// Newton–Raphson updates performed.
    pub iterations: usize,
    /// Whether the Newton–Raphson iteration met the tolerance.
    pub converged: bool,
    /// Whether the foot is an orthogonal projection inside the domain
    /// (`false`: closest point of the patch boundary).
    pub inside: bool,
}

impl PatchProjection {
    /// `|x_s − x̂_m|`.
    pub fn distance(&self) -> Real {
        self.signed_distance.abs()
    }
}

/// Largest change of (η, ζ) per update.
const MAX_STEP: Real = 1.0;
/// The iteration gives up on the patch outside the domain widened by this.
const FAR: Real = 1.0;

/// Orthogonal projection of `xs` onto `patch` (eqs. 4.81–4.84).
///
/// `None` if `xs` is not finite or the patch is degenerate (no normal at the
/// start nor at the domain centre). Cost: typically 2–4 updates, each one
/// patch evaluation with second derivatives and a 3 × 3 solve; no
/// allocation.
///
/// ```
/// use contact_smooth::{project_onto_patch, ProjectionParams, TrianglePatch, EdgeCurveParams};
/// use fv_mesh::Vector;
/// // a patch of the unit sphere with exact normals
/// let x = [
///     Vector::new(1.0, 0.0, 0.0),
///     Vector::new(0.9, 0.3, 0.0).normalize(),
///     Vector::new(0.9, 0.3, 0.3).normalize(),
/// ];
/// let patch = TrianglePatch::new(x, x, &EdgeCurveParams::default());
/// let xs = 1.2 * Vector::new(0.95, 0.2, 0.1).normalize();
/// let p = project_onto_patch(&patch, &xs, &ProjectionParams::default()).unwrap();
/// assert!(p.converged && p.inside && p.iterations <= 10);
/// assert!((p.signed_distance - 0.2).abs() < 1e-3);
/// ```
pub fn project_onto_patch<P: NagataPatch + ?Sized>(
    patch: &P,
    xs: &Vector,
    params: &ProjectionParams,
) -> Option<PatchProjection> {
    let scale = patch.size();
    if !(xs.iter().all(|v| v.is_finite()) && scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let domain = patch.domain();
    let (e0, z0) = patch.flat_start(xs);
    let (mut eta, mut zeta) = domain.clamp(e0, z0);
    let mut d = patch.derivatives(eta, zeta);
    let mut w = match normal_derivatives(&d) {
        Some(w) => Some(w),
        None => {
            (eta, zeta) = domain.centre();
            d = patch.derivatives(eta, zeta);
            Some(normal_derivatives(&d)?)
        }
    };
    let mut g = w.map_or(0.0, |w| (xs - d.x).dot(&w.n));
    let mut converged = false;
    let mut updates = 0;
    let mut interior = None;
    loop {
        if updates > 0 {
            d = patch.derivatives(eta, zeta);
            w = normal_derivatives(&d);
        }
        let Some(w) = w else {
            break;
        };
        let f = d.x + g * w.n - xs;
        if f.norm() <= params.tolerance * (scale + g.abs()) {
            converged = true;
            interior = Some((d.x, w.n));
            break;
        }
        if updates == params.max_iterations {
            break;
        }
        let Some(delta) = solve3(&(d.s1 + g * w.n_eta), &(d.s2 + g * w.n_zeta), &w.n, &(-f)) else {
            break;
        };
        let len = (delta.x * delta.x + delta.y * delta.y).sqrt();
        let s = if len > MAX_STEP { MAX_STEP / len } else { 1.0 };
        eta += s * delta.x;
        zeta += s * delta.y;
        g += s * delta.z;
        updates += 1;
        if !domain.contains(eta, zeta, FAR) {
            break;
        }
    }
    if let Some((x, n)) = interior {
        if domain.contains(eta, zeta, params.inside_tolerance) {
            return Some(PatchProjection {
                eta,
                zeta,
                point: x,
                normal: n,
                signed_distance: g,
                iterations: updates,
                converged,
                inside: true,
            });
        }
    }
    // the sides the iterate has crossed (all of them if it has not)
    let sides = match domain.violated_sides(eta, zeta) {
        0 => u8::MAX,
        m => m,
    };
    let (eta, zeta, x) = closest_on_boundary(patch, xs, sides)?;
    let normal = patch.normal(eta, zeta).or_else(|| {
        // a collapsed corner: the normal just inside the domain
        let (ce, cz) = domain.centre();
        patch.normal(eta + 1e-6 * (ce - eta), zeta + 1e-6 * (cz - zeta))
    })?;
    let r = xs - x;
    let sign = if r.dot(&normal) < 0.0 { -1.0 } else { 1.0 };
    Some(PatchProjection {
        eta,
        zeta,
        point: x,
        normal,
        signed_distance: sign * r.norm(),
        iterations: updates,
        converged,
        inside: false,
    })
}

/// Solves `[c₁ c₂ c₃] x = b` (the Newton step of eq. 4.83 with the
/// Jacobian of eq. 4.84 as columns) by Cramer's rule with cross products;
/// `None` when the columns are (nearly) linearly dependent or the result
/// is not finite. Hand-written: a pivoted LU of a 3 × 3 costs several times
/// more, and this solve is the projection's inner loop.
fn solve3(c1: &Vector, c2: &Vector, c3: &Vector, b: &Vector) -> Option<Vector> {
    let c23 = c2.cross(c3);
    let det = c1.dot(&c23);
    let scale = c1.norm() * c2.norm() * c3.norm();
    if !(det.abs() > 1e-14 * scale) {
        return None;
    }
    let x = Vector::new(b.dot(&c23), c1.dot(&b.cross(c3)), c1.dot(&c2.cross(b))) / det;
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Closest point to `xs` on the sides of the patch boundary selected by
/// the bit mask `sides`: `(η, ζ, x)`.
fn closest_on_boundary<P: NagataPatch + ?Sized>(
    patch: &P,
    xs: &Vector,
    sides: u8,
) -> Option<(Real, Real, Vector)> {
    let mut best: Option<(Real, Real, Vector, Real)> = None;
    for (k, side) in patch.domain().edges().iter().enumerate() {
        if sides & (1 << k) == 0 {
            continue;
        }
        let (t, x) = closest_on_side(patch, xs, side);
        let d2 = (x - xs).norm_squared();
        if d2.is_finite() && best.is_none_or(|b| d2 < b.3) {
            let e = side.start[0] + t * side.direction[0];
            let z = side.start[1] + t * side.direction[1];
            best = Some((e, z, x, d2));
        }
    }
    best.map(|(e, z, x, _)| (e, z, x))
}

/// Closest point of one side to `xs`: `(t, x(t))`. Along a side every
/// patch is the quadratic `p₀ + p₁ t + p₂ t²` (the edge curve, eq. 4.76),
/// taken from the derivatives at `t = 0`; Newton on `φ(t) = |x(t) − x_s|²/2`
/// from the best of `t = 0, ½, 1`, kept within `[0, 1]` and never uphill.
fn closest_on_side<P: NagataPatch + ?Sized>(
    patch: &P,
    xs: &Vector,
    side: &DomainEdge,
) -> (Real, Vector) {
    let [a, b] = side.direction;
    let d = patch.derivatives(side.start[0], side.start[1]);
    let p0 = d.x - xs;
    let p1 = a * d.s1 + b * d.s2;
    let p2 = 0.5 * ((a * a) * d.x_ee + (2.0 * a * b) * d.x_ez + (b * b) * d.x_zz);
    let r = |t: Real| p0 + p1 * t + p2 * (t * t);
    let mut t: Real = 0.0;
    let mut f = r(0.0).norm_squared();
    for s in [0.5, 1.0] {
        let fs = r(s).norm_squared();
        if fs < f {
            (t, f) = (s, fs);
        }
    }
    for _ in 0..10 {
        let rt = r(t);
        let xt = p1 + p2 * (2.0 * t);
        let g1 = rt.dot(&xt);
        let g2 = xt.norm_squared() + 2.0 * rt.dot(&p2);
        let next = if g2 > 0.0 {
            (t - g1 / g2).clamp(0.0, 1.0)
        } else if g1 > 0.0 {
            0.0
        } else {
            1.0
        };
        let fn_ = r(next).norm_squared();
        if !(fn_ <= f) {
            break;
        }
        let done = (next - t).abs() <= 1e-14;
        (t, f) = (next, fn_);
        if done {
            break;
        }
    }
    (t, r(t) + xs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edge_curve::EdgeCurveParams;
    use crate::quad_patch::QuadPatch;
    use crate::triangle_patch::TrianglePatch;

    fn sphere_tri() -> TrianglePatch {
        let x = [
            Vector::new(1.0, 0.0, 0.0),
            Vector::new(0.9, 0.4, 0.0).normalize(),
            Vector::new(0.9, 0.4, 0.4).normalize(),
        ];
        TrianglePatch::new(x, x, &EdgeCurveParams::default())
    }

    #[test]
    fn interior_foot_is_orthogonal() {
        let t = sphere_tri();
        let prm = ProjectionParams::default();
        for (dir, r) in [
            (Vector::new(0.95, 0.25, 0.1), 1.3),
            (Vector::new(0.95, 0.25, 0.1), 0.8),
            (Vector::new(0.93, 0.3, 0.05), 1.0),
        ] {
            let xs = r * dir.normalize();
            let p = project_onto_patch(&t, &xs, &prm).unwrap();
            assert!(p.converged && p.inside, "{p:?}");
            assert!(p.iterations <= 5, "{}", p.iterations);
            let d = t.derivatives(p.eta, p.zeta);
            let rr = xs - p.point;
            assert!(rr.dot(&d.s1).abs() < 1e-12 && rr.dot(&d.s2).abs() < 1e-12);
            assert!((rr - p.signed_distance * p.normal).norm() < 1e-11);
            assert!((p.normal.norm() - 1.0).abs() < 1e-14);
            // outward normal: sign of the gap follows the radius
            assert_eq!(p.signed_distance > 0.0, r > 1.0, "{p:?}");
        }
    }

    #[test]
    fn outside_foot_is_on_the_boundary() {
        let t = sphere_tri();
        let prm = ProjectionParams::default();
        // beyond the edge ζ = 0 (the x-y plane side)
        let xs = 1.1 * Vector::new(0.97, 0.2, -0.2).normalize();
        let p = project_onto_patch(&t, &xs, &prm).unwrap();
        assert!(!p.inside);
        assert!(p.zeta.abs() < 1e-14, "{p:?}");
        // no other boundary point is closer
        for k in 0..=200 {
            let s = k as Real / 200.0;
            for (e, z) in [(s, 0.0), (1.0, s), (s, s)] {
                assert!((t.point(e, z) - xs).norm() >= p.distance() - 1e-12);
            }
        }
    }

    #[test]
    fn degenerate_patches_give_none() {
        let x = Vector::new(1.0, 2.0, 3.0);
        let t = TrianglePatch::flat([x, x, x]);
        assert!(project_onto_patch(&t, &Vector::zeros(), &ProjectionParams::default()).is_none());
        let q = QuadPatch::flat([Vector::zeros(), Vector::x(), Vector::x(), Vector::zeros()]);
        assert!(project_onto_patch(&q, &Vector::y(), &ProjectionParams::default()).is_none());
        let good = sphere_tri();
        let nan = Vector::new(Real::NAN, 0.0, 0.0);
        assert!(project_onto_patch(&good, &nan, &ProjectionParams::default()).is_none());
    }

    #[test]
    fn params_are_validated() {
        assert!(ProjectionParams::default().validate().is_ok());
        for bad in [
            ProjectionParams {
                max_iterations: 0,
                ..Default::default()
            },
            ProjectionParams {
                tolerance: 0.0,
                ..Default::default()
            },
            ProjectionParams {
                inside_tolerance: Real::NAN,
                ..Default::default()
            },
        ] {
            assert!(bad.validate().is_err());
        }
    }
}
