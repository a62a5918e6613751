//! Interpolation at the projection of a face centre by normalised
//! barycentric coordinates on the centre triangulation of the opposite face
//! (thesis §4.4, eqs. 4.26–4.27, Fig. 4.22).
use crate::sutherland_hodgman::Point2;
use fv_mesh::{Real, Surface, Vector};

/// Where a point falls in the centre triangulation of a face: triangle
/// (centre, point `i`, point `j`) with barycentric coordinates `zeta`
/// (same order). `i`, `j` are positions in the face's point list.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Located {
    /// Face (in the surface it was located on).
    pub face: u32,
    /// First point of the triangle side (position in the face's point list).
    pub i: u32,
    /// Second point of the triangle side.
    pub j: u32,
    /// Barycentric coordinates (centre, i, j); sum 1 (eq. 4.27).
    pub zeta: [Real; 3],
}

impl Located {
    /// The smallest coordinate: ≥ 0 inside the triangle, negative outside
    /// (distance-like measure of how far outside).
    pub fn min_zeta(&self) -> Real {
        self.zeta[0].min(self.zeta[1]).min(self.zeta[2])
    }

    /// Interpolates the point values `values` (indexed by local surface
    /// point) at the located point (eq. 4.26); the centre value is the mean
    /// of the face's point values. Outside the triangle the negative
    /// coordinates are clamped to zero and the rest renormalised (the
    /// closest-to-inside value).
    pub fn interpolate(&self, surface: &Surface, values: &[Vector]) -> Vector {
        let fp = surface.face(self.face as usize);
        let centre = fp
            .iter()
            .fold(Vector::zeros(), |a, &p| a + values[p as usize])
            / fp.len().max(1) as Real;
        let z = self.zeta.map(|z| z.max(0.0));
        let sum = z[0] + z[1] + z[2];
        if !(sum > 0.0) {
            return centre;
        }
        (centre * z[0]
            + values[fp[self.i as usize] as usize] * z[1]
            + values[fp[self.j as usize] as usize] * z[2])
            / sum
    }
}

/// Barycentric coordinates of `x` in triangle `(a, b, c)`; `None` if the
/// triangle is degenerate.
pub fn barycentric(x: &Point2, a: &Point2, b: &Point2, c: &Point2) -> Option<[Real; 3]> {
    let (v0, v1, v2) = (b - a, c - a, x - a);
    let det = v0.x * v1.y - v0.y * v1.x;
    let scale = v0.norm_squared().max(v1.norm_squared());
    if !(det.abs() > 1e-14 * scale) {
        return None;
    }
    let l1 = (v2.x * v1.y - v2.y * v1.x) / det;
    let l2 = (v0.x * v2.y - v0.y * v2.x) / det;
    Some([1.0 - l1 - l2, l1, l2])
}

/// Locates `x` in the centre triangulation of polygon `poly`, the projected
/// points of face `face` in their face order (any orientation): the
/// triangle with the largest smallest coordinate (the containing triangle
/// if there is one). `None` if every triangle is degenerate.
pub fn locate_in_polygon(face: u32, poly: &[Point2], x: &Point2) -> Option<Located> {
    let n = poly.len();
    if n < 3 {
        return None;
    }
    let c = poly.iter().fold(Point2::zeros(), |a, p| a + p) / n as Real;
    let mut best: Option<Located> = None;
    for i in 0..n {
        let j = if i + 1 == n { 0 } else { i + 1 };
        if let Some(zeta) = barycentric(x, &c, &poly[i], &poly[j]) {
            let cand = Located {
                face,
                i: i as u32,
                j: j as u32,
                zeta,
            };
            if best.is_none_or(|b| cand.min_zeta() > b.min_zeta()) {
                best = Some(cand);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_and_location() {
        let (a, b, c) = (
            Point2::new(0.0, 0.0),
            Point2::new(2.0, 0.0),
            Point2::new(0.0, 1.0),
        );
        let z = barycentric(&Point2::new(0.5, 0.25), &a, &b, &c).unwrap();
        assert!(
            (z[0] - 0.5).abs() < 1e-15
                && (z[1] - 0.25).abs() < 1e-15
                && (z[2] - 0.25).abs() < 1e-15
        );
        assert!(barycentric(&a, &a, &b, &(b * 2.0)).is_none());
        // unit square, clockwise order, point near a corner
        let sq = [
            Point2::new(0.0, 0.0),
            Point2::new(0.0, 1.0),
            Point2::new(1.0, 1.0),
            Point2::new(1.0, 0.0),
        ];
        let l = locate_in_polygon(3, &sq, &Point2::new(0.9, 0.5)).unwrap();
        assert_eq!((l.face, l.i, l.j), (3, 2, 3));
        assert!(l.min_zeta() >= 0.0);
        let out = locate_in_polygon(3, &sq, &Point2::new(1.5, 0.5)).unwrap();
        assert!(out.min_zeta() < 0.0);
        assert!(locate_in_polygon(0, &sq[..2], &a).is_none());
    }
}
