//! Separating-axis test between an oriented box and the infinite prism of
//! another box: the front condition of the advancing front.
use crate::obb::Obb;
use fv_mesh::Real;

/// Relative margin that keeps [`obb_meets_prism`] a superset of
/// [`crate::obb_overlap`] under round-off.
const MARGIN: Real = 1e-9;

/// Whether box `b` meets the prism of box `a`: `a`'s rectangle (axes 0
/// and 1) extruded without limit along its third axis (the face normal),
/// widened by the absolute distance `slack`.
///
/// With one extent infinite, only the axes normal to the extrusion can
/// separate: the two rectangle axes of `a` and `n × b_k` for the three
/// axes of `b`. Whenever [`crate::obb_overlap`]`(a, b)` holds this holds
/// too (a relative margin of 10⁻⁹ absorbs round-off), so slave faces
/// meeting a master face's prism are a superset of those whose boxes
/// overlap it, and (with `slack` the local-phase tolerance) of those whose
/// projection touches the master polygon. The cheap first half of the
/// front condition of [`crate::AdvancingFront`].
pub fn obb_meets_prism(a: &Obb, b: &Obb, slack: Real) -> bool {
    let n = a.axes[2];
    let d = b.centre - a.centre;
    let rb = |w: &fv_mesh::Vector| {
        b.half[0] * b.axes[0].dot(w).abs()
            + b.half[1] * b.axes[1].dot(w).abs()
            + b.half[2] * b.axes[2].dot(w).abs()
    };
    for i in 0..2 {
        let w = a.axes[i];
        if d.dot(&w).abs() > (a.half[i] + rb(&w)) * (1.0 + MARGIN) + slack {
            return false;
        }
    }
    for k in 0..3 {
        let w = n.cross(&b.axes[k]);
        if w.norm_squared() < 1e-20 {
            continue;
        }
        let ra = a.half[0] * a.axes[0].dot(&w).abs() + a.half[1] * a.axes[1].dot(&w).abs();
        if d.dot(&w).abs() > (ra + rb(&w)) * (1.0 + MARGIN) + slack * w.norm() {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obb::plane_basis;
    use crate::obb_overlap;
    use fv_mesh::Vector;

    #[test]
    fn prism_is_a_superset_of_the_box_and_ignores_height() {
        let mut seed = 99u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64)
        };
        let mut extra = 0;
        for _ in 0..20000 {
            let mk = |rnd: &mut dyn FnMut() -> f64| {
                let n = Vector::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
                let (u, v) = plane_basis(&n);
                Obb {
                    centre: Vector::new(rnd(), rnd(), rnd()) * 2.0,
                    axes: [u, v, n],
                    half: [0.05 + rnd(), 0.05 + rnd(), 0.01 + 0.3 * rnd()],
                }
            };
            let a = mk(&mut rnd);
            let b = mk(&mut rnd);
            let p = obb_meets_prism(&a, &b, 0.0);
            if obb_overlap(&a, &b) {
                assert!(p);
            } else if p {
                extra += 1;
            }
            // moving b along a's normal does not change the answer
            let shifted = Obb {
                centre: b.centre + a.axes[2] * (10.0 * rnd() - 5.0),
                ..b
            };
            assert_eq!(obb_meets_prism(&a, &shifted, 0.0), p);
            // a tall version of a contains the answer
            let tall = Obb {
                half: [a.half[0], a.half[1], 1e3],
                ..a
            };
            assert_eq!(obb_overlap(&tall, &b), p);
        }
        assert!(extra > 0);
    }
}
