//! A bound of a face box (eq. 4.10) that needs neither the convex hull nor
//! the minimum-area rectangle.
use crate::aabb::Aabb;
use crate::face_boxes::face_data_valid;
use crate::obb::FaceBoxSize;
use fv_mesh::{Real, Surface};

/// An axis-aligned box that contains the OBB [`crate::face_obb`] builds for
/// face `f` of `s` with `size` (and so the AABB of that OBB); `None` when
/// the face fails the validity conditions of [`crate::FaceBoxes`] that do
/// not need its box (such a face is in no pair). Cost O(face points).
///
/// With c the face centre, n its normal, ρ the largest distance from c to
/// a face point and d the signed distances of the points from the plane
/// (c, n): the minimum-area rectangle is tight about the projected points,
/// which lie within ρ of c, so along each rectangle axis its centre is
/// within ρ − a of c for half side a ≤ ρ, and inflated by the factor
/// (1 + i) its sides reach at most ρ + i a ≤ (1 + i) ρ from c. The OBB
/// thus lies in the cylinder of axis n through c, radius √2 (1 + i) ρ,
/// spanning [min(d_min, 0) − e⁻, max(d_max, 0) + e⁺] along n, whose AABB
/// is returned: along axis k, `c_k + t n_k` over that span widened by the
/// radius times √(1 − n_k²). The bound does not depend on the rectangle's
/// axes, which can turn by 90° under a small motion of the points. It is
/// widened by a relative 10⁻⁹ of the radius plus 10⁻¹² of the largest
/// coordinate and extent, far above the round-off of either box.
pub fn face_box_bound(s: &Surface, f: usize, size: &FaceBoxSize, min_area: Real) -> Option<Aabb> {
    if !face_data_valid(s, f, min_area) {
        return None;
    }
    let c = s.face_centres[f];
    let n = s.face_normals[f];
    let (mut rho2, mut dmin, mut dmax) = (0.0f64, 0.0f64, 0.0f64);
    for &p in s.face(f) {
        let r = s.points[p as usize] - c;
        rho2 = rho2.max(r.norm_squared());
        let d = r.dot(&n);
        dmin = dmin.min(d);
        dmax = dmax.max(d);
    }
    let lo = dmin - size.extrude_in;
    let hi = dmax + size.extrude_out;
    let radius = std::f64::consts::SQRT_2 * (1.0 + size.inflation) * rho2.sqrt();
    let nn = n.norm_squared();
    let mut b = Aabb::empty();
    for k in 0..3 {
        let (a, z) = (n[k] * lo, n[k] * hi);
        let across = radius * (1.0 - n[k] * n[k] / nn).max(0.0).sqrt();
        let slack = 1e-9 * radius + 1e-12 * (c[k].abs() + lo.abs() + hi.abs() + radius);
        b.min[k] = c[k] + a.min(z) - across - slack;
        b.max[k] = c[k] + a.max(z) + across + slack;
    }
    Some(b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obb::{face_obb, ObbScratch};
    use fv_mesh::generators::box_mesh;
    use fv_mesh::Vector;

    /// The bound contains the AABB of the OBB of every face of a warped,
    /// sheared, rotated surface, and is not far larger.
    #[test]
    fn bound_contains_the_face_box() {
        let mesh = box_mesh(
            Vector::new(0.0, 0.0, -1.0),
            Vector::new(1.0, 1.0, 0.0),
            [7, 5, 1],
            [1.0; 3],
        )
        .unwrap();
        let mut s = Surface::new(&mesh, mesh.patch_index("zmax").unwrap()).unwrap();
        let (sn, cs) = 0.7f64.sin_cos();
        let pts: Vec<Vector> = s
            .points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let w = 0.03 * ((i * 7919 % 13) as f64 / 13.0 - 0.5);
                let q = Vector::new(p.x + 0.3 * p.y, p.y, 0.4 * p.x * p.x + w);
                Vector::new(cs * q.x - sn * q.z, q.y, sn * q.x + cs * q.z)
            })
            .collect();
        s.update_points(&pts);
        let size = FaceBoxSize {
            extrude_out: 0.05,
            extrude_in: 0.2,
            inflation: 0.05,
        };
        let mut scratch = ObbScratch::default();
        for f in 0..s.n_faces() {
            let pts = s.face(f).iter().map(|&p| s.points[p as usize]);
            let obb = face_obb(
                pts,
                &s.face_normals[f],
                &s.face_centres[f],
                &size,
                &mut scratch,
                None,
            )
            .unwrap()
            .aabb();
            let b = face_box_bound(&s, f, &size, 0.0).unwrap();
            assert!(b.contains_box(&obb), "face {f}: {b:?} ⊉ {obb:?}");
            let (wb, wo) = (b.max - b.min, obb.max - obb.min);
            assert!(
                wb.norm() < 2.5 * wo.norm(),
                "face {f}: {wb:?} against {wo:?}"
            );
        }
    }

    #[test]
    fn degenerate_face_has_no_bound() {
        let mesh = box_mesh(Vector::zeros(), Vector::repeat(1.0), [1, 1, 1], [1.0; 3]).unwrap();
        let mut s = Surface::new(&mesh, 0).unwrap();
        let size = FaceBoxSize {
            extrude_out: 0.25,
            extrude_in: 1.0,
            inflation: 0.05,
        };
        assert!(face_box_bound(&s, 0, &size, 0.0).is_some());
        let flat = vec![Vector::zeros(); s.n_points()];
        s.update_points(&flat);
        assert!(face_box_bound(&s, 0, &size, 1e-12).is_none());
    }
}
