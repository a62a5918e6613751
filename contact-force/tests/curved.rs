//! A polygonal cylinder (the outer patch of an annular sector) pressed into
//! a flat block: the gap is piecewise linear, so segment-to-segment
//! integrates the penalty pressure of the faceted geometry exactly.
use contact_force::{
    all_pairs, swap_pairs, ContactAlgorithm, ContactLaw, ContactTractions, Pointwise,
    SegmentToSegment, SlipHistory,
};
use fv_mesh::generators::{annulus_mesh, box_mesh};
use fv_mesh::{Real, Surface, Vector};
use std::f64::consts::FRAC_PI_2;

const EPS: Real = 1e6;

/// ∫_l^h ⟨−(a + b x)⟩ dx.
fn integral(a: Real, b: Real, l: Real, h: Real) -> Real {
    let (lo, hi) = if b == 0.0 {
        if a < 0.0 {
            (l, h)
        } else {
            return 0.0;
        }
    } else if b > 0.0 {
        (l, h.min(-a / b))
    } else {
        (l.max(-a / b), h)
    };
    if hi <= lo {
        return 0.0;
    }
    -a * (hi - lo) - 0.5 * b * (hi * hi - lo * lo)
}

#[test]
fn faceted_cylinder_on_a_block() {
    let (r, half, nt, lz, delta) = (1.0, 0.3, 24, 0.1, 2e-3);
    let ann = annulus_mesh(
        0.5,
        r,
        -FRAC_PI_2 - half,
        -FRAC_PI_2 + half,
        0.0,
        lz,
        [3, nt, 1],
        1.0,
    )
    .unwrap();
    let cyl = Surface::new(&ann, ann.patch_index("outer").unwrap()).unwrap();
    let y0 = -r + delta;
    let blk = box_mesh(
        Vector::new(-0.5, -2.0, -0.05),
        Vector::new(0.5, y0, 0.15),
        [13, 1, 2],
        [1.0; 3],
    )
    .unwrap();
    let flat = Surface::new(&blk, blk.patch_index("ymax").unwrap()).unwrap();
    let law = ContactLaw::new(EPS, 0.0, 0.0, SlipHistory::Incremental).unwrap();

    // reference: every chord of the polygonal arc against the plane y = y0
    let dt = 2.0 * half / nt as Real;
    let mut force = 0.0;
    for i in 0..nt {
        let (t1, t2) = (
            -FRAC_PI_2 - half + i as Real * dt,
            -FRAC_PI_2 - half + (i + 1) as Real * dt,
        );
        let (x1, y1, x2, y2) = (r * t1.cos(), r * t1.sin(), r * t2.cos(), r * t2.sin());
        let b = (y2 - y1) / (x2 - x1);
        force += EPS * lz * integral(y1 - b * x1 - y0, b, x1.min(x2), x1.max(x2));
    }

    let pairs = all_pairs(flat.n_faces(), cyl.n_faces());
    let mut out = ContactTractions::new();
    let st = SegmentToSegment::new()
        .compute(&flat, &cyl, &pairs, &law, &mut out)
        .unwrap();
    assert!(
        (st.master_force - Vector::new(0.0, -force, 0.0)).norm() <= 1e-12 * force,
        "{:?} vs {force}",
        st.master_force
    );
    assert!((st.master_force + st.slave_force).norm() <= 1e-12 * force);
    assert!((st.max_penetration - delta).abs() <= 1e-12);
    // the arc as master: the gap follows each facet's normal; close, not exact
    let mut out2 = ContactTractions::new();
    let sw = SegmentToSegment::new()
        .compute(
            &cyl,
            &flat,
            &swap_pairs(&pairs, cyl.n_faces()),
            &law,
            &mut out2,
        )
        .unwrap();
    let rel = (sw.slave_force.y + force).abs() / force;
    println!(
        "faceted cylinder: F = {force:.6}; swapped {:.6} (rel. {rel:.2e})",
        -sw.slave_force.y
    );
    assert!(rel < 0.02, "{rel}");
    assert!((sw.master_force + sw.slave_force).norm() <= 1e-12 * force);
    // pointwise: pressure from the corner gaps only, partial contact misjudged
    let pw = Pointwise::new()
        .compute(&flat, &cyl, &pairs, &law, &mut out2)
        .unwrap();
    let rel = (pw.slave_force.y - force).abs() / force;
    println!(
        "faceted cylinder: pointwise {:.6} (rel. {rel:.2e})",
        pw.slave_force.y
    );
    assert!(rel < 0.2, "{rel}");
}
