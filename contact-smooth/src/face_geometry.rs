//! Centre and area vector of a polygon by central decomposition (the face
//! normal `n_b` of eq. 4.80).
use fv_mesh::{Real, Vector};

/// Centre and area vector of the polygon `poly` (indices into `points`):
/// triangles fanned from the vertex average, centre the area-weighted mean
/// of their centroids (the vertex average if the area vanishes).
///
/// An empty polygon, or one with an index out of range, gives zeros. The
/// area vector follows the right-hand rule of the vertex order.
pub fn polygon_centre_area(points: &[Vector], poly: &[usize]) -> (Vector, Vector) {
    let n = poly.len();
    if n == 0 || poly.iter().any(|&p| p >= points.len()) {
        return (Vector::zeros(), Vector::zeros());
    }
    let est = poly.iter().map(|&p| points[p]).sum::<Vector>() / n as Real;
    if n == 3 {
        let (a, b, c) = (points[poly[0]], points[poly[1]], points[poly[2]]);
        return (est, 0.5 * (b - a).cross(&(c - a)));
    }
    let mut sum_a = Vector::zeros();
    let mut sum_ac = Vector::zeros();
    let mut sum_mag = 0.0;
    for i in 0..n {
        let a = points[poly[i]];
        let b = points[poly[(i + 1) % n]];
        let tri = 0.5 * (a - est).cross(&(b - est));
        let m = tri.norm();
        sum_a += tri;
        sum_mag += m;
        sum_ac += m * (a + b + est) / 3.0;
    }
    let centre = if sum_mag > Real::MIN_POSITIVE {
        sum_ac / sum_mag
    } else {
        est
    };
    (centre, sum_a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_and_triangle() {
        let p = [
            Vector::new(0.0, 0.0, 0.0),
            Vector::new(2.0, 0.0, 0.0),
            Vector::new(2.0, 1.0, 0.0),
            Vector::new(0.0, 1.0, 0.0),
        ];
        let (c, a) = polygon_centre_area(&p, &[0, 1, 2, 3]);
        assert!((c - Vector::new(1.0, 0.5, 0.0)).norm() < 1e-15);
        assert!((a - Vector::new(0.0, 0.0, 2.0)).norm() < 1e-15);
        let (_, a) = polygon_centre_area(&p, &[0, 2, 1]);
        assert!((a - Vector::new(0.0, 0.0, -1.0)).norm() < 1e-15);
        assert_eq!(polygon_centre_area(&p, &[]).1, Vector::zeros());
        assert_eq!(polygon_centre_area(&p, &[0, 1, 7]).1, Vector::zeros());
    }
}
