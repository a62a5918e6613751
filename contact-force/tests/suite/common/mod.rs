//! Shared set-up: flat contact patches cut from `box_mesh` blocks.
#![allow(dead_code)]
use contact_force::{ContactLaw, SlipHistory};
use fv_mesh::generators::box_mesh;
use fv_mesh::{Real, Surface, Vector};

/// The `zmax` patch (normal +z) of the block `[x0,x1]×[y0,y1]×[z−1, z]`
/// with `n` faces: the lower body's contact surface.
pub fn lower(n: [usize; 2], x: [Real; 2], y: [Real; 2], z: Real) -> Surface {
    let m = box_mesh(
        Vector::new(x[0], y[0], z - 1.0),
        Vector::new(x[1], y[1], z),
        [n[0], n[1], 1],
        [1.0; 3],
    )
    .unwrap();
    Surface::new(&m, m.patch_index("zmax").unwrap()).unwrap()
}

/// The `zmin` patch (normal −z) of the block `[x0,x1]×[y0,y1]×[z, z+1]`:
/// the upper body's contact surface.
pub fn upper(n: [usize; 2], x: [Real; 2], y: [Real; 2], z: Real) -> Surface {
    let m = box_mesh(
        Vector::new(x[0], y[0], z),
        Vector::new(x[1], y[1], z + 1.0),
        [n[0], n[1], 1],
        [1.0; 3],
    )
    .unwrap();
    Surface::new(&m, m.patch_index("zmin").unwrap()).unwrap()
}

/// Moves every point of `s` by `f(x)`.
pub fn deform(s: &mut Surface, f: impl Fn(&Vector) -> Vector) {
    let moved: Vec<Vector> = s.points.iter().map(|x| x + f(x)).collect();
    s.update_points(&moved);
}

/// A law with the given penalties and friction, incremental slip.
pub fn law(eps_n: Real, eps_t: Real, mu: Real) -> ContactLaw {
    ContactLaw::new(eps_n, eps_t, mu, SlipHistory::Incremental).unwrap()
}

/// |a − b| ≤ tol · max(|b|, floor).
pub fn close(a: Real, b: Real, tol: Real, floor: Real) -> bool {
    (a - b).abs() <= tol * b.abs().max(floor)
}

/// Corners of the x-range of face `f` (axis-aligned rectangular faces).
pub fn x_range(s: &Surface, f: usize) -> (Real, Real, Real) {
    let xs: Vec<Real> = s.face(f).iter().map(|&p| s.points[p as usize].x).collect();
    let ys: Vec<Real> = s.face(f).iter().map(|&p| s.points[p as usize].y).collect();
    let fold = |v: &[Real], max: bool| {
        v.iter().copied().fold(
            if max {
                Real::NEG_INFINITY
            } else {
                Real::INFINITY
            },
            |a, b| if max { a.max(b) } else { a.min(b) },
        )
    };
    (
        fold(&xs, false),
        fold(&xs, true),
        fold(&ys, true) - fold(&ys, false),
    )
}
