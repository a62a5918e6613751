//! A tilted slave surface over a flat master: the gap is linear, the
//! pressure ε_n ⟨−g⟩ is piecewise linear, and the segment-to-segment
//! algorithm integrates it exactly on every face of both sides (partial
//! contact included, step c*).
use crate::common::{close, deform, law, lower, upper, x_range};
use contact_force::{
    all_pairs, swap_pairs, ContactAlgorithm, ContactTractions, Pointwise, SegmentToSegment,
};
use fv_mesh::{Real, Vector};

const EPS: Real = 1e6;

/// ∫_{x0}^{x1} ⟨−(a + b x)⟩ dx and ∫ x ⟨−(a + b x)⟩ dx for b > 0.
fn integrals(a: Real, b: Real, x0: Real, x1: Real) -> (Real, Real) {
    let hi = x1.min(-a / b);
    if hi <= x0 {
        return (0.0, 0.0);
    }
    let i = -a * (hi - x0) - 0.5 * b * (hi * hi - x0 * x0);
    let j = -0.5 * a * (hi * hi - x0 * x0) - b * (hi.powi(3) - x0.powi(3)) / 3.0;
    (i, j)
}

#[test]
fn linear_gap_is_integrated_exactly_with_partial_contact() {
    // g(x) = a + b x along the master normal +z: contact for x < 0.4
    let (a, b) = (-2e-3, 5e-3);
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let mut s = upper([7, 5], [0.0, 1.0], [0.0, 1.0], 0.0);
    deform(&mut s, |x| Vector::new(0.0, 0.0, a + b * x.x));
    let pairs = all_pairs(16, 35);
    let mut out = ContactTractions::new();
    let stats = SegmentToSegment::new()
        .compute(&m, &s, &pairs, &law(EPS, 0.0, 0.0), &mut out)
        .unwrap();

    let (i_total, j_total) = integrals(a, b, 0.0, 1.0);
    let force = EPS * i_total;
    assert!(
        close(stats.normal_force, force, 1e-12, 0.0),
        "{} vs {force}",
        stats.normal_force
    );
    assert!((stats.master_force - Vector::new(0.0, 0.0, -force)).norm() <= 1e-12 * force);
    assert!((stats.master_force + stats.slave_force).norm() <= 1e-12 * force);
    assert!(close(stats.contact_area, 0.4, 1e-12, 0.0));
    assert!(close(stats.max_penetration, -a, 1e-12, 0.0));

    // every master face: force = ε ∫_face ⟨−g⟩ dA
    let mut lumped = 0.0;
    let mut correction = 0.0;
    for f in 0..16 {
        let (x0, x1, w) = x_range(&m, f);
        let (i, j) = integrals(a, b, x0, x1);
        let fz = out.master.normal_traction[f].z * m.face_mag[f];
        assert!(
            close(fz, -EPS * w * i, 1e-12, force),
            "master {f}: {fz} vs {}",
            -EPS * w * i
        );
        assert!(close(
            out.master.contact_fraction[f],
            ((x1.min(0.4) - x0) / (x1 - x0)).max(0.0),
            1e-12,
            1.0
        ));
        // moment about the y axis through the origin, face forces at the face centres
        let xc = m.face_centres[f].x;
        lumped += -xc * fz;
        correction += EPS * w * (j - xc * i);
    }
    // moment of the pressure = lumped moment + the analytic lumping terms
    let moment = EPS * j_total;
    assert!(
        close(lumped + correction, moment, 1e-12, 0.0),
        "{lumped} + {correction} vs {moment}"
    );
    println!("moment: continuous {moment}, face-centre lumped {lumped}");

    // every slave face (tilted): the reaction, along the master normal
    for f in 0..35 {
        let (x0, x1, w) = x_range(&s, f);
        let (i, _) = integrals(a, b, x0, x1);
        let force_f = out.slave.normal_traction[f] * s.face_mag[f];
        assert!(
            (force_f - Vector::new(0.0, 0.0, EPS * w * i)).norm() <= 1e-12 * force,
            "slave {f}"
        );
        let n = s.face_normals[f];
        assert!(close(
            out.slave.pressure[f],
            -out.slave.normal_traction[f].dot(&n),
            1e-15,
            1.0
        ));
    }

    // swapped: the gap is measured along the tilted normal and the force
    // follows it, so the forces agree in magnitude to O(b²) and in direction
    // to the tilt angle
    let (mut out2, pairs2) = (ContactTractions::new(), swap_pairs(&pairs, 35));
    let st2 = SegmentToSegment::new()
        .compute(&s, &m, &pairs2, &law(EPS, 0.0, 0.0), &mut out2)
        .unwrap();
    let rel = (st2.slave_force.z - stats.master_force.z).abs() / force;
    println!("swapped: relative difference of the normal force {rel:.3e}");
    assert!(rel < 2.0 * b * b, "swapped: relative difference {rel}");
    assert!((st2.master_force + st2.slave_force).norm() <= 1e-12 * force);
    let angle = st2.slave_force.normalize().cross(&Vector::z()).norm();
    assert!(close(angle, b, 1e-3, 0.0), "{angle}");
}

#[test]
fn fully_in_contact_tilt_pointwise_total_force_is_exact() {
    // g ∈ [−4e-3, −2e-3]: every point penetrates; the mean of the corner
    // pressures is the pressure at the face centre (eq. 4.11)
    let (a, b) = (-4e-3, 2e-3);
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let mut s = upper([7, 5], [0.0, 1.0], [0.0, 1.0], 0.0);
    deform(&mut s, |x| Vector::new(0.0, 0.0, a + b * x.x));
    let pairs = all_pairs(16, 35);
    let force = EPS * integrals(a, b, 0.0, 1.0).0;
    let mut out = ContactTractions::new();
    let sts = SegmentToSegment::new()
        .compute(&m, &s, &pairs, &law(EPS, 0.0, 0.0), &mut out)
        .unwrap();
    assert!(close(sts.normal_force, force, 1e-12, 0.0));
    assert!(close(sts.contact_area, 1.0, 1e-12, 0.0));
    let pw = Pointwise::new()
        .compute(&m, &s, &pairs, &law(EPS, 0.0, 0.0), &mut out)
        .unwrap();
    assert!(
        close(-pw.slave_force.z, -force, 1e-12, 0.0),
        "{} vs {force}",
        pw.slave_force.z
    );
    // the GGI transfer (eq. 4.5) uses areas projected on the master plane:
    // the master force is short by the factor cos θ = 1/√(1 + b²)
    let cos = 1.0 / (1.0 + b * b).sqrt();
    assert!(
        close(pw.master_force.z, -force * cos, 1e-12, 0.0),
        "{}",
        pw.master_force.z / force
    );
    for f in 0..35 {
        let (x0, x1, _) = x_range(&s, f);
        let g = a + b * 0.5 * (x0 + x1);
        assert!(close(out.slave.pressure[f], -EPS * g, 1e-12, 0.0));
    }
    assert!(close(pw.max_penetration, -a, 1e-12, 0.0));
}
