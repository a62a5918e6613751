//! Deterministic scenarios: all detectors agree, and the pair definition
//! behaves as documented on simple geometries.
use crate::common::{Patch, Placement};
use contact_detect::{
    AdvancingFront, BruteForce, BvhDetector, CandidatePairs, DetectError, DetectParams,
    DetectionMethod, Detector,
};
use fv_mesh::{Surface, Vector};

fn params(h: f64) -> DetectParams {
    DetectParams {
        mean_cell_height: Some(h),
        ..Default::default()
    }
}

/// Runs all three detectors (advancing front cold) and checks they agree.
fn all_agree(master: &Surface, slave: &Surface, p: DetectParams) -> CandidatePairs {
    let mut reference = CandidatePairs::new();
    BruteForce::new(p)
        .detect(master, slave, &mut reference)
        .unwrap();
    for m in [DetectionMethod::Bvh, DetectionMethod::AdvancingFront] {
        let mut d = m.detector(p).unwrap();
        let mut out = CandidatePairs::new();
        d.detect(master, slave, &mut out).unwrap();
        assert_eq!(out, reference, "{m} differs from brute force");
    }
    reference
}

#[test]
fn conformal_touching_grids_pair_the_3x3_neighbourhood() {
    let master = Patch::new([4, 4], false, true, &Placement::default());
    let slave = Patch::new([4, 4], false, false, &Placement::default());
    let pairs = all_agree(&master.surface, &slave.surface, params(0.25));
    assert_eq!(pairs.n_master(), 16);
    // corners 4, edges 6, interior 9 (touching neighbours count)
    assert_eq!(pairs.n_pairs(), 4 * 4 + 8 * 6 + 4 * 9);
    for m in 0..16 {
        let c = master.surface.face_centres[m];
        for &s in pairs.slaves_of(m) {
            let d = slave.surface.face_centres[s as usize] - c;
            assert!(d.x.abs() < 0.26 && d.y.abs() < 0.26);
        }
    }
}

#[test]
fn separation_limit_follows_the_extrusions() {
    // master box z ∈ [-h, h/4], slave box z ∈ [g - h/4, g + h]: overlap iff -2h ≤ g ≤ h/2
    let h = 0.25;
    let count = |g: f64| {
        let master = Patch::new([3, 3], false, true, &Placement::default());
        let slave = Patch::new(
            [3, 3],
            false,
            false,
            &Placement {
                shift: Vector::new(0.0, 0.0, g),
                ..Default::default()
            },
        );
        all_agree(&master.surface, &slave.surface, params(h)).n_pairs()
    };
    assert!(count(0.124) > 0);
    assert_eq!(count(0.126), 0);
    assert!(count(-0.49) > 0);
    assert_eq!(count(-0.51), 0);
    assert_eq!(count(5.0), 0);
}

#[test]
fn rotated_curved_and_triangulated_surfaces_agree() {
    let master = Patch::new(
        [7, 5],
        false,
        true,
        &Placement {
            jitter: 0.12,
            jitter_z: 0.005,
            seed: 3,
            ..Default::default()
        },
    );
    let slave = Patch::new(
        [6, 8],
        true,
        false,
        &Placement {
            rotate: 0.4,
            tilt: 0.05,
            curvature: 0.6,
            shift: Vector::new(0.2, -0.1, -0.02),
            jitter: 0.1,
            jitter_z: 0.01,
            seed: 9,
        },
    );
    let pairs = all_agree(&master.surface, &slave.surface, DetectParams::default());
    assert!(pairs.n_pairs() > 20);
    // swapping the roles is another valid problem
    all_agree(&slave.surface, &master.surface, DetectParams::default());
}

#[test]
fn advancing_front_is_warm_after_a_small_motion() {
    let master = Patch::new([12, 12], false, true, &Placement::default());
    let mut slave = Patch::new(
        [10, 10],
        false,
        false,
        &Placement {
            rotate: 0.2,
            ..Default::default()
        },
    );
    let p = DetectParams::default();
    let mut af = AdvancingFront::new(p);
    let mut bf = BruteForce::new(p);
    let (mut a, mut b) = (CandidatePairs::new(), CandidatePairs::new());
    let cold = af.detect(&master.surface, &slave.surface, &mut a).unwrap();
    assert_eq!(cold.seed_searches, 1);
    assert!(af.has_seeds());
    slave.place(&Placement {
        rotate: 0.2,
        shift: Vector::new(0.01, 0.02, -0.005),
        ..Default::default()
    });
    let warm = af.detect(&master.surface, &slave.surface, &mut a).unwrap();
    let brute = bf.detect(&master.surface, &slave.surface, &mut b).unwrap();
    assert_eq!(a, b);
    // the corners of the master are not covered by the rotated slave
    assert!(
        warm.seed_searches <= cold.master_faces_in_zone / 10,
        "{warm:?}"
    );
    assert!(
        warm.aabb_tests * 5 < brute.aabb_tests,
        "{warm:?} vs {brute:?}"
    );
    // reset forgets the seeds
    af.reset();
    assert!(!af.has_seeds());
    let again = af.detect(&master.surface, &slave.surface, &mut a).unwrap();
    assert_eq!(a, b);
    assert!(again.seed_searches >= 1);
}

#[test]
fn partial_overlap_uses_seed_searches_and_stays_exact() {
    let master = Patch::new([8, 8], true, true, &Placement::default());
    let mut slave = Patch::new(
        [5, 5],
        false,
        false,
        &Placement {
            shift: Vector::new(0.6, 0.3, 0.0),
            ..Default::default()
        },
    );
    let p = params(0.125);
    let mut af = AdvancingFront::new(p);
    let (mut a, mut b) = (CandidatePairs::new(), CandidatePairs::new());
    for step in 0..5 {
        slave.place(&Placement {
            shift: Vector::new(0.6 - 0.05 * step as f64, 0.3, 0.0),
            ..Default::default()
        });
        af.detect(&master.surface, &slave.surface, &mut a).unwrap();
        BvhDetector::new(p)
            .detect(&master.surface, &slave.surface, &mut b)
            .unwrap();
        assert_eq!(a, b, "step {step}");
        assert!(a.n_pairs() > 0);
    }
}

#[test]
fn freeze_returns_the_last_pairs() {
    let master = Patch::new([4, 4], false, true, &Placement::default());
    let mut slave = Patch::new([3, 3], false, false, &Placement::default());
    for m in DetectionMethod::ALL {
        let mut d = m.detector(DetectParams::default()).unwrap();
        slave.place(&Placement::default());
        let mut first = CandidatePairs::new();
        d.detect(&master.surface, &slave.surface, &mut first)
            .unwrap();
        assert!(first.n_pairs() > 0);
        d.set_frozen(true);
        assert!(d.is_frozen());
        slave.place(&Placement {
            shift: Vector::new(0.0, 0.0, 10.0),
            ..Default::default()
        });
        let mut out = CandidatePairs::new();
        let st = d.detect(&master.surface, &slave.surface, &mut out).unwrap();
        assert!(st.frozen && st.aabb_tests == 0);
        assert_eq!(out, first, "{m}");
        d.set_frozen(false);
        let st = d.detect(&master.surface, &slave.surface, &mut out).unwrap();
        assert!(!st.frozen);
        assert_eq!(out.n_pairs(), 0, "{m}");
        // frozen with a different slave surface: a new search
        d.set_frozen(true);
        let other = Patch::new([2, 2], false, false, &Placement::default());
        let st = d.detect(&master.surface, &other.surface, &mut out).unwrap();
        assert!(!st.frozen && out.n_pairs() > 0, "{m}");
    }
}

#[test]
fn degenerate_and_non_finite_faces_are_skipped() {
    let master = Patch::new([4, 4], true, true, &Placement::default());
    let mut slave = Patch::new([4, 4], true, false, &Placement::default());
    // collapse one interior edge: the two triangles sharing it lose their area
    let s = &slave.surface;
    let e = (0..s.n_edges()).find(|&e| !s.is_border_edge(e)).unwrap();
    let [a, b] = s.edges[e];
    let mut pts = s.points.clone();
    pts[b as usize] = pts[a as usize];
    slave.surface.update_points(&pts);
    let zero: Vec<usize> = (0..slave.surface.n_faces())
        .filter(|&f| slave.surface.face_mag[f] < 1e-14)
        .collect();
    assert_eq!(zero.len(), 2);
    let pairs = all_agree(&master.surface, &slave.surface, DetectParams::default());
    for (_, s) in pairs.iter() {
        assert!(!zero.contains(&(s as usize)));
    }
    let mut st = BruteForce::new(DetectParams::default());
    let stats = st
        .detect(&master.surface, &slave.surface, &mut CandidatePairs::new())
        .unwrap();
    assert_eq!(stats.skipped_faces, 2);

    // a NaN point: its faces are skipped, nothing panics
    let mut pts = slave.surface.points.clone();
    pts[3] = Vector::new(f64::NAN, 0.0, 0.0);
    slave.surface.update_points(&pts);
    let pairs = all_agree(&master.surface, &slave.surface, DetectParams::default());
    for (_, s) in pairs.iter() {
        assert!(!slave.surface.face(s as usize).contains(&3));
    }
    // every point NaN: no pair, no panic (h̄ cannot be estimated from the slave)
    let nan = vec![Vector::repeat(f64::NAN); slave.surface.n_points()];
    slave.surface.update_points(&nan);
    assert_eq!(
        all_agree(&master.surface, &slave.surface, DetectParams::default()).n_pairs(),
        0
    );
    assert_eq!(
        all_agree(&slave.surface, &slave.surface, DetectParams::default()).n_pairs(),
        0
    );
}

#[test]
fn inconsistent_surfaces_are_errors_and_empty_surfaces_give_no_pairs() {
    let master = Patch::new([3, 3], false, true, &Placement::default());
    let slave = Patch::new([3, 3], false, false, &Placement::default());
    let mut bad = slave.surface.clone();
    bad.face_normals.pop();
    let mut bad2 = slave.surface.clone();
    bad2.face_points[0] = 10_000;
    let mut bad3 = slave.surface.clone();
    bad3.face_offsets.pop();
    let mut bad4 = slave.surface.clone();
    bad4.point_faces[0] = 99;
    let mut bad5 = slave.surface.clone();
    bad5.point_face_offsets.truncate(3);
    let mut empty = slave.surface.clone();
    empty.faces.clear();
    empty.face_offsets = vec![0];
    empty.face_points.clear();
    empty.face_neighbour_offsets = vec![0];
    empty.face_neighbours.clear();
    empty.face_centres.clear();
    empty.face_normals.clear();
    empty.face_mag.clear();
    empty.face_areas.clear();
    empty.points.clear();
    empty.point_face_offsets = vec![0];
    empty.point_faces.clear();
    for m in DetectionMethod::ALL {
        let mut d = m.detector(DetectParams::default()).unwrap();
        let mut out = CandidatePairs::new();
        for b in [&bad, &bad2, &bad3, &bad4, &bad5] {
            let e = d.detect(&master.surface, b, &mut out).unwrap_err();
            assert!(
                matches!(e, DetectError::InvalidSurface { side: "slave", .. }),
                "{e}"
            );
            let e = d.detect(b, &master.surface, &mut out).unwrap_err();
            assert!(
                matches!(e, DetectError::InvalidSurface { side: "master", .. }),
                "{e}"
            );
        }
        d.detect(&master.surface, &empty, &mut out).unwrap();
        assert_eq!((out.n_master(), out.n_pairs()), (9, 0));
        d.detect(&empty, &master.surface, &mut out).unwrap();
        assert_eq!((out.n_master(), out.n_pairs()), (0, 0));
        d.detect(&empty, &empty, &mut out).unwrap();
        assert_eq!(out.n_master(), 0);
    }
}

#[test]
fn estimated_height_is_the_mean_face_size() {
    let master = Patch::new([4, 4], false, true, &Placement::default());
    let slave = Patch::new([2, 2], false, false, &Placement::default());
    let mut out = CandidatePairs::new();
    let st = BruteForce::new(DetectParams::default())
        .detect(&master.surface, &slave.surface, &mut out)
        .unwrap();
    let expect = (16.0 * 0.25 + 4.0 * 0.5) / 20.0;
    assert!((st.mean_cell_height - expect).abs() < 1e-12);
    assert_eq!(st.master_faces_in_zone, 16);
}

/// Configurations on which earlier versions of the advancing front missed
/// pairs (a slave sheet dipping out of the band, border triangles whose
/// boxes overhang the border, a border bay across a master face).
#[test]
fn regression_cases_of_the_advancing_front() {
    struct R {
        master: ([usize; 2], bool, Placement),
        slave: ([usize; 2], bool, Placement),
        h: f64,
    }
    let cases = [
        R {
            master: ([2, 2], false, Placement::default()),
            slave: (
                [5, 8],
                true,
                Placement {
                    curvature: 0.998,
                    jitter: 0.149,
                    jitter_z: 0.0199,
                    seed: 54367177323342364,
                    shift: Vector::new(0.0, 0.0, -0.8238),
                    ..Default::default()
                },
            ),
            h: 0.3671,
        },
        R {
            master: ([4, 2], false, Placement::default()),
            slave: (
                [6, 6],
                true,
                Placement {
                    rotate: -0.5208,
                    tilt: 0.2005,
                    curvature: 0.9522,
                    jitter: 0.0731,
                    seed: 11516131871284748756,
                    shift: Vector::new(0.2269, 0.5759, 0.0),
                    ..Default::default()
                },
            ),
            h: 0.2205,
        },
        R {
            master: (
                [5, 6],
                true,
                Placement {
                    jitter: 0.03695,
                    jitter_z: 0.006892,
                    seed: 15549120581714013029,
                    ..Default::default()
                },
            ),
            slave: (
                [8, 4],
                false,
                Placement {
                    rotate: 0.7027,
                    tilt: -0.1331,
                    curvature: -0.5033,
                    jitter_z: 0.02584,
                    seed: 398579457099360304,
                    shift: Vector::new(-0.5128, 0.3161, 0.0),
                    ..Default::default()
                },
            ),
            h: 0.05,
        },
    ];
    for (k, c) in cases.iter().enumerate() {
        let p = params(c.h);
        let master = Patch::new(c.master.0, c.master.1, true, &c.master.2);
        let mut slave = Patch::new(c.slave.0, c.slave.1, false, &c.slave.2);
        let reference = all_agree(&master.surface, &slave.surface, p);
        assert!(reference.n_pairs() > 0, "case {k}");
        all_agree(&slave.surface, &master.surface, p);
        // warm after a small motion
        let mut af = AdvancingFront::new(p);
        let mut out = CandidatePairs::new();
        af.detect(&master.surface, &slave.surface, &mut out)
            .unwrap();
        let mut moved = c.slave.2;
        moved.shift += Vector::new(0.01, -0.02, 0.002);
        slave.place(&moved);
        af.detect(&master.surface, &slave.surface, &mut out)
            .unwrap();
        let mut bf = CandidatePairs::new();
        BruteForce::new(p)
            .detect(&master.surface, &slave.surface, &mut bf)
            .unwrap();
        assert_eq!(out, bf, "case {k} after motion");
    }
}
