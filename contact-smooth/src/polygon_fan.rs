//! Centre point and normal for the fan decomposition of faces that are not
//! triangles or regular quadrilaterals (n-gons, degenerate quadrilaterals).
//!
//! The face is split into triangles `(x_c, xᵢ, xᵢ₊₁)`, each a triangular
//! Nagata patch; their outer sides are the face's own edge curves, so the
//! surface stays gap-free with the neighbours, and neighbouring fan
//! triangles share their spokes `x_c xᵢ`.
//!
//! The centre normal `n_c` is the mean of the vertex normals. The centre
//! `x_c = x̄ + t n_c` is lifted from the vertex average `x̄` so that every
//! spoke chord is orthogonal to the mean of its end normals,
//! `(x_c − xᵢ)·(nᵢ + n_c) = 0`, in the least-squares sense:
//!
//! ```text
//! t = −Σ ((x̄ − xᵢ)·mᵢ)(n_c·mᵢ) / Σ (n_c·mᵢ)²,   mᵢ = nᵢ + n_c
//! ```
//!
//! This is the condition under which eq. 4.77 has no singular part (a
//! chord of a sphere is orthogonal to the sum of its end normals), so it
//! puts `x_c` on a sphere exactly and on a smooth surface to `O(h⁴)`.
//!
//! Like the curvature parameter ([`crate::curvature_parameter`]), the lift
//! is switched off when every vertex normal is within
//! [`EdgeCurveParams::parallel_angle`] of `n_c`, and ramped in up to twice
//! that angle, so a flat polygon gives an exactly flat fan.
use crate::edge_curve::{parallel_ramp, EdgeCurveParams};
use crate::face_geometry::polygon_centre_area;
use fv_mesh::{Real, Vector};

/// `(x_c, n_c)` for the polygon `poly` with vertex normals `normals`;
/// `None` if the polygon is empty, refers to a point out of range of
/// `points` or `normals`, or has no normal (vertex normals and area vector
/// all vanish).
pub fn fan_centre(
    points: &[Vector],
    normals: &[Vector],
    poly: &[usize],
    params: &EdgeCurveParams,
) -> Option<(Vector, Vector)> {
    if poly.is_empty()
        || poly
            .iter()
            .any(|&p| p >= points.len() || p >= normals.len())
    {
        return None;
    }
    let k = poly.len() as Real;
    let mean = poly.iter().map(|&p| points[p]).sum::<Vector>() / k;
    let sum_n = poly.iter().map(|&p| normals[p]).sum::<Vector>();
    let nc = sum_n
        .try_normalize(1e-300)
        .or_else(|| polygon_centre_area(points, poly).1.try_normalize(1e-300))?;
    let (mut num, mut den) = (0.0, 0.0);
    let mut spread: Real = 0.0;
    for &p in poly {
        let n = normals[p];
        let m = n + nc;
        let a = nc.dot(&m);
        num += (mean - points[p]).dot(&m) * a;
        den += a * a;
        spread = spread.max(n.cross(&nc).norm().atan2(n.dot(&nc)));
    }
    let t = if den > 1e-300 { -num / den } else { 0.0 };
    let s = parallel_ramp(spread, params.parallel_angle);
    let xc = mean + nc * if t.is_finite() { s * t } else { 0.0 };
    Some((xc, nc))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_of_a_spherical_polygon_is_on_the_sphere() {
        let p = EdgeCurveParams::default();
        // irregular pentagon on the unit sphere around the pole
        let angles: [Real; 5] = [0.0, 1.1, 2.5, 3.6, 5.0];
        let pts: Vec<Vector> = angles
            .iter()
            .enumerate()
            .map(|(i, &a)| {
                let polar: Real = 0.3 + 0.02 * i as Real;
                Vector::new(polar.sin() * a.cos(), polar.sin() * a.sin(), polar.cos())
            })
            .collect();
        let poly = [0, 1, 2, 3, 4];
        let (xc, nc) = fan_centre(&pts, &pts, &poly, &p).unwrap();
        assert!((xc.norm() - 1.0).abs() < 1e-3, "{}", xc.norm());
        assert!((nc.norm() - 1.0).abs() < 1e-15);
        // regular: exact
        let reg: Vec<Vector> = (0..6)
            .map(|i| {
                let a = i as Real * std::f64::consts::PI / 3.0;
                Vector::new(0.4 * a.cos(), 0.4 * a.sin(), (1.0 - 0.16_f64).sqrt())
            })
            .collect();
        let (xc, _) = fan_centre(&reg, &reg, &[0, 1, 2, 3, 4, 5], &p).unwrap();
        assert!((xc - Vector::z()).norm() < 1e-15);
        assert!(fan_centre(&reg, &reg, &[], &p).is_none());
        let zero = vec![Vector::zeros(); 6];
        assert!(fan_centre(&zero, &zero, &[0, 1, 2], &p).is_none());
        // flat polygon with nearly parallel normals: not lifted
        let flat = [Vector::zeros(), Vector::x(), Vector::y()];
        let t = 0.05_f64.to_radians();
        let n = [Vector::z(), Vector::new(t.sin(), 0.0, t.cos()), Vector::z()];
        let (xc, _) = fan_centre(&flat, &n, &[0, 1, 2], &p).unwrap();
        assert_eq!(xc.z, 0.0);
    }
}
