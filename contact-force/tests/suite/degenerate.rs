//! Degenerate input: no panic, no traction where there is no contact, errors
//! only for inconsistent input.
use crate::common::{close, law, lower, upper};
use contact_detect::CandidatePairs;
use contact_force::{
    all_pairs, ContactAlgorithmKind, ContactError, ContactLaw, ContactTractions, SlipHistory,
    NO_GAP,
};
use fv_mesh::generators::box_mesh;
use fv_mesh::{Real, Surface, Vector};

const EPS: Real = 1e6;

fn all_finite(out: &ContactTractions) -> bool {
    [&out.master, &out.slave].iter().all(|s| {
        s.normal_traction
            .iter()
            .chain(&s.tangential_traction)
            .all(|t| t.iter().all(|x| x.is_finite()))
            && s.pressure
                .iter()
                .chain(&s.contact_fraction)
                .all(|x| x.is_finite())
    })
}

#[test]
fn no_pairs() {
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let s = upper([7, 5], [0.0, 1.0], [0.0, 1.0], -1e-3);
    let empty_rows: Vec<Vec<u32>> = Vec::new();
    let empty_detected = CandidatePairs::new();
    for kind in ContactAlgorithmKind::ALL {
        for pairs in [
            &empty_rows as &dyn contact_force::FacePairs,
            &empty_detected,
            &vec![Vec::new(); 16],
        ] {
            let mut out = ContactTractions::new();
            let st = kind
                .build()
                .compute(&m, &s, pairs, &law(EPS, 1e5, 0.3), &mut out)
                .unwrap();
            assert_eq!(st.normal_force, 0.0);
            assert_eq!(st.n_overlapping_pairs, 0);
            assert_eq!(out.master.n_faces(), 16);
            assert_eq!(out.slave.n_faces(), 35);
            assert!(out.master.gap.iter().all(|&g| g == NO_GAP));
            assert!(all_finite(&out));
        }
    }
}

#[test]
fn inconsistent_input_is_an_error() {
    let m = lower([2, 2], [0.0, 1.0], [0.0, 1.0], 0.0);
    let s = upper([2, 2], [0.0, 1.0], [0.0, 1.0], -1e-3);
    let mut out = ContactTractions::new();
    for kind in ContactAlgorithmKind::ALL {
        let mut alg = kind.build();
        let bad_index = vec![vec![0, 4], vec![], vec![], vec![]];
        let e = alg
            .compute(&m, &s, &bad_index, &law(EPS, 0.0, 0.0), &mut out)
            .unwrap_err();
        assert!(matches!(e, ContactError::InvalidPairs(_)), "{e}");
        let too_many = all_pairs(5, 4);
        assert!(alg
            .compute(&m, &s, &too_many, &law(EPS, 0.0, 0.0), &mut out)
            .is_err());
        let bad_law = ContactLaw {
            normal_penalty: -1.0,
            tangential_penalty: 0.0,
            friction: 0.0,
            slip_history: SlipHistory::Incremental,
        };
        assert!(alg
            .compute(&m, &s, &all_pairs(4, 4), &bad_law, &mut out)
            .is_err());
    }
}

#[test]
fn zero_area_faces_are_skipped() {
    // collapse the first column of slave faces (x ∈ [0, 1/7] → x = 1/7)
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let mut s = upper([7, 5], [0.0, 1.0], [0.0, 1.0], -1e-3);
    let h = 1.0 / 7.0;
    let moved: Vec<Vector> = s
        .points
        .iter()
        .map(|x| Vector::new(x.x.max(h), x.y, x.z))
        .collect();
    s.update_points(&moved);
    assert!(s.face_mag.iter().filter(|&&a| a == 0.0).count() == 5);
    let pairs = all_pairs(16, 35);
    for kind in ContactAlgorithmKind::ALL {
        let mut out = ContactTractions::new();
        let st = kind
            .build()
            .compute(&m, &s, &pairs, &law(EPS, 1e5, 0.3), &mut out)
            .unwrap();
        assert!(all_finite(&out), "{kind}");
        if matches!(
            kind,
            ContactAlgorithmKind::SegmentToSegment | ContactAlgorithmKind::SegmentToSegmentNagata
        ) {
            assert!(close(st.contact_area, 1.0 - h, 1e-12, 0.0));
            assert!(close(st.normal_force, EPS * 1e-3 * (1.0 - h), 1e-12, 0.0));
        }
        // every point of the surface at one place: nothing at all
        let mut c = s.clone();
        c.update_points(&vec![Vector::new(0.5, 0.5, 0.0); c.n_points()]);
        let st = kind
            .build()
            .compute(&m, &c, &pairs, &law(EPS, 1e5, 0.3), &mut out)
            .unwrap();
        assert_eq!(st.normal_force, 0.0, "{kind}");
        assert!(all_finite(&out));
        // and as master
        let st = kind
            .build()
            .compute(&c, &m, &all_pairs(35, 16), &law(EPS, 1e5, 0.3), &mut out)
            .unwrap();
        assert_eq!(st.normal_force, 0.0, "{kind}");
        assert!(all_finite(&out));
    }
}

#[test]
fn non_finite_points_do_not_panic() {
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let mut s = upper([7, 5], [0.0, 1.0], [0.0, 1.0], -1e-3);
    let mut moved = s.points.clone();
    moved[10] = Vector::new(Real::NAN, 0.0, Real::INFINITY);
    s.update_points(&moved);
    for kind in ContactAlgorithmKind::ALL {
        let mut out = ContactTractions::new();
        let st = kind
            .build()
            .compute(&m, &s, &all_pairs(16, 35), &law(EPS, 1e5, 0.3), &mut out)
            .unwrap();
        assert!(
            st.normal_force.is_finite() && st.normal_force > 0.0,
            "{kind}"
        );
        assert!(all_finite(&out), "{kind}");
    }
}

#[test]
fn perpendicular_and_same_facing_surfaces_do_not_touch() {
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    // a wall crossing the master: the xmin patch (normal −x) of a box
    let b = box_mesh(
        Vector::new(0.5, 0.0, -0.5),
        Vector::new(1.5, 1.0, 0.5),
        [2, 2, 2],
        [1.0; 3],
    )
    .unwrap();
    let wall = Surface::new(&b, b.patch_index("xmin").unwrap()).unwrap();
    // a surface facing the same way as the master, penetrating it
    let same = lower([7, 5], [0.0, 1.0], [0.0, 1.0], -1e-3);
    for (s, name) in [(&wall, "wall"), (&same, "same facing")] {
        for kind in ContactAlgorithmKind::ALL {
            let mut out = ContactTractions::new();
            let pairs = all_pairs(16, s.n_faces());
            let st = kind
                .build()
                .compute(&m, s, &pairs, &law(EPS, 1e5, 0.3), &mut out)
                .unwrap();
            assert_eq!(st.normal_force, 0.0, "{kind} {name}");
            assert_eq!(st.slave_force, Vector::zeros(), "{kind} {name}");
            assert!(all_finite(&out));
        }
    }
}
