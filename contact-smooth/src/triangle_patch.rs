//! Triangular Nagata patch (thesis eq. 4.78, Tables 4.8, 4.9 and 4.11).
//!
//! Corners `x₀₀, x₁₀, x₁₁` (in the face's vertex order) over
//! `0 ≤ ζ ≤ η ≤ 1`:
//!
//! ```text
//! x(η, ζ) = c₀₀ + c₁₀ η + c₀₁ ζ + c₁₁ ηζ + c₂₀ η² + c₀₂ ζ²
//! ```
//!
//! (eq. 4.78 as printed lacks the `c₂₀ η²` term and writes `c₁₁ η²`; the
//! form above is Nagata's, the one consistent with Tables 4.8 and 4.11).
//! The three sides are the edge curves of eq. 4.76, so neighbouring patches
//! sharing an edge (and its end normals) meet without a gap.
use crate::edge_curve::{curvature_parameter, EdgeCurveParams};
use crate::patch::{solve_2x2_least_squares, NagataPatch, PatchDerivatives, PatchDomain};
use fv_mesh::{Real, Vector};

/// Coefficients of a triangular Nagata patch (Table 4.8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrianglePatch {
    /// `c₀₀ = x₀₀`.
    pub c00: Vector,
    /// `c₁₀ = x₁₀ − x₀₀ − c₁`.
    pub c10: Vector,
    /// `c₀₁ = x₁₁ − x₁₀ + c₁ − c₃`.
    pub c01: Vector,
    /// `c₁₁ = c₃ − c₁ − c₂`.
    pub c11: Vector,
    /// `c₂₀ = c₁`.
    pub c20: Vector,
    /// `c₀₂ = c₂`.
    pub c02: Vector,
    /// Corners `x₀₀, x₁₀, x₁₁`.
    pub corners: [Vector; 3],
}

impl Default for TrianglePatch {
    fn default() -> Self {
        TrianglePatch {
            c00: Vector::zeros(),
            c10: Vector::zeros(),
            c01: Vector::zeros(),
            c11: Vector::zeros(),
            c20: Vector::zeros(),
            c02: Vector::zeros(),
            corners: [Vector::zeros(); 3],
        }
    }
}

impl TrianglePatch {
    /// The patch through corners `x = [x₀₀, x₁₀, x₁₁]` with unit normals `n`.
    ///
    /// Curvature parameters (Table 4.9): `c₁` on `x₀₀x₁₀`, `c₂` on
    /// `x₁₀x₁₁`, `c₃` on `x₀₀x₁₁`. The normal of the patch follows the
    /// right-hand rule of the corner order.
    pub fn new(x: [Vector; 3], n: [Vector; 3], params: &EdgeCurveParams) -> Self {
        let c1 = curvature_parameter(&(x[1] - x[0]), &n[0], &n[1], params);
        let c2 = curvature_parameter(&(x[2] - x[1]), &n[1], &n[2], params);
        let c3 = curvature_parameter(&(x[2] - x[0]), &n[0], &n[2], params);
        TrianglePatch {
            c00: x[0],
            c10: x[1] - x[0] - c1,
            c01: x[2] - x[1] + c1 - c3,
            c11: c3 - c1 - c2,
            c20: c1,
            c02: c2,
            corners: x,
        }
    }

    /// The flat triangle through the corners (all curvature parameters zero).
    pub fn flat(x: [Vector; 3]) -> Self {
        let z = Vector::zeros();
        Self::new(x, [z; 3], &EdgeCurveParams::default())
    }
}

impl NagataPatch for TrianglePatch {
    fn domain(&self) -> PatchDomain {
        PatchDomain::Triangle
    }

    fn point(&self, eta: Real, zeta: Real) -> Vector {
        self.c00
            + self.c10 * eta
            + self.c01 * zeta
            + self.c11 * (eta * zeta)
            + self.c20 * (eta * eta)
            + self.c02 * (zeta * zeta)
    }

    fn derivatives(&self, eta: Real, zeta: Real) -> PatchDerivatives {
        PatchDerivatives {
            x: self.point(eta, zeta),
            s1: self.c10 + self.c11 * zeta + self.c20 * (2.0 * eta),
            s2: self.c01 + self.c11 * eta + self.c02 * (2.0 * zeta),
            x_ee: 2.0 * self.c20,
            x_ez: self.c11,
            x_zz: 2.0 * self.c02,
        }
    }

    /// Flat map `x₀₀ + η (x₁₀ − x₀₀) + ζ (x₁₁ − x₁₀)`, inverted in the
    /// least-squares sense; the domain centre for a degenerate triangle.
    fn flat_start(&self, xs: &Vector) -> (Real, Real) {
        let [x0, x1, x2] = self.corners;
        solve_2x2_least_squares(&(x1 - x0), &(x2 - x1), &(xs - x0))
            .unwrap_or_else(|| self.domain().centre())
    }

    fn size(&self) -> Real {
        let [x0, x1, x2] = self.corners;
        (x1 - x0).norm().max((x2 - x1).norm()).max((x2 - x0).norm())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edge_curve::EdgeCurve;

    fn sphere_triangle() -> ([Vector; 3], [Vector; 3]) {
        let x = [
            Vector::new(1.0, 0.1, 0.2).normalize(),
            Vector::new(0.8, 0.6, 0.1).normalize(),
            Vector::new(0.7, 0.3, 0.6).normalize(),
        ];
        (x, x)
    }

    #[test]
    fn corners_and_sides_are_the_edge_curves() {
        let (x, n) = sphere_triangle();
        let p = EdgeCurveParams::default();
        let t = TrianglePatch::new(x, n, &p);
        assert!((t.point(0.0, 0.0) - x[0]).norm() < 1e-15);
        assert!((t.point(1.0, 0.0) - x[1]).norm() < 1e-15);
        assert!((t.point(1.0, 1.0) - x[2]).norm() < 1e-15);
        let e1 = EdgeCurve::new(x[0], x[1], &n[0], &n[1], &p);
        let e2 = EdgeCurve::new(x[1], x[2], &n[1], &n[2], &p);
        let e3 = EdgeCurve::new(x[0], x[2], &n[0], &n[2], &p);
        for k in 0..=8 {
            let s = k as Real / 8.0;
            assert!((t.point(s, 0.0) - e1.point(s)).norm() < 1e-15);
            assert!((t.point(1.0, s) - e2.point(s)).norm() < 1e-15);
            assert!((t.point(s, s) - e3.point(s)).norm() < 1e-15);
        }
        // the patch normal at the corners is the given normal
        for (e, z, k) in [(0.0, 0.0, 0), (1.0, 0.0, 1), (1.0, 1.0, 2)] {
            let m = t.normal(e, z).unwrap();
            assert!((m - n[k]).norm() < 1e-12, "corner {k}: {m:?}");
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let (x, n) = sphere_triangle();
        let t = TrianglePatch::new(x, n, &EdgeCurveParams::default());
        let (e, z, h) = (0.6, 0.25, 1e-6);
        let d = t.derivatives(e, z);
        let s1 = (t.point(e + h, z) - t.point(e - h, z)) / (2.0 * h);
        let s2 = (t.point(e, z + h) - t.point(e, z - h)) / (2.0 * h);
        assert!((s1 - d.s1).norm() < 1e-9 && (s2 - d.s2).norm() < 1e-9);
        let dp = t.derivatives(e + h, z);
        let dm = t.derivatives(e - h, z);
        assert!(((dp.s1 - dm.s1) / (2.0 * h) - d.x_ee).norm() < 1e-8);
        assert!(((dp.s2 - dm.s2) / (2.0 * h) - d.x_ez).norm() < 1e-8);
        let dp = t.derivatives(e, z + h);
        let dm = t.derivatives(e, z - h);
        assert!(((dp.s2 - dm.s2) / (2.0 * h) - d.x_zz).norm() < 1e-8);
    }

    #[test]
    fn flat_start_inverts_the_flat_map() {
        let (x, _) = sphere_triangle();
        let t = TrianglePatch::flat(x);
        let p = x[0] + 0.7 * (x[1] - x[0]) + 0.2 * (x[2] - x[1]);
        let (e, z) = t.flat_start(&(p + 0.3 * t.normal(0.5, 0.2).unwrap()));
        assert!((e - 0.7).abs() < 1e-12 && (z - 0.2).abs() < 1e-12);
        let degenerate = TrianglePatch::flat([x[0], x[0], x[1]]);
        assert_eq!(degenerate.flat_start(&p), PatchDomain::Triangle.centre());
    }
}
