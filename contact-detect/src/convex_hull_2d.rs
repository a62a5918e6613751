//! Convex hull of a small planar point set (Andrew's monotone chain).
use nalgebra::Vector2;

/// 2-D point or vector.
pub type V2 = Vector2<f64>;

#[inline]
fn cross(o: V2, a: V2, b: V2) -> f64 {
    (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
}

/// Writes the convex hull of `points` into `hull`, counter-clockwise,
/// without collinear points; `sorted` is scratch space.
///
/// Cost O(n log n). Fewer than three distinct non-collinear points give a
/// hull of 0, 1 or 2 points. Non-finite points are ignored.
pub fn convex_hull(points: &[V2], sorted: &mut Vec<V2>, hull: &mut Vec<V2>) {
    sorted.clear();
    sorted.extend(points.iter().filter(|p| p.x.is_finite() && p.y.is_finite()));
    sorted.sort_unstable_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    hull.clear();
    let n = sorted.len();
    if n < 3 {
        hull.extend_from_slice(sorted);
        return;
    }
    // lower hull
    for &p in sorted.iter() {
        while hull.len() >= 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        hull.push(p);
    }
    // upper hull
    let lower = hull.len() + 1;
    for &p in sorted.iter().rev().skip(1) {
        while hull.len() >= lower && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        hull.push(p);
    }
    hull.pop(); // the first point is repeated at the end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_with_inner_and_collinear_points() {
        let pts = [
            V2::new(0.0, 0.0),
            V2::new(0.5, 0.0),
            V2::new(1.0, 0.0),
            V2::new(0.5, 0.5),
            V2::new(1.0, 1.0),
            V2::new(0.0, 1.0),
            V2::new(0.0, 1.0),
        ];
        let (mut s, mut h) = (Vec::new(), Vec::new());
        convex_hull(&pts, &mut s, &mut h);
        assert_eq!(h.len(), 4);
        // counter-clockwise
        let area: f64 = (0..4)
            .map(|i| {
                let (a, b) = (h[i], h[(i + 1) % 4]);
                a.x * b.y - a.y * b.x
            })
            .sum();
        assert!((area - 2.0).abs() < 1e-12);
    }

    #[test]
    fn degenerate_inputs() {
        let (mut s, mut h) = (Vec::new(), Vec::new());
        convex_hull(&[], &mut s, &mut h);
        assert!(h.is_empty());
        convex_hull(&[V2::new(1.0, 1.0), V2::new(1.0, 1.0)], &mut s, &mut h);
        assert_eq!(h.len(), 1);
        let line = [V2::new(0.0, 0.0), V2::new(1.0, 1.0), V2::new(2.0, 2.0)];
        convex_hull(&line, &mut s, &mut h);
        assert_eq!(h.len(), 2);
        convex_hull(&[V2::new(f64::NAN, 0.0), V2::new(0.0, 0.0)], &mut s, &mut h);
        assert_eq!(h.len(), 1);
    }
}
