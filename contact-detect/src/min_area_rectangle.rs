//! Minimum-area enclosing rectangle of a convex polygon by rotating
//! calipers (thesis §4.2.1, Fig. 4.10 a, ref. [128]).
use crate::convex_hull_2d::V2;

/// A rectangle in the plane: centre, unit direction of its first side and
/// half side lengths (along `axis` and along its left normal).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rectangle {
    /// Centre.
    pub centre: V2,
    /// Unit direction of the first side; the second is `(-axis.y, axis.x)`.
    pub axis: V2,
    /// Half lengths along `axis` and along its left normal.
    pub half: V2,
}

impl Rectangle {
    /// Area of the rectangle.
    pub fn area(&self) -> f64 {
        4.0 * self.half.x * self.half.y
    }
}

#[inline]
fn left(d: V2) -> V2 {
    V2::new(-d.y, d.x)
}

/// The minimum-area rectangle enclosing the convex polygon `hull`
/// (counter-clockwise, as [`crate::convex_hull_2d::convex_hull`] returns it).
///
/// One side of the optimal rectangle is collinear with a hull edge; the
/// three other supporting vertices (extreme along the edge, against it, and
/// along its inward normal) only move forward as the edge advances, so all
/// edges are tried in O(n) (rotating calipers). Hulls of up to 8 vertices
/// (every triangle and quadrilateral face) are scanned directly, which is
/// faster at that size and gives the same rectangle. Ties keep the first edge.
/// A hull of one point gives a zero-size rectangle, of two points a
/// zero-width one along the segment; `None` for an empty hull.
pub fn min_area_rectangle(hull: &[V2]) -> Option<Rectangle> {
    let n = hull.len();
    match n {
        0 => return None,
        1 => {
            return Some(Rectangle {
                centre: hull[0],
                axis: V2::new(1.0, 0.0),
                half: V2::zeros(),
            })
        }
        2 => {
            let e = hull[1] - hull[0];
            let len = e.norm();
            let axis = if len > 0.0 && len.is_finite() {
                e / len
            } else {
                V2::new(1.0, 0.0)
            };
            return Some(Rectangle {
                centre: 0.5 * (hull[0] + hull[1]),
                axis,
                half: V2::new(0.5 * len, 0.0),
            });
        }
        _ => {}
    }
    let (i, [lo, hi, base, top]) = if n <= SMALL_HULL {
        scan(hull)?
    } else {
        calipers(hull)?
    };
    let d = hull[if i + 1 == n { 0 } else { i + 1 }] - hull[i];
    let l = d.norm();
    let axis = d / l;
    let (lo, hi, base, top) = (lo / l, hi / l, base / l, top / l);
    Some(Rectangle {
        centre: axis * (0.5 * (lo + hi)) + left(axis) * (0.5 * (base + top)),
        axis,
        half: V2::new(0.5 * (hi - lo), 0.5 * (top - base)),
    })
}

/// Hulls up to this size are scanned edge by edge (O(n²), branch-free
/// inner loop), larger ones use the rotating calipers (O(n)); both return
/// the same edge and extents.
const SMALL_HULL: usize = 8;

/// Best edge and its extents `[lo, hi, base, top]` along the unnormalised
/// edge direction and its left normal, by a direct scan of every vertex.
fn scan(hull: &[V2]) -> Option<(usize, [f64; 4])> {
    let n = hull.len();
    let mut best: Option<(f64, usize, [f64; 4])> = None;
    for i in 0..n {
        let d = hull[if i + 1 == n { 0 } else { i + 1 }] - hull[i];
        let l2 = d.norm_squared();
        if !(l2 > 0.0 && l2.is_finite()) {
            continue;
        }
        let nrm = left(d);
        let (mut lo, mut hi, mut top) = (f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for p in hull {
            let x = p.dot(&d);
            let y = p.dot(&nrm);
            // plain comparisons (minsd/maxsd): no NaN can reach a hull
            lo = if x < lo { x } else { lo };
            hi = if x > hi { x } else { hi };
            top = if y > top { y } else { top };
        }
        let base = hull[i].dot(&nrm);
        let area = (hi - lo) * (top - base) / l2;
        if best.as_ref().is_none_or(|(a, _, _)| area < *a) {
            best = Some((area, i, [lo, hi, base, top]));
        }
    }
    best.map(|(_, i, e)| (i, e))
}

/// Like [`scan`], by rotating calipers: the three supporting vertices only
/// move forward as the edge advances.
fn calipers(hull: &[V2]) -> Option<(usize, [f64; 4])> {
    let n = hull.len();
    // indices stay in 0..n (no modulo in the loop)
    let next = |k: usize| if k + 1 == n { 0 } else { k + 1 };
    // advance index `k` while the next vertex is further along `dir`
    let climb = |mut k: usize, dir: V2| {
        let mut here = hull[k].dot(&dir);
        for _ in 0..n {
            let k1 = next(k);
            let there = hull[k1].dot(&dir);
            if there > here {
                (k, here) = (k1, there);
            } else {
                break;
            }
        }
        k
    };
    // Edge directions are left unnormalised: every projection then scales
    // with the edge length L, the area with L², and only the winner is
    // normalised (no square root per edge).
    let mut best: Option<(f64, usize, [f64; 4])> = None;
    let (mut k_max, mut k_top, mut k_min) = (0usize, 0usize, 0usize);
    let mut started = false;
    for i in 0..n {
        let d = hull[next(i)] - hull[i];
        let l2 = d.norm_squared();
        if !(l2 > 0.0 && l2.is_finite()) {
            continue;
        }
        let nrm = left(d);
        if !started {
            // first valid edge: full scan for the three extremes
            let (mut bmax, mut btop, mut bmin) =
                (hull[0].dot(&d), hull[0].dot(&nrm), -hull[0].dot(&d));
            for (j, p) in hull.iter().enumerate().skip(1) {
                let (x, y) = (p.dot(&d), p.dot(&nrm));
                if x > bmax {
                    (bmax, k_max) = (x, j);
                }
                if y > btop {
                    (btop, k_top) = (y, j);
                }
                if -x > bmin {
                    (bmin, k_min) = (-x, j);
                }
            }
            started = true;
        } else {
            k_max = climb(k_max, d);
            k_top = climb(k_top, nrm);
            k_min = climb(k_min, -d);
        }
        let base = hull[i].dot(&nrm);
        let (lo, hi) = (hull[k_min].dot(&d), hull[k_max].dot(&d));
        let top = hull[k_top].dot(&nrm);
        let area = (hi - lo) * (top - base) / l2;
        if best.as_ref().is_none_or(|(a, _, _)| area < *a) {
            best = Some((area, i, [lo, hi, base, top]));
        }
    }
    best.map(|(_, i, e)| (i, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::convex_hull_2d::convex_hull;

    /// O(n²) reference: every edge direction, extents by a full scan.
    fn naive(hull: &[V2]) -> f64 {
        let n = hull.len();
        let mut best = f64::INFINITY;
        for i in 0..n {
            let e = hull[(i + 1) % n] - hull[i];
            let d = e / e.norm();
            let nrm = left(d);
            let (mut lo, mut hi, mut blo, mut bhi) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for p in hull {
                lo = lo.min(p.dot(&d));
                hi = hi.max(p.dot(&d));
                blo = blo.min(p.dot(&nrm));
                bhi = bhi.max(p.dot(&nrm));
            }
            best = best.min((hi - lo) * (bhi - blo));
        }
        best
    }

    fn contains(r: &Rectangle, p: V2) -> bool {
        let q = p - r.centre;
        let tol = 1e-9 * (1.0 + r.half.norm());
        q.dot(&r.axis).abs() <= r.half.x + tol && q.dot(&left(r.axis)).abs() <= r.half.y + tol
    }

    #[test]
    fn rotated_rectangle_is_recovered() {
        let (s, c) = 0.3f64.sin_cos();
        let rot = |x: f64, y: f64| V2::new(c * x - s * y, s * x + c * y);
        let hull = [rot(0.0, 0.0), rot(2.0, 0.0), rot(2.0, 1.0), rot(0.0, 1.0)];
        let r = min_area_rectangle(&hull).unwrap();
        assert!((r.area() - 2.0).abs() < 1e-12);
        assert!(
            (r.axis.x * s - r.axis.y * c).abs() < 1e-12
                || (r.axis.x * c + r.axis.y * s).abs() < 1e-12
        );
        for p in hull {
            assert!(contains(&r, p));
        }
    }

    #[test]
    fn matches_naive_on_pseudo_random_polygons() {
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64)
        };
        let (mut sorted, mut hull) = (Vec::new(), Vec::new());
        for case in 0..2000 {
            let n = 3 + case % 12;
            let aspect = 0.05 + 3.0 * rnd();
            let pts: Vec<V2> = (0..n).map(|_| V2::new(rnd(), aspect * rnd())).collect();
            convex_hull(&pts, &mut sorted, &mut hull);
            if hull.len() < 3 {
                continue;
            }
            let r = min_area_rectangle(&hull).unwrap();
            assert_eq!(scan(&hull), calipers(&hull), "case {case}");
            let reference = naive(&hull);
            assert!(
                (r.area() - reference).abs() <= 1e-12 * (1.0 + reference),
                "case {case}: {} vs {reference}",
                r.area()
            );
            for &p in &pts {
                assert!(contains(&r, p), "case {case}");
            }
        }
    }

    #[test]
    fn degenerate_hulls() {
        assert!(min_area_rectangle(&[]).is_none());
        let r = min_area_rectangle(&[V2::new(1.0, 2.0)]).unwrap();
        assert_eq!(r.area(), 0.0);
        let r = min_area_rectangle(&[V2::new(0.0, 0.0), V2::new(0.0, 2.0)]).unwrap();
        assert_eq!(r.half, V2::new(1.0, 0.0));
        assert_eq!(r.centre, V2::new(0.0, 1.0));
    }
}
