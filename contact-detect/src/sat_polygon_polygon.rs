//! 2-D separating-axis test between two polygons: the local phase of
//! detection (thesis §4.2.2, last paragraph).
use crate::convex_hull_2d::V2;
use fv_mesh::Real;

#[inline]
fn interval(poly: &[V2], axis: V2) -> (Real, Real) {
    let mut lo = Real::INFINITY;
    let mut hi = Real::NEG_INFINITY;
    for p in poly {
        let x = p.x * axis.x + p.y * axis.y;
        lo = lo.min(x);
        hi = hi.max(x);
    }
    (lo, hi)
}

/// Whether an edge normal of `edges_of` separates `a` from `b` by more than `tol`.
#[inline]
fn separated_by_edges_of(edges_of: &[V2], a: &[V2], b: &[V2], tol: Real) -> bool {
    let n = edges_of.len();
    if n < 2 {
        return false;
    }
    let mut prev = edges_of[n - 1];
    for &p in edges_of {
        let e = p - prev;
        prev = p;
        let axis = V2::new(-e.y, e.x);
        let len = (axis.x * axis.x + axis.y * axis.y).sqrt();
        if !(len > 0.0 && len.is_finite()) {
            continue;
        }
        let (alo, ahi) = interval(a, axis);
        let (blo, bhi) = interval(b, axis);
        let gap = tol * len;
        if ahi + gap < blo || bhi + gap < alo {
            return true;
        }
    }
    false
}

/// Whether polygons `a` and `b` overlap: no edge normal of either separates
/// their projections by more than `tol` (absolute distance), so touching
/// polygons overlap.
///
/// Exact for convex polygons (separating axis theorem); for a non-convex
/// polygon it answers for the convex hulls or conservatively (an overlap
/// may be reported for separated hulls, never the reverse). Vertex order
/// and orientation do not matter; zero-length edges are skipped. An empty
/// polygon overlaps nothing. Cost O((n_a + n_b)²) flops, early exit on the
/// first separating axis.
pub fn polygons_overlap(a: &[V2], b: &[V2], tol: Real) -> bool {
    if a.is_empty() || b.is_empty() {
        return false;
    }
    !(separated_by_edges_of(a, a, b, tol) || separated_by_edges_of(b, a, b, tol))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64) -> Vec<V2> {
        vec![
            V2::new(x, y),
            V2::new(x + s, y),
            V2::new(x + s, y + s),
            V2::new(x, y + s),
        ]
    }

    #[test]
    fn squares_and_triangles() {
        let a = square(0.0, 0.0, 1.0);
        assert!(polygons_overlap(&a, &square(0.5, 0.5, 1.0), 0.0));
        // touching edge and touching corner count
        assert!(polygons_overlap(&a, &square(1.0, 0.0, 1.0), 0.0));
        assert!(polygons_overlap(&a, &square(1.0, 1.0, 1.0), 0.0));
        assert!(!polygons_overlap(&a, &square(1.0 + 1e-6, 0.0, 1.0), 0.0));
        assert!(polygons_overlap(&a, &square(1.0 + 1e-6, 0.0, 1.0), 1e-5));
        // triangle whose bounding box overlaps but which is separated by its hypotenuse
        let t = vec![V2::new(1.2, 0.5), V2::new(2.0, 0.5), V2::new(2.0, -0.3)];
        let t2 = vec![V2::new(0.9, 1.6), V2::new(2.0, 0.5), V2::new(2.0, 2.0)];
        assert!(!polygons_overlap(&a, &t, 0.0));
        assert!(!polygons_overlap(&a, &t2, 0.0));
        // reversed orientation does not matter
        let mut r = square(0.5, 0.5, 1.0);
        r.reverse();
        assert!(polygons_overlap(&a, &r, 0.0));
        // containment
        assert!(polygons_overlap(&a, &square(0.25, 0.25, 0.5), 0.0));
        assert!(polygons_overlap(&square(0.25, 0.25, 0.5), &a, 0.0));
    }

    #[test]
    fn degenerate_polygons() {
        let a = square(0.0, 0.0, 1.0);
        assert!(!polygons_overlap(&a, &[], 0.0));
        assert!(polygons_overlap(&a, &[V2::new(0.5, 0.5)], 0.0));
        assert!(!polygons_overlap(&a, &[V2::new(1.5, 0.5)], 0.0));
        // a segment crossing the square, and one beside it
        assert!(polygons_overlap(
            &a,
            &[V2::new(-1.0, 0.5), V2::new(2.0, 0.5)],
            0.0
        ));
        assert!(!polygons_overlap(
            &a,
            &[V2::new(-1.0, 1.5), V2::new(2.0, 1.6)],
            0.0
        ));
        // repeated points
        let rep = vec![V2::new(0.2, 0.2), V2::new(0.2, 0.2), V2::new(0.4, 0.4)];
        assert!(polygons_overlap(&a, &rep, 0.0));
        let _ = polygons_overlap(&a, &[V2::new(f64::NAN, 0.0)], 0.0); // no panic
    }
}
