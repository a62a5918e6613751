//! Centre triangulation of a segment and its occluded volume (thesis §4.4,
//! steps d–e, eqs. 4.24–4.25).
use crate::sutherland_hodgman::Point2;
use fv_mesh::Real;

/// Area and integral of a gap over a convex polygon by centre
/// triangulation (eqs. 4.24 / 4.25):
/// `(Σ_i Γ_i, Σ_i ⅓ (g_i + g_{i+1} + g_c) Γ_i)`.
///
/// The centre `x_c` is the mean of the polygon points and `g_c` the mean of
/// their values; for a gap that is affine over the polygon (a segment
/// between two flat faces) this is the gap at `x_c` (step e projects `x_c`
/// onto the slave face), and the sum is the exact integral. With the
/// non-positive part of a segment (step c*) the integral is the occluded
/// volume `ḡ_{n,k} Γ_k` of eq. 4.19. Triangle areas are signed, so a
/// clockwise polygon gives a negative area. O(n).
pub fn central_integral(poly: &[Point2], values: &[Real]) -> (Real, Real) {
    let n = poly.len().min(values.len());
    if n < 3 {
        return (0.0, 0.0);
    }
    let inv = 1.0 / n as Real;
    let c = poly[..n].iter().fold(Point2::zeros(), |a, p| a + p) * inv;
    let gc = values[..n].iter().sum::<Real>() * inv;
    let (mut area, mut integral) = (0.0, 0.0);
    for i in 0..n {
        let j = if i + 1 == n { 0 } else { i + 1 };
        let (p, q) = (poly[i] - c, poly[j] - c);
        let a = 0.5 * (p.x * q.y - p.y * q.x);
        area += a;
        integral += a * (values[i] + values[j] + gc) / 3.0;
    }
    (area, integral)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_function_is_integrated_exactly() {
        // pentagon, g = 1 + 2x - 3y: integral = area · g(area centroid)
        let poly = [
            Point2::new(0.0, 0.0),
            Point2::new(2.0, 0.0),
            Point2::new(2.5, 1.0),
            Point2::new(1.0, 2.0),
            Point2::new(-0.5, 1.0),
        ];
        let g = |p: &Point2| 1.0 + 2.0 * p.x - 3.0 * p.y;
        let values: Vec<Real> = poly.iter().map(g).collect();
        let (area, integral) = central_integral(&poly, &values);
        // reference: fan triangulation from point 0 with exact triangle centroids
        let (mut a_ref, mut i_ref) = (0.0, 0.0);
        for k in 1..4 {
            let (p, q) = (poly[k] - poly[0], poly[k + 1] - poly[0]);
            let a = 0.5 * (p.x * q.y - p.y * q.x);
            let centroid = (poly[0] + poly[k] + poly[k + 1]) / 3.0;
            a_ref += a;
            i_ref += a * g(&centroid);
        }
        assert!((area - a_ref).abs() < 1e-14);
        assert!((integral - i_ref).abs() < 1e-14 * i_ref.abs());
        assert_eq!(central_integral(&poly[..2], &values[..2]), (0.0, 0.0));
    }
}
