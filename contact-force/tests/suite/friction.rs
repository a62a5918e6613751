//! Coulomb friction on flat surfaces in full contact: stick (traction =
//! tangential penalty × slip), slip (|t_t| = μ p), both opposing the slip,
//! on both surfaces; slip interpolated by barycentric coordinates (4.26);
//! increments and slip history.
use crate::common::{close, deform, lower, upper};
use contact_force::{
    all_pairs, ContactAlgorithm, ContactAlgorithmKind, ContactLaw, ContactTractions, FrictionState,
    SegmentToSegment, SlipHistory,
};
use fv_mesh::{Real, Surface, Vector};

const EPS_N: Real = 1e6;
const EPS_T: Real = 1e5;
const MU: Real = 0.3;
const DELTA: Real = 1e-3;
const P: Real = EPS_N * DELTA;

fn law(history: SlipHistory) -> ContactLaw {
    ContactLaw::new(EPS_N, EPS_T, MU, history).unwrap()
}

/// Master 4×4 and slave 7×5 faces pressed by δ. Segment-to-segment: master
/// [0,1]², slave [−0.1,1.1]²; pointwise: the other way round, so that every
/// slave point projects inside the master. Every face of the smaller surface
/// stays fully covered under small in-plane motions.
fn surfaces(kind: ContactAlgorithmKind) -> (Surface, Surface) {
    let (small, big) = ([0.0, 1.0], [-0.1, 1.1]);
    let (xm, xs) = match kind {
        ContactAlgorithmKind::SegmentToSegment | ContactAlgorithmKind::SegmentToSegmentNagata => {
            (small, big)
        }
        ContactAlgorithmKind::Pointwise | ContactAlgorithmKind::PointwiseNagata => (big, small),
    };
    (lower([4, 4], xm, xm, 0.0), upper([7, 5], xs, xs, -DELTA))
}

fn translate_slave(
    d: Vector,
    kind: ContactAlgorithmKind,
    history: SlipHistory,
) -> (
    Surface,
    Surface,
    ContactTractions,
    contact_force::ContactStats,
) {
    let (m, mut s) = surfaces(kind);
    let pairs = all_pairs(m.n_faces(), s.n_faces());
    let mut alg = kind.build();
    alg.commit_increment(&m, &s);
    deform(&mut s, |_| d);
    let mut out = ContactTractions::new();
    let stats = alg
        .compute(&m, &s, &pairs, &law(history), &mut out)
        .unwrap();
    (m, s, out, stats)
}

/// Every face carries (covered fraction) × the full-contact value: pressure
/// `P`, tangential traction `t_master` on the master and `−t_master` on the
/// slave; the totals balance.
fn check_friction(
    kind: ContactAlgorithmKind,
    d: Vector,
    t_master: Vector,
    state: FrictionState,
    (m, s, out, stats): (
        Surface,
        Surface,
        ContactTractions,
        contact_force::ContactStats,
    ),
) {
    let scale = t_master.norm();
    for f in 0..m.n_faces() {
        let cov = out.ggi.master_coverage(f);
        assert!(
            close(out.master.pressure[f], cov * P, 1e-12, 1.0),
            "{kind} master {f}"
        );
        assert!(
            (out.master.tangential_traction[f] - t_master * cov).norm() <= 1e-12 * scale,
            "{kind} master {f}"
        );
        if cov > 0.0 {
            assert_eq!(out.master.friction_state[f], state, "{kind} master {f}");
            assert!(
                (out.master.slip[f] + d).norm() <= 1e-12 * d.norm(),
                "{kind} master {f}"
            );
        }
    }
    for f in 0..s.n_faces() {
        let cov = out.ggi.slave_coverage(f);
        assert!(
            close(out.slave.pressure[f], cov * P, 1e-12, 1.0),
            "{kind} slave {f}"
        );
        assert!(
            (out.slave.tangential_traction[f] + t_master * cov).norm() <= 1e-12 * scale,
            "{kind} slave {f}"
        );
        if cov > 0.0 {
            assert_eq!(out.slave.friction_state[f], state, "{kind} slave {f}");
            assert!(
                (out.slave.slip[f] - d).norm() <= 1e-12 * d.norm(),
                "{kind} slave {f}"
            );
        }
    }
    // contact area 1: total frictional force t_master, action = reaction
    assert!(close(stats.contact_area, 1.0, 1e-12, 0.0), "{kind}");
    assert!(
        (stats.tangential_force - t_master).norm() <= 1e-12 * scale,
        "{kind}"
    );
    assert!(
        (stats.master_force + stats.slave_force).norm() <= 1e-12 * P,
        "{kind}"
    );
}

#[test]
fn stick_below_the_limit() {
    let d = Vector::new(1e-3, 0.5e-3, 0.0); // ε_t |d| = 111.8 < μ p = 300
    for kind in ContactAlgorithmKind::ALL {
        // on the master: along the slave motion (opposite to its own slip −d)
        let run = translate_slave(d, kind, SlipHistory::Incremental);
        assert_eq!(run.3.n_slip, 0);
        check_friction(kind, d, d * EPS_T, FrictionState::Stick, run);
    }
}

#[test]
fn slip_above_the_limit_returns_to_the_cone() {
    let d = Vector::new(4e-3, -3e-3, 0.0); // ε_t |d| = 500 > μ p = 300
    for kind in ContactAlgorithmKind::ALL {
        let run = translate_slave(d, kind, SlipHistory::Incremental);
        assert_eq!(run.3.n_stick, 0);
        check_friction(kind, d, d.normalize() * (MU * P), FrictionState::Slip, run);
    }
}

#[test]
fn slip_is_interpolated_barycentrically_both_ways() {
    // master rotated in its plane by θ about (0.5, 0.5): a linear in-plane
    // displacement field, which eq. 4.26 interpolates exactly
    let theta = 2e-3;
    let c = Vector::new(0.5, 0.5, 0.0);
    let du = |x: &Vector| Vector::z().cross(&(x - c)) * theta;
    let (mut m, s) = surfaces(ContactAlgorithmKind::SegmentToSegment);
    let pairs = all_pairs(m.n_faces(), s.n_faces());
    let mut alg = SegmentToSegment::new();
    alg.commit_increment(&m, &s);
    let reference = m.clone();
    deform(&mut m, du);
    let mut out = ContactTractions::new();
    let stats = alg
        .compute(&m, &s, &pairs, &law(SlipHistory::Incremental), &mut out)
        .unwrap();
    for f in 0..m.n_faces() {
        // own increment at the face centre (mean of the point increments)
        let u = du(&reference.face_centres[f]);
        assert!((out.master.slip[f] - u).norm() <= 1e-12 * theta, "{f}");
        assert!((out.master.tangential_traction[f] + u * EPS_T).norm() <= 1e-9 * theta * EPS_T);
    }
    for f in 0..s.n_faces() {
        if out.ggi.slave_coverage(f) > 1.0 - 1e-12 {
            // the master increment at the point of the moved master hit by
            // the ray from the slave centre: x_ref + du(x_ref) = x_s, i.e.
            // (I + θ J) r_ref = r_s with J = ẑ×, J² = −1 in the plane
            let r = s.face_centres[f] - c;
            let u = du(&(c + (r - Vector::z().cross(&r) * theta) / (1.0 + theta * theta)));
            assert!(
                (out.slave.slip[f] + u).norm() <= 1e-12 * theta,
                "{f}: {:?} vs {:?}",
                out.slave.slip[f],
                -u
            );
        }
    }
    // a rotation: no net tangential force, a torque about z
    assert!(stats.tangential_force.norm() <= 1e-9 * EPS_T * theta);
}

#[test]
fn commit_increment_resets_the_slip_or_keeps_the_elastic_slip() {
    let d = Vector::new(1e-3, 0.0, 0.0);
    for (history, expect) in [
        (SlipHistory::Incremental, 0.0),
        (SlipHistory::Accumulated, EPS_T * 1e-3),
    ] {
        for kind in ContactAlgorithmKind::ALL {
            let (m, mut s) = surfaces(kind);
            let pairs = all_pairs(m.n_faces(), s.n_faces());
            let mut alg = kind.build();
            let mut out = ContactTractions::new();
            // first call: the current positions become the reference
            alg.compute(&m, &s, &pairs, &law(history), &mut out)
                .unwrap();
            assert!(out
                .master
                .tangential_traction
                .iter()
                .all(|t| t.norm() == 0.0));
            deform(&mut s, |_| d);
            alg.compute(&m, &s, &pairs, &law(history), &mut out)
                .unwrap();
            assert!(close(
                out.master.tangential_traction[5].x,
                EPS_T * 1e-3,
                1e-12,
                0.0
            ));
            alg.commit_increment(&m, &s);
            let stats = alg
                .compute(&m, &s, &pairs, &law(history), &mut out)
                .unwrap();
            assert!(
                close(stats.tangential_force.x, expect, 1e-12, 1.0),
                "{kind} {history:?}: {}",
                stats.tangential_force.x
            );
            // a further motion adds to the kept elastic slip, up to the cone
            deform(&mut s, |_| d * 3.0);
            let stats = alg
                .compute(&m, &s, &pairs, &law(history), &mut out)
                .unwrap();
            let t = (expect + 3.0 * EPS_T * 1e-3).min(MU * P);
            assert!(
                close(stats.tangential_force.x, t, 1e-12, 1.0),
                "{kind} {history:?}"
            );
            alg.reset();
        }
    }
}
