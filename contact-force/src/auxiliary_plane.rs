//! The auxiliary plane of a master face and the ray-tracing gap (thesis
//! §4.4, eq. 4.14 and step a of Fig. 4.19).
use crate::sutherland_hodgman::{Affine2, Point2};
use fv_mesh::{Real, Surface, Vector};

/// Pairs whose unit normals satisfy `n_m · n_s > -MIN_FACING_COSINE` are
/// not in contact: the slave face does not face the master face (its back
/// side, or a face steeper than ≈ 87° to the master, where the ray-tracing
/// gap along `n_m` is ill-conditioned).
pub const MIN_FACING_COSINE: Real = 0.05;

/// Intersections smaller than `AREA_TOLERANCE ×` the master face area are
/// dropped (round-off slivers of touching faces).
pub const AREA_TOLERANCE: Real = 1e-12;

/// The plane through a face centre `r` with the face's unit normal `n`
/// (step a), with an orthonormal in-plane basis `e1, e2` such that
/// `(e1, e2, n)` is right-handed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AuxiliaryPlane {
    /// Plane origin (the face centre).
    pub origin: Vector,
    /// Unit normal.
    pub normal: Vector,
    /// First in-plane axis.
    pub e1: Vector,
    /// Second in-plane axis, `n × e1`.
    pub e2: Vector,
}

impl AuxiliaryPlane {
    /// The plane through `origin` with normal `normal` (normalised here);
    /// `None` if either is not finite or the normal vanishes.
    pub fn new(origin: Vector, normal: Vector) -> Option<Self> {
        let len = normal.norm();
        if !(len > 0.0) || !len.is_finite() || !origin.iter().all(|x| x.is_finite()) {
            return None;
        }
        let n = normal / len;
        // the coordinate axis least aligned with n
        let a = n.map(Real::abs);
        let axis = if a.x <= a.y && a.x <= a.z {
            Vector::x()
        } else if a.y <= a.z {
            Vector::y()
        } else {
            Vector::z()
        };
        let e1 = axis.cross(&n).normalize();
        let e2 = n.cross(&e1);
        Some(AuxiliaryPlane {
            origin,
            normal: n,
            e1,
            e2,
        })
    }

    /// The plane of face `f` of `surface` (centre, unit normal); `None` for
    /// a degenerate face (zero or non-finite area).
    pub fn of_face(surface: &Surface, f: usize) -> Option<Self> {
        let mag = surface.face_mag[f];
        if !(mag > 0.0) || !mag.is_finite() {
            return None;
        }
        Self::new(surface.face_centres[f], surface.face_normals[f])
    }

    /// In-plane coordinates of the orthogonal projection of `x` (step b).
    #[inline]
    pub fn project(&self, x: &Vector) -> Point2 {
        let d = x - self.origin;
        Point2::new(d.dot(&self.e1), d.dot(&self.e2))
    }

    /// The point of the plane with in-plane coordinates `p`.
    #[inline]
    pub fn lift(&self, p: &Point2) -> Vector {
        self.origin + self.e1 * p.x + self.e2 * p.y
    }

    /// The ray-tracing gap (eq. 4.14) from the point of this plane with
    /// coordinates `p` to the plane through `point` with unit normal
    /// `normal`, measured along this plane's normal: `g(p)` such that
    /// `lift(p) + g n` lies on the other plane. It is affine in `p`.
    ///
    /// `None` unless the other plane faces this one
    /// (`n · normal ≤ -`[`MIN_FACING_COSINE`]). Positive gap: the other
    /// plane lies on the side the normal points to (separation);
    /// negative: penetration.
    pub fn ray_gap(&self, point: &Vector, normal: &Vector) -> Option<Affine2> {
        let d = self.normal.dot(normal);
        if !(d <= -MIN_FACING_COSINE) {
            return None;
        }
        Some(Affine2 {
            c: (point - self.origin).dot(normal) / d,
            n: Point2::new(-self.e1.dot(normal) / d, -self.e2.dot(normal) / d),
        })
    }

    /// Projects the points of face `f` of `surface` into `out`, ordered
    /// counter-clockwise in this plane. Returns the signed area before any
    /// reordering (negative if the face was seen from its back).
    pub fn project_face(&self, surface: &Surface, f: usize, out: &mut Vec<Point2>) -> Real {
        out.clear();
        out.extend(
            surface
                .face(f)
                .iter()
                .map(|&p| self.project(&surface.points[p as usize])),
        );
        let a = crate::sutherland_hodgman::signed_area(out);
        if a < 0.0 {
            out.reverse();
        }
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_and_gap() {
        let n = Vector::new(0.3, -0.2, 0.9).normalize();
        let pl = AuxiliaryPlane::new(Vector::new(1.0, 2.0, 3.0), n * 2.0).unwrap();
        assert!((pl.e1.cross(&pl.e2) - pl.normal).norm() < 1e-15);
        assert!(pl.e1.dot(&pl.normal).abs() < 1e-15);
        let p = Point2::new(0.3, -0.7);
        assert!((pl.project(&pl.lift(&p)) - p).norm() < 1e-15);
        // a tilted plane facing this one
        let ns = (-n + Vector::new(0.1, 0.05, 0.0)).normalize();
        let xs = pl.origin + 0.2 * n + Vector::new(0.1, 0.0, 0.0);
        let g = pl.ray_gap(&xs, &ns).unwrap();
        for q in [Point2::zeros(), p, Point2::new(1.0, 2.0)] {
            let hit = pl.lift(&q) + pl.normal * g.value(&q);
            assert!((hit - xs).dot(&ns).abs() < 1e-14);
        }
        // facing away, or perpendicular: none
        assert!(pl.ray_gap(&xs, &n).is_none());
        assert!(pl.ray_gap(&xs, &pl.e1).is_none());
        assert!(AuxiliaryPlane::new(Vector::zeros(), Vector::zeros()).is_none());
        assert!(AuxiliaryPlane::new(Vector::new(Real::NAN, 0.0, 0.0), n).is_none());
    }
}
