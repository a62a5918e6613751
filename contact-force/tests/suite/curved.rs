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

/// The arc as the master, smoothed (thesis §4.6.1): the gap of a block
/// point (x, y0) is its distance to the circle, √(x² + y0²) − r, along the
/// radial normal, so the force on the block is
/// `ε L_z ∫ ⟨−g⟩ (−y0/√(x² + y0²)) dx` (midpoint rule on a fine grid).
/// Smoothing removes most of the faceting error of the flat master.
#[test]
fn smoothed_arc_master_against_the_exact_circle() {
    let (r, half, nt, lz, delta) = (1.0, 0.3, 24, 0.1, 2e-3);
    let ann = annulus_mesh(
        0.5,
        r,
        -FRAC_PI_2 - half,
        -FRAC_PI_2 + half,
        0.0,
        lz,
        [1, nt, 1],
        1.0,
    )
    .unwrap();
    let cyl = Surface::new(&ann, ann.patch_index("outer").unwrap()).unwrap();
    let y0 = -r + delta;
    let blk = box_mesh(
        Vector::new(-0.5, -2.0, -0.05),
        Vector::new(0.5, y0, 0.15),
        [37, 1, 2],
        [1.0; 3],
    )
    .unwrap();
    let flat = Surface::new(&blk, blk.patch_index("ymax").unwrap()).unwrap();
    let law = ContactLaw::new(EPS, 0.0, 0.0, SlipHistory::Incremental).unwrap();
    let n = 200_000;
    let dx = 0.4 / n as Real;
    let exact: Real = (0..n)
        .map(|i| {
            let x = -0.2 + (i as Real + 0.5) * dx;
            let d = (x * x + y0 * y0).sqrt();
            EPS * lz * (r - d).max(0.0) * (-y0 / d) * dx
        })
        .sum();
    let pairs = swap_pairs(&all_pairs(flat.n_faces(), cyl.n_faces()), cyl.n_faces());
    let mut rel = Vec::new();
    for (name, mut alg) in [
        (
            "segment-to-segment",
            Box::new(SegmentToSegment::new()) as Box<dyn ContactAlgorithm>,
        ),
        (
            "segment-to-segment-nagata",
            Box::new(SegmentToSegment::nagata()),
        ),
        ("pointwise", Box::new(Pointwise::new())),
        ("pointwise-nagata", Box::new(Pointwise::nagata())),
    ] {
        let mut out = ContactTractions::new();
        let st = alg.compute(&cyl, &flat, &pairs, &law, &mut out).unwrap();
        assert_eq!(alg.kind().name(), name);
        // the block lies below the arc: pushed down
        let e = (-st.slave_force.y - exact) / exact;
        println!(
            "smoothed arc: {name}: F = {:.6} vs {exact:.6} ({e:+.2e})",
            -st.slave_force.y
        );
        if name.starts_with("segment") {
            assert!((st.master_force + st.slave_force).norm() <= 1e-12 * exact);
        }
        rel.push(e.abs());
    }
    // segment-to-segment: 3.8e-2 flat (the facets' sagitta against the
    // 2e-3 penetration), 7e-4 smoothed (what remains: the linear gap on the
    // sub-triangles at the contact edges)
    assert!(rel[0] > 0.03 && rel[1] < 1.5e-3, "{rel:?}");
    // pointwise: 5.8e-2 flat, 1.0e-2 smoothed (the face average of the
    // point gaps misjudges the partly touching faces at the contact edges)
    assert!(rel[2] > 0.04 && rel[3] < 0.02, "{rel:?}");
}

/// A rigid master that only translates is smoothed once; one that rotates
/// is refreshed in place.
#[test]
fn translated_master_is_smoothed_once() {
    let ann = annulus_mesh(0.5, 1.0, -1.9, -1.2, 0.0, 0.1, [1, 12, 1], 1.0).unwrap();
    let mut cyl = Surface::new(&ann, ann.patch_index("outer").unwrap()).unwrap();
    let blk = box_mesh(
        Vector::new(-0.5, -2.0, 0.0),
        Vector::new(0.5, -0.999, 0.1),
        [10, 1, 1],
        [1.0; 3],
    )
    .unwrap();
    let flat = Surface::new(&blk, blk.patch_index("ymax").unwrap()).unwrap();
    let law = ContactLaw::new(EPS, 0.0, 0.0, SlipHistory::Incremental).unwrap();
    let pairs = swap_pairs(&all_pairs(flat.n_faces(), cyl.n_faces()), cyl.n_faces());
    let mut s2s = SegmentToSegment::nagata();
    let mut pw = Pointwise::nagata();
    let x0 = cyl.points.clone();
    let mut forces = Vec::new();
    for step in 0..4 {
        let d = Vector::new(0.01 * step as Real, -2e-4 * step as Real, 0.0);
        let moved: Vec<Vector> = x0.iter().map(|x| x + d).collect();
        cyl.update_points(&moved);
        let mut out = ContactTractions::new();
        forces.push(
            s2s.compute(&cyl, &flat, &pairs, &law, &mut out)
                .unwrap()
                .normal_force,
        );
        pw.compute(&cyl, &flat, &pairs, &law, &mut out).unwrap();
    }
    assert_eq!(
        (s2s.smoothing_refreshes(), pw.smoothing_refreshes()),
        (1, 1)
    );
    assert!(forces.windows(2).all(|w| w[1] > w[0]), "{forces:?}");
    let (c, s) = (0.01f64.cos(), 0.01f64.sin());
    let rotated: Vec<Vector> = x0
        .iter()
        .map(|p| Vector::new(c * p.x - s * p.y, s * p.x + c * p.y, p.z))
        .collect();
    cyl.update_points(&rotated);
    let mut out = ContactTractions::new();
    s2s.compute(&cyl, &flat, &pairs, &law, &mut out).unwrap();
    assert_eq!(s2s.smoothing_refreshes(), 2);
    assert_eq!(SegmentToSegment::new().smoothing_refreshes(), 0);
}
