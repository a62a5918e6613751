//! Edge cases: flat surfaces and nearly parallel normals, degenerate and
//! general polygons, symmetry planes, flat/curved transitions, bad input.
//!
//! Measured:
//! * plate of quadrilaterals, triangles, pentagons and hexagons in z = 0:
//!   every patch point has z = 0 exactly; tilted, within 1.3e-15 of the
//!   plane and the patches are the bilinear ones bit for bit; normals
//!   randomly tilted by up to 0.05° (pairwise below the 0.1° threshold):
//!   exactly flat; 0.15°, 0.3°, 1°: bulges 3.1e-4, 7.1e-4, 3.2e-3 (unit
//!   spacing);
//! * an edge whose chord leans 30 % out of normals 0.3° apart: bulge 28.9
//!   |d| by eq. 4.77 alone, 0.26 |d| with the cap;
//! * sphere of hexagons and pentagons (dual of the geodesic sphere, 42 /
//!   162 / 642 faces, fan decomposition): flat/Nagata 447 / 1758 / 7020,
//!   orders 3.88, 3.88;
//! * hemisphere of 192 quadrilaterals on z = 0: rim normal error 9.8e-2
//!   and position error 4.8e-3 without the symmetry plane, 2.5e-16 and
//!   4.44e-5 (= the full sphere's) with it;
//! * plate joined tangentially to a cylinder: junction normal error 0.10
//!   without the transition correction, 0 with it; position error next to
//!   the junction 5.5e-3 → 3.1e-5.
use crate::common::*;
use contact_smooth::{
    curvature_parameter, EdgeCurve, EdgeCurveParams, NagataPatch, NagataSurface, NormalWeighting,
    PatchKind, PatchRef, PointNormalParams, QuadPatch, SmoothError, SmoothingOptions,
    SymmetryPlane, TrianglePatch,
};
use fv_mesh::{Real, Vector};

fn opts() -> SmoothingOptions {
    SmoothingOptions::default()
}

/// A plate of quadrilaterals, triangles, a pentagon and a hexagon in z = 0.
fn mixed_plate() -> Mesh {
    let mut points = Vec::new();
    for j in 0..4 {
        for i in 0..5 {
            // slightly irregular grid
            let (x, y) = (
                i as Real + 0.1 * (j as Real).sin(),
                j as Real + 0.07 * i as Real,
            );
            points.push(Vector::new(x, y, 0.0));
        }
    }
    let id = |i: usize, j: usize| j * 5 + i;
    let faces = vec![
        vec![id(0, 0), id(1, 0), id(1, 1), id(0, 1)],
        vec![id(1, 0), id(2, 0), id(2, 1)],
        vec![id(1, 0), id(2, 1), id(1, 1)],
        // pentagon and hexagon
        vec![id(2, 0), id(3, 0), id(4, 0), id(4, 1), id(3, 1), id(2, 1)],
        vec![id(0, 1), id(1, 1), id(2, 1), id(2, 2), id(1, 2), id(0, 2)],
        vec![id(2, 1), id(3, 1), id(4, 1), id(4, 2), id(3, 2), id(2, 2)],
        vec![id(0, 2), id(1, 2), id(2, 2), id(2, 3), id(1, 3), id(0, 3)],
        vec![id(2, 2), id(3, 2), id(4, 2), id(4, 3), id(3, 3)],
        vec![id(2, 2), id(3, 3), id(2, 3)],
    ];
    Mesh { points, faces }
}

fn max_plane_distance(s: &NagataSurface, n: &Vector, origin: &Vector) -> Real {
    max_patch_error(s, |x| (x - origin).dot(n).abs(), 10)
}

#[test]
fn flat_surface_gives_exactly_flat_patches() {
    let m = mixed_plate();
    let s = NagataSurface::new(&m.points, &m.faces, &[], opts()).unwrap();
    assert_eq!(s.kind(0), Some(PatchKind::Quad));
    assert_eq!(s.kind(1), Some(PatchKind::Triangle));
    assert_eq!(s.kind(3), Some(PatchKind::Fan));
    // exactly in z = 0: every curvature parameter is exactly zero
    assert_eq!(max_plane_distance(&s, &Vector::z(), &Vector::zeros()), 0.0);
    for n in s.point_normals() {
        assert_eq!(*n, Vector::z());
    }
    // the same plate tilted: normals differ by rounding only, patches are
    // the flat (bilinear) ones bit for bit
    let rot = nalgebra::Rotation3::from_euler_angles(0.3, -0.7, 1.1);
    let shift = Vector::new(0.3, 2.0, -1.0);
    let tilted: Vec<Vector> = m.points.iter().map(|x| rot * x + shift).collect();
    let s = NagataSurface::new(&tilted, &m.faces, &[], opts()).unwrap();
    let d = max_plane_distance(&s, &(rot * Vector::z()), &shift);
    println!("tilted plate: max distance from the plane {d:.2e}");
    assert!(d < 1e-14);
    let Some(PatchRef::Quad(q)) = s.patch(0) else {
        panic!("quadrilateral expected")
    };
    let f = &m.faces[0];
    assert_eq!(
        *q,
        QuadPatch::flat([tilted[f[0]], tilted[f[1]], tilted[f[2]], tilted[f[3]]])
    );
}

#[test]
fn nearly_parallel_normals() {
    let m = mixed_plate();
    let mut s = NagataSurface::new(&m.points, &m.faces, &[], opts()).unwrap();
    let mut rng = Lcg(5);
    let mut tilt = |angle: Real| -> Vec<Vector> {
        (0..m.points.len())
            .map(|_| {
                let a = angle * rng.next();
                let phi = 2.0 * std::f64::consts::PI * rng.next();
                Vector::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos())
            })
            .collect()
    };
    // below the 0.1° threshold between any two normals: exactly flat
    let n = tilt(0.05_f64.to_radians());
    s.update_with_normals(&m.points, &n).unwrap();
    assert_eq!(max_plane_distance(&s, &Vector::z(), &Vector::zeros()), 0.0);
    // within the ramp (0.1°–0.2°) and beyond it: continuous, small bulges
    // (at most |d| tan(θ/2)/4 for consistent normals)
    for deg in [0.15, 0.3, 1.0] {
        let n = tilt((deg as Real).to_radians());
        s.update_with_normals(&m.points, &n).unwrap();
        let d = max_plane_distance(&s, &Vector::z(), &Vector::zeros());
        println!("normals tilted up to {deg}°: max distance from the plane {d:.2e}");
        assert!(d > 0.0 && d < 1.5 * (deg as Real).to_radians(), "{d}");
    }
    // inconsistent data: normals 0.3° apart, chord leaning 30 % out of their
    // tangent plane. Eq. 4.77 alone inflates the edge; the cap bounds it.
    let (x0, x1) = (Vector::zeros(), Vector::new(1.0, 0.0, 0.3));
    let a = 0.3_f64.to_radians();
    let (n0, n1) = (Vector::z(), Vector::new(a.sin(), 0.0, a.cos()));
    let bulge = |p: &EdgeCurveParams| {
        let e = EdgeCurve::new(x0, x1, &n0, &n1, p);
        (0..=100)
            .map(|k| {
                let t = k as Real / 100.0;
                (e.point(t) - (x0 + t * (x1 - x0))).norm()
            })
            .fold(0.0, Real::max)
    };
    let raw = EdgeCurveParams {
        max_curvature_ratio: Real::INFINITY,
        ..Default::default()
    };
    let (b_raw, b_cap) = (bulge(&raw), bulge(&EdgeCurveParams::default()));
    println!("inconsistent edge: bulge {b_raw:.3} without the cap, {b_cap:.3} with it");
    assert!(b_raw > 10.0 && b_cap <= 0.25 * (x1 - x0).norm() + 1e-15);
    assert!(curvature_parameter(&(x1 - x0), &n0, &n0, &raw) == Vector::zeros());
}

#[test]
fn degenerate_polygons_fall_back() {
    let on_sphere = |v: Vector| v.normalize();
    let x = [
        on_sphere(Vector::new(1.0, -0.2, -0.2)),
        on_sphere(Vector::new(1.0, 0.2, -0.2)),
        on_sphere(Vector::new(1.0, 0.2, 0.2)),
        on_sphere(Vector::new(1.0, -0.2, 0.2)),
    ];
    let mut points = x.to_vec();
    points.push(x[0]); // point 4 coincides with point 0
    points.push(0.5 * (x[1] + x[2])); // point 5 on the segment 1–2: a sliver
    points.push(on_sphere(0.2 * x[0] + 0.3 * x[1] + 0.5 * x[2])); // 6 inside triangle 0 1 2
    let faces = vec![
        vec![0, 1, 2, 2], // repeated index: a triangle
        vec![0, 1, 2, 4], // coincident points: a fan with one empty triangle
        vec![1, 5, 2],    // zero area: skipped
        vec![0, 2, 1, 3], // symmetric bow tie, zero net area: skipped
        vec![0, 1, 2, 6], // dart (reflex corner at 6): a fan
    ];
    let s = NagataSurface::new(&points, &faces, &[], opts()).unwrap();
    assert_eq!(s.kind(0), Some(PatchKind::Triangle));
    assert_eq!(s.kind(1), Some(PatchKind::Fan));
    assert_eq!(s.kind(2), Some(PatchKind::Degenerate));
    assert_eq!(s.kind(3), Some(PatchKind::Degenerate));
    assert_eq!(s.kind(4), Some(PatchKind::Fan));
    // every point of a valid face has a unit normal, the collapsed corner included
    for p in [0, 1, 2, 4, 6] {
        assert!((s.point_normals()[p].norm() - 1.0).abs() < 1e-14);
    }
    // exact sphere normals from here on: the checks below are about the
    // fallbacks, not about the few-face point normals
    let s = {
        let mut s = s;
        let exact: Vec<Vector> = points.iter().map(|p| p.normalize()).collect();
        s.update_with_normals(&points, &exact).unwrap();
        s
    };
    // a point over the dart (outside the notch 0–6–2)
    let over = 1.02 * on_sphere(0.2 * x[0] + 0.6 * x[1] + 0.2 * x[2]);
    let dart = s.closest_projection(&over, &[4]).unwrap().unwrap();
    println!("dart: gap {:.4} (exact 0.02)", dart.signed_distance);
    assert!(dart.inside && (dart.signed_distance - 0.02).abs() < 1e-3);
    let Some(PatchRef::Fan { valid, .. }) = s.patch(1) else {
        panic!("fan expected")
    };
    assert_eq!(valid, &[true, true, true, false]);
    // the triangle is the triangle patch of its three points
    let Some(PatchRef::Triangle(t)) = s.patch(0) else {
        panic!("triangle expected")
    };
    let n = s.point_normals();
    assert_eq!(
        *t,
        TrianglePatch::new([x[0], x[1], x[2]], [n[0], n[1], n[2]], &Default::default())
    );
    // projection: the degenerate face alone gives nothing, with others it is skipped
    let xs = 1.05 * on_sphere(Vector::new(1.0, 0.05, -0.1));
    assert_eq!(s.closest_projection(&xs, &[2]).unwrap(), None);
    let p = s.closest_projection(&xs, &[2, 1]).unwrap().unwrap();
    assert_eq!(p.face, 1);
    assert!(p.inside && p.converged);
    let q = s.closest_projection(&xs, &[0]).unwrap().unwrap();
    println!(
        "collapsed quadrilateral as a fan: foot {:.2e} from the triangle patch's",
        (p.point - q.point).norm()
    );
    assert!((p.point - q.point).norm() < 1e-3);
    assert!((p.signed_distance - 0.05).abs() < 1e-3);
}

/// Sorts the faces around every point of `m` cyclically: the dual mesh
/// (hexagons and 12 pentagons for a geodesic sphere), face centroids
/// projected onto the unit sphere.
fn dual_of_sphere(m: &Mesh) -> Mesh {
    let centres: Vec<Vector> = m
        .faces
        .iter()
        .map(|f| f.iter().map(|&p| m.points[p]).sum::<Vector>().normalize())
        .collect();
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); m.points.len()];
    for (f, face) in m.faces.iter().enumerate() {
        for &p in face {
            around[p].push(f);
        }
    }
    let faces = around
        .into_iter()
        .enumerate()
        .map(|(p, mut fs)| {
            let n = m.points[p].normalize();
            let u = (centres[fs[0]] - m.points[p]).cross(&n).normalize();
            let v = n.cross(&u);
            fs.sort_by(|&a, &b| {
                let ang = |f: usize| {
                    let d = centres[f] - m.points[p];
                    d.dot(&v).atan2(d.dot(&u))
                };
                ang(a).total_cmp(&ang(b))
            });
            // counter-clockwise about the outward normal
            let (_, area) = contact_smooth::polygon_centre_area(&centres, &fs);
            if area.dot(&n) < 0.0 {
                fs.reverse();
            }
            fs
        })
        .collect();
    Mesh {
        points: centres,
        faces,
    }
}

/// N-gons (fan decomposition around the lifted centre): a sphere of
/// hexagons and pentagons converges like the triangle meshes.
#[test]
fn polygons_are_fanned_accurately() {
    let mut h = Vec::new();
    let mut e = Vec::new();
    for n in [2, 4, 8] {
        let m = dual_of_sphere(&geodesic_sphere(1.0, n));
        let s = NagataSurface::new(&m.points, &m.faces, &[], opts()).unwrap();
        assert!((0..s.n_faces()).all(|f| s.kind(f) == Some(PatchKind::Fan)));
        let err = max_patch_error(&s, sphere_error(1.0), 12);
        // flat reference: the same fans with flat triangles around the vertex average
        let mut flat: Real = 0.0;
        for f in &m.faces {
            let c = f.iter().map(|&p| m.points[p]).sum::<Vector>() / f.len() as Real;
            for i in 0..f.len() {
                let t = TrianglePatch::flat([c, m.points[f[i]], m.points[f[(i + 1) % f.len()]]]);
                for (a, b) in samples(false, 12) {
                    flat = flat.max((t.point(a, b).norm() - 1.0).abs());
                }
            }
        }
        println!(
            "sphere of {} polygons: h = {:.4}, flat {flat:.3e}, Nagata {err:.3e}, ratio {:.1}",
            m.faces.len(),
            m.mean_edge(),
            flat / err
        );
        assert!(flat / err > 50.0);
        h.push(m.mean_edge());
        e.push(err);
    }
    let o = orders(&h, &e);
    println!("polygons: observed orders {o:.3?}");
    assert!(o.iter().all(|&o| o > 3.0));
}

/// Upper half of a cube sphere, cut by the symmetry plane z = 0 (Fig. 4.40,
/// left): without the plane the rim normals tilt upwards.
#[test]
fn symmetry_plane_restores_rim_normals() {
    let full = cube_sphere(1.0, 8);
    let half = Mesh {
        points: full.points.clone(),
        faces: full
            .faces
            .iter()
            .filter(|f| f.iter().map(|&p| full.points[p].z).sum::<Real>() > 0.0)
            .cloned()
            .collect(),
    };
    let plane = SymmetryPlane::new(Vector::zeros(), Vector::z());
    let rim: Vec<usize> = (0..half.points.len())
        .filter(|&p| half.points[p].z.abs() < 1e-12)
        .collect();
    assert_eq!(rim.len(), 32);
    let s_full = NagataSurface::new(&full.points, &full.faces, &[], opts()).unwrap();
    let e_full = max_patch_error(&s_full, sphere_error(1.0), 12);
    let mut errors = Vec::new();
    for planes in [&[][..], &[plane][..]] {
        let s = NagataSurface::new(&half.points, &half.faces, planes, opts()).unwrap();
        let nerr = rim
            .iter()
            .map(|&p| (s.point_normals()[p] - half.points[p]).norm())
            .fold(0.0, Real::max);
        let e = max_patch_error(&s, sphere_error(1.0), 12);
        println!(
            "hemisphere, {} symmetry plane(s): rim normal error {nerr:.2e}, position error {e:.3e} (full sphere {e_full:.3e})",
            planes.len()
        );
        errors.push((nerr, e));
        if !planes.is_empty() {
            assert!(rim.iter().all(|&p| s.symmetry_planes_of(p) == 1));
        }
    }
    assert!(errors[0].0 > 0.05 && errors[1].0 < 1e-12);
    assert!(errors[0].1 > 10.0 * e_full);
    assert!(errors[1].1 <= e_full * (1.0 + 1e-9));
}

/// Plate z = 0 (x ≤ 0) continued tangentially by a cylinder of radius 1
/// about the axis (0, y, −1) (Fig. 4.40, right).
#[test]
fn transition_correction_at_a_flat_to_curved_junction() {
    let mut row: Vec<Vector> = [-3.0, -2.0, -1.0, 0.0]
        .iter()
        .map(|&x| Vector::new(x, 0.0, 0.0))
        .collect();
    for k in 1..=4 {
        let phi = 0.25 * k as Real;
        row.push(Vector::new(phi.sin(), 0.0, phi.cos() - 1.0));
    }
    let nx = row.len();
    let mut points = Vec::new();
    for j in 0..=3 {
        points.extend(row.iter().map(|r| r + Vector::new(0.0, j as Real, 0.0)));
    }
    let mut faces = Vec::new();
    for j in 0..3 {
        for i in 0..nx - 1 {
            let a = j * nx + i;
            faces.push(vec![a, a + 1, a + 1 + nx, a + nx]);
        }
    }
    // error of the patches next to the junction (x from −1 to sin 0.25)
    let exact = |x: &Vector| {
        if !(-1.0..=0.25_f64.sin()).contains(&x.x) {
            0.0
        } else if x.x <= 0.0 {
            x.z.abs()
        } else {
            (x.x.hypot(x.z + 1.0) - 1.0).abs()
        }
    };
    let mut results = Vec::new();
    for transition in [None, Some(Default::default())] {
        let o = SmoothingOptions {
            normals: PointNormalParams {
                transition,
                ..Default::default()
            },
            ..Default::default()
        };
        let s = NagataSurface::new(&points, &faces, &[], o).unwrap();
        let n = s.point_normals()[nx + 3];
        let e = max_patch_error(&s, exact, 20);
        println!(
            "flat/curved junction, correction {}: junction normal error {:.2e}, position error {e:.3e}",
            transition.is_some(),
            (n - Vector::z()).norm()
        );
        results.push(((n - Vector::z()).norm(), e));
    }
    assert!(results[0].0 > 0.05 && results[1].0 == 0.0);
    assert!(results[1].1 < 0.5 * results[0].1);
}

#[test]
fn bad_input_is_an_error() {
    let m = mixed_plate();
    let bad_face = vec![vec![0, 1, 99]];
    assert!(matches!(
        NagataSurface::new(&m.points, &bad_face, &[], opts()),
        Err(SmoothError::InvalidSurface(_))
    ));
    let mut nan = m.points.clone();
    nan[3].y = Real::NAN;
    assert!(NagataSurface::new(&nan, &m.faces, &[], opts()).is_err());
    let mut s = NagataSurface::new(&m.points, &m.faces, &[], opts()).unwrap();
    assert!(s.update_points(&nan).is_err());
    assert!(s.update_points(&m.points[1..]).is_err());
    assert!(s.update_with_normals(&m.points, &m.points[1..]).is_err());
    assert!(s
        .closest_projection(&Vector::zeros(), &[m.faces.len()])
        .is_err());
    let mut bad = opts();
    bad.projection.max_iterations = 0;
    assert!(matches!(
        NagataSurface::new(&m.points, &m.faces, &[], bad),
        Err(SmoothError::InvalidParameter {
            name: "max_iterations",
            ..
        })
    ));
    let e = NormalWeighting::from_name("cotangent").unwrap_err();
    assert_eq!(
        e.to_string(),
        "unknown point-normal weighting 'cotangent'; valid weightings: equal, angle, area, \
         edge-length-reciprocal, angle-edge-length-reciprocal, angle-circumcircle"
    );
    assert_eq!(
        NormalWeighting::from_name(" angle ").unwrap(),
        NormalWeighting::Angle
    );
}
