//! Two flat parallel squares: uniform penetration, partial overlap,
//! conforming and non-conforming meshes, master/slave swap, pointwise vs
//! segment-to-segment, and the pairs of the detection crate.
use crate::common::{close, law, lower, upper};
use contact_detect::{BruteForce, CandidatePairs, DetectParams, Detector};
use contact_force::{
    all_pairs, swap_pairs, ContactAlgorithm, ContactAlgorithmKind, ContactStats, ContactTractions,
    FacePairs, Pointwise, SegmentToSegment,
};
use fv_mesh::{Real, Surface, Vector};

const EPS: Real = 1e6;
const DELTA: Real = 1e-3;

fn run(
    alg: &mut dyn ContactAlgorithm,
    m: &Surface,
    s: &Surface,
    pairs: &dyn FacePairs,
) -> (ContactTractions, ContactStats) {
    let mut out = ContactTractions::new();
    let stats = alg
        .compute(m, s, pairs, &law(EPS, 0.0, 0.0), &mut out)
        .unwrap();
    (out, stats)
}

/// Uniform pressure ε δ on every face of both sides, action = reaction.
fn check_uniform(
    m: &Surface,
    s: &Surface,
    out: &ContactTractions,
    stats: &ContactStats,
    area: Real,
) {
    let p = EPS * DELTA;
    for f in 0..m.n_faces() {
        assert!(
            close(out.master.pressure[f], p, 1e-12, 0.0),
            "master {f}: {}",
            out.master.pressure[f]
        );
        assert!((out.master.normal_traction[f] - Vector::new(0.0, 0.0, -p)).norm() <= 1e-12 * p);
        assert!(close(out.master.gap[f], -DELTA, 1e-12, 0.0));
        assert!(close(out.master.contact_fraction[f], 1.0, 1e-12, 0.0));
    }
    for f in 0..s.n_faces() {
        assert!(
            close(out.slave.pressure[f], p, 1e-12, 0.0),
            "slave {f}: {}",
            out.slave.pressure[f]
        );
        assert!((out.slave.normal_traction[f] - Vector::new(0.0, 0.0, p)).norm() <= 1e-12 * p);
        assert!(close(out.slave.gap[f], -DELTA, 1e-12, 0.0));
        assert!(close(out.slave.contact_fraction[f], 1.0, 1e-12, 0.0));
    }
    let f = p * area;
    assert!(close(stats.normal_force, f, 1e-12, 0.0));
    assert!((stats.master_force - Vector::new(0.0, 0.0, -f)).norm() <= 1e-12 * f);
    assert!(
        (stats.master_force + stats.slave_force).norm() <= 1e-12 * f,
        "action ≠ reaction"
    );
    assert!(close(out.master.total_force(m).z, -f, 1e-12, 0.0));
    assert!(close(stats.max_pressure, p, 1e-12, 0.0));
    assert!(close(stats.max_penetration, DELTA, 1e-12, 0.0));
}

#[test]
fn uniform_penetration_conforming_and_non_conforming() {
    for (nm, ns) in [
        ([4, 4], [4, 4]),
        ([4, 4], [7, 5]),
        ([7, 5], [4, 4]),
        ([1, 1], [3, 2]),
    ] {
        let m = lower(nm, [0.0, 1.0], [0.0, 1.0], 0.0);
        let s = upper(ns, [0.0, 1.0], [0.0, 1.0], -DELTA);
        let pairs = all_pairs(m.n_faces(), s.n_faces());
        let (out, stats) = run(&mut SegmentToSegment::new(), &m, &s, &pairs);
        check_uniform(&m, &s, &out, &stats, 1.0);
        assert!(
            close(stats.contact_area, 1.0, 1e-12, 0.0),
            "{}",
            stats.contact_area
        );
        assert_eq!(stats.n_active, m.n_faces());
        // GGI weights: every face fully covered (eq. 4.9)
        for f in 0..m.n_faces() {
            assert!(close(out.ggi.master_coverage(f), 1.0, 1e-12, 0.0));
        }
        for f in 0..s.n_faces() {
            assert!(close(out.ggi.slave_coverage(f), 1.0, 1e-12, 0.0));
        }
        // the pointwise algorithm: every slave point penetrates by δ
        let (out, stats) = run(&mut Pointwise::new(), &m, &s, &pairs);
        check_uniform(&m, &s, &out, &stats, 1.0);
        assert!(close(stats.contact_area, 1.0, 1e-12, 0.0));
    }
}

#[test]
fn pairs_from_the_detector_give_the_same_tractions() {
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let s = upper([7, 5], [0.0, 1.0], [0.0, 1.0], -DELTA);
    let mut pairs = CandidatePairs::new();
    let params = DetectParams {
        mean_cell_height: Some(0.25),
        ..Default::default()
    };
    BruteForce::new(params).detect(&m, &s, &mut pairs).unwrap();
    assert!(pairs.n_pairs() < 16 * 35);
    for kind in ContactAlgorithmKind::ALL {
        let mut alg = kind.build();
        let (a, sa) = run(alg.as_mut(), &m, &s, &pairs);
        let (b, sb) = run(alg.as_mut(), &m, &s, &all_pairs(16, 35));
        check_uniform(&m, &s, &a, &sa, 1.0);
        assert!((sa.master_force - sb.master_force).norm() <= 1e-12 * sa.normal_force);
        for f in 0..16 {
            assert!(close(
                a.master.pressure[f],
                b.master.pressure[f],
                1e-12,
                0.0
            ));
        }
    }
}

/// Part over the unit master square of a slave face of size `h` centred
/// at `c`, the slave shifted by `d` (> 0) in x and y: the faces sticking
/// out past x = 1 or y = 1 are partly covered.
fn covered_share(c: &Vector, (hx, hy): (Real, Real), (dx, dy): (Real, Real)) -> Real {
    let fx = if c.x > 1.0 - hx + dx {
        (1.0 - (c.x - 0.5 * hx)) / hx
    } else {
        1.0
    };
    let fy = if c.y > 1.0 - hy + dy {
        (1.0 - (c.y - 0.5 * hy)) / hy
    } else {
        1.0
    };
    fx * fy
}

#[test]
fn partial_overlap_gives_the_exact_overlap_area() {
    // slave shifted by half a slave face in x and a quarter of one in y
    let (hx, hy) = (1.0 / 7.0, 1.0 / 5.0);
    let (dx, dy) = (0.5 * hx, 0.25 * hy);
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let s = upper([7, 5], [dx, 1.0 + dx], [dy, 1.0 + dy], -DELTA);
    let pairs = all_pairs(16, 35);
    let (out, stats) = run(&mut SegmentToSegment::new(), &m, &s, &pairs);
    let overlap = (1.0 - dx) * (1.0 - dy);
    let p = EPS * DELTA;
    assert!(
        close(stats.contact_area, overlap, 1e-12, 0.0),
        "{} vs {overlap}",
        stats.contact_area
    );
    assert!(close(stats.normal_force, p * overlap, 1e-12, 0.0));
    assert!((stats.master_force + stats.slave_force).norm() <= 1e-12 * p);
    // master faces: pressure = ε δ × covered fraction
    for f in 0..16 {
        let c = m.face_centres[f];
        let fx = if c.x < 0.25 { (0.25 - dx) / 0.25 } else { 1.0 };
        let fy = if c.y < 0.25 { (0.25 - dy) / 0.25 } else { 1.0 };
        assert!(
            close(out.master.pressure[f], p * fx * fy, 1e-12, 0.0),
            "{f}"
        );
        assert!(close(out.master.contact_fraction[f], fx * fy, 1e-12, 0.0));
    }
    // slave faces sticking out past x = 1 or y = 1 are partly loaded
    for f in 0..35 {
        let share = covered_share(&s.face_centres[f], (hx, hy), (dx, dy));
        assert!(close(out.slave.pressure[f], p * share, 1e-12, 0.0), "{f}");
    }
    // master and slave swapped: the same total forces
    let swapped = swap_pairs(&pairs, 35);
    let (_, sw) = run(&mut SegmentToSegment::new(), &s, &m, &swapped);
    assert!((sw.master_force - stats.slave_force).norm() <= 1e-10 * stats.normal_force);
    assert!((sw.slave_force - stats.master_force).norm() <= 1e-10 * stats.normal_force);
    assert!(close(sw.contact_area, overlap, 1e-10, 0.0));
}

/// Pointwise: a slave that overhangs the master presses with the part of
/// each face over it (its GGI coverage), as segment-to-segment does.
/// Without the coverage (the thesis's eq. 4.11, beyond-border points
/// open) an overhang of 1.8 % of a face cost the edge faces half their
/// pressure.
#[test]
fn pointwise_overhanging_slave_presses_with_its_covered_part() {
    let (hx, hy) = (1.0 / 7.0, 1.0 / 5.0);
    let p = EPS * DELTA;
    for (kx, ky) in [(0.018, 0.018), (0.5, 0.25)] {
        let (dx, dy) = (kx * hx, ky * hy);
        let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
        let s = upper([7, 5], [dx, 1.0 + dx], [dy, 1.0 + dy], -DELTA);
        let pairs = all_pairs(16, 35);
        for mut alg in [Pointwise::new(), Pointwise::nagata()] {
            let (out, stats) = run(&mut alg, &m, &s, &pairs);
            let overlap = (1.0 - dx) * (1.0 - dy);
            assert!(
                close(stats.normal_force, p * overlap, 1e-12, 0.0),
                "overhang {kx}: {} vs {}",
                stats.normal_force,
                p * overlap
            );
            assert!(
                close(stats.contact_area, overlap, 1e-12, 0.0),
                "{}",
                stats.contact_area
            );
            for f in 0..35 {
                let share = covered_share(&s.face_centres[f], (hx, hy), (dx, dy));
                assert!(
                    close(out.slave.pressure[f], p * share, 1e-12, 0.0),
                    "overhang {kx}, face {f}: {} vs {}",
                    out.slave.pressure[f],
                    p * share
                );
            }
        }
    }
}

#[test]
fn swapping_master_and_slave_gives_the_same_forces() {
    for (nm, ns) in [([4, 4], [4, 4]), ([4, 4], [7, 5])] {
        let m = lower(nm, [0.0, 1.0], [0.0, 1.0], 0.0);
        let s = upper(ns, [0.3, 1.2], [-0.1, 0.7], -DELTA);
        let pairs = all_pairs(m.n_faces(), s.n_faces());
        let (_, a) = run(&mut SegmentToSegment::new(), &m, &s, &pairs);
        let (_, b) = run(
            &mut SegmentToSegment::new(),
            &s,
            &m,
            &swap_pairs(&pairs, s.n_faces()),
        );
        let overlap = 0.7 * 0.7;
        assert!(close(a.contact_area, overlap, 1e-12, 0.0));
        assert!((a.master_force - b.slave_force).norm() <= 1e-10 * a.normal_force);
        assert!((a.slave_force - b.master_force).norm() <= 1e-10 * a.normal_force);
    }
}

#[test]
fn separated_surfaces_carry_nothing_but_report_the_gap() {
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let s = upper([7, 5], [0.0, 1.0], [0.0, 1.0], 2e-3);
    let pairs = all_pairs(16, 35);
    for kind in ContactAlgorithmKind::ALL {
        let (out, stats) = run(kind.build().as_mut(), &m, &s, &pairs);
        assert_eq!(stats.normal_force, 0.0);
        assert_eq!(stats.contact_area, 0.0);
        assert_eq!(stats.n_active, 0);
        assert!(out.master.pressure.iter().all(|&p| p == 0.0));
        assert!(out.slave.pressure.iter().all(|&p| p == 0.0));
        for f in 0..16 {
            assert!(
                close(out.master.gap[f], 2e-3, 1e-12, 0.0),
                "{kind}: {}",
                out.master.gap[f]
            );
        }
        for f in 0..35 {
            assert!(close(out.slave.gap[f], 2e-3, 1e-12, 0.0));
        }
    }
}
