//! One contact-force call on two facing non-conformal surfaces (as in every
//! outer iteration), for both algorithms, against the number of faces.
//!
//! Master: n × n quadrilaterals on [0,1]², normal +z; slave: the bottom of a
//! box 1.2 times wider with (n+3) × (n+1) faces, rotated by 0.1 rad about the
//! vertical and pressed in by 10⁻³; pairs from the BVH detector (computed
//! once, outside the timing). Friction on (μ = 0.3), the slave moved by a
//! small tangential offset so that the friction branch runs.
//! `FVC_BENCH_MAX_FACES` (default 40000) caps n².
//!
//! `contact_force_curved`: the same with a curved master, n × n faces of
//! a cylinder R = 2 over a 1 × 1 patch (0.5 rad), whose outside is pressed
//! into a flat slave of (n+3) × (n+1) faces everywhere (the sagitta is
//! 0.063, the penetration 0.07 to 0.007): every segment in contact, where
//! the Nagata variants project the most. The master does not move (a
//! rigid master, smoothed once).
use contact_detect::{BvhDetector, CandidatePairs, DetectParams, Detector};
use contact_force::{ContactAlgorithmKind, ContactLaw, ContactTractions, SlipHistory};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use fv_mesh::generators::{annulus_mesh, box_mesh};
use fv_mesh::{Surface, Vector};
use std::hint::black_box;

fn surfaces(n: usize) -> (Surface, Surface) {
    let m = box_mesh(
        Vector::new(0.0, 0.0, -0.1),
        Vector::new(1.0, 1.0, 0.0),
        [n, n, 1],
        [1.0; 3],
    )
    .expect("box");
    let master = Surface::new(&m, m.patch_index("zmax").expect("zmax")).expect("surface");
    let s = box_mesh(
        Vector::new(-0.1, -0.1, 0.0),
        Vector::new(1.1, 1.1, 0.1),
        [n + 3, n + 1, 1],
        [1.0; 3],
    )
    .expect("box");
    let mut slave = Surface::new(&s, s.patch_index("zmin").expect("zmin")).expect("surface");
    let (sn, cs) = 0.1f64.sin_cos();
    let c = Vector::new(0.5, 0.5, 0.0);
    let moved: Vec<Vector> = slave
        .points
        .iter()
        .map(|x| {
            let d = x - c;
            c + Vector::new(cs * d.x - sn * d.y, sn * d.x + cs * d.y, d.z - 1e-3)
        })
        .collect();
    slave.update_points(&moved);
    (master, slave)
}

fn curved_surfaces(n: usize) -> (Surface, Surface) {
    let r = 2.0;
    let m = annulus_mesh(
        r - 0.1,
        r,
        -std::f64::consts::FRAC_PI_2 - 0.25,
        -std::f64::consts::FRAC_PI_2 + 0.25,
        0.0,
        1.0,
        [1, n, n],
        1.0,
    )
    .expect("annulus");
    let master = Surface::new(&m, m.patch_index("outer").expect("outer")).expect("surface");
    let s = box_mesh(
        Vector::new(-0.6, -3.0, -0.1),
        Vector::new(0.6, -r + 0.07, 1.1),
        [n + 3, 1, n + 1],
        [1.0; 3],
    )
    .expect("box");
    let slave = Surface::new(&s, s.patch_index("ymax").expect("ymax")).expect("surface");
    (master, slave)
}

fn bench_curved(c: &mut Criterion) {
    let max: usize = std::env::var("FVC_BENCH_MAX_FACES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(40_000);
    let law = ContactLaw::new(1e6, 0.0, 0.0, SlipHistory::Incremental).expect("law");
    let mut group = c.benchmark_group("contact_force_curved");
    group.sample_size(10);
    for n in [25usize, 50, 100] {
        if n * n > max {
            continue;
        }
        let (master, slave) = curved_surfaces(n);
        let mut pairs = CandidatePairs::new();
        BvhDetector::new(DetectParams::default())
            .detect(&master, &slave, &mut pairs)
            .expect("detect");
        group.throughput(Throughput::Elements(pairs.n_pairs() as u64));
        for kind in ContactAlgorithmKind::ALL {
            let mut alg = kind.build();
            let mut out = ContactTractions::new();
            group.bench_with_input(BenchmarkId::new(kind.name(), n * n), &n, |b, _| {
                b.iter(|| {
                    black_box(
                        alg.compute(&master, &slave, &pairs, &law, &mut out)
                            .expect("compute"),
                    )
                })
            });
        }
    }
    group.finish();
}

fn bench(c: &mut Criterion) {
    let max: usize = std::env::var("FVC_BENCH_MAX_FACES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(40_000);
    let law = ContactLaw::new(1e6, 1e5, 0.3, SlipHistory::Incremental).expect("law");
    let mut group = c.benchmark_group("contact_force");
    group.sample_size(10);
    for n in [25usize, 50, 100, 200] {
        if n * n > max {
            continue;
        }
        let (master, mut slave) = surfaces(n);
        let mut pairs = CandidatePairs::new();
        BvhDetector::new(DetectParams::default())
            .detect(&master, &slave, &mut pairs)
            .expect("detect");
        group.throughput(Throughput::Elements(pairs.n_pairs() as u64));
        for kind in ContactAlgorithmKind::ALL {
            let mut alg = kind.build();
            let mut out = ContactTractions::new();
            alg.commit_increment(&master, &slave);
            let shifted: Vec<Vector> = slave
                .points
                .iter()
                .map(|x| x + Vector::new(2e-4, 0.0, 0.0))
                .collect();
            slave.update_points(&shifted);
            group.bench_with_input(BenchmarkId::new(kind.name(), n * n), &n, |b, _| {
                b.iter(|| {
                    black_box(
                        alg.compute(&master, &slave, &pairs, &law, &mut out)
                            .expect("compute"),
                    )
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench, bench_curved);
criterion_main!(benches);
