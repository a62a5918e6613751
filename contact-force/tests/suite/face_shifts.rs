//! Face shifts (`ContactAlgorithm::set_face_shifts`): the gap is measured
//! between the faces translated by their shifts, on both algorithms.
use crate::common::{close, law, lower, upper};
use contact_force::{
    all_pairs, ContactAlgorithm, ContactStats, ContactTractions, Pointwise, SegmentToSegment,
};
use fv_mesh::{Real, Surface, Vector};

const EPS: Real = 1e6;
const DELTA: Real = 1e-3;

fn algorithms() -> [(&'static str, Box<dyn ContactAlgorithm>); 2] {
    [
        ("segment-to-segment", Box::new(SegmentToSegment::new())),
        ("pointwise", Box::new(Pointwise::new())),
    ]
}

fn run(
    alg: &mut dyn ContactAlgorithm,
    m: &Surface,
    s: &Surface,
    shifts: (&[Vector], &[Vector]),
) -> (ContactTractions, ContactStats) {
    let pairs = all_pairs(m.n_faces(), s.n_faces());
    let mut out = ContactTractions::new();
    alg.set_face_shifts(shifts.0, shifts.1);
    let stats = alg
        .compute(m, s, &pairs, &law(EPS, 0.0, 0.0), &mut out)
        .unwrap();
    (out, stats)
}

/// Two touching unit squares (gap 0), conforming 4 × 1 faces; the slave
/// faces shifted down by δ and up by δ in turn (the zig-zag that the
/// surface points cannot show): the faces shifted into the master carry
/// ε_n δ over their whole area (the pointwise algorithm: at their points,
/// whose gaps it takes per face), the others nothing, and the master
/// receives the same force.
#[test]
fn alternating_slave_shifts_press_every_other_face() {
    let m = lower([4, 1], [0.0, 1.0], [0.0, 1.0], 0.0);
    let s = upper([4, 1], [0.0, 1.0], [0.0, 1.0], 0.0);
    let shift = |f: usize| Vector::new(0.0, 0.0, if f.is_multiple_of(2) { -DELTA } else { DELTA });
    let slave: Vec<Vector> = (0..s.n_faces()).map(shift).collect();
    for (name, mut alg) in algorithms() {
        let (out, stats) = run(alg.as_mut(), &m, &s, (&[], &slave));
        for (f, d) in slave.iter().enumerate() {
            let pressed = d.z < 0.0;
            let p = out.slave.pressure[f];
            if pressed {
                assert!(close(p, EPS * DELTA, 1e-9, 0.0), "{name} face {f}: {p}");
                assert!(
                    close(out.slave.gap[f], -DELTA, 1e-9, 0.0),
                    "{name} face {f}"
                );
                assert!(close(out.slave.contact_fraction[f], 1.0, 1e-9, 0.0));
            } else {
                assert_eq!(p, 0.0, "{name} face {f}");
                assert!(close(out.slave.gap[f], DELTA, 1e-9, 0.0), "{name} face {f}");
            }
        }
        let force = EPS * DELTA * 0.5;
        assert!(
            close(stats.slave_force.z, force, 1e-9, 0.0),
            "{name}: {stats:?}"
        );
        assert!(
            (stats.master_force + stats.slave_force).norm() <= 1e-9 * force,
            "{name}: action ≠ reaction"
        );
        assert!(close(stats.max_penetration, DELTA, 1e-9, 0.0), "{name}");
    }
}

/// The master faces shifted up by δ: a uniform penetration δ, as if the
/// master surface had moved.
#[test]
fn master_shift_moves_the_master_faces() {
    let m = lower([3, 2], [0.0, 1.0], [0.0, 1.0], 0.0);
    let s = upper([5, 3], [0.0, 1.0], [0.0, 1.0], 0.0);
    let master = vec![Vector::new(0.0, 0.0, DELTA); m.n_faces()];
    for (name, mut alg) in algorithms() {
        let (out, stats) = run(alg.as_mut(), &m, &s, (&master, &[]));
        for f in 0..s.n_faces() {
            assert!(
                close(out.slave.pressure[f], EPS * DELTA, 1e-9, 0.0),
                "{name} slave {f}: {}",
                out.slave.pressure[f]
            );
        }
        assert!(close(stats.normal_force, EPS * DELTA, 1e-9, 0.0), "{name}");
    }
}

/// The same shift on both sides, with an in-plane part, changes nothing:
/// the gap depends on the relative translation only (along the normal;
/// the overlaps are those of the surfaces).
#[test]
fn equal_shifts_change_nothing() {
    let m = lower([4, 4], [0.0, 1.0], [0.0, 1.0], 0.0);
    let s = upper([7, 5], [0.0, 1.0], [0.0, 1.0], -DELTA);
    let d = Vector::new(0.02, -0.01, 0.3);
    let (master, slave) = (vec![d; m.n_faces()], vec![d; s.n_faces()]);
    for (name, mut alg) in algorithms() {
        let (plain, plain_stats) = run(alg.as_mut(), &m, &s, (&[], &[]));
        let (shifted, stats) = run(alg.as_mut(), &m, &s, (&master, &slave));
        for (side, a, b) in [
            ("slave", &shifted.slave.pressure, &plain.slave.pressure),
            ("master", &shifted.master.pressure, &plain.master.pressure),
        ] {
            for (f, (&p, &q)) in a.iter().zip(b).enumerate() {
                assert!(close(p, q, 1e-9, 0.0), "{name} {side} {f}: {p} against {q}");
            }
        }
        assert!(close(
            stats.normal_force,
            plain_stats.normal_force,
            1e-9,
            0.0
        ));
        // and the plain answer is the uniform ε_n δ
        assert!(
            close(plain_stats.normal_force, EPS * DELTA, 1e-9, 0.0),
            "{name}"
        );
    }
}
