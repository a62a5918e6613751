//! Projection onto the smoothed surface (eqs. 4.81–4.84): feet against the
//! analytic closest point, iteration counts, normals.
//!
//! Seeded points at distance δ ∈ [−0.1, 0.1] from the exact surface (R = 1),
//! all faces as candidates, default options. `e_pos` is the Nagata position
//! error (24 × 24 samples per patch), `θ_max` the largest angle between
//! patch and exact normals. Measured:
//!
//! | mesh                       | e_pos    | max gap error | max foot error | θ_max    | updates max / mean |
//! |----------------------------|----------|---------------|----------------|----------|--------------------|
//! | sphere, 320 triangles      | 8.94e-5  | 8.51e-5       | 2.44e-4        | 2.52e-3  | 3 / 2.65           |
//! | sphere, 384 quadrilaterals | 4.44e-5  | 4.43e-5       | 1.07e-4        | 1.37e-3  | 3 / 2.72           |
//! | cylinder, 144 quads        | 3.69e-5  | 3.69e-5       | 4.89e-5        | 4.33e-4  | 3 / 2.52           |
//! | cylinder, 288 triangles    | 3.69e-5  | 3.69e-5       | 4.89e-5        | 4.33e-4  | 3 / 2.51           |
//!
//! The gap never exceeds `e_pos`; the foot is within `e_pos + |δ| θ_max`
//! of the analytic foot (its tangential offset comes from the tilt of the
//! patch normal). Points at radius 0.3–5 converge in at most 4 updates.
//! The same foot is found among the faces around the nearest point's faces.
use crate::common::*;
use contact_smooth::{NagataSurface, PatchRef, SmoothingOptions, SurfaceProjection};
use fv_mesh::{Real, Vector};

/// Largest angle between the patch normal and `exact` over 40 × 40 samples
/// of every patch (the tests allow 5 % more between samples).
fn max_normal_angle(s: &NagataSurface, exact: &dyn Fn(&Vector) -> Vector) -> Real {
    let mut worst: Real = 0.0;
    for f in 0..s.n_faces() {
        let (patch, square): (&dyn contact_smooth::NagataPatch, bool) = match s.patch(f) {
            Some(PatchRef::Triangle(t)) => (t, false),
            Some(PatchRef::Quad(q)) => (q, true),
            _ => continue,
        };
        for (e, z) in samples(square, 40) {
            let n = patch.normal(e, z).unwrap();
            let m = exact(&patch.point(e, z));
            worst = worst.max(n.cross(&m).norm().asin());
        }
    }
    worst
}

/// Smallest distance from `xs` to 24 × 24 samples of each of the faces.
fn sampled_distance(s: &NagataSurface, xs: &Vector, faces: &[usize]) -> Real {
    let mut best = Real::INFINITY;
    for &f in faces {
        let (patch, square): (&dyn contact_smooth::NagataPatch, bool) = match s.patch(f) {
            Some(PatchRef::Triangle(t)) => (t, false),
            Some(PatchRef::Quad(q)) => (q, true),
            _ => continue,
        };
        for (e, z) in samples(square, 24) {
            best = best.min((patch.point(e, z) - xs).norm());
        }
    }
    best
}

/// Candidate faces: the faces around the faces of the mesh point nearest to `xs`.
fn local_candidates(s: &NagataSurface, xs: &Vector, out: &mut Vec<usize>) {
    let nearest = (0..s.n_points())
        .min_by(|&a, &b| {
            (s.points()[a] - xs)
                .norm()
                .total_cmp(&(s.points()[b] - xs).norm())
        })
        .unwrap();
    out.clear();
    let mut ring = Vec::new();
    for c in s.table().corners(nearest) {
        s.faces_around_face(c.face, &mut ring).unwrap();
        out.extend_from_slice(&ring);
    }
    out.sort_unstable();
    out.dedup();
}

struct Stats {
    max_iterations: usize,
    mean_iterations: Real,
    gap_error: Real,
    foot_error: Real,
    boundary_feet: usize,
}

/// Projects `n` seeded points and checks every foot; `point(rng)` returns
/// `(xs, analytic foot, δ)`, `xs` = analytic foot + δ · exact normal.
fn run(
    name: &str,
    s: &NagataSurface,
    e_pos: Real,
    theta: Real,
    n: usize,
    exact_normal: &dyn Fn(&Vector) -> Vector,
    mut point: impl FnMut(&mut Lcg) -> (Vector, Vector, Real),
) -> Stats {
    let all: Vec<usize> = (0..s.n_faces()).collect();
    let mut rng = Lcg(2024);
    let mut st = Stats {
        max_iterations: 0,
        mean_iterations: 0.0,
        gap_error: 0.0,
        foot_error: 0.0,
        boundary_feet: 0,
    };
    let mut cand = Vec::new();
    for k in 0..n {
        let (xs, foot, delta) = point(&mut rng);
        let p: SurfaceProjection = s.closest_projection(&xs, &all).unwrap().unwrap();
        assert!(p.converged, "{name}: not converged at {xs:?}");
        assert!(p.iterations <= 10);
        st.max_iterations = st.max_iterations.max(p.iterations);
        st.mean_iterations += p.iterations as Real / n as Real;
        // the gap: within the position error of the surface
        let gap = (p.signed_distance - delta).abs();
        assert!(
            gap <= e_pos * (1.0 + 1e-9),
            "{name}: gap error {gap} > {e_pos}"
        );
        st.gap_error = st.gap_error.max(gap);
        // the foot: within the position error plus the tilt of the patch normal
        let fe = (p.point - foot).norm();
        assert!(
            fe <= e_pos + 1.05 * delta.abs() * theta,
            "{name}: foot error {fe}"
        );
        st.foot_error = st.foot_error.max(fe);
        // unit, consistent normal; orthogonal projection
        assert!((p.normal.norm() - 1.0).abs() < 1e-14);
        let ang = p.normal.cross(&exact_normal(&p.point)).norm().asin();
        assert!(
            ang <= 1.05 * theta,
            "{name}: normal off by {ang} > {theta}, {p:?}"
        );
        if p.inside {
            assert!((xs - p.point - p.signed_distance * p.normal).norm() < 1e-10);
        } else {
            st.boundary_feet += 1;
        }
        // a local candidate list finds the same foot
        local_candidates(s, &xs, &mut cand);
        let q = s.closest_projection(&xs, &cand).unwrap().unwrap();
        assert!(
            (q.point - p.point).norm() < 1e-12,
            "{name}: local candidates differ"
        );
        // and no sampled point of those patches is closer
        if k % 10 == 0 {
            let nearest = sampled_distance(s, &xs, &cand);
            assert!(
                p.distance() <= nearest + 1e-12,
                "{name}: a closer point exists"
            );
        }
    }
    println!(
        "{name}: e_pos {e_pos:.3e}, θ_max {theta:.3e}; max gap error {:.3e}, max foot error {:.3e}, \
         iterations max {} mean {:.2}, boundary feet {}/{n}",
        st.gap_error, st.foot_error, st.max_iterations, st.mean_iterations, st.boundary_feet
    );
    st
}

fn sphere_points(rng: &mut Lcg) -> (Vector, Vector, Real) {
    let u = rng.direction();
    let delta = 0.2 * (rng.next() - 0.5);
    ((1.0 + delta) * u, u, delta)
}

#[test]
fn sphere_triangles_and_quadrilaterals() {
    for (name, m) in [
        ("sphere, 320 triangles", geodesic_sphere(1.0, 4)),
        ("sphere, 384 quadrilaterals", cube_sphere(1.0, 8)),
    ] {
        let s = NagataSurface::new(&m.points, &m.faces, &[], SmoothingOptions::default()).unwrap();
        let e_pos = max_patch_error(&s, sphere_error(1.0), 24);
        let theta = max_normal_angle(&s, &|x| x.normalize());
        let st = run(
            name,
            &s,
            e_pos,
            theta,
            2000,
            &|x| x.normalize(),
            sphere_points,
        );
        assert!(st.max_iterations <= 4 && st.mean_iterations < 3.0);
        assert!(st.gap_error <= e_pos);
    }
}

#[test]
fn cylinder_quadrilaterals_and_triangles() {
    for tri in [false, true] {
        let m = cylinder(1.0, 1.0, 24, 6, tri);
        let s = NagataSurface::new(&m.points, &m.faces, &[], SmoothingOptions::default()).unwrap();
        let e_pos = max_patch_error(&s, cylinder_error(1.0), 24);
        let radial = |x: &Vector| Vector::new(x.x, x.y, 0.0).normalize();
        let theta = max_normal_angle(&s, &radial);
        let name = if tri {
            "cylinder, triangles"
        } else {
            "cylinder, quadrilaterals"
        };
        let st = run(name, &s, e_pos, theta, 1000, &radial, |rng| {
            let t = 2.0 * std::f64::consts::PI * rng.next();
            let z = 0.2 + 0.6 * rng.next();
            let u = Vector::new(t.cos(), t.sin(), 0.0);
            let delta = 0.2 * (rng.next() - 0.5);
            (
                (1.0 + delta) * u + z * Vector::z(),
                u + z * Vector::z(),
                delta,
            )
        });
        assert!(st.max_iterations <= 4);
    }
}

/// Far outside and deep inside (towards the centre of curvature) the start
/// from the flat projection still converges within the thesis's 10 updates.
#[test]
fn far_points_converge() {
    let m = geodesic_sphere(1.0, 4);
    let s = NagataSurface::new(&m.points, &m.faces, &[], SmoothingOptions::default()).unwrap();
    let e_pos = max_patch_error(&s, sphere_error(1.0), 24);
    let all: Vec<usize> = (0..s.n_faces()).collect();
    let mut rng = Lcg(99);
    let mut worst = 0;
    for r in [0.3, 0.6, 2.0, 5.0] {
        for _ in 0..200 {
            let u = rng.direction();
            let p = s.closest_projection(&(r * u), &all).unwrap().unwrap();
            assert!(p.converged && p.iterations <= 10, "r = {r}: {p:?}");
            worst = worst.max(p.iterations);
            assert!((p.signed_distance - (r - 1.0)).abs() <= e_pos * (1.0 + 1e-9));
        }
    }
    println!("far points: at most {worst} iterations");
    assert!(worst <= 6);
}

/// A rigid motion of the master (update in place): feet move with it.
#[test]
fn rigid_motion_moves_the_feet() {
    let m = cube_sphere(1.0, 6);
    let mut s = NagataSurface::new(&m.points, &m.faces, &[], SmoothingOptions::default()).unwrap();
    let all: Vec<usize> = (0..s.n_faces()).collect();
    let xs = Vector::new(0.4, 0.7, 0.75);
    let before = s.closest_projection(&xs, &all).unwrap().unwrap();
    let rot = nalgebra::Rotation3::from_axis_angle(&Vector::y_axis(), 0.7);
    let shift = Vector::new(3.0, -1.0, 0.5);
    let moved: Vec<Vector> = m.points.iter().map(|x| rot * x + shift).collect();
    s.update_points(&moved).unwrap();
    let after = s
        .closest_projection(&(rot * xs + shift), &all)
        .unwrap()
        .unwrap();
    assert_eq!(after.face, before.face);
    assert!((after.point - (rot * before.point + shift)).norm() < 1e-12);
    assert!((after.normal - rot * before.normal).norm() < 1e-12);
    assert!((after.signed_distance - before.signed_distance).abs() < 1e-12);
}

/// On the coarsest meshes (20 triangles, 24 quadrilaterals) the patch
/// normals jump across edges and more feet land on patch boundaries: every
/// foot is still the closest point among the candidates (no sampled point
/// of any candidate patch is closer).
#[test]
fn coarse_mesh_feet_are_closest() {
    for m in [geodesic_sphere(1.0, 1), cube_sphere(1.0, 2)] {
        let s = NagataSurface::new(&m.points, &m.faces, &[], SmoothingOptions::default()).unwrap();
        let all: Vec<usize> = (0..s.n_faces()).collect();
        let mut rng = Lcg(77);
        let mut boundary = 0;
        for _ in 0..500 {
            let xs = (0.8 + 0.4 * rng.next()) * rng.direction();
            let p = s.closest_projection(&xs, &all).unwrap().unwrap();
            assert!(p.iterations <= 10 && (p.normal.norm() - 1.0).abs() < 1e-14);
            let nearest = sampled_distance(&s, &xs, &all);
            assert!(
                p.distance() <= nearest + 1e-12,
                "{} > {nearest}",
                p.distance()
            );
            if !p.inside {
                boundary += 1;
                // a boundary foot: the distance is measured to the foot itself
                assert!(((xs - p.point).norm() - p.distance()).abs() < 1e-14);
            }
        }
        println!(
            "{} faces: {boundary}/500 feet on patch boundaries",
            m.faces.len()
        );
    }
}
