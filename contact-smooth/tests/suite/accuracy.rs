//! Position accuracy of the Nagata surface on analytic shapes (issue 9
//! acceptance): sampled patch points against the exact sphere or cylinder,
//! compared with the flat faces of the same mesh, and the observed order
//! under refinement.
//!
//! Measured (default options: Max's weighting of corner normals refined by
//! the quadric fit), maximum radial error over 12 × 12 samples per patch,
//! R = 1:
//!
//! | mesh                          | faces           | flat / Nagata      | order      |
//! |-------------------------------|-----------------|--------------------|------------|
//! | geodesic sphere, triangles    | 80, 320, 1280   | 52, 231, 872       | 4.18, 3.92 |
//! | cube sphere, quadrilaterals   | 96, 384, 1536   | 53, 206, 828       | 3.92, 3.99 |
//! | cylinder, quadrilaterals      | 64, 256, 1024   | 102, 413, 1658     | 4.03, 4.01 |
//! | cylinder, triangles           | 128, 512, 2048  | 102, 413, 1658     | 4.03, 4.01 |
//!
//! (Max's weighting alone, which is exact on a sphere: cube sphere 58, 213,
//! 836; geodesic 52, 199, 783. The fit matters on irregular meshes of other
//! shapes: `half_tube_triangulations`.)
//!
//! The coarsest meshes of each family (icosahedron: 20 faces, ratio 16;
//! 2 × 2 per cube face: 24 faces, ratio 20; 8 segments: ratio 24) are
//! coarser than 1/50 allows. With the thesis's equally weighted face normals
//! the error is limited by first-order normals (see
//! `thesis_weighting_is_limited_by_the_normals`).
use crate::common::*;
use contact_smooth::{
    NagataPatch, NagataSurface, NormalFit, PatchRef, PointNormalParams, SmoothingOptions,
};
use fv_mesh::{Real, Vector};

struct Level {
    h: Real,
    faces: usize,
    flat: Real,
    nagata: Real,
}

fn measure(
    meshes: &[Mesh],
    error: &dyn Fn(&Vector) -> Real,
    options: SmoothingOptions,
) -> Vec<Level> {
    meshes
        .iter()
        .map(|m| {
            let s = NagataSurface::new(&m.points, &m.faces, &[], options).unwrap();
            Level {
                h: m.mean_edge(),
                faces: m.faces.len(),
                flat: max_flat_error(m, error, 12),
                nagata: max_patch_error(&s, error, 12),
            }
        })
        .collect()
}

fn report(name: &str, levels: &[Level]) -> Vec<Real> {
    let h: Vec<Real> = levels.iter().map(|l| l.h).collect();
    let e: Vec<Real> = levels.iter().map(|l| l.nagata).collect();
    let o = orders(&h, &e);
    for l in levels {
        println!(
            "{name}: {:5} faces, h = {:.4}, flat {:.3e}, Nagata {:.3e}, ratio {:.1}",
            l.faces,
            l.h,
            l.flat,
            l.nagata,
            l.flat / l.nagata
        );
    }
    println!("{name}: observed orders {o:.3?}");
    o
}

fn check(name: &str, levels: &[Level], min_ratio: Real, min_order: Real) {
    let o = report(name, levels);
    for l in levels {
        assert!(
            l.flat / l.nagata >= min_ratio,
            "{name}, {} faces: ratio {}",
            l.faces,
            l.flat / l.nagata
        );
    }
    for (k, ok) in o.iter().enumerate() {
        assert!(
            *ok >= min_order,
            "{name}: order {ok} between levels {k} and {}",
            k + 1
        );
    }
}

#[test]
fn sphere_triangles() {
    let meshes: Vec<Mesh> = [2, 4, 8].map(|n| geodesic_sphere(1.0, n)).into();
    let levels = measure(&meshes, &sphere_error(1.0), SmoothingOptions::default());
    check("sphere, triangles", &levels, 50.0, 3.9);
}

#[test]
fn sphere_quadrilaterals() {
    let meshes: Vec<Mesh> = [4, 8, 16].map(|n| cube_sphere(1.0, n)).into();
    let levels = measure(&meshes, &sphere_error(1.0), SmoothingOptions::default());
    check("sphere, quadrilaterals", &levels, 50.0, 3.8);
}

#[test]
fn cylinder_quadrilaterals() {
    let meshes: Vec<Mesh> = [(16, 4), (32, 8), (64, 16)]
        .map(|(a, b)| cylinder(1.0, 1.0, a, b, false))
        .into();
    let levels = measure(&meshes, &cylinder_error(1.0), SmoothingOptions::default());
    check("cylinder, quadrilaterals", &levels, 100.0, 3.9);
}

#[test]
fn cylinder_triangles() {
    let meshes: Vec<Mesh> = [(16, 4), (32, 8), (64, 16)]
        .map(|(a, b)| cylinder(1.0, 1.0, a, b, true))
        .into();
    let levels = measure(&meshes, &cylinder_error(1.0), SmoothingOptions::default());
    check("cylinder, triangles", &levels, 100.0, 3.9);
}

/// The coarsest meshes: still much better than flat, not by 50.
#[test]
fn coarsest_meshes() {
    let err = sphere_error(1.0);
    let l = measure(
        &[geodesic_sphere(1.0, 1), cube_sphere(1.0, 2)],
        &err,
        SmoothingOptions::default(),
    );
    report("coarsest spheres (20 triangles, 24 quadrilaterals)", &l);
    assert!(l[0].flat / l[0].nagata > 15.0 && l[1].flat / l[1].nagata > 19.0);
    let l = measure(
        &[cylinder(1.0, 1.0, 8, 2, false)],
        &cylinder_error(1.0),
        SmoothingOptions::default(),
    );
    report("coarsest cylinder (8 segments)", &l);
    assert!(l[0].flat / l[0].nagata > 24.0);
}

/// Thesis choice (equal weights of face normals): on these irregular
/// sphere meshes the point normals are only first-order accurate (their
/// error halves with h), so the Nagata surface converges at about second
/// order; with the exact normals of the same meshes it is fourth order
/// again. Measured: geodesic 320/1280/5120 faces ratio 21/54/42, orders
/// 3.4, 1.6, point-normal error 9.0e-3/4.5e-3/2.4e-3; cube 96/384/1536
/// faces ratio 12/8/7, orders 1.3, 1.8, point-normal error
/// 5.2e-2/3.8e-2/2.1e-2; exact normals: orders 3.99, 4.00 and 3.88, 3.97.
#[test]
fn thesis_weighting_is_limited_by_the_normals() {
    let thesis = SmoothingOptions {
        normals: PointNormalParams::thesis(),
        ..Default::default()
    };
    let err = sphere_error(1.0);
    let geo: Vec<Mesh> = [4, 8, 16].map(|n| geodesic_sphere(1.0, n)).into();
    let cube: Vec<Mesh> = [4, 8, 16].map(|n| cube_sphere(1.0, n)).into();
    for (name, meshes) in [("geodesic", &geo), ("cube", &cube)] {
        let levels = measure(meshes, &err, thesis);
        report(&format!("{name} sphere, equal weights"), &levels);
        let mut exact = Vec::new();
        for (m, l) in meshes.iter().zip(&levels) {
            assert!(
                l.flat / l.nagata > 6.0,
                "{name}: ratio {}",
                l.flat / l.nagata
            );
            let mut s = NagataSurface::new(&m.points, &m.faces, &[], thesis).unwrap();
            let nerr = s
                .point_normals()
                .iter()
                .zip(&m.points)
                .map(|(n, x)| (n - x.normalize()).norm())
                .fold(0.0, Real::max);
            println!(
                "{name}: {} faces, max point-normal error {nerr:.2e}",
                m.faces.len()
            );
            assert!(nerr > 1e-3, "equal weights are not exact here");
            let normals: Vec<Vector> = m.points.iter().map(|x| x.normalize()).collect();
            s.update_with_normals(&m.points, &normals).unwrap();
            exact.push(max_patch_error(&s, &err, 12));
        }
        let h: Vec<Real> = meshes.iter().map(|m| m.mean_edge()).collect();
        let o = orders(&h, &exact);
        println!("{name}: exact normals, errors {exact:?}, orders {o:.3?}");
        assert!(o.iter().all(|&o| o > 3.8));
    }
}

/// Radial error of a point from the tube of the block-in-half-tube case
/// (radius 3, axis y = 3, z = 0).
fn tube_error(x: &Vector) -> Real {
    ((x.y - 3.0).powi(2) + x.z.powi(2)).sqrt() - 3.0
}

/// Largest radial error and range over the block's positions of the mean
/// radial error under the block's 2 × 2 m footprint (x ∈ [x₀, x₀ + 2],
/// |z| < 1, x₀ = 1.5 … 11.5 by 0.1 m): the geometric part of the contact
/// force oscillation.
fn tube_figures(s: &NagataSurface) -> (Real, Real) {
    let (tri, quad) = (samples(false, 12), samples(true, 12));
    let mut found = Vec::new();
    for f in 0..s.n_faces() {
        let (p, pts): (&dyn NagataPatch, _) = match s.patch(f) {
            Some(PatchRef::Triangle(t)) => (t, &tri),
            Some(PatchRef::Quad(q)) => (q, &quad),
            _ => continue,
        };
        for &(e, z) in pts {
            let x = p.point(e, z);
            if x.z.abs() < 1.0 && x.x > 1.0 && x.x < 14.0 {
                found.push((x.x, tube_error(&x)));
            }
        }
    }
    let worst = found.iter().map(|s| s.1.abs()).fold(0.0, Real::max);
    let (mut lo, mut hi) = (Real::MAX, Real::MIN);
    for k in 0..=100 {
        let x0 = 1.5 + 0.1 * k as Real;
        let inside: Vec<Real> = found
            .iter()
            .filter(|s| s.0 >= x0 && s.0 < x0 + 2.0)
            .map(|s| s.1)
            .collect();
        let mean = inside.iter().sum::<Real>() / inside.len() as Real;
        lo = lo.min(mean);
        hi = hi.max(mean);
    }
    (worst, hi - lo)
}

/// The irregular Frontal-Delaunay triangulations of the block-in-half-tube
/// case (thesis §4.6.1; `validation/cases/block-in-half-tube`): weighted
/// normals are first-order there, the quadric fit (the default) second
/// order. Measured over 1 < x < 14, |z| < 1 (Max's weighting; without →
/// with the fit): coarse tube (780 triangles) largest radial error
/// 2.96e-3 → 8.5e-5 m (exact normals: 8.8e-5), footprint mean range
/// 2.0e-4 → 1.55e-5 m (2.0 % → 0.16 % of the case's 0.01 overlap); fine
/// tube (2,440) 4.5e-4 → 6.9e-6 m and 3.2e-6 → 3.9e-7 m.
#[test]
fn half_tube_triangulations() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../validation/cases/block-in-half-tube");
    for file in ["tube-coarse.msh", "tube-fine.msh"] {
        let mesh = fv_mesh::read_gmsh(&dir.join(file)).unwrap();
        let inner = mesh.patch_index("inner").unwrap();
        let surface = fv_mesh::Surface::new(&mesh, inner).unwrap();
        let mut figures = Vec::new();
        for fit in [None, Some(NormalFit::default())] {
            let mut options = SmoothingOptions::default();
            options.normals.fit = fit;
            let s = NagataSurface::from_surface(&surface, &[], options).unwrap();
            let (worst, range) = tube_figures(&s);
            println!(
                "{file}: fit {}: largest radial error {worst:.3e} m, footprint mean range {range:.3e} m",
                fit.is_some()
            );
            figures.push((worst, range));
        }
        let [(w0, r0), (w1, r1)] = [figures[0], figures[1]];
        assert!(w1 < 0.05 * w0 && r1 < 0.2 * r0, "{file}: {figures:?}");
        if file == "tube-coarse.msh" {
            assert!(r1 < 2.5e-5 && w1 < 1.5e-4, "{r1} {w1}");
        }
    }
}
