//! Detection time against the number of faces per surface, from scratch and
//! after a small motion (issue: contact-detect).
//!
//! Two facing square surfaces of N quadrilaterals each: the master is the
//! top of a unit box, the slave the bottom of a box 1.2 times wider, rotated
//! by 0.1 rad about the vertical so that the grids are non-conformal and the
//! slave covers the master. "After a small motion": the slave alternates
//! between two positions 2 % of a face apart (plus a 10⁻³ rad twist), so
//! every call follows a small motion, as between outer iterations; within
//! the skin of [`PairReuse`], which therefore searches once and then reuses.
//!
//! Environment: `FVC_BENCH_MAX_FACES` (default 1000000) caps N;
//! `FVC_BENCH_BRUTE_MAX` (default 10000) caps N for brute force in the
//! criterion loop; `FVC_BENCH_BRUTE_ONCE=1` times one brute-force call at
//! N = 10⁵ outside criterion (tens of seconds); `FVC_BENCH_TABLE=1` skips
//! criterion and prints a table of the minimum and median of repeated
//! calls (the minimum is the figure least disturbed by other processes on
//! a shared machine).
use contact_detect::{
    AdvancingFront, BruteForce, BvhDetector, CandidatePairs, DetectParams, DetectionMethod,
    Detector, PairReuse, DEFAULT_SKIN,
};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use fv_mesh::generators::box_mesh;
use fv_mesh::{Surface, Vector};
use std::hint::black_box;
use std::time::{Duration, Instant};

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Master surface with n × n faces on [0,1]², normal +z.
fn master(n: usize) -> Surface {
    let m = box_mesh(
        Vector::new(0.0, 0.0, -0.1),
        Vector::new(1.0, 1.0, 0.0),
        [n, n, 1],
        [1.0; 3],
    )
    .expect("box");
    Surface::new(&m, m.patch_index("zmax").expect("zmax")).expect("surface")
}

/// Slave surface with n × n faces on [-0.1,1.1]², normal -z; returns it
/// with its reference points.
fn slave(n: usize) -> (Surface, Vec<Vector>) {
    let m = box_mesh(
        Vector::new(-0.1, -0.1, 0.0),
        Vector::new(1.1, 1.1, 0.1),
        [n, n, 1],
        [1.0; 3],
    )
    .expect("box");
    let s = Surface::new(&m, m.patch_index("zmin").expect("zmin")).expect("surface");
    let r = s.points.clone();
    (s, r)
}

/// Reference points rotated by `angle` about the vertical through the
/// centre, shifted by `shift`.
fn moved(reference: &[Vector], angle: f64, shift: Vector) -> Vec<Vector> {
    let (s, c) = angle.sin_cos();
    reference
        .iter()
        .map(|x| {
            let r = x - Vector::new(0.5, 0.5, 0.0);
            Vector::new(c * r.x - s * r.y + 0.5, s * r.x + c * r.y + 0.5, r.z) + shift
        })
        .collect()
}

struct Pair {
    master: Surface,
    slave_a: Surface,
    slave_b: Surface,
}

fn setup(n: usize) -> Pair {
    let master = master(n);
    let (mut slave_a, reference) = slave(n);
    let h = 1.0 / n as f64;
    let mut slave_b = slave_a.clone();
    slave_a.update_points(&moved(&reference, 0.1, Vector::new(0.0, 0.0, -0.05 * h)));
    slave_b.update_points(&moved(
        &reference,
        0.101,
        Vector::new(0.02 * h, 0.01 * h, -0.06 * h),
    ));
    Pair {
        master,
        slave_a,
        slave_b,
    }
}

/// Minimum and median wall time of `f` over up to `max_runs` calls (at
/// least 3, at most about `budget`).
fn min_median(max_runs: usize, budget: Duration, mut f: impl FnMut()) -> (Duration, Duration) {
    let mut t = Vec::new();
    let start = Instant::now();
    while t.len() < max_runs && (t.len() < 3 || start.elapsed() < budget) {
        let s = Instant::now();
        f();
        t.push(s.elapsed());
    }
    t.sort();
    (t[0], t[t.len() / 2])
}

fn table(max_faces: usize, brute_max: usize) {
    let params = DetectParams::default();
    let mut out = CandidatePairs::new();
    println!("| N | detector | case | min | median |");
    println!("|---|---|---|---|---|");
    for n in [32usize, 100, 316, 1000] {
        if n * n > max_faces * 11 / 10 {
            continue;
        }
        let p = setup(n);
        let nf = n * n;
        let budget = Duration::from_secs(if nf > 200_000 { 20 } else { 4 });
        let row = |name: &str, case: &str, (a, b): (Duration, Duration)| {
            println!("| {nf} | {name} | {case} | {a:.3?} | {b:.3?} |");
        };
        if nf <= brute_max {
            let mut d = BruteForce::new(params);
            row(
                "brute-force",
                "any",
                min_median(10, budget, || {
                    d.detect(&p.master, &p.slave_b, &mut out).expect("bf");
                }),
            );
        }
        let mut bvh = BvhDetector::new(params);
        let mut flip = false;
        row(
            "bvh",
            "any",
            min_median(20, budget, || {
                flip = !flip;
                let s = if flip { &p.slave_a } else { &p.slave_b };
                bvh.detect(&p.master, s, &mut out).expect("bvh");
            }),
        );
        let mut af = AdvancingFront::new(params);
        row(
            "advancing-front",
            "cold",
            min_median(20, budget, || {
                af.reset();
                af.detect(&p.master, &p.slave_a, &mut out).expect("af");
            }),
        );
        af.reset();
        let cold = af.detect(&p.master, &p.slave_a, &mut out).expect("af");
        let warm = af.detect(&p.master, &p.slave_b, &mut out).expect("af");
        eprintln!("N = {nf}: cold {cold:?}\nN = {nf}: warm {warm:?}");
        row(
            "advancing-front",
            "after small motion",
            min_median(20, budget, || {
                flip = !flip;
                let s = if flip { &p.slave_a } else { &p.slave_b };
                af.detect(&p.master, s, &mut out).expect("af");
            }),
        );
        let mut reuse =
            PairReuse::new(DetectionMethod::AdvancingFront, params, DEFAULT_SKIN).expect("reuse");
        row(
            "pair-reuse",
            "after small motion",
            min_median(20, budget, || {
                flip = !flip;
                let s = if flip { &p.slave_a } else { &p.slave_b };
                reuse.detect(&p.master, s, &mut out).expect("reuse");
            }),
        );
        eprintln!(
            "N = {nf}: pair reuse (searches, lists, reuses) {:?}",
            reuse.counts()
        );
        let mut ws = contact_detect::Workspace::default();
        row(
            "(boxes and zone only)",
            "any",
            min_median(20, budget, || {
                ws.prepare(&p.master, &p.slave_a, &params).expect("prepare");
            }),
        );
    }
}

fn bench(c: &mut Criterion) {
    if std::env::var("FVC_BENCH_TABLE").is_ok() {
        table(
            env_usize("FVC_BENCH_MAX_FACES", 1_000_000),
            env_usize("FVC_BENCH_BRUTE_MAX", 10_000),
        );
        return;
    }
    let max_faces = env_usize("FVC_BENCH_MAX_FACES", 1_000_000);
    let brute_max = env_usize("FVC_BENCH_BRUTE_MAX", 10_000);
    let params = DetectParams::default();
    let sizes: Vec<usize> = [32usize, 100, 316, 1000]
        .into_iter()
        .filter(|n| n * n <= max_faces * 11 / 10)
        .collect();
    let mut out = CandidatePairs::new();

    for &n in &sizes {
        let t = Instant::now();
        let p = setup(n);
        let nf = n * n;
        eprintln!("N = {nf}: surfaces built in {:.2?}", t.elapsed());
        // one reference call for the statistics
        let mut bvh = BvhDetector::new(params);
        let st = bvh.detect(&p.master, &p.slave_a, &mut out).expect("bvh");
        eprintln!(
            "N = {nf}: {} pairs, {} master / {} slave faces in the zone",
            st.pairs, st.master_faces_in_zone, st.slave_faces_in_zone
        );

        let mut g = c.benchmark_group(format!("detect_from_scratch/{nf}"));
        g.sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(if nf > 200_000 { 20 } else { 3 }));
        if nf <= brute_max {
            let mut d = BruteForce::new(params);
            g.bench_function(BenchmarkId::new("brute-force", nf), |b| {
                b.iter(|| black_box(d.detect(&p.master, &p.slave_a, &mut out).expect("bf")))
            });
        }
        g.bench_function(BenchmarkId::new("bvh", nf), |b| {
            b.iter(|| black_box(bvh.detect(&p.master, &p.slave_a, &mut out).expect("bvh")))
        });
        let mut af = AdvancingFront::new(params);
        g.bench_function(BenchmarkId::new("advancing-front-cold", nf), |b| {
            b.iter(|| {
                af.reset();
                black_box(af.detect(&p.master, &p.slave_a, &mut out).expect("af"))
            })
        });
        g.finish();

        let mut g = c.benchmark_group(format!("detect_after_small_motion/{nf}"));
        g.sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(if nf > 200_000 { 20 } else { 3 }));
        let mut flip = false;
        let next = |flip: &mut bool| {
            *flip = !*flip;
            if *flip {
                &p.slave_b
            } else {
                &p.slave_a
            }
        };
        af.reset();
        af.detect(&p.master, &p.slave_a, &mut out).expect("af");
        let st = af.detect(&p.master, &p.slave_b, &mut out).expect("af");
        eprintln!("N = {nf}: warm advancing front {st:?}");
        g.bench_function(BenchmarkId::new("advancing-front-warm", nf), |b| {
            b.iter(|| {
                let s = next(&mut flip);
                black_box(af.detect(&p.master, s, &mut out).expect("af"))
            })
        });
        g.bench_function(BenchmarkId::new("bvh", nf), |b| {
            b.iter(|| {
                let s = next(&mut flip);
                black_box(bvh.detect(&p.master, s, &mut out).expect("bvh"))
            })
        });
        let mut reuse =
            PairReuse::new(DetectionMethod::AdvancingFront, params, DEFAULT_SKIN).expect("reuse");
        g.bench_function(BenchmarkId::new("pair-reuse", nf), |b| {
            b.iter(|| {
                let s = next(&mut flip);
                black_box(reuse.detect(&p.master, s, &mut out).expect("reuse"))
            })
        });
        if nf <= brute_max {
            let mut d = BruteForce::new(params);
            g.bench_function(BenchmarkId::new("brute-force", nf), |b| {
                b.iter(|| {
                    let s = next(&mut flip);
                    black_box(d.detect(&p.master, s, &mut out).expect("bf"))
                })
            });
        }
        g.finish();

        if nf > brute_max && nf <= 110_000 && std::env::var("FVC_BENCH_BRUTE_ONCE").is_ok() {
            let mut d = BruteForce::new(params);
            let t = Instant::now();
            let st = d.detect(&p.master, &p.slave_b, &mut out).expect("bf");
            eprintln!(
                "N = {nf}: one brute-force call took {:.2?} ({} AABB tests)",
                t.elapsed(),
                st.aabb_tests
            );
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
