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
        // plain comparisons compile to minsd/maxsd (NaN is ignored either way)
        lo = if x < lo { x } else { lo };
        hi = if x > hi { x } else { hi };
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
    let tol2 = tol * tol;
    let mut prev = edges_of[n - 1];
    for &p in edges_of {
        let e = p - prev;
        prev = p;
        // unnormalised axis: gaps scale with its length, compared squared
        let axis = V2::new(-e.y, e.x);
        let len2 = axis.x * axis.x + axis.y * axis.y;
        if !(len2 > 0.0 && len2.is_finite()) {
            continue;
        }
        let (alo, ahi) = interval(a, axis);
        let (blo, bhi) = interval(b, axis);
        let gap = (blo - ahi).max(alo - bhi);
        if gap > 0.0 && gap * gap > tol2 * len2 {
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

/// A polygon with its separating axes precomputed: the unit normal of
/// every edge with the polygon's extent along it, and its bounding box in
/// its own coordinates (see [`prepare_polygon`]).
#[derive(Debug, Clone, Copy)]
pub struct PreparedPolygon<'a> {
    /// Vertices.
    pub points: &'a [V2],
    /// Unit normal of edge `i` (from point `i` to `i + 1`); zero for a zero-length edge.
    pub axes: &'a [V2],
    /// Extent `[min, max]` of the polygon along each axis (unbounded for a zero axis).
    pub extents: &'a [[Real; 2]],
    /// Bounding box `[x_min, x_max, y_min, y_max]`.
    pub bbox: [Real; 4],
}

/// Appends the edge normals of `points` and the polygon's extents along
/// them to `axes` and `extents`; returns its bounding box.
pub fn prepare_polygon(
    points: &[V2],
    axes: &mut Vec<V2>,
    extents: &mut Vec<[Real; 2]>,
) -> [Real; 4] {
    let n = points.len();
    let mut bbox = [
        Real::INFINITY,
        Real::NEG_INFINITY,
        Real::INFINITY,
        Real::NEG_INFINITY,
    ];
    for p in points {
        bbox[0] = bbox[0].min(p.x);
        bbox[1] = bbox[1].max(p.x);
        bbox[2] = bbox[2].min(p.y);
        bbox[3] = bbox[3].max(p.y);
    }
    for i in 0..n {
        let e = points[if i + 1 == n { 0 } else { i + 1 }] - points[i];
        let len = e.norm();
        if len > 0.0 && len.is_finite() {
            let a = V2::new(-e.y, e.x) / len;
            let (lo, hi) = interval(points, a);
            axes.push(a);
            extents.push([lo, hi]);
        } else {
            axes.push(V2::zeros());
            extents.push([Real::NEG_INFINITY, Real::INFINITY]);
        }
    }
    bbox
}

/// Whether prepared polygon `a` and polygon `b` overlap: no axis among
/// `a`'s coordinate axes, `a`'s edge normals and `b`'s edge normals
/// separates their projections by more than `tol` (absolute distance).
///
/// For convex polygons this is [`polygons_overlap`] (the coordinate axes
/// only reject earlier); for a non-convex one it is at least as tight.
/// An empty polygon overlaps nothing. Cost: one pass over `b` per axis,
/// no square root for `a`'s axes.
pub fn prepared_polygons_overlap(a: &PreparedPolygon, b: &[V2], tol: Real) -> bool {
    if a.points.is_empty() || b.is_empty() {
        return false;
    }
    let (xlo, xhi) = interval(b, V2::new(1.0, 0.0));
    let (ylo, yhi) = interval(b, V2::new(0.0, 1.0));
    if xhi + tol < a.bbox[0]
        || a.bbox[1] + tol < xlo
        || yhi + tol < a.bbox[2]
        || a.bbox[3] + tol < ylo
    {
        return false;
    }
    for (&axis, ext) in a.axes.iter().zip(a.extents) {
        let (lo, hi) = interval(b, axis);
        if hi + tol < ext[0] || ext[1] + tol < lo {
            return false;
        }
    }
    !separated_by_edges_of(b, a.points, b, tol)
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
    fn prepared_matches_plain_on_convex_polygons() {
        let mut seed = 5u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64)
        };
        let (mut sorted, mut hull_a, mut hull_b) = (Vec::new(), Vec::new(), Vec::new());
        let mut overlaps = 0;
        for _ in 0..5000 {
            let pts = |rnd: &mut dyn FnMut() -> f64, cx: f64| {
                (0..3 + (rnd() * 5.0) as usize)
                    .map(|_| V2::new(cx + rnd(), rnd()))
                    .collect::<Vec<_>>()
            };
            let a = pts(&mut rnd, 0.0);
            let b = pts(&mut rnd, 0.6);
            crate::convex_hull(&a, &mut sorted, &mut hull_a);
            crate::convex_hull(&b, &mut sorted, &mut hull_b);
            let (mut axes, mut ext) = (Vec::new(), Vec::new());
            let bbox = prepare_polygon(&hull_a, &mut axes, &mut ext);
            let pa = PreparedPolygon {
                points: &hull_a,
                axes: &axes,
                extents: &ext,
                bbox,
            };
            let plain = polygons_overlap(&hull_a, &hull_b, 1e-12);
            assert_eq!(prepared_polygons_overlap(&pa, &hull_b, 1e-12), plain);
            overlaps += plain as usize;
        }
        assert!(overlaps > 500 && overlaps < 4500, "{overlaps}");
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
