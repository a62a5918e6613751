//! What every Nagata patch offers to the projection: position, first and
//! second derivatives (thesis Table 4.11), its parameter domain (Fig. 4.38)
//! and a starting point from the flat face.
use fv_mesh::{Real, Vector};

/// Position and derivatives of a patch at one local point `(η, ζ)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchDerivatives {
    /// `x(η, ζ)`.
    pub x: Vector,
    /// `s₁ = ∂x/∂η` (Table 4.11).
    pub s1: Vector,
    /// `s₂ = ∂x/∂ζ` (Table 4.11).
    pub s2: Vector,
    /// `∂²x/∂η²`.
    pub x_ee: Vector,
    /// `∂²x/∂η∂ζ`.
    pub x_ez: Vector,
    /// `∂²x/∂ζ²`.
    pub x_zz: Vector,
}

/// Parameter domain of a patch (Fig. 4.38).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PatchDomain {
    /// `0 ≤ ζ ≤ η ≤ 1`.
    Triangle,
    /// `0 ≤ η, ζ ≤ 1`.
    Square,
}

/// One side of a parameter domain: `(η, ζ) = start + t · direction`, `t ∈ [0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DomainEdge {
    /// `(η, ζ)` at `t = 0`.
    pub start: [Real; 2],
    /// `d(η, ζ)/dt`.
    pub direction: [Real; 2],
}

const TRIANGLE_EDGES: [DomainEdge; 3] = [
    DomainEdge {
        start: [0.0, 0.0],
        direction: [1.0, 0.0],
    },
    DomainEdge {
        start: [1.0, 0.0],
        direction: [0.0, 1.0],
    },
    DomainEdge {
        start: [0.0, 0.0],
        direction: [1.0, 1.0],
    },
];

const SQUARE_EDGES: [DomainEdge; 4] = [
    DomainEdge {
        start: [0.0, 0.0],
        direction: [1.0, 0.0],
    },
    DomainEdge {
        start: [1.0, 0.0],
        direction: [0.0, 1.0],
    },
    DomainEdge {
        start: [0.0, 1.0],
        direction: [1.0, 0.0],
    },
    DomainEdge {
        start: [0.0, 0.0],
        direction: [0.0, 1.0],
    },
];

impl PatchDomain {
    /// Whether `(η, ζ)` lies in the domain, widened by `tol`.
    pub fn contains(self, eta: Real, zeta: Real, tol: Real) -> bool {
        match self {
            PatchDomain::Triangle => zeta >= -tol && zeta <= eta + tol && eta <= 1.0 + tol,
            PatchDomain::Square => {
                eta >= -tol && eta <= 1.0 + tol && zeta >= -tol && zeta <= 1.0 + tol
            }
        }
    }

    /// A point of the domain near `(η, ζ)` (the nearest for the square; for
    /// the triangle, the nearest point of the triangle in the `(η, ζ)` plane).
    /// Non-finite input gives the centre.
    pub fn clamp(self, eta: Real, zeta: Real) -> (Real, Real) {
        if !(eta.is_finite() && zeta.is_finite()) {
            return self.centre();
        }
        match self {
            PatchDomain::Square => (eta.clamp(0.0, 1.0), zeta.clamp(0.0, 1.0)),
            PatchDomain::Triangle => {
                if self.contains(eta, zeta, 0.0) {
                    return (eta, zeta);
                }
                // nearest point on each side, keep the closest
                let mut best = (0.0, 0.0);
                let mut best_d = Real::INFINITY;
                for e in TRIANGLE_EDGES {
                    let [a, b] = e.direction;
                    let (pe, pz) = (eta - e.start[0], zeta - e.start[1]);
                    let t = ((pe * a + pz * b) / (a * a + b * b)).clamp(0.0, 1.0);
                    let (qe, qz) = (e.start[0] + t * a, e.start[1] + t * b);
                    let dist = (qe - eta).powi(2) + (qz - zeta).powi(2);
                    if dist < best_d {
                        best_d = dist;
                        best = (qe, qz);
                    }
                }
                best
            }
        }
    }

    /// Bit `k` set: `(η, ζ)` lies beyond side `k` of [`PatchDomain::edges`]
    /// (0 inside the domain).
    pub fn violated_sides(self, eta: Real, zeta: Real) -> u8 {
        let bit = |c: bool, k: u8| if c { 1u8 << k } else { 0 };
        match self {
            PatchDomain::Triangle => bit(zeta < 0.0, 0) | bit(eta > 1.0, 1) | bit(zeta > eta, 2),
            PatchDomain::Square => {
                bit(zeta < 0.0, 0) | bit(eta > 1.0, 1) | bit(zeta > 1.0, 2) | bit(eta < 0.0, 3)
            }
        }
    }

    /// The centroid of the domain: `(2/3, 1/3)` or `(1/2, 1/2)`.
    pub fn centre(self) -> (Real, Real) {
        match self {
            PatchDomain::Triangle => (2.0 / 3.0, 1.0 / 3.0),
            PatchDomain::Square => (0.5, 0.5),
        }
    }

    /// The sides of the domain; side `k` maps to polygon edge `k`
    /// (triangle: `x₀₀x₁₀`, `x₁₀x₁₁`, `x₀₀x₁₁`; square: `x₀₀x₁₀`, `x₁₀x₁₁`,
    /// `x₀₁x₁₁`, `x₀₀x₀₁`).
    pub fn edges(self) -> &'static [DomainEdge] {
        match self {
            PatchDomain::Triangle => &TRIANGLE_EDGES,
            PatchDomain::Square => &SQUARE_EDGES,
        }
    }
}

/// A Nagata patch: a quadratic (triangle, eq. 4.78) or serendipity-like
/// (quadrilateral, eq. 4.79) polynomial surface over a [`PatchDomain`].
pub trait NagataPatch {
    /// The parameter domain.
    fn domain(&self) -> PatchDomain;

    /// Position `x(η, ζ)`.
    fn point(&self, eta: Real, zeta: Real) -> Vector;

    /// Position with first and second derivatives.
    fn derivatives(&self, eta: Real, zeta: Real) -> PatchDerivatives;

    /// `(η, ζ)` of the projection of `xs` onto the flat face through the
    /// patch corners (may lie outside the domain); the start of the
    /// Newton–Raphson projection.
    fn flat_start(&self, xs: &Vector) -> (Real, Real);

    /// A length of the patch (its longest corner-to-corner distance), the
    /// scale of the projection tolerances.
    fn size(&self) -> Real;

    /// Unit normal `s₁ × s₂ / |s₁ × s₂|` (eq. 4.82), `None` where the
    /// parametrisation is singular.
    fn normal(&self, eta: Real, zeta: Real) -> Option<Vector> {
        let d = self.derivatives(eta, zeta);
        let n = d.s1.cross(&d.s2);
        let m = n.norm();
        (m > 0.0 && m.is_finite()).then(|| n / m)
    }
}

/// Least-squares `(η, ζ)` of `r ≈ η a + ζ b` (normal equations); `None` if
/// `a`, `b` are (nearly) parallel.
pub(crate) fn solve_2x2_least_squares(a: &Vector, b: &Vector, r: &Vector) -> Option<(Real, Real)> {
    let (aa, ab, bb) = (a.dot(a), a.dot(b), b.dot(b));
    let (ra, rb) = (r.dot(a), r.dot(b));
    let det = aa * bb - ab * ab;
    if !(det > 1e-24 * aa * bb) {
        return None;
    }
    Some(((ra * bb - rb * ab) / det, (rb * aa - ra * ab) / det))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn domain_membership_and_clamping() {
        let t = PatchDomain::Triangle;
        assert!(t.contains(0.5, 0.25, 0.0));
        assert!(!t.contains(0.25, 0.5, 0.0));
        assert!(t.contains(1.0 + 1e-10, 0.0, 1e-9));
        assert_eq!(t.clamp(0.25, 0.5), (0.375, 0.375));
        assert_eq!(t.clamp(2.0, 0.5), (1.0, 0.5));
        assert_eq!(t.clamp(0.5, -1.0), (0.5, 0.0));
        assert_eq!(t.clamp(Real::NAN, 0.0), t.centre());
        let s = PatchDomain::Square;
        assert!(s.contains(0.0, 1.0, 0.0));
        assert_eq!(s.clamp(-1.0, 2.0), (0.0, 1.0));
        assert_eq!(t.violated_sides(0.5, 0.25), 0);
        assert_eq!(t.violated_sides(1.5, -0.1), 0b011);
        assert_eq!(t.violated_sides(0.2, 0.4), 0b100);
        assert_eq!(s.violated_sides(-0.1, 1.2), 0b1100);
        for d in [t, s] {
            let (e, z) = d.centre();
            assert!(d.contains(e, z, 0.0));
            for edge in d.edges() {
                for k in 0..=4 {
                    let u = k as Real / 4.0;
                    let e = edge.start[0] + u * edge.direction[0];
                    let z = edge.start[1] + u * edge.direction[1];
                    assert!(d.contains(e, z, 1e-15));
                }
            }
        }
    }

    #[test]
    fn least_squares_2x2() {
        let a = Vector::new(1.0, 0.0, 0.0);
        let b = Vector::new(1.0, 1.0, 0.0);
        let r = 0.3 * a + 0.7 * b + Vector::new(0.0, 0.0, 5.0);
        let (e, z) = solve_2x2_least_squares(&a, &b, &r).unwrap();
        assert!((e - 0.3).abs() < 1e-14 && (z - 0.7).abs() < 1e-14);
        assert!(solve_2x2_least_squares(&a, &(2.0 * a), &r).is_none());
    }
}
