//! Sutherland–Hodgman polygon clipping in the auxiliary plane (thesis §4.4,
//! step c and Fig. 4.21) and the clip of a segment to its non-positive-gap
//! part (step c*).
//!
//! Both are the same operation: keep the part of a polygon where a function,
//! linear along every edge, is ≤ 0. For step c the function is the signed
//! distance to one edge of the convex clipper (repeated for every edge); for
//! step c* it is the normal gap, given by its values at the polygon points.
use fv_mesh::Real;

/// A point of the auxiliary plane (in-plane coordinates).
pub type Point2 = nalgebra::Vector2<Real>;

/// An affine function of the auxiliary-plane coordinates, `c + n · p`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine2 {
    /// Value at the plane origin.
    pub c: Real,
    /// Gradient.
    pub n: Point2,
}

impl Affine2 {
    /// Value at `p`.
    #[inline]
    pub fn value(&self, p: &Point2) -> Real {
        self.c + self.n.dot(p)
    }
}

/// Signed area of a polygon (shoelace; positive when counter-clockwise).
pub fn signed_area(poly: &[Point2]) -> Real {
    let n = poly.len();
    if n < 3 {
        return 0.0;
    }
    // relative to the first point: smaller round-off far from the origin
    let o = poly[0];
    let mut a = 0.0;
    for i in 1..n - 1 {
        let (p, q) = (poly[i] - o, poly[i + 1] - o);
        a += p.x * q.y - p.y * q.x;
    }
    0.5 * a
}

/// Keeps the part of `poly` where the vertex values `values` (linearly
/// interpolated along the edges) are ≤ 0; writes its points to `out_poly`
/// and their values to `out_values` (0 at the new points).
///
/// This is step c* of §4.4 ("use the normal gap values at points of polygon
/// k to loop over its edges and form polygon k'") and one pass of
/// Sutherland–Hodgman. For a convex polygon and a function that is linear
/// over it, the result is the exact convex intersection. Cost O(n), no
/// allocation once the outputs are large enough.
pub fn clip_non_positive(
    poly: &[Point2],
    values: &[Real],
    out_poly: &mut Vec<Point2>,
    out_values: &mut Vec<Real>,
) {
    out_poly.clear();
    out_values.clear();
    let n = poly.len().min(values.len());
    if n == 0 {
        return;
    }
    let (mut p_prev, mut g_prev) = (poly[n - 1], values[n - 1]);
    for i in 0..n {
        let (p, g) = (poly[i], values[i]);
        let inside = g <= 0.0;
        let prev_inside = g_prev <= 0.0;
        if inside != prev_inside {
            // the signs differ, so t ∈ [0, 1]
            let t = g_prev / (g_prev - g);
            if t.is_finite() {
                out_poly.push(p_prev + (p - p_prev) * t);
                out_values.push(0.0);
            }
        }
        if inside {
            out_poly.push(p);
            out_values.push(g);
        }
        p_prev = p;
        g_prev = g;
    }
}

/// Reusable buffers of [`clip_convex`].
#[derive(Debug, Clone, Default)]
pub struct ClipScratch {
    values: Vec<Real>,
    out_values: Vec<Real>,
    tmp: Vec<Point2>,
}

/// Clips polygon `subject` by the convex, counter-clockwise polygon
/// `clipper` (Sutherland–Hodgman, thesis Fig. 4.21); writes the intersection
/// polygon (counter-clockwise if `subject` is) to `out`.
///
/// Points on a clipper edge count as inside, so coincident edges of
/// conforming meshes keep their full area. The result is empty if the
/// polygons do not overlap (touching polygons give a zero-area polygon).
/// Cost O(|subject| · |clipper|); no allocation once the buffers have grown.
pub fn clip_convex(
    subject: &[Point2],
    clipper: &[Point2],
    out: &mut Vec<Point2>,
    scratch: &mut ClipScratch,
) {
    out.clear();
    out.extend_from_slice(subject);
    let nc = clipper.len();
    if nc < 3 {
        out.clear();
        return;
    }
    for i in 0..nc {
        if out.is_empty() {
            return;
        }
        let a = clipper[i];
        let e = clipper[(i + 1) % nc] - a;
        // outside distance (scaled): > 0 right of edge a→b
        let f = Affine2 {
            c: -(e.y * a.x - e.x * a.y),
            n: Point2::new(e.y, -e.x),
        };
        scratch.values.clear();
        scratch.values.extend(out.iter().map(|p| f.value(p)));
        std::mem::swap(out, &mut scratch.tmp);
        clip_non_positive(&scratch.tmp, &scratch.values, out, &mut scratch.out_values);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: Real, y0: Real, h: Real) -> Vec<Point2> {
        vec![
            Point2::new(x0, y0),
            Point2::new(x0 + h, y0),
            Point2::new(x0 + h, y0 + h),
            Point2::new(x0, y0 + h),
        ]
    }

    #[test]
    fn overlapping_squares_and_triangle() {
        let mut out = Vec::new();
        let mut s = ClipScratch::default();
        clip_convex(
            &square(0.0, 0.0, 1.0),
            &square(0.5, 0.25, 1.0),
            &mut out,
            &mut s,
        );
        assert!((signed_area(&out) - 0.5 * 0.75).abs() < 1e-15);
        // identical squares: full area
        clip_convex(
            &square(0.0, 0.0, 1.0),
            &square(0.0, 0.0, 1.0),
            &mut out,
            &mut s,
        );
        assert!((signed_area(&out) - 1.0).abs() < 1e-15);
        // disjoint
        clip_convex(
            &square(0.0, 0.0, 1.0),
            &square(2.0, 0.0, 1.0),
            &mut out,
            &mut s,
        );
        assert!(signed_area(&out).abs() < 1e-15);
        // touching along an edge: zero area
        clip_convex(
            &square(0.0, 0.0, 1.0),
            &square(1.0, 0.0, 1.0),
            &mut out,
            &mut s,
        );
        assert!(signed_area(&out).abs() < 1e-15);
        // triangle x + y ≤ 1 clipped by the unit square shifted by (0.5, 0)
        let tri = vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(0.0, 1.0),
        ];
        clip_convex(&tri, &square(0.5, 0.0, 1.0), &mut out, &mut s);
        assert!((signed_area(&out) - 0.125).abs() < 1e-15);
        // degenerate clipper
        clip_convex(&tri, &tri[..2], &mut out, &mut s);
        assert!(out.is_empty());
    }

    #[test]
    fn non_positive_part() {
        let sq = square(0.0, 0.0, 1.0);
        // g = x - 0.25: keeps x ≤ 0.25
        let g: Vec<Real> = sq.iter().map(|p| p.x - 0.25).collect();
        let (mut p, mut v) = (Vec::new(), Vec::new());
        clip_non_positive(&sq, &g, &mut p, &mut v);
        assert!((signed_area(&p) - 0.25).abs() < 1e-15);
        assert!(v.iter().all(|&x| x <= 0.0));
        // all positive: empty; all non-positive: unchanged
        let pos: Vec<Real> = vec![1.0; 4];
        clip_non_positive(&sq, &pos, &mut p, &mut v);
        assert!(p.is_empty());
        let neg: Vec<Real> = vec![-1.0, 0.0, -2.0, 0.0];
        clip_non_positive(&sq, &neg, &mut p, &mut v);
        assert_eq!(p, sq);
        assert_eq!(v, neg);
        clip_non_positive(&[], &[], &mut p, &mut v);
        assert!(p.is_empty());
    }
}
