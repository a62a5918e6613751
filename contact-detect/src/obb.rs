//! Oriented bounding box of a face (thesis §4.2.1, eq. 4.10, Fig. 4.10).
use crate::aabb::Aabb;
use crate::convex_hull_2d::{convex_hull, V2};
use crate::min_area_rectangle::min_area_rectangle;
use fv_mesh::{Real, Vector};

/// Oriented box: centre r_c, orientation R_a (three orthonormal axes) and
/// extent vector a (half side lengths) — the three parameters of §4.2.1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obb {
    /// Centre r_c.
    pub centre: Vector,
    /// Orthonormal, right-handed axes (rows of R_a); for a face box the
    /// third is the face normal.
    pub axes: [Vector; 3],
    /// Half side lengths along the axes.
    pub half: [Real; 3],
}

impl Obb {
    /// The smallest axis-aligned box containing this box.
    pub fn aabb(&self) -> Aabb {
        let mut r = Vector::zeros();
        for (a, &h) in self.axes.iter().zip(&self.half) {
            r += a.abs() * h;
        }
        Aabb {
            min: self.centre - r,
            max: self.centre + r,
        }
    }

    /// Whether point `p` lies in the box (with absolute tolerance `tol`).
    pub fn contains(&self, p: &Vector, tol: Real) -> bool {
        let d = p - self.centre;
        self.axes
            .iter()
            .zip(&self.half)
            .all(|(a, &h)| d.dot(a).abs() <= h + tol)
    }
}

/// Orthonormal basis `(e1, e2)` of the plane normal to the unit vector `n`,
/// with `e1 × e2 = n` (Duff et al. 2017, branch-free and continuous away
/// from `n.z = -1`).
#[inline]
pub fn plane_basis(n: &Vector) -> (Vector, Vector) {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vector::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vector::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// Writes a triangle or quadrilateral that is strictly convex in its given
/// order into `hull`, counter-clockwise (the convex hull without sorting);
/// `false` for anything else.
fn convex_in_order(p: &[V2], hull: &mut Vec<V2>) -> bool {
    let n = p.len();
    if !(3..=4).contains(&n) {
        return false;
    }
    let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    let mut sign = 0.0;
    for i in 0..n {
        let (a, b, c) = (p[i], p[next(i)], p[next(next(i))]);
        let e = b - a;
        let f = c - b;
        let cr = e.x * f.y - e.y * f.x;
        if !(cr.abs() > 0.0) || (sign != 0.0 && cr.signum() != sign) {
            return false;
        }
        sign = cr.signum();
    }
    hull.clear();
    if sign > 0.0 {
        hull.extend_from_slice(p);
    } else {
        hull.extend(p.iter().rev());
    }
    true
}

/// Scratch buffers of [`face_obb`], reused between faces.
#[derive(Debug, Default, Clone)]
pub struct ObbScratch {
    projected: Vec<V2>,
    sorted: Vec<V2>,
    hull: Vec<V2>,
}

/// Extrusions and inflation of a face box in absolute units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceBoxSize {
    /// e⁺: extrusion along the normal, out of the body (eq. 4.10: 0.25 h̄).
    pub extrude_out: Real,
    /// e⁻: extrusion against the normal, into the body (eq. 4.10: h̄).
    pub extrude_in: Real,
    /// Relative inflation of the in-plane rectangle (0.05).
    pub inflation: Real,
}

/// Builds the box of a face (Fig. 4.10) and, if asked, appends the face
/// polygon, in the box's in-plane coordinates relative to its centre, to
/// `polygon`.
///
/// Steps: project the points onto the plane through `centre` normal to
/// the unit `normal`; minimum-area enclosing rectangle of their convex hull
/// by rotating calipers; rectangle inflated by `size.inflation`; along the
/// normal the box spans `[min(d_min, 0) − e⁻, max(d_max, 0) + e⁺]`, where
/// `d` are the signed distances of the points from the plane (zero for a
/// planar face, eq. 4.10; a warped face keeps all its points inside).
/// Returns `None` if the points give no rectangle (no finite point).
pub fn face_obb(
    points: impl Iterator<Item = Vector> + Clone,
    normal: &Vector,
    centre: &Vector,
    size: &FaceBoxSize,
    scratch: &mut ObbScratch,
    polygon: Option<&mut Vec<V2>>,
) -> Option<Obb> {
    let (e1, e2) = plane_basis(normal);
    scratch.projected.clear();
    let (mut dmin, mut dmax) = (0.0f64, 0.0f64);
    for x in points.clone() {
        let r = x - centre;
        scratch.projected.push(V2::new(r.dot(&e1), r.dot(&e2)));
        let d = r.dot(normal);
        dmin = if d < dmin { d } else { dmin };
        dmax = if d > dmax { d } else { dmax };
    }
    if !convex_in_order(&scratch.projected, &mut scratch.hull) {
        convex_hull(&scratch.projected, &mut scratch.sorted, &mut scratch.hull);
    }
    let rect = min_area_rectangle(&scratch.hull)?;
    let u = e1 * rect.axis.x + e2 * rect.axis.y;
    let v = normal.cross(&u);
    let lo = dmin - size.extrude_in;
    let hi = dmax + size.extrude_out;
    let obb = Obb {
        centre: centre + e1 * rect.centre.x + e2 * rect.centre.y + normal * (0.5 * (lo + hi)),
        axes: [u, v, *normal],
        half: [
            rect.half.x * (1.0 + size.inflation),
            rect.half.y * (1.0 + size.inflation),
            0.5 * (hi - lo),
        ],
    };
    if let Some(polygon) = polygon {
        polygon.extend(points.map(|x| {
            let r = x - obb.centre;
            V2::new(r.dot(&u), r.dot(&v))
        }));
    }
    let ok = obb.centre.iter().all(|c| c.is_finite()) && obb.half.iter().all(|h| h.is_finite());
    ok.then_some(obb)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal_and_right_handed() {
        for n in [
            Vector::z(),
            -Vector::z(),
            Vector::x(),
            Vector::new(0.3, -0.4, 0.5).normalize(),
            Vector::new(1e-9, 0.0, -1.0).normalize(),
        ] {
            let (a, b) = plane_basis(&n);
            assert!((a.norm() - 1.0).abs() < 1e-12 && (b.norm() - 1.0).abs() < 1e-12);
            assert!(a.dot(&b).abs() < 1e-12 && a.dot(&n).abs() < 1e-12);
            assert!((a.cross(&b) - n).norm() < 1e-12);
        }
    }

    #[test]
    fn unit_square_box() {
        let pts = [
            Vector::new(0.0, 0.0, 0.0),
            Vector::new(1.0, 0.0, 0.0),
            Vector::new(1.0, 1.0, 0.0),
            Vector::new(0.0, 1.0, 0.0),
        ];
        let size = FaceBoxSize {
            extrude_out: 0.25,
            extrude_in: 1.0,
            inflation: 0.05,
        };
        let mut poly = Vec::new();
        let b = face_obb(
            pts.iter().copied(),
            &Vector::z(),
            &Vector::new(0.5, 0.5, 0.0),
            &size,
            &mut ObbScratch::default(),
            Some(&mut poly),
        )
        .unwrap();
        assert!((b.half[0] - 0.525).abs() < 1e-12 && (b.half[1] - 0.525).abs() < 1e-12);
        assert!((b.half[2] - 0.625).abs() < 1e-12);
        assert!((b.centre - Vector::new(0.5, 0.5, -0.375)).norm() < 1e-12);
        for p in &pts {
            assert!(b.contains(p, 0.0));
        }
        assert!(b.contains(&Vector::new(0.5, 0.5, 0.25), 1e-12));
        assert!(!b.contains(&Vector::new(0.5, 0.5, 0.26), 0.0));
        assert!(b.contains(&Vector::new(0.5, 0.5, -1.0), 1e-12));
        assert!(!b.contains(&Vector::new(0.5, 0.5, -1.01), 0.0));
        let a = b.aabb();
        assert!((a.min - Vector::new(-0.025, -0.025, -1.0)).norm() < 1e-12);
        assert!((a.max - Vector::new(1.025, 1.025, 0.25)).norm() < 1e-12);
        assert_eq!(poly.len(), 4);
        for p in &poly {
            assert!((p.x.abs() - 0.5).abs() < 1e-12 && (p.y.abs() - 0.5).abs() < 1e-12);
        }
    }

    #[test]
    fn warped_face_points_stay_inside() {
        let pts = [
            Vector::new(0.0, 0.0, 0.1),
            Vector::new(1.0, 0.0, -0.1),
            Vector::new(1.0, 1.0, 0.1),
            Vector::new(0.0, 1.0, -0.1),
        ];
        let size = FaceBoxSize {
            extrude_out: 0.0,
            extrude_in: 0.0,
            inflation: 0.0,
        };
        let mut poly = Vec::new();
        let b = face_obb(
            pts.iter().copied(),
            &Vector::z(),
            &Vector::new(0.5, 0.5, 0.0),
            &size,
            &mut ObbScratch::default(),
            Some(&mut poly),
        )
        .unwrap();
        for p in &pts {
            assert!(b.contains(p, 1e-12));
        }
        assert!((b.half[2] - 0.1).abs() < 1e-12);
    }
}
