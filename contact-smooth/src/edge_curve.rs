//! The Nagata edge curve (thesis eqs. 4.76–4.77, Fig. 4.36).
//!
//! Between end points `x₀`, `x₁ = x₀ + d` with unit normals `n₀`, `n₁` the
//! edge is the quadratic
//!
//! ```text
//! x(ζ) = x₀ + (d − c) ζ + c ζ²,   0 ≤ ζ ≤ 1            (4.76)
//! ```
//!
//! whose end tangents `d ∓ c` are orthogonal to `n₀` and `n₁`. The
//! curvature parameter `c` is the minimum-norm solution of
//! `n₀·c = n₀·d`, `n₁·c = −n₁·d` (eq. 4.77). Written with the mean and the
//! half difference of the normals, `v = (n₀+n₁)/2` and `w = (n₀−n₁)/2`
//! (Nagata 2005), it splits into two orthogonal parts,
//!
//! ```text
//! c = (d·w)/(v·v) v + (d·v)/(w·w) w,
//! ```
//!
//! the first carrying the curvature of the edge, the second singular when
//! the normals become parallel (`w → 0`) while the chord is not orthogonal
//! to them (`d·v ≠ 0`): the "inflated, wrongly oriented" edges of §4.6.1.
//! Symmetrically the first part is singular for anti-parallel normals.
//!
//! # Degenerate-case treatment (ours, documented)
//!
//! * **Parallel threshold** (as Nagata 2005 and the implementations
//!   following it, e.g. Neto et al.): when the angle θ between the end
//!   normals is below [`EdgeCurveParams::parallel_angle`] (default 0.1°), or
//!   above π minus it, the edge is linear (`c = 0`), so a flat surface gives
//!   exactly flat patches. Unlike a hard switch we ramp `c` linearly from
//!   0 at θ = θ_tol to the full eq. 4.77 value at θ = 2 θ_tol, so the edge
//!   depends continuously on the normals.
//! * **Norm cap** (beyond the thesis): `|c|` is limited to
//!   [`EdgeCurveParams::max_curvature_ratio`]` · |d|` (default 1, the value
//!   of a 90° circular arc, `|c| = |d| tan(θ/2)`), scaling `c` down. This
//!   bounds the inflation for inconsistent data (nearly parallel normals and
//!   a chord leaning out of their tangent plane) without touching
//!   consistently sampled smooth surfaces.
//! * A zero or non-finite normal, or a zero chord, gives a linear edge.
use crate::SmoothError;
use fv_mesh::{Real, Vector};

/// Parameters of the curvature parameter (eq. 4.77) near its singular cases.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeCurveParams {
    /// θ_tol, radians: below this angle between the end normals (or above
    /// π − θ_tol) the edge is linear; full eq. 4.77 from 2 θ_tol on.
    /// Default 0.1° (Nagata 2005).
    pub parallel_angle: Real,
    /// Largest `|c| / |d|`; larger curvature parameters are scaled down.
    /// Default 1 (a 90° circular arc).
    pub max_curvature_ratio: Real,
}

impl Default for EdgeCurveParams {
    fn default() -> Self {
        EdgeCurveParams {
            parallel_angle: 0.1_f64.to_radians(),
            max_curvature_ratio: 1.0,
        }
    }
}

impl EdgeCurveParams {
    /// Checks that `parallel_angle` is in `[0, π/4]` and `max_curvature_ratio`
    /// positive (infinity allowed: no cap).
    pub fn validate(&self) -> Result<(), SmoothError> {
        let a = self.parallel_angle;
        if !(0.0..=std::f64::consts::FRAC_PI_4).contains(&a) {
            return Err(SmoothError::InvalidParameter {
                name: "parallel_angle",
                value: a,
                reason: "must be in [0, π/4] radians",
            });
        }
        let r = self.max_curvature_ratio;
        if !(r > 0.0) {
            return Err(SmoothError::InvalidParameter {
                name: "max_curvature_ratio",
                value: r,
                reason: "must be positive (infinity: no cap)",
            });
        }
        Ok(())
    }
}

/// Linear ramp: 0 for `x ≤ t`, 1 for `x ≥ 2t` (a step at `t = 0`).
pub(crate) fn parallel_ramp(x: Real, t: Real) -> Real {
    if t <= 0.0 {
        return if x > 0.0 { 1.0 } else { 0.0 };
    }
    ((x - t) / t).clamp(0.0, 1.0)
}

/// Curvature parameter `c(d, n₀, n₁)` of eq. 4.77 with the degenerate-case
/// treatment of the module documentation.
///
/// `n0`, `n1` need not be exactly unit (they are normalised); a zero or
/// non-finite normal gives `c = 0`. Cost: a few dozen flops, no allocation.
///
/// ```
/// use contact_smooth::{curvature_parameter, EdgeCurveParams};
/// use fv_mesh::Vector;
/// // quarter circle of radius 1: from (1,0,0) to (0,1,0), radial normals
/// let d = Vector::new(-1.0, 1.0, 0.0);
/// let c = curvature_parameter(&d, &Vector::x(), &Vector::y(), &EdgeCurveParams::default());
/// // |c| = |d| tan(45°), pointing to the centre of the arc
/// assert!((c - Vector::new(-1.0, -1.0, 0.0)).norm() < 1e-12);
/// ```
pub fn curvature_parameter(
    d: &Vector,
    n0: &Vector,
    n1: &Vector,
    params: &EdgeCurveParams,
) -> Vector {
    let (m0, m1) = (n0.norm(), n1.norm());
    let dd = d.norm();
    if !(m0 > 0.0 && m1 > 0.0 && m0.is_finite() && m1.is_finite() && dd > 0.0) {
        return Vector::zeros();
    }
    let (u0, u1) = (n0 / m0, n1 / m1);
    let v = 0.5 * (u0 + u1);
    let w = 0.5 * (u0 - u1);
    let (vv, ww) = (v.norm_squared(), w.norm_squared());
    let tol = params.parallel_angle;
    // tan(θ/2) = |w|/|v|: the angle θ between the normals is needed only
    // when it is within 2 θ_tol of 0 or π
    let t2 = tol.tan().powi(2);
    let s = if ww >= vv * t2 && vv >= ww * t2 {
        1.0
    } else {
        // accurate at both ends of [0, π]
        let theta = 2.0 * ww.sqrt().atan2(vv.sqrt());
        parallel_ramp(theta, tol) * parallel_ramp(std::f64::consts::PI - theta, tol)
    };
    if s == 0.0 {
        return Vector::zeros();
    }
    // s > 0 implies θ > θ_tol and π − θ > θ_tol, so vv, ww > 0
    let c = s * ((d.dot(&w) / vv) * v + (d.dot(&v) / ww) * w);
    let cap = params.max_curvature_ratio * dd;
    let cn = c.norm();
    if cn > cap {
        c * (cap / cn)
    } else {
        c
    }
}

/// One Nagata edge curve (eq. 4.76): `x(ζ) = x₀ + (d − c) ζ + c ζ²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeCurve {
    /// Start point `x₀`.
    pub x0: Vector,
    /// Chord `d = x₁ − x₀`.
    pub d: Vector,
    /// Curvature parameter `c` (eq. 4.77).
    pub c: Vector,
}

impl EdgeCurve {
    /// The edge from `x0` (normal `n0`) to `x1` (normal `n1`).
    pub fn new(x0: Vector, x1: Vector, n0: &Vector, n1: &Vector, params: &EdgeCurveParams) -> Self {
        let d = x1 - x0;
        EdgeCurve {
            x0,
            d,
            c: curvature_parameter(&d, n0, n1, params),
        }
    }

    /// Point at `ζ` (eq. 4.76).
    pub fn point(&self, zeta: Real) -> Vector {
        self.x0 + (self.d - self.c) * zeta + self.c * (zeta * zeta)
    }

    /// Tangent `dx/dζ = d − c + 2 c ζ`.
    pub fn tangent(&self, zeta: Real) -> Vector {
        self.d - self.c + self.c * (2.0 * zeta)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> EdgeCurveParams {
        EdgeCurveParams::default()
    }

    #[test]
    fn end_tangents_orthogonal_to_normals() {
        let x0 = Vector::new(0.1, -0.2, 0.3);
        let x1 = Vector::new(1.0, 0.4, 0.1);
        let n0 = Vector::new(0.1, 0.2, 1.0).normalize();
        let n1 = Vector::new(-0.3, 0.1, 1.0).normalize();
        let e = EdgeCurve::new(x0, x1, &n0, &n1, &p());
        assert!(e.tangent(0.0).dot(&n0).abs() < 1e-14);
        assert!(e.tangent(1.0).dot(&n1).abs() < 1e-14);
        assert!((e.point(1.0) - x1).norm() < 1e-15);
        // eq. 4.77 in the thesis's matrix form
        let a = n0.dot(&n1);
        let d = x1 - x0;
        let (b0, b1) = (n0.dot(&d), -n1.dot(&d));
        let c = (n0 * (b0 - a * b1) + n1 * (-a * b0 + b1)) / (1.0 - a * a);
        assert!((c - e.c).norm() < 1e-14);
    }

    #[test]
    fn reversed_edge_is_the_same_curve() {
        let x0 = Vector::new(0.0, 0.0, 0.0);
        let x1 = Vector::new(1.0, 0.2, 0.1);
        let n0 = Vector::new(0.2, 0.0, 1.0).normalize();
        let n1 = Vector::new(-0.1, 0.3, 1.0).normalize();
        let e = EdgeCurve::new(x0, x1, &n0, &n1, &p());
        let r = EdgeCurve::new(x1, x0, &n1, &n0, &p());
        for k in 0..=10 {
            let t = k as Real / 10.0;
            assert!((e.point(t) - r.point(1.0 - t)).norm() < 1e-15);
        }
    }

    #[test]
    fn parallel_and_antiparallel_normals_give_linear_edges() {
        let d = Vector::new(1.0, 0.0, 0.3);
        let n = Vector::new(0.0, 0.0, 1.0);
        assert_eq!(curvature_parameter(&d, &n, &n, &p()), Vector::zeros());
        assert_eq!(curvature_parameter(&d, &n, &(-n), &p()), Vector::zeros());
        // 0.05° apart: still linear
        let t = 0.05_f64.to_radians();
        let n1 = Vector::new(t.sin(), 0.0, t.cos());
        assert_eq!(curvature_parameter(&d, &n, &n1, &p()), Vector::zeros());
        // zero normal, zero chord
        assert_eq!(
            curvature_parameter(&d, &Vector::zeros(), &n, &p()),
            Vector::zeros()
        );
        assert_eq!(
            curvature_parameter(&Vector::zeros(), &n, &n1, &p()),
            Vector::zeros()
        );
    }

    #[test]
    fn ramp_is_continuous_and_cap_bounds_inflation() {
        // chord leaning out of the tangent plane by 0.3: eq. 4.77 explodes
        let d = Vector::new(1.0, 0.0, 0.3);
        let n0 = Vector::z();
        let tol = p().parallel_angle;
        let mut last = 0.0;
        for k in 0..=400 {
            let t = 3.0 * tol * k as Real / 400.0;
            let n1 = Vector::new(t.sin(), 0.0, t.cos());
            let c = curvature_parameter(&d, &n0, &n1, &p());
            assert!(c.norm() <= d.norm() * (1.0 + 1e-12));
            if k > 0 {
                // continuous: no jump larger than the cap allows per step
                assert!((c.norm() - last).abs() <= d.norm());
            }
            last = c.norm();
        }
        let none = EdgeCurveParams {
            max_curvature_ratio: Real::INFINITY,
            ..p()
        };
        let t = 3.0 * tol;
        let n1 = Vector::new(t.sin(), 0.0, t.cos());
        assert!(curvature_parameter(&d, &n0, &n1, &none).norm() > 50.0 * d.norm());
    }

    #[test]
    fn circular_arc_is_approximated_to_fourth_order() {
        // quadratic Nagata curve of a circular arc of angle φ: max radial error
        let err = |phi: Real| {
            let x0 = Vector::new(1.0, 0.0, 0.0);
            let x1 = Vector::new(phi.cos(), phi.sin(), 0.0);
            let e = EdgeCurve::new(x0, x1, &x0, &x1, &p());
            (0..=100)
                .map(|k| (e.point(k as Real / 100.0).norm() - 1.0).abs())
                .fold(0.0, Real::max)
        };
        let (e1, e2) = (err(0.4), err(0.2));
        let order = (e1 / e2).log2();
        assert!(order > 3.9, "order {order}");
    }

    #[test]
    fn parameters_are_validated() {
        assert!(p().validate().is_ok());
        let bad = EdgeCurveParams {
            parallel_angle: -1.0,
            ..p()
        };
        assert!(bad.validate().is_err());
        let bad = EdgeCurveParams {
            max_curvature_ratio: Real::NAN,
            ..p()
        };
        assert!(bad.validate().is_err());
    }
}
