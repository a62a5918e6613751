//! Cost of projecting a point onto the Nagata surface (thesis eqs.
//! 4.81–4.84) and of refreshing the surface after the points move.
//!
//! Unit sphere meshed with 1280 triangles (geodesic) and 1536
//! quadrilaterals (cube sphere); 1000 seeded points at distance ±0.05 from
//! the sphere. `closest-ring2`: one call of
//! `NagataSurface::closest_projection` with the faces around the faces of
//! the nearest mesh point as candidates (23.9 triangles or 16.0
//! quadrilaterals on average); `closest-ring1`: the faces of the nearest
//! point only (6 or 4); `one-patch`: the projection onto the face of the
//! foot only; `update-points`: `update_points` of the whole surface
//! (normals and coefficients, no allocation).
//!
//! Measured (release, 2 cores shared with other builds, load average 5–10,
//! so upper bounds), median:
//!
//! | case            | closest, ring 2 | closest, ring 1 | one patch | update_points |
//! |-----------------|-----------------|-----------------|-----------|---------------|
//! | 1280 triangles  | 26 µs           | 7.1 µs          | 0.67 µs   | 0.45 ms       |
//! | 1536 quads      | 21 µs           | 4.8 µs          | 0.85 µs   | 1.0 ms        |
//!
//! A candidate whose foot lies outside it costs about twice the one-patch
//! time (the iteration leaves the domain, then the crossed sides are searched).
use contact_smooth::{project_onto_patch, NagataSurface, PatchRef, SmoothingOptions};
use criterion::{criterion_group, criterion_main, Criterion};
use fv_mesh::Vector;
use std::hint::black_box;
use std::time::Duration;

#[path = "../tests/suite/common/mod.rs"]
mod common;
use common::{cube_sphere, geodesic_sphere, Lcg, Mesh};

struct Case {
    name: &'static str,
    surface: NagataSurface,
    points: Vec<Vector>,
    ring2: Vec<Vec<usize>>,
    ring1: Vec<Vec<usize>>,
    feet: Vec<usize>,
    mesh: Mesh,
}

fn case(name: &'static str, mesh: Mesh) -> Case {
    let surface = NagataSurface::new(&mesh.points, &mesh.faces, &[], SmoothingOptions::default())
        .expect("valid mesh");
    let mut rng = Lcg(31);
    let points: Vec<Vector> = (0..1000)
        .map(|_| (1.0 + 0.1 * (rng.next() - 0.5)) * rng.direction())
        .collect();
    let (mut ring1, mut ring2, mut feet) = (Vec::new(), Vec::new(), Vec::new());
    let mut around = Vec::new();
    for xs in &points {
        let nearest = (0..surface.n_points())
            .min_by(|&a, &b| {
                (surface.points()[a] - xs)
                    .norm()
                    .total_cmp(&(surface.points()[b] - xs).norm())
            })
            .unwrap_or(0);
        let r1: Vec<usize> = surface
            .table()
            .corners(nearest)
            .iter()
            .map(|c| c.face)
            .collect();
        let mut r2 = Vec::new();
        for &f in &r1 {
            surface
                .faces_around_face(f, &mut around)
                .expect("face in range");
            r2.extend_from_slice(&around);
        }
        r2.sort_unstable();
        r2.dedup();
        let foot = surface
            .closest_projection(xs, &r2)
            .expect("valid input")
            .expect("a foot");
        feet.push(foot.face);
        ring1.push(r1);
        ring2.push(r2);
    }
    let mean = |r: &[Vec<usize>]| r.iter().map(Vec::len).sum::<usize>() as f64 / r.len() as f64;
    println!(
        "{name}: {} faces, {:.1} / {:.1} candidate faces per point (ring 1 / ring 2)",
        surface.n_faces(),
        mean(&ring1),
        mean(&ring2)
    );
    Case {
        name,
        surface,
        points,
        ring2,
        ring1,
        feet,
        mesh,
    }
}

fn bench(c: &mut Criterion) {
    let cases = [
        case("triangles-1280", geodesic_sphere(1.0, 8)),
        case("quads-1536", cube_sphere(1.0, 16)),
    ];
    let mut g = c.benchmark_group("nagata");
    g.sample_size(30).measurement_time(Duration::from_secs(3));
    for cs in &cases {
        let n = cs.points.len();
        for (label, cands) in [("ring2", &cs.ring2), ("ring1", &cs.ring1)] {
            g.bench_function(format!("closest-{label}/{}", cs.name), |b| {
                let mut k = 0;
                b.iter(|| {
                    k = (k + 1) % n;
                    black_box(cs.surface.closest_projection(&cs.points[k], &cands[k]))
                })
            });
        }
        g.bench_function(format!("one-patch/{}", cs.name), |b| {
            let prm = cs.surface.options().projection;
            let mut k = 0;
            b.iter(|| {
                k = (k + 1) % n;
                match cs.surface.patch(cs.feet[k]) {
                    Some(PatchRef::Triangle(t)) => {
                        black_box(project_onto_patch(t, &cs.points[k], &prm))
                    }
                    Some(PatchRef::Quad(q)) => {
                        black_box(project_onto_patch(q, &cs.points[k], &prm))
                    }
                    _ => None,
                }
            })
        });
        g.bench_function(format!("update-points/{}", cs.name), |b| {
            let mut s = cs.surface.clone();
            b.iter(|| black_box(s.update_points(&cs.mesh.points)))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
